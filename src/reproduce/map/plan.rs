//! The map's points: every knob value on every scene under every variant,
//! the deep-input-queue warp series, and the 2-D grid over the two knobs
//! that move WaSP most (chosen from the one-at-a-time results).

use super::knobs::{self, Knob, Variant};
use crate::study::point::Point;
use crate::study::runner::Task;
use wasp_rtl::policy::PolicySpec;
use wasp_sim::config::{Dispatch, Override};

/// Input-queue entries of the warp-slot series: deep enough that a full
/// core queue never holds the rasterizer back on the shipped scenes, so
/// that extra warp slots buy latency hiding only, not queue room.
pub const DEEP_QUEUE: u32 = 1024;

/// The overrides of `warps` warp slots with a [`DEEP_QUEUE`]-entry input
/// queue.
pub fn deep_queue(warps: u32) -> [Override; 2] {
    [
        Override::new("core.max_warps", &warps),
        Override::new("core.input_queue", &DEEP_QUEUE),
    ]
}

/// The shipped scenes the map leaves out unless `--map-scenes all`: the
/// three 3D scenes with the most cycles on the shipped machine (the
/// scanline baseline, shared-tile), measured once over the whole suite.
/// They hold 52% of the map's simulated cycles (the two SuperTuxKart
/// tracks alone 45%), and without them the whole study fits in 15 minutes
/// on two cores. Every game keeps at least two scenes; the 2D and
/// procedural scenes, which cost little, are all kept; the paper's
/// experiments run on every scene.
pub const LEFT_OUT: [&str; 3] = [
    "stk-blackforest-start",
    "stk-cocoatemple-start",
    "oa-dm5-spawn1",
];

/// The scenes the map runs on.
#[derive(clap::ValueEnum, Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SceneChoice {
    /// Every scene but stk-blackforest-start, stk-cocoatemple-start and
    /// oa-dm5-spawn1, the 3D scenes with the most cycles (`LEFT_OUT`);
    /// scenes named with --scenes, or not shipped with wasp, always run.
    #[default]
    Budget,
    /// Every scene of the reproduction.
    All,
}

impl SceneChoice {
    /// Whether the map runs on `scene`; `named`: the scenes were named on
    /// the command line (the user's choice, all kept).
    pub fn keeps(self, scene: &str, named: bool) -> bool {
        self == SceneChoice::All || named || !LEFT_OUT.contains(&scene)
    }
}

/// What the map runs.
#[derive(Clone, Debug)]
pub struct MapPlan {
    /// The knobs, one at a time.
    pub knobs: Vec<Knob>,
    /// The shipped WaSP.
    pub wasp: PolicySpec,
    /// The reduced form (`--quick`).
    pub quick: bool,
    /// Warp counts of the deep-input-queue series.
    pub deep_queue_warps: Vec<u32>,
    /// The scenes it runs on.
    pub scene_choice: SceneChoice,
    /// The reproduction's scenes were named on the command line.
    pub named_scenes: bool,
}

/// A cell of the 2-D grid: a value of each of two knobs.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Cell {
    /// Index of the first knob in [`MapPlan::knobs`] and its value.
    pub a: (usize, &'static str),
    /// The second knob and its value.
    pub b: (usize, &'static str),
}

impl MapPlan {
    /// The map of `wasp`, full or quick.
    pub fn new(wasp: PolicySpec, quick: bool) -> MapPlan {
        MapPlan {
            knobs: knobs::all(),
            wasp,
            quick,
            deep_queue_warps: if quick {
                vec![64, 128]
            } else {
                vec![32, 48, 64, 96, 128]
            },
            scene_choice: SceneChoice::default(),
            named_scenes: false,
        }
    }

    /// The map on the scenes `choice` keeps; `named`: the reproduction's
    /// scenes were named on the command line.
    pub fn on(mut self, choice: SceneChoice, named: bool) -> MapPlan {
        self.scene_choice = choice;
        self.named_scenes = named;
        self
    }

    /// Whether the map runs on `scene`.
    pub fn keeps(&self, scene: &str) -> bool {
        self.scene_choice.keeps(scene, self.named_scenes)
    }

    /// The shipped machine (shared-tile dispatch) with `sets`, then the
    /// variant's overrides.
    fn point(&self, scene: &str, sets: &[Override], v: Variant) -> Point {
        let mut p = Point::new(scene, "paper", &[]).set("raster.dispatch", &Dispatch::SharedTile);
        for s in sets.iter().cloned().chain(v.overrides(self.wasp)) {
            p = p.with(s);
        }
        p
    }

    /// Knob `k` at `value` on `scene` under `v`.
    pub fn knob_point(&self, scene: &str, k: &Knob, value: &str, v: Variant) -> Point {
        let p = self.point(scene, &k.overrides(value), v);
        let p = match k.format(value) {
            Some(f) => p.stored(f),
            None => p,
        };
        match k.order(value) {
            Some(o) => p.drawn(o),
            None => p,
        }
    }

    /// The shipped machine on `scene` under `v`.
    pub fn shipped_point(&self, scene: &str, v: Variant) -> Point {
        self.point(scene, &[], v)
    }

    /// `warps` warp slots and a [`DEEP_QUEUE`]-entry input queue.
    pub fn deep_queue_point(&self, scene: &str, warps: u32, v: Variant) -> Point {
        self.point(scene, &deep_queue(warps), v)
    }

    /// A cell of the 2-D grid.
    pub fn cell_point(&self, scene: &str, c: &Cell, v: Variant) -> Point {
        let (ka, kb) = (&self.knobs[c.a.0], &self.knobs[c.b.0]);
        let mut sets = ka.overrides(c.a.1);
        sets.extend(kb.overrides(c.b.1));
        let p = self.point(scene, &sets, v);
        let p = match ka.format(c.a.1).or(kb.format(c.b.1)) {
            Some(f) => p.stored(f),
            None => p,
        };
        match ka.order(c.a.1).or(kb.order(c.b.1)) {
            Some(o) => p.drawn(o),
            None => p,
        }
    }

    /// The variants of the deep-queue series: the baseline, WaSP and the
    /// oracle; the quick look runs the baseline only (what the warp-slot
    /// question reads).
    pub fn deep_queue_variants(&self) -> &'static [Variant] {
        if self.quick {
            &[Variant::Baseline]
        } else {
            &[Variant::Baseline, Variant::Wasp, Variant::Oracle]
        }
    }

    /// The variants of the 2-D grid.
    pub const GRID_VARIANTS: [Variant; 2] = [Variant::Baseline, Variant::Wasp];

    /// The one-at-a-time tasks and the warp-slot series on `scenes`, in a
    /// fixed order.
    pub fn tasks(&self, scenes: &[String]) -> Vec<Task> {
        let mut t = Vec::new();
        for s in scenes {
            for k in &self.knobs {
                for value in k.values_for(self.quick) {
                    for v in Variant::ALL {
                        t.push(Task::Run(self.knob_point(s, k, value, v)));
                    }
                }
            }
            for &w in &self.deep_queue_warps {
                for &v in self.deep_queue_variants() {
                    t.push(Task::Run(self.deep_queue_point(s, w, v)));
                }
            }
        }
        t
    }

    /// The cells of the grid over knobs `a` and `b`: every pair of their
    /// values.
    pub fn grid(&self, a: usize, b: usize) -> Vec<Cell> {
        let (ka, kb) = (&self.knobs[a], &self.knobs[b]);
        let mut cells = Vec::new();
        for &x in ka.values_for(self.quick) {
            for &y in kb.values_for(self.quick) {
                cells.push(Cell {
                    a: (a, x),
                    b: (b, y),
                });
            }
        }
        cells
    }

    /// The grid's tasks on `scenes`.
    pub fn grid_tasks(&self, scenes: &[String], cells: &[Cell]) -> Vec<Task> {
        let mut t = Vec::new();
        for s in scenes {
            for c in cells {
                for v in Self::GRID_VARIANTS {
                    t.push(Task::Run(self.cell_point(s, c, v)));
                }
            }
        }
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::point::Resolver;

    fn wasp() -> PolicySpec {
        PolicySpec::Wasp {
            threshold: 0,
            cf: 3.0,
        }
    }

    #[test]
    fn the_shipped_value_of_every_knob_is_the_shipped_point() {
        let m = MapPlan::new(wasp(), false);
        for k in &m.knobs {
            assert_eq!(
                m.knob_point("s", k, k.shipped, Variant::Wasp),
                m.shipped_point("s", Variant::Wasp)
            );
        }
        // And the shipped point is the reproduction's shipped WaSP.
        let mut r = Resolver::default();
        let a = r.config(&m.shipped_point("s", Variant::Wasp)).unwrap();
        assert_eq!(a, wasp_sim::config::MachineConfig::paper());
    }

    #[test]
    fn tasks_cover_every_value_and_variant() {
        let m = MapPlan::new(wasp(), false);
        let scenes = vec!["a".to_string(), "b".to_string()];
        let values: usize = m.knobs.iter().map(|k| k.values.len()).sum();
        let per_scene = values * Variant::ALL.len() + 5 * 3;
        assert_eq!(m.tasks(&scenes).len(), 2 * per_scene);
        let q = MapPlan::new(wasp(), true);
        let quick: usize = q.knobs.iter().map(|k| k.quick.len()).sum();
        assert!(quick < values);
        let cells = m.grid(0, 1);
        assert_eq!(
            cells.len(),
            m.knobs[0].values.len() * m.knobs[1].values.len()
        );
        assert_eq!(m.grid_tasks(&scenes, &cells).len(), 2 * cells.len() * 2);
        // A cell at the shipped value of one knob is that knob's point of
        // the other: the grid reuses the one-at-a-time results.
        let c = Cell {
            a: (0, "64"),
            b: (1, "31"),
        };
        assert_eq!(
            m.cell_point("a", &c, Variant::Wasp),
            m.knob_point("a", &m.knobs[1], "31", Variant::Wasp)
        );
    }

    #[test]
    fn the_map_keeps_at_least_two_scenes_of_each_game() {
        let defs = wasp_frontend::def::all().unwrap();
        let m = MapPlan::new(wasp(), false);
        for name in LEFT_OUT {
            assert!(defs.iter().any(|d| d.name == name), "{name} is shipped");
            assert!(!m.keeps(name));
        }
        use wasp_frontend::def::Game;
        for g in Game::ALL {
            let of: Vec<_> = defs.iter().filter(|d| d.game == g).collect();
            let kept = of.iter().filter(|d| m.keeps(&d.name)).count();
            assert!(kept >= of.len().min(2), "{g:?}");
        }
        // Every quick scene is in the map, so the quick look is unchanged.
        for q in crate::reproduce::plan::QUICK_SCENES {
            assert!(m.keeps(q), "{q}");
        }
        // A scene of the user's and scenes named on the command line run.
        assert!(m.keeps("my-scene"));
        let named = MapPlan::new(wasp(), false).on(SceneChoice::Budget, true);
        assert!(named.keeps(LEFT_OUT[0]));
        let all = MapPlan::new(wasp(), false).on(SceneChoice::All, false);
        assert!(all.keeps(LEFT_OUT[0]));
    }
}
