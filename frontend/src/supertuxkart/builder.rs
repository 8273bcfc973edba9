//! The track under construction: the models, billboards and library
//! instances of a scene digest placed in world space (LOD levels chosen
//! by distance from the eye), merged into one mesh per material, and the
//! sky cube around the eye.

use super::*;

/// Key of an output material.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub(super) enum MatKey {
    Textured {
        base: PathBuf,
        second: Option<PathBuf>,
    },
    Untextured,
    Sky(PathBuf),
}

pub(super) struct Builder<'a> {
    pub(super) root: &'a Path,
    pub(super) track_dir: PathBuf,
    pub(super) track_mats: HashMap<String, MatProps>,
    pub(super) lib_mats: HashMap<String, MatProps>,
    pub(super) global_mats: HashMap<String, MatProps>,
    pub(super) tex_index: HashMap<String, PathBuf>,
    pub(super) spm_cache: HashMap<PathBuf, Rc<Spm>>,
    pub(super) lib_cache: HashMap<String, Rc<Digest>>,
    pub(super) eye: Vec3,
    pub(super) cam_right: Vec3,
    pub(super) cam_up: Vec3,
    /// Textures, their texels decoded at the end ([`decode_images`]).
    pub(super) textures: Vec<Texture>,
    /// The image file of each texture.
    pub(super) tex_paths: Vec<PathBuf>,
    pub(super) tex_ids: HashMap<(PathBuf, bool), usize>,
    pub(super) materials: Vec<Material>,
    pub(super) mat_ids: HashMap<(MatKey, u8), usize>,
    pub(super) meshes: Vec<Mesh>,
    pub(super) missing: Vec<String>,
    /// Objects placed so far: the id of the next one (a placed model or
    /// billboard is one object, each of its mesh buffers a draw call).
    pub(super) objects: u32,
}

impl<'a> Builder<'a> {
    /// An empty track in `track_dir` seen from `eye` (right-handed), the
    /// track's and the shared `materials.xml` read and the shared textures
    /// indexed.
    pub(super) fn new(root: &'a Path, track_dir: &Path, eye: Vec3) -> Result<Self, SceneError> {
        let mut b = Builder {
            root,
            track_dir: track_dir.to_path_buf(),
            track_mats: HashMap::new(),
            lib_mats: HashMap::new(),
            global_mats: HashMap::new(),
            tex_index: HashMap::new(),
            spm_cache: HashMap::new(),
            lib_cache: HashMap::new(),
            eye,
            cam_right: [1.0, 0.0, 0.0],
            cam_up: [0.0, 1.0, 0.0],
            textures: Vec::new(),
            tex_paths: Vec::new(),
            tex_ids: HashMap::new(),
            materials: Vec::new(),
            mat_ids: HashMap::new(),
            meshes: Vec::new(),
            missing: Vec::new(),
            objects: 0,
        };
        parse_materials(&track_dir.join("materials.xml"), &mut b.track_mats)?;
        parse_materials(
            &root.join("textures").join("materials.xml"),
            &mut b.global_mats,
        )?;
        index_textures(&root.join("textures"), &mut b.tex_index, 0);
        Ok(b)
    }

    /// Decode every texture's image (in parallel), downscaled to
    /// [`MAX_TEXTURE_SIDE`].
    pub(super) fn decode_textures(&mut self) -> Result<(), SceneError> {
        let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
        let images = decode_images(&self.tex_paths, MAX_TEXTURE_SIDE, threads)?;
        for (t, (width, height, rgba)) in self.textures.iter_mut().zip(images) {
            (t.width, t.height, t.rgba) = (width, height, rgba);
        }
        Ok(())
    }

    /// The output mesh of a material (created on first use).
    pub(super) fn mesh_for(&mut self, material: usize, with_uv2: bool) -> usize {
        if let Some(i) = self.meshes.iter().position(|m| m.material == material) {
            return i;
        }
        self.meshes.push(Mesh {
            positions: Vec::new(),
            uv: Vec::new(),
            uv2: with_uv2.then(Vec::new),
            indices: Vec::new(),
            material,
            ..Default::default()
        });
        self.meshes.len() - 1
    }

    /// A new object's id.
    fn new_object(&mut self) -> u32 {
        self.objects += 1;
        self.objects - 1
    }

    fn spm(&mut self, path: &Path) -> Result<Rc<Spm>, SceneError> {
        if let Some(s) = self.spm_cache.get(path) {
            return Ok(s.clone());
        }
        let bytes = std::fs::read(path)
            .map_err(|e| SceneError::in_file(path, format!("cannot read: {e}")))?;
        let s = Rc::new(parse_spm(&bytes, path)?);
        self.spm_cache.insert(path.to_path_buf(), s.clone());
        Ok(s)
    }

    fn add_model(&mut self, path: &Path, xf: &Xf) -> Result<(), SceneError> {
        let spm = self.spm(path)?;
        let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
        // A mirroring transform flips the winding; so does the z flip.
        let flip = xf.det() > 0.0;
        let object = self.new_object();
        for b in &spm.buffers {
            let (mat, uv2) = self.material(&spm.materials[b.material], &dir)?;
            let mi = self.mesh_for(mat, uv2);
            let mesh = &mut self.meshes[mi];
            let base = mesh.positions.len() as u32;
            mesh.positions
                .extend(b.positions.iter().map(|p| to_rh(xf.apply(*p))));
            match &b.uv {
                Some(uv) => mesh.uv.extend_from_slice(uv),
                None => mesh
                    .uv
                    .extend(std::iter::repeat_n([0.0, 0.0], b.positions.len())),
            }
            if let Some(out) = mesh.uv2.as_mut() {
                match &b.uv2 {
                    Some(uv2) => out.extend_from_slice(uv2),
                    None => out.extend(std::iter::repeat_n([0.0, 0.0], b.positions.len())),
                }
            }
            mesh.draws.push(Draw {
                triangles: (b.indices.len() / 3) as u32,
                object,
            });
            for t in b.indices.chunks_exact(3) {
                if flip {
                    mesh.indices
                        .extend_from_slice(&[base + t[0], base + t[2], base + t[1]]);
                } else {
                    mesh.indices
                        .extend_from_slice(&[base + t[0], base + t[1], base + t[2]]);
                }
            }
        }
        Ok(())
    }

    fn add_billboard(
        &mut self,
        dir: &Path,
        texture: &str,
        w: f32,
        h: f32,
        xf: &Xf,
    ) -> Result<(), SceneError> {
        let Some(path) = self.find_texture(texture, dir) else {
            return Ok(());
        };
        let mut props = self.mat_props(texture);
        if props.blend == Blend::Opaque {
            props.blend = Blend::AlphaBlend;
        }
        let key = (
            MatKey::Textured {
                base: path.clone(),
                second: None,
            },
            props.blend as u8,
        );
        let mat = match self.mat_ids.get(&key) {
            Some(&i) => i,
            None => {
                let t = self.texture(&path, false)?;
                self.materials.push(Material {
                    state: None,
                    name: texture.to_string(),
                    blend: props.blend,
                    shader: shader::standard(t, Filter::Trilinear),
                });
                self.mat_ids.insert(key, self.materials.len() - 1);
                self.materials.len() - 1
            }
        };
        let c = to_rh(xf.t);
        let (r, u) = (scale(self.cam_right, w * 0.5), scale(self.cam_up, h * 0.5));
        let object = self.new_object();
        let mi = self.mesh_for(mat, false);
        let mesh = &mut self.meshes[mi];
        mesh.draws.push(Draw {
            triangles: 2,
            object,
        });
        let base = mesh.positions.len() as u32;
        mesh.positions.extend_from_slice(&[
            sub(sub(c, r), u),
            sub(add(c, r), u),
            add(add(c, r), u),
            add(sub(c, r), u),
        ]);
        mesh.uv
            .extend_from_slice(&[[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]]);
        if let Some(uv2) = mesh.uv2.as_mut() {
            uv2.extend_from_slice(&[[0.0; 2]; 4]);
        }
        mesh.indices
            .extend_from_slice(&[base, base + 1, base + 2, base, base + 2, base + 3]);
        Ok(())
    }

    fn library(&mut self, name: &str) -> Result<Option<Rc<Digest>>, SceneError> {
        if let Some(d) = self.lib_cache.get(name) {
            return Ok(Some(d.clone()));
        }
        let dir = self.root.join("library").join(name);
        let file = dir.join("node.xml");
        if !file.is_file() {
            return Ok(None);
        }
        let mut mats = HashMap::new();
        parse_materials(&dir.join("materials.xml"), &mut mats)?;
        for (k, v) in mats {
            self.lib_mats.entry(k).or_insert(v);
        }
        let d = Rc::new(digest(&file, &dir, self.root)?);
        self.lib_cache.insert(name.to_string(), d.clone());
        Ok(Some(d))
    }

    pub(super) fn place(
        &mut self,
        items: &[Item],
        parent: &Xf,
        depth: u32,
    ) -> Result<(), SceneError> {
        for it in items {
            match it {
                Item::Model { path, xf } => {
                    if path.is_file() {
                        self.add_model(path, &parent.then(xf))?;
                    }
                }
                Item::Lod { levels, xf } => {
                    let w = parent.then(xf);
                    let d = len(sub(to_rh(w.t), self.eye));
                    if let Some((_, path)) = levels.iter().find(|(ld, _)| *ld >= d) {
                        if path.is_file() {
                            self.add_model(path, &w)?;
                        }
                    }
                }
                Item::Library { name, xf } => {
                    if depth < MAX_LIBRARY_DEPTH {
                        if let Some(d) = self.library(name)? {
                            self.place(&d.items, &parent.then(xf), depth + 1)?;
                        }
                    }
                }
                Item::Billboard {
                    dir,
                    texture,
                    width,
                    height,
                    xf,
                } => {
                    let w = parent.then(xf);
                    self.add_billboard(dir, texture, *width, *height, &w)?;
                }
            }
        }
        Ok(())
    }

    /// The sky cube around the eye; `names` has 6 textures (top, bottom,
    /// left, right, front, back) or one for every face.
    pub(super) fn add_sky(&mut self, names: &[String]) -> Result<(), SceneError> {
        let pick = |i: usize| &names[if names.len() >= 6 { i } else { 0 }];
        let s = SKY_HALF_SIZE;
        let e = self.eye;
        // Faces in right-handed coordinates (z already flipped), each as
        // (corner, u axis, v axis) seen from inside, v = 0 at the top.
        let faces: [(Vec3, Vec3, Vec3); 6] = [
            ([-s, s, -s], [2.0 * s, 0.0, 0.0], [0.0, 0.0, 2.0 * s]), // top (+y)
            ([-s, -s, s], [2.0 * s, 0.0, 0.0], [0.0, 0.0, -2.0 * s]), // bottom (-y)
            ([s, s, -s], [0.0, 0.0, 2.0 * s], [0.0, -2.0 * s, 0.0]), // left (+x)
            ([-s, s, s], [0.0, 0.0, -2.0 * s], [0.0, -2.0 * s, 0.0]), // right (-x)
            ([-s, s, s], [2.0 * s, 0.0, 0.0], [0.0, -2.0 * s, 0.0]), // front (+z)
            ([s, s, -s], [-2.0 * s, 0.0, 0.0], [0.0, -2.0 * s, 0.0]), // back (-z)
        ];
        for (i, (c, u, v)) in faces.iter().enumerate() {
            let name = pick(i).clone();
            let Some(path) = self.find_texture(&name, &self.track_dir.clone()) else {
                continue;
            };
            let key = (MatKey::Sky(path.clone()), Blend::Opaque as u8);
            let mat = match self.mat_ids.get(&key) {
                Some(&m) => m,
                None => {
                    let t = self.texture(&path, false)?;
                    self.materials.push(Material {
                        state: None,
                        name: format!("sky {name}"),
                        blend: Blend::Opaque,
                        shader: shader::unlit(t, Filter::Bilinear),
                    });
                    self.mat_ids.insert(key, self.materials.len() - 1);
                    self.materials.len() - 1
                }
            };
            let p0 = add(e, *c);
            let pts = [p0, add(p0, *u), add(add(p0, *u), *v), add(p0, *v)];
            // Seen from inside: make the winding counter-clockwise there.
            let n = cross(sub(pts[1], pts[0]), sub(pts[3], pts[0]));
            let inward = sub(e, p0);
            let idx: [u32; 6] = if n[0] * inward[0] + n[1] * inward[1] + n[2] * inward[2] > 0.0 {
                [0, 1, 2, 0, 2, 3]
            } else {
                [0, 2, 1, 0, 3, 2]
            };
            self.meshes.push(Mesh {
                positions: pts.to_vec(),
                uv: vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
                uv2: None,
                indices: idx.to_vec(),
                material: mat,
                sky: true,
                ..Default::default()
            });
        }
        Ok(())
    }
}
