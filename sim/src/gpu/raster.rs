//! The paper's raster pipeline for shared-tile dispatch: the Tile Fetcher,
//! one Rasterizer and Early-Z stage for the whole GPU, the warp scheduler's
//! placement of quads into the cores' input queues, the tile barrier and
//! the colour-buffer flush.
//!
//! The paper (Section II-A): "the Tile Fetcher fetches the primitives
//! corresponding to each tile in the frame, one tile at a time"; "The
//! Raster Pipeline renders each tile sequentially"; the Z-buffer and the
//! colour buffer "have the size of just one tile"; "the Color Buffer is
//! flushed to the Frame Buffer in main memory, after a tile has been
//! completely processed". Section II-D: "All warps in a tile need to
//! finalize before another tile starts its execution in the GPU core".
//!
//! Per cycle:
//! 1. the flush hands one line of the last tile's colour buffer to main
//!    memory, if one is left;
//! 2. with no tile open, the fetcher opens the next one in trace order
//!    (Z-order) — under a blocking flush only once the flush is done;
//! 3. the rasterizer produces up to `raster.quads_per_cycle` quads in the
//!    tile's rasterization order. A quad Early-Z rejected (a `z` record of
//!    the trace) costs its slot and goes nowhere; a surviving quad goes to
//!    the input queue of the core the map names. If that queue is full the
//!    rasterizer waits (in order: back-pressure) until a later cycle.
//!
//! After the cores' end of cycle, the tile closes when every quad is
//! rasterized and every core has launched, run and retired all of its
//! warps (the barrier); its colour buffer then starts to flush. (wasp: the
//! rasterizer does not start the next tile before the barrier: the input
//! queues carry no tile tag, so a quad of the next tile queued behind the
//! current tile's quads could otherwise launch before the barrier. The next
//! tile's first quads are rasterized in the cycle after the barrier and can
//! launch in that cycle, so only the queues' head start is lost.)

use super::core_model::CoreModel;
use super::raster_cursor::RasterCursor;
use crate::config::{ColorFlush, CoreMapTable};
use crate::mem::MemorySystem;
use crate::trace::{Tile, Trace};
use serde::{Deserialize, Serialize};
use std::collections::VecDeque;
use wasp_waves::{Traceable, Tracer};

/// Block number of the frame buffer's first 64-byte line (byte address
/// 2^42): far above the texture addresses of every workload.
const FRAME_BUFFER_BLOCK: u64 = 1 << 36;

/// Counters of the raster pipeline.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct RasterStats {
    /// Quads rasterized, Early-Z-rejected ones included.
    pub quads_rasterized: u64,
    /// Quads Early-Z rejected (recorded by the trace).
    pub quads_rejected: u64,
    /// Cycles the rasterizer had a quad for a core whose input queue was
    /// full (back-pressure).
    pub backpressure_cycles: u64,
    /// Cycles with every quad of the open tile rasterized, waiting for the
    /// tile barrier.
    pub barrier_cycles: u64,
    /// Cycles with no tile open while tiles remained (the cycle after a
    /// barrier, and a blocking flush).
    pub between_tiles_cycles: u64,
    /// Colour-buffer lines written to main memory.
    pub flush_lines: u64,
}

/// What the raster pipeline did in a cycle.
#[derive(Clone, Copy, Debug)]
pub struct RasterCycle {
    /// The tile it opened, if any.
    pub opened: Option<u32>,
    /// It made progress: a line written, a tile opened, a quad
    /// rasterized.
    pub progress: bool,
}

/// The shared raster pipeline.
#[derive(Debug)]
pub struct SharedRaster {
    rate: u32,
    /// Early-Z-rejected quads one slot disposes of.
    rejected_per_slot: u32,
    map: CoreMapTable,
    flush_mode: ColorFlush,
    /// The open tile.
    tile: Option<usize>,
    next_tile: usize,
    /// The end of the frame's tiles: none at or past it is opened
    /// (`usize::MAX`: the trace's end).
    end: usize,
    /// Where the rasterizer is in the open tile.
    cursor: RasterCursor,
    /// The core whose full input queue refused the quad at the cursor
    /// (back-pressure): the quad is offered again only once that queue has
    /// room, since until then the core refuses it (`CoreModel::input_full`)
    /// and nothing else of the rasterizer can move.
    waiting_on: Option<usize>,
    /// Colour-buffer lines still to write, oldest tile's first (a tile's
    /// flush may still run when the next tile closes).
    flush: VecDeque<u64>,
    stats: RasterStats,
    /// What the pipeline did in the last cycle (for the waveform).
    signals: RasterSignals,
}

/// Per-cycle signals of the raster pipeline.
#[derive(Clone, Copy, Debug, Default)]
struct RasterSignals {
    /// Surviving quads sent to a core.
    sent: u32,
    /// Early-Z-rejected quads.
    rejected: u32,
    /// Waiting on a full input FIFO.
    backpressure: bool,
    /// A colour-buffer line written.
    flushed: bool,
}

impl SharedRaster {
    /// The same pipeline disposing of `k` (>= 1) Early-Z-rejected quads per
    /// raster slot (`raster.rejected_per_slot`).
    pub fn with_rejected_per_slot(mut self, k: u32) -> Self {
        self.rejected_per_slot = k.max(1);
        self
    }

    /// A pipeline with no tile open.
    pub fn new(rate: u32, map: CoreMapTable, flush_mode: ColorFlush) -> Self {
        SharedRaster {
            rate,
            rejected_per_slot: 1,
            map,
            flush_mode,
            tile: None,
            next_tile: 0,
            end: usize::MAX,
            cursor: RasterCursor::default(),
            waiting_on: None,
            flush: VecDeque::new(),
            stats: RasterStats::default(),
            signals: RasterSignals::default(),
        }
    }

    /// The open tile, if any.
    pub fn tile(&self) -> Option<usize> {
        self.tile
    }

    /// Start a frame: its tiles `tiles` are opened in order, the counters
    /// start from zero. The pipeline must be [`done`](Self::done) with
    /// the previous frame.
    pub fn start_frame(&mut self, tiles: std::ops::Range<usize>) {
        self.next_tile = tiles.start;
        self.end = tiles.end;
        self.stats = RasterStats::default();
    }

    /// Every tile before `tiles` rendered and its colour buffer flushed.
    pub fn done(&self, tiles: usize) -> bool {
        self.tile.is_none() && self.next_tile >= tiles && self.flush.is_empty()
    }

    /// The counters.
    pub fn stats(&self) -> &RasterStats {
        &self.stats
    }

    /// The surviving quads of the open tile (indices in rasterization
    /// order) placed in input FIFOs in the last evaluated cycle.
    pub fn placed_now(&self) -> std::ops::Range<u32> {
        self.cursor.next - self.signals.sent..self.cursor.next
    }

    /// The core the map names for in-tile quad (x, y).
    #[inline]
    pub fn core_of(&self, x: u32, y: u32) -> usize {
        self.map.core(x, y)
    }

    /// Phase 1 of cycle `now`: flush a line, open a tile if none is open,
    /// rasterize.
    pub fn evaluate<C: CoreModel>(
        &mut self,
        now: u64,
        trace: &Trace,
        cores: &mut [C],
        mem: &mut MemorySystem,
    ) -> RasterCycle {
        self.signals = RasterSignals::default();
        let mut progress = false;
        if let Some(block) = self.flush.pop_front() {
            self.signals.flushed = true;
            mem.write_back(now, block);
            self.stats.flush_lines += 1;
            progress = true;
        }
        let tiles = trace.tiles();
        let mut opened = None;
        if self.tile.is_none() {
            let may_open = self.flush_mode != ColorFlush::Blocking || self.flush.is_empty();
            if self.next_tile >= tiles.len().min(self.end) {
                return RasterCycle {
                    opened: None,
                    progress,
                };
            }
            if !may_open {
                self.stats.between_tiles_cycles += 1;
                return RasterCycle {
                    opened: None,
                    progress,
                };
            }
            let t = self.next_tile;
            self.next_tile += 1;
            self.tile = Some(t);
            self.cursor = RasterCursor::start(&tiles[t]);
            self.waiting_on = None;
            for c in cores.iter_mut() {
                c.begin_shared_tile(t);
            }
            opened = Some(t as u32);
            progress = true;
        }
        let t = self.tile.expect("a tile is open");
        progress |= self.rasterize(&tiles[t], cores);
        RasterCycle { opened, progress }
    }

    /// Rasterize up to the rate; whether a quad was rasterized.
    fn rasterize<C: CoreModel>(&mut self, tile: &Tile, cores: &mut [C]) -> bool {
        let mut budget = self.rate;
        if self.cursor.done() {
            self.stats.barrier_cycles += 1;
            return false;
        }
        if let Some(c) = self.waiting_on {
            // Still refused: the cycle is one more of back-pressure, as the
            // offer below would find.
            if cores[c].input_full() {
                self.stats.backpressure_cycles += 1;
                self.signals.backpressure = true;
                return false;
            }
            self.waiting_on = None;
        }
        let before = self.stats.quads_rasterized;
        while budget > 0 {
            let k = self
                .cursor
                .reject(budget.saturating_mul(self.rejected_per_slot));
            if k > 0 {
                budget -= k.div_ceil(self.rejected_per_slot);
                self.stats.quads_rasterized += u64::from(k);
                self.stats.quads_rejected += u64::from(k);
                self.signals.rejected += k;
                continue;
            }
            let Some(i) = self.cursor.peek() else {
                break;
            };
            let q = tile.quad(i as usize).expect("quad in tile");
            let core = self.map.core(q.x(), q.y());
            if !cores[core].push_quad(i, q.x(), q.y()) {
                self.waiting_on = Some(core);
                self.stats.backpressure_cycles += 1;
                self.signals.backpressure = true;
                break;
            }
            self.signals.sent += 1;
            self.cursor.advance(tile);
            budget -= 1;
            self.stats.quads_rasterized += 1;
        }
        self.stats.quads_rasterized != before
    }

    /// After the cores' end of cycle: close the open tile if every quad is
    /// rasterized and every core has drained it (the barrier), and queue
    /// its colour-buffer flush. Returns the closed tile.
    #[inline]
    pub fn end_cycle<C: CoreModel>(&mut self, trace: &Trace, cores: &mut [C]) -> Option<usize> {
        let t = self.tile?;
        if !self.cursor.done() || !cores.iter().all(|c| c.drained()) {
            return None;
        }
        Some(self.close(t, trace, cores))
    }

    /// Close tile `t` (the barrier passed).
    #[inline(never)]
    fn close<C: CoreModel>(&mut self, t: usize, trace: &Trace, cores: &mut [C]) -> usize {
        for c in cores.iter_mut() {
            c.end_shared_tile();
        }
        self.tile = None;
        if self.flush_mode != ColorFlush::None {
            flush_lines(trace, t, &mut self.flush);
        }
        t
    }
}

impl Traceable for SharedRaster {
    /// `tile` (the open tile's index + 1, 0 for none), `quad` (the next
    /// quad to rasterize), `sent` and `rejected` (quads this cycle),
    /// `backpressure` (waiting on a full input FIFO), `flush_left` (colour
    /// lines still to write) and `flushed` (a line written this cycle).
    fn trace<T: Tracer + ?Sized>(&self, t: &mut T) {
        t.signal(
            "tile",
            32,
            self.tile.map_or(0, |x| x as u64 + 1) & 0xffff_ffff,
        );
        t.signal("quad", 32, u64::from(self.cursor.next));
        let w = (u32::BITS - self.rate.leading_zeros()).max(1);
        t.signal("sent", w, u64::from(self.signals.sent));
        t.signal("rejected", w, u64::from(self.signals.rejected));
        t.bit("backpressure", self.signals.backpressure);
        t.signal("flush_left", 16, self.flush.len().min(0xffff) as u64);
        t.bit("flushed", self.signals.flushed);
    }
}

/// Append to `out` the 64-byte frame-buffer lines of tile `t`'s pixels
/// inside the frame, in address order (4 bytes a pixel, the frame
/// row-major from [`FRAME_BUFFER_BLOCK`], each row starting on a line: the
/// pitch is the row rounded up to 64 bytes).
fn flush_lines(trace: &Trace, t: usize, out: &mut VecDeque<u64>) {
    let h = trace.header();
    let tile = &trace.tiles()[t];
    let size = u64::from(h.tile);
    let (fw, fh) = (u64::from(h.frame_w), u64::from(h.frame_h));
    let (x0, y0) = (u64::from(tile.tx()) * size, u64::from(tile.ty()) * size);
    let (x1, y1) = ((x0 + size).min(fw), (y0 + size).min(fh));
    let pitch = (fw * 4).div_ceil(64) * 64;
    for y in y0..y1 {
        let row = y * pitch;
        let first = (row + x0 * 4) / 64;
        let last = (row + x1 * 4 - 1) / 64;
        out.extend((first..=last).map(|line| FRAME_BUFFER_BLOCK + line));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::trace::TraceHeader;

    fn one_tile(frame: (u32, u32), tile: (u32, u32)) -> Trace {
        let mut b = Trace::builder(TraceHeader::new("t", frame.0, frame.1, 64)).unwrap();
        b.begin_tile(tile.0, tile.1).unwrap();
        b.quad(0, 0, &[crate::trace::Instr::Alu(1)]).unwrap();
        b.end_tile().unwrap();
        b.finish().unwrap()
    }

    #[test]
    fn a_full_tile_flushes_256_lines_in_address_order() {
        let t = one_tile((1960, 768), (1, 2));
        let mut v = VecDeque::new();
        flush_lines(&t, 0, &mut v);
        assert_eq!(v.len(), 64 * 4);
        let v: Vec<u64> = v.into();
        // Row 128 of the frame, pixels 64..128: bytes 256..512 of the row
        // (7840 bytes of pixels, a pitch of 7872).
        let row = 128 * 7872;
        assert_eq!(v[0], FRAME_BUFFER_BLOCK + (row + 256) / 64);
        assert!(v.windows(2).all(|w| w[0] < w[1]));
        // A second tile's lines go behind the first's.
        let mut q = VecDeque::from(v.clone());
        flush_lines(&t, 0, &mut q);
        assert_eq!(q.len(), 512);
        assert_eq!(q[256], v[0]);
    }

    #[test]
    fn an_edge_tile_flushes_only_its_pixels_in_the_frame() {
        // 1960 = 30 x 64 + 40: the last tile column is 40 pixels wide
        // (160 bytes a row, starting 64-byte aligned: 3 lines a row);
        // 768 rows = 12 tiles exactly.
        let t = one_tile((1960, 768), (30, 11));
        let mut v = VecDeque::new();
        flush_lines(&t, 0, &mut v);
        assert_eq!(v.len(), 64 * 3);
        // A 100x10 frame: its first tile holds 64x10 pixels, 256 bytes a
        // row (4 lines) in a pitch of 448 (7 lines).
        let t = one_tile((100, 10), (0, 0));
        v.clear();
        flush_lines(&t, 0, &mut v);
        assert_eq!(v.len(), 40);
        assert_eq!(v[4], FRAME_BUFFER_BLOCK + 7, "row 1 starts on line 7");
    }
}
