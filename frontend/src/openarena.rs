//! OpenArena maps: Quake 3 IBSP version 46 files inside `.pk3` (zip)
//! archives, their shader scripts, JPEG/TGA textures and lightmaps, with a
//! camera at a player spawn point.
//!
//! # Data layout
//!
//! The data root passed to [`load`] is the directory holding `baseoa/`,
//! `<package root>/usr/share/games/openarena`. `wasp scenes fetch`
//! unpacks the three packages into one package root,
//! `$WASP_SCENES/openarena`, so that `baseoa/` holds all three archives:
//!
//! ```text
//! $WASP_SCENES/openarena/usr/share/games/openarena           <- data root
//!     baseoa/pak0.pk3            (openarena-data) scripts/*.shader, shared textures, models
//!     baseoa/pak1-maps.pk3       (openarena-081-maps) maps/<map>.bsp (50 maps)
//!     baseoa/pak4-textures.pk3   (openarena-081-textures) textures/**
//! ```
//!
//! One directory per package works too: with the data root
//! `$WASP_SCENES/openarena-data/usr/share/games/openarena`, the archives
//! of `$WASP_SCENES/<package>/usr/share/games/openarena/baseoa/` for each
//! of [`PACKAGES`] are read as well (`<data root>/../../../../<package>/...`;
//! an archive whose file name was already found is not read twice).
//! [`DATA_DIRS`] lists both data roots, [`find_data_root`] picks the
//! first present. Archives are read in file-name order, a later one
//! overriding an earlier one's file of the same (case-insensitive) name,
//! as Quake 3 does. [`maps`] lists the `maps/*.bsp` found.
//!
//! # BSP lumps used
//!
//! Header `"IBSP"`, version 46, 17 lumps (offset, length). Used: 0
//! entities (text), 1 shaders (64-byte name, surface flags, contents: 72
//! bytes), 10 vertices (position, surface uv, lightmap uv, normal, RGBA:
//! 44 bytes; a non-finite position is an error, other non-finite
//! attributes become 0: q3map2 left NaN lightmap coordinates on a few
//! vertices of six shipped maps), 11 mesh vertices (i32), 13 faces (104 bytes: shader, fog,
//! type, first vertex, vertex count, first mesh vertex, mesh vertex
//! count, lightmap index, lightmap rectangle and axes, normal, patch
//! size), 14 lightmaps (128x128 RGB each). Face types: 1 (polygon) and 3
//! (triangle mesh) are indexed through the mesh vertices; 2 (Bezier
//! patch: a grid of 3x3-control-point biquadratic patches) is tessellated
//! with [`PATCH_LEVEL`] segments per patch side; 4 (flares) is skipped.
//! Faces are emitted counter-clockwise seen from the front (the BSP
//! stores them clockwise); patch triangles are oriented by their vertex
//! normals. Lightmap indices past the lump (q3map2 `-external`) read
//! `maps/<map>/lm_NNNN.tga` when present.
//!
//! # Shader scripts (`scripts/*.shader`)
//!
//! A minimal parser (`//` and `/* */` comments, quoted tokens, nested
//! braces): per shader, `surfaceparm` values, `skyparms`, and its stages'
//! `map` / `clampMap` / `animMap` (first frame) textures, `blendFunc`
//! and `alphaFunc`. The base texture is the first stage map that is not
//! `$lightmap` / `$whiteimage` (a shader without a script uses the image
//! of its own name). Blend: a `blendFunc` on the first stage makes the
//! surface [`Blend::AlphaBlend`]; otherwise an `alphaFunc` makes it
//! [`Blend::AlphaTest`]; otherwise opaque. `surfaceparm nodraw` (or the
//! nodraw surface flag) and fog volumes are skipped; `surfaceparm sky`
//! surfaces use the `unlit` template with the first stage's image (or the
//! `skyParms` far box's `_ft` side). A face with a lightmap whose shader
//! has a `$lightmap` stage, or no script, uses `lightmapped`; others
//! `standard`. Base textures filter trilinearly, lightmaps bilinearly.
//! Images: `.tga` then `.jpg` (then `.png`) whatever extension the script
//! names; TGA is read by [`decode_tga`] (uncompressed and RLE, true-colour
//! and grey). A texture found in no archive is replaced by one shared
//! 64x64 checkerboard named `missing` (Quake 3 draws its default image
//! there too). Textures wider or taller than [`MAX_TEXTURE_SIDE`] are
//! downscaled to it.
//!
//! # Coordinates and camera
//!
//! Quake units, right-handed, Z up (kept; the camera's `up` is +Z).
//! `spawn:N` is the N-th `info_player_deathmatch` (then
//! `info_player_start`, then CTF team spawns) in entity order: eye
//! [`EYE_HEIGHT`] (26) above its origin, i.e. 50 above the floor the
//! origin floats 24 units over, looking along its `angle` (degrees about
//! Z, 0 = +X). Vertical field of view [`FOV_Y_DEG`] (Quake 3's
//! default `cg_fov 90` horizontal at 4:3), near [`NEAR`], far [`FAR`].

use super::bytes::Bytes;
use super::def::SceneDef;
use super::vec3::{cross, dot, sub};
use super::{
    shader, Blend, Camera, Filter, Material, Mesh, Scene, SceneError, Texture, Vec2, Vec3,
};
use std::collections::HashMap;
use std::fs::File;
use std::io::Read;
use std::path::{Path, PathBuf};

/// Where the data root may be, relative to `$WASP_SCENES`: the three
/// packages unpacked into `openarena/` (`wasp scenes fetch`), or each into
/// its own directory (then the root is in `openarena-data/`).
pub const DATA_DIRS: [&str; 2] = [
    "openarena/usr/share/games/openarena",
    "openarena-data/usr/share/games/openarena",
];
/// The packages whose `baseoa/*.pk3` are read, each unpacked into
/// `$WASP_SCENES/<package>/`.
pub const PACKAGES: [&str; 3] = [
    "openarena-data",
    "openarena-081-maps",
    "openarena-081-textures",
];
/// Vertical field of view: 90 degrees horizontal at 4:3.
pub const FOV_Y_DEG: f32 = 73.739_8;
/// Near plane (Quake units).
pub const NEAR: f32 = 4.0;
/// Far plane (Quake units).
pub const FAR: f32 = 16384.0;
/// Eye height above the spawn point's origin (Quake units): Quake 3's
/// `DEFAULT_VIEWHEIGHT`. Spawn origins sit 24 units above the floor (the
/// player box's centre: every spawn of the shipped maps measured so), so
/// the eye is 50 units above the floor, as in the game.
pub const EYE_HEIGHT: f32 = 26.0;
/// Segments per side of each tessellated 3x3 Bezier patch.
pub const PATCH_LEVEL: usize = 4;
/// Textures larger than this (either side) are downscaled to it.
pub const MAX_TEXTURE_SIDE: u32 = 1024;
/// Lightmap side (texels).
pub const LIGHTMAP_SIDE: usize = 128;

const SURF_NODRAW: i32 = 0x80;
const SURF_SKY: i32 = 0x4;
const CONTENTS_FOG: i32 = 0x40;

/// The first of [`DATA_DIRS`] under `cache` that holds `baseoa/`.
pub fn find_data_root(cache: &Path) -> Option<PathBuf> {
    DATA_DIRS
        .iter()
        .map(|d| cache.join(d))
        .find(|r| r.join("baseoa").is_dir())
}

// ---------------------------------------------------------------------------
// BSP

/// A shader (texture) reference of the BSP.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BspShader {
    /// Shader name (e.g. `textures/base_wall/concrete`).
    pub name: String,
    /// Surface flags.
    pub flags: i32,
    /// Content flags.
    pub contents: i32,
}

/// A drawing vertex.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BspVertex {
    /// Position.
    pub pos: Vec3,
    /// Surface texture coordinates.
    pub uv: Vec2,
    /// Lightmap coordinates.
    pub lm: Vec2,
    /// Normal.
    pub normal: Vec3,
}

/// A face (surface).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BspFace {
    /// Index into [`Bsp::shaders`].
    pub shader: usize,
    /// 1 polygon, 2 patch, 3 mesh, 4 flare.
    pub kind: i32,
    /// First vertex.
    pub first_vertex: usize,
    /// Vertex count.
    pub n_vertices: usize,
    /// First mesh vertex.
    pub first_meshvert: usize,
    /// Mesh vertex count.
    pub n_meshverts: usize,
    /// Lightmap index (negative: none).
    pub lightmap: i32,
    /// Face normal (polygons).
    pub normal: Vec3,
    /// Patch control grid size.
    pub size: [usize; 2],
    /// Byte offset of the face record (for errors).
    pub offset: usize,
}

/// The parts of an IBSP v46 file the loader uses.
#[derive(Clone, Debug, PartialEq)]
pub struct Bsp {
    /// Entity lump text.
    pub entities: String,
    /// Byte offset of the entity lump.
    pub entities_offset: usize,
    /// Shaders.
    pub shaders: Vec<BspShader>,
    /// Vertices.
    pub vertices: Vec<BspVertex>,
    /// Mesh vertices (offsets from a face's first vertex).
    pub meshverts: Vec<i32>,
    /// Faces (validated: ranges inside the vertex and mesh-vertex lumps).
    pub faces: Vec<BspFace>,
    /// Lightmaps, 128x128 RGB each.
    pub lightmaps: Vec<Vec<u8>>,
}

/// Parse an IBSP version 46 file (`file` names it in errors).
pub fn parse_bsp(bytes: &[u8], file: &Path) -> Result<Bsp, SceneError> {
    let r = Bytes::new(bytes, file);
    if r.slice(0, 4, "magic")? != b"IBSP" {
        return Err(r.err(0, "not a Quake 3 BSP: magic is not \"IBSP\""));
    }
    let version = r.i32_at(4, "version")?;
    if version != 46 {
        return Err(r.err(4, format!("BSP version {version} (expected 46)")));
    }
    let lump = |i: usize, rec: usize, what: &str| -> Result<(usize, usize), SceneError> {
        let at = 8 + 8 * i;
        let off = r.i32_at(at, "lump directory")?;
        let len = r.i32_at(at + 4, "lump directory")?;
        if off < 0 || len < 0 || off as usize + len as usize > bytes.len() {
            return Err(r.err(
                at,
                format!(
                    "{what} lump ({off}, {len} bytes) outside the file ({} bytes)",
                    bytes.len()
                ),
            ));
        }
        if !(len as usize).is_multiple_of(rec) {
            return Err(r.err(
                at + 4,
                format!("{what} lump length {len} is not a multiple of {rec}"),
            ));
        }
        Ok((off as usize, len as usize / rec))
    };
    let (eoff, elen) = lump(0, 1, "entities")?;
    let entities = String::from_utf8_lossy(&bytes[eoff..eoff + elen])
        .trim_end_matches('\0')
        .to_string();

    let (soff, sn) = lump(1, 72, "shaders")?;
    let mut shaders = Vec::with_capacity(sn);
    for i in 0..sn {
        let at = soff + 72 * i;
        let raw = r.slice(at, 64, "shader name")?;
        let end = raw.iter().position(|&c| c == 0).unwrap_or(64);
        shaders.push(BspShader {
            name: String::from_utf8_lossy(&raw[..end]).into_owned(),
            flags: r.i32_at(at + 64, "shader flags")?,
            contents: r.i32_at(at + 68, "shader contents")?,
        });
    }

    let (voff, vn) = lump(10, 44, "vertices")?;
    let mut vertices = Vec::with_capacity(vn);
    for i in 0..vn {
        let at = voff + 44 * i;
        let f = |k: usize| r.f32_at(at + 4 * k, "vertex position");
        // Attributes other than the position: non-finite values (q3map2
        // leaves NaN lightmap coordinates on a few vertices of six shipped
        // maps) become 0.
        let g = |k: usize| -> Result<f32, SceneError> {
            let b = r.slice(at + 4 * k, 4, "vertex")?;
            let v = f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
            Ok(if v.is_finite() { v } else { 0.0 })
        };
        vertices.push(BspVertex {
            pos: [f(0)?, f(1)?, f(2)?],
            uv: [g(3)?, g(4)?],
            lm: [g(5)?, g(6)?],
            normal: [g(7)?, g(8)?, g(9)?],
        });
    }

    let (moff, mn) = lump(11, 4, "mesh vertices")?;
    let meshverts = (0..mn)
        .map(|i| r.i32_at(moff + 4 * i, "mesh vertex"))
        .collect::<Result<Vec<_>, _>>()?;

    let (foff, fcount) = lump(13, 104, "faces")?;
    let mut faces = Vec::with_capacity(fcount);
    for i in 0..fcount {
        let at = foff + 104 * i;
        let g = |k: usize| r.i32_at(at + 4 * k, "face");
        let idx = |v: i32, what: &str| -> Result<usize, SceneError> {
            usize::try_from(v).map_err(|_| r.err(at, format!("face {i}: negative {what} {v}")))
        };
        let shader = idx(g(0)?, "shader")?;
        let kind = g(2)?;
        let first_vertex = idx(g(3)?, "first vertex")?;
        let n_vertices = idx(g(4)?, "vertex count")?;
        let first_meshvert = idx(g(5)?, "first mesh vertex")?;
        let n_meshverts = idx(g(6)?, "mesh vertex count")?;
        let lightmap = g(7)?;
        let normal = [
            r.f32_at(at + 84, "face normal")?,
            r.f32_at(at + 88, "face normal")?,
            r.f32_at(at + 92, "face normal")?,
        ];
        let size = [idx(g(24)?, "patch width")?, idx(g(25)?, "patch height")?];
        if shader >= shaders.len() {
            return Err(r.err(
                at,
                format!("face {i}: shader {shader} out of range ({})", shaders.len()),
            ));
        }
        if first_vertex
            .checked_add(n_vertices)
            .is_none_or(|e| e > vertices.len())
        {
            return Err(r.err(
                at + 12,
                format!(
                    "face {i}: vertices {first_vertex}+{n_vertices} out of range ({})",
                    vertices.len()
                ),
            ));
        }
        if matches!(kind, 1 | 3) {
            if first_meshvert
                .checked_add(n_meshverts)
                .is_none_or(|e| e > meshverts.len())
            {
                return Err(r.err(
                    at + 20,
                    format!(
                        "face {i}: mesh vertices {first_meshvert}+{n_meshverts} out of range ({})",
                        meshverts.len()
                    ),
                ));
            }
            if n_meshverts % 3 != 0 {
                return Err(r.err(
                    at + 24,
                    format!("face {i}: {n_meshverts} mesh vertices, not whole triangles"),
                ));
            }
            let span = &meshverts[first_meshvert..first_meshvert + n_meshverts];
            for (j, &m) in span.iter().enumerate() {
                let k = first_meshvert + j;
                if m < 0 || m as usize >= n_vertices {
                    return Err(r.err(
                        moff + 4 * k,
                        format!("face {i}: mesh vertex {m} outside its {n_vertices} vertices"),
                    ));
                }
            }
        }
        if kind == 2 {
            let [w, h] = size;
            if w < 3 || h < 3 || w % 2 == 0 || h % 2 == 0 || w.checked_mul(h) != Some(n_vertices) {
                return Err(r.err(
                    at + 96,
                    format!(
                        "face {i}: patch grid {w}x{h} (odd, >= 3, = {n_vertices} vertices expected)"
                    ),
                ));
            }
        }
        faces.push(BspFace {
            shader,
            kind,
            first_vertex,
            n_vertices,
            first_meshvert,
            n_meshverts,
            lightmap,
            normal,
            size,
            offset: at,
        });
    }

    let lm_bytes = LIGHTMAP_SIDE * LIGHTMAP_SIDE * 3;
    let (loff, ln) = lump(14, lm_bytes, "lightmaps")?;
    let lightmaps = (0..ln)
        .map(|i| bytes[loff + i * lm_bytes..loff + (i + 1) * lm_bytes].to_vec())
        .collect();
    Ok(Bsp {
        entities,
        entities_offset: eoff,
        shaders,
        vertices,
        meshverts,
        faces,
        lightmaps,
    })
}

// ---------------------------------------------------------------------------
// Text: entities and shader scripts

/// Tokens of Quake text (entities, shader scripts): `//` and `/* */`
/// comments, quoted strings, braces; each with its byte offset.
fn tokenize(text: &str) -> Vec<(usize, String, bool)> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if c.is_ascii_whitespace() {
            i += 1;
        } else if c == b'/' && b.get(i + 1) == Some(&b'/') {
            while i < b.len() && b[i] != b'\n' {
                i += 1;
            }
        } else if c == b'/' && b.get(i + 1) == Some(&b'*') {
            i += 2;
            while i < b.len() && !(b[i] == b'*' && b.get(i + 1) == Some(&b'/')) {
                i += 1;
            }
            i = (i + 2).min(b.len());
        } else if c == b'"' {
            let start = i;
            i += 1;
            let s = i;
            while i < b.len() && b[i] != b'"' {
                i += 1;
            }
            out.push((
                start,
                String::from_utf8_lossy(&b[s..i.min(b.len())]).into_owned(),
                true,
            ));
            i += 1;
        } else if c == b'{' || c == b'}' {
            out.push((i, (c as char).to_string(), false));
            i += 1;
        } else {
            let s = i;
            while i < b.len() && !b[i].is_ascii_whitespace() && b[i] != b'{' && b[i] != b'}' {
                if b[i] == b'/' && matches!(b.get(i + 1), Some(b'/' | b'*')) {
                    break;
                }
                i += 1;
            }
            out.push((s, String::from_utf8_lossy(&b[s..i]).into_owned(), false));
        }
    }
    out
}

/// Parse the entity lump: a list of key/value maps.
pub fn parse_entities(
    text: &str,
    file: &Path,
    base: usize,
) -> Result<Vec<HashMap<String, String>>, SceneError> {
    let toks = tokenize(text);
    let mut out = Vec::new();
    let mut i = 0;
    while i < toks.len() {
        let (at, t, quoted) = &toks[i];
        if *quoted || t != "{" {
            return Err(SceneError::at(
                file,
                (base + at) as u64,
                format!("entities: expected `{{`, found `{t}`"),
            ));
        }
        i += 1;
        let mut e = HashMap::new();
        loop {
            let Some((at, k, kq)) = toks.get(i) else {
                return Err(SceneError::at(
                    file,
                    (base + text.len()) as u64,
                    "entities: unterminated entity (missing `}`)",
                ));
            };
            if !kq && k == "}" {
                i += 1;
                break;
            }
            let Some((_, v, _)) = toks.get(i + 1) else {
                return Err(SceneError::at(
                    file,
                    (base + at) as u64,
                    format!("entities: key `{k}` without a value"),
                ));
            };
            e.insert(k.clone(), v.clone());
            i += 2;
        }
        out.push(e);
    }
    Ok(out)
}

/// One shader stage.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Stage {
    /// `map` / `clampMap` / first `animMap` image (`$lightmap`, `$whiteimage` kept as is).
    pub map: Option<String>,
    /// Set by `clampMap`.
    pub clamp: bool,
    /// `blendFunc` present (and not `GL_ONE GL_ZERO`).
    pub blend: bool,
    /// `alphaFunc` present.
    pub alpha_test: bool,
}

/// A shader script entry.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct ShaderDef {
    /// Name.
    pub name: String,
    /// `surfaceparm` values (lower case).
    pub surfaceparms: Vec<String>,
    /// `skyParms` far box base name (`-` omitted).
    pub farbox: Option<String>,
    /// Stages in order.
    pub stages: Vec<Stage>,
}

impl ShaderDef {
    /// Whether a `surfaceparm` is set.
    pub fn has(&self, parm: &str) -> bool {
        self.surfaceparms.iter().any(|p| p == parm)
    }

    /// The first stage image that is not `$lightmap` / `$whiteimage`.
    pub fn base(&self) -> Option<(&str, bool)> {
        self.stages.iter().find_map(|s| {
            s.map
                .as_deref()
                .filter(|m| !m.starts_with('$'))
                .map(|m| (m, s.clamp))
        })
    }

    /// Whether a stage maps `$lightmap`.
    pub fn uses_lightmap(&self) -> bool {
        self.stages.iter().any(|s| {
            s.map
                .as_deref()
                .is_some_and(|m| m.eq_ignore_ascii_case("$lightmap"))
        })
    }

    /// The blend mode the stages imply.
    pub fn blend(&self) -> Blend {
        match self.stages.first() {
            Some(s) if s.blend => Blend::AlphaBlend,
            _ if self.stages.iter().any(|s| s.alpha_test) => Blend::AlphaTest,
            _ => Blend::Opaque,
        }
    }
}

/// Parse a shader script (`file` names it in errors).
pub fn parse_shaders(text: &str, file: &Path) -> Result<Vec<ShaderDef>, SceneError> {
    let toks = tokenize(text);
    let err = |at: usize, m: String| SceneError::at(file, at as u64, m);
    let mut out = Vec::new();
    let mut i = 0;
    while i < toks.len() {
        let (at, name, _) = &toks[i];
        if name == "{" || name == "}" {
            return Err(err(*at, format!("expected a shader name, found `{name}`")));
        }
        match toks.get(i + 1) {
            Some((_, b, false)) if b == "{" => {}
            _ => {
                return Err(err(
                    *at,
                    format!("shader `{name}`: expected `{{` after the name"),
                ))
            }
        }
        i += 2;
        let mut def = ShaderDef {
            name: name.clone(),
            ..Default::default()
        };
        let mut stage: Option<Stage> = None;
        loop {
            let Some((at, t, q)) = toks.get(i) else {
                return Err(err(text.len(), format!("shader `{name}`: missing `}}`")));
            };
            let lower = t.to_ascii_lowercase();
            let arg = |k: usize| toks.get(i + k).map(|t| t.1.clone()).unwrap_or_default();
            match (lower.as_str(), q) {
                ("{", false) => {
                    if stage.is_some() {
                        return Err(err(*at, format!("shader `{name}`: nested stage")));
                    }
                    stage = Some(Stage::default());
                }
                ("}", false) => match stage.take() {
                    Some(s) => def.stages.push(s),
                    None => {
                        i += 1;
                        break;
                    }
                },
                ("surfaceparm", _) if stage.is_none() => {
                    def.surfaceparms.push(arg(1).to_ascii_lowercase());
                }
                ("skyparms", _) if stage.is_none() => {
                    let fb = arg(1);
                    if fb != "-" && !fb.is_empty() {
                        def.farbox = Some(fb);
                    }
                }
                ("map" | "clampmap", _) => {
                    if let Some(s) = stage.as_mut() {
                        if s.map.is_none() {
                            s.map = Some(arg(1));
                            s.clamp = lower == "clampmap";
                        }
                    }
                }
                ("animmap", _) => {
                    if let Some(s) = stage.as_mut() {
                        if s.map.is_none() {
                            s.map = Some(arg(2));
                        }
                    }
                }
                ("blendfunc", _) => {
                    if let Some(s) = stage.as_mut() {
                        let a = arg(1).to_ascii_lowercase();
                        let b = arg(2).to_ascii_lowercase();
                        s.blend = !(a == "gl_one" && b == "gl_zero");
                    }
                }
                ("alphafunc", _) => {
                    if let Some(s) = stage.as_mut() {
                        s.alpha_test = true;
                    }
                }
                _ => {}
            }
            i += 1;
        }
        out.push(def);
    }
    Ok(out)
}

// ---------------------------------------------------------------------------
// TGA

/// Decode a TGA image (types 2, 3, 10, 11: true-colour 24/32 bit or grey
/// 8 bit, uncompressed or RLE) to RGBA8, top row first.
pub fn decode_tga(bytes: &[u8], file: &Path) -> Result<(u32, u32, Vec<u8>), SceneError> {
    let r = Bytes::new(bytes, file);
    let h = r.slice(0, 18, "TGA header")?;
    let id_len = h[0] as usize;
    let cmap_type = h[1];
    let kind = h[2];
    let cmap_len = u16::from_le_bytes([h[5], h[6]]) as usize;
    let cmap_bits = h[7] as usize;
    let width = u16::from_le_bytes([h[12], h[13]]) as usize;
    let height = u16::from_le_bytes([h[14], h[15]]) as usize;
    let bpp = h[16] as usize;
    let top_first = h[17] & 0x20 != 0;
    let (grey, rle) = match kind {
        2 => (false, false),
        3 => (true, false),
        10 => (false, true),
        11 => (true, true),
        _ => {
            return Err(r.err(
                2,
                format!("TGA image type {kind} (only 2, 3, 10, 11 are supported)"),
            ))
        }
    };
    let ok_depth = if grey {
        bpp == 8
    } else {
        bpp == 24 || bpp == 32
    };
    if !ok_depth {
        return Err(r.err(16, format!("TGA depth {bpp} bits for image type {kind}")));
    }
    if width == 0 || height == 0 {
        return Err(r.err(12, format!("TGA size {width}x{height}")));
    }
    let px = bpp / 8;
    let mut pos = 18 + id_len;
    if cmap_type == 1 {
        pos += cmap_len * cmap_bits.div_ceil(8);
    }
    let n = width * height;
    // Even RLE needs at least one byte per 128 pixels: bound allocations.
    let min_bytes = if rle {
        n.div_ceil(128) * (1 + px)
    } else {
        n * px
    };
    if bytes.len().saturating_sub(pos) < min_bytes {
        return Err(r.err(
            pos.min(bytes.len()),
            format!("truncated TGA: {width}x{height} pixels need more data"),
        ));
    }
    let to_rgba = |p: &[u8]| -> [u8; 4] {
        match p.len() {
            1 => [p[0], p[0], p[0], 255],
            3 => [p[2], p[1], p[0], 255],
            _ => [p[2], p[1], p[0], p[3]],
        }
    };
    let mut pixels: Vec<[u8; 4]> = Vec::with_capacity(n);
    if rle {
        while pixels.len() < n {
            let hdr = r.slice(pos, 1, "RLE packet")?[0];
            pos += 1;
            let count = (hdr & 0x7f) as usize + 1;
            if pixels.len() + count > n {
                return Err(r.err(pos - 1, "RLE packet runs past the image"));
            }
            if hdr & 0x80 != 0 {
                let p = to_rgba(r.slice(pos, px, "RLE pixel")?);
                pos += px;
                pixels.extend(std::iter::repeat_n(p, count));
            } else {
                let raw = r.slice(pos, px * count, "RLE raw pixels")?;
                pos += px * count;
                pixels.extend(raw.chunks_exact(px).map(to_rgba));
            }
        }
    } else {
        let raw = r.slice(pos, n * px, "pixels")?;
        pixels.extend(raw.chunks_exact(px).map(to_rgba));
    }
    let mut rgba = Vec::with_capacity(n * 4);
    for y in 0..height {
        let src = if top_first { y } else { height - 1 - y };
        for p in &pixels[src * width..(src + 1) * width] {
            rgba.extend_from_slice(p);
        }
    }
    Ok((width as u32, height as u32, rgba))
}

// ---------------------------------------------------------------------------
// pk3 file system

/// The `.pk3` archives of the game, indexed by lower-case entry name.
pub struct Paks {
    archives: Vec<(PathBuf, zip::ZipArchive<File>)>,
    index: HashMap<String, (usize, String)>,
}

impl Paks {
    /// Open every `baseoa/*.pk3` of the data root (and of the sibling
    /// package directories, see the module documentation).
    pub fn open(data_root: &Path) -> Result<Paks, SceneError> {
        let mut dirs = vec![data_root.join("baseoa")];
        // <cache>/<package>/usr/share/games/openarena: siblings.
        if let Some(cache) = data_root.ancestors().nth(5) {
            for p in PACKAGES {
                let d = cache.join(p).join("usr/share/games/openarena/baseoa");
                if !dirs.contains(&d) {
                    dirs.push(d);
                }
            }
        }
        let mut pk3s: Vec<PathBuf> = Vec::new();
        for d in &dirs {
            let Ok(rd) = std::fs::read_dir(d) else {
                continue;
            };
            let mut here: Vec<PathBuf> = rd.flatten().map(|e| e.path()).collect();
            here.sort();
            for p in here {
                let is_pk3 = p.extension().is_some_and(|x| x.eq_ignore_ascii_case("pk3"));
                if is_pk3 && !pk3s.iter().any(|q| q.file_name() == p.file_name()) {
                    pk3s.push(p);
                }
            }
        }
        if pk3s.is_empty() {
            return Err(SceneError::in_file(
                data_root.join("baseoa"),
                "no .pk3 files (the data root is <package root>/usr/share/games/openarena, holding baseoa/)",
            ));
        }
        pk3s.sort_by(|a, b| a.file_name().cmp(&b.file_name()).then(a.cmp(b)));
        let mut paks = Paks {
            archives: Vec::new(),
            index: HashMap::new(),
        };
        for p in pk3s {
            let f =
                File::open(&p).map_err(|e| SceneError::in_file(&p, format!("cannot open: {e}")))?;
            let z = zip::ZipArchive::new(f)
                .map_err(|e| SceneError::in_file(&p, format!("bad pk3 (zip): {e}")))?;
            let ai = paks.archives.len();
            for name in z.file_names() {
                if !name.ends_with('/') {
                    paks.index
                        .insert(name.to_ascii_lowercase(), (ai, name.to_string()));
                }
            }
            paks.archives.push((p, z));
        }
        Ok(paks)
    }

    /// Whether an entry exists.
    pub fn contains(&self, name: &str) -> bool {
        self.index.contains_key(&name.to_ascii_lowercase())
    }

    /// An entry's name as stored (its case), if it exists.
    pub fn entry_name(&self, name: &str) -> Option<&str> {
        self.index
            .get(&name.to_ascii_lowercase())
            .map(|(_, n)| n.as_str())
    }

    /// Entry names (original case) matching a filter.
    pub fn names(&self, keep: impl Fn(&str) -> bool) -> Vec<String> {
        let mut v: Vec<String> = self
            .index
            .values()
            .map(|(_, n)| n.clone())
            .filter(|n| keep(n))
            .collect();
        v.sort();
        v
    }

    /// The path naming an entry in errors: `<pk3>/<entry>`.
    pub fn path_of(&self, name: &str) -> PathBuf {
        match self.index.get(&name.to_ascii_lowercase()) {
            Some((ai, n)) => self.archives[*ai].0.join(n),
            None => PathBuf::from(name),
        }
    }

    /// Read an entry.
    pub fn read(&mut self, name: &str) -> Result<Vec<u8>, SceneError> {
        let (ai, entry) = self
            .index
            .get(&name.to_ascii_lowercase())
            .cloned()
            .ok_or_else(|| SceneError::in_file(name, "not found in any pk3"))?;
        let (path, z) = &mut self.archives[ai];
        let full = path.join(&entry);
        let mut f = z
            .by_name(&entry)
            .map_err(|e| SceneError::in_file(&full, format!("cannot read from pk3: {e}")))?;
        let mut out = Vec::with_capacity(f.size().min(1 << 28) as usize);
        f.read_to_end(&mut out)
            .map_err(|e| SceneError::in_file(&full, format!("cannot inflate: {e}")))?;
        Ok(out)
    }
}

/// Every map (`maps/<name>.bsp` in the pk3s), sorted.
pub fn maps(data_root: &Path) -> Result<Vec<String>, SceneError> {
    let paks = Paks::open(data_root)?;
    let mut v: Vec<String> = paks
        .names(|n| {
            let l = n.to_ascii_lowercase();
            l.starts_with("maps/") && l.ends_with(".bsp") && !l[5..].contains('/')
        })
        .into_iter()
        .map(|n| n[5..n.len() - 4].to_string())
        .collect();
    v.sort();
    v.dedup();
    Ok(v)
}

// ---------------------------------------------------------------------------
// Geometry

fn biquadratic(c: &[BspVertex; 9], s: f32, t: f32) -> BspVertex {
    let w = |u: f32| [(1.0 - u) * (1.0 - u), 2.0 * u * (1.0 - u), u * u];
    let (ws, wt) = (w(s), w(t));
    let mut v = BspVertex {
        pos: [0.0; 3],
        uv: [0.0; 2],
        lm: [0.0; 2],
        normal: [0.0; 3],
    };
    for (j, wj) in wt.iter().enumerate() {
        for (i, wi) in ws.iter().enumerate() {
            let k = wi * wj;
            let p = &c[j * 3 + i];
            for a in 0..3 {
                v.pos[a] += k * p.pos[a];
                v.normal[a] += k * p.normal[a];
            }
            for a in 0..2 {
                v.uv[a] += k * p.uv[a];
                v.lm[a] += k * p.lm[a];
            }
        }
    }
    v
}

/// A face's triangles as (vertices, indices), counter-clockwise seen from
/// the front; None for faces that are not drawn (flares, unknown types).
pub fn face_triangles(bsp: &Bsp, f: &BspFace) -> Option<(Vec<BspVertex>, Vec<u32>)> {
    let verts = &bsp.vertices[f.first_vertex..f.first_vertex + f.n_vertices];
    match f.kind {
        1 | 3 => {
            let mv = &bsp.meshverts[f.first_meshvert..f.first_meshvert + f.n_meshverts];
            let mut idx = Vec::with_capacity(mv.len());
            for t in mv.chunks_exact(3) {
                // Stored clockwise: reverse.
                idx.extend_from_slice(&[t[0] as u32, t[2] as u32, t[1] as u32]);
            }
            Some((verts.to_vec(), idx))
        }
        2 => {
            let [w, h] = f.size;
            let l = PATCH_LEVEL;
            let mut out_v = Vec::new();
            let mut out_i = Vec::new();
            for py in 0..(h - 1) / 2 {
                for px in 0..(w - 1) / 2 {
                    let mut c = [verts[0]; 9];
                    for j in 0..3 {
                        for i in 0..3 {
                            c[j * 3 + i] = verts[(py * 2 + j) * w + px * 2 + i];
                        }
                    }
                    let base = out_v.len() as u32;
                    for j in 0..=l {
                        for i in 0..=l {
                            out_v.push(biquadratic(&c, i as f32 / l as f32, j as f32 / l as f32));
                        }
                    }
                    let row = (l + 1) as u32;
                    for j in 0..l as u32 {
                        for i in 0..l as u32 {
                            let a = base + j * row + i;
                            for t in [[a, a + 1, a + row + 1], [a, a + row + 1, a + row]] {
                                let (p0, p1, p2) = (
                                    &out_v[t[0] as usize],
                                    &out_v[t[1] as usize],
                                    &out_v[t[2] as usize],
                                );
                                let n = cross(sub(p1.pos, p0.pos), sub(p2.pos, p0.pos));
                                let vn = [
                                    p0.normal[0] + p1.normal[0] + p2.normal[0],
                                    p0.normal[1] + p1.normal[1] + p2.normal[1],
                                    p0.normal[2] + p1.normal[2] + p2.normal[2],
                                ];
                                if dot(n, vn) < 0.0 {
                                    out_i.extend_from_slice(&[t[0], t[2], t[1]]);
                                } else {
                                    out_i.extend_from_slice(&t);
                                }
                            }
                        }
                    }
                }
            }
            Some((out_v, out_i))
        }
        _ => None,
    }
}

// ---------------------------------------------------------------------------
// The loader

/// A camera selector: `spawn:N`.
pub fn parse_camera(sel: &str) -> Option<usize> {
    let (k, n) = sel.split_once(':')?;
    if k.trim() != "spawn" {
        return None;
    }
    n.trim().parse().ok()
}

/// Spawn points (origin, yaw in degrees) in the order `spawn:N` counts them.
pub fn spawn_points(entities: &[HashMap<String, String>]) -> Vec<(Vec3, f32)> {
    let mut out = Vec::new();
    for class in [
        "info_player_deathmatch",
        "info_player_start",
        "team_ctf_redspawn",
        "team_ctf_bluespawn",
        "team_ctf_redplayer",
        "team_ctf_blueplayer",
    ] {
        for e in entities {
            if e.get("classname")
                .is_some_and(|c| c.eq_ignore_ascii_case(class))
            {
                let Some(o) = e.get("origin") else { continue };
                let v: Vec<f32> = o
                    .split_whitespace()
                    .filter_map(|w| w.parse().ok())
                    .collect();
                if v.len() != 3 || v.iter().any(|x: &f32| !x.is_finite()) {
                    continue;
                }
                let yaw = e
                    .get("angle")
                    .and_then(|a| a.trim().parse::<f32>().ok())
                    .filter(|a| a.is_finite())
                    .unwrap_or(0.0);
                out.push(([v[0], v[1], v[2]], yaw));
            }
        }
        if !out.is_empty() && class == "info_player_start" {
            break;
        }
    }
    out
}

struct Builder<'a> {
    paks: &'a mut Paks,
    shaders: HashMap<String, ShaderDef>,
    textures: Vec<Texture>,
    tex_ids: HashMap<(String, bool), usize>,
    missing: Option<usize>,
    materials: Vec<Material>,
    meshes: Vec<Mesh>,
    mat_mesh: HashMap<(usize, i32), Option<usize>>,
    lightmap_ids: HashMap<i32, Option<usize>>,
    map: String,
    missing_names: Vec<String>,
}

impl Builder<'_> {
    /// Resolve an image name to a pk3 entry: the name, then `.tga`,
    /// `.jpg`, `.png` in place of its extension.
    fn find_image(&self, name: &str) -> Option<String> {
        let name = name.replace('\\', "/");
        if let Some(n) = self.paks.entry_name(&name) {
            return Some(n.to_string());
        }
        let stem = match name.rfind('.') {
            Some(d) if !name[d..].contains('/') => &name[..d],
            _ => name.as_str(),
        };
        ["tga", "jpg", "png"]
            .iter()
            .find_map(|e| self.paks.entry_name(&format!("{stem}.{e}")))
            .map(str::to_string)
    }

    fn decode(&mut self, entry: &str) -> Result<(u32, u32, Vec<u8>), SceneError> {
        let bytes = self.paks.read(entry)?;
        let path = self.paks.path_of(entry);
        let (w, h, rgba) = if entry.to_ascii_lowercase().ends_with(".tga") {
            decode_tga(&bytes, &path)?
        } else {
            let img = image::load_from_memory(&bytes)
                .map_err(|e| SceneError::in_file(&path, format!("cannot decode image: {e}")))?;
            let im = img.to_rgba8();
            let (w, h) = im.dimensions();
            (w, h, im.into_raw())
        };
        if w.max(h) > MAX_TEXTURE_SIDE {
            let s = MAX_TEXTURE_SIDE as f64 / w.max(h) as f64;
            let nw = ((w as f64 * s).round() as u32).max(1);
            let nh = ((h as f64 * s).round() as u32).max(1);
            let im = image::RgbaImage::from_raw(w, h, rgba)
                .ok_or_else(|| SceneError::in_file(&path, "image size mismatch"))?;
            let im = image::imageops::resize(&im, nw, nh, image::imageops::FilterType::Triangle);
            return Ok((nw, nh, im.into_raw()));
        }
        Ok((w, h, rgba))
    }

    /// A texture by image name; the shared checkerboard if it is missing.
    fn texture(&mut self, name: &str, repeat: bool) -> Result<usize, SceneError> {
        let Some(entry) = self.find_image(name) else {
            self.missing_names.push(name.to_string());
            return Ok(self.missing_texture());
        };
        let key = (entry.to_ascii_lowercase(), repeat);
        if let Some(&i) = self.tex_ids.get(&key) {
            return Ok(i);
        }
        let (width, height, rgba) = self.decode(&entry)?;
        self.textures.push(Texture {
            name: entry,
            width,
            height,
            rgba,
            repeat,
        });
        self.tex_ids.insert(key, self.textures.len() - 1);
        Ok(self.textures.len() - 1)
    }

    fn missing_texture(&mut self) -> usize {
        if let Some(i) = self.missing {
            return i;
        }
        let mut rgba = Vec::with_capacity(64 * 64 * 4);
        for y in 0..64 {
            for x in 0..64 {
                let on = ((x / 8) + (y / 8)) % 2 == 0;
                rgba.extend_from_slice(if on {
                    &[255, 255, 255, 255]
                } else {
                    &[64, 64, 64, 255]
                });
            }
        }
        self.textures.push(Texture {
            name: "missing".into(),
            width: 64,
            height: 64,
            rgba,
            repeat: true,
        });
        self.missing = Some(self.textures.len() - 1);
        self.textures.len() - 1
    }

    fn lightmap(&mut self, bsp: &Bsp, lm: i32) -> Result<Option<usize>, SceneError> {
        if lm < 0 {
            return Ok(None);
        }
        if let Some(&t) = self.lightmap_ids.get(&lm) {
            return Ok(t);
        }
        let l = lm as usize;
        let tex = if l < bsp.lightmaps.len() {
            let rgb = &bsp.lightmaps[l];
            let mut rgba = Vec::with_capacity(LIGHTMAP_SIDE * LIGHTMAP_SIDE * 4);
            for p in rgb.chunks_exact(3) {
                rgba.extend_from_slice(&[p[0], p[1], p[2], 255]);
            }
            self.textures.push(Texture {
                name: format!("maps/{}.bsp lightmap {l}", self.map),
                width: LIGHTMAP_SIDE as u32,
                height: LIGHTMAP_SIDE as u32,
                rgba,
                repeat: false,
            });
            Some(self.textures.len() - 1)
        } else {
            let entry = format!("maps/{}/lm_{l:04}.tga", self.map);
            if self.paks.contains(&entry) {
                let (width, height, rgba) = self.decode(&entry)?;
                self.textures.push(Texture {
                    name: entry,
                    width,
                    height,
                    rgba,
                    repeat: false,
                });
                Some(self.textures.len() - 1)
            } else {
                None
            }
        };
        self.lightmap_ids.insert(lm, tex);
        Ok(tex)
    }

    /// The mesh for (shader, lightmap); None if not drawn.
    fn mesh(&mut self, bsp: &Bsp, shader: usize, lm: i32) -> Result<Option<usize>, SceneError> {
        if let Some(&m) = self.mat_mesh.get(&(shader, lm)) {
            return Ok(m);
        }
        let s = &bsp.shaders[shader];
        let def = self.shaders.get(&s.name.to_ascii_lowercase()).cloned();
        let nodraw = s.flags & SURF_NODRAW != 0
            || s.contents & CONTENTS_FOG != 0
            || def
                .as_ref()
                .is_some_and(|d| d.has("nodraw") || d.has("fog"));
        let sky = s.flags & SURF_SKY != 0 || def.as_ref().is_some_and(|d| d.has("sky"));
        let result = if nodraw || s.name.eq_ignore_ascii_case("noshader") {
            None
        } else if sky {
            let image = def.as_ref().and_then(|d| {
                d.base()
                    .map(|(m, _)| m.to_string())
                    .or_else(|| d.farbox.as_ref().map(|f| format!("{f}_ft.tga")))
            });
            match image {
                Some(img) => {
                    let t = self.texture(&img, true)?;
                    self.materials.push(Material {
                        name: s.name.clone(),
                        blend: Blend::Opaque,
                        shader: shader::unlit(t, Filter::Trilinear),
                    });
                    Some(self.new_mesh(false))
                }
                None => None,
            }
        } else {
            let (image, clamp, blend, wants_lm) = match &def {
                Some(d) => match d.base() {
                    Some((m, c)) => (m.to_string(), c, d.blend(), d.uses_lightmap()),
                    // Only $lightmap / $whiteimage stages: nothing textured.
                    None => (s.name.clone(), false, d.blend(), d.uses_lightmap()),
                },
                None => (s.name.clone(), false, Blend::Opaque, true),
            };
            let t = self.texture(&image, !clamp)?;
            let lmt = if wants_lm {
                self.lightmap(bsp, lm)?
            } else {
                None
            };
            let (name, program) = match lmt {
                Some(l) => (
                    format!("{} +lightmap {lm}", s.name),
                    shader::lightmapped(t, l, Filter::Trilinear),
                ),
                None => (s.name.clone(), shader::standard(t, Filter::Trilinear)),
            };
            self.materials.push(Material {
                name,
                blend,
                shader: program,
            });
            Some(self.new_mesh(lmt.is_some()))
        };
        self.mat_mesh.insert((shader, lm), result);
        Ok(result)
    }

    fn new_mesh(&mut self, lightmapped: bool) -> usize {
        self.meshes.push(Mesh {
            positions: Vec::new(),
            uv: Vec::new(),
            uv2: lightmapped.then(Vec::new),
            indices: Vec::new(),
            material: self.materials.len() - 1,
        });
        self.meshes.len() - 1
    }
}

/// Load map `def.map` from `data_root` (see the module documentation).
pub fn load(data_root: &Path, def: &SceneDef) -> Result<Scene, SceneError> {
    let mut paks = Paks::open(data_root)?;
    let entry = format!("maps/{}.bsp", def.map);
    if !paks.contains(&entry) {
        return Err(SceneError::in_file(
            data_root.join("baseoa"),
            format!("no map `{}` (no {entry} in the pk3s)", def.map),
        ));
    }
    let bsp_path = paks.path_of(&entry);
    let spawn_n = parse_camera(&def.camera).ok_or_else(|| {
        SceneError::in_file(
            &bsp_path,
            format!("camera `{}`: expected spawn:N", def.camera),
        )
    })?;
    let bytes = paks.read(&entry)?;
    let bsp = parse_bsp(&bytes, &bsp_path)?;
    drop(bytes);
    let entities = parse_entities(&bsp.entities, &bsp_path, bsp.entities_offset)?;
    let spawns = spawn_points(&entities);
    let &(origin, yaw) = spawns.get(spawn_n).ok_or_else(|| {
        SceneError::in_file(
            &bsp_path,
            format!(
                "camera spawn:{spawn_n}: the map has {} spawn points",
                spawns.len()
            ),
        )
    })?;

    // Shader scripts: first definition of a name wins.
    let mut shaders = HashMap::new();
    for script in paks.names(|n| {
        let l = n.to_ascii_lowercase();
        l.starts_with("scripts/") && l.ends_with(".shader")
    }) {
        let bytes = paks.read(&script)?;
        let text = String::from_utf8_lossy(&bytes);
        for s in parse_shaders(&text, &paks.path_of(&script))? {
            shaders.entry(s.name.to_ascii_lowercase()).or_insert(s);
        }
    }

    let mut b = Builder {
        paks: &mut paks,
        shaders,
        textures: Vec::new(),
        tex_ids: HashMap::new(),
        missing: None,
        materials: Vec::new(),
        meshes: Vec::new(),
        mat_mesh: HashMap::new(),
        lightmap_ids: HashMap::new(),
        map: def.map.clone(),
        missing_names: Vec::new(),
    };
    for f in &bsp.faces {
        let Some(mi) = b.mesh(&bsp, f.shader, f.lightmap)? else {
            continue;
        };
        let Some((verts, idx)) = face_triangles(&bsp, f) else {
            continue;
        };
        let mesh = &mut b.meshes[mi];
        let base = mesh.positions.len() as u32;
        mesh.positions.extend(verts.iter().map(|v| v.pos));
        mesh.uv.extend(verts.iter().map(|v| v.uv));
        if let Some(uv2) = mesh.uv2.as_mut() {
            uv2.extend(verts.iter().map(|v| v.lm));
        }
        mesh.indices.extend(idx.iter().map(|i| base + i));
    }
    let mut meshes = std::mem::take(&mut b.meshes);
    meshes.retain(|m| !m.indices.is_empty());
    let (blended, mut all): (Vec<Mesh>, Vec<Mesh>) = meshes
        .into_iter()
        .partition(|m| b.materials[m.material].blend == Blend::AlphaBlend);
    all.extend(blended);
    let tris: usize = all.iter().map(|m| m.indices.len() / 3).sum();
    let mut missing = std::mem::take(&mut b.missing_names);
    missing.sort();
    missing.dedup();
    let (s, c) = yaw.to_radians().sin_cos();
    let eye = [origin[0], origin[1], origin[2] + EYE_HEIGHT];
    Ok(Scene {
        name: format!("openarena:{}:{}", def.map, def.camera.replace(':', "")),
        source: format!(
            "OpenArena map `{}` (Debian openarena-data / openarena-081-maps / openarena-081-textures, GPL; {} triangles, {} textures, {} missing images{})",
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
            target: [eye[0] + c, eye[1] + s, eye[2]],
            up: [0.0, 0.0, 1.0],
            fov_y_deg: FOV_Y_DEG,
            near: NEAR,
            far: FAR,
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::def::Game;
    use proptest::prelude::*;
    use std::io::Write;

    fn def(map: &str, camera: &str) -> SceneDef {
        SceneDef {
            name: format!("test-{map}"),
            game: Game::Openarena,
            map: map.into(),
            camera: camera.into(),
            width: 1960,
            height: 768,
            description: String::new(),
            shader: None,
        }
    }

    fn vertex(b: &mut Vec<u8>, p: Vec3, uv: Vec2, lm: Vec2) {
        for v in [p[0], p[1], p[2], uv[0], uv[1], lm[0], lm[1], 0.0, 0.0, 1.0] {
            b.extend_from_slice(&v.to_le_bytes());
        }
        b.extend_from_slice(&[255; 4]);
    }

    #[allow(clippy::too_many_arguments)]
    fn face(
        b: &mut Vec<u8>,
        shader: i32,
        kind: i32,
        fv: i32,
        nv: i32,
        fm: i32,
        nm: i32,
        lm: i32,
        size: [i32; 2],
    ) {
        for v in [shader, -1, kind, fv, nv, fm, nm, lm, 0, 0, 0, 0] {
            b.extend_from_slice(&v.to_le_bytes());
        }
        for v in [0.0f32; 3 + 6] {
            b.extend_from_slice(&v.to_le_bytes());
        }
        for v in [0.0f32, 0.0, 1.0] {
            b.extend_from_slice(&v.to_le_bytes());
        }
        for v in size {
            b.extend_from_slice(&v.to_le_bytes());
        }
    }

    /// A hand-made IBSP 46: two shaders, a floor quad (polygon, lightmap
    /// 0), a flat 3x3 patch, a flare, one lightmap; the lightmap lump last
    /// so that any truncation cuts a lump.
    fn tiny_bsp() -> Vec<u8> {
        let ents = b"{\n\"classname\" \"worldspawn\"\n}\n{\n\"classname\" \"info_player_deathmatch\"\n\"origin\" \"16 32 24\"\n\"angle\" \"90\"\n}\n\0".to_vec();
        let mut shaders = Vec::new();
        for (name, flags) in [("textures/t/floor", 0), ("textures/t/nodraw", SURF_NODRAW)] {
            let mut n = [0u8; 64];
            n[..name.len()].copy_from_slice(name.as_bytes());
            shaders.extend_from_slice(&n);
            shaders.extend_from_slice(&flags.to_le_bytes());
            shaders.extend_from_slice(&1i32.to_le_bytes());
        }
        let mut verts = Vec::new();
        for (x, y) in [(0.0, 0.0), (64.0, 0.0), (64.0, 64.0), (0.0, 64.0)] {
            vertex(
                &mut verts,
                [x, y, 0.0],
                [x / 64.0, y / 64.0],
                [x / 128.0, y / 128.0],
            );
        }
        for j in 0..3 {
            for i in 0..3 {
                let (x, y) = (i as f32 * 32.0, j as f32 * 32.0);
                vertex(&mut verts, [x, y, 8.0], [x / 64.0, y / 64.0], [0.5, 0.5]);
            }
        }
        let mut mv = Vec::new();
        // Stored clockwise seen from +z (the BSP's convention).
        for i in [0i32, 2, 1, 0, 3, 2] {
            mv.extend_from_slice(&i.to_le_bytes());
        }
        let mut faces = Vec::new();
        face(&mut faces, 0, 1, 0, 4, 0, 6, 0, [0, 0]);
        face(&mut faces, 0, 2, 4, 9, 0, 0, -1, [3, 3]);
        face(&mut faces, 1, 1, 0, 4, 0, 6, -1, [0, 0]);
        face(&mut faces, 0, 4, 0, 0, 0, 0, -1, [0, 0]);
        let lm: Vec<u8> = (0..LIGHTMAP_SIDE * LIGHTMAP_SIDE * 3)
            .map(|i| (i % 251) as u8)
            .collect();
        let mut lumps: Vec<Vec<u8>> = vec![Vec::new(); 17];
        lumps[0] = ents;
        lumps[1] = shaders;
        lumps[10] = verts;
        lumps[11] = mv;
        lumps[13] = faces;
        let mut out = b"IBSP".to_vec();
        out.extend_from_slice(&46i32.to_le_bytes());
        let mut off = 8 + 17 * 8;
        let order: Vec<usize> = (0..17).filter(|&i| i != 14).chain([14]).collect();
        let mut dir = vec![(0usize, 0usize); 17];
        let mut body = Vec::new();
        for &i in &order {
            let data = if i == 14 { &lm } else { &lumps[i] };
            dir[i] = (off, data.len());
            body.extend_from_slice(data);
            off += data.len();
        }
        for (o, l) in dir {
            out.extend_from_slice(&(o as i32).to_le_bytes());
            out.extend_from_slice(&(l as i32).to_le_bytes());
        }
        out.extend_from_slice(&body);
        out
    }

    #[test]
    fn parses_a_tiny_bsp() {
        let b = parse_bsp(&tiny_bsp(), Path::new("t.bsp")).unwrap();
        assert_eq!(b.shaders.len(), 2);
        assert_eq!(b.shaders[1].name, "textures/t/nodraw");
        assert_eq!(b.shaders[1].flags, SURF_NODRAW);
        assert_eq!(b.vertices.len(), 13);
        assert_eq!(b.vertices[2].pos, [64.0, 64.0, 0.0]);
        assert_eq!(b.vertices[2].lm, [0.5, 0.5]);
        assert_eq!(b.meshverts, vec![0, 2, 1, 0, 3, 2]);
        assert_eq!(b.faces.len(), 4);
        assert_eq!((b.faces[1].kind, b.faces[1].size), (2, [3, 3]));
        assert_eq!(b.lightmaps.len(), 1);
        assert_eq!(b.lightmaps[0][250..252], [250, 0]);
        let ents = parse_entities(&b.entities, Path::new("t.bsp"), b.entities_offset).unwrap();
        assert_eq!(spawn_points(&ents), vec![([16.0, 32.0, 24.0], 90.0)]);
        // The polygon comes out counter-clockwise seen from +z.
        let (v, i) = face_triangles(&b, &b.faces[0]).unwrap();
        assert_eq!(i, vec![0, 1, 2, 0, 2, 3]);
        let n = cross(sub(v[1].pos, v[0].pos), sub(v[2].pos, v[0].pos));
        assert!(n[2] > 0.0);
        // The patch: (L+1)^2 vertices, 2 L^2 triangles, facing +z, flat.
        let (v, i) = face_triangles(&b, &b.faces[1]).unwrap();
        assert_eq!(v.len(), (PATCH_LEVEL + 1) * (PATCH_LEVEL + 1));
        assert_eq!(i.len(), 6 * PATCH_LEVEL * PATCH_LEVEL);
        assert!(v.iter().all(|p| (p.pos[2] - 8.0).abs() < 1e-5));
        assert_eq!(v[v.len() - 1].pos, [64.0, 64.0, 8.0]);
        for t in i.chunks_exact(3) {
            let n = cross(
                sub(v[t[1] as usize].pos, v[t[0] as usize].pos),
                sub(v[t[2] as usize].pos, v[t[0] as usize].pos),
            );
            assert!(n[2] > 0.0);
        }
        assert!(face_triangles(&b, &b.faces[3]).is_none());
    }

    #[test]
    fn bsp_errors_name_file_and_offset() {
        let f = Path::new("bad.bsp");
        let e = parse_bsp(b"IBSQ", f).unwrap_err();
        assert_eq!((e.file.as_path(), e.offset), (f, Some(0)));
        let mut v = tiny_bsp();
        v[4] = 47;
        assert_eq!(parse_bsp(&v, f).unwrap_err().offset, Some(4));
        // A mesh vertex past its face's vertices.
        let mut v = tiny_bsp();
        let moff = i32::from_le_bytes(v[8 + 8 * 11..8 + 8 * 11 + 4].try_into().unwrap()) as usize;
        v[moff + 4..moff + 8].copy_from_slice(&9i32.to_le_bytes());
        let e = parse_bsp(&v, f).unwrap_err();
        assert_eq!(e.offset, Some(moff as u64 + 4), "{e}");
        // A face whose vertices run past the lump.
        let mut v = tiny_bsp();
        let foff = i32::from_le_bytes(v[8 + 8 * 13..8 + 8 * 13 + 4].try_into().unwrap()) as usize;
        v[foff + 16..foff + 20].copy_from_slice(&1000i32.to_le_bytes());
        let e = parse_bsp(&v, f).unwrap_err();
        assert_eq!(e.offset, Some(foff as u64 + 12), "{e}");
        // A bad patch size.
        let mut v = tiny_bsp();
        v[foff + 104 + 96..foff + 104 + 100].copy_from_slice(&2i32.to_le_bytes());
        assert!(parse_bsp(&v, f).unwrap_err().message.contains("patch"));
        let v = tiny_bsp();
        let e = parse_bsp(&v[..v.len() - 1], f).unwrap_err();
        assert!(e.message.contains("outside the file"), "{e}");
    }

    proptest! {
        #[test]
        fn bsp_random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..600)) {
            if let Err(e) = parse_bsp(&bytes, Path::new("r.bsp")) {
                prop_assert_eq!(e.file, PathBuf::from("r.bsp"));
                prop_assert!(e.offset.is_some());
            }
        }

        #[test]
        fn bsp_truncations_are_errors(cut in 0usize..60_000) {
            let v = tiny_bsp();
            let cut = cut % v.len();
            let e = parse_bsp(&v[..cut], Path::new("t.bsp")).unwrap_err();
            prop_assert!(e.offset.unwrap() <= v.len() as u64);
        }

        #[test]
        fn bsp_corruptions_never_panic(at in 0usize..2000, byte in any::<u8>()) {
            let mut v = tiny_bsp();
            v[at % 2000] = byte;
            if let Ok(b) = parse_bsp(&v, Path::new("c.bsp")) {
                for f in &b.faces {
                    let _ = face_triangles(&b, f);
                }
                let _ = parse_entities(&b.entities, Path::new("c.bsp"), 0);
            }
        }

        #[test]
        fn tga_random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..300)) {
            if let Err(e) = decode_tga(&bytes, Path::new("r.tga")) {
                prop_assert!(e.offset.is_some());
            }
        }

        #[test]
        fn tga_truncations_are_errors(cut in 0usize..200, rle in any::<bool>()) {
            let v = tiny_tga(rle, false);
            let cut = cut % v.len();
            prop_assert!(decode_tga(&v[..cut], Path::new("t.tga")).is_err());
        }

        #[test]
        fn text_parsers_never_panic(text in "[{}\"a-z/* \n]{0,80}") {
            let _ = parse_entities(&text, Path::new("e"), 0);
            let _ = parse_shaders(&text, Path::new("s.shader"));
        }
    }

    /// A 3x2 TGA: BGR(A), uncompressed or RLE.
    fn tiny_tga(rle: bool, alpha: bool) -> Vec<u8> {
        let px = if alpha { 4 } else { 3 };
        let mut v = vec![0u8; 18];
        v[0] = 2; // id length
        v[2] = if rle { 10 } else { 2 };
        v[12] = 3;
        v[14] = 2;
        v[16] = 8 * px as u8;
        v.extend_from_slice(b"id");
        // Bottom row first: bottom = red red blue, top = green x3.
        let red: &[u8] = &[0, 0, 255, 200][..px];
        let blue: &[u8] = &[255, 0, 0, 100][..px];
        let green: &[u8] = &[0, 255, 0, 255][..px];
        if rle {
            v.push(0x81);
            v.extend_from_slice(red);
            v.push(0x00);
            v.extend_from_slice(blue);
            v.push(0x82);
            v.extend_from_slice(green);
        } else {
            for p in [red, red, blue, green, green, green] {
                v.extend_from_slice(p);
            }
        }
        v
    }

    #[test]
    fn decodes_tga() {
        for rle in [false, true] {
            for alpha in [false, true] {
                let (w, h, rgba) = decode_tga(&tiny_tga(rle, alpha), Path::new("t.tga")).unwrap();
                assert_eq!((w, h), (3, 2));
                let a = |x: u8| if alpha { x } else { 255 };
                assert_eq!(&rgba[0..4], &[0, 255, 0, 255]);
                assert_eq!(&rgba[12..16], &[255, 0, 0, a(200)]);
                assert_eq!(&rgba[20..24], &[0, 0, 255, a(100)]);
            }
        }
        let mut v = tiny_tga(false, false);
        v[17] = 0x20; // top row first
        let (_, _, rgba) = decode_tga(&v, Path::new("t.tga")).unwrap();
        assert_eq!(&rgba[0..4], &[255, 0, 0, 255]);
        let mut v = tiny_tga(false, false);
        v[2] = 1;
        assert_eq!(
            decode_tga(&v, Path::new("t.tga")).unwrap_err().offset,
            Some(2)
        );
        let mut v = tiny_tga(true, false);
        v[20] = 0x86; // 7 pixels: run past the end
        assert!(decode_tga(&v, Path::new("t.tga"))
            .unwrap_err()
            .message
            .contains("past"));
    }

    #[test]
    fn parses_shader_scripts() {
        let text = r#"
// comment { not a brace
textures/a/lit
{
    qer_editorimage textures/a/x.tga
    surfaceparm nomarks
    {
        map $lightmap
        rgbGen identity
    }
    {
        map textures/a/base.tga
        blendFunc GL_DST_COLOR GL_ZERO
    }
}
textures/a/glass { surfaceparm trans /* c */ { map textures/a/glass.jpg blendfunc add } }
textures/a/grate
{
    { clampMap textures/a/grate.tga alphaFunc GE128 depthWrite }
    { map $lightmap blendFunc filter }
}
textures/a/sky { surfaceparm sky surfaceparm noimpact skyparms env/red - - }
textures/a/anim { { animMap 5 textures/a/f1.tga textures/a/f2.tga } }
"#;
        let s = parse_shaders(text, Path::new("x.shader")).unwrap();
        assert_eq!(s.len(), 5);
        assert_eq!(s[0].name, "textures/a/lit");
        assert_eq!(s[0].base(), Some(("textures/a/base.tga", false)));
        assert!(s[0].uses_lightmap());
        assert_eq!(s[0].blend(), Blend::Opaque);
        assert_eq!(s[1].blend(), Blend::AlphaBlend);
        assert_eq!(s[2].base(), Some(("textures/a/grate.tga", true)));
        assert_eq!(s[2].blend(), Blend::AlphaTest);
        assert!(s[3].has("sky") && s[3].base().is_none());
        assert_eq!(s[3].farbox.as_deref(), Some("env/red"));
        assert_eq!(s[4].base(), Some(("textures/a/f1.tga", false)));
        let e = parse_shaders("a { { map x }", Path::new("x.shader")).unwrap_err();
        assert!(e.message.contains("missing"), "{e}");
        let e = parse_shaders("a b { }", Path::new("x.shader")).unwrap_err();
        assert_eq!(e.offset, Some(0));
        let e = parse_entities("{ \"a\" \"b\" } x", Path::new("e"), 100).unwrap_err();
        assert_eq!(e.offset, Some(112));
    }

    #[test]
    fn camera_selectors() {
        assert_eq!(parse_camera("spawn:2"), Some(2));
        assert_eq!(parse_camera("start:0"), None);
        assert_eq!(parse_camera("spawn:x"), None);
    }

    /// A whole synthetic game on disk: a pk3 with the map, a shader
    /// script, a TGA and a JPEG.
    #[test]
    fn loads_a_synthetic_map() {
        let root = std::env::temp_dir().join(format!("wasp-oa-test-{}", std::process::id()));
        std::fs::create_dir_all(root.join("baseoa")).unwrap();
        let mut jpg = Vec::new();
        image::RgbImage::from_pixel(8, 8, image::Rgb([200, 100, 50]))
            .write_to(
                &mut std::io::Cursor::new(&mut jpg),
                image::ImageFormat::Jpeg,
            )
            .unwrap();
        let write_pk3 = |name: &str, files: &[(&str, &[u8])]| {
            let f = File::create(root.join("baseoa").join(name)).unwrap();
            let mut z = zip::ZipWriter::new(f);
            let o = zip::write::SimpleFileOptions::default()
                .compression_method(zip::CompressionMethod::Deflated);
            for (n, d) in files {
                z.start_file(*n, o).unwrap();
                z.write_all(d).unwrap();
            }
            z.finish().unwrap();
        };
        let script = b"textures/t/floor\n{\n{\nmap $lightmap\n}\n{\nmap textures/t/floor.tga\nblendfunc filter\n}\n}\n";
        write_pk3(
            "pak0.pk3",
            &[("scripts/t.shader", script), ("textures/t/floor.jpg", &jpg)],
        );
        write_pk3(
            "pak1.pk3",
            &[
                ("maps/mini.bsp", &tiny_bsp()),
                ("Textures/T/Floor.tga", &tiny_tga(true, true)),
            ],
        );
        assert_eq!(maps(&root).unwrap(), vec!["mini".to_string()]);
        let s = load(&root, &def("mini", "spawn:0")).unwrap();
        // The floor polygon (lightmapped) and the patch (no lightmap);
        // the nodraw face and the flare are dropped.
        assert_eq!(s.meshes.len(), 2);
        let tris: usize = s.meshes.iter().map(|m| m.indices.len() / 3).sum();
        assert_eq!(tris, 2 + 2 * PATCH_LEVEL * PATCH_LEVEL);
        let lit = s.meshes.iter().find(|m| m.uv2.is_some()).unwrap();
        assert_eq!(lit.uv2.as_ref().unwrap()[2], [0.5, 0.5]);
        let mat = &s.materials[lit.material];
        assert_eq!(mat.blend, Blend::Opaque);
        // The script's .tga wins over the JPEG of the same stem; the later
        // pk3's mixed-case entry matches case-insensitively.
        assert_eq!(s.textures[0].name, "Textures/T/Floor.tga");
        assert_eq!((s.textures[0].width, s.textures[0].height), (3, 2));
        assert_eq!(s.textures[1].width, LIGHTMAP_SIDE as u32);
        assert_eq!(&s.textures[1].rgba[0..4], &[0, 1, 2, 255]);
        let Camera::Perspective {
            eye, target, up, ..
        } = s.camera
        else {
            panic!()
        };
        assert_eq!(eye, [16.0, 32.0, 24.0 + EYE_HEIGHT]);
        assert!((target[1] - eye[1] - 1.0).abs() < 1e-6 && (target[0] - eye[0]).abs() < 1e-6);
        assert_eq!(up, [0.0, 0.0, 1.0]);
        let e = load(&root, &def("mini", "spawn:1")).unwrap_err();
        assert!(e.message.contains("1 spawn points"), "{e}");
        let e = load(&root, &def("nope", "spawn:0")).unwrap_err();
        assert!(e.message.contains("maps/nope.bsp"), "{e}");
        // A corrupt BSP inside a pk3: the error names pk3/entry and offset.
        write_pk3("pak2.pk3", &[("maps/mini.bsp", &tiny_bsp()[..500])]);
        let e = load(&root, &def("mini", "spawn:0")).unwrap_err();
        assert!(
            e.file.ends_with("pak2.pk3/maps/mini.bsp") && e.offset.is_some(),
            "{e}"
        );
        std::fs::remove_dir_all(&root).unwrap();
    }

    /// The real data root in the scene cache (`$WASP_SCENES`, else the
    /// user's cache directory), if fetched.
    pub(super) fn real_root() -> Option<PathBuf> {
        let cache = crate::fetch::cache_dir();
        let found = find_data_root(&cache);
        if found.is_none() {
            eprintln!(
                "skipped: no OpenArena data under {} ({DATA_DIRS:?}); run `wasp scenes fetch`",
                cache.display()
            );
        }
        found
    }

    /// Checks on a loaded real scene: UVs finite, textures well-formed,
    /// the eye inside the bounds of the geometry.
    pub(super) fn check_real(s: &Scene, min_tris: usize) {
        let tris: usize = s.meshes.iter().map(|m| m.indices.len() / 3).sum();
        assert!(tris >= min_tris, "{}: {tris} triangles", s.name);
        let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
        for m in &s.meshes {
            assert_eq!(m.uv.len(), m.positions.len());
            assert!(m.uv.iter().all(|u| u[0].is_finite() && u[1].is_finite()));
            if let Some(uv2) = &m.uv2 {
                assert!(uv2.iter().all(|u| u[0].is_finite() && u[1].is_finite()));
            }
            assert!(m.indices.iter().all(|&i| (i as usize) < m.positions.len()));
            for p in &m.positions {
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
        }
        for mat in &s.materials {
            for op in &mat.shader {
                if let crate::ShaderOp::Tex(t) = op {
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
                eye[k] >= lo[k] && eye[k] <= hi[k],
                "{}: eye {eye:?} outside {lo:?}..{hi:?}",
                s.name
            );
        }
    }

    #[test]
    #[ignore = "needs fetched game data: wasp scenes fetch openarena"]
    fn real_shipped_scenes() {
        let Some(root) = real_root() else { return };
        for d in crate::def::all().unwrap() {
            if d.game != Game::Openarena {
                continue;
            }
            let t = std::time::Instant::now();
            let s = load(&root, &d).unwrap();
            let el = t.elapsed();
            check_real(&s, 2_000);
            assert!(
                !s.textures.iter().any(|t| t.name == "missing"),
                "{}",
                s.source
            );
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
    #[ignore = "needs fetched game data: wasp scenes fetch openarena"]
    fn real_polygons_wind_with_their_normals_and_spawns_float_24_above_the_floor() {
        let Some(root) = real_root() else { return };
        let mut paks = Paks::open(&root).unwrap();
        let bytes = paks.read("maps/oa_dm1.bsp").unwrap();
        let bsp = parse_bsp(&bytes, Path::new("oa_dm1.bsp")).unwrap();
        let (mut agree, mut disagree) = (0, 0);
        for f in bsp.faces.iter().filter(|f| f.kind == 1) {
            let (v, i) = face_triangles(&bsp, f).unwrap();
            for t in i.chunks_exact(3) {
                let n = cross(
                    sub(v[t[1] as usize].pos, v[t[0] as usize].pos),
                    sub(v[t[2] as usize].pos, v[t[0] as usize].pos),
                );
                if dot(n, f.normal) > 0.0 {
                    agree += 1
                } else {
                    disagree += 1
                }
            }
        }
        assert!(agree > 100 * disagree, "{agree} {disagree}");
        let s = load(&root, &def("oa_dm1", "spawn:0")).unwrap();
        check_real(&s, 5_000);
        let ents = parse_entities(&bsp.entities, Path::new("x"), 0).unwrap();
        for (o, _) in spawn_points(&ents) {
            // Nearest surface straight below the origin.
            let mut best = f32::MAX;
            for m in &s.meshes {
                for t in m.indices.chunks_exact(3) {
                    let (a, b, c) = (
                        m.positions[t[0] as usize],
                        m.positions[t[1] as usize],
                        m.positions[t[2] as usize],
                    );
                    let e = |p: Vec3, q: Vec3| {
                        (q[0] - p[0]) * (o[1] - p[1]) - (q[1] - p[1]) * (o[0] - p[0])
                    };
                    let (w0, w1, w2) = (e(b, c), e(c, a), e(a, b));
                    let sum = w0 + w1 + w2;
                    if sum.abs() < 1e-6 {
                        continue;
                    }
                    if (w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0)
                        || (w0 <= 0.0 && w1 <= 0.0 && w2 <= 0.0)
                    {
                        let z = (w0 * a[2] + w1 * b[2] + w2 * c[2]) / sum;
                        if z <= o[2] && o[2] - z < best {
                            best = o[2] - z;
                        }
                    }
                }
            }
            assert!((best - 24.0).abs() < 1.0, "spawn {o:?}: floor {best} below");
        }
    }

    #[test]
    #[ignore = "needs fetched game data: wasp scenes fetch openarena"]
    fn preview_images() {
        let Some(root) = real_root() else { return };
        let list = std::env::var("OA_PREVIEW").unwrap_or("oa_dm1:spawn:0".into());
        for item in list.split(',') {
            let (map, cam) = item.split_once(':').unwrap();
            let s = load(&root, &def(map, cam)).unwrap();
            let out = std::env::temp_dir().join(format!("oa-{map}-{}.png", cam.replace(':', "")));
            crate::supertuxkart::preview::render(&s, 980, 384, &out);
            eprintln!("{}", out.display());
        }
    }
}

#[cfg(test)]
mod all_maps {
    use super::*;
    use crate::def::Game;

    /// Every map of the fetched packages with `spawn:0`: reports each and
    /// fails on any load error.
    #[test]
    #[ignore = "needs fetched game data: wasp scenes fetch openarena"]
    fn every_map_loads() {
        let Some(root) = super::tests::real_root() else {
            return;
        };
        let mut fails = Vec::new();
        let all = maps(&root).unwrap();
        assert!(all.len() >= 40, "{all:?}");
        for m in &all {
            let d = SceneDef {
                name: m.clone(),
                game: Game::Openarena,
                map: m.clone(),
                camera: "spawn:0".into(),
                width: 1960,
                height: 768,
                description: String::new(),
                shader: None,
            };
            let t = std::time::Instant::now();
            match load(&root, &d) {
                Ok(s) => {
                    super::tests::check_real(&s, 500);
                    eprintln!(
                        "OK {m}: {} {:.2?}",
                        s.source.split("GPL; ").nth(1).unwrap_or(""),
                        t.elapsed()
                    );
                }
                Err(e) => {
                    eprintln!("FAIL {m}: {e}");
                    fails.push(format!("{m}: {e}"));
                }
            }
        }
        eprintln!("{} maps, {} failures", all.len(), fails.len());
        assert!(fails.is_empty(), "{fails:#?}");
    }
}
