//! `wasp scenes`: its options and the dispatch to `list`, `fetch` and
//! `capture`.

use super::fetch::{self, FetchArgs};
use super::list::{self, ListArgs};
use crate::cli_error::CliError;
use crate::scenes_dir::ScenesDir;
use clap::{Args, Subcommand};

/// Options of `wasp scenes`.
#[derive(Args, Debug, Clone)]
pub struct ScenesArgs {
    #[command(subcommand)]
    pub command: ScenesCommand,
    /// No progress output on stderr (as `-q` after `list` or `fetch`).
    #[arg(long, short)]
    pub quiet: bool,
}

impl ScenesArgs {
    /// The `-q` of `list` or `fetch`, set also by a `-q` before them.
    pub fn quiet_mut(&mut self) -> &mut bool {
        let before = self.quiet;
        let q = match &mut self.command {
            ScenesCommand::List(a) => &mut a.quiet,
            ScenesCommand::Fetch(a) => &mut a.quiet,
            ScenesCommand::Capture(a) => &mut a.quiet,
        };
        *q |= before;
        q
    }

    /// The `--scenes-dir` of `scenes list` and `scenes capture` (fetching
    /// reads no definition).
    pub fn scenes_dir(&self) -> Option<&ScenesDir> {
        match &self.command {
            ScenesCommand::List(a) => Some(&a.scene_defs),
            ScenesCommand::Capture(a) => Some(&a.scene_defs),
            ScenesCommand::Fetch(_) => None,
        }
    }
}

/// `wasp scenes list|fetch`.
#[derive(Subcommand, Debug, Clone)]
pub enum ScenesCommand {
    /// List the scene definitions (built in, plus --scenes-dir) and whether their game
    /// data is in the cache.
    List(ListArgs),
    /// Download a game's Debian packages (apt-get download) and unpack
    /// them (dpkg-deb) into the scene cache: $WASP_SCENES, else
    /// $XDG_CACHE_HOME/wasp/scenes, else ~/.cache/wasp/scenes. Needs a
    /// Debian-family host (apt-get, dpkg-deb); all four games are about
    /// 835 MB to download and 0.9 GB unpacked.
    Fetch(FetchArgs),
    /// Run a game's own engine headless (xvfb-run) at an engine-route
    /// scene's camera and resolution under apitrace, and store the capture
    /// in the scene cache (captures/SCENE.trace, with SCENE.json beside
    /// it). Needs the game's Debian package (openarena, or teeworlds and
    /// teeworlds-server), xvfb and apitrace; installs nothing.
    Capture(crate::capture::CaptureArgs),
}

/// Run `wasp scenes`.
pub fn scenes(args: &ScenesArgs) -> Result<(), CliError> {
    match &args.command {
        ScenesCommand::List(_) => list::list(),
        ScenesCommand::Fetch(f) => fetch::fetch(f),
        ScenesCommand::Capture(a) => crate::capture::capture(a),
    }
}
