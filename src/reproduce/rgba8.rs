//! The scenes with every texture in RGBA8, beside their own textures.
//!
//! The shipped scenes store their textures as a mobile port ships them
//! (the `etc2` rule, docs/textures.md). The headline table also gives the
//! workload's CF and footprint ratios and ideal memory's headroom with
//! every texture in RGBA8, the layout wasp used before compressed formats,
//! so that both sit beside the paper's numbers. The tasks: each scene
//! characterised in RGBA8 (sharing the map's RGBA8 trace where the map runs
//! on the scene), and the baseline and ideal memory in RGBA8 on the plan's
//! first machine, which on the shared-tile machine are the map's
//! `texture-format` `rgba8` points (the same machines, run once): the
//! only extra simulations are those of the scenes the map leaves out.

use super::figures::{group_values, scene_figures, Figure, Figures};
use super::paper;
use super::plan::Plan;
use super::prose::pct;
use crate::study::runner::{Outcome, Task};
use std::fmt::Write as _;
use wasp_frontend::texture::FormatChoice;
use wasp_rtl::policy::PolicySpec;
use wasp_sim::config::Dispatch;

/// The format of the comparison.
pub const RGBA8: FormatChoice = FormatChoice::Rgba8;

/// The machine the RGBA8 runs are on: the plan's first (the paper's
/// shared-tile machine unless `--machines` says otherwise).
pub fn machine(plan: &Plan) -> Option<Dispatch> {
    plan.dispatches.first().copied()
}

/// Every scene characterised in RGBA8, and its baseline and ideal memory
/// in RGBA8 on [`machine`].
pub fn tasks(plan: &Plan) -> Vec<Task> {
    let mut t = Vec::new();
    for s in &plan.scenes {
        t.push(Task::Characterize {
            scene: s.name.clone(),
            config: "paper".into(),
            format: Some(RGBA8),
        });
        if let Some(d) = machine(plan) {
            let base = plan.policy_point(&s.name, d, PolicySpec::Baseline);
            t.push(Task::Run(base.stored(RGBA8)));
            t.push(Task::Run(plan.ideal_point(&s.name, d).stored(RGBA8)));
        }
    }
    t
}

/// The run as if every scene stored its textures in RGBA8: its RGBA8
/// characterisations as the scenes', and its RGBA8 baseline and ideal
/// memory runs under the plan's own points of [`machine`] (so that the
/// figures of [`super::figures`] read them unchanged). Empty when the run
/// has none.
pub fn view(plan: &Plan, out: &Outcome) -> Outcome {
    let mut v = Outcome::default();
    for ((scene, f), c) in &out.scenes_as {
        if *f == RGBA8 {
            v.scenes.insert(scene.clone(), c.clone());
        }
    }
    if let Some(d) = machine(plan) {
        for s in &plan.scenes {
            let base = plan.policy_point(&s.name, d, PolicySpec::Baseline);
            for p in [base, plan.ideal_point(&s.name, d)] {
                if let Some(r) = out.get(&p.stored(RGBA8)) {
                    v.points.insert(p, r.clone());
                }
            }
        }
    }
    v
}

/// The texture format every scene of the plan was characterised in
/// (`etc2` for the shipped scenes), if they share one.
pub fn own_format(plan: &Plan, out: &Outcome) -> Option<String> {
    let mut formats = plan
        .scenes
        .iter()
        .filter_map(|s| out.scenes.get(&s.name).map(|c| c.texture_format.as_str()));
    let first = formats.next()?;
    formats.all(|f| f == first).then(|| first.to_string())
}

/// The suffix naming the textures of a headline row: `, textures etc2`
/// for the scenes' own format (`, the scenes' textures` when they differ)
/// and `, textures rgba8` for the RGBA8 rows.
pub fn suffix(own: Option<&str>) -> String {
    match own {
        Some(f) => format!(", textures {f}"),
        None => ", the scenes' textures".into(),
    }
}

/// The RGBA8 suffix.
pub fn rgba8_suffix() -> String {
    format!(", textures {RGBA8}")
}

/// Ideal memory's speedup in RGBA8 on machine `d` (the figure of
/// [`Figures::motivation`] on the RGBA8 view), or None when the RGBA8 runs
/// are not on `d`.
pub fn ideal(plan: &Plan, view: &Outcome, d: Dispatch) -> Option<Figure> {
    (machine(plan) == Some(d) && !view.points.is_empty())
        .then(|| Figures::new(plan, view).motivation(d))
}

/// The bullet of "Why the numbers differ" on the textures: CF and ideal
/// memory's headroom with the scenes' own textures and with RGBA8 on the
/// first machine, and which is closer to the paper's CF (nothing when the
/// run has no RGBA8 measurements).
pub fn note(md: &mut String, plan: &Plan, out: &Outcome) {
    let view = view(plan, out);
    let Some(d) = machine(plan).filter(|_| !view.scenes.is_empty()) else {
        return;
    };
    let cf_of = |o: &Outcome| {
        scene_figures(plan, o)
            .into_iter()
            .find(|f| f.id == "cf")
            .map(|f| group_values(&f, 0))
    };
    let (Some(own), Some(rgba8)) = (cf_of(out), cf_of(&view)) else {
        return;
    };
    let own_name = own_format(plan, out).unwrap_or_else(|| "the scenes' own".into());
    let f2 = |v: Option<f64>| v.map_or("-".into(), |x| format!("{x:.2}"));
    let target = paper::CF.value;
    let closer = match (own[0], rgba8[0]) {
        (Some(a), Some(b)) if (a - target).abs() < (b - target).abs() => {
            format!("{own_name} textures bring the games' CF closer to the paper's {target}")
        }
        (Some(a), Some(b)) if (a - target).abs() > (b - target).abs() => {
            format!("rgba8 textures bring the games' CF closer to the paper's {target}")
        }
        (Some(_), Some(_)) => format!("both formats are as far from the paper's {target}"),
        _ => "one format only was measured".into(),
    };
    let headroom = |o: &Outcome| group_values(&Figures::new(plan, o).motivation(d), 0);
    let (hi, h8) = (headroom(out), headroom(&view));
    let _ = writeln!(
        md,
        "- **Texture format** (the scenes store theirs as {own_name}; docs/textures.md): CF is \
         {} on games ({} 3D, {} 2D) against {} ({} 3D, {} 2D) with every texture in rgba8; \
         {closer}. Ideal memory makes the {d} baseline {} faster on 3D and {} on 2D scenes \
         with {own_name} textures, {} and {} with rgba8.",
        f2(own[0]),
        f2(own[1]),
        f2(own[2]),
        f2(rgba8[0]),
        f2(rgba8[1]),
        f2(rgba8[2]),
        pct(hi[1]),
        pct(hi[2]),
        pct(h8[1]),
        pct(h8[2]),
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reproduce::contrary;
    use crate::study::point::Point;

    /// The contrary quick look with RGBA8 results: every RGBA8
    /// characterisation has CF `cf` and every RGBA8 ideal run is
    /// `ideal_cycles`.
    fn with_rgba8(cf: f64, ideal_cycles: u64) -> (Plan, Outcome) {
        let (plan, mut out) = contrary::outcome(vec![Dispatch::SharedTile]);
        for c in out.scenes.values_mut() {
            c.texture_format = "etc2".into();
        }
        for t in tasks(&plan) {
            match t {
                Task::Characterize { scene, .. } => {
                    let mut c = out.scenes[&scene].clone();
                    c.cf = cf;
                    c.texture_format = "rgba8".into();
                    out.scenes_as.insert((scene, RGBA8), c);
                }
                Task::Run(p) => {
                    let ideal = p.value_of("memory.ideal") == Some(&toml::Value::Boolean(true));
                    let plain = Point {
                        texture_format: None,
                        ..p.clone()
                    };
                    let mut r = out.points[&plain].clone();
                    if ideal {
                        r.stats.cycles = ideal_cycles;
                    }
                    out.points.insert(p, r);
                }
                Task::Timeline { .. } => {}
            }
        }
        (plan, out)
    }

    #[test]
    fn the_tasks_are_the_maps_rgba8_points_on_the_first_machine() {
        let (plan, _) = contrary::outcome(vec![Dispatch::PerCoreTile, Dispatch::SharedTile]);
        let map = super::super::map::plan::MapPlan::new(plan.wasp, true);
        let t = tasks(&plan);
        assert_eq!(t.len(), 3 * plan.scenes.len());
        let knob = map.knobs.iter().find(|k| k.texture_format).unwrap();
        let map_tasks = map.tasks(&[plan.scenes[0].name.clone()]);
        // On the shared-tile machine the RGBA8 runs are the map's points.
        let shared = Plan {
            dispatches: vec![Dispatch::SharedTile],
            ..plan.clone()
        };
        let s = &shared.scenes[0].name;
        for v in [
            super::super::map::knobs::Variant::Baseline,
            super::super::map::knobs::Variant::Ideal,
        ] {
            let p = map.knob_point(s, knob, "rgba8", v);
            assert!(map_tasks.contains(&Task::Run(p.clone())));
            assert!(tasks(&shared).contains(&Task::Run(p)));
        }
        // With the per-core-tile machine first, they run there.
        let Task::Run(p) = &t[1] else { panic!("a run") };
        let dispatch = p.value_of("raster.dispatch").and_then(toml::Value::as_str);
        assert_eq!(dispatch, Some("per-core-tile"), "{p:?}");
        assert_eq!(p.texture_format, Some(RGBA8));
    }

    #[test]
    fn the_view_reads_the_rgba8_results_under_the_plans_points() {
        let (plan, out) = with_rgba8(4.0, 500);
        assert_eq!(own_format(&plan, &out).as_deref(), Some("etc2"));
        let v = view(&plan, &out);
        assert_eq!(v.scenes.len(), plan.scenes.len());
        assert!(v.scenes.values().all(|c| c.cf == 4.0));
        let d = Dispatch::SharedTile;
        let f = ideal(&plan, &v, d).unwrap();
        // Baseline 1000 cycles against ideal 500: +100%.
        assert_eq!(group_values(&f, 0)[1], Some(1.0));
        assert!(ideal(&plan, &v, Dispatch::PerCoreTile).is_none());
        assert!(view(&plan, &Outcome::default()).scenes.is_empty());
    }

    #[test]
    fn the_note_says_which_format_comes_closer_to_the_papers_cf() {
        // The contrary run's own CF: 1.50 on its 3D scenes, 4.00 on its 2D
        // ones, 2.75 on games.
        let (plan, out) = with_rgba8(4.0, 500);
        let mut md = String::new();
        note(&mut md, &plan, &out);
        assert!(md.contains("the scenes store theirs as etc2"), "{md}");
        assert!(
            md.contains("CF is 2.75 on games (1.50 3D, 4.00 2D) against 4.00"),
            "{md}"
        );
        assert!(md.contains("+25.0% faster on 3D"), "{md}");
        assert!(md.contains("+100.0% and +100.0% with rgba8"), "{md}");
        assert!(
            md.contains("etc2 textures bring the games' CF closer"),
            "{md}"
        );
        let (plan, out) = with_rgba8(2.5, 500);
        let mut md = String::new();
        note(&mut md, &plan, &out);
        assert!(
            md.contains("rgba8 textures bring the games' CF closer"),
            "{md}"
        );
        let mut none = String::new();
        note(
            &mut none,
            &plan,
            &contrary::outcome(vec![Dispatch::SharedTile]).1,
        );
        assert!(none.is_empty(), "{none}");
    }

    #[test]
    fn the_headline_gives_each_texture_row_beside_its_rgba8_twin() {
        use crate::reproduce::headline::{headline, headline_md};
        let (plan, out) = with_rgba8(4.0, 500);
        let machines = vec![(Dispatch::SharedTile, Figures::new(&plan, &out))];
        let rows = headline(&plan, &out, &machines);
        let claims: Vec<&str> = rows.iter().map(|r| r.claim.as_str()).collect();
        let at = |c: &str| {
            claims
                .iter()
                .position(|x| *x == c)
                .unwrap_or_else(|| panic!("{c}: {claims:?}"))
        };
        for c in ["CF", "Ideal-memory speedup", "Footprint ratio, mesh4"] {
            let own = at(&format!("{c}, textures etc2"));
            assert_eq!(at(&format!("{c}, textures rgba8")), own + 1, "{c}");
            assert_eq!(rows[own].paper, rows[own + 1].paper, "{c}");
        }
        let cf = &rows[at("CF, textures rgba8")];
        assert_eq!(cf.ours[0], ["4.00", "4.00", "4.00", "4.00"]);
        assert_eq!(rows[at("CF, textures etc2")].ours[0][0], "2.75");
        let ideal = &rows[at("Ideal-memory speedup, textures rgba8")];
        assert_eq!(ideal.ours[0][1], "+100.0%");
        let mut md = String::new();
        headline_md(&mut md, &rows, &plan);
        assert!(md.contains("Rows ending `textures rgba8`"), "{md}");
        // Without RGBA8 results the rows keep their plain names.
        let (plan, out) = contrary::outcome(vec![Dispatch::SharedTile]);
        let machines = vec![(Dispatch::SharedTile, Figures::new(&plan, &out))];
        let rows = headline(&plan, &out, &machines);
        assert!(rows.iter().any(|r| r.claim == "CF"));
        assert!(!rows.iter().any(|r| r.claim.contains("textures")));
    }
}
