//! The decompressed byte stream and the format's basic types read from it:
//! bytes, variable-length unsigned integers, floats, doubles, strings and
//! blobs. It holds one decompressed block at a time and tracks the offset
//! in the whole decompressed stream for errors.

use crate::container::Container;
use crate::error::{Fault, FaultKind};

/// The decompressed stream, read block by block from its container.
pub(crate) struct Stream {
    container: Container,
    buf: Vec<u8>,
    pos: usize,
    /// The decompressed offset of `buf[0]`.
    base: u64,
    ended: bool,
}

impl Stream {
    pub(crate) fn new(container: Container) -> Stream {
        Stream {
            container,
            buf: Vec::new(),
            pos: 0,
            base: 0,
            ended: false,
        }
    }

    /// The offset of the next byte in the decompressed stream.
    #[inline]
    pub(crate) fn offset(&self) -> u64 {
        self.base + self.pos as u64
    }

    /// Loads blocks until one has a byte left; false at the end.
    #[cold]
    fn fill(&mut self) -> Result<bool, Fault> {
        while self.pos >= self.buf.len() {
            if self.ended {
                return Ok(false);
            }
            let offset = self.offset();
            self.base = offset;
            self.pos = 0;
            self.buf.clear();
            if !self.container.next_block(&mut self.buf, offset)? {
                self.ended = true;
                return Ok(false);
            }
        }
        Ok(true)
    }

    fn truncated(&self) -> Fault {
        Fault {
            offset: self.offset(),
            kind: FaultKind::Truncated,
        }
    }

    /// Whether the stream has ended (at an item boundary this is a clean
    /// end).
    pub(crate) fn at_end(&mut self) -> Result<bool, Fault> {
        Ok(self.pos >= self.buf.len() && !self.fill()?)
    }

    /// One byte.
    #[inline]
    pub(crate) fn byte(&mut self) -> Result<u8, Fault> {
        if self.pos >= self.buf.len() && !self.fill()? {
            return Err(self.truncated());
        }
        let b = self.buf[self.pos];
        self.pos += 1;
        Ok(b)
    }

    /// A variable-length unsigned integer: 7 bits per byte, least
    /// significant first, the top bit set on every byte but the last.
    #[inline]
    pub(crate) fn uint(&mut self) -> Result<u64, Fault> {
        // Fast path: a one-byte integer (most counts, ids and indices).
        if let Some(&b) = self.buf.get(self.pos) {
            if b & 0x80 == 0 {
                self.pos += 1;
                return Ok(u64::from(b));
            }
        }
        let start = self.offset();
        let mut value = 0u64;
        let mut shift = 0u32;
        loop {
            let b = self.byte()?;
            let bits = u64::from(b & 0x7f);
            if shift >= 64 || (shift == 63 && bits > 1) {
                return Err(Fault::corrupt(
                    start,
                    format!("an integer at decompressed offset {start} does not fit 64 bits"),
                ));
            }
            value |= bits << shift;
            if b & 0x80 == 0 {
                return Ok(value);
            }
            shift += 7;
        }
    }

    /// `N` raw bytes.
    fn array<const N: usize>(&mut self) -> Result<[u8; N], Fault> {
        let mut out = [0u8; N];
        if let Some(s) = self.buf.get(self.pos..self.pos + N) {
            out.copy_from_slice(s);
            self.pos += N;
            return Ok(out);
        }
        for b in out.iter_mut() {
            *b = self.byte()?;
        }
        Ok(out)
    }

    /// A 32-bit float (little-endian, as apitrace writes it on the
    /// machines it runs on).
    pub(crate) fn f32(&mut self) -> Result<f32, Fault> {
        Ok(f32::from_le_bytes(self.array()?))
    }

    /// A 64-bit float.
    pub(crate) fn f64(&mut self) -> Result<f64, Fault> {
        Ok(f64::from_le_bytes(self.array()?))
    }

    /// `n` bytes appended to `out`. Nothing is reserved beyond what the
    /// stream delivers, so a corrupt length cannot exhaust memory.
    pub(crate) fn bytes_into(&mut self, n: u64, out: &mut Vec<u8>) -> Result<(), Fault> {
        let mut left = n;
        out.reserve(n.min(1 << 20) as usize);
        while left > 0 {
            if self.pos >= self.buf.len() && !self.fill()? {
                return Err(self.truncated());
            }
            let take = (self.buf.len() - self.pos).min(usize::try_from(left).unwrap_or(usize::MAX));
            out.extend_from_slice(&self.buf[self.pos..self.pos + take]);
            self.pos += take;
            left -= take as u64;
        }
        Ok(())
    }

    /// A length-prefixed blob.
    pub(crate) fn blob(&mut self) -> Result<Vec<u8>, Fault> {
        let n = self.uint()?;
        let mut out = Vec::new();
        self.bytes_into(n, &mut out)?;
        Ok(out)
    }

    /// A length-prefixed string. Bytes that are not UTF-8 read as U+FFFD
    /// (the format does not say which encoding a string has).
    pub(crate) fn string(&mut self) -> Result<String, Fault> {
        let n = self.uint()?;
        if let Some(s) = self.buf.get(self.pos..).and_then(|b| b.get(..n as usize)) {
            let text = String::from_utf8_lossy(s).into_owned();
            self.pos += n as usize;
            return Ok(text);
        }
        let mut out = Vec::new();
        self.bytes_into(n, &mut out)?;
        Ok(match String::from_utf8(out) {
            Ok(s) => s,
            Err(e) => String::from_utf8_lossy(e.as_bytes()).into_owned(),
        })
    }

    /// Skips a length-prefixed string.
    pub(crate) fn skip_string(&mut self) -> Result<(), Fault> {
        let mut left = self.uint()?;
        while left > 0 {
            if self.pos >= self.buf.len() && !self.fill()? {
                return Err(self.truncated());
            }
            let take = (self.buf.len() - self.pos).min(usize::try_from(left).unwrap_or(usize::MAX));
            self.pos += take;
            left -= take as u64;
        }
        Ok(())
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A stream over `blocks` (each one Snappy chunk).
    pub(crate) fn stream_of(blocks: &[&[u8]]) -> Stream {
        let file = crate::container::tests::snappy_file(blocks);
        Stream::new(crate::container::from_bytes(file).unwrap().0)
    }

    #[test]
    fn integers_strings_and_floats_read_across_block_boundaries() {
        // 300 = 0b10_0101100 -> ac 02; "hi"; 1.5f32; a 64-bit maximum.
        let mut all = vec![0xac, 0x02, 0x02, b'h', b'i'];
        all.extend_from_slice(&1.5f32.to_le_bytes());
        all.extend_from_slice(&[0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0xff, 0x01]);
        all.extend_from_slice(&[0x03, 1, 2, 3]);
        for cut in 1..all.len() {
            let mut s = stream_of(&[&all[..cut], &all[cut..]]);
            assert_eq!(s.uint().unwrap(), 300);
            assert_eq!(s.string().unwrap(), "hi");
            assert_eq!(s.f32().unwrap(), 1.5);
            assert_eq!(s.uint().unwrap(), u64::MAX);
            assert_eq!(s.blob().unwrap(), vec![1, 2, 3]);
            assert_eq!(s.offset(), all.len() as u64);
            assert!(s.at_end().unwrap());
            assert_eq!(s.byte().unwrap_err().kind, FaultKind::Truncated);
        }
    }

    #[test]
    fn oversized_integers_and_lengths_past_the_end_are_faults() {
        let mut s = stream_of(&[&[0xff; 10], &[0x7f]]);
        let e = s.uint().unwrap_err();
        assert!(matches!(e.kind, FaultKind::Corrupt(ref m) if m.contains("64 bits")));
        // A blob claiming 2^40 bytes with 3 present: truncated, at offset 9.
        let mut s = stream_of(&[&[0x80, 0x80, 0x80, 0x80, 0x80, 0x20, 7, 8, 9]]);
        let e = s.blob().unwrap_err();
        assert_eq!((e.kind, e.offset), (FaultKind::Truncated, 9));
    }
}
