//! The experiments of the paper's Sections III and V as study points.
//!
//! The scenes come through two routes (wasp's loaders and the games' own
//! engines, [`super::routes`]): where a camera has both, the route choice
//! (`--routes`; (wasp) default the engine, whose draw calls are the
//! game's own, as the paper's are) says which twin the study and its
//! group means count ([`Plan::scenes`]) and which is reported beside them
//! ([`Plan::beside`]), and both twins run the comparison points of "The
//! loaders against the engine" ([`Plan::route_points`]).
//!
//! Every point is the shipped configuration (configs/paper.toml, or
//! configs/paper-width2.toml for the width-2 sensitivity) with overrides;
//! nothing is chosen per scene. Each experiment runs under every dispatch
//! mode of the plan (the paper's shared-tile machine first).

use super::routes::{self, LeftOut, RouteChoice, Twin};
use crate::study::point::Point;
use crate::study::runner::Task;
use std::path::Path;
use wasp_frontend::def::{Game, Route, SceneDef};
use wasp_rtl::policy::PolicySpec;
use wasp_rtl::subset::SubsetSpec;
use wasp_sim::config::{Dispatch, MachineConfig};
use wasp_sim::mem::PrefetchKind;

/// The scene of each game in the quick look: the one of its game that
/// simulates fastest on the shipped machine (`wasp run` wall time on a
/// 2-core machine: 0.13 to 0.79 s, against up to 2.35 s for the slowest),
/// so that the first look takes about a minute. The choice concerns speed
/// only; no result is tuned by it.
pub const QUICK_SCENES: [&str; 5] = [
    "stk-lighthouse-start",
    "oa-wrackdm17-spawn2",
    "tw-dm1-spawn0",
    "fb-level1",
    "procedural-plane",
];

/// A scene's group in averages: the paper's games are 2D and 3D Android
/// games; ours are grouped the same way, procedural scenes apart.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Group {
    /// SuperTuxKart, OpenArena.
    ThreeD,
    /// Teeworlds, Frozen Bubble.
    TwoD,
    /// Built-in procedural scenes (not games; labelled apart).
    Procedural,
}

impl Group {
    /// The group of a game.
    pub fn of(g: Game) -> Group {
        match g {
            Game::Supertuxkart | Game::Openarena => Group::ThreeD,
            Game::Teeworlds | Game::FrozenBubble => Group::TwoD,
            Game::Procedural => Group::Procedural,
        }
    }

    /// Label in tables and plots.
    pub fn label(self) -> &'static str {
        match self {
            Group::ThreeD => "3D",
            Group::TwoD => "2D",
            Group::Procedural => "procedural",
        }
    }
}

/// A scene of the plan.
#[derive(Clone, Debug)]
pub struct SceneInfo {
    /// Scene name.
    pub name: String,
    /// Its group.
    pub group: Group,
    /// Where its draw calls come from (wasp's loader or the game's engine).
    pub route: Route,
}

/// A pipeline width of the sensitivity study and its base configuration.
#[derive(Clone, Debug)]
pub struct Width {
    /// Instructions issued per cycle.
    pub width: u32,
    /// Base configuration name.
    pub config: &'static str,
    /// The paper's best warp count at this width.
    pub paper_best_warps: u32,
}

/// Everything `wasp reproduce` runs.
#[derive(Clone, Debug)]
pub struct Plan {
    /// The scenes of the study and its group means, in `wasp scenes list`
    /// order.
    pub scenes: Vec<SceneInfo>,
    /// The scenes reported beside the means: the twins of the route not
    /// chosen ([`super::routes`]); they run the comparison points only.
    pub beside: Vec<SceneInfo>,
    /// Every scene of the run (the study's and those beside), in `wasp
    /// scenes list` order.
    pub every: Vec<SceneInfo>,
    /// The loader and engine twin pairs of the run.
    pub twins: Vec<Twin>,
    /// Which twin counts (`--routes`).
    pub routes: RouteChoice,
    /// Scenes named for the run but left out of it (an engine scene whose
    /// capture or import failed), with why; set by the caller.
    pub left_out: Vec<LeftOut>,
    /// Machines (shared-tile first).
    pub dispatches: Vec<Dispatch>,
    /// The shipped WaSP policy (configs/paper.toml).
    pub wasp: PolicySpec,
    /// The rival heuristics, baseline first.
    pub policies: Vec<PolicySpec>,
    /// Thresholds of the threshold sweep.
    pub thresholds: Vec<u32>,
    /// Mesh sizes of the subset study (mesh4 is the shipped subset).
    pub meshes: Vec<u32>,
    /// Early-Z-rejected quads per raster slot beyond the shipped 1 (beyond
    /// the paper: how much the raster rate matters).
    pub early_z: Vec<u32>,
    /// Widths of the sensitivity study.
    pub widths: Vec<Width>,
    /// Warp counts of the sensitivity study.
    pub warps: Vec<u32>,
    /// Scenes drawn as timelines (one per game).
    pub timeline_scenes: Vec<String>,
    /// Policies drawn as timelines.
    pub timeline_policies: Vec<PolicySpec>,
    /// Cycles of each timeline.
    pub timeline_window: (u64, u64),
    /// The quick subset.
    pub quick: bool,
}

/// One scene per game, in `Game::ALL` order: for the timelines the first
/// by name, for the quick look the one of [`QUICK_SCENES`] (else the
/// first), a loader scene where the game has one.
fn one_per_game<'a>(defs: &[&'a SceneDef], quick: bool) -> Vec<&'a SceneDef> {
    let mut per_game: Vec<&SceneDef> = Vec::new();
    for g in Game::ALL {
        let all: Vec<&SceneDef> = defs.iter().copied().filter(|d| d.game == g).collect();
        let loader: Vec<&SceneDef> = all
            .iter()
            .copied()
            .filter(|d| d.route == Route::Loader)
            .collect();
        let of = if loader.is_empty() { all } else { loader };
        let listed = of.iter().find(|d| QUICK_SCENES.contains(&d.name.as_str()));
        let pick = if quick {
            listed.or(of.first())
        } else {
            of.first()
        };
        if let Some(d) = pick {
            per_game.push(d);
        }
    }
    per_game
}

/// The widths of the sensitivity study: width 4 in the quick look, else
/// widths 2 and 4, each with the paper's best warp count.
fn widths(quick: bool) -> Vec<Width> {
    let four = Width {
        width: 4,
        config: "paper",
        paper_best_warps: 64,
    };
    if quick {
        return vec![four];
    }
    vec![
        Width {
            width: 2,
            config: "paper-width2",
            paper_best_warps: 48,
        },
        four,
    ]
}

impl Plan {
    /// The plan over `defs`: the full reproduction or, `quick`, the first
    /// look (one scene of each game, [`QUICK_SCENES`], the heuristics, ideal memory,
    /// the meshes, four thresholds, width 4 at 32/48/64 warps, one timeline,
    /// the shared-tile machine only); engine twins count (wasp's default
    /// route choice).
    #[cfg(test)]
    pub fn new(defs: &[SceneDef], quick: bool, dispatches: Vec<Dispatch>) -> Plan {
        Self::with_routes(defs, quick, dispatches, RouteChoice::default())
    }

    /// The plan over `defs` as `Plan::new` makes it, with the twin of route
    /// `routes` counting in the study
    /// (the quick look takes a camera of each game with both its routes).
    pub fn with_routes(
        defs: &[SceneDef],
        quick: bool,
        dispatches: Vec<Dispatch>,
        routes: RouteChoice,
    ) -> Plan {
        let paper = MachineConfig::paper();
        let wasp = paper.scheduler.policy;
        let threshold = match wasp {
            PolicySpec::Wasp { threshold, .. } => threshold,
            _ => 0,
        };
        let l0 = paper.l0.as_ref().map_or(paper.l1.mshrs, |c| c.mshrs);
        let mut kept: Vec<&SceneDef> = defs.iter().collect();
        if quick {
            let picks = one_per_game(&kept, true);
            kept.retain(|d| {
                picks
                    .iter()
                    .any(|p| p.name == d.name || routes::are_twins(p, d))
            });
        }
        let info = |d: &SceneDef| SceneInfo {
            name: d.name.clone(),
            group: Group::of(d.game),
            route: d.route,
        };
        let (counted, beside): (Vec<&SceneDef>, Vec<&SceneDef>) =
            kept.iter().partition(|d| routes::counts(d, &kept, routes));
        let per_game = one_per_game(&counted, quick);
        let timeline_scenes: Vec<String> = if quick {
            per_game.iter().take(1).map(|d| d.name.clone()).collect()
        } else {
            per_game.iter().map(|d| d.name.clone()).collect()
        };
        let step = if quick { 4 } else { 2 };
        Plan {
            scenes: counted.iter().map(|d| info(d)).collect(),
            beside: beside.iter().map(|d| info(d)).collect(),
            every: kept.iter().map(|d| info(d)).collect(),
            twins: routes::twins(&kept),
            routes,
            left_out: Vec::new(),
            dispatches: if quick {
                dispatches.into_iter().take(1).collect()
            } else {
                dispatches
            },
            wasp,
            policies: vec![
                PolicySpec::Baseline,
                PolicySpec::FullPriority,
                PolicySpec::FreeMshr(10),
                wasp,
                PolicySpec::WaspMeasured { threshold },
            ],
            thresholds: (0..l0).step_by(step).collect(),
            meshes: vec![2, 4, 8, 16],
            early_z: if quick { vec![16] } else { vec![4, 16] },
            widths: widths(quick),
            warps: if quick {
                vec![32, 48, 64]
            } else {
                vec![28, 32, 48, 64, 128]
            },
            timeline_scenes,
            timeline_policies: if quick {
                vec![wasp]
            } else {
                vec![PolicySpec::Baseline, PolicySpec::FullPriority, wasp]
            },
            timeline_window: (1, 20_000),
            quick,
        }
    }

    /// The shipped machine under dispatch `d` running `policy`.
    pub fn policy_point(&self, scene: &str, d: Dispatch, policy: PolicySpec) -> Point {
        Point::new(scene, "paper", &[])
            .set("raster.dispatch", &d)
            .set("scheduler.policy", &policy)
    }

    /// The scanline baseline with zero-latency main memory.
    pub fn ideal_point(&self, scene: &str, d: Dispatch) -> Point {
        self.policy_point(scene, d, PolicySpec::Baseline)
            .set("memory.ideal", &true)
    }

    /// WaSP at threshold `t` (the shipped CF).
    pub fn threshold_point(&self, scene: &str, d: Dispatch, t: u32) -> Point {
        let cf = match self.wasp {
            PolicySpec::Wasp { cf, .. } => cf,
            _ => 3.0,
        };
        self.policy_point(scene, d, PolicySpec::Wasp { threshold: t, cf })
    }

    /// `policy` with a coarse Early-Z disposing of `k` rejected quads a
    /// raster slot (`k` = 1: the shipped machine).
    pub fn early_z_point(&self, scene: &str, d: Dispatch, k: u32, policy: PolicySpec) -> Point {
        let p = self.policy_point(scene, d, policy);
        if k == 1 {
            p
        } else {
            p.set("raster.rejected_per_slot", &k)
        }
    }

    /// The policies of the Early-Z study.
    pub fn early_z_policies(&self) -> [PolicySpec; 3] {
        [PolicySpec::Baseline, PolicySpec::FullPriority, self.wasp]
    }

    /// WaSP with the MeshN subset.
    pub fn mesh_point(&self, scene: &str, d: Dispatch, n: u32) -> Point {
        self.policy_point(scene, d, self.wasp)
            .set("scheduler.subset", &SubsetSpec::Mesh(n))
    }

    /// `policy` at width `w` with `warps` warp slots (and as many input
    /// queue entries).
    pub fn sensitivity_point(
        &self,
        scene: &str,
        d: Dispatch,
        w: &Width,
        warps: u32,
        policy: PolicySpec,
    ) -> Point {
        Point::new(scene, w.config, &[])
            .set("raster.dispatch", &d)
            .set("scheduler.policy", &policy)
            .set("core.max_warps", &warps)
            .set("core.input_queue", &warps)
    }

    /// The file of a timeline picture under the figures folder.
    pub fn timeline_file(scene: &str, d: Dispatch, policy: PolicySpec) -> String {
        let p = policy.to_string().replace(':', "-");
        format!("timeline.{scene}.{d}.{p}.png")
    }

    /// The machine of "The loaders against the engine": the plan's first
    /// (the paper's shared-tile machine unless `--machines` leaves it out).
    pub fn route_dispatch(&self) -> Dispatch {
        self.dispatches[0]
    }

    /// The points each scene of a twin pair runs for "The loaders against
    /// the engine", on [`Plan::route_dispatch`], with their labels: the
    /// baseline, WaSP, the raster prefetcher and the oracle tile
    /// prefetcher (both on the baseline scheduler, as the map runs them).
    pub fn route_points(&self, scene: &str) -> [(&'static str, Point); 4] {
        let d = self.route_dispatch();
        let base = self.policy_point(scene, d, PolicySpec::Baseline);
        [
            ("baseline", base.clone()),
            ("WaSP", self.policy_point(scene, d, self.wasp)),
            (
                "raster prefetcher",
                base.set("prefetch.kind", &PrefetchKind::Raster),
            ),
            (
                "oracle",
                base.set("prefetch.kind", &PrefetchKind::OracleTile),
            ),
        ]
    }

    /// Whether `scene` is one of the study's (counted in the means).
    pub fn counts(&self, scene: &str) -> bool {
        self.scenes.iter().any(|s| s.name == scene)
    }

    /// The tasks of "The loaders against the engine" the study does not
    /// run already: the characterisation of the scenes beside, and the
    /// comparison points of both twins.
    fn route_tasks(&self) -> Vec<Task> {
        let mut t = Vec::new();
        for tw in &self.twins {
            for name in [&tw.loader, &tw.engine] {
                // The study characterises its scenes and runs the baseline
                // and WaSP on every machine.
                let counted = self.counts(name);
                if !counted {
                    t.push(Task::Characterize {
                        scene: name.clone(),
                        config: "paper".into(),
                        format: None,
                    });
                }
                let skip = if counted { 2 } else { 0 };
                for (_, p) in self.route_points(name).into_iter().skip(skip) {
                    t.push(Task::Run(p));
                }
            }
        }
        t
    }

    /// Every task, in a fixed order.
    pub fn tasks(&self, figures: &Path) -> Vec<Task> {
        let mut t = Vec::new();
        for s in &self.scenes {
            t.push(Task::Characterize {
                scene: s.name.clone(),
                config: "paper".into(),
                format: None,
            });
        }
        for &d in &self.dispatches {
            for s in &self.scenes {
                let n = &s.name;
                for &p in &self.policies {
                    t.push(Task::Run(self.policy_point(n, d, p)));
                }
                t.push(Task::Run(self.ideal_point(n, d)));
                for &th in &self.thresholds {
                    t.push(Task::Run(self.threshold_point(n, d, th)));
                }
                for &m in &self.meshes {
                    t.push(Task::Run(self.mesh_point(n, d, m)));
                }
                for &k in &self.early_z {
                    for p in self.early_z_policies() {
                        t.push(Task::Run(self.early_z_point(n, d, k, p)));
                    }
                }
                for w in &self.widths {
                    for &k in &self.warps {
                        for p in [PolicySpec::Baseline, self.wasp] {
                            t.push(Task::Run(self.sensitivity_point(n, d, w, k, p)));
                        }
                    }
                }
            }
            for s in &self.timeline_scenes {
                for &p in &self.timeline_policies {
                    t.push(Task::Timeline {
                        point: self.policy_point(s, d, p),
                        from: self.timeline_window.0,
                        to: self.timeline_window.1,
                        out: figures.join(Self::timeline_file(s, d, p)),
                    });
                }
            }
        }
        t.extend(self.route_tasks());
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;
    use wasp_frontend::def;

    fn defs() -> Vec<SceneDef> {
        def::all().unwrap()
    }

    #[test]
    fn the_full_plan_covers_every_experiment_on_every_scene() {
        let d = defs();
        let p = Plan::new(&d, false, vec![Dispatch::SharedTile, Dispatch::PerCoreTile]);
        assert_eq!(p.scenes.len(), d.len());
        assert_eq!(p.warps, [28, 32, 48, 64, 128]);
        assert_eq!(p.timeline_scenes.len(), 5, "one scene per game");
        let tasks = p.tasks(&PathBuf::from("f"));
        let runs = tasks.iter().filter(|t| matches!(t, Task::Run(_))).count();
        let per_scene = p.policies.len()
            + 1
            + p.thresholds.len()
            + p.meshes.len()
            + 3 * p.early_z.len()
            + 2 * 5 * 2;
        assert_eq!(runs, 2 * d.len() * per_scene);
        // The shipped WaSP at mesh4 is the heuristics' WaSP point described
        // another way: the same machine.
        let mut r = crate::study::point::Resolver::default();
        let a = r
            .config(&p.policy_point("x", Dispatch::SharedTile, p.wasp))
            .unwrap();
        let b = r
            .config(&p.mesh_point("x", Dispatch::SharedTile, 4))
            .unwrap();
        assert_eq!(a, b);
        let w4 = &p.widths[1];
        let c = r
            .config(&p.sensitivity_point("x", Dispatch::SharedTile, w4, 64, p.wasp))
            .unwrap();
        assert_eq!(a, c);
    }

    #[test]
    fn the_quick_plan_takes_one_listed_scene_of_each_game() {
        let d = defs();
        let p = Plan::new(&d, true, vec![Dispatch::SharedTile, Dispatch::PerCoreTile]);
        assert_eq!(p.dispatches, [Dispatch::SharedTile]);
        let game = |n: &str| d.iter().find(|x| x.name == n).unwrap().game;
        let games: Vec<Game> = p.scenes.iter().map(|s| game(&s.name)).collect();
        let mut uniq = games.clone();
        uniq.dedup();
        assert_eq!(games, uniq, "one scene per game");
        let names: Vec<&str> = p.scenes.iter().map(|s| s.name.as_str()).collect();
        let mut listed = QUICK_SCENES.to_vec();
        listed.sort();
        let mut got = names.clone();
        got.sort();
        assert_eq!(got, listed);
    }

    fn count_runs(tasks: &[Task]) -> usize {
        tasks.iter().filter(|t| matches!(t, Task::Run(_))).count()
    }

    #[test]
    fn engine_scenes_join_their_games_group_and_the_route_choice_picks_who_counts() {
        let every = def::every().unwrap();
        let loader = defs();
        let d = [Dispatch::SharedTile, Dispatch::PerCoreTile];
        let p = Plan::with_routes(&every, false, d.to_vec(), RouteChoice::Engine);
        let twins = every.len() - loader.len();
        assert_eq!(p.twins.len(), twins);
        assert_eq!(p.every.len(), every.len());
        // Every engine twin counts, in its game's group; its loader scene
        // is beside the means.
        for tw in &p.twins {
            let e = p.scenes.iter().find(|s| s.name == tw.engine).unwrap();
            let game = every.iter().find(|x| x.name == tw.engine).unwrap().game;
            assert_eq!((e.group, e.route), (Group::of(game), Route::Engine));
            assert!(p.beside.iter().any(|s| s.name == tw.loader));
            assert!(!p.counts(&tw.loader));
        }
        assert_eq!(p.scenes.len(), loader.len());
        assert!(p
            .timeline_scenes
            .contains(&"oa-dm1-spawn0-engine".to_string()));
        // The study's tasks are those of as many scenes as before; the
        // comparison adds, per pair, the scene beside (a characterisation
        // and four points) and the prefetchers on the twin that counts.
        let base = Plan::with_routes(&loader, false, d.to_vec(), RouteChoice::Loader);
        let (t, tb) = (p.tasks(Path::new("f")), base.tasks(Path::new("f")));
        assert_eq!(count_runs(&t), count_runs(&tb) + twins * (4 + 2));
        assert_eq!(t.len(), tb.len() + twins * (1 + 4 + 2));
        // The reverse: the loader scenes count, the engine twins beside.
        let l = Plan::with_routes(&every, false, d.to_vec(), RouteChoice::Loader);
        let names = |v: &[SceneInfo]| v.iter().map(|s| s.name.clone()).collect::<Vec<_>>();
        assert_eq!(names(&l.scenes), names(&base.scenes));
        assert!(l.beside.iter().all(|s| s.route == Route::Engine));
        assert_eq!(l.timeline_scenes, base.timeline_scenes);
        // Both: every scene counts, nothing beside.
        let b = Plan::with_routes(&every, false, d.to_vec(), RouteChoice::Both);
        assert_eq!((b.scenes.len(), b.beside.len()), (every.len(), 0));
        // The comparison's points are the heuristics' baseline and WaSP and
        // the map's prefetchers on the first machine.
        let pts = p.route_points("x");
        assert_eq!(
            pts[0].1,
            p.policy_point("x", Dispatch::SharedTile, PolicySpec::Baseline)
        );
        assert_eq!(pts[1].1, p.policy_point("x", Dispatch::SharedTile, p.wasp));
        let oracle = pts[3].1.value_of("prefetch.kind");
        assert_eq!(oracle.and_then(|v| v.as_str()), Some("oracle-tile"));
    }

    #[test]
    fn the_quick_look_takes_a_camera_with_both_its_routes() {
        let every = def::every().unwrap();
        let p = Plan::with_routes(
            &every,
            true,
            vec![Dispatch::SharedTile],
            RouteChoice::Engine,
        );
        let mut all: Vec<&str> = p.every.iter().map(|s| s.name.as_str()).collect();
        all.sort();
        let mut want: Vec<String> = QUICK_SCENES.iter().map(|s| s.to_string()).collect();
        want.extend(["oa-wrackdm17-spawn2-engine", "tw-dm1-spawn0-engine"].map(String::from));
        want.sort();
        assert_eq!(all, want);
        assert_eq!(p.twins.len(), 2);
        assert_eq!(p.timeline_scenes, ["stk-lighthouse-start"]);
        // A left-out twin (dropped from the definitions) leaves its loader
        // scene counting.
        let without: Vec<SceneDef> = every
            .into_iter()
            .filter(|d| d.name != "tw-dm1-spawn0-engine")
            .collect();
        let q = Plan::with_routes(
            &without,
            true,
            vec![Dispatch::SharedTile],
            RouteChoice::Engine,
        );
        assert!(q.counts("tw-dm1-spawn0") && q.counts("oa-wrackdm17-spawn2-engine"));
        assert_eq!(q.twins.len(), 1);
    }
}
