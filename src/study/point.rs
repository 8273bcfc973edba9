//! A point of a study: one scene on one machine, and the key its result is
//! cached under.
//!
//! A point names a scene, a base configuration (`paper`, `paper-width2` or
//! a TOML file) and the overrides ([`Override`]) applied to it in order, and
//! optionally the draw order the scene is rendered in and the format its
//! textures are stored in (default: the scene definition's own). Every
//! other knob a study varies (policy, dispatch, subset, ideal memory,
//! warps, MSHRs) is one of those overrides, so two points that describe the
//! same machine on the same scene resolve to the same effective
//! configuration and share one result.
//!
//! The cache key hashes (64-bit FNV-1a) the scene's identity (its
//! definition with the point's draw order, and the fetched packages'
//! versions), the effective
//! configuration and the identity of the `wasp` binary (a hash of the
//! executable's bytes): a rebuilt simulator never reuses a result of
//! another build.

use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::hash::Hasher;
use std::path::Path;
use std::sync::OnceLock;
use wasp_frontend::def::{Route, SceneDef};
use wasp_frontend::fetch;
use wasp_frontend::raster::DrawOrder;
use wasp_frontend::texture::FormatChoice;
use wasp_sim::config::{MachineConfig, Override};

/// One scene on one machine.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct Point {
    /// Scene name (`wasp scenes list`).
    pub scene: String,
    /// Base configuration: `paper` (configs/paper.toml, embedded),
    /// `paper-width2` (configs/paper-width2.toml, embedded) or a TOML file.
    pub config: String,
    /// Overrides applied in order (as `--set`; written `PATH=VALUE` in
    /// records).
    pub sets: Vec<Override>,
    /// The draw order the scene is rendered in (`None`: the scene
    /// definition's `draw_order`). Points of one scene in two orders run
    /// on two traces and have two keys.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub draw_order: Option<DrawOrder>,
    /// How the scene's textures are stored (`None`: the scene definition's
    /// `texture_format`). Points of one scene in two formats run on two
    /// traces and have two keys.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub texture_format: Option<FormatChoice>,
}

impl Point {
    /// A point on `config` with `sets`.
    pub fn new(scene: &str, config: &str, sets: &[Override]) -> Point {
        Point {
            scene: scene.to_string(),
            config: config.to_string(),
            sets: sets.to_vec(),
            draw_order: None,
            texture_format: None,
        }
    }

    /// The same point on the scene rendered in draw order `order`.
    pub fn drawn(&self, order: DrawOrder) -> Point {
        Point {
            draw_order: Some(order),
            ..self.clone()
        }
    }

    /// The same point on the scene with its textures stored as `format`.
    pub fn stored(&self, format: FormatChoice) -> Point {
        Point {
            texture_format: Some(format),
            ..self.clone()
        }
    }

    /// The scene definition `def` (of [`Point::scene`]) as this point
    /// renders it: with the point's draw order and texture format, where
    /// it names them.
    pub fn scene_def(&self, def: &SceneDef) -> SceneDef {
        SceneDef {
            draw_order: self.draw_order.unwrap_or(def.draw_order),
            texture_format: self.texture_format.unwrap_or(def.texture_format),
            ..def.clone()
        }
    }

    /// The same point with one more override.
    pub fn with(&self, set: Override) -> Point {
        let mut p = self.clone();
        p.sets.push(set);
        p
    }

    /// The same point with field `path` set to `value` (see
    /// [`Override::new`]).
    pub fn set<T: Serialize + ?Sized>(&self, path: &str, value: &T) -> Point {
        self.with(Override::new(path, value))
    }

    /// The value of the last override of field `path`, if any.
    #[cfg(test)]
    pub fn value_of(&self, path: &str) -> Option<&toml::Value> {
        self.sets
            .iter()
            .rev()
            .find(|o| o.path() == path)
            .map(Override::value)
    }

    /// The overrides' texts, separated by spaces.
    pub fn sets_text(&self) -> String {
        let texts: Vec<String> = self.sets.iter().map(Override::to_string).collect();
        texts.join(" ")
    }

    /// `scene config set1 set2 ...` for messages.
    pub fn describe(&self) -> String {
        let mut s = format!("{} on {}", self.scene, self.config);
        if let Some(o) = self.draw_order {
            s.push_str(&format!(" --draw-order {o}"));
        }
        if let Some(f) = self.texture_format {
            s.push_str(&format!(" --texture-format {f}"));
        }
        for x in &self.sets {
            s.push_str(&format!(" --set {x}"));
        }
        s
    }
}

/// The base configuration a point names.
pub fn base_config(name: &str) -> Result<MachineConfig, String> {
    match name {
        "paper" => Ok(MachineConfig::paper()),
        "paper-width2" => Ok(MachineConfig::paper_width2()),
        path => MachineConfig::load(Path::new(path)).map_err(|e| e.to_string()),
    }
}

/// Resolves points to effective configurations, caching base configurations
/// by name.
#[derive(Default)]
pub struct Resolver {
    bases: HashMap<String, MachineConfig>,
}

impl Resolver {
    /// The effective configuration of `p` (base, then every override,
    /// validated).
    pub fn config(&mut self, p: &Point) -> Result<MachineConfig, String> {
        if !self.bases.contains_key(&p.config) {
            let c = base_config(&p.config)?;
            self.bases.insert(p.config.clone(), c);
        }
        let base = &self.bases[&p.config];
        base.with_overrides(&p.sets).map_err(|e| e.to_string())
    }
}

/// A stable 64-bit FNV-1a hash of `parts`, each followed by a NUL byte, as
/// 16 hex digits.
pub fn hash_parts(parts: &[&[u8]]) -> String {
    let mut h = fnv::FnvHasher::default();
    for p in parts {
        h.write(p);
        h.write_u8(0);
    }
    format!("{:016x}", h.finish())
}

/// The identity of the running `wasp` binary: a hash of the executable's
/// bytes (computed once), or the crate version when it cannot be read.
///
/// `WASP_STUDY_BINARY_ID` overrides it: a developer changing only report
/// code can reuse the points of an earlier build by naming its id (the
/// `binary` field of its point records). Results then come from that
/// build, not this one; use it for nothing else.
pub fn binary_id() -> &'static str {
    static ID: OnceLock<String> = OnceLock::new();
    ID.get_or_init(|| {
        if let Some(id) = std::env::var("WASP_STUDY_BINARY_ID")
            .ok()
            .filter(|s| !s.is_empty())
        {
            return id;
        }
        let bytes = std::env::current_exe().and_then(std::fs::read);
        match bytes {
            Ok(b) => hash_parts(&[&b]),
            Err(_) => format!("version-{}", env!("CARGO_PKG_VERSION")),
        }
    })
}

/// The identity of a scene: its definition (the draw order included: see
/// [`Point::scene_def`]) and, for a loader scene of a game, the versions
/// of the packages its data came from; for an engine scene, its capture's
/// sidecar ([`crate::engine_frame::capture_identity`]).
pub fn scene_identity(def: &SceneDef) -> String {
    let mut s = format!("{def:?}");
    if def.route == Route::Engine {
        s.push_str(&crate::engine_frame::capture_identity(def));
        return s;
    }
    if let Some(v) = fetch::fetched_versions(def.game) {
        for (p, ver) in v {
            s.push_str(&format!(" {p}={ver}"));
        }
    }
    s
}

/// The cache key of a point whose scene has identity `scene_id` and whose
/// effective configuration is `cfg`, for the binary `binary`.
pub fn point_key(binary: &str, scene_id: &str, cfg: &MachineConfig) -> String {
    let cfg_json = serde_json::to_string(cfg).expect("configurations serialize");
    hash_parts(&[
        b"wasp-point-1",
        binary.as_bytes(),
        scene_id.as_bytes(),
        cfg_json.as_bytes(),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A point with the `--set` texts `sets`.
    fn point(scene: &str, config: &str, sets: &[&str]) -> Point {
        Point::new(scene, config, &Override::parse_sets(sets).unwrap())
    }

    #[test]
    fn fnv_hash_is_the_published_one() {
        // FNV-1a 64 of "a" is af63dc4c8601ec8c; with the NUL separator the
        // hash is of "a\0".
        let mut h = fnv::FnvHasher::default();
        h.write(b"a");
        assert_eq!(format!("{:016x}", h.finish()), "af63dc4c8601ec8c");
        assert_ne!(hash_parts(&[b"a", b"b"]), hash_parts(&[b"ab"]));
        assert_eq!(hash_parts(&[b"x"]), hash_parts(&[b"x"]));
    }

    #[test]
    fn equal_machines_share_a_key_and_different_ones_do_not() {
        let mut r = Resolver::default();
        let a = point("s", "paper", &["scheduler.policy=\"baseline\""]);
        let b = point(
            "s",
            "paper",
            &["scheduler.policy=\"wasp\"", "scheduler.policy=\"baseline\""],
        );
        let c = point("s", "paper", &["scheduler.policy=\"wasp:2:3\""]);
        let ka = point_key("bin", "scene", &r.config(&a).unwrap());
        let kb = point_key("bin", "scene", &r.config(&b).unwrap());
        let kc = point_key("bin", "scene", &r.config(&c).unwrap());
        assert_eq!(ka, kb);
        assert_ne!(ka, kc);
        assert_ne!(ka, point_key("other-bin", "scene", &r.config(&a).unwrap()));
        assert_ne!(ka, point_key("bin", "scene2", &r.config(&a).unwrap()));
    }

    #[test]
    fn two_draw_orders_of_a_scene_make_two_keys() {
        let def = wasp_frontend::def::lookup("procedural-plane").unwrap();
        let mut r = Resolver::default();
        let p = Point::new("procedural-plane", "paper", &[]);
        let cfg = r.config(&p).unwrap();
        let key = |p: &Point| point_key("bin", &scene_identity(&p.scene_def(&def)), &cfg);
        let ordered = p.drawn(DrawOrder::FrontToBackDraw);
        assert_ne!(key(&p), key(&ordered));
        assert_ne!(key(&ordered), key(&p.drawn(DrawOrder::FrontToBackObject)));
        // Naming the scene's own order is the same scene, the same key.
        assert_eq!(def.draw_order, DrawOrder::AsLoaded);
        assert_eq!(key(&p), key(&p.drawn(DrawOrder::AsLoaded)));
        assert!(ordered
            .describe()
            .starts_with("procedural-plane on paper --draw-order front-to-back-draw"));
        // A point without an order reads and writes as before.
        let json = serde_json::to_string(&p).unwrap();
        assert!(!json.contains("draw_order"), "{json}");
        let back: Point = serde_json::from_str(&serde_json::to_string(&ordered).unwrap()).unwrap();
        assert_eq!(back, ordered);
    }

    #[test]
    fn two_texture_formats_of_a_scene_make_two_keys() {
        let def = wasp_frontend::def::lookup("procedural-plane").unwrap();
        let cfg = Resolver::default()
            .config(&Point::new("procedural-plane", "paper", &[]))
            .unwrap();
        let p = Point::new("procedural-plane", "paper", &[]);
        let key = |p: &Point| point_key("bin", &scene_identity(&p.scene_def(&def)), &cfg);
        // The scene's own format is the etc2 rule.
        let etc2 = p.stored(FormatChoice::Etc2);
        let rgba8 = p.stored(FormatChoice::Rgba8);
        assert_ne!(key(&p), key(&rgba8));
        assert_eq!(key(&p), key(&etc2));
        assert!(etc2.describe().ends_with("--texture-format etc2"));
        let json = serde_json::to_string(&p).unwrap();
        assert!(!json.contains("texture_format"), "{json}");
        let back: Point = serde_json::from_str(&serde_json::to_string(&etc2).unwrap()).unwrap();
        assert_eq!(back, etc2);
    }

    #[test]
    fn bad_overrides_and_configs_are_reported() {
        let mut r = Resolver::default();
        let e = r.config(&point("s", "paper", &["l0.mshrs=0"])).unwrap_err();
        assert!(e.contains("l0.mshrs"), "{e}");
        let e = r
            .config(&Point::new("s", "/nonexistent/x.toml", &[]))
            .unwrap_err();
        assert!(e.contains("/nonexistent/x.toml"), "{e}");
    }
}
