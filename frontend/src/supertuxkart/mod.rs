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

mod driveline;
mod materials;
mod spm;
mod xml;

use driveline::*;
use materials::*;
pub use spm::{half_to_f32, parse_spm, Spm, SpmBuffer, SpmMaterial};
use xml::*;

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
    use spm::tiny_spm;

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
        let found = crate::fetch::cached_data_root(Game::Supertuxkart, "tracks");
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
