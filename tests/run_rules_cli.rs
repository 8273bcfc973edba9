//! Whole-program tests of the scheduler's rules as `wasp run` and
//! `wasp compare` take them: the launch rule and the blocked rule, chosen
//! by flag or by `--set`, reported and counted.

use serde_json::Value;

mod common;
use common::run::{dir, run_json, synth_trace};
use common::{ok, stderr, wasp};

/// A synthetic trace in a fresh scratch folder `launch-rule-{name}`.
fn launch_rule_trace(name: &str) -> String {
    let d = dir(&format!("launch-rule-{name}"));
    synth_trace(&d, 3)
}

#[test]
fn the_launch_rule_is_hold_by_default_and_its_held_cycles_counted() {
    let trace = launch_rule_trace("hold");
    // The default is the paper's `hold`; the JSON says so and carries the
    // hold idle core-cycles, in total and per core.
    let hold = run_json(&["--trace", &trace, "--policy", "wasp:14"]);
    assert_eq!(hold["launch_rule"], "hold");
    let per_core: Vec<u64> = hold["held_cycles_per_core"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_u64().unwrap())
        .collect();
    assert_eq!(per_core.len(), 4);
    assert_eq!(
        hold["held_cycles"].as_u64().unwrap(),
        per_core.iter().sum::<u64>()
    );
    assert!(hold["held_cycles"].as_u64().unwrap() > 0);
}

#[test]
fn the_flag_and_set_both_choose_launch_which_never_holds() {
    let trace = launch_rule_trace("launch");
    // --launch-rule and --set both choose `launch`, which never holds.
    let flag = run_json(&[
        "--trace",
        &trace,
        "--policy",
        "wasp:14",
        "--launch-rule",
        "launch",
    ]);
    let set = run_json(&[
        "--trace",
        &trace,
        "--policy",
        "wasp:14",
        "--set",
        "scheduler.launch_rule=\"launch\"",
    ]);
    for v in [&flag, &set] {
        assert_eq!(v["launch_rule"], "launch");
        assert_eq!(v["held_cycles"], 0);
    }
    assert_eq!(flag["cycles"], set["cycles"]);
}

#[test]
fn run_and_compare_report_the_launch_rule() {
    let trace = launch_rule_trace("report");
    // The text table names the rule and the held cycles.
    let table = ok(&wasp(&[
        "run",
        "-q",
        "--trace",
        &trace,
        "--launch-rule",
        "launch",
    ]));
    assert!(table.contains("launch rule launch"), "{table}");
    assert!(table.contains("hold idle core-cycles 0"), "{table}");
    // compare applies the rule to every run and shows the held column.
    let o = ok(&wasp(&[
        "compare",
        "-q",
        "--trace",
        &trace,
        "--policies",
        "baseline,wasp:14",
        "--launch-rule",
        "hold",
    ]));
    assert!(o.contains("launch rule hold") && o.contains("held"), "{o}");
}

#[test]
fn a_bad_launch_rule_is_a_usage_error_naming_the_choices() {
    let trace = launch_rule_trace("bad");
    // A bad rule is a usage error that names the choices.
    let o = wasp(&["run", "-q", "--trace", &trace, "--launch-rule", "idle"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("hold or launch"), "{}", stderr(&o));
    let o = wasp(&[
        "run",
        "-q",
        "--trace",
        &trace,
        "--set",
        "scheduler.launch_rule=\"idle\"",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("scheduler.launch_rule"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn the_json_names_the_blocked_rule_and_counts_episodes() {
    let d = dir("blocked");
    let t = synth_trace(&d, 4);
    // The default rule, then each rule by flag and by --set.
    let v = run_json(&["--trace", &t, "--policy", "wasp:4"]);
    assert_eq!(v["blocked_on"], "l1-miss");
    let mut episodes = Vec::new();
    for rule in ["first-level", "l1-miss", "dram"] {
        let a = run_json(&["--trace", &t, "--policy", "wasp:4", "--blocked-on", rule]);
        let set = format!("scheduler.blocked_on=\"{rule}\"");
        let mut b = run_json(&["--trace", &t, "--policy", "wasp:4", "--set", &set]);
        // Each names the machine with the option as given.
        let named = b["machine"].as_str().unwrap().to_string();
        assert!(named.ends_with(&format!(" + {set}")), "{named}");
        b["machine"] = a["machine"].clone();
        assert_eq!(a, b, "{rule}");
        assert_eq!(a["blocked_on"], rule);
        let e = a["blocked"]["episodes"].as_u64().unwrap();
        assert!(e <= a["tex_instructions"].as_u64().unwrap());
        assert!(a["blocked"]["priority_episodes"].as_u64().unwrap() <= e);
        episodes.push(e);
    }
    assert!(
        episodes[0] > episodes[1] && episodes[1] >= episodes[2] && episodes[2] > 0,
        "{episodes:?}"
    );
    // compare runs every policy under the rule it is given.
    let j = ok(&wasp(&[
        "compare",
        "-q",
        "--trace",
        &t,
        "--policies",
        "baseline,wasp:4",
        "--blocked-on",
        "dram",
        "--json",
        "-",
    ]));
    let v: Value = serde_json::from_str(&j).unwrap();
    for r in v.as_array().unwrap() {
        assert_eq!(r["blocked_on"], "dram");
    }
    let o = wasp(&["run", "-q", "--trace", &t, "--blocked-on", "l2"]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("first-level"), "{}", stderr(&o));
}
