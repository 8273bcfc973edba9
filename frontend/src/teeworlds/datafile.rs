//! Teeworlds' datafile container (version 4): the header, item types,
//! items and zlib-compressed data blocks a map is stored in.

use super::*;

/// One item of a datafile.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Item {
    /// Item type.
    pub type_id: u16,
    /// Item id (index within its type, as written).
    pub id: u16,
    /// File offset of the first `i32` of the payload.
    pub offset: u64,
    /// The payload.
    pub ints: Vec<i32>,
}

#[derive(Clone, Copy, Debug)]
pub(super) struct Block {
    /// File offset of the stored bytes.
    pub(super) offset: usize,
    /// Stored length.
    pub(super) len: usize,
    /// Uncompressed size (version 4).
    pub(super) size: Option<usize>,
    /// File offset of the `i32` declaring this block's size or offset.
    pub(super) field: u64,
}

/// A parsed Teeworlds datafile: items, and data blocks decompressed on
/// demand. Every offset and count is checked against the file.
#[derive(Debug)]
pub struct Datafile<'a> {
    pub(super) path: &'a Path,
    pub(super) bytes: &'a [u8],
    /// Format version (3 or 4).
    pub version: i32,
    /// Items, in file order.
    pub items: Vec<Item>,
    pub(super) blocks: Vec<Block>,
}

pub(super) fn read_i32(
    path: &Path,
    bytes: &[u8],
    off: usize,
    what: &str,
) -> Result<i32, SceneError> {
    match bytes.get(off..off.saturating_add(4)) {
        Some(b) if b.len() == 4 => Ok(i32::from_le_bytes([b[0], b[1], b[2], b[3]])),
        _ => Err(SceneError::at(
            path,
            bytes.len() as u64,
            format!(
                "truncated: {what} needs bytes {off}..{}, the file has {}",
                off.saturating_add(4),
                bytes.len()
            ),
        )),
    }
}

pub(super) fn non_negative(
    path: &Path,
    v: i32,
    off: usize,
    what: &str,
) -> Result<usize, SceneError> {
    usize::try_from(v).map_err(|_| SceneError::at(path, off as u64, format!("{what} is {v} (< 0)")))
}

/// The header's counts and the areas they place: the tables start at byte
/// 36, the item area follows them and the data area follows the items.
#[derive(Clone, Copy, Debug)]
struct Header {
    version: i32,
    num_types: usize,
    num_items: usize,
    num_data: usize,
    item_size: usize,
    data_size: usize,
    /// File offset of the item area.
    items_start: usize,
    /// File offset of the data area.
    data_start: usize,
}

/// Check the fixed part of the header: its length, the magic, the version
/// (returned) and the declared file size.
fn read_version(path: &Path, bytes: &[u8]) -> Result<i32, SceneError> {
    if bytes.len() < 36 {
        return Err(SceneError::at(
            path,
            bytes.len() as u64,
            format!(
                "truncated: a datafile header is 36 bytes, the file has {}",
                bytes.len()
            ),
        ));
    }
    match &bytes[0..4] {
        b"DATA" => {}
        b"ATAD" => {
            return Err(SceneError::at(
                path,
                0,
                "big-endian datafile (magic ATAD) is not supported",
            ))
        }
        m => {
            return Err(SceneError::at(
                path,
                0,
                format!("not a Teeworlds datafile: magic {m:?}, expected \"DATA\""),
            ))
        }
    }
    let version = read_i32(path, bytes, 4, "version")?;
    if version != 3 && version != 4 {
        return Err(SceneError::at(
            path,
            4,
            format!("datafile version {version}: only 3 and 4 are supported"),
        ));
    }
    let size = non_negative(path, read_i32(path, bytes, 8, "size")?, 8, "size")?;
    if size as u64 + 16 > bytes.len() as u64 {
        return Err(SceneError::at(
            path,
            bytes.len() as u64,
            format!(
                "truncated: the header says the file has {} bytes, it has {}",
                size as u64 + 16,
                bytes.len()
            ),
        ));
    }
    Ok(version)
}

impl Header {
    /// Read the header: [`read_version`], then the five counts; reject
    /// counts the file cannot hold before anything is allocated.
    fn parse(path: &Path, bytes: &[u8]) -> Result<Self, SceneError> {
        let version = read_version(path, bytes)?;
        let mut counts = [0usize; 5];
        let names = [
            "num_item_types",
            "num_items",
            "num_data",
            "item_size",
            "data_size",
        ];
        for (i, name) in names.iter().enumerate() {
            let off = 16 + 4 * i;
            counts[i] = non_negative(path, read_i32(path, bytes, off, name)?, off, name)?;
        }
        let [num_types, num_items, num_data, item_size, data_size] = counts;
        // Every table entry takes at least 4 bytes of the file: reject counts
        // the file cannot hold before allocating anything.
        let table = num_types
            .saturating_mul(12)
            .saturating_add(num_items.saturating_mul(4))
            .saturating_add(num_data.saturating_mul(if version == 4 { 8 } else { 4 }));
        let items_start = 36usize.saturating_add(table);
        let data_start = items_start.saturating_add(item_size);
        let end = data_start.saturating_add(data_size);
        if end > bytes.len() {
            return Err(SceneError::at(
                path,
                bytes.len() as u64,
                format!(
                    "truncated: header, tables ({num_types} item types, {num_items} items, \
                     {num_data} data blocks), {item_size} item bytes and {data_size} data bytes \
                     need {end} bytes, the file has {}",
                    bytes.len()
                ),
            ));
        }
        if item_size % 4 != 0 {
            return Err(SceneError::at(
                path,
                28,
                format!("item_size {item_size} is not a multiple of 4"),
            ));
        }
        Ok(Self {
            version,
            num_types,
            num_items,
            num_data,
            item_size,
            data_size,
            items_start,
            data_start,
        })
    }

    /// File offset of the item offset table (after the item types).
    fn item_offsets_at(&self) -> usize {
        36 + 12 * self.num_types
    }

    /// File offset of the data offset table (after the item offsets).
    fn data_offsets_at(&self) -> usize {
        self.item_offsets_at() + 4 * self.num_items
    }

    /// File offset of the (version 4) uncompressed size table.
    fn data_sizes_at(&self) -> usize {
        self.data_offsets_at() + 4 * self.num_data
    }
}

/// Check the item type table: every entry names a type id that fits 16 bits
/// and a range of items inside the item count. (The items carry their own
/// type, so the table is only checked.)
fn check_item_types(path: &Path, bytes: &[u8], h: &Header) -> Result<(), SceneError> {
    let mut off = 36;
    for _ in 0..h.num_types {
        let t = read_i32(path, bytes, off, "item type")?;
        let start = read_i32(path, bytes, off + 4, "item type start")?;
        let num = read_i32(path, bytes, off + 8, "item type count")?;
        if !(0..=0xffff).contains(&t)
            || start < 0
            || num < 0
            || start as usize + num as usize > h.num_items
        {
            return Err(SceneError::at(
                path,
                off as u64,
                format!(
                    "item type entry {{type {t}, start {start}, count {num}}} is out of \
                     range ({} items)",
                    h.num_items
                ),
            ));
        }
        off += 12;
    }
    Ok(())
}

/// Read item `i`, whose offset (relative to the item area) is the `i32` at
/// `field`: its type and id, size and payload, all inside the item area.
fn read_item(
    path: &Path,
    bytes: &[u8],
    h: &Header,
    i: usize,
    field: usize,
) -> Result<Item, SceneError> {
    let item_size = h.item_size;
    let rel = non_negative(
        path,
        read_i32(path, bytes, field, "item offset")?,
        field,
        "item offset",
    )?;
    if rel.saturating_add(8) > item_size {
        return Err(SceneError::at(
            path,
            field as u64,
            format!(
                "item {i} at {rel}: its 8-byte header is outside the {item_size}-byte item area"
            ),
        ));
    }
    let at = h.items_start + rel;
    let key = read_i32(path, bytes, at, "item type and id")?;
    let len = non_negative(
        path,
        read_i32(path, bytes, at + 4, "item size")?,
        at + 4,
        "item size",
    )?;
    if len % 4 != 0 || rel + 8 + len > item_size {
        return Err(SceneError::at(
            path,
            (at + 4) as u64,
            format!(
                "item {i}: size {len} is not a multiple of 4 or runs past the \
                 {item_size}-byte item area"
            ),
        ));
    }
    let ints = bytes[at + 8..at + 8 + len]
        .chunks_exact(4)
        .map(|b| i32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect();
    Ok(Item {
        type_id: ((key as u32) >> 16) as u16,
        id: (key as u32 & 0xffff) as u16,
        offset: (at + 8) as u64,
        ints,
    })
}

/// Read the data offset table: each block's start, relative to the data
/// area and inside it.
fn read_block_starts(path: &Path, bytes: &[u8], h: &Header) -> Result<Vec<usize>, SceneError> {
    let mut starts = Vec::with_capacity(h.num_data);
    for i in 0..h.num_data {
        let field = h.data_offsets_at() + 4 * i;
        let rel = non_negative(
            path,
            read_i32(path, bytes, field, "data offset")?,
            field,
            "data offset",
        )?;
        if rel > h.data_size {
            return Err(SceneError::at(
                path,
                field as u64,
                format!(
                    "data block {i} starts at {rel}, past the {}-byte data area",
                    h.data_size
                ),
            ));
        }
        starts.push(rel);
    }
    Ok(starts)
}

/// Build the block table from the starts: block `i` spans its start to the
/// next block's (the last one to the end of the data area); version 4 adds
/// each block's uncompressed size, bounded by [`MAX_BLOCK`].
fn read_blocks(
    path: &Path,
    bytes: &[u8],
    h: &Header,
    starts: &[usize],
) -> Result<Vec<Block>, SceneError> {
    let mut blocks = Vec::with_capacity(h.num_data);
    for i in 0..h.num_data {
        let field = h.data_offsets_at() + 4 * i;
        let next = starts.get(i + 1).copied().unwrap_or(h.data_size);
        if next < starts[i] {
            return Err(SceneError::at(
                path,
                (field + 4) as u64,
                format!(
                    "data block {} starts at {next}, before block {i} (at {})",
                    i + 1,
                    starts[i]
                ),
            ));
        }
        let size_field = h.data_sizes_at() + 4 * i;
        let size = if h.version == 4 {
            let f = size_field;
            let s = non_negative(path, read_i32(path, bytes, f, "data size")?, f, "data size")?;
            if s > MAX_BLOCK {
                return Err(SceneError::at(
                    path,
                    f as u64,
                    format!("data block {i} declares {s} bytes (limit {MAX_BLOCK})"),
                ));
            }
            Some(s)
        } else {
            None
        };
        blocks.push(Block {
            offset: h.data_start + starts[i],
            len: next - starts[i],
            size,
            field: if h.version == 4 {
                size_field as u64
            } else {
                field as u64
            },
        });
    }
    Ok(blocks)
}

impl<'a> Datafile<'a> {
    /// Parse the header, the item types, the items and the data block table.
    pub fn parse(path: &'a Path, bytes: &'a [u8]) -> Result<Self, SceneError> {
        let h = Header::parse(path, bytes)?;
        check_item_types(path, bytes, &h)?;
        let items = (0..h.num_items)
            .map(|i| read_item(path, bytes, &h, i, h.item_offsets_at() + 4 * i))
            .collect::<Result<Vec<_>, _>>()?;
        let starts = read_block_starts(path, bytes, &h)?;
        let blocks = read_blocks(path, bytes, &h, &starts)?;
        Ok(Self {
            path,
            bytes,
            version: h.version,
            items,
            blocks,
        })
    }

    /// Number of data blocks.
    pub fn num_data(&self) -> usize {
        self.blocks.len()
    }

    /// Data block `index`, decompressed; `field` is the file offset of the
    /// item field naming it (for errors).
    pub fn data(&self, index: i32, field: u64, what: &str) -> Result<Vec<u8>, SceneError> {
        let block = usize::try_from(index)
            .ok()
            .and_then(|i| self.blocks.get(i))
            .ok_or_else(|| {
                SceneError::at(
                    self.path,
                    field,
                    format!(
                        "{what}: data block {index} does not exist ({} blocks)",
                        self.blocks.len()
                    ),
                )
            })?;
        let raw = &self.bytes[block.offset..block.offset + block.len];
        let Some(size) = block.size else {
            return Ok(raw.to_vec());
        };
        let mut out = Vec::with_capacity(size.min(raw.len().saturating_mul(64)));
        flate2::read::ZlibDecoder::new(raw)
            .take(size as u64 + 1)
            .read_to_end(&mut out)
            .map_err(|e| {
                SceneError::at(
                    self.path,
                    block.offset as u64,
                    format!("{what}: data block {index}: zlib: {e}"),
                )
            })?;
        if out.len() != size {
            return Err(SceneError::at(
                self.path,
                block.field,
                format!(
                    "{what}: data block {index} decompresses to {}{} bytes, the table says {size}",
                    out.len().min(size + 1),
                    if out.len() > size { "+" } else { "" }
                ),
            ));
        }
        Ok(out)
    }
}

#[cfg(test)]
/// Write a datafile (version 4) from items and uncompressed data blocks.
pub(super) fn datafile(items: &[(u16, u16, Vec<i32>)], data: &[Vec<u8>]) -> Vec<u8> {
    use std::io::Write;
    let mut types: Vec<u16> = items.iter().map(|i| i.0).collect();
    types.sort();
    types.dedup();
    let mut sorted: Vec<&(u16, u16, Vec<i32>)> = items.iter().collect();
    sorted.sort_by_key(|i| (i.0, i.1));
    let mut item_bytes = Vec::new();
    let mut item_offsets = Vec::new();
    for (t, id, ints) in &sorted {
        item_offsets.push(item_bytes.len() as i32);
        item_bytes.extend(((*t as i32) << 16 | *id as i32).to_le_bytes());
        item_bytes.extend(((ints.len() * 4) as i32).to_le_bytes());
        for v in ints {
            item_bytes.extend(v.to_le_bytes());
        }
    }
    let mut data_bytes = Vec::new();
    let mut data_offsets = Vec::new();
    for d in data {
        data_offsets.push(data_bytes.len() as i32);
        let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
        z.write_all(d).unwrap();
        data_bytes.extend(z.finish().unwrap());
    }
    let mut out = Vec::new();
    out.extend(b"DATA");
    let mut head = vec![4i32, 0, 0];
    head.extend([
        types.len() as i32,
        items.len() as i32,
        data.len() as i32,
        item_bytes.len() as i32,
        data_bytes.len() as i32,
    ]);
    for t in &types {
        let start = sorted.iter().position(|i| i.0 == *t).unwrap() as i32;
        let num = sorted.iter().filter(|i| i.0 == *t).count() as i32;
        head.extend([*t as i32, start, num]);
    }
    head.extend(&item_offsets);
    head.extend(&data_offsets);
    head.extend(data.iter().map(|d| d.len() as i32));
    for v in head {
        out.extend(v.to_le_bytes());
    }
    out.extend(item_bytes);
    out.extend(data_bytes);
    let size = (out.len() - 16) as i32;
    out[8..12].copy_from_slice(&size.to_le_bytes());
    out
}
