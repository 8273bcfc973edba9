//! Where a rasterizer is in a tile's rasterization order, and one cycle of
//! a core's own rasterizer (per-core-tile dispatch). The shared raster
//! pipeline (`raster.rs`) walks its open tile with the same cursor.

use crate::trace::Tile;

/// A rasterizer's place in a tile's rasterization order: the next
/// surviving quad, and the Early-Z-rejected quads still to rasterize before
/// it (or, past the last quad, at the tile's end). Both the shared
/// rasterizer and a core's own (per-core-tile dispatch) walk a tile with
/// it.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct RasterCursor {
    /// Next surviving quad.
    pub(crate) next: u32,
    /// Surviving quads of the tile.
    quads: u32,
    /// Rejected quads before `next`.
    gap: u32,
}

impl RasterCursor {
    /// At the start of `tile`.
    pub(crate) fn start(tile: &Tile) -> Self {
        let quads = tile.quad_count() as u32;
        RasterCursor {
            next: 0,
            quads,
            gap: if quads > 0 {
                tile.rejected_before(0)
            } else {
                tile.rejected_after_last()
            },
        }
    }

    /// Rasterize up to `budget` rejected quads; returns how many.
    #[inline]
    pub(crate) fn reject(&mut self, budget: u32) -> u32 {
        let k = self.gap.min(budget);
        self.gap -= k;
        k
    }

    /// The next surviving quad, if no rejected quad comes first.
    #[inline]
    pub(crate) fn peek(&self) -> Option<u32> {
        (self.gap == 0 && self.next < self.quads).then_some(self.next)
    }

    /// The quad [`peek`](Self::peek) gave has been delivered.
    #[inline]
    pub(crate) fn advance(&mut self, tile: &Tile) {
        self.next += 1;
        self.gap = if self.next < self.quads {
            tile.rejected_before(self.next as usize)
        } else {
            tile.rejected_after_last()
        };
    }

    /// One cycle of a core's own rasterizer (per-core-tile dispatch): up
    /// to `slots` raster slots, each disposing of `rejected_per_slot`
    /// Early-Z-rejected quads (no warp) or delivering one surviving quad
    /// (index, in-tile x, y) through `push`, which returns `false` when the
    /// input queue refuses it (the rasterizer then waits). Adds the quads
    /// rasterized to `rasterized` and, of them, the rejected ones to
    /// `rejected`.
    #[inline(always)]
    pub(crate) fn own_cycle(
        &mut self,
        tile: &Tile,
        slots: u32,
        rejected_per_slot: u32,
        rasterized: &mut u64,
        rejected: &mut u64,
        mut push: impl FnMut(u32, u32, u32) -> bool,
    ) {
        let mut budget = slots;
        while budget > 0 {
            let k = self.reject(budget.saturating_mul(rejected_per_slot));
            if k > 0 {
                budget -= k.div_ceil(rejected_per_slot);
                *rasterized += u64::from(k);
                *rejected += u64::from(k);
                continue;
            }
            let Some(i) = self.peek() else {
                break;
            };
            let q = tile.quad(i as usize).expect("quad in tile");
            if !push(i, q.x(), q.y()) {
                break;
            }
            self.advance(tile);
            budget -= 1;
            *rasterized += 1;
        }
    }

    /// Every quad of the tile rasterized.
    #[inline]
    pub(crate) fn done(&self) -> bool {
        self.next >= self.quads && self.gap == 0
    }
}
