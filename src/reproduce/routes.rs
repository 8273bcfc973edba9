//! The two routes of a reproduction's scenes: which scene of a loader and
//! engine twin pair (the same game, map, camera and frame drawn by wasp's
//! loader and by the game's own engine) counts in the group means, and
//! which is reported beside them.
//!
//! (wasp) By default ([`RouteChoice::Engine`]) the engine twin represents
//! its camera in the study and the group means, and the loader scene is
//! reported beside them ("The loaders against the engine"): the paper's
//! suite is its games' own draw streams, which the engine route is, and
//! counting both would weigh a camera twice. `--routes loader` keeps the
//! loader scenes in the means instead (the study before engine scenes
//! existed), `--routes both` counts both twins. A twin that could not be
//! rendered leaves its partner in the means.

use clap::ValueEnum;
use wasp_frontend::def::{Route, SceneDef};

/// Which scene of a twin pair counts in the study and its means.
#[derive(ValueEnum, Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum RouteChoice {
    /// The engine twin; the loader scene is reported beside (wasp's
    /// default: the paper's workloads are the games' own draw calls).
    #[default]
    Engine,
    /// The loader scene; the engine twin is reported beside.
    Loader,
    /// Both twins count.
    Both,
}

impl RouteChoice {
    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            RouteChoice::Engine => "engine",
            RouteChoice::Loader => "loader",
            RouteChoice::Both => "both",
        }
    }

    /// Whether a scene of route `r` with a twin in the run counts in the
    /// study.
    pub fn counts(self, r: Route) -> bool {
        match self {
            RouteChoice::Engine => r == Route::Engine,
            RouteChoice::Loader => r == Route::Loader,
            RouteChoice::Both => true,
        }
    }
}

/// A loader scene and its engine twin, both in the run.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Twin {
    /// The loader scene's name.
    pub loader: String,
    /// The engine scene's name.
    pub engine: String,
}

/// A scene named for the run but left out of it, with why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LeftOut {
    /// The scene.
    pub name: String,
    /// Its route.
    pub route: Route,
    /// Why (the error of its capture or import).
    pub reason: String,
}

/// Whether `a` and `b` are twins: the same game, map, camera and frame
/// through the two routes.
pub fn are_twins(a: &SceneDef, b: &SceneDef) -> bool {
    a.route != b.route
        && a.game == b.game
        && a.map == b.map
        && a.camera == b.camera
        && (a.width, a.height) == (b.width, b.height)
}

/// The twin pairs among `defs`, in the order of their loader scenes.
pub fn twins(defs: &[&SceneDef]) -> Vec<Twin> {
    let mut v = Vec::new();
    for l in defs.iter().filter(|d| d.route == Route::Loader) {
        if let Some(e) = defs.iter().find(|e| are_twins(l, e)) {
            v.push(Twin {
                loader: l.name.clone(),
                engine: e.name.clone(),
            });
        }
    }
    v
}

/// Whether scene `d` of `defs` counts in the study under `choice`: it has
/// no twin in `defs`, or its route is the one chosen.
pub fn counts(d: &SceneDef, defs: &[&SceneDef], choice: RouteChoice) -> bool {
    choice.counts(d.route) || !defs.iter().any(|t| are_twins(d, t))
}

#[cfg(test)]
mod tests {
    use super::*;
    use wasp_frontend::def;

    #[test]
    fn twins_pair_by_camera_and_the_choice_decides_who_counts() {
        let every = def::every().unwrap();
        let get = |n: &str| every.iter().find(|d| d.name == n).unwrap();
        let (l, e, other) = (
            get("oa-dm1-spawn0"),
            get("oa-dm1-spawn0-engine"),
            get("oa-dm5-spawn1"),
        );
        assert!(are_twins(l, e) && are_twins(e, l));
        assert!(!are_twins(l, other) && !are_twins(l, l));
        let defs = [other, e, l];
        assert_eq!(
            twins(&defs),
            [Twin {
                loader: "oa-dm1-spawn0".into(),
                engine: "oa-dm1-spawn0-engine".into()
            }]
        );
        use RouteChoice::*;
        let who = |c| -> Vec<&str> {
            defs.iter()
                .filter(|d| counts(d, &defs, c))
                .map(|d| d.name.as_str())
                .collect()
        };
        assert_eq!(who(Engine), ["oa-dm5-spawn1", "oa-dm1-spawn0-engine"]);
        assert_eq!(who(Loader), ["oa-dm5-spawn1", "oa-dm1-spawn0"]);
        assert_eq!(who(Both).len(), 3);
        // An engine scene without its loader twin counts whatever the choice.
        assert!(counts(e, &[e, other], Loader));
    }
}
