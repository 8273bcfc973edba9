//! Test fixtures of the texture path: a texture with distinct texels, a
//! texture instruction, and the UVs of a quad.

use super::*;

pub(super) fn tex(name: &str, w: u32, h: u32, repeat: bool) -> Texture {
    let mut rgba = Vec::with_capacity((w * h * 4) as usize);
    for y in 0..h {
        for x in 0..w {
            rgba.extend_from_slice(&[(x * 7) as u8, (y * 5) as u8, ((x ^ y) * 3) as u8, 255]);
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

pub(super) fn sample(filter: Filter) -> TexSample {
    TexSample::new(0, 0, filter)
}

/// UVs of a quad at `origin` whose pixels step `step` texels in u (x) and
/// v (y) on a `size`-texel texture.
pub(super) fn quad_uvs(origin: [f32; 2], step: f32, size: f32) -> [[f32; 2]; 4] {
    let d = step / size;
    let (u, v) = (origin[0], origin[1]);
    [[u, v], [u + d, v], [u, v + d], [u + d, v + d]]
}
