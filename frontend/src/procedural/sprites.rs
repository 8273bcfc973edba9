//! The sprites scene: a 2D match-3 puzzle screen (backdrop, board, gems,
//! side panel with a portrait and a score, sparkles) in painter's order
//! under an orthographic camera.

use super::*;

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
        let on = crate::render::glyph(char::from(b'0' + d as u8))
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
        ..Default::default()
    }
}

/// Where the screen's parts go in a `w` x `h` frame: a margin, a board of
/// `cols` x `rows` square cells at (`bx`, `by`), the side panel to its
/// right.
struct Layout {
    w: f32,
    h: f32,
    margin: f32,
    cell: f32,
    cols: u32,
    rows: u32,
    bx: f32,
    by: f32,
}

impl Layout {
    fn new(w: f32, h: f32) -> Self {
        let margin = (h / 24.0).round().max(4.0);
        let cell = ((h - 2.0 * margin) / 8.0).floor().max(8.0);
        Self {
            w,
            h,
            margin,
            cell,
            cols: 10,
            rows: 8,
            bx: 2.0 * margin,
            by: margin,
        }
    }
}

/// The board's cells, light and dark in a checkerboard (material 1).
fn board(l: &Layout) -> Mesh {
    let mut cells = empty_mesh(1);
    for r in 0..l.rows {
        for c in 0..l.cols {
            let x = l.bx + c as f32 * l.cell;
            let y = l.by + r as f32 * l.cell;
            let u0 = if (r + c) % 2 == 0 { 0.0 } else { 0.5 };
            push_quad(
                &mut cells,
                [x, y, x + l.cell, y + l.cell],
                [u0, 0.0, u0 + 0.5, 1.0],
                1.0,
            );
        }
    }
    cells
}

/// The gems (material 3): a random kind in most cells, a few falling.
fn gems(l: &Layout, rng: &mut Rng) -> Mesh {
    let cell = l.cell;
    let mut gems = empty_mesh(3);
    for r in 0..l.rows {
        for c in 0..l.cols {
            if rng.chance(0.08) {
                continue;
            }
            let kind = rng.below(6) as u32;
            // A few gems fall, half a cell down.
            let fall = if rng.chance(0.05) { 0.5 * cell } else { 0.0 };
            let g = cell * 0.86;
            let x = l.bx + c as f32 * cell + (cell - g) / 2.0;
            let y = l.by + r as f32 * cell + (cell - g) / 2.0 + fall;
            let (au, av) = ((kind % 4) as f32 * 0.25, (kind / 4) as f32 * 0.25);
            push_quad(
                &mut gems,
                [x, y, x + g, y + g],
                [au, av, au + 0.25, av + 0.25],
                2.0,
            );
        }
    }
    gems
}

/// The side panel right of the board: the panel (material 2), the
/// portrait on it (4) and the score below the portrait (5).
fn side_panel(l: &Layout) -> (Mesh, Mesh, Mesh) {
    let (h, margin) = (l.h, l.margin);
    let px0 = l.bx + l.cols as f32 * l.cell + 2.0 * margin;
    let px1 = (l.w - 2.0 * margin).max(px0 + 16.0);
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
    (panel, portrait, digits)
}

/// Sparkles over the board at random places and sizes (material 6).
fn sparkles(l: &Layout, rng: &mut Rng) -> Mesh {
    let mut sparkles = empty_mesh(6);
    for _ in 0..14 {
        let s = rng.range_f64(24.0, 96.0) as f32;
        let x = l.bx + rng.range_f64(0.0, f64::from(l.cols as f32 * l.cell)) as f32 - s / 2.0;
        let y = l.by + rng.range_f64(0.0, f64::from(l.rows as f32 * l.cell)) as f32 - s / 2.0;
        push_quad(
            &mut sparkles,
            [x, y, x + s, y + s],
            [0.0, 0.0, 1.0, 1.0],
            4.0,
        );
    }
    sparkles
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
    let layout = Layout::new(w, h);
    let cells = board(&layout);
    // The gems draw from the generator before the sparkles.
    let gems = gems(&layout, &mut rng);
    let (panel, portrait, digits) = side_panel(&layout);
    let sparkles = sparkles(&layout, &mut rng);
    let sprite = |name: &str, blend: Blend, tex: usize, filter: Filter| Material {
        state: None,
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
    use crate::procedural::tests::{def, no_colour};
    use crate::raster::rasterize;

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
}
