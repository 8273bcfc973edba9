//! Minimal and malformed traces: what reads, and every broken rule
//! reported with its line.

use crate::testkit::*;
use crate::Problem::{self, *};
use crate::{Instr, Trace};

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

/// Each `text => line, pattern,` fails to parse, at `line`, with a
/// problem that matches `pattern` (and a message naming file and line).
macro_rules! reported {
    ($($text:expr => $line:expr, $pat:pat $(if $guard:expr)?,)+) => {
        $(reported_at_line(&$text, $line, |p| matches!(p, $pat $(if $guard)?));)+
    };
}

/// `text` fails to parse at `line` with a problem that `check` accepts.
fn reported_at_line(text: &str, line: usize, check: impl Fn(&Problem) -> bool) {
    let (l, p, msg) = fail(text);
    assert!(check(&p), "{text:?}: got {p:?} ({msg})");
    assert_eq!(l, line, "{text:?}: {msg}");
}

#[test]
fn a_bad_first_line_is_reported() {
    reported! {
        "" => 1, EmptyInput,
        "wasp-trace 1" => 1, MissingHeader { missing: "workload NAME", .. },
        "wasp-trace 6\n" => 1, UnsupportedVersion(v) if v == "6",
        "wasp-trace 0\n" => 1, UnsupportedVersion(v) if v == "0",
        "wasp-trace 02\n" => 1, UnsupportedVersion(v) if v == "02",
        "wasp-trace  2\n" => 1, BadMagic(_),
        "wasp-trace\n" => 1, BadMagic(_),
        "wasp-trace 1 x\n" => 1, BadMagic(_),
        " wasp-trace 1\n" => 1, BadMagic(_),
        "# c\nwasp-trace 1\n" => 1, BadMagic(_),
    }
}

#[test]
fn a_bad_or_misplaced_header_line_is_reported() {
    reported! {
        "wasp-trace 1\nframe 1 1 tile 2\n" => 2, MissingHeader { missing: "workload NAME", .. },
        "wasp-trace 1\nworkload w\ntile 0 0\n" => 3,
            MissingHeader { missing: "frame W H tile T", .. },
        "wasp-trace 1\nworkload w\n" => 2, MissingHeader { .. },
        "wasp-trace 1\nworkload \n" => 2, EmptyWorkload,
        "wasp-trace 1\nworkload a\nworkload b\n" => 3, MisplacedHeader("workload"),
        body("workload b\n") => 4, MisplacedHeader("workload"),
        body("frame 1 1 tile 2\n") => 4, MisplacedHeader("frame"),
        "wasp-trace 1\nbogus\n" => 2, UnknownDirective { .. },
    }
}

#[test]
fn a_bad_frame_line_is_reported() {
    reported! {
        "wasp-trace 1\nworkload w\nframe 10 10 tile\n" => 3,
            WrongFieldCount { directive: "frame", .. },
        "wasp-trace 1\nworkload w\nframe 10 10 tyle 2\n" => 3,
            WrongFieldCount { directive: "frame", .. },
        "wasp-trace 1\nworkload w\nframe 0 10 tile 2\n" => 3, BadFrame { dim: "width", .. },
        "wasp-trace 1\nworkload w\nframe 10 65537 tile 2\n" => 3,
            NumberTooLarge { what: "frame height", .. },
        "wasp-trace 1\nworkload w\nframe 10 10 tile 7\n" => 3, BadTileSize(7),
        "wasp-trace 1\nworkload w\nframe 10 10 tile 0\n" => 3, BadTileSize(0),
        "wasp-trace 1\nworkload w\nframe -1 10 tile 2\n" => 3,
            BadNumber { what: "frame width", .. },
    }
}

#[test]
fn a_bad_tile_record_is_reported() {
    reported! {
        body("tile 0 0\nx 1 2\n") => 5,
            UnknownDirective { expected: "`q X Y ...`, `z N` or `end`", .. },
        body("tile 0 0\nq 0 0 a1\nend\nq 0 0 a1\n") => 7, QuadWithoutTile,
        body("q 0 0 a1\n") => 4, QuadWithoutTile,
        body("end\n") => 4, EndWithoutTile,
        body("tile 0 0\nq 0 0 a1\nend x\n") => 6, WrongFieldCount { directive: "end", .. },
        body("tile 0 0\nq 0 0 a1\n") => 5, TileNotClosed { tx: 0, ty: 0 },
        body("tile 0 0\nq 0 0 a1\ntile 1 0\n") => 6, TileNotClosed { tx: 0, ty: 0 },
        body("tile 0 0\nend\n") => 5, EmptyTile { .. },
        body("tile 2 0\n") => 4, TileOutsideFrame { tiles_x: 2, tiles_y: 2, .. },
        body("tile 0 2\n") => 4, TileOutsideFrame { .. },
        body("tile 0\n") => 4, WrongFieldCount { directive: "tile", .. },
        body("tile 0 99999999999\n") => 4, NumberTooLarge { what: "tile y", .. },
        body("tile 0 0\nq 0 0 a1\nend\ntile 0 0\n") => 7, DuplicateTile { tx: 0, ty: 0 },
    }
}

#[test]
fn a_bad_quad_line_is_reported() {
    reported! {
        body("tile 0 0\nq 32 0 a1\n") => 5, QuadOutsideTile { x: 32, side: 32, .. },
        body("tile 0 0\nq 0 32 a1\n") => 5, QuadOutsideTile { .. },
        // Frame 100x70: tile 1 0 holds pixel columns 64..99, quads x 0..17.
        body("tile 1 0\nq 18 0 a1\n") => 5, QuadOutsideFrame { x: 18, px: 100, .. },
        body("tile 0 1\nq 0 3 a1\n") => 5, QuadOutsideFrame { py: 70, .. },
        // Version 1 only: scanline order, each position once.
        body1("tile 0 0\nq 1 0 a1\nq 1 0 a1\n") => 6, DuplicateQuad { x: 1, y: 0 },
        body1("tile 0 0\nq 1 1 a1\nq 2 0 a1\n") => 6,
            QuadOutOfOrder { x: 2, y: 0, prev_x: 1, prev_y: 1 },
        body("tile 0 0\nq 0 0\n") => 5, EmptyQuad { x: 0, y: 0 },
        body("tile 0 0\nq 0\n") => 5, WrongFieldCount { directive: "q", .. },
        body("tile 0 0\nq 0 x a1\n") => 5, BadNumber { what: "quad y", .. },
    }
}

#[test]
fn a_bad_alu_instruction_is_reported() {
    reported! {
        body("tile 0 0\nq 0 0 a0\n") => 5, ZeroAlu,
        body("tile 0 0\nq 0 0 a\n") => 5, BadInstr(_),
        body("tile 0 0\nq 0 0 a-1\n") => 5, BadInstr(_),
        body("tile 0 0\nq 0 0 a2147483648\n") => 5, NumberTooLarge { what: "ALU run", .. },
        body("tile 0 0\nq 0 0 a3 a2\n") => 5, AdjacentAlu { first: 3, second: 2 },
        body("tile 0 0\nq 0 0 x5\n") => 5, BadInstr(_),
        body("tile 0 0\nq 0 0 a1 # c\n") => 5, BadInstr(_),
    }
}

#[test]
fn a_bad_texture_instruction_is_reported() {
    let blocks_1025 = (0..1025)
        .map(|i| format!("{i:x}"))
        .collect::<Vec<_>>()
        .join(",");
    reported! {
        body("tile 0 0\nq 0 0 t\n") => 5, TexNoBlock,
        body("tile 0 0\nq 0 0 t1,\n") => 5, EmptyBlockEntry(_),
        body("tile 0 0\nq 0 0 t,1\n") => 5, EmptyBlockEntry(_),
        body("tile 0 0\nq 0 0 t1,,2\n") => 5, EmptyBlockEntry(_),
        body("tile 0 0\nq 0 0 t1g\n") => 5, BadHex { .. },
        body("tile 0 0\nq 0 0 t0x1\n") => 5, BadHex { .. },
        body("tile 0 0\nq 0 0 t+1\n") => 5, BadHex { .. },
        body("tile 0 0\nq 0 0 t10000000000000000\n") => 5, BadHex { .. },
        body("tile 0 0\nq 0 0 t1a,2,1A\n") => 5, DuplicateBlock(0x1a),
        body(&format!("tile 0 0\nq 0 0 t{blocks_1025}\n")) => 5, TooManyBlocks(1025),
    }
}

#[test]
fn a_control_character_is_reported() {
    reported! {
        body("tile 0 0\nq 0 0 a1\x0b\n") => 5, ControlCharacter,
        body("# bell \x07\n") => 4, ControlCharacter,
        body("tile 0 0\nq 0 0 a1\rx\n") => 5, ControlCharacter,
    }
}
