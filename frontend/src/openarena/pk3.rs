//! The pk3 file system: zip archives layered in name order, later
//! ones overriding earlier ones, plus loose files.

use super::*;

/// The `.pk3` archives of the game, indexed by lower-case entry name.
pub struct Paks {
    pub(super) archives: Vec<(PathBuf, zip::ZipArchive<File>)>,
    pub(super) index: HashMap<String, (usize, String)>,
}

impl Paks {
    /// Open every `baseoa/*.pk3` of the data root (and of the sibling
    /// package directories, see the module documentation).
    pub fn open(data_root: &Path) -> Result<Paks, SceneError> {
        let mut dirs = vec![data_root.join("baseoa")];
        // <cache>/<package>/usr/share/games/openarena: siblings.
        if let Some(cache) = data_root.ancestors().nth(5) {
            for p in PACKAGES {
                let d = cache.join(p).join("usr/share/games/openarena/baseoa");
                if !dirs.contains(&d) {
                    dirs.push(d);
                }
            }
        }
        let mut pk3s: Vec<PathBuf> = Vec::new();
        for d in &dirs {
            let Ok(rd) = std::fs::read_dir(d) else {
                continue;
            };
            let mut here: Vec<PathBuf> = rd.flatten().map(|e| e.path()).collect();
            here.sort();
            for p in here {
                let is_pk3 = p.extension().is_some_and(|x| x.eq_ignore_ascii_case("pk3"));
                if is_pk3 && !pk3s.iter().any(|q| q.file_name() == p.file_name()) {
                    pk3s.push(p);
                }
            }
        }
        if pk3s.is_empty() {
            return Err(SceneError::in_file(
                data_root.join("baseoa"),
                "no .pk3 files (the data root is <package root>/usr/share/games/openarena, holding baseoa/)",
            ));
        }
        pk3s.sort_by(|a, b| a.file_name().cmp(&b.file_name()).then(a.cmp(b)));
        let mut paks = Paks {
            archives: Vec::new(),
            index: HashMap::new(),
        };
        for p in pk3s {
            let f =
                File::open(&p).map_err(|e| SceneError::in_file(&p, format!("cannot open: {e}")))?;
            let z = zip::ZipArchive::new(f)
                .map_err(|e| SceneError::in_file(&p, format!("bad pk3 (zip): {e}")))?;
            let ai = paks.archives.len();
            for name in z.file_names() {
                if !name.ends_with('/') {
                    paks.index
                        .insert(name.to_ascii_lowercase(), (ai, name.to_string()));
                }
            }
            paks.archives.push((p, z));
        }
        Ok(paks)
    }

    /// Whether an entry exists.
    pub fn contains(&self, name: &str) -> bool {
        self.index.contains_key(&name.to_ascii_lowercase())
    }

    /// An entry's name as stored (its case), if it exists.
    pub fn entry_name(&self, name: &str) -> Option<&str> {
        self.index
            .get(&name.to_ascii_lowercase())
            .map(|(_, n)| n.as_str())
    }

    /// Entry names (original case) matching a filter.
    pub fn names(&self, keep: impl Fn(&str) -> bool) -> Vec<String> {
        let mut v: Vec<String> = self
            .index
            .values()
            .map(|(_, n)| n.clone())
            .filter(|n| keep(n))
            .collect();
        v.sort();
        v
    }

    /// The path naming an entry in errors: `<pk3>/<entry>`.
    pub fn path_of(&self, name: &str) -> PathBuf {
        match self.index.get(&name.to_ascii_lowercase()) {
            Some((ai, n)) => self.archives[*ai].0.join(n),
            None => PathBuf::from(name),
        }
    }

    /// Read an entry.
    pub fn read(&mut self, name: &str) -> Result<Vec<u8>, SceneError> {
        let (ai, entry) = self
            .index
            .get(&name.to_ascii_lowercase())
            .cloned()
            .ok_or_else(|| SceneError::in_file(name, "not found in any pk3"))?;
        let (path, z) = &mut self.archives[ai];
        let full = path.join(&entry);
        let mut f = z
            .by_name(&entry)
            .map_err(|e| SceneError::in_file(&full, format!("cannot read from pk3: {e}")))?;
        let mut out = Vec::with_capacity(f.size().min(1 << 28) as usize);
        f.read_to_end(&mut out)
            .map_err(|e| SceneError::in_file(&full, format!("cannot inflate: {e}")))?;
        Ok(out)
    }
}

/// Every map (`maps/<name>.bsp` in the pk3s), sorted.
pub fn maps(data_root: &Path) -> Result<Vec<String>, SceneError> {
    let paks = Paks::open(data_root)?;
    let mut v: Vec<String> = paks
        .names(|n| {
            let l = n.to_ascii_lowercase();
            l.starts_with("maps/") && l.ends_with(".bsp") && !l[5..].contains('/')
        })
        .into_iter()
        .map(|n| n[5..n.len() - 4].to_string())
        .collect();
    v.sort();
    v.dedup();
    Ok(v)
}
