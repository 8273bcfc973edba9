//! Getting game data: Debian's packages, downloaded with `apt-get
//! download` and unpacked with `dpkg-deb` into a cache outside the
//! repository (the data is GPL / CC-BY-SA and is never committed).
//!
//! Layout of the cache ([`cache_dir`]):
//!
//! ```text
//! <cache>/<game>/                     package root: every package of the game
//!   .wasp-fetched                     marker: one `package version` line each
//!   usr/share/games/<game>/...        the games' data, as the packages ship it
//!   usr/share/doc/<package>/copyright licences
//! ```
//!
//! Data roots ([`data_root`]), as the packages lay them out (`dpkg-deb -c`):
//!
//! | game | packages | data root under the package root |
//! |---|---|---|
//! | supertuxkart | supertuxkart-data | `usr/share/games/supertuxkart/data` |
//! | openarena | openarena-data, openarena-081-maps, openarena-081-textures | `usr/share/games/openarena` (its `baseoa/` holds pak0.pk3, pak1-maps.pk3 and pak4-textures.pk3 side by side) |
//! | teeworlds | teeworlds-data | `usr/share/games/teeworlds/data` |
//! | frozen-bubble | frozen-bubble-data | `usr/share/games/frozen-bubble` |

use super::def::Game;
use super::SceneError;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// Name of the marker file written after a complete fetch.
pub const MARKER: &str = ".wasp-fetched";

/// The scene cache: `$WASP_SCENES`, else `$XDG_CACHE_HOME/wasp/scenes`,
/// else `~/.cache/wasp/scenes` (else a directory under the system's
/// temporary directory when there is no home).
pub fn cache_dir() -> PathBuf {
    let env = |k: &str| std::env::var_os(k).filter(|v| !v.is_empty());
    if let Some(d) = env("WASP_SCENES") {
        return PathBuf::from(d);
    }
    if let Some(d) = env("XDG_CACHE_HOME").map(PathBuf::from) {
        if d.is_absolute() {
            return d.join("wasp").join("scenes");
        }
    }
    match env("HOME") {
        Some(h) => PathBuf::from(h).join(".cache").join("wasp").join("scenes"),
        None => std::env::temp_dir().join("wasp-scenes"),
    }
}

/// Where the game's packages are unpacked: `<cache>/<game>`.
pub fn package_root(game: Game) -> PathBuf {
    cache_dir().join(game.name())
}

/// The game's data directory relative to its package root.
pub fn data_subdir(game: Game) -> &'static str {
    match game {
        Game::Supertuxkart => "usr/share/games/supertuxkart/data",
        Game::Openarena => "usr/share/games/openarena",
        Game::Teeworlds => "usr/share/games/teeworlds/data",
        Game::FrozenBubble => "usr/share/games/frozen-bubble",
        Game::Procedural => "",
    }
}

/// The game's data directory: what its loader's `load(data_root, def)` gets.
pub fn data_root(game: Game) -> PathBuf {
    package_root(game).join(data_subdir(game))
}

/// The game's data root in the scene cache, for tests that need real game
/// data: under the package root `wasp scenes fetch` unpacks into
/// ([`package_root`]), else under a directory named after the game's first
/// package (`<cache>/<package>`, as a manual `dpkg-deb -x` of it lays it
/// out); the first whose data root holds `probe` (a path relative to it),
/// None when neither does.
#[cfg(test)]
pub(crate) fn cached_data_root(game: Game, probe: &str) -> Option<PathBuf> {
    let per_package = cache_dir().join(game.packages().first()?);
    [package_root(game), per_package]
        .into_iter()
        .map(|p| p.join(data_subdir(game)))
        .find(|r| r.join(probe).exists())
}

/// The subtree of the package's files wasp unpacks.
fn games_subtree(game: Game) -> String {
    let dir = match game {
        Game::Supertuxkart => "supertuxkart",
        Game::Openarena => "openarena",
        Game::Teeworlds => "teeworlds",
        Game::FrozenBubble => "frozen-bubble",
        Game::Procedural => "",
    };
    format!("./usr/share/games/{dir}")
}

/// Whether the game's data is in the cache (procedural scenes always are).
pub fn is_fetched(game: Game) -> bool {
    game == Game::Procedural || package_root(game).join(MARKER).is_file()
}

/// The `package version` lines of the game's marker, if fetched.
pub fn fetched_versions(game: Game) -> Option<Vec<(String, String)>> {
    let text = std::fs::read_to_string(package_root(game).join(MARKER)).ok()?;
    Some(
        text.lines()
            .filter(|l| !l.starts_with('#'))
            .filter_map(|l| {
                let (p, v) = l.split_once(' ')?;
                Some((p.to_string(), v.trim().to_string()))
            })
            .collect(),
    )
}

/// The bytes `apt-get download` would fetch for the game's packages
/// (their sizes as `apt-get download --print-uris` lists them), or None
/// when apt cannot say (no apt, stale lists, unknown package).
pub fn download_bytes(game: Game) -> Option<u64> {
    if game == Game::Procedural {
        return Some(0);
    }
    let out = Command::new("apt-get")
        .args(["download", "--print-uris"])
        .args(game.packages())
        .stderr(Stdio::null())
        .output()
        .ok()?;
    if !out.status.success() {
        return None;
    }
    let sizes = print_uris_sizes(&String::from_utf8_lossy(&out.stdout));
    (sizes.len() == game.packages().len()).then(|| sizes.iter().sum())
}

/// The sizes in `apt-get download --print-uris` lines (`'URI' FILE SIZE
/// HASH`).
fn print_uris_sizes(text: &str) -> Vec<u64> {
    text.lines()
        .filter(|l| l.starts_with('\''))
        .filter_map(|l| l.split_whitespace().nth(2)?.parse().ok())
        .collect()
}

fn tool_missing(tool: &str) -> bool {
    Command::new(tool)
        .arg("--version")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .is_err()
}

fn run(cmd: &mut Command, what: &str, dir: &Path) -> Result<std::process::Output, SceneError> {
    let out = cmd
        .output()
        .map_err(|e| SceneError::in_file(dir, format!("{what}: cannot run: {e}")))?;
    if !out.status.success() {
        let err = String::from_utf8_lossy(&out.stderr);
        let tail: Vec<&str> = err.lines().rev().take(6).collect();
        let tail: Vec<&str> = tail.into_iter().rev().collect();
        return Err(SceneError::in_file(
            dir,
            format!("{what} failed ({}): {}", out.status, tail.join(" | ")),
        ));
    }
    Ok(out)
}

/// Download and unpack the game's packages into [`package_root`], replacing
/// an earlier copy, and write the marker. `progress` hears each step.
/// Returns the data root.
pub fn fetch(game: Game, progress: &mut dyn FnMut(&str)) -> Result<PathBuf, SceneError> {
    if game == Game::Procedural {
        progress("procedural scenes need no download");
        return Ok(PathBuf::new());
    }
    let cache = cache_dir();
    for tool in ["apt-get", "dpkg-deb", "tar"] {
        if tool_missing(tool) {
            return Err(SceneError::in_file(
                &cache,
                format!(
                    "`{tool}` not found: `wasp scenes fetch` uses Debian's apt-get and dpkg-deb \
                     (install apt and dpkg, or unpack the packages {} by hand into {} and \
                     write {MARKER} there)",
                    game.packages().join(", "),
                    package_root(game).display()
                ),
            ));
        }
    }
    std::fs::create_dir_all(&cache)
        .map_err(|e| SceneError::in_file(&cache, format!("cannot create the scene cache: {e}")))?;
    let pid = std::process::id();
    let download = cache.join(format!(".download-{}-{pid}", game.name()));
    let staging = cache.join(format!(".unpack-{}-{pid}", game.name()));
    let cleanup = |p: &Path| {
        let _ = std::fs::remove_dir_all(p);
    };
    cleanup(&download);
    cleanup(&staging);
    let result = (|| {
        std::fs::create_dir_all(&download)
            .and_then(|_| std::fs::create_dir_all(&staging))
            .map_err(|e| SceneError::in_file(&download, format!("cannot create: {e}")))?;
        let mut marker = format!("# fetched by wasp scenes fetch {}\n", game.name());
        for pkg in game.packages() {
            progress(&format!("downloading {pkg} (apt-get download)"));
            run(
                Command::new("apt-get")
                    .arg("download")
                    .arg(pkg)
                    .current_dir(&download),
                &format!("apt-get download {pkg}"),
                &download,
            )
            .map_err(|mut e| {
                e.message.push_str(
                    " (if the package is unknown or the lists are stale, run `apt-get update` \
                     as root first)",
                );
                e
            })?;
            let deb = std::fs::read_dir(&download)
                .map_err(|e| SceneError::in_file(&download, e.to_string()))?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .find(|p| {
                    p.file_name()
                        .and_then(|n| n.to_str())
                        .is_some_and(|n| n.starts_with(&format!("{pkg}_")) && n.ends_with(".deb"))
                })
                .ok_or_else(|| {
                    SceneError::in_file(
                        &download,
                        format!("apt-get download {pkg} left no {pkg}_*.deb"),
                    )
                })?;
            let version = run(
                Command::new("dpkg-deb")
                    .args(["-f"])
                    .arg(&deb)
                    .arg("Version"),
                "dpkg-deb -f",
                &deb,
            )?;
            let version = String::from_utf8_lossy(&version.stdout).trim().to_string();
            progress(&format!("unpacking {pkg} {version}"));
            // dpkg-deb --fsys-tarfile DEB | tar -x -C STAGING GAME-DATA DOC
            let mut dpkg = Command::new("dpkg-deb")
                .arg("--fsys-tarfile")
                .arg(&deb)
                .stdout(Stdio::piped())
                .stderr(Stdio::piped())
                .spawn()
                .map_err(|e| SceneError::in_file(&deb, format!("dpkg-deb: cannot run: {e}")))?;
            let tar_in = dpkg.stdout.take().expect("piped");
            let tar = run(
                Command::new("tar")
                    .arg("-x")
                    .arg("-C")
                    .arg(&staging)
                    .arg(games_subtree(game))
                    .arg(format!("./usr/share/doc/{pkg}"))
                    .stdin(tar_in),
                "tar -x",
                &deb,
            );
            let dpkg_out = dpkg
                .wait_with_output()
                .map_err(|e| SceneError::in_file(&deb, format!("dpkg-deb: {e}")))?;
            // A tar failure is the cause when both fail (dpkg-deb then dies
            // of a broken pipe).
            tar?;
            if !dpkg_out.status.success() {
                return Err(SceneError::in_file(
                    &deb,
                    format!(
                        "dpkg-deb --fsys-tarfile failed ({}): {}",
                        dpkg_out.status,
                        String::from_utf8_lossy(&dpkg_out.stderr).trim()
                    ),
                ));
            }
            std::fs::remove_file(&deb).map_err(|e| SceneError::in_file(&deb, e.to_string()))?;
            marker.push_str(&format!("{pkg} {version}\n"));
        }
        let data = staging.join(data_subdir(game));
        if !data.is_dir() {
            return Err(SceneError::in_file(
                &data,
                "the unpacked packages have no data directory here (the package layout \
                 changed?)",
            ));
        }
        std::fs::write(staging.join(MARKER), marker)
            .map_err(|e| SceneError::in_file(&staging, format!("writing the marker: {e}")))?;
        let root = package_root(game);
        cleanup(&root);
        std::fs::rename(&staging, &root).map_err(|e| {
            SceneError::in_file(&root, format!("moving the unpacked data in place: {e}"))
        })?;
        Ok(data_root(game))
    })();
    cleanup(&download);
    cleanup(&staging);
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layout_of_the_cache() {
        for g in Game::ALL {
            if g != Game::Procedural {
                let r = data_root(g);
                assert!(r.starts_with(package_root(g)));
                assert!(r.to_string_lossy().contains("usr/share/games"));
                assert!(games_subtree(g).starts_with("./usr/share/games/"));
            }
        }
        assert!(is_fetched(Game::Procedural));
    }

    #[test]
    fn download_sizes_come_from_the_print_uris_lines() {
        let text =
            "'http://deb.debian.org/debian/pool/main/t/teeworlds/teeworlds-data_0.7.5-2_all.deb' \
                    teeworlds-data_0.7.5-2_all.deb 7633736 SHA256:b867\n\
                    'http://x/a.deb' a_1_all.deb 10 SHA256:00\n\
                    Reading package lists...\n";
        assert_eq!(print_uris_sizes(text), [7_633_736, 10]);
        assert_eq!(download_bytes(Game::Procedural), Some(0));
    }
}
