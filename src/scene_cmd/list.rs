//! `wasp scenes list`: the scene definitions and whether their data is
//! in the cache.

use super::defs::scene_err;
use crate::cli_error::CliError;
use crate::scenes_dir::ScenesDir;
use clap::Args;
use wasp_frontend::def::{self, Game, Route};
use wasp_frontend::fetch;

/// Options of `wasp scenes list`.
#[derive(Args, Debug, Clone)]
pub struct ListArgs {
    #[command(flatten)]
    pub scene_defs: ScenesDir,
    /// No progress output on stderr; results, warnings and errors still
    /// print. (The list shows none.)
    #[arg(long, short)]
    pub quiet: bool,
}

/// Run `wasp scenes list`.
pub fn list() -> Result<(), CliError> {
    let defs = def::every().map_err(scene_err)?;
    println!(
        "{:<28} {:<14} {:<18} {:<16} {:>10}  data",
        "scene", "game", "map", "camera", "frame"
    );
    for d in &defs {
        let data = if d.route == Route::Engine {
            let (trace, _) = crate::capture::capture_paths(&d.name);
            if trace.is_file() {
                "engine: captured".to_string()
            } else {
                format!("engine: not captured (wasp scenes capture {})", d.name)
            }
        } else if d.game == Game::Procedural {
            "built in".to_string()
        } else if fetch::is_fetched(d.game) {
            "fetched".to_string()
        } else {
            format!("not fetched (wasp scenes fetch {})", d.game)
        };
        println!(
            "{:<28} {:<14} {:<18} {:<16} {:>10}  {data}",
            d.name,
            d.game.name(),
            d.map,
            d.camera,
            format!("{}x{}", d.width, d.height)
        );
    }
    match def::scenes_dir() {
        Some(d) => println!(
            "scene definitions: built in, and {} (--scenes-dir / WASP_SCENES_DIR)",
            d.display()
        ),
        None => println!("scene definitions: built in"),
    }
    println!("scene cache: {}", fetch::cache_dir().display());
    Ok(())
}
