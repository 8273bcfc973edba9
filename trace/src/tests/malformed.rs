//! Minimal and malformed traces: what reads, and every broken rule
//! reported with its line.

use crate::testkit::*;
use crate::{Instr, Problem, Trace};

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
            "wasp-trace 6\n".into(),
            1,
            |p| matches!(p, UnsupportedVersion(v) if v == "6"),
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
