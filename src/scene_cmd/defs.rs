//! What the scene commands share: a scene definition found by name or
//! file, the error of a failed scene step, and the note for a draw order
//! that a 2D scene's painter's order overrides.

use crate::cli_error::CliError;
use wasp_frontend::def::{self, Route, SceneDef};
use wasp_frontend::raster::DrawOrder;

/// The note for a draw order that changes nothing on a 2D scene, if
/// `asked` is not what takes effect.
pub fn painter_note(scene: &str, asked: DrawOrder, took: DrawOrder) -> Option<String> {
    (asked != took).then(|| {
        format!(
            "wasp: note: {scene} is a 2D scene drawn in painter's order without a depth test \
             (its order is its picture): draw order {asked} changes nothing, it is drawn {took}"
        )
    })
}

/// A failed scene step (loading, rendering, fetching) as a CLI failure.
pub fn scene_err(e: impl std::fmt::Display) -> CliError {
    CliError::failed(e.to_string())
}

/// The loader-route scene `name` (a name of `wasp scenes list` or a
/// definition file); an engine scene is refused with the commands that
/// draw it.
pub fn find_def(name: &str) -> Result<SceneDef, CliError> {
    let d = find_any_def(name)?;
    if d.route == Route::Engine {
        return Err(CliError::usage(format!(
            "scene {} takes the engine route (route = \"engine\"): its frame comes from the \
             game's engine, not a loader; run `wasp scenes capture {}`, then import the capture \
             with `wasp import-gl`",
            d.name, d.name
        )));
    }
    Ok(d)
}

/// The scene `name` of either route (a name of `wasp scenes list` or a
/// definition file).
pub fn find_any_def(name: &str) -> Result<SceneDef, CliError> {
    // A name that is a path on disk but no definition file: say what it is,
    // rather than that no scene has that name.
    let p = std::path::Path::new(name);
    if p.is_dir() {
        return Err(CliError::usage(format!(
            "{name} is a directory, not a scene name or scene file (see `wasp scenes list`)"
        )));
    }
    let is_toml = p.extension().is_some_and(|x| x == "toml");
    if p.exists() && !is_toml {
        return Err(CliError::usage(format!(
            "{name} is not a scene definition: a scene file is TOML and ends in .toml \
             (see scenes/*.toml)"
        )));
    }
    if is_toml && !p.exists() {
        return Err(CliError::usage(format!("{name}: no such scene file")));
    }
    def::lookup(name).map_err(|e| CliError::usage(e.to_string()))
}
