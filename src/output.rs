//! The command line's output options, one grammar for every subcommand:
//! an output option takes a FILE, `-` naming standard output; at most one
//! output of a command goes to standard output; and every output is
//! checked before any work (a file in a folder that does not exist fails at
//! once, naming the path, not after a long simulation).

use crate::CliError;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Whether `path` names standard output (`-`).
pub fn is_stdout(path: &Path) -> bool {
    path.as_os_str() == "-"
}

/// Whether the option `path` (if given) names standard output.
pub fn to_stdout(path: &Option<PathBuf>) -> bool {
    path.as_deref().is_some_and(is_stdout)
}

/// One output option of a command: its flag (`--json`) and its value.
pub struct Output<'a> {
    /// The flag as the user types it.
    pub flag: &'static str,
    /// Its value, if given.
    pub path: Option<&'a Path>,
    /// Whether `-` (standard output) is allowed: not for a picture whose
    /// format comes from its file name.
    pub stdout_ok: bool,
}

impl<'a> Output<'a> {
    /// An output that may go to standard output.
    pub fn new(flag: &'static str, path: Option<&'a Path>) -> Self {
        Self {
            flag,
            path,
            stdout_ok: true,
        }
    }

    /// An output that must be a file (a picture named by its extension).
    pub fn file_only(flag: &'static str, path: Option<&'a Path>) -> Self {
        Self {
            flag,
            path,
            stdout_ok: false,
        }
    }
}

/// Check a command's outputs before it does any work: at most one goes to
/// standard output, no two name the same file, and every file can be
/// created where it is named (its folder exists; it is not a folder).
pub fn check(outputs: &[Output]) -> Result<(), CliError> {
    let given: Vec<(&str, &Path)> = outputs
        .iter()
        .filter_map(|o| o.path.map(|p| (o.flag, p)))
        .collect();
    if let Some(o) = outputs
        .iter()
        .find(|o| !o.stdout_ok && o.path.is_some_and(is_stdout))
    {
        return Err(CliError::usage(format!(
            "{} -: this output is a picture whose format comes from its file name (.png or \
             .svg); name a file",
            o.flag
        )));
    }
    let on_stdout: Vec<&str> = given
        .iter()
        .filter(|(_, p)| is_stdout(p))
        .map(|(f, _)| *f)
        .collect();
    if on_stdout.len() > 1 {
        return Err(CliError::usage(format!(
            "{}: only one output can go to standard output (`-`); name a file for the others",
            on_stdout
                .iter()
                .map(|f| format!("{f} -"))
                .collect::<Vec<_>>()
                .join(" and ")
        )));
    }
    for (i, (flag, path)) in given.iter().enumerate() {
        if is_stdout(path) {
            continue;
        }
        if let Some((other, _)) = given[..i].iter().find(|(_, p)| p == path) {
            return Err(CliError::usage(format!(
                "{other} and {flag} both name {}: give each output its own file",
                path.display()
            )));
        }
        writable(flag, path)?;
    }
    Ok(())
}

/// Whether a file can be created at `path`: its folder exists, it is not
/// itself a folder, and a file can be made in that folder (tried with a
/// probe file, removed at once: permissions, a read-only file system or a
/// full disk fail here, not after the work). `flag` names the option in
/// the error.
pub fn writable(flag: &str, path: &Path) -> Result<(), CliError> {
    if path.is_dir() {
        return Err(CliError::usage(format!(
            "{flag} {}: is a folder; name a file",
            path.display()
        )));
    }
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if !folder.exists() {
        return Err(CliError::usage(format!(
            "{flag} {}: the folder {} does not exist",
            path.display(),
            folder.display()
        )));
    }
    if !folder.is_dir() {
        return Err(CliError::usage(format!(
            "{flag} {}: {} is not a folder",
            path.display(),
            folder.display()
        )));
    }
    let probe = folder.join(format!(".wasp-probe-{}", std::process::id()));
    match std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&probe)
    {
        Ok(_) => {
            let _ = std::fs::remove_file(&probe);
            Ok(())
        }
        // A probe left by an earlier process of this id: the folder took it.
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => Ok(()),
        Err(e) => Err(CliError::usage(format!(
            "{flag} {}: cannot write in the folder {}: {e}",
            path.display(),
            folder.display()
        ))),
    }
}

/// Write `text` to FILE, or to standard output for `-`.
pub fn emit(path: &Path, text: &str) -> Result<(), CliError> {
    write_bytes(path, text.as_bytes())
}

/// Write `bytes` to FILE, or to standard output for `-`.
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<(), CliError> {
    if is_stdout(path) {
        let mut out = std::io::stdout().lock();
        out.write_all(bytes)
            .and_then(|_| out.flush())
            .map_err(|e| CliError::failed(format!("writing to standard output: {e}")))
    } else {
        std::fs::write(path, bytes)
            .map_err(|e| CliError::failed(format!("cannot write {}: {e}", path.display())))
    }
}

/// A buffered writer to FILE, or to standard output for `-`.
pub fn create(path: &Path) -> Result<Box<dyn Write>, CliError> {
    if is_stdout(path) {
        return Ok(Box::new(BufWriter::new(std::io::stdout())));
    }
    File::create(path)
        .map(|f| Box::new(BufWriter::new(f)) as Box<dyn Write>)
        .map_err(|e| CliError::failed(format!("cannot create {}: {e}", path.display())))
}

/// How an output is named in messages: its path, or `standard output`.
pub fn name(path: &Path) -> String {
    if is_stdout(path) {
        "standard output".into()
    } else {
        path.display().to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(s: &str) -> &Path {
        Path::new(s)
    }

    #[test]
    fn one_output_on_standard_output_at_most() {
        let ok = [
            Output::new("--json", Some(p("-"))),
            Output::new("--csv", None),
        ];
        assert!(check(&ok).is_ok());
        let two = [
            Output::new("--json", Some(p("-"))),
            Output::new("--csv", Some(p("-"))),
        ];
        let e = check(&two).unwrap_err().to_string();
        assert!(
            e.starts_with("--json - and --csv -: only one output can go to standard output"),
            "{e}"
        );
    }

    #[test]
    fn files_are_checked_before_any_work() {
        let e = check(&[Output::new("--csv", Some(p("/nonexistent/dir/x.csv")))])
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "--csv /nonexistent/dir/x.csv: the folder /nonexistent/dir does not exist"
        );
        let tmp = std::env::temp_dir();
        let e = check(&[Output::new("--json", Some(&tmp))])
            .unwrap_err()
            .to_string();
        assert!(e.ends_with("is a folder; name a file"), "{e}");
        let same = [
            Output::new("--json", Some(p("a.out"))),
            Output::new("--csv", Some(p("a.out"))),
        ];
        let e = check(&same).unwrap_err().to_string();
        assert!(e.starts_with("--json and --csv both name a.out"), "{e}");
        // A bare file name is in the current folder.
        assert!(check(&[Output::new("--json", Some(p("x.json")))]).is_ok());
        // A folder that takes no files (even for root: /proc).
        if cfg!(target_os = "linux") {
            let e = check(&[Output::new("--json", Some(p("/proc/x.json")))])
                .unwrap_err()
                .to_string();
            assert!(
                e.starts_with("--json /proc/x.json: cannot write in the folder /proc: "),
                "{e}"
            );
        }
        let e = check(&[Output::file_only("--timeline", Some(p("-")))])
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("--timeline -: this output is a picture"),
            "{e}"
        );
    }
}
