//! The `--scenes-dir` option, offered by the commands that read scene
//! definitions (`scenes list`, `scenes capture`, `render`, `characterize`,
//! `reproduce`, `sweep`, `merge --sweep`) and by no other.

use crate::cli_error::CliError;
use clap::Args;
use std::path::PathBuf;

/// A folder of extra scene definitions.
#[derive(Args, Debug, Clone, Default)]
pub struct ScenesDir {
    /// A folder of extra scene definitions (*.toml): they add scenes or
    /// replace a shipped one of the same name (the shipped ones are built
    /// into the binary). Also WASP_SCENES_DIR.
    #[arg(long, value_name = "DIR")]
    pub scenes_dir: Option<PathBuf>,
}

impl ScenesDir {
    /// Make the folder, if given, the one scene definitions are read from.
    pub fn apply(&self) -> Result<(), CliError> {
        let Some(d) = &self.scenes_dir else {
            return Ok(());
        };
        if !d.is_dir() {
            return Err(CliError::usage(format!(
                "--scenes-dir {}: not a folder of scene definitions",
                d.display()
            )));
        }
        wasp_frontend::def::set_scenes_dir(d.clone());
        Ok(())
    }
}
