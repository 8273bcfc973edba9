//! Whole-program tests of `wasp run`: its results as JSON, CSV and a
//! table, the options that choose the machine (policy, subset, ideal
//! memory, dispatch, DRAM model, `--set`), and its progress bar.

use wasp_sim::config::MachineConfig;
use wasp_sim::trace::Trace;

mod common;
use common::run::{dir, run_json, synth_trace, tiny_config, tiny_trace};
use common::{ok, stderr, wasp};

#[test]
fn every_policy_conserves_warps() {
    let d = dir("conserve");
    let cfg = tiny_config(&d);
    let trace = tiny_trace();
    let quads = Trace::read(&trace).unwrap().quad_count() as u64;
    for policy in [
        "baseline",
        "fullpriority",
        "freemshr:10",
        "wasp:4",
        "wasp:2:1.5",
    ] {
        let v = run_json(&["--config", &cfg, "--trace", &trace, "--policy", policy]);
        assert_eq!(v["warps"], quads, "{policy}");
        assert_eq!(v["policy"], policy);
        assert!(v["cycles"].as_u64().unwrap() > 0);
        for key in [
            "ipc",
            "instructions",
            "l0",
            "l1",
            "l2",
            "dram",
            "memory_latency",
            "energy",
        ] {
            assert!(!v[key].is_null(), "{policy}: {key} missing");
        }
        for key in [
            "accesses",
            "hits",
            "misses",
            "secondary_misses",
            "stall_cycles",
        ] {
            assert!(v["l1"][key].is_u64(), "{policy}: l1.{key}");
        }
    }
}

#[test]
fn json_is_byte_identical_on_repeat() {
    let d = dir("determinism");
    let t = synth_trace(&d, 2);
    let a = wasp(&["run", "-q", "--trace", &t, "--json", "-"]);
    let b = wasp(&["run", "-q", "--trace", &t, "--json", "-"]);
    assert!(a.status.success());
    assert_eq!(a.stdout, b.stdout);
}

#[test]
fn ideal_memory_is_never_slower() {
    let d = dir("ideal");
    let t = synth_trace(&d, 4);
    for policy in ["baseline", "wasp:4"] {
        let real = run_json(&["--trace", &t, "--policy", policy]);
        let ideal = run_json(&["--trace", &t, "--policy", policy, "--ideal-memory"]);
        assert!(
            ideal["cycles"].as_u64() <= real["cycles"].as_u64(),
            "{policy}"
        );
        assert_eq!(ideal["ideal_memory"], true);
    }
}

#[test]
fn subsets_change_the_priority_set() {
    let d = dir("subsets");
    let t = synth_trace(&d, 6);
    let m4 = run_json(&[
        "--trace",
        &t,
        "--policy",
        "fullpriority",
        "--subset",
        "mesh4",
    ]);
    let m2 = run_json(&[
        "--trace",
        &t,
        "--policy",
        "fullpriority",
        "--subset",
        "mesh2",
    ]);
    assert_eq!(m4["subset"]["subset_size_ratio"], 1.0 / 16.0);
    assert_eq!(m2["subset"]["subset_size_ratio"], 0.25);
    assert!(m2["subset"]["priority_warps"].as_u64() > m4["subset"]["priority_warps"].as_u64());
    let f2 = m2["subset"]["texture_footprint_ratio"].as_f64().unwrap();
    let f4 = m4["subset"]["texture_footprint_ratio"].as_f64().unwrap();
    assert!(f2 > f4 && f4 > 0.0 && f2 <= 1.0, "{f2} {f4}");
}

#[test]
fn csv_and_table_outputs() {
    let d = dir("csv");
    let cfg = tiny_config(&d);
    let o = ok(&wasp(&[
        "run",
        "-q",
        "--config",
        &cfg,
        "--trace",
        &tiny_trace(),
        "--csv",
        "-",
    ]));
    let lines: Vec<&str> = o.lines().collect();
    assert_eq!(lines.len(), 2, "{o}");
    let header: Vec<&str> = lines[0].split(',').collect();
    let values: Vec<&str> = lines[1].split(',').collect();
    assert_eq!(header.len(), values.len());
    let i = header.iter().position(|h| *h == "l1.misses").unwrap();
    assert!(values[i].parse::<u64>().is_ok());
    let table = ok(&wasp(&[
        "run",
        "-q",
        "--config",
        &cfg,
        "--trace",
        &tiny_trace(),
    ]));
    assert!(table.contains("cycles") && table.contains("l1") && table.contains("energy"));
}

#[test]
fn both_dispatch_modes_report_their_machine_and_instruments() {
    let d = dir("dispatch");
    let trace = synth_trace(&d, 5);
    let shared = run_json(&["--trace", &trace]);
    let per_core = run_json(&["--trace", &trace, "--dispatch", "per-core-tile"]);
    assert_eq!(shared["dispatch"], "shared-tile");
    assert_eq!(per_core["dispatch"], "per-core-tile");
    for r in [&shared, &per_core] {
        let tiles = r["tiles"].as_u64().unwrap();
        assert_eq!(r["per_tile"].as_array().unwrap().len() as u64, tiles);
        let occ = &r["occupancy"];
        let mean = occ["mean"].as_f64().unwrap();
        assert!(mean > 0.0 && mean <= 64.0, "{occ}");
        let hist: u64 = occ["histogram"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_u64().unwrap())
            .sum();
        assert_eq!(hist, 4 * r["cycles"].as_u64().unwrap());
        assert!(r["priority_lead"]["priority_warps"].as_u64().unwrap() > 0);
    }
    // Under shared-tile dispatch the tiles follow one another.
    let tiles = shared["per_tile"].as_array().unwrap();
    for w in tiles.windows(2) {
        assert!(w[0]["end"].as_u64() < w[1]["start"].as_u64(), "{w:?}");
    }
    let e = stderr(&wasp(&["run", "--trace", &trace, "--dispatch", "sideways"]));
    assert!(e.contains("shared-tile or per-core-tile"), "{e}");
}

#[test]
fn the_json_names_the_dram_model_and_both_models_run() {
    let d = dir("dram-model");
    let trace = synth_trace(&d, 6);
    let banked = run_json(&["--trace", &trace]);
    assert_eq!(
        banked["dram_model"], "banked: 4 channels x 8 banks / 6 cycles a line",
        "the shipped config selects the banked model"
    );
    assert!(banked["dram"]["activates"].as_u64().unwrap() > 0);
    let mut c = MachineConfig::paper();
    c.dram.model = wasp_sim::mem::DramModel::Fixed;
    let p = d.join("fixed.toml");
    std::fs::write(&p, c.to_toml()).unwrap();
    let fixed = run_json(&["--trace", &trace, "--config", p.to_str().unwrap()]);
    assert_eq!(
        fixed["dram_model"],
        "fixed: row hit 50 / row miss 100 cycles"
    );
    assert_eq!(fixed["dram"]["activates"].as_u64(), Some(0));
    assert_eq!(banked["warps"], fixed["warps"]);
    assert_ne!(banked["cycles"], fixed["cycles"]);
}

#[test]
fn set_overrides_a_field_and_names_a_bad_one() {
    let d = dir("set");
    let trace = synth_trace(&d, 7);
    let fixed = run_json(&["--trace", &trace, "--set", "dram.model=fixed"]);
    assert_eq!(
        fixed["dram_model"],
        "fixed: row hit 50 / row miss 100 cycles"
    );
    let o = wasp(&["run", "-q", "--trace", &trace, "--set", "l0.mshrs=40"]);
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert!(e.contains("--set l0.mshrs=40") && e.contains("31"), "{e}");
    let o = wasp(&["run", "-q", "--trace", &trace, "--set", "l0.msrhs=4"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("expected one of:"), "{}", stderr(&o));
}

/// A config file with a few fields is the shipped machine with those
/// fields changed, the same as `--set`; `extends` picks the base.
#[test]
fn a_partial_config_file_patches_the_shipped_machine() {
    let d = dir("partial");
    let trace = synth_trace(&d, 3);
    let patch = d.join("l0.toml");
    std::fs::write(&patch, "[l0]\nmshrs = 8\n").unwrap();
    let mut from_file = run_json(&["--trace", &trace, "--config", patch.to_str().unwrap()]);
    let from_set = run_json(&["--trace", &trace, "--set", "l0.mshrs=8"]);
    // Each names what changed the base: the file, or the override.
    let p = patch.display().to_string();
    assert_eq!(from_file["machine"], format!("paper-width4-64warps + {p}"));
    assert_eq!(from_set["machine"], "paper-width4-64warps + l0.mshrs=8");
    from_file["machine"] = from_set["machine"].clone();
    assert_eq!(from_file, from_set);
    assert_ne!(from_file, run_json(&["--trace", &trace]));
    let w2 = d.join("w2.toml");
    std::fs::write(&w2, "extends = \"paper-width2\"\n[l1]\nmshrs = 8\n").unwrap();
    let narrow = run_json(&["--trace", &trace, "--config", w2.to_str().unwrap()]);
    assert!(narrow["l0"].is_null(), "no L0 at width 2");
    let w2 = w2.display().to_string();
    assert_eq!(narrow["machine"], format!("paper-width2-48warps + {w2}"));
    // An unknown key still fails, naming the file and line.
    std::fs::write(&patch, "[l0]\nmshrs = 8\nmshr = 9\n").unwrap();
    let o = wasp(&["run", "-q", "--config", patch.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("l0.toml:3: l0.mshr: unknown field"),
        "{}",
        stderr(&o)
    );
}

/// `wasp run` on a terminal draws a progress bar on stderr; `-q` hides it,
/// and so does a stderr that is not a terminal.
#[test]
fn run_progress_only_on_a_terminal_and_never_under_q() {
    let d = dir("progress");
    let trace = synth_trace(&d, 3);
    // Not a terminal (the test harness captures stderr).
    for q in [true, false] {
        let mut a = vec!["run", "--trace", &trace];
        if q {
            a.push("-q");
        }
        let o = wasp(&a);
        ok(&o);
        let e = stderr(&o);
        assert!(
            !e.contains("simulating") && !e.contains(" tiles 00:"),
            "{e}"
        );
        if q {
            assert_eq!(e, "", "-q must keep stderr empty");
        }
    }
    // On a terminal, through script(1) when it is installed.
    let has_script = std::process::Command::new("script")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    if !has_script {
        eprintln!("note: script(1) missing: the terminal half of this test did not run");
        return;
    }
    let on_tty = |q: bool| -> String {
        let cmd = format!(
            "{} run {}--trace {trace}",
            env!("CARGO_BIN_EXE_wasp"),
            if q { "-q " } else { "" }
        );
        let o = std::process::Command::new("script")
            .args(["-qec", &cmd, "/dev/null"])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
        String::from_utf8_lossy(&o.stdout).into_owned()
    };
    // The bar: "simulating [===>   ] 3/8 tiles 00:00:00 eta 0s".
    let bar = |s: &str| s.contains("simulating") || s.contains(" tiles 00:");
    let loud = on_tty(false);
    assert!(
        loud.contains("simulating") && loud.contains(" tiles 00:"),
        "{loud}"
    );
    assert!(loud.contains("cycles"), "{loud}");
    let quiet = on_tty(true);
    assert!(!bar(&quiet), "{quiet}");
    assert!(
        quiet.contains("cycles"),
        "the table is still printed: {quiet}"
    );
}
