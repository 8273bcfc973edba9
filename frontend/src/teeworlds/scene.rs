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

/// Where a group lands for the camera: its clip rectangle (world units),
/// the shift from group space to world space and the screen's top-left
/// corner in group space (parallax applied).
#[derive(Clone, Copy, Debug)]
struct GroupView {
    clip: Option<[f32; 4]>,
    shift: [f32; 2],
    screen: [f32; 2],
}

impl GroupView {
    /// The view of `group` for a camera centred at `center` seeing `vw` x
    /// `vh` world units; `None` for a group clipped to an empty rectangle
    /// (the game draws nothing of it).
    fn new(group: &Group, center: [f32; 2], (vw, vh): (f32, f32)) -> Option<Self> {
        let clip = match group.clip {
            Some([x, y, w, h]) => {
                if w <= 0 || h <= 0 {
                    return None;
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
        Some(Self {
            clip,
            shift,
            screen,
        })
    }
}

/// The scene under construction: the map's images turned into textures on
/// first use, one material per drawn mesh, the meshes in render order.
struct Builder<'a> {
    data_root: &'a Path,
    map_path: &'a Path,
    map_bytes: &'a [u8],
    map: &'a Map,
    template: Option<&'a str>,
    /// The camera's view (world units).
    view: (f32, f32),
    stats: BuildStats,
    textures: Vec<Texture>,
    /// The texture of each map image, once loaded.
    tex_of_image: Vec<Option<usize>>,
    materials: Vec<Material>,
    meshes: Vec<Mesh>,
    /// Layers drawn so far: the depth of the next one, and whether a quad
    /// layer is the background (the first drawn, opaque).
    order: usize,
}

impl Builder<'_> {
    /// The texture of map image `img`, loaded the first time it is asked for.
    fn texture(&mut self, img: usize) -> Result<usize, SceneError> {
        if let Some(t) = self.tex_of_image[img] {
            return Ok(t);
        }
        let t = map_texture(
            self.data_root,
            self.map_path,
            self.map_bytes,
            &self.map.images[img],
        )?;
        self.textures.push(t);
        self.tex_of_image[img] = Some(self.textures.len() - 1);
        Ok(self.textures.len() - 1)
    }

    /// A new material drawing texture `tex` (bilinear) with `blend`.
    fn material(
        &mut self,
        name: String,
        blend: Blend,
        tex: Option<usize>,
    ) -> Result<usize, SceneError> {
        let shader = program(self.template, tex, Filter::Bilinear)
            .map_err(|m| SceneError::in_file(self.map_path, m))?;
        self.materials.push(Material {
            state: None,
            name,
            blend,
            shader,
        });
        Ok(self.materials.len() - 1)
    }

    /// The layers of group `gi` in order (the game layer is not drawn).
    fn group(&mut self, gi: usize, group: &Group, view: GroupView) -> Result<(), SceneError> {
        let map = self.map;
        for li in group.start_layer..group.start_layer + group.num_layers {
            let layer = &map.layers[li];
            let lname = if layer.name.is_empty() {
                format!("g{gi}/l{li}")
            } else {
                format!("g{gi}/l{li} {}", layer.name)
            };
            match &layer.kind {
                LayerKind::Tiles(t) if t.game => {}
                LayerKind::Tiles(t) => self.tile_layer(&lname, t, view)?,
                LayerKind::Quads(q) => self.quad_layer(&lname, q, view)?,
                LayerKind::Other(_) => {}
            }
        }
        Ok(())
    }

    /// A tile layer: the tiles the game submits for the screen, opaque
    /// tiles (of an opaque layer) in one mesh and the rest blended in
    /// another.
    fn tile_layer(
        &mut self,
        lname: &str,
        t: &TileLayer,
        view: GroupView,
    ) -> Result<(), SceneError> {
        let (vw, vh) = self.view;
        let GroupView {
            clip,
            shift,
            screen,
        } = view;
        let z = self.order as f32;
        let tex = t.image.map(|i| self.texture(i)).transpose()?;
        let (tw, th) = tex
            .map(|i| (self.textures[i].width, self.textures[i].height))
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
                self.stats.tiles += 1;
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
            let m = self.material(format!("teeworlds:{lname}:tiles:{tag}"), blend, tex)?;
            self.meshes.extend(b.finish(m));
            drawn = true;
        }
        if drawn {
            self.stats.layers_drawn += 1;
            self.order += 1;
        }
        Ok(())
    }

    /// A quad layer: every quad placed by its position envelope (offset,
    /// rotation about its pivot); opaque only as the first layer drawn.
    fn quad_layer(
        &mut self,
        lname: &str,
        q: &QuadLayer,
        view: GroupView,
    ) -> Result<(), SceneError> {
        let GroupView { clip, shift, .. } = view;
        let z = self.order as f32;
        let tex = q.image.map(|i| self.texture(i)).transpose()?;
        let mut b = MeshBuilder::new(z, clip);
        for quad in &q.quads {
            let c = [0usize, 1, 3, 2];
            let (off, rot) = quad_motion(self.map, quad);
            let pivot = quad.points[4];
            let (sin, cos) = rot.sin_cos();
            let pos = c.map(|k| {
                let (dx, dy) = (quad.points[k][0] - pivot[0], quad.points[k][1] - pivot[1]);
                [
                    pivot[0] + dx * cos - dy * sin + off[0] + shift[0],
                    pivot[1] + dx * sin + dy * cos + off[1] + shift[1],
                ]
            });
            let uv = c.map(|k| quad.uv[k]);
            b.quad(pos, uv);
            self.stats.quads += 1;
            if let Some(ti) = tex {
                if quad.uv.iter().flatten().any(|v| !(0.0..=1.0).contains(v)) {
                    self.textures[ti].repeat = true;
                }
            }
        }
        if !b.indices.is_empty() {
            let blend = if self.order == 0 {
                Blend::Opaque
            } else {
                Blend::AlphaBlend
            };
            let m = self.material(format!("teeworlds:{lname}:quads"), blend, tex)?;
            self.meshes.extend(b.finish(m));
            self.stats.layers_drawn += 1;
            self.order += 1;
        }
        Ok(())
    }
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
    let (vw, vh) = view;
    let mut b = Builder {
        data_root,
        map_path,
        map_bytes,
        map,
        template,
        view,
        stats: BuildStats::default(),
        textures: Vec::new(),
        tex_of_image: vec![None; map.images.len()],
        materials: Vec::new(),
        meshes: Vec::new(),
        order: 0,
    };
    for (gi, group) in map.groups.iter().enumerate() {
        if let Some(gv) = GroupView::new(group, center, view) {
            b.group(gi, group, gv)?;
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
        meshes: b.meshes,
        materials: b.materials,
        textures: b.textures,
        camera: Camera::Ortho {
            left: center[0] - vw / 2.0,
            top: center[1] - vh / 2.0,
            width: vw,
            height: vh,
        },
    };
    Ok((scene, b.stats))
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
