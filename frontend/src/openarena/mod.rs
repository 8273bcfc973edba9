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

mod bsp;
mod geometry;
mod pk3;
mod text;
mod tga;

use super::{
    shader, Blend, Camera, Filter, Material, Mesh, Scene, SceneError, Texture, Vec2, Vec3,
};
pub use bsp::*;
pub use geometry::*;
pub use pk3::*;
use std::collections::HashMap;
use std::fs::File;
use std::io::Read;
use std::path::{Path, PathBuf};
pub use text::*;
pub use tga::*;

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
        let found = crate::fetch::cached_data_root(Game::Openarena, "baseoa");
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
