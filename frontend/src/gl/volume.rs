//! 3D textures (`GL_TEXTURE_3D`): their uploads (glTexImage3D,
//! glTexSubImage3D), how the front end holds one (a stack of 2D slices,
//! each a texture of its own laid out block-linear as the loaders'
//! textures are), and which slices a sample reads.
//!
//! # Which slices (OpenGL 1.2 specification, 3.8.5 and 3.8.6)
//!
//! With `w = r * depth` (r the third texture coordinate after the texture
//! matrix and the division by q, at level 0):
//!
//! * `GL_NEAREST` in r reads slice `k = wrap(floor(w))`;
//! * `GL_LINEAR` reads slices `k0 = wrap(floor(w - 1/2))` and
//!   `k1 = wrap(k0 + 1)`, weighted `1 - g` and `g`, `g = frac(w - 1/2)`.
//!   (wasp) When `g` is 0 (r on a slice centre, where the Teeworlds client
//!   puts its r to pick one tile per slice) only `k0` is read: such a
//!   texture is an array of 2D layers, which a mobile port stores as an
//!   OpenGL ES 3.0 `GL_TEXTURE_2D_ARRAY`, whose layer is never filtered;
//!   reading the weightless slice would double the tiles' texture blocks.
//!   When `k0` and `k1` wrap to the same slice (an edge under clamping, or
//!   one slice), it is read once.
//!
//! `wrap` follows GL_TEXTURE_WRAP_R: `GL_REPEAT` is `k mod depth`,
//! `GL_MIRRORED_REPEAT` mirrors every other period, every other mode
//! clamps to `0..depth` (`GL_CLAMP` as `GL_CLAMP_TO_EDGE`: the border
//! colour is not modelled, (wasp)). The filter in r is the one the
//! texture instruction uses in s and t: GL_TEXTURE_MIN_FILTER's
//! (`GL_NEAREST` or `GL_LINEAR`; a mipmapped 3D texture is not modelled).

use super::args::{self, CallError};
use super::enums as gl;
use super::textures::{level_of, size_of, to_rgba, Level, TexObject, Textures, PLACEHOLDER};
use crate::Texture;
use wasp_gltrace::Call;

/// The slices one sample reads: the first, and the second with its
/// weight (1/65536 units, the first has the rest).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Slices {
    pub first: u32,
    pub second: Option<(u32, u16)>,
}

/// Slice `k` wrapped into `0..depth` by the wrap mode `mode`.
fn wrap(k: i64, depth: u32, mode: i64) -> u32 {
    let d = i64::from(depth);
    match mode {
        gl::REPEAT => k.rem_euclid(d) as u32,
        gl::MIRRORED_REPEAT => {
            let m = k.rem_euclid(2 * d);
            (if m >= d { 2 * d - 1 - m } else { m }) as u32
        }
        _ => k.clamp(0, d - 1) as u32,
    }
}

/// The slices a sample at `r` reads of a texture of `depth` slices
/// wrapped by `mode`, `linear` for GL_LINEAR (module docs).
pub fn slices_at(r: f64, depth: u32, mode: i64, linear: bool) -> Slices {
    let w = r * f64::from(depth);
    if !linear {
        return Slices {
            first: wrap(w.floor() as i64, depth, mode),
            second: None,
        };
    }
    let w = w - 0.5;
    let k0 = w.floor();
    let g = w - k0;
    let (a, b) = (
        wrap(k0 as i64, depth, mode),
        wrap(k0 as i64 + 1, depth, mode),
    );
    Slices {
        first: a,
        second: (a != b)
            .then(|| (b, (g * 65536.0).round().min(65535.0) as u16))
            .filter(|&(_, weight)| weight != 0),
    }
}

/// The slices each triangle (three entries of `indices` into `r`) of a
/// draw reads of 3D texture `tex`; `Err` names what is not modelled: r
/// selecting different slices at a triangle's corners (the front end
/// samples one or two slices per triangle).
pub fn triangle_slices(tex: &TexObject, r: &[f64], indices: &[u32]) -> Result<Vec<Slices>, String> {
    let linear = tex.min_filter == gl::LINEAR;
    let (depth, mode) = (tex.depth(), tex.wrap[2]);
    indices
        .chunks_exact(3)
        .map(|t| {
            let at = |i: u32| slices_at(r[i as usize], depth, mode, linear);
            let s = at(t[0]);
            if at(t[1]) == s && at(t[2]) == s {
                Ok(s)
            } else {
                Err(format!(
                    "a 3D texture whose r coordinate selects different slices across a \
                     triangle (texture {})",
                    tex.id
                ))
            }
        })
        .collect()
}

impl TexObject {
    /// Slice `k` of level 0 as the front end's 2D texture (repeat as
    /// [`TexObject::texture`] says).
    pub fn slice_texture(&self, k: u32) -> Texture {
        let l0 = &self.levels[&0];
        let n = l0.width as usize * l0.height as usize * 4;
        let at = k as usize * n;
        Texture {
            name: format!("gl texture {} slice {k}", self.id),
            width: l0.width,
            height: l0.height,
            rgba: self.rgba[at..at + n].to_vec(),
            repeat: self.wrap[..2].contains(&gl::REPEAT),
        }
    }
}

/// Width, height and depth of a 3D upload from argument `i` on.
fn size3(call: &Call, i: usize) -> Result<(u32, u32, u32), CallError> {
    let (w, h) = size_of(call, i)?;
    let d = args::count(call, i + 2)?;
    if d == 0 || d > 16384 || w as u64 * h as u64 * d as u64 > 1 << 28 {
        return Err(CallError::at(
            call,
            format!("size {w}x{h}x{d}: expected 1 to 16384 slices and at most 2^28 texels"),
        ));
    }
    Ok((w, h, d as u32))
}

impl Textures {
    /// glTexImage3D(target, level, internalformat, width, height, depth,
    /// border, format, type, pixels): the level's size and formats kept,
    /// level 0's texels as RGBA8 (the placeholder when unreadable, as for
    /// 2D).
    pub fn image_3d(&mut self, call: &Call) -> Result<(), CallError> {
        let level = level_of(call, 1)?;
        let internal = args::int(call, 2)?;
        let (width, height, depth) = size3(call, 3)?;
        let (format, ty) = (args::int(call, 7)?, args::int(call, 8)?);
        let pixels = call.arg(9).as_bytes().map(<[u8]>::to_vec);
        let (align, row_len) = (self.unpack_alignment, self.unpack_row_length);
        let t = self.bound_mut(gl::TEXTURE_3D);
        t.levels.insert(
            level,
            Level {
                width,
                height,
                depth,
                internal,
                format,
                ty,
                compressed: false,
            },
        );
        if level != 0 {
            return Ok(());
        }
        let n = width as usize * height as usize * depth as usize;
        // Slices one after another: as rows of one image `depth` times as
        // tall (GL's unpack rules go on from slice to slice).
        let all = height.saturating_mul(depth);
        (t.rgba, t.placeholder) = match pixels {
            None => (vec![0; n * 4], None),
            Some(p) => match to_rgba(&p, width, all, format, ty, align, row_len) {
                Ok(rgba) => (rgba, None),
                Err(why) => (PLACEHOLDER.repeat(n), Some(why)),
            },
        };
        Ok(())
    }

    /// glTexSubImage3D(target, level, xoffset, yoffset, zoffset, width,
    /// height, depth, format, type, pixels): level 0's texels updated.
    pub fn sub_image_3d(&mut self, call: &Call) -> Result<(), CallError> {
        let level = level_of(call, 1)?;
        let (x, y, z) = (
            args::count(call, 2)?,
            args::count(call, 3)?,
            args::count(call, 4)?,
        );
        let (w, h, d) = size3(call, 5)?;
        let (format, ty) = (args::int(call, 8)?, args::int(call, 9)?);
        let (align, row_len) = (self.unpack_alignment, self.unpack_row_length);
        let pixels = call.arg(10).as_bytes().map(<[u8]>::to_vec);
        let t = self.bound_mut(gl::TEXTURE_3D);
        let Some(l) = t.levels.get(&level) else {
            return Err(CallError::at(
                call,
                format!("level {level} was never uploaded"),
            ));
        };
        let (lw, lh, ld) = (l.width as usize, l.height as usize, l.depth as usize);
        if x + w as usize > lw || y + h as usize > lh || z + d as usize > ld {
            return Err(CallError::at(
                call,
                format!("box {x},{y},{z} {w}x{h}x{d} outside level {level}'s {lw}x{lh}x{ld}"),
            ));
        }
        if level != 0 || t.placeholder.is_some() {
            return Ok(());
        }
        let (w, h, d) = (w as usize, h as usize, d as usize);
        let rgba = pixels
            .and_then(|p| to_rgba(&p, w as u32, (h * d) as u32, format, ty, align, row_len).ok())
            .unwrap_or_else(|| PLACEHOLDER.repeat(w * h * d));
        for (row, src) in rgba.chunks_exact(w * 4).enumerate() {
            let (slice, yy) = (z + row / h, y + row % h);
            let at = ((slice * lh + yy) * lw + x) * 4;
            t.rgba[at..at + src.len()].copy_from_slice(src);
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::super::args::test_calls::*;
    use super::*;
    use wasp_gltrace::Value;

    #[test]
    fn slices_follow_the_filter_and_the_wrap_mode() {
        // 256 slices, r at slice 7's centre: nearest reads 7; linear reads
        // 7 and 8, 8 with weight 0: slice 7 alone.
        let r = 7.5 / 256.0;
        let near = slices_at(r, 256, gl::REPEAT, false);
        assert_eq!(
            near,
            Slices {
                first: 7,
                second: None
            }
        );
        let lin = slices_at(r, 256, gl::REPEAT, true);
        assert_eq!(
            lin,
            Slices {
                first: 7,
                second: None
            }
        );
        // A quarter of the way from slice 2's centre to slice 3's.
        let q = slices_at(2.75 / 4.0, 4, gl::REPEAT, true);
        assert_eq!(
            q,
            Slices {
                first: 2,
                second: Some((3, 16384))
            }
        );
        // Past the last centre: repeat wraps to slice 0, clamping reads the
        // last slice once, mirroring reads it twice (once).
        let top = 3.75 / 4.0;
        assert_eq!(slices_at(top, 4, gl::REPEAT, true).second, Some((0, 16384)));
        let clamp = slices_at(top, 4, 0x812F, true);
        assert_eq!(
            clamp,
            Slices {
                first: 3,
                second: None
            }
        );
        assert_eq!(slices_at(top, 4, gl::MIRRORED_REPEAT, true).second, None);
        assert_eq!(slices_at(-0.1, 4, gl::MIRRORED_REPEAT, false).first, 0);
        assert_eq!(slices_at(1.3, 4, gl::MIRRORED_REPEAT, false).first, 2);
    }

    #[test]
    fn uploads_keep_every_slice_and_sub_images_land_in_theirs() {
        let i = Value::SInt;
        let mut t = Textures::new(1);
        t.bind(gl::TEXTURE_3D, 4);
        t.pixel_store(gl::UNPACK_ALIGNMENT, 1).unwrap();
        // 2x1x3 GL_LUMINANCE: texel (x, 0, z) is 10 z + x.
        let px = vec![0, 1, 10, 11, 20, 21];
        let args = vec![e(gl::TEXTURE_3D), i(0), e(gl::RGBA), i(2), i(1), i(3), i(0)];
        let fmt = vec![e(gl::LUMINANCE), e(gl::UNSIGNED_BYTE), Value::Blob(px)];
        t.image_3d(&call(1, "glTexImage3D", [args, fmt].concat()))
            .unwrap();
        let o = t.objects_3d[&4].clone();
        assert_eq!((o.depth(), o.rgba.len()), (3, 2 * 3 * 4));
        assert_eq!(o.slice_texture(2).rgba, [20, 20, 20, 255, 21, 21, 21, 255]);
        assert!(!t.objects.contains_key(&4), "the 2D name is another object");
        // Slice 1, texel 1: 99.
        let sub = vec![e(gl::TEXTURE_3D), i(0), i(1), i(0), i(1), i(1), i(1), i(1)];
        let fmt = vec![
            e(gl::LUMINANCE),
            e(gl::UNSIGNED_BYTE),
            Value::Blob(vec![99]),
        ];
        t.sub_image_3d(&call(2, "glTexSubImage3D", [sub.clone(), fmt].concat()))
            .unwrap();
        let o = &t.objects_3d[&4];
        assert_eq!(&o.slice_texture(1).rgba[4..8], &[99, 99, 99, 255]);
        assert_eq!(&o.slice_texture(0).rgba[4..8], &[1, 1, 1, 255]);
        let mut far = sub;
        far[4] = i(3);
        let fmt = vec![e(gl::LUMINANCE), e(gl::UNSIGNED_BYTE), Value::Blob(vec![9])];
        let err = t.sub_image_3d(&call(3, "glTexSubImage3D", [far, fmt].concat()));
        assert!(err.unwrap_err().message.contains("outside level 0's 2x1x3"));
    }
}
