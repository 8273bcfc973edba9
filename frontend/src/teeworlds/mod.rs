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

mod datafile;
mod map;

pub use datafile::*;
pub use map::*;

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

    /// The real data root in the scene cache, if it holds `maps/dm1.map`.
    fn real_data_root() -> Option<PathBuf> {
        crate::fetch::cached_data_root(crate::def::Game::Teeworlds, "maps/dm1.map")
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
