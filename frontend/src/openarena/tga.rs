//! TGA textures (uncompressed or RLE, BGR or BGRA), decoded by the
//! `image` crate.

use super::*;
use image::ImageFormat;

/// Decode a TGA image (true-colour 24/32 bit or grey 8 bit, uncompressed
/// or RLE) to RGBA8, top row first. Errors name the file.
pub fn decode_tga(bytes: &[u8], file: &Path) -> Result<(u32, u32, Vec<u8>), SceneError> {
    crate::image_decode::decode_rgba(file, bytes, ImageFormat::Tga)
}

#[cfg(test)]
/// A 3x2 TGA: BGR(A), uncompressed or RLE.
pub(super) fn tiny_tga(rle: bool, alpha: bool) -> Vec<u8> {
    let px = if alpha { 4 } else { 3 };
    let mut v = vec![0u8; 18];
    v[0] = 2; // id length
    v[2] = if rle { 10 } else { 2 };
    v[12] = 3;
    v[14] = 2;
    v[16] = 8 * px as u8;
    v.extend_from_slice(b"id");
    // Bottom row first: bottom = red red blue, top = green x3.
    let red: &[u8] = &[0, 0, 255, 200][..px];
    let blue: &[u8] = &[255, 0, 0, 100][..px];
    let green: &[u8] = &[0, 255, 0, 255][..px];
    if rle {
        v.push(0x81);
        v.extend_from_slice(red);
        v.push(0x00);
        v.extend_from_slice(blue);
        v.push(0x82);
        v.extend_from_slice(green);
    } else {
        for p in [red, red, blue, green, green, green] {
            v.extend_from_slice(p);
        }
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decodes_tga() {
        for rle in [false, true] {
            for alpha in [false, true] {
                let (w, h, rgba) = decode_tga(&tiny_tga(rle, alpha), Path::new("t.tga")).unwrap();
                assert_eq!((w, h), (3, 2));
                let a = |x: u8| if alpha { x } else { 255 };
                assert_eq!(&rgba[0..4], &[0, 255, 0, 255]);
                assert_eq!(&rgba[12..16], &[255, 0, 0, a(200)]);
                assert_eq!(&rgba[20..24], &[0, 0, 255, a(100)]);
            }
        }
        let mut v = tiny_tga(false, false);
        v[17] = 0x20; // top row first
        let (_, _, rgba) = decode_tga(&v, Path::new("t.tga")).unwrap();
        assert_eq!(&rgba[0..4], &[255, 0, 0, 255]);
        let mut v = tiny_tga(false, false);
        v[2] = 4; // no such image type
        let e = decode_tga(&v, Path::new("t.tga")).unwrap_err();
        assert_eq!(e.file, Path::new("t.tga"));
        assert!(e.message.contains("TGA"), "{e}");
        // An RLE packet that runs past the image is cut at its end (the
        // decoder's rule): the image keeps its size.
        let mut v = tiny_tga(true, false);
        v[20] = 0x86;
        let (w, h, rgba) = decode_tga(&v, Path::new("t.tga")).unwrap();
        assert_eq!((w, h, rgba.len()), (3, 2, 24));
    }
}
