//! Traces of several frames (format 5): builder, writer and reader round
//! trips, reading in pieces, older files as one frame, and the errors a
//! frame boundary can raise.

use crate::testkit::*;
use crate::{Instr, Problem, Trace, TraceBuilder, TraceHeader};

/// Frame `f` of a 128x64 frame with 64-pixel tiles: both tiles, each quad's
/// program and blocks depending on `f`.
fn frame(b: &mut TraceBuilder, f: u32) {
    for tx in [1, 0] {
        b.begin_tile(tx, 0).unwrap();
        b.quad(f, 1, &[Instr::Alu(f + 1), Instr::Tex(&[u64::from(f) + 7])])
            .unwrap();
        b.rejected(f + 2).unwrap();
        b.quad(3, 3, &[Instr::TriTex(&[1, 2])]).unwrap();
        b.end_tile().unwrap();
    }
}

fn three_frames() -> Trace {
    let mut b = Trace::builder(TraceHeader::new("w", 128, 64, 64)).unwrap();
    b.note("three frames").unwrap();
    for f in 0..3 {
        if f > 0 {
            b.next_frame().unwrap();
        }
        assert_eq!(b.frame_count(), f as usize + 1);
        frame(&mut b, f);
    }
    b.finish().unwrap()
}

#[test]
fn a_three_frame_trace_round_trips_through_text() {
    let t = three_frames();
    assert_eq!(t.frame_count(), 3);
    assert_eq!(t.frames().collect::<Vec<_>>(), vec![0..2, 2..4, 4..6]);
    assert_eq!(t.frame_tiles(1)[0].quad(0).unwrap().instr_count(), 3);
    assert_eq!(
        (t.frame_of_tile(0), t.frame_of_tile(3), t.frame_of_tile(5)),
        (0, 1, 2)
    );
    let text = t.to_text();
    assert!(
        text.starts_with("wasp-trace 5\n#three frames\nworkload w\n"),
        "{text}"
    );
    assert_eq!(text.matches("\nnext-frame\n").count(), 2);
    assert!(text.contains("end\nnext-frame\ntile 1 0\n"), "{text}");
    let back = Trace::parse(&text, "f").unwrap();
    assert_eq!(back, t);
    assert_eq!(back.to_text(), text);
    // In pieces (cuts fall on `tile` lines, so a piece may end in a
    // boundary) the same trace.
    for pieces in 2..=6 {
        assert_eq!(
            Trace::parse_pieces(&text, "f", pieces).unwrap(),
            t,
            "{pieces}"
        );
    }
    // Per-frame statistics count one frame; the whole trace's, all three.
    let (one, all) = (t.frame_stats(2), t.stats());
    assert_eq!((one.tiles, one.warps, all.warps), (2, 4, 12));
    assert_eq!(all.frame_quads, 3 * one.frame_quads);
    assert!(close(all.coverage, one.coverage));
}

#[test]
fn a_one_frame_trace_is_written_in_format_4_as_before() {
    let mut b = Trace::builder(TraceHeader::new("w", 128, 64, 64)).unwrap();
    frame(&mut b, 0);
    let t = b.finish().unwrap();
    assert_eq!(t.frame_count(), 1);
    assert_eq!(t.frames().collect::<Vec<_>>(), vec![0..2]);
    let text = t.to_text();
    assert!(text.starts_with("wasp-trace 4\n") && !text.contains("next-frame"));
    // A format-5 file of one frame reads as that trace and is written back
    // in format 4 (line 1 only changes).
    let v5 = text.replacen("wasp-trace 4", "wasp-trace 5", 1);
    assert_eq!(Trace::parse(&v5, "v5").unwrap().to_text(), text);
}

#[test]
fn older_formats_load_as_one_frame() {
    for path in [TINY, OVERDRAW, SYNTH_SMALL] {
        let t = Trace::read(path).unwrap();
        assert_eq!(t.frame_count(), 1, "{path}");
        assert_eq!(t.frames().next(), Some(0..t.tiles().len()));
        assert_eq!(t.frame_stats(0), t.stats());
    }
    let t = Trace::parse(&format!("{HEAD3}tile 0 0\nq 0 0 a1\nend\n"), "v3").unwrap();
    assert_eq!(t.frame_count(), 1);
}

#[test]
fn empty_frames_and_tiles_repeated_across_frames_are_kept() {
    let mut b = Trace::builder(TraceHeader::new("w", 128, 64, 64)).unwrap();
    b.next_frame().unwrap(); // frame 0 drew nothing
    frame(&mut b, 1);
    assert_eq!(
        b.begin_tile(0, 0),
        Err(Problem::DuplicateTile { tx: 0, ty: 0 })
    );
    b.next_frame().unwrap();
    b.next_frame().unwrap(); // frame 2 drew nothing either; so does 3
    let t = b.finish().unwrap();
    assert_eq!(t.frames().collect::<Vec<_>>(), vec![0..0, 0..2, 2..2, 2..2]);
    let text = t.to_text();
    assert!(text.ends_with("end\nnext-frame\nnext-frame\n"), "{text}");
    assert!(text.contains("tile 64\nnext-frame\ntile 1 0\n"), "{text}");
    assert_eq!(Trace::parse(&text, "e").unwrap(), t);
    for pieces in 2..=4 {
        assert_eq!(Trace::parse_pieces(&text, "e", pieces).unwrap(), t);
    }
}

#[test]
fn a_frame_boundary_inside_a_tile_or_in_an_old_format_names_its_line() {
    let head5 = HEAD4.replacen("4", "5", 1);
    let (line, p, _) = fail(&format!("{head5}tile 0 0\nq 0 0 a1\nnext-frame\nend\n"));
    assert_eq!((line, p), (6, Problem::TileNotClosed { tx: 0, ty: 0 }));
    let (line, p, msg) = fail(&format!("{head5}tile 0 0\nq 0 0 a1\nend\nnext-frame 2\n"));
    assert_eq!(line, 7);
    assert!(matches!(p, Problem::WrongFieldCount { .. }), "{msg}");
    assert!(
        msg.ends_with("`next-frame` line with 2 fields (expected `next-frame`)"),
        "{msg}"
    );
    let (line, p, _) = fail(&format!("{HEAD4}tile 0 0\nq 0 0 a1\nend\nnext-frame\n"));
    assert_eq!((line, p), (7, Problem::FrameMarkerInOldVersion(4)));
    let (line, p, _) = fail(&format!("{HEAD3}next-frame\n"));
    assert_eq!((line, p), (4, Problem::FrameMarkerInOldVersion(3)));
    let (line, p, _) = fail(&format!("{head5}tile 0 0\nq 0 0 a1\nend\ntile 0 0\n"));
    assert_eq!((line, p), (7, Problem::DuplicateTile { tx: 0, ty: 0 }));
    let (line, p, _) = fail("wasp-trace 5\nworkload w\nnext-frame\n");
    assert_eq!(line, 3);
    assert!(matches!(p, Problem::MissingHeader { .. }));
    // The builder refuses a boundary in an open tile, changing nothing.
    let mut b = Trace::builder(TraceHeader::new("w", 64, 64, 64)).unwrap();
    b.begin_tile(0, 0).unwrap();
    assert_eq!(b.next_frame(), Err(Problem::TileNotClosed { tx: 0, ty: 0 }));
    assert_eq!(b.frame_count(), 1);
}

#[test]
fn appending_a_trace_of_frames_continues_the_current_frame() {
    let t = three_frames();
    let mut b = Trace::builder(t.header().clone()).unwrap();
    b.note("three frames").unwrap();
    // Its first frame's tiles are already here: refused, nothing changed.
    frame(&mut b, 9);
    assert_eq!(
        b.append(t.clone()),
        Err(Problem::DuplicateTile { tx: 1, ty: 0 })
    );
    assert_eq!((b.frame_count(), b.tile_count()), (1, 2));
    b.next_frame().unwrap();
    b.append(t.clone()).unwrap();
    // The current frame is the appended trace's last: its tiles are taken.
    assert_eq!(
        b.begin_tile(0, 0),
        Err(Problem::DuplicateTile { tx: 0, ty: 0 })
    );
    let all = b.finish().unwrap();
    assert_eq!(
        all.frames().collect::<Vec<_>>(),
        vec![0..2, 2..4, 4..6, 6..8]
    );
    assert_eq!(&all.tiles()[2..], t.tiles());
}

#[test]
fn traces_concatenate_frame_after_frame() {
    let t = three_frames();
    let mut b = Trace::builder(TraceHeader::new("other", 128, 64, 64)).unwrap();
    frame(&mut b, 5);
    let one = b.finish().unwrap();
    let all = Trace::concat(one.clone(), [t.clone(), one.clone()]).unwrap();
    assert_eq!(all.header().workload, "other");
    assert_eq!(all.frame_count(), 5);
    assert_eq!(all.frame_tiles(0), one.tiles());
    assert_eq!(all.frame_tiles(2), t.frame_tiles(1));
    assert_eq!(all.frame_tiles(4), one.tiles());
    let small = Trace::builder(TraceHeader::new("w", 64, 64, 64))
        .unwrap()
        .finish()
        .unwrap();
    assert!(matches!(
        Trace::concat(one, [small]),
        Err(Problem::FrameMismatch { .. })
    ));
}
