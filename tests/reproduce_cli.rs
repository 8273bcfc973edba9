//! `wasp reproduce` as a user runs it: the report and its files, a point
//! checked against `wasp render` + `wasp run`, a resumed run, bad input.
//!
//! The scene is a small procedural one (a scene definition file, 320x192
//! pixels) so that the quick look runs in seconds in a debug build.

mod common;
use common::{ok, scratch, stderr, wasp};
use std::path::Path;

const TINY: &str = r#"name = "tiny-plane"
game = "procedural"
map = "plane"
camera = "ground"
width = 320
height = 192
description = "A small procedural plane for tests"
"#;

fn csv_rows(path: &Path) -> Vec<Vec<String>> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(split_csv)
        .collect()
}

/// Split a CSV line (fields may be quoted with doubled quotes inside).
fn split_csv(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut cur = String::new();
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                cur.push('"');
                chars.next();
            }
            ('"', _) => quoted = !quoted,
            (',', false) => out.push(std::mem::take(&mut cur)),
            _ => cur.push(c),
        }
    }
    out.push(cur);
    out
}

#[test]
fn the_quick_look_reports_resumes_and_agrees_with_wasp_run() {
    let dir = scratch("reproduce", "quick");
    let scene = dir.join("tiny-plane.toml");
    std::fs::write(&scene, TINY).unwrap();
    let out = dir.join("out");
    let (s, o) = (scene.to_str().unwrap(), out.to_str().unwrap());
    let args = ["reproduce", "--quick", "--scenes", s, "--out", o];
    let first = wasp(&args);
    ok(&first);
    let err = stderr(&first);
    assert!(err.contains("0 already done"), "{err}");
    assert!(err.contains("s wall") && err.contains("tasks/s"), "{err}");

    // The report: the side-by-side table and every embedded figure exists.
    let report = std::fs::read_to_string(out.join("REPORT.md")).unwrap();
    for needle in [
        "## The paper's headline numbers beside ours",
        "| WaSP speedup | +3.9% |",
        "| Fullpriority speedup | +1.3% |",
        "| Memory latency change (WaSP) | -9.0% |",
        "**A subset of the scenes**",
        "**Quick look**",
        "## Why the numbers differ",
    ] {
        assert!(report.contains(needle), "REPORT.md lacks {needle:?}");
    }
    let mut figures = 0;
    for line in report.lines() {
        if let Some(rest) = line.strip_prefix("![") {
            let file = rest.split("](").nth(1).unwrap().trim_end_matches(')');
            let path = out.join(file);
            assert!(path.is_file(), "{} is missing", path.display());
            let bytes = std::fs::read(&path).unwrap();
            assert_eq!(&bytes[1..4], b"PNG", "{} is not a PNG", path.display());
            if !file.starts_with("figures/timeline.") {
                assert!(path.with_extension("svg").is_file());
            }
            figures += 1;
        }
    }
    assert!(figures >= 15, "only {figures} figures embedded");

    // A point spot-checked against render + run: the baseline of the
    // heuristics figure.
    let trace = dir.join("tiny.trace");
    ok(&wasp(&[
        "render",
        s,
        "--trace-out",
        trace.to_str().unwrap(),
        "-q",
    ]));
    let run = ok(&wasp(&[
        "run",
        "--trace",
        trace.to_str().unwrap(),
        "--policy",
        "baseline",
        "--json",
        "-",
        "-q",
    ]));
    let v: serde_json::Value = serde_json::from_str(&run).unwrap();
    let cycles = v["cycles"].as_u64().unwrap();
    let rows = csv_rows(&out.join("data/points.csv"));
    let col = |name: &str| rows[0].iter().position(|c| c == name).unwrap();
    let (sets, cyc) = (col("sets"), col("cycles"));
    let base = rows
        .iter()
        .find(|r| r[sets] == "raster.dispatch=\"shared-tile\" scheduler.policy=\"baseline\"")
        .expect("the baseline point");
    assert_eq!(base[cyc], cycles.to_string());
    // The heuristics figure's data is built from those points.
    let speed = csv_rows(&out.join("data/speedup.shared-tile.csv"));
    assert_eq!(speed[0][0], "category");
    assert!(speed.iter().any(|r| r[0] == "tiny-plane"));

    // A killed run: one point lost, the rest kept; the next run redoes one.
    let points: Vec<_> = std::fs::read_dir(out.join("points"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    assert!(points.len() >= 10, "{} points", points.len());
    std::fs::remove_file(&points[0]).unwrap();
    let again = wasp(&args);
    ok(&again);
    let err = stderr(&again);
    assert!(err.contains("(1 run, "), "{err}");
    let report2 = std::fs::read_to_string(out.join("REPORT.md")).unwrap();
    assert_eq!(report, report2, "the same results give the same report");
    // Quiet: no progress, notes or closing summary.
    let quiet = wasp(&[&args[..], &["-q"]].concat());
    ok(&quiet);
    assert_eq!(stderr(&quiet), "", "-q printed on stderr");
    assert!(
        report.contains(&format!(
            "Generated by `wasp reproduce --quick --scenes {s}`"
        )),
        "{}",
        report.lines().nth(2).unwrap_or("")
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_requests_are_refused_before_any_run() {
    let dir = scratch("reproduce", "bad");
    let o = dir.join("out");
    let o = o.to_str().unwrap();
    for (args, needle) in [
        (
            vec!["--scenes", "no-such-scene"],
            "no scene `no-such-scene`",
        ),
        (vec!["--jobs", "0"], "--jobs 0"),
        (
            vec!["--scenes", "procedural-plane,procedural-plane"],
            "named twice",
        ),
        (vec!["--machines", "sideways"], "sideways"),
        (vec!["--routes", "neither"], "neither"),
    ] {
        let mut a = vec!["reproduce", "--out", o, "-q"];
        a.extend(args);
        let r = wasp(&a);
        assert_eq!(r.status.code(), Some(2), "{a:?}");
        assert!(stderr(&r).contains(needle), "{a:?}: {}", stderr(&r));
    }
    assert!(
        !dir.join("out/points").exists() || {
            std::fs::read_dir(dir.join("out/points")).unwrap().count() == 0
        }
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_dry_run_counts_the_plan_with_its_engine_twins_and_writes_nothing() {
    let dir = scratch("reproduce", "dry-run");
    let out = dir.join("out");
    let o = out.to_str().unwrap();
    let counts = |routes: &str| {
        let r = wasp(&[
            "reproduce",
            "--quick",
            "--dry-run",
            "--routes",
            routes,
            "--out",
            o,
        ]);
        ok(&r);
        String::from_utf8(r.stdout).unwrap()
    };
    // The quick look's cameras bring their engine twins: two pairs, one
    // scene of each beside the means; each pair adds a characterisation
    // and four points for the scene beside and the two prefetchers for
    // the one that counts (7 tasks). Each scene in the means is also
    // characterised in RGBA8 and runs the baseline and ideal memory so
    // (3 tasks each).
    let engine = counts("engine");
    for said in [
        "scenes: 5 in the study and its means, 2 beside them (5 loader, 2 engine)",
        "twin pairs: 2",
        "the paper's experiments: 150 tasks,",
        "without the engine scenes: the paper's experiments: 136 tasks,",
    ] {
        assert!(engine.contains(said), "lacks {said:?}:\n{engine}");
    }
    // Both twins counting: each engine twin runs the whole quick study.
    let both = counts("both");
    assert!(
        both.contains("scenes: 7 in the study and its means, 0 beside them"),
        "{both}"
    );
    assert!(!out.exists(), "a dry run writes nothing");
    let _ = std::fs::remove_dir_all(&dir);
}
