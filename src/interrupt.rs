//! Ctrl-C: the one handler of the process (through `ctrlc`, for SIGINT,
//! SIGTERM and SIGHUP), which runs the action the command registered last
//! and ends with status 130; and what an interrupted study says: `wasp
//! reproduce` and `wasp sweep` store every finished point as it ends
//! (atomically), so Ctrl-C loses only the points being run, and the same
//! command run again resumes from the rest.

use std::path::Path;
use std::sync::{Mutex, OnceLock, PoisonError};

/// What the handler does before it ends the process: the action the
/// running command registered last (a study's message, a capture's
/// clean-up).
type Action = Box<dyn Fn() + Send>;

/// The action registered last, if any.
static ACTION: Mutex<Option<Action>> = Mutex::new(None);

/// On Ctrl-C (SIGINT, and SIGTERM or SIGHUP too), run `action` and end
/// with the conventional status 130. The handler is installed once,
/// through `ctrlc`, and runs on a thread of its own, so `action` may do
/// anything; a later call replaces the action.
pub fn on_interrupt(action: impl Fn() + Send + 'static) {
    static INSTALLED: OnceLock<()> = OnceLock::new();
    *ACTION.lock().unwrap_or_else(PoisonError::into_inner) = Some(Box::new(action));
    INSTALLED.get_or_init(|| {
        if let Err(e) = ctrlc::set_handler(run_action) {
            eprintln!("wasp: cannot catch Ctrl-C: {e}");
        }
    });
}

/// The handler: the registered action, then exit status 130.
fn run_action() {
    if let Some(action) = ACTION
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .as_ref()
    {
        action();
    }
    std::process::exit(130)
}

/// On Ctrl-C, say that the finished points in `dir` are kept and that
/// `again` (the command, as the user would retype it) resumes, then end
/// with status 130.
pub fn say_resume_on_interrupt(dir: &Path, again: &str) {
    let text = format!(
        "\nwasp: interrupted: the finished points are kept in {}; run `{again}` again to \
         resume (only the unfinished points run)\n",
        dir.display()
    );
    on_interrupt(move || eprint!("{text}"));
}
