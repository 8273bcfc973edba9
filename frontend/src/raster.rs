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

/// Sub-pixel bits of the fixed-point screen coordinates.
const SUBPIXEL_BITS: u32 = 8;
const SUB: i64 = 1 << SUBPIXEL_BITS;
/// Guard band: triangles are clipped to `|x|, |y| <= GUARD * w`.
const GUARD: f64 = 8.0;
/// Colour of pixels no triangle covers.
const CLEAR: [f32; 4] = [0.08, 0.09, 0.12, 1.0];

/// Options of the front end.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RasterOptions {
    /// Tile edge in pixels (even; the paper's 64).
    pub tile: u32,
    /// Cull back faces (clockwise in normalized device coordinates).
    pub cull_back_faces: bool,
    /// Compute the picture (off: the trace only, faster; the image is the
    /// clear colour). Alpha-tested surfaces need their alpha for their
    /// depth writes, so it is always sampled.
    pub colour: bool,
    /// Hidden-surface removal by a per-tile depth pre-pass over the opaque
    /// triangles (as tile-based deferred renderers do): only the nearest
    /// opaque fragment of a pixel survives early-Z. Off by default: plain
    /// early-Z in submission order.
    pub depth_prepass: bool,
    /// Worker threads for the tiles (0: one per available core). The
    /// result does not depend on it.
    pub threads: usize,
}

impl Default for RasterOptions {
    fn default() -> Self {
        Self {
            tile: 64,
            cull_back_faces: false,
            colour: true,
            depth_prepass: false,
            threads: 0,
        }
    }
}

/// Counts of one material.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct MaterialStats {
    /// Material name.
    pub name: String,
    /// Blend mode.
    pub blend: String,
    /// Input triangles.
    pub triangles: u64,
    /// Surviving (triangle, quad) fragments it shaded: its warps.
    pub warps: u64,
    /// Quads of its triangles rejected by early-Z.
    pub quads_rejected_early_z: u64,
    /// Pixels it shaded (surviving, inside the triangle).
    pub pixels: u64,
}

/// What the front end did.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct RasterStats {
    /// Input triangles.
    pub primitives: u64,
    /// Triangles entirely outside the view frustum.
    pub culled_outside: u64,
    /// Back faces culled (only with `cull_back_faces`).
    pub culled_back_faces: u64,
    /// Triangles with zero area on screen.
    pub degenerate: u64,
    /// Triangles crossing the near or far plane or the guard band, clipped.
    pub clipped: u64,
    /// Screen triangles after clipping (set up and binned).
    pub setup_triangles: u64,
    /// (tile, triangle) entries of the polygon lists.
    pub bin_entries: u64,
    /// Tile records of the trace: tiles that rasterized at least one quad,
    /// shaded or rejected by early-Z (a tile whose every quad was rejected
    /// is a record without warps).
    pub tiles: u64,
    /// (triangle, quad) pairs with at least one covered pixel.
    pub quads_covered: u64,
    /// Of those, quads whose every covered pixel failed the depth test.
    pub quads_rejected_early_z: u64,
    /// Of those, quads the hierarchical (coarse) depth test rejected
    /// without testing their pixels (the rest were tested pixel by pixel).
    pub quads_rejected_hiz: u64,
    /// Surviving (triangle, quad) fragments: the warps (quad records of the
    /// trace), one per fragment as in a hardware TBR.
    pub warps: u64,
    /// Quad positions with at least one surviving fragment (warps /
    /// positions is the overdraw the shader cores see).
    pub positions: u64,
    /// Pixels shaded (surviving, inside their triangle).
    pub pixels_shaded: u64,
    /// Per material, in scene order.
    pub materials: Vec<MaterialStats>,
}

/// Where the front end's time went: wall-clock seconds of each phase of
/// [`rasterize`] (not part of the results, which never depend on time).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct RasterTimings {
    /// Mip chains and the texture heap layout ([`TextureSet::new`]).
    pub textures: f64,
    /// Geometry (transform, clip, set-up) and binning into tiles.
    pub geometry: f64,
    /// Raster, early-Z, texturing, shading of the tiles and building the
    /// trace.
    pub tiles: f64,
}

impl RasterTimings {
    /// All phases.
    pub fn total(&self) -> f64 {
        self.textures + self.geometry + self.tiles
    }
}

/// A rasterized frame: the trace, the picture and the counts.
#[derive(Clone, Debug)]
pub struct Frame {
    /// The warps of the frame.
    pub trace: Trace,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// RGBA8, row-major, top row first.
    pub image: Vec<u8>,
    /// What the front end did.
    pub stats: RasterStats,
    /// How long each phase took.
    pub timings: RasterTimings,
}

/// A vertex in clip space with its attributes.
#[derive(Clone, Copy, Debug, PartialEq)]
struct ClipVert {
    p: [f64; 4],
    uv: [f64; 2],
    uv2: [f64; 2],
}

impl ClipVert {
    fn lerp(&self, o: &ClipVert, t: f64) -> ClipVert {
        let l = |a: f64, b: f64| a + (b - a) * t;
        ClipVert {
            p: [
                l(self.p[0], o.p[0]),
                l(self.p[1], o.p[1]),
                l(self.p[2], o.p[2]),
                l(self.p[3], o.p[3]),
            ],
            uv: [l(self.uv[0], o.uv[0]), l(self.uv[1], o.uv[1])],
            uv2: [l(self.uv2[0], o.uv2[0]), l(self.uv2[1], o.uv2[1])],
        }
    }
}

/// The clip planes, as `dot(plane, p) >= 0` inside.
const CLIP_PLANES: [[f64; 4]; 6] = [
    [0.0, 0.0, 1.0, 1.0],    // near: z >= -w
    [0.0, 0.0, -1.0, 1.0],   // far: z <= w
    [1.0, 0.0, 0.0, GUARD],  // guard left
    [-1.0, 0.0, 0.0, GUARD], // guard right
    [0.0, 1.0, 0.0, GUARD],  // guard bottom
    [0.0, -1.0, 0.0, GUARD], // guard top
];

#[inline]
fn plane_dist(pl: &[f64; 4], p: &[f64; 4]) -> f64 {
    pl[0] * p[0] + pl[1] * p[1] + pl[2] * p[2] + pl[3] * p[3]
}

/// Clips a triangle against the near, far and guard-band planes; `out`
/// receives the polygon (empty when nothing is left). Returns whether any
/// plane cut the triangle.
fn clip_triangle(tri: [ClipVert; 3], out: &mut Vec<ClipVert>, tmp: &mut Vec<ClipVert>) -> bool {
    out.clear();
    out.extend_from_slice(&tri);
    let mut cut = false;
    for pl in &CLIP_PLANES {
        if out.iter().all(|v| plane_dist(pl, &v.p) >= 0.0) {
            continue;
        }
        cut = true;
        tmp.clear();
        let n = out.len();
        for i in 0..n {
            let a = out[i];
            let b = out[(i + 1) % n];
            let (da, db) = (plane_dist(pl, &a.p), plane_dist(pl, &b.p));
            if da >= 0.0 {
                tmp.push(a);
            }
            if (da >= 0.0) != (db >= 0.0) {
                let t = da / (da - db);
                tmp.push(a.lerp(&b, t));
            }
        }
        std::mem::swap(out, tmp);
        if out.len() < 3 {
            out.clear();
            return true;
        }
    }
    cut
}

/// A triangle ready to rasterize.
#[derive(Clone, Debug)]
struct Setup {
    /// Edge functions `A x + B y + C` in fixed point (inside: >= 0; C
    /// includes the fill-rule bias).
    edges: [[i64; 3]; 3],
    /// Pixel bounding box, clamped to the frame: x0..x1, y0..y1 (exclusive).
    bbox: [u32; 4],
    /// Attribute planes `a + b (x - x0) + c (y - y0)` at pixel coordinates:
    /// depth, 1/w, u/w, v/w, u2/w, v2/w.
    planes: [[f64; 3]; 6],
    /// Origin of the planes.
    origin: [f64; 2],
    /// Smallest 1/w of the vertices (helper pixels are clamped above half
    /// of it, so extrapolation never divides by ~0).
    min_inv_w: f64,
    /// Mesh material.
    material: u32,
    /// Depth key for back-to-front sorting (mean clip w).
    sort_w: f64,
}

impl Setup {
    /// Depth (0 near to 1 far) at pixel position (x, y).
    #[inline]
    fn depth_at(&self, x: f64, y: f64) -> f32 {
        let p = &self.planes[0];
        (p[0] + p[1] * (x - self.origin[0]) + p[2] * (y - self.origin[1])) as f32
    }

    /// Perspective-correct uv and uv2 at pixel position (x, y).
    #[inline]
    fn uvs_at(&self, x: f64, y: f64) -> ([f32; 2], [f32; 2]) {
        let (_, a, b) = self.attributes(x, y);
        (a, b)
    }

    /// Perspective-correct uv at pixel position (x, y): the same as
    /// `uvs_at(x, y).0`, without uv2.
    #[inline]
    fn uv_at(&self, x: f64, y: f64) -> [f32; 2] {
        let dx = x - self.origin[0];
        let dy = y - self.origin[1];
        let ev = |p: &[f64; 3]| p[0] + p[1] * dx + p[2] * dy;
        let w = 1.0 / ev(&self.planes[1]).max(0.5 * self.min_inv_w);
        [
            (ev(&self.planes[2]) * w) as f32,
            (ev(&self.planes[3]) * w) as f32,
        ]
    }

    /// Perspective-correct attributes at pixel position (x, y) (pixel
    /// centres are at half-integers): depth, uv, uv2.
    #[inline]
    fn attributes(&self, x: f64, y: f64) -> (f32, [f32; 2], [f32; 2]) {
        let dx = x - self.origin[0];
        let dy = y - self.origin[1];
        let ev = |p: &[f64; 3]| p[0] + p[1] * dx + p[2] * dy;
        let depth = ev(&self.planes[0]);
        let inv_w = ev(&self.planes[1]).max(0.5 * self.min_inv_w);
        let w = 1.0 / inv_w;
        let uv = [
            (ev(&self.planes[2]) * w) as f32,
            (ev(&self.planes[3]) * w) as f32,
        ];
        let uv2 = [
            (ev(&self.planes[4]) * w) as f32,
            (ev(&self.planes[5]) * w) as f32,
        ];
        (depth as f32, uv, uv2)
    }
}

/// Column-major 4x4 matrix times a point.
fn transform(m: &[[f64; 4]; 4], p: Vec3) -> [f64; 4] {
    let (x, y, z) = (f64::from(p[0]), f64::from(p[1]), f64::from(p[2]));
    let mut o = [0.0; 4];
    for (r, row) in m.iter().enumerate() {
        o[r] = row[0] * x + row[1] * y + row[2] * z + row[3];
    }
    o
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn normalize(a: [f64; 3]) -> Option<[f64; 3]> {
    let l = dot(a, a).sqrt();
    (l > 1e-12 && l.is_finite()).then(|| [a[0] / l, a[1] / l, a[2] / l])
}
fn v64(v: Vec3) -> [f64; 3] {
    [f64::from(v[0]), f64::from(v[1]), f64::from(v[2])]
}

/// The camera's view-projection matrix (rows) for a frame of this aspect.
fn view_projection(scene: &Scene, aspect: f64) -> Result<[[f64; 4]; 4], SceneError> {
    let bad = |m: &str| SceneError::in_file(&scene.name, format!("camera: {m}"));
    match scene.camera {
        Camera::Perspective {
            eye,
            target,
            up,
            fov_y_deg,
            near,
            far,
        } => {
            let (n, f) = (f64::from(near), f64::from(far));
            if !(n > 0.0 && f > n && f.is_finite()) {
                return Err(bad(&format!(
                    "near {near} and far {far}: expected 0 < near < far"
                )));
            }
            let fov = f64::from(fov_y_deg);
            if !(fov > 0.0 && fov < 180.0) {
                return Err(bad(&format!(
                    "fov_y_deg {fov_y_deg}: expected 0 to 180 degrees"
                )));
            }
            let e = v64(eye);
            let fw =
                normalize(sub(v64(target), e)).ok_or_else(|| bad("eye and target coincide"))?;
            let s = normalize(cross(fw, v64(up)))
                .ok_or_else(|| bad("up is parallel to the view direction"))?;
            let u = cross(s, fw);
            let t = 1.0 / (fov.to_radians() / 2.0).tan();
            let view = [
                [s[0], s[1], s[2], -dot(s, e)],
                [u[0], u[1], u[2], -dot(u, e)],
                [-fw[0], -fw[1], -fw[2], dot(fw, e)],
                [0.0, 0.0, 0.0, 1.0],
            ];
            let proj = [
                [t / aspect, 0.0, 0.0, 0.0],
                [0.0, t, 0.0, 0.0],
                [0.0, 0.0, (f + n) / (n - f), 2.0 * f * n / (n - f)],
                [0.0, 0.0, -1.0, 0.0],
            ];
            let mut m = [[0.0; 4]; 4];
            for r in 0..4 {
                for c in 0..4 {
                    m[r][c] = (0..4).map(|k| proj[r][k] * view[k][c]).sum();
                }
            }
            Ok(m)
        }
        Camera::Ortho {
            left,
            top,
            width,
            height,
        } => {
            let (l, t, w, h) = (
                f64::from(left),
                f64::from(top),
                f64::from(width),
                f64::from(height),
            );
            if !(w > 0.0 && h > 0.0 && w.is_finite() && h.is_finite()) {
                return Err(bad(&format!(
                    "ortho width {width} and height {height}: expected > 0"
                )));
            }
            // z range of the scene: larger z is nearer (smaller depth).
            let (mut zmin, mut zmax) = (f64::INFINITY, f64::NEG_INFINITY);
            for m in &scene.meshes {
                for p in &m.positions {
                    zmin = zmin.min(f64::from(p[2]));
                    zmax = zmax.max(f64::from(p[2]));
                }
            }
            // zmax (nearest) -> ndc -0.9, zmin -> +0.9 (a margin, so
            // rounding never puts a layer outside the near or far plane).
            let span = if zmax > zmin { zmax - zmin } else { 1.0 };
            let zref = if zmax > zmin { zmax } else { zmax + 0.5 };
            Ok([
                [2.0 / w, 0.0, 0.0, -2.0 * l / w - 1.0],
                [0.0, -2.0 / h, 0.0, 2.0 * t / h + 1.0],
                [0.0, 0.0, -1.8 / span, 1.8 * zref / span - 0.9],
                [0.0, 0.0, 0.0, 1.0],
            ])
        }
    }
}

/// Checks the scene's references so the pipeline cannot index out of range.
fn validate(scene: &Scene) -> Result<(), SceneError> {
    let err = |m: String| Err(SceneError::in_file(&scene.name, m));
    for (i, t) in scene.textures.iter().enumerate() {
        if t.width == 0 || t.height == 0 || t.rgba.len() != t.width as usize * t.height as usize * 4
        {
            return err(format!(
                "texture {i} ({}): {}x{} with {} bytes (expected width x height x 4 > 0)",
                t.name,
                t.width,
                t.height,
                t.rgba.len()
            ));
        }
    }
    for (i, m) in scene.materials.iter().enumerate() {
        if m.shader.is_empty() || m.shader.iter().all(|op| matches!(op, ShaderOp::Alu(0))) {
            return err(format!(
                "material {i} ({}) has an empty shader program",
                m.name
            ));
        }
        for op in &m.shader {
            if let ShaderOp::Tex(s) = op {
                if s.texture >= scene.textures.len() {
                    return err(format!(
                        "material {i} ({}) samples texture {} of {}",
                        m.name,
                        s.texture,
                        scene.textures.len()
                    ));
                }
                if s.uv_set > 1 {
                    return err(format!(
                        "material {i} ({}) uses UV set {} (expected 0 or 1)",
                        m.name, s.uv_set
                    ));
                }
            }
        }
    }
    for (i, m) in scene.meshes.iter().enumerate() {
        let n = m.positions.len();
        if m.material >= scene.materials.len() {
            return err(format!(
                "mesh {i} uses material {} of {}",
                m.material,
                scene.materials.len()
            ));
        }
        if m.uv.len() != n {
            return err(format!("mesh {i}: {} UVs for {n} positions", m.uv.len()));
        }
        match &m.uv2 {
            Some(uv2) if uv2.len() != n => {
                return err(format!(
                    "mesh {i}: {} second UVs for {n} positions",
                    uv2.len()
                ))
            }
            None => {
                let needs = scene.materials[m.material]
                    .shader
                    .iter()
                    .any(|op| matches!(op, ShaderOp::Tex(s) if s.uv_set == 1));
                if needs {
                    return err(format!(
                        "mesh {i}: material {} samples UV set 1 but the mesh has no second UVs",
                        scene.materials[m.material].name
                    ));
                }
            }
            _ => {}
        }
        if m.indices.len() % 3 != 0 {
            return err(format!(
                "mesh {i}: {} indices (expected a multiple of 3)",
                m.indices.len()
            ));
        }
        if let Some(&bad) = m.indices.iter().find(|&&x| x as usize >= n) {
            return err(format!("mesh {i}: index {bad} of {n} vertices"));
        }
    }
    Ok(())
}

/// Builds the setup of one screen triangle; `None` if degenerate or culled.
fn setup(
    v: &[ClipVert; 3],
    width: u32,
    height: u32,
    material: u32,
    sort_w: f64,
    cull_back: bool,
    stats: &mut RasterStats,
) -> Option<Setup> {
    let (wf, hf) = (f64::from(width), f64::from(height));
    let mut sx = [0i64; 3];
    let mut sy = [0i64; 3];
    let mut attrs = [[0.0f64; 6]; 3];
    for i in 0..3 {
        let p = v[i].p;
        let inv_w = 1.0 / p[3];
        let (nx, ny, nz) = (p[0] * inv_w, p[1] * inv_w, p[2] * inv_w);
        let x = (nx * 0.5 + 0.5) * wf;
        let y = (0.5 - ny * 0.5) * hf;
        if !(x.is_finite() && y.is_finite() && inv_w.is_finite()) {
            stats.degenerate += 1;
            return None;
        }
        sx[i] = (x * SUB as f64).round() as i64;
        sy[i] = (y * SUB as f64).round() as i64;
        attrs[i] = [
            nz * 0.5 + 0.5,
            inv_w,
            v[i].uv[0] * inv_w,
            v[i].uv[1] * inv_w,
            v[i].uv2[0] * inv_w,
            v[i].uv2[1] * inv_w,
        ];
    }
    let area2 = (sx[1] - sx[0]) * (sy[2] - sy[0]) - (sx[2] - sx[0]) * (sy[1] - sy[0]);
    if area2 == 0 {
        stats.degenerate += 1;
        return None;
    }
    // Screen y grows down: counter-clockwise in NDC is negative here.
    if cull_back && area2 > 0 {
        stats.culled_back_faces += 1;
        return None;
    }
    let order: [usize; 3] = if area2 > 0 { [0, 1, 2] } else { [0, 2, 1] };
    let px = order.map(|i| sx[i]);
    let py = order.map(|i| sy[i]);
    let mut edges = [[0i64; 3]; 3];
    for (a, edge) in edges.iter_mut().enumerate() {
        let b = (a + 1) % 3;
        let ea = py[a] - py[b];
        let eb = px[b] - px[a];
        let ec = -(ea * px[a] + eb * py[a]);
        // Top-left rule: a pixel centre exactly on an edge belongs to the
        // triangle only if the edge is a left edge (inside to its right) or
        // a top edge (horizontal, inside below).
        let top_left = ea > 0 || (ea == 0 && eb > 0);
        *edge = [ea, eb, ec - i64::from(!top_left)];
    }
    let xmin = *px.iter().min().expect("3");
    let xmax = *px.iter().max().expect("3");
    let ymin = *py.iter().min().expect("3");
    let ymax = *py.iter().max().expect("3");
    // Pixel i has its centre at (i + 0.5): covered range of centres.
    let lo = |v: i64| ((v - SUB / 2 + SUB - 1).div_euclid(SUB)).max(0);
    let hi = |v: i64, lim: u32| ((v - SUB / 2).div_euclid(SUB) + 1).min(i64::from(lim));
    let bbox = [lo(xmin), hi(xmax, width), lo(ymin), hi(ymax, height)];
    if bbox[0] >= bbox[1] || bbox[2] >= bbox[3] {
        // Covers no pixel centre of the frame.
        stats.culled_outside += 1;
        return None;
    }
    // Attribute planes over the snapped positions, in pixels.
    let fx = |i: usize| sx[i] as f64 / SUB as f64;
    let fy = |i: usize| sy[i] as f64 / SUB as f64;
    let (x0, y0) = (fx(0), fy(0));
    let (x1, y1, x2, y2) = (fx(1) - x0, fy(1) - y0, fx(2) - x0, fy(2) - y0);
    let det = x1 * y2 - x2 * y1;
    let mut planes = [[0.0f64; 3]; 6];
    for (k, plane) in planes.iter_mut().enumerate() {
        let (a0, a1, a2) = (
            attrs[0][k],
            attrs[1][k] - attrs[0][k],
            attrs[2][k] - attrs[0][k],
        );
        *plane = [a0, (a1 * y2 - a2 * y1) / det, (a2 * x1 - a1 * x2) / det];
    }
    let min_inv_w = attrs.iter().map(|a| a[1]).fold(f64::INFINITY, f64::min);
    Some(Setup {
        edges,
        bbox: [
            bbox[0] as u32,
            bbox[1] as u32,
            bbox[2] as u32,
            bbox[3] as u32,
        ],
        planes,
        origin: [x0, y0],
        min_inv_w,
        material,
        sort_w,
    })
}

/// Whether a triangle's edges overlap the pixel centres of a rectangle.
fn overlaps(s: &Setup, x0: u32, x1: u32, y0: u32, y1: u32) -> bool {
    let cx = |x: u32| i64::from(x) * SUB + SUB / 2;
    for e in &s.edges {
        // The corner where the edge function is largest.
        let x = if e[0] > 0 { cx(x1 - 1) } else { cx(x0) };
        let y = if e[1] > 0 { cx(y1 - 1) } else { cx(y0) };
        if e[0] * x + e[1] * y + e[2] < 0 {
            return false;
        }
    }
    true
}

/// Geometry and tiling: every triangle set up, in draw order.
fn geometry(
    scene: &Scene,
    width: u32,
    height: u32,
    opts: &RasterOptions,
    stats: &mut RasterStats,
) -> Result<Vec<Setup>, SceneError> {
    let m = view_projection(scene, f64::from(width) / f64::from(height))?;
    let mut opaque = Vec::new();
    let mut blended = Vec::new();
    let (mut poly, mut tmp) = (Vec::with_capacity(12), Vec::with_capacity(12));
    let mut clip = Vec::new();
    for mesh in &scene.meshes {
        let material = &scene.materials[mesh.material];
        let blend = material.blend == Blend::AlphaBlend;
        clip.clear();
        clip.extend(mesh.positions.iter().map(|&p| transform(&m, p)));
        let tris = mesh.indices.len() as u64 / 3;
        stats.primitives += tris;
        stats.materials[mesh.material].triangles += tris;
        for t in mesh.indices.chunks_exact(3) {
            let idx = [t[0] as usize, t[1] as usize, t[2] as usize];
            let p = [clip[idx[0]], clip[idx[1]], clip[idx[2]]];
            // Trivial reject against the real frustum.
            let outside = |k: usize, sgn: f64| p.iter().all(|q| sgn * q[k] > q[3]);
            if outside(0, 1.0)
                || outside(0, -1.0)
                || outside(1, 1.0)
                || outside(1, -1.0)
                || outside(2, 1.0)
                || outside(2, -1.0)
                || p.iter().any(|q| q.iter().any(|c| !c.is_finite()))
            {
                stats.culled_outside += 1;
                continue;
            }
            let vert = |k: usize| ClipVert {
                p: p[k],
                uv: [f64::from(mesh.uv[idx[k]][0]), f64::from(mesh.uv[idx[k]][1])],
                uv2: mesh.uv2.as_ref().map_or([0.0; 2], |u| {
                    [f64::from(u[idx[k]][0]), f64::from(u[idx[k]][1])]
                }),
            };
            let tri = [vert(0), vert(1), vert(2)];
            let sort_w = (p[0][3] + p[1][3] + p[2][3]) / 3.0;
            let cut = clip_triangle(tri, &mut poly, &mut tmp);
            if cut {
                stats.clipped += 1;
            }
            if poly.len() < 3 {
                stats.culled_outside += 1;
                continue;
            }
            for k in 1..poly.len() - 1 {
                let tri = [poly[0], poly[k], poly[k + 1]];
                if let Some(s) = setup(
                    &tri,
                    width,
                    height,
                    mesh.material as u32,
                    sort_w,
                    opts.cull_back_faces,
                    stats,
                ) {
                    if blend {
                        blended.push(s);
                    } else {
                        opaque.push(s);
                    }
                }
            }
        }
    }
    if matches!(scene.camera, Camera::Perspective { .. }) {
        // Back to front; sort_by is stable, so ties keep submission order.
        blended.sort_by(|a, b| b.sort_w.total_cmp(&a.sort_w));
    }
    opaque.extend(blended);
    stats.setup_triangles = opaque.len() as u64;
    Ok(opaque)
}

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

/// The coverage mask of the quad with top-left pixel (qx, qy): bit i for
/// pixel i (0 top-left, 1 top-right, 2 bottom-left, 3 bottom-right),
/// pixels at or beyond (xend, yend) excluded.
#[inline]
fn coverage(s: &Setup, qx: u32, qy: u32, xend: u32, yend: u32) -> u8 {
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
fn row_span(s: &Setup, qy: u32, x0: u32, x1: u32) -> (u32, u32) {
    span_of(&[row_cover(s, qy), row_cover(s, qy + 1)], x0, x1)
}

/// [`row_span`] from the two rows' covered ranges ([`row_cover`]).
#[inline]
fn span_of(cover: &[(i64, i64); 2], x0: u32, x1: u32) -> (u32, u32) {
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
fn row_cover(s: &Setup, row: u32) -> (i64, i64) {
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
fn covered_quads(cover: &[(i64, i64); 2], qy: u32, xa: u32, xb: u32, xend: u32, yend: u32) -> u64 {
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
fn depth_lower_bound(s: &Setup, xa: u32, xb: u32, ya: u32, yb: u32) -> f32 {
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
struct CoarseDepth {
    /// Tile edge in pixels.
    tile: u32,
    /// Blocks per block row.
    cols: u32,
    /// Per block, an upper bound of its stored depths.
    max: Vec<f32>,
    /// Per block, whether a depth changed since `max` was computed.
    dirty: Vec<bool>,
}

impl CoarseDepth {
    /// Block width in pixels (even: whole quads).
    const BLOCK_W: u32 = 8;

    fn new(tile: u32) -> CoarseDepth {
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
    fn clear(&mut self) {
        self.max.fill(1.0);
        self.dirty.fill(false);
    }

    /// Every block recomputed before its next use (after writes not
    /// reported by [`CoarseDepth::wrote`]).
    fn invalidate(&mut self) {
        self.dirty.fill(true);
    }

    /// The block of tile pixel (lx, ly).
    #[inline]
    fn block(&self, lx: u32, ly: u32) -> usize {
        ((ly / 2) * self.cols + lx / Self::BLOCK_W) as usize
    }

    /// Tile pixel (lx, ly) got a new depth.
    #[inline]
    fn wrote(&mut self, lx: u32, ly: u32) {
        let k = self.block(lx, ly);
        self.dirty[k] = true;
    }

    /// Whether a triangle whose depth is at least `z` at every pixel it
    /// covers in the block of tile pixel (lx, ly) fails the depth test at
    /// all of them against `depth` (the tile's depth buffer).
    #[inline]
    fn hidden(&mut self, depth: &[f32], lx: u32, ly: u32, z: f32) -> bool {
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
