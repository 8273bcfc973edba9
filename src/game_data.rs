//! Fetching the game data a command needs, as `wasp scenes fetch` does:
//! `render`, `characterize` (of named scenes), `reproduce` and `sweep`
//! fetch a game's Debian packages into
//! the scene cache the first time one of its scenes is used, saying what
//! they download and how much.

use wasp_frontend::def::Game;
use wasp_frontend::fetch;

/// Megabytes (10^6 bytes) as text.
pub fn megabytes(bytes: u64) -> String {
    format!("{:.0} MB", bytes as f64 / 1e6)
}

/// Fetch every game of `games` (repeats allowed) whose data is not in the
/// scene cache;
/// `quiet` silences the notes of what is downloaded (errors still name
/// the game).
pub fn fetch_missing(games: &[Game], quiet: bool) -> Result<(), String> {
    let mut missing: Vec<Game> = games
        .iter()
        .copied()
        .filter(|g| !fetch::is_fetched(*g))
        .collect();
    missing.sort_by_key(|g| g.name());
    missing.dedup();
    for g in missing {
        if !quiet {
            let size = fetch::download_bytes(g)
                .map_or_else(String::new, |b| format!(", {} to download", megabytes(b)));
            eprintln!(
                "wasp: fetching the {} data ({}{size}) once, into the scene cache {}",
                g.name(),
                g.packages().join(", "),
                fetch::cache_dir().display()
            );
        }
        fetch::fetch(g, &mut |m| {
            if !quiet {
                eprintln!("wasp:   {m}");
            }
        })
        .map_err(|e| format!("fetching the {} data: {e}", g.name()))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_read_in_megabytes() {
        assert_eq!(megabytes(835_313_472), "835 MB");
        assert_eq!(megabytes(7_633_736), "8 MB");
    }

    #[test]
    fn procedural_scenes_fetch_nothing() {
        assert_eq!(fetch_missing(&[Game::Procedural], false), Ok(()));
    }
}
