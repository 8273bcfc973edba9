//! End-to-end tests of the OpenArena loader: a synthetic game on disk,
//! and the fetched game data (ignored unless asked for).

use super::*;
use crate::def::Game;
use std::io::Write;

fn def(map: &str, camera: &str) -> SceneDef {
    crate::def::test_def(Game::Openarena, map, camera, 1960, 768)
}

/// Writes the pk3 `name` of `files` (entry name, contents) into
/// `root`'s baseoa.
fn write_pk3(root: &Path, name: &str, files: &[(&str, &[u8])]) {
    let f = File::create(root.join("baseoa").join(name)).unwrap();
    let mut z = zip::ZipWriter::new(f);
    let o = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated);
    for (n, d) in files {
        z.start_file(*n, o).unwrap();
        z.write_all(d).unwrap();
    }
    z.finish().unwrap();
}

/// Writes a whole synthetic game under a fresh temporary root named
/// after `test` and returns the root: a pk3 with the map, a shader
/// script, a TGA and a JPEG.
fn synthetic_game(test: &str) -> PathBuf {
    let root = std::env::temp_dir().join(format!("wasp-oa-{test}-{}", std::process::id()));
    std::fs::create_dir_all(root.join("baseoa")).unwrap();
    let mut jpg = Vec::new();
    image::RgbImage::from_pixel(8, 8, image::Rgb([200, 100, 50]))
        .write_to(
            &mut std::io::Cursor::new(&mut jpg),
            image::ImageFormat::Jpeg,
        )
        .unwrap();
    let script = b"textures/t/floor\n{\n{\nmap $lightmap\n}\n{\nmap textures/t/floor.tga\nblendfunc filter\n}\n}\n";
    write_pk3(
        &root,
        "pak0.pk3",
        &[("scripts/t.shader", script), ("textures/t/floor.jpg", &jpg)],
    );
    write_pk3(
        &root,
        "pak1.pk3",
        &[
            ("maps/mini.bsp", &tiny_bsp()),
            ("Textures/T/Floor.tga", &tiny_tga(true, true)),
        ],
    );
    root
}

#[test]
fn loads_a_synthetic_map() {
    let root = synthetic_game("load");
    assert_eq!(maps(&root).unwrap(), vec!["mini".to_string()]);
    let s = load(&root, &def("mini", "spawn:0")).unwrap();
    // The floor polygon (lightmapped) and the patch (no lightmap);
    // the nodraw face and the flare are dropped.
    assert_eq!(s.meshes.len(), 2);
    let tris: usize = s.meshes.iter().map(|m| m.indices.len() / 3).sum();
    assert_eq!(tris, 2 + 2 * PATCH_LEVEL * PATCH_LEVEL);
    // Each BSP face is a draw call; the tiny map has no leaves or
    // models, so each face is an object of its own.
    let draws: Vec<(u32, u32)> = s
        .meshes
        .iter()
        .flat_map(|m| m.draws.iter().map(|d| (d.triangles, d.object)))
        .collect();
    assert_eq!(draws.len(), 2);
    assert_ne!(draws[0].1, draws[1].1);
    for m in &s.meshes {
        let drawn: u32 = m.draws.iter().map(|d| d.triangles).sum();
        assert_eq!(drawn as usize, m.indices.len() / 3);
    }
    let lit = s.meshes.iter().find(|m| m.uv2.is_some()).unwrap();
    assert_eq!(lit.uv2.as_ref().unwrap()[2], [0.5, 0.5]);
    let mat = &s.materials[lit.material];
    assert_eq!(mat.blend, Blend::Opaque);
    // The script's .tga wins over the JPEG of the same stem; the later
    // pk3's mixed-case entry matches case-insensitively.
    assert_eq!(s.textures[0].name, "Textures/T/Floor.tga");
    std::fs::remove_dir_all(&root).unwrap();
}

#[test]
fn textures_are_uploaded_at_the_engines_picmip() {
    let root = synthetic_game("picmip");
    let s = load(&root, &def("mini", "spawn:0")).unwrap();
    // Uploaded as the engine does at r_picmip 1: 3x2 rounded down to 2x2,
    // then halved; at picmip 0, only rounded down. Lightmaps keep 128.
    assert_eq!((s.textures[0].width, s.textures[0].height), (1, 1));
    let mut d0 = def("mini", "spawn:0");
    d0.picmip = Some(0);
    let s0 = load(&root, &d0).unwrap();
    assert_eq!((s0.textures[0].width, s0.textures[0].height), (2, 2));
    assert_eq!(s0.textures[1].width, LIGHTMAP_SIDE as u32);
    assert_eq!(s.textures[1].width, LIGHTMAP_SIDE as u32);
    assert_eq!(&s.textures[1].rgba[0..4], &[0, 1, 2, 255]);
    std::fs::remove_dir_all(&root).unwrap();
}

#[test]
fn the_camera_stands_at_the_spawn_point() {
    let root = synthetic_game("camera");
    let s = load(&root, &def("mini", "spawn:0")).unwrap();
    std::fs::remove_dir_all(&root).unwrap();
    let Camera::Perspective {
        eye,
        target,
        up,
        fov_y_deg,
        ..
    } = s.camera
    else {
        panic!()
    };
    // The engine's cg_fov 90 across 1960 pixels.
    assert!((fov_y_deg - 42.79).abs() < 0.01, "{fov_y_deg}");
    assert_eq!(eye, [16.0, 32.0, 24.0 + EYE_HEIGHT]);
    assert!((target[1] - eye[1] - 1.0).abs() < 1e-6 && (target[0] - eye[0]).abs() < 1e-6);
    assert_eq!(up, [0.0, 0.0, 1.0]);
}

#[test]
fn a_bad_spawn_map_or_bsp_is_an_error() {
    let root = synthetic_game("errors");
    let e = load(&root, &def("mini", "spawn:1")).unwrap_err();
    assert!(e.message.contains("1 spawn points"), "{e}");
    let e = load(&root, &def("nope", "spawn:0")).unwrap_err();
    assert!(e.message.contains("maps/nope.bsp"), "{e}");
    // A corrupt BSP inside a pk3: the error names pk3/entry and offset.
    write_pk3(&root, "pak2.pk3", &[("maps/mini.bsp", &tiny_bsp()[..500])]);
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
        let drawn: u32 = m.draws.iter().map(|d| d.triangles).sum();
        assert!(
            m.draws.is_empty() || drawn as usize == m.indices.len() / 3,
            "{}: draw calls cover {drawn} of {} triangles",
            s.name,
            m.indices.len() / 3
        );
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
    for d in crate::def::shipped(Game::Openarena) {
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
    // Every face (not only those visible from spawn 0), so that the floor
    // under every spawn point is loaded.
    let mut every_face = def("oa_dm1", "spawn:0");
    every_face.vis = Some(crate::def::OaVis::All);
    let s = load(&root, &every_face).unwrap();
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
                if (w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0) || (w0 <= 0.0 && w1 <= 0.0 && w2 <= 0.0) {
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
        crate::render::write_preview(&s, 980, 384, &out);
        eprintln!("{}", out.display());
    }
}
