//! The core's own rasterizer (per-core-tile dispatch): each cycle up to its
//! share of `raster.quads_per_cycle` raster slots over the core's tile, in
//! its rasterization order. A slot disposes of `raster.rejected_per_slot`
//! Early-Z-rejected quads (which go nowhere) or delivers one surviving quad
//! to the input FIFOs; when the FIFO refuses it, the rasterizer waits.
//! (Under shared-tile dispatch the GPU's one rasterizer, `gpu/raster.rs`,
//! fills the FIFOs instead and this one stays idle.)

use super::CoreStats;
use crate::gpu::raster_cursor::RasterCursor;
use crate::trace::Tile;

/// A core's own rasterizer.
#[derive(Clone, Copy, Debug)]
pub(crate) struct OwnRaster {
    /// Where it is in the tile.
    cursor: RasterCursor,
    /// Raster slots a cycle.
    rate: u32,
    /// Early-Z-rejected quads one slot disposes of (>= 1).
    rejected_per_slot: u32,
}

impl OwnRaster {
    /// A rasterizer of `rate` slots a cycle, each disposing of
    /// `rejected_per_slot` rejected quads, with no tile.
    pub(crate) fn new(rate: u32, rejected_per_slot: u32) -> Self {
        OwnRaster {
            cursor: RasterCursor::default(),
            rate,
            rejected_per_slot: rejected_per_slot.max(1),
        }
    }

    /// Start on `tile`.
    pub(crate) fn start(&mut self, tile: &Tile) {
        self.cursor = RasterCursor::start(tile);
    }

    /// Surviving quads of the tile delivered so far.
    pub(crate) fn delivered(&self) -> u32 {
        self.cursor.next
    }

    /// Every quad of the tile rasterized.
    #[inline]
    pub(crate) fn is_idle(&self) -> bool {
        self.cursor.done()
    }

    /// One cycle on `tile`: each surviving quad (index, in-tile x, y) goes
    /// to `accept`, which returns `false` when the FIFO refuses it. Counts
    /// the quads in `stats`; returns whether any was rasterized.
    #[inline(always)]
    pub(crate) fn run(
        &mut self,
        tile: &Tile,
        stats: &mut CoreStats,
        mut accept: impl FnMut(u32, u32, u32) -> bool,
    ) -> bool {
        let before = stats.quads_rasterized;
        let mut budget = self.rate;
        let per_slot = self.rejected_per_slot;
        let c = &mut self.cursor;
        while budget > 0 {
            let k = c.reject(budget.saturating_mul(per_slot));
            if k > 0 {
                budget -= k.div_ceil(per_slot);
                stats.quads_rasterized += u64::from(k);
                stats.quads_rejected += u64::from(k);
                continue;
            }
            let Some(i) = c.peek() else {
                break;
            };
            let q = tile.quad(i as usize).expect("quad in tile");
            if !accept(i, q.x(), q.y()) {
                break;
            }
            c.advance(tile);
            budget -= 1;
            stats.quads_rasterized += 1;
        }
        stats.quads_rasterized != before
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::trace::{Instr, Trace, TraceHeader};

    /// One 8x8-pixel tile: `rejected[i]` rejected quads before surviving
    /// quad `i`, then `after` at the end.
    fn tile(rejected: &[u32], after: u32) -> Trace {
        let mut b = Trace::builder(TraceHeader::new("raster", 8, 8, 8)).unwrap();
        b.begin_tile(0, 0).unwrap();
        for (i, &r) in rejected.iter().enumerate() {
            if r > 0 {
                b.rejected(r).unwrap();
            }
            b.quad(i as u32 % 4, i as u32 / 4, &[Instr::Alu(1)])
                .unwrap();
        }
        if after > 0 {
            b.rejected(after).unwrap();
        }
        b.end_tile().unwrap();
        b.finish().unwrap()
    }

    /// Per cycle, the quads delivered, until the tile is done.
    fn cycles(t: &Trace, rate: u32, per_slot: u32, room: &[usize]) -> Vec<Vec<u32>> {
        let tile = &t.tiles()[0];
        let mut r = OwnRaster::new(rate, per_slot);
        let mut stats = CoreStats::default();
        r.start(tile);
        let mut out = vec![];
        for &room in room {
            let mut got = vec![];
            let before = stats.quads_rasterized;
            let progress = r.run(tile, &mut stats, |i, _, _| {
                (got.len() < room).then(|| got.push(i)).is_some()
            });
            assert_eq!(progress, stats.quads_rasterized > before);
            out.push(got);
            if r.is_idle() {
                break;
            }
        }
        assert!(r.is_idle());
        assert_eq!(
            stats.quads_rasterized,
            t.quad_count() as u64 + t.rejected_count()
        );
        out
    }

    #[test]
    fn a_slot_takes_a_quad_or_its_share_of_rejected_ones() {
        // Two slots a cycle; 3 rejected quads before quad 1, one slot each.
        let t = tile(&[0, 3, 0], 0);
        assert_eq!(cycles(&t, 2, 1, &[9; 9]), [vec![0], vec![], vec![1, 2]]);
        // Four rejected quads a slot: the 3 take one slot.
        assert_eq!(cycles(&t, 2, 4, &[9; 9]), [vec![0], vec![1, 2]]);
        // Rejected quads after the last one keep the tile open.
        let t = tile(&[0], 5);
        assert_eq!(cycles(&t, 2, 1, &[9; 9]), [vec![0], vec![], vec![]]);
    }

    #[test]
    fn a_full_fifo_makes_it_wait() {
        let t = tile(&[0, 0, 0], 0);
        assert_eq!(
            cycles(&t, 4, 1, &[1, 0, 0, 2]),
            [vec![0], vec![], vec![], vec![1, 2]]
        );
    }
}
