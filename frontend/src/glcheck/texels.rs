//! The texels of a rewritten texture upload: every texel's RGB replaced by
//! one colour (the texture's id, or the count's unit), its alpha the one
//! the original upload gives in OpenGL (the internal format decides
//! whether there is alpha, and at what precision), as RGBA8 rows with no
//! padding.

use crate::gl::textures::to_rgba;

/// GL internal formats and enums this module reads.
pub(super) const RGBA8: i64 = 0x8058;
const RGBA4: i64 = 0x8056;
const RGB5_A1: i64 = 0x8057;
const RGBA2: i64 = 0x8055;
const ALPHA4: i64 = 0x803B;
const LUMINANCE4_ALPHA4: i64 = 0x8043;
const LUMINANCE6_ALPHA2: i64 = 0x8044;

/// Where the alpha of a texel of internal format `internal` comes from
/// and with how many bits; `None`: the format has no alpha (alpha reads 1).
fn alpha_bits(internal: i64) -> Option<u32> {
    match internal {
        // 2 (luminance-alpha), 4 (RGBA), GL_ALPHA, GL_RGBA,
        // GL_LUMINANCE_ALPHA, GL_BGRA and the sized 8-bit-or-more ones.
        2 | 4 | 0x1906 | 0x1908 | 0x190A | 0x80E1 => Some(8),
        0x803C..=0x803E | 0x8045..=0x8048 | 0x8058..=0x805B => Some(8),
        // GL_INTENSITY*: alpha is the intensity.
        0x8049..=0x804D => Some(8),
        RGBA4 | ALPHA4 | LUMINANCE4_ALPHA4 => Some(4),
        RGBA2 | LUMINANCE6_ALPHA2 => Some(2),
        RGB5_A1 => Some(1),
        _ => None,
    }
}

/// An 8-bit alpha stored in `bits` bits and read back as 8 bits (rounded
/// to the nearest level, as OpenGL converts to unsigned normalized).
fn quantize(a: u8, bits: u32) -> u8 {
    if bits >= 8 {
        return a;
    }
    let levels = (1u32 << bits) - 1;
    let q = (u32::from(a) * levels + 127) / 255;
    ((q * 255 + levels / 2) / levels) as u8
}

/// How an upload's pixels are laid out in client memory.
#[derive(Clone, Copy, Debug)]
pub(super) struct Unpack {
    pub align: usize,
    pub row_length: usize,
}

/// The RGBA8 texels of a `width` x `height` upload of `pixels` (format,
/// type) into internal format `internal`, every texel's RGB `rgb`. The
/// alpha is the upload's where the format has alpha (decoded as the
/// importer decodes it), else 255; `Err` says why the pixels could not be
/// decoded (the alpha is then 255).
pub(super) fn id_texels(
    pixels: Option<&[u8]>,
    (width, height): (u32, u32),
    (internal, format, ty): (i64, i64, i64),
    unpack: Unpack,
    rgb: [u8; 3],
) -> (Vec<u8>, Option<String>) {
    let n = width as usize * height as usize;
    let mut alpha = vec![255u8; n];
    let mut why = None;
    if let (Some(bits), Some(p)) = (alpha_bits(internal), pixels) {
        match to_rgba(
            p,
            width,
            height,
            format,
            ty,
            unpack.align,
            unpack.row_length,
        ) {
            Ok(rgba) => {
                for (a, px) in alpha.iter_mut().zip(rgba.chunks_exact(4)) {
                    *a = quantize(px[3], bits);
                }
            }
            Err(e) => why = Some(e),
        }
    }
    let mut out = Vec::with_capacity(n * 4);
    for a in alpha {
        out.extend_from_slice(&[rgb[0], rgb[1], rgb[2], a]);
    }
    (out, why)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn alpha_follows_the_internal_format() {
        let rgba = [10u8, 20, 30, 200, 1, 2, 3, 100];
        let unpack = Unpack {
            align: 4,
            row_length: 0,
        };
        let fmt = |internal| (internal, 0x1908, 0x1401);
        let (t, why) = id_texels(Some(&rgba), (2, 1), fmt(0x1908), unpack, [7, 0, 0]);
        assert_eq!((t, why), (vec![7, 0, 0, 200, 7, 0, 0, 100], None));
        // GL_RGB internally: alpha 1 whatever the data says.
        let (t, _) = id_texels(Some(&rgba), (2, 1), fmt(0x1907), unpack, [1, 1, 1]);
        assert_eq!(t, vec![1, 1, 1, 255, 1, 1, 1, 255]);
        // GL_RGB5_A1: one bit of alpha; GL_RGBA4: 16 levels.
        let (t, _) = id_texels(Some(&rgba), (2, 1), fmt(RGB5_A1), unpack, [0, 0, 0]);
        assert_eq!((t[3], t[7]), (255, 0));
        let (t, _) = id_texels(Some(&rgba), (2, 1), fmt(RGBA4), unpack, [0, 0, 0]);
        assert_eq!((t[3], t[7]), (204, 102));
        // Undecodable pixels: alpha 1, and the reason.
        let (t, why) = id_texels(Some(&rgba), (2, 1), (4, 0x1908, 0x1406), unpack, [0, 0, 0]);
        assert_eq!(t[3], 255);
        assert!(why.is_some());
    }
}
