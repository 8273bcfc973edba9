//! Whole-program tests of the prefetchers (`prefetch.kind`): on every
//! shipped trace, under every launch policy and both dispatch modes, a
//! run with each prefetcher finishes, repeats byte for byte and reports
//! its `prefetch` block with counts that add up; `none` is the golden run;
//! `compare` and `sweep` take the option through `--set` and `set`.

use serde_json::Value;

mod common;
use common::{ok, stderr, wasp};

const TRACES: [&str; 3] = ["tiny", "overdraw", "synthetic-small"];
const POLICIES: [&str; 5] = [
    "baseline",
    "fullpriority",
    "freemshr:10",
    "wasp:0:3",
    "wasp-m:0",
];

fn trace_path(name: &str) -> String {
    format!("{}/tests/traces/{name}.trace", env!("CARGO_MANIFEST_DIR"))
}

/// `--set gpu.tile_size=T` for the trace's own tile size.
fn tile_set(path: &str) -> String {
    let text = std::fs::read_to_string(path).unwrap();
    let frame = text.lines().find(|l| l.starts_with("frame ")).unwrap();
    format!("gpu.tile_size={}", frame.rsplit(' ').next().unwrap())
}

/// `wasp run --json -` of `trace` with `extra` arguments, as text.
fn run(trace: &str, extra: &[&str]) -> String {
    let path = trace_path(trace);
    let tile = tile_set(&path);
    let mut args = vec!["run", "-q", "--trace", &path, "--set", &tile, "--json", "-"];
    args.extend_from_slice(extra);
    ok(&wasp(&args))
}

/// The prefetch block's counts add up, and the block describes `kind`.
fn check_block(v: &Value, kind: &str, what: &str) {
    let p = &v["prefetch"];
    assert_eq!(p["kind"], kind, "{what}");
    let n = |k: &str| p[k].as_u64().unwrap_or_else(|| panic!("{what}: {k}"));
    assert!(n("generated") > 0, "{what}: nothing generated");
    assert_eq!(
        n("issued"),
        n("hits") + n("pending") + n("misses"),
        "{what}: every lookup is a hit, a pending miss or a miss"
    );
    assert!(
        n("useful") <= n("misses"),
        "{what}: useful at most once each"
    );
    assert!(n("late") <= n("useful"), "{what}");
    assert_eq!(
        n("useful") + n("useless") + n("unused_at_end"),
        n("misses"),
        "{what}: each prefetch miss is used, evicted unused or still there"
    );
    assert_eq!(
        n("duplicates") + n("dropped") + n("cancelled") + n("issued"),
        n("generated"),
        "{what}: each request is skipped, dropped, cancelled or issued once"
    );
    if kind == "oracle-tile" {
        assert_eq!((n("duplicates"), n("dropped")), (0, 0), "{what}");
    }
}

#[test]
fn every_trace_policy_and_dispatch_runs_with_each_prefetcher() {
    for trace in TRACES {
        for kind in ["oracle-tile", "raster"] {
            let set = format!("prefetch.kind={kind}");
            for policy in POLICIES {
                for dispatch in ["shared-tile", "per-core-tile"] {
                    let what = format!("{trace} {kind} {policy} {dispatch}");
                    let args = ["--set", &set, "--policy", policy, "--dispatch", dispatch];
                    let text = run(trace, &args);
                    let v: Value = serde_json::from_str(&text).unwrap();
                    check_block(&v, kind, &what);
                    assert_eq!(v["policy"], policy, "{what}");
                    assert_eq!(v["dispatch"], dispatch, "{what}");
                    // Deterministic: the same run again, byte for byte
                    // (once per trace and kind under each dispatch mode).
                    if policy == "wasp:0:3" {
                        assert_eq!(run(trace, &args), text, "{what}: not deterministic");
                    }
                }
            }
        }
    }
}

#[test]
fn the_width2_machine_runs_each_prefetcher_on_the_scheduler_level_cache() {
    for kind in ["oracle-tile", "raster"] {
        let set = format!("prefetch.kind={kind}");
        let text = run(
            "synthetic-small",
            &[
                "--config",
                concat!(env!("CARGO_MANIFEST_DIR"), "/configs/paper-width2.toml"),
                "--set",
                &set,
            ],
        );
        let v: Value = serde_json::from_str(&text).unwrap();
        check_block(&v, kind, kind);
        assert!(v["l0"].is_null());
    }
}

/// `none` spelled out is the shipped machine: the golden files, field for
/// field, with no prefetch block.
#[test]
fn prefetch_none_is_the_golden_run() {
    for trace in TRACES {
        let text = run(
            trace,
            &["--set", "prefetch.kind=none", "--policy", "wasp:0:3"],
        );
        let got: Value = serde_json::from_str(&text).unwrap();
        let path = format!(
            "{}/tests/golden/current/{trace}-wasp.json",
            env!("CARGO_MANIFEST_DIR")
        );
        let want: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        assert!(got.get("prefetch").is_none(), "{trace}");
        // The name says what was set; everything else is the golden run.
        let mut got = got;
        let named = got["machine"].as_str().unwrap().to_string();
        assert!(named.ends_with(" + prefetch.kind=none"), "{named}");
        got["machine"] = want["machine"].clone();
        assert_eq!(got, want, "{trace}");
    }
}

#[test]
fn the_table_reports_the_prefetcher_and_bad_kinds_are_refused() {
    let path = trace_path("synthetic-small");
    let tile = tile_set(&path);
    let t = ok(&wasp(&[
        "run",
        "-q",
        "--trace",
        &path,
        "--set",
        &tile,
        "--set",
        "prefetch.kind=raster",
    ]));
    assert!(
        t.contains("prefetch raster (queue 32 filtered, L1 reserve 4)"),
        "{t}"
    );
    assert!(t.contains("prefetch L1 lookups"), "{t}");
    let plain = ok(&wasp(&["run", "-q", "--trace", &path, "--set", &tile]));
    assert!(!plain.contains("prefetch"), "{plain}");
    let o = wasp(&[
        "run",
        "-q",
        "--trace",
        &path,
        "--set",
        "prefetch.kind=stride",
    ]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("stride"), "{}", stderr(&o));
    let o = wasp(&[
        "run",
        "-q",
        "--trace",
        &path,
        "--set",
        "prefetch.kind=raster",
        "--set",
        "prefetch.l1_reserve=16",
    ]);
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains("prefetch.l1_reserve = 16: must be in 0..=15"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn compare_and_sweep_take_the_prefetcher_through_set() {
    let path = trace_path("synthetic-small");
    let tile = tile_set(&path);
    let j = ok(&wasp(&[
        "compare",
        "-q",
        "--trace",
        &path,
        "--set",
        &tile,
        "--set",
        "prefetch.kind=oracle-tile",
        "--policies",
        "baseline,wasp:0:3",
        "--json",
        "-",
    ]));
    let v: Value = serde_json::from_str(&j).unwrap();
    for run in v.as_array().unwrap() {
        assert_eq!(run["prefetch"]["kind"], "oracle-tile");
    }
    // The table's header names the prefetcher and a non-default issue
    // order, and names neither on the shipped machine.
    let table = |extra: &[&str]| {
        let mut args = vec!["compare", "-q", "--trace", &path, "--set", &tile];
        args.extend_from_slice(extra);
        args.extend_from_slice(&["--policies", "baseline"]);
        ok(&wasp(&args)).lines().next().unwrap().to_string()
    };
    let set = table(&["--set", "prefetch.kind=raster", "--set", "core.issue=gto"]);
    assert!(set.ends_with("|  issue gto  |  prefetch raster"), "{set}");
    let shipped = table(&[]);
    assert!(
        !shipped.contains("prefetch") && !shipped.contains("issue"),
        "{shipped}"
    );
    let d = common::scratch("prefetch", "sweep");
    let file = d.join("sweep.toml");
    let sweep = |kind: &str| {
        format!(
            "scenes = [\"procedural-plane\"]\npolicies = [\"baseline\", \"wasp:0:3\"]\n\
             [[configs]]\nname = \"pf\"\nbase = \"paper\"\nset = [\"prefetch.kind={kind}\"]\n"
        )
    };
    std::fs::write(&file, sweep("raster")).unwrap();
    let list = ok(&wasp(&["sweep", file.to_str().unwrap(), "--list"]));
    assert_eq!(list.lines().count(), 2, "{list}");
    std::fs::write(&file, sweep("stride")).unwrap();
    let o = wasp(&["sweep", file.to_str().unwrap(), "--list"]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("stride"), "{}", stderr(&o));
}
