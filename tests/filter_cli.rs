//! Whole-program tests of the texture filter rate: with no filter cycles
//! the simulator reproduces, byte for byte, the runs recorded in
//! `tests/golden/` before the filter unit existed, and the run JSON says
//! which filter ran.

use serde_json::Value;

mod common;
use common::{ok, wasp};

const TRACES: [&str; 3] = ["tiny", "overdraw", "synthetic-small"];
const POLICIES: [(&str, &str); 2] = [("baseline", "baseline"), ("wasp:4", "wasp")];

fn trace_path(name: &str) -> String {
    format!("{}/tests/traces/{name}.trace", env!("CARGO_MANIFEST_DIR"))
}

/// The tile size a trace's `frame` line names.
fn tile_of(path: &str) -> String {
    let text = std::fs::read_to_string(path).unwrap();
    let frame = text.lines().find(|l| l.starts_with("frame ")).unwrap();
    frame.rsplit(' ').next().unwrap().to_string()
}

fn run_json(trace: &str, policy: &str, sets: &[&str]) -> Value {
    let tile = format!("gpu.tile_size={}", tile_of(trace));
    let mut a = vec![
        "run", "-q", "--trace", trace, "--policy", policy, "--set", &tile,
    ];
    for s in sets {
        a.extend_from_slice(&["--set", s]);
    }
    a.extend_from_slice(&["--json", "-"]);
    serde_json::from_str(&ok(&wasp(&a))).unwrap()
}

fn golden(trace: &str, policy: &str) -> Value {
    let p = format!(
        "{}/tests/golden/{trace}-{policy}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap()
}

/// The run without its `filter` block, which the golden runs predate, its
/// machine named as in the golden runs (without the overrides), and
/// reduced to the fields the golden runs have (later ones, such as
/// `launch_rule`, `blocked_on` and `blocked`, are new fields, not changed
/// ones; the test fails if a golden field is missing).
fn without_filter(mut v: Value, golden: &Value) -> (Value, Value) {
    let o = v.as_object_mut().unwrap();
    let f = o.remove("filter").expect("filter block");
    // The machine is named with the run's overrides, which the golden runs
    // predate: its base name must be the golden one.
    let base = golden["machine"].as_str().unwrap();
    let named = o["machine"].as_str().unwrap().to_string();
    assert!(named.starts_with(&format!("{base} + ")), "{named}");
    o.insert("machine".into(), golden["machine"].clone());
    let keys = golden.as_object().unwrap();
    o.retain(|k, _| keys.contains_key(k));
    (v, f)
}

#[test]
fn no_filter_cycles_reproduce_the_golden_runs() {
    let d = common::scratch("filter", "golden");
    for name in TRACES {
        let path = trace_path(name);
        // The same trace as version 4 with every texture instruction
        // trilinear: with no filter cycles the marker changes no timing.
        let text = std::fs::read_to_string(&path).unwrap();
        let first = text.find('\n').unwrap();
        let tri_body: String = text[first..]
            .split('\n')
            .map(|l| {
                if l.starts_with("q ") {
                    l.replace(" t", " T")
                } else {
                    l.to_string()
                }
            })
            .collect::<Vec<_>>()
            .join("\n");
        let tri = d.join(format!("{name}-tri.trace"));
        std::fs::write(&tri, format!("wasp-trace 4{tri_body}")).unwrap();
        let tri = tri.display().to_string();
        for (policy, file) in POLICIES {
            let want = golden(name, file);
            for timing in ["overlap", "serial"] {
                let t = format!("core.filter_timing=\"{timing}\"");
                // The golden runs predate the blocked_on rule: a warp then
                // blocked on its first-level miss.
                let sets = [
                    "core.filter_cycles_bilinear=0",
                    "core.filter_cycles_trilinear=0",
                    "scheduler.blocked_on=\"first-level\"",
                    t.as_str(),
                ];
                let (got, f) = without_filter(run_json(&path, policy, &sets), &want);
                assert_eq!(got, want, "{name} {policy} {timing}");
                assert_eq!(f["busy_cycles"], 0);
                assert_eq!(f["wait_cycles"], 0);
                assert_eq!(f["trilinear_instructions"], 0);
                assert_eq!(f["timing"], timing);
                let (got, f) = without_filter(run_json(&tri, policy, &sets), &want);
                assert_eq!(got, want, "{name} {policy} {timing}, all trilinear");
                assert_eq!(f["trilinear_instructions"], want["tex_instructions"]);
                assert_eq!(f["trilinear_share"], 1.0);
            }
        }
    }
}

#[test]
fn the_run_json_says_which_filter_ran() {
    let path = trace_path("synthetic-small");
    let v = run_json(&path, "baseline", &[]);
    let f = &v["filter"];
    assert_eq!(f["cycles_bilinear"], 1, "{f}");
    assert_eq!(f["cycles_trilinear"], 2, "{f}");
    assert_eq!(f["timing"], "overlap", "{f}");
    // Every texture instruction holds the filter for its one pass.
    assert_eq!(f["busy_cycles"], v["tex_instructions"], "{f}");
    assert_eq!(
        f["trilinear_instructions"], 0,
        "a version-1 trace is bilinear"
    );
    let busy = f["busy_fraction"].as_f64().unwrap();
    assert!(busy > 0.0 && busy < 1.0, "{f}");
    let s = run_json(&path, "baseline", &["core.filter_timing=\"serial\""]);
    assert_eq!(s["filter"]["timing"], "serial");
    assert!(s["cycles"].as_u64() > v["cycles"].as_u64());
    // `compare` carries it too, and the table prints it.
    let j = ok(&wasp(&[
        "compare",
        "-q",
        "--trace",
        &path,
        "--set",
        "gpu.tile_size=64",
        "--set",
        "core.filter_cycles_trilinear=3",
        "--policies",
        "baseline,wasp:4",
        "--json",
        "-",
    ]));
    let runs: Value = serde_json::from_str(&j).unwrap();
    for r in runs.as_array().unwrap() {
        assert_eq!(r["filter"]["cycles_trilinear"], 3, "{r}");
    }
    let table = ok(&wasp(&["run", "-q", "--trace", &path]));
    assert!(table.contains("filter 1/2 cycles (overlap)"), "{table}");
}
