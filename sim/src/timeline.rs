//! A run's timeline over a window of cycles: what `wasp run --timeline`
//! draws so that a reader sees the fill and drain of every tile.
//!
//! Per cycle of the window: the warps resident in each core, the misses
//! outstanding at each cache level (MSHR entries awaiting their reply,
//! summed over the level's instances) and the priority warps launched in
//! that cycle on each core. Tile boundaries are recorded as events: the
//! cycle a tile's first quad is rasterized (shared-tile dispatch) or the
//! cycle a core takes the tile (per-core-tile dispatch), and the cycle its
//! last warp retires.

use serde::Serialize;

/// One cycle of the timeline.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct TimelineSample {
    /// The cycle.
    pub cycle: u64,
    /// Warps resident (launched, not retired) in each core.
    pub resident: Vec<u32>,
    /// Misses outstanding at the end of the cycle: `[L0, L1, L2]`, L0 and L1
    /// summed over the cores (L0 is 0 on a machine without L0).
    pub outstanding: [u32; 3],
    /// Priority warps launched in the cycle, per core.
    pub priority_launches: Vec<u32>,
}

/// A tile's start or end within the window.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct TileMark {
    /// The cycle.
    pub cycle: u64,
    /// Index of the tile in the trace.
    pub tile: u32,
    /// The core that renders it (per-core-tile dispatch), or `None` when
    /// every core shares it (shared-tile dispatch).
    pub core: Option<u32>,
    /// `true`: the tile starts; `false`: its last warp retired.
    pub start: bool,
}

/// The timeline of one run over `from..=to`.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Timeline {
    /// First cycle of the window.
    pub from: u64,
    /// Last cycle of the window (the run's last cycle if it ended earlier).
    pub to: u64,
    /// Shader cores.
    pub cores: usize,
    /// Warp slots per core (the top of the occupancy axis).
    pub max_warps: u32,
    /// Whether the machine has an L0.
    pub has_l0: bool,
    /// The dispatch mode, as in the configuration.
    pub dispatch: String,
    /// One sample per cycle of the window, in cycle order.
    pub samples: Vec<TimelineSample>,
    /// Tile starts and ends within the window, in cycle order.
    pub marks: Vec<TileMark>,
}

impl Timeline {
    /// An empty timeline for the window `from..=to`.
    pub fn new(
        from: u64,
        to: u64,
        cores: usize,
        max_warps: u32,
        has_l0: bool,
        dispatch: &str,
    ) -> Self {
        Timeline {
            from,
            to,
            cores,
            max_warps,
            has_l0,
            dispatch: dispatch.to_string(),
            samples: Vec::new(),
            marks: Vec::new(),
        }
    }

    /// Whether `cycle` lies in the window.
    pub fn covers(&self, cycle: u64) -> bool {
        cycle >= self.from && cycle <= self.to
    }

    /// Record that `tile` starts (`start`) or ends in `cycle` (on `core`,
    /// per-core-tile dispatch), if the cycle lies in the window.
    pub fn mark(&mut self, cycle: u64, tile: u32, core: Option<u32>, start: bool) {
        if self.covers(cycle) {
            self.marks.push(TileMark {
                cycle,
                tile,
                core,
                start,
            });
        }
    }
}
