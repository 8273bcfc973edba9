//! Procedural scenes: no download needed. Used by unit tests and as the
//! embedded default. Their names start with `procedural:` so every report
//! says they are not game data.
//!
//! * `procedural:plane` — a 3D scene: a large tiled stone ground plane in
//!   perspective (its 512x512 texture repeats every 8 units, so distant
//!   quads minify and hit deep mip levels), eight crates and brick blocks
//!   and a sky. Every material uses the `standard` shader template (the
//!   default of a lit, textured 3D surface; base texture trilinear, the
//!   sky bilinear) unless the scene definition names another. The scene
//!   also carries baked lightmaps (shadows and ambient occlusion computed
//!   here by casting rays to a directional light) and a second UV set, so
//!   `shader = "lightmapped"` gives a Quake-3-style lit variant
//!   (`scenes/procedural-plane-lit.toml`). Cameras: `ground` (default,
//!   eye height 1.7) and `high` (looking down from 25 units).
//! * `procedural:sprites` — a 2D match-3 puzzle screen under an
//!   orthographic camera: a tiled backdrop, an 8x10 board of opaque cells,
//!   alpha-blended gems (a few falling between cells), a translucent side
//!   panel with a portrait and score digits, and sparkles on top, in
//!   back-to-front (painter's) order. Every material uses the `sprite`
//!   template (bilinear; the pixel font nearest). Camera: `full`.
//!
//! Textures are generated from integer hashes, so a scene is identical on
//! every machine.

use super::def::{Game, SceneDef};
use super::shader;
use super::{Blend, Camera, Filter, Material, Mesh, Scene, SceneError, ShaderOp, Texture, Vec3};
use crate::rng::Rng;

/// The procedural maps.
pub const MAPS: [&str; 2] = ["plane", "sprites"];

/// Load a procedural scene from its definition (`game = "procedural"`).
pub fn load(def: &SceneDef) -> Result<Scene, SceneError> {
    let file = format!("scenes/{}.toml", def.name);
    if def.game != Game::Procedural {
        return Err(SceneError::in_file(
            &file,
            format!("game {}: expected procedural", def.game),
        ));
    }
    let mut scene = match def.map.as_str() {
        "plane" => plane(&def.camera, def.shader.as_deref().unwrap_or("standard"))
            .map_err(|e| SceneError::in_file(&file, e.message))?,
        "sprites" => sprites(&def.camera, def.width, def.height)?,
        other => {
            return Err(SceneError::in_file(
                &file,
                format!(
                    "procedural map `{other}` (expected one of {})",
                    MAPS.join(", ")
                ),
            ))
        }
    };
    if let (Some(t), "sprites") = (&def.shader, def.map.as_str()) {
        apply_template(&mut scene, t).map_err(|m| SceneError::in_file(&file, m))?;
    }
    Ok(scene)
}

/// Replace every material's program by the template `name` over the
/// material's first texture (and, for `lightmapped`, its second).
pub fn apply_template(scene: &mut Scene, name: &str) -> Result<(), String> {
    if !shader::TEMPLATES.contains(&name) {
        return Err(format!(
            "shader template `{name}` (expected one of {})",
            shader::TEMPLATES.join(", ")
        ));
    }
    let has_uv2 = scene.meshes.iter().all(|m| m.uv2.is_some());
    for m in &mut scene.materials {
        let tex: Vec<_> = m
            .shader
            .iter()
            .filter_map(|op| match op {
                ShaderOp::Tex(s) => Some(*s),
                ShaderOp::Alu(_) => None,
            })
            .collect();
        let Some(base) = tex.first() else {
            return Err(format!("material {} has no texture", m.name));
        };
        m.shader = match name {
            "standard" => shader::standard(base.texture, base.filter),
            "sprite" => shader::sprite(base.texture, base.filter),
            "unlit" => shader::unlit(base.texture, base.filter),
            _ => {
                let Some(lm) = tex.get(1).filter(|s| s.uv_set == 1) else {
                    return Err(format!(
                        "template lightmapped needs a lightmap; material {} has none",
                        m.name
                    ));
                };
                if !has_uv2 {
                    return Err(format!(
                        "template lightmapped needs a second UV set; {} has none",
                        scene.name
                    ));
                }
                shader::lightmapped(base.texture, lm.texture, base.filter)
            }
        };
    }
    Ok(())
}

// ---------------------------------------------------------------------
// Texture synthesis.

/// A hash of (x, y, seed) to 0..1.
fn hash(x: i32, y: i32, seed: u32) -> f32 {
    let mut h = (x as u32).wrapping_mul(0x8da6_b343)
        ^ (y as u32).wrapping_mul(0xd816_3841)
        ^ seed.wrapping_mul(0xcb1a_b31f);
    h ^= h >> 13;
    h = h.wrapping_mul(0x5bd1_e995);
    h ^= h >> 15;
    (h & 0x00ff_ffff) as f32 / 16_777_216.0
}

/// Smooth value noise with lattice period `period` (tileable).
fn value_noise(x: f32, y: f32, period: i32, seed: u32) -> f32 {
    // floor without a libm call (texture synthesis is a hot loop).
    let fl = |v: f32| {
        let i = v as i32;
        (i - i32::from((i as f32) > v)) as f32
    };
    let (xf, yf) = (fl(x), fl(y));
    let (fx, fy) = (x - xf, y - yf);
    let (sx, sy) = (fx * fx * (3.0 - 2.0 * fx), fy * fy * (3.0 - 2.0 * fy));
    let (x0, y0) = (
        (xf as i32).rem_euclid(period),
        (yf as i32).rem_euclid(period),
    );
    let (x1, y1) = ((x0 + 1) % period, (y0 + 1) % period);
    let a = hash(x0, y0, seed);
    let b = hash(x1, y0, seed);
    let c = hash(x0, y1, seed);
    let d = hash(x1, y1, seed);
    let top = a + (b - a) * sx;
    let bot = c + (d - c) * sx;
    top + (bot - top) * sy
}

/// Fractal noise over a texture of `size` texels, tileable: `octaves`
/// octaves starting at `cells` lattice cells across.
fn fbm(x: u32, y: u32, size: u32, cells: i32, octaves: u32, seed: u32) -> f32 {
    let (mut sum, mut amp, mut norm, mut c) = (0.0, 1.0, 0.0, cells);
    for o in 0..octaves {
        let s = c as f32 / size as f32;
        sum += amp * value_noise(x as f32 * s, y as f32 * s, c, seed + o);
        norm += amp;
        amp *= 0.5;
        c *= 2;
    }
    sum / norm
}

fn texture(name: &str, w: u32, h: u32, repeat: bool, f: impl Fn(u32, u32) -> [f32; 4]) -> Texture {
    let mut rgba = Vec::with_capacity((w * h * 4) as usize);
    for y in 0..h {
        for x in 0..w {
            let c = f(x, y);
            for v in c {
                rgba.push((v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8);
            }
        }
    }
    Texture {
        name: name.into(),
        width: w,
        height: h,
        rgba,
        repeat,
    }
}

fn mix(a: [f32; 3], b: [f32; 3], t: f32) -> [f32; 3] {
    [
        a[0] + (b[0] - a[0]) * t,
        a[1] + (b[1] - a[1]) * t,
        a[2] + (b[2] - a[2]) * t,
    ]
}

fn scale(c: [f32; 3], k: f32) -> [f32; 4] {
    [c[0] * k, c[1] * k, c[2] * k, 1.0]
}

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

// ---------------------------------------------------------------------
// The plane scene.

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
    // Textures: 0 stone, 1 crate, 2 brick, 3 sky, 4 ground lightmap,
    // 5 block lightmap, 6 white (the sky's lightmap).
    let mut meshes = Vec::new();

    // Ground: a 24x24 grid of patches.
    let (gx0, gx1, gz0, gz1) = (-1500.0f32, 1500.0f32, -850.0f32, 20.0f32);
    let n = 24u32;
    let mut ground = Mesh {
        positions: Vec::new(),
        uv: Vec::new(),
        uv2: Some(Vec::new()),
        indices: Vec::new(),
        material: 0,
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
    meshes.push(ground);

    // Blocks: five faces each (no bottom).
    let mut faces: Vec<([f32; 3], f32)> = Vec::new();
    let mut crates = Mesh {
        positions: Vec::new(),
        uv: Vec::new(),
        uv2: Some(Vec::new()),
        indices: Vec::new(),
        material: 1,
    };
    let mut bricks = Mesh {
        material: 2,
        ..crates.clone()
    };
    for b in &BLOCKS {
        let c = b.corners();
        let m = if b.brick { &mut bricks } else { &mut crates };
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
        for (q, w, h) in quads {
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
            let lm =
                |s: f32, t: f32| [(cu + 1.0 + 14.0 * s) / 128.0, (cv + 1.0 + 14.0 * t) / 128.0];
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
    }
    meshes.push(crates);
    meshes.push(bricks);

    // Sky: a vertical quad far away.
    let (sx0, sx1, sy0, sy1, sz) = (-3000.0f32, 3000.0f32, -60.0f32, 700.0f32, -900.0f32);
    meshes.push(Mesh {
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
    });

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

// ---------------------------------------------------------------------
// The sprites scene.

fn backdrop_texture() -> Texture {
    let n = 256;
    texture("proc/backdrop.tex", n, n, true, |x, y| {
        let stripe = ((x + y) / 32) % 2 == 0;
        let g = fbm(x, y, n, 8, 4, 61);
        let c = if stripe {
            [0.20, 0.16, 0.36]
        } else {
            [0.16, 0.20, 0.40]
        };
        scale(c, 0.8 + 0.4 * g)
    })
}

/// Two board cells side by side (light, dark), bevelled.
fn cell_texture() -> Texture {
    texture("proc/cells.tex", 128, 64, false, |x, y| {
        let (lx, ly) = (x % 64, y);
        let base = if x < 64 {
            [0.55, 0.60, 0.78]
        } else {
            [0.42, 0.47, 0.66]
        };
        let edge = lx.min(ly).min(63 - lx).min(63 - ly);
        let k = if edge < 3 {
            if lx < 3 || ly < 3 {
                1.25
            } else {
                0.7
            }
        } else {
            0.95 + 0.1 * hash(lx as i32 / 4, ly as i32 / 4, 71)
        };
        scale(base, k)
    })
}

/// Gem shapes 0..6 inside a unit cell: signed "inside" measure.
fn gem_inside(kind: u32, u: f32, v: f32) -> f32 {
    let (x, y) = (u - 0.5, v - 0.5);
    match kind {
        0 => 0.42 - (x * x + y * y).sqrt(),
        1 => 0.45 - (x.abs() + y.abs()),
        2 => 0.36 - x.abs().max(y.abs()),
        3 => {
            // Triangle pointing up.
            let a = 0.4 - y;
            let b = 0.35 + y * 0.55 - x.abs();
            a.min(b).min(y + 0.38)
        }
        4 => {
            let (ax, ay) = (x.abs(), y.abs());
            0.4 - (ax * 0.866 + ay * 0.5).max(ay)
        }
        _ => {
            let r = (x * x + y * y).sqrt();
            let a = y.atan2(x);
            0.28 + 0.12 * (5.0 * a).cos() - r
        }
    }
}

const GEM_COLOURS: [[f32; 3]; 6] = [
    [0.90, 0.15, 0.20],
    [0.20, 0.45, 0.95],
    [0.20, 0.80, 0.30],
    [0.95, 0.80, 0.15],
    [0.70, 0.30, 0.90],
    [0.95, 0.55, 0.15],
];

/// 4x4 atlas of 64x64 gems (6 used), anti-aliased alpha, a highlight.
fn gem_texture() -> Texture {
    texture("proc/gems.tex", 256, 256, false, |x, y| {
        let kind = (y / 64) * 4 + x / 64;
        if kind >= 6 {
            return [0.0; 4];
        }
        let (u, v) = ((x % 64) as f32 / 63.0, (y % 64) as f32 / 63.0);
        let d = gem_inside(kind, u, v);
        let a = (d * 64.0 + 0.5).clamp(0.0, 1.0);
        let c = GEM_COLOURS[kind as usize];
        let shade = 0.65 + 0.7 * (0.5 - v).max(-0.3) + 0.3 * (d * 4.0).min(0.4);
        let hl = ((0.12 - ((u - 0.38).powi(2) + (v - 0.33).powi(2)).sqrt()) * 30.0).clamp(0.0, 1.0);
        let col = mix(
            [c[0] * shade, c[1] * shade, c[2] * shade],
            [1.0, 1.0, 1.0],
            hl,
        );
        [col[0], col[1], col[2], a]
    })
}

fn sparkle_texture() -> Texture {
    texture("proc/sparkle.tex", 64, 64, false, |x, y| {
        let (dx, dy) = ((x as f32 - 31.5) / 32.0, (y as f32 - 31.5) / 32.0);
        let r = (dx * dx + dy * dy).sqrt();
        let star = (1.0 - (dx.abs() * dy.abs()).sqrt() * 8.0).max(0.0) * (1.0 - r).max(0.0);
        let glow = (1.0 - r).max(0.0).powi(3);
        let a = (star + 0.6 * glow).min(1.0);
        [1.0, 0.95, 0.75, a]
    })
}

fn panel_texture() -> Texture {
    texture("proc/panel.tex", 128, 128, false, |x, y| {
        let edge = x.min(y).min(127 - x).min(127 - y);
        if edge < 4 {
            [0.85, 0.75, 0.40, 0.95]
        } else {
            let g = fbm(x, y, 128, 4, 3, 81);
            [0.06, 0.06, 0.12 + 0.08 * g, 0.72]
        }
    })
}

fn portrait_texture() -> Texture {
    texture("proc/portrait.tex", 256, 256, false, |x, y| {
        let (u, v) = (x as f32 / 255.0 - 0.5, y as f32 / 255.0 - 0.5);
        let head = 0.36 - (u * u + (v * 1.1) * (v * 1.1)).sqrt();
        if head < 0.0 {
            let ring = 0.48 - (u * u + v * v).sqrt();
            return if ring > 0.0 {
                [0.95, 0.80, 0.35, (ring * 60.0).clamp(0.0, 0.5)]
            } else {
                [0.0; 4]
            };
        }
        let eye = |ex: f32| 0.05 - ((u - ex).powi(2) + (v + 0.06).powi(2)).sqrt();
        let mouth = 0.02 - (((u * u + (v - 0.05).powi(2)).sqrt() - 0.16).abs()).max(0.12 - v);
        if eye(-0.12) > 0.0 || eye(0.12) > 0.0 || mouth > 0.0 {
            return [0.1, 0.08, 0.1, 1.0];
        }
        let s = 0.85 + 0.6 * head;
        [0.98 * s, 0.78 * s, 0.55 * s, (head * 80.0).clamp(0.0, 1.0)]
    })
}

/// Digits 0-9 of the 3x5 pixel font, 8x scaled, in a 256x64 atlas (glyph
/// d at x = 25 d, 24x40 texels).
fn digit_texture() -> Texture {
    texture("proc/digits.tex", 256, 64, false, |x, y| {
        let d = x / 25;
        let (gx, gy) = ((x % 25) / 8, y / 8);
        if d > 9 || x % 25 >= 24 || gy >= 5 {
            return [0.0; 4];
        }
        let on = super::render::glyph(char::from(b'0' + d as u8))
            .is_some_and(|g| g[gy as usize] & (4 >> gx) != 0);
        if on {
            [1.0, 0.92, 0.55, 1.0]
        } else {
            [0.0; 4]
        }
    })
}

/// A sprite quad (screen rectangle, atlas rectangle in 0..1, layer z).
fn push_quad(m: &mut Mesh, rect: [f32; 4], uv: [f32; 4], z: f32) {
    let [x0, y0, x1, y1] = rect;
    let [u0, v0, u1, v1] = uv;
    let base = m.positions.len() as u32;
    m.positions
        .extend_from_slice(&[[x0, y0, z], [x1, y0, z], [x1, y1, z], [x0, y1, z]]);
    m.uv.extend_from_slice(&[[u0, v0], [u1, v0], [u1, v1], [u0, v1]]);
    m.indices
        .extend_from_slice(&[base, base + 1, base + 2, base, base + 2, base + 3]);
}

fn empty_mesh(material: usize) -> Mesh {
    Mesh {
        positions: Vec::new(),
        uv: Vec::new(),
        uv2: None,
        indices: Vec::new(),
        material,
    }
}

/// The match-3 screen for a `width` x `height` frame (camera `full`).
pub fn sprites(camera: &str, width: u32, height: u32) -> Result<Scene, SceneError> {
    if !matches!(camera, "full" | "default" | "") {
        return Err(SceneError::in_file(
            "scenes/procedural-sprites.toml",
            format!("camera `{camera}` of procedural:sprites (expected full)"),
        ));
    }
    let (w, h) = (width as f32, height as f32);
    let mut rng = Rng::new(0x5eed_0003);
    // Materials: 0 backdrop, 1 cells, 2 panel, 3 gems, 4 portrait,
    // 5 digits, 6 sparkles.
    let mut backdrop = empty_mesh(0);
    push_quad(
        &mut backdrop,
        [0.0, 0.0, w, h],
        [0.0, 0.0, w / 256.0, h / 256.0],
        0.0,
    );
    let margin = (h / 24.0).round().max(4.0);
    let cell = ((h - 2.0 * margin) / 8.0).floor().max(8.0);
    let (cols, rows) = (10u32, 8u32);
    let (bx, by) = (2.0 * margin, margin);
    let mut cells = empty_mesh(1);
    let mut gems = empty_mesh(3);
    for r in 0..rows {
        for c in 0..cols {
            let x = bx + c as f32 * cell;
            let y = by + r as f32 * cell;
            let u0 = if (r + c) % 2 == 0 { 0.0 } else { 0.5 };
            push_quad(
                &mut cells,
                [x, y, x + cell, y + cell],
                [u0, 0.0, u0 + 0.5, 1.0],
                1.0,
            );
        }
    }
    for r in 0..rows {
        for c in 0..cols {
            if rng.chance(0.08) {
                continue;
            }
            let kind = rng.below(6) as u32;
            // A few gems fall, half a cell down.
            let fall = if rng.chance(0.05) { 0.5 * cell } else { 0.0 };
            let g = cell * 0.86;
            let x = bx + c as f32 * cell + (cell - g) / 2.0;
            let y = by + r as f32 * cell + (cell - g) / 2.0 + fall;
            let (au, av) = ((kind % 4) as f32 * 0.25, (kind / 4) as f32 * 0.25);
            push_quad(
                &mut gems,
                [x, y, x + g, y + g],
                [au, av, au + 0.25, av + 0.25],
                2.0,
            );
        }
    }
    let px0 = bx + cols as f32 * cell + 2.0 * margin;
    let px1 = (w - 2.0 * margin).max(px0 + 16.0);
    let mut panel = empty_mesh(2);
    push_quad(
        &mut panel,
        [px0, margin, px1, h - margin],
        [0.0, 0.0, 1.0, 1.0],
        1.0,
    );
    let mut portrait = empty_mesh(4);
    let ps = (h * 0.42).min(px1 - px0 - 2.0 * margin).max(8.0);
    let pcx = (px0 + px1) / 2.0;
    push_quad(
        &mut portrait,
        [
            pcx - ps / 2.0,
            2.0 * margin,
            pcx + ps / 2.0,
            2.0 * margin + ps,
        ],
        [0.0, 0.0, 1.0, 1.0],
        2.0,
    );
    let mut digits = empty_mesh(5);
    let score = "048210";
    let (gw, gh) = (24.0 * 2.0, 40.0 * 2.0);
    let sx = pcx - gw * score.len() as f32 / 2.0;
    let sy = 3.0 * margin + ps;
    for (i, ch) in score.bytes().enumerate() {
        let d = f32::from(ch - b'0');
        let x = sx + i as f32 * gw;
        push_quad(
            &mut digits,
            [x, sy, x + gw - 6.0, sy + gh],
            [
                d * 25.0 / 256.0,
                0.0,
                (d * 25.0 + 24.0) / 256.0,
                40.0 / 64.0,
            ],
            3.0,
        );
    }
    let mut sparkles = empty_mesh(6);
    for _ in 0..14 {
        let s = rng.range_f64(24.0, 96.0) as f32;
        let x = bx + rng.range_f64(0.0, f64::from(cols as f32 * cell)) as f32 - s / 2.0;
        let y = by + rng.range_f64(0.0, f64::from(rows as f32 * cell)) as f32 - s / 2.0;
        push_quad(
            &mut sparkles,
            [x, y, x + s, y + s],
            [0.0, 0.0, 1.0, 1.0],
            4.0,
        );
    }
    let sprite = |name: &str, blend: Blend, tex: usize, filter: Filter| Material {
        name: name.into(),
        blend,
        shader: shader::sprite(tex, filter),
    };
    Ok(Scene {
        name: "procedural:sprites".into(),
        source: "procedural (generated by wasp, no game data)".into(),
        meshes: vec![backdrop, cells, panel, gems, portrait, digits, sparkles],
        materials: vec![
            sprite("backdrop", Blend::Opaque, 0, Filter::Bilinear),
            sprite("cells", Blend::Opaque, 1, Filter::Bilinear),
            sprite("panel", Blend::AlphaBlend, 2, Filter::Bilinear),
            sprite("gems", Blend::AlphaBlend, 3, Filter::Bilinear),
            sprite("portrait", Blend::AlphaBlend, 4, Filter::Bilinear),
            sprite("digits", Blend::AlphaBlend, 5, Filter::Nearest),
            sprite("sparkles", Blend::AlphaBlend, 6, Filter::Bilinear),
        ],
        textures: vec![
            backdrop_texture(),
            cell_texture(),
            panel_texture(),
            gem_texture(),
            portrait_texture(),
            digit_texture(),
            sparkle_texture(),
        ],
        camera: Camera::Ortho {
            left: 0.0,
            top: 0.0,
            width: w,
            height: h,
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::{rasterize, RasterOptions};
    use wasp_rtl::subset::SubsetSpec;

    fn def(map: &str, w: u32, h: u32) -> SceneDef {
        SceneDef {
            name: format!("procedural-{map}"),
            game: Game::Procedural,
            map: map.into(),
            camera: if map == "plane" { "ground" } else { "full" }.into(),
            width: w,
            height: h,
            description: String::new(),
            shader: None,
        }
    }

    fn no_colour() -> RasterOptions {
        RasterOptions {
            colour: false,
            ..RasterOptions::default()
        }
    }

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

    #[test]
    fn scenes_are_deterministic() {
        for map in MAPS {
            let d = def(map, 320, 192);
            let a = rasterize(&load(&d).unwrap(), 320, 192, &RasterOptions::default()).unwrap();
            let b = rasterize(&load(&d).unwrap(), 320, 192, &RasterOptions::default()).unwrap();
            assert_eq!(a.trace.to_text(), b.trace.to_text(), "{map}");
            assert_eq!(a.image, b.image, "{map}");
        }
    }

    #[test]
    fn sprites_overdraw_is_one_warp_per_fragment_and_ratio_is_the_sprite_template() {
        let scene = load(&def("sprites", 960, 384)).unwrap();
        let f = rasterize(&scene, 960, 384, &no_colour()).unwrap();
        let s = f.trace.stats();
        assert_eq!(s.positions, s.frame_quads, "the backdrop covers the frame");
        assert!(s.warps > s.positions, "overdraw: positions repeat");
        assert_eq!(s.warps, f.stats.warps);
        assert_eq!(s.positions, f.stats.positions);
        let want = shader::mem_ratio(&shader::sprite(0, Filter::Bilinear));
        assert!((s.mem_instr_ratio - want).abs() < 1e-12);
        // Painter's order: the blended layers are never rejected.
        for m in &f.stats.materials {
            if m.blend == "alphablend" {
                assert_eq!(m.quads_rejected_early_z, 0, "{}", m.name);
            }
        }
    }

    #[test]
    fn template_override_and_bad_names() {
        let mut d = def("plane", 256, 128);
        let s = load(&d).unwrap();
        assert!(s
            .materials
            .iter()
            .all(|m| shader::mem_ratio(&m.shader) == 1.0 / 11.0));
        d.shader = Some("lightmapped".into());
        let s = load(&d).unwrap();
        assert_eq!(s.name, "procedural:plane:lit");
        assert!(s
            .materials
            .iter()
            .all(|m| shader::mem_ratio(&m.shader) == 2.0 / 14.0));
        let f = rasterize(&s, 256, 128, &no_colour()).unwrap();
        let want = shader::mem_ratio(&shader::lightmapped(0, 1, Filter::Trilinear));
        assert!((f.trace.stats().mem_instr_ratio - want).abs() < 1e-12);
        d.shader = Some("fancy".into());
        assert!(load(&d).unwrap_err().message.contains("fancy"));
        let mut d = def("sprites", 256, 128);
        d.shader = Some("lightmapped".into());
        assert!(load(&d).is_err());
        let mut d = def("nowhere", 256, 128);
        d.map = "nowhere".into();
        assert!(load(&d).unwrap_err().message.contains("plane"));
    }
}
