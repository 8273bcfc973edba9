//! `wasp`: the command-line front end of the wasp cycle model.

mod bench_cmd;
mod capture;
mod charts;
mod check_mesa;
mod cli_error;
mod compare_cmd;
mod compare_variants;
mod cost_cmd;
mod engine_frame;
mod engine_render;
mod example_cmd;
mod fonts;
mod game_data;
mod heat;
mod import_gl_cmd;
mod interrupt;
mod output;
mod palette;
mod picture;
mod pool;
mod reproduce;
mod run_cmd;
mod scene_cmd;
mod scenes_dir;
mod study;
mod sweep_cmd;
mod synth_cmd;
mod timeline_plot;
mod trace_cat_cmd;

use clap::{Parser, Subcommand};
use cli_error::CliError;
use std::process::ExitCode;

/// wasp: a cycle model of a tile-based-rendering mobile GPU shader core with
/// the WaSP warp scheduler ("WaSP: Warp Scheduling to Mimic Prefetching in
/// Graphics Workloads") modelled at register-transfer granularity.
///
/// With no subcommand, wasp runs the paper's worked example (`wasp example`).
#[derive(Parser, Debug)]
#[command(name = "wasp", version, about, long_about)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,

    /// No progress output on stderr, before any subcommand as after it
    /// (`wasp -q reproduce` is `wasp reproduce -q`); with no subcommand, the
    /// worked example without notes.
    #[arg(long, short)]
    quiet: bool,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// The paper's worked example (Section III-A) on the RTL scheduler.
    ///
    /// 15 warps with one texture access each (W0-W4 read block A, W5-W9 B,
    /// W10-W14 C), a single-level cache with 3 MSHRs, main memory latency 7,
    /// one access per cycle. Prints the three chronographs of the paper's
    /// figure: scanline order (the baseline), all priority warps first
    /// (Fullpriority) and the WaSP launch rule, with their cycle and stall
    /// totals. The launch orders come from the launch policies running on
    /// the RTL blocks (split queue, 5-bit free-MSHR register, 7-bit
    /// non-blocked priority counter, x CF shift-add, subtract, compare).
    Example(example_cmd::ExampleArgs),

    /// Simulate a workload trace on the GPU model and report statistics.
    ///
    /// The whole GPU: shader cores with the launch scheduler at
    /// register-transfer granularity, L0/L1 texture caches, shared L2 and
    /// open-row DRAM, all with MSHRs. Prints a table (or JSON/CSV with
    /// --json/--csv), optionally writes the waveform with --vcd.
    Run(run_cmd::RunArgs),

    /// Run several launch policies on the same trace and print speedups
    /// against the first (the scanline baseline by default).
    Compare(compare_cmd::CompareArgs),

    /// Write a synthetic workload trace (a textured-surface model with a
    /// stated memory-instruction ratio and block reuse), and report the
    /// figures it measures. Synthetic workloads say so in their names.
    Synth(synth_cmd::SynthArgs),

    /// Join traces into one trace of several frames: the frames of each
    /// file after those of the one before (`wasp trace-cat A.trace
    /// B.trace --out AB.trace`). `run` and `compare` run the frames in
    /// order, caches and DRAM carrying over, and report the last frame;
    /// `--warm K` runs only the K frames before it.
    TraceCat(trace_cat_cmd::TraceCatArgs),

    /// The hardware overhead of WaSP: an inventory from the RTL blocks in
    /// bits and gate equivalents, the Verilog twin synthesized by Yosys, and
    /// the register file it saves.
    Cost(cost_cmd::CostArgs),

    /// Measure simulation speed: simulated core-cycles per second with
    /// tracing off and on, and its growth with tile count and warp count.
    /// Build with --release for meaningful numbers.
    Bench(bench_cmd::BenchArgs),

    /// List the scene definitions (built in, plus --scenes-dir) and fetch real games' data.
    ///
    /// Game data (SuperTuxKart, OpenArena, Teeworlds, Frozen Bubble) comes
    /// from Debian's packages into a cache outside the repository
    /// ($WASP_SCENES, else ~/.cache/wasp/scenes); procedural scenes need
    /// nothing.
    Scenes(scene_cmd::ScenesArgs),

    /// Rasterize a scene through the TBR front end and write the frame as
    /// a PNG (real texel colours) with optional overlays (tile grid,
    /// priority subset, per-quad heat map from a cycle-model run), and/or
    /// save its trace for `wasp run --trace`.
    Render(scene_cmd::RenderArgs),

    /// Import one frame of an apitrace capture of a fixed-function OpenGL
    /// 1.x program: its draw calls, in issue order and with the state the
    /// program set, through wasp's rasterizer, Early-Z and texture path
    /// into a trace (docs/import-gl.md). Prints a summary.
    ImportGl(import_gl_cmd::ImportGlArgs),

    /// Characterise scenes like the paper's Table I: memory-instruction
    /// ratio, block reuse in tile, CF, Min_Estimate1/2 and the texture
    /// footprint ratio of every priority subset, beside the paper's values.
    Characterize(scene_cmd::CharacterizeArgs),

    /// Reproduce the paper's evaluation: every experiment of Sections III
    /// and V on the shipped scenes, under the paper's shared-tile machine
    /// and the per-core-tile machine, in parallel and resumable, with plots
    /// (PNG, SVG), data (CSV, JSON) and REPORT.md setting the paper's
    /// numbers beside ours.
    Reproduce(reproduce::ReproduceArgs),

    /// Run a grid of simulations described by a sweep file: scenes x
    /// configurations x dispatch modes x launch policies (docs/sweep.md).
    ///
    /// Points run in parallel, each scene rendered once; finished points are
    /// stored in the --out folder and skipped by a rerun. Writes
    /// DIR/results.csv and DIR/results.json and prints cycles and speedups
    /// against the first policy. For a cluster, --jobs-file writes one
    /// command per point (`--point N`), and `wasp merge` combines them.
    Sweep(sweep_cmd::SweepArgs),

    /// Combine the point results of study folders (e.g. one per cluster
    /// node) into one table: CSV on standard output by default.
    ///
    /// With --sweep FILE the rows are that sweep's points in order, as in
    /// its results.csv, and points without a result are listed (exit 1).
    Merge(sweep_cmd::MergeArgs),
}

fn main() -> ExitCode {
    // A reader that stops early (`wasp scenes list | head -3`) ends wasp
    // quietly, as it does other Unix tools, instead of `println!`
    // panicking on the broken pipe: the Rust runtime ignores SIGPIPE, so
    // the default action is restored before anything is written.
    #[cfg(unix)]
    // SAFETY: setting a signal's disposition to its default at start, with
    // no other thread running and no handler involved.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let mut cli = Cli::parse();
    if let Some(c) = cli.command.as_mut() {
        *c.quiet_mut() |= cli.quiet;
    }
    let result = cli
        .command
        .as_ref()
        .and_then(Command::scenes_dir)
        .map_or(Ok(()), scenes_dir::ScenesDir::apply)
        .and_then(|()| dispatch(cli));
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("wasp: error: {e}");
            ExitCode::from(e.exit_code())
        }
    }
}

impl Command {
    /// The subcommand's own `-q`, which a `-q` before it sets too.
    fn quiet_mut(&mut self) -> &mut bool {
        match self {
            Command::Example(a) => &mut a.quiet,
            Command::Run(a) => &mut a.inputs.quiet,
            Command::Compare(a) => &mut a.inputs.quiet,
            Command::Synth(a) => &mut a.quiet,
            Command::TraceCat(a) => &mut a.quiet,
            Command::Cost(a) => &mut a.quiet,
            Command::Bench(a) => &mut a.quiet,
            Command::Scenes(a) => a.quiet_mut(),
            Command::Render(a) => &mut a.quiet,
            Command::ImportGl(a) => &mut a.quiet,
            Command::Characterize(a) => &mut a.quiet,
            Command::Reproduce(a) => &mut a.quiet,
            Command::Sweep(a) => &mut a.quiet,
            Command::Merge(a) => &mut a.quiet,
        }
    }

    /// The `--scenes-dir` option of the commands that read scene
    /// definitions.
    fn scenes_dir(&self) -> Option<&scenes_dir::ScenesDir> {
        match self {
            Command::Scenes(a) => a.scenes_dir(),
            Command::Render(a) => Some(&a.scene_defs),
            Command::Characterize(a) => Some(&a.scene_defs),
            Command::Reproduce(a) => Some(&a.scene_defs),
            Command::Sweep(a) => Some(&a.scene_defs),
            Command::Merge(a) => Some(&a.scene_defs),
            _ => None,
        }
    }
}

/// Run the command.
fn dispatch(cli: Cli) -> Result<(), CliError> {
    match cli.command {
        Some(Command::Example(args)) => example_cmd::run(&args),
        Some(Command::Run(args)) => run_cmd::run(&args),
        Some(Command::Compare(args)) => compare_cmd::compare(&args),
        Some(Command::Bench(args)) => bench_cmd::run(&args),
        Some(Command::Cost(args)) => cost_cmd::run(&args),
        Some(Command::Synth(args)) => synth_cmd::run(&args),
        Some(Command::TraceCat(args)) => trace_cat_cmd::run(&args),
        Some(Command::Scenes(args)) => scene_cmd::scenes(&args),
        Some(Command::Render(args)) if engine_render::is_engine_scene(&args.scene) => {
            engine_render::render(&args)
        }
        Some(Command::Render(args)) => scene_cmd::render(&args),
        Some(Command::ImportGl(args)) => import_gl_cmd::run(&args),
        Some(Command::Characterize(args)) => scene_cmd::characterize(&args),
        Some(Command::Reproduce(args)) => reproduce::run(&args),
        Some(Command::Sweep(args)) => sweep_cmd::sweep(&args),
        Some(Command::Merge(args)) => sweep_cmd::merge(&args),
        None => example_cmd::run(&example_cmd::ExampleArgs {
            quiet: cli.quiet,
            ..example_cmd::ExampleArgs::default()
        }),
    }
}
