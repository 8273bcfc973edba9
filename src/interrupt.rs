//! What an interrupted study says: `wasp reproduce` and `wasp sweep` store
//! every finished point as it ends (atomically), so Ctrl-C loses only the
//! points being run, and the same command run again resumes from the
//! rest. The handler says so and ends the process as SIGINT would.

use std::path::Path;
use std::sync::OnceLock;

/// The message, composed before the handler is installed (a signal handler
/// may only call async-signal-safe functions: it writes these bytes).
static MESSAGE: OnceLock<Vec<u8>> = OnceLock::new();

/// On SIGINT, say that the finished points in `dir` are kept and that
/// `again` (the command, as the user would retype it) resumes, then end
/// with the conventional status 130.
pub fn say_resume_on_interrupt(dir: &Path, again: &str) {
    let text = format!(
        "\nwasp: interrupted: the finished points are kept in {}; run `{again}` again to \
         resume (only the unfinished points run)\n",
        dir.display()
    );
    if MESSAGE.set(text.into_bytes()).is_err() {
        return;
    }
    #[cfg(unix)]
    // SAFETY: installs a handler that only calls write(2) and _exit(2),
    // both async-signal-safe, on a message set once before installation.
    unsafe {
        libc::signal(
            libc::SIGINT,
            on_interrupt as extern "C" fn(libc::c_int) as libc::sighandler_t,
        );
    }
}

#[cfg(unix)]
extern "C" fn on_interrupt(_: libc::c_int) {
    if let Some(m) = MESSAGE.get() {
        // SAFETY: write(2) of a static buffer to standard error.
        unsafe {
            libc::write(2, m.as_ptr().cast(), m.len());
        }
    }
    // SAFETY: _exit(2) ends the process without running anything else.
    unsafe { libc::_exit(130) }
}

/// The command line that started this process, quoted for a shell.
pub fn command_line() -> String {
    std::env::args()
        .enumerate()
        .map(|(i, a)| {
            if i == 0 {
                "wasp".to_string()
            } else {
                crate::study::jobs::shell_quote(&a)
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}
