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
//! bytes), 2 planes, 3 nodes, 4 leaves, 5 leaf faces and 16 visibility
//! data (the faces drawn from the eye: [`Vis`]; the scene's `vis = "all"`
//! draws every face), 10 vertices (position, surface uv, lightmap uv, normal, RGBA:
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
//! there too). Each image is brought to the size the engine uploads it
//! at ([`upload_size`]: sides rounded down to a power of two, then halved
//! `picmip` times, 1 by default as the engine's `r_picmip`; not for
//! shaders with `nopicmip` or `nomipmaps`, nor lightmaps); textures wider
//! or taller than [`MAX_TEXTURE_SIDE`] after that are downscaled to it.
//!
//! # Draw calls and objects
//!
//! For the draw orders that sort ([`crate::raster::DrawOrder`]): a draw
//! call is one BSP face (a surface with one shader), as Quake 3 adds its
//! draw surfaces; its object is the first BSP leaf that lists it (a
//! brush model for the faces of doors and platforms), see
//! [`Bsp::face_objects`]. `surfaceparm sky` surfaces are [`Mesh::sky`].
//! The game's renderer sorts its draw surfaces by shader, not by depth
//! (`docs/scenes.md`), so the shipped scenes keep the order loaded: the
//! sky meshes first (its sky shaders sort before the opaque ones; the
//! scene's `sky = "as-loaded"` keeps them in place), then one mesh per
//! (shader, lightmap) in order of first use by the faces, faces in lump
//! order, the alpha-blended meshes last.
//!
//! # Coordinates and camera
//!
//! Quake units, right-handed, Z up (kept; the camera's `up` is +Z).
//! `spawn:N` is the N-th `info_player_deathmatch` (then
//! `info_player_start`, then CTF team spawns) in entity order: eye
//! [`EYE_HEIGHT`] (26) above its origin, i.e. 50 above the floor the
//! origin floats 24 units over, looking along its `angle` (degrees about
//! Z, 0 = +X). Vertical field of view the engine's at the scene's width
//! and height ([`fov_y_deg`]: its default `cg_fov 90` across the frame;
//! [`FOV_Y_4_3_DEG`] with the scene's `fov = "4:3"`), near [`NEAR`], far
//! [`FAR`].

use super::bytes::Bytes;
use super::def::{OaFov, OaSky, OaVis, SceneDef};
use super::vec3::{cross, dot, sub};

mod bsp;
mod camera;
mod geometry;
mod materials;
mod pk3;
mod text;
mod tga;
mod upload;
mod vis;

use super::{
    shader, Blend, Camera, Draw, Filter, Material, Mesh, Scene, SceneError, Texture, Vec2, Vec3,
};
pub use bsp::*;
pub use camera::*;
pub use geometry::*;
use materials::*;
pub use pk3::*;
use std::collections::HashMap;
use std::fs::File;
use std::io::Read;
use std::path::{Path, PathBuf};
pub use text::*;
pub use tga::*;
pub use upload::*;
pub use vis::*;

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
/// (wasp) The loader's vertical field of view before it followed the
/// engine, kept for scenes with `fov = "4:3"`: 90 degrees across at 4:3
/// ([`fov_y_deg`]`(640, 480)`), whatever the frame's aspect.
pub const FOV_Y_4_3_DEG: f32 = 73.739_8;
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

/// Every shader script of the pk3s (`scripts/*.shader`), by lower-case
/// name; the first definition of a name wins.
fn shader_scripts(paks: &mut Paks) -> Result<HashMap<String, ShaderDef>, SceneError> {
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
    Ok(shaders)
}

/// Add every drawn face of `bsp` to the mesh of its (shader, lightmap),
/// one draw call each, of the face's object; with `visible`, only the
/// faces it marks.
fn add_faces(b: &mut Builder, bsp: &Bsp, visible: Option<&[bool]>) -> Result<(), SceneError> {
    for (fi, f) in bsp.faces.iter().enumerate() {
        if visible.is_some_and(|v| !v[fi]) {
            continue;
        }
        let Some(mi) = b.mesh(bsp, f.shader, f.lightmap)? else {
            continue;
        };
        let Some((verts, idx)) = face_triangles(bsp, f) else {
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
        mesh.draws.push(Draw {
            triangles: (idx.len() / 3) as u32,
            object: bsp.face_objects[fi],
        });
    }
    Ok(())
}

/// The spawn point the camera stands at: the map's spawn `spawn_n`
/// (origin, yaw in degrees).
fn spawn_point(bsp: &Bsp, bsp_path: &Path, spawn_n: usize) -> Result<(Vec3, f32), SceneError> {
    let entities = parse_entities(&bsp.entities, bsp_path, bsp.entities_offset)?;
    let spawns = spawn_points(&entities);
    spawns.get(spawn_n).copied().ok_or_else(|| {
        SceneError::in_file(
            bsp_path,
            format!(
                "camera spawn:{spawn_n}: the map has {} spawn points",
                spawns.len()
            ),
        )
    })
}

/// The pk3s under `data_root`, map `def.map` parsed from them, and the
/// spawn point (origin, yaw in degrees) its `spawn:N` camera names.
fn open_map(data_root: &Path, def: &SceneDef) -> Result<(Paks, Bsp, Vec3, f32), SceneError> {
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
    let (origin, yaw) = spawn_point(&bsp, &bsp_path, spawn_n)?;
    Ok((paks, bsp, origin, yaw))
}

/// The spawn point (origin, yaw in degrees) of scene `def`'s `spawn:N`
/// camera in its map under `data_root`: where the loader's camera stands
/// ([`EYE_HEIGHT`] above the origin), and where `wasp scenes capture`
/// places the engine's.
pub fn scene_spawn(data_root: &Path, def: &SceneDef) -> Result<(Vec3, f32), SceneError> {
    let (_, _, origin, yaw) = open_map(data_root, def)?;
    Ok((origin, yaw))
}

/// Load map `def.map` from `data_root` (see the module documentation).
pub fn load(data_root: &Path, def: &SceneDef) -> Result<Scene, SceneError> {
    let (mut paks, bsp, origin, yaw) = open_map(data_root, def)?;
    let shaders = shader_scripts(&mut paks)?;
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
        picmip: def.oa_picmip(),
    };
    let eye = [origin[0], origin[1], origin[2] + EYE_HEIGHT];
    let visible = match def.oa_vis() {
        OaVis::Pvs => bsp.vis.visible_faces(eye, bsp.faces.len()),
        OaVis::All => None,
    };
    add_faces(&mut b, &bsp, visible.as_deref())?;
    // Order: sky (unless `sky = "as-loaded"`), opaque and alpha-tested,
    // then alpha-blended.
    let mut meshes = std::mem::take(&mut b.meshes);
    meshes.retain(|m| !m.indices.is_empty());
    let (blended, solid): (Vec<Mesh>, Vec<Mesh>) = meshes
        .into_iter()
        .partition(|m| b.materials[m.material].blend == Blend::AlphaBlend);
    let sky_first = def.oa_sky() == OaSky::First;
    let (mut all, solid): (Vec<Mesh>, Vec<Mesh>) =
        solid.into_iter().partition(|m| sky_first && m.sky);
    all.extend(solid);
    all.extend(blended);
    let tris: usize = all.iter().map(|m| m.indices.len() / 3).sum();
    let mut missing = std::mem::take(&mut b.missing_names);
    missing.sort();
    missing.dedup();
    let (s, c) = yaw.to_radians().sin_cos();
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
            fov_y_deg: scene_fov_y_deg(def),
            near: NEAR,
            far: FAR,
        },
    })
}

#[cfg(test)]
mod all_maps;
#[cfg(test)]
mod tests;
