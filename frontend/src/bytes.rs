//! Little-endian reading of the games' binary files (SuperTuxKart's SPM
//! meshes, OpenArena's BSP maps, Frozen Bubble's GIF sprites), written
//! once: every read names what it reads, and a short file is an error that
//! names the file, the offset and how many bytes were needed and left.

use super::SceneError;
use std::path::Path;

/// A cursor over a file's bytes. Sequential reads ([`Bytes::u16`] and the
/// like) advance it; [`Bytes::i32_at`] and [`Bytes::f32_at`] read at an
/// offset without moving it.
#[derive(Clone, Debug)]
pub struct Bytes<'a> {
    bytes: &'a [u8],
    pos: usize,
    file: &'a Path,
}

impl<'a> Bytes<'a> {
    /// A cursor at the start of `bytes`, the contents of `file`.
    pub fn new(bytes: &'a [u8], file: &'a Path) -> Self {
        Bytes {
            bytes,
            pos: 0,
            file,
        }
    }

    /// An error at offset `at` of the file.
    pub fn err(&self, at: usize, msg: impl Into<String>) -> SceneError {
        SceneError::at(self.file, at as u64, msg)
    }

    /// The cursor's offset.
    pub fn pos(&self) -> usize {
        self.pos
    }

    /// Bytes after the cursor.
    pub fn remaining(&self) -> usize {
        self.bytes.len() - self.pos
    }

    /// The `n` bytes at `at`, without moving the cursor.
    pub fn slice(&self, at: usize, n: usize, what: &str) -> Result<&'a [u8], SceneError> {
        match at.checked_add(n) {
            Some(end) if end <= self.bytes.len() => Ok(&self.bytes[at..end]),
            _ => Err(self.err(
                at,
                format!(
                    "truncated: {what} needs {n} bytes, {} left",
                    self.bytes.len().saturating_sub(at)
                ),
            )),
        }
    }

    /// The next `n` bytes.
    pub fn take(&mut self, n: usize, what: &str) -> Result<&'a [u8], SceneError> {
        let s = self.slice(self.pos, n, what)?;
        self.pos += n;
        Ok(s)
    }

    /// The next byte.
    pub fn u8(&mut self, what: &str) -> Result<u8, SceneError> {
        Ok(self.take(1, what)?[0])
    }

    /// The next little-endian `u16`.
    pub fn u16(&mut self, what: &str) -> Result<u16, SceneError> {
        let b = self.take(2, what)?;
        Ok(u16::from_le_bytes([b[0], b[1]]))
    }

    /// The next little-endian `u32`.
    pub fn u32(&mut self, what: &str) -> Result<u32, SceneError> {
        let b = self.take(4, what)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }

    /// The next little-endian `f32`, whatever its value.
    pub fn f32(&mut self, what: &str) -> Result<f32, SceneError> {
        Ok(f32::from_bits(self.u32(what)?))
    }

    /// The next little-endian `f32`, which must be finite.
    pub fn finite_f32(&mut self, what: &str) -> Result<f32, SceneError> {
        let at = self.pos;
        let v = self.f32(what)?;
        self.finite(at, v, what)
    }

    /// The little-endian `i32` at `at`.
    pub fn i32_at(&self, at: usize, what: &str) -> Result<i32, SceneError> {
        let b = self.slice(at, 4, what)?;
        Ok(i32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }

    /// The little-endian `f32` at `at`, which must be finite.
    pub fn f32_at(&self, at: usize, what: &str) -> Result<f32, SceneError> {
        let v = f32::from_bits(self.i32_at(at, what)? as u32);
        self.finite(at, v, what)
    }

    /// `v`, read at `at`, if finite.
    pub fn finite(&self, at: usize, v: f32, what: &str) -> Result<f32, SceneError> {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.err(at, format!("{what} is not finite ({v})")))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_little_endian_and_names_short_files() {
        let data = [1u8, 2, 3, 4, 5, 6, 0, 0, 0, 0x80, 0x7f, 9];
        let file = Path::new("x.bin");
        let mut b = Bytes::new(&data, file);
        assert_eq!(b.u8("a").unwrap(), 1);
        assert_eq!(b.u16("b").unwrap(), 0x0302);
        assert_eq!(b.pos(), 3);
        assert_eq!(b.u32("c").unwrap(), 0x0006_0504);
        assert_eq!(b.i32_at(0, "d").unwrap(), 0x0403_0201);
        // Bytes 7..11 are +infinity.
        let e = b.finite_f32("inf").unwrap_err();
        assert_eq!(e.offset, Some(7));
        assert!(e.message.contains("inf is not finite"), "{e}");
        assert_eq!(b.remaining(), 1);
        let e = b.u32("tail").unwrap_err();
        assert_eq!(
            e.to_string(),
            "x.bin at offset 11: truncated: tail needs 4 bytes, 1 left"
        );
        let e = b.i32_at(usize::MAX, "far").unwrap_err();
        assert!(e.message.contains("needs 4 bytes, 0 left"), "{e}");
        let mut b = Bytes::new(&data, file);
        assert_eq!(b.take(3, "t").unwrap(), &[1, 2, 3]);
        assert_eq!(b.f32_at(7, "f").unwrap_err().offset, Some(7));
        assert_eq!(b.f32_at(5, "g").unwrap(), f32::from_bits(0x0000_0006));
    }
}
