//! Test data for the report's prose: a quick look whose every number
//! contradicts the paper, as a real run could (tests only). The report
//! built from it must say what these numbers show, not what the paper
//! found.

use super::plan::{Group, Plan};
use crate::study::cache::tests::sample_stats;
use crate::study::cache::PointRecord;
use crate::study::point::Point;
use crate::study::runner::{Outcome, Task};
use serde_json::json;
use wasp_frontend::characterize::Characterization;
use wasp_frontend::def::{self, SceneDef};
use wasp_rtl::policy::PolicySpec;
use wasp_sim::config::Dispatch;
use wasp_sim::stats::{LatencyStats, RunStats};

/// Statistics that contradict the paper on every claim: WaSP and
/// Fullpriority slower than the baseline, Fullpriority stalling the L0
/// less than the baseline and WaSP more, latency, energy and misses rising
/// under WaSP, WaSP@48 slower than the baseline@64, priority warps behind
/// their raster order and waiting less than regular ones.
pub fn point_stats(p: &Point) -> RunStats {
    let policy = p
        .value_of("scheduler.policy")
        .and_then(|v| v.as_str()?.parse().ok());
    let wasp = matches!(
        policy,
        Some(PolicySpec::Wasp { .. } | PolicySpec::WaspMeasured { .. })
    );
    let fullpriority = policy == Some(PolicySpec::FullPriority);
    let warps = p
        .value_of("core.max_warps")
        .and_then(toml::Value::as_integer);
    let warps = warps.map_or(64.0, |w| w as f64);
    let mut cycles = 1000.0 + 5.0 * (64.0 - warps);
    if wasp {
        cycles *= 1.10;
    }
    if fullpriority {
        cycles *= 1.02;
    }
    if p.value_of("memory.ideal").is_some() {
        cycles *= 0.8;
    }
    let stall = if wasp {
        0.20
    } else if fullpriority {
        0.05
    } else {
        0.10
    };
    let more = if wasp { 1.1 } else { 1.0 };
    let mut s = sample_stats();
    s.cycles = cycles.round() as u64;
    if let Some(l0) = &mut s.l0 {
        l0.stall_fraction = stall;
    }
    s.occupancy.mean = 40.0;
    s.priority_lead.mean = -3.0;
    s.gate.closed_share = 0.5;
    s.memory_latency = LatencyStats {
        all: 100.0 * more,
        priority: 90.0,
        regular: 100.0,
    };
    s.energy.total_nj = 1000.0 * more;
    s.energy.static_nj = 500.0 * more;
    s.l1.misses = (1000.0 * more).round() as u64;
    s.l2.misses = 100;
    s.raster.quads_rasterized = 100;
    s.raster.quads_rejected = 10;
    s.raster.backpressure_cycles = 100;
    s
}

/// A workload characterisation against the paper's: the subsets' footprint
/// ratios in the reverse of the paper's order (Mesh4 smallest), and the 2D
/// scenes' CF above the 3D ones'.
pub fn characterization(def: &SceneDef) -> Characterization {
    let cf = if Group::of(def.game) == Group::TwoD {
        4.0
    } else {
        1.5
    };
    let footprints: Vec<serde_json::Value> = [
        ("top16", 0.9),
        ("hlines", 0.8),
        ("vlines", 0.7),
        ("mesh2", 0.95),
        ("mesh4", 0.1),
        ("mesh8", 0.05),
        ("mesh16", 0.02),
        ("random:1", 0.5),
    ]
    .iter()
    .map(|(subset, ratio)| {
        json!({"subset": subset, "size_ratio": 0.1, "warp_ratio": 0.1,
               "footprint_ratio": ratio, "paper": null})
    })
    .collect();
    serde_json::from_value(json!({
        "scene": def.name, "workload": def.name, "width": 64, "height": 64, "tiles": 1,
        "warps": 100, "warps_per_tile": 100.0, "positions": 100, "warps_per_position": 1.0,
        "rejected_early_z": 0, "mem_instr_ratio": 0.1, "reuse": 5.0, "cf": cf,
        "blocks_per_tex_instr": 1.0, "min_estimate1": 0.3, "min_estimate2": 0.2,
        "footprints": footprints, "raster_seconds": 0.0
    }))
    .expect("a characterisation")
}

/// A quick look on `machines` whose every point and scene holds the
/// contrary numbers above.
pub fn outcome(machines: Vec<Dispatch>) -> (Plan, Outcome) {
    let defs = def::all().unwrap();
    let plan = Plan::new(&defs, true, machines);
    let mut out = Outcome::default();
    for t in plan.tasks(std::path::Path::new("figures")) {
        match t {
            Task::Run(p) => {
                let stats = point_stats(&p);
                let record = PointRecord {
                    key: String::new(),
                    point: p.clone(),
                    binary: String::new(),
                    stats,
                };
                out.points.insert(p, record);
            }
            Task::Characterize { scene, .. } => {
                let d = defs
                    .iter()
                    .find(|d| d.name == scene)
                    .expect("a shipped scene");
                out.scenes.insert(scene, characterization(d));
            }
            Task::Timeline { .. } => {}
        }
    }
    (plan, out)
}
