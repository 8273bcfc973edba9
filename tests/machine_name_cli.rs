//! Whole-program tests of the machine as run: its name carries every
//! override in the table, the JSON, the CSV and `wasp cost`, and the header
//! prints the warp slots and the input queue's depth.

mod common;
use common::run::{dir, tiny_config, tiny_trace};
use common::{ok, wasp};

#[test]
fn overrides_are_named_everywhere() {
    let d = dir("machine-name");
    let cfg = tiny_config(&d);
    let t = tiny_trace();
    let base = ["run", "-q", "--config", &cfg, "--trace", &t];
    let with = |extra: &[&str]| {
        let mut a = base.to_vec();
        a.extend_from_slice(extra);
        ok(&wasp(&a))
    };
    // No override: the bare name, as the golden runs have it.
    let v: serde_json::Value = serde_json::from_str(&with(&["--json", "-"])).unwrap();
    assert_eq!(v["machine"], "paper-width4-64warps");
    let set = ["--set", "core.max_warps=32", "--set", "l0.mshrs = 8"];
    let named = "paper-width4-64warps + core.max_warps=32 + l0.mshrs=8";
    let json = with(&[&set[..], &["--json", "-"]].concat());
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(v["machine"], named);
    let csv = with(&[&set[..], &["--csv", "-"]].concat());
    assert!(csv.contains(named), "{csv}");
    let table = with(&set);
    assert!(table.starts_with(&format!("machine {named}  |")), "{table}");
    // max_warps alone keeps the queue: the header says both.
    assert!(
        table.contains("warps per core 32  input queue 64 entries"),
        "{table}"
    );
    let cmp = ok(&wasp(&[
        "compare",
        "-q",
        "--config",
        &cfg,
        "--trace",
        &t,
        "--policies",
        "baseline",
        "--set",
        "core.max_warps=32",
        "--set",
        "core.input_queue=32",
    ]));
    assert!(
        cmp.contains("+ core.max_warps=32 + core.input_queue=32")
            && cmp.contains("warps per core 32  input queue 32 entries"),
        "{cmp}"
    );
    let cost = ok(&wasp(&[
        "cost",
        "--no-yosys",
        "--config",
        &cfg,
        "--set",
        "core.input_queue=32",
    ]));
    assert!(
        cost.starts_with(
            "WaSP hardware overhead: machine paper-width4-64warps + core.input_queue=32,"
        ) && cost.lines().next().unwrap().ends_with("input queue 32"),
        "{cost}"
    );
}
