//! `wasp trace-cat`: join traces into one trace of several frames, the
//! frames of each file after those of the one before.

use crate::cli_error::CliError;
use crate::output::{self, emit, Input, Output};
use clap::Args;
use std::path::{Path, PathBuf};
use wasp_sim::trace::Trace;

/// Options of `wasp trace-cat`.
#[derive(Args, Debug, Clone)]
pub struct TraceCatArgs {
    /// The traces, in frame order (each one or more frames; all of the
    /// same frame and tile size). A file may be named more than once.
    #[arg(required = true, value_name = "TRACE")]
    pub traces: Vec<PathBuf>,
    /// Write the joined trace to FILE (`-` for standard output). It keeps
    /// the first trace's workload name and header notes.
    #[arg(long, short, value_name = "FILE")]
    pub out: PathBuf,
    /// No progress output on stderr (the note of what was written);
    /// results, warnings and errors still print.
    #[arg(long, short)]
    pub quiet: bool,
}

/// Run the command.
pub fn run(args: &TraceCatArgs) -> Result<(), CliError> {
    let inputs: Vec<Input> = args
        .traces
        .iter()
        .map(|t| Input::file("TRACE", Some(t)))
        .collect();
    output::check(&[Output::new("--out", Some(&args.out))], &inputs)?;
    let read = |p: &Path| Trace::read(p).map_err(|e| CliError::usage(e.to_string()));
    let first = read(&args.traces[0])?;
    let mut rest = Vec::with_capacity(args.traces.len() - 1);
    for p in &args.traces[1..] {
        rest.push(read(p)?);
    }
    let names = args.traces.iter().map(|p| p.display().to_string());
    let mut all = Trace::concat(first, rest).map_err(|e| {
        CliError::usage(format!(
            "joining {}: {e}",
            names.collect::<Vec<_>>().join(", ")
        ))
    })?;
    // Where the frames came from, as a header note.
    let files: Vec<String> = args
        .traces
        .iter()
        .map(|p| p.display().to_string())
        .collect();
    if all.frame_count() > 1 {
        all.push_note(format!(" trace-cat: {}", files.join(" ")))
            .map_err(|e| CliError::usage(format!("a file name: {e}")))?;
    }
    emit(&args.out, &all.to_text())?;
    if !args.quiet && !output::is_stdout(&args.out) {
        eprintln!(
            "wasp: wrote {} ({} frames, {} tiles)",
            args.out.display(),
            all.frame_count(),
            all.tiles().len()
        );
    }
    Ok(())
}
