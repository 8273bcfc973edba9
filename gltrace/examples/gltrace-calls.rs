//! Prints a capture's calls as `NUMBER NAME`, one a line, in the order
//! `apitrace dump` prints them, then (on standard error) the call and frame
//! counts and the time taken. Used to compare this reader with
//! `apitrace dump` (scripts/gltrace-compare.sh) and to time it:
//!
//! `cargo run --release -p wasp-gltrace --example gltrace-calls -- CAPTURE [--quiet]`

use std::io::Write;
use std::time::Instant;
use wasp_gltrace::{is_frame_end, Capture};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let Some(path) = args.first() else {
        eprintln!("usage: gltrace-calls CAPTURE [--quiet]");
        std::process::exit(2);
    };
    let quiet = args.iter().any(|a| a == "--quiet");
    let start = Instant::now();
    let result = run(path, quiet);
    let secs = start.elapsed().as_secs_f64();
    match result {
        Ok((calls, frames, bytes, blob_bytes, incomplete)) => eprintln!(
            "calls: {calls}, frames: {frames}, decompressed bytes: {bytes}, blob bytes: \
             {blob_bytes}, incomplete calls: {incomplete:?}, seconds: {secs:.3}"
        ),
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }
}

type Counts = (u64, u64, u64, u64, Vec<u64>);

fn run(path: &str, quiet: bool) -> Result<Counts, Box<dyn std::error::Error>> {
    let mut capture = Capture::open(path)?;
    eprintln!(
        "version {} (semantic {}), {:?}, API {}",
        capture.version,
        capture.semantic_version,
        capture.compression,
        capture.api.describe()
    );
    let out = std::io::stdout();
    let mut out = std::io::BufWriter::new(out.lock());
    let (mut calls, mut frames, mut blob_bytes) = (0u64, 0u64, 0u64);
    for call in capture.by_ref() {
        let call = call?;
        calls += 1;
        frames += u64::from(is_frame_end(&call.name));
        blob_bytes += call
            .args
            .iter()
            .filter_map(|a| a.as_bytes())
            .map(|b| b.len() as u64)
            .sum::<u64>();
        if !quiet {
            writeln!(out, "{} {}", call.no, call.name)?;
        }
    }
    out.flush()?;
    Ok((
        calls,
        frames,
        capture.offset(),
        blob_bytes,
        capture.incomplete_calls().to_vec(),
    ))
}
