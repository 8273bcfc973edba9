//! The checked-in traces of `tests/traces`: what they hold, and how they
//! read and write back.

use crate::testkit::*;
use crate::{footprint_ratio, Instr, Tile, Trace};

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
