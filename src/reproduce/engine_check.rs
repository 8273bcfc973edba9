//! The engine scenes of a reproduction checked before its plan is made:
//! each is characterised (captured first when the scene cache lacks its
//! capture, then its frame imported); one that cannot be drawn is left out
//! of the run, with why, for the report.

use super::plan::{Plan, SceneInfo};
use super::routes::LeftOut;
use crate::study::cache::Cache;
use crate::study::runner::{self, RunnerOptions, Task};
use wasp_frontend::def::Route;

/// The engine scenes of `plan` that cannot be captured or imported, with
/// why: each is characterised (which captures it when the scene cache
/// lacks it and imports its frame; the result is stored, so the study's
/// own characterisation finds it done).
pub fn left_out(plan: &Plan, cache: &Cache, opts: &RunnerOptions) -> Result<Vec<LeftOut>, String> {
    let engine: Vec<&SceneInfo> = plan
        .every
        .iter()
        .filter(|s| s.route == Route::Engine)
        .collect();
    if engine.is_empty() {
        return Ok(Vec::new());
    }
    let tasks: Vec<Task> = engine
        .iter()
        .map(|s| Task::Characterize {
            scene: s.name.clone(),
            config: "paper".into(),
            format: None,
        })
        .collect();
    let opts = RunnerOptions {
        label: "engine scenes".into(),
        ..opts.clone()
    };
    let out = runner::run(&tasks, cache, &opts)?;
    let mut left = Vec::new();
    for s in engine.iter().filter(|s| !out.scenes.contains_key(&s.name)) {
        let reason = out
            .failures
            .iter()
            .find(|f| f.starts_with(&format!("characterising {} ", s.name)))
            .and_then(|f| f.split_once("): ").map(|x| x.1.to_string()))
            .unwrap_or_else(|| "its characterisation did not finish".into());
        eprintln!(
            "wasp: warning: leaving out the engine scene {}: {reason}",
            s.name
        );
        left.push(LeftOut {
            name: s.name.clone(),
            route: s.route,
            reason,
        });
    }
    Ok(left)
}
