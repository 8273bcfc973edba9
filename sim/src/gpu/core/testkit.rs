//! Test fixtures of the shader core's unit tests: a one-tile frame of
//! quads running one program, and the paper's machine on 8-pixel tiles
//! with a given filter unit.

use crate::config::{FilterTiming, MachineConfig};
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
