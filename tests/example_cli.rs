//! Whole-program tests of `wasp example`: the text, the JSON, the waveform
//! and the errors, run as a user runs them.

use serde_json::Value;
use std::path::{Path, PathBuf};
use wasp_waves::readback;

mod common;
use common::{stderr, stdout, wasp};

fn tmp(name: &str) -> PathBuf {
    common::scratch("test", name)
}

#[test]
fn no_subcommand_shows_the_example() {
    let o = wasp(&[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let s = stdout(&o);
    assert!(s.contains("Scanline order (baseline) [baseline]: 18 cycles, 0 stall cycles"));
    assert!(s.contains(
        "All priority warps first (Fullpriority) [fullpriority]: 21 cycles, 6 stall cycles"
    ));
    assert!(s.contains("[wasp:1:1]: 16 cycles, 0 stall cycles"));
    assert!(s.contains("11.1% fewer cycles"));
}

#[test]
fn json_has_the_three_runs() {
    let o = wasp(&["example", "--json", "-"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: Value = serde_json::from_str(&stdout(&o)).unwrap();
    let obj = v.as_object().unwrap();
    let keys: Vec<&str> = obj.keys().map(|k| k.as_str()).collect();
    assert_eq!(keys.len(), 3);
    for (key, cycles, stalls) in [
        ("scanline", 18, 0),
        ("all_priority_first", 21, 6),
        ("wasp", 16, 0),
    ] {
        assert_eq!(v[key]["cycles"], cycles, "{key}");
        assert_eq!(v[key]["stall_cycles"], stalls, "{key}");
        assert_eq!(
            v[key]["timeline"].as_array().unwrap().len(),
            cycles as usize
        );
    }
    assert_eq!(v["wasp"]["machine"]["threshold"], 1);
    assert_eq!(v["wasp"]["cf"], 1.0);
    assert_eq!(v["all_priority_first"]["timeline"][3]["blocked"], true);
    assert_eq!(v["scanline"]["timeline"][0]["outcome"], "X");
}

#[test]
fn json_is_deterministic() {
    let a = wasp(&["example", "--json", "-"]);
    let b = wasp(&["example", "--json", "-"]);
    assert_eq!(a.stdout, b.stdout);
}

#[test]
fn machine_flags_change_the_result() {
    let o = wasp(&["example", "--json", "-", "--mshrs", "31", "--latency", "20"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: Value = serde_json::from_str(&stdout(&o)).unwrap();
    // Plenty of MSHRs: no stall, and clustering all misses first pays off.
    for key in ["scanline", "all_priority_first", "wasp"] {
        assert_eq!(v[key]["stall_cycles"], 0, "{key}");
    }
    // Scanline: C missed by W10 in cycle 11 answers in 31.
    assert_eq!(v["scanline"]["cycles"], 31);
    assert!(v["all_priority_first"]["cycles"].as_u64() < v["scanline"]["cycles"].as_u64());
}

#[test]
fn values_the_registers_cannot_hold_are_refused() {
    let o = wasp(&["example", "--mshrs", "32"]);
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert!(e.contains("--mshrs 32") && e.contains("5-bit"), "{e}");
    let o = wasp(&["example", "--mshrs", "0"]);
    assert_eq!(o.status.code(), Some(2));
    let o = wasp(&["example", "--latency", "0"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--latency"));
    let o = wasp(&["example", "--threshold", "3"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("threshold"));
    let o = wasp(&["example", "--mshrs", "-1"]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn help_explains_each_subcommand() {
    let o = wasp(&["--help"]);
    assert!(o.status.success());
    let s = stdout(&o);
    assert!(s.contains("example") && s.contains("worked example"));
    let o = wasp(&["example", "--help"]);
    let s = stdout(&o);
    for flag in [
        "--json",
        "--vcd",
        "--latency",
        "--mshrs",
        "--threshold",
        "--launch-rule",
    ] {
        assert!(s.contains(flag), "{flag} missing from help");
    }
}

/// The waveform must say, cycle by cycle, what the chronograph says.
#[test]
fn vcd_matches_the_chronographs_cycle_by_cycle() {
    let dir = tmp("vcd");
    let vcd = dir.join("example.vcd");
    let o = wasp(&["example", "--json", "-", "--vcd", vcd.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let report: Value = serde_json::from_str(&stdout(&o)).unwrap();
    let bytes = std::fs::read(&vcd).unwrap();
    let text = String::from_utf8(bytes.clone()).unwrap();
    assert!(text.contains("$timescale"));
    assert!(text.contains("one time unit = one clock cycle"));
    let rb = readback::values_by_cycle(&bytes).unwrap();
    // Final timestamp one past the longest run.
    assert_eq!(rb.end_time(), Some(22));

    for key in ["scanline", "all_priority_first", "wasp"] {
        let sig = |name: &str| format!("wasp_example.{key}.{name}");
        for row in report[key]["timeline"].as_array().unwrap() {
            let c = row["cycle"].as_u64().unwrap();
            let at = |name: &str| {
                rb.value_at(&sig(name), c)
                    .unwrap_or_else(|| panic!("{} missing at {c}", sig(name)))
            };
            the_cache_matches_the_row(key, c, row, &at);
            the_scheduler_matches_the_row(key, c, row, &at);
        }
    }
    the_save_file_preselects_the_signals(&dir.join("example.vcd.gtkw"));
    std::fs::remove_dir_all(dir).ok();
}

/// The cache's signals at cycle `c` of run `key` (`at` reads a signal)
/// are the chronograph's `row`: MSHRs held, the stall and the access.
fn the_cache_matches_the_row(key: &str, c: u64, row: &Value, at: &dyn Fn(&str) -> u64) {
    assert_eq!(
        at("cache.mshr_occupancy"),
        row["mshrs_held"].as_u64().unwrap()
    );
    assert_eq!(
        at("cache.cache_stall") == 1,
        row["blocked"].as_bool().unwrap()
    );
    let valid = at("cache.access_valid") == 1;
    assert_eq!(valid, !row["warp"].is_null(), "{key} cycle {c}");
    if valid {
        assert_eq!(at("cache.access_warp"), row["warp"].as_u64().unwrap());
        let block = row["block"].as_str().unwrap();
        assert_eq!(
            at("cache.access_block"),
            (block.as_bytes()[0] - b'A' + 1) as u64
        );
        let code = match row["outcome"].as_str().unwrap() {
            "H" => 1,
            "X" => 2,
            "O" => 3,
            o => panic!("outcome {o}"),
        };
        assert_eq!(at("cache.access_outcome"), code);
    }
}

/// The scheduler's signals at cycle `c` of run `key` are the
/// chronograph's `row`: free MSHRs, non-blocked priority warps, the launch
/// and WaSP's real free MSHRs.
fn the_scheduler_matches_the_row(key: &str, c: u64, row: &Value, at: &dyn Fn(&str) -> u64) {
    assert_eq!(
        at("scheduler.free_mshrs"),
        row["free_mshrs"].as_u64().unwrap(),
        "{key} cycle {c}"
    );
    assert_eq!(
        at("scheduler.nonblocked_priority"),
        row["nonblocked_priority"].as_u64().unwrap(),
        "{key} cycle {c}"
    );
    let launched = !row["launched"].is_null();
    let launch = at("scheduler.launch");
    assert_eq!(launch != 0, launched, "{key} cycle {c}");
    if launched {
        let class = row["launched"][1].as_str().unwrap();
        assert_eq!(launch, if class == "priority" { 2 } else { 1 });
    }
    if let Some(real) = row["real_free_mshrs"].as_i64() {
        let bits = at("scheduler.real_free_mshrs");
        // 11-bit two's complement.
        let v = if bits & 0x400 != 0 {
            bits as i64 - 0x800
        } else {
            bits as i64
        };
        assert_eq!(v, real, "{key} cycle {c}");
        assert_eq!(at("scheduler.priority_over_regular") == 1, real > 1);
    }
}

/// The GTKWave save file preselects the signals with GTKWave's vector names.
fn the_save_file_preselects_the_signals(path: &Path) {
    let gtkw = std::fs::read_to_string(path).unwrap();
    assert!(gtkw.contains("[dumpfile]"));
    assert!(
        gtkw.contains("[*] one time unit = one clock cycle\n"),
        "{gtkw}"
    );
    assert!(gtkw.contains("wasp_example.wasp.scheduler.free_mshrs[4:0]"));
    assert!(gtkw.contains("wasp_example.wasp.scheduler.real_free_mshrs[10:0]"));
    assert!(gtkw.contains("wasp_example.wasp.scheduler.priority_over_regular\n"));
}

#[test]
fn unwritable_vcd_path_is_a_clear_error() {
    let o = wasp(&["example", "--vcd", "/nonexistent-dir/x.vcd"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o)
            .contains("--vcd /nonexistent-dir/x.vcd: the folder /nonexistent-dir does not exist"),
        "{}",
        stderr(&o)
    );
}

/// The launch rule: the paper's example is the same under both rules; at
/// threshold 2 `hold` idles 4 cycles (19 in all) where `launch` sends W5 and
/// W10 at once (17).
#[test]
fn the_launch_rule_flag() {
    let json = |args: &[&str]| -> Value {
        let mut a = vec!["example", "--json", "-"];
        a.extend_from_slice(args);
        let o = wasp(&a);
        assert!(o.status.success(), "{}", stderr(&o));
        serde_json::from_str(&stdout(&o)).unwrap()
    };
    let hold = json(&[]);
    assert_eq!(hold["wasp"]["machine"]["launch_rule"], "hold");
    let launch = json(&["--launch-rule", "launch"]);
    assert_eq!(launch["wasp"]["machine"]["launch_rule"], "launch");
    assert_eq!(launch["wasp"]["cycles"], 16);
    assert_eq!(launch["wasp"]["timeline"], hold["wasp"]["timeline"]);
    for (rule, cycles, held) in [("hold", 19, 4), ("launch", 17, 0)] {
        let v = json(&["--threshold", "2", "--launch-rule", rule]);
        assert_eq!(v["wasp"]["cycles"], cycles, "{rule}");
        assert_eq!(v["wasp"]["held_cycles"], held, "{rule}");
    }
    let text = stdout(&wasp(&["example", "--launch-rule", "launch"]));
    assert!(text.contains("launch rule launch"), "{text}");
    let o = wasp(&["example", "--launch-rule", "never"]);
    assert_eq!(o.status.code(), Some(2));
}
