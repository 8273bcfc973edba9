//! Test fixtures of the shader core's unit tests: a one-tile frame of
//! quads running one program, the paper's machine on 8-pixel tiles with a
//! given filter unit or on one core, and a core's state cycle by cycle.

use super::CoreSnapshot;
use crate::config::{FilterTiming, MachineConfig};
use crate::gpu::Gpu;
use crate::trace::{Instr, Trace, TraceHeader};

/// A 8x8-pixel frame whose quads (x, y) each run `program`.
pub(super) fn trace(quads: &[(u32, u32)], program: &[Instr]) -> Trace {
    let mut b = Trace::builder(TraceHeader::new("filter", 8, 8, 8)).unwrap();
    b.begin_tile(0, 0).unwrap();
    for &(x, y) in quads {
        b.quad(x, y, program).unwrap();
    }
    b.end_tile().unwrap();
    b.finish().unwrap()
}

/// The paper's machine on 8-pixel tiles with the filter unit given.
pub(super) fn cfg(bil: u32, tri: u32, timing: FilterTiming) -> MachineConfig {
    let mut c = MachineConfig::paper();
    c.gpu.tile_size = 8;
    c.core.filter_cycles_bilinear = bil;
    c.core.filter_cycles_trilinear = tri;
    c.core.filter_timing = timing;
    c.validate().unwrap();
    c
}

pub(super) const OVERLAP: FilterTiming = FilterTiming::Overlap;
pub(super) const SERIAL: FilterTiming = FilterTiming::Serial;

/// A one-core machine (the paper's otherwise) with `width`, `warps`
/// slots and ALU latency `alu`.
pub(super) fn one_core(width: u32, warps: u32, alu: u32) -> MachineConfig {
    let mut c = cfg(1, 2, OVERLAP);
    c.gpu.cores = 1;
    c.raster.quads_per_cycle = 4;
    c.core.pipeline_width = width;
    c.core.max_warps = warps;
    c.core.alu_latency = alu;
    c.validate().unwrap();
    c
}

/// Each cycle's counters of core 0 (instructions, texture
/// instructions, warps launched) and its snapshot, to the end.
pub(super) fn cycles(c: &MachineConfig, t: &Trace) -> Vec<([u64; 3], CoreSnapshot)> {
    let mut gpu = Gpu::new(c, t).unwrap();
    let mut out = vec![];
    while !gpu.done() {
        gpu.step().unwrap();
        let core = &gpu.cores()[0];
        let s = core.stats();
        out.push((
            [s.instructions, s.tex_instructions, s.warps_launched],
            core.snapshot(),
        ));
    }
    out
}
