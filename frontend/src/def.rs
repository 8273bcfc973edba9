//! Scene definitions: small TOML files under `scenes/` naming a game, a
//! map, a camera, a resolution and (optionally) a shader template.
//!
//! ```toml
//! name = "stk-lighthouse-start"
//! game = "supertuxkart"         # supertuxkart | openarena | teeworlds | frozen-bubble | procedural
//! map = "lighthouse"            # the track, map, level or procedural scene
//! camera = "start:0"            # loader-specific camera selector (see each loader)
//! width = 1960
//! height = 768
//! description = "Lighthouse track, behind the first start position"
//! draw_order = "as-loaded"      # optional: as-loaded (default) | front-to-back-object | front-to-back-draw
//! texture_format = "etc2"       # optional: etc2 (default) | rgba8 | etc2-rgb | etc2-rgba | astc-4x4 | astc-6x6 | astc-8x8
//! route = "loader"              # optional: loader (default) | engine (OpenArena, Teeworlds)
//! fov = "engine"                # optional, OpenArena loader only: engine (default) | 4:3
//! picmip = 1                    # optional, OpenArena loader only: 0..=16 (default 1)
//! sky = "first"                 # optional, OpenArena loader only: first (default) | as-loaded
//! vis = "pvs"                   # optional, OpenArena loader only: pvs (default) | all
//! ```
//!
//! `fov` and `picmip` make the OpenArena loader see what the game's engine
//! sees (docs/scenes.md, "The loaders against the engine"): by default its
//! camera has the engine's field of view at the scene's width and height
//! (`cg_fov 90` across the frame) and its textures the engine's upload
//! sizes at `r_picmip 1`, it draws the sky before the rest and only the
//! faces in the eye's potentially visible set, as the engine does.
//! `fov = "4:3"` (wasp) keeps the loader's earlier camera, 73.74 degrees
//! up whatever the aspect (90 across at 4:3), `picmip = 0` (wasp) the
//! images at their stored sizes (all of the shipped scenes' images have
//! power-of-two sides), `sky = "as-loaded"` (wasp) the sky in the order
//! of first use and `vis = "all"` (wasp) every face of the map, so that
//! results measured before the loader followed the engine can be drawn
//! again.
//!
//! The route says where the scene's draw calls come from: `loader` (the
//! default) re-reads the game's data with wasp's loader; `engine` runs the
//! game's own engine headless under apitrace (`wasp scenes capture`), for
//! the games whose engines are fixed-function GL (OpenArena, Teeworlds).
//!
//! A scene's textures are stored by the `etc2` rule unless it names a
//! format (docs/textures.md: what a mobile port ships); an engine scene's
//! follow the rule from the draw state the engine set.
//! [`all`] lists the loader-route scenes (what `sweep` draws); [`every`]
//! lists both routes (what `scenes list`, `characterize` and `reproduce`
//! take).

use super::raster::DrawOrder;
use super::texture::FormatChoice;
use super::SceneError;
use serde::{Deserialize, Serialize};
use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// The games wasp loads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Game {
    /// SuperTuxKart (3D racing): `supertuxkart-data`.
    Supertuxkart,
    /// OpenArena (3D shooter): `openarena-data`, `openarena-081-maps`,
    /// `openarena-081-textures`.
    Openarena,
    /// Teeworlds (2D platformer): `teeworlds-data`.
    Teeworlds,
    /// Frozen Bubble (2D puzzle): `frozen-bubble-data`.
    FrozenBubble,
    /// Procedural scenes that need no download.
    Procedural,
}

impl Game {
    /// Every game.
    pub const ALL: [Game; 5] = [
        Game::Supertuxkart,
        Game::Openarena,
        Game::Teeworlds,
        Game::FrozenBubble,
        Game::Procedural,
    ];

    /// The Debian packages holding the game's data.
    pub fn packages(self) -> &'static [&'static str] {
        match self {
            Game::Supertuxkart => &["supertuxkart-data"],
            Game::Openarena => &[
                "openarena-data",
                "openarena-081-maps",
                "openarena-081-textures",
            ],
            Game::Teeworlds => &["teeworlds-data"],
            Game::FrozenBubble => &["frozen-bubble-data"],
            Game::Procedural => &[],
        }
    }

    /// The name used in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Game::Supertuxkart => "supertuxkart",
            Game::Openarena => "openarena",
            Game::Teeworlds => "teeworlds",
            Game::FrozenBubble => "frozen-bubble",
            Game::Procedural => "procedural",
        }
    }
}

impl fmt::Display for Game {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Where a scene's draw calls come from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Route {
    /// wasp's loader re-reads the game's data (the default).
    #[default]
    Loader,
    /// The game's own engine, run headless under apitrace
    /// (`wasp scenes capture`).
    Engine,
}

impl Route {
    /// The name in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Route::Loader => "loader",
            Route::Engine => "engine",
        }
    }

    /// The games whose engine wasp can capture: fixed-function OpenGL 1.x
    /// engines packaged by Debian.
    pub const ENGINE_GAMES: [Game; 2] = [Game::Openarena, Game::Teeworlds];
}

/// The OpenArena loader's field of view (`fov` in scene files).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum OaFov {
    /// The engine's: its default `cg_fov 90` across the frame's width, the
    /// vertical angle from the aspect
    /// ([`super::openarena::fov_y_deg`]; the default).
    #[default]
    #[serde(rename = "engine")]
    Engine,
    /// (wasp) The loader's camera before it followed the engine: 73.74
    /// degrees up ([`super::openarena::FOV_Y_4_3_DEG`], 90 across at 4:3)
    /// at any aspect.
    #[serde(rename = "4:3")]
    FourThree,
}

/// Where the OpenArena loader puts the sky in its draw order (`sky` in
/// scene files).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum OaSky {
    /// Before everything else, as the engine draws it (its sky shaders sort
    /// before the opaque ones; the default).
    #[default]
    First,
    /// (wasp) Where its shader is first used among the opaque meshes: the
    /// loader's order before it followed the engine.
    AsLoaded,
}

/// Which faces the OpenArena loader draws (`vis` in scene files).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum OaVis {
    /// The faces of the leaves in the potentially visible set of the
    /// eye's cluster, as the engine draws them (the default; see
    /// `frontend/src/openarena/vis.rs`).
    #[default]
    Pvs,
    /// (wasp) Every face of the map: the loader before it followed the
    /// engine.
    All,
}

/// The largest `picmip` a scene file may name: the engine's range for
/// `r_picmip` (0 to 16).
pub const MAX_PICMIP: u32 = 16;

impl fmt::Display for Route {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// One scene definition.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneDef {
    /// Unique name (also the file stem).
    pub name: String,
    /// Game.
    pub game: Game,
    /// Track, map, level or procedural scene name.
    pub map: String,
    /// Loader-specific camera selector.
    pub camera: String,
    /// Frame width in pixels.
    pub width: u32,
    /// Frame height in pixels.
    pub height: u32,
    /// What the scene shows.
    #[serde(default)]
    pub description: String,
    /// Shader template override (see [`super::shader`]); default per material.
    #[serde(default)]
    pub shader: Option<String>,
    /// Order of the opaque geometry ([`DrawOrder`]: `as-loaded`, the
    /// default, `front-to-back-object` or `front-to-back-draw`).
    #[serde(default)]
    pub draw_order: DrawOrder,
    /// How the scene's textures are stored ([`FormatChoice`]: the `etc2`
    /// rule, the default, `rgba8`, or one format for all; see
    /// docs/textures.md). An engine scene's are `rgba8`.
    #[serde(default)]
    pub texture_format: FormatChoice,
    /// Where the draw calls come from ([`Route`]: `loader`, the default,
    /// or `engine`).
    #[serde(default)]
    pub route: Route,
    /// OpenArena loader only: its field of view ([`OaFov`]; `None`: the
    /// engine's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fov: Option<OaFov>,
    /// OpenArena loader only: the engine's `r_picmip` the textures are
    /// sized by, 0 to [`MAX_PICMIP`] (`None`: the engine's default, 1; 0
    /// keeps the stored size of every image whose sides are powers of
    /// two).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub picmip: Option<u32>,
    /// OpenArena loader only: where the sky is drawn ([`OaSky`]; `None`:
    /// first, as the engine draws it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sky: Option<OaSky>,
    /// OpenArena loader only: which faces are drawn ([`OaVis`]; `None`:
    /// the potentially visible set, as the engine draws them).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vis: Option<OaVis>,
}

impl SceneDef {
    /// Parse a definition; `source` names it in errors.
    pub fn parse(text: &str, source: &Path) -> Result<Self, SceneError> {
        let d: SceneDef = toml::from_str(text)
            .map_err(|e| SceneError::in_file(source, e.to_string().trim_end().to_string()))?;
        if d.width == 0 || d.height == 0 || d.width > 16384 || d.height > 16384 {
            return Err(SceneError::in_file(
                source,
                format!(
                    "width x height = {}x{}: each must be in 1..=16384",
                    d.width, d.height
                ),
            ));
        }
        if d.name.is_empty() || d.name.contains(char::is_whitespace) {
            return Err(SceneError::in_file(
                source,
                format!("name {:?}: must be non-empty, without spaces", d.name),
            ));
        }
        if d.route == Route::Engine && !Route::ENGINE_GAMES.contains(&d.game) {
            let games: Vec<&str> = Route::ENGINE_GAMES.iter().map(|g| g.name()).collect();
            return Err(SceneError::in_file(
                source,
                format!(
                    "route = \"engine\" with game = \"{}\": only {} have an engine wasp can \
                     capture (fixed-function OpenGL); use route = \"loader\"",
                    d.game,
                    games.join(" and ")
                ),
            ));
        }
        d.check_openarena_options(source)?;
        Ok(d)
    }

    /// `fov`, `picmip`, `sky` and `vis` are options of the OpenArena loader: an error
    /// naming the file and the field on another game, on an engine scene
    /// (whose camera and textures are the engine's own), or past the
    /// engine's `r_picmip` range.
    fn check_openarena_options(&self, source: &Path) -> Result<(), SceneError> {
        let named: Vec<&str> = [
            ("fov", self.fov.is_some()),
            ("picmip", self.picmip.is_some()),
            ("sky", self.sky.is_some()),
            ("vis", self.vis.is_some()),
        ]
        .iter()
        .filter(|(_, set)| *set)
        .map(|(n, _)| *n)
        .collect();
        if let Some(field) = named.first() {
            if self.game != Game::Openarena {
                return Err(SceneError::in_file(
                    source,
                    format!(
                        "{field} with game = \"{}\": {field} is an option of the openarena loader only",
                        self.game
                    ),
                ));
            }
            if self.route == Route::Engine {
                return Err(SceneError::in_file(
                    source,
                    format!(
                        "{field} with route = \"engine\": the engine's capture has its own camera and \
                         textures; {field} is an option of the loader route only"
                    ),
                ));
            }
        }
        match self.picmip {
            Some(p) if p > MAX_PICMIP => Err(SceneError::in_file(
                source,
                format!("picmip = {p}: must be in 0..={MAX_PICMIP} (the engine's r_picmip range)"),
            )),
            _ => Ok(()),
        }
    }

    /// The OpenArena loader's field of view (the engine's unless `fov`
    /// says otherwise).
    pub fn oa_fov(&self) -> OaFov {
        self.fov.unwrap_or_default()
    }

    /// The `r_picmip` the OpenArena loader sizes textures by (the engine's
    /// default, 1, unless `picmip` says otherwise).
    pub fn oa_picmip(&self) -> u32 {
        self.picmip.unwrap_or(1)
    }

    /// Where the OpenArena loader draws the sky (first, as the engine does,
    /// unless `sky` says otherwise).
    pub fn oa_sky(&self) -> OaSky {
        self.sky.unwrap_or_default()
    }

    /// Which faces the OpenArena loader draws (the potentially visible
    /// set, as the engine does, unless `vis` says otherwise).
    pub fn oa_vis(&self) -> OaVis {
        self.vis.unwrap_or_default()
    }

    /// Read a definition file.
    pub fn load(path: &Path) -> Result<Self, SceneError> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| SceneError::in_file(path, format!("cannot read: {e}")))?;
        Self::parse(&text, path)
    }
}

/// A folder of extra scene definitions set by the front end
/// (`--scenes-dir`), read before `WASP_SCENES_DIR`.
static EXTRA_DIR: OnceLock<PathBuf> = OnceLock::new();

/// Name the folder of extra scene definitions (`--scenes-dir`); the first
/// call wins.
pub fn set_scenes_dir(dir: PathBuf) {
    let _ = EXTRA_DIR.set(dir);
}

/// The folder of extra scene definitions: `--scenes-dir`, else the
/// `WASP_SCENES_DIR` environment variable, else none. (`WASP_SCENES` names
/// the cache of fetched game data, not definitions.)
pub fn scenes_dir() -> Option<PathBuf> {
    EXTRA_DIR.get().cloned().or_else(|| {
        std::env::var_os("WASP_SCENES_DIR")
            .filter(|v| !v.is_empty())
            .map(PathBuf::from)
    })
}

/// Every loader-route scene definition of [`every`]: the scenes `sweep`
/// draws, sorted by name.
pub fn all() -> Result<Vec<SceneDef>, SceneError> {
    let mut defs = every()?;
    defs.retain(|d| d.route == Route::Loader);
    Ok(defs)
}

/// Every scene definition of both routes: the shipped ones embedded in the
/// binary ([`super::builtin::BUILTIN`]), then those of [`scenes_dir`], which
/// add scenes or replace a shipped one of the same name; sorted by name.
pub fn every() -> Result<Vec<SceneDef>, SceneError> {
    let mut defs: Vec<SceneDef> = super::builtin::BUILTIN
        .iter()
        .map(|(name, text)| SceneDef::parse(text, Path::new(&format!("(built in) {name}.toml"))))
        .collect::<Result<_, _>>()?;
    if let Some(dir) = scenes_dir() {
        for d in list(&dir)? {
            match defs.iter_mut().find(|x| x.name == d.name) {
                Some(x) => *x = d,
                None => defs.push(d),
            }
        }
    }
    defs.sort_by(|a, b| a.name.cmp(&b.name));
    Ok(defs)
}

/// The scene `name` of [`every`] (either route), or the definition file
/// `name` (a path ending in `.toml`).
pub fn lookup(name: &str) -> Result<SceneDef, SceneError> {
    let as_path = Path::new(name);
    if as_path.extension().is_some_and(|x| x == "toml") && as_path.exists() {
        return SceneDef::load(as_path);
    }
    let defs = every()?;
    let names: Vec<&str> = defs.iter().map(|d| d.name.as_str()).collect();
    defs.iter()
        .find(|d| d.name == name)
        .cloned()
        .ok_or_else(|| {
            SceneError::in_file(
                "scenes",
                format!("no scene named `{name}` (known: {})", names.join(", ")),
            )
        })
}

/// Every definition under `dir`, sorted by name.
pub fn list(dir: &Path) -> Result<Vec<SceneDef>, SceneError> {
    let rd = std::fs::read_dir(dir)
        .map_err(|e| SceneError::in_file(dir, format!("cannot list scene definitions: {e}")))?;
    let mut defs = Vec::new();
    for entry in rd {
        let entry = entry.map_err(|e| SceneError::in_file(dir, e.to_string()))?;
        let p = entry.path();
        if p.extension().is_some_and(|x| x == "toml") {
            defs.push(SceneDef::load(&p)?);
        }
    }
    defs.sort_by(|a, b| a.name.cmp(&b.name));
    Ok(defs)
}

/// Find a scene by name under `dir` alone (or treat `name` as a path to a
/// file).
pub fn find(dir: &Path, name: &str) -> Result<SceneDef, SceneError> {
    let as_path = Path::new(name);
    if as_path.extension().is_some_and(|x| x == "toml") && as_path.exists() {
        return SceneDef::load(as_path);
    }
    let defs = list(dir)?;
    let names: Vec<&str> = defs.iter().map(|d| d.name.as_str()).collect();
    defs.iter()
        .find(|d| d.name == name)
        .cloned()
        .ok_or_else(|| {
            SceneError::in_file(
                dir,
                format!("no scene named `{name}` (known: {})", names.join(", ")),
            )
        })
}

/// A `width` x `height` scene of `game` on `map` seen from `camera`, for
/// the loaders' tests.
#[cfg(test)]
pub(crate) fn test_def(game: Game, map: &str, camera: &str, width: u32, height: u32) -> SceneDef {
    SceneDef {
        name: format!("test-{map}"),
        game,
        map: map.into(),
        camera: camera.into(),
        width,
        height,
        description: String::new(),
        shader: None,
        draw_order: Default::default(),
        texture_format: Default::default(),
        route: Route::Loader,
        fov: None,
        picmip: None,
        sky: None,
        vis: None,
    }
}

/// The shipped scene definitions of `game`, for the loaders' tests.
#[cfg(test)]
pub(crate) fn shipped(game: Game) -> Vec<SceneDef> {
    all()
        .unwrap()
        .into_iter()
        .filter(|d| d.game == game)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_rejects() {
        let ok = "name = \"x\"\ngame = \"frozen-bubble\"\nmap = \"1\"\ncamera = \"full\"\nwidth = 640\nheight = 480\n";
        let d = SceneDef::parse(ok, Path::new("x.toml")).unwrap();
        assert_eq!(d.game, Game::FrozenBubble);
        let e = SceneDef::parse(&format!("{ok}colour = 1\n"), Path::new("x.toml")).unwrap_err();
        assert!(e.message.contains("colour"), "{e}");
        let e = SceneDef::parse(&ok.replace("640", "0"), Path::new("x.toml")).unwrap_err();
        assert!(e.message.contains("width"), "{e}");
        let e =
            SceneDef::parse(&ok.replace("frozen-bubble", "doom"), Path::new("x.toml")).unwrap_err();
        assert!(
            e.message.contains("doom") || e.message.contains("variant"),
            "{e}"
        );
    }

    #[test]
    fn the_draw_order_is_optional_and_checked() {
        let ok = "name = \"x\"\ngame = \"supertuxkart\"\nmap = \"m\"\ncamera = \"start:0\"\nwidth = 64\nheight = 32\n";
        let d = SceneDef::parse(ok, Path::new("x.toml")).unwrap();
        assert_eq!(d.draw_order, DrawOrder::AsLoaded);
        for o in DrawOrder::ALL {
            let text = format!("{ok}draw_order = \"{o}\"\n");
            assert_eq!(
                SceneDef::parse(&text, Path::new("x.toml"))
                    .unwrap()
                    .draw_order,
                o
            );
        }
        let e = SceneDef::parse(
            &format!("{ok}draw_order = \"back-to-front\"\n"),
            Path::new("dir/x.toml"),
        )
        .unwrap_err();
        let m = e.to_string();
        assert!(m.starts_with("dir/x.toml: "), "{m}");
        assert!(m.contains("line 7") && m.contains("draw_order"), "{m}");
        assert!(
            m.contains("`back-to-front`")
                && m.contains("`as-loaded`, `front-to-back-object`, `front-to-back-draw`"),
            "{m}"
        );
    }

    #[test]
    fn the_texture_format_is_optional_and_checked() {
        let ok = "name = \"x\"\ngame = \"supertuxkart\"\nmap = \"m\"\ncamera = \"start:0\"\nwidth = 64\nheight = 32\n";
        let d = SceneDef::parse(ok, Path::new("x.toml")).unwrap();
        assert_eq!(d.texture_format, FormatChoice::Etc2, "a mobile port's");
        for c in FormatChoice::all() {
            let text = format!("{ok}texture_format = \"{c}\"\n");
            let d = SceneDef::parse(&text, Path::new("x.toml")).unwrap();
            assert_eq!(d.texture_format, c);
        }
        let e = SceneDef::parse(
            &format!("{ok}texture_format = \"dxt1\"\n"),
            Path::new("dir/x.toml"),
        )
        .unwrap_err();
        let m = e.to_string();
        assert!(m.starts_with("dir/x.toml: ") && m.contains("line 7"), "{m}");
        assert!(
            m.contains("unknown texture format `dxt1`")
                && m.contains("rgba8, etc2, etc2-rgb, etc2-rgba, astc-4x4, astc-6x6, astc-8x8"),
            "{m}"
        );
    }

    #[test]
    fn the_route_is_optional_and_checked() {
        let ok = "name = \"x\"\ngame = \"openarena\"\nmap = \"oa_dm1\"\ncamera = \"spawn:0\"\nwidth = 64\nheight = 32\n";
        let d = SceneDef::parse(ok, Path::new("x.toml")).unwrap();
        assert_eq!(d.route, Route::Loader);
        let d = SceneDef::parse(&format!("{ok}route = \"engine\"\n"), Path::new("x.toml")).unwrap();
        assert_eq!(d.route, Route::Engine);
        let e = SceneDef::parse(&format!("{ok}route = \"gpu\"\n"), Path::new("d/x.toml"))
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("d/x.toml: ") && e.contains("line 7"), "{e}");
        assert!(
            e.contains("`gpu`") && e.contains("expected `loader` or `engine`"),
            "{e}"
        );
        let stk = ok.replace("openarena", "supertuxkart");
        let e = SceneDef::parse(&format!("{stk}route = \"engine\"\n"), Path::new("s.toml"))
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("s.toml: ")
                && e.contains("supertuxkart")
                && e.contains("openarena and teeworlds"),
            "{e}"
        );
    }

    #[test]
    fn an_engine_scene_takes_the_texture_format_rule_too() {
        let ok = "name = \"x\"\ngame = \"openarena\"\nmap = \"oa_dm1\"\ncamera = \"spawn:0\"\nwidth = 64\nheight = 32\nroute = \"engine\"\n";
        let d = SceneDef::parse(ok, Path::new("x.toml")).unwrap();
        assert_eq!(d.texture_format, FormatChoice::Etc2);
        let named = format!("{ok}texture_format = \"rgba8\"\n");
        let d = SceneDef::parse(&named, Path::new("x.toml")).unwrap();
        assert_eq!(d.texture_format, FormatChoice::Rgba8);
        for d in every().unwrap() {
            assert_eq!(d.texture_format, FormatChoice::Etc2, "{}", d.name);
        }
    }

    #[test]
    fn the_openarena_options_are_optional_and_checked() {
        let ok = "name = \"x\"\ngame = \"openarena\"\nmap = \"oa_dm1\"\ncamera = \"spawn:0\"\nwidth = 64\nheight = 32\n";
        let d = SceneDef::parse(ok, Path::new("x.toml")).unwrap();
        assert_eq!((d.fov, d.picmip, d.sky, d.vis), (None, None, None, None));
        assert_eq!(d.oa_vis(), OaVis::Pvs);
        let d = SceneDef::parse(&format!("{ok}vis = \"all\"\n"), Path::new("x.toml")).unwrap();
        assert_eq!(d.oa_vis(), OaVis::All);
        let e = SceneDef::parse(&format!("{ok}vis = \"some\"\n"), Path::new("d/x.toml"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("`some`") && e.contains("`pvs`") && e.contains("`all`"),
            "{e}"
        );
        let d = SceneDef::parse(ok, Path::new("x.toml")).unwrap();
        assert_eq!(
            (d.oa_fov(), d.oa_picmip(), d.oa_sky()),
            (OaFov::Engine, 1, OaSky::First)
        );
        let text = format!("{ok}fov = \"4:3\"\npicmip = 0\nsky = \"as-loaded\"\n");
        let d = SceneDef::parse(&text, Path::new("x.toml")).unwrap();
        assert_eq!(
            (d.oa_fov(), d.oa_picmip(), d.oa_sky()),
            (OaFov::FourThree, 0, OaSky::AsLoaded)
        );
        let d = SceneDef::parse(
            &format!("{ok}fov = \"engine\"\npicmip = 16\nsky = \"first\"\n"),
            Path::new("x.toml"),
        )
        .unwrap();
        assert_eq!(
            (d.oa_fov(), d.oa_picmip(), d.oa_sky()),
            (OaFov::Engine, 16, OaSky::First)
        );
        let err = |extra: &str, base: &str| {
            SceneDef::parse(&format!("{base}{extra}"), Path::new("d/x.toml"))
                .unwrap_err()
                .to_string()
        };
        let e = err("fov = \"wide\"\n", ok);
        assert!(
            e.starts_with("d/x.toml: ") && e.contains("line 7") && e.contains("`wide`"),
            "{e}"
        );
        assert!(e.contains("`engine`") && e.contains("`4:3`"), "{e}");
        let e = err("picmip = 17\n", ok);
        assert!(
            e.starts_with("d/x.toml: ") && e.contains("picmip = 17") && e.contains("0..=16"),
            "{e}"
        );
        let e = err("picmip = -1\n", ok);
        assert!(
            e.starts_with("d/x.toml: ") && e.contains("line 7") && e.contains("picmip"),
            "{e}"
        );
        let e = err("sky = \"last\"\n", ok);
        assert!(
            e.contains("`last`") && e.contains("`first`") && e.contains("`as-loaded`"),
            "{e}"
        );
        let stk = ok.replace("openarena", "supertuxkart");
        let e = err("picmip = 0\n", &stk);
        assert!(
            e.starts_with("d/x.toml: ") && e.contains("picmip") && e.contains("supertuxkart"),
            "{e}"
        );
        let e = err("route = \"engine\"\nfov = \"4:3\"\n", ok);
        assert!(e.contains("fov with route = \"engine\""), "{e}");
        // Scenes that name none serialize as before.
        let d = SceneDef::parse(ok, Path::new("x.toml")).unwrap();
        let json = serde_json::to_string(&d).unwrap();
        assert!(
            !json.contains("fov") && !json.contains("picmip") && !json.contains("sky"),
            "{json}"
        );
    }

    #[test]
    fn engine_scenes_are_listed_but_not_drawn() {
        let every = every().unwrap();
        let all = all().unwrap();
        let engine: Vec<&str> = every
            .iter()
            .filter(|d| d.route == Route::Engine)
            .map(|d| d.name.as_str())
            .collect();
        assert_eq!(
            engine,
            [
                "oa-dm1-spawn0-engine",
                "oa-dm5-spawn1-engine",
                "oa-wrackdm17-spawn2-engine",
                "tw-dm1-spawn0-engine"
            ]
        );
        assert_eq!(all.len() + engine.len(), every.len());
        assert!(all.iter().all(|d| d.route == Route::Loader));
        // Each twin has the camera, map and frame of its loader scene.
        for name in engine {
            let twin = every.iter().find(|d| d.name == name).unwrap();
            let base = all
                .iter()
                .find(|d| d.name == name.trim_end_matches("-engine"))
                .unwrap();
            assert_eq!(
                (&twin.game, &twin.map, &twin.camera, twin.width, twin.height),
                (&base.game, &base.map, &base.camera, base.width, base.height)
            );
        }
        assert!(lookup("oa-dm1-spawn0-engine").is_ok());
    }

    #[test]
    fn shipped_scenes_keep_the_order_loaded() {
        // No shipped game's renderer sorts opaque draws by depth
        // (docs/scenes.md), so every shipped scene draws as loaded.
        for d in all().unwrap() {
            assert_eq!(d.draw_order, DrawOrder::AsLoaded, "{}", d.name);
        }
    }
}
