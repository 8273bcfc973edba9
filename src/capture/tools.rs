//! What a capture needs on the host and how its processes are run: the
//! Debian packages and programs each engine needs (checked, never
//! installed: a missing one is an error giving the `apt-get install`
//! line), a temporary work folder, and child processes run in a process
//! group of their own that is always stopped (TERM, then KILL) when the
//! run ends, fails or passes its deadline.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitStatus, Stdio};
use std::sync::atomic::{AtomicI32, Ordering};
use std::time::{Duration, Instant};

/// The process group running now (0: none), for the interrupt handler.
static RUNNING: AtomicI32 = AtomicI32::new(0);

/// On Ctrl-C, SIGTERM or SIGHUP (one handler, through `ctrlc`), stop the
/// running process group (TERM, then KILL a second later), remove the
/// partial capture `partial` and end with status 130: the engine, Xvfb
/// and a game server never outlive wasp.
pub fn stop_groups_on_interrupt(partial: &Path) {
    let partial = partial.to_path_buf();
    crate::interrupt::on_interrupt(move || {
        let pg = RUNNING.load(Ordering::SeqCst);
        if pg > 0 {
            // TERM first, so that Xvfb removes its display's lock file,
            // then KILL whatever is left a second later.
            signal_group(pg, libc::SIGTERM);
            std::thread::sleep(Duration::from_secs(1));
            signal_group(pg, libc::SIGKILL);
        }
        let _ = std::fs::remove_file(&partial);
        eprint!("\nwasp: capture interrupted: the engine is stopped, nothing is kept\n");
    });
}

/// Send `sig` to every process of group `pg`; whether the group exists.
/// Signals sent, not caught, so `libc` rather than `ctrlc`.
fn signal_group(pg: libc::pid_t, sig: libc::c_int) -> bool {
    // SAFETY: kill(2) with a negative pid signals the process group we
    // created (its id is the leader's pid); no memory is involved.
    unsafe { libc::kill(-pg, sig) == 0 }
}

/// A program a capture runs and the Debian package that ships it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Need {
    /// Program (absolute path, or a name looked up on PATH).
    pub program: &'static str,
    /// Debian package.
    pub package: &'static str,
}

/// What every capture needs besides its engine: Xvfb and apitrace.
pub const COMMON_NEEDS: [Need; 2] = [
    Need {
        program: "xvfb-run",
        package: "xvfb",
    },
    Need {
        program: "apitrace",
        package: "apitrace",
    },
];

/// `program` as found: itself if absolute, else the first match on PATH
/// (and `/usr/sbin`, `/sbin`, where `ip` lives).
pub fn find_program(program: &str) -> Option<PathBuf> {
    let p = Path::new(program);
    if p.is_absolute() {
        return p.is_file().then(|| p.to_path_buf());
    }
    let path = std::env::var_os("PATH").unwrap_or_default();
    std::env::split_paths(&path)
        .chain(["/usr/sbin", "/sbin", "/usr/games"].map(PathBuf::from))
        .map(|d| d.join(program))
        .find(|c| c.is_file())
}

/// The installed version of Debian package `pkg` (`dpkg-query`), if any.
fn package_version(pkg: &str) -> Option<String> {
    let out = Command::new("dpkg-query")
        .args(["-W", "-f=${Status}\t${Version}", pkg])
        .stderr(Stdio::null())
        .output()
        .ok()?;
    let text = String::from_utf8_lossy(&out.stdout);
    let (status, version) = text.split_once('\t')?;
    (out.status.success() && status.ends_with(" installed")).then(|| version.to_string())
}

/// The error for the packages whose programs are missing.
pub fn missing_message(missing: &[Need]) -> String {
    let mut pkgs: Vec<&str> = missing.iter().map(|n| n.package).collect();
    pkgs.dedup();
    let progs: Vec<String> = missing
        .iter()
        .map(|n| format!("{} ({})", n.program, n.package))
        .collect();
    format!(
        "not installed: {}. wasp installs nothing itself; install them (as root) with:\n    \
         apt-get install {}",
        progs.join(", "),
        pkgs.join(" ")
    )
}

/// Check that every program of `needs` is there; the packages' versions
/// (`?` where dpkg cannot say), or the error naming the `apt-get install`
/// line.
pub fn check(needs: &[Need]) -> Result<Vec<(String, String)>, String> {
    let missing: Vec<Need> = needs
        .iter()
        .copied()
        .filter(|n| find_program(n.program).is_none())
        .collect();
    if !missing.is_empty() {
        return Err(missing_message(&missing));
    }
    Ok(needs
        .iter()
        .map(|n| {
            let v = package_version(n.package).unwrap_or_else(|| "?".into());
            (n.package.to_string(), v)
        })
        .collect())
}

/// A temporary folder removed when dropped.
pub struct WorkDir(pub PathBuf);

impl WorkDir {
    /// A fresh folder for scene `name` under the system's temporary folder.
    pub fn new(name: &str) -> Result<Self, String> {
        let d = std::env::temp_dir().join(format!("wasp-capture-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).map_err(|e| format!("{}: cannot create: {e}", d.display()))?;
        Ok(Self(d))
    }
}

impl Drop for WorkDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// A child process leading a process group of its own; dropping it stops
/// the whole group (the engine, Xvfb, a game server).
pub struct Group {
    child: Child,
    pub started: Instant,
}

impl Group {
    /// Start `cmd` as the leader of a new process group, its standard
    /// output and error into `log`.
    pub fn spawn(cmd: &mut Command, log: &Path) -> Result<Self, String> {
        use std::os::unix::process::CommandExt;
        let out = std::fs::File::create(log)
            .map_err(|e| format!("{}: cannot create: {e}", log.display()))?;
        let err = out.try_clone().map_err(|e| e.to_string())?;
        let child = cmd
            .process_group(0)
            .stdin(Stdio::null())
            .stdout(out)
            .stderr(err)
            .spawn()
            .map_err(|e| format!("cannot run {:?}: {e}", cmd.get_program()))?;
        RUNNING.store(child.id() as i32, Ordering::SeqCst);
        Ok(Self {
            child,
            started: Instant::now(),
        })
    }

    /// Send `sig` to every process of the group.
    pub fn signal(&self, sig: libc::c_int) {
        signal_group(self.child.id() as libc::pid_t, sig);
    }

    /// The leader's exit status, if it has ended.
    pub fn try_wait(&mut self) -> Result<Option<ExitStatus>, String> {
        self.child.try_wait().map_err(|e| e.to_string())
    }

    /// Wait until the leader ends or `deadline` passes (then stop the
    /// group and say so); `tick` runs every 200 ms while waiting.
    pub fn wait_until(
        &mut self,
        deadline: Instant,
        what: &str,
        tick: &mut dyn FnMut(),
    ) -> Result<ExitStatus, String> {
        loop {
            if let Some(s) = self.try_wait()? {
                return Ok(s);
            }
            if Instant::now() >= deadline {
                self.stop();
                return Err(format!(
                    "{what} did not finish within {:.0} s: stopped",
                    deadline.duration_since(self.started).as_secs_f64()
                ));
            }
            tick();
            std::thread::sleep(Duration::from_millis(200));
        }
    }

    /// Stop the group: TERM, then KILL after 3 s if any process remains.
    pub fn stop(&mut self) {
        self.signal(libc::SIGTERM);
        let t = Instant::now();
        while t.elapsed() < Duration::from_secs(3) {
            if matches!(self.child.try_wait(), Ok(Some(_))) && !self.group_alive() {
                return;
            }
            std::thread::sleep(Duration::from_millis(100));
        }
        self.signal(libc::SIGKILL);
        let _ = self.child.wait();
    }

    /// Forget the group in the interrupt handler once it is gone.
    fn forget(&self) {
        let _ = RUNNING.compare_exchange(
            self.child.id() as i32,
            0,
            Ordering::SeqCst,
            Ordering::SeqCst,
        );
    }

    /// Whether any process of the group is still there.
    fn group_alive(&self) -> bool {
        // Signal 0 only checks that the group exists.
        signal_group(self.child.id() as libc::pid_t, 0)
    }
}

impl Drop for Group {
    fn drop(&mut self) {
        if !matches!(self.child.try_wait(), Ok(Some(_))) || self.group_alive() {
            self.stop();
        }
        self.forget();
    }
}

/// The text of `path` (lossy), or empty.
pub fn read_log(path: &Path) -> String {
    let mut s = Vec::new();
    if let Ok(mut f) = std::fs::File::open(path) {
        let _ = f.read_to_end(&mut s);
    }
    String::from_utf8_lossy(&s).into_owned()
}

/// The last `n` lines of `text`, joined with ` | `.
pub fn tail(text: &str, n: usize) -> String {
    let lines: Vec<&str> = text.lines().filter(|l| !l.trim().is_empty()).collect();
    lines[lines.len().saturating_sub(n)..].join(" | ")
}

/// Frames in an apitrace capture (`apitrace info`: its `FramesCount`).
pub fn frame_count(trace: &Path) -> Result<u64, String> {
    let out = Command::new("apitrace")
        .arg("info")
        .arg(trace)
        .output()
        .map_err(|e| format!("apitrace info: cannot run: {e}"))?;
    let text = String::from_utf8_lossy(&out.stdout);
    let v: serde_json::Value = serde_json::from_str(&text).map_err(|e| {
        format!(
            "{}: apitrace info gave no JSON ({e}): {}",
            trace.display(),
            tail(&String::from_utf8_lossy(&out.stderr), 3)
        )
    })?;
    v.get("FramesCount")
        .and_then(|f| f.as_u64())
        .ok_or_else(|| format!("{}: apitrace info has no FramesCount", trace.display()))
}

/// The quoted command line of `cmd`, program first.
pub fn command_line(cmd: &Command) -> Vec<String> {
    std::iter::once(cmd.get_program())
        .chain(cmd.get_args())
        .map(|a| a.to_string_lossy().into_owned())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_missing_program_names_the_apt_get_line() {
        let needs = [
            Need {
                program: "/nonexistent/wasp-test/openarena",
                package: "openarena",
            },
            Need {
                program: "wasp-no-such-program-xvfb-run",
                package: "xvfb",
            },
            Need {
                program: "sh",
                package: "dash",
            },
        ];
        let e = check(&needs).unwrap_err();
        assert!(e.contains("\n    apt-get install openarena xvfb"), "{e}");
        assert!(!e.contains("dash"), "{e}");
        assert!(
            e.contains("/nonexistent/wasp-test/openarena (openarena)"),
            "{e}"
        );
    }

    #[test]
    fn a_group_past_its_deadline_is_stopped() {
        let d = WorkDir::new("group-test").unwrap();
        let log = d.0.join("log");
        let mut g =
            Group::spawn(Command::new("sh").args(["-c", "sleep 30 & sleep 30"]), &log).unwrap();
        let t = Instant::now();
        let e = g
            .wait_until(
                Instant::now() + Duration::from_millis(300),
                "sleep",
                &mut || {},
            )
            .unwrap_err();
        assert!(e.contains("sleep did not finish"), "{e}");
        assert!(t.elapsed() < Duration::from_secs(5));
        assert!(!g.group_alive(), "the background sleep is stopped too");
    }

    #[test]
    fn tails_skip_blank_lines() {
        assert_eq!(tail("a\n\nb\nc\n", 2), "b | c");
        assert_eq!(tail("", 3), "");
    }
}
