//! `wasp reproduce --dry-run`: the plan's task counts, with and without
//! the engine scenes, printed without running, fetching, capturing or
//! writing anything.

use super::map;
use super::plan::Plan;
use super::ReproduceArgs;
use crate::cli_error::CliError;
use crate::study::cache::Cache;
use crate::study::count::{count, Counts};
use crate::study::runner::{RunnerOptions, Task};
use wasp_frontend::def::{self, SceneDef};

/// `--dry-run`: the counts of `plan` (and of its map before the grid) on
/// standard output, and those without the engine scenes.
pub fn print(
    args: &ReproduceArgs,
    plan: &Plan,
    map: &map::plan::MapPlan,
    defs: Vec<SceneDef>,
) -> Result<(), CliError> {
    let opts = RunnerOptions {
        jobs: 1,
        quiet: true,
        fetch: false,
        label: "counting".into(),
        scenes: defs.clone(),
    };
    let cache = Cache::read_only(&args.out);
    let count = |plan: &Plan| -> Result<[Counts; 2], CliError> {
        let (tasks, paper) = super::study_tasks(plan, map, &args.out.join("figures"));
        let c = |t: &[Task]| count(t, &cache, &opts).map_err(CliError::failed);
        Ok([c(&tasks[..paper])?, c(&tasks)?])
    };
    let [paper_counts, all] = count(plan)?;
    // The same run without the engine scenes, for comparison.
    let loader: Vec<SceneDef> = defs
        .into_iter()
        .filter(|d| d.route == def::Route::Loader)
        .collect();
    let without = Plan::with_routes(&loader, args.quick, args.machines.dispatches(), args.routes);
    let [paper_without, all_without] = count(&without)?;
    let route = |r: def::Route| plan.every.iter().filter(|s| s.route == r).count();
    println!(
        "scenes: {} in the study and its means, {} beside them ({} loader, {} engine)",
        plan.scenes.len(),
        plan.beside.len(),
        route(def::Route::Loader),
        route(def::Route::Engine)
    );
    println!("twin pairs: {}", plan.twins.len());
    for (what, c) in [
        ("the paper's experiments", paper_counts),
        ("with the map, before its 2-D grid", all),
        (
            "without the engine scenes: the paper's experiments",
            paper_without,
        ),
        (
            "without the engine scenes: with the map, before its grid",
            all_without,
        ),
    ] {
        println!(
            "{what}: {} tasks, {} distinct ({} to run, {} already done), {} the same as \
             another{}",
            c.tasks,
            c.to_run + c.done,
            c.to_run,
            c.done,
            c.same,
            if c.failing > 0 {
                format!(", {} on engine scenes without a capture", c.failing)
            } else {
                String::new()
            }
        );
    }
    Ok(())
}
