//! GIF images (87a/89a): the first image of a file LZW-decoded into an
//! RGBA texture, its transparent colour transparent.

use super::*;

/// Largest GIF canvas accepted (pixels).
const MAX_GIF_PIXELS: usize = 4096 * 4096;

/// GIF data sub-blocks up to the terminator, concatenated.
fn sub_blocks(r: &mut Bytes, what: &str) -> Result<Vec<u8>, SceneError> {
    let mut out = Vec::new();
    loop {
        let n = r.u8(what)? as usize;
        if n == 0 {
            return Ok(out);
        }
        out.extend_from_slice(r.take(n, what)?);
    }
}

/// LZW-decode GIF image data to at most `limit` colour indices.
fn lzw_decode(data: &[u8], min_size: u8, limit: usize) -> Result<Vec<u8>, String> {
    let clear = 1u16 << min_size;
    let end = clear + 1;
    let mut prefix = vec![0u16; 4096];
    let mut suffix = vec![0u8; 4096];
    let mut first = vec![0u8; 4096];
    for c in 0..clear {
        suffix[c as usize] = c as u8;
        first[c as usize] = c as u8;
    }
    let mut size = min_size as u32 + 1;
    let mut next = clear + 2;
    let mut prev: Option<u16> = None;
    let mut out = Vec::with_capacity(limit.min(1 << 20));
    let mut stack = Vec::with_capacity(4096);
    let (mut acc, mut bits, mut byte) = (0u32, 0u32, 0usize);
    loop {
        while bits < size {
            let Some(&b) = data.get(byte) else {
                return Err(format!(
                    "image data ends (no end code) after {} of {limit} pixels",
                    out.len()
                ));
            };
            acc |= (b as u32) << bits;
            bits += 8;
            byte += 1;
        }
        let code = (acc & ((1 << size) - 1)) as u16;
        acc >>= size;
        bits -= size;
        if code == clear {
            size = min_size as u32 + 1;
            next = clear + 2;
            prev = None;
            continue;
        }
        if code == end {
            return Ok(out);
        }
        let Some(p) = prev else {
            if code >= clear {
                return Err(format!(
                    "LZW code {code} after a clear code (literals < {clear})"
                ));
            }
            out.push(code as u8);
            prev = Some(code);
            if out.len() >= limit {
                return Ok(out);
            }
            continue;
        };
        // The string for `code` (or, for the code being defined, prev's
        // string plus its first byte).
        let (walk, extra) = if code < next {
            (code, None)
        } else if code == next && next < 4096 {
            (p, Some(first[p as usize]))
        } else {
            return Err(format!("LZW code {code} is not defined yet (next {next})"));
        };
        stack.clear();
        let mut c = walk;
        while c >= clear {
            stack.push(suffix[c as usize]);
            c = prefix[c as usize];
        }
        stack.push(c as u8);
        let head = c as u8;
        out.extend(stack.iter().rev());
        if let Some(x) = extra {
            out.push(x);
        }
        if next < 4096 {
            prefix[next as usize] = p;
            suffix[next as usize] = head;
            first[next as usize] = first[p as usize];
            next += 1;
            if next == (1 << size) && size < 12 {
                size += 1;
            }
        }
        prev = Some(code);
        if out.len() >= limit {
            out.truncate(limit);
            return Ok(out);
        }
    }
}

/// Decode the first image of a GIF (87a/89a) into an RGBA texture of the
/// logical screen size; the transparent colour (graphic control extension)
/// and pixels outside the frame are transparent black. Errors name the
/// file and the byte offset.
pub fn decode_gif(path: &Path, bytes: &[u8]) -> Result<(u32, u32, Vec<u8>), SceneError> {
    let mut r = Bytes::new(bytes, path);
    let sig = r.take(6, "GIF signature")?.to_vec();
    if sig != b"GIF87a" && sig != b"GIF89a" {
        return Err(r.err(0, format!("not a GIF: signature {sig:?}")));
    }
    let sw = r.u16("screen width")? as usize;
    let sh = r.u16("screen height")? as usize;
    if sw == 0 || sh == 0 || sw * sh > MAX_GIF_PIXELS {
        return Err(r.err(
            6,
            format!("GIF screen {sw}x{sh}: expected 1..{MAX_GIF_PIXELS} pixels"),
        ));
    }
    let flags = r.u8("screen flags")?;
    r.take(2, "background and aspect")?;
    let global = if flags & 0x80 != 0 {
        let n = 2usize << (flags & 7);
        Some(r.take(3 * n, "global colour table")?.to_vec())
    } else {
        None
    };
    let mut transparent: Option<u8> = None;
    loop {
        let at = r.pos();
        match r.u8("block introducer")? {
            0x21 => {
                let label = r.u8("extension label")?;
                let body = sub_blocks(&mut r, "extension")?;
                if label == 0xf9 {
                    if body.len() < 4 {
                        return Err(r.err(at, "graphic control extension shorter than 4 bytes"));
                    }
                    transparent = (body[0] & 1 != 0).then_some(body[3]);
                }
            }
            0x2c => {
                let left = r.u16("image left")? as usize;
                let top = r.u16("image top")? as usize;
                let w = r.u16("image width")? as usize;
                let h = r.u16("image height")? as usize;
                let iflags = r.u8("image flags")?;
                let local = if iflags & 0x80 != 0 {
                    let n = 2usize << (iflags & 7);
                    Some(r.take(3 * n, "local colour table")?.to_vec())
                } else {
                    None
                };
                let table = local
                    .or(global)
                    .ok_or_else(|| r.err(at, "image without a local or a global colour table"))?;
                let min_at = r.pos();
                let min_size = r.u8("LZW minimum code size")?;
                if !(1..=11).contains(&min_size) {
                    return Err(r.err(min_at, format!("LZW minimum code size {min_size}")));
                }
                let data_at = r.pos();
                let data = sub_blocks(&mut r, "image data")?;
                if w * h > MAX_GIF_PIXELS {
                    return Err(r.err(at, format!("GIF image {w}x{h} too large")));
                }
                let idx = lzw_decode(&data, min_size, w * h).map_err(|m| r.err(data_at, m))?;
                if idx.len() < w * h {
                    return Err(r.err(
                        data_at,
                        format!("image data holds {} of {}x{} pixels", idx.len(), w, h),
                    ));
                }
                // Interlaced rows come in 4 passes.
                let rows: Vec<usize> = if iflags & 0x40 != 0 {
                    (0..h)
                        .step_by(8)
                        .chain((4..h).step_by(8))
                        .chain((2..h).step_by(4))
                        .chain((1..h).step_by(2))
                        .collect()
                } else {
                    (0..h).collect()
                };
                let colours = table.len() / 3;
                let mut rgba = vec![0u8; sw * sh * 4];
                for (k, &y) in rows.iter().enumerate() {
                    for x in 0..w {
                        let i = idx[k * w + x];
                        let (sx, sy) = (left + x, top + y);
                        if Some(i) == transparent || sx >= sw || sy >= sh {
                            continue;
                        }
                        if i as usize >= colours {
                            return Err(r.err(
                                data_at,
                                format!("colour index {i} outside the {colours}-colour table"),
                            ));
                        }
                        let c = &table[3 * i as usize..3 * i as usize + 3];
                        let o = 4 * (sy * sw + sx);
                        rgba[o..o + 4].copy_from_slice(&[c[0], c[1], c[2], 255]);
                    }
                }
                return Ok((sw as u32, sh as u32, rgba));
            }
            0x3b => return Err(r.err(at, "GIF ends (trailer) before any image")),
            b => {
                return Err(r.err(
                    at,
                    format!("unknown GIF block 0x{b:02x} (expected 0x21, 0x2c or 0x3b)"),
                ))
            }
        }
    }
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
    fn lzw_handles_growing_codes() {
        // Hand-coded stream (min size 2: clear 4, end 5, first free code 6):
        // clear, 1 -> "1"; 6 is the code being defined (prev "1" + its first
        // byte) -> "11"; 7 likewise -> "111", and defining 7 fills the 3-bit
        // codes, so the end code that follows is 4 bits wide.
        let codes: [(u32, u32); 5] = [(4, 3), (1, 3), (6, 3), (7, 3), (5, 4)];
        let pack = |codes: &[(u32, u32)]| {
            let (mut acc, mut bits) = (0u64, 0u32);
            for &(c, n) in codes {
                acc |= (c as u64) << bits;
                bits += n;
            }
            acc.to_le_bytes()[..bits.div_ceil(8) as usize].to_vec()
        };
        assert_eq!(lzw_decode(&pack(&codes), 2, 100).unwrap(), vec![1; 6]);
        // Existing codes: clear, 1, 2 (defines 6 = "12"), 6 -> "12"
        // (defines 7 = "21"), 7 -> "21" (4 bits from here), end.
        let codes = [(4, 3), (1, 3), (2, 3), (6, 3), (7, 4), (5, 4)];
        assert_eq!(
            lzw_decode(&pack(&codes), 2, 100).unwrap(),
            vec![1, 2, 1, 2, 2, 1]
        );
        // A code beyond the next free one is an error, not a panic.
        assert!(lzw_decode(&pack(&[(4, 3), (1, 3), (7, 3)]), 2, 100).is_err());
    }

    #[test]
    fn every_gif_truncation_is_an_error_with_an_offset() {
        let px = [0u8, 1, 2, 3, 3, 2, 1, 0, 1, 1, 2, 2];
        let gif = encode_gif(4, 3, &PAL, &px, Some(0), false);
        // The trailer is not needed once the image is decoded.
        for len in 0..gif.len() - 1 {
            let e = decode_gif(Path::new("cut.gif"), &gif[..len]).expect_err("truncated");
            assert_eq!(e.file, Path::new("cut.gif"));
            assert!(e.offset.is_some(), "{e}");
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
            if let Err(e) = decode_gif(Path::new("r.gif"), &bytes) {
                prop_assert!(e.offset.is_some());
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
