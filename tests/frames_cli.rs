//! Traces of several frames through the program: `wasp trace-cat` joins
//! traces written by `wasp synth`, `wasp run` and `wasp compare` run the
//! frames in order and report the last with a record per frame, `--warm K`
//! picks the frames, and a bad `--warm` or a mismatched join is refused.

mod common;
use common::run::{dir, run_json, synth_trace, tiny_trace};
use common::{ok, stderr, wasp};

/// `wasp trace-cat` of `parts` into `out`.
fn cat(parts: &[&str], out: &str) {
    let mut a = vec!["trace-cat", "-q"];
    a.extend_from_slice(parts);
    a.extend_from_slice(&["--out", out]);
    ok(&wasp(&a));
}

#[test]
fn a_joined_trace_runs_frame_after_frame() {
    let d = dir("frames");
    let (a, b) = (synth_trace(&d, 1), synth_trace(&d, 2));
    let three = d.join("aba.trace").display().to_string();
    cat(&[&a, &b, &a], &three);
    let text = std::fs::read_to_string(&three).unwrap();
    assert!(text.starts_with("wasp-trace 5\n"), "{}", &text[..40]);
    assert_eq!(text.matches("\nnext-frame\n").count(), 2);

    let all = run_json(&["--trace", &three]);
    let frames = all["frames"].as_array().unwrap();
    let index: Vec<u64> = frames
        .iter()
        .map(|f| f["frame"].as_u64().unwrap())
        .collect();
    assert_eq!(index, vec![0, 1, 2]);
    // The report is the last frame's; frame 2 repeats frame 0 with the
    // caches warm.
    assert_eq!(all["cycles"], frames[2]["cycles"]);
    assert_eq!(all["l2"]["misses"], frames[2]["l2"]["misses"]);
    let l2 = |i: usize| frames[i]["l2"]["misses"].as_u64().unwrap();
    assert!(l2(2) < l2(0), "{} !< {}", l2(2), l2(0));
    // Frame 0 measures what a one-frame run of `a` does.
    let alone = run_json(&["--trace", &a]);
    assert!(
        alone.get("frames").is_none(),
        "no frame records for one frame"
    );
    assert_eq!(frames[0]["cycles"], alone["cycles"]);
    assert_eq!(frames[0]["l1"]["misses"], alone["l1"]["misses"]);

    // --warm 0: the last frame cold, which is the run of `a` alone.
    let cold = run_json(&["--trace", &three, "--warm", "0"]);
    assert_eq!(cold["frames"].as_array().unwrap().len(), 1);
    assert_eq!(cold["cycles"], alone["cycles"]);
    let one = run_json(&["--trace", &three, "--warm", "1"]);
    assert_eq!(one["frames"][0]["frame"], 1);

    // The table ends with the per-frame table.
    let table = ok(&wasp(&["run", "-q", "--trace", &three]));
    assert!(
        table.contains("frames: 3 run, the report above is frame 2's (after 2 earlier"),
        "{table}"
    );
    assert_eq!(
        table
            .lines()
            .filter(|l| l.trim_start().starts_with("2 "))
            .count(),
        1
    );
    // compare names the frame it measured.
    let c = ok(&wasp(&[
        "compare",
        "-q",
        "--trace",
        &three,
        "--policies",
        "baseline,wasp:0:3",
        "--warm",
        "1",
    ]));
    assert!(
        c.lines()
            .next()
            .unwrap()
            .contains("|  frame 2 after 1 earlier"),
        "{c}"
    );
}

#[test]
fn warm_beyond_the_trace_and_mismatched_joins_are_refused() {
    let d = dir("frames-bad");
    let a = synth_trace(&d, 3);
    let two = d.join("aa.trace").display().to_string();
    cat(&[&a, &a], &two);
    for cmd in ["run", "compare"] {
        let o = wasp(&[cmd, "-q", "--trace", &two, "--warm", "2"]);
        assert_eq!(o.status.code(), Some(2), "{cmd}");
        let e = stderr(&o);
        assert!(
            e.contains(&format!(
                "--warm 2: {two} has 2 frames, so at most 1 can run before the last"
            )),
            "{cmd}: {e}"
        );
    }
    let o = wasp(&["run", "-q", "--trace", &a, "--warm", "1"]);
    assert!(
        stderr(&o).contains("has 1 frame, so at most 0"),
        "{}",
        stderr(&o)
    );
    let o = wasp(&["run", "-q", "--trace", &a, "--warm", "x"]);
    assert_eq!(o.status.code(), Some(2));
    // The tiny trace has 8-pixel tiles: it cannot join a 64-pixel one.
    let out = d.join("bad.trace");
    let o = wasp(&[
        "trace-cat",
        &a,
        &tiny_trace(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("(expected 256x128 with 64-pixel tiles)"),
        "{}",
        stderr(&o)
    );
    assert!(!out.exists(), "nothing written");
}
