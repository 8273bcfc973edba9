//! Teeworlds (2D platformer): maps of `teeworlds-data` 0.7.5 as 2D scenes.
//!
//! # Data layout
//!
//! The data root passed to [`load`] is the game's data directory inside the
//! unpacked Debian package: `<unpacked teeworlds-data>/usr/share/games/teeworlds/data`
//! ([`DATA_SUBDIR`] under the directory `dpkg-deb -x` unpacked the package
//! into; with `wasp scenes fetch`, `$WASP_SCENES/teeworlds/` + [`DATA_SUBDIR`]).
//! Files read:
//!
//! - `maps/<map>.map`: the map (a "DATAFILE", format below); `def.map` is the
//!   file stem (`dm1`, `ctf2`, ...).
//! - `mapres/<image>.png`: external images named by the map's image items
//!   (tilesets of 16x16 tiles, backgrounds, doodads).
//!
//! Data licence: CC-BY-SA 3.0 (`maps/license.txt`, `debian/copyright`).
//!
//! # Datafile format (as implemented here; little-endian `i32` throughout)
//!
//! | offset | field |
//! |---|---|
//! | 0 | magic `DATA` (`ATAD` = big-endian writer: rejected) |
//! | 4 | version: 3 (raw data blocks) or 4 (zlib data blocks) |
//! | 8 | size: file length - 16 |
//! | 12 | swaplen (ignored) |
//! | 16..36 | num_item_types, num_items, num_data, item_size, data_size |
//! | 36 | item types: `num_item_types` x {type_id, start, num} |
//! | .. | item offsets: `num_items` x i32, relative to the item area |
//! | .. | data offsets: `num_data` x i32, relative to the data area |
//! | .. | (version 4) uncompressed data sizes: `num_data` x i32 |
//! | .. | item area (`item_size` bytes): each item = {type_id << 16 \| id, size in bytes, size/4 ints} |
//! | .. | data area (`data_size` bytes): block *i* spans offset *i* .. offset *i+1* (last: to `data_size`) |
//!
//! Map items (type id: layout as `i32` fields):
//!
//! - 2 image: version, width, height, external, name (data index of a
//!   NUL-terminated string), data (data index of the pixels, embedded
//!   images only), version >= 2: format (0 RGB, 1 RGBA).
//! - 4 group: version, offset x, offset y, parallax x, parallax y (percent),
//!   start layer, layer count; version >= 2: use clipping, clip x, y, w, h
//!   (world units); version >= 3: name (3 ints).
//! - 5 layer: (layer version, type, flags), then per type:
//!   - 2 tiles: version, width, height, flags (1 = game layer), colour
//!     r g b a, colour envelope, envelope offset, image (-1 = none), data;
//!     the data block holds {index, flags, skip, reserved} bytes per tile;
//!     version >= 4 run-length packs them: each stored tile stands for
//!     `skip + 1` tiles.
//!   - 3 quads: version, quad count, data, image; the data block holds 152
//!     bytes per quad: 5 points (4 corners top-left, top-right,
//!     bottom-left, bottom-right, then the pivot) and 4 texture coordinates
//!     as 22.10 fixed point, 4 RGBA colours, position and colour envelopes.
//! - 3 envelope: version, channels (3 position, 4 colour), first point,
//!   point count, name (8 ints), version >= 2: synchronized.
//! - 6 envelope points: every envelope's points, concatenated: time (ms),
//!   curve type, 4 values (22.10 fixed point); 6 ints a point, 22 when the
//!   envelopes are version 3 (bezier tangents follow, unused by the
//!   shipped maps' curves).
//! - 0 version, 1 info: not needed.
//!
//! # Scene
//!
//! The game renders the groups in order and, inside each, the layers in
//! order (painter's order); so does the scene. World units are the game's:
//! a tile is [`TILE_SIZE`] = 32 units (its tileset cell is 64x64 texels of
//! a 1024x1024 image). The camera is the game's default view at zoom 1
//! ([`view_size`]: 1 150 000 square units at the frame's aspect, at most
//! 1500 wide and 1050 high; 1500 x 588 units at 1960x768). A group with
//! parallax `p` (percent) and offset `o` seen from camera centre `c` is
//! placed at `g - o + c * (1 - p/100)` (the game maps its screen to
//! `o + c*p/100 +- size/2` in group space), so the scene is exact for this
//! one camera. Geometry:
//!
//! - tile layers: the tiles the game submits for this view (its visible
//!   range plus one tile of margin, edge tiles extended past the layer
//!   border as the game does), one quad (2 triangles) per non-empty tile,
//!   UVs into the 16x16 tileset (half-texel inset) with the flip and rotate
//!   flags honoured. Tiles flagged opaque (and a layer alpha of 255) go to
//!   a `Blend::Opaque` mesh (the game draws them with blending off), the
//!   rest to a `Blend::AlphaBlend` mesh.
//! - quad layers: every quad, 2 triangles, `Blend::AlphaBlend`; the very
//!   first layer drawn, when it is a quad layer (the sky gradient), is
//!   `Blend::Opaque`. Animated quads (position envelopes: falling snow,
//!   drifting clouds) are placed as at map time [`ENVELOPE_TIME_MS`] = 0,
//!   i.e. at each quad's own time offset into its looping envelope, moved
//!   and rotated about their pivot as the game does (step, linear, slow,
//!   fast and smooth curves).
//! - group clip rectangles (scissor in the game) clip the geometry.
//! - the game layer (entities and collision) is not drawn.
//! - not modelled: colours (layer tint, quad vertex colours, colour
//!   envelopes), players, weapons, particles, HUD.
//!
//! z is the draw order of the layer (0 = first drawn, larger = nearer).
//! Materials use the `sprite` template with [`Filter::Bilinear`] (the game
//! filters linearly); untextured layers (image -1) get the template's ALU
//! instructions without the texture instruction.
//!
//! Camera selectors: `spawn:N` centres the view on the Nth spawn point
//! (entities spawn, red spawn and blue spawn of the game layer, in row-major
//! order, counted from 0); `center` centres it on the game layer.

use super::def::SceneDef;
use super::{
    shader, Blend, Camera, Filter, Material, Mesh, Scene, SceneError, ShaderOp, Texture, Vec2, Vec3,
};
use std::io::Read;
use std::path::{Path, PathBuf};

/// The Debian package holding the data.
pub const PACKAGE: &str = "teeworlds-data";
/// The data root inside the unpacked package.
pub const DATA_SUBDIR: &str = "usr/share/games/teeworlds/data";
/// Size of a tile in world units.
pub const TILE_SIZE: f32 = 32.0;
/// Game-layer tile index of entity 0 (`255 - 16*4`); entity `e` is stored
/// as `ENTITY_OFFSET + e`.
pub const ENTITY_OFFSET: u8 = 191;
/// Entities that are spawn points: spawn, red spawn, blue spawn.
pub const SPAWN_ENTITIES: [u8; 3] = [1, 2, 3];

/// Tile flag: mirror horizontally (the game calls it "vflip").
pub const TILEFLAG_VFLIP: u8 = 1;
/// Tile flag: mirror vertically (the game calls it "hflip").
pub const TILEFLAG_HFLIP: u8 = 2;
/// Tile flag: drawn without blending.
pub const TILEFLAG_OPAQUE: u8 = 4;
/// Tile flag: rotate 90 degrees clockwise (after the flips).
pub const TILEFLAG_ROTATE: u8 = 8;

const ITEM_IMAGE: u16 = 2;
const ITEM_ENVELOPE: u16 = 3;
const ITEM_ENVPOINTS: u16 = 6;
const ITEM_GROUP: u16 = 4;
const ITEM_LAYER: u16 = 5;
const LAYER_TILES: i32 = 2;
const LAYER_QUADS: i32 = 3;
const QUAD_BYTES: usize = 152;
/// Largest uncompressed data block accepted.
const MAX_BLOCK: usize = 256 << 20;
/// Largest tile layer accepted (tiles).
const MAX_TILES: usize = 1 << 24;

// ---------------------------------------------------------------------------
// Datafile
// ---------------------------------------------------------------------------

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
struct Block {
    /// File offset of the stored bytes.
    offset: usize,
    /// Stored length.
    len: usize,
    /// Uncompressed size (version 4).
    size: Option<usize>,
    /// File offset of the `i32` declaring this block's size or offset.
    field: u64,
}

/// A parsed Teeworlds datafile: items, and data blocks decompressed on
/// demand. Every offset and count is checked against the file.
#[derive(Debug)]
pub struct Datafile<'a> {
    path: &'a Path,
    bytes: &'a [u8],
    /// Format version (3 or 4).
    pub version: i32,
    /// Items, in file order.
    pub items: Vec<Item>,
    blocks: Vec<Block>,
}

fn read_i32(path: &Path, bytes: &[u8], off: usize, what: &str) -> Result<i32, SceneError> {
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

fn non_negative(path: &Path, v: i32, off: usize, what: &str) -> Result<usize, SceneError> {
    usize::try_from(v).map_err(|_| SceneError::at(path, off as u64, format!("{what} is {v} (< 0)")))
}

impl<'a> Datafile<'a> {
    /// Parse the header, the item types, the items and the data block table.
    pub fn parse(path: &'a Path, bytes: &'a [u8]) -> Result<Self, SceneError> {
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
        let mut off = 36;
        for _ in 0..num_types {
            let t = read_i32(path, bytes, off, "item type")?;
            let start = read_i32(path, bytes, off + 4, "item type start")?;
            let num = read_i32(path, bytes, off + 8, "item type count")?;
            if !(0..=0xffff).contains(&t)
                || start < 0
                || num < 0
                || start as usize + num as usize > num_items
            {
                return Err(SceneError::at(
                    path,
                    off as u64,
                    format!(
                        "item type entry {{type {t}, start {start}, count {num}}} is out of \
                         range ({num_items} items)"
                    ),
                ));
            }
            off += 12;
        }
        let mut items = Vec::with_capacity(num_items);
        for i in 0..num_items {
            let field = off + 4 * i;
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
                    format!("item {i} at {rel}: its 8-byte header is outside the {item_size}-byte item area"),
                ));
            }
            let at = items_start + rel;
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
            items.push(Item {
                type_id: ((key as u32) >> 16) as u16,
                id: (key as u32 & 0xffff) as u16,
                offset: (at + 8) as u64,
                ints,
            });
        }
        off += 4 * num_items;
        let offsets_at = off;
        let sizes_at = off + 4 * num_data;
        let mut starts = Vec::with_capacity(num_data);
        for i in 0..num_data {
            let field = offsets_at + 4 * i;
            let rel = non_negative(
                path,
                read_i32(path, bytes, field, "data offset")?,
                field,
                "data offset",
            )?;
            if rel > data_size {
                return Err(SceneError::at(
                    path,
                    field as u64,
                    format!("data block {i} starts at {rel}, past the {data_size}-byte data area"),
                ));
            }
            starts.push(rel);
        }
        let mut blocks = Vec::with_capacity(num_data);
        for i in 0..num_data {
            let field = offsets_at + 4 * i;
            let next = starts.get(i + 1).copied().unwrap_or(data_size);
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
            let size = if version == 4 {
                let f = sizes_at + 4 * i;
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
                offset: data_start + starts[i],
                len: next - starts[i],
                size,
                field: if version == 4 {
                    (sizes_at + 4 * i) as u64
                } else {
                    field as u64
                },
            });
        }
        Ok(Self {
            path,
            bytes,
            version,
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

// ---------------------------------------------------------------------------
// Map
// ---------------------------------------------------------------------------

/// An image of the map.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MapImage {
    /// Name (`mapres/<name>.png` when external).
    pub name: String,
    /// Width as recorded in the map.
    pub width: u32,
    /// Height as recorded in the map.
    pub height: u32,
    /// External (a file under `mapres/`) or embedded.
    pub external: bool,
    /// Embedded: the data block of the pixels.
    pub data: i32,
    /// Embedded: bytes per pixel (3 RGB, 4 RGBA).
    pub channels: u32,
    offset: u64,
}

/// A group of layers.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Group {
    /// Offset (world units).
    pub offset: [i32; 2],
    /// Parallax (percent; 100 = moves with the game layer).
    pub parallax: [i32; 2],
    /// First layer (index into [`Map::layers`]).
    pub start_layer: usize,
    /// Number of layers.
    pub num_layers: usize,
    /// Clip rectangle x, y, w, h (world units), if clipping.
    pub clip: Option<[i32; 4]>,
    /// Name (version 3 groups).
    pub name: String,
}

/// One tile.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tile {
    /// Tileset index (0 = empty) or game-layer value.
    pub index: u8,
    /// `TILEFLAG_*` bits.
    pub flags: u8,
}

/// A tile layer.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TileLayer {
    /// Width in tiles.
    pub width: usize,
    /// Height in tiles.
    pub height: usize,
    /// The game layer (collision and entities).
    pub game: bool,
    /// Colour (RGBA 0..255).
    pub color: [i32; 4],
    /// Image index, if textured.
    pub image: Option<usize>,
    /// Tiles, row-major.
    pub tiles: Vec<Tile>,
}

/// A quad of a quad layer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quad {
    /// Corners (top-left, top-right, bottom-left, bottom-right) and pivot.
    pub points: [[f32; 2]; 5],
    /// Texture coordinates of the 4 corners.
    pub uv: [[f32; 2]; 4],
    /// Corner colours (RGBA 0..255).
    pub colors: [[i32; 4]; 4],
    /// Position envelope (-1 = none).
    pub pos_env: i32,
    /// Time offset into the position envelope (ms).
    pub pos_env_offset: i32,
    /// Colour envelope (-1 = none).
    pub color_env: i32,
}

/// A quad layer.
#[derive(Clone, Debug, PartialEq)]
pub struct QuadLayer {
    /// Image index, if textured.
    pub image: Option<usize>,
    /// Quads.
    pub quads: Vec<Quad>,
}

/// What a layer holds.
#[derive(Clone, Debug, PartialEq)]
pub enum LayerKind {
    /// Tiles.
    Tiles(TileLayer),
    /// Quads.
    Quads(QuadLayer),
    /// Another layer type (not drawn).
    Other(i32),
}

/// A layer.
#[derive(Clone, Debug, PartialEq)]
pub struct Layer {
    /// Layer flags (1 = detail).
    pub flags: i32,
    /// Name (newer layer versions).
    pub name: String,
    /// Content.
    pub kind: LayerKind,
}

/// A point of an envelope.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EnvPoint {
    /// Time (ms).
    pub time: i32,
    /// Curve to the next point: 0 step, 1 linear, 2 slow, 3 fast, 4 smooth.
    pub curve: i32,
    /// Values (22.10 fixed point): position x, y, rotation (degrees), or
    /// colour r, g, b, a.
    pub values: [i32; 4],
}

/// An envelope: an animation curve, looping over its last point's time.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Envelope {
    /// Channels (3 position, 4 colour).
    pub channels: i32,
    /// Points, by time.
    pub points: Vec<EnvPoint>,
}

impl Envelope {
    /// The channel values at `time_ms`, as the game evaluates them.
    pub fn eval(&self, time_ms: f64) -> [f32; 4] {
        let fx = |p: &EnvPoint| p.values.map(|v| v as f32 / 1024.0);
        let (Some(first), Some(last)) = (self.points.first(), self.points.last()) else {
            return [0.0; 4];
        };
        if self.points.len() == 1 || last.time <= 0 {
            return fx(first);
        }
        let t = time_ms % last.time as f64;
        for w in self.points.windows(2) {
            let (a, b) = (&w[0], &w[1]);
            if t >= a.time as f64 && t <= b.time as f64 {
                let span = (b.time - a.time) as f64;
                let x = if span > 0.0 {
                    ((t - a.time as f64) / span) as f32
                } else {
                    0.0
                };
                let x = match a.curve {
                    0 => 0.0,
                    2 => x * x * x,
                    3 => 1.0 - (1.0 - x).powi(3),
                    4 => -2.0 * x * x * x + 3.0 * x * x,
                    _ => x,
                };
                let (va, vb) = (fx(a), fx(b));
                return [0, 1, 2, 3].map(|c| va[c] + (vb[c] - va[c]) * x);
            }
        }
        fx(last)
    }
}

/// A parsed map.
#[derive(Clone, Debug, PartialEq)]
pub struct Map {
    /// Images, by index.
    pub images: Vec<MapImage>,
    /// Envelopes, by index.
    pub envelopes: Vec<Envelope>,
    /// Groups, in render order.
    pub groups: Vec<Group>,
    /// Layers, in file order.
    pub layers: Vec<Layer>,
}

fn field(path: &Path, item: &Item, i: usize, what: &str) -> Result<i32, SceneError> {
    item.ints.get(i).copied().ok_or_else(|| {
        SceneError::at(
            path,
            item.offset,
            format!(
                "item (type {}, id {}) has {} fields, `{what}` is field {i}",
                item.type_id,
                item.id,
                item.ints.len()
            ),
        )
    })
}

fn field_at(item: &Item, i: usize) -> u64 {
    item.offset + 4 * i as u64
}

/// Decode a name stored as 3 (or more) ints: 4 bytes each, most significant
/// first, each byte offset by 128, NUL-terminated.
fn ints_to_str(ints: &[i32]) -> String {
    let mut s = String::new();
    'outer: for v in ints {
        for shift in [24u32, 16, 8, 0] {
            let b = ((*v as u32 >> shift) & 0xff) as u8;
            let c = b.wrapping_sub(128);
            if c == 0 {
                break 'outer;
            }
            s.push(if c.is_ascii_graphic() || c == b' ' {
                c as char
            } else {
                '?'
            });
        }
    }
    s
}

fn image_index(
    path: &Path,
    v: i32,
    at: u64,
    num_images: usize,
) -> Result<Option<usize>, SceneError> {
    if v == -1 {
        return Ok(None);
    }
    match usize::try_from(v) {
        Ok(i) if i < num_images => Ok(Some(i)),
        _ => Err(SceneError::at(
            path,
            at,
            format!("image index {v}: the map has {num_images} images"),
        )),
    }
}

impl Map {
    /// Parse a map from the bytes of a `.map` file.
    pub fn parse(path: &Path, bytes: &[u8]) -> Result<Self, SceneError> {
        let df = Datafile::parse(path, bytes)?;
        let mut images = Vec::new();
        for item in df.items.iter().filter(|i| i.type_id == ITEM_IMAGE) {
            let version = field(path, item, 0, "image version")?;
            let w = field(path, item, 1, "image width")?;
            let h = field(path, item, 2, "image height")?;
            let external = field(path, item, 3, "image external")? != 0;
            let name_idx = field(path, item, 4, "image name")?;
            let data = field(path, item, 5, "image data")?;
            let name_bytes = df.data(name_idx, field_at(item, 4), "image name")?;
            let end = name_bytes
                .iter()
                .position(|&b| b == 0)
                .unwrap_or(name_bytes.len());
            let name = String::from_utf8_lossy(&name_bytes[..end]).into_owned();
            if external
                && (name.is_empty()
                    || name.contains(['/', '\\'])
                    || name.starts_with('.')
                    || name.len() > 128)
            {
                return Err(SceneError::at(
                    path,
                    field_at(item, 4),
                    format!("external image name {name:?} is not a plain file name"),
                ));
            }
            let channels = if version >= 2 && item.ints.len() > 6 {
                match item.ints[6] {
                    0 => 3,
                    1 => 4,
                    f => {
                        return Err(SceneError::at(
                            path,
                            field_at(item, 6),
                            format!("image format {f}: expected 0 (RGB) or 1 (RGBA)"),
                        ))
                    }
                }
            } else {
                4
            };
            if !external && (w <= 0 || h <= 0 || w > 16384 || h > 16384) {
                return Err(SceneError::at(
                    path,
                    field_at(item, 1),
                    format!("embedded image {name:?} is {w}x{h}: expected 1..=16384 each"),
                ));
            }
            images.push(MapImage {
                name,
                width: w.max(0) as u32,
                height: h.max(0) as u32,
                external,
                data,
                channels,
                offset: item.offset,
            });
        }

        let layer_items: Vec<&Item> = df
            .items
            .iter()
            .filter(|i| i.type_id == ITEM_LAYER)
            .collect();
        let mut layers = Vec::with_capacity(layer_items.len());
        for item in &layer_items {
            layers.push(parse_layer(&df, path, item, images.len())?);
        }

        let env_items: Vec<&Item> = df
            .items
            .iter()
            .filter(|i| i.type_id == ITEM_ENVELOPE)
            .collect();
        let point_ints: Vec<i32> = df
            .items
            .iter()
            .filter(|i| i.type_id == ITEM_ENVPOINTS)
            .flat_map(|i| i.ints.iter().copied())
            .collect();
        // Version 3 envelopes store bezier tangents with each point.
        let stride = if env_items
            .iter()
            .any(|e| e.ints.first().is_some_and(|&v| v >= 3))
        {
            22
        } else {
            6
        };
        let num_points = point_ints.len() / stride;
        let mut envelopes = Vec::with_capacity(env_items.len());
        for item in &env_items {
            let channels = field(path, item, 1, "envelope channels")?;
            let start = field(path, item, 2, "envelope start point")?;
            let num = field(path, item, 3, "envelope point count")?;
            let range = match (usize::try_from(start), usize::try_from(num)) {
                (Ok(s), Ok(n)) if s.saturating_add(n) <= num_points => s..s + n,
                _ => {
                    return Err(SceneError::at(
                        path,
                        field_at(item, 2),
                        format!("envelope points {start}+{num}: the map has {num_points} points"),
                    ))
                }
            };
            let points = range
                .map(|k| {
                    let p = &point_ints[k * stride..k * stride + 6];
                    EnvPoint {
                        time: p[0],
                        curve: p[1],
                        values: [p[2], p[3], p[4], p[5]],
                    }
                })
                .collect();
            envelopes.push(Envelope { channels, points });
        }

        let mut groups = Vec::new();
        for item in df.items.iter().filter(|i| i.type_id == ITEM_GROUP) {
            let version = field(path, item, 0, "group version")?;
            let mut g = [0i32; 6];
            for (k, name) in [
                "offset x",
                "offset y",
                "parallax x",
                "parallax y",
                "start layer",
                "layer count",
            ]
            .iter()
            .enumerate()
            {
                g[k] = field(path, item, k + 1, name)?;
            }
            let start = usize::try_from(g[4]).ok();
            let num = usize::try_from(g[5]).ok();
            let (start_layer, num_layers) = match (start, num) {
                (Some(s), Some(n)) if s.saturating_add(n) <= layers.len() => (s, n),
                _ => {
                    return Err(SceneError::at(
                        path,
                        field_at(item, 5),
                        format!(
                            "group layers {}..{}+{}: the map has {} layers",
                            g[4],
                            g[4],
                            g[5],
                            layers.len()
                        ),
                    ))
                }
            };
            let clip = if version >= 2 && item.ints.len() >= 12 && item.ints[7] != 0 {
                Some([item.ints[8], item.ints[9], item.ints[10], item.ints[11]])
            } else {
                None
            };
            let name = if version >= 3 && item.ints.len() >= 15 {
                ints_to_str(&item.ints[12..15])
            } else {
                String::new()
            };
            groups.push(Group {
                offset: [g[0], g[1]],
                parallax: [g[2], g[3]],
                start_layer,
                num_layers,
                clip,
                name,
            });
        }
        Ok(Map {
            images,
            envelopes,
            groups,
            layers,
        })
    }

    /// The game layer, if any.
    pub fn game_layer(&self) -> Option<&TileLayer> {
        self.layers.iter().find_map(|l| match &l.kind {
            LayerKind::Tiles(t) if t.game => Some(t),
            _ => None,
        })
    }

    /// Spawn points (world units, tile centres) in row-major order.
    pub fn spawn_points(&self) -> Vec<[f32; 2]> {
        let Some(g) = self.game_layer() else {
            return Vec::new();
        };
        let mut out = Vec::new();
        for (i, t) in g.tiles.iter().enumerate() {
            if t.index > ENTITY_OFFSET && SPAWN_ENTITIES.contains(&(t.index - ENTITY_OFFSET)) {
                let (x, y) = (i % g.width, i / g.width);
                out.push([(x as f32 + 0.5) * TILE_SIZE, (y as f32 + 0.5) * TILE_SIZE]);
            }
        }
        out
    }
}

fn parse_layer(
    df: &Datafile,
    path: &Path,
    item: &Item,
    num_images: usize,
) -> Result<Layer, SceneError> {
    let ltype = field(path, item, 1, "layer type")?;
    let flags = field(path, item, 2, "layer flags")?;
    match ltype {
        LAYER_TILES => {
            let version = field(path, item, 3, "tile layer version")?;
            let w = field(path, item, 4, "tile layer width")?;
            let h = field(path, item, 5, "tile layer height")?;
            let tflags = field(path, item, 6, "tile layer flags")?;
            let mut color = [0i32; 4];
            for (k, c) in color.iter_mut().enumerate() {
                *c = field(path, item, 7 + k, "tile layer colour")?;
            }
            let image = image_index(
                path,
                field(path, item, 13, "tile layer image")?,
                field_at(item, 13),
                num_images,
            )?;
            let data = field(path, item, 14, "tile layer data")?;
            let (width, height) = match (usize::try_from(w), usize::try_from(h)) {
                (Ok(a), Ok(b)) if a > 0 && b > 0 && a.saturating_mul(b) <= MAX_TILES => (a, b),
                _ => {
                    return Err(SceneError::at(
                        path,
                        field_at(item, 4),
                        format!(
                            "tile layer is {w}x{h}: expected positive, at most {MAX_TILES} tiles"
                        ),
                    ))
                }
            };
            let raw = df.data(data, field_at(item, 14), "tile layer data")?;
            let n = width * height;
            let tiles = if version >= 4 {
                let mut tiles = Vec::with_capacity(n);
                for t in raw.chunks_exact(4) {
                    let run = t[2] as usize + 1;
                    let tile = Tile {
                        index: t[0],
                        flags: t[1],
                    };
                    let take = run.min(n - tiles.len());
                    tiles.extend(std::iter::repeat_n(tile, take));
                    if tiles.len() == n {
                        break;
                    }
                }
                if tiles.len() != n || raw.len() % 4 != 0 {
                    return Err(SceneError::at(
                        path,
                        field_at(item, 14),
                        format!(
                            "tile layer data ({} bytes, run-length packed) expands to {} tiles, \
                             the layer is {width}x{height} = {n}",
                            raw.len(),
                            tiles.len()
                        ),
                    ));
                }
                tiles
            } else {
                if raw.len() != n * 4 {
                    return Err(SceneError::at(
                        path,
                        field_at(item, 14),
                        format!(
                            "tile layer data is {} bytes, the layer is {width}x{height} = {} bytes",
                            raw.len(),
                            n * 4
                        ),
                    ));
                }
                raw.chunks_exact(4)
                    .map(|t| Tile {
                        index: t[0],
                        flags: t[1],
                    })
                    .collect()
            };
            let name = if version >= 3 && item.ints.len() >= 18 {
                ints_to_str(&item.ints[15..18])
            } else {
                String::new()
            };
            Ok(Layer {
                flags,
                name,
                kind: LayerKind::Tiles(TileLayer {
                    width,
                    height,
                    game: tflags & 1 != 0,
                    color,
                    image,
                    tiles,
                }),
            })
        }
        LAYER_QUADS => {
            let version = field(path, item, 3, "quad layer version")?;
            let num = field(path, item, 4, "quad count")?;
            let data = field(path, item, 5, "quad data")?;
            let image = image_index(
                path,
                field(path, item, 6, "quad layer image")?,
                field_at(item, 6),
                num_images,
            )?;
            let num = usize::try_from(num).map_err(|_| {
                SceneError::at(path, field_at(item, 4), format!("quad count {num} (< 0)"))
            })?;
            let raw = if num == 0 {
                Vec::new()
            } else {
                df.data(data, field_at(item, 5), "quad data")?
            };
            if raw.len() < num.saturating_mul(QUAD_BYTES) {
                return Err(SceneError::at(
                    path,
                    field_at(item, 4),
                    format!(
                        "{num} quads need {} bytes, the data block has {}",
                        num.saturating_mul(QUAD_BYTES),
                        raw.len()
                    ),
                ));
            }
            let quads = raw
                .chunks_exact(QUAD_BYTES)
                .take(num)
                .map(|q| {
                    let int = |i: usize| {
                        i32::from_le_bytes([q[4 * i], q[4 * i + 1], q[4 * i + 2], q[4 * i + 3]])
                    };
                    let fx = |i: usize| int(i) as f32 / 1024.0;
                    let mut points = [[0.0; 2]; 5];
                    for (k, p) in points.iter_mut().enumerate() {
                        *p = [fx(2 * k), fx(2 * k + 1)];
                    }
                    let mut colors = [[0; 4]; 4];
                    for (k, c) in colors.iter_mut().enumerate() {
                        for (j, v) in c.iter_mut().enumerate() {
                            *v = int(10 + 4 * k + j);
                        }
                    }
                    let mut uv = [[0.0; 2]; 4];
                    for (k, t) in uv.iter_mut().enumerate() {
                        *t = [fx(26 + 2 * k), fx(27 + 2 * k)];
                    }
                    Quad {
                        points,
                        uv,
                        colors,
                        pos_env: int(34),
                        pos_env_offset: int(35),
                        color_env: int(36),
                    }
                })
                .collect();
            let name = if version >= 2 && item.ints.len() >= 10 {
                ints_to_str(&item.ints[7..10])
            } else {
                String::new()
            };
            Ok(Layer {
                flags,
                name,
                kind: LayerKind::Quads(QuadLayer { image, quads }),
            })
        }
        other => Ok(Layer {
            flags,
            name: String::new(),
            kind: LayerKind::Other(other),
        }),
    }
}

// ---------------------------------------------------------------------------
// Scene building
// ---------------------------------------------------------------------------

/// The game's view size (world units) at zoom 1 for a frame aspect ratio
/// (width / height): 1 150 000 square units, at most 1500 wide, at most
/// 1050 high.
pub fn view_size(aspect: f32) -> (f32, f32) {
    let f = (1_150_000.0f32).sqrt() / aspect.sqrt();
    let (mut w, mut h) = (f * aspect, f);
    if w > 1500.0 {
        w = 1500.0;
        h = w / aspect;
    }
    if h > 1050.0 {
        h = 1050.0;
        w = h * aspect;
    }
    (w, h)
}

/// Camera selector of a scene definition.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CameraSel {
    /// Centred on the Nth spawn point.
    Spawn(usize),
    /// Centred on the game layer.
    Center,
}

impl CameraSel {
    /// Parse `spawn:N` or `center`.
    pub fn parse(s: &str) -> Option<Self> {
        if s == "center" || s == "centre" {
            return Some(Self::Center);
        }
        s.strip_prefix("spawn:")
            .and_then(|n| n.parse().ok())
            .map(Self::Spawn)
    }
}

/// Triangle vertex being clipped: x, y, u, v.
type ClipVert = [f32; 4];

fn clip_polygon(poly: Vec<ClipVert>, axis: usize, bound: f32, keep_greater: bool) -> Vec<ClipVert> {
    let inside = |v: &ClipVert| {
        if keep_greater {
            v[axis] >= bound
        } else {
            v[axis] <= bound
        }
    };
    let mut out = Vec::with_capacity(poly.len() + 2);
    for i in 0..poly.len() {
        let a = poly[i];
        let b = poly[(i + 1) % poly.len()];
        let (ia, ib) = (inside(&a), inside(&b));
        if ia {
            out.push(a);
        }
        if ia != ib {
            let t = (bound - a[axis]) / (b[axis] - a[axis]);
            let mut v = [0.0; 4];
            for k in 0..4 {
                v[k] = a[k] + (b[k] - a[k]) * t;
            }
            v[axis] = bound;
            out.push(v);
        }
    }
    out
}

/// Accumulates one mesh's triangles, clipping to a rectangle if asked.
struct MeshBuilder {
    positions: Vec<Vec3>,
    uv: Vec<Vec2>,
    indices: Vec<u32>,
    z: f32,
    clip: Option<[f32; 4]>,
}

impl MeshBuilder {
    fn new(z: f32, clip: Option<[f32; 4]>) -> Self {
        Self {
            positions: Vec::new(),
            uv: Vec::new(),
            indices: Vec::new(),
            z,
            clip,
        }
    }

    fn push(&mut self, p: [f32; 2], t: [f32; 2]) -> u32 {
        self.positions.push([p[0], p[1], self.z]);
        self.uv.push(t);
        (self.positions.len() - 1) as u32
    }

    /// A quad with corners in drawing order c0 c1 c2 c3 (triangles c0 c1 c2
    /// and c0 c2 c3).
    fn quad(&mut self, p: [[f32; 2]; 4], t: [[f32; 2]; 4]) {
        let inside = |c: &[f32; 4], q: &[f32; 2]| {
            q[0] >= c[0] && q[0] <= c[2] && q[1] >= c[1] && q[1] <= c[3]
        };
        match self.clip {
            Some(c) if !p.iter().all(|q| inside(&c, q)) => {
                for tri in [[0usize, 1, 2], [0, 2, 3]] {
                    let mut poly: Vec<ClipVert> = tri
                        .iter()
                        .map(|&k| [p[k][0], p[k][1], t[k][0], t[k][1]])
                        .collect();
                    poly = clip_polygon(poly, 0, c[0], true);
                    poly = clip_polygon(poly, 0, c[2], false);
                    poly = clip_polygon(poly, 1, c[1], true);
                    poly = clip_polygon(poly, 1, c[3], false);
                    if poly.len() < 3 {
                        continue;
                    }
                    let base: Vec<u32> = poly
                        .iter()
                        .map(|v| self.push([v[0], v[1]], [v[2], v[3]]))
                        .collect();
                    for k in 1..base.len() - 1 {
                        self.indices.extend([base[0], base[k], base[k + 1]]);
                    }
                }
            }
            _ => {
                let i: Vec<u32> = (0..4).map(|k| self.push(p[k], t[k])).collect();
                self.indices.extend([i[0], i[1], i[2], i[0], i[2], i[3]]);
            }
        }
    }

    fn finish(self, material: usize) -> Option<Mesh> {
        if self.indices.is_empty() {
            return None;
        }
        Some(Mesh {
            positions: self.positions,
            uv: self.uv,
            uv2: None,
            indices: self.indices,
            material,
        })
    }
}

/// The fragment program of a material: the definition's template (default
/// `sprite`) on `tex`, or, untextured, the template's ALU work alone.
pub(crate) fn program(
    template: Option<&str>,
    tex: Option<usize>,
    filter: Filter,
) -> Result<Vec<ShaderOp>, String> {
    let t = tex.unwrap_or(0);
    let full = match template.unwrap_or("sprite") {
        "sprite" => shader::sprite(t, filter),
        "unlit" => shader::unlit(t, filter),
        "standard" => shader::standard(t, filter),
        "lightmapped" => {
            return Err(
                "shader template `lightmapped` needs a lightmap; 2D scenes have none".into(),
            )
        }
        other => {
            return Err(format!(
                "unknown shader template `{other}` (known: {})",
                shader::TEMPLATES.join(", ")
            ))
        }
    };
    if tex.is_some() {
        return Ok(full);
    }
    let alu: u32 = full
        .iter()
        .map(|op| match op {
            ShaderOp::Alu(n) => *n,
            ShaderOp::Tex(_) => 0,
        })
        .sum();
    Ok(vec![ShaderOp::Alu(alu)])
}

fn load_png(path: &Path) -> Result<(u32, u32, Vec<u8>), SceneError> {
    let bytes =
        std::fs::read(path).map_err(|e| SceneError::in_file(path, format!("cannot read: {e}")))?;
    let img = image::load_from_memory_with_format(&bytes, image::ImageFormat::Png)
        .map_err(|e| SceneError::in_file(path, format!("PNG: {e}")))?
        .to_rgba8();
    let (w, h) = img.dimensions();
    if w == 0 || h == 0 {
        return Err(SceneError::in_file(path, "PNG has no pixels"));
    }
    Ok((w, h, img.into_raw()))
}

fn map_texture(
    data_root: &Path,
    map_path: &Path,
    df_bytes: &[u8],
    img: &MapImage,
) -> Result<Texture, SceneError> {
    if img.external {
        let path = data_root.join("mapres").join(format!("{}.png", img.name));
        let (width, height, rgba) = load_png(&path)?;
        return Ok(Texture {
            name: format!("mapres/{}.png", img.name),
            width,
            height,
            rgba,
            repeat: false,
        });
    }
    let df = Datafile::parse(map_path, df_bytes)?;
    let raw = df.data(img.data, img.offset + 20, "embedded image")?;
    let n = img.width as usize * img.height as usize;
    if raw.len() != n * img.channels as usize {
        return Err(SceneError::at(
            map_path,
            img.offset + 20,
            format!(
                "embedded image {:?}: {} bytes of pixels, {}x{}x{} expected",
                img.name,
                raw.len(),
                img.width,
                img.height,
                img.channels
            ),
        ));
    }
    let rgba = if img.channels == 4 {
        raw
    } else {
        raw.chunks_exact(3)
            .flat_map(|p| [p[0], p[1], p[2], 255])
            .collect()
    };
    Ok(Texture {
        name: format!("{} (embedded)", img.name),
        width: img.width,
        height: img.height,
        rgba,
        repeat: false,
    })
}

/// Path of a map's file under the data root.
pub fn map_path(data_root: &Path, map: &str) -> Result<PathBuf, SceneError> {
    let stem = map.strip_suffix(".map").unwrap_or(map);
    if stem.is_empty()
        || !stem
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
    {
        return Err(SceneError::in_file(
            data_root.join("maps"),
            format!("map name {map:?}: expected a file stem such as `dm1`"),
        ));
    }
    Ok(data_root.join("maps").join(format!("{stem}.map")))
}

/// Tile UVs of corners TL, TR, BR, BL for a tileset index and flags.
fn tile_uv(index: u8, flags: u8, tex_w: u32, tex_h: u32) -> [[f32; 2]; 4] {
    let (tx, ty) = ((index % 16) as f32, (index / 16) as f32);
    let (iu, iv) = (0.5 / tex_w.max(1) as f32, 0.5 / tex_h.max(1) as f32);
    let (u0, u1) = (tx / 16.0 + iu, (tx + 1.0) / 16.0 - iu);
    let (v0, v1) = (ty / 16.0 + iv, (ty + 1.0) / 16.0 - iv);
    let mut c = [[u0, v0], [u1, v0], [u1, v1], [u0, v1]];
    if flags & TILEFLAG_VFLIP != 0 {
        for k in &mut c {
            k[0] = if k[0] == u0 { u1 } else { u0 };
        }
    }
    if flags & TILEFLAG_HFLIP != 0 {
        for k in &mut c {
            k[1] = if k[1] == v0 { v1 } else { v0 };
        }
    }
    if flags & TILEFLAG_ROTATE != 0 {
        c = [c[3], c[0], c[1], c[2]];
    }
    c
}

/// Time (ms since the map started) at which animated quads are placed.
pub const ENVELOPE_TIME_MS: f64 = 0.0;

/// A quad's position envelope at [`ENVELOPE_TIME_MS`] (plus the quad's
/// time offset): offset (world units) and rotation (radians, about the
/// pivot point).
fn quad_motion(map: &Map, quad: &Quad) -> ([f32; 2], f32) {
    let Some(env) = usize::try_from(quad.pos_env)
        .ok()
        .and_then(|i| map.envelopes.get(i))
    else {
        return ([0.0; 2], 0.0);
    };
    let v = env.eval(ENVELOPE_TIME_MS + quad.pos_env_offset as f64);
    ([v[0], v[1]], v[2].to_radians())
}

/// Statistics of a built scene (for reports and tests).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BuildStats {
    /// Layers drawn (with at least one triangle).
    pub layers_drawn: usize,
    /// Tiles emitted.
    pub tiles: usize,
    /// Map quads emitted.
    pub quads: usize,
}

/// Build the scene of `map` (already parsed from `map_bytes` at `map_path`)
/// for a camera centred at `center` with the view `view` (world units).
#[allow(clippy::too_many_arguments)]
pub fn build(
    data_root: &Path,
    map_path: &Path,
    map_bytes: &[u8],
    map: &Map,
    center: [f32; 2],
    view: (f32, f32),
    template: Option<&str>,
    name: String,
) -> Result<(Scene, BuildStats), SceneError> {
    let filter = Filter::Bilinear;
    let (vw, vh) = view;
    let mut stats = BuildStats::default();
    let mut textures: Vec<Texture> = Vec::new();
    let mut tex_of_image: Vec<Option<usize>> = vec![None; map.images.len()];
    let mut materials = Vec::new();
    let mut meshes = Vec::new();
    let mut get_tex = |img: usize, textures: &mut Vec<Texture>| -> Result<usize, SceneError> {
        if let Some(t) = tex_of_image[img] {
            return Ok(t);
        }
        let t = map_texture(data_root, map_path, map_bytes, &map.images[img])?;
        textures.push(t);
        tex_of_image[img] = Some(textures.len() - 1);
        Ok(textures.len() - 1)
    };
    let mut material = |mname: String, blend: Blend, tex: Option<usize>| {
        program(template, tex, filter)
            .map(|shader| {
                materials.push(Material {
                    name: mname,
                    blend,
                    shader,
                });
                materials.len() - 1
            })
            .map_err(|m| SceneError::in_file(map_path, m))
    };
    let mut order = 0usize;
    for (gi, group) in map.groups.iter().enumerate() {
        let clip = match group.clip {
            Some([x, y, w, h]) => {
                if w <= 0 || h <= 0 {
                    continue;
                }
                let (x, y) = (x as f32, y as f32);
                Some([x, y, x + w as f32, y + h as f32])
            }
            None => None,
        };
        let p = [
            group.parallax[0] as f32 / 100.0,
            group.parallax[1] as f32 / 100.0,
        ];
        let o = [group.offset[0] as f32, group.offset[1] as f32];
        // Group space -> world: g - o + c * (1 - p).
        let shift = [
            -o[0] + center[0] * (1.0 - p[0]),
            -o[1] + center[1] * (1.0 - p[1]),
        ];
        // The screen in group space.
        let screen = [
            o[0] + center[0] * p[0] - vw / 2.0,
            o[1] + center[1] * p[1] - vh / 2.0,
        ];
        for li in group.start_layer..group.start_layer + group.num_layers {
            let layer = &map.layers[li];
            let lname = if layer.name.is_empty() {
                format!("g{gi}/l{li}")
            } else {
                format!("g{gi}/l{li} {}", layer.name)
            };
            let z = order as f32;
            match &layer.kind {
                LayerKind::Tiles(t) if t.game => {}
                LayerKind::Tiles(t) => {
                    let tex = t.image.map(|i| get_tex(i, &mut textures)).transpose()?;
                    let (tw, th) = tex
                        .map(|i| (textures[i].width, textures[i].height))
                        .unwrap_or((1024, 1024));
                    let mut opaque = MeshBuilder::new(z, clip);
                    let mut blended = MeshBuilder::new(z, clip);
                    // The game's visible range: (int)(screen / 32) - 1 ..
                    // (int)(screen end / 32) + 1, out-of-layer tiles clamped.
                    let tile = |v: f32| (v / TILE_SIZE) as i64;
                    let (x0, y0) = (tile(screen[0]) - 1, tile(screen[1]) - 1);
                    let (x1, y1) = (tile(screen[0] + vw) + 1, tile(screen[1] + vh) + 1);
                    for y in y0..y1 {
                        let my = y.clamp(0, t.height as i64 - 1) as usize;
                        for x in x0..x1 {
                            let mx = x.clamp(0, t.width as i64 - 1) as usize;
                            let tile = t.tiles[my * t.width + mx];
                            if tile.index == 0 {
                                continue;
                            }
                            let (gx, gy) = (x as f32 * TILE_SIZE, y as f32 * TILE_SIZE);
                            let pos = [
                                [gx, gy],
                                [gx + TILE_SIZE, gy],
                                [gx + TILE_SIZE, gy + TILE_SIZE],
                                [gx, gy + TILE_SIZE],
                            ]
                            .map(|q| [q[0] + shift[0], q[1] + shift[1]]);
                            let uv = if tex.is_some() {
                                tile_uv(tile.index, tile.flags, tw, th)
                            } else {
                                [[0.0; 2]; 4]
                            };
                            stats.tiles += 1;
                            if tile.flags & TILEFLAG_OPAQUE != 0 && t.color[3] >= 255 {
                                opaque.quad(pos, uv);
                            } else {
                                blended.quad(pos, uv);
                            }
                        }
                    }
                    let mut drawn = false;
                    for (b, blend, tag) in [
                        (opaque, Blend::Opaque, "opaque"),
                        (blended, Blend::AlphaBlend, "blended"),
                    ] {
                        if b.indices.is_empty() {
                            continue;
                        }
                        let m = material(format!("teeworlds:{lname}:tiles:{tag}"), blend, tex)?;
                        meshes.extend(b.finish(m));
                        drawn = true;
                    }
                    if drawn {
                        stats.layers_drawn += 1;
                        order += 1;
                    }
                }
                LayerKind::Quads(q) => {
                    let tex = q.image.map(|i| get_tex(i, &mut textures)).transpose()?;
                    let mut b = MeshBuilder::new(z, clip);
                    for quad in &q.quads {
                        let c = [0usize, 1, 3, 2];
                        let (off, rot) = quad_motion(map, quad);
                        let pivot = quad.points[4];
                        let (sin, cos) = rot.sin_cos();
                        let pos = c.map(|k| {
                            let (dx, dy) =
                                (quad.points[k][0] - pivot[0], quad.points[k][1] - pivot[1]);
                            [
                                pivot[0] + dx * cos - dy * sin + off[0] + shift[0],
                                pivot[1] + dx * sin + dy * cos + off[1] + shift[1],
                            ]
                        });
                        let uv = c.map(|k| quad.uv[k]);
                        b.quad(pos, uv);
                        stats.quads += 1;
                        if let Some(ti) = tex {
                            if quad.uv.iter().flatten().any(|v| !(0.0..=1.0).contains(v)) {
                                textures[ti].repeat = true;
                            }
                        }
                    }
                    if !b.indices.is_empty() {
                        let blend = if order == 0 {
                            Blend::Opaque
                        } else {
                            Blend::AlphaBlend
                        };
                        let m = material(format!("teeworlds:{lname}:quads"), blend, tex)?;
                        meshes.extend(b.finish(m));
                        stats.layers_drawn += 1;
                        order += 1;
                    }
                }
                LayerKind::Other(_) => {}
            }
        }
    }
    let scene = Scene {
        name,
        source: format!(
            "{PACKAGE} 0.7.5 (Debian), {} (CC-BY-SA 3.0)",
            map_path
                .strip_prefix(data_root)
                .unwrap_or(map_path)
                .display()
        ),
        meshes,
        materials,
        textures,
        camera: Camera::Ortho {
            left: center[0] - vw / 2.0,
            top: center[1] - vh / 2.0,
            width: vw,
            height: vh,
        },
    };
    Ok((scene, stats))
}

/// Load a Teeworlds scene: `def.map` names `maps/<map>.map` under
/// `data_root` (see the module documentation), `def.camera` is `spawn:N`
/// or `center`.
pub fn load(data_root: &Path, def: &SceneDef) -> Result<Scene, SceneError> {
    load_with_stats(data_root, def).map(|(s, _)| s)
}

/// [`load`], also returning what was emitted.
pub fn load_with_stats(
    data_root: &Path,
    def: &SceneDef,
) -> Result<(Scene, BuildStats), SceneError> {
    let path = map_path(data_root, &def.map)?;
    let bytes = std::fs::read(&path)
        .map_err(|e| SceneError::in_file(&path, format!("cannot read: {e}")))?;
    let map = Map::parse(&path, &bytes)?;
    let sel = CameraSel::parse(&def.camera).ok_or_else(|| {
        SceneError::in_file(
            &path,
            format!(
                "scene `{}`: camera {:?}: expected `spawn:N` or `center`",
                def.name, def.camera
            ),
        )
    })?;
    let game = map
        .game_layer()
        .ok_or_else(|| SceneError::in_file(&path, "the map has no game layer"))?;
    let center = match sel {
        CameraSel::Center => [
            game.width as f32 * TILE_SIZE / 2.0,
            game.height as f32 * TILE_SIZE / 2.0,
        ],
        CameraSel::Spawn(n) => {
            let spawns = map.spawn_points();
            *spawns.get(n).ok_or_else(|| {
                SceneError::in_file(
                    &path,
                    format!(
                        "scene `{}`: camera spawn:{n}, the map has {} spawn points",
                        def.name,
                        spawns.len()
                    ),
                )
            })?
        }
    };
    let view = view_size(def.width as f32 / def.height as f32);
    build(
        data_root,
        &path,
        &bytes,
        &map,
        center,
        view,
        def.shader.as_deref(),
        format!("teeworlds:{}:{}", def.map, def.camera),
    )
}

/// A tiny software rasterizer for eyeballing loaders (tests only): draws
/// the meshes in submission order (painter's order), nearest texel,
/// untextured materials light blue, alpha blending for blended materials.
#[cfg(test)]
pub(crate) fn render_preview(scene: &Scene, w: u32, h: u32) -> image::RgbaImage {
    let Camera::Ortho {
        left,
        top,
        width,
        height,
    } = scene.camera
    else {
        panic!("preview needs an ortho camera")
    };
    let mut img = image::RgbaImage::from_pixel(w, h, image::Rgba([40, 40, 40, 255]));
    let (sx, sy) = (w as f32 / width, h as f32 / height);
    for m in &scene.meshes {
        let mat = &scene.materials[m.material];
        let tex = mat.shader.iter().find_map(|op| match op {
            ShaderOp::Tex(t) => Some(&scene.textures[t.texture]),
            _ => None,
        });
        for t in m.indices.chunks_exact(3) {
            let v = [t[0], t[1], t[2]].map(|i| {
                let p = m.positions[i as usize];
                ([(p[0] - left) * sx, (p[1] - top) * sy], m.uv[i as usize])
            });
            let area = (v[1].0[0] - v[0].0[0]) * (v[2].0[1] - v[0].0[1])
                - (v[2].0[0] - v[0].0[0]) * (v[1].0[1] - v[0].0[1]);
            if area.abs() < 1e-9 {
                continue;
            }
            let minx = v.iter().map(|q| q.0[0]).fold(f32::MAX, f32::min).max(0.0) as u32;
            let maxx = v
                .iter()
                .map(|q| q.0[0])
                .fold(f32::MIN, f32::max)
                .min(w as f32 - 1.0);
            let miny = v.iter().map(|q| q.0[1]).fold(f32::MAX, f32::min).max(0.0) as u32;
            let maxy = v
                .iter()
                .map(|q| q.0[1])
                .fold(f32::MIN, f32::max)
                .min(h as f32 - 1.0);
            if maxx < 0.0 || maxy < 0.0 {
                continue;
            }
            for py in miny..=maxy as u32 {
                for px in minx..=maxx as u32 {
                    let (fx, fy) = (px as f32 + 0.5, py as f32 + 0.5);
                    let e = |a: [f32; 2], b: [f32; 2]| {
                        ((b[0] - a[0]) * (fy - a[1]) - (fx - a[0]) * (b[1] - a[1])) / area
                    };
                    let (w0, w1, w2) = (e(v[1].0, v[2].0), e(v[2].0, v[0].0), e(v[0].0, v[1].0));
                    if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                        continue;
                    }
                    let src = match tex {
                        Some(tx) => {
                            let u = w0 * v[0].1[0] + w1 * v[1].1[0] + w2 * v[2].1[0];
                            let vv = w0 * v[0].1[1] + w1 * v[1].1[1] + w2 * v[2].1[1];
                            let wrap = |c: f32, n: u32| {
                                let c = if tx.repeat {
                                    c - c.floor()
                                } else {
                                    c.clamp(0.0, 1.0)
                                };
                                ((c * n as f32) as u32).min(n - 1)
                            };
                            let (ix, iy) = (wrap(u, tx.width), wrap(vv, tx.height));
                            let o = 4 * (iy * tx.width + ix) as usize;
                            [tx.rgba[o], tx.rgba[o + 1], tx.rgba[o + 2], tx.rgba[o + 3]]
                        }
                        None => [150, 190, 230, 255],
                    };
                    let dst = img.get_pixel_mut(px, py);
                    if mat.blend == Blend::AlphaBlend {
                        let a = src[3] as f32 / 255.0;
                        for (d, s) in dst.0.iter_mut().zip(src).take(3) {
                            *d = (s as f32 * a + *d as f32 * (1.0 - a)) as u8;
                        }
                    } else {
                        dst.0 = [src[0], src[1], src[2], 255];
                    }
                }
            }
        }
    }
    img
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Write a datafile (version 4) from items and uncompressed data blocks.
    fn datafile(items: &[(u16, u16, Vec<i32>)], data: &[Vec<u8>]) -> Vec<u8> {
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

    /// A 4x3 map: one embedded 32x32 RGBA tileset, a sky quad group
    /// (parallax 0), a game group with a tile layer and the game layer
    /// (one spawn at tile (1, 1)).
    fn tiny_map() -> Vec<u8> {
        let mut tileset = vec![0u8; 32 * 32 * 4];
        for (i, p) in tileset.chunks_exact_mut(4).enumerate() {
            p.copy_from_slice(&[(i % 256) as u8, 0, 0, 255]);
        }
        // Tiles: run-length packed (version 4): tile 1 x3 (skip 2), empty x5,
        // tile 2 flipped+rotated, tile 3 opaque, empty x2.
        let tiles = vec![
            1,
            0,
            2,
            0, //
            0,
            0,
            4,
            0, //
            2,
            TILEFLAG_VFLIP | TILEFLAG_ROTATE,
            0,
            0, //
            3,
            TILEFLAG_OPAQUE,
            0,
            0, //
            0,
            0,
            1,
            0,
        ];
        let mut game = vec![0u8; 12 * 4];
        game[(4 + 1) * 4] = ENTITY_OFFSET + 1;
        let mut quad = Vec::new();
        let pts: [[i32; 2]; 5] = [[0, 0], [128, 0], [0, 96], [128, 96], [64, 48]];
        for p in pts {
            quad.extend((p[0] * 1024).to_le_bytes());
            quad.extend((p[1] * 1024).to_le_bytes());
        }
        for _ in 0..4 {
            for c in [255i32, 255, 255, 255] {
                quad.extend(c.to_le_bytes());
            }
        }
        for t in [[0i32, 0], [1024, 0], [0, 1024], [1024, 1024]] {
            quad.extend(t[0].to_le_bytes());
            quad.extend(t[1].to_le_bytes());
        }
        for v in [-1i32, 0, -1, 0] {
            quad.extend(v.to_le_bytes());
        }
        assert_eq!(quad.len(), QUAD_BYTES);
        let data = vec![
            b"tiles\0".to_vec(), // 0
            tileset,             // 1
            tiles,               // 2
            game,                // 3
            quad,                // 4
        ];
        let tile_layer = |flags: i32, image: i32, data: i32| {
            vec![
                0, 2, 0, 4, 4, 3, flags, 255, 255, 255, 255, -1, 0, image, data,
            ]
        };
        let items = vec![
            (0u16, 0u16, vec![1]),
            (ITEM_IMAGE, 0, vec![2, 32, 32, 0, 0, 1, 1]),
            (ITEM_GROUP, 0, vec![3, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0]),
            (ITEM_GROUP, 1, vec![3, 0, 0, 100, 100, 1, 2, 0, 0, 0, 0, 0]),
            (ITEM_LAYER, 0, vec![0, 3, 0, 2, 1, 4, -1]),
            (ITEM_LAYER, 1, tile_layer(0, 0, 2)),
            (ITEM_LAYER, 2, tile_layer(1, -1, 3)),
        ];
        datafile(&items, &data)
    }

    fn def(map: &str, camera: &str) -> SceneDef {
        SceneDef {
            name: "t".into(),
            game: crate::def::Game::Teeworlds,
            map: map.into(),
            camera: camera.into(),
            width: 1960,
            height: 768,
            description: String::new(),
            shader: None,
        }
    }

    #[test]
    fn parses_a_hand_made_map() {
        let bytes = tiny_map();
        let map = Map::parse(Path::new("tiny.map"), &bytes).unwrap();
        assert_eq!(map.images.len(), 1);
        assert!(!map.images[0].external);
        assert_eq!(map.groups.len(), 2);
        assert_eq!(map.layers.len(), 3);
        let LayerKind::Tiles(t) = &map.layers[1].kind else {
            panic!("layer 1 is not tiles")
        };
        assert_eq!((t.width, t.height), (4, 3));
        let idx: Vec<u8> = t.tiles.iter().map(|t| t.index).collect();
        assert_eq!(idx, [1, 1, 1, 0, 0, 0, 0, 0, 2, 3, 0, 0]);
        assert_eq!(map.spawn_points(), vec![[48.0, 48.0]]);
        let LayerKind::Quads(q) = &map.layers[0].kind else {
            panic!("layer 0 is not quads")
        };
        assert_eq!(q.quads[0].points[3], [128.0, 96.0]);
    }

    #[test]
    fn tile_flags_map_uvs() {
        let c = tile_uv(17, 0, 1024, 1024);
        let e = 0.5 / 1024.0;
        assert_eq!(c[0], [1.0 / 16.0 + e, 1.0 / 16.0 + e]);
        assert_eq!(c[2], [2.0 / 16.0 - e, 2.0 / 16.0 - e]);
        let v = tile_uv(17, TILEFLAG_VFLIP, 1024, 1024);
        assert_eq!(v[0][0], c[1][0]);
        assert_eq!(v[0][1], c[0][1]);
        let h = tile_uv(17, TILEFLAG_HFLIP, 1024, 1024);
        assert_eq!(h[0], c[3]);
        let r = tile_uv(17, TILEFLAG_ROTATE, 1024, 1024);
        assert_eq!(r[0], c[3]);
        assert_eq!(r[1], c[0]);
    }

    #[test]
    fn view_matches_the_game() {
        let (w, h) = view_size(1960.0 / 768.0);
        assert!(
            (w - 1500.0).abs() < 1e-3 && (h - 587.755).abs() < 0.01,
            "{w}x{h}"
        );
        let (w, h) = view_size(4.0 / 3.0);
        assert!((w * h - 1_150_000.0).abs() < 10.0 && (w / h - 4.0 / 3.0).abs() < 1e-4);
    }

    #[test]
    fn clipping_keeps_the_inside() {
        let mut b = MeshBuilder::new(0.0, Some([0.0, 0.0, 10.0, 10.0]));
        b.quad(
            [[-10.0, -10.0], [20.0, -10.0], [20.0, 20.0], [-10.0, 20.0]],
            [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        );
        let area: f32 = b
            .indices
            .chunks(3)
            .map(|t| {
                let [a, bb, c] = [t[0], t[1], t[2]].map(|i| b.positions[i as usize]);
                ((bb[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (bb[1] - a[1])).abs() / 2.0
            })
            .sum();
        assert!((area - 100.0).abs() < 1e-3, "{area}");
        for (p, t) in b.positions.iter().zip(&b.uv) {
            assert!(p[0] >= 0.0 && p[0] <= 10.0 && p[1] >= 0.0 && p[1] <= 10.0);
            assert!((t[0] - (p[0] + 10.0) / 30.0).abs() < 1e-5);
        }
    }

    #[test]
    fn loads_a_hand_made_map_end_to_end() {
        let root = std::env::temp_dir().join(format!("wasp-tw-test-{}", std::process::id()));
        std::fs::create_dir_all(root.join("maps")).unwrap();
        std::fs::write(root.join("maps/tiny.map"), tiny_map()).unwrap();
        let (scene, stats) = load_with_stats(&root, &def("tiny", "spawn:0")).unwrap();
        // Extended edges: the 3x3 visible... every view tile maps to a
        // layer tile; the view (1500 x 588) covers far more than the layer.
        assert!(stats.tiles > 4, "{stats:?}");
        assert_eq!(stats.quads, 1);
        assert_eq!(scene.textures.len(), 1);
        assert_eq!(scene.textures[0].width, 32);
        assert_eq!(scene.materials[0].blend, Blend::Opaque); // the sky quad
        assert!(scene.materials[0]
            .shader
            .iter()
            .all(|op| matches!(op, ShaderOp::Alu(_))));
        assert!(scene
            .materials
            .iter()
            .any(|m| m.blend == Blend::Opaque && m.name.contains("tiles:opaque")));
        match scene.camera {
            Camera::Ortho {
                left,
                top,
                width,
                height,
            } => {
                assert!((left + width / 2.0 - 48.0).abs() < 1e-3);
                assert!((top + height / 2.0 - 48.0).abs() < 1e-3);
            }
            _ => panic!("not ortho"),
        }
        for m in &scene.meshes {
            assert_eq!(m.positions.len(), m.uv.len());
            assert!(m.indices.iter().all(|&i| (i as usize) < m.positions.len()));
        }
        let e = load(&root, &def("tiny", "spawn:3")).unwrap_err();
        assert!(e.message.contains("1 spawn"), "{e}");
        let e = load(&root, &def("../x", "center")).unwrap_err();
        assert!(e.message.contains("file stem"), "{e}");
        let mut d = def("tiny", "center");
        d.shader = Some("lightmapped".into());
        assert!(load(&root, &d).unwrap_err().message.contains("lightmap"));
        std::fs::remove_dir_all(&root).ok();
    }

    #[test]
    fn every_truncation_is_an_error_with_an_offset() {
        let bytes = tiny_map();
        for len in 0..bytes.len() {
            let e = Map::parse(Path::new("cut.map"), &bytes[..len])
                .expect_err("a truncated map must not parse");
            assert_eq!(e.file, Path::new("cut.map"));
            assert!(e.offset.is_some(), "{e}");
        }
    }

    #[test]
    fn bad_magic_and_version() {
        let mut bytes = tiny_map();
        bytes[4] = 9;
        let e = Map::parse(Path::new("v.map"), &bytes).unwrap_err();
        assert_eq!(e.offset, Some(4));
        bytes[0] = b'X';
        let e = Map::parse(Path::new("v.map"), &bytes).unwrap_err();
        assert_eq!(e.offset, Some(0));
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]

        #[test]
        fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..600)) {
            let mut b = bytes;
            if b.len() >= 8 && b[0] % 2 == 0 {
                b[0..4].copy_from_slice(b"DATA");
                b[4..8].copy_from_slice(&4i32.to_le_bytes());
            }
            if let Err(e) = Map::parse(Path::new("r.map"), &b) {
                prop_assert_eq!(e.file, PathBuf::from("r.map"));
            }
        }

        #[test]
        fn corrupted_maps_never_panic(pos in 0usize..4096, val in any::<u8>(), pos2 in 0usize..4096, val2 in any::<u8>()) {
            let mut b = tiny_map();
            let n = b.len();
            b[pos % n] = val;
            b[pos2 % n] = val2;
            if let Ok(map) = Map::parse(Path::new("c.map"), &b) {
                // Whatever parsed must be internally consistent...
                for g in &map.groups {
                    prop_assert!(g.start_layer + g.num_layers <= map.layers.len());
                }
                for l in &map.layers {
                    if let LayerKind::Tiles(t) = &l.kind {
                        prop_assert_eq!(t.tiles.len(), t.width * t.height);
                    }
                }
                // ... and build (or fail) without panicking.
                let built = build(
                    Path::new("/nonexistent"),
                    Path::new("c.map"),
                    &b,
                    &map,
                    [48.0, 48.0],
                    view_size(1960.0 / 768.0),
                    None,
                    "c".into(),
                );
                if let Ok((scene, _)) = built {
                    for m in &scene.meshes {
                        prop_assert!(m.indices.iter().all(|&i| (i as usize) < m.positions.len()));
                    }
                }
            }
        }
    }

    fn shipped_defs() -> Vec<SceneDef> {
        crate::def::all()
            .unwrap()
            .into_iter()
            .filter(|d| d.game == crate::def::Game::Teeworlds)
            .collect()
    }

    #[test]
    fn shipped_scene_definitions_are_valid() {
        let defs = shipped_defs();
        assert!(defs.len() >= 2);
        for d in defs {
            assert!(d.name.starts_with("tw-"), "{}", d.name);
            assert!(CameraSel::parse(&d.camera).is_some(), "{}", d.camera);
            map_path(Path::new("/data"), &d.map).unwrap();
        }
    }

    #[test]
    #[ignore = "needs fetched game data: wasp scenes fetch teeworlds"]
    fn real_shipped_scenes_load() {
        let root = real_data_root().expect("teeworlds-data not found");
        for d in shipped_defs() {
            let t0 = std::time::Instant::now();
            let (s, st) = load_with_stats(&root, &d).unwrap();
            let dt = t0.elapsed();
            let tris: usize = s.meshes.iter().map(|m| m.indices.len() / 3).sum();
            let texels: u64 = s
                .textures
                .iter()
                .map(|t| t.width as u64 * t.height as u64)
                .sum();
            println!(
                "{:18} meshes {:3} triangles {:5} materials {:3} textures {:2} ({:.1} Mtexels) \
                 tiles {:4} quads {:3} load {dt:?}",
                d.name,
                s.meshes.len(),
                tris,
                s.materials.len(),
                s.textures.len(),
                texels as f64 / 1e6,
                st.tiles,
                st.quads
            );
            assert!(tris > 500);
        }
    }

    /// The real data root in the scene cache (`$WASP_SCENES`, else the
    /// user's cache directory): unpacked per game by `wasp scenes fetch`,
    /// or per package by a manual `dpkg-deb -x`.
    fn real_data_root() -> Option<PathBuf> {
        let cache = crate::fetch::cache_dir();
        ["teeworlds", PACKAGE]
            .iter()
            .map(|d| cache.join(d).join(DATA_SUBDIR))
            .find(|r| r.join("maps/dm1.map").exists())
    }

    #[test]
    #[ignore = "needs fetched game data: wasp scenes fetch teeworlds"]
    fn real_dm1_spawn0() {
        let root = real_data_root().expect("teeworlds-data not found");
        let bytes = std::fs::read(root.join("maps/dm1.map")).unwrap();
        let map = Map::parse(Path::new("dm1.map"), &bytes).unwrap();
        assert_eq!(map.groups.len(), 7);
        assert_eq!(map.layers.len(), 13);
        let g = map.game_layer().unwrap();
        assert_eq!((g.width, g.height), (60, 50));
        assert_eq!(map.spawn_points().len(), 8);
        let (scene, stats) = load_with_stats(&root, &def("dm1", "spawn:0")).unwrap();
        assert!(stats.layers_drawn >= 8, "{stats:?}");
        assert!(stats.tiles > 300 && stats.quads >= 20, "{stats:?}");
        assert!(scene.textures.len() >= 5);
        for t in &scene.textures {
            assert!(
                t.width >= 256 && t.height >= 128,
                "{} {}x{}",
                t.name,
                t.width,
                t.height
            );
            assert_eq!(t.rgba.len(), (t.width * t.height * 4) as usize);
        }
        let Camera::Ortho {
            left,
            top,
            width,
            height,
        } = scene.camera
        else {
            panic!("not ortho")
        };
        let (cx, cy) = (left + width / 2.0, top + height / 2.0);
        assert!(cx > 0.0 && cx < 60.0 * 32.0 && cy > 0.0 && cy < 50.0 * 32.0);
        let tris: usize = scene.meshes.iter().map(|m| m.indices.len() / 3).sum();
        assert!(tris > 600, "{tris}");
    }

    #[test]
    #[ignore = "needs fetched game data; writes previews to $WASP_PREVIEW_DIR"]
    fn real_previews() {
        let root = real_data_root().expect("teeworlds-data not found");
        let Some(dir) = std::env::var_os("WASP_PREVIEW_DIR") else {
            return;
        };
        // WASP_PREVIEW_SCENES="map:camera,..." (default: a few views).
        let list = std::env::var("WASP_PREVIEW_SCENES")
            .unwrap_or_else(|_| "dm1:spawn:0,ctf2:center,dm3:spawn:1".into());
        for entry in list.split(',') {
            let (map, cam) = entry.split_once(':').expect("map:camera");
            let scene = load(&root, &def(map, cam)).unwrap();
            let img = render_preview(&scene, 980, 384);
            img.save(Path::new(&dir).join(format!("tw-{map}-{}.png", cam.replace(':', ""))))
                .unwrap();
        }
    }

    #[test]
    #[ignore = "needs fetched game data: wasp scenes fetch teeworlds"]
    fn real_every_map_loads() {
        let root = real_data_root().expect("teeworlds-data not found");
        let mut names: Vec<String> = std::fs::read_dir(root.join("maps"))
            .unwrap()
            .filter_map(|e| {
                let p = e.ok()?.path();
                if p.extension()? != "map" {
                    return None;
                }
                Some(p.file_stem()?.to_string_lossy().into_owned())
            })
            .collect();
        names.sort();
        assert!(names.len() >= 16, "{names:?}");
        let mut failures = Vec::new();
        for name in &names {
            for cam in ["center", "spawn:0"] {
                let t0 = std::time::Instant::now();
                match load_with_stats(&root, &def(name, cam)) {
                    Ok((s, st)) => {
                        let tris: usize = s.meshes.iter().map(|m| m.indices.len() / 3).sum();
                        println!(
                            "{name:6} {cam:8} meshes {:3} tris {:6} textures {:2} layers {:2} \
                             tiles {:5} quads {:4} {:?}",
                            s.meshes.len(),
                            tris,
                            s.textures.len(),
                            st.layers_drawn,
                            st.tiles,
                            st.quads,
                            t0.elapsed()
                        );
                        assert!(tris > 0);
                    }
                    Err(e) => failures.push(format!("{name} {cam}: {e}")),
                }
            }
        }
        assert!(failures.is_empty(), "{failures:#?}");
    }
}
