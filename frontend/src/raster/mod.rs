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
//!    alpha-tested triangles in submission order (the meshes as loaded,
//!    or sorted front to back by [`RasterOptions::draw_order`]: see
//!    [`DrawOrder`]), then the alpha-blended
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

use super::texture::{FormatChoice, QuadTexels, TextureFormat, TextureSet, TextureUse};
use super::{Blend, Camera, Compare, DrawState, Scene, SceneError, ShaderOp, Vec3};
use crate::trace::{Trace, TraceHeader};
use serde::Serialize;

mod coverage;
#[cfg(test)]
mod fixtures;
mod frame;
mod maps;
mod order;
mod pipeline;
mod records;
mod setup;
mod tile;
mod validate;

use coverage::*;
pub use frame::*;
use maps::TileMaps;
pub use maps::{rasterize_with_maps, PixelMaps};
pub use order::DrawOrder;
use order::*;
use pipeline::*;
use records::*;
use setup::*;
use tile::*;
use validate::*;

/// Sub-pixel bits of the fixed-point screen coordinates.
const SUBPIXEL_BITS: u32 = 8;
const SUB: i64 = 1 << SUBPIXEL_BITS;
/// Guard band: triangles are clipped to `|x|, |y| <= GUARD * w`.
const GUARD: f64 = 8.0;
/// Colour of pixels no triangle covers.
const CLEAR: [f32; 4] = [0.08, 0.09, 0.12, 1.0];

/// Rasterize `scene` into a `width` x `height` frame.
pub fn rasterize(
    scene: &Scene,
    width: u32,
    height: u32,
    opts: &RasterOptions,
) -> Result<Frame, SceneError> {
    rasterize_with(scene, width, height, opts, true)
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
