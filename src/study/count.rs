//! What a study's run would do, counted without running it (`wasp
//! reproduce --dry-run`): its tasks resolved to their keys as the runner
//! resolves them, with nothing fetched, captured or run.

use super::cache::Cache;
use super::runner::{capture_engines, resolve, RunnerOptions, Scenes, Task};

/// What a run of some tasks would do, counted without running them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Counts {
    /// Tasks.
    pub tasks: usize,
    /// Tasks to run (distinct and not stored).
    pub to_run: usize,
    /// Tasks whose result is stored already.
    pub done: usize,
    /// Tasks on the same machine as an earlier task (sharing its result).
    pub same: usize,
    /// Tasks that would fail at once (an engine scene without a capture).
    pub failing: usize,
}

/// Count what [`runner::run`](super::runner::run) would do with `tasks` and `cache`, running, fetching
/// and capturing nothing. A loader scene whose game data is not fetched
/// has another identity once fetched (its package versions), so its
/// stored results count as done only with the data in the scene cache.
pub fn count(tasks: &[Task], cache: &Cache, opts: &RunnerOptions) -> Result<Counts, String> {
    let mut scenes = Scenes::with(&opts.scenes);
    let offline = RunnerOptions {
        fetch: false,
        ..opts.clone()
    };
    let uncaptured = capture_engines(tasks, &mut scenes, &offline)?;
    let (out, todo) = resolve(tasks, cache, &mut scenes, &uncaptured)?;
    Ok(Counts {
        tasks: tasks.len(),
        to_run: todo.len(),
        done: out.cached,
        same: out.same,
        failing: out.failures.len(),
    })
}
