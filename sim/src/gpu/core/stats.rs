//! What a shader core counts: its counters over a run and, when asked,
//! a record of every warp.

/// Counters of one core.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize)]
pub struct CoreStats {
    /// Tiles rendered.
    pub tiles: u64,
    /// Warps launched.
    pub warps_launched: u64,
    /// Warps finished.
    pub warps_finished: u64,
    /// Priority warps launched.
    pub priority_launches: u64,
    /// Warp instructions issued (ALU and texture).
    pub instructions: u64,
    /// Texture instructions issued.
    pub tex_instructions: u64,
    /// Of those, trilinear ones.
    pub tri_tex_instructions: u64,
    /// Cycles the filter unit was busy: the sum of the filter cycles of
    /// the texture instructions it served.
    pub filter_busy_cycles: u64,
    /// Sum over texture instructions of the cycles their data waited for
    /// the filter unit (filter start - last block's arrival).
    pub filter_wait_cycles: u64,
    /// Hold idle cycles: cycles with a free slot and a warp waiting in the
    /// priority FIFO but no launch, because the policy's gate was closed, no
    /// regular warp waited and the launch rule is `hold` (WaSP:
    /// Real_freeMSHRs too low). Always 0 under `launch`.
    pub held_cycles: u64,
    /// Launches made with warps waiting in both FIFOs (the priority one and
    /// the regular one): the launches in which the policy's gate chose.
    pub both_waiting: u64,
    /// Of those, launches of the regular warp: the gate was closed, and the
    /// waiting priority warp fell behind its raster order.
    pub regular_first: u64,
    /// Sum over cycles of the CF meter's register, in quarters (`wasp-m`;
    /// 0 for other policies).
    pub cf_quarters_sum: u64,
    /// Cycles summed in `cf_quarters_sum`.
    pub cf_samples: u64,
    /// Sum over warps of each warp's mean texture latency.
    pub warp_latency_sum: [f64; 2],
    /// Warps with at least one texture instruction, [regular, priority].
    pub warps_with_tex: [u64; 2],
    /// Cycles with no tile (idle core).
    pub idle_cycles: u64,
    /// Sum over cycles of active warps (for average occupancy).
    pub occupancy_sum: u64,
    /// Cycles by warps resident at the end of the launch stage: entry `n`
    /// counts the cycles with `n` warps (`max_warps + 1` entries).
    pub occupancy_hist: Vec<u64>,
    /// Quads its own rasterizer rasterized, rejected ones included
    /// (per-core-tile dispatch).
    pub quads_rasterized: u64,
    /// Of those, quads Early-Z rejected.
    pub quads_rejected: u64,
    /// Blocked episodes: texture instructions whose warp became blocked
    /// (`[regular, priority]` warps).
    pub blocked_episodes: [u64; 2],
    /// Cycles from the cycle a warp became blocked to the cycle its last
    /// block arrived (unblocking it), summed over the episodes
    /// (`[regular, priority]`).
    pub blocked_cycles: [u64; 2],
}

impl CoreStats {
    /// Every counter zero, the occupancy histogram as long as this one's
    /// (what a core counts from when a frame begins).
    pub fn cleared(&self) -> CoreStats {
        CoreStats {
            occupancy_hist: vec![0; self.occupancy_hist.len()],
            ..CoreStats::default()
        }
    }
}

/// What one warp did, for per-quad pictures (heat maps) and analysis.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct WarpRecord {
    /// Index of its tile in the trace.
    pub tile: u32,
    /// Index of its quad in the tile.
    pub quad: u32,
    /// Core that ran it.
    pub core: u32,
    /// Whether it was launched as a priority warp.
    pub priority: bool,
    /// Mean memory latency of its texture instructions (cycles), if any.
    pub mem_latency: Option<f64>,
    /// Cycle it was launched.
    pub launched: u64,
    /// Cycle it finished.
    pub finished: u64,
}
