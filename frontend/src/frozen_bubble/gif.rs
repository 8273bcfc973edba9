//! GIF images (87a/89a): the first image of a file decoded by the `image`
//! crate into an RGBA texture, its transparent colour transparent black.

use super::*;
use image::ImageFormat;

/// Decode the first image of a GIF (87a/89a) into an RGBA texture of the
/// logical screen size; the transparent colour (graphic control extension)
/// and pixels outside the frame are transparent black. Errors name the
/// file.
pub fn decode_gif(path: &Path, bytes: &[u8]) -> Result<(u32, u32, Vec<u8>), SceneError> {
    crate::image_decode::decode_rgba(path, bytes, ImageFormat::Gif)
}

#[cfg(test)]
/// A GIF encoder for tests: clear codes every two pixels keep the code
/// size at min_size + 1.
pub(super) fn encode_gif(
    w: u16,
    h: u16,
    palette: &[[u8; 3]; 4],
    px: &[u8],
    transparent: Option<u8>,
    interlace: bool,
) -> Vec<u8> {
    let mut out = b"GIF89a".to_vec();
    out.extend(w.to_le_bytes());
    out.extend(h.to_le_bytes());
    out.extend([0x80 | 0x01, 0, 0]); // global table of 4 colours
    for c in palette {
        out.extend(c);
    }
    if let Some(t) = transparent {
        out.extend([0x21, 0xf9, 4, 1, 0, 0, t, 0]);
    }
    out.push(0x2c);
    out.extend([0u8, 0, 0, 0]);
    out.extend(w.to_le_bytes());
    out.extend(h.to_le_bytes());
    out.push(if interlace { 0x40 } else { 0 });
    out.push(2); // min code size: clear 4, end 5, codes of 3 bits
    let mut codes = Vec::new();
    for pair in px.chunks(2) {
        codes.push(4u8);
        codes.extend(pair);
    }
    codes.push(5);
    let (mut acc, mut bits, mut data) = (0u32, 0u32, Vec::new());
    for c in codes {
        acc |= (c as u32) << bits;
        bits += 3;
        while bits >= 8 {
            data.push(acc as u8);
            acc >>= 8;
            bits -= 8;
        }
    }
    if bits > 0 {
        data.push(acc as u8);
    }
    for chunk in data.chunks(255) {
        out.push(chunk.len() as u8);
        out.extend(chunk);
    }
    out.extend([0, 0x3b]);
    out
}

#[cfg(test)]
/// The palette of the test GIFs.
pub(super) const PAL: [[u8; 3]; 4] = [[0, 0, 0], [255, 0, 0], [0, 255, 0], [0, 0, 255]];

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn decodes_a_hand_made_gif() {
        let px = [0u8, 1, 2, 3, 3, 2, 1, 0, 1, 1, 2, 2];
        let gif = encode_gif(4, 3, &PAL, &px, Some(0), false);
        let (w, h, rgba) = decode_gif(Path::new("t.gif"), &gif).unwrap();
        assert_eq!((w, h), (4, 3));
        for (i, &p) in px.iter().enumerate() {
            let want = if p == 0 {
                [0, 0, 0, 0]
            } else {
                let c = PAL[p as usize];
                [c[0], c[1], c[2], 255]
            };
            assert_eq!(rgba[4 * i..4 * i + 4], want, "pixel {i}");
        }
        // Interlaced: rows stored in the order 0, 2, 1 for 3 rows.
        let stored = [0u8, 1, 2, 3, 1, 1, 2, 2, 3, 2, 1, 0];
        let gif = encode_gif(4, 3, &PAL, &stored, None, true);
        let (_, _, rgba) = decode_gif(Path::new("t.gif"), &gif).unwrap();
        assert_eq!(rgba[4 * 4..4 * 4 + 3], [0, 0, 255]); // row 1 = stored row 2
    }

    #[test]
    fn truncated_gifs_are_errors_naming_the_file() {
        let px = [0u8, 1, 2, 3, 3, 2, 1, 0, 1, 1, 2, 2];
        let gif = encode_gif(4, 3, &PAL, &px, Some(0), false);
        // Cut before the image data ends (the decoder needs no trailer).
        for len in 0..gif.len() - 4 {
            let e = decode_gif(Path::new("cut.gif"), &gif[..len]).expect_err("truncated");
            assert_eq!(e.file, Path::new("cut.gif"));
            assert!(e.message.contains("GIF"), "{e}");
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]

        #[test]
        fn random_gifs_never_panic(mut bytes in proptest::collection::vec(any::<u8>(), 0..400)) {
            if bytes.len() > 13 && bytes[0] % 2 == 0 {
                bytes[..6].copy_from_slice(b"GIF89a");
                bytes[6..10].copy_from_slice(&[8, 0, 8, 0]);
            }
            if let Ok((w, h, rgba)) = decode_gif(Path::new("r.gif"), &bytes) {
                prop_assert_eq!(rgba.len(), (w * h * 4) as usize);
            }
        }

        #[test]
        fn corrupted_gifs_never_panic(pos in 0usize..200, val in any::<u8>()) {
            let px = [0u8, 1, 2, 3, 3, 2, 1, 0, 1, 1, 2, 2];
            let mut gif = encode_gif(4, 3, &PAL, &px, Some(0), false);
            let n = gif.len();
            gif[pos % n] = val;
            if let Ok((w, h, rgba)) = decode_gif(Path::new("c.gif"), &gif) {
                prop_assert_eq!(rgba.len(), (w * h * 4) as usize);
            }
        }
    }
}
