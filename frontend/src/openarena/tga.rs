//! TGA textures (uncompressed or RLE, BGR or BGRA).

use super::*;

/// What the 18-byte header says: the size, bytes per pixel, whether the
/// data is run-length packed and whether the top row comes first, and
/// where the pixels start.
struct TgaHeader {
    width: usize,
    height: usize,
    /// Bytes per pixel: 1 (grey), 3 (BGR) or 4 (BGRA).
    px: usize,
    rle: bool,
    top_first: bool,
    /// File offset of the pixel data (after the id and colour map).
    data_at: usize,
}

/// Read and check the header (types 2, 3, 10, 11 at their depths).
fn read_header(r: &Bytes) -> Result<TgaHeader, SceneError> {
    let h = r.slice(0, 18, "TGA header")?;
    let id_len = h[0] as usize;
    let cmap_type = h[1];
    let kind = h[2];
    let cmap_len = u16::from_le_bytes([h[5], h[6]]) as usize;
    let cmap_bits = h[7] as usize;
    let width = u16::from_le_bytes([h[12], h[13]]) as usize;
    let height = u16::from_le_bytes([h[14], h[15]]) as usize;
    let bpp = h[16] as usize;
    let top_first = h[17] & 0x20 != 0;
    let (grey, rle) = match kind {
        2 => (false, false),
        3 => (true, false),
        10 => (false, true),
        11 => (true, true),
        _ => {
            return Err(r.err(
                2,
                format!("TGA image type {kind} (only 2, 3, 10, 11 are supported)"),
            ))
        }
    };
    let ok_depth = if grey {
        bpp == 8
    } else {
        bpp == 24 || bpp == 32
    };
    if !ok_depth {
        return Err(r.err(16, format!("TGA depth {bpp} bits for image type {kind}")));
    }
    if width == 0 || height == 0 {
        return Err(r.err(12, format!("TGA size {width}x{height}")));
    }
    let mut data_at = 18 + id_len;
    if cmap_type == 1 {
        data_at += cmap_len * cmap_bits.div_ceil(8);
    }
    Ok(TgaHeader {
        width,
        height,
        px: bpp / 8,
        rle,
        top_first,
        data_at,
    })
}

/// One pixel (grey, BGR or BGRA) as RGBA.
fn to_rgba(p: &[u8]) -> [u8; 4] {
    match p.len() {
        1 => [p[0], p[0], p[0], 255],
        3 => [p[2], p[1], p[0], 255],
        _ => [p[2], p[1], p[0], p[3]],
    }
}

/// The `n` pixels of run-length packed data from `pos`: packets of a
/// header byte (count - 1, top bit set for a run of one pixel) and the
/// pixels.
fn unpack_rle(r: &Bytes, mut pos: usize, px: usize, n: usize) -> Result<Vec<[u8; 4]>, SceneError> {
    let mut pixels: Vec<[u8; 4]> = Vec::with_capacity(n);
    while pixels.len() < n {
        let hdr = r.slice(pos, 1, "RLE packet")?[0];
        pos += 1;
        let count = (hdr & 0x7f) as usize + 1;
        if pixels.len() + count > n {
            return Err(r.err(pos - 1, "RLE packet runs past the image"));
        }
        if hdr & 0x80 != 0 {
            let p = to_rgba(r.slice(pos, px, "RLE pixel")?);
            pos += px;
            pixels.extend(std::iter::repeat_n(p, count));
        } else {
            let raw = r.slice(pos, px * count, "RLE raw pixels")?;
            pos += px * count;
            pixels.extend(raw.chunks_exact(px).map(to_rgba));
        }
    }
    Ok(pixels)
}

/// Decode a TGA image (types 2, 3, 10, 11: true-colour 24/32 bit or grey
/// 8 bit, uncompressed or RLE) to RGBA8, top row first.
pub fn decode_tga(bytes: &[u8], file: &Path) -> Result<(u32, u32, Vec<u8>), SceneError> {
    let r = Bytes::new(bytes, file);
    let h = read_header(&r)?;
    let (width, height, px, pos) = (h.width, h.height, h.px, h.data_at);
    let n = width * height;
    // Even RLE needs at least one byte per 128 pixels: bound allocations.
    let min_bytes = if h.rle {
        n.div_ceil(128) * (1 + px)
    } else {
        n * px
    };
    if bytes.len().saturating_sub(pos) < min_bytes {
        return Err(r.err(
            pos.min(bytes.len()),
            format!("truncated TGA: {width}x{height} pixels need more data"),
        ));
    }
    let pixels = if h.rle {
        unpack_rle(&r, pos, px, n)?
    } else {
        let raw = r.slice(pos, n * px, "pixels")?;
        raw.chunks_exact(px).map(to_rgba).collect()
    };
    let mut rgba = Vec::with_capacity(n * 4);
    for y in 0..height {
        let src = if h.top_first { y } else { height - 1 - y };
        for p in &pixels[src * width..(src + 1) * width] {
            rgba.extend_from_slice(p);
        }
    }
    Ok((width as u32, height as u32, rgba))
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
        v[2] = 1;
        assert_eq!(
            decode_tga(&v, Path::new("t.tga")).unwrap_err().offset,
            Some(2)
        );
        let mut v = tiny_tga(true, false);
        v[20] = 0x86; // 7 pixels: run past the end
        assert!(decode_tga(&v, Path::new("t.tga"))
            .unwrap_err()
            .message
            .contains("past"));
    }
}
