//! Whole-program tests of `wasp run`, `wasp compare` and `wasp synth`.

use serde_json::Value;
use std::path::{Path, PathBuf};
use wasp_sim::config::MachineConfig;
use wasp_sim::trace::Trace;
use wasp_waves::readback;

mod common;
use common::{ok, stderr, wasp};

fn dir(name: &str) -> PathBuf {
    common::scratch("run", name)
}

fn tiny_trace() -> String {
    concat!(env!("CARGO_MANIFEST_DIR"), "/tests/traces/tiny.trace").to_string()
}

/// The paper's machine with the tile size of the tiny trace (8 pixels).
fn tiny_config(d: &Path) -> String {
    let mut c = MachineConfig::paper();
    c.gpu.tile_size = 8;
    let p = d.join("tiny.toml");
    std::fs::write(&p, c.to_toml()).unwrap();
    p.display().to_string()
}

/// A small synthetic trace written by `wasp synth`.
fn synth_trace(d: &Path, seed: u64) -> String {
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

fn run_json(args: &[&str]) -> Value {
    let mut a = vec!["run", "-q", "--json", "-"];
    a.extend_from_slice(args);
    serde_json::from_str(&ok(&wasp(&a))).unwrap()
}

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
fn vcd_window_and_signals() {
    let d = dir("vcd");
    let cfg = tiny_config(&d);
    let vcd = d.join("run.vcd");
    let v = run_json(&[
        "--config",
        &cfg,
        "--trace",
        &tiny_trace(),
        "--vcd",
        vcd.to_str().unwrap(),
        "--vcd-from",
        "10",
        "--vcd-to",
        "40",
    ]);
    assert!(v["cycles"].as_u64().unwrap() > 40);
    let bytes = std::fs::read(&vcd).unwrap();
    let rb = readback::values_by_cycle(&bytes).unwrap();
    let names: Vec<&str> = rb.names().collect();
    for s in [
        "wasp.core0.scheduler.free_mshrs",
        "wasp.core0.scheduler.nonblocked_priority",
        "wasp.core0.scheduler.real_free_mshrs",
        "wasp.core0.scheduler.priority_over_regular",
        "wasp.core0.scheduler.launch",
        "wasp.core0.scheduler.prio_queue_occupancy",
        "wasp.core0.warps_active",
        "wasp.raster.tile",
        "wasp.raster.quad",
        "wasp.raster.sent",
        "wasp.raster.rejected",
        "wasp.raster.backpressure",
        "wasp.raster.flush_left",
    ] {
        assert!(names.contains(&s), "{s} missing: {names:?}");
    }
    // The rasterizer works on tile 1 (index 0) from the window's start.
    let tile = rb.signal("wasp.raster.tile").unwrap().changes()[0];
    assert_eq!(tile, (10, 1));
    let first = rb.signal("wasp.core0.warps_active").unwrap().changes()[0].0;
    assert_eq!(first, 10);
    assert_eq!(rb.end_time(), Some(41));
    let gtkw = std::fs::read_to_string(d.join("run.vcd.gtkw")).unwrap();
    assert!(gtkw.contains("wasp.core0.scheduler.free_mshrs[4:0]"));
    assert!(gtkw.contains("wasp.raster.quad[31:0]"), "{gtkw}");
}

#[test]
fn compare_prints_speedups_against_the_baseline() {
    let d = dir("compare");
    let t = synth_trace(&d, 8);
    let o = ok(&wasp(&[
        "compare",
        "-q",
        "--trace",
        &t,
        "--with-ideal",
        "--jobs",
        "2",
    ]));
    // The default list: the three rivals, the configuration's WaSP and the
    // measured-CF variant at its threshold.
    for p in [
        "baseline",
        "fullpriority",
        "freemshr:10",
        "wasp:0:3",
        "wasp-m:0",
        "+ideal memory",
    ] {
        assert!(o.contains(p), "{p} missing:\n{o}");
    }
    let base = o.lines().find(|l| l.starts_with("baseline ")).unwrap();
    assert!(base.contains("+0.00%"), "{base}");
    let j = ok(&wasp(&[
        "compare",
        "-q",
        "--trace",
        &t,
        "--policies",
        "baseline,wasp:4",
        "--json",
        "-",
    ]));
    let v: Value = serde_json::from_str(&j).unwrap();
    assert_eq!(v.as_array().unwrap().len(), 2);
    assert_eq!(v[0]["warps"], v[1]["warps"]);
}

#[test]
fn bench_reports_every_point_with_its_median_and_spread() {
    let trace = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/traces/synthetic-small.trace"
    );
    let out = wasp(&[
        "bench",
        "--repeats",
        "2",
        "--min-seconds",
        "0",
        "--trace",
        trace,
        "--json",
        "-",
    ]);
    let points: Value = serde_json::from_str(&ok(&out)).unwrap();
    let points = points.as_array().unwrap();
    let names: Vec<String> = points
        .iter()
        .map(|p| {
            format!(
                "{} {}",
                p["label"].as_str().unwrap(),
                p["mode"].as_str().unwrap()
            )
        })
        .collect();
    assert_eq!(
        names,
        [
            "tracing off",
            "tracing hooks",
            "tracing visitor",
            "tracing vcd",
            "dispatch shared-tile off",
            "dispatch per-core-tile off",
            "tiles off",
            "tiles off",
            "tiles off",
            "warps off",
            "warps off",
            "warps off"
        ]
    );
    // The four tracing modes simulate the same run.
    let cycles = points[0]["cycles"].as_u64().unwrap();
    assert!(cycles > 0);
    for p in &points[..4] {
        assert_eq!(p["cycles"].as_u64(), Some(cycles), "{p}");
    }
    for p in points {
        assert_eq!(p["samples"].as_u64(), Some(2), "{p}");
        let spread = p["spread"].as_f64().unwrap();
        let median = p["median_core_cycles_per_second"].as_f64().unwrap();
        assert!(spread >= 0.0 && spread.is_finite(), "{p}");
        // The median sample is never faster than the best one.
        let best = p["core_cycles_per_cpu_second"]
            .as_f64()
            .or(p["core_cycles_per_second"].as_f64())
            .unwrap();
        assert!(median > 0.0 && median <= best * (1.0 + 1e-9), "{p}");
    }
    let table = stderr(&out);
    assert!(
        table.contains("median") && table.contains("spread"),
        "{table}"
    );
    assert!(table.contains("tracing hook overhead"), "{table}");
    assert!(
        table.contains("synthetic-small.trace: read in")
            && table.contains("workload statistics in"),
        "{table}"
    );
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
fn the_timeline_is_drawn_as_png_or_svg() {
    let d = dir("timeline");
    let trace = synth_trace(&d, 6);
    let png = d.join("t.png");
    let svg = d.join("t.svg");
    for p in [&png, &svg] {
        ok(&wasp(&[
            "run",
            "-q",
            "--trace",
            &trace,
            "--timeline",
            p.to_str().unwrap(),
            "--timeline-to",
            "3000",
        ]));
    }
    let bytes = std::fs::read(&png).unwrap();
    assert!(bytes.starts_with(b"\x89PNG\r\n\x1a\n"));
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(
        text.contains("Resident warps per core"),
        "svg has the panels"
    );
    // A window after the run's end, and a wrong extension, are refused.
    let late = d.join("late.png");
    let e = stderr(&wasp(&[
        "run",
        "-q",
        "--trace",
        &trace,
        "--timeline",
        late.to_str().unwrap(),
        "--timeline-from",
        "900000000",
    ]));
    assert!(e.contains("before the window"), "{e}");
    assert!(!late.exists());
    let e = stderr(&wasp(&["run", "--trace", &trace, "--timeline", "t.gif"]));
    assert!(e.contains(".png or .svg"), "{e}");
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
fn the_launch_rule_is_chosen_reported_and_counted() {
    let d = dir("launch-rule");
    let trace = synth_trace(&d, 3);
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
        let b = run_json(&["--trace", &t, "--policy", "wasp:4", "--set", &set]);
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

/// Cycles `--vcd` writes a change at, read from the VCD's timestamps.
fn vcd_times(bytes: &[u8]) -> Vec<u64> {
    String::from_utf8_lossy(bytes)
        .lines()
        .filter_map(|l| l.strip_prefix('#'))
        .map(|t| t.parse().unwrap())
        .collect()
}

#[test]
fn vcd_time_axis_is_cycles_or_picoseconds_and_says_so() {
    let d = dir("vcd-time");
    let cfg = tiny_config(&d);
    let trace = tiny_trace();
    let write = |name: &str, extra: &[&str]| -> (String, String) {
        let vcd = d.join(name);
        let mut a = vec![
            "--config",
            &cfg,
            "--trace",
            &trace,
            "--vcd",
            vcd.to_str().unwrap(),
            "--vcd-from",
            "10",
            "--vcd-to",
            "40",
        ];
        a.extend_from_slice(extra);
        run_json(&a);
        let gtkw = std::fs::read_to_string(d.join(format!("{name}.gtkw"))).unwrap();
        (std::fs::read_to_string(&vcd).unwrap(), gtkw)
    };
    let (cycles, cycles_gtkw) = write("cycles.vcd", &[]);
    let (explicit, _) = write("explicit.vcd", &["--vcd-time", "cycles"]);
    assert_eq!(cycles, explicit.replace("explicit.vcd", "cycles.vcd"));
    let note = "one time unit = one GPU cycle at 600 MHz (1.667 ns)";
    assert!(
        cycles.contains(&format!("$comment\n    {note}\n$end")),
        "{cycles}"
    );
    assert!(cycles.contains("$timescale 1 ns $end"));
    assert!(
        cycles_gtkw.contains(&format!("[*] {note}\n")),
        "{cycles_gtkw}"
    );
    assert!(cycles_gtkw.contains("[timestart] 10\n"), "{cycles_gtkw}");

    let (real, real_gtkw) = write("real.vcd", &["--vcd-time", "real"]);
    assert!(real.contains("$timescale 1 ps $end"), "{real}");
    let note = "time unit = 1 ps; one GPU cycle at 600 MHz = 1667 ps: cycle N is at time N x 1667";
    assert!(real.contains(note), "{real}");
    assert!(real_gtkw.contains(&format!("[*] {note}\n")), "{real_gtkw}");
    assert!(real_gtkw.contains("[timestart] 16670\n"), "{real_gtkw}");
    let c = vcd_times(cycles.as_bytes());
    assert_eq!(c.first(), Some(&10));
    assert_eq!(c.last(), Some(&41));
    let scaled: Vec<u64> = c.iter().map(|t| t * 1667).collect();
    assert_eq!(vcd_times(real.as_bytes()), scaled);

    // The axis follows gpu.frequency_mhz.
    let (fast, _) = write("fast.vcd", &["--set", "gpu.frequency_mhz=1000"]);
    assert!(
        fast.contains("one GPU cycle at 1000 MHz (1.000 ns)"),
        "{fast}"
    );
    let (fast_real, _) = write(
        "fast-real.vcd",
        &["--set", "gpu.frequency_mhz=1000", "--vcd-time", "real"],
    );
    let scaled: Vec<u64> = c.iter().map(|t| t * 1000).collect();
    assert_eq!(vcd_times(fast_real.as_bytes()), scaled);

    // Checked before any work: an unknown axis, and an axis without --vcd.
    let o = wasp(&[
        "run",
        "--trace",
        &trace,
        "--vcd",
        "x.vcd",
        "--vcd-time",
        "ns",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("cycles") && stderr(&o).contains("real"));
    let o = wasp(&["run", "--trace", &trace, "--vcd-time", "real"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--vcd <FILE>"), "{}", stderr(&o));
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
