//! Reading a map from its datafile's items: images, envelopes and their
//! points, groups, and tile layers (run-length packed tiles unpacked) and
//! quad layers, each error at the offending item or field.

use super::*;

pub(super) fn field(path: &Path, item: &Item, i: usize, what: &str) -> Result<i32, SceneError> {
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

pub(super) fn field_at(item: &Item, i: usize) -> u64 {
    item.offset + 4 * i as u64
}

/// Decode a name stored as 3 (or more) ints: 4 bytes each, most significant
/// first, each byte offset by 128, NUL-terminated.
pub(super) fn ints_to_str(ints: &[i32]) -> String {
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

pub(super) fn image_index(
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
        let images = df
            .items
            .iter()
            .filter(|i| i.type_id == ITEM_IMAGE)
            .map(|item| parse_image(&df, path, item))
            .collect::<Result<Vec<_>, _>>()?;
        let layers = df
            .items
            .iter()
            .filter(|i| i.type_id == ITEM_LAYER)
            .map(|item| parse_layer(&df, path, item, images.len()))
            .collect::<Result<Vec<_>, _>>()?;
        let envelopes = parse_envelopes(&df, path)?;
        let groups = df
            .items
            .iter()
            .filter(|i| i.type_id == ITEM_GROUP)
            .map(|item| parse_group(path, item, layers.len()))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Map {
            images,
            envelopes,
            groups,
            layers,
        })
    }
}

/// An image item: its size, name (a plain file name when external) and
/// pixel format; the pixels stay in their data block.
fn parse_image(df: &Datafile, path: &Path, item: &Item) -> Result<MapImage, SceneError> {
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
    Ok(MapImage {
        name,
        width: w.max(0) as u32,
        height: h.max(0) as u32,
        external,
        data,
        channels,
        offset: item.offset,
    })
}

/// The envelope items with their points, which every envelope-points item
/// stores concatenated (each envelope names a range of them).
fn parse_envelopes(df: &Datafile, path: &Path) -> Result<Vec<Envelope>, SceneError> {
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
    Ok(envelopes)
}

/// A group item: offset, parallax, its range of the `num_layers` layers,
/// and (by version) its clip rectangle and name.
fn parse_group(path: &Path, item: &Item, num_layers: usize) -> Result<Group, SceneError> {
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
    let (start_layer, group_layers) = match (start, num) {
        (Some(s), Some(n)) if s.saturating_add(n) <= num_layers => (s, n),
        _ => {
            return Err(SceneError::at(
                path,
                field_at(item, 5),
                format!(
                    "group layers {}..{}+{}: the map has {} layers",
                    g[4], g[4], g[5], num_layers
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
    Ok(Group {
        offset: [g[0], g[1]],
        parallax: [g[2], g[3]],
        start_layer,
        num_layers: group_layers,
        clip,
        name,
    })
}

/// A layer item: its type and flags, then the tile or quad layer it holds
/// (any other type is kept as [`LayerKind::Other`]).
pub(super) fn parse_layer(
    df: &Datafile,
    path: &Path,
    item: &Item,
    num_images: usize,
) -> Result<Layer, SceneError> {
    let ltype = field(path, item, 1, "layer type")?;
    let flags = field(path, item, 2, "layer flags")?;
    match ltype {
        LAYER_TILES => parse_tile_layer(df, path, item, flags, num_images),
        LAYER_QUADS => parse_quad_layer(df, path, item, flags, num_images),
        other => Ok(Layer {
            flags,
            name: String::new(),
            kind: LayerKind::Other(other),
        }),
    }
}

/// A tile layer: size, colour, image and its tiles (unpacked by
/// [`unpack_tiles`]).
fn parse_tile_layer(
    df: &Datafile,
    path: &Path,
    item: &Item,
    flags: i32,
    num_images: usize,
) -> Result<Layer, SceneError> {
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
                format!("tile layer is {w}x{h}: expected positive, at most {MAX_TILES} tiles"),
            ))
        }
    };
    let raw = df.data(data, field_at(item, 14), "tile layer data")?;
    let tiles = unpack_tiles(path, item, version, &raw, width, height)?;
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

/// The `width` x `height` tiles of a tile layer's data block: 4 bytes a
/// tile, run-length packed from layer version 4 on (each stored tile
/// stands for `skip + 1` tiles).
fn unpack_tiles(
    path: &Path,
    item: &Item,
    version: i32,
    raw: &[u8],
    width: usize,
    height: usize,
) -> Result<Vec<Tile>, SceneError> {
    let n = width * height;
    if version >= 4 {
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
        if tiles.len() != n || !raw.len().is_multiple_of(4) {
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
        Ok(tiles)
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
        Ok(raw
            .chunks_exact(4)
            .map(|t| Tile {
                index: t[0],
                flags: t[1],
            })
            .collect())
    }
}

/// A quad layer: its image and `num` quads of [`QUAD_BYTES`] each.
fn parse_quad_layer(
    df: &Datafile,
    path: &Path,
    item: &Item,
    flags: i32,
    num_images: usize,
) -> Result<Layer, SceneError> {
    let version = field(path, item, 3, "quad layer version")?;
    let num = field(path, item, 4, "quad count")?;
    let data = field(path, item, 5, "quad data")?;
    let image = image_index(
        path,
        field(path, item, 6, "quad layer image")?,
        field_at(item, 6),
        num_images,
    )?;
    let num = usize::try_from(num)
        .map_err(|_| SceneError::at(path, field_at(item, 4), format!("quad count {num} (< 0)")))?;
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
        .map(decode_quad)
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

/// One quad's [`QUAD_BYTES`]: 5 points, 4 colours and 4 texture coordinates
/// (points and coordinates 22.10 fixed point), then its envelopes.
fn decode_quad(q: &[u8]) -> Quad {
    let int = |i: usize| i32::from_le_bytes([q[4 * i], q[4 * i + 1], q[4 * i + 2], q[4 * i + 3]]);
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
}

#[cfg(test)]
/// A 4x3 map: one embedded 32x32 RGBA tileset, a sky quad group
/// (parallax 0), a game group with a tile layer and the game layer
/// (one spawn at tile (1, 1)).
pub(super) fn tiny_map() -> Vec<u8> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
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
}
