use super::*;
use crate::instr::Op;
use crate::memo::Memo;
use proptest::prelude::*;

const TINY: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/traces/tiny.trace");
const OVERDRAW: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../tests/traces/overdraw.trace"
);
const SYNTH_SMALL: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../tests/traces/synthetic-small.trace"
);

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

// ---------------------------------------------------------------- files

#[test]
fn tiny_trace_contents() {
    let t = Trace::read(TINY).unwrap();
    let h = t.header();
    assert_eq!(h.workload, "hand:tiny");
    assert_eq!((h.frame_w, h.frame_h, h.tile), (16, 8, 8));
    assert_eq!(h.notes.len(), 8);
    assert_eq!(
        h.notes[0],
        " tiny.trace: a hand-written trace for the reader's tests (see FORMAT.md)."
    );
    assert_eq!((h.tiles_x(), h.tiles_y(), h.quads_per_side()), (2, 1, 4));

    let tiles = t.tiles();
    assert_eq!(tiles.len(), 2);
    assert_eq!((tiles[0].tx(), tiles[0].ty()), (0, 0));
    assert_eq!((tiles[1].tx(), tiles[1].ty()), (1, 0));
    assert_eq!(tiles[0].quad_count(), 16);
    assert_eq!(tiles[1].quad_count(), 10);
    assert_eq!(t.quad_count(), 26);

    // Quad (3, 3) of tile 0 0: shader A touching four base blocks.
    let q = tiles[0].quad_at(3, 3).unwrap();
    assert_eq!(q.index(), 15);
    assert_eq!(
        q.instrs().collect::<Vec<_>>(),
        vec![
            Instr::Alu(2),
            Instr::Tex(&[0x1a11, 0x1a12, 0x1a21, 0x1a22]),
            Instr::Alu(4),
            Instr::Tex(&[0x2000]),
            Instr::Alu(1),
        ]
    );
    assert_eq!(q.entry_count(), 5);
    assert_eq!(q.entry(3), Some(Instr::Tex(&[0x2000])));
    assert_eq!(q.entry(5), None);
    assert_eq!(q.instr_count(), 9);
    assert_eq!(q.tex_count(), 2);
    assert_eq!(
        q.unique_blocks(),
        vec![0x1a11, 0x1a12, 0x1a21, 0x1a22, 0x2000]
    );

    // The partially covered tile: only quads with x <= y.
    let t1 = &tiles[1];
    let positions: Vec<(u32, u32)> = t1.quads().map(|q| (q.x(), q.y())).collect();
    assert_eq!(
        positions,
        vec![
            (0, 0),
            (0, 1),
            (1, 1),
            (0, 2),
            (1, 2),
            (2, 2),
            (0, 3),
            (1, 3),
            (2, 3),
            (3, 3)
        ]
    );
    assert!(t1.quad_at(1, 0).is_none());
    assert_eq!(
        t1.quad_at(1, 1).unwrap().block_accesses(),
        &[0x3402, 0x3403, 0x3412, 0x3413]
    );
    assert_eq!(
        t1.unique_blocks(),
        vec![0x3402, 0x3403, 0x3412, 0x3413, 0x3414, 0x3422, 0x3423, 0x3424]
    );
    assert_eq!(tiles[0].unique_block_count(), 10);
}

#[test]
fn tiny_trace_statistics_match_hand_computation() {
    let t = Trace::read(TINY).unwrap();
    let s0 = t.tiles()[0].stats();
    assert_eq!(
        s0,
        TileStats {
            tx: 0,
            ty: 0,
            warps: 16,
            rejected_quads: 0,
            positions: 16,
            instrs: 16 * 9,
            tex_instrs: 32,
            tri_tex_instrs: 0,
            block_accesses: 36 + 16,
            warp_blocks: 52,
            unique_blocks: 10,
        }
    );
    assert!(close(s0.reuse(), 5.2));
    assert!(close(s0.cf(), 3.25));
    assert!(close(s0.min_estimate1(), 10.0 / 16.0));
    assert!(close(s0.min_estimate2(), 10.0 / 52.0));
    assert!(close(s0.mem_instr_ratio(), 2.0 / 9.0));
    let s1 = t.tiles()[1].stats();
    assert_eq!((s1.warps, s1.warp_blocks, s1.unique_blocks), (10, 23, 8));

    let s = t.stats();
    assert_eq!(s.workload, "hand:tiny");
    assert_eq!((s.tiles, s.warp_tiles, s.warps), (2, 2, 26));
    assert_eq!((s.rejected_quads, s.frame_quads), (0, 32));
    assert_eq!((s.instrs, s.tex_instrs), (224, 42));
    assert_eq!(
        (s.warp_blocks, s.tile_unique_blocks, s.frame_unique_blocks),
        (75, 18, 18)
    );
    assert!(close(s.coverage, 26.0 / 32.0));
    assert_eq!(s.positions, 26);
    assert!(close(s.warps_per_position, 1.0));
    assert!(close(s.mem_instr_ratio, 42.0 / 224.0));
    assert!(close(s.cf, 75.0 / 26.0));
    assert!(close(s.min_estimate1, 18.0 / 26.0));
    assert!(close(s.min_estimate2, 18.0 / 75.0));
    assert!(close(s.reuse, (16.0 * 5.2 + 10.0 * 2.875) / 26.0));
    assert!(close(s.warps_per_tile, 13.0));

    // Footprint of one quad in four (x, y even) and of Mesh4's (0, 0).
    let tile0 = &t.tiles()[0];
    assert!(close(
        footprint_ratio(tile0, |x, y| x % 2 == 0 && y % 2 == 0),
        0.5
    ));
    assert!(close(
        footprint_ratio(tile0, |x, y| x % 4 == 0 && y % 4 == 0),
        0.2
    ));
    assert!(close(footprint_ratio(tile0, |_, _| true), 1.0));
    assert!(close(footprint_ratio(tile0, |_, _| false), 0.0));
    // Tile 1 0: (0, 0) touches 1 of 8 blocks; (0,2),(2,2) add 3412 and 3413.
    let mesh2 = mean_footprint_ratio(&t, |x, y| x % 2 == 0 && y % 2 == 0);
    assert!(close(mesh2, (16.0 * 0.5 + 10.0 * 3.0 / 8.0) / 26.0));
}

#[test]
fn synthetic_small_trace_contents() {
    let t = Trace::read(SYNTH_SMALL).unwrap();
    let h = t.header();
    assert!(h.workload.starts_with("synthetic:"), "{}", h.workload);
    assert!(h.notes.iter().any(|n| n.contains("generator-params")));
    assert_eq!((h.frame_w, h.frame_h, h.tile), (128, 128, 64));
    let tiles = t.tiles();
    // Z-order over the 2x2 tile grid.
    let order: Vec<(u32, u32)> = tiles.iter().map(|t| (t.tx(), t.ty())).collect();
    assert_eq!(order, vec![(0, 0), (1, 0), (0, 1), (1, 1)]);
    let counts: Vec<usize> = tiles.iter().map(Tile::quad_count).collect();
    assert_eq!(counts, SYNTH_SMALL_QUADS);
    let q = tiles[0].quad(0).unwrap();
    assert_eq!((q.x(), q.y()), SYNTH_SMALL_Q0_POS);
    assert_eq!(q.instrs().collect::<Vec<_>>(), synth_small_q0_instrs());
    // The file is version 1; the writer reproduces it byte for byte but
    // for line 1 (it writes version 4, a superset).
    let text = std::fs::read_to_string(SYNTH_SMALL).unwrap();
    assert!(text.starts_with("wasp-trace 1\n"));
    assert_eq!(
        t.to_text(),
        text.replacen("wasp-trace 1\n", "wasp-trace 4\n", 1)
    );
}

// Pinned from tests/traces/synthetic-small.trace (tile 0 0 misses quads
// 0..2 of row 0 behind a silhouette; tile 1 1 is fully covered).
const SYNTH_SMALL_QUADS: [usize; 4] = [1006, 925, 527, 1024];
const SYNTH_SMALL_Q0_POS: (u32, u32) = (3, 0);
fn synth_small_q0_instrs() -> Vec<Instr<'static>> {
    vec![
        Instr::Alu(3),
        Instr::Tex(&[0x1245f5, 0x1245f4]),
        Instr::Alu(3),
    ]
}

#[test]
fn tiny_trace_round_trips_through_the_writer() {
    let t = Trace::read(TINY).unwrap();
    let text = t.to_text();
    // Read as version 1, written as version 4, the same records.
    assert!(text.starts_with("wasp-trace 4\n# tiny.trace"));
    assert!(text.contains("\nq 1 1 a2 t1a00,1a01,1a10,1a11 a4 t2000 a1\n"));
    assert_eq!(Trace::parse(&text, "rt").unwrap(), t);
}

#[test]
fn the_example_of_format_md_parses_with_a_repeated_position() {
    let md = include_str!("../../tests/traces/FORMAT.md");
    let start = md.find("```text\n").unwrap() + "```text\n".len();
    let text = &md[start..start + md[start..].find("```").unwrap()];
    let t = Trace::parse(text, "FORMAT.md").unwrap();
    let tile = &t.tiles()[0];
    assert_eq!((tile.quad_count(), tile.position_count()), (3, 2));
    assert_eq!(tile.quads_at(0, 0).count(), 2);
    // 12 rejected quads before the third warp, 3 after the last one, and a
    // tile without warps.
    let before: Vec<u32> = (0..3).map(|i| tile.rejected_before(i)).collect();
    assert_eq!(before, vec![0, 0, 12]);
    assert_eq!((tile.rejected_after_last(), tile.raster_count()), (3, 18));
    let hidden = &t.tiles()[2];
    assert_eq!((hidden.tx(), hidden.ty(), hidden.quad_count()), (0, 1, 0));
    assert_eq!(hidden.rejected_after_last(), 40);
    assert_eq!((t.quad_count(), t.rejected_count()), (4, 55));
    assert_eq!(t.to_text(), text, "the example is in the writer's form");
    // The module documentation repeats the same example.
    let doc = include_str!("lib.rs");
    for line in text.lines() {
        assert!(doc.contains(&format!("//! {line}\n")), "{line}");
    }
}

/// The words of `text` from the line that starts with `from` to the line
/// that starts with `to`, without the `//!` of documentation comments.
fn words_between(text: &str, from: &str, to: &str) -> Vec<String> {
    let lines: Vec<&str> = text
        .lines()
        .map(|l| l.strip_prefix("//!").unwrap_or(l).trim())
        .collect();
    let a = lines.iter().position(|l| l.starts_with(from)).unwrap();
    let b = a + lines[a..].iter().position(|l| l.starts_with(to)).unwrap();
    lines[a..b]
        .iter()
        .flat_map(|l| l.split_whitespace())
        .map(str::to_string)
        .collect()
}

#[test]
fn format_md_and_the_module_documentation_state_the_same_rules() {
    let md = include_str!("../../tests/traces/FORMAT.md");
    let doc = include_str!("lib.rs");
    let rules = |text: &str, end: &str| words_between(text, "A trace is UTF-8 text", end);
    let (a, b) = (rules(md, "## Statistics"), rules(doc, "# In memory"));
    assert!(a.len() > 500, "{}", a.len());
    assert_eq!(a, b, "tests/traces/FORMAT.md and trace/src/lib.rs differ");
    let example = |text: &str| words_between(text, "The first warp, at quad", "## Rules");
    assert_eq!(example(md), example(doc));
    for phrase in [
        "An older trace records no rejected quad, so its rasterizer cost counts surviving quads only.",
        "`z N`",
    ] {
        let words: Vec<&str> = phrase.split_whitespace().collect();
        assert!(a.windows(words.len()).any(|w| w == words.as_slice()), "{phrase}");
    }
}

#[test]
fn overdraw_trace_keeps_repeated_positions_in_file_order() {
    let t = Trace::read(OVERDRAW).unwrap();
    assert_eq!(t.header().workload, "hand:overdraw");
    let tiles = t.tiles();
    assert_eq!(tiles.len(), 2);
    let t0 = &tiles[0];
    let positions: Vec<(u32, u32)> = t0.quads().map(|q| (q.x(), q.y())).collect();
    // Triangle A covers row 0 and (0, 1); triangle B, drawn next, covers
    // (1, 0), (0, 1), (1, 1); sprite C, blended last, (1, 1) again.
    assert_eq!(
        positions,
        vec![(0, 0), (1, 0), (0, 1), (1, 0), (0, 1), (1, 1), (1, 1)]
    );
    assert_eq!((t0.quad_count(), t0.position_count()), (7, 4));
    let at: Vec<usize> = t0.quads_at(1, 1).map(|q| q.index()).collect();
    assert_eq!(at, vec![5, 6]);
    assert_eq!(t0.quad_at(1, 0).unwrap().index(), 1, "the first one");
    assert_eq!(t0.quad(6).unwrap().block_accesses(), &[0x5000]);
    assert!(t0.quad_at(2, 2).is_none());
    let s = t.stats();
    assert_eq!((s.warps, s.positions), (9, 6));
    assert!(close(s.warps_per_position, 1.5));
    assert!(close(s.coverage, 6.0 / 32.0));
    let s0 = t0.stats();
    // Warp blocks: A's 3 warps 1+1+1... counted per record.
    assert_eq!((s0.warps, s0.positions, s0.unique_blocks), (7, 4, 6));
    assert_eq!(s0.warp_blocks, 1 + 2 + 1 + 1 + 2 + 2 + 1);
    // A priority subset selects positions, so every fragment there.
    assert!(close(
        footprint_ratio(t0, |x, y| (x, y) == (1, 1)),
        3.0 / 6.0
    ));
    // Written back byte for byte but for line 1 (it is version 2 and
    // canonical; the writer writes version 3).
    let file = std::fs::read_to_string(OVERDRAW).unwrap();
    assert_eq!(
        t.to_text(),
        file.replacen("wasp-trace 2\n", "wasp-trace 4\n", 1)
    );
}

#[test]
fn read_reports_missing_file() {
    let e = Trace::read("/nonexistent/dir/x.trace").unwrap_err();
    assert!(matches!(e, TraceError::Io { .. }));
    assert!(e
        .to_string()
        .starts_with("/nonexistent/dir/x.trace: cannot read: "));
}

// ---------------------------------------------------------------- errors

const HEAD: &str = "wasp-trace 2\nworkload w\nframe 100 70 tile 64\n";
const HEAD1: &str = "wasp-trace 1\nworkload w\nframe 100 70 tile 64\n";

/// Parses `text` and returns (line, problem, message) of the error.
fn fail(text: &str) -> (usize, Problem, String) {
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

fn body(s: &str) -> String {
    format!("{HEAD}{s}")
}

fn body1(s: &str) -> String {
    format!("{HEAD1}{s}")
}

#[test]
fn minimal_traces_parse() {
    let t = Trace::parse(HEAD, "x").unwrap();
    assert!(t.tiles().is_empty());
    let t = Trace::parse(&body("tile 1 1\nq 0 0 a1\nend"), "x").unwrap(); // no final LF
    assert_eq!(t.tiles()[0].quad_count(), 1);
    let crlf = body("tile 0 0\nq 0 0 t1\nend\n").replace('\n', "\r\n");
    let t = Trace::parse(&crlf, "x").unwrap();
    assert_eq!(t.tiles()[0].quad(0).unwrap().block_accesses(), &[1]);
    // Blanks, tabs, blank lines, comments anywhere, upper-case hex, zeros.
    let t = Trace::parse(
        &body("\n  tile\t0  0 \n# c\n\tq 0 0  a01 tFF,00a\n   # c2\nend\n\n"),
        "x",
    )
    .unwrap();
    let q = t.tiles()[0].quad(0).unwrap();
    assert_eq!(
        q.instrs().collect::<Vec<_>>(),
        vec![Instr::Alu(1), Instr::Tex(&[0xff, 0xa])]
    );
    assert!(t.header().notes.is_empty());
}

#[test]
fn version_2_allows_repeats_in_any_order_and_version_1_does_not() {
    let records = "tile 0 0\nq 1 1 a1\nq 0 0 a1\nq 1 1 t5\nq 1 1 a3\nend\n";
    let t = Trace::parse(&body(records), "x").unwrap();
    let tile = &t.tiles()[0];
    let got: Vec<(u32, u32, u64)> = tile
        .quads()
        .map(|q| (q.x(), q.y(), q.instr_count()))
        .collect();
    assert_eq!(got, vec![(1, 1, 1), (0, 0, 1), (1, 1, 1), (1, 1, 3)]);
    assert_eq!(tile.position_count(), 2);
    // Three warps at (1, 1), never merged: the `a1` and `a3` stay apart.
    assert_eq!(tile.quads_at(1, 1).count(), 3);
    assert_eq!(
        t.to_text(),
        body(records).replacen("wasp-trace 2\n", "wasp-trace 4\n", 1)
    );
    // The same records under version 1 break its order rule.
    let (line, p, _) = fail(&body1(records));
    assert_eq!(line, 6);
    assert!(
        matches!(p, Problem::QuadOutOfOrder { x: 0, y: 0, .. }),
        "{p:?}"
    );
    // Version 1 still reads what it always read, into the same trace.
    let v1 = "tile 0 0\nq 0 0 a1\nq 1 0 t5\nq 0 1 a2\nend\n";
    let a = Trace::parse(&body1(v1), "x").unwrap();
    let b = Trace::parse(&body(v1), "x").unwrap();
    assert_eq!(a, b);
    assert_eq!(
        a.to_text(),
        body(v1).replacen("wasp-trace 2\n", "wasp-trace 4\n", 1)
    );
    // Version 2 keeps every other rule.
    let (_, p, _) = fail(&body("tile 0 0\nq 1 1 a1\nq 1 1\nend\n"));
    assert!(matches!(p, Problem::EmptyQuad { x: 1, y: 1 }), "{p:?}");
    let (_, p, _) = fail(&body("tile 0 0\nq 1 1 a1\nq 1 32 a1\nend\n"));
    assert!(matches!(p, Problem::QuadOutsideTile { .. }), "{p:?}");
}

#[test]
fn every_malformation_is_reported_with_its_line() {
    use Problem::*;
    type Case = (String, usize, fn(&Problem) -> bool);
    let cases: Vec<Case> = vec![
        ("".into(), 1, |p| matches!(p, EmptyInput)),
        ("wasp-trace 1".into(), 1, |p| {
            matches!(
                p,
                MissingHeader {
                    missing: "workload NAME",
                    ..
                }
            )
        }),
        (
            "wasp-trace 5\n".into(),
            1,
            |p| matches!(p, UnsupportedVersion(v) if v == "5"),
        ),
        (
            "wasp-trace 0\n".into(),
            1,
            |p| matches!(p, UnsupportedVersion(v) if v == "0"),
        ),
        (
            "wasp-trace 02\n".into(),
            1,
            |p| matches!(p, UnsupportedVersion(v) if v == "02"),
        ),
        ("wasp-trace  2\n".into(), 1, |p| matches!(p, BadMagic(_))),
        ("wasp-trace\n".into(), 1, |p| matches!(p, BadMagic(_))),
        ("wasp-trace 1 x\n".into(), 1, |p| matches!(p, BadMagic(_))),
        (" wasp-trace 1\n".into(), 1, |p| matches!(p, BadMagic(_))),
        ("# c\nwasp-trace 1\n".into(), 1, |p| {
            matches!(p, BadMagic(_))
        }),
        ("wasp-trace 1\nframe 1 1 tile 2\n".into(), 2, |p| {
            matches!(
                p,
                MissingHeader {
                    missing: "workload NAME",
                    ..
                }
            )
        }),
        ("wasp-trace 1\nworkload w\ntile 0 0\n".into(), 3, |p| {
            matches!(
                p,
                MissingHeader {
                    missing: "frame W H tile T",
                    ..
                }
            )
        }),
        ("wasp-trace 1\nworkload w\n".into(), 2, |p| {
            matches!(p, MissingHeader { .. })
        }),
        ("wasp-trace 1\nworkload \n".into(), 2, |p| {
            matches!(p, EmptyWorkload)
        }),
        ("wasp-trace 1\nworkload a\nworkload b\n".into(), 3, |p| {
            matches!(p, MisplacedHeader("workload"))
        }),
        (body("workload b\n"), 4, |p| {
            matches!(p, MisplacedHeader("workload"))
        }),
        (body("frame 1 1 tile 2\n"), 4, |p| {
            matches!(p, MisplacedHeader("frame"))
        }),
        (
            "wasp-trace 1\nworkload w\nframe 10 10 tile\n".into(),
            3,
            |p| {
                matches!(
                    p,
                    WrongFieldCount {
                        directive: "frame",
                        ..
                    }
                )
            },
        ),
        (
            "wasp-trace 1\nworkload w\nframe 10 10 tyle 2\n".into(),
            3,
            |p| {
                matches!(
                    p,
                    WrongFieldCount {
                        directive: "frame",
                        ..
                    }
                )
            },
        ),
        (
            "wasp-trace 1\nworkload w\nframe 0 10 tile 2\n".into(),
            3,
            |p| matches!(p, BadFrame { dim: "width", .. }),
        ),
        (
            "wasp-trace 1\nworkload w\nframe 10 65537 tile 2\n".into(),
            3,
            |p| {
                matches!(
                    p,
                    NumberTooLarge {
                        what: "frame height",
                        ..
                    }
                )
            },
        ),
        (
            "wasp-trace 1\nworkload w\nframe 10 10 tile 7\n".into(),
            3,
            |p| matches!(p, BadTileSize(7)),
        ),
        (
            "wasp-trace 1\nworkload w\nframe 10 10 tile 0\n".into(),
            3,
            |p| matches!(p, BadTileSize(0)),
        ),
        (
            "wasp-trace 1\nworkload w\nframe -1 10 tile 2\n".into(),
            3,
            |p| {
                matches!(
                    p,
                    BadNumber {
                        what: "frame width",
                        ..
                    }
                )
            },
        ),
        ("wasp-trace 1\nbogus\n".into(), 2, |p| {
            matches!(p, UnknownDirective { .. })
        }),
        (body("tile 0 0\nx 1 2\n"), 5, |p| {
            matches!(
                p,
                UnknownDirective {
                    expected: "`q X Y ...`, `z N` or `end`",
                    ..
                }
            )
        }),
        (body("tile 0 0\nq 0 0 a1\nend\nq 0 0 a1\n"), 7, |p| {
            matches!(p, QuadWithoutTile)
        }),
        (body("q 0 0 a1\n"), 4, |p| matches!(p, QuadWithoutTile)),
        (body("end\n"), 4, |p| matches!(p, EndWithoutTile)),
        (body("tile 0 0\nq 0 0 a1\nend x\n"), 6, |p| {
            matches!(
                p,
                WrongFieldCount {
                    directive: "end",
                    ..
                }
            )
        }),
        (body("tile 0 0\nq 0 0 a1\n"), 5, |p| {
            matches!(p, TileNotClosed { tx: 0, ty: 0 })
        }),
        (body("tile 0 0\nq 0 0 a1\ntile 1 0\n"), 6, |p| {
            matches!(p, TileNotClosed { tx: 0, ty: 0 })
        }),
        (body("tile 0 0\nend\n"), 5, |p| {
            matches!(p, EmptyTile { .. })
        }),
        (body("tile 2 0\n"), 4, |p| {
            matches!(
                p,
                TileOutsideFrame {
                    tiles_x: 2,
                    tiles_y: 2,
                    ..
                }
            )
        }),
        (body("tile 0 2\n"), 4, |p| {
            matches!(p, TileOutsideFrame { .. })
        }),
        (body("tile 0\n"), 4, |p| {
            matches!(
                p,
                WrongFieldCount {
                    directive: "tile",
                    ..
                }
            )
        }),
        (body("tile 0 99999999999\n"), 4, |p| {
            matches!(p, NumberTooLarge { what: "tile y", .. })
        }),
        (body("tile 0 0\nq 0 0 a1\nend\ntile 0 0\n"), 7, |p| {
            matches!(p, DuplicateTile { tx: 0, ty: 0 })
        }),
        (body("tile 0 0\nq 32 0 a1\n"), 5, |p| {
            matches!(
                p,
                QuadOutsideTile {
                    x: 32,
                    side: 32,
                    ..
                }
            )
        }),
        (body("tile 0 0\nq 0 32 a1\n"), 5, |p| {
            matches!(p, QuadOutsideTile { .. })
        }),
        // Frame 100x70: tile 1 0 holds pixel columns 64..99, quads x 0..17.
        (body("tile 1 0\nq 18 0 a1\n"), 5, |p| {
            matches!(p, QuadOutsideFrame { x: 18, px: 100, .. })
        }),
        (body("tile 0 1\nq 0 3 a1\n"), 5, |p| {
            matches!(p, QuadOutsideFrame { py: 70, .. })
        }),
        // Version 1 only: scanline order, each position once.
        (body1("tile 0 0\nq 1 0 a1\nq 1 0 a1\n"), 6, |p| {
            matches!(p, DuplicateQuad { x: 1, y: 0 })
        }),
        (body1("tile 0 0\nq 1 1 a1\nq 2 0 a1\n"), 6, |p| {
            matches!(
                p,
                QuadOutOfOrder {
                    x: 2,
                    y: 0,
                    prev_x: 1,
                    prev_y: 1
                }
            )
        }),
        (body("tile 0 0\nq 0 0\n"), 5, |p| {
            matches!(p, EmptyQuad { x: 0, y: 0 })
        }),
        (body("tile 0 0\nq 0\n"), 5, |p| {
            matches!(p, WrongFieldCount { directive: "q", .. })
        }),
        (body("tile 0 0\nq 0 x a1\n"), 5, |p| {
            matches!(p, BadNumber { what: "quad y", .. })
        }),
        (body("tile 0 0\nq 0 0 a0\n"), 5, |p| matches!(p, ZeroAlu)),
        (body("tile 0 0\nq 0 0 a\n"), 5, |p| matches!(p, BadInstr(_))),
        (body("tile 0 0\nq 0 0 a-1\n"), 5, |p| {
            matches!(p, BadInstr(_))
        }),
        (body("tile 0 0\nq 0 0 a2147483648\n"), 5, |p| {
            matches!(
                p,
                NumberTooLarge {
                    what: "ALU run",
                    ..
                }
            )
        }),
        (body("tile 0 0\nq 0 0 a3 a2\n"), 5, |p| {
            matches!(
                p,
                AdjacentAlu {
                    first: 3,
                    second: 2
                }
            )
        }),
        (body("tile 0 0\nq 0 0 x5\n"), 5, |p| {
            matches!(p, BadInstr(_))
        }),
        (body("tile 0 0\nq 0 0 t\n"), 5, |p| matches!(p, TexNoBlock)),
        (body("tile 0 0\nq 0 0 t1,\n"), 5, |p| {
            matches!(p, EmptyBlockEntry(_))
        }),
        (body("tile 0 0\nq 0 0 t,1\n"), 5, |p| {
            matches!(p, EmptyBlockEntry(_))
        }),
        (body("tile 0 0\nq 0 0 t1,,2\n"), 5, |p| {
            matches!(p, EmptyBlockEntry(_))
        }),
        (body("tile 0 0\nq 0 0 t1g\n"), 5, |p| {
            matches!(p, BadHex { .. })
        }),
        (body("tile 0 0\nq 0 0 t0x1\n"), 5, |p| {
            matches!(p, BadHex { .. })
        }),
        (body("tile 0 0\nq 0 0 t+1\n"), 5, |p| {
            matches!(p, BadHex { .. })
        }),
        (body("tile 0 0\nq 0 0 t10000000000000000\n"), 5, |p| {
            matches!(p, BadHex { .. })
        }),
        (body("tile 0 0\nq 0 0 t1a,2,1A\n"), 5, |p| {
            matches!(p, DuplicateBlock(0x1a))
        }),
        (
            body(&format!(
                "tile 0 0\nq 0 0 t{}\n",
                (0..1025)
                    .map(|i| format!("{i:x}"))
                    .collect::<Vec<_>>()
                    .join(",")
            )),
            5,
            |p| matches!(p, TooManyBlocks(1025)),
        ),
        (body("tile 0 0\nq 0 0 a1 # c\n"), 5, |p| {
            matches!(p, BadInstr(_))
        }),
        (body("tile 0 0\nq 0 0 a1\x0b\n"), 5, |p| {
            matches!(p, ControlCharacter)
        }),
        (body("# bell \x07\n"), 4, |p| matches!(p, ControlCharacter)),
        (body("tile 0 0\nq 0 0 a1\rx\n"), 5, |p| {
            matches!(p, ControlCharacter)
        }),
    ];
    for (text, line, check) in cases {
        let (l, p, msg) = fail(&text);
        assert!(check(&p), "{text:?}: got {p:?} ({msg})");
        assert_eq!(l, line, "{text:?}: {msg}");
    }
}

#[test]
fn error_messages_read_well() {
    let (_, _, msg) = fail(&body("tile 0 0\nq 40 3 a1\n"));
    assert_eq!(
        msg,
        "x.trace:5: quad 40 3 outside the tile (expected x and y from 0 to 31)"
    );
    let (_, _, msg) = fail("wasp-trace 5\n");
    assert_eq!(
        msg,
        "x.trace:1: unsupported format version `5` (expected 4, 3, 2 or 1)"
    );
    let (_, _, msg) = fail(&body1("tile 0 0\nq 1 0 a1\nq 1 0 a2\n"));
    assert_eq!(
        msg,
        "x.trace:6: quad 1 0 appears twice in the tile (expected each quad at most once in \
         format 1; formats 2 to 4 allow repeats)"
    );
    let (_, _, msg) = fail(&body1("tile 0 0\nq 1 1 a1\nq 2 0 a1\n"));
    assert_eq!(
        msg,
        "x.trace:6: quad 2 0 after quad 1 1 (expected scanline order in format 1: y, then x \
         increasing)"
    );
    let (_, _, msg) = fail(&body("tile 0 0\nq 0 0 t1,1\n"));
    assert_eq!(
        msg,
        "x.trace:5: block 1 listed twice in one texture instruction (expected distinct blocks)"
    );
    let (_, _, msg) = fail(&body(&format!("tile 0 0\nq 0 0 a{}\n", "9".repeat(200))));
    assert!(msg.len() < 200, "{msg}");
}

#[test]
fn invalid_utf8_reports_its_line() {
    let mut bytes = body("tile 0 0\n").into_bytes();
    bytes.extend_from_slice(b"q 0 0 t\xff\n");
    let e = Trace::parse_bytes(&bytes, "b.trace").unwrap_err();
    assert_eq!(e.line(), Some(5));
    assert_eq!(e.problem(), Some(&Problem::InvalidUtf8));
}

// ---------------------------------------------------------------- builder

#[test]
fn builder_merges_alu_runs_and_rejects_without_changing_state() {
    let mut b = Trace::builder(TraceHeader::new("w", 64, 64, 64)).unwrap();
    assert_eq!(b.alu(1), Err(Problem::InstrWithoutQuad));
    assert_eq!(b.begin_quad(0, 0), Err(Problem::QuadWithoutTile));
    b.begin_tile(0, 0).unwrap();
    assert_eq!(b.end_tile(), Err(Problem::EmptyTile { tx: 0, ty: 0 }));
    b.begin_quad(0, 1).unwrap();
    assert_eq!(b.begin_quad(0, 2), Err(Problem::EmptyQuad { x: 0, y: 1 }));
    b.alu(3).unwrap();
    b.alu(2).unwrap();
    assert_eq!(b.tex(&[5, 5]), Err(Problem::DuplicateBlock(5)));
    assert_eq!(b.tex(&[]), Err(Problem::TexNoBlock));
    b.tex(&[5, 6]).unwrap();
    b.alu(1).unwrap();
    assert_eq!(
        b.alu(MAX_ALU_RUN),
        Err(Problem::AluRunTooLong(1 + u64::from(MAX_ALU_RUN)))
    );
    b.quad(1, 1, &[Instr::Tex(&[7]), Instr::Alu(4)]).unwrap();
    assert_eq!(
        b.finish().unwrap_err(),
        Problem::TileNotClosed { tx: 0, ty: 0 }
    );

    let mut b = Trace::builder(TraceHeader::new("w", 64, 64, 64)).unwrap();
    b.begin_tile(0, 0).unwrap();
    b.quad(
        0,
        1,
        &[
            Instr::Alu(3),
            Instr::Alu(2),
            Instr::Tex(&[5, 6]),
            Instr::Alu(1),
        ],
    )
    .unwrap();
    b.quad(1, 1, &[Instr::Tex(&[7]), Instr::Alu(4)]).unwrap();
    b.end_tile().unwrap();
    assert_eq!(
        b.begin_tile(0, 0),
        Err(Problem::DuplicateTile { tx: 0, ty: 0 })
    );
    let t = b.finish().unwrap();
    let q = t.tiles()[0].quad(0).unwrap();
    assert_eq!(
        q.instrs().collect::<Vec<_>>(),
        vec![Instr::Alu(5), Instr::Tex(&[5, 6]), Instr::Alu(1)]
    );
    assert_eq!(t.tiles()[0].quad(1).unwrap().block_accesses(), &[7]);
    assert_eq!(t.instr_count(), 7 + 5);
    assert_eq!(t.tex_count(), 2);
}

#[test]
fn builder_appends_tiles_built_elsewhere() {
    let part = |tx: u32, quads: &[(u32, u32)]| {
        let mut b = Trace::builder(TraceHeader::new("part", 128, 64, 64)).unwrap();
        b.begin_tile(tx, 0).unwrap();
        for &(x, y) in quads {
            b.quad(x, y, &[Instr::Alu(x + 1)]).unwrap();
        }
        b.end_tile().unwrap();
        b.finish().unwrap()
    };
    let mut b = Trace::builder(TraceHeader::new("w", 128, 64, 64)).unwrap();
    b.append(part(1, &[(3, 0), (1, 0), (3, 0)])).unwrap();
    b.append(part(0, &[(0, 0)])).unwrap();
    assert_eq!(
        b.append(part(1, &[(0, 0)])),
        Err(Problem::DuplicateTile { tx: 1, ty: 0 })
    );
    let other = Trace::builder(TraceHeader::new("w", 64, 64, 64))
        .unwrap()
        .finish()
        .unwrap();
    assert!(matches!(
        b.append(other),
        Err(Problem::FrameMismatch { .. })
    ));
    b.begin_tile(0, 0).unwrap_err(); // already appended
    let t = b.finish().unwrap();
    assert_eq!(t.header().workload, "w");
    let order: Vec<(u32, usize)> = t.tiles().iter().map(|t| (t.tx(), t.quad_count())).collect();
    assert_eq!(order, vec![(1, 3), (0, 1)]);
    // A version-1 builder checks the appended tiles' order.
    let mut b = Trace::builder(TraceHeader::new("w", 128, 64, 64)).unwrap();
    b.require_scanline_order();
    assert_eq!(
        b.append(part(1, &[(3, 0), (1, 0)])),
        Err(Problem::QuadOutOfOrder {
            x: 1,
            y: 0,
            prev_x: 3,
            prev_y: 0
        })
    );
    b.append(part(1, &[(1, 0), (3, 0)])).unwrap();
}

#[test]
fn builder_allows_repeats_unless_scanline_order_is_required() {
    let mut b = Trace::builder(TraceHeader::new("w", 64, 64, 64)).unwrap();
    b.begin_tile(0, 0).unwrap();
    b.quad(0, 1, &[Instr::Alu(1)]).unwrap();
    b.quad(0, 1, &[Instr::Alu(2)]).unwrap();
    b.quad(0, 0, &[Instr::Alu(3)]).unwrap();
    b.end_tile().unwrap();
    let t = b.finish().unwrap();
    let counts: Vec<u64> = t.tiles()[0].quads().map(|q| q.instr_count()).collect();
    assert_eq!(counts, vec![1, 2, 3], "never merged, never reordered");

    let mut b = Trace::builder(TraceHeader::new("w", 64, 64, 64)).unwrap();
    b.require_scanline_order();
    b.begin_tile(0, 0).unwrap();
    b.quad(0, 1, &[Instr::Alu(1)]).unwrap();
    assert_eq!(
        b.begin_quad(0, 1),
        Err(Problem::DuplicateQuad { x: 0, y: 1 })
    );
    assert_eq!(
        b.begin_quad(0, 0),
        Err(Problem::QuadOutOfOrder {
            x: 0,
            y: 0,
            prev_x: 0,
            prev_y: 1
        })
    );
    b.quad(1, 1, &[Instr::Alu(1)]).unwrap();
    b.end_tile().unwrap();
    assert_eq!(b.finish().unwrap().quad_count(), 2);
}

#[test]
fn builder_rejects_bad_headers() {
    let bad = |h: TraceHeader| Trace::builder(h).unwrap_err();
    assert_eq!(bad(TraceHeader::new("", 1, 1, 2)), Problem::EmptyWorkload);
    assert!(matches!(
        bad(TraceHeader::new(" w", 1, 1, 2)),
        Problem::BadText { .. }
    ));
    assert!(matches!(
        bad(TraceHeader::new("a\nb", 1, 1, 2)),
        Problem::BadText { .. }
    ));
    assert!(matches!(
        bad(TraceHeader::new("w", 1, 0, 2)),
        Problem::BadFrame { .. }
    ));
    assert_eq!(
        bad(TraceHeader::new("w", 1, 1, 514)),
        Problem::BadTileSize(514)
    );
    let mut h = TraceHeader::new("w", 1, 1, 2);
    h.notes.push("x\ry".into());
    assert!(matches!(
        bad(h),
        Problem::BadText {
            field: TextField::Note,
            ..
        }
    ));
}

// ---------------------------------------------------------------- proptests

/// An instruction of a generated quad: (ALU run, no blocks) or (0 for
/// bilinear, 1 for trilinear, blocks).
type SpecInstr = (u32, Vec<u64>);

/// A strategy for arbitrary valid traces, built through the builder:
/// version-4 traces (positions in any order, repeats, rejected quads
/// between and after the quads, tiles of rejected quads only, trilinear
/// texture instructions) or, with `scanline`, traces that are also valid
/// version 1 (no rejected quad, every texture instruction bilinear).
fn arb_trace_v(scanline: bool) -> impl Strategy<Value = Trace> {
    let header = (
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
        });
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
    let quad = proptest::collection::vec(instr, 1..6);
    // Rejected quads before each quad and after the last (mostly none; a
    // count may come in two calls, which the builder adds up).
    let rejected = prop_oneof![
        4 => Just(0u32),
        3 => 1u32..40,
        1 => 1u32..=MAX_REJECTED_RUN,
    ];
    let rejections = proptest::collection::vec((rejected, any::<bool>()), 9);
    header
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
        .prop_map(move |(hd, tiles)| {
            let (nx, ny, side) = (hd.tiles_x(), hd.tiles_y(), hd.quads_per_side());
            let mut b = Trace::builder(hd).unwrap();
            let reject = |b: &mut TraceBuilder, (n, split): (u32, bool)| {
                if n == 0 || scanline {
                    return;
                }
                if split && n > 1 {
                    b.rejected(n / 2).unwrap();
                    b.rejected(n - n / 2).unwrap();
                } else {
                    b.rejected(n).unwrap();
                }
            };
            for (tx, ty, quads, rej, hidden) in tiles {
                let (tx, ty) = (tx % nx, ty % ny);
                if b.begin_tile(tx, ty).is_err() {
                    continue; // duplicate tile
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
                    reject(&mut b, (rej[8].0.max(1), rej[8].1));
                }
                for (i, (x, y, instrs)) in placed.into_iter().enumerate() {
                    reject(&mut b, rej[i]);
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
                    reject(&mut b, rej[8]);
                }
                b.end_tile().unwrap();
            }
            b.finish().unwrap()
        })
}

fn arb_trace() -> impl Strategy<Value = Trace> {
    prop_oneof![arb_trace_v(false), arb_trace_v(true)]
}

/// Mutations of a valid trace text: some keep it valid, most break it.
fn mutate(text: &str, ops: &[(u8, usize, usize, String)]) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    for (kind, a, b, s) in ops {
        if lines.is_empty() {
            break;
        }
        let i = a % lines.len();
        let j = b % lines.len();
        match kind % 8 {
            0 => {
                lines.remove(i);
            }
            1 => {
                let l = lines[i].clone();
                lines.insert(j, l);
            }
            2 => lines.swap(i, j),
            3 => lines.insert(i, s.clone()),
            4 => {
                let l = &mut lines[i];
                let mut cut = (*b).min(l.len());
                while !l.is_char_boundary(cut) {
                    cut -= 1;
                }
                l.insert_str(cut, s);
            }
            5 => {
                let l = &mut lines[i];
                let mut cut = (*b).min(l.len());
                while !l.is_char_boundary(cut) {
                    cut -= 1;
                }
                l.truncate(cut);
            }
            6 => {
                // Change one digit.
                let l = &mut lines[i];
                if let Some(p) = l
                    .char_indices()
                    .filter(|(_, c)| c.is_ascii_digit())
                    .map(|(p, _)| p)
                    .nth(*b % 4)
                {
                    l.replace_range(p..p + 1, &((b % 10).to_string()));
                }
            }
            _ => lines[i] = lines[i].replace(' ', s),
        }
    }
    lines.join("\n")
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

    #[test]
    fn round_trip_is_exact(t in arb_trace()) {
        let text = t.to_text();
        let back = Trace::parse(&text, "rt").unwrap();
        prop_assert_eq!(&back, &t);
        prop_assert_eq!(back.to_text(), text);
    }

    #[test]
    fn scanline_traces_read_the_same_as_version_1(t in arb_trace_v(true)) {
        let text = t.to_text().replacen("wasp-trace 4\n", "wasp-trace 1\n", 1);
        prop_assert_eq!(Trace::parse(&text, "v1").unwrap(), t);
    }

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..400)) {
        let _ = Trace::parse_bytes(&bytes, "r");
        let mut prefixed = HEAD.as_bytes().to_vec();
        prefixed.extend_from_slice(&bytes);
        let _ = Trace::parse_bytes(&prefixed, "r");
        let mut prefixed = HEAD3.as_bytes().to_vec();
        prefixed.extend_from_slice(&bytes);
        let _ = Trace::parse_bytes(&prefixed, "r");
    }

    #[test]
    fn random_token_soup_never_panics(
        toks in proptest::collection::vec(prop_oneof![
            Just("tile".to_string()), Just("q".to_string()), Just("end".to_string()),
            Just("workload".to_string()), Just("frame".to_string()), Just("\n".to_string()),
            Just("#".to_string()), Just("a1".to_string()), Just("a0".to_string()),
            Just("t1,2".to_string()), Just("tffffffffffffffff".to_string()),
            Just("4294967296".to_string()), Just("t".to_string()), Just(",".to_string()),
            Just("z".to_string()), Just("\nz".to_string()), Just("2147483648".to_string()),
            (0u32..40).prop_map(|n| n.to_string()), "[ -~]{0,4}",
        ], 0..80),
        v3 in any::<bool>(),
    ) {
        let head = if v3 { HEAD3 } else { HEAD };
        let text = format!("{head}{}", toks.join(" "));
        if let Ok(t) = Trace::parse(&text, "soup") {
            prop_assert_eq!(Trace::parse(&t.to_text(), "soup2").unwrap(), t);
        }
    }

    #[test]
    fn mutated_traces_never_panic(
        t in arb_trace(),
        ops in proptest::collection::vec((any::<u8>(), any::<usize>(), 0usize..40, "[ -~\t\r]{0,6}"), 1..6),
    ) {
        let text = mutate(&t.to_text(), &ops);
        match Trace::parse(&text, "m") {
            Ok(t2) => prop_assert_eq!(Trace::parse(&t2.to_text(), "m2").unwrap(), t2),
            Err(e) => {
                let msg = e.to_string();
                prop_assert!(msg.starts_with("m:"), "{}", msg);
                prop_assert!(msg.contains("(expected "), "{}", msg);
            }
        }
    }

    #[test]
    fn reading_in_pieces_is_reading_on_one_thread(
        t in arb_trace(),
        pieces in 2usize..6,
        ops in proptest::collection::vec((any::<u8>(), any::<usize>(), 0usize..40, "[ -~\t\r]{0,6}"), 0..4),
    ) {
        let text = if ops.is_empty() { t.to_text() } else { mutate(&t.to_text(), &ops) };
        let one = Trace::parse_with(&text, "m", 1, usize::MAX);
        prop_assert_eq!(Trace::parse_with(&text, "m", pieces, 0), one);
    }

    #[test]
    fn one_tile_traces_appended_give_the_trace_back(t in arb_trace()) {
        // What the front end does: each tile built alone, then appended.
        let mut b = Trace::builder(t.header().clone()).unwrap();
        for tile in t.tiles() {
            let part = Trace {
                header: t.header().clone(),
                tiles: vec![tile.clone()],
                stats: Memo::default(),
            };
            let part = Trace::parse(&part.to_text(), "part").unwrap();
            b.append(part).unwrap();
        }
        let back = b.finish().unwrap();
        prop_assert_eq!(back.rejected_count(), t.rejected_count());
        prop_assert_eq!(&back, &t);
    }

    #[test]
    fn statistics_are_consistent(t in arb_trace()) {
        let s = t.stats();
        prop_assert_eq!(s.warps as usize, t.quad_count());
        prop_assert_eq!(s.rejected_quads, t.rejected_count());
        prop_assert!(s.positions <= s.warps && s.positions >= s.warp_tiles);
        prop_assert!(s.warp_tiles <= s.tiles);
        let least = if s.warps > 0 { 1.0 } else { 0.0 };
        prop_assert!(s.warps_per_tile >= least);
        for x in [s.warps_per_position, s.coverage, s.warps_per_tile, s.instrs_per_warp,
                  s.mem_instr_ratio, s.reuse, s.cf, s.min_estimate1, s.min_estimate2] {
            prop_assert!(x.is_finite(), "{:?}", s);
        }
        prop_assert!(s.coverage <= 1.0);
        prop_assert_eq!(s.instrs, t.instr_count());
        prop_assert!(s.warp_blocks >= s.tile_unique_blocks);
        prop_assert!(s.block_accesses >= s.warp_blocks);
        prop_assert!(s.tile_unique_blocks >= s.frame_unique_blocks);
        // The frame's distinct blocks, the plain way: every access of every
        // tile, sorted and deduplicated.
        let mut all: Vec<u64> = t
            .tiles()
            .iter()
            .flat_map(|tile| tile.block_accesses().iter().copied())
            .collect();
        all.sort_unstable();
        all.dedup();
        prop_assert_eq!(s.frame_unique_blocks, all.len() as u64);
        let tile_unique: usize = t.tiles().iter().map(|tile| tile.unique_block_count()).sum();
        prop_assert_eq!(s.tile_unique_blocks, tile_unique as u64);
        let warp_blocks: u64 = t.tile_stats().iter().map(|ts| ts.warp_blocks).sum();
        prop_assert_eq!(s.warp_blocks, warp_blocks);
        for tile in t.tiles() {
            let ts = tile.stats();
            prop_assert!(tile.quad_count() > 0 || tile.rejected_count() > 0);
            prop_assert_eq!(ts.rejected_quads, tile.rejected_count());
            prop_assert_eq!(
                tile.raster_count(),
                tile.quad_count() as u64 + tile.rejected_count()
            );
            let by_gap: u64 = (0..tile.quad_count())
                .map(|i| u64::from(tile.rejected_before(i)))
                .sum::<u64>()
                + u64::from(tile.rejected_after_last());
            prop_assert_eq!(by_gap, tile.rejected_count());
            for x in [ts.cf(), ts.reuse(), ts.min_estimate1(), ts.min_estimate2(), ts.mem_instr_ratio()] {
                prop_assert!(x.is_finite());
            }
            prop_assert!(ts.unique_blocks == 0 || ts.reuse() >= 1.0);
            prop_assert!(close(footprint_ratio(tile, |_, _| true), 1.0));
            let f = footprint_ratio(tile, |x, _| x % 2 == 0);
            prop_assert!((0.0..=1.0).contains(&f));
        }
    }
}

#[test]
fn statistics_are_remembered_and_not_part_of_equality() {
    let t = Trace::read(TINY).unwrap();
    let fresh = t.clone();
    let first = t.stats();
    // The remembered statistics are the computed ones, and a trace that
    // has them equals one that has not computed them yet.
    assert_eq!(first, TraceStats::of(&t));
    assert_eq!(t.stats(), first);
    assert_eq!(t, fresh);
    assert!(format!("{t:?}").contains("Memo(computed)"));
    assert!(format!("{fresh:?}").contains("Memo(not computed)"));
    assert_eq!(fresh.stats(), first);
    // A tile's distinct-block count likewise.
    let tile = &t.tiles()[0];
    let plain = tile.unique_blocks().len();
    assert!(plain > 0);
    assert_eq!(tile.unique_block_count(), plain);
    assert_eq!(tile.unique_block_count(), plain);
    assert_eq!(tile, &fresh.tiles()[0]);
}

// ---- format 3: Early-Z-rejected quads ----

const HEAD3: &str = "wasp-trace 3\nworkload w\nframe 128 64 tile 64\n";

#[test]
fn rejected_quads_round_trip_and_sit_where_they_were_rasterized() {
    let text = format!(
        "{HEAD3}tile 0 0\nz 5\nq 0 0 a1\nq 1 0 a2\nz 3\nq 2 0 a1\nz 7\nend\ntile 1 0\nz 9\nend\n"
    );
    let t = Trace::parse(&text, "z").unwrap();
    let a = &t.tiles()[0];
    assert_eq!(a.quad_count(), 3);
    assert_eq!(
        (0..3).map(|i| a.rejected_before(i)).collect::<Vec<_>>(),
        vec![5, 0, 3]
    );
    assert_eq!(a.rejected_before(3), 0, "past the last quad");
    assert_eq!(a.rejected_after_last(), 7);
    assert_eq!((a.rejected_count(), a.raster_count()), (15, 18));
    // A tile whose every quad Early-Z rejected: no warp, raster time only.
    let b = &t.tiles()[1];
    assert_eq!((b.quad_count(), b.rejected_after_last()), (0, 9));
    assert_eq!(t.rejected_count(), 24);
    assert_eq!(
        t.to_text(),
        text.replacen("wasp-trace 3\n", "wasp-trace 4\n", 1),
        "the writer writes what it read, as version 4"
    );
    // Statistics of a trace with a warp-less tile stay finite.
    let st = t.stats();
    assert!(st.cf.is_finite() && st.min_estimate1.is_finite());
}

#[test]
fn the_builder_adds_up_rejections_and_keeps_them_canonical() {
    let mut b = Trace::builder(TraceHeader::new("w", 64, 64, 64)).unwrap();
    assert_eq!(b.rejected(1), Err(Problem::RejectedWithoutTile));
    b.begin_tile(0, 0).unwrap();
    assert_eq!(b.rejected(0), Err(Problem::ZeroRejected));
    b.rejected(2).unwrap();
    b.rejected(3).unwrap();
    b.quad(0, 0, &[Instr::Alu(1)]).unwrap();
    b.quad(1, 0, &[Instr::Alu(1)]).unwrap();
    b.rejected(MAX_REJECTED_RUN).unwrap();
    assert!(matches!(b.rejected(1), Err(Problem::RejectedRunTooLong(_))));
    b.end_tile().unwrap();
    let t = b.finish().unwrap();
    let tile = &t.tiles()[0];
    assert_eq!(tile.rejected_before(0), 5);
    assert_eq!(tile.rejected_before(1), 0);
    assert_eq!(tile.rejected_after_last(), MAX_REJECTED_RUN);
    assert!(t
        .to_text()
        .contains("tile 0 0\nz 5\nq 0 0 a1\nq 1 0 a1\nz 4194304\nend\n"));
    // A tile with rejections after its quads only keeps no per-quad list:
    // it equals the same tile read back.
    let mut b = Trace::builder(TraceHeader::new("w", 64, 64, 64)).unwrap();
    b.begin_tile(0, 0).unwrap();
    b.quad(0, 0, &[Instr::Alu(1)]).unwrap();
    b.rejected(4).unwrap();
    b.end_tile().unwrap();
    let t = b.finish().unwrap();
    assert_eq!(Trace::parse(&t.to_text(), "rt").unwrap(), t);
}

#[test]
fn bad_rejection_records_are_errors_with_their_line() {
    let cases: &[(&str, usize, &str)] = &[
        ("tile 0 0\nz 0\nq 0 0 a1\nend\n", 5, "0 rejected quads"),
        ("tile 0 0\nz\nq 0 0 a1\nend\n", 5, "`z N`"),
        ("tile 0 0\nz 1 2\nq 0 0 a1\nend\n", 5, "`z N`"),
        ("tile 0 0\nz x\nq 0 0 a1\nend\n", 5, "rejected quads"),
        ("tile 0 0\nz 4294967296\nend\n", 5, "rejected quads"),
        ("z 3\ntile 0 0\nq 0 0 a1\nend\n", 4, "outside any tile"),
        (
            "tile 0 0\nz 2\nz 3\nq 0 0 a1\nend\n",
            6,
            "two `z` lines in a row",
        ),
        ("tile 0 0\nq 0 0 a1\nend\nz 3\n", 7, "outside any tile"),
    ];
    for (body, line, want) in cases {
        let text = format!("{HEAD3}{body}");
        let e = Trace::parse(&text, "bad.trace").unwrap_err();
        let msg = e.to_string();
        assert!(
            msg.starts_with(&format!("bad.trace:{line}: ")),
            "{body:?}: {msg}"
        );
        assert!(msg.contains(want), "{body:?}: {msg}");
    }
    // Formats 1 and 2 have no `z` line.
    for v in [1, 2] {
        let text = format!(
            "wasp-trace {v}\nworkload w\nframe 64 64 tile 64\ntile 0 0\nz 2\nq 0 0 a1\nend\n"
        );
        let msg = Trace::parse(&text, "old.trace").unwrap_err().to_string();
        assert!(msg.starts_with("old.trace:5: "), "{msg}");
        assert!(msg.contains(&format!("format-{v} trace")), "{msg}");
    }
    // A version-2 trace without `z` lines still loads, with no rejection.
    let text = "wasp-trace 2\nworkload w\nframe 64 64 tile 64\ntile 0 0\nq 0 0 a1\nend\n";
    let t = Trace::parse(text, "v2").unwrap();
    assert_eq!(t.rejected_count(), 0);
    assert!(t.to_text().starts_with("wasp-trace 4\n"));
}

#[test]
fn a_trace_with_rejections_reads_alike_in_pieces() {
    // Enough tiles for several pieces, rejections in each.
    let mut b = Trace::builder(TraceHeader::new("w", 64 * 60, 64 * 60, 64)).unwrap();
    for ty in 0..60 {
        for tx in 0..60 {
            b.begin_tile(tx, ty).unwrap();
            b.rejected(1 + tx).unwrap();
            for i in 0..160 {
                b.quad(
                    i % 32,
                    i / 32,
                    &[Instr::Alu(1 + i), Instr::Tex(&[u64::from(i)])],
                )
                .unwrap();
                if i % 7 == 3 {
                    b.rejected(i).unwrap();
                }
            }
            b.end_tile().unwrap();
        }
    }
    let t = b.finish().unwrap();
    let text = t.to_text();
    assert!(text.len() > 4 << 20, "large enough for the pieces path");
    assert_eq!(Trace::parse(&text, "big").unwrap(), t);
}

#[test]
fn a_hand_built_tile_answers_where_its_rejected_quads_are() {
    let build = |split: bool, tail: u32| {
        let mut b = Trace::builder(TraceHeader::new("w", 64, 64, 64)).unwrap();
        b.begin_tile(0, 0).unwrap();
        b.rejected(3).unwrap();
        b.quad(0, 0, &[Instr::Alu(1)]).unwrap();
        b.quad(1, 0, &[Instr::Tex(&[9])]).unwrap();
        if split {
            b.rejected(2).unwrap();
            b.rejected(3).unwrap();
        } else {
            b.rejected(5).unwrap();
        }
        b.quad(1, 0, &[Instr::Alu(2)]).unwrap();
        b.quad(0, 1, &[Instr::Alu(3)]).unwrap();
        if tail > 0 {
            b.rejected(tail).unwrap();
        }
        b.end_tile().unwrap();
        b.finish().unwrap()
    };
    let t = build(false, 4);
    let tile = &t.tiles()[0];
    assert_eq!(tile.quad_count(), 4);
    let before: Vec<u32> = (0..4).map(|i| tile.rejected_before(i)).collect();
    assert_eq!(before, vec![3, 0, 5, 0]);
    assert_eq!(tile.rejected_after_last(), 4);
    assert_eq!((tile.rejected_count(), tile.raster_count()), (12, 16));
    assert_eq!(t.rejected_count(), 12);
    assert_eq!(tile.stats().rejected_quads, 12);
    assert_eq!(t.stats().rejected_quads, 12);
    // Split calls add up to the same tile; other rejections make another.
    assert_eq!(build(true, 4), t);
    assert_ne!(build(false, 5), t);
    assert_ne!(build(false, 0), t);
    assert_eq!(
        t.to_text().split_once("tile 0 0\n").unwrap().1,
        "z 3\nq 0 0 a1\nq 1 0 t9\nz 5\nq 1 0 a2\nq 0 1 a3\nz 4\nend\n"
    );
    assert_eq!(Trace::parse(&t.to_text(), "rt").unwrap(), t);
}

#[test]
fn a_failed_rejection_changes_nothing() {
    let mut b = Trace::builder(TraceHeader::new("w", 64, 64, 64)).unwrap();
    b.begin_tile(0, 0).unwrap();
    b.begin_quad(0, 0).unwrap();
    // The open quad has no instruction yet.
    assert_eq!(b.rejected(2), Err(Problem::EmptyQuad { x: 0, y: 0 }));
    b.alu(1).unwrap();
    b.rejected(MAX_REJECTED_RUN - 1).unwrap();
    assert_eq!(
        b.rejected(2),
        Err(Problem::RejectedRunTooLong(u64::from(MAX_REJECTED_RUN) + 1))
    );
    b.rejected(1).unwrap();
    b.end_tile().unwrap();
    assert_eq!(b.rejected(1), Err(Problem::RejectedWithoutTile));
    let t = b.finish().unwrap();
    assert_eq!(t.tiles()[0].rejected_after_last(), MAX_REJECTED_RUN);
    assert_eq!(t.tiles()[0].rejected_before(0), 0);
    // A tile with no line at all is still refused.
    let mut b = Trace::builder(TraceHeader::new("w", 64, 64, 64)).unwrap();
    b.begin_tile(0, 0).unwrap();
    assert_eq!(b.rejected(0), Err(Problem::ZeroRejected));
    assert_eq!(b.end_tile(), Err(Problem::EmptyTile { tx: 0, ty: 0 }));
}

#[test]
fn more_bad_rejection_records_name_their_line() {
    let cases: &[(&str, usize, &str)] = &[
        // Adjacent even with a comment or blank line between.
        (
            "tile 0 0\nq 0 0 a1\nz 2\n# c\n\nz 3\nend\n",
            9,
            "two `z` lines in a row",
        ),
        ("tile 0 0\nz 2\n  z 1\nend\n", 6, "two `z` lines in a row"),
        ("tile 0 0\nz 4194305\nend\n", 5, "at most 4194304"),
        ("tile 0 0\nz -1\nend\n", 5, "bad rejected quads `-1`"),
        ("tile 0 0\nz 1x\nend\n", 5, "expected a decimal number"),
        ("tile 0 0\nz\tz\nend\n", 5, "bad rejected quads `z`"),
        ("tile 0 0\nend\n", 5, "tile 0 0 is empty"),
        ("tile 0 0\nz 2\ntile 1 0\n", 6, "tile 0 0 is not closed"),
        ("tile 0 0\nz 2\n", 5, "tile 0 0 is not closed"),
        ("tile 0 0\nzz 2\nend\n", 5, "`q X Y ...`, `z N` or `end`"),
    ];
    for (body, line, want) in cases {
        let text = format!("{HEAD3}{body}");
        let msg = Trace::parse(&text, "bad.trace").unwrap_err().to_string();
        assert!(
            msg.starts_with(&format!("bad.trace:{line}: ")),
            "{body:?}: {msg}"
        );
        assert!(msg.contains(want), "{body:?}: {msg}");
        assert!(msg.contains("(expected "), "{body:?}: {msg}");
    }
    // `z` before the header.
    let msg = Trace::parse("wasp-trace 3\nz 1\n", "h.trace")
        .unwrap_err()
        .to_string();
    assert!(msg.starts_with("h.trace:2: `z` before the header"), "{msg}");
    // Not adjacent: a quad or another tile between.
    let ok = format!("{HEAD3}tile 0 0\nz 2\nq 0 0 a1\nz 3\nend\ntile 1 0\nz 1\nend\n");
    let t = Trace::parse(&ok, "ok").unwrap();
    assert_eq!(t.rejected_count(), 6);
}

#[test]
fn older_files_load_without_rejected_quads() {
    for (path, version) in [(TINY, 1), (OVERDRAW, 2), (SYNTH_SMALL, 1)] {
        let text = std::fs::read_to_string(path).unwrap();
        assert!(
            text.starts_with(&format!("wasp-trace {version}\n")),
            "{path}"
        );
        let t = Trace::read(path).unwrap();
        assert_eq!(t.rejected_count(), 0, "{path}");
        assert_eq!(t.stats().rejected_quads, 0, "{path}");
        for tile in t.tiles() {
            assert_eq!(tile.raster_count(), tile.quad_count() as u64, "{path}");
            assert_eq!(tile.rejected_after_last(), 0, "{path}");
            assert!((0..tile.quad_count()).all(|i| tile.rejected_before(i) == 0));
        }
        // Written as version 4, the same records: only line 1 changes.
        let v4 = t.to_text();
        assert!(v4.starts_with("wasp-trace 4\n"));
        assert!(!v4.contains("\nz "), "{path}");
        assert_eq!(Trace::parse(&v4, "v4").unwrap(), t);
    }
}

#[test]
fn a_tile_without_warps_stays_out_of_per_tile_means() {
    let text =
        format!("{HEAD3}tile 0 0\nq 0 0 a1 t1,2\nq 1 0 a1 t2\nz 4\nend\ntile 1 0\nz 9\nend\n");
    let t = Trace::parse(&text, "z").unwrap();
    let hidden = &t.tiles()[1];
    let hs = hidden.stats();
    assert_eq!((hs.warps, hs.positions, hs.unique_blocks), (0, 0, 0));
    assert_eq!(hs.rejected_quads, 9);
    for x in [
        hs.cf(),
        hs.reuse(),
        hs.min_estimate1(),
        hs.min_estimate2(),
        hs.mem_instr_ratio(),
    ] {
        assert_eq!(x, 0.0);
    }
    assert_eq!(footprint_ratio(hidden, |_, _| true), 1.0);
    assert_eq!(hidden.position_count(), 0);
    assert!(hidden.quad(0).is_none() && hidden.quads().next().is_none());
    let s = t.stats();
    assert_eq!(
        (s.tiles, s.warp_tiles, s.warps, s.rejected_quads),
        (2, 1, 2, 13)
    );
    // Means over the tile with warps only: as if the hidden tile were not there.
    assert!(close(s.warps_per_tile, 2.0));
    assert!(close(s.cf, 1.5));
    assert!(close(s.min_estimate1, 1.0));
    assert!(close(s.reuse, 1.5));
    assert!(close(mean_footprint_ratio(&t, |x, _| x == 0), 1.0));
    assert!(close(mean_footprint_ratio(&t, |x, _| x == 1), 0.5));
    // A trace of hidden tiles only.
    let text = format!("{HEAD3}tile 1 0\nz 9\nend\n");
    let s = Trace::parse(&text, "z").unwrap().stats();
    assert_eq!(
        (s.tiles, s.warp_tiles, s.warps, s.rejected_quads),
        (1, 0, 0, 9)
    );
    assert_eq!(
        (s.warps_per_tile, s.cf, s.reuse, s.coverage),
        (0.0, 0.0, 0.0, 0.0)
    );
}

// ---------------------------------------------------------------- trilinear

const HEAD4: &str = "wasp-trace 4\nworkload w\nframe 128 64 tile 64\n";

#[test]
fn trilinear_instructions_round_trip_and_count() {
    let text = format!(
        "{HEAD4}tile 0 0\nq 0 0 a2 T1a,2b a1 t3\nq 1 0 TFF\nz 2\nend\ntile 1 0\nq 0 0 t4 T5\nend\n"
    );
    let t = Trace::parse(&text, "tri").unwrap();
    let q = t.tiles()[0].quad(0).unwrap();
    assert_eq!(
        q.instrs().collect::<Vec<_>>(),
        vec![
            Instr::Alu(2),
            Instr::TriTex(&[0x1a, 0x2b]),
            Instr::Alu(1),
            Instr::Tex(&[3]),
        ]
    );
    assert_eq!((q.tex_count(), q.trilinear_count()), (2, 1));
    assert!(Instr::TriTex(&[1]).is_trilinear() && !Instr::Tex(&[1]).is_trilinear());
    assert_eq!(Instr::TriTex(&[1, 2]).blocks(), Some(&[1u64, 2][..]));
    assert_eq!(Instr::Alu(3).blocks(), None);
    // Upper-case hex digits read, written lower-case; `T` stays `T`.
    assert_eq!(
        t.tiles()[0].quad(1).unwrap().entry(0),
        Some(Instr::TriTex(&[0xff]))
    );
    assert_eq!(t.tiles()[0].trilinear_count(), 2);
    assert_eq!((t.tex_count(), t.trilinear_count()), (5, 3));
    let s = t.stats();
    assert_eq!((s.tex_instrs, s.tri_tex_instrs), (5, 3));
    assert!(close(s.trilinear_share, 0.6));
    assert_eq!(t.tiles()[1].stats().tri_tex_instrs, 1);
    assert_eq!(t.to_text(), text.replace("TFF", "Tff"));
    // The core's view: the flag with the block count.
    let tile = &t.tiles()[0];
    assert_eq!(tile.op_kind(1), Some(OpKind::Tex { len: 2, tri: true }));
    assert_eq!(tile.op_kind(3), Some(OpKind::Tex { len: 1, tri: false }));
    // The same blocks bilinear or trilinear are different instructions.
    let bil = Trace::parse(&text.replace('T', "t"), "bil").unwrap();
    assert_ne!(bil, t);
    assert_eq!(bil.trilinear_count(), 0);
    // The builder's three ways to add one.
    let mut b = Trace::builder(TraceHeader::new("w", 64, 64, 64)).unwrap();
    b.begin_tile(0, 0).unwrap();
    b.begin_quad(0, 0).unwrap();
    b.tex_trilinear(&[1]).unwrap();
    b.tex_filtered(&[2], true).unwrap();
    b.instr(Instr::TriTex(&[3])).unwrap();
    b.tex_filtered(&[4], false).unwrap();
    assert_eq!(b.tex_trilinear(&[5, 5]), Err(Problem::DuplicateBlock(5)));
    b.end_tile().unwrap();
    let t = b.finish().unwrap();
    assert_eq!((t.tex_count(), t.trilinear_count()), (4, 3));
    assert!(t.to_text().contains("\nq 0 0 T1 T2 T3 t4\n"));
}

#[test]
fn an_instruction_entry_stays_twelve_bytes() {
    assert_eq!(std::mem::size_of::<Op>(), 12);
}

#[test]
fn trilinear_in_an_older_version_is_an_error_naming_the_token() {
    for v in [1, 2, 3] {
        let text = format!(
            "wasp-trace {v}\nworkload w\nframe 64 64 tile 64\ntile 0 0\nq 0 0 a1 T1a,2\nend\n"
        );
        let e = Trace::parse(&text, "old.trace").unwrap_err();
        assert_eq!(e.line(), Some(5));
        assert_eq!(
            e.problem(),
            Some(&Problem::TrilinearInOldVersion {
                version: v,
                token: "T1a,2".into()
            })
        );
        assert_eq!(
            e.to_string(),
            format!(
                "old.trace:5: trilinear texture instruction `T1a,2` in a format-{v} trace \
                 (expected `T` only from format 4 on: write `t`, or `wasp-trace 4` on line 1)"
            )
        );
        // The same with `t` loads, every texture instruction bilinear.
        let t = Trace::parse(&text.replace('T', "t"), "old.trace").unwrap();
        assert_eq!((t.tex_count(), t.trilinear_count()), (1, 0));
    }
}

#[test]
fn bad_trilinear_tokens_are_errors_with_their_line() {
    let cases: [(&str, Problem); 6] = [
        ("T", Problem::TexNoBlock),
        ("T1,,2", Problem::EmptyBlockEntry("T1,,2".into())),
        ("T1g", Problem::BadHex { found: "1g".into() }),
        ("T7,7", Problem::DuplicateBlock(7)),
        ("TT1", Problem::BadHex { found: "T1".into() }),
        ("tT1", Problem::BadHex { found: "T1".into() }),
    ];
    for (tok, want) in cases {
        let text = format!("{HEAD4}tile 0 0\nq 0 0 a1 {tok}\nend\n");
        let e = Trace::parse(&text, "t.trace").unwrap_err();
        assert_eq!(e.line(), Some(5), "{tok}");
        assert_eq!(e.problem(), Some(&want), "{tok}");
        assert!(e.to_string().contains("(expected "), "{e}");
    }
    let many = (0..1025)
        .map(|i| format!("{i:x}"))
        .collect::<Vec<_>>()
        .join(",");
    let text = format!("{HEAD4}tile 0 0\nq 0 0 T{many}\nend\n");
    assert_eq!(
        Trace::parse(&text, "t").unwrap_err().problem(),
        Some(&Problem::TooManyBlocks(1025))
    );
    let msg = Trace::parse(&format!("{HEAD4}tile 0 0\nq 0 0 T\nend\n"), "t")
        .unwrap_err()
        .to_string();
    assert_eq!(
        msg,
        "t:5: texture instruction without blocks (expected `t` or `T` and hex block numbers)"
    );
}

#[test]
fn a_trilinear_error_in_a_piece_is_reported_as_on_one_thread() {
    // A version-3 text long enough to be read in pieces, with one `T`
    // near the end: the pieces fail, the one-thread read names its line.
    let mut text = String::from("wasp-trace 3\nworkload w\nframe 4096 64 tile 64\n");
    for tx in 0..64 {
        text.push_str(&format!("tile {tx} 0\nq 0 0 a1 t{tx:x}\nend\n"));
    }
    let good = Trace::parse_with(&text, "p", 4, 0).unwrap();
    assert_eq!(good.trilinear_count(), 0);
    let bad = text.replacen("q 0 0 a1 t3e\n", "q 0 0 a1 T3e\n", 1);
    let line = bad.lines().position(|l| l.ends_with("T3e")).unwrap() + 1;
    let e = Trace::parse_with(&bad, "p", 4, 0).unwrap_err();
    assert_eq!(e, Trace::parse_with(&bad, "p", 1, usize::MAX).unwrap_err());
    assert_eq!(e.line(), Some(line));
    assert!(e.to_string().contains("`T3e` in a format-3 trace"), "{e}");
    // As version 4 it reads, in pieces or not, the same.
    let v4 = bad.replacen("wasp-trace 3\n", "wasp-trace 4\n", 1);
    let a = Trace::parse_with(&v4, "p", 4, 0).unwrap();
    assert_eq!(a, Trace::parse_with(&v4, "p", 1, usize::MAX).unwrap());
    assert_eq!(a.trilinear_count(), 1);
}

/// A version-4 trace of one 64-pixel tile holding `body` (its lines).
fn one_tile(body: &str) -> String {
    format!("wasp-trace 4\nworkload w\nframe 64 64 tile 64\ntile 0 0\n{body}end\n")
}

#[test]
fn every_number_of_a_trace_is_bounded() {
    // At each bound the trace is read; just above it the reader names the
    // file and line, the token and the allowed range, on the plain and on
    // the multi-threaded path alike.
    let alu_max = format!("q 0 0 a{MAX_ALU_RUN}\n");
    let alu_over = format!("q 0 0 a{}\n", MAX_ALU_RUN + 1);
    let z_max = format!("q 0 0 a1\nz {MAX_REJECTED_RUN}\n");
    let z_over = format!("z {}\n", MAX_REJECTED_RUN + 1);
    let blocks = |n: usize| {
        (1..=n)
            .map(|b| format!("{b:x}"))
            .collect::<Vec<_>>()
            .join(",")
    };
    let tex_max = format!("q 0 0 t{}\n", blocks(MAX_TEX_BLOCKS));
    let tex_over = format!("q 0 0 T{}\n", blocks(MAX_TEX_BLOCKS + 1));
    for ok in [&alu_max, &z_max, &tex_max] {
        let text = one_tile(ok);
        Trace::parse(&text, "b.trace").unwrap_or_else(|e| panic!("{ok}: {e}"));
    }
    // A program of exactly the bound: 15 full ALU runs, a texture
    // instruction after each, and a last run to fill it up.
    let runs = MAX_QUAD_INSTRS / MAX_ALU_RUN - 1;
    let full = (0..runs)
        .map(|_| format!("a{MAX_ALU_RUN} t1"))
        .collect::<Vec<_>>()
        .join(" ");
    let last = MAX_QUAD_INSTRS - runs * (MAX_ALU_RUN + 1);
    let at_bound = format!("q 0 0 {full} a{last}");
    // One texture instruction more; or one ALU instruction more, found
    // in the middle of the line.
    let prog_over = format!("{at_bound} t2\n");
    let prog_over_alu = format!("q 0 0 a1 t2 {full} a{last}\n");
    let t = Trace::parse(&one_tile(&format!("{at_bound}\n")), "b.trace").unwrap();
    let instrs: u64 = t.tiles()[0]
        .quads()
        .map(|q| {
            q.instrs()
                .map(|i| match i {
                    Instr::Alu(n) => u64::from(n),
                    _ => 1,
                })
                .sum::<u64>()
        })
        .sum();
    assert_eq!(instrs, u64::from(MAX_QUAD_INSTRS));
    let cases: [(&str, String); 5] = [
        (
            &alu_over,
            format!(
                "ALU run `{}` out of range (expected at most {MAX_ALU_RUN})",
                MAX_ALU_RUN + 1
            ),
        ),
        (
            &z_over,
            format!(
                "rejected quads `{}` out of range (expected at most {MAX_REJECTED_RUN})",
                MAX_REJECTED_RUN + 1
            ),
        ),
        (
            &tex_over,
            format!(
                "texture instruction with {} blocks (expected at most {MAX_TEX_BLOCKS})",
                MAX_TEX_BLOCKS + 1
            ),
        ),
        (
            &prog_over,
            format!(
                "quad program of {} instructions (expected 1 to {MAX_QUAD_INSTRS}",
                MAX_QUAD_INSTRS + 1
            ),
        ),
        (
            &prog_over_alu,
            format!(
                "quad program of {} instructions (expected 1 to {MAX_QUAD_INSTRS}",
                MAX_QUAD_INSTRS + 2
            ),
        ),
    ];
    for (body, want) in cases {
        let text = one_tile(body);
        for (threads, min) in [(1, usize::MAX), (3, 0)] {
            let e = Trace::parse_with(&text, "b.trace", threads, min)
                .unwrap_err()
                .to_string();
            assert!(e.starts_with("b.trace:5: "), "{e}");
            assert!(e.contains(&want), "{e}\nwanted {want}");
        }
    }
}

#[test]
fn the_builder_holds_a_quad_program_to_its_bound() {
    let mut b = Trace::builder(TraceHeader::new("w", 64, 64, 64)).unwrap();
    b.begin_tile(0, 0).unwrap();
    b.begin_quad(0, 0).unwrap();
    let runs = MAX_QUAD_INSTRS / MAX_ALU_RUN - 1;
    for _ in 0..runs {
        b.alu(MAX_ALU_RUN).unwrap();
        b.tex(&[1]).unwrap();
    }
    b.alu(MAX_QUAD_INSTRS - runs * (MAX_ALU_RUN + 1)).unwrap();
    // The program is full: nothing more fits, and a refusal changes nothing.
    assert_eq!(
        b.alu(1),
        Err(Problem::QuadTooLong(u64::from(MAX_QUAD_INSTRS) + 1))
    );
    assert_eq!(
        b.tex(&[2]),
        Err(Problem::QuadTooLong(u64::from(MAX_QUAD_INSTRS) + 1))
    );
    // The next quad starts from zero.
    b.begin_quad(1, 0).unwrap();
    b.alu(MAX_ALU_RUN).unwrap();
    b.end_tile().unwrap();
    b.finish().unwrap();
}
