//! Whole-program tests of the inputs `wasp run` refuses: a bad machine
//! configuration, trace, policy or subset, and values out of their bounds,
//! each a usage error that names the culprit before any work.

use wasp_sim::config::MachineConfig;

mod common;
use common::run::{dir, tiny_trace};
use common::{stderr, wasp};

#[test]
fn bad_inputs_are_clear_errors() {
    let d = dir("errors");
    let cfg = d.join("bad.toml");
    let text = MachineConfig::paper()
        .to_toml()
        .replace("max_warps = 64", "max_warps = 64\nmax_wraps = 1");
    std::fs::write(&cfg, text).unwrap();
    let o = wasp(&[
        "run",
        "--config",
        cfg.to_str().unwrap(),
        "--trace",
        &tiny_trace(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert!(e.contains("bad.toml") && e.contains("max_wraps"), "{e}");

    let trace = d.join("bad.trace");
    std::fs::write(
        &trace,
        "wasp-trace 1\nworkload x\nframe 16 16 tile 8\ntile 0 0\nq 9 0 a1\nend\n",
    )
    .unwrap();
    let o = wasp(&["run", "--trace", trace.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert!(e.contains("bad.trace:5"), "{e}");

    let o = wasp(&["run", "--policy", "wasp:99"]);
    assert_eq!(o.status.code(), Some(2));
    let o = wasp(&["run", "--subset", "mesh3"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("mesh4"));
}

#[test]
fn an_absurd_bank_count_fails_fast_naming_the_field() {
    // 2^32 - 1 banks once made the process try to allocate tens of GB and
    // abort; the bound refuses it before anything is built.
    let o = wasp(&["run", "-q", "--set", "dram.banks=4294967295"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("dram.banks = 4294967295") && e.contains("1..=64"),
        "{e}"
    );
    // The same bound from a config file, and for an enormous latency.
    let d = dir("bounds");
    let p = d.join("huge.toml");
    let text =
        wasp_sim::config::PAPER_TOML.replacen("hit_latency = 18", "hit_latency = 4000000000", 1);
    std::fs::write(&p, text).unwrap();
    let o = wasp(&["run", "-q", "--config", p.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("huge.toml")
            && e.contains("l2.hit_latency = 4000000000")
            && e.contains("1..=10000"),
        "{e}"
    );
}

#[test]
fn an_absurd_alu_run_in_a_trace_fails_fast_naming_line_and_range() {
    // `a2147483647` was once accepted and ran for minutes with no progress
    // shown under `-q`; the trace bounds refuse it while reading.
    let d = dir("alu-bound");
    let p = d.join("long.trace");
    std::fs::write(
        &p,
        "wasp-trace 4\nworkload w\nframe 64 64 tile 64\ntile 0 0\nq 0 0 a2147483647\nend\n",
    )
    .unwrap();
    let o = wasp(&["run", "-q", "--trace", p.to_str().unwrap()]);
    assert_ne!(o.status.code(), Some(0), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("long.trace:5: ALU run `2147483647` out of range (expected at most 4096)"),
        "{e}"
    );
}
