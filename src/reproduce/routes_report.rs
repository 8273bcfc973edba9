//! REPORT.md's words on the two routes of the scenes (wasp's loaders and
//! the games' own engines): the route of every scene in the scene list,
//! the scenes reported beside the means and those left out (with why),
//! and the section "The loaders against the engine" with `data/routes.csv`:
//! for each camera with both routes in the run, the loader scene against
//! its engine twin (the workload's figures and the cycles of the
//! baseline, WaSP, the raster prefetcher and the oracle), every sentence
//! built from the run's numbers.

use super::plan::{Plan, SceneInfo};
use super::prose::pct;
use super::routes::Twin;
use crate::study::runner::Outcome;
use std::fmt::Write as _;
use wasp_frontend::def::Route;
use wasp_sim::stats::csv_text;

/// A scene's name with its route, as scene lists print it.
pub fn named(s: &SceneInfo) -> String {
    format!("{} ({})", s.name, s.route)
}

/// How many scenes of the study each route drew, for "This run
/// measured": "13 drawn by wasp's loaders, 3 by the games' engines".
pub fn route_counts(plan: &Plan) -> String {
    let n = |r: Route| plan.scenes.iter().filter(|s| s.route == r).count();
    let (l, e) = (n(Route::Loader), n(Route::Engine));
    match (l, e) {
        (_, 0) => "all drawn by wasp's loaders".into(),
        (0, _) => "all drawn by the games' engines".into(),
        _ => format!("{l} drawn by wasp's loaders, {e} by the games' engines"),
    }
}

/// The lines after the scene list: the scenes reported beside the means
/// and the scenes left out, each with its route and why.
pub fn scene_list_notes(md: &mut String, plan: &Plan) {
    if !plan.beside.is_empty() {
        let names: Vec<String> = plan.beside.iter().map(named).collect();
        let _ = writeln!(
            md,
            "- beside the means ({}): {} — the twins of the route not counted (`--routes {}`), \
             compared in \"The loaders against the engine\"",
            names.len(),
            names.join(", "),
            plan.routes.name()
        );
    }
    for l in &plan.left_out {
        let _ = writeln!(
            md,
            "- **left out**: {} ({}), which could not be drawn: {}",
            l.name,
            l.route,
            l.reason.trim_end_matches('.')
        );
    }
}

/// One scene of a twin pair in the comparison.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RouteRow {
    /// The camera: the loader scene's name.
    pub camera: String,
    /// The scene's route.
    pub route: Route,
    /// The scene.
    pub scene: String,
    /// Quads shaded (warps).
    pub quads: Option<f64>,
    /// Quads Early-Z rejected.
    pub rejects: Option<f64>,
    /// Shaded warps per quad position.
    pub warps_per_position: Option<f64>,
    /// Distinct blocks per tile.
    pub blocks_per_tile: Option<f64>,
    /// Distinct blocks per warp (CF).
    pub cf: Option<f64>,
    /// The Mesh4 subset's footprint ratio.
    pub mesh4: Option<f64>,
    /// Cycles of the baseline, WaSP, the raster prefetcher and the oracle
    /// ([`Plan::route_points`] order).
    pub cycles: [Option<f64>; 4],
}

impl RouteRow {
    /// The speedup over the baseline of the point `i` of
    /// [`RouteRow::cycles`] (1: WaSP, 2: raster, 3: oracle).
    pub fn speedup(&self, i: usize) -> Option<f64> {
        Some(self.cycles[0]? / self.cycles[i]? - 1.0)
    }
}

/// The rows of the twin pairs of `plan` from the run: loader, then engine.
pub fn rows(plan: &Plan, out: &Outcome) -> Vec<RouteRow> {
    let mut v = Vec::new();
    for Twin { loader, engine } in &plan.twins {
        for (route, scene) in [(Route::Loader, loader), (Route::Engine, engine)] {
            let c = out.scenes.get(scene);
            let points = plan.route_points(scene);
            v.push(RouteRow {
                camera: loader.clone(),
                route,
                scene: scene.clone(),
                quads: c.map(|c| c.warps as f64),
                rejects: c.map(|c| c.rejected_early_z as f64),
                warps_per_position: c.map(|c| c.warps_per_position),
                blocks_per_tile: c.map(|c| c.blocks_per_tile),
                cf: c.map(|c| c.cf),
                mesh4: c.and_then(|c| {
                    c.footprints
                        .iter()
                        .find(|f| f.subset == "mesh4")
                        .map(|f| f.footprint_ratio)
                }),
                cycles: points
                    .map(|(_, p)| out.get(&p).map(|r| r.cycles()).filter(|c| c.is_finite())),
            });
        }
    }
    v
}

/// The columns of `data/routes.csv` after camera, route and scene.
const COLUMNS: [&str; 10] = [
    "quads_shaded",
    "early_z_rejects",
    "warps_per_position",
    "blocks_per_tile",
    "cf",
    "mesh4_footprint_ratio",
    "cycles_baseline",
    "cycles_wasp",
    "cycles_raster_prefetcher",
    "cycles_oracle",
];

fn values(r: &RouteRow) -> [Option<f64>; 10] {
    [
        r.quads,
        r.rejects,
        r.warps_per_position,
        r.blocks_per_tile,
        r.cf,
        r.mesh4,
        r.cycles[0],
        r.cycles[1],
        r.cycles[2],
        r.cycles[3],
    ]
}

/// `data/routes.csv`: a row per scene of a twin pair (empty: not run).
pub fn routes_csv(rows: &[RouteRow]) -> String {
    let header = ["camera", "route", "scene"].into_iter().chain(COLUMNS);
    let records = rows.iter().map(|r| {
        [r.camera.clone(), r.route.to_string(), r.scene.clone()]
            .into_iter()
            .chain(values(r).map(|v| v.map_or(String::new(), |x| x.to_string())))
            .collect::<Vec<String>>()
    });
    csv_text(std::iter::once(header.map(String::from).collect::<Vec<String>>()).chain(records))
}

fn int(v: Option<f64>) -> String {
    v.map_or("-".into(), |x| format!("{x:.0}"))
}

fn dec(v: Option<f64>, places: usize) -> String {
    v.map_or("-".into(), |x| format!("{x:.places$}"))
}

/// The workload's figures of a row as the table and the sentences print
/// them: quads, rejects, warps per position, blocks per tile, CF, Mesh4.
fn shown(r: &RouteRow) -> [String; 6] {
    [
        int(r.quads),
        int(r.rejects),
        dec(r.warps_per_position, 2),
        dec(r.blocks_per_tile, 1),
        dec(r.cf, 2),
        dec(r.mesh4, 3),
    ]
}

/// Cycles with the speedup over the baseline (`123456 (+3.2%)`).
fn cycles_cell(r: &RouteRow, i: usize) -> String {
    match (r.cycles[i], i) {
        (None, _) => "-".into(),
        (Some(c), 0) => format!("{c:.0}"),
        (Some(c), _) => format!("{c:.0} ({})", pct(r.speedup(i))),
    }
}

/// The section "The loaders against the engine".
pub fn section(md: &mut String, plan: &Plan, rows: &[RouteRow]) {
    let _ = writeln!(md, "\n## The loaders against the engine\n");
    let engine_left: Vec<String> = plan
        .left_out
        .iter()
        .filter(|l| l.route == Route::Engine)
        .map(|l| format!("{} ({})", l.name, l.reason.trim_end_matches('.')))
        .collect();
    let left = if engine_left.is_empty() {
        String::new()
    } else {
        format!(
            " Left out, without an engine frame: {}.",
            engine_left.join("; ")
        )
    };
    if rows.is_empty() {
        let _ = writeln!(
            md,
            "No camera of this run has both a loader scene and an engine twin (`route = \
             \"engine\"`), so nothing is compared here.{left}"
        );
        return;
    }
    let _ = writeln!(
        md,
        "Each camera with both routes in this run: wasp's loader scene against its engine \
         twin, the frame the game's own engine drew (captured with apitrace and imported as \
         `wasp import-gl` does), on the {} machine. The {} counts in the run's group means \
         (`--routes {}`).{left} Cycles are followed by the speedup over the baseline; the \
         raster prefetcher and the oracle tile prefetcher run on the baseline scheduler. \
         (data: `data/routes.csv`)\n",
        plan.route_dispatch(),
        match plan.routes {
            super::routes::RouteChoice::Engine => "engine twin",
            super::routes::RouteChoice::Loader => "loader scene",
            super::routes::RouteChoice::Both => "pair (both twins)",
        },
        plan.routes.name()
    );
    let _ = writeln!(
        md,
        "| camera | route | quads shaded | Early-Z rejects | warps per position | blocks per \
         tile | CF | Mesh4 footprint ratio | baseline cycles | WaSP | raster prefetcher | \
         oracle |\n|---|---|---|---|---|---|---|---|---|---|---|---|"
    );
    for r in rows {
        let cells: Vec<String> = shown(r)
            .into_iter()
            .chain((0..4).map(|i| cycles_cell(r, i)))
            .collect();
        let _ = writeln!(md, "| {} | {} | {} |", r.camera, r.route, cells.join(" | "));
    }
    let _ = writeln!(md);
    for pair in rows.chunks(2) {
        if let [l, e] = pair {
            let _ = writeln!(md, "- {}\n", pair_sentence(l, e));
        }
    }
}

/// `e / l` as "1.23x" (`-` when either is missing or `l` is zero).
fn ratio(e: Option<f64>, l: Option<f64>) -> String {
    match (e, l) {
        (Some(e), Some(l)) if l != 0.0 => format!("{:.2}x", e / l),
        _ => "-".into(),
    }
}

/// The techniques (WaSP, raster, oracle) by speedup, best first, when all
/// three ran.
fn ranking(r: &RouteRow) -> Option<Vec<&'static str>> {
    let mut v: Vec<(&str, f64)> = vec![
        ("WaSP", r.speedup(1)?),
        ("the raster prefetcher", r.speedup(2)?),
        ("the oracle", r.speedup(3)?),
    ];
    v.sort_by(|a, b| b.1.total_cmp(&a.1));
    Some(v.into_iter().map(|x| x.0).collect())
}

/// The sentence of one camera: the engine's figures against the loader's
/// and the speedups through each route.
fn pair_sentence(l: &RouteRow, e: &RouteRow) -> String {
    let (es, ls) = (shown(e), shown(l));
    let mut s = format!(
        "**{}**: the engine ({}) shades {} the loader's quads ({} against {}), Early-Z \
         rejects {} as many ({} against {}); {} warps per position against {}, {} blocks \
         per tile against {}, a CF of {} against {}, a Mesh4 footprint ratio of {} against \
         {}.",
        l.camera,
        e.scene,
        ratio(e.quads, l.quads),
        es[0],
        ls[0],
        ratio(e.rejects, l.rejects),
        es[1],
        ls[1],
        es[2],
        ls[2],
        es[3],
        ls[3],
        es[4],
        ls[4],
        es[5],
        ls[5]
    );
    let _ = write!(
        s,
        " Over the baseline, WaSP gains {} through the engine and {} through the loader, the \
         raster prefetcher {} and {}, the oracle {} and {}",
        pct(e.speedup(1)),
        pct(l.speedup(1)),
        pct(e.speedup(2)),
        pct(l.speedup(2)),
        pct(e.speedup(3)),
        pct(l.speedup(3))
    );
    match (ranking(e), ranking(l)) {
        (Some(a), Some(b)) if a == b => {
            let _ = write!(s, "; both routes rank them {}.", a.join(", then "));
        }
        (Some(a), Some(b)) => {
            let _ = write!(
                s,
                "; the routes rank them differently: {} through the engine, {} through the \
                 loader.",
                a.join(", then "),
                b.join(", then ")
            );
        }
        _ => s.push_str(" (a point did not run)."),
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reproduce::routes::{LeftOut, RouteChoice};
    use wasp_frontend::def::{self, SceneDef};
    use wasp_sim::config::Dispatch;

    fn row(route: Route, scene: &str, quads: f64, cycles: [f64; 4]) -> RouteRow {
        RouteRow {
            camera: "cam".into(),
            route,
            scene: scene.into(),
            quads: Some(quads),
            rejects: Some(quads / 10.0),
            warps_per_position: Some(1.5),
            blocks_per_tile: Some(100.0),
            cf: Some(3.25),
            mesh4: Some(0.5),
            cycles: cycles.map(Some),
        }
    }

    fn plan_with(names: &[&str], left: Vec<LeftOut>) -> Plan {
        let every: Vec<SceneDef> = def::every().unwrap();
        let defs: Vec<SceneDef> = names
            .iter()
            .map(|n| every.iter().find(|d| d.name == *n).unwrap().clone())
            .collect();
        let mut p = Plan::with_routes(
            &defs,
            false,
            vec![Dispatch::SharedTile],
            RouteChoice::Engine,
        );
        p.left_out = left;
        p
    }

    #[test]
    fn the_routes_table_and_its_sentences_follow_the_numbers() {
        let l = row(Route::Loader, "cam", 1000.0, [100.0, 80.0, 125.0, 50.0]);
        let e = row(
            Route::Engine,
            "cam-engine",
            1500.0,
            [200.0, 250.0, 160.0, 100.0],
        );
        let rows = vec![l.clone(), e.clone()];
        let text = routes_csv(&rows);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0].split(',').count(), 13);
        assert_eq!(
            lines[2],
            "cam,engine,cam-engine,1500,150,1.5,100,3.25,0.5,200,250,160,100"
        );
        let plan = plan_with(&["oa-dm1-spawn0", "oa-dm1-spawn0-engine"], Vec::new());
        let mut md = String::new();
        section(&mut md, &plan, &rows);
        for said in [
            "## The loaders against the engine",
            "The engine twin counts in the run's group means (`--routes engine`)",
            "| cam | engine | 1500 | 150 | 1.50 | 100.0 | 3.25 | 0.500 | 200 | 250 (-20.0%) | \
             160 (+25.0%) | 100 (+100.0%) |",
            "the engine (cam-engine) shades 1.50x the loader's quads (1500 against 1000)",
            "WaSP gains -20.0% through the engine and +25.0% through the loader",
            "the routes rank them differently: the oracle, then the raster prefetcher, then \
             WaSP through the engine, the oracle, then WaSP, then the raster prefetcher through \
             the loader.",
        ] {
            assert!(md.contains(said), "lacks {said:?}:\n{md}");
        }
        // The same order through both routes is said so.
        let same = row(
            Route::Engine,
            "cam-engine",
            1000.0,
            [100.0, 80.0, 125.0, 50.0],
        );
        assert!(pair_sentence(&l, &same).contains("both routes rank them the oracle, then WaSP"));
        // A point that did not run shows as missing, never as a number.
        let mut gap = e.clone();
        gap.cycles[3] = None;
        assert!(pair_sentence(&l, &gap).contains("the oracle - and +100.0% (a point"));
        assert!(routes_csv(&[gap]).ends_with(",200,250,160,\n"));
    }

    #[test]
    fn a_scene_left_out_is_named_with_why() {
        let left = LeftOut {
            name: "tw-dm1-spawn0-engine".into(),
            route: Route::Engine,
            reason: "engine scene tw-dm1-spawn0-engine: call 12: needs GL_TEXTURE_3D.".into(),
        };
        let plan = plan_with(&["tw-dm1-spawn0"], vec![left]);
        let mut md = String::new();
        scene_list_notes(&mut md, &plan);
        assert_eq!(
            md,
            "- **left out**: tw-dm1-spawn0-engine (engine), which could not be drawn: engine \
             scene tw-dm1-spawn0-engine: call 12: needs GL_TEXTURE_3D\n"
        );
        let mut md = String::new();
        section(&mut md, &plan, &rows(&plan, &Outcome::default()));
        assert!(
            md.contains(
                "nothing is compared here. Left out, without an engine frame: \
                 tw-dm1-spawn0-engine (engine scene tw-dm1-spawn0-engine: call 12: needs \
                 GL_TEXTURE_3D)."
            ),
            "{md}"
        );
        assert_eq!(route_counts(&plan), "all drawn by wasp's loaders");
    }

    #[test]
    fn the_scenes_beside_the_means_are_listed_with_their_route() {
        let plan = plan_with(
            &["oa-dm1-spawn0", "oa-dm1-spawn0-engine", "oa-dm5-spawn1"],
            Vec::new(),
        );
        let mut md = String::new();
        scene_list_notes(&mut md, &plan);
        assert!(
            md.starts_with("- beside the means (1): oa-dm1-spawn0 (loader) — the twins"),
            "{md}"
        );
        assert_eq!(
            route_counts(&plan),
            "1 drawn by wasp's loaders, 1 by the games' engines"
        );
        // Rows of a run where nothing ran: every figure missing.
        let r = rows(&plan, &Outcome::default());
        assert_eq!(r.len(), 2);
        assert_eq!((r[0].route, r[1].route), (Route::Loader, Route::Engine));
        assert!(r[1].quads.is_none() && r[1].cycles.iter().all(Option::is_none));
    }
}
