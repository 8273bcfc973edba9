//! Whole-program tests of `wasp compare` and `wasp bench`, the commands
//! that run one trace several times: the speedups against the baseline,
//! and the timing of every point.

use serde_json::Value;

mod common;
use common::run::{dir, synth_trace};
use common::{ok, stderr, wasp};

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
