//! `wasp scenes capture SCENE`: run a game's own engine headless (Xvfb)
//! at an engine-route scene's camera and resolution under apitrace, and
//! store the capture and a JSON sidecar in the scene cache:
//!
//! ```text
//! <cache>/captures/<scene>.trace   the apitrace capture (`apitrace dump`, `glretrace`)
//! <cache>/captures/<scene>.json    engine, package version, command line, resolution,
//!                                  frames, seconds, camera
//! ```
//!
//! It installs nothing: a missing game package, `xvfb-run` or `apitrace`
//! stops it with the `apt-get install` line to run. One engine per file:
//! [`openarena`], [`teeworlds`]; the tool checks and the process control
//! (process groups, deadlines) are in [`tools`].

mod openarena;
mod teeworlds;
pub mod tools;

use crate::cli_error::CliError;
use crate::scenes_dir::ScenesDir;
use clap::Args;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::time::Instant;
use wasp_frontend::def::{self, Game, Route, SceneDef};
use wasp_frontend::fetch;

/// Options of `wasp scenes capture`.
#[derive(Args, Debug, Clone)]
pub struct CaptureArgs {
    /// An engine-route scene (`route = "engine"`, e.g. oa-dm1-spawn0-engine;
    /// see `wasp scenes list`) or its definition file.
    #[arg(value_name = "SCENE")]
    pub scene: String,
    #[command(flatten)]
    pub scene_defs: ScenesDir,
    /// Capture again even if the scene cache holds a capture.
    #[arg(long)]
    pub force: bool,
    /// OpenArena: frames drawn at the scene's camera once it is in place
    /// (warm-up frames, then the last one, which is the scene's frame);
    /// default 5. (The Teeworlds client counts no frames: it draws 2 s
    /// after the player joins.)
    #[arg(long, value_name = "N")]
    pub frames: Option<u32>,
    /// No progress output on stderr; errors still print.
    #[arg(long, short)]
    pub quiet: bool,
}

/// The capture and sidecar paths of a scene in the scene cache.
pub fn capture_paths(scene: &str) -> (PathBuf, PathBuf) {
    let dir = fetch::cache_dir().join("captures");
    (
        dir.join(format!("{scene}.trace")),
        dir.join(format!("{scene}.json")),
    )
}

/// The JSON sidecar written beside a capture.
#[derive(Serialize, Debug)]
pub struct Sidecar {
    /// The scene captured.
    pub scene: String,
    /// The engine, e.g. `ioquake3 (OpenArena), renderer opengl1`.
    pub engine: String,
    /// Debian packages and versions used (game, apitrace, xvfb).
    pub packages: Vec<(String, String)>,
    /// The command line run (program and arguments).
    pub command: Vec<String>,
    /// Engine console script run after the map loads, if any.
    pub script: Option<String>,
    /// Frame width and height (pixels).
    pub width: u32,
    pub height: u32,
    /// Frames in the capture (`apitrace info`), the scene's frame last.
    pub frames: u64,
    /// Frames drawn at the scene's camera (OpenArena), else None.
    pub frames_at_camera: Option<u32>,
    /// Wall-clock seconds of the capture run.
    pub seconds: f64,
    /// Bytes of the capture.
    pub bytes: u64,
    /// Where the camera stood and how it was placed.
    pub camera: serde_json::Value,
}

/// Progress lines on stderr unless quiet.
pub struct Progress {
    quiet: bool,
    start: Instant,
}

impl Progress {
    fn new(quiet: bool) -> Self {
        Self {
            quiet,
            start: Instant::now(),
        }
    }

    /// Say `msg` with the seconds since the capture started.
    pub fn say(&self, msg: &str) {
        if !self.quiet {
            eprintln!(
                "wasp: capture: [{:5.1} s] {msg}",
                self.start.elapsed().as_secs_f64()
            );
        }
    }
}

/// The engine-route scene `name`, or a usage error saying why not.
pub fn engine_scene(name: &str) -> Result<SceneDef, CliError> {
    let d = def::lookup(name).map_err(|e| CliError::usage(e.to_string()))?;
    if d.route != Route::Engine {
        let twins: Vec<String> = def::every()
            .map_err(|e| CliError::failed(e.to_string()))?
            .into_iter()
            .filter(|t| t.route == Route::Engine)
            .map(|t| t.name)
            .collect();
        return Err(CliError::usage(format!(
            "scene {} uses wasp's loader (route = \"loader\"): only engine-route scenes are \
             captured (route = \"engine\"; shipped: {}); draw it with `wasp render {}`",
            d.name,
            twins.join(", "),
            d.name
        )));
    }
    Ok(d)
}

/// The frames at the camera `--frames` asks for on scene `def`.
fn frames(def: &SceneDef, asked: Option<u32>) -> Result<u32, CliError> {
    match (def.game, asked) {
        (_, Some(0)) => Err(CliError::usage("--frames 0: expected at least 1")),
        (Game::Openarena, n) => Ok(n.unwrap_or(openarena::DEFAULT_FRAMES)),
        (_, Some(n)) => Err(CliError::usage(format!(
            "--frames {n}: {} is a {} scene, whose client counts no frames (it draws for \
             2 s after the player joins); --frames applies to OpenArena scenes",
            def.name, def.game
        ))),
        (_, None) => Ok(0),
    }
}

/// Run `wasp scenes capture`: the capture's path goes to standard output.
pub fn capture(args: &CaptureArgs) -> Result<(), CliError> {
    let def = engine_scene(&args.scene)?;
    let trace = ensure_capture(&def, args.force, args.frames, args.quiet)?;
    println!("{}", trace.display());
    Ok(())
}

/// The capture of engine-route scene `def` in the scene cache: the one
/// there (unless `force`), else a new one. Returns its path.
pub fn ensure_capture(
    def: &SceneDef,
    force: bool,
    frames_asked: Option<u32>,
    quiet: bool,
) -> Result<PathBuf, CliError> {
    let frames = frames(def, frames_asked)?;
    let (trace, json) = capture_paths(&def.name);
    if trace.is_file() && json.is_file() && !force {
        if !quiet {
            eprintln!(
                "wasp: capture: {} is in the scene cache: {} (--force captures again)",
                def.name,
                trace.display()
            );
        }
        return Ok(trace);
    }
    let needs = needs(def.game);
    let packages = tools::check(&needs).map_err(CliError::failed)?;
    let dir = trace.parent().expect("captures folder");
    std::fs::create_dir_all(dir)
        .map_err(|e| CliError::failed(format!("{}: cannot create: {e}", dir.display())))?;
    let progress = Progress::new(quiet);
    let work = tools::WorkDir::new(&def.name).map_err(CliError::failed)?;
    let partial = dir.join(format!(".{}.{}.trace", def.name, std::process::id()));
    let _ = std::fs::remove_file(&partial);
    tools::stop_groups_on_interrupt(&partial);
    let result = match def.game {
        Game::Openarena => openarena::capture(def, frames, &partial, &work, &progress),
        Game::Teeworlds => teeworlds::capture(def, &partial, &work, &progress),
        g => Err(format!(
            "{g}: no engine capture (route = \"engine\" is refused for it)"
        )),
    };
    let run = match result {
        Ok(run) => run,
        Err(e) => {
            let _ = std::fs::remove_file(&partial);
            return Err(CliError::failed(format!("capture of {}: {e}", def.name)));
        }
    };
    finish(def, run, packages, &partial, &trace, &json, &progress)?;
    Ok(trace)
}

/// The programs and packages a capture of `game` needs.
pub fn needs(game: Game) -> Vec<tools::Need> {
    let engine: &[tools::Need] = match game {
        Game::Openarena => &openarena::NEEDS,
        Game::Teeworlds => &teeworlds::NEEDS,
        _ => &[],
    };
    engine.iter().chain(&tools::COMMON_NEEDS).copied().collect()
}

/// What an engine's capture run reports.
pub struct EngineRun {
    pub engine: String,
    pub command: Vec<String>,
    pub script: Option<String>,
    pub frames_at_camera: Option<u32>,
    pub seconds: f64,
    pub camera: serde_json::Value,
}

/// Check the partial capture, move it in place and write the sidecar.
fn finish(
    def: &SceneDef,
    run: EngineRun,
    packages: Vec<(String, String)>,
    partial: &Path,
    trace: &Path,
    json: &Path,
    progress: &Progress,
) -> Result<(), CliError> {
    let fail = |e: String| {
        let _ = std::fs::remove_file(partial);
        CliError::failed(format!("capture of {}: {e}", def.name))
    };
    let frames = tools::frame_count(partial).map_err(fail)?;
    if frames == 0 {
        return Err(fail(format!(
            "{}: the capture holds no complete frame",
            partial.display()
        )));
    }
    let bytes = std::fs::metadata(partial).map(|m| m.len()).unwrap_or(0);
    std::fs::rename(partial, trace)
        .map_err(|e| fail(format!("{}: cannot move in place: {e}", trace.display())))?;
    // The command as run wrote the partial file that is now `trace`.
    let command = run
        .command
        .into_iter()
        .map(|a| a.replace(&*partial.to_string_lossy(), &trace.to_string_lossy()))
        .collect();
    let side = Sidecar {
        scene: def.name.clone(),
        engine: run.engine,
        packages,
        command,
        script: run.script,
        width: def.width,
        height: def.height,
        frames,
        frames_at_camera: run.frames_at_camera,
        seconds: (run.seconds * 10.0).round() / 10.0,
        bytes,
        camera: run.camera,
    };
    let text = serde_json::to_string_pretty(&side).expect("sidecar serializes");
    std::fs::write(json, text + "\n")
        .map_err(|e| CliError::failed(format!("{}: cannot write: {e}", json.display())))?;
    progress.say(&format!(
        "{frames} frames, {:.1} MB in {:.1} s: {}",
        bytes as f64 / 1e6,
        side.seconds,
        trace.display()
    ));
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_loader_scene_is_refused_with_the_engine_twins_named() {
        let e = engine_scene("oa-dm1-spawn0").unwrap_err().to_string();
        assert!(e.contains("route = \"loader\""), "{e}");
        assert!(e.contains("oa-dm1-spawn0-engine"), "{e}");
        assert!(e.contains("wasp render oa-dm1-spawn0"), "{e}");
        let e = engine_scene("no-such-scene").unwrap_err().to_string();
        assert!(e.contains("no scene named `no-such-scene`"), "{e}");
        assert_eq!(
            engine_scene("tw-dm1-spawn0-engine").unwrap().game,
            Game::Teeworlds
        );
    }

    #[test]
    fn every_engine_needs_xvfb_and_apitrace() {
        for g in [Game::Openarena, Game::Teeworlds] {
            let pk: Vec<&str> = needs(g).iter().map(|n| n.package).collect();
            assert!(pk.contains(&"xvfb") && pk.contains(&"apitrace"), "{pk:?}");
        }
        let tw: Vec<&str> = needs(Game::Teeworlds).iter().map(|n| n.package).collect();
        assert!(tw.contains(&"teeworlds") && tw.contains(&"teeworlds-server"));
        assert_eq!(needs(Game::Openarena)[0].package, "openarena");
    }

    #[test]
    fn frames_apply_to_openarena_only() {
        let oa = def::lookup("oa-dm1-spawn0-engine").unwrap();
        let tw = def::lookup("tw-dm1-spawn0-engine").unwrap();
        assert_eq!(frames(&oa, None).unwrap(), openarena::DEFAULT_FRAMES);
        assert_eq!(frames(&oa, Some(3)).unwrap(), 3);
        assert!(frames(&oa, Some(0)).is_err());
        let e = frames(&tw, Some(3)).unwrap_err().to_string();
        assert!(e.contains("--frames 3") && e.contains("OpenArena"), "{e}");
        assert!(frames(&tw, None).is_ok());
    }

    #[test]
    fn captures_live_in_the_scene_cache() {
        let (t, j) = capture_paths("oa-dm1-spawn0-engine");
        assert_eq!(
            t.parent(),
            Some(fetch::cache_dir().join("captures").as_path())
        );
        assert!(t.ends_with("oa-dm1-spawn0-engine.trace"));
        assert!(j.ends_with("oa-dm1-spawn0-engine.json"));
    }
}
