//! A sweep file: a user's grid of scenes x draw orders x texture formats x
//! configurations x dispatch modes x launch policies (docs/sweep.md), and its expansion
//! into points (see
//! [`super::jobs`] for running them one at a time on a cluster).
//!
//! ```toml
//! scenes = ["procedural-plane"]          # or ["all"]
//! policies = ["baseline", "wasp:0:3"]    # scheduler.policy values
//! dispatches = ["shared-tile"]           # optional: default the config's own
//! draw_orders = ["as-loaded", "front-to-back-draw"]  # optional: default the scene's own
//! texture_formats = ["rgba8", "etc2"]    # optional: default the scene's own
//! [[configs]]
//! name = "shipped"                       # the label in the results
//! base = "paper"                         # paper | paper-width2 | a TOML file
//! set = ["l0.mshrs=8"]                   # --set overrides, in order
//! ```
//!
//! Points are numbered from 1 in the order scene, draw order, texture
//! format, configuration, dispatch, policy (the last varies fastest).
//! Everything is checked when the file is read and expanded, before any
//! simulation: unknown fields, scenes, draw orders, texture formats,
//! policies and dispatch modes,
//! duplicate names, missing base files, and every point's effective
//! configuration.

use super::point::{Point, Resolver};
use serde::Deserialize;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use toml::Spanned;
use wasp_frontend::raster::DrawOrder;
use wasp_frontend::texture::FormatChoice;
use wasp_rtl::policy::PolicySpec;
use wasp_sim::config::{Dispatch, MachineConfig, Override};

/// The largest grid a sweep file may describe.
pub const MAX_POINTS: usize = 100_000;

/// The file as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSweep {
    scenes: Spanned<Vec<Spanned<String>>>,
    policies: Spanned<Vec<Spanned<String>>>,
    dispatches: Option<Spanned<Vec<Spanned<String>>>>,
    draw_orders: Option<Spanned<Vec<Spanned<String>>>>,
    texture_formats: Option<Spanned<Vec<Spanned<String>>>>,
    configs: Option<Spanned<Vec<Spanned<RawConfig>>>>,
}

/// A `[[configs]]` entry as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawConfig {
    name: Spanned<String>,
    base: Spanned<String>,
    #[serde(default)]
    set: Vec<Spanned<String>>,
}

/// One `[[configs]]` entry: a named machine.
#[derive(Clone, Debug, PartialEq)]
pub struct ConfigEntry {
    /// The label in the results (unique in the file).
    pub name: String,
    /// `paper`, `paper-width2` or the absolute path of a TOML file.
    pub base: String,
    /// Its overrides (as `--set`), applied in order.
    pub set: Vec<Override>,
    /// The line of the entry in the file.
    pub line: usize,
}

/// A parsed and checked sweep file.
#[derive(Clone, Debug)]
pub struct Sweep {
    /// The file as named on the command line (for messages).
    pub shown: String,
    /// Scene names, in order (`all` expanded).
    pub scenes: Vec<String>,
    /// Machines, in order.
    pub configs: Vec<ConfigEntry>,
    /// Dispatch modes, in order; `[None]` when the file names none (each
    /// configuration's own).
    pub dispatches: Vec<Option<String>>,
    /// Draw orders, in order; `[None]` when the file names none (each
    /// scene's own).
    pub draw_orders: Vec<Option<DrawOrder>>,
    /// Texture formats, in order; `[None]` when the file names none (each
    /// scene's own).
    pub texture_formats: Vec<Option<FormatChoice>>,
    /// Launch policies (`scheduler.policy` values), in order.
    pub policies: Vec<String>,
}

/// One point of a sweep with its labels.
#[derive(Clone, Debug)]
pub struct SweepPoint {
    /// Position in the sweep, from 1.
    pub index: usize,
    /// Scene name.
    pub scene: String,
    /// The configuration entry's name.
    pub config: String,
    /// The effective dispatch mode.
    pub dispatch: String,
    /// The policy as written in the file.
    pub policy: String,
    /// The effective draw order (the file's, else the scene's own).
    pub draw_order: DrawOrder,
    /// The effective texture format (the file's, else the scene's own).
    pub texture_format: FormatChoice,
    /// The point the runner runs.
    pub point: Point,
    /// Its effective configuration (shared by the point's scenes).
    pub machine: Arc<MachineConfig>,
}

impl SweepPoint {
    /// `scene, config NAME, DISPATCH, POLICY` for listings and messages,
    /// with `, draw order ORDER` and `, textures FORMAT` when the point
    /// names them.
    pub fn describe(&self) -> String {
        let mut s = format!(
            "{}, config {}, {}, {}",
            self.scene, self.config, self.dispatch, self.policy
        );
        if let Some(o) = self.point.draw_order {
            s.push_str(&format!(", draw order {o}"));
        }
        if let Some(f) = self.point.texture_format {
            s.push_str(&format!(", textures {f}"));
        }
        s
    }
}

/// Line (from 1) of byte `offset` in `text`.
fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())].matches('\n').count() + 1
}

/// A sweep file's text, for messages that name its lines.
struct SweepFile<'a> {
    text: &'a str,
    shown: &'a str,
    dir: &'a Path,
}

impl SweepFile<'_> {
    /// `FILE:LINE` of byte `offset`.
    fn at(&self, offset: usize) -> String {
        format!("{}:{}", self.shown, line_of(self.text, offset))
    }

    /// A list field is not empty and names nothing twice.
    fn list(&self, field: &str, v: &Spanned<Vec<Spanned<String>>>) -> Result<(), String> {
        if v.get_ref().is_empty() {
            return Err(format!(
                "{}: {field} is empty: name at least one",
                self.at(v.span().start)
            ));
        }
        for (i, x) in v.get_ref().iter().enumerate() {
            let first = v.get_ref()[..i]
                .iter()
                .position(|y| y.get_ref() == x.get_ref());
            if let Some(j) = first {
                return Err(format!(
                    "{}: {field}[{i}] `{}` is listed twice (also {field}[{j}])",
                    self.at(x.span().start),
                    x.get_ref()
                ));
            }
        }
        Ok(())
    }

    /// An optional list field whose values parse as `T`: each value as
    /// written and parsed, or `[None]` when the field is absent (the
    /// configuration keeps its own).
    fn optional<T: std::str::FromStr>(
        &self,
        field: &str,
        v: Option<&Spanned<Vec<Spanned<String>>>>,
    ) -> Result<Vec<Option<(String, T)>>, String>
    where
        T::Err: std::fmt::Display,
    {
        let Some(v) = v else {
            return Ok(vec![None]);
        };
        self.list(field, v)?;
        v.get_ref()
            .iter()
            .enumerate()
            .map(|(i, x)| {
                let parsed = x
                    .get_ref()
                    .parse::<T>()
                    .map_err(|e| format!("{}: {field}[{i}]: {e}", self.at(x.span().start)))?;
                Ok(Some((x.get_ref().clone(), parsed)))
            })
            .collect()
    }

    /// The scenes named (`all`: every one of `known`).
    fn scenes(
        &self,
        raw: &Spanned<Vec<Spanned<String>>>,
        known: &[String],
    ) -> Result<Vec<String>, String> {
        let mut scenes = Vec::new();
        for (i, s) in raw.get_ref().iter().enumerate() {
            let name = s.get_ref();
            if name == "all" {
                if raw.get_ref().len() > 1 {
                    return Err(format!(
                        "{}: scenes: `all` stands for every scene and cannot be listed with others",
                        self.at(s.span().start)
                    ));
                }
                scenes = known.to_vec();
            } else if known.contains(name) {
                scenes.push(name.clone());
            } else {
                return Err(format!(
                    "{}: scenes[{i}]: no scene named `{name}` (see `wasp scenes list`)",
                    self.at(s.span().start)
                ));
            }
        }
        Ok(scenes)
    }

    /// The `[[configs]]` entries, checked: at least one, names unique, base
    /// files present, overrides of the form PATH=VALUE.
    fn configs(
        &self,
        raw: Option<&Spanned<Vec<Spanned<RawConfig>>>>,
    ) -> Result<Vec<ConfigEntry>, String> {
        let raw_configs = match raw {
            Some(c) if !c.get_ref().is_empty() => c.get_ref(),
            Some(c) => {
                return Err(format!(
                    "{}: configs is empty: add at least one [[configs]] entry",
                    self.at(c.span().start)
                ))
            }
            None => {
                return Err(format!(
                    "{}: no [[configs]] entry: add at least one (name, base, set)",
                    self.shown
                ))
            }
        };
        let mut configs: Vec<ConfigEntry> = Vec::new();
        for (i, c) in raw_configs.iter().enumerate() {
            let c = c.get_ref();
            let name = c.name.get_ref();
            let here = self.at(c.name.span().start);
            if name.trim().is_empty() {
                return Err(format!("{here}: configs[{i}].name is empty"));
            }
            if let Some(j) = configs.iter().position(|x| &x.name == name) {
                return Err(format!(
                    "{here}: configs[{i}].name `{name}` is used twice (also configs[{j}], line {})",
                    configs[j].line
                ));
            }
            let base = self.base(i, &c.base)?;
            let mut set = Vec::new();
            for (k, s) in c.set.iter().enumerate() {
                set.push(s.get_ref().parse().map_err(|_| {
                    format!(
                        "{}: configs[{i}].set[{k}] `{}`: expected PATH=VALUE, e.g. l0.mshrs=24",
                        self.at(s.span().start),
                        s.get_ref()
                    )
                })?);
            }
            configs.push(ConfigEntry {
                name: name.clone(),
                base,
                set,
                line: line_of(self.text, c.name.span().start),
            });
        }
        Ok(configs)
    }

    /// The base of entry `i`: `paper`, `paper-width2` or an existing file
    /// (relative to the sweep file's folder), as an absolute path.
    fn base(&self, i: usize, base: &Spanned<String>) -> Result<String, String> {
        match base.get_ref().as_str() {
            b @ ("paper" | "paper-width2") => Ok(b.to_string()),
            b => {
                let p = self.dir.join(b);
                if !p.is_file() {
                    return Err(format!(
                        "{}: configs[{i}].base `{b}`: no such file ({}); a base is paper, \
                         paper-width2 or a TOML file",
                        self.at(base.span().start),
                        p.display()
                    ));
                }
                Ok(p.canonicalize().unwrap_or(p).display().to_string())
            }
        }
    }
}

impl Sweep {
    /// Read and check the sweep file `path` against the scenes of
    /// `wasp scenes list`.
    pub fn load(path: &Path) -> Result<Sweep, String> {
        let shown = path.display().to_string();
        let text =
            std::fs::read_to_string(path).map_err(|e| format!("cannot read {shown}: {e}"))?;
        let abs = std::path::absolute(path).map_err(|e| format!("{shown}: {e}"))?;
        let dir = abs.parent().unwrap_or(Path::new("/")).to_path_buf();
        let defs = wasp_frontend::def::all().map_err(|e| e.to_string())?;
        let known: Vec<String> = defs.into_iter().map(|d| d.name).collect();
        Sweep::parse(&text, &shown, &dir, &known)
    }

    /// Parse and check `text`, the sweep file shown as `shown` in messages,
    /// whose relative base paths are relative to `dir`, with the scene names
    /// `known`.
    pub fn parse(text: &str, shown: &str, dir: &Path, known: &[String]) -> Result<Sweep, String> {
        let raw: RawSweep = toml::from_str(text).map_err(|e| {
            let message = e.message().trim_end().replace('\n', ": ");
            match e.span().map(|s| line_of(text, s.start)) {
                // A missing field is reported at its table: the line says
                // nothing more.
                Some(l) if !message.starts_with("missing field") => {
                    let src = text.lines().nth(l - 1).unwrap_or("").trim();
                    format!("{shown}:{l}: {message} (in `{src}`)")
                }
                Some(l) => format!("{shown}:{l}: {message}"),
                None => format!("{shown}: {message}"),
            }
        })?;
        let f = SweepFile { text, shown, dir };
        f.list("scenes", &raw.scenes)?;
        f.list("policies", &raw.policies)?;
        let scenes = f.scenes(&raw.scenes, known)?;
        let mut policies = Vec::new();
        for (i, p) in raw.policies.get_ref().iter().enumerate() {
            p.get_ref()
                .parse::<PolicySpec>()
                .map_err(|e| format!("{}: policies[{i}]: {e}", f.at(p.span().start)))?;
            policies.push(p.get_ref().clone());
        }
        let dispatches: Vec<Option<String>> = f
            .optional::<Dispatch>("dispatches", raw.dispatches.as_ref())?
            .into_iter()
            .map(|d| d.map(|(text, _)| text))
            .collect();
        let draw_orders: Vec<Option<DrawOrder>> = f
            .optional::<DrawOrder>("draw_orders", raw.draw_orders.as_ref())?
            .into_iter()
            .map(|d| d.map(|(_, o)| o))
            .collect();
        let texture_formats: Vec<Option<FormatChoice>> = f
            .optional::<FormatChoice>("texture_formats", raw.texture_formats.as_ref())?
            .into_iter()
            .map(|d| d.map(|(_, t)| t))
            .collect();
        let configs = f.configs(raw.configs.as_ref())?;
        let sizes = [
            scenes.len(),
            draw_orders.len() * texture_formats.len(),
            configs.len(),
            dispatches.len(),
            policies.len(),
        ];
        let count = sizes.iter().try_fold(1usize, |a, &b| a.checked_mul(b));
        if count.is_none_or(|n| n > MAX_POINTS) {
            return Err(format!(
                "{shown}: {} scenes x {} draw orders x {} texture formats x {} configs x {} \
                 dispatches x {} policies is more than {MAX_POINTS} points: split the sweep into \
                 several files",
                sizes[0],
                draw_orders.len(),
                texture_formats.len(),
                sizes[2],
                sizes[3],
                sizes[4]
            ));
        }
        Ok(Sweep {
            shown: shown.to_string(),
            scenes,
            configs,
            dispatches,
            draw_orders,
            texture_formats,
            policies,
        })
    }

    /// The number of points.
    pub fn len(&self) -> usize {
        self.scenes.len()
            * self.draw_orders.len()
            * self.texture_formats.len()
            * self.configs.len()
            * self.dispatches.len()
            * self.policies.len()
    }

    /// Every point in sweep order, each machine resolved (base, overrides,
    /// dispatch, policy; validated). The first machine that does not
    /// resolve is the error, with its entry, dispatch and policy.
    pub fn points(&self) -> Result<Vec<SweepPoint>, String> {
        let mut resolver = Resolver::default();
        // The machines do not depend on the scene: resolve each once.
        let mut machines = Vec::new();
        for c in &self.configs {
            for d in &self.dispatches {
                for pol in &self.policies {
                    let mut sets = c.set.clone();
                    if let Some(d) = d {
                        sets.push(Override::new("raster.dispatch", d));
                    }
                    sets.push(Override::new("scheduler.policy", pol));
                    let p = Point {
                        scene: String::new(),
                        config: c.base.clone(),
                        sets,
                        draw_order: None,
                        texture_format: None,
                    };
                    let cfg = resolver.config(&p).map_err(|e| {
                        let d = d.as_deref().unwrap_or("its own dispatch");
                        format!(
                            "{}:{}: configs `{}` with {d} and policy {pol}: {e}",
                            self.shown, c.line, c.name
                        )
                    })?;
                    machines.push((c, pol, p, Arc::new(cfg)));
                }
            }
        }
        let mut out = Vec::with_capacity(self.len());
        for scene in &self.scenes {
            // The scene's own order and format, for the points that name
            // none.
            let def =
                wasp_frontend::def::lookup(scene).map_err(|e| format!("{}: {e}", self.shown))?;
            for &order in &self.draw_orders {
                for &format in &self.texture_formats {
                    for (c, pol, p, cfg) in &machines {
                        let mut point = Point {
                            scene: scene.clone(),
                            ..p.clone()
                        };
                        point.draw_order = order;
                        point.texture_format = format;
                        out.push(SweepPoint {
                            index: out.len() + 1,
                            scene: scene.clone(),
                            config: c.name.clone(),
                            dispatch: cfg.raster.dispatch.to_string(),
                            policy: (*pol).clone(),
                            draw_order: order.unwrap_or(def.draw_order),
                            texture_format: format.unwrap_or(def.texture_format),
                            point,
                            machine: cfg.clone(),
                        });
                    }
                }
            }
        }
        Ok(out)
    }
}

/// `N<TAB>description` for every point.
pub fn listing(points: &[SweepPoint]) -> String {
    points
        .iter()
        .map(|p| format!("{}\t{}\n", p.index, p.describe()))
        .collect()
}

/// `path` made absolute against the current directory.
pub fn absolute(path: &Path) -> Result<PathBuf, String> {
    std::path::absolute(path).map_err(|e| format!("{}: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn known() -> Vec<String> {
        ["procedural-plane", "procedural-sprites", "oa-dm1-spawn0"]
            .map(String::from)
            .to_vec()
    }

    fn parse(text: &str) -> Result<Sweep, String> {
        Sweep::parse(text, "sweep.toml", Path::new("/nonexistent"), &known())
    }

    const GOOD: &str = r#"
scenes = ["procedural-plane", "procedural-sprites"]
policies = ["baseline", "fullpriority", "wasp:0:3"]
dispatches = ["shared-tile", "per-core-tile"]
[[configs]]
name = "shipped"
base = "paper"
[[configs]]
name = "l0-8"
base = "paper"
set = ["l0.mshrs=8"]
"#;

    #[test]
    fn points_expand_scene_config_dispatch_policy_in_order() {
        let s = parse(GOOD).unwrap();
        assert_eq!(s.len(), 2 * 2 * 2 * 3);
        let pts = s.points().unwrap();
        assert_eq!(pts.len(), 24);
        assert_eq!(
            (1..=24).collect::<Vec<_>>(),
            pts.iter().map(|p| p.index).collect::<Vec<_>>()
        );
        let p = &pts[0];
        assert_eq!(
            (&*p.scene, &*p.config, &*p.dispatch, &*p.policy),
            ("procedural-plane", "shipped", "shared-tile", "baseline")
        );
        assert_eq!(pts[1].policy, "fullpriority");
        assert_eq!(pts[3].dispatch, "per-core-tile");
        assert_eq!(pts[6].config, "l0-8");
        assert_eq!(pts[12].scene, "procedural-sprites");
        // Overrides: the entry's, then dispatch, then policy.
        assert_eq!(
            pts[11].point,
            Point::new(
                "procedural-plane",
                "paper",
                &Override::parse_sets(&[
                    "l0.mshrs=8",
                    "raster.dispatch=\"per-core-tile\"",
                    "scheduler.policy=\"wasp:0:3\""
                ])
                .unwrap()
            )
        );
        assert_eq!(pts[11].machine.l0.as_ref().map(|l| l.mshrs), Some(8));
        assert_eq!(pts[11].machine.scheduler.policy.to_string(), "wasp:0:3");
        assert_eq!(
            pts[11].describe(),
            "procedural-plane, config l0-8, per-core-tile, wasp:0:3"
        );
        assert!(listing(&pts[..2]).starts_with("1\tprocedural-plane, config shipped, "));
    }

    #[test]
    fn without_dispatches_each_machine_keeps_its_own() {
        let s = parse(
            "scenes = [\"all\"]\npolicies = [\"baseline\"]\n[[configs]]\nname = \"a\"\nbase = \"paper\"\nset = [\"raster.dispatch=\\\"per-core-tile\\\"\"]\n",
        )
        .unwrap();
        assert_eq!(s.scenes, known());
        let pts = s.points().unwrap();
        assert_eq!(pts.len(), 3);
        assert_eq!(pts[0].dispatch, "per-core-tile");
        assert_eq!(pts[0].point.sets.len(), 2);
    }

    #[test]
    fn mistakes_are_named_with_file_line_and_field() {
        let cases: &[(&str, &str)] = &[
            (
                "scenes = [\"procedural-plane\"]\npolicies = [\"baseline\"]\n[[configs]]\nname = \"a\"\nbase = \"paper\"\n[[configs]]\nname = \"a\"\nbase = \"paper\"\n",
                "sweep.toml:7: configs[1].name `a` is used twice (also configs[0], line 4)",
            ),
            (
                "scenes = [\"procedural-plane\", \"nope\"]\npolicies = [\"baseline\"]\n[[configs]]\nname = \"a\"\nbase = \"paper\"\n",
                "sweep.toml:1: scenes[1]: no scene named `nope` (see `wasp scenes list`)",
            ),
            (
                "scenes = [\"procedural-plane\"]\n\npolicies = [\"baseline\", \"sometimes\"]\n[[configs]]\nname = \"a\"\nbase = \"paper\"\n",
                "sweep.toml:3: policies[1]: ",
            ),
            (
                "scenes = []\npolicies = [\"baseline\"]\n[[configs]]\nname = \"a\"\nbase = \"paper\"\n",
                "sweep.toml:1: scenes is empty",
            ),
            (
                "scenes = [\"procedural-plane\"]\npolicies = [\"baseline\"]\n",
                "sweep.toml: no [[configs]] entry",
            ),
            (
                "scenes = [\"procedural-plane\"]\npolicies = \"baseline\"\n",
                "sweep.toml:2: invalid type: string \"baseline\", expected a sequence (in \
                 `policies = \"baseline\"`)",
            ),
            (
                "scenes = [\"procedural-plane\"]\n",
                "sweep.toml:1: missing field `policies`",
            ),
            (
                "scenes = [\"procedural-plane\"]\npolicies = [\"baseline\"]\ndispatches = [\"diagonal\"]\n[[configs]]\nname = \"a\"\nbase = \"paper\"\n",
                "sweep.toml:3: dispatches[0]: unknown dispatch `diagonal`",
            ),
            (
                "scenes = [\"procedural-plane\"]\npolicies = [\"baseline\"]\n[[configs]]\nname = \"a\"\nbase = \"paper\"\nsets = []\n",
                "sweep.toml:6: unknown field `sets`",
            ),
            (
                "scenes = [\"procedural-plane\"]\npolicies = [\"baseline\"]\n[[configs]]\nname = \"a\"\nbase = \"mine.toml\"\n",
                "sweep.toml:5: configs[0].base `mine.toml`: no such file (/nonexistent/mine.toml)",
            ),
            (
                "scenes = [\"procedural-plane\"]\npolicies = [\"baseline\", \"baseline\"]\n[[configs]]\nname = \"a\"\nbase = \"paper\"\n",
                "sweep.toml:2: policies[1] `baseline` is listed twice (also policies[0])",
            ),
            (
                "scenes = [\"all\", \"procedural-plane\"]\npolicies = [\"baseline\"]\n[[configs]]\nname = \"a\"\nbase = \"paper\"\n",
                "sweep.toml:1: scenes: `all` stands for every scene",
            ),
            (
                "scenes = [\"procedural-plane\"]\npolicies = [\"baseline\"]\n[[configs]]\nname = \"a\"\nbase = \"paper\"\nset = [\"l0.mshrs\"]\n",
                "sweep.toml:6: configs[0].set[0] `l0.mshrs`: expected PATH=VALUE",
            ),
        ];
        for (text, want) in cases {
            let e = parse(text).unwrap_err();
            assert!(e.starts_with(want), "got: {e}\nwant: {want}");
        }
    }

    #[test]
    fn draw_orders_vary_after_the_scene_and_are_checked() {
        let s = parse(
            "scenes = [\"procedural-plane\", \"procedural-sprites\"]\ndraw_orders = [\"as-loaded\", \"front-to-back-draw\"]\npolicies = [\"baseline\", \"wasp\"]\n[[configs]]\nname = \"a\"\nbase = \"paper\"\n",
        )
        .unwrap();
        assert_eq!(s.len(), 2 * 2 * 2);
        let pts = s.points().unwrap();
        let orders: Vec<DrawOrder> = pts.iter().map(|p| p.draw_order).collect();
        use DrawOrder::{AsLoaded as A, FrontToBackDraw as D};
        assert_eq!(orders, [A, A, D, D, A, A, D, D]);
        assert_eq!(pts[2].point.draw_order, Some(D));
        assert_eq!(pts[2].point, pts[0].point.drawn(D));
        assert_eq!(
            pts[3].describe(),
            "procedural-plane, config a, shared-tile, wasp, draw order front-to-back-draw"
        );
        assert_eq!(pts[4].scene, "procedural-sprites");
        // Without the list, each scene keeps its own order.
        let pts = parse(GOOD).unwrap().points().unwrap();
        assert!(pts.iter().all(|p| p.point.draw_order.is_none()));
        assert!(pts.iter().all(|p| p.draw_order == A));
        for (text, want) in [
            (
                "scenes = [\"procedural-plane\"]\ndraw_orders = [\"sideways\"]\npolicies = [\"baseline\"]\n[[configs]]\nname = \"a\"\nbase = \"paper\"\n",
                "sweep.toml:2: draw_orders[0]: unknown draw order `sideways` (expected as-loaded, \
                 front-to-back-object or front-to-back-draw)",
            ),
            (
                "scenes = [\"procedural-plane\"]\ndraw_orders = [\"as-loaded\", \"as-loaded\"]\npolicies = [\"baseline\"]\n[[configs]]\nname = \"a\"\nbase = \"paper\"\n",
                "sweep.toml:2: draw_orders[1] `as-loaded` is listed twice (also draw_orders[0])",
            ),
            (
                "scenes = [\"procedural-plane\"]\ndraw_orders = []\npolicies = [\"baseline\"]\n[[configs]]\nname = \"a\"\nbase = \"paper\"\n",
                "sweep.toml:2: draw_orders is empty",
            ),
        ] {
            let e = parse(text).unwrap_err();
            assert!(e.starts_with(want), "got: {e}\nwant: {want}");
        }
    }

    #[test]
    fn texture_formats_vary_after_the_draw_order_and_are_checked() {
        let s = parse(
            "scenes = [\"procedural-plane\"]\ndraw_orders = [\"as-loaded\", \"front-to-back-draw\"]\ntexture_formats = [\"rgba8\", \"etc2\"]\npolicies = [\"baseline\"]\n[[configs]]\nname = \"a\"\nbase = \"paper\"\n",
        )
        .unwrap();
        assert_eq!(s.len(), 2 * 2);
        let pts = s.points().unwrap();
        let formats: Vec<FormatChoice> = pts.iter().map(|p| p.texture_format).collect();
        use FormatChoice::{Etc2 as E, Rgba8 as R};
        assert_eq!(formats, [R, E, R, E]);
        assert_eq!(pts[1].point.texture_format, Some(E));
        assert_eq!(
            pts[3].point,
            pts[0].point.drawn(DrawOrder::FrontToBackDraw).stored(E)
        );
        assert_eq!(
            pts[1].describe(),
            "procedural-plane, config a, shared-tile, baseline, draw order as-loaded, textures etc2"
        );
        // Without the list, each scene keeps its own format (the etc2 rule
        // for the shipped scenes).
        let pts = parse(GOOD).unwrap().points().unwrap();
        assert!(pts.iter().all(|p| p.point.texture_format.is_none()));
        assert!(pts.iter().all(|p| p.texture_format == E));
        for (text, want) in [
            (
                "scenes = [\"procedural-plane\"]\ntexture_formats = [\"dxt1\"]\npolicies = [\"baseline\"]\n[[configs]]\nname = \"a\"\nbase = \"paper\"\n",
                "sweep.toml:2: texture_formats[0]: unknown texture format `dxt1` (expected one of \
                 rgba8, etc2,",
            ),
            (
                "scenes = [\"procedural-plane\"]\ntexture_formats = [\"etc2\", \"etc2\"]\npolicies = [\"baseline\"]\n[[configs]]\nname = \"a\"\nbase = \"paper\"\n",
                "sweep.toml:2: texture_formats[1] `etc2` is listed twice (also texture_formats[0])",
            ),
        ] {
            let e = parse(text).unwrap_err();
            assert!(e.starts_with(want), "got: {e}\nwant: {want}");
        }
    }

    #[test]
    fn an_override_that_does_not_resolve_names_its_machine() {
        let s = parse(
            "scenes = [\"procedural-plane\"]\npolicies = [\"baseline\", \"wasp\"]\n[[configs]]\nname = \"ok\"\nbase = \"paper\"\n[[configs]]\nname = \"bad\"\nbase = \"paper\"\nset = [\"l0.mshrs=0\"]\n",
        )
        .unwrap();
        let e = s.points().unwrap_err();
        assert!(
            e.starts_with(
                "sweep.toml:7: configs `bad` with its own dispatch and policy baseline: "
            ),
            "{e}"
        );
        assert!(e.contains("l0.mshrs"), "{e}");
    }

    #[test]
    fn a_grid_over_the_cap_is_refused_before_expansion() {
        let policies: Vec<String> = (0..400).map(|t| format!("\"wasp:{t}\"")).collect();
        let configs: String = (0..300)
            .map(|i| format!("[[configs]]\nname = \"c{i}\"\nbase = \"paper\"\n"))
            .collect();
        let text = format!(
            "scenes = [\"procedural-plane\"]\npolicies = [{}]\n{configs}",
            policies.join(", ")
        );
        let e = parse(&text).unwrap_err();
        assert!(
            e.contains(
                "1 scenes x 1 draw orders x 1 texture formats x 300 configs x 1 dispatches x \
                 400 policies is more than 100000 points"
            ),
            "{e}"
        );
    }

    #[test]
    fn relative_bases_are_found_beside_the_sweep_file() {
        let d = std::env::temp_dir().join(format!("wasp-sweep-base-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        std::fs::write(d.join("m.toml"), MachineConfig::paper().to_toml()).unwrap();
        let s = Sweep::parse(
            "scenes = [\"procedural-plane\"]\npolicies = [\"baseline\"]\n[[configs]]\nname = \"m\"\nbase = \"m.toml\"\n",
            "x.toml",
            &d,
            &known(),
        )
        .unwrap();
        let base = PathBuf::from(&s.configs[0].base);
        assert!(base.is_absolute() && base.ends_with("m.toml"), "{base:?}");
        assert_eq!(*s.points().unwrap()[0].machine, {
            let mut c = MachineConfig::paper();
            c.scheduler.policy = wasp_rtl::policy::PolicySpec::Baseline;
            c
        });
        let _ = std::fs::remove_dir_all(&d);
    }
}
