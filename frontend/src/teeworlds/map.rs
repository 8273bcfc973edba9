//! A Teeworlds map inside its datafile: images (embedded or external
//! tilesets), groups with their parallax and offsets, tile and quad
//! layers, and the game layer with its spawn points.

use super::*;

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
    pub(super) offset: u64,
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

impl Map {
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
