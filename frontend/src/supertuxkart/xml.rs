//! SuperTuxKart's scene files: the Irrlicht object transforms, the XML
//! helpers, and the digest of a `scene.xml` (what to place where).

use super::*;

/// An affine transform: `p' = m p + t` (column vectors).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Xf {
    pub(super) m: [[f32; 3]; 3],
    pub(super) t: Vec3,
}

impl Xf {
    pub(super) const IDENTITY: Xf = Xf {
        m: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        t: [0.0; 3],
    };

    /// `T + Rz Ry Rx S` from xyz, hpr (degrees) and scale.
    pub(super) fn from_parts(xyz: Vec3, hpr: Vec3, scale: Vec3) -> Xf {
        let (sx, cx) = hpr[0].to_radians().sin_cos();
        let (sy, cy) = hpr[1].to_radians().sin_cos();
        let (sz, cz) = hpr[2].to_radians().sin_cos();
        let rx = [[1.0, 0.0, 0.0], [0.0, cx, -sx], [0.0, sx, cx]];
        let ry = [[cy, 0.0, sy], [0.0, 1.0, 0.0], [-sy, 0.0, cy]];
        let rz = [[cz, -sz, 0.0], [sz, cz, 0.0], [0.0, 0.0, 1.0]];
        let r = mat_mul(&rz, &mat_mul(&ry, &rx));
        let mut m = r;
        for row in &mut m {
            for (c, v) in row.iter_mut().enumerate() {
                *v *= scale[c];
            }
        }
        Xf { m, t: xyz }
    }

    pub(super) fn apply(&self, p: Vec3) -> Vec3 {
        let m = &self.m;
        [
            m[0][0] * p[0] + m[0][1] * p[1] + m[0][2] * p[2] + self.t[0],
            m[1][0] * p[0] + m[1][1] * p[1] + m[1][2] * p[2] + self.t[1],
            m[2][0] * p[0] + m[2][1] * p[1] + m[2][2] * p[2] + self.t[2],
        ]
    }

    /// `self` after `inner`.
    pub(super) fn then(&self, inner: &Xf) -> Xf {
        Xf {
            m: mat_mul(&self.m, &inner.m),
            t: self.apply(inner.t),
        }
    }

    pub(super) fn det(&self) -> f32 {
        let m = &self.m;
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    }
}

pub(super) fn mat_mul(a: &[[f32; 3]; 3], b: &[[f32; 3]; 3]) -> [[f32; 3]; 3] {
    let mut o = [[0.0; 3]; 3];
    for (i, row) in o.iter_mut().enumerate() {
        for (j, v) in row.iter_mut().enumerate() {
            *v = (0..3).map(|k| a[i][k] * b[k][j]).sum();
        }
    }
    o
}

/// SuperTuxKart (left-handed) to wasp (right-handed) coordinates.
pub(super) fn to_rh(p: Vec3) -> Vec3 {
    [p[0], p[1], -p[2]]
}

// ---------------------------------------------------------------------------
// XML helpers

pub(super) fn read_text(path: &Path) -> Result<String, SceneError> {
    let bytes =
        std::fs::read(path).map_err(|e| SceneError::in_file(path, format!("cannot read: {e}")))?;
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}

pub(super) fn parse_xml<'a>(
    text: &'a str,
    file: &Path,
) -> Result<roxmltree::Document<'a>, SceneError> {
    roxmltree::Document::parse(text).map_err(|e| {
        let p = e.pos();
        let offset: usize = text
            .split_inclusive('\n')
            .take(p.row.saturating_sub(1) as usize)
            .map(str::len)
            .sum::<usize>()
            + p.col.saturating_sub(1) as usize;
        SceneError::at(file, offset as u64, format!("bad XML: {e}"))
    })
}

pub(super) fn floats(
    node: roxmltree::Node,
    attr: &str,
    file: &Path,
) -> Result<Option<Vec<f32>>, SceneError> {
    let Some(s) = node.attribute(attr) else {
        return Ok(None);
    };
    s.split_whitespace()
        .map(|w| {
            w.parse::<f32>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    SceneError::at(
                        file,
                        node.range().start as u64,
                        format!("<{}> {attr}=\"{s}\": not a list of numbers", tag(node)),
                    )
                })
        })
        .collect::<Result<Vec<_>, _>>()
        .map(Some)
}

pub(super) fn vec3_attr(
    node: roxmltree::Node,
    attr: &str,
    file: &Path,
) -> Result<Option<Vec3>, SceneError> {
    match floats(node, attr, file)? {
        None => Ok(None),
        Some(v) if v.len() == 3 => Ok(Some([v[0], v[1], v[2]])),
        Some(v) if v.len() == 1 => Ok(Some([v[0]; 3])),
        Some(_) => Err(SceneError::at(
            file,
            node.range().start as u64,
            format!("<{}> {attr}: expected 3 numbers", tag(node)),
        )),
    }
}

pub(super) fn f32_attr(
    node: roxmltree::Node,
    attr: &str,
    file: &Path,
) -> Result<Option<f32>, SceneError> {
    match floats(node, attr, file)? {
        None => Ok(None),
        Some(v) if v.len() == 1 => Ok(Some(v[0])),
        Some(_) => Err(SceneError::at(
            file,
            node.range().start as u64,
            format!("<{}> {attr}: expected one number", tag(node)),
        )),
    }
}

pub(super) fn tag<'a>(node: roxmltree::Node<'a, '_>) -> &'a str {
    node.tag_name().name()
}

pub(super) fn yes(node: roxmltree::Node, attr: &str) -> bool {
    matches!(
        node.attribute(attr).map(str::trim),
        Some("Y" | "y" | "true" | "1" | "yes")
    )
}

/// Position: `xyz` or `x`/`y`/`z`.
pub(super) fn position(node: roxmltree::Node, file: &Path) -> Result<Vec3, SceneError> {
    if let Some(p) = vec3_attr(node, "xyz", file)? {
        return Ok(p);
    }
    Ok([
        f32_attr(node, "x", file)?.unwrap_or(0.0),
        f32_attr(node, "y", file)?.unwrap_or(0.0),
        f32_attr(node, "z", file)?.unwrap_or(0.0),
    ])
}

/// The node's transform: position, `hpr` (or heading `h` about Y), `scale`.
pub(super) fn transform(node: roxmltree::Node, file: &Path) -> Result<Xf, SceneError> {
    let xyz = position(node, file)?;
    let hpr = match vec3_attr(node, "hpr", file)? {
        Some(r) => r,
        None => [0.0, f32_attr(node, "h", file)?.unwrap_or(0.0), 0.0],
    };
    let s = vec3_attr(node, "scale", file)?.unwrap_or([1.0; 3]);
    Ok(Xf::from_parts(xyz, hpr, s))
}

/// The `if` condition of an object, for a normal race (not reversed, not
/// CTF, not networked, nothing locked, no flooding, doors closed).
pub(super) fn condition_holds(cond: Option<&str>) -> bool {
    let Some(c) = cond.map(str::trim) else {
        return true;
    };
    !matches!(
        c,
        "false"
            | "isTrackReverse"
            | "isReverse"
            | "isCTF"
            | "hasFlooding"
            | "showDoorOpen"
            | "isEasterEgg"
    ) && !c.starts_with("isLocked")
}

// ---------------------------------------------------------------------------
// Scene description (digested XML)

#[derive(Clone, Debug)]
pub(super) enum Item {
    Model {
        path: PathBuf,
        xf: Xf,
    },
    Lod {
        /// (distance, model), ascending.
        levels: Vec<(f32, PathBuf)>,
        xf: Xf,
    },
    Library {
        name: String,
        xf: Xf,
    },
    Billboard {
        dir: PathBuf,
        texture: String,
        width: f32,
        height: f32,
        xf: Xf,
    },
}

/// A `scene.xml` or `node.xml`, reduced to what the loader uses.
#[derive(Clone, Debug, Default)]
pub(super) struct Digest {
    pub(super) items: Vec<Item>,
    pub(super) sky: Option<Vec<String>>,
    pub(super) starts: Vec<(Vec3, f32)>,
    pub(super) default_start: Option<(usize, f32, f32, f32)>,
    pub(super) cutscene_cameras: Vec<Vec3>,
}

/// The LOD groups of a file (`<group name>` elements): name -> levels
/// (`lod_distance`, model), ascending by distance.
fn lod_groups(
    doc: &roxmltree::Document,
    file: &Path,
    dir: &Path,
) -> Result<HashMap<String, Vec<(f32, PathBuf)>>, SceneError> {
    let mut groups: HashMap<String, Vec<(f32, PathBuf)>> = HashMap::new();
    for g in doc.descendants().filter(|n| n.has_tag_name("group")) {
        let Some(name) = g.attribute("name") else {
            continue;
        };
        let mut levels = Vec::new();
        for o in g.children().filter(|n| n.is_element()) {
            if let (Some(m), Some(dist)) = (
                o.attribute("model").filter(|m| !m.is_empty()),
                f32_attr(o, "lod_distance", file)?,
            ) {
                levels.push((dist, dir.join(m)));
            }
        }
        levels.sort_by(|a, b| a.0.total_cmp(&b.0));
        groups.insert(name.to_string(), levels);
    }
    Ok(groups)
}

/// A file being digested: where it is, its LOD groups and the digest so
/// far.
struct Digester<'a> {
    file: &'a Path,
    /// The file's directory (models are relative to it).
    dir: &'a Path,
    data_root: &'a Path,
    groups: HashMap<String, Vec<(f32, PathBuf)>>,
    d: Digest,
}

impl Digester<'_> {
    /// Digest element `n` (its `if` condition holding); a `<track>`'s
    /// children go on `stack` to be digested next, in order.
    fn element<'d, 'i>(
        &mut self,
        n: roxmltree::Node<'d, 'i>,
        stack: &mut Vec<roxmltree::Node<'d, 'i>>,
    ) -> Result<(), SceneError> {
        let file = self.file;
        match tag(n) {
            "track" => {
                self.model(n)?;
                let mut kids: Vec<_> = n.children().filter(|c| c.is_element()).collect();
                kids.reverse();
                stack.extend(kids);
            }
            "static-object" | "object" => self.object(n)?,
            "water" => self.model(n)?,
            "library" => {
                if let Some(name) = n.attribute("name") {
                    self.d.items.push(Item::Library {
                        name: name.to_string(),
                        xf: transform(n, file)?,
                    });
                }
            }
            "item" | "banana" | "small-nitro" | "big-nitro" => self.race_item(n)?,
            "sky-box" | "sky-dome" => {
                if let Some(t) = n.attribute("texture") {
                    let names: Vec<String> = t.split_whitespace().map(str::to_string).collect();
                    if !names.is_empty() {
                        self.d.sky = Some(names);
                    }
                }
            }
            "start" => {
                self.d
                    .starts
                    .push((position(n, file)?, f32_attr(n, "h", file)?.unwrap_or(0.0)));
            }
            "default-start" => {
                self.d.default_start = Some((
                    f32_attr(n, "karts-per-row", file)?
                        .unwrap_or(2.0)
                        .clamp(1.0, 16.0) as usize,
                    f32_attr(n, "forwards-distance", file)?.unwrap_or(1.5),
                    f32_attr(n, "sidewards-distance", file)?.unwrap_or(3.0),
                    f32_attr(n, "upwards-distance", file)?.unwrap_or(0.1),
                ));
            }
            _ => {}
        }
        Ok(())
    }

    /// The `model` of a `<track>` or `<water>` element, placed by its
    /// transform (nothing without a model).
    fn model(&mut self, n: roxmltree::Node) -> Result<(), SceneError> {
        if let Some(m) = n.attribute("model").filter(|m| !m.is_empty()) {
            self.d.items.push(Item::Model {
                path: self.dir.join(m),
                xf: transform(n, self.file)?,
            });
        }
        Ok(())
    }

    /// A `<static-object>` or `<object>`: a cutscene camera, a billboard,
    /// a LOD instance or a model; emitters, triggers and physics-only
    /// objects are skipped.
    fn object(&mut self, n: roxmltree::Node) -> Result<(), SceneError> {
        let file = self.file;
        let ty = n.attribute("type").unwrap_or("");
        let inter = n.attribute("interaction").unwrap_or("");
        if ty == "cutscene_camera" {
            self.d.cutscene_cameras.push(position(n, file)?);
            return Ok(());
        }
        if matches!(
            ty,
            "sfx-emitter" | "action-trigger" | "static_follow_kart" | "particle-emitter"
        ) || matches!(inter, "physics-only" | "physicsonly")
        {
            return Ok(());
        }
        let xf = transform(n, file)?;
        if ty == "billboard" {
            if let Some(t) = n.attribute("texture") {
                self.d.items.push(Item::Billboard {
                    dir: self.dir.to_path_buf(),
                    texture: t.to_string(),
                    width: f32_attr(n, "width", file)?.unwrap_or(1.0),
                    height: f32_attr(n, "height", file)?.unwrap_or(1.0),
                    xf,
                });
            }
            return Ok(());
        }
        if yes(n, "lod_instance") {
            if let Some(levels) = n.attribute("lod_group").and_then(|g| self.groups.get(g)) {
                self.d.items.push(Item::Lod {
                    levels: levels.clone(),
                    xf,
                });
                return Ok(());
            }
        }
        if let Some(m) = n.attribute("model").filter(|m| !m.is_empty()) {
            self.d.items.push(Item::Model {
                path: self.dir.join(m),
                xf,
            });
        }
        Ok(())
    }

    /// A race item (gift box, banana, nitro can) with its model from
    /// `data/models`; CTF-only items are skipped.
    fn race_item(&mut self, n: roxmltree::Node) -> Result<(), SceneError> {
        if yes(n, "ctf") {
            return Ok(());
        }
        let model = match tag(n) {
            "item" => "gift-box.spm",
            "banana" => "banana.spm",
            "small-nitro" => "nitrotank-small.spm",
            _ => "nitrotank-big.spm",
        };
        self.d.items.push(Item::Model {
            path: self.data_root.join("models").join(model),
            xf: transform(n, self.file)?,
        });
        Ok(())
    }
}

/// Digest a `scene.xml` or a library's `node.xml` (`file`, in `dir`): its
/// elements in document order, a `<track>`'s children where it stands,
/// those whose `if` condition fails for a normal race skipped.
pub(super) fn digest(file: &Path, dir: &Path, data_root: &Path) -> Result<Digest, SceneError> {
    let text = read_text(file)?;
    let doc = parse_xml(&text, file)?;
    let mut g = Digester {
        file,
        dir,
        data_root,
        groups: lod_groups(&doc, file, dir)?,
        d: Digest::default(),
    };
    let root = doc.root_element();
    let mut stack: Vec<roxmltree::Node> = root.children().filter(|n| n.is_element()).collect();
    stack.reverse();
    while let Some(n) = stack.pop() {
        if condition_holds(n.attribute("if")) {
            g.element(n, &mut stack)?;
        }
    }
    Ok(g.d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn transforms_follow_irrlicht_euler_order() {
        // Heading 90 about Y turns +Z into +X; X rotation first, then Y.
        let x = Xf::from_parts([1.0, 2.0, 3.0], [0.0, 90.0, 0.0], [1.0; 3]);
        let p = x.apply([0.0, 0.0, 1.0]);
        assert!(
            (p[0] - 2.0).abs() < 1e-5 && (p[1] - 2.0).abs() < 1e-5 && (p[2] - 3.0).abs() < 1e-5
        );
        let x = Xf::from_parts([0.0; 3], [90.0, 90.0, 0.0], [2.0, 1.0, 1.0]);
        // (0,1,0) -X90-> (0,0,1) -Y90-> (1,0,0).
        let p = x.apply([0.0, 1.0, 0.0]);
        assert!(
            (p[0] - 1.0).abs() < 1e-5 && p[1].abs() < 1e-5 && p[2].abs() < 1e-5,
            "{p:?}"
        );
        // Scale applies first.
        let p = x.apply([1.0, 0.0, 0.0]);
        assert!((len(p) - 2.0).abs() < 1e-5);
        let a = Xf::from_parts([1.0, 0.0, 0.0], [0.0, 30.0, 10.0], [1.0; 3]);
        let b = Xf::from_parts([0.0, 5.0, 0.0], [20.0, 0.0, 0.0], [1.5; 3]);
        let q = [0.3, -0.7, 2.0];
        let (c1, c2) = (a.then(&b).apply(q), a.apply(b.apply(q)));
        assert!(len(sub(c1, c2)) < 1e-4);
    }

    #[test]
    fn conditions_for_a_normal_race() {
        assert!(condition_holds(None));
        assert!(condition_holds(Some("isTrackNotReverse")));
        assert!(condition_holds(Some("isNotCTF")));
        assert!(!condition_holds(Some("isTrackReverse")));
        assert!(!condition_holds(Some("isLocked(gp1)")));
        assert!(!condition_holds(Some("false")));
    }
}
