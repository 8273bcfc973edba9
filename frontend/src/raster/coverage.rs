//! Which pixels and quads a set-up triangle covers (edge functions with
//! the top-left rule, row spans), and the coarse per-quad depth bounds
//! the depth pre-pass tests against.

use super::*;

/// The coverage mask of the quad with top-left pixel (qx, qy): bit i for
/// pixel i (0 top-left, 1 top-right, 2 bottom-left, 3 bottom-right),
/// pixels at or beyond (xend, yend) excluded.
#[inline]
pub(super) fn coverage(s: &Setup, qx: u32, qy: u32, xend: u32, yend: u32) -> u8 {
    let cx = i64::from(qx) * SUB + SUB / 2;
    let cy = i64::from(qy) * SUB + SUB / 2;
    let e = &s.edges;
    let base = [
        e[0][0] * cx + e[0][1] * cy + e[0][2],
        e[1][0] * cx + e[1][1] * cy + e[1][2],
        e[2][0] * cx + e[2][1] * cy + e[2][2],
    ];
    let mut mask = 0u8;
    for i in 0..4u32 {
        let (dx, dy) = (i & 1, i >> 1);
        if qx + dx >= xend || qy + dy >= yend {
            continue;
        }
        let (ox, oy) = (i64::from(dx) * SUB, i64::from(dy) * SUB);
        let inside = (0..3).all(|k| base[k] + e[k][0] * ox + e[k][1] * oy >= 0);
        mask |= u8::from(inside) << i;
    }
    mask
}

/// The pixel columns `x0..x1` (x0 even, a quad boundary) narrowed to the
/// quads a triangle can cover in the quad row starting at pixel row `qy`:
/// from each edge function, the range of pixel centres on or inside it in
/// either of the two rows, intersected over the edges, widened by a pixel
/// on each side. A superset of the covered quads ([`coverage`] decides
/// exactly), so the raster need not visit every quad of the bounding box.
#[inline]
pub(super) fn row_span(s: &Setup, qy: u32, x0: u32, x1: u32) -> (u32, u32) {
    span_of(&[row_cover(s, qy), row_cover(s, qy + 1)], x0, x1)
}

/// [`row_span`] from the two rows' covered ranges ([`row_cover`]).
#[inline]
pub(super) fn span_of(cover: &[(i64, i64); 2], x0: u32, x1: u32) -> (u32, u32) {
    let (mut lo, mut hi) = (i64::MAX, i64::MIN);
    for &(rlo, rhi) in cover {
        if rlo <= rhi {
            lo = lo.min(rlo);
            hi = hi.max(rhi);
        }
    }
    if lo > hi {
        return (x0, x0);
    }
    let start = lo.saturating_sub(1).clamp(i64::from(x0), i64::from(x1)) as u32 & !1;
    let end = hi.saturating_add(2).clamp(i64::from(x0), i64::from(x1)) as u32;
    (start.max(x0), end)
}

/// The pixel columns whose centres are on or inside all three edges of `s`
/// in pixel row `row`: an inclusive range, empty when lo > hi. Exact: the
/// same integer test as [`coverage`], solved for x.
#[inline]
pub(super) fn row_cover(s: &Setup, row: u32) -> (i64, i64) {
    let cy = i64::from(row) * SUB + SUB / 2;
    let (mut lo, mut hi) = (i64::MIN, i64::MAX);
    for e in &s.edges {
        let (a, v0) = (e[0], e[1] * cy + e[2]);
        // Inside at pixel x: a (x SUB + SUB/2) + v0 >= 0.
        let num = -v0 - a * (SUB / 2);
        if a > 0 {
            lo = lo.max(-((-num).div_euclid(a * SUB)));
        } else if a < 0 {
            hi = hi.min((-num).div_euclid(-a * SUB));
        } else if v0 < 0 {
            lo = i64::MAX;
        }
    }
    (lo, hi)
}

/// How many quads of the quad row starting at pixel row `qy`, with their
/// top-left pixel in columns `xa..xb` (xa even), [`coverage`] finds covered
/// (pixels at or beyond (xend, yend) excluded), from the exact covered
/// ranges of the two pixel rows (`cover`: [`row_cover`] of rows qy and
/// qy + 1) rather than quad by quad.
pub(super) fn covered_quads(
    cover: &[(i64, i64); 2],
    qy: u32,
    xa: u32,
    xb: u32,
    xend: u32,
    yend: u32,
) -> u64 {
    if xa >= xb {
        return 0;
    }
    // Quad k holds pixels 2k and 2k + 1; the segment holds quads ka..=kb.
    let (ka, kb) = (i64::from(xa / 2), i64::from((xb - 1) / 2));
    let quads = |(lo, hi): (i64, i64)| {
        let (lo, hi) = (lo.max(i64::from(xa)), hi.min(i64::from(xend) - 1));
        if lo > hi {
            return None;
        }
        let (a, b) = (lo.div_euclid(2).max(ka), hi.div_euclid(2).min(kb));
        (a <= b).then_some((a, b))
    };
    let top = quads(cover[0]);
    let bottom = if qy + 1 < yend { quads(cover[1]) } else { None };
    let len = |(a, b): (i64, i64)| (b - a + 1) as u64;
    match (top, bottom) {
        (None, None) => 0,
        (Some(r), None) | (None, Some(r)) => len(r),
        (Some(r), Some(q)) => {
            let common = (r.0.max(q.0), r.1.min(q.1));
            len(r) + len(q) - if common.0 <= common.1 { len(common) } else { 0 }
        }
    }
}

/// A lower bound of the depth [`Setup::depth_at`] gives at every pixel
/// centre of columns `xa..=xb` and rows `ya..=yb` (NaN if the plane is not
/// finite). The plane's minimum over the rectangle is at a corner; the
/// bound allows for the rounding of evaluating the plane in f64 (far more
/// than it can be), and rounding to f32 keeps the order.
#[inline]
pub(super) fn depth_lower_bound(s: &Setup, xa: u32, xb: u32, ya: u32, yb: u32) -> f32 {
    let p = &s.planes[0];
    let dx = |x: u32| f64::from(x) + 0.5 - s.origin[0];
    let dy = |y: u32| f64::from(y) + 0.5 - s.origin[1];
    let (dxa, dxb, dya, dyb) = (dx(xa), dx(xb), dy(ya), dy(yb));
    let x = if p[1] >= 0.0 { dxa } else { dxb };
    let y = if p[2] >= 0.0 { dya } else { dyb };
    let v = p[0] + p[1] * x + p[2] * y;
    let size =
        p[0].abs() + p[1].abs() * dxa.abs().max(dxb.abs()) + p[2].abs() * dya.abs().max(dyb.abs());
    (v - size * 1e-12) as f32
}

/// Hierarchical (coarse) depth of a tile: per block of
/// [`CoarseDepth::BLOCK_W`] x 2 pixels (the quads of one quad row in a
/// block column), an upper bound of the depths stored at its pixels. A
/// triangle whose depth is above a block's bound at every pixel fails the
/// early-Z test (`<=`) at every pixel of it, so its quads there are
/// rejected without testing them one by one. Depths only decrease, so the
/// bound stays an upper bound as they change; a block written since its
/// bound was computed is marked and recomputed only when the stale bound
/// fails to reject.
pub(super) struct CoarseDepth {
    /// Tile edge in pixels.
    pub(super) tile: u32,
    /// Blocks per block row.
    pub(super) cols: u32,
    /// Per block, an upper bound of its stored depths.
    pub(super) max: Vec<f32>,
    /// Per block, whether a depth changed since `max` was computed.
    pub(super) dirty: Vec<bool>,
}

impl CoarseDepth {
    /// Block width in pixels (even: whole quads).
    pub(super) const BLOCK_W: u32 = 8;

    pub(super) fn new(tile: u32) -> CoarseDepth {
        let cols = tile.div_ceil(Self::BLOCK_W);
        let n = (cols * tile.div_ceil(2)) as usize;
        CoarseDepth {
            tile,
            cols,
            max: vec![1.0; n],
            dirty: vec![false; n],
        }
    }

    /// Every depth back to 1 (a cleared depth buffer).
    pub(super) fn clear(&mut self) {
        self.max.fill(1.0);
        self.dirty.fill(false);
    }

    /// Every block recomputed before its next use (after writes not
    /// reported by [`CoarseDepth::wrote`]).
    pub(super) fn invalidate(&mut self) {
        self.dirty.fill(true);
    }

    /// The block of tile pixel (lx, ly).
    #[inline]
    pub(super) fn block(&self, lx: u32, ly: u32) -> usize {
        ((ly / 2) * self.cols + lx / Self::BLOCK_W) as usize
    }

    /// Tile pixel (lx, ly) got a new depth.
    #[inline]
    pub(super) fn wrote(&mut self, lx: u32, ly: u32) {
        let k = self.block(lx, ly);
        self.dirty[k] = true;
    }

    /// Whether a triangle whose depth is at least `z` at every pixel it
    /// covers in the block of tile pixel (lx, ly) fails the depth test at
    /// all of them against `depth` (the tile's depth buffer).
    #[inline]
    pub(super) fn hidden(&mut self, depth: &[f32], lx: u32, ly: u32, z: f32) -> bool {
        let k = self.block(lx, ly);
        if z > self.max[k] {
            return true;
        }
        if !self.dirty[k] {
            return false;
        }
        let (x0, y0) = (lx / Self::BLOCK_W * Self::BLOCK_W, ly / 2 * 2);
        let x1 = (x0 + Self::BLOCK_W).min(self.tile);
        let t = self.tile as usize;
        let mut m = f32::NEG_INFINITY;
        for y in y0..y0 + 2 {
            let row = y as usize * t;
            for &d in &depth[row + x0 as usize..row + x1 as usize] {
                m = m.max(d);
            }
        }
        self.max[k] = m;
        self.dirty[k] = false;
        z > m
    }
}
