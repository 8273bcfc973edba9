//! Helpers of the `wasp run` tests: a scratch folder per test, the tiny
//! trace and the machine it fits, small synthetic traces written by
//! `wasp synth`, and a run's JSON result.

use super::{ok, wasp};
use serde_json::Value;
use std::path::{Path, PathBuf};
use wasp_sim::config::MachineConfig;

/// A fresh scratch folder `wasp-run-{pid}-{name}` in the temp dir.
pub fn dir(name: &str) -> PathBuf {
    super::scratch("run", name)
}

/// The path of the tiny trace shipped with the tests.
pub fn tiny_trace() -> String {
    concat!(env!("CARGO_MANIFEST_DIR"), "/tests/traces/tiny.trace").to_string()
}

/// The paper's machine with the tile size of the tiny trace (8 pixels).
pub fn tiny_config(d: &Path) -> String {
    let mut c = MachineConfig::paper();
    c.gpu.tile_size = 8;
    let p = d.join("tiny.toml");
    std::fs::write(&p, c.to_toml()).unwrap();
    p.display().to_string()
}

/// A small synthetic trace written by `wasp synth`.
pub fn synth_trace(d: &Path, seed: u64) -> String {
    let p = d.join(format!("synth-{seed}.trace"));
    let s = seed.to_string();
    let out = ok(&wasp(&[
        "synth",
        "-o",
        p.to_str().unwrap(),
        "--frame",
        "256x128",
        "--seed",
        &s,
    ]));
    assert!(out.contains("synthetic:"), "{out}");
    p.display().to_string()
}

/// `wasp run -q --json -` with `args`, its JSON result parsed.
pub fn run_json(args: &[&str]) -> Value {
    let mut a = vec!["run", "-q", "--json", "-"];
    a.extend_from_slice(args);
    serde_json::from_str(&ok(&wasp(&a))).unwrap()
}

/// `wasp run -q` of the tiny trace on the machine `cfg` ([`tiny_config`])
/// with `args`: the process's output, whatever its status.
pub fn run_tiny(cfg: &str, args: &[&str]) -> std::process::Output {
    let t = tiny_trace();
    let mut a = vec!["run", "-q", "--config", cfg, "--trace", &t];
    a.extend_from_slice(args);
    wasp(&a)
}
