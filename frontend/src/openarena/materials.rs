//! The scene's materials, textures and meshes: images found in the pk3s
//! (TGA, JPEG, PNG; at the engine's upload size, see [`super::upload`];
//! downscaled past [`MAX_TEXTURE_SIDE`]), the shared checkerboard for
//! missing ones, lightmaps, and one material and mesh per (shader,
//! lightmap) as the shader scripts and surface flags say.

use super::*;

pub(super) struct Builder<'a> {
    pub(super) paks: &'a mut Paks,
    pub(super) shaders: HashMap<String, ShaderDef>,
    pub(super) textures: Vec<Texture>,
    pub(super) tex_ids: HashMap<(String, bool, u32), usize>,
    pub(super) missing: Option<usize>,
    pub(super) materials: Vec<Material>,
    pub(super) meshes: Vec<Mesh>,
    pub(super) mat_mesh: HashMap<(usize, i32), Option<usize>>,
    pub(super) lightmap_ids: HashMap<i32, Option<usize>>,
    pub(super) map: String,
    pub(super) missing_names: Vec<String>,
    /// The engine's `r_picmip` the textures are uploaded at (the scene's
    /// `picmip`).
    pub(super) picmip: u32,
}

impl Builder<'_> {
    /// Resolve an image name to a pk3 entry: the name, then `.tga`,
    /// `.jpg`, `.png` in place of its extension.
    fn find_image(&self, name: &str) -> Option<String> {
        let name = name.replace('\\', "/");
        if let Some(n) = self.paks.entry_name(&name) {
            return Some(n.to_string());
        }
        let stem = match name.rfind('.') {
            Some(d) if !name[d..].contains('/') => &name[..d],
            _ => name.as_str(),
        };
        ["tga", "jpg", "png"]
            .iter()
            .find_map(|e| self.paks.entry_name(&format!("{stem}.{e}")))
            .map(str::to_string)
    }

    /// Decode image `entry`; with `picmip`, at the engine's upload size for
    /// that `r_picmip` ([`upload`]), else as stored; downscaled past
    /// [`MAX_TEXTURE_SIDE`].
    fn decode(
        &mut self,
        entry: &str,
        picmip: Option<u32>,
    ) -> Result<(u32, u32, Vec<u8>), SceneError> {
        let bytes = self.paks.read(entry)?;
        let path = self.paks.path_of(entry);
        let (w, h, rgba) = if entry.to_ascii_lowercase().ends_with(".tga") {
            decode_tga(&bytes, &path)?
        } else {
            let img = image::load_from_memory(&bytes)
                .map_err(|e| SceneError::in_file(&path, format!("cannot decode image: {e}")))?;
            let im = img.to_rgba8();
            let (w, h) = im.dimensions();
            (w, h, im.into_raw())
        };
        let (w, h, rgba) = match picmip {
            Some(p) => upload(w, h, rgba, p, &path)?,
            None => (w, h, rgba),
        };
        if w.max(h) > MAX_TEXTURE_SIDE {
            let s = MAX_TEXTURE_SIDE as f64 / w.max(h) as f64;
            let nw = ((w as f64 * s).round() as u32).max(1);
            let nh = ((h as f64 * s).round() as u32).max(1);
            let im = image::RgbaImage::from_raw(w, h, rgba)
                .ok_or_else(|| SceneError::in_file(&path, "image size mismatch"))?;
            let im = image::imageops::resize(&im, nw, nh, image::imageops::FilterType::Triangle);
            return Ok((nw, nh, im.into_raw()));
        }
        Ok((w, h, rgba))
    }

    /// A texture by image name, uploaded as the engine does at the scene's
    /// `r_picmip` if `picmip` (the shader allows it), else at `r_picmip`
    /// 0; the shared checkerboard if it is missing.
    fn texture(&mut self, name: &str, repeat: bool, picmip: bool) -> Result<usize, SceneError> {
        let Some(entry) = self.find_image(name) else {
            self.missing_names.push(name.to_string());
            return Ok(self.missing_texture());
        };
        let levels = if picmip { self.picmip } else { 0 };
        let key = (entry.to_ascii_lowercase(), repeat, levels);
        if let Some(&i) = self.tex_ids.get(&key) {
            return Ok(i);
        }
        let (width, height, rgba) = self.decode(&entry, Some(levels))?;
        self.textures.push(Texture {
            name: entry,
            width,
            height,
            rgba,
            repeat,
        });
        self.tex_ids.insert(key, self.textures.len() - 1);
        Ok(self.textures.len() - 1)
    }

    fn missing_texture(&mut self) -> usize {
        if let Some(i) = self.missing {
            return i;
        }
        let mut rgba = Vec::with_capacity(64 * 64 * 4);
        for y in 0..64 {
            for x in 0..64 {
                let on = ((x / 8) + (y / 8)) % 2 == 0;
                rgba.extend_from_slice(if on {
                    &[255, 255, 255, 255]
                } else {
                    &[64, 64, 64, 255]
                });
            }
        }
        self.textures.push(Texture {
            name: "missing".into(),
            width: 64,
            height: 64,
            rgba,
            repeat: true,
        });
        self.missing = Some(self.textures.len() - 1);
        self.textures.len() - 1
    }

    fn lightmap(&mut self, bsp: &Bsp, lm: i32) -> Result<Option<usize>, SceneError> {
        if lm < 0 {
            return Ok(None);
        }
        if let Some(&t) = self.lightmap_ids.get(&lm) {
            return Ok(t);
        }
        let l = lm as usize;
        let tex = if l < bsp.lightmaps.len() {
            let rgb = &bsp.lightmaps[l];
            let mut rgba = Vec::with_capacity(LIGHTMAP_SIDE * LIGHTMAP_SIDE * 4);
            for p in rgb.chunks_exact(3) {
                rgba.extend_from_slice(&[p[0], p[1], p[2], 255]);
            }
            self.textures.push(Texture {
                name: format!("maps/{}.bsp lightmap {l}", self.map),
                width: LIGHTMAP_SIDE as u32,
                height: LIGHTMAP_SIDE as u32,
                rgba,
                repeat: false,
            });
            Some(self.textures.len() - 1)
        } else {
            let entry = format!("maps/{}/lm_{l:04}.tga", self.map);
            if self.paks.contains(&entry) {
                let (width, height, rgba) = self.decode(&entry, None)?;
                self.textures.push(Texture {
                    name: entry,
                    width,
                    height,
                    rgba,
                    repeat: false,
                });
                Some(self.textures.len() - 1)
            } else {
                None
            }
        };
        self.lightmap_ids.insert(lm, tex);
        Ok(tex)
    }

    /// The mesh for (shader, lightmap); None if not drawn.
    pub(super) fn mesh(
        &mut self,
        bsp: &Bsp,
        shader: usize,
        lm: i32,
    ) -> Result<Option<usize>, SceneError> {
        if let Some(&m) = self.mat_mesh.get(&(shader, lm)) {
            return Ok(m);
        }
        let s = &bsp.shaders[shader];
        let def = self.shaders.get(&s.name.to_ascii_lowercase()).cloned();
        let nodraw = s.flags & SURF_NODRAW != 0
            || s.contents & CONTENTS_FOG != 0
            || def
                .as_ref()
                .is_some_and(|d| d.has("nodraw") || d.has("fog"));
        let sky = s.flags & SURF_SKY != 0 || def.as_ref().is_some_and(|d| d.has("sky"));
        let result = if nodraw || s.name.eq_ignore_ascii_case("noshader") {
            None
        } else if sky {
            // A stage's image follows the shader's nopicmip; the sky box
            // of skyParms is picmipped always.
            let image = def.as_ref().and_then(|d| {
                d.base()
                    .map(|(m, _)| (m.to_string(), !d.nopicmip))
                    .or_else(|| d.farbox.as_ref().map(|f| (format!("{f}_ft.tga"), true)))
            });
            match image {
                Some((img, picmip)) => {
                    let t = self.texture(&img, true, picmip)?;
                    self.materials.push(Material {
                        state: None,
                        name: s.name.clone(),
                        blend: Blend::Opaque,
                        shader: shader::unlit(t, Filter::Trilinear),
                    });
                    let m = self.new_mesh(false);
                    self.meshes[m].sky = true;
                    Some(m)
                }
                None => None,
            }
        } else {
            let (image, clamp, blend, wants_lm) = match &def {
                Some(d) => match d.base() {
                    Some((m, c)) => (m.to_string(), c, d.blend(), d.uses_lightmap()),
                    // Only $lightmap / $whiteimage stages: nothing textured.
                    None => (s.name.clone(), false, d.blend(), d.uses_lightmap()),
                },
                None => (s.name.clone(), false, Blend::Opaque, true),
            };
            let picmip = !def.as_ref().is_some_and(|d| d.nopicmip);
            let t = self.texture(&image, !clamp, picmip)?;
            let lmt = if wants_lm {
                self.lightmap(bsp, lm)?
            } else {
                None
            };
            let (name, program) = match lmt {
                Some(l) => (
                    format!("{} +lightmap {lm}", s.name),
                    shader::lightmapped(t, l, Filter::Trilinear),
                ),
                None => (s.name.clone(), shader::standard(t, Filter::Trilinear)),
            };
            self.materials.push(Material {
                state: None,
                name,
                blend,
                shader: program,
            });
            Some(self.new_mesh(lmt.is_some()))
        };
        self.mat_mesh.insert((shader, lm), result);
        Ok(result)
    }

    fn new_mesh(&mut self, lightmapped: bool) -> usize {
        self.meshes.push(Mesh {
            positions: Vec::new(),
            uv: Vec::new(),
            uv2: lightmapped.then(Vec::new),
            indices: Vec::new(),
            material: self.materials.len() - 1,
            ..Default::default()
        });
        self.meshes.len() - 1
    }
}
