//! The map's numbers: for one machine (a knob value, a grid cell, a point of
//! the warp series) and one group of scenes, the baseline's cycles against
//! the shipped machine, every variant's speedup over that machine's
//! baseline, and WaSP's instruments.
//!
//! Speedups are per scene `baseline cycles / cycles - 1`, then the
//! arithmetic mean over the group's scenes, as in the rest of the report.

use super::knobs::Variant;
use crate::reproduce::figures::mean;
use crate::reproduce::plan::Group;
use crate::study::cache::PointRecord;
use crate::study::point::Point;
use crate::study::runner::Outcome;
use serde::Serialize;
use wasp_sim::stats::RunStats;

/// The groups a map row is given for, in table order.
pub const GROUPS: [Group; 3] = [Group::ThreeD, Group::TwoD, Group::Procedural];

/// One machine's numbers over one group of scenes (None where no scene of
/// the group has the runs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Metrics {
    /// The baseline's cycles against the shipped machine's baseline
    /// (`cycles / shipped cycles - 1`: positive is slower).
    pub baseline_cycles: Option<f64>,
    /// WaSP's speedup over this machine's baseline.
    pub wasp: Option<f64>,
    /// Fullpriority's speedup.
    pub fullpriority: Option<f64>,
    /// The raster prefetcher's speedup (baseline launch order).
    pub raster: Option<f64>,
    /// The oracle tile prefetcher's speedup: the bound of launching early
    /// to prefetch.
    pub oracle: Option<f64>,
    /// Ideal memory's speedup: the headroom memory leaves.
    pub ideal: Option<f64>,
    /// Share of WaSP's launches with both FIFOs waiting in which the gate
    /// kept the priority warp back.
    pub gate_closed: Option<f64>,
    /// Mean lead of WaSP's priority warps (raster position minus launch
    /// rank).
    pub lead: Option<f64>,
    /// The baseline's drain share of a tile's cycles.
    pub drain: Option<f64>,
    /// The baseline's share of cycles in which a full core queue held the
    /// rasterizer back.
    pub backpressure: Option<f64>,
    /// The baseline's mean warps resident per core.
    pub occupancy: Option<f64>,
    /// The baseline's primary misses in the scheduler-level cache (L0 at
    /// width 4) per warp.
    pub l0_misses_per_warp: Option<f64>,
    /// The baseline's share of DRAM requests that met another row open.
    pub row_conflicts: Option<f64>,
    /// The baseline's L1 and L2 misses per warp (the L1 below the L0 at
    /// width 4).
    pub lower_misses_per_warp: (Option<f64>, Option<f64>),
    /// The oracle's share of prefetch misses a demand access merged into
    /// while in flight (late prefetches).
    pub oracle_late: Option<f64>,
    /// The oracle's share of prefetched lines evicted before any use.
    pub oracle_useless: Option<f64>,
    /// The oracle's share of core-cycles its queue head waited for free
    /// L1 MSHRs beyond the reserve.
    pub oracle_reserve_wait: Option<f64>,
    /// The DRAM's mean queue wait under the oracle, and under WaSP.
    pub dram_wait: (Option<f64>, Option<f64>),
    /// The baseline run's CF: distinct blocks per warp.
    pub cf: Option<f64>,
    /// The baseline run's distinct blocks per tile (Min_Estimate1 x warps
    /// / tiles: the tiles' summed footprints over the tiles).
    pub blocks_per_tile: Option<f64>,
}

impl Metrics {
    /// The speedup of `v` (None for the baseline itself).
    pub fn speedup(&self, v: Variant) -> Option<f64> {
        match v {
            Variant::Baseline => None,
            Variant::Wasp => self.wasp,
            Variant::FullPriority => self.fullpriority,
            Variant::Raster => self.raster,
            Variant::Oracle => self.oracle,
            Variant::Ideal => self.ideal,
        }
    }
}

/// The scenes of a map and their groups.
pub struct MapScenes<'a> {
    /// (name, group), in plan order.
    pub scenes: Vec<(&'a str, Group)>,
}

impl MapScenes<'_> {
    /// The names of the scenes of `g`.
    pub fn of(&self, g: Group) -> impl Iterator<Item = &str> + '_ {
        self.scenes.iter().filter(move |s| s.1 == g).map(|s| s.0)
    }
}

/// `base cycles / x cycles - 1`.
fn speedup(base: &PointRecord, x: &PointRecord) -> f64 {
    base.cycles() / x.cycles() - 1.0
}

/// The numbers of the machine that `point(scene, variant)` names, over the
/// scenes of `g`; `shipped(scene)` is the shipped machine's baseline.
pub fn metrics(
    out: &Outcome,
    scenes: &MapScenes,
    g: Group,
    point: &dyn Fn(&str, Variant) -> Point,
    shipped: &dyn Fn(&str) -> Point,
) -> Metrics {
    let per_scene = |f: &dyn Fn(&str) -> Option<f64>| mean(scenes.of(g).filter_map(f));
    let rec = |s: &str, v: Variant| out.get(&point(s, v));
    let gain = |v: Variant| {
        per_scene(&|s: &str| {
            let (b, x) = (rec(s, Variant::Baseline)?, rec(s, v)?);
            Some(speedup(b, x))
        })
    };
    let stat =
        |v: Variant, f: fn(&RunStats) -> Option<f64>| per_scene(&|s: &str| f(&rec(s, v)?.stats));
    // A statistic of the baseline per warp.
    let per_warp = |f: fn(&RunStats) -> u64| {
        per_scene(&|s: &str| {
            let r = &rec(s, Variant::Baseline)?.stats;
            Some(f(r) as f64 / r.warps as f64)
        })
    };
    Metrics {
        baseline_cycles: per_scene(&|s: &str| {
            let (b, x) = (out.get(&shipped(s))?, rec(s, Variant::Baseline)?);
            Some(x.cycles() / b.cycles() - 1.0)
        }),
        wasp: gain(Variant::Wasp),
        fullpriority: gain(Variant::FullPriority),
        raster: gain(Variant::Raster),
        oracle: gain(Variant::Oracle),
        ideal: gain(Variant::Ideal),
        gate_closed: stat(Variant::Wasp, |r| Some(r.gate.closed_share)),
        lead: stat(Variant::Wasp, |r| Some(r.priority_lead.mean)),
        drain: stat(Variant::Baseline, |r| Some(r.tile_timing.drain_share)),
        backpressure: stat(Variant::Baseline, |r| {
            Some(r.raster.backpressure_cycles as f64 / r.cycles as f64)
        }),
        occupancy: stat(Variant::Baseline, |r| Some(r.occupancy.mean)),
        l0_misses_per_warp: per_warp(|r| r.l0.as_ref().unwrap_or(&r.l1).misses),
        row_conflicts: stat(Variant::Baseline, |r| {
            Some(r.dram.row_conflicts as f64 / r.dram.requests as f64)
        }),
        lower_misses_per_warp: (per_warp(|r| r.l1.misses), per_warp(|r| r.l2.misses)),
        oracle_late: stat(Variant::Oracle, |r| Some(r.prefetch.as_ref()?.late_share)),
        oracle_useless: stat(Variant::Oracle, |r| {
            let p = r.prefetch.as_ref()?;
            (p.counts.misses > 0).then(|| p.useless as f64 / p.counts.misses as f64)
        }),
        oracle_reserve_wait: stat(Variant::Oracle, |r| {
            let cores = r.held_cycles_per_core.len() as f64;
            let waits = r.prefetch.as_ref()?.counts.reserve_waits as f64;
            Some(waits / (r.cycles as f64 * cores))
        }),
        dram_wait: (
            stat(Variant::Oracle, |r| Some(r.dram.avg_queue_wait)),
            stat(Variant::Wasp, |r| Some(r.dram.avg_queue_wait)),
        ),
        cf: stat(Variant::Baseline, |r| Some(r.cf)),
        blocks_per_tile: stat(Variant::Baseline, |r| {
            (r.tiles > 0).then(|| r.min_estimate1 * r.warps as f64 / r.tiles as f64)
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::cache::tests::stats_of;

    fn rec(p: &Point, cycles: u64, closed: f64) -> PointRecord {
        let mut stats = stats_of(cycles);
        stats.gate.closed_share = closed;
        PointRecord {
            key: String::new(),
            point: p.clone(),
            binary: String::new(),
            stats,
        }
    }

    #[test]
    fn metrics_are_means_of_per_scene_speedups() {
        let wasp = wasp_rtl::policy::PolicySpec::SHIPPED_WASP;
        let point = |s: &str, v: Variant| Point::new(s, "paper", &v.overrides(wasp));
        let shipped = |s: &str| Point::new(s, "shipped", &[]);
        let mut out = Outcome::default();
        // Scene a: baseline 110, WaSP 100 (+10%); scene b: 200 / 250
        // (-20%); the shipped baseline is 100 on both.
        for (s, b, w) in [("a", 110, 100), ("b", 200, 250)] {
            for (p, c) in [
                (point(s, Variant::Baseline), b),
                (point(s, Variant::Wasp), w),
                (shipped(s), 100),
            ] {
                out.points.insert(p.clone(), rec(&p, c, 0.5));
            }
        }
        let scenes = MapScenes {
            scenes: vec![
                ("a", Group::ThreeD),
                ("b", Group::ThreeD),
                ("c", Group::TwoD),
            ],
        };
        let m = metrics(&out, &scenes, Group::ThreeD, &point, &shipped);
        assert!((m.wasp.unwrap() - (0.1 + -0.2) / 2.0).abs() < 1e-12);
        assert!((m.baseline_cycles.unwrap() - (0.1 + 1.0) / 2.0).abs() < 1e-12);
        assert_eq!(m.gate_closed, Some(0.5));
        assert_eq!(m.oracle, None, "no oracle runs");
        let none = metrics(&out, &scenes, Group::TwoD, &point, &shipped);
        assert_eq!(none, Metrics::default());
    }
}
