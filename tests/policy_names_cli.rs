//! Whole-program tests of policy names: a bare `wasp`, `wasp-m` or
//! `freemshr` is the machine's own, every output names the policy
//! resolved, and names are case-sensitive.

mod common;
use common::run::{dir, tiny_config, tiny_trace};
use common::{ok, stderr, wasp};

/// `wasp run --json -` of the tiny trace with `extra` options: its policy.
fn policy_of(cfg: &str, extra: &[&str]) -> String {
    let t = tiny_trace();
    let mut a = vec!["run", "-q", "--config", cfg, "--trace", &t, "--json", "-"];
    a.extend_from_slice(extra);
    let v: serde_json::Value = serde_json::from_str(&ok(&wasp(&a))).unwrap();
    v["policy"].as_str().unwrap().to_string()
}

#[test]
fn bare_names_are_the_machines_policy_resolved() {
    let d = dir("names");
    let cfg = tiny_config(&d);
    assert_eq!(policy_of(&cfg, &["--policy", "wasp"]), "wasp:0:3");
    assert_eq!(policy_of(&cfg, &["--policy", "wasp-m"]), "wasp-m:0");
    assert_eq!(policy_of(&cfg, &["--policy", "freemshr"]), "freemshr:10");
    let own = [
        "--set",
        "scheduler.policy=\"wasp:2:1.5\"",
        "--policy",
        "wasp",
    ];
    assert_eq!(policy_of(&cfg, &own), "wasp:2:1.5");
    let own = [
        "--set",
        "scheduler.policy=\"wasp:2:1.5\"",
        "--policy",
        "wasp-m",
    ];
    assert_eq!(policy_of(&cfg, &own), "wasp-m:2");
    // compare's rows name the resolved policy too.
    let out = ok(&wasp(&[
        "compare",
        "-q",
        "--config",
        &cfg,
        "--trace",
        &tiny_trace(),
        "--policies",
        "baseline,wasp",
    ]));
    assert!(out.lines().any(|l| l.starts_with("wasp:0:3 ")), "{out}");
}

#[test]
fn policy_names_are_case_sensitive() {
    let o = wasp(&["run", "-q", "--policy", "WASP"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("lower case (`wasp`)"), "{}", stderr(&o));
}
