//! Materials and textures: `materials.xml` blend and alpha modes, the
//! output material of each SPM material (found textures, shader
//! template), the index of the shared texture tree, and the textures
//! decoded (in parallel, in order) and downscaled.

use super::*;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct MatProps {
    pub(super) blend: Blend,
    pub(super) unlit: bool,
    pub(super) clamp: bool,
}

pub(super) fn parse_materials(
    path: &Path,
    out: &mut HashMap<String, MatProps>,
) -> Result<(), SceneError> {
    if !path.is_file() {
        return Ok(());
    }
    let text = read_text(path)?;
    let doc = parse_xml(&text, path)?;
    for m in doc.descendants().filter(|n| n.has_tag_name("material")) {
        let Some(name) = m.attribute("name") else {
            continue;
        };
        let shader = m.attribute("shader").unwrap_or("");
        let blend = match shader {
            "alphatest" | "grass" => Blend::AlphaTest,
            "alphablend" | "additive" | "displace" => Blend::AlphaBlend,
            _ => Blend::Opaque,
        };
        out.entry(name.to_string()).or_insert(MatProps {
            blend,
            unlit: shader == "unlit",
            clamp: yes(m, "clampu") && yes(m, "clampv"),
        });
    }
    Ok(())
}

/// Decode an image file to RGBA8, downscaled to at most `max_side`.
pub(super) fn decode_image(path: &Path, max_side: u32) -> Result<(u32, u32, Vec<u8>), SceneError> {
    let bytes =
        std::fs::read(path).map_err(|e| SceneError::in_file(path, format!("cannot read: {e}")))?;
    let img = image::load_from_memory(&bytes)
        .map_err(|e| SceneError::in_file(path, format!("cannot decode image: {e}")))?;
    let mut rgba = img.to_rgba8();
    let (w, h) = rgba.dimensions();
    if w == 0 || h == 0 {
        return Err(SceneError::in_file(path, "empty image"));
    }
    if w.max(h) > max_side {
        let s = max_side as f64 / w.max(h) as f64;
        let nw = ((w as f64 * s).round() as u32).max(1);
        let nh = ((h as f64 * s).round() as u32).max(1);
        rgba = image::imageops::resize(&rgba, nw, nh, image::imageops::FilterType::Triangle);
    }
    let (w, h) = rgba.dimensions();
    Ok((w, h, rgba.into_raw()))
}

/// A decoded image: width, height, RGBA8 texels.
pub(super) type Image = (u32, u32, Vec<u8>);

/// Decodes the image files `paths` ([`decode_image`]) on up to `threads`
/// threads, results in `paths` order; a file named twice is decoded once.
/// The first error in `paths` order, if any.
pub(super) fn decode_images(
    paths: &[PathBuf],
    max_side: u32,
    threads: usize,
) -> Result<Vec<Image>, SceneError> {
    let mut unique: Vec<&PathBuf> = paths.iter().collect();
    unique.sort();
    unique.dedup();
    let next = std::sync::atomic::AtomicUsize::new(0);
    let work = || {
        let mut done = Vec::new();
        loop {
            let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            let Some(p) = unique.get(i) else {
                return done;
            };
            done.push((i, decode_image(p, max_side)));
        }
    };
    let threads = threads.clamp(1, unique.len().max(1));
    let mut results: Vec<(usize, Result<Image, SceneError>)> = if threads > 1 {
        std::thread::scope(|sc| {
            let others: Vec<_> = (1..threads).map(|_| sc.spawn(work)).collect();
            let mut all = work();
            for h in others {
                all.extend(h.join().expect("image decoding thread"));
            }
            all
        })
    } else {
        work()
    };
    results.sort_by_key(|r| r.0);
    let mut decoded: Vec<Option<Result<Image, SceneError>>> =
        results.into_iter().map(|r| Some(r.1)).collect();
    let slot: Vec<usize> = paths
        .iter()
        .map(|p| unique.binary_search(&p).expect("every path is in the list"))
        .collect();
    let mut uses = vec![0usize; unique.len()];
    for &i in &slot {
        uses[i] += 1;
    }
    slot.iter()
        .map(|&i| {
            uses[i] -= 1;
            // The last use takes the texels; earlier ones copy them.
            let r = if uses[i] == 0 {
                decoded[i].take()
            } else {
                decoded[i].clone()
            };
            r.expect("decoded")
        })
        .collect()
}

impl Builder<'_> {
    pub(super) fn mat_props(&self, name: &str) -> MatProps {
        let base = Path::new(name)
            .file_name()
            .map(|f| f.to_string_lossy().into_owned())
            .unwrap_or_default();
        for map in [&self.track_mats, &self.lib_mats, &self.global_mats] {
            if let Some(p) = map.get(&base) {
                return *p;
            }
        }
        MatProps {
            blend: Blend::Opaque,
            unlit: false,
            clamp: false,
        }
    }

    /// Find a texture file: the model's directory, the track, the shared
    /// texture tree.
    pub(super) fn find_texture(&self, name: &str, dir: &Path) -> Option<PathBuf> {
        let file = Path::new(name).file_name()?.to_string_lossy().into_owned();
        for d in [dir, self.track_dir.as_path()] {
            let p = d.join(&file);
            if p.is_file() {
                return Some(p);
            }
        }
        self.tex_index.get(&file.to_ascii_lowercase()).cloned()
    }

    pub(super) fn texture(&mut self, path: &Path, repeat: bool) -> Result<usize, SceneError> {
        let key = (path.to_path_buf(), repeat);
        if let Some(&i) = self.tex_ids.get(&key) {
            return Ok(i);
        }
        let name = path
            .strip_prefix(self.root)
            .unwrap_or(path)
            .to_string_lossy()
            .into_owned();
        // Decoded later, all at once on several threads.
        self.textures.push(Texture {
            name,
            width: 0,
            height: 0,
            rgba: Vec::new(),
            repeat,
        });
        self.tex_paths.push(path.to_path_buf());
        let i = self.textures.len() - 1;
        self.tex_ids.insert(key, i);
        Ok(i)
    }

    /// The material for an SPM material in `dir`; None if it has no usable
    /// texture (then ALU-only), with whether a second UV set is used.
    pub(super) fn material(
        &mut self,
        m: &SpmMaterial,
        dir: &Path,
    ) -> Result<(usize, bool), SceneError> {
        let base = m
            .texture
            .as_deref()
            .and_then(|t| self.find_texture(t, dir).map(|p| (t, p)));
        let Some((base_name, base_path)) = base else {
            if let Some(t) = &m.texture {
                self.missing.push(t.clone());
            }
            return Ok((self.untextured(), false));
        };
        let props = self.mat_props(base_name);
        let second = m
            .texture2
            .as_deref()
            .and_then(|t| self.find_texture(t, dir));
        if let (Some(t), None) = (&m.texture2, &second) {
            self.missing.push(t.clone());
        }
        let key = (
            MatKey::Textured {
                base: base_path.clone(),
                second: second.clone(),
            },
            props.blend as u8,
        );
        if let Some(&i) = self.mat_ids.get(&key) {
            return Ok((i, second.is_some()));
        }
        let t0 = self.texture(&base_path, !props.clamp)?;
        let shader = match &second {
            Some(p) => {
                let t1 = self.texture(p, true)?;
                shader::lightmapped(t0, t1, Filter::Trilinear)
            }
            None if props.unlit => shader::unlit(t0, Filter::Trilinear),
            None => shader::standard(t0, Filter::Trilinear),
        };
        self.materials.push(Material {
            state: None,
            name: base_name.to_string(),
            blend: props.blend,
            shader,
        });
        let i = self.materials.len() - 1;
        self.mat_ids.insert(key, i);
        Ok((i, second.is_some()))
    }

    fn untextured(&mut self) -> usize {
        let key = (MatKey::Untextured, Blend::Opaque as u8);
        if let Some(&i) = self.mat_ids.get(&key) {
            return i;
        }
        self.materials.push(Material {
            state: None,
            name: "untextured (vertex colour)".into(),
            blend: Blend::Opaque,
            shader: vec![ShaderOp::Alu(10)],
        });
        let i = self.materials.len() - 1;
        self.mat_ids.insert(key, i);
        i
    }
}

/// Index image files under `dir` by lower-case file name (first found wins,
/// directories visited in name order).
pub(super) fn index_textures(dir: &Path, out: &mut HashMap<String, PathBuf>, depth: u32) {
    let Ok(rd) = std::fs::read_dir(dir) else {
        return;
    };
    let mut entries: Vec<PathBuf> = rd.flatten().map(|e| e.path()).collect();
    entries.sort();
    let (dirs, files): (Vec<PathBuf>, Vec<PathBuf>) = entries.into_iter().partition(|p| p.is_dir());
    for f in files {
        let ext = f
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
            .unwrap_or_default();
        if matches!(ext.as_str(), "png" | "jpg" | "jpeg") {
            if let Some(n) = f.file_name() {
                out.entry(n.to_string_lossy().to_ascii_lowercase())
                    .or_insert(f.clone());
            }
        }
    }
    if depth < 4 {
        for d in dirs {
            index_textures(&d, out, depth + 1);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn images_decode_in_order_once_each_on_any_number_of_threads() {
        let dir = std::env::temp_dir().join(format!("wasp-stk-decode-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mut paths = Vec::new();
        for (i, name) in ["a.png", "b.png", "c.png"].iter().enumerate() {
            let p = dir.join(name);
            image::RgbaImage::from_pixel(2 + i as u32, 3, image::Rgba([i as u8, 2, 3, 255]))
                .save(&p)
                .unwrap();
            paths.push(p);
        }
        let list = vec![
            paths[1].clone(),
            paths[0].clone(),
            paths[1].clone(),
            paths[2].clone(),
        ];
        let one = decode_images(&list, 1024, 1).unwrap();
        assert_eq!(
            one.iter().map(|d| (d.0, d.2[0])).collect::<Vec<_>>(),
            vec![(3, 1), (2, 0), (3, 1), (4, 2)]
        );
        for threads in [2, 4] {
            assert_eq!(decode_images(&list, 1024, threads).unwrap(), one);
        }
        // The first failure in list order is the error.
        let bad = vec![paths[0].clone(), dir.join("x.png"), dir.join("y.png")];
        let e = decode_images(&bad, 1024, 3).unwrap_err();
        assert!(e.to_string().contains("x.png"), "{e}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
