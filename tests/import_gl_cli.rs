//! Whole-program tests of `wasp import-gl` on `tests/gl/quads.trace` (the
//! capture of `tests/gl/quads.c`, described in `tests/gl/README.md`), and
//! its errors on bad input.

use std::path::{Path, PathBuf};

mod common;
use common::{ok, stderr, wasp};

/// Draw calls per frame of quads.trace: `apitrace dump tests/gl/quads.trace
/// | grep -cE '^[0-9]+ glDraw(Arrays|Elements)'` prints 21 for its 3 frames, 7 each (two
/// glDrawElements, a strip and a fan, three GL_QUADS).
const DRAWS_PER_FRAME: u64 = 7;

fn capture() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/gl/quads.trace")
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// `wasp import-gl quads.trace ARGS --trace-out DIR/out.trace --json
/// DIR/out.json`: the printed summary and the JSON.
fn import(name: &str, args: &[&str]) -> (String, serde_json::Value, PathBuf) {
    let d = common::scratch("importgl", name);
    let (trace, json) = (d.join("out.trace"), d.join("out.json"));
    let cap = capture();
    let mut a = vec![
        "import-gl",
        s(&cap),
        "--trace-out",
        s(&trace),
        "--json",
        s(&json),
        "-q",
    ];
    a.extend_from_slice(args);
    let out = ok(&wasp(&a));
    let j: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    (out, j, trace)
}

fn u(v: &serde_json::Value) -> u64 {
    v.as_u64().unwrap_or_else(|| panic!("not a count: {v}"))
}

#[test]
fn the_last_frame_of_quads_trace_gives_the_counts_its_geometry_gives() {
    let (out, j, trace) = import("last", &[]);
    assert!(
        out.lines()
            .any(|l| l == format!("draw calls: {DRAWS_PER_FRAME}")),
        "{out}"
    );
    assert_eq!((u(&j["frame"]), u(&j["frames_read"])), (2, 3));
    assert_eq!((u(&j["width"]), u(&j["height"])), (256, 128), "the window");
    assert_eq!(u(&j["draw_calls"]), DRAWS_PER_FRAME);
    // Every draw is two triangles; none is clipped or culled (the strip's
    // and fan's winding is counter-clockwise, like the quads').
    assert_eq!(u(&j["triangles_submitted"]), 2 * DRAWS_PER_FRAME);
    assert_eq!(u(&j["triangles_after_clipping_and_culling"]), 14);
    let d = j["draws"].as_array().unwrap();
    let px = |i: usize| u(&d[i]["pixels"]);
    let shaded = |i: usize| u(&d[i]["quads_shaded"]);
    let rejected = |i: usize| u(&d[i]["quads_rejected_early_z"]);
    // Frame 2: modelview x + 0.2, glFrustum(-1, 1, -0.5, 0.5, 1, 10) on
    // 256x128, so a point (x, y, z) lands at column 128 (1 + x / -z), row
    // 64 (1 - 2 y / -z). The back quad (x -1.3..0.7, y -1..1, z -3) spans
    // columns 72.5..157.9 and rows 21.3..106.7: 85 x 86 pixel centres.
    // Drawn first, nothing rejects it.
    assert_eq!((px(0), rejected(0)), (85 * 86, 0));
    // The front quad (x -0.3..1.7, y -0.5..0.8, z -2.5): columns
    // 112.6..215.0, rows 23.0..89.6: 102 x 67; nearer than the back one.
    assert_eq!((px(1), rejected(1)), (102 * 67, 0));
    // The strip (x -1.8..-0.8, y -1.2..-0.2, z -4): 32 x 32 pixels at
    // columns 70..101, rows 70..101, behind the back quad from column 73:
    // columns 70 to 72 stay, 3 x 32 pixels. Its 16 x 16 quads, plus the 16
    // its diagonal splits between its triangles, are covered; of those the
    // 2 quad columns holding columns 70-72 (16 quads each, and one split
    // quad in each) shade, the rest are rejected.
    assert_eq!(px(2), 3 * 32);
    assert_eq!(shaded(2) + rejected(2), 16 * 16 + 16);
    assert_eq!(shaded(2), 2 * 16 + 2);
    // The fan (z -3.5) lies behind the front quad but for its right tip
    // (column 215.8, past the front quad's 215.0): one pixel.
    assert_eq!((px(3), shaded(3)), (1, 1));
    assert!(rejected(3) > 0);
    // The orthographic pass (GL_ALWAYS: no rejects), in pixels: the opaque
    // quad 64 x 48, the blended one 80 x 60 and the alpha-tested one 80 x
    // 80 (its warps run whatever the alpha test discards: 40 x 40 quads and
    // the 40 its 45-degree diagonal splits).
    assert_eq!([px(4), px(5), px(6)], [64 * 48, 80 * 60, 80 * 80]);
    assert_eq!([rejected(4), rejected(5), rejected(6)], [0, 0, 0]);
    assert_eq!(shaded(6), 40 * 40 + 40);
    assert!(shaded(4) >= 32 * 24 && shaded(5) >= 40 * 30);
    // The totals are the draws' sums, and the trace holds them.
    let all = |f: &dyn Fn(usize) -> u64| (0..d.len()).map(f).sum::<u64>();
    assert_eq!(u(&j["quads_shaded"]), all(&shaded));
    assert_eq!(u(&j["quads_rejected_early_z"]), all(&rejected));
    assert_eq!(u(&j["quads_shaded"]), 7458);
    assert_eq!(u(&j["quads_rejected_early_z"]), 429);
    let text = std::fs::read_to_string(&trace).unwrap();
    assert!(text.starts_with("wasp-trace"), "a trace");
    assert!(text.contains("7458 fragments shaded"), "its closing note");
    // Every quad magnifies its texture, so only level 0 is read: texture
    // 1's 8x8 texels are 4 blocks of 4x4, texture 2's 4x4 one block.
    assert_eq!(u(&j["distinct_blocks"]), 5);
    let t = j["textures"].as_array().unwrap();
    assert_eq!(t.len(), 2);
    assert_eq!(
        t[0]["levels"],
        serde_json::json!([0, 1]),
        "two uploaded levels"
    );
    assert_eq!((u(&t[1]["width"]), u(&t[1]["height"])), (4, 4));
    // What the model does not use is counted by name.
    assert_eq!(
        u(&j["unmodelled_calls"]["glClearColor"]),
        3,
        "one per frame read"
    );
    assert_eq!(u(&j["unsupported_draws_skipped"]), 0);
}

#[test]
fn frames_are_chosen_by_index_and_the_first_differs_from_the_last() {
    let (_, j, _) = import("first", &["--frame", "0"]);
    assert_eq!((u(&j["frame"]), u(&j["first_call"])), (0, 0));
    assert_eq!(u(&j["draw_calls"]), DRAWS_PER_FRAME);
    // Frame 0's geometry sits 0.2 units (perspective) and 16 pixels
    // (orthographic) to the left: same pixels for the quads inside the
    // frame, but a different overlap of strip and back quad.
    let d = j["draws"].as_array().unwrap();
    assert_eq!(
        u(&d[6]["pixels"]),
        80 * 80,
        "the alpha-tested quad does not move"
    );
    assert_ne!(u(&j["quads_rejected_early_z"]), 429);
}

#[test]
fn a_range_of_frames_is_one_trace_whose_frames_are_the_single_imports() {
    // Each frame alone, then frames 0..2 in one trace.
    let single: Vec<String> = (0..3)
        .map(|f| {
            let (_, _, t) = import(&format!("single{f}"), &["--frame", &f.to_string()]);
            std::fs::read_to_string(t).unwrap()
        })
        .collect();
    let (out, j, t) = import("range", &["--frames", "0..2"]);
    assert_eq!(u(&j["frame"]), 2, "the summary is the last frame's");
    assert!(
        out.lines()
            .any(|l| l == format!("draw calls: {DRAWS_PER_FRAME}")),
        "{out}"
    );
    let joined = std::fs::read_to_string(&t).unwrap();
    assert_eq!(joined.matches("\nnext-frame").count(), 2, "three frames");
    // The tile lines of each frame are those of its single import.
    let tiles = |text: &str| -> Vec<String> {
        text.lines()
            .skip_while(|l| !l.starts_with("tile"))
            .filter(|l| *l != "next-frame")
            .map(str::to_string)
            .collect()
    };
    let want: Vec<String> = single.iter().flat_map(|t| tiles(t)).collect();
    assert_eq!(tiles(&joined), want);
    // A range past the end, or backwards, writes nothing.
    let d = common::scratch("importgl", "range-bad");
    let out = d.join("never.trace");
    let cap = capture();
    for (range, says) in [("1..3", "3 complete frames"), ("2..1", "A <= B")] {
        let o = wasp(&[
            "import-gl",
            s(&cap),
            "--frames",
            range,
            "--trace-out",
            s(&out),
        ]);
        assert!(!o.status.success());
        assert!(stderr(&o).contains(says), "{range}: {}", stderr(&o));
        assert!(!out.exists());
    }
}

#[test]
fn bad_input_is_an_error_that_names_the_file_and_writes_nothing() {
    let d = common::scratch("importgl", "bad");
    let out = d.join("never.trace");
    let cap = capture();
    let o = wasp(&["import-gl", s(&cap), "--frame", "3", "--trace-out", s(&out)]);
    assert!(!o.status.success());
    let e = stderr(&o);
    assert!(
        e.contains("quads.trace") && e.contains("3 complete frames (0 to 2)"),
        "{e}"
    );
    assert!(!out.exists());
    let not = d.join("not-a-capture.trace");
    std::fs::write(&not, "hello, not a capture\n").unwrap();
    let o = wasp(&["import-gl", s(&not), "--trace-out", s(&out)]);
    let e = stderr(&o);
    assert!(
        !o.status.success()
            && e.contains("not-a-capture.trace")
            && e.contains("not an apitrace capture"),
        "{e}"
    );
    let bytes = std::fs::read(&cap).unwrap();
    let cut = d.join("cut.trace");
    std::fs::write(&cut, &bytes[..bytes.len() / 2]).unwrap();
    let o = wasp(&["import-gl", s(&cut), "--trace-out", s(&out)]);
    let e = stderr(&o);
    assert!(
        !o.status.success() && e.contains("cut.trace") && e.contains("truncated"),
        "{e}"
    );
    assert!(!out.exists());
}
