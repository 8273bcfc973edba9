//! `wasp`: the command-line front end of the wasp cycle model.

mod example_cmd;

use clap::{Parser, Subcommand};
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
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Some(Command::Example(args)) => example_cmd::run(&args),
        None => example_cmd::run(&example_cmd::ExampleArgs::default()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("wasp: error: {e}");
            ExitCode::from(e.exit_code())
        }
    }
}

/// An error the CLI reports: a message and an exit code (2 for bad input,
/// 1 for failures while running).
#[derive(Debug)]
pub struct CliError {
    message: String,
    usage: bool,
}

impl CliError {
    /// Bad input from the user (exit code 2).
    pub fn usage(message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
            usage: true,
        }
    }

    /// A failure while running (exit code 1).
    pub fn failed(message: impl Into<String>) -> Self {
        Self {
            message: message.into(),
            usage: false,
        }
    }

    fn exit_code(&self) -> u8 {
        if self.usage {
            2
        } else {
            1
        }
    }
}

impl std::fmt::Display for CliError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}
