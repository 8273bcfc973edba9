//! End-to-end tests of the SuperTuxKart loader: a synthetic track on
//! disk, and the fetched game data (ignored unless asked for).

use super::*;
use crate::def::Game;
use spm::tiny_spm;

fn def(map: &str, camera: &str) -> SceneDef {
    crate::def::test_def(Game::Supertuxkart, map, camera, 1960, 768)
}

/// Writes a whole synthetic track under a fresh temporary root named
/// after `test` and returns the root: scene.xml with the track model, a
/// static object, a library instance, a LOD instance, quads, a texture
/// and materials.xml.
fn synthetic_track(test: &str) -> PathBuf {
    let root = std::env::temp_dir().join(format!("wasp-stk-{test}-{}", std::process::id()));
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
    root
}

#[test]
fn loads_a_synthetic_track() {
    let root = synthetic_track("load");
    let s = load(&root, &def("mini", "start:1")).unwrap();
    std::fs::remove_dir_all(&root).unwrap();
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
    // Every placed model is an object, each of its buffers a draw call
    // (a run of the material's merged mesh).
    let mut objects: Vec<u32> = s
        .meshes
        .iter()
        .flat_map(|m| m.draws.iter().map(|d| d.object))
        .collect();
    objects.sort_unstable();
    objects.dedup();
    assert_eq!(objects, [0, 1, 2, 3]);
    for m in &s.meshes {
        let drawn: u32 = m.draws.iter().map(|d| d.triangles).sum();
        assert_eq!(drawn as usize, m.indices.len() / 3);
        assert!(!m.sky);
    }
    // The 2048-wide JPEG is downscaled to 1024 wide.
    assert!(s.textures.iter().any(|t| t.width == 1024 && t.height == 8));
    // The rotated, scaled object: local (1, 0.5, -1) -> z-flip of
    // (10 + 2*(-1), 1, -2*1) ... check one transformed vertex exists.
    let want =
        to_rh(Xf::from_parts([10.0, 0.0, 0.0], [0.0, 90.0, 0.0], [2.0; 3]).apply([1.0, 0.5, -1.0]));
    assert!(m0.positions.iter().any(|p| len(sub(*p, want)) < 1e-4));
}

#[test]
fn the_camera_stands_at_the_start_position() {
    let root = synthetic_track("camera");
    let s = load(&root, &def("mini", "start:1")).unwrap();
    std::fs::remove_dir_all(&root).unwrap();
    // Camera: kart 1 is in the second column, 3.1 m behind the line
    // (on the loop's last quad), facing +z in the game = -z here.
    let Camera::Perspective { eye, target, .. } = s.camera else {
        panic!()
    };
    assert!(target[2] < eye[2]);
    assert!((eye[1] - (0.1 + CAM_UP)).abs() < 1e-4, "{eye:?}");
}

#[test]
fn a_bad_start_track_or_camera_is_an_error() {
    let root = synthetic_track("errors");
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
        let drawn: u32 = m.draws.iter().map(|d| d.triangles).sum();
        assert!(
            m.draws.is_empty() || drawn as usize == m.indices.len() / 3,
            "{}: draw calls cover {drawn} of {} triangles",
            s.name,
            m.indices.len() / 3
        );
        assert!(!m.sky || s.materials[m.material].name.starts_with("sky "));
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
    for d in crate::def::shipped(Game::Supertuxkart) {
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
        crate::render::write_preview(&s, 980, 384, &out);
        eprintln!("{}", out.display());
    }
}
