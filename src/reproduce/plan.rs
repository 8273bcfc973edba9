//! The experiments of the paper's Sections III and V as study points.
//!
//! Every point is the shipped configuration (configs/paper.toml, or
//! configs/paper-width2.toml for the width-2 sensitivity) with overrides;
//! nothing is chosen per scene. Each experiment runs under every dispatch
//! mode of the plan (the paper's shared-tile machine first).

use crate::study::point::Point;
use crate::study::runner::Task;
use std::path::Path;
use wasp_frontend::def::{Game, SceneDef};
use wasp_rtl::policy::PolicySpec;
use wasp_sim::config::{Dispatch, MachineConfig};

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
    /// Scenes, in `wasp scenes list` order.
    pub scenes: Vec<SceneInfo>,
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
/// first).
fn one_per_game(defs: &[SceneDef], quick: bool) -> Vec<&SceneDef> {
    let mut per_game: Vec<&SceneDef> = Vec::new();
    for g in Game::ALL {
        let of: Vec<&SceneDef> = defs.iter().filter(|d| d.game == g).collect();
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
    /// the shared-tile machine only).
    pub fn new(defs: &[SceneDef], quick: bool, dispatches: Vec<Dispatch>) -> Plan {
        let paper = MachineConfig::paper();
        let wasp = paper.scheduler.policy;
        let threshold = match wasp {
            PolicySpec::Wasp { threshold, .. } => threshold,
            _ => 0,
        };
        let l0 = paper.l0.as_ref().map_or(paper.l1.mshrs, |c| c.mshrs);
        let per_game = one_per_game(defs, quick);
        let mut scenes: Vec<SceneInfo> = defs
            .iter()
            .map(|d| SceneInfo {
                name: d.name.clone(),
                group: Group::of(d.game),
            })
            .collect();
        if quick {
            scenes.retain(|s| per_game.iter().any(|d| d.name == s.name));
        }
        let timeline_scenes: Vec<String> = if quick {
            per_game.iter().take(1).map(|d| d.name.clone()).collect()
        } else {
            per_game.iter().map(|d| d.name.clone()).collect()
        };
        let step = if quick { 4 } else { 2 };
        Plan {
            scenes,
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
            .with(format!("raster.dispatch=\"{d}\""))
            .with(format!("scheduler.policy=\"{policy}\""))
    }

    /// The scanline baseline with zero-latency main memory.
    pub fn ideal_point(&self, scene: &str, d: Dispatch) -> Point {
        self.policy_point(scene, d, PolicySpec::Baseline)
            .with("memory.ideal=true")
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
            p.with(format!("raster.rejected_per_slot={k}"))
        }
    }

    /// The policies of the Early-Z study.
    pub fn early_z_policies(&self) -> [PolicySpec; 3] {
        [PolicySpec::Baseline, PolicySpec::FullPriority, self.wasp]
    }

    /// WaSP with the MeshN subset.
    pub fn mesh_point(&self, scene: &str, d: Dispatch, n: u32) -> Point {
        self.policy_point(scene, d, self.wasp)
            .with(format!("scheduler.subset=\"mesh{n}\""))
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
            .with(format!("raster.dispatch=\"{d}\""))
            .with(format!("scheduler.policy=\"{policy}\""))
            .with(format!("core.max_warps={warps}"))
            .with(format!("core.input_queue={warps}"))
    }

    /// The file of a timeline picture under the figures folder.
    pub fn timeline_file(scene: &str, d: Dispatch, policy: PolicySpec) -> String {
        let p = policy.to_string().replace(':', "-");
        format!("timeline.{scene}.{d}.{p}.png")
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
}
