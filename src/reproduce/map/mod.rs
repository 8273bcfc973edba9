//! "What decides WaSP's gain": the map of the machine's unstated choices.
//!
//! The paper's machine leaves choices unstated (warps per core, MSHR
//! counts, DRAM latency, input-queue depth, raster and Early-Z rates,
//! texture latency and filter rate, issue order, core map). The map varies
//! each one at a time over a range a mobile GPU could have and runs, at
//! every value, the baseline, WaSP, Fullpriority, a raster texture
//! prefetcher, the oracle tile prefetcher (the bound of launching early to
//! prefetch) and ideal memory; then a 2-D grid over the two knobs that move
//! WaSP most, chosen from those results; and the warp counts again with a
//! deep input queue, which separates queue room from latency hiding.
//!
//! - [`knobs`]: the knobs, their values and the variants run at each;
//! - [`plan`]: the points;
//! - [`data`]: one machine's numbers over a group of scenes;
//! - [`table`](mod@table): every machine's numbers, the ranges, the grid's choice;
//! - [`report`]: the REPORT.md section and `data/map.*`;
//! - [`figures`]: the tornado, warps, grid and area figures;
//! - [`conclusion`]: the sentences on warp slots and the paper's claims;
//! - [`textures`]: the sentence on compressed textures and the paper's CF;
//! - [`sweeps`]: the map as sweep files, for one cluster job a point.

pub mod conclusion;
pub mod data;
pub mod edges;
pub mod figures;
pub mod knobs;
pub mod plan;
pub mod report;
pub mod sweeps;
pub mod table;
pub mod textures;

use super::plan::{Plan, SceneInfo};
use crate::study::cache::Cache;
use crate::study::runner::{self, Outcome, RunnerOptions};
use data::MapScenes;
use plan::{Cell, MapPlan};
use table::MapTable;
use wasp_frontend::def::Route;

/// The scenes of `plan` the map may run on: its loader-route scenes
/// (counted in the study or beside it), or its engine scenes in a run
/// without loader scenes. (wasp) Engine twins stay out of the map so that
/// its scene set, and so the study's time, is the same whichever route the
/// means count.
pub fn eligible(plan: &Plan) -> Vec<&SceneInfo> {
    let loader = plan.every.iter().any(|s| s.route == Route::Loader);
    plan.every
        .iter()
        .filter(|s| s.route == Route::Loader || !loader)
        .collect()
}

/// The scenes of `plan` the map runs on, with their groups: those of
/// [`eligible`] that the map keeps.
pub fn scenes<'a>(plan: &'a Plan, map: &MapPlan) -> MapScenes<'a> {
    MapScenes {
        scenes: eligible(plan)
            .into_iter()
            .filter(|s| map.keeps(&s.name))
            .map(|s| (s.name.as_str(), s.group))
            .collect(),
    }
}

/// The names of the scenes of `plan` the map runs on, in plan order.
pub fn scene_names(plan: &Plan, map: &MapPlan) -> Vec<String> {
    scenes(plan, map)
        .scenes
        .iter()
        .map(|s| s.0.to_string())
        .collect()
}

/// The map's table from a run's results, with the grid's cells when given.
pub fn table(plan: &Plan, map: &MapPlan, out: &Outcome, cells: &[Cell]) -> MapTable {
    let sc = scenes(plan, map);
    MapTable::new(map, out, &sc).with_grid(map, out, &sc, cells)
}

/// The map's one-at-a-time tasks on the scenes of `plan` (the grid's come
/// after them, from [`run_grid`]).
pub fn tasks(plan: &Plan, map: &MapPlan) -> Vec<crate::study::runner::Task> {
    map.tasks(&scene_names(plan, map))
}

/// The second phase: choose the two knobs that move WaSP most from the
/// one-at-a-time results in `out`, run their grid, and add its results to
/// `out`. Returns the grid's cells (none without a map or two knobs).
pub fn run_grid(
    plan: &Plan,
    map: &MapPlan,
    out: &mut Outcome,
    cache: &Cache,
    opts: &RunnerOptions,
) -> Result<Vec<Cell>, String> {
    let sc = scenes(plan, map);
    let t = MapTable::new(map, out, &sc);
    let Some((a, b)) = table::top_two(&t.knobs) else {
        return Ok(Vec::new());
    };
    let cells = map.grid(a, b);
    let tasks = map.grid_tasks(&scene_names(plan, map), &cells);
    if !opts.quiet {
        eprintln!(
            "wasp: the 2-D grid over {} and {}: {} cells, {} tasks",
            map.knobs[a].label,
            map.knobs[b].label,
            cells.len(),
            tasks.len()
        );
    }
    // The first phase's machines, run or found stored: a grid point on one
    // of them is the same as an earlier task of this run, not one done
    // before it (a fresh run should not say "already done").
    let known: std::collections::HashSet<String> =
        out.points.values().map(|r| r.key.clone()).collect();
    let more = runner::run(&tasks, cache, opts)?;
    let again: std::collections::HashSet<&String> = more
        .points
        .values()
        .map(|r| &r.key)
        .filter(|k| known.contains(*k))
        .collect();
    let again = again.len().min(more.cached);
    out.points.extend(more.points);
    out.failures.extend(more.failures);
    out.ran += more.ran;
    out.cached += more.cached - again;
    out.same += more.same + again;
    out.seconds += more.seconds;
    Ok(cells)
}
