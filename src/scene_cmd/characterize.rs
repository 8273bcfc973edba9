//! `wasp characterize`: the workload characterisation of scenes (the
//! paper's Table II figures) as a table, JSON or CSV.

use super::defs::{find_any_def, painter_note, scene_err};
use crate::cli_error::CliError;
use crate::output::{self, emit, Output};
use crate::scenes_dir::ScenesDir;
use clap::Args;
use std::path::PathBuf;
use wasp_frontend::characterize::{self, Characterization};
use wasp_frontend::def::{self, Game, Route, SceneDef};
use wasp_frontend::fetch;
use wasp_frontend::raster::DrawOrder;
use wasp_frontend::texture::FormatChoice;

/// Options of `wasp characterize`.
#[derive(Args, Debug, Clone)]
pub struct CharacterizeArgs {
    /// Scenes (names or definition files) of either route; default: every
    /// scene whose data (a loader scene) or capture (an engine scene) is in
    /// the cache, the procedural ones included. A named engine scene is
    /// captured when the cache lacks its capture.
    #[arg(value_name = "SCENE")]
    pub scenes: Vec<String>,
    #[command(flatten)]
    pub scene_defs: ScenesDir,
    /// Write the characterisation as JSON to FILE (`-` for standard
    /// output).
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// Write it as CSV to FILE (`-` for standard output).
    #[arg(long, value_name = "FILE")]
    pub csv: Option<PathBuf>,
    /// Hidden-surface removal by a depth pre-pass (see `wasp render`).
    #[arg(long)]
    pub depth_prepass: bool,
    /// Order of the opaque geometry (see `wasp render`); repeat it to
    /// characterise every scene in each order given (default: each
    /// scene's own `draw_order`).
    #[arg(long, value_name = "ORDER")]
    pub draw_order: Vec<DrawOrder>,
    /// How the textures are stored (see `wasp render`); repeat it to
    /// characterise every scene in each format given (default: each
    /// scene's own `texture_format`).
    #[arg(long, value_name = "FORMAT")]
    pub texture_format: Vec<FormatChoice>,
    /// No progress output on stderr (progress bars, notes of what is being
    /// done); results, warnings and errors still print.
    #[arg(long, short)]
    pub quiet: bool,
}

/// Whether the frame of `d` can be drawn without a download or a
/// capture: a loader scene's game data, an engine scene's capture, is in
/// the scene cache.
fn in_cache(d: &SceneDef) -> bool {
    match d.route {
        Route::Loader => fetch::is_fetched(d.game),
        Route::Engine => crate::capture::capture_paths(&d.name).0.is_file(),
    }
}

/// The scenes `wasp characterize` takes, each in every draw order asked
/// for: the named ones (their games' data fetched, their engines
/// captured, if missing), else every scene whose data or capture is in
/// the cache.
fn characterize_defs(args: &CharacterizeArgs) -> Result<Vec<SceneDef>, CliError> {
    let defs: Vec<SceneDef> = if args.scenes.is_empty() {
        let all = def::every().map_err(scene_err)?;
        let (have, missing): (Vec<_>, Vec<_>) = all.into_iter().partition(in_cache);
        if !missing.is_empty() {
            let names: Vec<&str> = missing.iter().map(|d| d.name.as_str()).collect();
            eprintln!(
                "wasp: skipping scenes without fetched data or a capture ({}); see `wasp \
                 scenes list`",
                names.join(", ")
            );
        }
        have
    } else {
        let named: Vec<SceneDef> = args
            .scenes
            .iter()
            .map(|s| find_any_def(s))
            .collect::<Result<_, _>>()?;
        let games: Vec<Game> = named
            .iter()
            .filter(|d| d.route == Route::Loader)
            .map(|d| d.game)
            .collect();
        crate::game_data::fetch_missing(&games, args.quiet).map_err(CliError::failed)?;
        named
    };
    // Each scene in each order and format asked for (none: its own),
    // scene by scene.
    Ok(defs
        .into_iter()
        .flat_map(|d| {
            let orders = match args.draw_order.is_empty() {
                true => vec![d.draw_order],
                false => args.draw_order.clone(),
            };
            let formats = match args.texture_format.is_empty() {
                true => vec![d.texture_format],
                false => args.texture_format.clone(),
            };
            orders.into_iter().flat_map(move |o| {
                let d = d.clone();
                formats.clone().into_iter().map(move |f| SceneDef {
                    draw_order: o,
                    texture_format: f,
                    ..d.clone()
                })
            })
        })
        .collect())
}

/// The characterisation of `d`: a loader scene through its loader, an
/// engine scene from its capture (made now when missing).
fn characterize_one(d: &SceneDef, args: &CharacterizeArgs) -> Result<Characterization, String> {
    if d.route == Route::Loader {
        return characterize::characterize_def(d, args.depth_prepass).map_err(|e| e.to_string());
    }
    if args.depth_prepass {
        return Err(format!(
            "--depth-prepass applies to loader scenes: {} is the engine's own draw calls",
            d.name
        ));
    }
    crate::engine_frame::capture(d, true, args.quiet)?;
    let opts = wasp_frontend::raster::RasterOptions {
        colour: false,
        ..Default::default()
    };
    let (frame, secs) = crate::engine_frame::frame(d, &opts)?;
    Ok(characterize::characterize(&d.name, &frame, secs))
}

/// Run `wasp characterize`.
pub fn characterize(args: &CharacterizeArgs) -> Result<(), CliError> {
    output::check(
        &[
            Output::new("--json", args.json.as_deref()),
            Output::new("--csv", args.csv.as_deref()),
        ],
        &[output::Input::folder(
            "--scenes-dir",
            args.scene_defs.scenes_dir.as_deref(),
            "toml",
        )],
    )?;
    let defs = characterize_defs(args)?;
    let mut rows: Vec<Characterization> = Vec::new();
    let mut failed = Vec::new();
    for (i, d) in defs.iter().enumerate() {
        if !args.quiet {
            let mut order = match args.draw_order.is_empty() {
                true => String::new(),
                false => format!(" in draw order {}", d.draw_order),
            };
            if !args.texture_format.is_empty() {
                order.push_str(&format!(" with textures as {}", d.texture_format));
            }
            eprintln!(
                "wasp: characterising {}{order} ({} of {})",
                d.name,
                i + 1,
                defs.len()
            );
        }
        match characterize_one(d, args) {
            Ok(c) => {
                if let Some(n) = painter_note(&d.name, d.draw_order, c.draw_order) {
                    if !args.quiet {
                        eprintln!("{n}");
                    }
                }
                rows.push(c)
            }
            Err(e) => {
                eprintln!(
                    "wasp: {} ({}, {}): {e}",
                    d.name, d.draw_order, d.texture_format
                );
                failed.push(format!(
                    "{} ({}, {})",
                    d.name, d.draw_order, d.texture_format
                ));
            }
        }
    }
    if rows.is_empty() {
        return Err(CliError::failed("no scene could be characterised"));
    }
    if !output::to_stdout(&args.json) && !output::to_stdout(&args.csv) {
        println!(
            "Workload characterisation (ours: the scenes named in each column; paper: ten \
             Android games on TEAPOT)"
        );
        print!("{}", characterize::table(&rows));
    }
    if let Some(p) = &args.json {
        let text = serde_json::to_string_pretty(&rows)
            .map_err(|e| CliError::failed(format!("encoding JSON: {e}")))?
            + "\n";
        emit(p, &text)?;
    }
    if let Some(p) = &args.csv {
        emit(p, &characterize::csv(&rows))?;
    }
    if !failed.is_empty() {
        return Err(CliError::failed(format!(
            "could not characterise: {}",
            failed.join(", ")
        )));
    }
    Ok(())
}
