//! End-to-end tests of the Teeworlds loader: a hand-made map on disk, the
//! shipped scene definitions, and the fetched game data (ignored unless
//! asked for).

use super::*;

fn def(map: &str, camera: &str) -> SceneDef {
    crate::def::test_def(crate::def::Game::Teeworlds, map, camera, 1960, 768)
}

#[test]
fn loads_a_hand_made_map_end_to_end() {
    let root = std::env::temp_dir().join(format!("wasp-tw-test-{}", std::process::id()));
    std::fs::create_dir_all(root.join("maps")).unwrap();
    std::fs::write(root.join("maps/tiny.map"), tiny_map()).unwrap();
    let (scene, stats) = load_with_stats(&root, &def("tiny", "spawn:0")).unwrap();
    // Extended edges: the 3x3 visible... every view tile maps to a
    // layer tile; the view (1500 x 588) covers far more than the layer.
    assert!(stats.tiles > 4, "{stats:?}");
    assert_eq!(stats.quads, 1);
    assert_eq!(scene.textures.len(), 1);
    assert_eq!(scene.textures[0].width, 32);
    assert_eq!(scene.materials[0].blend, Blend::Opaque); // the sky quad
    assert!(scene.materials[0]
        .shader
        .iter()
        .all(|op| matches!(op, ShaderOp::Alu(_))));
    assert!(scene
        .materials
        .iter()
        .any(|m| m.blend == Blend::Opaque && m.name.contains("tiles:opaque")));
    match scene.camera {
        Camera::Ortho {
            left,
            top,
            width,
            height,
        } => {
            assert!((left + width / 2.0 - 48.0).abs() < 1e-3);
            assert!((top + height / 2.0 - 48.0).abs() < 1e-3);
        }
        _ => panic!("not ortho"),
    }
    for m in &scene.meshes {
        assert_eq!(m.positions.len(), m.uv.len());
        assert!(m.indices.iter().all(|&i| (i as usize) < m.positions.len()));
    }
    let e = load(&root, &def("tiny", "spawn:3")).unwrap_err();
    assert!(e.message.contains("1 spawn"), "{e}");
    let e = load(&root, &def("../x", "center")).unwrap_err();
    assert!(e.message.contains("file stem"), "{e}");
    let mut d = def("tiny", "center");
    d.shader = Some("lightmapped".into());
    assert!(load(&root, &d).unwrap_err().message.contains("lightmap"));
    std::fs::remove_dir_all(&root).ok();
}

fn shipped_defs() -> Vec<SceneDef> {
    crate::def::shipped(crate::def::Game::Teeworlds)
}

#[test]
fn shipped_scene_definitions_are_valid() {
    let defs = shipped_defs();
    assert!(defs.len() >= 2);
    for d in defs {
        assert!(d.name.starts_with("tw-"), "{}", d.name);
        assert!(CameraSel::parse(&d.camera).is_some(), "{}", d.camera);
        map_path(Path::new("/data"), &d.map).unwrap();
    }
}

#[test]
#[ignore = "needs fetched game data: wasp scenes fetch teeworlds"]
fn real_shipped_scenes_load() {
    let root = real_data_root().expect("teeworlds-data not found");
    for d in shipped_defs() {
        let t0 = std::time::Instant::now();
        let (s, st) = load_with_stats(&root, &d).unwrap();
        let dt = t0.elapsed();
        let tris: usize = s.meshes.iter().map(|m| m.indices.len() / 3).sum();
        let texels: u64 = s
            .textures
            .iter()
            .map(|t| t.width as u64 * t.height as u64)
            .sum();
        println!(
            "{:18} meshes {:3} triangles {:5} materials {:3} textures {:2} ({:.1} Mtexels) \
             tiles {:4} quads {:3} load {dt:?}",
            d.name,
            s.meshes.len(),
            tris,
            s.materials.len(),
            s.textures.len(),
            texels as f64 / 1e6,
            st.tiles,
            st.quads
        );
        assert!(tris > 500);
    }
}

/// The real data root in the scene cache, if it holds `maps/dm1.map`.
fn real_data_root() -> Option<PathBuf> {
    crate::fetch::cached_data_root(crate::def::Game::Teeworlds, "maps/dm1.map")
}

#[test]
#[ignore = "needs fetched game data: wasp scenes fetch teeworlds"]
fn real_dm1_spawn0() {
    let root = real_data_root().expect("teeworlds-data not found");
    let bytes = std::fs::read(root.join("maps/dm1.map")).unwrap();
    let map = Map::parse(Path::new("dm1.map"), &bytes).unwrap();
    assert_eq!(map.groups.len(), 7);
    assert_eq!(map.layers.len(), 13);
    let g = map.game_layer().unwrap();
    assert_eq!((g.width, g.height), (60, 50));
    assert_eq!(map.spawn_points().len(), 8);
    let (scene, stats) = load_with_stats(&root, &def("dm1", "spawn:0")).unwrap();
    assert!(stats.layers_drawn >= 8, "{stats:?}");
    assert!(stats.tiles > 300 && stats.quads >= 20, "{stats:?}");
    assert!(scene.textures.len() >= 5);
    for t in &scene.textures {
        assert!(
            t.width >= 256 && t.height >= 128,
            "{} {}x{}",
            t.name,
            t.width,
            t.height
        );
        assert_eq!(t.rgba.len(), (t.width * t.height * 4) as usize);
    }
    let Camera::Ortho {
        left,
        top,
        width,
        height,
    } = scene.camera
    else {
        panic!("not ortho")
    };
    let (cx, cy) = (left + width / 2.0, top + height / 2.0);
    assert!(cx > 0.0 && cx < 60.0 * 32.0 && cy > 0.0 && cy < 50.0 * 32.0);
    let tris: usize = scene.meshes.iter().map(|m| m.indices.len() / 3).sum();
    assert!(tris > 600, "{tris}");
}

#[test]
#[ignore = "needs fetched game data; writes previews to $WASP_PREVIEW_DIR"]
fn real_previews() {
    let root = real_data_root().expect("teeworlds-data not found");
    let Some(dir) = std::env::var_os("WASP_PREVIEW_DIR") else {
        return;
    };
    // WASP_PREVIEW_SCENES="map:camera,..." (default: a few views).
    let list = std::env::var("WASP_PREVIEW_SCENES")
        .unwrap_or_else(|_| "dm1:spawn:0,ctf2:center,dm3:spawn:1".into());
    for entry in list.split(',') {
        let (map, cam) = entry.split_once(':').expect("map:camera");
        let scene = load(&root, &def(map, cam)).unwrap();
        let out = Path::new(&dir).join(format!("tw-{map}-{}.png", cam.replace(':', "")));
        crate::render::write_preview(&scene, 980, 384, &out);
    }
}

#[test]
#[ignore = "needs fetched game data: wasp scenes fetch teeworlds"]
fn real_every_map_loads() {
    let root = real_data_root().expect("teeworlds-data not found");
    let mut names: Vec<String> = std::fs::read_dir(root.join("maps"))
        .unwrap()
        .filter_map(|e| {
            let p = e.ok()?.path();
            if p.extension()? != "map" {
                return None;
            }
            Some(p.file_stem()?.to_string_lossy().into_owned())
        })
        .collect();
    names.sort();
    assert!(names.len() >= 16, "{names:?}");
    let mut failures = Vec::new();
    for name in &names {
        for cam in ["center", "spawn:0"] {
            let t0 = std::time::Instant::now();
            match load_with_stats(&root, &def(name, cam)) {
                Ok((s, st)) => {
                    let tris: usize = s.meshes.iter().map(|m| m.indices.len() / 3).sum();
                    println!(
                        "{name:6} {cam:8} meshes {:3} tris {:6} textures {:2} layers {:2} \
                         tiles {:5} quads {:4} {:?}",
                        s.meshes.len(),
                        tris,
                        s.textures.len(),
                        st.layers_drawn,
                        st.tiles,
                        st.quads,
                        t0.elapsed()
                    );
                    assert!(tris > 0);
                }
                Err(e) => failures.push(format!("{name} {cam}: {e}")),
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}
