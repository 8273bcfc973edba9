//! The scene: the one-player screen at the start of a level as sprites
//! in the game's blit order, one textured quad each (images loaded once,
//! the launcher cropped to its opaque pixels).

use super::*;

fn load_image(gfx: &Path, rel: &str) -> Result<Texture, SceneError> {
    let path = gfx.join(rel);
    let bytes = std::fs::read(&path)
        .map_err(|e| SceneError::in_file(&path, format!("cannot read: {e}")))?;
    let (width, height, rgba) = if rel.ends_with(".gif") {
        decode_gif(&path, &bytes)?
    } else {
        let img = image::load_from_memory_with_format(&bytes, image::ImageFormat::Png)
            .map_err(|e| SceneError::in_file(&path, format!("PNG: {e}")))?
            .to_rgba8();
        let (w, h) = img.dimensions();
        (w, h, img.into_raw())
    };
    if width == 0 || height == 0 {
        return Err(SceneError::in_file(&path, "image has no pixels"));
    }
    Ok(Texture {
        name: format!("gfx/{rel}"),
        width,
        height,
        rgba,
        repeat: false,
    })
}

/// Crop a texture to the bounding box of its non-transparent texels;
/// returns the crop's offset. Fully transparent textures stay as they are.
fn crop_to_alpha(t: &mut Texture) -> (u32, u32) {
    let (w, h) = (t.width as usize, t.height as usize);
    let opaque = |x: usize, y: usize| t.rgba[4 * (y * w + x) + 3] != 0;
    let (mut x0, mut y0, mut x1, mut y1) = (w, h, 0, 0);
    for y in 0..h {
        for x in 0..w {
            if opaque(x, y) {
                x0 = x0.min(x);
                y0 = y0.min(y);
                x1 = x1.max(x + 1);
                y1 = y1.max(y + 1);
            }
        }
    }
    if x0 >= x1 || y0 >= y1 {
        return (0, 0);
    }
    let mut rgba = Vec::with_capacity((x1 - x0) * (y1 - y0) * 4);
    for y in y0..y1 {
        rgba.extend_from_slice(&t.rgba[4 * (y * w + x0)..4 * (y * w + x1)]);
    }
    t.rgba = rgba;
    t.width = (x1 - x0) as u32;
    t.height = (y1 - y0) as u32;
    (x0 as u32, y0 as u32)
}

/// Colours in decreasing frequency (ties: lower colour first).
fn colours_by_frequency(level: &Level) -> Vec<u8> {
    let mut count = [0usize; COLOURS as usize];
    for b in &level.bubbles {
        count[b.colour as usize] += 1;
    }
    let mut c: Vec<u8> = (0..COLOURS).filter(|&c| count[c as usize] > 0).collect();
    c.sort_by_key(|&c| std::cmp::Reverse(count[c as usize]));
    c
}

/// Sprites of a scene under construction: one texture and one material per
/// image file, one quad mesh per sprite, z = draw order.
struct Sprites<'a> {
    gfx: PathBuf,
    lpath: &'a Path,
    template: Option<&'a str>,
    textures: Vec<Texture>,
    materials: Vec<Material>,
    meshes: Vec<Mesh>,
    /// (file, material, texture, crop offset)
    loaded: Vec<(String, usize, usize, (u32, u32))>,
}

impl Sprites<'_> {
    /// The material, texture and crop offset of an image file.
    fn image(
        &mut self,
        rel: &str,
        blend: Blend,
        crop: bool,
    ) -> Result<(usize, usize, (u32, u32)), SceneError> {
        if let Some(e) = self.loaded.iter().find(|e| e.0 == rel) {
            return Ok((e.1, e.2, e.3));
        }
        let mut t = load_image(&self.gfx, rel)?;
        let off = if crop { crop_to_alpha(&mut t) } else { (0, 0) };
        self.textures.push(t);
        let ti = self.textures.len() - 1;
        let shader = program(self.template, Some(ti), Filter::Bilinear)
            .map_err(|m| SceneError::in_file(self.lpath, m))?;
        self.materials.push(Material {
            state: None,
            name: format!("frozen-bubble:{rel}"),
            blend,
            shader,
        });
        let mi = self.materials.len() - 1;
        self.loaded.push((rel.to_string(), mi, ti, off));
        Ok((mi, ti, off))
    }

    /// Size (pixels) of an image file, once cropped.
    fn size(&mut self, rel: &str, blend: Blend) -> Result<(f32, f32), SceneError> {
        let (_, ti, _) = self.image(rel, blend, false)?;
        Ok((
            self.textures[ti].width as f32,
            self.textures[ti].height as f32,
        ))
    }

    /// Draw an image file with its top-left corner (before cropping) at x, y.
    fn draw(
        &mut self,
        rel: &str,
        x: f32,
        y: f32,
        blend: Blend,
        crop: bool,
    ) -> Result<(), SceneError> {
        let (mi, ti, off) = self.image(rel, blend, crop)?;
        let (w, h) = (
            self.textures[ti].width as f32,
            self.textures[ti].height as f32,
        );
        let (x, y) = (x + off.0 as f32, y + off.1 as f32);
        let z = self.meshes.len() as f32;
        self.meshes.push(Mesh {
            positions: vec![[x, y, z], [x + w, y, z], [x + w, y + h, z], [x, y + h, z]],
            uv: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            uv2: None,
            indices: vec![0, 1, 2, 0, 2, 3],
            material: mi,
            ..Default::default()
        });
        Ok(())
    }
}

impl Sprites<'_> {
    /// The playfield: the background, the compressor (centred on
    /// `COMPRESSOR_X`, its bottom at the playfield top) and the level's
    /// bubbles.
    fn playfield(&mut self, level: &Level) -> Result<(), SceneError> {
        let ab = Blend::AlphaBlend;
        self.draw("back_one_player.png", 0.0, 0.0, Blend::Opaque, false)?;
        let (cw, ch) = self.size("compressor_main.png", ab)?;
        self.draw(
            "compressor_main.png",
            COMPRESSOR_X - (cw / 2.0).floor(),
            TOP_LIMIT - ch,
            ab,
            false,
        )?;
        for b in &level.bubbles {
            let (x, y) = bubble_position(b.col, b.row);
            self.draw(
                &format!("balls/bubble-{}.gif", b.colour + 1),
                x,
                y,
                ab,
                false,
            )?;
        }
        Ok(())
    }

    /// The progress dots (shots until a new row: `TIME_APPEARS_NEW_ROOT`
    /// + 1 of them): one red, then green ones, one pixel apart.
    fn progress_dots(&mut self) -> Result<(), SceneError> {
        let ab = Blend::AlphaBlend;
        for i in 0..=TIME_APPEARS_NEW_ROOT {
            let dot = if i == 0 {
                "dot_red.png"
            } else {
                "dot_green.png"
            };
            // Dots one pixel apart.
            let (_, dh) = self.size(dot, ab)?;
            self.draw(
                dot,
                PROGRESS.0,
                PROGRESS.1 + (dh + 1.0) * i as f32,
                ab,
                false,
            )?;
        }
        Ok(())
    }

    /// The launcher: the next bubble under its cover, the bubble to launch
    /// (the level's most frequent colour; the next one is the second),
    /// the shooter (cropped) and the penguin.
    fn launcher(&mut self, level: &Level) -> Result<(), SceneError> {
        let ab = Blend::AlphaBlend;
        let colours = colours_by_frequency(level);
        let launch = colours.first().copied().unwrap_or(0);
        let next = colours.get(1).copied().unwrap_or(launch);
        self.draw(
            &format!("balls/bubble-{}.gif", next + 1),
            NEXT_BUBBLE.0,
            NEXT_BUBBLE.1,
            ab,
            false,
        )?;
        self.draw(
            "on_top_next.png",
            NEXT_BUBBLE.0 + ON_TOP_NEXT_REL.0,
            NEXT_BUBBLE.1 + ON_TOP_NEXT_REL.1,
            ab,
            false,
        )?;
        self.draw(
            &format!("balls/bubble-{}.gif", launch + 1),
            (LEFT_LIMIT + RIGHT_LIMIT) / 2.0 - BUBBLE_SIZE / 2.0,
            INITIAL_BUBBLE_Y,
            ab,
            false,
        )?;
        self.draw("shooter.png", CANON.0, CANON.1, ab, true)?;
        self.draw(
            "pinguins/anime-shooter_p1_0020.png",
            PENGUIN.0,
            PENGUIN.1,
            ab,
            false,
        )
    }
}

/// The scene of level `n` (`level`, read from `lpath`): the one-player
/// screen's sprites in the game's blit order.
pub(super) fn build(
    data_root: &Path,
    lpath: &Path,
    level: &Level,
    n: usize,
    def: &SceneDef,
) -> Result<Scene, SceneError> {
    let mut s = Sprites {
        gfx: data_root.join("gfx"),
        lpath,
        template: def.shader.as_deref(),
        textures: Vec::new(),
        materials: Vec::new(),
        meshes: Vec::new(),
        loaded: Vec::new(),
    };
    s.playfield(level)?;
    s.progress_dots()?;
    s.launcher(level)?;
    let (left, top, width, height) = screen_view(def.width as f32 / def.height as f32);
    Ok(Scene {
        name: format!("frozen-bubble:{}:level:{n}", def.map),
        source: format!(
            "{PACKAGE} 2.212 (Debian), data/{} level {n} and gfx/ (GPL-2)",
            def.map
        ),
        meshes: s.meshes,
        materials: s.materials,
        textures: s.textures,
        camera: Camera::Ortho {
            left,
            top,
            width,
            height,
        },
    })
}
