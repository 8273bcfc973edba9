//! End-to-end tests of the Frozen Bubble loader: a hand-made data root,
//! the shipped scene definitions, and the fetched game data (ignored
//! unless asked for).

use super::*;
use gif::{encode_gif, PAL};

fn def(camera: &str) -> SceneDef {
    crate::def::test_def(crate::def::Game::FrozenBubble, "levels", camera, 1024, 768)
}

/// A data root with hand-made images and levels (GIF and PNG writers
/// of this module's tests and the image crate).
fn fake_root() -> PathBuf {
    let root = std::env::temp_dir().join(format!("wasp-fb-test-{}", std::process::id()));
    let gfx = root.join("gfx");
    std::fs::create_dir_all(gfx.join("balls")).unwrap();
    std::fs::create_dir_all(gfx.join("pinguins")).unwrap();
    std::fs::create_dir_all(root.join("data")).unwrap();
    std::fs::write(root.join("data/levels"), TINY).unwrap();
    let png = |rel: &str, w: u32, h: u32| {
        let img = image::RgbaImage::from_fn(w, h, |x, y| {
            image::Rgba([x as u8, y as u8, 0, if x == 0 { 0 } else { 255 }])
        });
        img.save(gfx.join(rel)).unwrap();
    };
    png("back_one_player.png", 640, 480);
    png("compressor_main.png", 252, 51);
    png("dot_red.png", 7, 7);
    png("dot_green.png", 7, 7);
    png("on_top_next.png", 39, 39);
    png("shooter.png", 100, 100);
    png("pinguins/anime-shooter_p1_0020.png", 80, 60);
    let px = vec![1u8; 32 * 32];
    for c in 1..=8 {
        std::fs::write(
            gfx.join(format!("balls/bubble-{c}.gif")),
            encode_gif(32, 32, &PAL, &px, Some(0), false),
        )
        .unwrap();
    }
    root
}

#[test]
fn loads_a_hand_made_level_end_to_end() {
    let root = fake_root();
    let scene = load(&root, &def("level:3")).unwrap();
    // background, compressor, 15 bubbles, 9 dots, next + frame,
    // launch, shooter, penguin.
    assert_eq!(scene.meshes.len(), 2 + 15 + 9 + 2 + 1 + 2);
    assert_eq!(scene.materials[0].blend, Blend::Opaque);
    assert!(scene.materials[1..]
        .iter()
        .all(|m| m.blend == Blend::AlphaBlend));
    // Bubble textures once per colour; the shooter cropped by a column.
    let shooter = scene
        .textures
        .iter()
        .find(|t| t.name.ends_with("shooter.png"))
        .unwrap();
    assert_eq!((shooter.width, shooter.height), (99, 100));
    let m = &scene.meshes[scene.meshes.len() - 2];
    assert_eq!(m.positions[0], [CANON.0 + 1.0, CANON.1, m.positions[0][2]]);
    assert_eq!(
        scene.camera,
        Camera::Ortho {
            left: 0.0,
            top: 0.0,
            width: 640.0,
            height: 480.0
        }
    );
    let e = load(&root, &def("level:4")).unwrap_err();
    assert!(e.message.contains("3 levels"), "{e}");
    let e = load(&root, &def("level:0")).unwrap_err();
    assert!(e.message.contains("level:N"), "{e}");
    std::fs::remove_dir_all(&root).ok();
}

fn shipped_defs() -> Vec<SceneDef> {
    crate::def::shipped(crate::def::Game::FrozenBubble)
}

#[test]
fn shipped_scene_definitions_are_valid() {
    let defs = shipped_defs();
    assert!(defs.len() >= 2);
    for d in defs {
        assert!(d.name.starts_with("fb-"), "{}", d.name);
        assert!(parse_camera(&d.camera).is_some(), "{}", d.camera);
        levels_path(Path::new("/data"), &d.map).unwrap();
    }
}

#[test]
#[ignore = "needs fetched game data: wasp scenes fetch frozen-bubble"]
fn real_shipped_scenes_load() {
    let root = real_data_root().expect("frozen-bubble-data not found");
    for d in shipped_defs() {
        let t0 = std::time::Instant::now();
        let s = load(&root, &d).unwrap();
        let dt = t0.elapsed();
        let tris: usize = s.meshes.iter().map(|m| m.indices.len() / 3).sum();
        let texels: u64 = s
            .textures
            .iter()
            .map(|t| t.width as u64 * t.height as u64)
            .sum();
        println!(
            "{:18} meshes {:3} triangles {:4} materials {:3} textures {:2} ({:.2} Mtexels) load {dt:?}",
            d.name,
            s.meshes.len(),
            tris,
            s.materials.len(),
            s.textures.len(),
            texels as f64 / 1e6,
        );
        assert!(tris > 40);
    }
}

/// The real data root in the scene cache, if it holds `data/levels`.
fn real_data_root() -> Option<PathBuf> {
    crate::fetch::cached_data_root(crate::def::Game::FrozenBubble, "data/levels")
}

#[test]
#[ignore = "needs fetched game data: wasp scenes fetch frozen-bubble"]
fn real_level1() {
    let root = real_data_root().expect("frozen-bubble-data not found");
    let text = std::fs::read(root.join("data/levels")).unwrap();
    let levels = parse_levels(Path::new("levels"), &text).unwrap();
    assert_eq!(levels.len(), 100);
    assert_eq!(levels[0].bubbles.len(), 30);
    let scene = load(&root, &def("level:1")).unwrap();
    assert_eq!(scene.meshes.len(), 2 + 30 + 9 + 2 + 1 + 2);
    let bubble = scene
        .textures
        .iter()
        .find(|t| t.name.ends_with("bubble-7.gif"))
        .unwrap();
    assert_eq!((bubble.width, bubble.height), (32, 32));
    // A round bubble: transparent corners, opaque centre.
    assert_eq!(bubble.rgba[3], 0);
    assert_eq!(bubble.rgba[4 * (16 * 32 + 16) + 3], 255);
    let back = &scene.textures[0];
    assert_eq!((back.width, back.height), (640, 480));
    for t in &scene.textures {
        assert_eq!(
            t.rgba.len(),
            (t.width * t.height * 4) as usize,
            "{}",
            t.name
        );
    }
}

#[test]
#[ignore = "needs fetched game data: wasp scenes fetch frozen-bubble"]
fn real_levels_load() {
    let root = real_data_root().expect("frozen-bubble-data not found");
    let mut failures = Vec::new();
    for n in [1, 2, 10, 25, 50, 75, 99, 100] {
        let t0 = std::time::Instant::now();
        match load(&root, &def(&format!("level:{n}"))) {
            Ok(s) => {
                let tris: usize = s.meshes.iter().map(|m| m.indices.len() / 3).sum();
                println!(
                    "level {n:3}: meshes {:3} tris {:3} textures {:2} {:?}",
                    s.meshes.len(),
                    tris,
                    s.textures.len(),
                    t0.elapsed()
                );
            }
            Err(e) => failures.push(format!("level {n}: {e}")),
        }
    }
    // Every bubble GIF of the package (normal and colour-blind) decodes.
    for entry in std::fs::read_dir(root.join("gfx/balls")).unwrap() {
        let p = entry.unwrap().path();
        if p.extension().is_some_and(|x| x == "gif") {
            if let Err(e) = decode_gif(&p, &std::fs::read(&p).unwrap()) {
                failures.push(e.to_string());
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
#[ignore = "needs fetched game data; writes previews to $WASP_PREVIEW_DIR"]
fn real_previews() {
    let root = real_data_root().expect("frozen-bubble-data not found");
    let Some(dir) = std::env::var_os("WASP_PREVIEW_DIR") else {
        return;
    };
    for (n, w, h) in [(1, 1024, 768), (50, 1024, 768), (100, 1960, 768)] {
        let mut d = def(&format!("level:{n}"));
        d.width = w;
        d.height = h;
        let scene = load(&root, &d).unwrap();
        let out = Path::new(&dir).join(format!("fb-level{n}.png"));
        crate::render::write_preview(&scene, w / 2, h / 2, &out);
    }
}
