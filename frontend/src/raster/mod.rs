//! The TBR front end (the paper's Section II): geometry, tiling engine and
//! raster pipeline up to the shader cores, producing the cycle model's
//! [`Trace`] and the picture of the frame.
//!
//! # Pipeline
//!
//! 1. **Geometry**: every triangle of every mesh is transformed to clip
//!    space (a perspective camera: OpenGL-style look-at view and projection
//!    with the frame's aspect ratio; an orthographic camera: its rectangle
//!    onto the frame, depth from the layer `z`, larger `z` nearer). A
//!    triangle entirely outside one frustum plane is culled. Triangles
//!    crossing the near or far plane, or a guard band of 8x the viewport
//!    (which keeps fixed-point coordinates small), are clipped in
//!    homogeneous space (Sutherland-Hodgman, attributes interpolated
//!    linearly in clip space) and fan-triangulated. Back-face culling is
//!    off by default ([`RasterOptions::cull_back_faces`]: front faces are
//!    counter-clockwise in normalized device coordinates, OpenGL's default),
//!    because the loaders do not all know the games' face culling state.
//! 2. **Setup**: screen positions are snapped to 1/256 pixel; edge
//!    functions are exact 64-bit integers; attributes (depth, 1/w, u/w,
//!    v/w, u2/w, v2/w) are planes in screen space.
//! 3. **Tiling engine**: each triangle is binned to every 64x64 tile its
//!    edges overlap (the polygon list: one index list per tile, in draw
//!    order). Tiles are visited in Z-order (Morton order of tile x, y);
//!    a tile that rasterizes no quad is skipped (one whose every quad
//!    Early-Z rejects is kept: a tile record without warps).
//! 4. **Raster pipeline, per tile**: draw order is the opaque and
//!    alpha-tested triangles in submission order, then the alpha-blended
//!    ones back to front (perspective: by the mean clip-space w of their
//!    vertices, farthest first, ties in submission order; orthographic:
//!    submission order, which loaders give back to front, the painter's
//!    order of 2D games). Each triangle is rasterized into 2x2 quads,
//!    pixel centres inside by the top-left fill rule. Early-Z with the
//!    tile's depth buffer (test `<=`, so a later triangle at the same
//!    depth wins, as painter's order wants): opaque triangles write the
//!    depth of their surviving pixels, alpha-tested ones of the pixels
//!    their alpha test keeps (alpha >= 0.5), alpha-blended ones are tested
//!    but write nothing and so never hide what is behind them. A quad with
//!    no surviving pixel launches no warp: the trace records it where it
//!    was rasterized, as a rejected quad (a `z` record of trace format 4;
//!    every quad counted in [`RasterStats::quads_rejected_early_z`] is
//!    there exactly once). UVs are interpolated
//!    perspective-correctly at all 4 pixel centres, helper pixels outside
//!    the triangle included (they feed the derivatives and take part in
//!    the texture fetch, as in hardware).
//!
//! # Overdraw: one warp per fragment
//!
//! As in hardware, every surviving (triangle, quad) fragment is its own
//! warp, running its material's shader program. A tile's warps are emitted
//! (trace format 4) in rasterization order, the order the rasterizer hands
//! them to the shader core: triangles in draw order (above), each
//! triangle's quads in scanline order, with the count of quads Early-Z
//! rejected between two warps (and after the last) where they fall in that
//! order, since each costs the rasterizer a slot. Where triangles overlap, a quad
//! position therefore holds several warps ([`RasterStats::warps`] vs
//! [`RasterStats::positions`]: the overdraw the shader core sees, also
//! written as a header note of the trace). Early-Z decides which fragments
//! survive, so a fragment hidden by one drawn *earlier* is never shaded,
//! but one hidden by a later triangle is (`--depth-prepass` removes those
//! too, as a deferred renderer would).
//!
//! # Picture
//!
//! Each surviving pixel's colour is the product of its shader's texture
//! samples (base colour modulated by a lightmap), filtered as the texture
//! instruction says with the quad's level of detail; alpha comes from the
//! first sample. Alpha-tested pixels with alpha below 0.5 are discarded;
//! alpha-blended ones are blended over (`src * a + dst * (1 - a)`).
//!
//! # Speed
//!
//! Tiles are independent: worker threads ([`RasterOptions::threads`]) take
//! them one at a time and build their trace records; the results are
//! joined in Z-order, so the trace and picture never depend on the thread
//! count. Each quad row of a triangle visits only the span its edges allow.
//! Hierarchical Z, as TBR hardware has it: per block of 8x2 pixels (the
//! quads of a quad row in a block column) the tile keeps an upper bound of
//! its stored depths, recomputed lazily after writes; a triangle whose
//! nearest depth over the block is farther than that bound fails the
//! depth test at every pixel there, so its quads in the block are rejected
//! (and counted, exactly, from the edges' covered ranges) without testing
//! them one by one ([`RasterStats::quads_rejected_hiz`]; the results, the
//! trace's rejected quads included, are the same as testing every quad).
//! Opaque and alpha-tested colours are shaded once per pixel, for the
//! fragment that ends up visible (when a blended fragment needs the colour
//! below it, or at the end of the tile), not once per fragment; the alpha
//! test reads an alpha-only copy of its texture. Mip chains are built in
//! parallel, only for textures a set-up triangle samples (the others keep
//! their heap layout). [`Frame::timings`] says where the time went (`wasp
//! render --timings`).

use super::texture::{QuadTexels, TextureSet, TextureUse};
use super::{Blend, Camera, Scene, SceneError, ShaderOp, Vec3};
use crate::trace::{Trace, TraceHeader};
use serde::Serialize;

mod coverage;
mod frame;
mod setup;

use coverage::*;
pub use frame::*;
use setup::*;

/// Sub-pixel bits of the fixed-point screen coordinates.
const SUBPIXEL_BITS: u32 = 8;
const SUB: i64 = 1 << SUBPIXEL_BITS;
/// Guard band: triangles are clipped to `|x|, |y| <= GUARD * w`.
const GUARD: f64 = 8.0;
/// Colour of pixels no triangle covers.
const CLEAR: [f32; 4] = [0.08, 0.09, 0.12, 1.0];

/// One surviving (triangle, quad) fragment of a tile.
#[derive(Clone, Copy, Debug)]
struct Frag {
    /// Quad position in the tile: y * side + x.
    pos: u32,
    material: u32,
    /// First entry of the tile's block ranges for its texture instructions.
    range: u32,
    /// Quads Early-Z rejected since the previous fragment (in
    /// rasterization order): the trace's `z` record before this warp.
    rej: u32,
}

/// Per-shader facts the inner loop needs.
struct MatInfo {
    blend: Blend,
    /// Texture instructions in program order.
    tex: Vec<super::TexSample>,
    /// The whole program.
    shader: Vec<ShaderOp>,
}

/// What every tile's rasterization reads.
struct TileCtx<'a> {
    setups: &'a [Setup],
    mats: &'a [MatInfo],
    textures: &'a TextureSet<'a>,
    tile: u32,
    width: u32,
    height: u32,
    colour: bool,
    prepass: bool,
    /// Reject quads by the tile's coarse depth before testing them one by
    /// one (the same results; off only to check that in tests).
    hiz: bool,
}

/// One tile's working state and results, reused from tile to tile.
struct TileBuf {
    depth: Vec<f32>,
    colour: Vec<[f32; 4]>,
    frags: Vec<Frag>,
    /// Per texture instruction: its blocks in `pool` (start, length) and
    /// whether it is trilinear (it read two mip levels).
    ranges: Vec<(u32, u32, bool)>,
    pool: Vec<u64>,
    scratch: Vec<u64>,
    covered: u64,
    rejected: u64,
    /// Of `rejected`, those the coarse depth rejected.
    rejected_hiz: u64,
    /// Quads rejected since the last surviving fragment (after the last
    /// one once the tile is done: the `z` record that ends the tile). It
    /// saturates, and the trace builder refuses more than a `z` record
    /// holds, so a count too large for the trace is an error, never a
    /// wrong count.
    rej_since: u32,
    pixels: u64,
    /// The depth buffer's coarse bounds.
    coarse: CoarseDepth,
    /// Per material: fragments shaded (warps), quads rejected, pixels.
    per_material: Vec<[u64; 3]>,
    /// Deferred colour: per pixel, 1 + the fragment whose colour the pixel
    /// shows (the last opaque or alpha-tested fragment written there), 0
    /// when the colour is already in `colour`; and that pixel's UVs.
    pending: Vec<u32>,
    pending_uv: Vec<[[f32; 2]; 2]>,
    /// Per fragment, the level of detail of each texture instruction.
    lambdas: Vec<[f32; 8]>,
    /// Distinct quad positions of the fragments.
    positions: u64,
    /// Per quad position, whether a fragment is there (all false between
    /// tiles).
    seen: Vec<bool>,
    /// The tile's trace records (None: the tile rasterized no quad, so it
    /// has no record).
    part: Result<Option<Trace>, crate::trace::Problem>,
}

impl TileBuf {
    fn new(tile: u32, materials: usize) -> TileBuf {
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
        }
    }

    /// Shades the deferred pixel `at`, if any, into `colour`.
    #[inline]
    fn resolve(&mut self, ctx: &TileCtx, at: usize) {
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

/// Rasterize, early-Z test, texture and shade the triangles `list` of tile
/// (tx, ty) into `b`.
fn raster_tile(ctx: &TileCtx, tx: u32, ty: u32, list: &[u32], b: &mut TileBuf) {
    let t = ctx.tile;
    let (ox, oy) = (tx * t, ty * t);
    let (tw, th) = (t.min(ctx.width - ox), t.min(ctx.height - oy));
    let (xend, yend) = (ox + tw, oy + th);
    let side = t / 2;
    b.depth.fill(1.0);
    b.colour.fill(CLEAR);
    b.pending.fill(0);
    b.lambdas.clear();
    b.frags.clear();
    b.ranges.clear();
    b.pool.clear();
    b.covered = 0;
    b.rejected = 0;
    b.rejected_hiz = 0;
    b.rej_since = 0;
    b.coarse.clear();
    b.pixels = 0;
    b.per_material.iter_mut().for_each(|c| *c = [0; 3]);
    // The quads of a triangle inside the tile: (x0, x1, y0, y1), x0 and
    // y0 aligned to quads.
    let span = |s: &Setup| {
        (
            s.bbox[0].max(ox) & !1,
            s.bbox[1].min(xend),
            s.bbox[2].max(oy) & !1,
            s.bbox[3].min(yend),
        )
    };
    if ctx.prepass {
        // Depth pre-pass (hidden-surface removal): the nearest opaque depth
        // of every pixel first, so only visible fragments survive early-Z.
        for &si in list {
            let s = &ctx.setups[si as usize];
            if ctx.mats[s.material as usize].blend != Blend::Opaque {
                continue;
            }
            let (x0, x1, y0, y1) = span(s);
            for qy in (y0..y1).step_by(2) {
                let (rx0, rx1) = row_span(s, qy, x0, x1);
                for qx in (rx0..rx1).step_by(2) {
                    let mask = coverage(s, qx, qy, xend, yend);
                    for i in (0..4u32).filter(|i| mask & (1 << i) != 0) {
                        let (px, py) = (qx + (i & 1), qy + (i >> 1));
                        let z = s.depth_at(f64::from(px) + 0.5, f64::from(py) + 0.5);
                        let at = ((py - oy) * t + px - ox) as usize;
                        b.depth[at] = b.depth[at].min(z);
                    }
                }
            }
        }
    }
    if ctx.prepass {
        b.coarse.invalidate();
    }
    for &si in list {
        let s = &ctx.setups[si as usize];
        let mat = &ctx.mats[s.material as usize];
        let mc = s.material as usize;
        let (x0, x1, y0, y1) = span(s);
        for qy in (y0..y1).step_by(2) {
            let cover = [row_cover(s, qy), row_cover(s, qy + 1)];
            let (rx0, rx1) = span_of(&cover, x0, x1);
            // The row in segments of one coarse-depth block each.
            let mut xa = rx0;
            while xa < rx1 {
                let xb =
                    (ox + ((xa - ox) / CoarseDepth::BLOCK_W + 1) * CoarseDepth::BLOCK_W).min(rx1);
                let seg = (xa, xb);
                xa = xb;
                if ctx.hiz {
                    // Hierarchical Z: the segment's pixels span columns
                    // seg.0..xb (the last quad's second pixel at xb when
                    // xb is odd) and rows qy, qy + 1, within the tile.
                    let lb =
                        depth_lower_bound(s, seg.0, xb.min(xend - 1), qy, (qy + 1).min(yend - 1));
                    if b.coarse.hidden(&b.depth, seg.0 - ox, qy - oy, lb) {
                        let n = covered_quads(&cover, qy, seg.0, xb, xend, yend);
                        b.covered += n;
                        b.rejected += n;
                        b.rejected_hiz += n;
                        b.rej_since = b.rej_since.saturating_add(n as u32);
                        b.per_material[mc][1] += n;
                        continue;
                    }
                }
                for qx in (seg.0..seg.1).step_by(2) {
                    let mask = coverage(s, qx, qy, xend, yend);
                    if mask == 0 {
                        continue;
                    }
                    b.covered += 1;
                    // Early-Z on the covered pixels.
                    let mut z = [0.0f32; 4];
                    let mut live = 0u8;
                    for i in (0..4u32).filter(|i| mask & (1 << i) != 0) {
                        let (px, py) = (qx + (i & 1), qy + (i >> 1));
                        z[i as usize] = s.depth_at(f64::from(px) + 0.5, f64::from(py) + 0.5);
                        if z[i as usize] <= b.depth[((py - oy) * t + px - ox) as usize] {
                            live |= 1 << i;
                        }
                    }
                    if live == 0 {
                        b.rejected += 1;
                        b.rej_since = b.rej_since.saturating_add(1);
                        b.per_material[mc][1] += 1;
                        continue;
                    }
                    let npix = u64::from(live.count_ones());
                    b.pixels += npix;
                    b.per_material[mc][0] += 1;
                    b.per_material[mc][2] += npix;
                    // UVs at all 4 pixel centres (helper pixels included).
                    let mut uv = [[0.0f32; 2]; 4];
                    let mut uv2 = [[0.0f32; 2]; 4];
                    // (uv2 only when a sample reads it.)
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
                    // Texture instructions: the quad's blocks.
                    let first = b.ranges.len() as u32;
                    let mut lambdas = [0.0f32; 8];
                    // An alpha test reads the first sample's alpha at the
                    // texels its blocks were found from.
                    let alpha_tested = mat.blend == Blend::AlphaTest;
                    let mut texels = None;
                    for (k, smp) in mat.tex.iter().enumerate() {
                        let set = if smp.uv_set == 1 { &uv2 } else { &uv };
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
                        // Trilinear in the trace: the sample filtered two mip
                        // levels (a trilinear sample that magnifies or sits
                        // at the last level reads one level: one bilinear
                        // pass).
                        let tri = ctx.textures.reads_two_levels(smp, lambda);
                        b.ranges
                            .push((b.pool.len() as u32, b.scratch.len() as u32, tri));
                        b.pool.extend_from_slice(&b.scratch);
                    }
                    let frag = b.frags.len() as u32;
                    b.frags.push(Frag {
                        pos: ((qy - oy) / 2) * side + (qx - ox) / 2,
                        material: s.material,
                        range: first,
                        rej: std::mem::take(&mut b.rej_since),
                    });
                    if ctx.colour {
                        b.lambdas.push(lambdas);
                    }
                    // Depth writes and colour. An opaque or alpha-tested pixel's
                    // colour is deferred: only the last one written to a pixel
                    // shows, so it is shaded once, when a blended fragment needs
                    // it as the destination or at the end of the tile (same
                    // inputs, same colour as shading every fragment).
                    for i in (0..4u32).filter(|i| live & (1 << i) != 0) {
                        let (px, py) = (qx + (i & 1), qy + (i >> 1));
                        let at = ((py - oy) * t + px - ox) as usize;
                        let k = i as usize;
                        let write = match mat.blend {
                            Blend::Opaque => true,
                            Blend::AlphaTest => {
                                // Without texture, alpha 1 (as `shade`).
                                texels
                                    .as_ref()
                                    .map_or(1.0, |q| ctx.textures.quad_alpha(q, k))
                                    >= 0.5
                            }
                            Blend::AlphaBlend => {
                                if ctx.colour {
                                    b.resolve(ctx, at);
                                    let c = shade(ctx.textures, mat, &uv[k], &uv2[k], &lambdas);
                                    let d = b.colour[at];
                                    let a = c[3];
                                    b.colour[at] = [
                                        c[0] * a + d[0] * (1.0 - a),
                                        c[1] * a + d[1] * (1.0 - a),
                                        c[2] * a + d[2] * (1.0 - a),
                                        1.0,
                                    ];
                                }
                                false
                            }
                        };
                        if write {
                            b.depth[at] = z[k];
                            b.coarse.wrote(px - ox, py - oy);
                            if ctx.colour {
                                b.pending[at] = frag + 1;
                                b.pending_uv[at] = [uv[k], uv2[k]];
                            }
                        }
                    }
                }
            }
        }
    }
    if ctx.colour {
        for ly in 0..th {
            for lx in 0..tw {
                b.resolve(ctx, (ly * t + lx) as usize);
            }
        }
    }
}

/// The trace records of the tile `b` holds: one warp per fragment, in
/// rasterization order (the order [`raster_tile`] produced them), as a
/// one-tile trace with `header`'s frame; counts its quad positions.
fn build_tile(
    ctx: &TileCtx,
    header: &TraceHeader,
    tx: u32,
    ty: u32,
    b: &mut TileBuf,
) -> Result<Option<Trace>, crate::trace::Problem> {
    b.positions = 0;
    if b.frags.is_empty() && b.rej_since == 0 {
        return Ok(None);
    }
    let side = ctx.tile / 2;
    let mut builder = Trace::builder(header.clone())?;
    builder.begin_tile(tx, ty)?;
    let entries: usize = b
        .frags
        .iter()
        .map(|f| ctx.mats[f.material as usize].shader.len())
        .sum();
    builder.reserve(b.frags.len(), entries, b.pool.len());
    for f in &b.frags {
        if !b.seen[f.pos as usize] {
            b.seen[f.pos as usize] = true;
            b.positions += 1;
        }
        if f.rej > 0 {
            builder.rejected(f.rej)?;
        }
        builder.begin_quad(f.pos % side, f.pos / side)?;
        let mut r = f.range as usize;
        for op in &ctx.mats[f.material as usize].shader {
            match op {
                ShaderOp::Alu(0) => {}
                ShaderOp::Alu(n) => builder.alu(*n)?,
                ShaderOp::Tex(_) => {
                    let (start, len, tri) = b.ranges[r];
                    r += 1;
                    builder.tex_filtered(&b.pool[start as usize..(start + len) as usize], tri)?;
                }
            }
        }
    }
    for f in &b.frags {
        b.seen[f.pos as usize] = false;
    }
    if b.rej_since > 0 {
        builder.rejected(b.rej_since)?;
    }
    builder.end_tile()?;
    builder.finish().map(Some)
}

/// Rasterize `scene` into a `width` x `height` frame.
pub fn rasterize(
    scene: &Scene,
    width: u32,
    height: u32,
    opts: &RasterOptions,
) -> Result<Frame, SceneError> {
    rasterize_with(scene, width, height, opts, true)
}

/// [`rasterize`], with or without the hierarchical depth test (`hiz`; the
/// results are the same, [`RasterStats::quads_rejected_hiz`] aside).
fn rasterize_with(
    scene: &Scene,
    width: u32,
    height: u32,
    opts: &RasterOptions,
    hiz: bool,
) -> Result<Frame, SceneError> {
    let fail = |m: String| SceneError::in_file(&scene.name, m);
    if width == 0 || height == 0 || width > 16384 || height > 16384 {
        return Err(fail(format!(
            "frame {width}x{height}: expected 1 to 16384 pixels each"
        )));
    }
    if opts.tile < 2 || !opts.tile.is_multiple_of(2) || opts.tile > 512 {
        return Err(fail(format!(
            "tile {}: expected an even size from 2 to 512",
            opts.tile
        )));
    }
    validate(scene)?;
    let mut stats = RasterStats {
        materials: scene
            .materials
            .iter()
            .map(|m| MaterialStats {
                name: m.name.clone(),
                blend: format!("{:?}", m.blend).to_lowercase(),
                ..Default::default()
            })
            .collect(),
        ..Default::default()
    };
    let clock = std::time::Instant::now();
    let mut timings = RasterTimings::default();
    let threads = match opts.threads {
        0 => std::thread::available_parallelism().map_or(1, |n| n.get()),
        n => n,
    }
    .clamp(1, 64);
    let setups = geometry(scene, width, height, opts, &mut stats)?;
    timings.geometry = clock.elapsed().as_secs_f64();
    // Textures: only those of materials a set-up triangle uses are sampled;
    // an alpha test reads its material's first texture's alpha.
    let tex_clock = std::time::Instant::now();
    let mut uses = vec![
        TextureUse {
            sampled: false,
            alpha_tested: false,
        };
        scene.textures.len()
    ];
    let mut used_mat = vec![false; scene.materials.len()];
    for s in &setups {
        used_mat[s.material as usize] = true;
    }
    for (m, _) in scene.materials.iter().zip(&used_mat).filter(|(_, &u)| u) {
        let mut first = true;
        for op in &m.shader {
            if let ShaderOp::Tex(s) = op {
                uses[s.texture].sampled = true;
                uses[s.texture].alpha_tested |= first && m.blend == Blend::AlphaTest;
                first = false;
            }
        }
    }
    let textures = TextureSet::with_threads(&scene.textures, threads, &uses);
    timings.textures = tex_clock.elapsed().as_secs_f64();
    let mats: Vec<MatInfo> = scene
        .materials
        .iter()
        .map(|m| {
            let tex: Vec<_> = m
                .shader
                .iter()
                .filter_map(|op| match op {
                    ShaderOp::Tex(s) => Some(*s),
                    ShaderOp::Alu(_) => None,
                })
                .collect();
            MatInfo {
                blend: m.blend,
                tex,
                shader: m.shader.clone(),
            }
        })
        .collect();

    // Tiling engine: polygon lists.
    let t = opts.tile;
    let (tiles_x, tiles_y) = (width.div_ceil(t), height.div_ceil(t));
    let mut lists: Vec<Vec<u32>> = vec![Vec::new(); (tiles_x * tiles_y) as usize];
    for (i, s) in setups.iter().enumerate() {
        let [x0, x1, y0, y1] = s.bbox;
        for ty in y0 / t..=(y1 - 1) / t {
            for tx in x0 / t..=(x1 - 1) / t {
                let (tx0, ty0) = ((tx * t).max(x0), (ty * t).max(y0));
                let (tx1, ty1) = (((tx + 1) * t).min(x1), ((ty + 1) * t).min(y1));
                if overlaps(s, tx0, tx1, ty0, ty1) {
                    lists[(ty * tiles_x + tx) as usize].push(i as u32);
                    stats.bin_entries += 1;
                }
            }
        }
    }

    // Geometry includes the binning.
    timings.geometry = clock.elapsed().as_secs_f64() - timings.textures;

    // Raster pipeline, tile by tile in Z-order; tiles are independent, so
    // batches of them run on worker threads and are emitted in order.
    let mut header = TraceHeader::new(scene.name.clone(), width, height, t);
    header
        .notes
        .push(format!(" scene {} ({})", scene.name, scene.source));
    let mut builder = Trace::builder(header).map_err(|e| fail(format!("trace header: {e}")))?;
    let mut image = vec![0u8; width as usize * height as usize * 4];
    for px in image.chunks_exact_mut(4) {
        px.copy_from_slice(&to_u8(CLEAR));
    }
    let ctx = TileCtx {
        setups: &setups,
        mats: &mats,
        textures: &textures,
        tile: t,
        width,
        height,
        colour: opts.colour,
        prepass: opts.depth_prepass,
        hiz,
    };
    let order: Vec<(u32, u32)> = crate::trace::z_order(tiles_x, tiles_y)
        .into_iter()
        .filter(|&(tx, ty)| !lists[(ty * tiles_x + tx) as usize].is_empty())
        .collect();
    // Tiles are handed out one at a time (costs vary a lot), each worker
    // building its tile's trace records too; results are used in order.
    let batch = threads * 16;
    let bufs: Vec<std::sync::Mutex<TileBuf>> = (0..batch.min(order.len().max(1)))
        .map(|_| std::sync::Mutex::new(TileBuf::new(t, scene.materials.len())))
        .collect();
    let part_header = builder.header().clone();
    for chunk in order.chunks(batch) {
        let next = std::sync::atomic::AtomicUsize::new(0);
        let work = || loop {
            let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            let Some(&(tx, ty)) = chunk.get(i) else {
                break;
            };
            let mut b = bufs[i].lock().unwrap_or_else(|e| e.into_inner());
            raster_tile(&ctx, tx, ty, &lists[(ty * tiles_x + tx) as usize], &mut b);
            b.part = build_tile(&ctx, &part_header, tx, ty, &mut b);
        };
        if threads > 1 && chunk.len() > 1 {
            std::thread::scope(|sc| {
                for _ in 1..threads.min(chunk.len()) {
                    sc.spawn(work);
                }
                work();
            });
        } else {
            work();
        }
        for (&(tx, ty), b) in chunk.iter().zip(&bufs) {
            let mut b = b.lock().unwrap_or_else(|e| e.into_inner());
            stats.quads_covered += b.covered;
            stats.quads_rejected_early_z += b.rejected;
            stats.quads_rejected_hiz += b.rejected_hiz;
            stats.warps += b.frags.len() as u64;
            stats.positions += b.positions;
            stats.pixels_shaded += b.pixels;
            for (m, c) in stats.materials.iter_mut().zip(&b.per_material) {
                m.warps += c[0];
                m.quads_rejected_early_z += c[1];
                m.pixels += c[2];
            }
            let (ox, oy) = (tx * t, ty * t);
            let (tw, th) = (t.min(width - ox), t.min(height - oy));
            if opts.colour {
                for ly in 0..th {
                    let row = ((oy + ly) * width + ox) as usize * 4;
                    for lx in 0..tw {
                        let c = to_u8(b.colour[(ly * t + lx) as usize]);
                        let at = row + lx as usize * 4;
                        image[at..at + 4].copy_from_slice(&c);
                    }
                }
            }
            let part = std::mem::replace(&mut b.part, Ok(None))
                .map_err(|e| fail(format!("building the trace: {e}")))?;
            if let Some(part) = part {
                stats.tiles += 1;
                builder
                    .append(part)
                    .map_err(|e| fail(format!("building the trace: {e}")))?;
            }
        }
    }
    let note = format!(
        " rasterized by wasp scene::raster: {} triangles ({} clipped, {} culled), {} quads \
         covered, {} rejected by early-Z, {} fragments shaded, one warp each in \
         rasterization order, at {} quad positions ({:.2} warps per position); texture heap \
         {} KiB at {:#x}, 4x4-texel 64-byte blocks in Morton order",
        stats.primitives,
        stats.clipped,
        stats.culled_outside + stats.culled_back_faces,
        stats.quads_covered,
        stats.quads_rejected_early_z,
        stats.warps,
        stats.positions,
        if stats.positions == 0 {
            0.0
        } else {
            stats.warps as f64 / stats.positions as f64
        },
        textures.heap_bytes() / 1024,
        super::texture::HEAP_BASE
    );
    builder
        .note(note)
        .map_err(|e| fail(format!("trace note: {e}")))?;
    let trace = builder
        .finish()
        .map_err(|e| fail(format!("building the trace: {e}")))?;
    timings.tiles = clock.elapsed().as_secs_f64() - timings.textures - timings.geometry;
    Ok(Frame {
        trace,
        width,
        height,
        image,
        stats,
        timings,
    })
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
        let s = textures.sample_rgba(smp.texture, smp.filter, *at, lambda);
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

fn to_u8(c: [f32; 4]) -> [u8; 4] {
    let q = |v: f32| (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
    [q(c[0]), q(c[1]), q(c[2]), q(c[3])]
}

/// Rasterize and time: (frame, seconds), for `wasp bench` and reports.
pub fn rasterize_timed(
    scene: &Scene,
    width: u32,
    height: u32,
    opts: &RasterOptions,
) -> Result<(Frame, f64), SceneError> {
    let start = std::time::Instant::now();
    let f = rasterize(scene, width, height, opts)?;
    Ok((f, start.elapsed().as_secs_f64()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Filter, Material, Mesh, TexSample, Texture};

    /// A camera at the origin looking down -z, y up.
    fn look_down_z(fov_y_deg: f32, near: f32, far: f32) -> Camera {
        Camera::Perspective {
            eye: [0.0, 0.0, 0.0],
            target: [0.0, 0.0, -1.0],
            up: [0.0, 1.0, 0.0],
            fov_y_deg,
            near,
            far,
        }
    }

    fn checker(name: &str, n: u32) -> Texture {
        let mut rgba = Vec::new();
        for y in 0..n {
            for x in 0..n {
                let v = if ((x / 4) + (y / 4)) % 2 == 0 {
                    230
                } else {
                    40
                };
                rgba.extend_from_slice(&[v, v, v, 255]);
            }
        }
        Texture {
            name: name.into(),
            width: n,
            height: n,
            rgba,
            repeat: true,
        }
    }

    fn mat(name: &str, blend: Blend, tex: usize) -> Material {
        Material {
            name: name.into(),
            blend,
            shader: crate::shader::standard(tex, Filter::Bilinear),
        }
    }

    fn quad_mesh(x0: f32, y0: f32, x1: f32, y1: f32, z: f32, material: usize) -> Mesh {
        Mesh {
            positions: vec![[x0, y0, z], [x1, y0, z], [x1, y1, z], [x0, y1, z]],
            uv: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            uv2: None,
            indices: vec![0, 1, 2, 0, 2, 3],
            material,
        }
    }

    fn ortho_scene(meshes: Vec<Mesh>, materials: Vec<Material>, w: f32, h: f32) -> Scene {
        Scene {
            name: "test:ortho".into(),
            source: "unit test".into(),
            meshes,
            materials,
            textures: vec![checker("c", 64)],
            camera: Camera::Ortho {
                left: 0.0,
                top: 0.0,
                width: w,
                height: h,
            },
        }
    }

    #[test]
    fn tiles_are_visited_in_z_order_and_empty_tiles_skipped() {
        // 256x192 frame: 4x3 tiles; the quad leaves tile (3, 2) empty.
        let scene = ortho_scene(
            vec![
                quad_mesh(0.0, 0.0, 256.0, 128.0, 0.0, 0),
                quad_mesh(0.0, 128.0, 192.0, 192.0, 0.0, 0),
            ],
            vec![mat("m", Blend::Opaque, 0)],
            256.0,
            192.0,
        );
        let f = rasterize(&scene, 256, 192, &RasterOptions::default()).unwrap();
        let got: Vec<(u32, u32)> = f.trace.tiles().iter().map(|t| (t.tx(), t.ty())).collect();
        let want: Vec<(u32, u32)> = crate::trace::z_order(4, 3)
            .into_iter()
            .filter(|&p| p != (3, 2))
            .collect();
        assert_eq!(got, want);
        assert_eq!(
            got[..5],
            [(0, 0), (1, 0), (0, 1), (1, 1), (2, 0)],
            "Morton order"
        );
        // Every tile is fully covered: 32x32 quad positions each, one warp
        // each but where a rectangle's diagonal crosses a quad: both of its
        // triangles shade a fragment there (each pixel exactly once).
        let mut extra = 0;
        for tile in f.trace.tiles() {
            assert_eq!(tile.position_count(), 1024);
            extra += tile.quad_count() - 1024;
        }
        assert_eq!(extra as u64, f.stats.warps - f.stats.positions);
        assert!(extra > 0);
        assert_eq!(f.stats.pixels_shaded, 256 * 128 + 192 * 64);
    }

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
        let setups = geometry(&scene, 96, 96, &RasterOptions::default(), &mut stats).unwrap();
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
    fn early_z_rejects_hidden_quads_but_blended_sprites_do_not() {
        // Perspective: a near opaque square drawn first hides a far one.
        let persp = |meshes: Vec<Mesh>, materials: Vec<Material>| Scene {
            name: "test:persp".into(),
            source: "unit test".into(),
            meshes,
            materials,
            textures: vec![checker("c", 64)],
            camera: look_down_z(60.0, 0.1, 100.0),
        };
        let near = quad_mesh(-5.0, -5.0, 5.0, 5.0, -2.0, 0);
        let far = quad_mesh(-1.0, -1.0, 1.0, 1.0, -10.0, 1);
        let scene = persp(
            vec![near.clone(), far.clone()],
            vec![mat("near", Blend::Opaque, 0), mat("far", Blend::Opaque, 0)],
        );
        let f = rasterize(&scene, 128, 128, &RasterOptions::default()).unwrap();
        assert!(f.stats.quads_rejected_early_z > 0);
        assert_eq!(
            f.stats.materials[1].quads_rejected_early_z,
            f.stats.quads_rejected_early_z
        );
        assert_eq!(f.stats.materials[1].warps, 0, "far square hidden");
        // The trace records every rejected quad where it was rasterized:
        // the far square is drawn last, so after each tile's warps.
        assert_eq!(f.trace.rejected_count(), f.stats.quads_rejected_early_z);
        for t in f.trace.tiles() {
            assert_eq!(u64::from(t.rejected_after_last()), t.rejected_count());
        }
        assert_eq!(f.stats.positions, 64 * 64);
        // The near square's two triangles share a diagonal: the 64 quads it
        // crosses hold one fragment of each, two warps.
        assert_eq!(f.stats.warps, f.stats.positions + 64);
        assert_eq!(f.trace.quad_count() as u64, f.stats.warps);
        assert_eq!(f.trace.stats().positions, f.stats.positions);
        // The same far square, but the near one alpha-blended: both shade.
        let scene = persp(
            vec![near, far],
            vec![
                mat("near", Blend::AlphaBlend, 0),
                mat("far", Blend::Opaque, 0),
            ],
        );
        let g = rasterize(&scene, 128, 128, &RasterOptions::default()).unwrap();
        assert_eq!(g.stats.quads_rejected_early_z, 0);
        let far_quads = g.stats.materials[1].warps;
        assert!(far_quads > 0);
        assert_eq!(g.stats.materials[0].warps, f.stats.warps);
        assert_eq!(g.stats.positions, 64 * 64);
        assert_eq!(g.stats.warps, f.stats.warps + far_quads);
        // Where the sprite covers the far square, the position holds two
        // warps of one 11-instruction program each (never merged): the far
        // square's first (opaque, drawn first), then the sprite's
        // (blended, drawn last).
        let tile = g
            .trace
            .tiles()
            .iter()
            .find(|t| t.tx() == 0 && t.ty() == 0)
            .unwrap();
        let at: Vec<_> = tile.quads_at(31, 31).collect();
        assert_eq!(at.len(), 2);
        for q in &at {
            assert_eq!((q.instr_count(), q.tex_count()), (11, 1));
        }
        assert!(at[0].index() < at[1].index());
    }

    #[test]
    fn warps_come_in_rasterization_order() {
        // Two overlapping opaque squares (orthographic, the second nearer):
        // the tile's warps are all quads of the first square's triangles in
        // scanline order per triangle, then the second square's.
        let scene = ortho_scene(
            vec![
                quad_mesh(0.0, 0.0, 16.0, 16.0, 0.0, 0),
                quad_mesh(8.0, 8.0, 24.0, 24.0, 1.0, 1),
            ],
            vec![mat("a", Blend::Opaque, 0), mat("b", Blend::Opaque, 0)],
            32.0,
            32.0,
        );
        let f = rasterize(&scene, 32, 32, &RasterOptions::default()).unwrap();
        let tile = &f.trace.tiles()[0];
        let pos: Vec<(u32, u32)> = tile.quads().map(|q| (q.x(), q.y())).collect();
        // Square a: 8x8 quads plus 8 on the shared diagonal; square b the
        // same, 16 of its positions over a's.
        assert_eq!(pos.len(), 2 * (64 + 8));
        assert_eq!(f.stats.positions, 64 + 64 - 16);
        // Each triangle's quads are in scanline order; where the order goes
        // back, a new triangle starts: 4 triangles, 4 runs.
        let runs = 1 + pos
            .windows(2)
            .filter(|w| (w[1].1, w[1].0) <= (w[0].1, w[0].0))
            .count();
        assert_eq!(runs, 4);
        // Square a's warps (quads 0..8) all come before square b's (4..12).
        assert!(pos[..72].iter().all(|&(x, y)| x < 8 && y < 8));
        let in_b = |v: u32| (4..12).contains(&v);
        assert!(pos[72..].iter().all(|&(x, y)| in_b(x) && in_b(y)));
        // Threads do not change the trace.
        for threads in [1, 3] {
            let g = rasterize(
                &scene,
                32,
                32,
                &RasterOptions {
                    threads,
                    ..RasterOptions::default()
                },
            )
            .unwrap();
            assert_eq!(g.trace.to_text(), f.trace.to_text());
        }
    }

    /// A tilted textured plane: y = -1, z from -1 to -20, uv = (x, -z).
    fn tilted() -> Scene {
        Scene {
            name: "test:tilted".into(),
            source: "unit test".into(),
            meshes: vec![Mesh {
                positions: vec![
                    [-10.0, -1.0, -1.0],
                    [10.0, -1.0, -1.0],
                    [10.0, -1.0, -20.0],
                    [-10.0, -1.0, -20.0],
                ],
                uv: vec![[-10.0, 1.0], [10.0, 1.0], [10.0, 20.0], [-10.0, 20.0]],
                uv2: None,
                indices: vec![0, 1, 2, 0, 2, 3],
                material: 0,
            }],
            materials: vec![mat("ground", Blend::Opaque, 0)],
            textures: vec![checker("c", 64)],
            camera: look_down_z(90.0, 0.1, 100.0),
        }
    }

    #[test]
    fn uvs_are_perspective_correct() {
        let scene = tilted();
        let (w, h) = (200u32, 200u32);
        let mut stats = RasterStats {
            materials: vec![MaterialStats::default()],
            ..Default::default()
        };
        let setups = geometry(&scene, w, h, &RasterOptions::default(), &mut stats).unwrap();
        // Analytic: the ray through pixel centre (px, py) of a 90-degree
        // camera at the origin hits y = -1 at t = 1 / -ndc_y, so
        // x = ndc_x * t, z = -t; the plane's uv = (x, -z).
        let mut checked = 0;
        for &(px, py) in &[(100u32, 150u32), (37, 120), (160, 190), (100, 101)] {
            let (x, y) = (f64::from(px) + 0.5, f64::from(py) + 0.5);
            let nx = x / f64::from(w) * 2.0 - 1.0;
            let ny = 1.0 - y / f64::from(h) * 2.0;
            let t = 1.0 / -ny;
            let want = [nx * t, t];
            if !(1.0..=20.0).contains(&t) || want[0].abs() > 10.0 {
                continue;
            }
            let s = setups
                .iter()
                .find(|s| {
                    let (cx, cy) = (i64::from(px) * SUB + SUB / 2, i64::from(py) * SUB + SUB / 2);
                    s.edges.iter().all(|e| e[0] * cx + e[1] * cy + e[2] >= 0)
                })
                .expect("covered");
            let (_, uv, _) = s.attributes(x, y);
            assert!(
                (f64::from(uv[0]) - want[0]).abs() < 1e-3 * t.max(1.0)
                    && (f64::from(uv[1]) - want[1]).abs() < 1e-3 * t.max(1.0),
                "pixel ({px},{py}): got {uv:?}, want {want:?}"
            );
            // Affine interpolation would be far off on this plane.
            checked += 1;
        }
        assert!(checked >= 3);
    }

    #[test]
    fn a_triangle_crossing_the_near_plane_is_clipped() {
        let a = ClipVert {
            p: [0.0, 0.0, -2.0, 0.5], // behind the near plane (z < -w)
            uv: [0.0, 0.0],
            uv2: [0.0, 0.0],
        };
        let b = ClipVert {
            p: [1.0, 0.0, 0.5, 1.0],
            uv: [1.0, 0.0],
            uv2: [0.0, 0.0],
        };
        let c = ClipVert {
            p: [0.0, 1.0, 0.5, 1.0],
            uv: [0.0, 1.0],
            uv2: [0.0, 0.0],
        };
        let (mut out, mut tmp) = (Vec::new(), Vec::new());
        assert!(clip_triangle([a, b, c], &mut out, &mut tmp));
        assert_eq!(out.len(), 4, "one vertex cut off: a quadrilateral");
        for v in &out {
            assert!(v.p[2] + v.p[3] >= -1e-12, "{v:?}");
        }
        // The ground plane extends behind the camera: it is clipped and
        // still rasterizes without NaNs, covering the bottom of the frame.
        let mut scene = tilted();
        scene.meshes[0].positions[0][2] = 5.0;
        scene.meshes[0].positions[1][2] = 5.0;
        let f = rasterize(&scene, 128, 64, &RasterOptions::default()).unwrap();
        assert!(f.stats.clipped >= 1);
        assert!(f.stats.warps > 0);
        // The bottom-left quad is covered.
        assert!(f.trace.tiles().iter().any(|t| t.tx() == 0 && t.ty() == 0));
        let img_bottom = &f.image[((63 * 128) * 4) as usize..((63 * 128 + 1) * 4) as usize];
        assert_ne!(img_bottom, to_u8(CLEAR));
    }

    #[test]
    fn alpha_tested_texels_below_half_write_no_depth() {
        let mut tex = checker("c", 8);
        for px in tex.rgba.chunks_exact_mut(4) {
            px[3] = 0; // fully cut out
        }
        let mut scene = ortho_scene(
            vec![
                quad_mesh(0.0, 0.0, 32.0, 32.0, 1.0, 0),
                quad_mesh(0.0, 0.0, 32.0, 32.0, 0.0, 1),
            ],
            vec![
                mat("cutout", Blend::AlphaTest, 0),
                mat("behind", Blend::Opaque, 0),
            ],
            32.0,
            32.0,
        );
        scene.textures = vec![tex];
        let f = rasterize(&scene, 32, 32, &RasterOptions::default()).unwrap();
        assert_eq!(f.stats.quads_rejected_early_z, 0);
        // 256 quads each, plus the 16 quads on each square's diagonal.
        assert_eq!(f.stats.materials[0].warps, 16 * 16 + 16);
        assert_eq!(f.stats.materials[1].warps, 16 * 16 + 16);
        assert_eq!(f.stats.positions, 16 * 16);
        assert_eq!(f.stats.warps, 2 * (16 * 16 + 16));
        // With an opaque texture the cut-out hides the square behind.
        for px in scene.textures[0].rgba.chunks_exact_mut(4) {
            px[3] = 255;
        }
        let g = rasterize(&scene, 32, 32, &RasterOptions::default()).unwrap();
        assert_eq!(g.stats.materials[1].warps, 0);
    }

    /// Timing of the front end on the procedural scenes at the paper's
    /// 1960x768 (a measurement, not a check: run with
    /// `cargo test --release -p wasp-sim raster_timing -- --ignored --nocapture`).
    #[test]
    #[ignore = "timing measurement; run in release with --ignored --nocapture"]
    fn raster_timing() {
        use crate::procedural;
        let scenes = [
            procedural::plane("ground", "standard").unwrap(),
            procedural::plane("ground", "lightmapped").unwrap(),
            procedural::sprites("full", 1960, 768).unwrap(),
        ];
        // CPU seconds of this process (user + system), from /proc (Linux):
        // the machine may be shared, so wall time alone misleads.
        fn cpu_seconds() -> f64 {
            let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
            let after = stat.rsplit_once(')').map_or("", |x| x.1);
            let f: Vec<f64> = after
                .split_whitespace()
                .map(|t| t.parse().unwrap_or(0.0))
                .collect();
            // Fields 14 and 15 (utime, stime) are the 12th and 13th after
            // the command name; clock ticks of 1/100 s.
            (f.get(11).copied().unwrap_or(0.0) + f.get(12).copied().unwrap_or(0.0)) / 100.0
        }
        for scene in &scenes {
            for (colour, threads) in [(false, 1), (true, 1), (false, 0), (true, 0)] {
                let opts = RasterOptions {
                    colour,
                    threads,
                    ..RasterOptions::default()
                };
                let cpu0 = cpu_seconds();
                let runs = 5;
                let best = (0..runs)
                    .map(|_| rasterize_timed(scene, 1960, 768, &opts).unwrap().1)
                    .fold(f64::INFINITY, f64::min);
                let cpu = (cpu_seconds() - cpu0) / f64::from(runs);
                println!(
                    "{:<24} colour {:<5} threads {:<4} wall best of {runs}: {:.3} s, CPU per run: {:.3} s",
                    scene.name,
                    colour,
                    if threads == 0 { "auto".to_string() } else { threads.to_string() },
                    best,
                    cpu
                );
            }
        }
    }

    #[test]
    fn bad_scenes_are_errors_not_panics() {
        let mut scene = ortho_scene(
            vec![quad_mesh(0.0, 0.0, 8.0, 8.0, 0.0, 0)],
            vec![mat("m", Blend::Opaque, 0)],
            8.0,
            8.0,
        );
        scene.meshes[0].indices.push(9);
        assert!(rasterize(&scene, 8, 8, &RasterOptions::default()).is_err());
        scene.meshes[0].indices.truncate(6);
        scene.materials[0].shader = vec![ShaderOp::Tex(TexSample {
            texture: 3,
            uv_set: 0,
            filter: Filter::Nearest,
        })];
        let e = rasterize(&scene, 8, 8, &RasterOptions::default()).unwrap_err();
        assert!(e.message.contains("texture 3"), "{e}");
    }

    /// A perspective scene of random triangles of every blend mode at
    /// random depths, with exact copies drawn again (depth ties) and a
    /// texture whose alpha test discards half the texels.
    fn random_scene(seed: u64, n: u32) -> Scene {
        let mut seed = seed;
        let mut next = |m: f32| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 40) as f32 / (1u64 << 24) as f32 * m
        };
        let mut tex = checker("c", 64);
        for px in tex.rgba.chunks_exact_mut(4) {
            px[3] = px[0];
        }
        let mut meshes: Vec<Mesh> = Vec::new();
        for t in 0..n {
            let material = (t % 5) as usize % 3;
            let mesh = if t % 7 == 6 && !meshes.is_empty() {
                // A copy of an earlier triangle: the same depths.
                let k = next(meshes.len() as f32) as usize % meshes.len();
                Mesh {
                    material,
                    ..meshes[k].clone()
                }
            } else {
                let (cx, cy, z, r) = (
                    next(16.0) - 8.0,
                    next(12.0) - 6.0,
                    -2.0 - next(30.0),
                    next(9.0),
                );
                let mut positions = Vec::new();
                for _ in 0..3 {
                    positions.push([
                        cx + next(2.0 * r) - r,
                        cy + next(2.0 * r) - r,
                        z + next(4.0) - 2.0,
                    ]);
                }
                Mesh {
                    positions,
                    uv: vec![[0.0, 0.0], [1.0, 0.0], [0.5, 1.0]],
                    uv2: None,
                    indices: vec![0, 1, 2],
                    material,
                }
            };
            meshes.push(mesh);
        }
        Scene {
            name: "test:random".into(),
            source: "unit test".into(),
            meshes,
            materials: vec![
                mat("opaque", Blend::Opaque, 0),
                mat("tested", Blend::AlphaTest, 0),
                mat("blended", Blend::AlphaBlend, 0),
            ],
            textures: vec![tex],
            camera: look_down_z(60.0, 0.5, 40.0),
        }
    }

    fn trace_bytes(f: &Frame) -> Vec<u8> {
        let mut out = Vec::new();
        f.trace.write(&mut out).unwrap();
        out
    }

    #[test]
    fn hierarchical_z_changes_no_result() {
        let mut rejected = 0;
        for (seed, (w, h), tile, prepass) in [
            (1u64, (200u32, 150u32), 64u32, false),
            (2, (200, 150), 64, true),
            (3, (97, 61), 10, false),
            (4, (128, 96), 6, false),
            (5, (130, 70), 16, true),
        ] {
            let scene = random_scene(0x9e37_79b9_7f4a_7c15 ^ seed, 300);
            let opts = RasterOptions {
                tile,
                depth_prepass: prepass,
                threads: 1,
                ..Default::default()
            };
            let fast = rasterize_with(&scene, w, h, &opts, true).unwrap();
            let slow = rasterize_with(&scene, w, h, &opts, false).unwrap();
            assert_eq!(slow.stats.quads_rejected_hiz, 0);
            assert!(fast.stats.quads_rejected_hiz <= fast.stats.quads_rejected_early_z);
            rejected += fast.stats.quads_rejected_hiz;
            assert_eq!(trace_bytes(&fast), trace_bytes(&slow), "seed {seed}");
            assert_eq!(
                fast.trace.rejected_count(),
                fast.stats.quads_rejected_early_z,
                "seed {seed}: every rejected quad is in the trace"
            );
            assert!(fast.image == slow.image, "seed {seed}: picture differs");
            let stats = RasterStats {
                quads_rejected_hiz: 0,
                ..fast.stats.clone()
            };
            assert_eq!(stats, slow.stats, "seed {seed}");
            assert!(
                slow.stats.quads_rejected_early_z > 0,
                "seed {seed}: no overdraw"
            );
        }
        assert!(rejected > 0, "the coarse test rejected nothing");
    }

    #[test]
    fn hidden_triangles_are_rejected_coarsely_and_visible_ones_are_not() {
        let persp = |meshes: Vec<Mesh>| Scene {
            name: "test:hiz".into(),
            source: "unit test".into(),
            meshes,
            materials: vec![
                mat("near", Blend::Opaque, 0),
                mat("far", Blend::Opaque, 0),
                mat("nearer", Blend::Opaque, 0),
                mat("tie", Blend::Opaque, 0),
            ],
            textures: vec![checker("c", 64)],
            camera: look_down_z(60.0, 0.1, 100.0),
        };
        // The near square fills the frame; the far one behind it is
        // hidden, the tie (the near square again: a later triangle at the
        // same depth wins) and then the nearer one in front are not.
        let near = quad_mesh(-5.0, -5.0, 5.0, 5.0, -2.0, 0);
        let far = quad_mesh(-1.0, -1.0, 1.0, 1.0, -10.0, 1);
        let nearer = quad_mesh(-0.5, -0.5, 0.5, 0.5, -1.5, 2);
        let tie = Mesh {
            material: 3,
            ..near.clone()
        };
        let scene = persp(vec![near, far, tie, nearer]);
        let f = rasterize(&scene, 128, 128, &RasterOptions::default()).unwrap();
        let m = &f.stats.materials;
        assert!(m[1].quads_rejected_early_z > 0);
        assert_eq!(m[1].warps, 0);
        assert!(m[2].warps > 0 && m[3].warps > 0);
        assert_eq!(m[2].quads_rejected_early_z, 0);
        assert_eq!(m[3].quads_rejected_early_z, 0);
        assert_eq!(m[3].warps, m[0].warps);
        assert_eq!(
            f.stats.quads_rejected_hiz, m[1].quads_rejected_early_z,
            "every hidden quad of the far square, nothing else, rejected coarsely"
        );
        let g = rasterize_with(&scene, 128, 128, &RasterOptions::default(), false).unwrap();
        assert_eq!(trace_bytes(&f), trace_bytes(&g));
        assert_eq!(
            g.stats.quads_rejected_early_z,
            f.stats.quads_rejected_early_z
        );
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
        let setups = geometry(&scene, w, h, &RasterOptions::default(), &mut stats).unwrap();
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

    #[test]
    fn procedural_scenes_record_every_rejected_quad_in_the_trace() {
        use crate::def::{Game, SceneDef};
        use crate::procedural;
        let (w, h) = (320, 192);
        let mut rejected = 0;
        for map in procedural::MAPS {
            let def = SceneDef {
                name: format!("procedural-{map}"),
                game: Game::Procedural,
                map: map.into(),
                camera: if map == "plane" { "ground" } else { "full" }.into(),
                width: w,
                height: h,
                description: String::new(),
                shader: None,
            };
            let scene = procedural::load(&def).unwrap();
            for depth_prepass in [false, true] {
                let opts = RasterOptions {
                    colour: false,
                    depth_prepass,
                    ..RasterOptions::default()
                };
                let f = rasterize(&scene, w, h, &opts).unwrap();
                let what = format!("{map}, prepass {depth_prepass}");
                let want = f.stats.quads_rejected_early_z;
                // Every rejected quad (coarse ones included) is in the
                // trace once: with the warps, every covered quad.
                assert_eq!(f.trace.rejected_count(), want, "{what}");
                assert_eq!(f.trace.stats().rejected_quads, want, "{what}");
                let produced: u64 = f.trace.tiles().iter().map(|t| t.raster_count()).sum();
                assert_eq!(produced, f.stats.quads_covered, "{what}");
                assert_eq!(f.stats.warps + want, f.stats.quads_covered, "{what}");
                assert_eq!(f.trace.tiles().len() as u64, f.stats.tiles, "{what}");
                // Written as format 4 and read back, each stays in place.
                let back = Trace::parse(&f.trace.to_text(), "rt").unwrap();
                assert_eq!(back, f.trace, "{what}");
                rejected += want;
            }
        }
        assert!(rejected > 0, "no procedural scene rejected a quad");
    }

    #[test]
    fn rejected_quads_sit_between_the_warps_they_were_rasterized_between() {
        // One 64x64 tile: a near left half, a far square hidden behind it,
        // then a right half nothing hides.
        let scene = ortho_scene(
            vec![
                quad_mesh(0.0, 0.0, 32.0, 64.0, 1.0, 0),
                quad_mesh(4.0, 4.0, 20.0, 20.0, 0.0, 1),
                quad_mesh(32.0, 0.0, 64.0, 64.0, 0.5, 2),
            ],
            vec![
                mat("near", Blend::Opaque, 0),
                mat("hidden", Blend::Opaque, 0),
                mat("right", Blend::Opaque, 0),
            ],
            64.0,
            64.0,
        );
        let f = rasterize(&scene, 64, 64, &RasterOptions::default()).unwrap();
        let m = &f.stats.materials;
        assert_eq!(m[1].warps, 0, "the far square is hidden");
        let hidden = m[1].quads_rejected_early_z;
        assert!(hidden >= 64, "{hidden}");
        assert_eq!(f.stats.quads_rejected_early_z, hidden);
        let tile = &f.trace.tiles()[0];
        assert_eq!(tile.quad_count() as u64, m[0].warps + m[2].warps);
        let first = m[0].warps as usize;
        for i in 0..tile.quad_count() {
            let want = if i == first { hidden } else { 0 };
            assert_eq!(u64::from(tile.rejected_before(i)), want, "quad {i}");
        }
        assert_eq!(tile.rejected_after_last(), 0);
        assert_eq!(tile.raster_count(), f.stats.quads_covered);
        assert!(f.trace.to_text().contains(&format!("\nz {hidden}\nq ")));
    }

    #[test]
    fn a_tile_whose_every_quad_is_rejected_is_a_record_without_warps() {
        // (Raster order makes this rare: the first fragment drawn at a
        // pixel passes the depth test. The record must still be written.)
        let textures = TextureSet::new(&[]);
        let ctx = TileCtx {
            setups: &[],
            mats: &[],
            textures: &textures,
            tile: 64,
            width: 128,
            height: 64,
            colour: false,
            prepass: false,
            hiz: true,
        };
        let header = TraceHeader::new("w", 128, 64, 64);
        let mut b = TileBuf::new(64, 0);
        assert!(build_tile(&ctx, &header, 1, 0, &mut b).unwrap().is_none());
        b.rej_since = 37;
        let t = build_tile(&ctx, &header, 1, 0, &mut b)
            .unwrap()
            .expect("a record");
        let tile = &t.tiles()[0];
        assert_eq!((tile.tx(), tile.ty(), tile.quad_count()), (1, 0, 0));
        assert_eq!(tile.rejected_after_last(), 37);
        assert_eq!((tile.rejected_count(), tile.raster_count()), (37, 37));
        assert!(t.to_text().ends_with("\ntile 1 0\nz 37\nend\n"));
        assert_eq!(b.positions, 0);
    }
}
