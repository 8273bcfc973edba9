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

/// The codes of GIF image data: `size`-bit codes packed least significant
/// bit first.
struct Codes<'a> {
    data: &'a [u8],
    /// Bits read but not yet consumed, the oldest lowest.
    acc: u32,
    bits: u32,
    /// Next byte of `data` to read.
    byte: usize,
}

impl Codes<'_> {
    /// The next `size`-bit code; `None` when the data ends first.
    fn next(&mut self, size: u32) -> Option<u16> {
        while self.bits < size {
            let &b = self.data.get(self.byte)?;
            self.acc |= (b as u32) << self.bits;
            self.bits += 8;
            self.byte += 1;
        }
        let code = (self.acc & ((1 << size) - 1)) as u16;
        self.acc >>= size;
        self.bits -= size;
        Some(code)
    }
}

/// The LZW string table: each code above the literals is a known code's
/// string (`prefix`) plus one byte (`suffix`); `first` is the string's
/// first byte.
struct StringTable {
    prefix: Vec<u16>,
    suffix: Vec<u8>,
    first: Vec<u8>,
    min_size: u8,
    /// The clear code (the literals are below it; the end code follows it).
    clear: u16,
    /// Current code size (bits).
    size: u32,
    /// The next code to define.
    next: u16,
}

impl StringTable {
    fn new(min_size: u8) -> Self {
        let clear = 1u16 << min_size;
        let prefix = vec![0u16; 4096];
        let mut suffix = vec![0u8; 4096];
        let mut first = vec![0u8; 4096];
        for c in 0..clear {
            suffix[c as usize] = c as u8;
            first[c as usize] = c as u8;
        }
        Self {
            prefix,
            suffix,
            first,
            min_size,
            clear,
            size: min_size as u32 + 1,
            next: clear + 2,
        }
    }

    /// Forget every defined code (a clear code).
    fn reset(&mut self) {
        self.size = self.min_size as u32 + 1;
        self.next = self.clear + 2;
    }

    /// Append the string of `code` to `out`, `p` being the previous code:
    /// a defined code's string, or for the code being defined, `p`'s string
    /// plus its first byte. Returns the first byte appended.
    fn expand(
        &self,
        code: u16,
        p: u16,
        stack: &mut Vec<u8>,
        out: &mut Vec<u8>,
    ) -> Result<u8, String> {
        let next = self.next;
        let (walk, extra) = if code < next {
            (code, None)
        } else if code == next && next < 4096 {
            (p, Some(self.first[p as usize]))
        } else {
            return Err(format!("LZW code {code} is not defined yet (next {next})"));
        };
        stack.clear();
        let mut c = walk;
        while c >= self.clear {
            stack.push(self.suffix[c as usize]);
            c = self.prefix[c as usize];
        }
        stack.push(c as u8);
        out.extend(stack.iter().rev());
        if let Some(x) = extra {
            out.push(x);
        }
        Ok(c as u8)
    }

    /// Define the next code as `p`'s string plus `head`, widening the codes
    /// when they fill their size (up to 12 bits; a full table stays full).
    fn define(&mut self, p: u16, head: u8) {
        let next = self.next;
        if next < 4096 {
            self.prefix[next as usize] = p;
            self.suffix[next as usize] = head;
            self.first[next as usize] = self.first[p as usize];
            self.next += 1;
            if self.next == (1 << self.size) && self.size < 12 {
                self.size += 1;
            }
        }
    }
}

/// LZW-decode GIF image data to at most `limit` colour indices.
fn lzw_decode(data: &[u8], min_size: u8, limit: usize) -> Result<Vec<u8>, String> {
    let mut table = StringTable::new(min_size);
    let clear = table.clear;
    let end = clear + 1;
    let mut codes = Codes {
        data,
        acc: 0,
        bits: 0,
        byte: 0,
    };
    let mut prev: Option<u16> = None;
    let mut out = Vec::with_capacity(limit.min(1 << 20));
    let mut stack = Vec::with_capacity(4096);
    loop {
        let Some(code) = codes.next(table.size) else {
            return Err(format!(
                "image data ends (no end code) after {} of {limit} pixels",
                out.len()
            ));
        };
        if code == clear {
            table.reset();
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
        let head = table.expand(code, p, &mut stack, &mut out)?;
        table.define(p, head);
        prev = Some(code);
        if out.len() >= limit {
            out.truncate(limit);
            return Ok(out);
        }
    }
}

/// The logical screen of a GIF: its size and global colour table.
struct Screen {
    width: usize,
    height: usize,
    global: Option<Vec<u8>>,
}

/// Read the signature and the logical screen descriptor (with the global
/// colour table, if any).
fn read_screen(r: &mut Bytes) -> Result<Screen, SceneError> {
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
    Ok(Screen {
        width: sw,
        height: sh,
        global,
    })
}

/// Decode the first image of a GIF (87a/89a) into an RGBA texture of the
/// logical screen size; the transparent colour (graphic control extension)
/// and pixels outside the frame are transparent black. Errors name the
/// file and the byte offset.
pub fn decode_gif(path: &Path, bytes: &[u8]) -> Result<(u32, u32, Vec<u8>), SceneError> {
    let mut r = Bytes::new(bytes, path);
    let screen = read_screen(&mut r)?;
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
                let rgba = decode_image(&mut r, at, &screen, transparent)?;
                return Ok((screen.width as u32, screen.height as u32, rgba));
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

/// Decode the image whose descriptor starts at `at` (after its
/// introducer) onto the transparent RGBA `screen`.
fn decode_image(
    r: &mut Bytes,
    at: usize,
    screen: &Screen,
    transparent: Option<u8>,
) -> Result<Vec<u8>, SceneError> {
    let (sw, sh) = (screen.width, screen.height);
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
    let table: &[u8] = match (&local, &screen.global) {
        (Some(t), _) | (None, Some(t)) => t,
        (None, None) => return Err(r.err(at, "image without a local or a global colour table")),
    };
    let min_at = r.pos();
    let min_size = r.u8("LZW minimum code size")?;
    if !(1..=11).contains(&min_size) {
        return Err(r.err(min_at, format!("LZW minimum code size {min_size}")));
    }
    let data_at = r.pos();
    let data = sub_blocks(r, "image data")?;
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
    Ok(rgba)
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
