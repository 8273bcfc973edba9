//! The file container around a capture's byte stream: apitrace's own Snappy
//! framing (the bytes `a` `t`, then chunks, each a 32-bit little-endian
//! length and a raw Snappy block) or, for older captures, gzip. The
//! container hands out the decompressed stream one block at a time, so a
//! capture is never held in memory whole.

use crate::error::Fault;
use flate2::read::MultiGzDecoder;
use std::fs::File;
use std::io::{BufReader, Read};
use std::path::Path;

/// The two bytes that open apitrace's Snappy container.
pub(crate) const SNAPPY_MAGIC: [u8; 2] = *b"at";
/// The two bytes that open a gzip stream.
const GZIP_MAGIC: [u8; 2] = [0x1f, 0x8b];
/// The four bytes that open a Zstandard frame (little-endian 0xFD2FB528).
const ZSTD_MAGIC: [u8; 4] = [0x28, 0xb5, 0x2f, 0xfd];
/// How many decompressed bytes a gzip capture yields per block.
const GZIP_BLOCK: usize = 1 << 20;
/// A Snappy block expands at most about 21 times (a 3-byte copy writes at
/// most 64 bytes); a chunk claiming more is corrupt, and is refused before
/// anything is allocated for it.
const SNAPPY_MAX_RATIO: u64 = 32;

/// How the decompressed stream is stored in the file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Compression {
    /// apitrace's Snappy framing (what apitrace writes by default).
    Snappy,
    /// gzip (older captures; `apitrace repack -z`).
    Gzip,
}

/// What a container reads its bytes from: a file or memory.
type Source = Box<dyn Read + Send>;

/// A source of decompressed blocks.
pub(crate) enum Container {
    Snappy(SnappyChunks),
    Gzip(Box<MultiGzDecoder<BufReader<Source>>>),
}

/// The reader of apitrace's Snappy framing.
pub(crate) struct SnappyChunks {
    file: BufReader<Source>,
    /// Offset in the file of the next chunk's length.
    file_offset: u64,
    file_len: u64,
    compressed: Vec<u8>,
    decoder: snap::raw::Decoder,
}

/// Opens `path` and recognizes its container by its first bytes. The error
/// is a plain message; the caller names the file.
pub(crate) fn open(path: &Path) -> Result<(Container, Compression), String> {
    let file = File::open(path).map_err(|e| format!("cannot open the capture: {e}"))?;
    let len = file
        .metadata()
        .map_err(|e| format!("cannot read the capture's size: {e}"))?
        .len();
    from_source(Box::new(file), len)
}

/// A container over a capture's bytes held in memory.
pub(crate) fn from_bytes(bytes: Vec<u8>) -> Result<(Container, Compression), String> {
    let len = bytes.len() as u64;
    from_source(Box::new(std::io::Cursor::new(bytes)), len)
}

/// Recognizes the container of the `len` bytes of `source` by its first
/// bytes.
fn from_source(mut source: Source, len: u64) -> Result<(Container, Compression), String> {
    let mut magic = [0u8; 4];
    let got = read_full(&mut source, &mut magic).map_err(|e| format!("cannot read: {e}"))?;
    let magic = &magic[..got];
    // The bytes after the magic, then the rest of the source.
    let rest = |skip: usize| -> BufReader<Source> {
        let head = std::io::Cursor::new(magic[skip..].to_vec());
        BufReader::with_capacity(1 << 16, Box::new(head.chain(source)))
    };
    if magic.starts_with(&SNAPPY_MAGIC) {
        let chunks = SnappyChunks {
            file: rest(2),
            file_offset: 2,
            file_len: len,
            compressed: Vec::new(),
            decoder: snap::raw::Decoder::new(),
        };
        return Ok((Container::Snappy(chunks), Compression::Snappy));
    }
    if magic.starts_with(&GZIP_MAGIC) {
        let gz = MultiGzDecoder::new(rest(0));
        return Ok((Container::Gzip(Box::new(gz)), Compression::Gzip));
    }
    if magic == ZSTD_MAGIC {
        return Err("a Zstandard-compressed capture is not supported; \
                    `apitrace repack -s IN OUT` rewrites it with Snappy"
            .into());
    }
    Err(format!(
        "not an apitrace capture: it opens with {} where apitrace's Snappy container \
         opens with the bytes 'a' 't' (and gzip with 1f 8b); a Brotli-compressed capture \
         (which has no magic bytes) is not supported either: `apitrace repack -s IN OUT` \
         rewrites one with Snappy",
        hex(magic)
    ))
}

impl Container {
    /// Replaces `out` with the next block of the decompressed stream.
    /// Returns false at the end of the stream. `offset` is the decompressed
    /// offset reached, for errors.
    pub(crate) fn next_block(&mut self, out: &mut Vec<u8>, offset: u64) -> Result<bool, Fault> {
        match self {
            Container::Snappy(s) => s.next_chunk(out, offset),
            Container::Gzip(gz) => {
                out.resize(GZIP_BLOCK, 0);
                let got = read_full(gz.as_mut(), out).map_err(|e| {
                    Fault::corrupt(offset, format!("truncated or corrupt gzip stream: {e}"))
                })?;
                out.truncate(got);
                Ok(got > 0)
            }
        }
    }
}

impl SnappyChunks {
    fn next_chunk(&mut self, out: &mut Vec<u8>, offset: u64) -> Result<bool, Fault> {
        let at = self.file_offset;
        let mut len = [0u8; 4];
        let got = read_full(&mut self.file, &mut len).map_err(|e| io_fault(offset, at, e))?;
        if got == 0 {
            return Ok(false);
        }
        if got < 4 {
            return Err(Fault::corrupt(
                offset,
                format!(
                    "truncated capture: the chunk at file offset {at} has {got} of the 4 bytes \
                     of its length"
                ),
            ));
        }
        let len = u64::from(u32::from_le_bytes(len));
        let left = self.file_len.saturating_sub(at + 4);
        if len == 0 || len > left {
            let what = if len == 0 {
                "a length of 0 (apitrace never writes an empty chunk)".to_string()
            } else {
                format!("{len} compressed bytes, and the file has {left} after its length")
            };
            let lead = if len == 0 { "corrupt" } else { "truncated" };
            return Err(Fault::corrupt(
                offset,
                format!("{lead} capture: the chunk at file offset {at} declares {what}"),
            ));
        }
        self.compressed.resize(len as usize, 0);
        let got =
            read_full(&mut self.file, &mut self.compressed).map_err(|e| io_fault(offset, at, e))?;
        if got < self.compressed.len() {
            return Err(Fault::corrupt(
                offset,
                format!("truncated capture: the chunk at file offset {at} ends after {got} of its {len} bytes"),
            ));
        }
        self.file_offset = at + 4 + len;
        let bad = |e: String| {
            Fault::corrupt(
                offset,
                format!("corrupt Snappy chunk at file offset {at}: {e}"),
            )
        };
        let size = snap::raw::decompress_len(&self.compressed).map_err(|e| bad(e.to_string()))?;
        if size as u64 > len * SNAPPY_MAX_RATIO + 64 {
            return Err(bad(format!(
                "{size} bytes claimed from {len} compressed bytes"
            )));
        }
        out.resize(size, 0);
        let wrote = self
            .decoder
            .decompress(&self.compressed, out)
            .map_err(|e| bad(e.to_string()))?;
        out.truncate(wrote);
        Ok(true)
    }
}

fn io_fault(offset: u64, at: u64, e: std::io::Error) -> Fault {
    Fault::corrupt(
        offset,
        format!("cannot read the chunk at file offset {at}: {e}"),
    )
}

/// Reads until `buf` is full or the reader ends; returns the bytes read.
fn read_full(r: &mut impl Read, buf: &mut [u8]) -> std::io::Result<usize> {
    let mut got = 0;
    while got < buf.len() {
        match r.read(&mut buf[got..]) {
            Ok(0) => break,
            Ok(n) => got += n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e),
        }
    }
    Ok(got)
}

fn hex(bytes: &[u8]) -> String {
    if bytes.is_empty() {
        return "no bytes (the file is empty)".into();
    }
    let h: Vec<String> = bytes.iter().map(|b| format!("{b:02x}")).collect();
    format!("the bytes {}", h.join(" "))
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use std::io::Write;

    fn temp(name: &str, bytes: &[u8]) -> std::path::PathBuf {
        let dir =
            std::env::temp_dir().join(format!("wasp-gltrace-container-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join(name);
        std::fs::File::create(&p).unwrap().write_all(bytes).unwrap();
        p
    }

    fn drain(c: &mut Container) -> Result<Vec<u8>, Fault> {
        let (mut all, mut block) = (Vec::new(), Vec::new());
        while c.next_block(&mut block, all.len() as u64)? {
            all.extend_from_slice(&block);
        }
        Ok(all)
    }

    /// A capture file of `blocks`, one Snappy chunk each.
    pub(crate) fn snappy_file(blocks: &[&[u8]]) -> Vec<u8> {
        let mut f = SNAPPY_MAGIC.to_vec();
        for b in blocks {
            let c = snap::raw::Encoder::new().compress_vec(b).unwrap();
            f.extend_from_slice(&(c.len() as u32).to_le_bytes());
            f.extend_from_slice(&c);
        }
        f
    }

    #[test]
    fn snappy_chunks_and_gzip_give_the_same_stream() {
        let data: Vec<u8> = (0..5000u32).map(|i| (i * 7 % 251) as u8).collect();
        let p = temp("two.trace", &snappy_file(&[&data[..3000], &data[3000..]]));
        let (mut c, kind) = open(&p).unwrap();
        assert_eq!(kind, Compression::Snappy);
        assert_eq!(drain(&mut c).unwrap(), data);

        let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
        gz.write_all(&data).unwrap();
        let p = temp("two.gz", &gz.finish().unwrap());
        let (mut c, kind) = open(&p).unwrap();
        assert_eq!(kind, Compression::Gzip);
        assert_eq!(drain(&mut c).unwrap(), data);
    }

    #[test]
    fn cut_chunks_and_foreign_files_are_refused_with_the_offset() {
        let whole = snappy_file(&[b"hello, hello, hello", b"world"]);
        // Cut inside the second chunk's length, then inside its data.
        let first = 2 + 4 + (u32::from_le_bytes(whole[2..6].try_into().unwrap()) as usize);
        let p = temp("cut1.trace", &whole[..first + 2]);
        let e = drain(&mut open(&p).unwrap().0).unwrap_err();
        assert!(format!("{e:?}").contains(&format!("chunk at file offset {first} has 2 of the 4")));
        let p = temp("cut2.trace", &whole[..whole.len() - 1]);
        let e = drain(&mut open(&p).unwrap().0).unwrap_err();
        assert!(format!("{e:?}").contains("truncated capture"), "{e:?}");

        let p = temp("text.trace", b"GIF89a");
        let e = open(&p).err().unwrap();
        assert!(
            e.contains("not an apitrace capture") && e.contains("47 49 46 38"),
            "{e}"
        );
        let p = temp("zstd.trace", &[0x28, 0xb5, 0x2f, 0xfd, 0]);
        assert!(open(&p).err().unwrap().contains("Zstandard"));
        let p = temp("empty.trace", b"");
        assert!(open(&p).err().unwrap().contains("empty"));
    }

    #[test]
    fn a_chunk_claiming_an_impossible_size_is_refused_before_allocating() {
        // Snappy's header: a varint of 2^32-1 decompressed bytes, then junk.
        let mut f = SNAPPY_MAGIC.to_vec();
        let block = [0xff, 0xff, 0xff, 0xff, 0x0f, 0, 0];
        f.extend_from_slice(&(block.len() as u32).to_le_bytes());
        f.extend_from_slice(&block);
        let p = temp("huge.trace", &f);
        let e = drain(&mut open(&p).unwrap().0).unwrap_err();
        assert!(
            format!("{e:?}").contains("corrupt Snappy chunk at file offset 2"),
            "{e:?}"
        );
    }
}
