//! `wasp cost`: the hardware-overhead report.

use crate::cli_error::CliError;
use crate::output::{self, emit, Output};
use clap::Args;
use std::path::{Path, PathBuf};
use wasp_rtl::cost::GateRules;
use wasp_sim::config::limits::MAX_WARPS;
use wasp_sim::cost::{report, RfParams};

/// Options of `wasp cost`.
#[derive(Args, Debug, Clone)]
pub struct CostArgs {
    /// Machine configuration (TOML); default: the embedded paper.toml.
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// Change one configuration field, e.g. `--set core.max_warps=32`
    /// (dotted TOML path = TOML value; repeatable, applied in order after
    /// --config, as in `wasp run`). The report names the machine with its
    /// overrides.
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub set: Vec<String>,
    /// Do not run Yosys on the Verilog twin.
    #[arg(long)]
    pub no_yosys: bool,
    /// Registers per thread, 1..=1024 as core.registers_per_thread
    /// (default: core.registers_per_thread).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub registers_per_thread: Option<u32>,
    /// Warps the baseline needs to match WaSP, 2..=128 as core.max_warps
    /// (default: the paper's figure for the machine's width: 48 at width 2,
    /// 64 at width 4).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(2..=MAX_WARPS as i64))]
    pub baseline_warps: Option<u32>,
    /// Warps WaSP needs, 1..=127 and fewer than the baseline's (default: the
    /// paper's 32 at width 2, 48 at width 4).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..MAX_WARPS as i64))]
    pub wasp_warps: Option<u32>,
    /// Write the report as JSON to FILE (`-` for standard output, in place
    /// of the table).
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// No progress output on stderr; results, warnings and errors still
    /// print. (Cost shows none.)
    #[arg(long, short)]
    pub quiet: bool,
}

/// Run the command.
pub fn run(args: &CostArgs) -> Result<(), CliError> {
    output::check(
        &[Output::new("--json", args.json.as_deref())],
        &[output::Input::file("--config", args.config.as_deref())],
    )?;
    let sets = crate::run_cmd::parse_sets(&args.set)?;
    let cfg = crate::run_cmd::machine(args.config.as_deref(), &sets)?;
    let mut rf = RfParams::for_config(&cfg);
    if let Some(r) = args.registers_per_thread {
        rf.registers_per_thread = r;
    }
    if args.baseline_warps.is_some() || args.wasp_warps.is_some() {
        rf.baseline_warps = args.baseline_warps.unwrap_or(rf.baseline_warps);
        rf.wasp_warps = args.wasp_warps.unwrap_or(rf.wasp_warps);
        // The report prices the register file of the warps WaSP saves: with
        // none saved there is nothing to price it against.
        if rf.wasp_warps >= rf.baseline_warps {
            return Err(CliError::usage(format!(
                "--wasp-warps {} with --baseline-warps {}: WaSP must need fewer warps than \
                 the baseline (the register file it saves is their difference)",
                rf.wasp_warps, rf.baseline_warps
            )));
        }
        rf.source = format!(
            "given: WaSP with {} warps matches the baseline with {}",
            rf.wasp_warps, rf.baseline_warps
        );
        rf.caveat = "These warp counts are given on the command line: an assumption, not a \
                     measurement. `wasp reproduce`'s sensitivity rows (REPORT.md) measure \
                     WaSP with fewer warps against the baseline on the shipped scenes."
            .into();
    }
    let r = report(&cfg, GateRules::default(), &rf, !args.no_yosys).map_err(CliError::usage)?;
    let json_stdout = output::to_stdout(&args.json);
    if let Some(p) = &args.json {
        let text = serde_json::to_string_pretty(&r)
            .map_err(|e| CliError::failed(format!("encoding JSON: {e}")))?
            + "\n";
        emit(p, &text)?;
    }
    if !json_stdout {
        emit(Path::new("-"), &r.to_table())?;
    }
    Ok(())
}
