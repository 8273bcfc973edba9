//! The frame of an engine-route scene for studies (`reproduce`,
//! `characterize`, the study runner): the capture in the scene cache
//! (`wasp scenes capture`) and its last complete frame imported as
//! `wasp import-gl` imports it, rasterized at a study's tile size.

use crate::capture::{capture_paths, ensure_capture};
use std::path::PathBuf;
use wasp_frontend::def::{Route, SceneDef};
use wasp_frontend::gl::{self, ImportOptions};
use wasp_frontend::raster::{rasterize_timed, Frame, RasterOptions};

/// The capture of engine scene `def` in the scene cache, made now when it
/// is missing and `capture` allows it; else an error naming the command
/// that makes it.
pub fn capture(def: &SceneDef, capture: bool, quiet: bool) -> Result<PathBuf, String> {
    let (trace, json) = capture_paths(&def.name);
    if trace.is_file() && json.is_file() {
        return Ok(trace);
    }
    if !capture {
        return Err(format!(
            "engine scene {}: no capture in the scene cache ({}): run `wasp scenes capture {}`",
            def.name,
            trace.display(),
            def.name
        ));
    }
    ensure_capture(def, false, None, quiet).map_err(|e| e.to_string())
}

/// The identity of an engine scene's capture for study keys: the JSON
/// sidecar written beside it (engine, package versions, size, time), or
/// "no capture" when there is none.
pub fn capture_identity(def: &SceneDef) -> String {
    if def.route != Route::Engine {
        return String::new();
    }
    let (_, json) = capture_paths(&def.name);
    match std::fs::read_to_string(&json) {
        Ok(text) => format!(" capture={text}"),
        Err(_) => " capture=none".into(),
    }
}

/// The last complete frame of engine scene `def`'s capture (which must be
/// in the scene cache: see [`capture`]) rasterized with `opts` (its draw
/// order and texture format are the definition's); with the seconds taken.
pub fn frame(def: &SceneDef, opts: &RasterOptions) -> Result<(Frame, f64), String> {
    let (path, _) = capture_paths(&def.name);
    let clock = std::time::Instant::now();
    let fail = |e: &dyn std::fmt::Display| format!("engine scene {}: {e}", def.name);
    let capture = wasp_gltrace::Capture::open(&path).map_err(|e| fail(&e))?;
    capture.require_gl().map_err(|e| fail(&e))?;
    let imported = gl::import(capture, &path, ImportOptions::default()).map_err(|e| fail(&e))?;
    let opts = RasterOptions {
        draw_order: def.draw_order,
        texture_format: def.texture_format,
        ..opts.clone()
    };
    let (frame, _) = rasterize_timed(&imported.scene, imported.width, imported.height, &opts)
        .map_err(|e| fail(&e))?;
    if (frame.width, frame.height) != (def.width, def.height) {
        return Err(fail(&format!(
            "the captured frame is {}x{}, the definition says {}x{}: capture it again \
             (`wasp scenes capture {} --force`)",
            frame.width, frame.height, def.width, def.height, def.name
        )));
    }
    Ok((frame, clock.elapsed().as_secs_f64()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn no_capture() -> SceneDef {
        let mut d = wasp_frontend::def::lookup("oa-dm1-spawn0-engine").unwrap();
        d.name = format!("test-never-captured-{}-engine", std::process::id());
        d
    }

    #[test]
    fn a_missing_capture_names_the_command_that_makes_it() {
        let d = no_capture();
        let e = capture(&d, false, true).unwrap_err();
        assert!(
            e.contains(&format!("run `wasp scenes capture {}`", d.name)),
            "{e}"
        );
        assert_eq!(capture_identity(&d), " capture=none");
        let loader = wasp_frontend::def::lookup("procedural-plane").unwrap();
        assert_eq!(capture_identity(&loader), "");
    }
}
