//! Trilinear texture instructions (`T`, format 4): how they read, count
//! and write, and the errors of bad or out-of-version ones.

use crate::testkit::*;
use crate::{Instr, OpKind, Problem, Trace, TraceHeader};

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
