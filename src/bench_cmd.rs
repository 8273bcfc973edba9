//! `wasp bench`: simulated core-cycles per second.
//!
//! How to read it: each row is one point, the best of `--repeats` samples;
//! a sample runs the point's simulation from reset, whole, as many times as
//! fills `--min-seconds` (column `runs`), so even short workloads are timed
//! over a long enough span. `seconds` and `core-cycles/s` are wall time per
//! run and its rate; `cpu-cc/s` is the rate over the thread's own on-CPU
//! time (Linux), which a loaded machine disturbs much less: compare rates
//! with it. Rows `tracing` (modes off, hooks, visitor, vcd, sampled in
//! turns) price tracing on one workload; the last line is the hook's
//! overhead with tracing off (hooks vs off), by both measures. Rows `tiles`
//! and `warps` show how the rate changes with the workload and warp slots.
//! `median` is the median sample's rate (by on-CPU time) and `spread` how
//! much slower the slowest sample was than the fastest: a difference
//! between points smaller than their spread is noise, and a warning says
//! so when a spread passes 10%.

use crate::cli_error::CliError;
use crate::output::{self, emit, Output};
use clap::builder::RangedU64ValueParser;
use clap::Args;
use std::path::PathBuf;
use wasp_sim::bench;
use wasp_sim::config::MachineConfig;

/// Options of `wasp bench`.
#[derive(Args, Debug, Clone)]
#[command(after_long_help = "\
Reading the table: every row is the best of --repeats samples; a sample \
simulates the point's workload from reset, whole, as many times as it takes \
to fill --min-seconds (column runs), and reports time per run. seconds and \
core-cycles/s are wall time; cpu-cc/s is core-cycles per second of the \
thread's on-CPU time (Linux), far less disturbed by other load: compare \
that. The tracing rows (off, hooks, visitor, vcd) are sampled in turns; \
the last line gives the tracing hook's overhead with tracing off (hooks \
path vs hook-free path) by wall and by CPU time. The tiles and warps rows \
show the rate against workload size and warp slots (tracing off). median \
is the median sample's cpu-cc/s and spread how much slower the slowest \
sample was than the fastest: differences smaller than the spread are noise.")]
pub struct BenchArgs {
    /// Machine configuration (TOML); default: the embedded paper.toml.
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// Workload size multiplier, 1..=64 (1: 32, 4..64 tiles; 64: 2048,
    /// 256..4096 tiles).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=MAX_SCALE as i64))]
    pub scale: u32,
    /// Measure the tracing and warp points on this trace instead of the
    /// generated 8x4-tile workload (and time reading it and its workload
    /// statistics).
    #[arg(long, value_name = "FILE")]
    pub trace: Option<PathBuf>,
    /// Samples per point, 1..=100; the fastest is kept.
    #[arg(long, default_value_t = 3, value_parser = RangedU64ValueParser::<usize>::new().range(1..=MAX_REPEATS))]
    pub repeats: usize,
    /// Least time of one sample, in seconds: whole runs are repeated until
    /// it has passed.
    #[arg(long, value_name = "SECONDS", default_value_t = bench::MIN_SAMPLE_SECONDS)]
    pub min_seconds: f64,
    /// Write the points as JSON to FILE (`-` for standard output).
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// No progress output on stderr (progress bars, notes of what is being
    /// done); results, warnings and errors still print.
    /// (Bench's rows on stderr are its result, and print.)
    #[arg(long, short)]
    pub quiet: bool,
}

/// Largest `--scale` (wasp): the growth rows then reach 4096 tiles, about
/// a 2048x2048 frame of 32x32 tiles, minutes of simulation per sample.
const MAX_SCALE: u32 = 64;

/// Most `--repeats` (wasp): more samples than this add time, not accuracy.
const MAX_REPEATS: u64 = 100;

/// A spread of samples above this is worth a warning.
const NOISY: f64 = 0.10;

/// Run the benchmark.
pub fn run(args: &BenchArgs) -> Result<(), CliError> {
    output::check(
        &[Output::new("--json", args.json.as_deref())],
        &[
            output::Input::file("--config", args.config.as_deref()),
            output::Input::file("--trace", args.trace.as_deref()),
        ],
    )?;
    let cfg = match &args.config {
        Some(p) => crate::run_cmd::read_config(p)?,
        None => MachineConfig::paper(),
    };
    if cfg!(debug_assertions) {
        eprintln!("wasp bench: this is a debug build; measure with `cargo run --release -- bench`");
    }
    if !(args.min_seconds.is_finite() && args.min_seconds >= 0.0) {
        return Err(CliError::usage(
            "--min-seconds must be a non-negative number".to_string(),
        ));
    }
    let trace = match &args.trace {
        Some(p) => Some(read_timed(p)?),
        None => None,
    };
    eprintln!(
        "{:<8}{:>8}{:>8}{:>7}{:>12}{:>14}{:>10}{:>16}{:>6}{:>14}{:>14}{:>8}",
        "point",
        "mode",
        "tiles",
        "warps",
        "cycles",
        "core-cycles",
        "seconds",
        "core-cycles/s",
        "runs",
        "cpu-cc/s",
        "median",
        "spread"
    );
    let points = bench::run(
        &cfg,
        args.scale,
        args.repeats,
        args.min_seconds,
        trace.as_ref(),
        &mut print_row,
    )
    .map_err(|e| CliError::failed(e.to_string()))?;
    print_overheads(&points);
    if let Some(p) = &args.json {
        let text = serde_json::to_string_pretty(&points)
            .map_err(|e| CliError::failed(format!("encoding JSON: {e}")))?
            + "\n";
        emit(p, &text)?;
    }
    Ok(())
}

/// Read the trace `p`, timing the read and its workload statistics (outside
/// the cycle loop but part of every `wasp run` on it: timed once).
fn read_timed(p: &std::path::Path) -> Result<wasp_sim::trace::Trace, CliError> {
    let start = std::time::Instant::now();
    let t = wasp_sim::trace::Trace::read(p).map_err(|e| CliError::usage(e.to_string()))?;
    let read = start.elapsed().as_secs_f64();
    let start = std::time::Instant::now();
    std::hint::black_box(t.stats());
    let stats = start.elapsed().as_secs_f64();
    let mb = std::fs::metadata(p).map(|m| m.len()).unwrap_or(0) as f64 / 1e6;
    eprintln!(
        "trace {}: read in {read:.3} s ({:.0} MB/s), workload statistics in {stats:.3} s (one run each)",
        p.display(),
        mb / read.max(1e-9)
    );
    Ok(t)
}

/// One row of the table, as its point ends.
fn print_row(p: &bench::Point) {
    let cpu = p
        .core_cycles_per_cpu_second
        .map_or("-".to_string(), |r| format!("{r:.0}"));
    eprintln!(
        "{:<8}{:>8}{:>8}{:>7}{:>12}{:>14}{:>10.4}{:>16.0}{:>6}{:>14}{:>14.0}{:>7.1}%",
        p.label,
        format!("{:?}", p.mode).to_lowercase(),
        p.tiles,
        p.max_warps,
        p.cycles,
        p.core_cycles,
        p.seconds,
        p.core_cycles_per_second,
        p.runs_per_sample,
        cpu,
        p.median_core_cycles_per_second,
        100.0 * p.spread
    );
}

/// The tracing hook's overhead and, when samples spread widely, a warning.
fn print_overheads(points: &[bench::Point]) {
    let point = |m: bench::Mode| points.iter().find(|p| p.label == "tracing" && p.mode == m);
    if let (Some(off), Some(hooks)) = (point(bench::Mode::Off), point(bench::Mode::Hooks)) {
        let cpu = match (off.cpu_seconds, hooks.cpu_seconds) {
            (Some(o), Some(h)) => format!(", {:+.2}% by CPU time", 100.0 * (h / o - 1.0)),
            _ => String::new(),
        };
        eprintln!(
            "tracing hook overhead with tracing off: {:+.2}% by wall time{cpu} (hooks path vs hook-free path)",
            100.0 * (hooks.seconds / off.seconds - 1.0)
        );
    }
    if let Some(worst) = points.iter().max_by(|a, b| a.spread.total_cmp(&b.spread)) {
        if worst.spread > NOISY {
            eprintln!(
                "wasp bench: the samples of one point differ by up to {:.0}% ({} {}): this machine is busy or noisy, \
                 and differences smaller than that are not measured; compare medians, or re-run with more --repeats",
                100.0 * worst.spread,
                worst.label,
                format!("{:?}", worst.mode).to_lowercase()
            );
        }
    }
}
