//! `wasp reproduce`: every experiment of the paper's Sections III and V on
//! the shipped scenes, under the paper's shared-tile machine and the
//! per-core-tile machine, with plots, data files and a report that sets our
//! numbers beside the paper's.
//!
//! - [`plan`]: the experiments as study points;
//! - [`paper`]: the paper's numbers;
//! - [`figures`]: the numbers of each figure, from the results;
//! - [`report`]: REPORT.md, the CSV/JSON files and the plots;
//! - [`answer`]: its opening "The answer", generated from the run;
//! - [`headline`]: its side-by-side table of the paper's numbers and ours
//!   (printed with [`digits`]; sweeps' edges flagged by [`edges`]);
//! - [`engine_check`]: the engine scenes checked (and those that cannot
//!   be drawn left out) before the plan is made; [`dry_run`]: the plan's
//!   counts without a run;
//! - [`routes`]: which twin of a loader and engine pair counts, and
//!   [`routes_report`]: the routes in the report and "The loaders against
//!   the engine";
//! - [`why`]: its bullets on why they differ, worded from the data by
//!   [`prose`];
//! - [`rgba8`]: the scenes with every texture in RGBA8, beside their own
//!   (`etc2`) textures in the headline table and the bullets.

pub mod answer;
#[cfg(test)]
mod contrary;
pub mod digits;
pub mod draw;
pub mod dry_run;
pub mod edges;
pub mod engine_check;
pub mod figures;
pub mod headline;
pub mod map;
pub mod paper;
pub mod plan;
pub mod prose;
pub mod report;
pub mod rgba8;
pub mod routes;
pub mod routes_report;
pub mod why;

use crate::cli_error::CliError;
use crate::study::cache::Cache;
use crate::study::runner::{self, RunnerOptions};
use clap::{Args, ValueEnum};
use plan::Plan;
use std::path::{Path, PathBuf};
use wasp_frontend::def::{self, SceneDef};
use wasp_sim::config::Dispatch;

/// Options of `wasp reproduce`.
#[derive(Args, Debug, Clone)]
pub struct ReproduceArgs {
    /// A first look: 74 s of CPU time with the game data cached, which two
    /// workers share (the first run also downloads the games' data, about
    /// 835 MB): the smallest scene of each game, the heuristics, ideal
    /// memory, the meshes, four thresholds, width 4 at 32/48/64 warps and
    /// one timeline on the first machine of --machines only, and the map
    /// over warps per core and L0 MSHRs (on the shared-tile machine).
    #[arg(long)]
    pub quick: bool,

    /// Output folder: REPORT.md, figures/, data/, and the finished points
    /// (points/, scenes/) that a later run with the same binary skips.
    #[arg(long, value_name = "DIR", default_value = "reproduce")]
    pub out: PathBuf,

    /// Machines: both (shared-tile, the paper's, and per-core-tile),
    /// shared-tile or per-core-tile.
    #[arg(long, value_name = "WHICH", default_value = "both")]
    pub machines: Machines,

    /// Only these scenes (comma separated names of `wasp scenes list`, or
    /// scene definition files; default: every listed scene). A subset is
    /// not the paper's suite: the report says so.
    #[arg(long, value_delimiter = ',', value_name = "SCENES")]
    pub scenes: Option<Vec<String>>,

    #[command(flatten)]
    pub scene_defs: crate::scenes_dir::ScenesDir,

    /// Simulations run at once (default: the machine's cores).
    #[arg(long, value_name = "N")]
    pub jobs: Option<usize>,

    /// No progress output on stderr (progress, notes of what is done, the
    /// closing summary); warnings and errors still print.
    #[arg(long, short)]
    pub quiet: bool,

    /// Write the map "What decides WaSP's gain" as sweep files into DIR
    /// (map-policies.toml, map-bounds.toml, map-deep-queue.toml) and run
    /// nothing: run them with `wasp sweep FILE --out OUT` (or one job per
    /// point with --jobs-file), then `wasp reproduce --out OUT` finds those
    /// points done (docs/reproduce.md).
    #[arg(long, value_name = "DIR")]
    pub sweep_files: Option<PathBuf>,

    /// The scenes of the map "What decides WaSP's gain": budget (every scene
    /// but the three 3D scenes with the most cycles, so that the whole
    /// study fits in 15 minutes on two cores; scenes named with --scenes
    /// always run) or all. The paper's experiments run on every scene.
    #[arg(long, value_name = "WHICH", default_value = "budget")]
    pub map_scenes: map::plan::SceneChoice,

    /// Where a camera has a loader scene and an engine twin (the game's own
    /// draw calls, `route = "engine"`), which counts in the study and its
    /// group means: engine (the twin; the loader scene is reported beside),
    /// loader (the reverse) or both. Both twins run the comparison "The
    /// loaders against the engine"; an engine scene that cannot be
    /// captured or imported is left out and the report says why.
    #[arg(long, value_name = "WHICH", default_value = "engine")]
    pub routes: routes::RouteChoice,

    /// Print the plan's counts and run nothing: scenes by route, tasks
    /// before the 2-D grid (whose tasks depend on the results), the
    /// simulations among them that are distinct, and those already done in
    /// --out. Engine scenes count as if they draw; a run leaves out those
    /// that cannot be captured or imported.
    #[arg(long, conflicts_with = "sweep_files")]
    pub dry_run: bool,
}

/// Which machines a reproduction runs.
#[derive(clap::ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Machines {
    /// Shared-tile (the paper's) and per-core-tile.
    Both,
    /// The paper's shared-tile machine only.
    SharedTile,
    /// The per-core-tile machine only.
    PerCoreTile,
}

impl Machines {
    fn dispatches(self) -> Vec<Dispatch> {
        match self {
            Machines::Both => vec![Dispatch::SharedTile, Dispatch::PerCoreTile],
            Machines::SharedTile => vec![Dispatch::SharedTile],
            Machines::PerCoreTile => vec![Dispatch::PerCoreTile],
        }
    }
}

/// Run the command.
pub fn run(args: &ReproduceArgs) -> Result<(), CliError> {
    let jobs = match args.jobs {
        Some(0) => return Err(CliError::usage("--jobs 0: expected at least 1")),
        Some(n) if n > 1024 => {
            return Err(CliError::usage(format!("--jobs {n}: at most 1024")));
        }
        Some(n) => n,
        None => std::thread::available_parallelism().map_or(1, |n| n.get()),
    };
    crate::output::folder(
        "--out",
        &args.out,
        "REPORT.md, figures/, data/ and the finished points",
    )?;
    if let Some(d) = &args.sweep_files {
        crate::output::folder("--sweep-files", d, "one sweep file per group")?;
    }
    let defs = chosen_scenes(args.scenes.as_deref())?;
    let plan = Plan::with_routes(&defs, args.quick, args.machines.dispatches(), args.routes);
    // The map "What decides WaSP's gain" runs on the shared-tile machine
    // beside the paper's experiments.
    let map =
        map::plan::MapPlan::new(plan.wasp, plan.quick).on(args.map_scenes, args.scenes.is_some());
    if let Some(dir) = &args.sweep_files {
        return write_sweep_files(dir, &map, &plan, args.quiet);
    }
    if args.dry_run {
        return dry_run::print(args, &plan, &map, defs);
    }
    let cache = Cache::open(&args.out).map_err(CliError::failed)?;
    let opts = RunnerOptions {
        jobs,
        quiet: args.quiet,
        fetch: true,
        label: "reproducing".into(),
        scenes: defs.clone(),
    };
    let plan = without_left_out(args, plan, defs, &cache, &opts)?;
    let figures = args.out.join("figures");
    std::fs::create_dir_all(&figures)
        .map_err(|e| CliError::failed(format!("cannot create {}: {e}", figures.display())))?;
    let (tasks, _) = study_tasks(&plan, &map, &figures);
    if !args.quiet {
        say_plan(args, &plan, &map, tasks.len(), jobs);
    }
    crate::interrupt::say_resume_on_interrupt(&args.out, &crate::study::jobs::command_line());
    let mut outcome = runner::run(&tasks, &cache, &opts).map_err(CliError::failed)?;
    let cells =
        map::run_grid(&plan, &map, &mut outcome, &cache, &opts).map_err(CliError::failed)?;
    let command = command(args, def::scenes_dir().as_deref());
    let written = report::write(&plan, Some(&map), &outcome, &cells, &args.out, &command)
        .map_err(CliError::failed)?;
    if !args.quiet {
        eprintln!(
            "wasp: in all (the {} tasks before the grid and the grid's): {}",
            tasks.len(),
            outcome.summary()
        );
        eprintln!("wasp: wrote {}", written.display());
    }
    if !outcome.failures.is_empty() {
        for f in &outcome.failures {
            eprintln!("wasp: failed: {f}");
        }
        return Err(CliError::failed(format!(
            "{} of {} tasks failed (the report leaves their points out)",
            outcome.failures.len(),
            tasks.len()
        )));
    }
    Ok(())
}

/// The tasks before the map's grid, drawing figures into `figures`: the
/// paper's experiments (with the RGBA8 rows), then the map's one-at-a-time
/// points; and how many of them are the paper's experiments.
fn study_tasks(
    plan: &Plan,
    map: &map::plan::MapPlan,
    figures: &Path,
) -> (Vec<runner::Task>, usize) {
    let mut tasks = plan.tasks(figures);
    tasks.extend(rgba8::tasks(plan));
    let paper = tasks.len();
    tasks.extend(map::tasks(plan, map));
    (tasks, paper)
}

/// The engine scenes first: the plan again without those of its engine
/// scenes that cannot be captured or imported (the report says why).
fn without_left_out(
    args: &ReproduceArgs,
    plan: Plan,
    defs: Vec<SceneDef>,
    cache: &Cache,
    opts: &RunnerOptions,
) -> Result<Plan, CliError> {
    let left_out = engine_check::left_out(&plan, cache, opts).map_err(CliError::failed)?;
    if left_out.is_empty() {
        return Ok(plan);
    }
    let defs: Vec<SceneDef> = defs
        .into_iter()
        .filter(|d| !left_out.iter().any(|l| l.name == d.name))
        .collect();
    let mut p = Plan::with_routes(&defs, args.quick, args.machines.dispatches(), args.routes);
    p.left_out = left_out;
    Ok(p)
}

/// The plan in words on stderr, before the run.
fn say_plan(
    args: &ReproduceArgs,
    plan: &Plan,
    map: &map::plan::MapPlan,
    tasks: usize,
    jobs: usize,
) {
    eprintln!(
        "wasp: reproducing the paper{}: {} scenes{}, {} machine(s), {} tasks before the 2-D \
         grid (its tasks follow once these choose its knobs), {} at once, into {}",
        if args.quick { " (quick look)" } else { "" },
        plan.scenes.len(),
        if plan.beside.is_empty() {
            String::new()
        } else {
            format!(" and {} beside the means (--routes)", plan.beside.len())
        },
        plan.dispatches.len(),
        tasks,
        jobs,
        args.out.display()
    );
    eprintln!(
        "wasp: including {}",
        map::report::plan_text(map, &map::scene_names(plan, map), map::eligible(plan).len())
    );
}

/// The scenes of `--scenes` (names of `wasp scenes list` or definition
/// files), else every listed scene of both routes.
fn chosen_scenes(names: Option<&[String]>) -> Result<Vec<SceneDef>, CliError> {
    let all = def::every().map_err(|e| CliError::failed(e.to_string()))?;
    let Some(names) = names else {
        return Ok(all);
    };
    let mut v = Vec::new();
    for n in names {
        match all.iter().find(|d| &d.name == n) {
            Some(d) => v.push(d.clone()),
            None if n.ends_with(".toml") => v.push(
                SceneDef::load(Path::new(n))
                    .map_err(|e| CliError::usage(format!("--scenes: {e}")))?,
            ),
            None => {
                return Err(CliError::usage(format!(
                    "--scenes: no scene `{n}`; `wasp scenes list` names them"
                )))
            }
        }
    }
    let mut seen = std::collections::HashSet::new();
    if let Some(d) = v.iter().find(|d| !seen.insert(d.name.clone())) {
        return Err(CliError::usage(format!(
            "--scenes: the scene `{}` is named twice",
            d.name
        )));
    }
    if v.is_empty() {
        return Err(CliError::usage("--scenes: name at least one scene"));
    }
    Ok(v)
}

/// The command that produced a report, with every option that changes
/// its results (not `--out`, `--jobs` or `-q`), for its "Generated by"
/// line; `scenes_dir` is the folder of extra scene definitions in effect
/// (`--scenes-dir` or `WASP_SCENES_DIR`), which may replace shipped scenes.
pub fn command(args: &ReproduceArgs, scenes_dir: Option<&Path>) -> report::Command {
    let mut line = "wasp reproduce".to_string();
    if args.quick {
        line.push_str(" --quick");
    }
    if args.machines != Machines::Both {
        let m = args.machines.to_possible_value().expect("no skipped value");
        line.push_str(&format!(" --machines {}", m.get_name()));
    }
    if args.map_scenes != map::plan::SceneChoice::default() {
        let m = args
            .map_scenes
            .to_possible_value()
            .expect("no skipped value");
        line.push_str(&format!(" --map-scenes {}", m.get_name()));
    }
    if args.routes != routes::RouteChoice::default() {
        line.push_str(&format!(" --routes {}", args.routes.name()));
    }
    if let Some(s) = &args.scenes {
        line.push_str(&format!(" --scenes {}", s.join(",")));
    }
    if let Some(d) = scenes_dir {
        let d = crate::study::jobs::shell_quote(&d.display().to_string());
        line.push_str(&format!(" --scenes-dir {d}"));
    }
    report::Command {
        line,
        subset: args.scenes.is_some(),
    }
}

/// `--sweep-files DIR`: the map's sweep files.
fn write_sweep_files(
    dir: &Path,
    map: &map::plan::MapPlan,
    plan: &Plan,
    quiet: bool,
) -> Result<(), CliError> {
    std::fs::create_dir_all(dir)
        .map_err(|e| CliError::failed(format!("cannot create {}: {e}", dir.display())))?;
    let scenes = map::scene_names(plan, map);
    for (name, text) in map::sweeps::files(map, &scenes) {
        let path = dir.join(name);
        crate::study::cache::write_atomic(&path, &text).map_err(CliError::failed)?;
        if !quiet {
            eprintln!("wasp: wrote {}", path.display());
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_command_line_keeps_what_changes_the_results() {
        let args = ReproduceArgs {
            quick: true,
            out: PathBuf::from("elsewhere"),
            machines: Machines::PerCoreTile,
            scenes: Some(vec!["a".into(), "b.toml".into()]),
            scene_defs: Default::default(),
            jobs: Some(3),
            quiet: true,
            sweep_files: None,
            map_scenes: map::plan::SceneChoice::All,
            routes: routes::RouteChoice::Both,
            dry_run: false,
        };
        let c = command(&args, None);
        assert_eq!(
            c.line,
            "wasp reproduce --quick --machines per-core-tile --map-scenes all --routes both \
             --scenes a,b.toml"
        );
        assert!(c.subset);
        // A folder of scene definitions may replace shipped scenes.
        let c = command(&args, Some(Path::new("my scenes")));
        assert!(
            c.line
                .ends_with(" --scenes a,b.toml --scenes-dir 'my scenes'"),
            "{}",
            c.line
        );
        let all = ReproduceArgs {
            quick: false,
            machines: Machines::Both,
            scenes: None,
            map_scenes: map::plan::SceneChoice::Budget,
            routes: routes::RouteChoice::Engine,
            ..args
        };
        assert_eq!(command(&all, None).line, "wasp reproduce");
    }
}
