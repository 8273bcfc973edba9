//! Runs of traces of several frames: a repeated frame finds warm caches,
//! the first frame of a run measures what a one-frame run of it does,
//! every counter restarts at a frame's start, and `warm` picks the frames.

use super::*;
use crate::gpu::Gpu;
use crate::stats::FrameRecord;
use crate::trace::Instr;

use super::tests::small_synth as synth;

/// `t` with every block number moved by `offset` (the same frame drawn
/// with other textures).
fn shifted(t: &Trace, offset: u64) -> Trace {
    let mut b = Trace::builder(t.header().clone()).unwrap();
    for tile in t.tiles() {
        b.begin_tile(tile.tx(), tile.ty()).unwrap();
        for q in tile.quads() {
            if tile.rejected_before(q.index()) > 0 {
                b.rejected(tile.rejected_before(q.index())).unwrap();
            }
            b.begin_quad(q.x(), q.y()).unwrap();
            for i in q.instrs() {
                match i {
                    Instr::Alu(n) => b.alu(n).unwrap(),
                    Instr::Tex(bl) | Instr::TriTex(bl) => {
                        let moved: Vec<u64> = bl.iter().map(|x| x + offset).collect();
                        b.tex_filtered(&moved, i.is_trilinear()).unwrap();
                    }
                }
            }
        }
        if tile.rejected_after_last() > 0 {
            b.rejected(tile.rejected_after_last()).unwrap();
        }
        b.end_tile().unwrap();
    }
    b.finish().unwrap()
}

fn cfg() -> MachineConfig {
    let c = MachineConfig::paper();
    c.validate().unwrap();
    c
}

fn sim(t: &Trace, opts: &RunOptions) -> RunStats {
    sim_on(&cfg(), t, opts)
}

fn sim_on(cfg: &MachineConfig, t: &Trace, opts: &RunOptions) -> RunStats {
    simulate(cfg, t, opts, &mut |_, _| {}).unwrap()
}

/// The report as JSON without what names the trace or positions in the
/// run (the workload, tile records and frame records).
fn figures(s: &RunStats) -> String {
    let mut s = s.clone();
    s.workload.clear();
    s.per_tile.clear();
    s.frames.clear();
    s.to_json()
}

#[test]
fn a_repeated_frame_finds_the_caches_warm() {
    let one = synth(3);
    let two = Trace::concat(one.clone(), [one.clone()]).unwrap();
    let s = sim(&two, &RunOptions::default());
    let [a, b] = &s.frames[..] else {
        panic!("two frame records: {:?}", s.frames)
    };
    assert_eq!((a.frame, b.frame), (0, 1));
    assert_eq!(
        (a.warps, b.warps),
        (one.quad_count() as u64, one.quad_count() as u64)
    );
    assert!(
        b.l2.misses < a.l2.misses,
        "{} !< {}",
        b.l2.misses,
        a.l2.misses
    );
    assert!(b.dram_requests < a.dram_requests);
    assert!(b.cycles < a.cycles);
    assert_eq!(b.start_cycle, a.cycles, "frame 1 starts when frame 0 ends");
    assert_eq!(s.last_cycle(), a.cycles + b.cycles);
    // The report is the last frame's.
    assert_eq!(FrameRecord::of(1, a.cycles, &s), *b);
    assert_eq!(s.tiles, one.tiles().len() as u64);
    // Frame 0 measures what a one-frame run of it does, every figure.
    let alone = sim(&one, &RunOptions::default());
    assert_eq!(FrameRecord::of(0, 0, &alone), *a);
    let mut gpu = Gpu::new(&cfg(), &two).unwrap();
    gpu.start_frame(two.frame_range(0));
    while !gpu.done() {
        gpu.step().unwrap();
    }
    let first = RunStats::collect_frame(&cfg(), &two, 0, gpu.end_frame().unwrap());
    assert_eq!(first, alone);
    assert!(alone.frames.is_empty() && !alone.to_json().contains("\"frames\""));
    assert_eq!(alone.last_cycle(), alone.cycles);
}

#[test]
fn every_counter_restarts_when_a_frame_begins() {
    // Frame 1 reads other blocks than frame 0 and, with ideal memory,
    // nothing of frame 0 changes its timing: it must measure what it
    // measures alone, counter for counter.
    let a = synth(5);
    let b = shifted(&synth(6), 1 << 40);
    let mut ideal = cfg();
    ideal.memory.ideal = true;
    let opts = RunOptions::default();
    let both = sim_on(&ideal, &Trace::concat(a, [b.clone()]).unwrap(), &opts);
    let alone = sim_on(&ideal, &b, &opts);
    assert_eq!(both.frames.len(), 2);
    assert!(
        figures(&both) == figures(&alone),
        "frame 1 differs from its run alone"
    );
    // Per-core-tile dispatch too.
    ideal.raster.dispatch = crate::config::Dispatch::PerCoreTile;
    let both = sim_on(
        &ideal,
        &Trace::concat(synth(5), [b.clone()]).unwrap(),
        &opts,
    );
    assert!(
        figures(&both) == figures(&sim_on(&ideal, &b, &opts)),
        "per-core-tile"
    );
}

#[test]
fn warm_runs_the_last_frame_after_k_earlier_ones() {
    let (x, y) = (synth(7), synth(8));
    let three = Trace::concat(x.clone(), [y.clone(), x.clone()]).unwrap();
    let warm = |k| RunOptions {
        warm: Some(k),
        ..RunOptions::default()
    };
    assert_eq!(warm(2).frames(&three).unwrap(), 0..3);
    assert_eq!(warm(0).frames(&three).unwrap(), 2..3);
    assert_eq!(RunOptions::default().frames(&three).unwrap(), 0..3);
    let e = warm(3).frames(&three).unwrap_err().to_string();
    assert_eq!(
        e,
        "warm-up of 3 frames: the trace has 3 frames, so at most 2 can run before the last"
    );
    let e = warm(1).frames(&x).unwrap_err().to_string();
    assert!(e.contains("the trace has 1 frame, so at most 0"), "{e}");
    // No warm-up: the last frame cold, as a one-frame run of it.
    let cold = sim(&three, &warm(0));
    assert_eq!(cold.frames.len(), 1);
    assert_eq!(cold.frames[0].frame, 2);
    assert!(figures(&cold) == figures(&sim(&x, &RunOptions::default())));
    // One frame of warm-up: frames 1 and 2.
    let one = sim(&three, &warm(1));
    let frames: Vec<usize> = one.frames.iter().map(|f| f.frame).collect();
    assert_eq!(frames, vec![1, 2]);
    assert_eq!(one.frames[0].warps, y.quad_count() as u64);
    // A one-frame trace with warm 0 is the plain run.
    assert_eq!(sim(&x, &warm(0)), sim(&x, &RunOptions::default()));
}
