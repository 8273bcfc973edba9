//! Geometry before the tiles: the view and projection, clipping in
//! homogeneous space against the guard band, triangle setup in fixed-point
//! screen coordinates, and binning into tiles.

use super::*;
use crate::{DrawState, Material, Mesh};

/// A vertex in clip space with its attributes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct ClipVert {
    pub(super) p: [f64; 4],
    pub(super) uv: [f64; 2],
    pub(super) uv2: [f64; 2],
}

impl ClipVert {
    pub(super) fn lerp(&self, o: &ClipVert, t: f64) -> ClipVert {
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
pub(super) const CLIP_PLANES: [[f64; 4]; 6] = [
    [0.0, 0.0, 1.0, 1.0],    // near: z >= -w
    [0.0, 0.0, -1.0, 1.0],   // far: z <= w
    [1.0, 0.0, 0.0, GUARD],  // guard left
    [-1.0, 0.0, 0.0, GUARD], // guard right
    [0.0, 1.0, 0.0, GUARD],  // guard bottom
    [0.0, -1.0, 0.0, GUARD], // guard top
];

#[inline]
pub(super) fn plane_dist(pl: &[f64; 4], p: &[f64; 4]) -> f64 {
    pl[0] * p[0] + pl[1] * p[1] + pl[2] * p[2] + pl[3] * p[3]
}

/// Clips a triangle against the near, far and guard-band planes; `out`
/// receives the polygon (empty when nothing is left). Returns whether any
/// plane cut the triangle.
pub(super) fn clip_triangle(
    tri: [ClipVert; 3],
    out: &mut Vec<ClipVert>,
    tmp: &mut Vec<ClipVert>,
) -> bool {
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
pub(super) struct Setup {
    /// Edge functions `A x + B y + C` in fixed point (inside: >= 0; C
    /// includes the fill-rule bias).
    pub(super) edges: [[i64; 3]; 3],
    /// Pixel bounding box, clamped to the frame: x0..x1, y0..y1 (exclusive).
    pub(super) bbox: [u32; 4],
    /// Attribute planes `a + b (x - x0) + c (y - y0)` at pixel coordinates:
    /// depth, 1/w, u/w, v/w, u2/w, v2/w.
    pub(super) planes: [[f64; 3]; 6],
    /// Origin of the planes.
    pub(super) origin: [f64; 2],
    /// Smallest 1/w of the vertices (helper pixels are clamped above half
    /// of it, so extrapolation never divides by ~0).
    pub(super) min_inv_w: f64,
    /// Mesh material.
    pub(super) material: u32,
    /// Depth key for back-to-front sorting (mean clip w).
    pub(super) sort_w: f64,
}

impl Setup {
    /// Depth (0 near to 1 far) at pixel position (x, y).
    #[inline]
    pub(super) fn depth_at(&self, x: f64, y: f64) -> f32 {
        let p = &self.planes[0];
        (p[0] + p[1] * (x - self.origin[0]) + p[2] * (y - self.origin[1])) as f32
    }

    /// Perspective-correct uv and uv2 at pixel position (x, y).
    #[inline]
    pub(super) fn uvs_at(&self, x: f64, y: f64) -> ([f32; 2], [f32; 2]) {
        let (_, a, b) = self.attributes(x, y);
        (a, b)
    }

    /// Perspective-correct uv at pixel position (x, y): the same as
    /// `uvs_at(x, y).0`, without uv2.
    #[inline]
    pub(super) fn uv_at(&self, x: f64, y: f64) -> [f32; 2] {
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
    pub(super) fn attributes(&self, x: f64, y: f64) -> (f32, [f32; 2], [f32; 2]) {
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
pub(super) fn transform(m: &[[f64; 4]; 4], p: Vec3) -> [f64; 4] {
    let (x, y, z) = (f64::from(p[0]), f64::from(p[1]), f64::from(p[2]));
    let mut o = [0.0; 4];
    for (r, row) in m.iter().enumerate() {
        o[r] = row[0] * x + row[1] * y + row[2] * z + row[3];
    }
    o
}

pub(super) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub(super) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub(super) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
pub(super) fn normalize(a: [f64; 3]) -> Option<[f64; 3]> {
    let l = dot(a, a).sqrt();
    (l > 1e-12 && l.is_finite()).then(|| [a[0] / l, a[1] / l, a[2] / l])
}
pub(super) fn v64(v: Vec3) -> [f64; 3] {
    [f64::from(v[0]), f64::from(v[1]), f64::from(v[2])]
}

/// The camera's view-projection matrix (rows) for a frame of this aspect.
pub(super) fn view_projection(scene: &Scene, aspect: f64) -> Result<[[f64; 4]; 4], SceneError> {
    let bad = |m: &str| SceneError::in_file(&scene.name, format!("camera: {m}"));
    match scene.camera {
        Camera::Perspective {
            eye,
            target,
            up,
            fov_y_deg,
            near,
            far,
        } => perspective(eye, target, up, fov_y_deg, (near, far), aspect).map_err(|m| bad(&m)),
        Camera::Ortho {
            left,
            top,
            width,
            height,
        } => ortho(scene, left, top, width, height).map_err(|m| bad(&m)),
        Camera::Clip => Ok([
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ]),
    }
}

/// An OpenGL-style look-at view and perspective projection.
fn perspective(
    eye: Vec3,
    target: Vec3,
    up: Vec3,
    fov_y_deg: f32,
    (near, far): (f32, f32),
    aspect: f64,
) -> Result<[[f64; 4]; 4], String> {
    let (n, f) = (f64::from(near), f64::from(far));
    if !(n > 0.0 && f > n && f.is_finite()) {
        return Err(format!(
            "near {near} and far {far}: expected 0 < near < far"
        ));
    }
    let fov = f64::from(fov_y_deg);
    if !(fov > 0.0 && fov < 180.0) {
        return Err(format!("fov_y_deg {fov_y_deg}: expected 0 to 180 degrees"));
    }
    let e = v64(eye);
    let fw = normalize(sub(v64(target), e)).ok_or("eye and target coincide")?;
    let s = normalize(cross(fw, v64(up))).ok_or("up is parallel to the view direction")?;
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

/// The orthographic camera's rectangle onto the frame, depth from the
/// scene's z range (larger z nearer).
fn ortho(
    scene: &Scene,
    left: f32,
    top: f32,
    width: f32,
    height: f32,
) -> Result<[[f64; 4]; 4], String> {
    let (l, t, w, h) = (
        f64::from(left),
        f64::from(top),
        f64::from(width),
        f64::from(height),
    );
    if !(w > 0.0 && h > 0.0 && w.is_finite() && h.is_finite()) {
        return Err(format!(
            "ortho width {width} and height {height}: expected > 0"
        ));
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

/// A triangle's vertices in screen space: positions snapped to 1/256
/// pixel (x, y) and the attributes (depth, 1/w, u/w, v/w, u2/w, v2/w).
struct Snapped {
    sx: [i64; 3],
    sy: [i64; 3],
    attrs: [[f64; 6]; 3],
}

/// Project and snap a clip-space triangle; `None` when a vertex does not
/// land on a finite screen position.
#[inline]
fn snap(
    v: &[ClipVert; 3],
    width: u32,
    height: u32,
    depth_range: Option<[f64; 2]>,
) -> Option<Snapped> {
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
            return None;
        }
        sx[i] = (x * SUB as f64).round() as i64;
        sy[i] = (y * SUB as f64).round() as i64;
        let depth = nz * 0.5 + 0.5;
        attrs[i] = [
            depth_range.map_or(depth, |[n, f]| n + (f - n) * depth),
            inv_w,
            v[i].uv[0] * inv_w,
            v[i].uv[1] * inv_w,
            v[i].uv2[0] * inv_w,
            v[i].uv2[1] * inv_w,
        ];
    }
    Some(Snapped { sx, sy, attrs })
}

/// The edge functions of a triangle wound clockwise on screen (`px`,
/// `py`), with the top-left fill rule folded into their constants.
#[inline]
fn edge_functions(px: [i64; 3], py: [i64; 3]) -> [[i64; 3]; 3] {
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
    edges
}

/// The attribute planes over the snapped positions, in pixels: per
/// attribute (value at the origin, d/dx, d/dy), and the origin (vertex 0).
#[inline]
fn attribute_planes(t: &Snapped) -> ([[f64; 3]; 6], [f64; 2]) {
    let (sx, sy, attrs) = (&t.sx, &t.sy, &t.attrs);
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
    (planes, [x0, y0])
}

/// What set-up needs of a triangle's draw: its material and pipeline
/// state (`None`: the material has none, and back faces are culled when
/// `cull_back` says so), and its depth key.
#[derive(Clone, Copy)]
pub(super) struct SetupCtx<'a> {
    pub(super) material: u32,
    pub(super) state: Option<&'a DrawState>,
    pub(super) cull_back: bool,
    pub(super) sort_w: f64,
}

/// Builds the setup of one screen triangle; `None` if degenerate, culled
/// or outside the frame (or the draw's scissor rectangle).
pub(super) fn setup(
    v: &[ClipVert; 3],
    width: u32,
    height: u32,
    cx: SetupCtx,
    stats: &mut RasterStats,
) -> Option<Setup> {
    let Some(t) = snap(v, width, height, cx.state.and_then(|s| s.depth_range)) else {
        stats.degenerate += 1;
        return None;
    };
    let (sx, sy) = (t.sx, t.sy);
    let area2 = (sx[1] - sx[0]) * (sy[2] - sy[0]) - (sx[2] - sx[0]) * (sy[1] - sy[0]);
    if area2 == 0 {
        stats.degenerate += 1;
        return None;
    }
    // Screen y grows down: counter-clockwise in NDC is negative here.
    let culled = match cx.state {
        None => cx.cull_back && area2 > 0,
        Some(st) => st.culls(area2 < 0),
    };
    if culled {
        stats.culled_back_faces += 1;
        return None;
    }
    let order: [usize; 3] = if area2 > 0 { [0, 1, 2] } else { [0, 2, 1] };
    let px = order.map(|i| sx[i]);
    let py = order.map(|i| sy[i]);
    let edges = edge_functions(px, py);
    let xmin = *px.iter().min().expect("3");
    let xmax = *px.iter().max().expect("3");
    let ymin = *py.iter().min().expect("3");
    let ymax = *py.iter().max().expect("3");
    // Pixel i has its centre at (i + 0.5): covered range of centres.
    let lo = |v: i64| ((v - SUB / 2 + SUB - 1).div_euclid(SUB)).max(0);
    let hi = |v: i64, lim: u32| ((v - SUB / 2).div_euclid(SUB) + 1).min(i64::from(lim));
    let mut bbox = [lo(xmin), hi(xmax, width), lo(ymin), hi(ymax, height)];
    if let Some([x0, y0, x1, y1]) = cx.state.and_then(|s| s.scissor) {
        bbox[0] = bbox[0].max(i64::from(x0));
        bbox[1] = bbox[1].min(i64::from(x1));
        bbox[2] = bbox[2].max(i64::from(y0));
        bbox[3] = bbox[3].min(i64::from(y1));
    }
    if bbox[0] >= bbox[1] || bbox[2] >= bbox[3] {
        // Covers no pixel centre of the frame.
        stats.culled_outside += 1;
        return None;
    }
    let (mut planes, origin) = attribute_planes(&t);
    if let Some((factor, units)) = cx.state.and_then(|s| s.polygon_offset) {
        let slope = planes[0][1].abs().max(planes[0][2].abs());
        planes[0][0] += f64::from(factor) * slope + f64::from(units) * DEPTH_UNIT;
    }
    let min_inv_w = t.attrs.iter().map(|a| a[1]).fold(f64::INFINITY, f64::min);
    Some(Setup {
        edges,
        bbox: [
            bbox[0] as u32,
            bbox[1] as u32,
            bbox[2] as u32,
            bbox[3] as u32,
        ],
        planes,
        origin,
        min_inv_w,
        material: cx.material,
        sort_w: cx.sort_w,
    })
}

/// Whether a triangle's edges overlap the pixel centres of a rectangle.
pub(super) fn overlaps(s: &Setup, x0: u32, x1: u32, y0: u32, y1: u32) -> bool {
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

/// The smallest depth difference of polygon offset's `units`: one step of
/// a 24-bit depth buffer (wasp).
const DEPTH_UNIT: f64 = 1.0 / 16_777_216.0;

/// Each mesh's clip-space positions, kept from its first run to its last
/// (a sorted draw order visits a mesh many times).
struct ClipCache {
    last_run: Vec<usize>,
    clips: Vec<Vec<[f64; 4]>>,
}

impl ClipCache {
    fn new(meshes: usize, runs: &[Run]) -> Self {
        let mut last_run = vec![0; meshes];
        for (i, r) in runs.iter().enumerate() {
            last_run[r.mesh] = i;
        }
        Self {
            last_run,
            clips: vec![Vec::new(); meshes],
        }
    }

    /// Mesh `mesh`'s positions transformed by `m` (on first use).
    fn positions(&mut self, m: &[[f64; 4]; 4], scene: &Scene, mesh: usize) -> &[[f64; 4]] {
        let (clip, from) = (&mut self.clips[mesh], &scene.meshes[mesh].positions);
        if clip.len() != from.len() {
            clip.extend(from.iter().map(|&p| transform(m, p)));
            if let Some(w) = &scene.meshes[mesh].clip_w {
                for (c, &w) in clip.iter_mut().zip(w) {
                    c[3] = f64::from(w);
                }
            }
        }
        clip
    }

    /// Drop mesh `mesh`'s positions if run `i` was its last.
    fn release(&mut self, i: usize, mesh: usize) {
        if self.last_run[mesh] == i {
            self.clips[mesh] = Vec::new();
        }
    }
}

/// Whether a clip-space triangle lies entirely outside one plane of the
/// real frustum (or has a coordinate that is not finite).
#[inline]
fn outside_frustum(p: &[[f64; 4]; 3]) -> bool {
    let outside = |k: usize, sgn: f64| p.iter().all(|q| sgn * q[k] > q[3]);
    outside(0, 1.0)
        || outside(0, -1.0)
        || outside(1, 1.0)
        || outside(1, -1.0)
        || outside(2, 1.0)
        || outside(2, -1.0)
        || p.iter().any(|q| q.iter().any(|c| !c.is_finite()))
}

/// The set-up triangles so far, opaque and alpha-tested ones apart from
/// the alpha-blended ones, and the clipper's buffers.
struct SetupLists<'a> {
    width: u32,
    height: u32,
    cull_back: bool,
    stats: &'a mut RasterStats,
    opaque: Vec<Setup>,
    blended: Vec<Setup>,
    poly: Vec<ClipVert>,
    tmp: Vec<ClipVert>,
}

impl SetupLists<'_> {
    /// Clip triangle `tri` of `mesh` (clip-space positions `p`; material
    /// `mat`; `blend`: to the back-to-front list), then set up the
    /// triangles of its fan.
    #[inline]
    fn triangle(
        &mut self,
        mesh: &Mesh,
        mat: &Material,
        blend: bool,
        tri: [ClipVert; 3],
        p: &[[f64; 4]; 3],
    ) {
        let sort_w = (p[0][3] + p[1][3] + p[2][3]) / 3.0;
        let cut = clip_triangle(tri, &mut self.poly, &mut self.tmp);
        if cut {
            self.stats.clipped += 1;
        }
        if self.poly.len() < 3 {
            self.stats.culled_outside += 1;
            return;
        }
        for k in 1..self.poly.len() - 1 {
            let tri = [self.poly[0], self.poly[k], self.poly[k + 1]];
            let cx = SetupCtx {
                material: mesh.material as u32,
                state: mat.state.as_ref(),
                cull_back: self.cull_back,
                sort_w,
            };
            if let Some(s) = setup(&tri, self.width, self.height, cx, self.stats) {
                if blend {
                    self.blended.push(s);
                } else {
                    self.opaque.push(s);
                }
            }
        }
    }
}

/// Geometry and tiling: every triangle of the `runs` (the draw order,
/// [`runs`]) set up, in that order, the alpha-blended ones last.
pub(super) fn geometry(
    scene: &Scene,
    runs: &[Run],
    width: u32,
    height: u32,
    opts: &RasterOptions,
    stats: &mut RasterStats,
) -> Result<Vec<Setup>, SceneError> {
    let m = view_projection(scene, f64::from(width) / f64::from(height))?;
    let mut out = SetupLists {
        width,
        height,
        cull_back: opts.cull_back_faces,
        stats,
        opaque: Vec::new(),
        blended: Vec::new(),
        poly: Vec::with_capacity(12),
        tmp: Vec::with_capacity(12),
    };
    let mut clips = ClipCache::new(scene.meshes.len(), runs);
    for (i, run) in runs.iter().enumerate() {
        let mesh = &scene.meshes[run.mesh];
        let material = &scene.materials[mesh.material];
        let blend = material.blend == Blend::AlphaBlend && material.state.is_none();
        let clip = clips.positions(&m, scene, run.mesh);
        let tris = run.count as u64;
        out.stats.primitives += tris;
        out.stats.materials[mesh.material].triangles += tris;
        let indices = &mesh.indices[run.first * 3..(run.first + run.count) * 3];
        for t in indices.chunks_exact(3) {
            let idx = [t[0] as usize, t[1] as usize, t[2] as usize];
            let p = [clip[idx[0]], clip[idx[1]], clip[idx[2]]];
            // Trivial reject against the real frustum.
            if outside_frustum(&p) {
                out.stats.culled_outside += 1;
                continue;
            }
            let vert = |k: usize| ClipVert {
                p: p[k],
                uv: [f64::from(mesh.uv[idx[k]][0]), f64::from(mesh.uv[idx[k]][1])],
                uv2: mesh.uv2.as_ref().map_or([0.0; 2], |u| {
                    [f64::from(u[idx[k]][0]), f64::from(u[idx[k]][1])]
                }),
            };
            out.triangle(mesh, material, blend, [vert(0), vert(1), vert(2)], &p);
        }
        clips.release(i, run.mesh);
    }
    let SetupLists {
        mut opaque,
        mut blended,
        stats,
        ..
    } = out;
    if matches!(scene.camera, Camera::Perspective { .. }) {
        // Back to front; sort_by is stable, so ties keep submission order.
        blended.sort_by(|a, b| b.sort_w.total_cmp(&a.sort_w));
    }
    opaque.extend(blended);
    stats.setup_triangles = opaque.len() as u64;
    Ok(opaque)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::fixtures::*;
    use crate::{Filter, Mesh, TexSample};

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
                ..Default::default()
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
        let runs = runs(&scene, DrawOrder::AsLoaded).0;
        let setups = geometry(&scene, &runs, w, h, &RasterOptions::default(), &mut stats).unwrap();
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
        scene.materials[0].shader = vec![ShaderOp::Tex(TexSample::new(3, 0, Filter::Nearest))];
        let e = rasterize(&scene, 8, 8, &RasterOptions::default()).unwrap_err();
        assert!(e.message.contains("texture 3"), "{e}");
    }
}
