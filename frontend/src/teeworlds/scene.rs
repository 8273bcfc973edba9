//! The scene of a map for one camera: groups and layers in the game's
//! render order, tile layers as the tiles the game submits for the view,
//! quad layers with their animated quads placed, parallax applied.

use super::*;

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

#[cfg(test)]
mod tests {
    use super::*;

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
}
