//! The command line's output options, one grammar for every subcommand:
//! an output option takes a FILE, `-` naming standard output; at most one
//! output of a command goes to standard output; no output names an input
//! of the command or another output; and every output is checked before
//! any work (a file in a folder that does not exist fails at once, naming
//! the path, not after a long simulation). Every file is written to a
//! temporary file in its folder and renamed into place ([`AtomicFile`]), so
//! a failed or interrupted run leaves the old file whole.

use crate::cli_error::CliError;
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

/// One input of a command that an output must not overwrite: a file
/// (`--trace`, `--config`, a sweep file) or a folder whose files of one
/// extension the command reads (`--scenes-dir`'s `*.toml`, a study's
/// `points/*.json`).
pub struct Input<'a> {
    /// The flag (or argument) as the user types it.
    pub flag: &'static str,
    /// Its value, if given.
    pub path: Option<&'a Path>,
    /// For a folder, the extension of the files the command reads in it:
    /// no output may be such a file there.
    pub folder: Option<&'static str>,
}

impl<'a> Input<'a> {
    /// An input file.
    pub fn file(flag: &'static str, path: Option<&'a Path>) -> Self {
        Self {
            flag,
            path,
            folder: None,
        }
    }

    /// An input folder whose `*.EXT` files the command reads.
    pub fn folder(flag: &'static str, path: Option<&'a Path>, ext: &'static str) -> Self {
        Self {
            flag,
            path,
            folder: Some(ext),
        }
    }
}

/// `path` made absolute with its links resolved, so that two spellings of
/// one file compare equal: the whole path when it exists, else its folder
/// (which must exist) joined with its name.
fn resolved(path: &Path) -> Option<PathBuf> {
    if let Ok(p) = path.canonicalize() {
        return Some(p);
    }
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    Some(folder.canonicalize().ok()?.join(path.file_name()?))
}

/// Whether `a` and `b` name the same file: the same resolved path, or (on
/// Unix) two links to one file.
fn same_file(a: &Path, b: &Path) -> bool {
    if let (Some(x), Some(y)) = (resolved(a), resolved(b)) {
        if x == y {
            return true;
        }
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if let (Ok(x), Ok(y)) = (std::fs::metadata(a), std::fs::metadata(b)) {
            return x.dev() == y.dev() && x.ino() == y.ino();
        }
    }
    false
}

/// Whether `file` lies inside the folder `dir`.
fn inside(file: &Path, dir: &Path) -> bool {
    match (resolved(file), dir.canonicalize()) {
        (Some(f), Ok(d)) => f.starts_with(d),
        _ => false,
    }
}

/// Check that no output names an input or lies in an input folder: an
/// error naming both, before any work is done.
fn not_an_input(flag: &str, path: &Path, inputs: &[Input]) -> Result<(), CliError> {
    for i in inputs {
        let Some(ip) = i.path.filter(|p| !is_stdout(p)) else {
            continue;
        };
        if let Some(ext) = i.folder {
            let read = path.extension().is_some_and(|e| e == ext);
            if read && inside(path, ip) {
                return Err(CliError::usage(format!(
                    "{flag} {}: {} {} holds the *.{ext} files this command reads; name a \
                     file elsewhere or of another kind",
                    path.display(),
                    i.flag,
                    ip.display()
                )));
            }
            continue;
        }
        if same_file(path, ip) {
            return Err(CliError::usage(format!(
                "{flag} {} names the same file as {} {}: the output would overwrite the \
                 input; name another file",
                path.display(),
                i.flag,
                ip.display()
            )));
        }
    }
    Ok(())
}

/// Check a command's outputs before it does any work: at most one goes to
/// standard output, no two name the same file, none names one of the
/// `inputs`, and every file can be created where it is named (its folder
/// exists; it is not a folder).
pub fn check(outputs: &[Output], inputs: &[Input]) -> Result<(), CliError> {
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
        if let Some((other, _)) = given[..i]
            .iter()
            .find(|(_, p)| !is_stdout(p) && (p == path || same_file(p, path)))
        {
            return Err(CliError::usage(format!(
                "{other} and {flag} both name {}: give each output its own file",
                path.display()
            )));
        }
        not_an_input(flag, path, inputs)?;
        writable(flag, path)?;
    }
    Ok(())
}

/// Check an output folder option before any work: `path`, if it exists,
/// must be a folder (`what` says what the command writes in it).
pub fn folder(flag: &str, path: &Path, what: &str) -> Result<(), CliError> {
    if path.exists() && !path.is_dir() {
        return Err(CliError::usage(format!(
            "{flag} {}: is a file; {flag} names a folder ({what}), made if missing",
            path.display()
        )));
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

/// Write `bytes` to FILE (through [`write_atomic`]), or to standard output
/// for `-`.
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<(), CliError> {
    if is_stdout(path) {
        let mut out = std::io::stdout().lock();
        out.write_all(bytes)
            .and_then(|_| out.flush())
            .map_err(|e| CliError::failed(format!("writing to standard output: {e}")))
    } else {
        write_atomic(path, bytes)
            .map_err(|e| CliError::failed(format!("cannot write {}: {e}", path.display())))
    }
}

/// Write `bytes` to `path` through a temporary file in the same folder,
/// renamed into place once whole: a reader never sees half a file, and a
/// failed write leaves the old file as it was. Every file wasp writes goes
/// through here or through [`AtomicFile`].
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let mut f = AtomicFile::create(path)?;
    f.write_all(bytes)?;
    f.commit()
}

/// A file being written: the bytes go to a temporary file beside `path`
/// (`.NAME.wasp-tmp-PID`), which [`AtomicFile::commit`] renames to `path`.
/// Dropped without a commit (an error on the way), it removes the
/// temporary file and leaves `path` untouched.
pub struct AtomicFile {
    path: PathBuf,
    tmp: PathBuf,
    out: Option<BufWriter<File>>,
}

impl AtomicFile {
    /// Start writing `path`.
    pub fn create(path: &Path) -> std::io::Result<Self> {
        let name = path.file_name().ok_or_else(|| {
            std::io::Error::new(std::io::ErrorKind::InvalidInput, "not a file name")
        })?;
        let mut tmp_name = std::ffi::OsString::from(".");
        tmp_name.push(name);
        tmp_name.push(format!(".wasp-tmp-{}", std::process::id()));
        let tmp = path.with_file_name(tmp_name);
        let file = File::create(&tmp)?;
        Ok(Self {
            path: path.to_path_buf(),
            tmp,
            out: Some(BufWriter::new(file)),
        })
    }

    /// Finish: flush, sync and rename the temporary file into place.
    pub fn commit(mut self) -> std::io::Result<()> {
        let out = self.out.take().expect("not committed yet");
        let file = out.into_inner().map_err(|e| e.into_error())?;
        file.sync_all()?;
        drop(file);
        let renamed = std::fs::rename(&self.tmp, &self.path);
        if renamed.is_err() {
            let _ = std::fs::remove_file(&self.tmp);
        }
        renamed
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.out.as_mut().expect("not committed").write(buf)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.out.as_mut().expect("not committed").flush()
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        if self.out.take().is_some() {
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}

/// Where a streamed output goes: standard output or an [`AtomicFile`].
pub enum Sink {
    /// Standard output (`-`).
    Stdout(BufWriter<std::io::Stdout>),
    /// A file, renamed into place by [`Sink::finish`].
    File(AtomicFile),
}

impl Sink {
    /// Finish the output: flush standard output, or commit the file.
    pub fn finish(self) -> std::io::Result<()> {
        match self {
            Sink::Stdout(mut w) => w.flush(),
            Sink::File(f) => f.commit(),
        }
    }
}

impl Write for Sink {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        match self {
            Sink::Stdout(w) => w.write(buf),
            Sink::File(f) => f.write(buf),
        }
    }
    fn flush(&mut self) -> std::io::Result<()> {
        match self {
            Sink::Stdout(w) => w.flush(),
            Sink::File(f) => f.flush(),
        }
    }
}

/// A writer to FILE (an [`AtomicFile`]), or to standard output for `-`;
/// [`Sink::finish`] ends it.
pub fn create(path: &Path) -> Result<Sink, CliError> {
    if is_stdout(path) {
        return Ok(Sink::Stdout(BufWriter::new(std::io::stdout())));
    }
    AtomicFile::create(path)
        .map(Sink::File)
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
        assert!(check(&ok, &[]).is_ok());
        let two = [
            Output::new("--json", Some(p("-"))),
            Output::new("--csv", Some(p("-"))),
        ];
        let e = check(&two, &[]).unwrap_err().to_string();
        assert!(
            e.starts_with("--json - and --csv -: only one output can go to standard output"),
            "{e}"
        );
    }

    #[test]
    fn files_are_checked_before_any_work() {
        let e = check(
            &[Output::new("--csv", Some(p("/nonexistent/dir/x.csv")))],
            &[],
        )
        .unwrap_err()
        .to_string();
        assert_eq!(
            e,
            "--csv /nonexistent/dir/x.csv: the folder /nonexistent/dir does not exist"
        );
        let tmp = std::env::temp_dir();
        let e = check(&[Output::new("--json", Some(&tmp))], &[])
            .unwrap_err()
            .to_string();
        assert!(e.ends_with("is a folder; name a file"), "{e}");
        let same = [
            Output::new("--json", Some(p("a.out"))),
            Output::new("--csv", Some(p("a.out"))),
        ];
        let e = check(&same, &[]).unwrap_err().to_string();
        assert!(e.starts_with("--json and --csv both name a.out"), "{e}");
        // A bare file name is in the current folder.
        assert!(check(&[Output::new("--json", Some(p("x.json")))], &[]).is_ok());
        // A folder that takes no files (even for root: /proc).
        if cfg!(target_os = "linux") {
            let e = check(&[Output::new("--json", Some(p("/proc/x.json")))], &[])
                .unwrap_err()
                .to_string();
            assert!(
                e.starts_with("--json /proc/x.json: cannot write in the folder /proc: "),
                "{e}"
            );
        }
        let e = check(&[Output::file_only("--timeline", Some(p("-")))], &[])
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("--timeline -: this output is a picture"),
            "{e}"
        );
    }

    /// A fresh folder under the system's temporary folder.
    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("wasp-output-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn no_output_names_an_input() {
        let d = scratch("inputs");
        let trace = d.join("in.trace");
        std::fs::write(&trace, "x").unwrap();
        // Another spelling of the same file.
        let other = d.join(".").join("in.trace");
        let e = check(
            &[Output::new("--json", Some(&other))],
            &[Input::file("--trace", Some(&trace))],
        )
        .unwrap_err()
        .to_string();
        assert!(e.starts_with("--json "), "{e}");
        assert!(e.contains("names the same file as --trace"), "{e}");
        let inside = d.join("x.json");
        let e = check(
            &[Output::new("--json", Some(&inside))],
            &[Input::folder("the study folder", Some(&d), "json")],
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("the study folder"), "{e}");
        // Files of another kind in the folder are not read: they may be
        // written.
        assert!(check(
            &[Output::new("--json", Some(&inside))],
            &[Input::folder("--scenes-dir", Some(&d), "toml")]
        )
        .is_ok());
        // Another file, or standard output, is fine.
        assert!(check(
            &[Output::new("--json", Some(&d.join("out.json")))],
            &[Input::file("--trace", Some(&trace))]
        )
        .is_ok());
        assert!(check(
            &[Output::new("--json", Some(p("-")))],
            &[Input::file("--trace", Some(&trace))]
        )
        .is_ok());
        // Two spellings of one output.
        let e = check(
            &[
                Output::new("--json", Some(&inside)),
                Output::new("--csv", Some(&d.join(".").join("x.json"))),
            ],
            &[],
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("both name"), "{e}");
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn atomic_writes_replace_whole_or_not_at_all() {
        let d = scratch("atomic");
        let f = d.join("out.json");
        std::fs::write(&f, "old").unwrap();
        // An abandoned write (an error on the way) leaves the old file and
        // no temporary file.
        {
            let mut w = AtomicFile::create(&f).unwrap();
            w.write_all(b"half a new fi").unwrap();
        }
        assert_eq!(std::fs::read_to_string(&f).unwrap(), "old");
        assert_eq!(std::fs::read_dir(&d).unwrap().count(), 1);
        // While the new file is written, the old one is still whole.
        let mut w = AtomicFile::create(&f).unwrap();
        w.write_all(b"new").unwrap();
        w.flush().unwrap();
        assert_eq!(std::fs::read_to_string(&f).unwrap(), "old");
        w.commit().unwrap();
        assert_eq!(std::fs::read_to_string(&f).unwrap(), "new");
        assert_eq!(std::fs::read_dir(&d).unwrap().count(), 1);
        write_atomic(&f, b"newer").unwrap();
        assert_eq!(std::fs::read_to_string(&f).unwrap(), "newer");
        // A folder that does not exist fails before anything is written.
        assert!(write_atomic(&d.join("no/such.json"), b"x").is_err());
        std::fs::remove_dir_all(&d).unwrap();
    }
}
