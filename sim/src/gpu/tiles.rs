//! Instruments of a tile's life: when it starts, fills, drains and ends,
//! its primary misses, and how far ahead of their neighbours its priority
//! warps launch.
//!
//! One [`TileTracker`] follows the tiles of one renderer: the whole GPU
//! under shared-tile dispatch, each core under per-core-tile dispatch.
//!
//! * **Fill** is the cycles from the tile's first launch to the first cycle
//!   its resident warps reach their peak; **drain** the cycles from its last
//!   launch to its last retire. The paper: "we have many occurrences of
//!   filling the core and draining the core with warps. These periods have
//!   low core occupancy" (Section II-D).
//! * **Lead** of a priority warp: its raster position (its index among the
//!   tile's warps in rasterization order) minus its launch rank (how many
//!   warps of the tile launched before it). Positive: it launched ahead of
//!   quads rasterized before it, which is what prefetching needs ("A
//!   priority warp must be scheduled sufficiently ahead of its adjacent
//!   regular warps", Section IV-C).
//! * A priority warp launched **after its subtile's regular warps** is one
//!   launched after some regular warp of its own 4x4-quad subtile (Mesh4's
//!   subtile): a neighbour then started without its prefetch.

use serde::{Deserialize, Serialize};

/// Lower edges of the lead histogram's bins (the last bin is open above).
pub const LEAD_BIN_EDGES: [i64; 14] = [
    i64::MIN,
    -256,
    -128,
    -64,
    -32,
    -16,
    -1,
    0,
    1,
    17,
    33,
    65,
    129,
    257,
];

/// One finished tile.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct TileRecord {
    /// Index of the tile in the trace.
    pub tile: u32,
    /// The core that rendered it (per-core-tile), or `None` (shared-tile).
    pub core: Option<u32>,
    /// Warps launched.
    pub warps: u32,
    /// Cycle it started (first rasterized quad, or the core took it).
    pub start: u64,
    /// Cycle its last warp retired.
    pub end: u64,
    /// `end - start + 1`.
    pub cycles: u64,
    /// Cycles from its first launch to its peak of resident warps.
    pub fill: u64,
    /// Cycles from its last launch to its last retire.
    pub drain: u64,
    /// Peak of resident warps (summed over cores under shared-tile).
    pub peak_resident: u32,
    /// Primary misses at the scheduler-level cache (L0, or L1 without L0)
    /// while it ran.
    pub primary_misses: u64,
}

/// One bin of the lead histogram: leads in `from..=to`.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct LeadBin {
    /// Smallest lead of the bin (`None`: unbounded below).
    pub from: Option<i64>,
    /// Largest lead of the bin (`None`: unbounded above).
    pub to: Option<i64>,
    /// Priority warps with a lead in the bin.
    pub count: u64,
}

/// The lead of priority warps over a run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LeadStats {
    /// Priority warps launched.
    pub priority_warps: u64,
    /// Mean lead (raster position minus launch rank); 0 without priority
    /// warps.
    pub mean: f64,
    /// Share of priority warps with a positive lead.
    pub ahead_share: f64,
    /// Share of priority warps launched after a regular warp of their own
    /// 4x4-quad subtile.
    pub after_subtile_regular_share: f64,
    /// Histogram of leads.
    pub histogram: Vec<LeadBin>,
}

/// Means over the tiles of a run.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TileTimingStats {
    /// Tiles rendered.
    pub tiles: u64,
    /// Mean cycles per tile.
    pub mean_cycles: f64,
    /// Mean fill time.
    pub mean_fill: f64,
    /// Mean drain time.
    pub mean_drain: f64,
    /// Share of the tiles' cycles spent filling.
    pub fill_share: f64,
    /// Share of the tiles' cycles spent draining.
    pub drain_share: f64,
    /// Mean primary misses per tile.
    pub mean_primary_misses: f64,
}

#[derive(Clone, Copy, Debug)]
struct Open {
    tile: u32,
    core: Option<u32>,
    start: u64,
    first_launch: Option<u64>,
    last_launch: u64,
    launches: u32,
    peak: u32,
    peak_at: u64,
    /// Subtiles (4x4 quads, row-major) with a regular warp launched.
    regular_seen: u64,
}

/// Follows the tiles of one renderer.
#[derive(Clone, Debug, Default)]
pub struct TileTracker {
    open: Option<Open>,
    records: Vec<TileRecord>,
    prio: u64,
    lead_sum: i64,
    ahead: u64,
    after_regular: u64,
    bins: [u64; LEAD_BIN_EDGES.len()],
}

fn bin_of(lead: i64) -> usize {
    LEAD_BIN_EDGES.partition_point(|&e| e <= lead) - 1
}

impl TileTracker {
    /// A tracker with no tile.
    pub fn new() -> Self {
        Self::default()
    }

    /// Tile `tile` starts in cycle `now` (on `core`, per-core-tile).
    pub fn start(&mut self, tile: u32, core: Option<u32>, now: u64) {
        self.open = Some(Open {
            tile,
            core,
            start: now,
            first_launch: None,
            last_launch: now,
            launches: 0,
            peak: 0,
            peak_at: now,
            regular_seen: 0,
        });
    }

    /// A warp of the open tile launched in cycle `now`: its index in the
    /// tile's rasterization order and its in-tile position (tiles of at most
    /// 32x32 quads: 64 subtiles).
    #[inline]
    pub fn launch(&mut self, now: u64, quad: u32, x: u32, y: u32, priority: bool) {
        let Some(o) = self.open.as_mut() else {
            return;
        };
        let rank = o.launches;
        o.launches += 1;
        o.first_launch.get_or_insert(now);
        o.last_launch = now;
        let sub = 1u64 << (((y >> 2) << 3 | (x >> 2)) & 63);
        if priority {
            let lead = i64::from(quad) - i64::from(rank);
            self.prio += 1;
            self.lead_sum += lead;
            self.ahead += u64::from(lead > 0);
            self.after_regular += u64::from(o.regular_seen & sub != 0);
            self.bins[bin_of(lead)] += 1;
        } else {
            o.regular_seen |= sub;
        }
    }

    /// Resident warps of the open tile in cycle `now` (the GPU reports them
    /// after each launch: occupancy rises only at a launch).
    #[inline]
    pub fn resident(&mut self, now: u64, n: u32) {
        if let Some(o) = self.open.as_mut() {
            if n > o.peak {
                o.peak = n;
                o.peak_at = now;
            }
        }
    }

    /// The open tile's last warp retired in cycle `now`; it caused
    /// `primary_misses` primary misses.
    pub fn finish(&mut self, now: u64, primary_misses: u64) {
        let Some(o) = self.open.take() else {
            return;
        };
        let first = o.first_launch.unwrap_or(o.start);
        self.records.push(TileRecord {
            tile: o.tile,
            core: o.core,
            warps: o.launches,
            start: o.start,
            end: now,
            cycles: now - o.start + 1,
            fill: o.peak_at.saturating_sub(first),
            drain: if o.launches == 0 {
                0
            } else {
                now - o.last_launch
            },
            peak_resident: o.peak,
            primary_misses,
        });
    }

    /// The finished tiles.
    pub fn records(&self) -> &[TileRecord] {
        &self.records
    }

    /// The lead statistics of several trackers together.
    pub fn lead_stats(trackers: &[TileTracker]) -> LeadStats {
        let mut bins = [0u64; LEAD_BIN_EDGES.len()];
        let (mut n, mut sum, mut ahead, mut after) = (0u64, 0i64, 0u64, 0u64);
        for t in trackers {
            n += t.prio;
            sum += t.lead_sum;
            ahead += t.ahead;
            after += t.after_regular;
            for (b, c) in bins.iter_mut().zip(t.bins) {
                *b += c;
            }
        }
        let share = |k: u64| if n == 0 { 0.0 } else { k as f64 / n as f64 };
        let histogram = bins
            .iter()
            .enumerate()
            .map(|(i, &count)| LeadBin {
                from: (LEAD_BIN_EDGES[i] != i64::MIN).then_some(LEAD_BIN_EDGES[i]),
                to: LEAD_BIN_EDGES.get(i + 1).map(|e| e - 1),
                count,
            })
            .collect();
        LeadStats {
            priority_warps: n,
            mean: if n == 0 { 0.0 } else { sum as f64 / n as f64 },
            ahead_share: share(ahead),
            after_subtile_regular_share: share(after),
            histogram,
        }
    }

    /// The tile means over `records`.
    pub fn timing(records: &[TileRecord]) -> TileTimingStats {
        let n = records.len() as u64;
        let sum = |f: &dyn Fn(&TileRecord) -> u64| records.iter().map(f).sum::<u64>();
        let cycles = sum(&|r| r.cycles);
        let mean = |s: u64| if n == 0 { 0.0 } else { s as f64 / n as f64 };
        let share = |s: u64| {
            if cycles == 0 {
                0.0
            } else {
                s as f64 / cycles as f64
            }
        };
        TileTimingStats {
            tiles: n,
            mean_cycles: mean(cycles),
            mean_fill: mean(sum(&|r| r.fill)),
            mean_drain: mean(sum(&|r| r.drain)),
            fill_share: share(sum(&|r| r.fill)),
            drain_share: share(sum(&|r| r.drain)),
            mean_primary_misses: mean(sum(&|r| r.primary_misses)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bins_cover_every_lead_once() {
        assert_eq!(bin_of(i64::MIN), 0);
        assert_eq!(bin_of(-1000), 0);
        assert_eq!(bin_of(-256), 1);
        assert_eq!(bin_of(-1), 6);
        assert_eq!(bin_of(0), 7);
        assert_eq!(bin_of(1), 8);
        assert_eq!(bin_of(16), 8);
        assert_eq!(bin_of(17), 9);
        assert_eq!(bin_of(1000), 13);
        let s = TileTracker::lead_stats(&[]);
        assert_eq!(s.histogram[0].from, None);
        assert_eq!(s.histogram[0].to, Some(-257));
        assert_eq!(s.histogram[7].from, Some(0));
        assert_eq!(s.histogram[7].to, Some(0));
        assert_eq!(s.histogram[13].to, None);
        assert_eq!(s.mean, 0.0);
    }

    /// A hand-made tile: warps 0..4 of subtile 0 (quads (0,0), (1,0),
    /// (2,0), (0,0) again as overdraw), a priority warp at raster position 3
    /// launched first, one at position 0 launched third.
    #[test]
    fn lead_fill_and_drain_by_hand() {
        let mut t = TileTracker::new();
        t.start(7, None, 10);
        t.launch(12, 3, 0, 0, true); // rank 0: lead +3, no regular seen
        t.resident(12, 1);
        t.launch(13, 1, 1, 0, false); // rank 1
        t.resident(13, 2);
        t.launch(14, 0, 0, 0, true); // rank 2: lead -2, after a regular
        t.resident(14, 3);
        t.launch(15, 2, 2, 0, false); // rank 3
        t.resident(15, 3);
        t.resident(20, 1);
        t.finish(30, 5);
        let r = &t.records()[0];
        assert_eq!(
            (r.tile, r.warps, r.start, r.end, r.cycles),
            (7, 4, 10, 30, 21)
        );
        assert_eq!((r.fill, r.drain, r.peak_resident), (2, 15, 3));
        assert_eq!(r.primary_misses, 5);
        let s = TileTracker::lead_stats(std::slice::from_ref(&t));
        assert_eq!(s.priority_warps, 2);
        assert_eq!(s.mean, 0.5);
        assert_eq!(s.ahead_share, 0.5);
        assert_eq!(s.after_subtile_regular_share, 0.5);
        assert_eq!(s.histogram[bin_of(3)].count, 1);
        assert_eq!(s.histogram[bin_of(-2)].count, 1);
        let m = TileTracker::timing(t.records());
        assert_eq!((m.tiles, m.mean_cycles, m.mean_fill), (1, 21.0, 2.0));
    }

    #[test]
    fn a_tile_without_warps_has_no_fill_or_drain() {
        let mut t = TileTracker::new();
        t.start(0, Some(2), 5);
        t.finish(9, 0);
        let r = &t.records()[0];
        assert_eq!((r.warps, r.fill, r.drain, r.cycles), (0, 0, 0, 5));
        assert_eq!(r.core, Some(2));
    }

    #[test]
    fn subtiles_are_4x4_quads() {
        // A regular warp at (3, 3) and a priority warp at (4, 0): different
        // subtiles; a priority warp at (0, 3): same subtile as (3, 3).
        let mut t = TileTracker::new();
        t.start(0, None, 0);
        t.launch(1, 0, 3, 3, false);
        t.launch(2, 1, 4, 0, true);
        assert_eq!(t.after_regular, 0);
        t.launch(3, 2, 0, 3, true);
        assert_eq!(t.after_regular, 1);
        t.launch(4, 3, 31, 31, false);
        t.launch(5, 4, 28, 28, true);
        assert_eq!(t.after_regular, 2);
    }
}
