//! The raster pipeline of one tile: its triangles rasterized into 2x2
//! quads in draw order, Early-Z against the tile's depth buffer (the
//! coarse, hierarchical test first), the texture blocks of every
//! surviving fragment, and the picture's colours (opaque ones shaded once
//! per visible pixel, blended fragments over them).

use super::*;

/// One surviving (triangle, quad) fragment of a tile.
#[derive(Clone, Copy, Debug)]
pub(super) struct Frag {
    /// Quad position in the tile: y * side + x.
    pub(super) pos: u32,
    pub(super) material: u32,
    /// First entry of the tile's block ranges for its texture instructions.
    pub(super) range: u32,
    /// Quads Early-Z rejected since the previous fragment (in
    /// rasterization order): the trace's `z` record before this warp.
    pub(super) rej: u32,
}

/// Per-shader facts the inner loop needs.
pub(super) struct MatInfo {
    /// Its pipeline state (its own, or what its blend mode means).
    pub(super) state: crate::DrawState,
    /// Texture instructions in program order.
    pub(super) tex: Vec<crate::TexSample>,
    /// The whole program.
    pub(super) shader: Vec<ShaderOp>,
}

/// What every tile's rasterization reads.
pub(super) struct TileCtx<'a> {
    pub(super) setups: &'a [Setup],
    pub(super) mats: &'a [MatInfo],
    pub(super) textures: &'a TextureSet<'a>,
    pub(super) tile: u32,
    pub(super) width: u32,
    pub(super) height: u32,
    pub(super) colour: bool,
    pub(super) prepass: bool,
    /// Reject quads by the tile's coarse depth before testing them one by
    /// one (the same results; off only to check that in tests).
    pub(super) hiz: bool,
    /// Record the per-pixel maps ([`PixelMaps`]).
    pub(super) maps: bool,
}

/// One tile's working state and results, reused from tile to tile.
pub(super) struct TileBuf {
    pub(super) depth: Vec<f32>,
    pub(super) colour: Vec<[f32; 4]>,
    pub(super) frags: Vec<Frag>,
    /// Per texture instruction: its blocks in `pool` (start, length) and
    /// whether it is trilinear (it read two mip levels).
    pub(super) ranges: Vec<(u32, u32, bool)>,
    pub(super) pool: Vec<u64>,
    pub(super) scratch: Vec<u64>,
    pub(super) covered: u64,
    pub(super) rejected: u64,
    /// Of `rejected`, those the coarse depth rejected.
    pub(super) rejected_hiz: u64,
    /// Quads rejected since the last surviving fragment (after the last
    /// one once the tile is done: the `z` record that ends the tile). It
    /// saturates, and the trace builder refuses more than a `z` record
    /// holds, so a count too large for the trace is an error, never a
    /// wrong count.
    pub(super) rej_since: u32,
    pub(super) pixels: u64,
    /// The depth buffer's coarse bounds.
    pub(super) coarse: CoarseDepth,
    /// Per material: fragments shaded (warps), quads rejected, pixels.
    pub(super) per_material: Vec<[u64; 3]>,
    /// Deferred colour: per pixel, 1 + the fragment whose colour the pixel
    /// shows (the last opaque or alpha-tested fragment written there), 0
    /// when the colour is already in `colour`; and that pixel's UVs.
    pub(super) pending: Vec<u32>,
    pub(super) pending_uv: Vec<[[f32; 2]; 2]>,
    /// Per fragment, the level of detail of each texture instruction.
    pub(super) lambdas: Vec<[f32; 8]>,
    /// Distinct quad positions of the fragments.
    pub(super) positions: u64,
    /// Per quad position, whether a fragment is there (all false between
    /// tiles).
    pub(super) seen: Vec<bool>,
    /// The tile's trace records (None: the tile rasterized no quad, so it
    /// has no record).
    pub(super) part: Result<Option<Trace>, crate::trace::Problem>,
    /// The tile's per-pixel maps (only when the context asks for them).
    pub(super) maps: Option<TileMaps>,
}

impl TileBuf {
    pub(super) fn new(tile: u32, materials: usize) -> TileBuf {
        TileBuf {
            depth: vec![1.0; (tile * tile) as usize],
            colour: vec![CLEAR; (tile * tile) as usize],
            frags: Vec::new(),
            ranges: Vec::new(),
            pool: Vec::new(),
            scratch: Vec::with_capacity(64),
            covered: 0,
            rejected: 0,
            rejected_hiz: 0,
            rej_since: 0,
            pixels: 0,
            coarse: CoarseDepth::new(tile),
            per_material: vec![[0; 3]; materials],
            pending: vec![0; (tile * tile) as usize],
            pending_uv: vec![[[0.0; 2]; 2]; (tile * tile) as usize],
            lambdas: Vec::new(),
            positions: 0,
            seen: vec![false; (tile / 2 * (tile / 2)) as usize],
            part: Ok(None),
            maps: None,
        }
    }

    /// Clear the buffers and counts for the next tile.
    fn reset(&mut self) {
        self.depth.fill(1.0);
        self.colour.fill(CLEAR);
        self.pending.fill(0);
        self.lambdas.clear();
        self.frags.clear();
        self.ranges.clear();
        self.pool.clear();
        self.covered = 0;
        self.rejected = 0;
        self.rejected_hiz = 0;
        self.rej_since = 0;
        self.coarse.clear();
        self.pixels = 0;
        self.per_material.iter_mut().for_each(|c| *c = [0; 3]);
    }

    /// Count a quad Early-Z rejected (of material `mc`).
    #[inline]
    fn reject(&mut self, mc: usize, n: u64) {
        self.rejected += n;
        self.rej_since = self.rej_since.saturating_add(n as u32);
        self.per_material[mc][1] += n;
    }

    /// Shades the deferred pixel `at`, if any, into `colour`.
    #[inline]
    pub(super) fn resolve(&mut self, ctx: &TileCtx, at: usize) {
        let f = self.pending[at];
        if f != 0 {
            let frag = (f - 1) as usize;
            let mat = &ctx.mats[self.frags[frag].material as usize];
            let [uv, uv2] = &self.pending_uv[at];
            let c = shade(ctx.textures, mat, uv, uv2, &self.lambdas[frag]);
            self.colour[at] = [c[0], c[1], c[2], 1.0];
            self.pending[at] = 0;
        }
    }
}

/// The pixels of one tile inside the frame: from (`ox`, `oy`) to
/// (`xend`, `yend`) exclusive, `tw` x `th` of the `t` x `t` tile.
#[derive(Clone, Copy, Debug)]
struct TileArea {
    t: u32,
    ox: u32,
    oy: u32,
    xend: u32,
    yend: u32,
    tw: u32,
    th: u32,
}

impl TileArea {
    fn new(ctx: &TileCtx, tx: u32, ty: u32) -> Self {
        let t = ctx.tile;
        let (ox, oy) = (tx * t, ty * t);
        let (tw, th) = (t.min(ctx.width - ox), t.min(ctx.height - oy));
        TileArea {
            t,
            ox,
            oy,
            xend: ox + tw,
            yend: oy + th,
            tw,
            th,
        }
    }

    /// The quads of a triangle inside the tile: (x0, x1, y0, y1), x0 and
    /// y0 aligned to quads.
    #[inline]
    fn span(&self, s: &Setup) -> (u32, u32, u32, u32) {
        (
            s.bbox[0].max(self.ox) & !1,
            s.bbox[1].min(self.xend),
            s.bbox[2].max(self.oy) & !1,
            s.bbox[3].min(self.yend),
        )
    }

    /// Index of frame pixel (`px`, `py`) in the tile's buffers.
    #[inline]
    fn at(&self, px: u32, py: u32) -> usize {
        ((py - self.oy) * self.t + px - self.ox) as usize
    }
}

/// Rasterize, early-Z test, texture and shade the triangles `list` of tile
/// (tx, ty) into `b`.
pub(super) fn raster_tile(ctx: &TileCtx, tx: u32, ty: u32, list: &[u32], b: &mut TileBuf) {
    let area = TileArea::new(ctx, tx, ty);
    b.reset();
    if ctx.maps {
        b.maps
            .get_or_insert_with(|| TileMaps::new(ctx.tile))
            .clear();
    }
    if ctx.prepass {
        depth_prepass(ctx, &area, list, b);
        b.coarse.invalidate();
    }
    let mut epoch = 0;
    for &si in list {
        let s = &ctx.setups[si as usize];
        let e = ctx.mats[s.material as usize].state.depth_epoch;
        if e != epoch {
            // The engine cleared the depth buffer since the last triangle.
            b.depth.fill(1.0);
            b.coarse.clear();
            epoch = e;
        }
        raster_triangle(ctx, &area, s, b);
    }
    if ctx.colour {
        for ly in 0..area.th {
            for lx in 0..area.tw {
                b.resolve(ctx, (ly * area.t + lx) as usize);
            }
        }
    }
}

/// Depth pre-pass (hidden-surface removal): the nearest opaque depth of
/// every pixel first, so only visible fragments survive early-Z.
fn depth_prepass(ctx: &TileCtx, a: &TileArea, list: &[u32], b: &mut TileBuf) {
    for &si in list {
        let s = &ctx.setups[si as usize];
        let st = &ctx.mats[s.material as usize].state;
        if !st.is_opaque() || !matches!(st.depth_test, Some(Compare::LEqual | Compare::Less)) {
            continue;
        }
        let (x0, x1, y0, y1) = a.span(s);
        for qy in (y0..y1).step_by(2) {
            let (rx0, rx1) = row_span(s, qy, x0, x1);
            for qx in (rx0..rx1).step_by(2) {
                let mask = coverage(s, qx, qy, a.xend, a.yend);
                for i in (0..4u32).filter(|i| mask & (1 << i) != 0) {
                    let (px, py) = (qx + (i & 1), qy + (i >> 1));
                    let z = s.depth_at(f64::from(px) + 0.5, f64::from(py) + 0.5);
                    let at = a.at(px, py);
                    b.depth[at] = b.depth[at].min(z);
                }
            }
        }
    }
}

/// Rasterize one triangle into the tile: its quad rows, each in segments
/// of one coarse-depth block, a segment the coarse depth hides rejected
/// whole, every other covered quad tested and shaded by [`raster_quad`].
#[inline]
fn raster_triangle(ctx: &TileCtx, a: &TileArea, s: &Setup, b: &mut TileBuf) {
    let mat = &ctx.mats[s.material as usize];
    let hiz = ctx.hiz && mat.state.depth_test.is_some_and(|c| c.fails_when_farther());
    let (x0, x1, y0, y1) = a.span(s);
    for qy in (y0..y1).step_by(2) {
        let cover = [row_cover(s, qy), row_cover(s, qy + 1)];
        let (rx0, rx1) = span_of(&cover, x0, x1);
        // The row in segments of one coarse-depth block each.
        let mut xa = rx0;
        while xa < rx1 {
            let xb =
                (a.ox + ((xa - a.ox) / CoarseDepth::BLOCK_W + 1) * CoarseDepth::BLOCK_W).min(rx1);
            let seg = (xa, xb);
            xa = xb;
            if hiz && coarse_reject(a, s, &cover, qy, seg, b) {
                continue;
            }
            for qx in (seg.0..seg.1).step_by(2) {
                let mask = coverage(s, qx, qy, a.xend, a.yend);
                if mask != 0 {
                    raster_quad(ctx, a, s, mat, (qx, qy), mask, b);
                }
            }
        }
    }
}

/// Hierarchical Z: whether the coarse depth hides the quads of segment
/// `seg` of quad row `qy` (of coverage `cover`); if so they are counted,
/// covered and rejected.
#[inline]
fn coarse_reject(
    a: &TileArea,
    s: &Setup,
    cover: &[(i64, i64); 2],
    qy: u32,
    seg: (u32, u32),
    b: &mut TileBuf,
) -> bool {
    let (xa, xb) = seg;
    // The segment's pixels span columns xa..xb (the last quad's second
    // pixel at xb when xb is odd) and rows qy, qy + 1, within the tile.
    let lb = depth_lower_bound(s, xa, xb.min(a.xend - 1), qy, (qy + 1).min(a.yend - 1));
    if !b.coarse.hidden(&b.depth, xa - a.ox, qy - a.oy, lb) {
        return false;
    }
    let n = covered_quads(cover, qy, xa, xb, a.xend, a.yend);
    b.covered += n;
    b.rejected_hiz += n;
    b.reject(s.material as usize, n);
    true
}

/// A fragment that survived early-Z: its quad, the pixels that passed
/// (`live`, with their depths), the UVs at the 4 pixel centres, each
/// texture instruction's level of detail and, for an alpha test, the
/// texels of the first one.
/// (References, so nothing large is copied per quad.)
struct Fragment<'f> {
    qx: u32,
    qy: u32,
    live: u8,
    z: &'f [f32; 4],
    uv: &'f [[f32; 2]; 4],
    uv2: &'f [[f32; 2]; 4],
    lambdas: &'f [f32; 8],
    texels: Option<&'f QuadTexels>,
    /// Its index in the tile's fragments.
    index: u32,
}

/// The quad at (`qx`, `qy`) of triangle `s`, whose pixels `mask` covers:
/// early-Z, then (if a pixel survives) its texture blocks, its fragment
/// and its pixels' depth and colour.
#[inline]
fn raster_quad(
    ctx: &TileCtx,
    a: &TileArea,
    s: &Setup,
    mat: &MatInfo,
    (qx, qy): (u32, u32),
    mask: u8,
    b: &mut TileBuf,
) {
    let mc = s.material as usize;
    b.covered += 1;
    // Early-Z on the covered pixels.
    let mut z = [0.0f32; 4];
    let mut live = 0u8;
    for i in (0..4u32).filter(|i| mask & (1 << i) != 0) {
        let (px, py) = (qx + (i & 1), qy + (i >> 1));
        z[i as usize] = s.depth_at(f64::from(px) + 0.5, f64::from(py) + 0.5);
        let pass = match mat.state.depth_test {
            Some(c) => c.passes(z[i as usize], b.depth[a.at(px, py)]),
            None => true,
        };
        if pass {
            live |= 1 << i;
        }
    }
    if live == 0 {
        b.reject(mc, 1);
        return;
    }
    let npix = u64::from(live.count_ones());
    b.pixels += npix;
    if let Some(m) = &mut b.maps {
        for i in (0..4u32).filter(|i| live & (1 << i) != 0) {
            let at = a.at(qx + (i & 1), qy + (i >> 1));
            m.shaded[at] = m.shaded[at].saturating_add(1);
        }
    }
    b.per_material[mc][0] += 1;
    b.per_material[mc][2] += npix;
    let (uv, uv2) = quad_uvs(s, mat, qx, qy);
    let first = b.ranges.len() as u32;
    let mut texels = None;
    let lambdas = texture_blocks(ctx, mat, &uv, &uv2, &mut texels, b);
    let index = b.frags.len() as u32;
    b.frags.push(Frag {
        pos: ((qy - a.oy) / 2) * (a.t / 2) + (qx - a.ox) / 2,
        material: s.material,
        range: first,
        rej: std::mem::take(&mut b.rej_since),
    });
    if ctx.colour {
        b.lambdas.push(lambdas);
    }
    let f = Fragment {
        qx,
        qy,
        live,
        z: &z,
        uv: &uv,
        uv2: &uv2,
        lambdas: &lambdas,
        texels: texels.as_ref(),
        index,
    };
    write_pixels(ctx, a, mat, &f, b);
}

/// UVs at all 4 pixel centres of quad (`qx`, `qy`), helper pixels
/// included (the second set only when a sample reads it).
#[inline]
fn quad_uvs(s: &Setup, mat: &MatInfo, qx: u32, qy: u32) -> ([[f32; 2]; 4], [[f32; 2]; 4]) {
    let mut uv = [[0.0f32; 2]; 4];
    let mut uv2 = [[0.0f32; 2]; 4];
    let with_uv2 = mat.tex.iter().any(|smp| smp.uv_set == 1);
    for i in 0..4u32 {
        let (px, py) = (qx + (i & 1), qy + (i >> 1));
        let (x, y) = (f64::from(px) + 0.5, f64::from(py) + 0.5);
        if with_uv2 {
            (uv[i as usize], uv2[i as usize]) = s.uvs_at(x, y);
        } else {
            uv[i as usize] = s.uv_at(x, y);
        }
    }
    (uv, uv2)
}

/// The quad's texture instructions: each one's blocks appended to the
/// tile's pool (with whether it read two mip levels), and its level of
/// detail; an alpha test also keeps in `texels` the texels its first
/// sample's blocks were found from (their alpha decides the test).
#[inline]
fn texture_blocks(
    ctx: &TileCtx,
    mat: &MatInfo,
    uv: &[[f32; 2]; 4],
    uv2: &[[f32; 2]; 4],
    texels: &mut Option<QuadTexels>,
    b: &mut TileBuf,
) -> [f32; 8] {
    let mut lambdas = [0.0f32; 8];
    let alpha_tested = mat.state.alpha_test.is_some();
    for (k, smp) in mat.tex.iter().enumerate() {
        let set = if smp.uv_set == 1 { uv2 } else { uv };
        let lambda = if k == 0 && alpha_tested {
            let q = texels.insert(QuadTexels::default());
            ctx.textures
                .quad_blocks_texels(smp, *set, &mut b.scratch, q)
        } else {
            ctx.textures.quad_blocks_lambda(smp, *set, &mut b.scratch)
        };
        if k < lambdas.len() {
            lambdas[k] = lambda;
        }
        // Trilinear in the trace: the sample filtered two mip levels (a
        // trilinear sample that magnifies or sits at the last level reads
        // one level: one bilinear pass).
        let tri = ctx.textures.reads_two_levels(smp, lambda);
        b.ranges
            .push((b.pool.len() as u32, b.scratch.len() as u32, tri));
        b.pool.extend_from_slice(&b.scratch);
    }
    lambdas
}

/// Depth writes and colour of a fragment's live pixels. A pixel the
/// alpha test fails writes nothing. An unblended pixel's colour is
/// deferred: only the last one written to a pixel shows, so it is shaded
/// once, when a blended fragment needs it as the destination or at the end
/// of the tile (same inputs, same colour as shading every fragment). A
/// blended pixel is shaded over what is there. Depth is written where the
/// state says so.
#[inline]
fn write_pixels(ctx: &TileCtx, a: &TileArea, mat: &MatInfo, f: &Fragment, b: &mut TileBuf) {
    let st = &mat.state;
    for i in (0..4u32).filter(|i| f.live & (1 << i) != 0) {
        let (px, py) = (f.qx + (i & 1), f.qy + (i >> 1));
        let at = a.at(px, py);
        let k = i as usize;
        if let Some((cmp, reference)) = st.alpha_test {
            // Without texture, alpha 1 (as `shade`).
            let alpha = f.texels.map_or(1.0, |q| ctx.textures.quad_alpha(q, k));
            if !cmp.passes(alpha, reference) {
                continue;
            }
        }
        if let Some(m) = &mut b.maps {
            m.written[at] = m.written[at].saturating_add(1);
            if st.colour_write {
                m.last[at] = b.frags[f.index as usize].material + 1;
            }
        }
        if ctx.colour && st.colour_write {
            match st.blend {
                Some((sf, df)) => {
                    b.resolve(ctx, at);
                    let c = shade(ctx.textures, mat, &f.uv[k], &f.uv2[k], f.lambdas);
                    let d = b.colour[at];
                    let mix = |j: usize| c[j] * sf.of(&c, &d, j) + d[j] * df.of(&c, &d, j);
                    b.colour[at] = [mix(0), mix(1), mix(2), 1.0];
                }
                None => {
                    b.pending[at] = f.index + 1;
                    b.pending_uv[at] = [f.uv[k], f.uv2[k]];
                }
            }
        }
        if st.depth_write {
            if f.z[k] > b.depth[at] {
                b.coarse.raised(px - a.ox, py - a.oy, f.z[k]);
            } else {
                b.coarse.wrote(px - a.ox, py - a.oy);
            }
            b.depth[at] = f.z[k];
        }
    }
}

/// The colour of one pixel: the product of its shader's texture samples,
/// alpha from the first.
#[inline]
fn shade(
    textures: &TextureSet,
    mat: &MatInfo,
    uv: &[f32; 2],
    uv2: &[f32; 2],
    lambdas: &[f32; 8],
) -> [f32; 4] {
    let mut c = [1.0f32; 4];
    for (k, smp) in mat.tex.iter().enumerate() {
        let at = if smp.uv_set == 1 { uv2 } else { uv };
        let lambda = lambdas.get(k).copied().unwrap_or(0.0);
        let s = textures.sample_rgba_of(smp, *at, lambda);
        c[0] *= s[0];
        c[1] *= s[1];
        c[2] *= s[2];
        if k == 0 {
            c[3] = s[3];
        }
    }
    if mat.tex.is_empty() {
        c = [0.7, 0.7, 0.7, 1.0];
    }
    c
}

#[cfg(test)]
mod tests;
