//! The plane scene: a tiled stone ground in perspective, crates and brick
//! blocks, a sky, and lightmaps baked by casting rays to a directional
//! light (shadows and ambient occlusion).

use super::*;

/// Stone floor: 4x4 slabs in two tints, grout, fractal grain.
fn stone_texture() -> Texture {
    let n = 512;
    texture("proc/stone-floor.tex", n, n, true, |x, y| {
        let (cx, cy) = (x / 128, y / 128);
        let (gx, gy) = (x % 128, y % 128);
        let grout = gx < 3 || gy < 3;
        let tint = if (cx + cy) % 2 == 0 {
            [0.62, 0.58, 0.50]
        } else {
            [0.44, 0.50, 0.46]
        };
        let slab = 0.85 + 0.3 * hash(cx as i32, cy as i32, 11);
        let grain = 0.7 + 0.6 * fbm(x, y, n, 8, 5, 21);
        if grout {
            scale([0.25, 0.24, 0.22], grain)
        } else {
            scale(tint, slab * grain)
        }
    })
}

/// Wooden crate: a frame and planks with streaks.
fn crate_texture() -> Texture {
    let n = 256;
    texture("proc/crate.tex", n, n, true, |x, y| {
        let border = x < 20 || y < 20 || x >= n - 20 || y >= n - 20;
        let seam = y % 36 < 2;
        let streak = fbm(x / 8, y * 4, n, 4, 4, 31);
        let base = [0.60, 0.42, 0.22];
        let k = if border {
            0.75 + 0.2 * streak
        } else if seam {
            0.35
        } else {
            0.8 + 0.35 * streak
        };
        let nail = border && ((x % 236 < 30 && y % 236 < 30) && (x % 236 > 8 && y % 236 > 8));
        if nail {
            scale([0.5, 0.5, 0.55], 0.7 + 0.3 * streak)
        } else {
            scale(base, k)
        }
    })
}

/// Brick wall: offset rows, mortar, per-brick colour.
fn brick_texture() -> Texture {
    let n = 256;
    texture("proc/brick.tex", n, n, true, |x, y| {
        let row = y / 32;
        let xo = (x + if row % 2 == 1 { 32 } else { 0 }) % n;
        let col = xo / 64;
        let mortar = y % 32 < 4 || xo % 64 < 4;
        let g = fbm(x, y, n, 16, 4, 41);
        if mortar {
            scale([0.70, 0.68, 0.62], 0.8 + 0.3 * g)
        } else {
            let v = hash(col as i32, row as i32, 43);
            scale(
                mix([0.62, 0.24, 0.16], [0.50, 0.30, 0.22], v),
                0.8 + 0.4 * g,
            )
        }
    })
}

/// Sky: zenith to horizon gradient with clouds (v = 0 at the top).
fn sky_texture() -> Texture {
    let (w, h) = (512, 256);
    texture("proc/sky.tex", w, h, false, |x, y| {
        let v = y as f32 / (h - 1) as f32;
        let base = mix([0.22, 0.42, 0.80], [0.78, 0.86, 0.95], v * v);
        let c = fbm(x, y * 2, w, 6, 5, 51);
        let cloud = ((c - 0.5) * 3.0).clamp(0.0, 1.0) * (1.0 - v * 0.6);
        let col = mix(base, [0.97, 0.97, 0.99], cloud);
        [col[0], col[1], col[2], 1.0]
    })
}

/// A box standing on the ground.
struct Block {
    centre: [f32; 2],
    size: [f32; 3],
    rot_deg: f32,
    brick: bool,
}

const BLOCKS: [Block; 8] = [
    Block {
        centre: [-3.0, -4.0],
        size: [1.6, 1.6, 1.6],
        rot_deg: 15.0,
        brick: false,
    },
    Block {
        centre: [2.5, -7.0],
        size: [2.0, 2.0, 2.0],
        rot_deg: -10.0,
        brick: false,
    },
    Block {
        centre: [-8.0, -14.0],
        size: [4.0, 6.0, 4.0],
        rot_deg: 0.0,
        brick: true,
    },
    Block {
        centre: [7.0, -18.0],
        size: [3.0, 3.0, 3.0],
        rot_deg: 35.0,
        brick: false,
    },
    Block {
        centre: [0.5, -26.0],
        size: [6.0, 3.0, 3.0],
        rot_deg: 0.0,
        brick: true,
    },
    Block {
        centre: [-18.0, -36.0],
        size: [8.0, 12.0, 8.0],
        rot_deg: 20.0,
        brick: true,
    },
    Block {
        centre: [20.0, -45.0],
        size: [10.0, 8.0, 6.0],
        rot_deg: -25.0,
        brick: true,
    },
    Block {
        centre: [-2.0, -70.0],
        size: [14.0, 20.0, 10.0],
        rot_deg: 0.0,
        brick: true,
    },
];

/// Direction towards the light (normalized in use).
const LIGHT: [f32; 3] = [-0.6, 0.65, -0.45];
/// Ground area the ground lightmap covers: x0, z0, x1, z1.
const LM_AREA: [f32; 4] = [-48.0, -104.0, 48.0, 8.0];

fn light_dir() -> [f32; 3] {
    let l = (LIGHT[0] * LIGHT[0] + LIGHT[1] * LIGHT[1] + LIGHT[2] * LIGHT[2]).sqrt();
    [LIGHT[0] / l, LIGHT[1] / l, LIGHT[2] / l]
}

impl Block {
    /// Local (x, z) axes after rotation about y.
    fn axes(&self) -> ([f32; 2], [f32; 2]) {
        let (s, c) = self.rot_deg.to_radians().sin_cos();
        ([c, -s], [s, c])
    }

    /// A world point in the block's frame.
    fn local(&self, p: [f32; 3]) -> [f32; 3] {
        let (ax, az) = self.axes();
        let (dx, dz) = (p[0] - self.centre[0], p[2] - self.centre[1]);
        [dx * ax[0] + dz * ax[1], p[1], dx * az[0] + dz * az[1]]
    }

    /// Whether the ray p + t d (t > 0) hits the block (slab test).
    fn hit(&self, p: [f32; 3], d: [f32; 3]) -> bool {
        let (ax, az) = self.axes();
        let lp = self.local(p);
        let ld = [
            d[0] * ax[0] + d[2] * ax[1],
            d[1],
            d[0] * az[0] + d[2] * az[1],
        ];
        let lo = [-self.size[0] / 2.0, 0.0, -self.size[2] / 2.0];
        let hi = [self.size[0] / 2.0, self.size[1], self.size[2] / 2.0];
        let (mut t0, mut t1) = (1e-4f32, f32::INFINITY);
        for k in 0..3 {
            if ld[k].abs() < 1e-9 {
                if lp[k] < lo[k] || lp[k] > hi[k] {
                    return false;
                }
            } else {
                let (a, b) = ((lo[k] - lp[k]) / ld[k], (hi[k] - lp[k]) / ld[k]);
                t0 = t0.max(a.min(b));
                t1 = t1.min(a.max(b));
            }
        }
        t0 <= t1
    }

    /// Distance on the ground from a point to the block's footprint.
    fn ground_distance(&self, x: f32, z: f32) -> f32 {
        let l = self.local([x, 0.0, z]);
        let dx = (l[0].abs() - self.size[0] / 2.0).max(0.0);
        let dz = (l[2].abs() - self.size[2] / 2.0).max(0.0);
        (dx * dx + dz * dz).sqrt()
    }

    /// The block's corners: bottom 0..4, top 4..8 (counter-clockwise seen
    /// from above, starting at local (-x, -z)).
    fn corners(&self) -> [Vec3; 8] {
        let (ax, az) = self.axes();
        let (hx, hz) = (self.size[0] / 2.0, self.size[2] / 2.0);
        let mut out = [[0.0; 3]; 8];
        let local = [(-hx, -hz), (-hx, hz), (hx, hz), (hx, -hz)];
        for (i, &(lx, lz)) in local.iter().enumerate() {
            // World = centre + lx * ax' + lz * az' (inverse rotation).
            let wx = self.centre[0] + lx * ax[0] + lz * az[0];
            let wz = self.centre[1] + lx * ax[1] + lz * az[1];
            out[i] = [wx, 0.0, wz];
            out[i + 4] = [wx, self.size[1], wz];
        }
        out
    }
}

/// Ground lightmap: sun and shadows of the blocks, ambient occlusion at
/// their feet; 2x2 supersampled.
fn ground_lightmap() -> Texture {
    let n = 256u32;
    let l = light_dir();
    texture("proc/ground-lightmap.tex", n, n, false, |x, y| {
        let mut lit = 0.0;
        for s in 0..4 {
            let fx = (x as f32 + 0.25 + 0.5 * (s & 1) as f32) / n as f32;
            let fz = (y as f32 + 0.25 + 0.5 * (s >> 1) as f32) / n as f32;
            let wx = LM_AREA[0] + fx * (LM_AREA[2] - LM_AREA[0]);
            let wz = LM_AREA[1] + fz * (LM_AREA[3] - LM_AREA[1]);
            if !BLOCKS.iter().any(|b| b.hit([wx, 0.0, wz], l)) {
                lit += 0.25;
            }
        }
        let fx = (x as f32 + 0.5) / n as f32;
        let fz = (y as f32 + 0.5) / n as f32;
        let wx = LM_AREA[0] + fx * (LM_AREA[2] - LM_AREA[0]);
        let wz = LM_AREA[1] + fz * (LM_AREA[3] - LM_AREA[1]);
        let d = BLOCKS
            .iter()
            .map(|b| b.ground_distance(wx, wz))
            .fold(f32::INFINITY, f32::min);
        let ao = 1.0 - 0.35 * (-d / 0.8).exp();
        let v = ((0.38 + 0.85 * l[1] * lit) * ao).min(1.0);
        [v, v * 0.98, v * 0.93, 1.0]
    })
}

/// Lightmap atlas of the blocks' faces: 8x8 cells of 16x16 texels, one
/// per (block, face), brightness from the face normal, darker near the
/// ground. Returns the texture and, per (block, face), the cell.
fn block_lightmap(faces: &[([f32; 3], f32)]) -> Texture {
    let l = light_dir();
    texture("proc/block-lightmap.tex", 128, 128, false, |x, y| {
        let cell = ((y / 16) * 8 + x / 16) as usize;
        let Some(&(n, height)) = faces.get(cell) else {
            return [1.0, 1.0, 1.0, 1.0];
        };
        let ndl = (n[0] * l[0] + n[1] * l[1] + n[2] * l[2]).max(0.0);
        // v = 0 at the top of a side face, 1 at its foot.
        let v = (y % 16) as f32 / 15.0;
        let ao = if n[1] > 0.5 {
            1.0
        } else {
            1.0 - 0.35 * (-(1.0 - v) * height / 0.8).exp()
        };
        let k = ((0.38 + 0.85 * ndl) * ao).min(1.0);
        [k, k * 0.98, k * 0.94, 1.0]
    })
}

/// The ground: a 24x24 grid of patches, uv2 on the ground lightmap
/// (material 0).
fn ground_mesh() -> Mesh {
    let (gx0, gx1, gz0, gz1) = (-1500.0f32, 1500.0f32, -850.0f32, 20.0f32);
    let n = 24u32;
    let mut ground = Mesh {
        positions: Vec::new(),
        uv: Vec::new(),
        uv2: Some(Vec::new()),
        indices: Vec::new(),
        material: 0,
        ..Default::default()
    };
    for j in 0..=n {
        for i in 0..=n {
            let x = gx0 + (gx1 - gx0) * i as f32 / n as f32;
            let z = gz0 + (gz1 - gz0) * j as f32 / n as f32;
            ground.positions.push([x, 0.0, z]);
            ground.uv.push([x / 8.0, z / 8.0]);
            let u2 = (x - LM_AREA[0]) / (LM_AREA[2] - LM_AREA[0]);
            let v2 = (z - LM_AREA[1]) / (LM_AREA[3] - LM_AREA[1]);
            ground.uv2.as_mut().expect("set").push([u2, v2]);
        }
    }
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i;
            let (b, c, d) = (a + 1, a + n + 2, a + n + 1);
            ground.indices.extend_from_slice(&[a, d, c, a, c, b]);
        }
    }
    ground
}

/// A block's five faces (no bottom) as (corners top-left, top-right,
/// bottom-right, bottom-left as seen from outside; width; height): the
/// four sides, then the top.
fn block_faces(b: &Block) -> Vec<([Vec3; 4], f32, f32)> {
    let c = b.corners();
    // Side faces: corners (i, i+1) bottom, (i+1, i) top.
    let mut quads: Vec<([Vec3; 4], f32, f32)> = Vec::new();
    for i in 0..4 {
        let j = (i + 1) % 4;
        let width = {
            let (dx, dz) = (c[j][0] - c[i][0], c[j][2] - c[i][2]);
            (dx * dx + dz * dz).sqrt()
        };
        // top-left, top-right, bottom-right, bottom-left as seen from
        // outside.
        quads.push(([c[i + 4], c[j + 4], c[j], c[i]], width, b.size[1]));
    }
    quads.push(([c[4], c[7], c[6], c[5]], b.size[0], b.size[2]));
    quads
}

/// Add face `q` (`w` x `h` world units) of block `b` to mesh `m`: its
/// normal and the block's height go to `faces`, whose index is the face's
/// cell of the block lightmap atlas; bricks repeat every 2 units, a crate
/// face shows its texture once.
fn push_face(
    m: &mut Mesh,
    faces: &mut Vec<([f32; 3], f32)>,
    b: &Block,
    (q, w, h): ([Vec3; 4], f32, f32),
) {
    let e1 = [q[1][0] - q[0][0], q[1][1] - q[0][1], q[1][2] - q[0][2]];
    let e2 = [q[3][0] - q[0][0], q[3][1] - q[0][1], q[3][2] - q[0][2]];
    let nrm = [
        e2[1] * e1[2] - e2[2] * e1[1],
        e2[2] * e1[0] - e2[0] * e1[2],
        e2[0] * e1[1] - e2[1] * e1[0],
    ];
    let len = (nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]).sqrt();
    let nrm = [nrm[0] / len, nrm[1] / len, nrm[2] / len];
    let cell = faces.len() as u32;
    faces.push((nrm, b.size[1]));
    let (cu, cv) = ((cell % 8) as f32 * 16.0, (cell / 8) as f32 * 16.0);
    let lm = |s: f32, t: f32| [(cu + 1.0 + 14.0 * s) / 128.0, (cv + 1.0 + 14.0 * t) / 128.0];
    let (su, sv) = if b.brick {
        (w / 2.0, h / 2.0)
    } else {
        (1.0, 1.0)
    };
    let base = m.positions.len() as u32;
    let uvs = [[0.0, 0.0], [su, 0.0], [su, sv], [0.0, sv]];
    let lms = [lm(0.0, 0.0), lm(1.0, 0.0), lm(1.0, 1.0), lm(0.0, 1.0)];
    for k in 0..4 {
        m.positions.push(q[k]);
        m.uv.push(uvs[k]);
        m.uv2.as_mut().expect("set").push(lms[k]);
    }
    m.indices
        .extend_from_slice(&[base, base + 1, base + 2, base, base + 2, base + 3]);
}

/// The blocks: the crates' mesh (material 1), the bricks' mesh (material
/// 2) and every face's (normal, block height) for the block lightmap.
fn block_meshes() -> (Mesh, Mesh, Vec<([f32; 3], f32)>) {
    let mut faces: Vec<([f32; 3], f32)> = Vec::new();
    let mut crates = Mesh {
        positions: Vec::new(),
        uv: Vec::new(),
        uv2: Some(Vec::new()),
        indices: Vec::new(),
        material: 1,
        ..Default::default()
    };
    let mut bricks = Mesh {
        material: 2,
        ..crates.clone()
    };
    for (object, b) in BLOCKS.iter().enumerate() {
        let m = if b.brick { &mut bricks } else { &mut crates };
        // Each block is an object and one draw call of its 5 faces.
        m.draws.push(Draw {
            triangles: 10,
            object: object as u32,
        });
        for face in block_faces(b) {
            push_face(m, &mut faces, b, face);
        }
    }
    (crates, bricks, faces)
}

/// The sky: a vertical quad far away (material 3).
fn sky_mesh() -> Mesh {
    let (sx0, sx1, sy0, sy1, sz) = (-3000.0f32, 3000.0f32, -60.0f32, 700.0f32, -900.0f32);
    Mesh {
        positions: vec![
            [sx0, sy1, sz],
            [sx1, sy1, sz],
            [sx1, sy0, sz],
            [sx0, sy0, sz],
        ],
        uv: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        uv2: Some(vec![[0.5, 0.5]; 4]),
        indices: vec![0, 1, 2, 0, 2, 3],
        material: 3,
        sky: true,
        ..Default::default()
    }
}

/// The plane scene with camera `ground` (default) or `high`, every
/// material on shader template `template` (`standard` by default).
pub fn plane(camera: &str, template: &str) -> Result<Scene, SceneError> {
    let (eye, target) = match camera {
        "ground" | "default" | "" => ([0.0, 1.7, 6.0], [0.0, 1.0, -20.0]),
        "high" => ([0.0, 25.0, 30.0], [0.0, 0.0, -30.0]),
        other => {
            return Err(SceneError::in_file(
                "scenes/procedural-plane.toml",
                format!("camera `{other}` of procedural:plane (expected ground or high)"),
            ))
        }
    };
    let name = match camera {
        "ground" | "default" | "" => "procedural:plane".to_string(),
        c => format!("procedural:plane:{c}"),
    };
    let (crates, bricks, faces) = block_meshes();
    let meshes = vec![ground_mesh(), crates, bricks, sky_mesh()];
    // Textures: 0 stone, 1 crate, 2 brick, 3 sky, 4 ground lightmap,
    // 5 block lightmap, 6 white (the sky's lightmap).
    let white = texture("proc/white.tex", 4, 4, false, |_, _| [1.0; 4]);
    let textures = vec![
        stone_texture(),
        crate_texture(),
        brick_texture(),
        sky_texture(),
        ground_lightmap(),
        block_lightmap(&faces),
        white,
    ];
    let mat = |name: &str, base: usize, lm: usize, filter: Filter| Material {
        state: None,
        name: name.into(),
        blend: Blend::Opaque,
        shader: shader::lightmapped(base, lm, filter),
    };
    let mut scene = Scene {
        name,
        source: "procedural (generated by wasp, no game data)".into(),
        meshes,
        materials: vec![
            mat("ground", 0, 4, Filter::Trilinear),
            mat("crate", 1, 5, Filter::Trilinear),
            mat("brick", 2, 5, Filter::Trilinear),
            mat("sky", 3, 6, Filter::Bilinear),
        ],
        textures,
        camera: Camera::Perspective {
            eye,
            target,
            up: [0.0, 1.0, 0.0],
            fov_y_deg: 60.0,
            near: 0.1,
            far: 1000.0,
        },
    };
    apply_template(&mut scene, template)
        .map_err(|m| SceneError::in_file("scenes/procedural-plane.toml", m))?;
    if template == "lightmapped" {
        scene.name.push_str(":lit");
    } else if template != "standard" {
        scene.name.push_str(&format!(":{template}"));
    }
    Ok(scene)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::procedural::tests::{def, no_colour};
    use crate::raster::rasterize;
    use wasp_rtl::subset::SubsetSpec;

    #[test]
    fn plane_trace_is_plausible() {
        let scene = load(&def("plane", 640, 256)).unwrap();
        assert_eq!(scene.name, "procedural:plane");
        let f = rasterize(&scene, 640, 256, &no_colour()).unwrap();
        let s = f.trace.stats();
        assert!(s.workload.starts_with("procedural:"));
        assert!(s.cf >= 1.0 && s.cf <= 4.0, "CF {}", s.cf);
        let want = shader::mem_ratio(&shader::standard(0, Filter::Trilinear));
        assert!(
            (s.mem_instr_ratio - want).abs() < 1e-12,
            "{}",
            s.mem_instr_ratio
        );
        // Every quad of the frame is shaded (ground, blocks and sky).
        assert_eq!(s.positions, s.frame_quads);
        assert!(s.warps >= s.positions);
        let side = 32;
        let ratio = |spec: SubsetSpec| {
            let sel = spec.build(side);
            crate::trace::mean_footprint_ratio(&f.trace, |x, y| sel.is_priority(x, y))
        };
        let (top, mesh4, mesh2) = (
            ratio(SubsetSpec::Top16),
            ratio(SubsetSpec::Mesh(4)),
            ratio(SubsetSpec::Mesh(2)),
        );
        assert!(
            top < mesh4 && mesh4 < mesh2,
            "top16 {top} mesh4 {mesh4} mesh2 {mesh2}"
        );
        // Distant ground minifies: mip levels beyond 0 are touched.
        let tex = crate::texture::TextureSet::new(&scene.textures);
        let stone = &tex.textures()[0];
        let lvl1 = stone.levels[1].first_block;
        let end = stone.base / 64 + stone.bytes / 64;
        let deep = f
            .trace
            .tiles()
            .iter()
            .flat_map(|t| t.block_accesses().iter().copied())
            .filter(|&b| b >= lvl1 && b < end)
            .count();
        assert!(deep > 0, "no minified access");
    }
}
