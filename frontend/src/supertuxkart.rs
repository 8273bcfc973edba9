//! SuperTuxKart tracks: `scene.xml` object placement, `.spm` meshes,
//! `materials.xml` blend modes, PNG/JPEG textures and a camera at a kart
//! start position or along the driveline.
//!
//! # Data layout
//!
//! The data root passed to [`load`] is the game's `data` directory inside
//! the unpacked `supertuxkart-data` package,
//! `<package root>/usr/share/games/supertuxkart/data`, where the package
//! root is `$WASP_SCENES/supertuxkart` (`wasp scenes fetch`) or
//! `$WASP_SCENES/supertuxkart-data` (one directory per package; both are
//! in [`DATA_DIRS`], [`find_data_root`] picks the first present):
//!
//! ```text
//! <data root>
//!     tracks/<map>/scene.xml, quads.xml, graph.xml, materials.xml, *.spm, *.png|*.jpg
//!     library/<name>/node.xml, materials.xml, *.spm, textures   (placed by <library>)
//!     textures/**            shared textures, textures/materials.xml
//!     models/*.spm           items: gift boxes, bananas, nitro cans
//! ```
//!
//! Every directory under `tracks/` holding a `scene.xml` is a
//! map: [`tracks`] lists them.
//!
//! # What is loaded
//!
//! * `<track model=..>` (the track mesh), `<static-object>` / `<object>`
//!   with a model (types `animation`, `movable`, none; at their rest
//!   transform), `<water>`, `<library>` instances (recursively, from
//!   `library/<name>/node.xml`, transforms composed), LOD instances
//!   (`lod_instance` + `lod_group`: the level whose `lod_distance` is the
//!   smallest one not below the instance's distance from the camera, none
//!   beyond the largest, as the game's LOD nodes do), `billboard` objects
//!   (camera-facing quads), items (`<item>`, `<banana>`, `<small-nitro>`,
//!   `<big-nitro>` with the models of `data/items.xml`) and the
//!   `<sky-box>` / `<sky-dome>` (a cube of half-size [`SKY_HALF_SIZE`]
//!   around the eye, drawn after the opaque geometry).
//! * Skipped: physics-only objects, objects whose `if` condition is false
//!   for a normal (not reversed, not CTF, not networked) race with
//!   everything unlocked, sound emitters, triggers, cutscene cameras,
//!   particle emitters, lights, CTF-only items.
//! * Object transforms: `xyz`, `hpr` in degrees (rotation about X, then
//!   Y, then Z, Irrlicht's Euler convention) and `scale`:
//!   `p' = T + Rz Ry Rx (S p)`.
//!
//! # Coordinates
//!
//! SuperTuxKart is left-handed, Y up. The scene is converted to a
//! right-handed, Y-up frame by negating z; triangles are emitted
//! counter-clockwise when seen from their front side (OpenGL's default).
//! UVs are as stored: v = 0 is the top row of the texture.
//!
//! # Materials and textures
//!
//! One material per (texture, second texture, blend) combination, one
//! mesh per material (instances merged, world space). `materials.xml`
//! (track, then library, then `textures/materials.xml`) sets the blend:
//! `alphatest` and `grass` are [`Blend::AlphaTest`]; `alphablend`,
//! `additive` and `displace` are [`Blend::AlphaBlend`]; the rest are
//! opaque. `unlit` uses the `unlit` template, a material with a second
//! texture and a second UV set uses `lightmapped`, every other textured
//! one `standard`; 3D surfaces filter trilinearly, the sky bilinearly.
//! `clampu` + `clampv` make a texture clamp, otherwise it repeats.
//! Buffers without a texture (vertex-coloured) get an ALU-only program.
//! Textures are decoded to RGBA8; those larger than
//! [`MAX_TEXTURE_SIDE`] are downscaled (triangle filter, aspect kept) to
//! that maximum side, as a mobile build's texture budget would.
//!
//! # SPM format (`.spm`, little-endian)
//!
//! ```text
//! "SP"  u8 b: version = b >> 3 (must be 1); kind = b & !0x08:
//!             0 space-partitioned (unsupported), 1 skinned "SPMA", else static "SPMN"
//! u8 flags: bit0 normals, bit1 vertex colours, bit2 tangents
//! f32 x 6 bounding box (min xyz, max xyz)
//! u16 material count; each: u8 len + texture name, u8 len + second texture name
//! u16 sector count; each:
//!   u16 buffer count; each:
//!     u32 vertex count (<= 65535)   u32 index count   u16 material
//!     vertex: f32 x3 position
//!             [u32 packed normal]             if normals
//!             [u8 c; if c != 128: u8 r,g,b]   if vertex colours (128 = white)
//!             [f16 u, v]                       if the material has a texture
//!             [f16 u2, v2]                     if it also has a second texture
//!             [u32 packed tangent]             if tangents and a texture
//!             [16 bytes joints and weights]    if skinned
//!     indices: u8 if vertex count <= 255, else u16
//! (skinned: armature and animation data follow; the bind pose is used)
//! ```
//!
//! # Cameras
//!
//! * `start:N`: kart start position N. Explicit `<start x y z h>`
//!   elements (arenas, soccer fields, the overworld) are used when present;
//!   otherwise positions are laid out behind the start line along the
//!   driveline (`quads.xml` + `graph.xml`, main line = first successor of
//!   every node) as a grid following `<default-start>`: kart N sits
//!   `0.1 + forwards-distance * (N + 1)` behind the line, in column
//!   `N % karts-per-row` spaced `sidewards-distance`, raised by
//!   `upwards-distance`. Tracks with neither (cutscenes) use their
//!   `cutscene_camera` objects, looking at the centre of the scene.
//!   The eye is [`CAM_BACK`] behind and [`CAM_UP`] above the kart,
//!   looking at a point [`CAM_AHEAD`] ahead of it.
//! * `driveline:F`: at fraction F (0..1) of the main driveline's length
//!   from the start line, [`CAM_UP`] above it, looking [`CAM_AHEAD`] ahead.
//!
//! Vertical field of view [`FOV_Y_DEG`], near [`NEAR`], far [`FAR`].

use super::bytes::Bytes;
use super::def::SceneDef;
use super::{
    shader, Blend, Camera, Filter, Material, Mesh, Scene, SceneError, ShaderOp, Texture, Vec2, Vec3,
};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::rc::Rc;

use super::vec3::{add, cross, len, normalize, scale, sub};

/// Where the data root may be, relative to `$WASP_SCENES`: the package
/// unpacked into `supertuxkart/` (`wasp scenes fetch`) or into
/// `supertuxkart-data/`.
pub const DATA_DIRS: [&str; 2] = [
    "supertuxkart/usr/share/games/supertuxkart/data",
    "supertuxkart-data/usr/share/games/supertuxkart/data",
];
/// Vertical field of view in degrees (the game's 80 is for 4:3-ish
/// screens; a 2.5:1 phone frame at 60 already spans ~112 degrees across).
pub const FOV_Y_DEG: f32 = 60.0;
/// Near plane (metres).
pub const NEAR: f32 = 0.5;
/// Far plane (metres).
pub const FAR: f32 = 1000.0;
/// Textures larger than this (either side) are downscaled to it.
pub const MAX_TEXTURE_SIDE: u32 = 1024;
/// Half the side of the sky cube around the eye (its corners stay
/// inside [`FAR`]).
pub const SKY_HALF_SIZE: f32 = 500.0;
/// Camera distance behind the kart (metres).
pub const CAM_BACK: f32 = 4.5;
/// Camera height above the kart (metres).
pub const CAM_UP: f32 = 2.0;
/// Distance ahead of the kart of the point looked at (metres).
pub const CAM_AHEAD: f32 = 6.0;
/// Library nesting limit (libraries placing libraries).
const MAX_LIBRARY_DEPTH: u32 = 8;

/// The first of [`DATA_DIRS`] under `cache` that holds `tracks/`.
pub fn find_data_root(cache: &Path) -> Option<PathBuf> {
    DATA_DIRS
        .iter()
        .map(|d| cache.join(d))
        .find(|r| r.join("tracks").is_dir())
}

/// Every track (directory under `tracks/` with a `scene.xml`), sorted.
pub fn tracks(data_root: &Path) -> Result<Vec<String>, SceneError> {
    let dir = data_root.join("tracks");
    let rd = std::fs::read_dir(&dir)
        .map_err(|e| SceneError::in_file(&dir, format!("cannot list tracks: {e}")))?;
    let mut out = Vec::new();
    for entry in rd.flatten() {
        if entry.path().join("scene.xml").is_file() {
            out.push(entry.file_name().to_string_lossy().into_owned());
        }
    }
    out.sort();
    Ok(out)
}

// ---------------------------------------------------------------------------
// SPM meshes

/// One SPM material: its textures (file names).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SpmMaterial {
    /// First texture (base colour); vertices carry UVs only if present.
    pub texture: Option<String>,
    /// Second texture (second UV set).
    pub texture2: Option<String>,
}

/// One mesh buffer of an SPM file (object space).
#[derive(Clone, Debug, PartialEq)]
pub struct SpmBuffer {
    /// Index into [`Spm::materials`].
    pub material: usize,
    /// Positions.
    pub positions: Vec<Vec3>,
    /// First UV set (if the material has a texture).
    pub uv: Option<Vec<Vec2>>,
    /// Second UV set (if the material has a second texture).
    pub uv2: Option<Vec<Vec2>>,
    /// Triangle list.
    pub indices: Vec<u32>,
}

/// A parsed SPM file.
#[derive(Clone, Debug, PartialEq)]
pub struct Spm {
    /// Skinned ("SPMA"): the bind pose is what the buffers hold.
    pub skinned: bool,
    /// Bounding box: min xyz, max xyz.
    pub bbox: [f32; 6],
    /// Materials.
    pub materials: Vec<SpmMaterial>,
    /// Mesh buffers.
    pub buffers: Vec<SpmBuffer>,
}

/// The next IEEE 754 binary16, which must be finite, as f32.
fn half(r: &mut Bytes, what: &str) -> Result<f32, SceneError> {
    let at = r.pos();
    let v = half_to_f32(r.u16(what)?);
    r.finite(at, v, what)
}

/// A name: a length byte, then that many bytes (none: no name).
fn name(r: &mut Bytes, what: &str) -> Result<Option<String>, SceneError> {
    let n = r.u8(what)? as usize;
    if n == 0 {
        return Ok(None);
    }
    let b = r.take(n, what)?;
    Ok(Some(String::from_utf8_lossy(b).into_owned()))
}

/// IEEE 754 binary16 to f32.
pub fn half_to_f32(h: u16) -> f32 {
    let sign = if h & 0x8000 != 0 { -1.0f32 } else { 1.0 };
    let exp = ((h >> 10) & 0x1f) as i32;
    let frac = (h & 0x3ff) as f32;
    match exp {
        0 => sign * frac * (2.0f32).powi(-24),
        31 => {
            if frac == 0.0 {
                sign * f32::INFINITY
            } else {
                f32::NAN
            }
        }
        _ => sign * (1.0 + frac / 1024.0) * (2.0f32).powi(exp - 15),
    }
}

/// Parse an SPM file (`file` names it in errors).
pub fn parse_spm(bytes: &[u8], file: &Path) -> Result<Spm, SceneError> {
    let mut r = Bytes::new(bytes, file);
    if r.take(2, "magic")? != b"SP" {
        return Err(r.err(0, "not an SPM file: magic is not \"SP\""));
    }
    let b = r.u8("version byte")?;
    if b >> 3 != 1 {
        return Err(r.err(2, format!("SPM version {} (expected 1)", b >> 3)));
    }
    let kind = b & !0x08;
    if kind == 0 {
        return Err(r.err(2, "space-partitioned SPM (SPMS) is not supported"));
    }
    let skinned = kind == 1;
    let flags = r.u8("flags")?;
    let (has_normal, has_color, has_tangent) = (flags & 1 != 0, flags & 2 != 0, flags & 4 != 0);
    let mut bbox = [0f32; 6];
    for v in &mut bbox {
        *v = r.f32("bounding box")?;
    }
    let nmat = r.u16("material count")? as usize;
    let mut materials = Vec::with_capacity(nmat);
    for _ in 0..nmat {
        let texture = name(&mut r, "texture name")?;
        let texture2 = name(&mut r, "second texture name")?;
        materials.push(SpmMaterial { texture, texture2 });
    }
    let nsec = r.u16("sector count")?;
    let mut buffers = Vec::new();
    for _ in 0..nsec {
        let nbuf = r.u16("buffer count")?;
        for _ in 0..nbuf {
            let at = r.pos();
            let nv = r.u32("vertex count")? as usize;
            if nv > 65535 {
                return Err(r.err(at, format!("{nv} vertices in a buffer (at most 65535)")));
            }
            let ni = r.u32("index count")? as usize;
            if !ni.is_multiple_of(3) {
                return Err(r.err(at + 4, format!("index count {ni} is not a multiple of 3")));
            }
            let mat_at = r.pos();
            let material = r.u16("material id")? as usize;
            if material >= materials.len() {
                return Err(r.err(
                    mat_at,
                    format!(
                        "material {material} out of range ({} materials)",
                        materials.len()
                    ),
                ));
            }
            let has_uv = materials[material].texture.is_some();
            let has_uv2 = has_uv && materials[material].texture2.is_some();
            let min_vertex = 12
                + 4 * has_normal as usize
                + has_color as usize
                + 4 * has_uv as usize
                + 4 * has_uv2 as usize
                + 4 * (has_uv && has_tangent) as usize
                + 16 * skinned as usize;
            if nv * min_vertex > r.remaining() {
                return Err(r.err(
                    r.pos(),
                    format!(
                        "truncated: {nv} vertices need at least {} bytes, {} left",
                        nv * min_vertex,
                        r.remaining()
                    ),
                ));
            }
            let mut positions = Vec::with_capacity(nv);
            let mut uv = has_uv.then(|| Vec::with_capacity(nv));
            let mut uv2 = has_uv2.then(|| Vec::with_capacity(nv));
            for _ in 0..nv {
                let p = [
                    r.finite_f32("position")?,
                    r.finite_f32("position")?,
                    r.finite_f32("position")?,
                ];
                positions.push(p);
                if has_normal {
                    r.take(4, "normal")?;
                }
                if has_color && r.u8("colour tag")? != 128 {
                    r.take(3, "colour")?;
                }
                if let Some(uv) = uv.as_mut() {
                    uv.push([half(&mut r, "uv")?, half(&mut r, "uv")?]);
                    if let Some(uv2) = uv2.as_mut() {
                        uv2.push([half(&mut r, "second uv")?, half(&mut r, "second uv")?]);
                    }
                    if has_tangent {
                        r.take(4, "tangent")?;
                    }
                }
                if skinned {
                    r.take(16, "joints and weights")?;
                }
            }
            let wide = nv > 255;
            let isize = if wide { 2 } else { 1 };
            let raw = r.take(ni * isize, "indices")?;
            let base = r.pos() - raw.len();
            let mut indices = Vec::with_capacity(ni);
            for k in 0..ni {
                let i = if wide {
                    u16::from_le_bytes([raw[2 * k], raw[2 * k + 1]]) as usize
                } else {
                    raw[k] as usize
                };
                if i >= nv {
                    return Err(r.err(
                        base + k * isize,
                        format!("index {i} out of range ({nv} vertices)"),
                    ));
                }
                indices.push(i as u32);
            }
            buffers.push(SpmBuffer {
                material,
                positions,
                uv,
                uv2,
                indices,
            });
        }
    }
    Ok(Spm {
        skinned,
        bbox,
        materials,
        buffers,
    })
}

// ---------------------------------------------------------------------------
// Transforms

/// An affine transform: `p' = m p + t` (column vectors).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Xf {
    m: [[f32; 3]; 3],
    t: Vec3,
}

impl Xf {
    const IDENTITY: Xf = Xf {
        m: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        t: [0.0; 3],
    };

    /// `T + Rz Ry Rx S` from xyz, hpr (degrees) and scale.
    fn from_parts(xyz: Vec3, hpr: Vec3, scale: Vec3) -> Xf {
        let (sx, cx) = hpr[0].to_radians().sin_cos();
        let (sy, cy) = hpr[1].to_radians().sin_cos();
        let (sz, cz) = hpr[2].to_radians().sin_cos();
        let rx = [[1.0, 0.0, 0.0], [0.0, cx, -sx], [0.0, sx, cx]];
        let ry = [[cy, 0.0, sy], [0.0, 1.0, 0.0], [-sy, 0.0, cy]];
        let rz = [[cz, -sz, 0.0], [sz, cz, 0.0], [0.0, 0.0, 1.0]];
        let r = mat_mul(&rz, &mat_mul(&ry, &rx));
        let mut m = r;
        for row in &mut m {
            for (c, v) in row.iter_mut().enumerate() {
                *v *= scale[c];
            }
        }
        Xf { m, t: xyz }
    }

    fn apply(&self, p: Vec3) -> Vec3 {
        let m = &self.m;
        [
            m[0][0] * p[0] + m[0][1] * p[1] + m[0][2] * p[2] + self.t[0],
            m[1][0] * p[0] + m[1][1] * p[1] + m[1][2] * p[2] + self.t[1],
            m[2][0] * p[0] + m[2][1] * p[1] + m[2][2] * p[2] + self.t[2],
        ]
    }

    /// `self` after `inner`.
    fn then(&self, inner: &Xf) -> Xf {
        Xf {
            m: mat_mul(&self.m, &inner.m),
            t: self.apply(inner.t),
        }
    }

    fn det(&self) -> f32 {
        let m = &self.m;
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    }
}

fn mat_mul(a: &[[f32; 3]; 3], b: &[[f32; 3]; 3]) -> [[f32; 3]; 3] {
    let mut o = [[0.0; 3]; 3];
    for (i, row) in o.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    o
}

/// SuperTuxKart (left-handed) to wasp (right-handed) coordinates.
fn to_rh(p: Vec3) -> Vec3 {
    [p[0], p[1], -p[2]]
}

// ---------------------------------------------------------------------------
// XML helpers

fn read_text(path: &Path) -> Result<String, SceneError> {
    let bytes =
        std::fs::read(path).map_err(|e| SceneError::in_file(path, format!("cannot read: {e}")))?;
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

fn parse_xml<'a>(text: &'a str, file: &Path) -> Result<roxmltree::Document<'a>, SceneError> {
    roxmltree::Document::parse(text).map_err(|e| {
        let p = e.pos();
        let offset: usize = text
            .split_inclusive('\n')
            .take(p.row.saturating_sub(1) as usize)
            .map(str::len)
            .sum::<usize>()
            + p.col.saturating_sub(1) as usize;
        SceneError::at(file, offset as u64, format!("bad XML: {e}"))
    })
}

fn floats(node: roxmltree::Node, attr: &str, file: &Path) -> Result<Option<Vec<f32>>, SceneError> {
    let Some(s) = node.attribute(attr) else {
        return Ok(None);
    };
    s.split_whitespace()
        .map(|w| {
            w.parse::<f32>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    SceneError::at(
                        file,
                        node.range().start as u64,
                        format!("<{}> {attr}=\"{s}\": not a list of numbers", tag(node)),
                    )
                })
        })
        .collect::<Result<Vec<_>, _>>()
        .map(Some)
}

fn vec3_attr(node: roxmltree::Node, attr: &str, file: &Path) -> Result<Option<Vec3>, SceneError> {
    match floats(node, attr, file)? {
        None => Ok(None),
        Some(v) if v.len() == 3 => Ok(Some([v[0], v[1], v[2]])),
        Some(v) if v.len() == 1 => Ok(Some([v[0]; 3])),
        Some(_) => Err(SceneError::at(
            file,
            node.range().start as u64,
            format!("<{}> {attr}: expected 3 numbers", tag(node)),
        )),
    }
}

fn f32_attr(node: roxmltree::Node, attr: &str, file: &Path) -> Result<Option<f32>, SceneError> {
    match floats(node, attr, file)? {
        None => Ok(None),
        Some(v) if v.len() == 1 => Ok(Some(v[0])),
        Some(_) => Err(SceneError::at(
            file,
            node.range().start as u64,
            format!("<{}> {attr}: expected one number", tag(node)),
        )),
    }
}

fn tag<'a>(node: roxmltree::Node<'a, '_>) -> &'a str {
    node.tag_name().name()
}

fn yes(node: roxmltree::Node, attr: &str) -> bool {
    matches!(
        node.attribute(attr).map(str::trim),
        Some("Y" | "y" | "true" | "1" | "yes")
    )
}

/// Position: `xyz` or `x`/`y`/`z`.
fn position(node: roxmltree::Node, file: &Path) -> Result<Vec3, SceneError> {
    if let Some(p) = vec3_attr(node, "xyz", file)? {
        return Ok(p);
    }
    Ok([
        f32_attr(node, "x", file)?.unwrap_or(0.0),
        f32_attr(node, "y", file)?.unwrap_or(0.0),
        f32_attr(node, "z", file)?.unwrap_or(0.0),
    ])
}

/// The node's transform: position, `hpr` (or heading `h` about Y), `scale`.
fn transform(node: roxmltree::Node, file: &Path) -> Result<Xf, SceneError> {
    let xyz = position(node, file)?;
    let hpr = match vec3_attr(node, "hpr", file)? {
        Some(r) => r,
        None => [0.0, f32_attr(node, "h", file)?.unwrap_or(0.0), 0.0],
    };
    let s = vec3_attr(node, "scale", file)?.unwrap_or([1.0; 3]);
    Ok(Xf::from_parts(xyz, hpr, s))
}

/// The `if` condition of an object, for a normal race (not reversed, not
/// CTF, not networked, nothing locked, no flooding, doors closed).
fn condition_holds(cond: Option<&str>) -> bool {
    let Some(c) = cond.map(str::trim) else {
        return true;
    };
    !matches!(
        c,
        "false"
            | "isTrackReverse"
            | "isReverse"
            | "isCTF"
            | "hasFlooding"
            | "showDoorOpen"
            | "isEasterEgg"
    ) && !c.starts_with("isLocked")
}

// ---------------------------------------------------------------------------
// Scene description (digested XML)

#[derive(Clone, Debug)]
enum Item {
    Model {
        path: PathBuf,
        xf: Xf,
    },
    Lod {
        /// (distance, model), ascending.
        levels: Vec<(f32, PathBuf)>,
        xf: Xf,
    },
    Library {
        name: String,
        xf: Xf,
    },
    Billboard {
        dir: PathBuf,
        texture: String,
        width: f32,
        height: f32,
        xf: Xf,
    },
}

/// A `scene.xml` or `node.xml`, reduced to what the loader uses.
#[derive(Clone, Debug, Default)]
struct Digest {
    items: Vec<Item>,
    sky: Option<Vec<String>>,
    starts: Vec<(Vec3, f32)>,
    default_start: Option<(usize, f32, f32, f32)>,
    cutscene_cameras: Vec<Vec3>,
}

fn digest(file: &Path, dir: &Path, data_root: &Path) -> Result<Digest, SceneError> {
    let text = read_text(file)?;
    let doc = parse_xml(&text, file)?;
    let mut d = Digest::default();
    // LOD groups of this file: name -> levels.
    let mut groups: HashMap<String, Vec<(f32, PathBuf)>> = HashMap::new();
    for g in doc.descendants().filter(|n| n.has_tag_name("group")) {
        let Some(name) = g.attribute("name") else {
            continue;
        };
        let mut levels = Vec::new();
        for o in g.children().filter(|n| n.is_element()) {
            if let (Some(m), Some(dist)) = (
                o.attribute("model").filter(|m| !m.is_empty()),
                f32_attr(o, "lod_distance", file)?,
            ) {
                levels.push((dist, dir.join(m)));
            }
        }
        levels.sort_by(|a, b| a.0.total_cmp(&b.0));
        groups.insert(name.to_string(), levels);
    }
    let root = doc.root_element();
    let mut stack: Vec<roxmltree::Node> = root.children().filter(|n| n.is_element()).collect();
    stack.reverse();
    while let Some(n) = stack.pop() {
        if !condition_holds(n.attribute("if")) {
            continue;
        }
        match tag(n) {
            "track" => {
                if let Some(m) = n.attribute("model").filter(|m| !m.is_empty()) {
                    d.items.push(Item::Model {
                        path: dir.join(m),
                        xf: transform(n, file)?,
                    });
                }
                let mut kids: Vec<_> = n.children().filter(|c| c.is_element()).collect();
                kids.reverse();
                stack.extend(kids);
            }
            "static-object" | "object" => {
                let ty = n.attribute("type").unwrap_or("");
                let inter = n.attribute("interaction").unwrap_or("");
                if ty == "cutscene_camera" {
                    d.cutscene_cameras.push(position(n, file)?);
                    continue;
                }
                if matches!(
                    ty,
                    "sfx-emitter" | "action-trigger" | "static_follow_kart" | "particle-emitter"
                ) || matches!(inter, "physics-only" | "physicsonly")
                {
                    continue;
                }
                let xf = transform(n, file)?;
                if ty == "billboard" {
                    if let Some(t) = n.attribute("texture") {
                        d.items.push(Item::Billboard {
                            dir: dir.to_path_buf(),
                            texture: t.to_string(),
                            width: f32_attr(n, "width", file)?.unwrap_or(1.0),
                            height: f32_attr(n, "height", file)?.unwrap_or(1.0),
                            xf,
                        });
                    }
                    continue;
                }
                if yes(n, "lod_instance") {
                    if let Some(levels) = n.attribute("lod_group").and_then(|g| groups.get(g)) {
                        d.items.push(Item::Lod {
                            levels: levels.clone(),
                            xf,
                        });
                        continue;
                    }
                }
                if let Some(m) = n.attribute("model").filter(|m| !m.is_empty()) {
                    d.items.push(Item::Model {
                        path: dir.join(m),
                        xf,
                    });
                }
            }
            "water" => {
                if let Some(m) = n.attribute("model").filter(|m| !m.is_empty()) {
                    d.items.push(Item::Model {
                        path: dir.join(m),
                        xf: transform(n, file)?,
                    });
                }
            }
            "library" => {
                if let Some(name) = n.attribute("name") {
                    d.items.push(Item::Library {
                        name: name.to_string(),
                        xf: transform(n, file)?,
                    });
                }
            }
            "item" | "banana" | "small-nitro" | "big-nitro" => {
                if yes(n, "ctf") {
                    continue;
                }
                let model = match tag(n) {
                    "item" => "gift-box.spm",
                    "banana" => "banana.spm",
                    "small-nitro" => "nitrotank-small.spm",
                    _ => "nitrotank-big.spm",
                };
                d.items.push(Item::Model {
                    path: data_root.join("models").join(model),
                    xf: transform(n, file)?,
                });
            }
            "sky-box" | "sky-dome" => {
                if let Some(t) = n.attribute("texture") {
                    let names: Vec<String> = t.split_whitespace().map(str::to_string).collect();
                    if !names.is_empty() {
                        d.sky = Some(names);
                    }
                }
            }
            "start" => {
                d.starts
                    .push((position(n, file)?, f32_attr(n, "h", file)?.unwrap_or(0.0)));
            }
            "default-start" => {
                d.default_start = Some((
                    f32_attr(n, "karts-per-row", file)?
                        .unwrap_or(2.0)
                        .clamp(1.0, 16.0) as usize,
                    f32_attr(n, "forwards-distance", file)?.unwrap_or(1.5),
                    f32_attr(n, "sidewards-distance", file)?.unwrap_or(3.0),
                    f32_attr(n, "upwards-distance", file)?.unwrap_or(0.1),
                ));
            }
            _ => {}
        }
    }
    Ok(d)
}

// ---------------------------------------------------------------------------
// Driveline

/// A driveline quad: p0 p1 is the entry edge, p3 p2 the exit edge.
type Quad = [Vec3; 4];

fn parse_quads(text: &str, file: &Path) -> Result<Vec<Quad>, SceneError> {
    let doc = parse_xml(text, file)?;
    let mut quads: Vec<Quad> = Vec::new();
    for q in doc.descendants().filter(|n| n.has_tag_name("quad")) {
        let mut pts = [[0.0f32; 3]; 4];
        for (k, p) in pts.iter_mut().enumerate() {
            let attr = format!("p{k}");
            let at = q.range().start as u64;
            let s = q
                .attribute(attr.as_str())
                .ok_or_else(|| SceneError::at(file, at, format!("<quad> without {attr}")))?;
            *p = if let Some((qi, pi)) = s.split_once(':') {
                let (qi, pi) = (qi.trim().parse::<usize>(), pi.trim().parse::<usize>());
                match (qi, pi) {
                    (Ok(qi), Ok(pi)) if qi < quads.len() && pi < 4 => quads[qi][pi],
                    _ => {
                        return Err(SceneError::at(
                            file,
                            at,
                            format!("<quad> {attr}=\"{s}\": bad reference to an earlier quad"),
                        ))
                    }
                }
            } else {
                vec3_attr(q, &attr, file)?.unwrap_or_default()
            };
        }
        quads.push(pts);
    }
    Ok(quads)
}

/// Successor lists of the drive graph (nodes = quads, in order).
fn parse_graph(text: &str, file: &Path, n: usize) -> Result<Vec<Vec<usize>>, SceneError> {
    let doc = parse_xml(text, file)?;
    let mut succ = vec![Vec::new(); n];
    let mut edge = |a: usize, b: usize, at: usize| -> Result<(), SceneError> {
        if a >= n || b >= n {
            return Err(SceneError::at(
                file,
                at as u64,
                format!("edge {a} -> {b}: node out of range ({n} quads)"),
            ));
        }
        succ[a].push(b);
        Ok(())
    };
    for e in doc.root_element().children().filter(|c| c.is_element()) {
        let at = e.range().start;
        let from = f32_attr(e, "from", file)?.map(|v| v as usize);
        let to = f32_attr(e, "to", file)?.map(|v| v as usize);
        let (Some(from), Some(to)) = (from, to) else {
            continue;
        };
        match tag(e) {
            "edge" => edge(from, to, at)?,
            "edge-line" | "edge-loop" => {
                for i in from..to.min(n) {
                    edge(i, i + 1, at)?;
                }
                if tag(e) == "edge-loop" {
                    edge(to, from, at)?;
                }
            }
            _ => {}
        }
    }
    Ok(succ)
}

/// The main driveline from node 0 following first successors, as
/// (centre of entry edge, centre of exit edge) segments.
fn main_line(quads: &[Quad], succ: &[Vec<usize>]) -> Vec<(Vec3, Vec3)> {
    let mut seen = vec![false; quads.len()];
    let mut out = Vec::new();
    let mut node = 0usize;
    while node < quads.len() && !seen[node] {
        seen[node] = true;
        let q = &quads[node];
        out.push((scale(add(q[0], q[1]), 0.5), scale(add(q[2], q[3]), 0.5)));
        match succ.get(node).and_then(|s| s.first()) {
            Some(&s) => node = s,
            None => break,
        }
    }
    out
}

/// The point at `dist` along the line (may be negative: before the start,
/// measured backwards from the line's end, the loop closing on the start)
/// and the direction of travel there.
fn along(line: &[(Vec3, Vec3)], dist: f32) -> (Vec3, Vec3) {
    let total: f32 = line.iter().map(|(a, b)| len(sub(*b, *a))).sum();
    let mut d = if total > 0.0 {
        dist.rem_euclid(total)
    } else {
        0.0
    };
    for (a, b) in line {
        let l = len(sub(*b, *a));
        if d <= l {
            let dir = normalize(sub(*b, *a));
            return (add(*a, scale(dir, d)), dir);
        }
        d -= l;
    }
    let (a, b) = line[line.len() - 1];
    (b, normalize(sub(b, a)))
}

fn line_length(line: &[(Vec3, Vec3)]) -> f32 {
    line.iter().map(|(a, b)| len(sub(*b, *a))).sum()
}

// ---------------------------------------------------------------------------
// Materials and textures

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct MatProps {
    blend: Blend,
    unlit: bool,
    clamp: bool,
}

fn parse_materials(path: &Path, out: &mut HashMap<String, MatProps>) -> Result<(), SceneError> {
    if !path.is_file() {
        return Ok(());
    }
    let text = read_text(path)?;
    let doc = parse_xml(&text, path)?;
    for m in doc.descendants().filter(|n| n.has_tag_name("material")) {
        let Some(name) = m.attribute("name") else {
            continue;
        };
        let shader = m.attribute("shader").unwrap_or("");
        let blend = match shader {
            "alphatest" | "grass" => Blend::AlphaTest,
            "alphablend" | "additive" | "displace" => Blend::AlphaBlend,
            _ => Blend::Opaque,
        };
        out.entry(name.to_string()).or_insert(MatProps {
            blend,
            unlit: shader == "unlit",
            clamp: yes(m, "clampu") && yes(m, "clampv"),
        });
    }
    Ok(())
}

/// Decode an image file to RGBA8, downscaled to at most `max_side`.
fn decode_image(path: &Path, max_side: u32) -> Result<(u32, u32, Vec<u8>), SceneError> {
    let bytes =
        std::fs::read(path).map_err(|e| SceneError::in_file(path, format!("cannot read: {e}")))?;
    let img = image::load_from_memory(&bytes)
        .map_err(|e| SceneError::in_file(path, format!("cannot decode image: {e}")))?;
    let mut rgba = img.to_rgba8();
    let (w, h) = rgba.dimensions();
    if w == 0 || h == 0 {
        return Err(SceneError::in_file(path, "empty image"));
    }
    if w.max(h) > max_side {
        let s = max_side as f64 / w.max(h) as f64;
        let nw = ((w as f64 * s).round() as u32).max(1);
        let nh = ((h as f64 * s).round() as u32).max(1);
        rgba = image::imageops::resize(&rgba, nw, nh, image::imageops::FilterType::Triangle);
    }
    let (w, h) = rgba.dimensions();
    Ok((w, h, rgba.into_raw()))
}

/// A decoded image: width, height, RGBA8 texels.
type Image = (u32, u32, Vec<u8>);

/// Decodes the image files `paths` ([`decode_image`]) on up to `threads`
/// threads, results in `paths` order; a file named twice is decoded once.
/// The first error in `paths` order, if any.
fn decode_images(
    paths: &[PathBuf],
    max_side: u32,
    threads: usize,
) -> Result<Vec<Image>, SceneError> {
    let mut unique: Vec<&PathBuf> = paths.iter().collect();
    unique.sort();
    unique.dedup();
    let next = std::sync::atomic::AtomicUsize::new(0);
    let work = || {
        let mut done = Vec::new();
        loop {
            let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            let Some(p) = unique.get(i) else {
                return done;
            };
            done.push((i, decode_image(p, max_side)));
        }
    };
    let threads = threads.clamp(1, unique.len().max(1));
    let mut results: Vec<(usize, Result<Image, SceneError>)> = if threads > 1 {
        std::thread::scope(|sc| {
            let others: Vec<_> = (1..threads).map(|_| sc.spawn(work)).collect();
            let mut all = work();
            for h in others {
                all.extend(h.join().expect("image decoding thread"));
            }
            all
        })
    } else {
        work()
    };
    results.sort_by_key(|r| r.0);
    let mut decoded: Vec<Option<Result<Image, SceneError>>> =
        results.into_iter().map(|r| Some(r.1)).collect();
    let slot: Vec<usize> = paths
        .iter()
        .map(|p| unique.binary_search(&p).expect("every path is in the list"))
        .collect();
    let mut uses = vec![0usize; unique.len()];
    for &i in &slot {
        uses[i] += 1;
    }
    slot.iter()
        .map(|&i| {
            uses[i] -= 1;
            // The last use takes the texels; earlier ones copy them.
            let r = if uses[i] == 0 {
                decoded[i].take()
            } else {
                decoded[i].clone()
            };
            r.expect("decoded")
        })
        .collect()
}

// ---------------------------------------------------------------------------
// The loader

/// Key of an output material.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
enum MatKey {
    Textured {
        base: PathBuf,
        second: Option<PathBuf>,
    },
    Untextured,
    Sky(PathBuf),
}

struct Builder<'a> {
    root: &'a Path,
    track_dir: PathBuf,
    track_mats: HashMap<String, MatProps>,
    lib_mats: HashMap<String, MatProps>,
    global_mats: HashMap<String, MatProps>,
    tex_index: HashMap<String, PathBuf>,
    spm_cache: HashMap<PathBuf, Rc<Spm>>,
    lib_cache: HashMap<String, Rc<Digest>>,
    eye: Vec3,
    cam_right: Vec3,
    cam_up: Vec3,
    /// Textures, their texels decoded at the end ([`decode_images`]).
    textures: Vec<Texture>,
    /// The image file of each texture.
    tex_paths: Vec<PathBuf>,
    tex_ids: HashMap<(PathBuf, bool), usize>,
    materials: Vec<Material>,
    mat_ids: HashMap<(MatKey, u8), usize>,
    meshes: Vec<Mesh>,
    missing: Vec<String>,
}

impl Builder<'_> {
    fn mat_props(&self, name: &str) -> MatProps {
        let base = Path::new(name)
            .file_name()
            .map(|f| f.to_string_lossy().into_owned())
            .unwrap_or_default();
        for map in [&self.track_mats, &self.lib_mats, &self.global_mats] {
            if let Some(p) = map.get(&base) {
                return *p;
            }
        }
        MatProps {
            blend: Blend::Opaque,
            unlit: false,
            clamp: false,
        }
    }

    /// Find a texture file: the model's directory, the track, the shared
    /// texture tree.
    fn find_texture(&self, name: &str, dir: &Path) -> Option<PathBuf> {
        let file = Path::new(name).file_name()?.to_string_lossy().into_owned();
        for d in [dir, self.track_dir.as_path()] {
            let p = d.join(&file);
            if p.is_file() {
                return Some(p);
            }
        }
        self.tex_index.get(&file.to_ascii_lowercase()).cloned()
    }

    fn texture(&mut self, path: &Path, repeat: bool) -> Result<usize, SceneError> {
        let key = (path.to_path_buf(), repeat);
        if let Some(&i) = self.tex_ids.get(&key) {
            return Ok(i);
        }
        let name = path
            .strip_prefix(self.root)
            .unwrap_or(path)
            .to_string_lossy()
            .into_owned();
        // Decoded later, all at once on several threads.
        self.textures.push(Texture {
            name,
            width: 0,
            height: 0,
            rgba: Vec::new(),
            repeat,
        });
        self.tex_paths.push(path.to_path_buf());
        let i = self.textures.len() - 1;
        self.tex_ids.insert(key, i);
        Ok(i)
    }

    /// The material for an SPM material in `dir`; None if it has no usable
    /// texture (then ALU-only), with whether a second UV set is used.
    fn material(&mut self, m: &SpmMaterial, dir: &Path) -> Result<(usize, bool), SceneError> {
        let base = m
            .texture
            .as_deref()
            .and_then(|t| self.find_texture(t, dir).map(|p| (t, p)));
        let Some((base_name, base_path)) = base else {
            if let Some(t) = &m.texture {
                self.missing.push(t.clone());
            }
            return Ok((self.untextured(), false));
        };
        let props = self.mat_props(base_name);
        let second = m
            .texture2
            .as_deref()
            .and_then(|t| self.find_texture(t, dir));
        if let (Some(t), None) = (&m.texture2, &second) {
            self.missing.push(t.clone());
        }
        let key = (
            MatKey::Textured {
                base: base_path.clone(),
                second: second.clone(),
            },
            props.blend as u8,
        );
        if let Some(&i) = self.mat_ids.get(&key) {
            return Ok((i, second.is_some()));
        }
        let t0 = self.texture(&base_path, !props.clamp)?;
        let shader = match &second {
            Some(p) => {
                let t1 = self.texture(p, true)?;
                shader::lightmapped(t0, t1, Filter::Trilinear)
            }
            None if props.unlit => shader::unlit(t0, Filter::Trilinear),
            None => shader::standard(t0, Filter::Trilinear),
        };
        self.materials.push(Material {
            name: base_name.to_string(),
            blend: props.blend,
            shader,
        });
        let i = self.materials.len() - 1;
        self.mat_ids.insert(key, i);
        Ok((i, second.is_some()))
    }

    fn untextured(&mut self) -> usize {
        let key = (MatKey::Untextured, Blend::Opaque as u8);
        if let Some(&i) = self.mat_ids.get(&key) {
            return i;
        }
        self.materials.push(Material {
            name: "untextured (vertex colour)".into(),
            blend: Blend::Opaque,
            shader: vec![ShaderOp::Alu(10)],
        });
        let i = self.materials.len() - 1;
        self.mat_ids.insert(key, i);
        i
    }

    /// The output mesh of a material (created on first use).
    fn mesh_for(&mut self, material: usize, with_uv2: bool) -> usize {
        if let Some(i) = self.meshes.iter().position(|m| m.material == material) {
            return i;
        }
        self.meshes.push(Mesh {
            positions: Vec::new(),
            uv: Vec::new(),
            uv2: with_uv2.then(Vec::new),
            indices: Vec::new(),
            material,
        });
        self.meshes.len() - 1
    }

    fn spm(&mut self, path: &Path) -> Result<Rc<Spm>, SceneError> {
        if let Some(s) = self.spm_cache.get(path) {
            return Ok(s.clone());
        }
        let bytes = std::fs::read(path)
            .map_err(|e| SceneError::in_file(path, format!("cannot read: {e}")))?;
        let s = Rc::new(parse_spm(&bytes, path)?);
        self.spm_cache.insert(path.to_path_buf(), s.clone());
        Ok(s)
    }

    fn add_model(&mut self, path: &Path, xf: &Xf) -> Result<(), SceneError> {
        let spm = self.spm(path)?;
        let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
        // A mirroring transform flips the winding; so does the z flip.
        let flip = xf.det() > 0.0;
        for b in &spm.buffers {
            let (mat, uv2) = self.material(&spm.materials[b.material], &dir)?;
            let mi = self.mesh_for(mat, uv2);
            let mesh = &mut self.meshes[mi];
            let base = mesh.positions.len() as u32;
            mesh.positions
                .extend(b.positions.iter().map(|p| to_rh(xf.apply(*p))));
            match &b.uv {
                Some(uv) => mesh.uv.extend_from_slice(uv),
                None => mesh
                    .uv
                    .extend(std::iter::repeat_n([0.0, 0.0], b.positions.len())),
            }
            if let Some(out) = mesh.uv2.as_mut() {
                match &b.uv2 {
                    Some(uv2) => out.extend_from_slice(uv2),
                    None => out.extend(std::iter::repeat_n([0.0, 0.0], b.positions.len())),
                }
            }
            for t in b.indices.chunks_exact(3) {
                if flip {
                    mesh.indices
                        .extend_from_slice(&[base + t[0], base + t[2], base + t[1]]);
                } else {
                    mesh.indices
                        .extend_from_slice(&[base + t[0], base + t[1], base + t[2]]);
                }
            }
        }
        Ok(())
    }

    fn add_billboard(
        &mut self,
        dir: &Path,
        texture: &str,
        w: f32,
        h: f32,
        xf: &Xf,
    ) -> Result<(), SceneError> {
        let Some(path) = self.find_texture(texture, dir) else {
            return Ok(());
        };
        let mut props = self.mat_props(texture);
        if props.blend == Blend::Opaque {
            props.blend = Blend::AlphaBlend;
        }
        let key = (
            MatKey::Textured {
                base: path.clone(),
                second: None,
            },
            props.blend as u8,
        );
        let mat = match self.mat_ids.get(&key) {
            Some(&i) => i,
            None => {
                let t = self.texture(&path, false)?;
                self.materials.push(Material {
                    name: texture.to_string(),
                    blend: props.blend,
                    shader: shader::standard(t, Filter::Trilinear),
                });
                self.mat_ids.insert(key, self.materials.len() - 1);
                self.materials.len() - 1
            }
        };
        let c = to_rh(xf.t);
        let (r, u) = (scale(self.cam_right, w * 0.5), scale(self.cam_up, h * 0.5));
        let mi = self.mesh_for(mat, false);
        let mesh = &mut self.meshes[mi];
        let base = mesh.positions.len() as u32;
        mesh.positions.extend_from_slice(&[
            sub(sub(c, r), u),
            sub(add(c, r), u),
            add(add(c, r), u),
            add(sub(c, r), u),
        ]);
        mesh.uv
            .extend_from_slice(&[[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]]);
        if let Some(uv2) = mesh.uv2.as_mut() {
            uv2.extend_from_slice(&[[0.0; 2]; 4]);
        }
        mesh.indices
            .extend_from_slice(&[base, base + 1, base + 2, base, base + 2, base + 3]);
        Ok(())
    }

    fn library(&mut self, name: &str) -> Result<Option<Rc<Digest>>, SceneError> {
        if let Some(d) = self.lib_cache.get(name) {
            return Ok(Some(d.clone()));
        }
        let dir = self.root.join("library").join(name);
        let file = dir.join("node.xml");
        if !file.is_file() {
            return Ok(None);
        }
        let mut mats = HashMap::new();
        parse_materials(&dir.join("materials.xml"), &mut mats)?;
        for (k, v) in mats {
            self.lib_mats.entry(k).or_insert(v);
        }
        let d = Rc::new(digest(&file, &dir, self.root)?);
        self.lib_cache.insert(name.to_string(), d.clone());
        Ok(Some(d))
    }

    fn place(&mut self, items: &[Item], parent: &Xf, depth: u32) -> Result<(), SceneError> {
        for it in items {
            match it {
                Item::Model { path, xf } => {
                    if path.is_file() {
                        self.add_model(path, &parent.then(xf))?;
                    }
                }
                Item::Lod { levels, xf } => {
                    let w = parent.then(xf);
                    let d = len(sub(to_rh(w.t), self.eye));
                    if let Some((_, path)) = levels.iter().find(|(ld, _)| *ld >= d) {
                        if path.is_file() {
                            self.add_model(path, &w)?;
                        }
                    }
                }
                Item::Library { name, xf } => {
                    if depth < MAX_LIBRARY_DEPTH {
                        if let Some(d) = self.library(name)? {
                            self.place(&d.items, &parent.then(xf), depth + 1)?;
                        }
                    }
                }
                Item::Billboard {
                    dir,
                    texture,
                    width,
                    height,
                    xf,
                } => {
                    let w = parent.then(xf);
                    self.add_billboard(dir, texture, *width, *height, &w)?;
                }
            }
        }
        Ok(())
    }

    /// The sky cube around the eye; `names` has 6 textures (top, bottom,
    /// left, right, front, back) or one for every face.
    fn add_sky(&mut self, names: &[String]) -> Result<(), SceneError> {
        let pick = |i: usize| &names[if names.len() >= 6 { i } else { 0 }];
        let s = SKY_HALF_SIZE;
        let e = self.eye;
        // Faces in right-handed coordinates (z already flipped), each as
        // (corner, u axis, v axis) seen from inside, v = 0 at the top.
        let faces: [(Vec3, Vec3, Vec3); 6] = [
            ([-s, s, -s], [2.0 * s, 0.0, 0.0], [0.0, 0.0, 2.0 * s]), // top (+y)
            ([-s, -s, s], [2.0 * s, 0.0, 0.0], [0.0, 0.0, -2.0 * s]), // bottom (-y)
            ([s, s, -s], [0.0, 0.0, 2.0 * s], [0.0, -2.0 * s, 0.0]), // left (+x)
            ([-s, s, s], [0.0, 0.0, -2.0 * s], [0.0, -2.0 * s, 0.0]), // right (-x)
            ([-s, s, s], [2.0 * s, 0.0, 0.0], [0.0, -2.0 * s, 0.0]), // front (+z)
            ([s, s, -s], [-2.0 * s, 0.0, 0.0], [0.0, -2.0 * s, 0.0]), // back (-z)
        ];
        for (i, (c, u, v)) in faces.iter().enumerate() {
            let name = pick(i).clone();
            let Some(path) = self.find_texture(&name, &self.track_dir.clone()) else {
                continue;
            };
            let key = (MatKey::Sky(path.clone()), Blend::Opaque as u8);
            let mat = match self.mat_ids.get(&key) {
                Some(&m) => m,
                None => {
                    let t = self.texture(&path, false)?;
                    self.materials.push(Material {
                        name: format!("sky {name}"),
                        blend: Blend::Opaque,
                        shader: shader::unlit(t, Filter::Bilinear),
                    });
                    self.mat_ids.insert(key, self.materials.len() - 1);
                    self.materials.len() - 1
                }
            };
            let p0 = add(e, *c);
            let pts = [p0, add(p0, *u), add(add(p0, *u), *v), add(p0, *v)];
            // Seen from inside: make the winding counter-clockwise there.
            let n = cross(sub(pts[1], pts[0]), sub(pts[3], pts[0]));
            let inward = sub(e, p0);
            let idx: [u32; 6] = if n[0] * inward[0] + n[1] * inward[1] + n[2] * inward[2] > 0.0 {
                [0, 1, 2, 0, 2, 3]
            } else {
                [0, 2, 1, 0, 3, 2]
            };
            self.meshes.push(Mesh {
                positions: pts.to_vec(),
                uv: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
                uv2: None,
                indices: idx.to_vec(),
                material: mat,
            });
        }
        Ok(())
    }
}

/// A camera selector.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CameraSel {
    /// Behind kart start position N.
    Start(usize),
    /// At this fraction (0..1) of the driveline.
    Driveline(f32),
}

/// Parse `start:N` or `driveline:F`.
pub fn parse_camera(sel: &str) -> Option<CameraSel> {
    let (kind, arg) = sel.split_once(':')?;
    match kind.trim() {
        "start" => arg.trim().parse().ok().map(CameraSel::Start),
        "driveline" => arg
            .trim()
            .parse::<f32>()
            .ok()
            .filter(|f| (0.0..=1.0).contains(f))
            .map(CameraSel::Driveline),
        _ => None,
    }
}

/// The kart (or camera base) position and direction of travel in the
/// game's coordinates, from the selector.
fn camera_base(
    sel: CameraSel,
    track_dir: &Path,
    scene: &Digest,
    scene_file: &Path,
) -> Result<(Vec3, Vec3, bool), SceneError> {
    let quads_file = track_dir.join("quads.xml");
    let graph_file = track_dir.join("graph.xml");
    let line = if quads_file.is_file() {
        let quads = parse_quads(&read_text(&quads_file)?, &quads_file)?;
        let succ = if graph_file.is_file() {
            parse_graph(&read_text(&graph_file)?, &graph_file, quads.len())?
        } else {
            (0..quads.len())
                .map(|i| vec![(i + 1) % quads.len()])
                .collect()
        };
        main_line(&quads, &succ)
    } else {
        Vec::new()
    };
    match sel {
        CameraSel::Driveline(f) => {
            if line.is_empty() {
                return Err(SceneError::in_file(
                    &quads_file,
                    "camera driveline:F needs a driveline (quads.xml): this track has none",
                ));
            }
            let (p, dir) = along(&line, f * line_length(&line));
            Ok((p, dir, false))
        }
        CameraSel::Start(n) => {
            if !scene.starts.is_empty() {
                let (p, h) = *scene.starts.get(n).ok_or_else(|| {
                    SceneError::in_file(
                        scene_file,
                        format!(
                            "camera start:{n}: the track has {} start positions",
                            scene.starts.len()
                        ),
                    )
                })?;
                let (s, c) = h.to_radians().sin_cos();
                return Ok((p, [s, 0.0, c], false));
            }
            if !line.is_empty() {
                if n >= 64 {
                    return Err(SceneError::in_file(
                        scene_file,
                        format!("camera start:{n}: at most 64 karts"),
                    ));
                }
                let (kpr, fwd, side, upw) = scene.default_start.unwrap_or((2, 1.5, 3.0, 0.1));
                let behind = 0.1 + fwd * (n as f32 + 1.0);
                let (p, dir) = along(&line, -behind);
                // Lateral axis: horizontal, perpendicular to travel.
                let lateral = normalize(cross([0.0, 1.0, 0.0], dir));
                let col = (n % kpr) as f32 - (kpr as f32 - 1.0) * 0.5;
                let p = add(add(p, scale(lateral, col * side)), [0.0, upw, 0.0]);
                return Ok((p, dir, false));
            }
            if let Some(&c) = scene.cutscene_cameras.get(n) {
                return Ok((c, [0.0, 0.0, 1.0], true));
            }
            Err(SceneError::in_file(
                scene_file,
                format!(
                    "camera start:{n}: no <start> elements, no driveline (quads.xml) and {} cutscene cameras",
                    scene.cutscene_cameras.len()
                ),
            ))
        }
    }
}

/// Load track `def.map` from `data_root` (see the module documentation).
pub fn load(data_root: &Path, def: &SceneDef) -> Result<Scene, SceneError> {
    let track_dir = data_root.join("tracks").join(&def.map);
    let scene_file = track_dir.join("scene.xml");
    if !scene_file.is_file() {
        return Err(SceneError::in_file(
            &scene_file,
            format!(
                "no track `{}` here (data root must be <unpacked supertuxkart-data>/usr/share/games/supertuxkart/data)",
                def.map
            ),
        ));
    }
    let sel = parse_camera(&def.camera).ok_or_else(|| {
        SceneError::in_file(
            &scene_file,
            format!(
                "camera `{}`: expected start:N or driveline:F (0 <= F <= 1)",
                def.camera
            ),
        )
    })?;
    let scene_digest = digest(&scene_file, &track_dir, data_root)?;

    // Camera (game coordinates), then converted.
    let (base, dir, cutscene) = camera_base(sel, &track_dir, &scene_digest, &scene_file)?;
    let (eye, target) = match sel {
        _ if cutscene => (base, base), // target fixed below from the bounds
        CameraSel::Start(_) => (
            add(add(base, scale(dir, -CAM_BACK)), [0.0, CAM_UP, 0.0]),
            add(add(base, scale(dir, CAM_AHEAD)), [0.0, CAM_UP * 0.5, 0.0]),
        ),
        CameraSel::Driveline(_) => (
            add(base, [0.0, CAM_UP, 0.0]),
            add(add(base, scale(dir, CAM_AHEAD)), [0.0, CAM_UP * 0.75, 0.0]),
        ),
    };
    let eye = to_rh(eye);
    let mut target = to_rh(target);

    let mut b = Builder {
        root: data_root,
        track_dir: track_dir.clone(),
        track_mats: HashMap::new(),
        lib_mats: HashMap::new(),
        global_mats: HashMap::new(),
        tex_index: HashMap::new(),
        spm_cache: HashMap::new(),
        lib_cache: HashMap::new(),
        eye,
        cam_right: [1.0, 0.0, 0.0],
        cam_up: [0.0, 1.0, 0.0],
        textures: Vec::new(),
        tex_paths: Vec::new(),
        tex_ids: HashMap::new(),
        materials: Vec::new(),
        mat_ids: HashMap::new(),
        meshes: Vec::new(),
        missing: Vec::new(),
    };
    parse_materials(&track_dir.join("materials.xml"), &mut b.track_mats)?;
    parse_materials(
        &data_root.join("textures").join("materials.xml"),
        &mut b.global_mats,
    )?;
    index_textures(&data_root.join("textures"), &mut b.tex_index, 0);
    let fwd = normalize(sub(target, eye));
    if !cutscene {
        b.cam_right = normalize(cross(fwd, [0.0, 1.0, 0.0]));
        b.cam_up = cross(b.cam_right, fwd);
    }
    b.place(&scene_digest.items, &Xf::IDENTITY, 0)?;
    if cutscene {
        // Look at the centre of the scene's bounds.
        let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
        for m in &b.meshes {
            for p in &m.positions {
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
        }
        target = if lo[0] <= hi[0] {
            scale(add(lo, hi), 0.5)
        } else {
            add(eye, [0.0, 0.0, -1.0])
        };
        if len(sub(target, eye)) < 1e-3 {
            target = add(eye, [0.0, 0.0, -1.0]);
        }
    }
    // Order: opaque and alpha-tested, sky, alpha-blended.
    let mut meshes = std::mem::take(&mut b.meshes);
    meshes.retain(|m| !m.indices.is_empty());
    if let Some(sky) = &scene_digest.sky {
        b.add_sky(sky)?;
    }
    let sky = std::mem::take(&mut b.meshes);
    let (blended, solid): (Vec<Mesh>, Vec<Mesh>) = meshes
        .into_iter()
        .partition(|m| b.materials[m.material].blend == Blend::AlphaBlend);
    let mut all = solid;
    all.extend(sky);
    all.extend(blended);
    let tris: usize = all.iter().map(|m| m.indices.len() / 3).sum();
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let images = decode_images(&b.tex_paths, MAX_TEXTURE_SIDE, threads)?;
    for (t, (width, height, rgba)) in b.textures.iter_mut().zip(images) {
        (t.width, t.height, t.rgba) = (width, height, rgba);
    }
    let mut missing = std::mem::take(&mut b.missing);
    missing.sort();
    missing.dedup();
    Ok(Scene {
        name: format!("supertuxkart:{}:{}", def.map, def.camera.replace(':', "")),
        source: format!(
            "SuperTuxKart track `{}` (Debian supertuxkart-data, GPL / CC-BY-SA; {} triangles, {} textures, {} missing images{})",
            def.map,
            tris,
            b.textures.len(),
            missing.len(),
            if missing.is_empty() { String::new() } else { format!(": {}", missing.join(", ")) }
        ),
        meshes: all,
        materials: b.materials,
        textures: b.textures,
        camera: Camera::Perspective {
            eye,
            target,
            up: [0.0, 1.0, 0.0],
            fov_y_deg: FOV_Y_DEG,
            near: NEAR,
            far: FAR,
        },
    })
}

/// Index image files under `dir` by lower-case file name (first found wins,
/// directories visited in name order).
fn index_textures(dir: &Path, out: &mut HashMap<String, PathBuf>, depth: u32) {
    let Ok(rd) = std::fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<PathBuf> = rd.flatten().map(|e| e.path()).collect();
    entries.sort();
    let (dirs, files): (Vec<PathBuf>, Vec<PathBuf>) = entries.into_iter().partition(|p| p.is_dir());
    for f in files {
        let ext = f
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
            .unwrap_or_default();
        if matches!(ext.as_str(), "png" | "jpg" | "jpeg") {
            if let Some(n) = f.file_name() {
                out.entry(n.to_string_lossy().to_ascii_lowercase())
                    .or_insert(f.clone());
            }
        }
    }
    if depth < 4 {
        for d in dirs {
            index_textures(&d, out, depth + 1);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::def::Game;
    use proptest::prelude::*;

    fn def(map: &str, camera: &str) -> SceneDef {
        SceneDef {
            name: format!("test-{map}"),
            game: Game::Supertuxkart,
            map: map.into(),
            camera: camera.into(),
            width: 1960,
            height: 768,
            description: String::new(),
            shader: None,
        }
    }

    /// A hand-made SPM: one static mesh, normals and vertex colours, two
    /// materials (one with a second texture), `nv` vertices in the first
    /// buffer (u16 indices past 255) and a 3-vertex second buffer.
    fn tiny_spm(nv: usize) -> Vec<u8> {
        let mut b = Vec::new();
        b.extend_from_slice(b"SP");
        b.push(0x08 | 2); // version 1, static
        b.push(0x03); // normals + colours
        for v in [-1.0f32, 0.0, -2.0, 1.0, 2.0, 3.0] {
            b.extend_from_slice(&v.to_le_bytes());
        }
        b.extend_from_slice(&2u16.to_le_bytes());
        for (t1, t2) in [("a.png", ""), ("b.jpg", "lm.png")] {
            b.push(t1.len() as u8);
            b.extend_from_slice(t1.as_bytes());
            b.push(t2.len() as u8);
            b.extend_from_slice(t2.as_bytes());
        }
        b.extend_from_slice(&1u16.to_le_bytes()); // sectors
        b.extend_from_slice(&2u16.to_le_bytes()); // buffers
                                                  // Buffer 0: material 0, nv vertices.
        b.extend_from_slice(&(nv as u32).to_le_bytes());
        b.extend_from_slice(&((nv - 2) as u32 * 3).to_le_bytes());
        b.extend_from_slice(&0u16.to_le_bytes());
        for i in 0..nv {
            for v in [i as f32, 0.5, -(i as f32)] {
                b.extend_from_slice(&v.to_le_bytes());
            }
            b.extend_from_slice(&[0, 0, 0, 0]); // normal
            if i % 2 == 0 {
                b.push(128); // white
            } else {
                b.extend_from_slice(&[255, 10, 20, 30]);
            }
            b.extend_from_slice(&0x3C00u16.to_le_bytes()); // u = 1
            b.extend_from_slice(&0x3800u16.to_le_bytes()); // v = 0.5
        }
        let wide = nv > 255;
        for t in 0..nv - 2 {
            for i in [0, t + 1, t + 2] {
                if wide {
                    b.extend_from_slice(&(i as u16).to_le_bytes());
                } else {
                    b.push(i as u8);
                }
            }
        }
        // Buffer 1: material 1 (two UV sets), 3 vertices.
        b.extend_from_slice(&3u32.to_le_bytes());
        b.extend_from_slice(&3u32.to_le_bytes());
        b.extend_from_slice(&1u16.to_le_bytes());
        for i in 0..3 {
            for v in [0.0f32, i as f32, 0.0] {
                b.extend_from_slice(&v.to_le_bytes());
            }
            b.extend_from_slice(&[0, 0, 0, 0]);
            b.push(128);
            b.extend_from_slice(&0xC000u16.to_le_bytes()); // u = -2
            b.extend_from_slice(&0x0000u16.to_le_bytes()); // v = 0
            b.extend_from_slice(&0x3400u16.to_le_bytes()); // u2 = 0.25
            b.extend_from_slice(&0x3C00u16.to_le_bytes()); // v2 = 1
        }
        b.extend_from_slice(&[2, 1, 0]);
        b
    }

    #[test]
    fn half_floats() {
        assert_eq!(half_to_f32(0x3C00), 1.0);
        assert_eq!(half_to_f32(0xC000), -2.0);
        assert_eq!(half_to_f32(0x3555), 0.333_251_95);
        assert_eq!(half_to_f32(0x0001), 2f32.powi(-24));
        assert_eq!(half_to_f32(0x7BFF), 65504.0);
        assert!(half_to_f32(0x7C00).is_infinite());
        assert!(half_to_f32(0x7E00).is_nan());
    }

    #[test]
    fn parses_a_tiny_spm() {
        for nv in [4, 300] {
            let s = parse_spm(&tiny_spm(nv), Path::new("t.spm")).unwrap();
            assert!(!s.skinned);
            assert_eq!(s.bbox, [-1.0, 0.0, -2.0, 1.0, 2.0, 3.0]);
            assert_eq!(s.materials[0].texture.as_deref(), Some("a.png"));
            assert_eq!(s.materials[0].texture2, None);
            assert_eq!(s.materials[1].texture2.as_deref(), Some("lm.png"));
            assert_eq!(s.buffers.len(), 2);
            let b0 = &s.buffers[0];
            assert_eq!(b0.positions.len(), nv);
            assert_eq!(b0.positions[3], [3.0, 0.5, -3.0]);
            assert_eq!(b0.uv.as_ref().unwrap()[nv - 1], [1.0, 0.5]);
            assert!(b0.uv2.is_none());
            assert_eq!(b0.indices.len(), (nv - 2) * 3);
            assert_eq!(
                &b0.indices[b0.indices.len() - 3..],
                &[0, nv as u32 - 2, nv as u32 - 1]
            );
            let b1 = &s.buffers[1];
            assert_eq!(b1.material, 1);
            assert_eq!(b1.uv.as_ref().unwrap()[0], [-2.0, 0.0]);
            assert_eq!(b1.uv2.as_ref().unwrap()[2], [0.25, 1.0]);
            assert_eq!(b1.indices, vec![2, 1, 0]);
        }
    }

    #[test]
    fn spm_errors_name_file_and_offset() {
        let f = Path::new("bad.spm");
        let e = parse_spm(b"XX\x0a\x03", f).unwrap_err();
        assert_eq!((e.file.as_path(), e.offset), (f, Some(0)));
        let mut v = tiny_spm(4);
        v[2] = 0x10; // version 2
        assert_eq!(parse_spm(&v, f).unwrap_err().offset, Some(2));
        let mut v = tiny_spm(4);
        v[2] = 0x08; // space-partitioned
        assert!(parse_spm(&v, f)
            .unwrap_err()
            .message
            .contains("space-partitioned"));
        // An index past the vertices: the first index of buffer 0.
        let mut v = tiny_spm(4);
        let first_index = v.len() - 3 - (3 * (12 + 4 + 1 + 8) + 10) - 6;
        v[first_index] = 9;
        let e = parse_spm(&v, f).unwrap_err();
        assert_eq!(e.offset, Some(first_index as u64), "{e}");
        assert!(e.message.contains("out of range"), "{e}");
        // Truncated.
        let v = tiny_spm(4);
        let e = parse_spm(&v[..v.len() - 1], f).unwrap_err();
        assert!(e.message.contains("truncated"), "{e}");
    }

    proptest! {
        #[test]
        fn spm_random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..512)) {
            if let Err(e) = parse_spm(&bytes, Path::new("r.spm")) {
                prop_assert_eq!(e.file, PathBuf::from("r.spm"));
                prop_assert!(e.offset.unwrap() <= bytes.len() as u64);
            }
        }

        #[test]
        fn spm_with_a_valid_header_and_random_body_never_panics(body in proptest::collection::vec(any::<u8>(), 0..400)) {
            let mut v = tiny_spm(4)[..28].to_vec();
            v.extend_from_slice(&body);
            let _ = parse_spm(&v, Path::new("r.spm"));
        }

        #[test]
        fn spm_truncations_are_errors(cut in 0usize..1000, nv in 3usize..300) {
            let v = tiny_spm(nv);
            let cut = cut % v.len();
            let e = parse_spm(&v[..cut], Path::new("t.spm")).unwrap_err();
            prop_assert!(e.offset.unwrap() <= cut as u64);
        }

        #[test]
        fn spm_corruptions_never_panic(at in 0usize..2000, byte in any::<u8>()) {
            let mut v = tiny_spm(5);
            let at = at % v.len();
            v[at] = byte;
            let _ = parse_spm(&v, Path::new("c.spm"));
        }
    }

    #[test]
    fn transforms_follow_irrlicht_euler_order() {
        // Heading 90 about Y turns +Z into +X; X rotation first, then Y.
        let x = Xf::from_parts([1.0, 2.0, 3.0], [0.0, 90.0, 0.0], [1.0; 3]);
        let p = x.apply([0.0, 0.0, 1.0]);
        assert!(
            (p[0] - 2.0).abs() < 1e-5 && (p[1] - 2.0).abs() < 1e-5 && (p[2] - 3.0).abs() < 1e-5
        );
        let x = Xf::from_parts([0.0; 3], [90.0, 90.0, 0.0], [2.0, 1.0, 1.0]);
        // (0,1,0) -X90-> (0,0,1) -Y90-> (1,0,0).
        let p = x.apply([0.0, 1.0, 0.0]);
        assert!(
            (p[0] - 1.0).abs() < 1e-5 && p[1].abs() < 1e-5 && p[2].abs() < 1e-5,
            "{p:?}"
        );
        // Scale applies first.
        let p = x.apply([1.0, 0.0, 0.0]);
        assert!((len(p) - 2.0).abs() < 1e-5);
        let a = Xf::from_parts([1.0, 0.0, 0.0], [0.0, 30.0, 10.0], [1.0; 3]);
        let b = Xf::from_parts([0.0, 5.0, 0.0], [20.0, 0.0, 0.0], [1.5; 3]);
        let q = [0.3, -0.7, 2.0];
        let (c1, c2) = (a.then(&b).apply(q), a.apply(b.apply(q)));
        assert!(len(sub(c1, c2)) < 1e-4);
    }

    #[test]
    fn camera_selectors() {
        assert_eq!(parse_camera("start:3"), Some(CameraSel::Start(3)));
        assert_eq!(
            parse_camera("driveline:0.25"),
            Some(CameraSel::Driveline(0.25))
        );
        assert_eq!(parse_camera("driveline:2"), None);
        assert_eq!(parse_camera("spawn:0"), None);
        assert_eq!(parse_camera("start"), None);
    }

    #[test]
    fn driveline_quads_and_graph() {
        let q = r#"<quads><quad p0="0 0 0" p1="2 0 0" p2="2 0 10" p3="0 0 10"/>
            <quad p0="0:3" p1="0:2" p2="2 0 20" p3="0 0 20"/></quads>"#;
        let quads = parse_quads(q, Path::new("quads.xml")).unwrap();
        assert_eq!(quads[1][0], [0.0, 0.0, 10.0]);
        assert_eq!(quads[1][1], [2.0, 0.0, 10.0]);
        let g =
            r#"<graph><node-list from-quad="0" to-quad="1"/><edge-loop from="0" to="1"/></graph>"#;
        let succ = parse_graph(g, Path::new("graph.xml"), 2).unwrap();
        assert_eq!(succ, vec![vec![1], vec![0]]);
        let line = main_line(&quads, &succ);
        assert_eq!(line.len(), 2);
        assert_eq!(line_length(&line), 20.0);
        let (p, d) = along(&line, 15.0);
        assert_eq!((p, d), ([1.0, 0.0, 15.0], [0.0, 0.0, 1.0]));
        // Behind the start: wraps onto the end of the loop.
        let (p, _) = along(&line, -2.0);
        assert_eq!(p, [1.0, 0.0, 18.0]);
        let bad = r#"<quads><quad p0="5:3" p1="0 0 0" p2="0 0 0" p3="0 0 0"/></quads>"#;
        let e = parse_quads(bad, Path::new("quads.xml")).unwrap_err();
        assert_eq!(e.offset, Some(7));
        let e = parse_graph(
            "<graph><edge from=\"0\" to=\"7\"/></graph>",
            Path::new("g.xml"),
            2,
        )
        .unwrap_err();
        assert!(e.message.contains("out of range"));
        let e = parse_quads("<quads><quad", Path::new("q.xml")).unwrap_err();
        assert!(e.offset.is_some() && e.message.contains("XML"), "{e}");
    }

    #[test]
    fn conditions_for_a_normal_race() {
        assert!(condition_holds(None));
        assert!(condition_holds(Some("isTrackNotReverse")));
        assert!(condition_holds(Some("isNotCTF")));
        assert!(!condition_holds(Some("isTrackReverse")));
        assert!(!condition_holds(Some("isLocked(gp1)")));
        assert!(!condition_holds(Some("false")));
    }

    #[test]
    fn images_decode_in_order_once_each_on_any_number_of_threads() {
        let dir = std::env::temp_dir().join(format!("wasp-stk-decode-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mut paths = Vec::new();
        for (i, name) in ["a.png", "b.png", "c.png"].iter().enumerate() {
            let p = dir.join(name);
            image::RgbaImage::from_pixel(2 + i as u32, 3, image::Rgba([i as u8, 2, 3, 255]))
                .save(&p)
                .unwrap();
            paths.push(p);
        }
        let list = vec![
            paths[1].clone(),
            paths[0].clone(),
            paths[1].clone(),
            paths[2].clone(),
        ];
        let one = decode_images(&list, 1024, 1).unwrap();
        assert_eq!(
            one.iter().map(|d| (d.0, d.2[0])).collect::<Vec<_>>(),
            vec![(3, 1), (2, 0), (3, 1), (4, 2)]
        );
        for threads in [2, 4] {
            assert_eq!(decode_images(&list, 1024, threads).unwrap(), one);
        }
        // The first failure in list order is the error.
        let bad = vec![paths[0].clone(), dir.join("x.png"), dir.join("y.png")];
        let e = decode_images(&bad, 1024, 3).unwrap_err();
        assert!(e.to_string().contains("x.png"), "{e}");
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// A whole synthetic track on disk: scene.xml with the track model, a
    /// static object, a library instance, a LOD instance, quads, a
    /// texture and materials.xml.
    #[test]
    fn loads_a_synthetic_track() {
        let root = std::env::temp_dir().join(format!("wasp-stk-test-{}", std::process::id()));
        let track = root.join("tracks/mini");
        let lib = root.join("library/thing");
        std::fs::create_dir_all(&track).unwrap();
        std::fs::create_dir_all(&lib).unwrap();
        std::fs::create_dir_all(root.join("textures")).unwrap();
        std::fs::write(track.join("m.spm"), tiny_spm(4)).unwrap();
        std::fs::write(lib.join("m.spm"), tiny_spm(4)).unwrap();
        let png = |p: &Path, a: u8| {
            image::RgbaImage::from_pixel(4, 2, image::Rgba([1, 2, 3, a]))
                .save(p)
                .unwrap();
        };
        png(&track.join("a.png"), 255);
        png(&root.join("textures/lm.png"), 255);
        image::RgbImage::from_pixel(2048, 16, image::Rgb([9, 9, 9]))
            .save(root.join("textures/b.jpg"))
            .unwrap();
        std::fs::write(
            track.join("materials.xml"),
            r#"<materials><material name="a.png" shader="alphatest"/></materials>"#,
        )
        .unwrap();
        std::fs::write(
            track.join("quads.xml"),
            r#"<quads><quad p0="-2 0 0" p1="2 0 0" p2="2 0 10" p3="-2 0 10"/>
               <quad p0="0:3" p1="0:2" p2="2 0 20" p3="-2 0 20"/></quads>"#,
        )
        .unwrap();
        std::fs::write(
            track.join("graph.xml"),
            r#"<graph><edge-loop from="0" to="1"/></graph>"#,
        )
        .unwrap();
        std::fs::write(
            track.join("scene.xml"),
            r#"<scene>
                <lod><group name="g"><static-object lod_distance="1000" lod_group="g" model="m.spm" xyz="0 0 0"/></group></lod>
                <track model="m.spm" x="0" y="0" z="0">
                  <static-object model="m.spm" xyz="10 0 0" hpr="0 90 0" scale="2 2 2"/>
                  <static-object model="m.spm" xyz="10 0 0" interaction="physics-only"/>
                  <static-object model="m.spm" xyz="10 0 0" if="isTrackReverse"/>
                  <static-object lod_instance="true" lod_group="g" xyz="0 5 0"/>
                </track>
                <library name="thing" xyz="0 0 5"/>
                <default-start karts-per-row="2" forwards-distance="1.5" sidewards-distance="3" upwards-distance="0.1"/>
              </scene>"#,
        )
        .unwrap();
        std::fs::write(
            lib.join("node.xml"),
            r#"<scene><object type="animation" model="m.spm" xyz="1 1 1"/></scene>"#,
        )
        .unwrap();
        let s = load(&root, &def("mini", "start:1")).unwrap();
        // 5 instances (track, object, LOD, library) x 2 buffers... 4 instances.
        let tris: usize = s.meshes.iter().map(|m| m.indices.len() / 3).sum();
        assert_eq!(tris, 4 * 3);
        assert_eq!(s.meshes.len(), 2);
        let m0 = s.meshes.iter().find(|m| m.uv2.is_none()).unwrap();
        let m1 = s.meshes.iter().find(|m| m.uv2.is_some()).unwrap();
        assert_eq!(s.materials[m0.material].blend, Blend::AlphaTest);
        assert_eq!(
            s.materials[m1.material].shader,
            shader::lightmapped(1, 2, Filter::Trilinear)
        );
        // The 2048-wide JPEG is downscaled to 1024 wide.
        assert!(s.textures.iter().any(|t| t.width == 1024 && t.height == 8));
        // The rotated, scaled object: local (1, 0.5, -1) -> z-flip of
        // (10 + 2*(-1), 1, -2*1) ... check one transformed vertex exists.
        let want = to_rh(
            Xf::from_parts([10.0, 0.0, 0.0], [0.0, 90.0, 0.0], [2.0; 3]).apply([1.0, 0.5, -1.0]),
        );
        assert!(m0.positions.iter().any(|p| len(sub(*p, want)) < 1e-4));
        // Camera: kart 1 is in the second column, 3.1 m behind the line
        // (on the loop's last quad), facing +z in the game = -z here.
        let Camera::Perspective { eye, target, .. } = s.camera else {
            panic!()
        };
        assert!(target[2] < eye[2]);
        assert!((eye[1] - (0.1 + CAM_UP)).abs() < 1e-4, "{eye:?}");
        let e = load(&root, &def("mini", "start:99")).unwrap_err();
        assert!(e.message.contains("64"), "{e}");
        let e = load(&root, &def("nope", "start:0")).unwrap_err();
        assert!(e.file.ends_with("tracks/nope/scene.xml"), "{e}");
        let e = load(&root, &def("mini", "top")).unwrap_err();
        assert!(e.message.contains("start:N"), "{e}");
        std::fs::remove_dir_all(&root).unwrap();
    }

    /// The real data root in the scene cache (`$WASP_SCENES`, else the
    /// user's cache directory), if fetched.
    pub(super) fn real_root() -> Option<PathBuf> {
        let cache = crate::fetch::cache_dir();
        let found = find_data_root(&cache);
        if found.is_none() {
            eprintln!(
                "skipped: no SuperTuxKart data under {} ({DATA_DIRS:?}); run `wasp scenes fetch`",
                cache.display()
            );
        }
        found
    }

    /// Checks on a loaded real scene: UVs finite, textures present and
    /// well-formed, the camera inside the bounds of the geometry.
    pub(super) fn check_real(s: &Scene, min_tris: usize, check_camera: bool) {
        let tris: usize = s.meshes.iter().map(|m| m.indices.len() / 3).sum();
        assert!(tris >= min_tris, "{}: {tris} triangles", s.name);
        let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
        for m in &s.meshes {
            assert_eq!(m.uv.len(), m.positions.len());
            if let Some(uv2) = &m.uv2 {
                assert_eq!(uv2.len(), m.positions.len());
                assert!(uv2.iter().all(|u| u[0].is_finite() && u[1].is_finite()));
            }
            assert!(m.uv.iter().all(|u| u[0].is_finite() && u[1].is_finite()));
            assert!(m.indices.iter().all(|&i| (i as usize) < m.positions.len()));
            if s.materials[m.material].name.starts_with("sky") {
                continue;
            }
            for p in &m.positions {
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
        }
        for mat in &s.materials {
            for op in &mat.shader {
                if let ShaderOp::Tex(t) = op {
                    let tex = &s.textures[t.texture];
                    assert!(
                        tex.width > 0
                            && tex.width <= MAX_TEXTURE_SIDE
                            && tex.height <= MAX_TEXTURE_SIDE
                    );
                    assert_eq!(tex.rgba.len(), (tex.width * tex.height * 4) as usize);
                }
            }
        }
        let Camera::Perspective { eye, .. } = s.camera else {
            panic!()
        };
        for k in 0..3 {
            assert!(
                !check_camera || eye[k] >= lo[k] && eye[k] <= hi[k],
                "{}: eye {eye:?} outside {lo:?}..{hi:?}",
                s.name
            );
        }
    }

    #[test]
    #[ignore = "needs fetched game data: wasp scenes fetch supertuxkart"]
    fn real_shipped_scenes() {
        let Some(root) = real_root() else { return };
        for d in crate::def::all().unwrap() {
            if d.game != Game::Supertuxkart {
                continue;
            }
            let t = std::time::Instant::now();
            let s = load(&root, &d).unwrap();
            let el = t.elapsed();
            check_real(&s, 10_000, true);
            let tris: usize = s.meshes.iter().map(|m| m.indices.len() / 3).sum();
            eprintln!(
                "{}: {tris} triangles, {} meshes, {} materials, {} textures ({:.1} MiB), loaded in {el:.2?}",
                d.name,
                s.meshes.len(),
                s.materials.len(),
                s.textures.len(),
                s.textures.iter().map(|t| t.rgba.len()).sum::<usize>() as f64 / (1 << 20) as f64
            );
        }
    }

    #[test]
    #[ignore = "needs fetched game data: wasp scenes fetch supertuxkart"]
    fn real_lighthouse_winding_faces_up() {
        let Some(root) = real_root() else { return };
        let s = load(&root, &def("lighthouse", "start:0")).unwrap();
        check_real(&s, 50_000, true);
        let Camera::Perspective { eye, .. } = s.camera else {
            panic!()
        };
        // The ground near the start, below the eye, faces up (+y) when
        // wound counter-clockwise.
        let (mut up, mut down) = (0.0f64, 0.0f64);
        for m in &s.meshes {
            if s.materials[m.material].name.starts_with("sky") {
                continue;
            }
            for t in m.indices.chunks_exact(3) {
                let (a, b, c) = (
                    m.positions[t[0] as usize],
                    m.positions[t[1] as usize],
                    m.positions[t[2] as usize],
                );
                let d = sub(a, eye);
                if d[0].abs() > 30.0 || d[2].abs() > 30.0 || d[1] > 0.0 {
                    continue;
                }
                let n = cross(sub(b, a), sub(c, a));
                if n[1] > 0.0 {
                    up += n[1] as f64
                } else {
                    down -= n[1] as f64
                }
            }
        }
        assert!(up > 10.0 * down, "up {up} down {down}");
    }

    #[test]
    #[ignore = "needs fetched game data: wasp scenes fetch supertuxkart"]
    fn preview_images() {
        let Some(root) = real_root() else { return };
        let list = std::env::var("STK_PREVIEW").unwrap_or("lighthouse:start:0".into());
        for item in list.split(',') {
            let (map, cam) = item.split_once(':').unwrap();
            let s = load(&root, &def(map, cam)).unwrap();
            let out = std::env::temp_dir().join(format!("stk-{map}-{}.png", cam.replace(':', "")));
            super::preview::render(&s, 980, 384, &out);
            eprintln!("{}", out.display());
        }
    }
}

#[cfg(test)]
mod all_tracks {
    use super::*;
    use crate::def::Game;

    /// Every track of the fetched package with `start:0`: reports each
    /// and fails on any load error.
    #[test]
    #[ignore = "needs fetched game data: wasp scenes fetch supertuxkart"]
    fn every_track_loads() {
        let Some(root) = super::tests::real_root() else {
            return;
        };
        let mut fails = Vec::new();
        for m in &tracks(&root).unwrap() {
            let d = SceneDef {
                name: m.clone(),
                game: Game::Supertuxkart,
                map: m.clone(),
                camera: "start:0".into(),
                width: 1960,
                height: 768,
                description: String::new(),
                shader: None,
            };
            let t = std::time::Instant::now();
            match load(&root, &d) {
                Ok(s) => {
                    // Cutscene cameras look at their stage from outside it.
                    let track_xml =
                        std::fs::read_to_string(root.join("tracks").join(m).join("track.xml"))
                            .unwrap_or_default();
                    let cutscene = track_xml.contains("cutscene");
                    super::tests::check_real(&s, 1_000, !cutscene);
                    eprintln!(
                        "OK {m}: {} meshes {} {:?}",
                        s.meshes.len(),
                        s.source.split("SA; ").nth(1).unwrap_or(""),
                        t.elapsed()
                    );
                }
                Err(e) => {
                    eprintln!("FAIL {m}: {e}");
                    fails.push(format!("{m}: {e}"));
                }
            }
        }
        eprintln!("{} failures: {fails:?}", fails.len());
        assert!(fails.is_empty(), "{fails:#?}");
    }
}

/// A crude software preview of a scene (tests only): near-plane clipping,
/// z-buffer, perspective-correct nearest texturing, back faces culled
/// (counter-clockwise = front), to check transforms, winding and cameras
/// by eye.
#[cfg(test)]
pub(crate) mod preview {
    use super::*;

    pub(crate) fn render(scene: &Scene, w: usize, h: usize, out: &Path) {
        let Camera::Perspective {
            eye,
            target,
            up,
            fov_y_deg,
            near,
            ..
        } = scene.camera
        else {
            return;
        };
        let f = normalize(sub(target, eye));
        let r = normalize(cross(f, up));
        let u = cross(r, f);
        let ty = (fov_y_deg.to_radians() * 0.5).tan();
        let tx = ty * w as f32 / h as f32;
        let mut color = vec![[40u8, 40, 60]; w * h];
        let mut depth = vec![0f32; w * h];
        for mesh in &scene.meshes {
            let mat = &scene.materials[mesh.material];
            let tex = mat.shader.iter().find_map(|op| match op {
                ShaderOp::Tex(t) => Some(&scene.textures[t.texture]),
                _ => None,
            });
            let blend = mat.blend;
            for t in mesh.indices.chunks_exact(3) {
                // View space: (x, y, z, u, v).
                let mut poly: Vec<[f32; 5]> = t
                    .iter()
                    .map(|&i| {
                        let d = sub(mesh.positions[i as usize], eye);
                        let uv = mesh.uv[i as usize];
                        [
                            super::super::vec3::dot(d, r),
                            super::super::vec3::dot(d, u),
                            super::super::vec3::dot(d, f),
                            uv[0],
                            uv[1],
                        ]
                    })
                    .collect();
                // Clip against z >= near.
                let mut clipped = Vec::new();
                for k in 0..poly.len() {
                    let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
                    if a[2] >= near {
                        clipped.push(a);
                    }
                    if (a[2] >= near) != (b[2] >= near) {
                        let s = (near - a[2]) / (b[2] - a[2]);
                        let mut p = [0.0; 5];
                        for c in 0..5 {
                            p[c] = a[c] + (b[c] - a[c]) * s;
                        }
                        clipped.push(p);
                    }
                }
                poly = clipped;
                if poly.len() < 3 {
                    continue;
                }
                // Screen: (sx, sy, 1/z, u/z, v/z).
                let scr: Vec<[f32; 5]> = poly
                    .iter()
                    .map(|p| {
                        let iz = 1.0 / p[2];
                        [
                            (p[0] * iz / tx * 0.5 + 0.5) * w as f32,
                            (0.5 - p[1] * iz / ty * 0.5) * h as f32,
                            iz,
                            p[3] * iz,
                            p[4] * iz,
                        ]
                    })
                    .collect();
                for k in 1..scr.len() - 1 {
                    let (a, b, c) = (scr[0], scr[k], scr[k + 1]);
                    // Screen y grows down: front faces have negative area here.
                    let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
                    if area >= 0.0 {
                        continue;
                    }
                    let x0 = a[0].min(b[0]).min(c[0]).max(0.0) as usize;
                    let x1 = (a[0].max(b[0]).max(c[0]).ceil() as usize).min(w);
                    let y0 = a[1].min(b[1]).min(c[1]).max(0.0) as usize;
                    let y1 = (a[1].max(b[1]).max(c[1]).ceil() as usize).min(h);
                    for py in y0..y1 {
                        for px in x0..x1 {
                            let (x, y) = (px as f32 + 0.5, py as f32 + 0.5);
                            let e = |p: [f32; 5], q: [f32; 5]| {
                                (q[0] - p[0]) * (y - p[1]) - (q[1] - p[1]) * (x - p[0])
                            };
                            let (w0, w1, w2) = (e(b, c) / area, e(c, a) / area, e(a, b) / area);
                            if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                                continue;
                            }
                            let iz = w0 * a[2] + w1 * b[2] + w2 * c[2];
                            let o = py * w + px;
                            if iz <= depth[o] {
                                continue;
                            }
                            let uu = (w0 * a[3] + w1 * b[3] + w2 * c[3]) / iz;
                            let vv = (w0 * a[4] + w1 * b[4] + w2 * c[4]) / iz;
                            let texel = match tex {
                                Some(t) => {
                                    let tx = ((uu.rem_euclid(1.0) * t.width as f32) as usize)
                                        .min(t.width as usize - 1);
                                    let ty = ((vv.rem_euclid(1.0) * t.height as f32) as usize)
                                        .min(t.height as usize - 1);
                                    let i = (ty * t.width as usize + tx) * 4;
                                    [t.rgba[i], t.rgba[i + 1], t.rgba[i + 2], t.rgba[i + 3]]
                                }
                                None => [200, 200, 200, 255],
                            };
                            match blend {
                                Blend::Opaque => {
                                    color[o] = [texel[0], texel[1], texel[2]];
                                    depth[o] = iz;
                                }
                                Blend::AlphaTest => {
                                    if texel[3] >= 128 {
                                        color[o] = [texel[0], texel[1], texel[2]];
                                        depth[o] = iz;
                                    }
                                }
                                Blend::AlphaBlend => {
                                    let al = texel[3] as u32;
                                    for ch in 0..3 {
                                        color[o][ch] = ((texel[ch] as u32 * al
                                            + color[o][ch] as u32 * (255 - al))
                                            / 255)
                                            as u8;
                                    }
                                }
                            }
                        }
                    }
                }
            }
        }
        let mut img = image::RgbImage::new(w as u32, h as u32);
        for (i, c) in color.iter().enumerate() {
            img.put_pixel((i % w) as u32, (i / w) as u32, image::Rgb(*c));
        }
        img.save(out).unwrap();
    }
}
