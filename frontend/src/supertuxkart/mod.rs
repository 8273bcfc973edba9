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
//! # Draw calls and objects
//!
//! For the draw orders that sort ([`crate::raster::DrawOrder`]): an
//! object is one placed model (the track, a static object, a library or
//! LOD instance, an item) or billboard, as the game's scene nodes are; a
//! draw call is one of its mesh buffers (one material), as the game's
//! renderer draws them. The sky cube's faces are [`Mesh::sky`]. The game's
//! own renderer sorts nothing by depth (`docs/scenes.md`), so the shipped
//! scenes keep the order loaded: one mesh per material in order of first
//! use, then the sky, then the alpha-blended meshes.
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
    shader, Blend, Camera, Draw, Filter, Material, Mesh, Scene, SceneError, ShaderOp, Texture,
    Vec2, Vec3,
};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::rc::Rc;

use super::vec3::{add, cross, len, normalize, scale, sub};

mod builder;
mod camera;
mod driveline;
mod materials;
mod spm;
mod xml;

use builder::*;
pub use camera::*;
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

/// The eye and the point looked at (game coordinates) for camera `sel`
/// from the kart or driveline position `base` facing `dir`. A cutscene
/// camera looks at itself here: its target is the scene's centre
/// ([`look_at_bounds`]), known once the scene is placed.
fn eye_and_target(sel: CameraSel, base: Vec3, dir: Vec3, cutscene: bool) -> (Vec3, Vec3) {
    match sel {
        _ if cutscene => (base, base),
        CameraSel::Start(_) => (
            add(add(base, scale(dir, -CAM_BACK)), [0.0, CAM_UP, 0.0]),
            add(add(base, scale(dir, CAM_AHEAD)), [0.0, CAM_UP * 0.5, 0.0]),
        ),
        CameraSel::Driveline(_) => (
            add(base, [0.0, CAM_UP, 0.0]),
            add(add(base, scale(dir, CAM_AHEAD)), [0.0, CAM_UP * 0.75, 0.0]),
        ),
    }
}

/// The centre of the bounds of `meshes`, for a camera at `eye` (a point
/// ahead of the eye when there is nothing, or the centre is the eye).
fn look_at_bounds(meshes: &[Mesh], eye: Vec3) -> Vec3 {
    let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
    for m in meshes {
        for p in &m.positions {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
    }
    let target = if lo[0] <= hi[0] {
        scale(add(lo, hi), 0.5)
    } else {
        add(eye, [0.0, 0.0, -1.0])
    };
    if len(sub(target, eye)) < 1e-3 {
        add(eye, [0.0, 0.0, -1.0])
    } else {
        target
    }
}

/// The track's meshes in drawing order: opaque and alpha-tested (empty
/// ones dropped), the sky, alpha-blended.
fn draw_order(b: &mut Builder, sky: Option<&[String]>) -> Result<Vec<Mesh>, SceneError> {
    let mut meshes = std::mem::take(&mut b.meshes);
    meshes.retain(|m| !m.indices.is_empty());
    if let Some(sky) = sky {
        b.add_sky(sky)?;
    }
    let sky = std::mem::take(&mut b.meshes);
    let (blended, solid): (Vec<Mesh>, Vec<Mesh>) = meshes
        .into_iter()
        .partition(|m| b.materials[m.material].blend == Blend::AlphaBlend);
    let mut all = solid;
    all.extend(sky);
    all.extend(blended);
    Ok(all)
}

/// The scene's source note: the track, its triangle and texture counts
/// and the images it names that the data lacks.
fn source_note(map: &str, tris: usize, textures: usize, missing: &mut Vec<String>) -> String {
    missing.sort();
    missing.dedup();
    format!(
        "SuperTuxKart track `{}` (Debian supertuxkart-data, GPL / CC-BY-SA; {} triangles, {} textures, {} missing images{})",
        map,
        tris,
        textures,
        missing.len(),
        if missing.is_empty() { String::new() } else { format!(": {}", missing.join(", ")) }
    )
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
    let (eye, target) = eye_and_target(sel, base, dir, cutscene);
    let eye = to_rh(eye);
    let mut target = to_rh(target);

    let mut b = Builder::new(data_root, &track_dir, eye)?;
    let fwd = normalize(sub(target, eye));
    if !cutscene {
        b.cam_right = normalize(cross(fwd, [0.0, 1.0, 0.0]));
        b.cam_up = cross(b.cam_right, fwd);
    }
    b.place(&scene_digest.items, &Xf::IDENTITY, 0)?;
    if cutscene {
        target = look_at_bounds(&b.meshes, eye);
    }
    let all = draw_order(&mut b, scene_digest.sky.as_deref())?;
    let tris: usize = all.iter().map(|m| m.indices.len() / 3).sum();
    b.decode_textures()?;
    let source = source_note(&def.map, tris, b.textures.len(), &mut b.missing);
    Ok(Scene {
        name: format!("supertuxkart:{}:{}", def.map, def.camera.replace(':', "")),
        source,
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

#[cfg(test)]
mod all_tracks;
#[cfg(test)]
mod tests;
