//! `wasp sweep` and `wasp merge`: a user's grid of simulations
//! (docs/sweep.md), run here in parallel or as one cluster job per point,
//! and its results combined from any number of study folders.

use crate::cli_error::CliError;
use crate::output::{self, emit, Output};
use crate::scenes_dir::ScenesDir;
use crate::study::cache::{read_points, write_atomic, Cache, PointRecord};
use crate::study::jobs;
use crate::study::merge;
use crate::study::runner::{self, RunnerOptions, Task};
use crate::study::sweep::{self, Sweep, SweepPoint};
use clap::Args;
use std::path::{Path, PathBuf};
use wasp_frontend::{def, fetch};

/// Options of `wasp sweep`.
#[derive(Args, Debug, Clone)]
pub struct SweepArgs {
    /// The sweep file (TOML; see docs/sweep.md).
    pub file: PathBuf,

    #[command(flatten)]
    pub scene_defs: ScenesDir,

    /// The study folder: finished points (`points/`), `results.csv` and
    /// `results.json`. A rerun skips the points it holds.
    #[arg(long, value_name = "DIR", default_value = "sweep-out")]
    pub out: PathBuf,

    /// Simulations at once (default: the machine's cores). Not with
    /// --jobs-file or --list, which run nothing.
    #[arg(long, value_name = "N", conflicts_with_all = ["jobs_file", "list"])]
    pub jobs: Option<usize>,

    /// Write one shell command per point to FILE (`-` for standard output;
    /// line N runs point N with --point N) for a cluster, instead of
    /// running anything.
    #[arg(long, value_name = "FILE", conflicts_with_all = ["point", "list"])]
    pub jobs_file: Option<PathBuf>,

    /// Print `N<TAB>description` for every point, and run nothing.
    #[arg(long, conflicts_with = "point")]
    pub list: bool,

    /// Run only point N (from 1; see --list) and store its result in the
    /// folder; `wasp merge` makes the tables.
    #[arg(long, value_name = "N")]
    pub point: Option<usize>,

    /// No progress output on stderr; results, warnings and errors still
    /// print.
    #[arg(long, short)]
    pub quiet: bool,
}

/// Options of `wasp merge`.
#[derive(Args, Debug, Clone)]
pub struct MergeArgs {
    /// Study folders (of `wasp sweep --out`, or their `points/` folders).
    #[arg(required = true, value_name = "DIR")]
    pub dirs: Vec<PathBuf>,

    /// The sweep file: one row per point in sweep order, with its columns
    /// (point, config, dispatch, policy, scene, draw_order); points without
    /// a result are listed and the exit code is 1.
    #[arg(long, value_name = "FILE")]
    pub sweep: Option<PathBuf>,

    /// With --sweep: a folder of extra scene definitions the sweep names.
    #[command(flatten)]
    pub scene_defs: ScenesDir,

    /// Write the table as CSV to FILE (`-` for standard output; the
    /// default when neither --csv nor --json is given).
    #[arg(long, value_name = "FILE")]
    pub csv: Option<PathBuf>,

    /// Write the records as JSON to FILE (`-` for standard output).
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,

    /// No progress output on stderr; results, warnings and errors still
    /// print. (Merge shows none.)
    #[arg(long, short)]
    pub quiet: bool,
}

/// Read the sweep file and expand it, every machine resolved.
fn load(file: &Path) -> Result<(Sweep, Vec<SweepPoint>), CliError> {
    let s = Sweep::load(file).map_err(CliError::usage)?;
    let points = s.points().map_err(CliError::usage)?;
    Ok((s, points))
}

/// Run `wasp sweep`.
pub fn sweep(args: &SweepArgs) -> Result<(), CliError> {
    let (s, points) = load(&args.file)?;
    if args.list {
        return emit(Path::new("-"), &sweep::listing(&points));
    }
    output::folder("--out", &args.out, "points/, results.csv and results.json")?;
    let out = sweep::absolute(&args.out).map_err(CliError::usage)?;
    if let Some(jobs) = &args.jobs_file {
        output::check(
            &[Output::new("--jobs-file", Some(jobs))],
            &sweep_inputs(args, &bases(&s)),
        )?;
        return write_jobs(args, &s, jobs, &out, &points);
    }
    let chosen: Vec<&SweepPoint> = match args.point {
        Some(n) if (1..=points.len()).contains(&n) => vec![&points[n - 1]],
        Some(n) => {
            return Err(CliError::usage(format!(
                "--point {n}: {} has points 1 to {} (see --list)",
                s.shown,
                points.len()
            )))
        }
        None => points.iter().collect(),
    };
    let cache = Cache::open(&out).map_err(CliError::failed)?;
    if args.point.is_none() {
        let (csv, json) = (out.join("results.csv"), out.join("results.json"));
        output::check(
            &[
                Output::new("--out's results.csv", Some(&csv)),
                Output::new("--out's results.json", Some(&json)),
            ],
            &sweep_inputs(args, &bases(&s)),
        )?;
    }
    if args.point.is_none() {
        crate::interrupt::say_resume_on_interrupt(&out, &crate::study::jobs::command_line());
    }
    let tasks: Vec<Task> = chosen.iter().map(|p| Task::Run(p.point.clone())).collect();
    let opts = RunnerOptions {
        jobs: args
            .jobs
            .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get())),
        quiet: args.quiet,
        // A cluster job never fetches: concurrent fetches into one scene
        // cache would race, so the error names `wasp scenes fetch`.
        fetch: args.point.is_none(),
        label: "sweep".into(),
        scenes: Vec::new(),
    };
    let outcome = runner::run(&tasks, &cache, &opts).map_err(CliError::failed)?;
    write_results(args, &s, &out, points.len(), &chosen, &outcome)?;
    if !args.quiet {
        eprintln!("wasp: {}", outcome.summary());
    }
    if !outcome.failures.is_empty() {
        let n = outcome.failures.len();
        let mut m = format!("{n} of {} points failed:", chosen.len());
        for f in outcome.failures.iter().take(10) {
            m.push_str("\n  ");
            m.push_str(f);
        }
        if n > 10 {
            m.push_str("\n  ...");
        }
        return Err(CliError::failed(m));
    }
    Ok(())
}

/// The results of the `chosen` points of a sweep of `total`: the tables in
/// the folder `out` and the summary on standard output (for `--point N`,
/// its cycles only).
fn write_results(
    args: &SweepArgs,
    s: &Sweep,
    out: &Path,
    total: usize,
    chosen: &[&SweepPoint],
    outcome: &runner::Outcome,
) -> Result<(), CliError> {
    let stored: Vec<(&SweepPoint, PointRecord)> = chosen
        .iter()
        .filter_map(|p| outcome.get(&p.point).map(|r| (*p, merge::as_stored(r))))
        .collect();
    let rows: Vec<(&SweepPoint, &PointRecord)> = stored.iter().map(|(p, r)| (*p, r)).collect();
    if args.point.is_none() {
        let csv = out.join("results.csv");
        let json = out.join("results.json");
        write_atomic(&csv, &merge::results_csv(&rows)).map_err(CliError::failed)?;
        write_atomic(&json, &merge::results_json(&rows)).map_err(CliError::failed)?;
        if !args.quiet {
            eprintln!("wasp: wrote {} and {}", csv.display(), json.display());
        }
    }
    match (args.point, rows.first()) {
        (Some(n), Some((p, r))) => println!(
            "point {n}/{total} ({}): {:.0} cycles",
            p.describe(),
            r.cycles()
        ),
        (Some(_), None) => {}
        (None, _) => emit(Path::new("-"), &merge::results_table(&rows, &s.policies[0]))?,
    }
    Ok(())
}

/// The configuration files a sweep names (its entries' bases that are
/// files).
fn bases(s: &Sweep) -> Vec<PathBuf> {
    s.configs
        .iter()
        .map(|c| PathBuf::from(&c.base))
        .filter(|p| p.is_absolute())
        .collect()
}

/// What `wasp sweep` reads, which no output may overwrite: the sweep file,
/// the configuration files it names and the scene definitions' folder.
fn sweep_inputs<'a>(args: &'a SweepArgs, bases: &'a [PathBuf]) -> Vec<output::Input<'a>> {
    let mut v = vec![
        output::Input::file("the sweep file", Some(&args.file)),
        output::Input::folder(
            "--scenes-dir",
            args.scene_defs.scenes_dir.as_deref(),
            "toml",
        ),
    ];
    v.extend(
        bases
            .iter()
            .map(|b| output::Input::file("a configuration the sweep file names", Some(b))),
    );
    v
}

/// Write the jobs file and say how to run it.
fn write_jobs(
    args: &SweepArgs,
    s: &Sweep,
    jobs: &Path,
    out: &Path,
    points: &[SweepPoint],
) -> Result<(), CliError> {
    let exe = std::env::current_exe()
        .map_err(|e| CliError::failed(format!("cannot find the wasp executable: {e}")))?;
    let file = std::fs::canonicalize(&args.file)
        .map_err(|e| CliError::usage(format!("{}: {e}", args.file.display())))?;
    let text = jobs::jobs_text(&exe, &file, out, points.len());
    emit(jobs, &text)?;
    let mut games: Vec<def::Game> = Vec::new();
    for d in def::all().map_err(|e| CliError::failed(e.to_string()))? {
        let used = s.scenes.contains(&d.name);
        if used && !fetch::is_fetched(d.game) && !games.contains(&d.game) {
            games.push(d.game);
        }
    }
    for g in games {
        eprintln!(
            "wasp: warning: the {0} data is not fetched here; run `wasp scenes fetch {0}` \
             before the jobs (they do not fetch)",
            g.name()
        );
    }
    if output::is_stdout(jobs) {
        // The jobs are the standard output: how to run them would mix in.
        return Ok(());
    }
    let abs_jobs = sweep::absolute(jobs).map_err(CliError::usage)?;
    emit(
        Path::new("-"),
        &jobs::how_to_run(&exe, &file, out, &abs_jobs, points.len()),
    )
}

/// Run `wasp merge`.
pub fn merge(args: &MergeArgs) -> Result<(), CliError> {
    for d in &args.dirs {
        if !d.is_dir() {
            return Err(CliError::usage(format!("{}: no such folder", d.display())));
        }
    }
    let points_dirs: Vec<PathBuf> = args
        .dirs
        .iter()
        .map(|d| match d.join("points").is_dir() {
            true => d.join("points"),
            false => d.clone(),
        })
        .collect();
    let mut inputs = vec![output::Input::file("--sweep", args.sweep.as_deref())];
    inputs.extend(
        points_dirs
            .iter()
            .map(|d| output::Input::folder("the study folder", Some(d), "json")),
    );
    output::check(
        &[
            Output::new("--csv", args.csv.as_deref()),
            Output::new("--json", args.json.as_deref()),
        ],
        &inputs,
    )?;
    let swept = match &args.sweep {
        Some(f) => Some(load(f)?),
        None => None,
    };
    let records = read_records(&args.dirs)?;
    let records = merge::combine(records).map_err(CliError::failed)?;
    let (csv, json) = (args.csv.clone(), args.json.clone());
    let csv = match (&csv, &json) {
        (None, None) => Some(PathBuf::from("-")),
        _ => csv,
    };
    let Some((_, points)) = swept else {
        let all: Vec<&PointRecord> = records.iter().collect();
        if let Some(w) = merge::mixed_builds(&all) {
            eprintln!("wasp: warning: {w}");
        }
        if let Some(p) = &csv {
            emit(p, &crate::study::table::points_csv(&all))?;
        }
        if let Some(p) = &json {
            let text = serde_json::to_string_pretty(&records)
                .map_err(|e| CliError::failed(format!("encoding JSON: {e}")))?;
            emit(p, &(text + "\n"))?;
        }
        return Ok(());
    };
    merge_sweep(args, &points, &records, csv.as_deref(), json.as_deref())
}

/// The point records of the study folders `dirs`, sorted by scene and key;
/// an error when there are none, a warning for each folder without any.
fn read_records(dirs: &[PathBuf]) -> Result<Vec<PointRecord>, CliError> {
    let mut records = Vec::new();
    for d in dirs {
        let found = read_points(std::slice::from_ref(d)).map_err(CliError::failed)?;
        if found.is_empty() && dirs.len() > 1 {
            eprintln!("wasp: warning: {} holds no point records", d.display());
        }
        records.extend(found);
    }
    records.sort_by(|a, b| (&a.point.scene, &a.key).cmp(&(&b.point.scene, &b.key)));
    if records.is_empty() {
        let names: Vec<String> = dirs.iter().map(|d| d.display().to_string()).collect();
        return Err(CliError::failed(format!(
            "no point records in {} (a study folder holds them in points/SCENE.KEY.json): \
             nothing to merge",
            names.join(", ")
        )));
    }
    Ok(records)
}

/// The rows of the sweep's `points` from `records`; the points without a
/// result are listed (exit code 1).
fn merge_sweep(
    args: &MergeArgs,
    points: &[SweepPoint],
    records: &[PointRecord],
    csv: Option<&Path>,
    json: Option<&Path>,
) -> Result<(), CliError> {
    let found = merge::match_points(points, records).map_err(CliError::failed)?;
    let rows: Vec<(&SweepPoint, &PointRecord)> = points
        .iter()
        .zip(&found)
        .filter_map(|(p, r)| r.map(|r| (p, r)))
        .collect();
    let used: Vec<&PointRecord> = rows.iter().map(|(_, r)| *r).collect();
    if let Some(w) = merge::mixed_builds(&used) {
        eprintln!("wasp: warning: {w}");
    }
    if let Some(p) = csv {
        emit(p, &merge::results_csv(&rows))?;
    }
    if let Some(p) = json {
        emit(p, &merge::results_json(&rows))?;
    }
    let missing: Vec<usize> = points
        .iter()
        .zip(&found)
        .filter(|(_, r)| r.is_none())
        .map(|(p, _)| p.index)
        .collect();
    if !missing.is_empty() {
        let file =
            sweep::absolute(args.sweep.as_deref().expect("a sweep")).map_err(CliError::usage)?;
        let dir = sweep::absolute(&args.dirs[0]).map_err(CliError::usage)?;
        return Err(CliError::failed(merge::missing_message(
            &missing,
            points.len(),
            &jobs::shell_quote(&file.display().to_string()),
            &jobs::shell_quote(&dir.display().to_string()),
        )));
    }
    Ok(())
}
