//! `wasp bench`: simulated core-cycles per second.

use crate::run_cmd::emit;
use crate::CliError;
use clap::Args;
use std::path::PathBuf;
use wasp_sim::bench;
use wasp_sim::config::MachineConfig;

/// Options of `wasp bench`.
#[derive(Args, Debug, Clone)]
pub struct BenchArgs {
    /// Machine configuration (TOML); default: the embedded paper.toml.
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// Workload size multiplier (1: 32, 4..64 tiles).
    #[arg(long, default_value_t = 1)]
    pub scale: u32,
    /// Measure the tracing and warp points on this trace instead of the
    /// generated 8x4-tile workload.
    #[arg(long, value_name = "FILE")]
    pub trace: Option<PathBuf>,
    /// Runs per point; the fastest is kept.
    #[arg(long, default_value_t = 3)]
    pub repeats: usize,
    /// Write the points as JSON to FILE (`-`: stdout).
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
}

/// Run the benchmark.
pub fn run(args: &BenchArgs) -> Result<(), CliError> {
    let cfg = match &args.config {
        Some(p) => MachineConfig::load(p).map_err(|e| CliError::usage(e.to_string()))?,
        None => MachineConfig::paper(),
    };
    if cfg!(debug_assertions) {
        eprintln!("wasp bench: this is a debug build; measure with `cargo run --release -- bench`");
    }
    eprintln!(
        "{:<8}{:>8}{:>8}{:>7}{:>12}{:>14}{:>10}{:>16}",
        "point", "mode", "tiles", "warps", "cycles", "core-cycles", "seconds", "core-cycles/s"
    );
    let trace = match &args.trace {
        Some(p) => {
            Some(wasp_sim::trace::Trace::read(p).map_err(|e| CliError::usage(e.to_string()))?)
        }
        None => None,
    };
    let points = bench::run(&cfg, args.scale, args.repeats, trace.as_ref(), &mut |p| {
        eprintln!(
            "{:<8}{:>8}{:>8}{:>7}{:>12}{:>14}{:>10.3}{:>16.0}",
            p.label,
            format!("{:?}", p.mode).to_lowercase(),
            p.tiles,
            p.max_warps,
            p.cycles,
            p.core_cycles,
            p.seconds,
            p.core_cycles_per_second
        );
    })
    .map_err(|e| CliError::failed(e.to_string()))?;
    let rate = |m: bench::Mode| {
        points
            .iter()
            .find(|p| p.label == "tracing" && p.mode == m)
            .map(|p| p.seconds)
    };
    if let (Some(off), Some(hooks)) = (rate(bench::Mode::Off), rate(bench::Mode::Hooks)) {
        eprintln!(
            "tracing hook overhead with tracing off: {:+.2}% (hooks path vs hook-free path)",
            100.0 * (hooks / off - 1.0)
        );
    }
    if let Some(p) = &args.json {
        let text = serde_json::to_string_pretty(&points)
            .map_err(|e| CliError::failed(format!("encoding JSON: {e}")))?
            + "\n";
        emit(p, &text)?;
    }
    Ok(())
}
