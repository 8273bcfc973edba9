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
    let stat = |v: Variant, path: &'static str| per_scene(&|s: &str| rec(s, v)?.get(path));
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
        gate_closed: stat(Variant::Wasp, "gate.closed_share"),
        lead: stat(Variant::Wasp, "priority_lead.mean"),
        drain: stat(Variant::Baseline, "tile_timing.drain_share"),
        backpressure: per_scene(&|s: &str| {
            let r = rec(s, Variant::Baseline)?;
            Some(r.get("raster.backpressure_cycles")? / r.cycles())
        }),
        occupancy: stat(Variant::Baseline, "occupancy.mean"),
        l0_misses_per_warp: per_scene(&|s: &str| {
            let r = rec(s, Variant::Baseline)?;
            let first = r.get("l0.misses").or_else(|| r.get("l1.misses"))?;
            Some(first / r.get("warps")?)
        }),
        row_conflicts: per_scene(&|s: &str| {
            let r = rec(s, Variant::Baseline)?;
            Some(r.get("dram.row_conflicts")? / r.get("dram.requests")?)
        }),
        lower_misses_per_warp: (
            per_scene(&|s: &str| {
                let r = rec(s, Variant::Baseline)?;
                Some(r.get("l1.misses")? / r.get("warps")?)
            }),
            per_scene(&|s: &str| {
                let r = rec(s, Variant::Baseline)?;
                Some(r.get("l2.misses")? / r.get("warps")?)
            }),
        ),
        oracle_late: stat(Variant::Oracle, "prefetch.late_share"),
        oracle_useless: per_scene(&|s: &str| {
            let r = rec(s, Variant::Oracle)?;
            let misses = r.get("prefetch.misses")?;
            (misses > 0.0).then(|| r.get("prefetch.useless").unwrap_or(0.0) / misses)
        }),
        oracle_reserve_wait: per_scene(&|s: &str| {
            let r = rec(s, Variant::Oracle)?;
            let cores = r.stats.get("held_cycles_per_core")?.as_array()?.len() as f64;
            Some(r.get("prefetch.reserve_waits")? / (r.cycles() * cores))
        }),
        dram_wait: (
            stat(Variant::Oracle, "dram.avg_queue_wait"),
            stat(Variant::Wasp, "dram.avg_queue_wait"),
        ),
        cf: stat(Variant::Baseline, "cf"),
        blocks_per_tile: per_scene(&|s: &str| {
            let r = rec(s, Variant::Baseline)?;
            let (tiles, warps) = (r.get("tiles")?, r.get("warps")?);
            (tiles > 0.0).then(|| r.get("min_estimate1").unwrap_or(0.0) * warps / tiles)
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rec(p: &Point, cycles: u64, closed: f64) -> PointRecord {
        PointRecord {
            key: String::new(),
            point: p.clone(),
            binary: String::new(),
            stats: serde_json::json!({"cycles": cycles, "gate": {"closed_share": closed}}),
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
