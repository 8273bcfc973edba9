//! The sizes at which the engine uploads a texture: each side rounded
//! down to a power of two, then halved `r_picmip` times (at least 1 texel),
//! the mip chain built from there; and the loader's image brought to that
//! size.
//!
//! ioquake3's renderer (`opengl1`, as OpenArena 0.8.8 runs it) resamples
//! an image whose side is not a power of two to the next power of two
//! and, with its default `r_roundImagesDown 1`, halves a side that came
//! out larger than the image's, which rounds each side down to a power of
//! two. With the image's shader allowing picmip, it then shifts each side
//! right by `r_picmip` (default 1) and clamps it to at least 1, and
//! uploads level 0 at that size, reached by 2x2 box-filtered halvings.
//! Picmip applies to the images of a shader's stages (`map`, `clampMap`,
//! `animMap`) unless the shader says `nopicmip` or `nomipmaps`, to the sky
//! box of `skyParms` always, and to the image of a surface whose shader
//! has no script; lightmaps are uploaded at their size (128x128).

use super::super::texture::halve;
use super::*;

/// The engine's upload size of a `w` x `h` image at `r_picmip` `picmip`
/// (0 when the shader says `nopicmip`): each side rounded down to a power
/// of two, then shifted right by `picmip`, at least 1.
pub fn upload_size(w: u32, h: u32, picmip: u32) -> (u32, u32) {
    let side = |s: u32| {
        let pot = if s == 0 {
            1
        } else {
            1u32 << (31 - s.leading_zeros())
        };
        pot.checked_shr(picmip).unwrap_or(0).max(1)
    };
    (side(w), side(h))
}

/// Bring a decoded `w` x `h` RGBA image to its [`upload_size`] at
/// `picmip`: resampled (triangle filter) to the power-of-two size if a
/// side is not one, then halved ([`halve`], the 2x2 box filter of the mip
/// chains) down to the upload size. An image already at that size is
/// returned as it is.
pub fn upload(
    w: u32,
    h: u32,
    rgba: Vec<u8>,
    picmip: u32,
    path: &Path,
) -> Result<(u32, u32, Vec<u8>), SceneError> {
    if rgba.len() as u64 != u64::from(w) * u64::from(h) * 4 {
        return Err(SceneError::in_file(
            path,
            format!("image size mismatch: {} bytes for {w}x{h} RGBA", rgba.len()),
        ));
    }
    let (uw, uh) = upload_size(w, h, picmip);
    let (pw, ph) = upload_size(w, h, 0);
    let (mut w, mut h, mut rgba) = if (pw, ph) == (w, h) {
        (w, h, rgba)
    } else {
        let im = image::RgbaImage::from_raw(w, h, rgba)
            .ok_or_else(|| SceneError::in_file(path, "image size mismatch"))?;
        let im = image::imageops::resize(&im, pw, ph, image::imageops::FilterType::Triangle);
        (pw, ph, im.into_raw())
    };
    while w > uw || h > uh {
        (w, h, rgba) = halve(w, h, &rgba);
    }
    Ok((w, h, rgba))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn upload_sizes_follow_the_engine() {
        // r_picmip 1: half per side.
        assert_eq!(upload_size(256, 256, 1), (128, 128));
        assert_eq!(upload_size(512, 128, 1), (256, 64));
        // At least one texel per side.
        assert_eq!(upload_size(1, 64, 1), (1, 32));
        assert_eq!(upload_size(2, 1, 1), (1, 1));
        assert_eq!(upload_size(64, 64, 16), (1, 1));
        // Sides rounded down to a power of two first (r_roundImagesDown).
        assert_eq!(upload_size(100, 300, 0), (64, 256));
        assert_eq!(upload_size(100, 300, 1), (32, 128));
        // nopicmip (0): the stored size of a power-of-two image.
        assert_eq!(upload_size(256, 32, 0), (256, 32));
    }

    #[test]
    fn an_upload_is_the_box_filtered_level_below() {
        // 4x2, two columns pairs: averages of 2x2 blocks.
        let px = |v: u8| [v, v, v, 255];
        let rows: [[u8; 4]; 2] = [[0, 100, 200, 40], [20, 60, 0, 80]];
        let rgba: Vec<u8> = rows.iter().flatten().flat_map(|&v| px(v)).collect();
        let (w, h, out) = upload(4, 2, rgba.clone(), 1, Path::new("t.tga")).unwrap();
        assert_eq!((w, h), (2, 1));
        assert_eq!(out, [px(45), px(80)].concat());
        // picmip 0 at a power-of-two size: the image as it is.
        let (w, h, same) = upload(4, 2, rgba.clone(), 0, Path::new("t.tga")).unwrap();
        assert_eq!((w, h, same), (4, 2, rgba));
        // Not a power of two: resampled down first.
        let odd = vec![7u8; 6 * 3 * 4];
        let (w, h, out) = upload(6, 3, odd, 1, Path::new("t.tga")).unwrap();
        assert_eq!((w, h), (2, 1));
        assert_eq!(out, [7u8; 8]);
        let e = upload(4, 4, vec![0; 3], 1, Path::new("bad.tga")).unwrap_err();
        assert!(e.to_string().contains("bad.tga"), "{e}");
    }
}
