//! Texture synthesis: integer hashes, tileable value and fractal noise,
//! and textures generated texel by texel (so a scene is identical on
//! every machine).

use super::*;

/// A hash of (x, y, seed) to 0..1.
pub(super) fn hash(x: i32, y: i32, seed: u32) -> f32 {
    let mut h = (x as u32).wrapping_mul(0x8da6_b343)
        ^ (y as u32).wrapping_mul(0xd816_3841)
        ^ seed.wrapping_mul(0xcb1a_b31f);
    h ^= h >> 13;
    h = h.wrapping_mul(0x5bd1_e995);
    h ^= h >> 15;
    (h & 0x00ff_ffff) as f32 / 16_777_216.0
}

/// Smooth value noise with lattice period `period` (tileable).
pub(super) fn value_noise(x: f32, y: f32, period: i32, seed: u32) -> f32 {
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
pub(super) fn fbm(x: u32, y: u32, size: u32, cells: i32, octaves: u32, seed: u32) -> f32 {
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

pub(super) fn texture(
    name: &str,
    w: u32,
    h: u32,
    repeat: bool,
    f: impl Fn(u32, u32) -> [f32; 4],
) -> Texture {
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

pub(super) fn mix(a: [f32; 3], b: [f32; 3], t: f32) -> [f32; 3] {
    [
        a[0] + (b[0] - a[0]) * t,
        a[1] + (b[1] - a[1]) * t,
        a[2] + (b[2] - a[2]) * t,
    ]
}

pub(super) fn scale(c: [f32; 3], k: f32) -> [f32; 4] {
    [c[0] * k, c[1] * k, c[2] * k, 1.0]
}
