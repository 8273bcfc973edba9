//! `wasp scenes fetch`: a game's data into the scene cache.

use super::defs::scene_err;
use crate::cli_error::CliError;
use clap::Args;
use wasp_frontend::def::Game;
use wasp_frontend::fetch;

/// Options of `wasp scenes fetch`.
#[derive(Args, Debug, Clone)]
pub struct FetchArgs {
    /// Games: supertuxkart, openarena, teeworlds, frozen-bubble.
    #[arg(value_name = "GAME", required_unless_present = "all")]
    pub games: Vec<String>,
    /// Every game.
    #[arg(long, conflicts_with = "games")]
    pub all: bool,
    /// Fetch a game again even when its data is already in the cache (by
    /// default a fetched game is skipped, saying so).
    #[arg(long)]
    pub force: bool,
    /// No progress output on stderr (what is downloaded and unpacked);
    /// errors still print.
    #[arg(long, short)]
    pub quiet: bool,
}

/// The game named `s` (any case), or a usage error listing the games.
fn parse_game(s: &str) -> Result<Game, CliError> {
    Game::ALL
        .into_iter()
        .find(|g| g.name() == s.to_ascii_lowercase())
        .ok_or_else(|| {
            let names: Vec<&str> = Game::ALL.iter().map(|g| g.name()).collect();
            CliError::usage(format!(
                "unknown game `{s}` (expected one of {})",
                names.join(", ")
            ))
        })
}

/// Run `wasp scenes fetch`.
pub fn fetch(f: &FetchArgs) -> Result<(), CliError> {
    let games: Vec<Game> = if f.all {
        Game::ALL
            .into_iter()
            .filter(|g| *g != Game::Procedural)
            .collect()
    } else {
        f.games
            .iter()
            .map(|g| parse_game(g))
            .collect::<Result<_, _>>()?
    };
    let quiet = f.quiet;
    for g in games {
        if g != Game::Procedural && fetch::is_fetched(g) && !f.force {
            if !quiet {
                eprintln!(
                    "wasp: {g}: already fetched in {}; skipped (--force fetches it again)",
                    fetch::cache_dir().display()
                );
            }
            continue;
        }
        let root = fetch::fetch(g, &mut |m| {
            if !quiet {
                eprintln!("wasp: {g}: {m}")
            }
        })
        .map_err(scene_err)?;
        if g != Game::Procedural && !quiet {
            eprintln!("wasp: {g}: data in {}", root.display());
        }
    }
    Ok(())
}
