//! Where a rasterizer is in a tile's rasterization order. The shared
//! raster pipeline (`raster.rs`) and a core's own rasterizer
//! (`core/raster.rs`, per-core-tile dispatch) walk a tile with it.

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

    /// Every quad of the tile rasterized.
    #[inline]
    pub(crate) fn done(&self) -> bool {
        self.next >= self.quads && self.gap == 0
    }
}
