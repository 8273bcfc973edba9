//! Which pixels and quads a set-up triangle covers (edge functions with
//! the top-left rule, row spans), and the coarse per-quad depth bounds
//! the depth pre-pass tests against.

use super::*;

/// The coverage mask of the quad with top-left pixel (qx, qy): bit i for
/// pixel i (0 top-left, 1 top-right, 2 bottom-left, 3 bottom-right),
/// pixels at or beyond (xend, yend) or outside the triangle's bounding
/// box (its scissor rectangle) excluded.
#[inline]
pub(super) fn coverage(s: &Setup, qx: u32, qy: u32, xend: u32, yend: u32) -> u8 {
    let (xend, yend) = (xend.min(s.bbox[1]), yend.min(s.bbox[3]));
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
        let (px, py) = (qx + dx, qy + dy);
        if px >= xend || py >= yend || px < s.bbox[0] || py < s.bbox[2] {
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
/// in pixel row `row`, inside its bounding box (its scissor rectangle):
/// an inclusive range, empty when lo > hi. Exact: the same integer test as
/// [`coverage`], solved for x.
#[inline]
pub(super) fn row_cover(s: &Setup, row: u32) -> (i64, i64) {
    let cy = i64::from(row) * SUB + SUB / 2;
    if row < s.bbox[2] || row >= s.bbox[3] {
        return (1, 0);
    }
    let (mut lo, mut hi) = (i64::from(s.bbox[0]), i64::from(s.bbox[1]) - 1);
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

    /// Tile pixel (lx, ly) got a depth `z` farther than the one it had
    /// (only depth tests other than `<`, `<=`, `==` allow it): the block's
    /// bound is raised to stay an upper bound.
    #[inline]
    pub(super) fn raised(&mut self, lx: u32, ly: u32, z: f32) {
        let k = self.block(lx, ly);
        self.max[k] = self.max[k].max(z);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::fixtures::*;

    #[test]
    fn row_spans_hold_every_covered_quad() {
        // Triangles of every orientation and size, thin slivers included.
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = |m: f32| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 40) as f32 / (1u64 << 24) as f32 * m
        };
        let mut mesh = quad_mesh(0.0, 0.0, 1.0, 1.0, 0.0, 0);
        mesh.positions.clear();
        mesh.uv.clear();
        mesh.indices.clear();
        for t in 0..400u32 {
            let (cx, cy, r) = (
                next(96.0),
                next(96.0),
                next(if t % 4 == 0 { 4.0 } else { 60.0 }),
            );
            for _ in 0..3 {
                mesh.positions
                    .push([cx + next(2.0 * r) - r, cy + next(2.0 * r) - r, 0.0]);
                mesh.uv.push([0.0, 0.0]);
            }
            mesh.indices.extend([3 * t, 3 * t + 1, 3 * t + 2]);
        }
        let scene = ortho_scene(vec![mesh], vec![mat("m", Blend::Opaque, 0)], 96.0, 96.0);
        let mut stats = RasterStats {
            materials: vec![MaterialStats::default()],
            ..Default::default()
        };
        let runs = runs(&scene, DrawOrder::AsLoaded).0;
        let setups =
            geometry(&scene, &runs, 96, 96, &RasterOptions::default(), &mut stats).unwrap();
        assert!(setups.len() > 350);
        let (mut visited, mut full) = (0u64, 0u64);
        for s in &setups {
            let (x0, x1) = (s.bbox[0] & !1, s.bbox[1]);
            for qy in (s.bbox[2] & !1..s.bbox[3]).step_by(2) {
                let (a, b) = row_span(s, qy, x0, x1);
                assert!(a % 2 == 0 && x0 <= a && b <= x1.max(a));
                for qx in (x0..x1).step_by(2) {
                    full += 1;
                    if coverage(s, qx, qy, 96, 96) != 0 {
                        assert!(a <= qx && qx < b, "quad {qx},{qy} outside {a}..{b}");
                    }
                }
                visited += u64::from(b.saturating_sub(a).div_ceil(2));
            }
        }
        assert!(visited < full, "the spans skip quads: {visited} of {full}");
    }

    #[test]
    fn top_left_rule_shares_edges_exactly() {
        // A fan of 4 triangles around a centre, edges through pixel
        // centres (diagonals and the square's sides): every pixel once.
        let mut m = quad_mesh(0.5, 0.5, 40.5, 40.5, 0.0, 0);
        m.positions.push([20.5, 20.5, 0.0]);
        m.uv.push([0.5, 0.5]);
        m.indices = vec![4, 0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0];
        let scene = ortho_scene(vec![m], vec![mat("m", Blend::Opaque, 0)], 64.0, 64.0);
        let f = rasterize(&scene, 64, 64, &RasterOptions::default()).unwrap();
        assert_eq!(f.stats.pixels_shaded, 40 * 40);
    }

    #[test]
    fn coarse_depth_bounds_its_blocks() {
        let t = 16u32;
        let mut depth = vec![1.0f32; (t * t) as usize];
        let mut c = CoarseDepth::new(t);
        assert!(!c.hidden(&depth, 3, 1, 1.0), "a tie passes");
        assert!(c.hidden(&depth, 3, 1, 1.5));
        // Block (0..8, 0..2): all but one pixel nearer.
        for y in 0..2 {
            for x in 0..8 {
                if (x, y) != (7, 1) {
                    depth[(y * t + x) as usize] = 0.25;
                    c.wrote(x, y);
                }
            }
        }
        assert!(!c.hidden(&depth, 0, 0, 0.5), "pixel (7, 1) is still at 1");
        depth[(t + 7) as usize] = 0.5;
        c.wrote(7, 1);
        assert!(!c.hidden(&depth, 6, 1, 0.5), "tie with the farthest pixel");
        assert!(c.hidden(&depth, 6, 1, 0.51));
        // Other blocks keep their bounds.
        assert!(!c.hidden(&depth, 8, 0, 0.9));
        assert!(!c.hidden(&depth, 0, 2, 0.9));
        // A stale bound is still an upper bound; clear starts over.
        depth[0] = 0.1;
        assert!(c.hidden(&depth, 0, 0, 0.6));
        c.clear();
        assert!(!c.hidden(&depth, 0, 0, 0.6));
        // A tile edge that is not a multiple of the block width.
        let mut c = CoarseDepth::new(6);
        let depth = vec![0.5f32; 36];
        c.invalidate();
        assert!(c.hidden(&depth, 5, 5, 0.75));
        assert!(!c.hidden(&depth, 5, 5, 0.5));
    }

    #[test]
    fn covered_quads_and_depth_bounds_match_the_quad_by_quad_test() {
        let scene = random_scene(0x51ed_270b_3d9a_4c1f, 400);
        let mut stats = RasterStats {
            materials: vec![MaterialStats::default(); 3],
            ..Default::default()
        };
        let (w, h) = (150u32, 100u32);
        let runs = runs(&scene, DrawOrder::AsLoaded).0;
        let setups = geometry(&scene, &runs, w, h, &RasterOptions::default(), &mut stats).unwrap();
        assert!(setups.len() > 300);
        let mut covered = 0;
        for (k, s) in setups.iter().enumerate() {
            // Clip rectangles like a tile's, at odd edges too.
            let (xend, yend) = (w - (k as u32 % 3), h - (k as u32 % 5));
            let (x0, x1) = (s.bbox[0] & !1, s.bbox[1].min(xend));
            for qy in (s.bbox[2] & !1..s.bbox[3].min(yend)).step_by(2) {
                for seg in (x0..x1.max(x0)).step_by(8) {
                    let xb = (seg + 8).min(x1);
                    let want = (seg..xb)
                        .step_by(2)
                        .filter(|&qx| coverage(s, qx, qy, xend, yend) != 0)
                        .count() as u64;
                    let cover = [row_cover(s, qy), row_cover(s, qy + 1)];
                    assert_eq!(covered_quads(&cover, qy, seg, xb, xend, yend), want);
                    covered += want;
                    let (xl, yl) = ((xb + 1).min(xend - 1), (qy + 1).min(yend - 1));
                    let lb = depth_lower_bound(s, seg, xl, qy, yl);
                    for y in qy..=yl {
                        for x in seg..=xl {
                            let z = s.depth_at(f64::from(x) + 0.5, f64::from(y) + 0.5);
                            assert!(lb <= z, "bound {lb} above depth {z}");
                        }
                    }
                }
            }
        }
        assert!(covered > 1000);
    }
}
