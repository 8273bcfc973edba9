//! Helpers the crate's tests share: the checked-in trace files, trace
//! heads of each version, a checker of reader errors and a strategy for
//! arbitrary valid traces.

use crate::{Problem, Trace, TraceBuilder, TraceHeader, MAX_ALU_RUN, MAX_REJECTED_RUN};
use proptest::prelude::*;

/// The checked-in traces of `tests/traces`: tiny (version 1), overdraw
/// (version 2) and synthetic-small (version 1).
pub(crate) const TINY: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/traces/tiny.trace");
pub(crate) const OVERDRAW: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../tests/traces/overdraw.trace"
);
pub(crate) const SYNTH_SMALL: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../tests/traces/synthetic-small.trace"
);

/// Whether two statistics agree to 1e-9.
pub(crate) fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

/// Trace heads, line 1 to the `frame` line, of versions 2, 1, 3 and 4.
pub(crate) const HEAD: &str = "wasp-trace 2\nworkload w\nframe 100 70 tile 64\n";
pub(crate) const HEAD1: &str = "wasp-trace 1\nworkload w\nframe 100 70 tile 64\n";
pub(crate) const HEAD3: &str = "wasp-trace 3\nworkload w\nframe 128 64 tile 64\n";
pub(crate) const HEAD4: &str = "wasp-trace 4\nworkload w\nframe 128 64 tile 64\n";

/// Parses `text` and returns (line, problem, message) of the error.
pub(crate) fn fail(text: &str) -> (usize, Problem, String) {
    match Trace::parse(text, "x.trace") {
        Ok(t) => panic!("parsed: {t:?}"),
        Err(e) => {
            let msg = e.to_string();
            let line = e.line().unwrap();
            assert!(msg.starts_with(&format!("x.trace:{line}: ")), "{msg}");
            assert!(msg.contains("(expected "), "{msg}");
            (line, e.problem().unwrap().clone(), msg)
        }
    }
}

/// Each text of `cases` fails to parse as `f.trace` at its line, with a
/// message that says its words.
pub(crate) fn reported_at(cases: &[(String, usize, &str)]) {
    for (text, line, says) in cases {
        let e = crate::Trace::parse(text, "f.trace").unwrap_err();
        assert_eq!(e.line(), Some(*line), "{e}");
        let m = e.to_string();
        assert!(m.starts_with(&format!("f.trace:{line}: ")), "{m}");
        assert!(m.contains(says), "{m}");
    }
}

/// A version-2 trace of `HEAD` and the lines `s`.
pub(crate) fn body(s: &str) -> String {
    format!("{HEAD}{s}")
}

/// A version-1 trace of `HEAD1` and the lines `s`.
pub(crate) fn body1(s: &str) -> String {
    format!("{HEAD1}{s}")
}

/// An instruction of a generated quad: (ALU run, no blocks) or (0 for
/// bilinear, 1 for trilinear, blocks).
type SpecInstr = (u32, Vec<u64>);

/// A generated tile: its position (any `u32`s, reduced into the frame),
/// its quads (position, instructions), the rejected quads before each of
/// the first 8 quads and after the last, and whether every quad of it is
/// hidden.
type SpecTile = (
    u32,
    u32,
    Vec<(u32, u32, Vec<SpecInstr>)>,
    Vec<(u32, bool)>,
    bool,
);

/// Headers: any frame up to 300x200, an even tile size, a name without
/// blank edges and up to 2 notes.
fn arb_header() -> impl Strategy<Value = TraceHeader> {
    (
        1u32..300,
        1u32..200,
        1u32..=32,
        "[ -~]{1,20}",
        proptest::collection::vec("[ -~\t]{0,12}", 0..3),
    )
        .prop_filter_map("blank-edged name", |(w, h, half, name, notes)| {
            let name = name.trim().to_string();
            if name.is_empty() {
                return None;
            }
            let mut hd = TraceHeader::new(name, w, h, 2 * half);
            hd.notes = notes;
            Some(hd)
        })
}

/// A quad's 1 to 5 instructions: ALU runs, and texture instructions of
/// any blocks or of few low blocks (descending), bilinear or trilinear.
fn arb_quad() -> impl Strategy<Value = Vec<SpecInstr>> + Clone {
    let instr = prop_oneof![
        (1u32..=MAX_ALU_RUN).prop_map(|n| (n, vec![])),
        (
            proptest::collection::btree_set(any::<u64>(), 1..6),
            any::<bool>()
        )
            .prop_map(|(s, tri)| (u32::from(tri), s.into_iter().collect::<Vec<u64>>())),
        (
            proptest::collection::btree_set(0u64..64, 1..5),
            any::<bool>()
        )
            .prop_map(|(s, tri)| (u32::from(tri), s.into_iter().rev().collect::<Vec<u64>>())),
    ];
    proptest::collection::vec(instr, 1..6)
}

/// A strategy for arbitrary valid traces, built through the builder:
/// version-4 traces (positions in any order, repeats, rejected quads
/// between and after the quads, tiles of rejected quads only, trilinear
/// texture instructions) or, with `scanline`, traces that are also valid
/// version 1 (no rejected quad, every texture instruction bilinear).
pub(crate) fn arb_trace_v(scanline: bool) -> impl Strategy<Value = Trace> {
    let quad = arb_quad();
    // Rejected quads before each quad and after the last (mostly none; a
    // count may come in two calls, which the builder adds up).
    let rejected = prop_oneof![
        4 => Just(0u32),
        3 => 1u32..40,
        1 => 1u32..=MAX_REJECTED_RUN,
    ];
    let rejections = proptest::collection::vec((rejected, any::<bool>()), 9);
    arb_header()
        .prop_flat_map(move |hd| {
            let tiles = proptest::collection::vec(
                (
                    any::<u32>(),
                    any::<u32>(),
                    proptest::collection::vec((any::<u32>(), any::<u32>(), quad.clone()), 1..8),
                    rejections.clone(),
                    prop::bool::weighted(0.15),
                ),
                0..5,
            );
            (Just(hd), tiles)
        })
        .prop_map(move |(hd, tiles)| build_trace(hd, tiles, scanline))
}

/// Add `n` rejected quads (in two calls when `split`); none in a
/// `scanline` trace.
fn reject(b: &mut TraceBuilder, (n, split): (u32, bool), scanline: bool) {
    if n == 0 || scanline {
        return;
    }
    if split && n > 1 {
        b.rejected(n / 2).unwrap();
        b.rejected(n - n / 2).unwrap();
    } else {
        b.rejected(n).unwrap();
    }
}

/// The trace of the generated `tiles` (see [`arb_trace_v`]).
fn build_trace(hd: TraceHeader, tiles: Vec<SpecTile>, scanline: bool) -> Trace {
    let mut b = Trace::builder(hd).unwrap();
    for tile in tiles {
        build_tile(&mut b, tile, scanline);
    }
    b.finish().unwrap()
}

/// One generated tile: its quads placed in the frame (in scanline order
/// without repeats for a `scanline` trace, else with a repeated position),
/// the rejected quads between them; a duplicate tile is skipped.
fn build_tile(b: &mut TraceBuilder, tile: SpecTile, scanline: bool) {
    let (nx, ny, side) = {
        let hd = b.header();
        (hd.tiles_x(), hd.tiles_y(), hd.quads_per_side())
    };
    let (tx, ty, quads, rej, hidden) = tile;
    let (tx, ty) = (tx % nx, ty % ny);
    if b.begin_tile(tx, ty).is_err() {
        return; // duplicate tile
    }
    let mut placed: Vec<(u32, u32, Vec<SpecInstr>)> = quads
        .into_iter()
        .map(|(x, y, q)| (x % side, y % side, q))
        .filter(|&(x, y, _)| b.header().quad_in_frame(tx, ty, x, y))
        .collect();
    if scanline {
        placed.sort_by_key(|&(x, y, _)| (y, x));
        placed.dedup_by_key(|&mut (x, y, _)| (x, y));
    } else if placed.len() > 2 {
        // Overdraw: repeat a position (a later fragment there).
        let (x, y, _) = placed[0];
        let q = placed[1].2.clone();
        placed.push((x, y, q));
    }
    if placed.is_empty() {
        placed.push((0, 0, vec![(1, vec![])]));
    }
    if hidden && !scanline {
        // A tile whose every quad Early-Z rejected.
        placed.clear();
        reject(b, (rej[8].0.max(1), rej[8].1), scanline);
    }
    for (i, (x, y, instrs)) in placed.into_iter().enumerate() {
        reject(b, rej[i], scanline);
        b.begin_quad(x, y).unwrap();
        for (n, blocks) in instrs {
            if blocks.is_empty() {
                // Merging may overflow the run limit: then skip it.
                let _ = b.alu(n);
            } else {
                b.tex_filtered(&blocks, n == 1 && !scanline).unwrap();
            }
        }
    }
    if !hidden {
        reject(b, rej[8], scanline);
    }
    b.end_tile().unwrap();
}

/// Arbitrary valid traces of either kind of [`arb_trace_v`].
pub(crate) fn arb_trace() -> impl Strategy<Value = Trace> {
    prop_oneof![arb_trace_v(false), arb_trace_v(true)]
}
