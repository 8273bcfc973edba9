//! Whole-program tests of `wasp compare --variant`: policies and machine
//! variants (a prefetcher, ideal memory) in one table of speedups against
//! one reference row, in the table, JSON and CSV.

use serde_json::Value;

mod common;
use common::{ok, stderr, wasp};

fn trace() -> String {
    concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/traces/synthetic-small.trace"
    )
    .to_string()
}

const ARGS: [&str; 10] = [
    "compare",
    "-q",
    "--policies",
    "baseline,wasp",
    "--variant",
    "raster:prefetch.kind=raster",
    "--variant",
    "oracle:prefetch.kind=oracle-tile",
    "--with-ideal",
    "--trace",
];

fn compare(extra: &[&str]) -> String {
    let t = trace();
    let mut a: Vec<&str> = ARGS.to_vec();
    a.push(&t);
    a.extend_from_slice(extra);
    ok(&wasp(&a))
}

#[test]
fn rivals_and_bounds_share_one_reference() {
    let v: Value = serde_json::from_str(&compare(&["--json", "-"])).unwrap();
    let rows = v.as_array().unwrap();
    let names: Vec<&str> = rows.iter().map(|r| r["row"].as_str().unwrap()).collect();
    assert_eq!(
        names,
        [
            "baseline",
            "wasp:0:3",
            "baseline +ideal memory",
            "raster/baseline",
            "raster/wasp:0:3",
            "oracle/baseline",
            "oracle/wasp:0:3"
        ]
    );
    let base = rows[0]["stats"]["cycles"].as_f64().unwrap();
    for r in rows {
        assert_eq!(r["reference"], "baseline");
        let c = r["stats"]["cycles"].as_f64().unwrap();
        let want = 100.0 * (base / c - 1.0);
        assert!((r["speedup_percent"].as_f64().unwrap() - want).abs() < 1e-9);
    }
    assert!(rows[3]["stats"]["machine"]
        .as_str()
        .unwrap()
        .ends_with(" + prefetch.kind=raster"));
    assert_eq!(rows[3]["variant"], "raster");
    assert!(rows[0]["variant"].is_null());
    // The prefetcher changes the run: its rows are not the reference's.
    assert_ne!(rows[3]["stats"]["cycles"], rows[0]["stats"]["cycles"]);

    let csv = compare(&["--csv", "-"]);
    let lines: Vec<&str> = csv.lines().collect();
    assert!(lines[0].starts_with("row,variant,reference,speedup_percent,"));
    assert_eq!(lines.len(), 8);
    assert!(lines[5].starts_with("raster/wasp:0:3,raster,baseline,"));

    let table = compare(&[]);
    assert!(
        table.contains("variant oracle: machine paper-width4-64warps + prefetch.kind=oracle-tile")
    );
    assert!(table.lines().any(|l| l.starts_with("oracle/wasp:0:3 ")));
    assert!(table.contains("speedup = baseline cycles / policy cycles - 1"));
}

#[test]
fn another_reference_and_bad_variants() {
    let v: Value =
        serde_json::from_str(&compare(&["--reference", "raster/baseline", "--json", "-"])).unwrap();
    let rows = v.as_array().unwrap();
    assert_eq!(rows[3]["speedup_percent"], 0.0);
    assert_eq!(rows[0]["reference"], "raster/baseline");
    let t = trace();
    for (bad, says) in [
        (vec!["--variant", "raster"], "NAME:KEY=VALUE"),
        (vec!["--variant", "x:l0.mshrs=0"], "--variant x: "),
        (vec!["--reference", "nope"], "--reference nope: no such row"),
    ] {
        let mut a = vec!["compare", "-q", "--trace", &t];
        a.extend_from_slice(&bad);
        let o = wasp(&a);
        assert_eq!(o.status.code(), Some(2), "{bad:?}");
        assert!(stderr(&o).contains(says), "{}", stderr(&o));
    }
}
