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

mod camera;
mod datafile;
mod map;
mod materials;
mod mesh;
mod parse;
mod scene;

pub use camera::*;
pub use datafile::*;
pub use map::*;
pub(crate) use materials::*;
use mesh::*;
#[cfg(test)]
use parse::tiny_map;
pub use scene::*;

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

#[cfg(test)]
mod tests;
