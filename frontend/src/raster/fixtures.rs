//! Test fixtures of the rasterizer: a camera, a checker texture,
//! materials, quads and scenes (orthographic ones, and random perspective
//! triangles of every blend mode).

use super::*;
use crate::{Filter, Material, Mesh, Texture};

/// A camera at the origin looking down -z, y up.
pub(super) fn look_down_z(fov_y_deg: f32, near: f32, far: f32) -> Camera {
    Camera::Perspective {
        eye: [0.0, 0.0, 0.0],
        target: [0.0, 0.0, -1.0],
        up: [0.0, 1.0, 0.0],
        fov_y_deg,
        near,
        far,
    }
}

pub(super) fn checker(name: &str, n: u32) -> Texture {
    let mut rgba = Vec::new();
    for y in 0..n {
        for x in 0..n {
            let v = if ((x / 4) + (y / 4)) % 2 == 0 {
                230
            } else {
                40
            };
            rgba.extend_from_slice(&[v, v, v, 255]);
        }
    }
    Texture {
        name: name.into(),
        width: n,
        height: n,
        rgba,
        repeat: true,
    }
}

pub(super) fn mat(name: &str, blend: Blend, tex: usize) -> Material {
    Material {
        state: None,
        name: name.into(),
        blend,
        shader: crate::shader::standard(tex, Filter::Bilinear),
    }
}

pub(super) fn quad_mesh(x0: f32, y0: f32, x1: f32, y1: f32, z: f32, material: usize) -> Mesh {
    Mesh {
        positions: vec![[x0, y0, z], [x1, y0, z], [x1, y1, z], [x0, y1, z]],
        uv: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        uv2: None,
        indices: vec![0, 1, 2, 0, 2, 3],
        material,
        ..Default::default()
    }
}

pub(super) fn ortho_scene(meshes: Vec<Mesh>, materials: Vec<Material>, w: f32, h: f32) -> Scene {
    Scene {
        name: "test:ortho".into(),
        source: "unit test".into(),
        meshes,
        materials,
        textures: vec![checker("c", 64)],
        camera: Camera::Ortho {
            left: 0.0,
            top: 0.0,
            width: w,
            height: h,
        },
    }
}

/// A perspective scene of random triangles of every blend mode at
/// random depths, with exact copies drawn again (depth ties) and a
/// texture whose alpha test discards half the texels.
pub(super) fn random_scene(seed: u64, n: u32) -> Scene {
    let mut seed = seed;
    let mut next = |m: f32| {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 40) as f32 / (1u64 << 24) as f32 * m
    };
    let mut tex = checker("c", 64);
    for px in tex.rgba.chunks_exact_mut(4) {
        px[3] = px[0];
    }
    let mut meshes: Vec<Mesh> = Vec::new();
    for t in 0..n {
        let material = (t % 5) as usize % 3;
        let mesh = if t % 7 == 6 && !meshes.is_empty() {
            // A copy of an earlier triangle: the same depths.
            let k = next(meshes.len() as f32) as usize % meshes.len();
            Mesh {
                material,
                ..meshes[k].clone()
            }
        } else {
            let (cx, cy, z, r) = (
                next(16.0) - 8.0,
                next(12.0) - 6.0,
                -2.0 - next(30.0),
                next(9.0),
            );
            let mut positions = Vec::new();
            for _ in 0..3 {
                positions.push([
                    cx + next(2.0 * r) - r,
                    cy + next(2.0 * r) - r,
                    z + next(4.0) - 2.0,
                ]);
            }
            Mesh {
                positions,
                uv: vec![[0.0, 0.0], [1.0, 0.0], [0.5, 1.0]],
                uv2: None,
                indices: vec![0, 1, 2],
                material,
                ..Default::default()
            }
        };
        meshes.push(mesh);
    }
    Scene {
        name: "test:random".into(),
        source: "unit test".into(),
        meshes,
        materials: vec![
            mat("opaque", Blend::Opaque, 0),
            mat("tested", Blend::AlphaTest, 0),
            mat("blended", Blend::AlphaBlend, 0),
        ],
        textures: vec![tex],
        camera: look_down_z(60.0, 0.5, 40.0),
    }
}

pub(super) fn trace_bytes(f: &Frame) -> Vec<u8> {
    let mut out = Vec::new();
    f.trace.write(&mut out).unwrap();
    out
}
