//! Combining point records (from one study folder or several, e.g. one
//! per cluster node) and laying them out as a sweep's results: the rows of
//! `results.csv` / `results.json` and the summary table of `wasp sweep`.
//!
//! A sweep point's record is found by its cache key, computed for every
//! build (`binary`) the records come from, or else by the point itself
//! (scene, draw order, base configuration, overrides); a record of the
//! running build is preferred.

use super::cache::PointRecord;
use super::point::{binary_id, point_key, scene_identity, Point};
use super::runner::Scenes;
use super::sweep::SweepPoint;
use std::collections::{BTreeSet, HashMap, HashSet};
use std::fmt::Write as _;
use wasp_frontend::raster::DrawOrder;
use wasp_frontend::texture::FormatChoice;
use wasp_sim::stats::csv_text;

/// `records` without repeats: records of the same key and point count once,
/// and records of the same key must hold the same statistics.
pub fn combine(records: Vec<PointRecord>) -> Result<Vec<PointRecord>, String> {
    let mut first: HashMap<String, usize> = HashMap::new();
    let mut seen: HashSet<(String, Point)> = HashSet::new();
    let mut out: Vec<PointRecord> = Vec::with_capacity(records.len());
    for r in records {
        if let Some(&i) = first.get(&r.key) {
            if out[i].stats != r.stats {
                return Err(format!(
                    "two records of key {} disagree: {} and {} (different results for one \
                     machine on one scene: were the folders written by a modified build?)",
                    r.key,
                    out[i].point.describe(),
                    r.point.describe()
                ));
            }
        } else {
            first.insert(r.key.clone(), out.len());
        }
        if seen.insert((r.key.clone(), r.point.clone())) {
            out.push(r);
        }
    }
    Ok(out)
}

/// A warning when `records` come from more than one build of `wasp`.
pub fn mixed_builds(records: &[&PointRecord]) -> Option<String> {
    let builds: BTreeSet<&str> = records.iter().map(|r| r.binary.as_str()).collect();
    (builds.len() > 1).then(|| {
        format!(
            "the results come from {} different builds of wasp (binaries {}): they may not be \
             comparable",
            builds.len(),
            builds.into_iter().collect::<Vec<_>>().join(", ")
        )
    })
}

/// The record of every sweep point, if there is one (see the module's
/// documentation for how it is found).
pub fn match_points<'a>(
    points: &[SweepPoint],
    records: &'a [PointRecord],
) -> Result<Vec<Option<&'a PointRecord>>, String> {
    let mut by_key: HashMap<&str, Vec<&PointRecord>> = HashMap::new();
    let mut by_point: HashMap<&Point, Vec<&PointRecord>> = HashMap::new();
    for r in records {
        by_key.entry(&r.key).or_default().push(r);
        by_point.entry(&r.point).or_default().push(r);
    }
    let me = binary_id();
    let mut builds: Vec<&str> = records.iter().map(|r| r.binary.as_str()).collect();
    builds.sort_by_key(|b| (*b != me, *b));
    builds.dedup();
    let mut scenes = Scenes::default();
    type At = (String, Option<DrawOrder>, Option<FormatChoice>);
    let mut ids: HashMap<At, String> = HashMap::new();
    let mut out = Vec::with_capacity(points.len());
    for p in points {
        let at = (p.scene.clone(), p.point.draw_order, p.point.texture_format);
        if !ids.contains_key(&at) {
            let id = scene_identity(&p.point.scene_def(scenes.def(&p.scene)?));
            ids.insert(at.clone(), id);
        }
        let id = &ids[&at];
        let mut found = None;
        for b in &builds {
            let key = point_key(b, id, &p.machine);
            if let Some(r) = by_key.get(key.as_str()) {
                found = Some(r[0]);
                break;
            }
        }
        if found.is_none() {
            found = by_point.get(&p.point).and_then(|v| {
                v.iter()
                    .find(|r| r.binary == me)
                    .or_else(|| v.first())
                    .copied()
            });
        }
        out.push(found);
    }
    Ok(out)
}

/// The message for sweep points without a result: how many, which, and
/// how to run them.
pub fn missing_message(missing: &[usize], total: usize, file: &str, dir: &str) -> String {
    let shown: Vec<String> = missing.iter().take(50).map(|n| n.to_string()).collect();
    let more = if missing.len() > 50 { ", ..." } else { "" };
    format!(
        "{} of {total} points have no result: {}{more}; run them with `wasp sweep {file} --out \
         {dir} --point N`",
        missing.len(),
        shown.join(", ")
    )
}

/// `r` as it reads back from its stored file (numbers through their JSON
/// text), so that a table of a fresh run and one of stored results agree
/// to the last digit.
pub fn as_stored(r: &PointRecord) -> PointRecord {
    let text = serde_json::to_string_pretty(r).expect("records serialize");
    serde_json::from_str(&text).expect("records parse back")
}

/// The columns that label a sweep's point.
const SWEEP_COLUMNS: [&str; 6] = [
    "point",
    "config",
    "dispatch",
    "policy",
    "scene",
    "draw_order",
];

/// Whether some point of `rows` names a texture format (then the outputs
/// show each point's; without, they are those of sweeps before texture
/// formats).
fn names_formats(rows: &[(&SweepPoint, &PointRecord)]) -> bool {
    rows.iter().any(|(p, _)| p.point.texture_format.is_some())
}

/// The sweep's results as CSV: `point`, `config`, `dispatch`, `policy`,
/// `scene`, `draw_order` (the effective one), `texture_format` (the
/// effective one, when some point names one), then every flattened
/// statistic (`wasp run --csv`'s names, in
/// the order they first appear in the rows; a statistic named like a sweep
/// column, e.g. the simulator's `policy`, is `stats.NAME`).
pub fn results_csv(rows: &[(&SweepPoint, &PointRecord)]) -> String {
    let flat: Vec<Vec<(String, String)>> = rows.iter().map(|(_, r)| r.flat_stats()).collect();
    let mut names: Vec<&str> = Vec::new();
    let mut seen: BTreeSet<&str> = BTreeSet::new();
    for (k, _) in flat.iter().flatten() {
        if seen.insert(k) {
            names.push(k);
        }
    }
    let formats = names_formats(rows);
    let mut header: Vec<String> = SWEEP_COLUMNS.iter().map(|c| c.to_string()).collect();
    if formats {
        header.push("texture_format".into());
    }
    header.extend(names.iter().map(|n| match SWEEP_COLUMNS.contains(n) {
        true => format!("stats.{n}"),
        false => n.to_string(),
    }));
    let records = rows.iter().zip(&flat).map(|((p, _), row)| {
        let mut r = vec![
            p.index.to_string(),
            p.config.clone(),
            p.dispatch.clone(),
            p.policy.clone(),
            p.scene.clone(),
            p.draw_order.to_string(),
        ];
        if formats {
            r.push(p.texture_format.to_string());
        }
        let row: HashMap<&str, &str> = row.iter().map(|(k, v)| (k.as_str(), v.as_str())).collect();
        r.extend(
            names
                .iter()
                .map(|n| row.get(n).copied().unwrap_or("").to_string()),
        );
        r
    });
    csv_text(std::iter::once(header).chain(records))
}

/// The sweep's results as a JSON array: per point its labels, the point
/// (base configuration and overrides), its key, build and statistics.
pub fn results_json(rows: &[(&SweepPoint, &PointRecord)]) -> String {
    let v: Vec<serde_json::Value> = rows
        .iter()
        .map(|(p, r)| {
            let mut v = serde_json::json!({
                "point": p.index,
                "config": p.config,
                "dispatch": p.dispatch,
                "policy": p.policy,
                "scene": p.scene,
                "draw_order": p.draw_order,
                "base": p.point.config,
                "sets": p.point.sets,
                "key": r.key,
                "binary": r.binary,
                "stats": r.stats_json(),
            });
            // Only a point that names a texture format shows it: the
            // results of other sweeps stay as they were.
            if p.point.texture_format.is_some() {
                v["texture_format"] = serde_json::json!(p.texture_format);
            }
            v
        })
        .collect();
    serde_json::to_string_pretty(&v).expect("results serialize") + "\n"
}

/// The summary table: point, scene, draw order, config, dispatch, policy,
/// cycles and the speedup against `first_policy` on the same scene, draw
/// order, configuration and dispatch (`-` when that point has no result).
pub fn results_table(rows: &[(&SweepPoint, &PointRecord)], first_policy: &str) -> String {
    fn at(p: &SweepPoint) -> (&str, DrawOrder, FormatChoice, &str, &str) {
        (
            &p.scene,
            p.draw_order,
            p.texture_format,
            &p.config,
            &p.dispatch,
        )
    }
    let formats = names_formats(rows);
    let reference: HashMap<_, f64> = rows
        .iter()
        .filter(|(p, _)| p.policy == first_policy)
        .map(|(p, r)| (at(p), r.cycles()))
        .collect();
    let order = if formats { "order/textures" } else { "order" };
    let head = [
        "point", "scene", order, "config", "dispatch", "policy", "cycles", "speedup",
    ];
    let mut cells: Vec<[String; 8]> = vec![head.map(String::from)];
    for (p, r) in rows {
        let c = r.cycles();
        let speedup = match reference.get(&at(p)) {
            Some(b) if c > 0.0 && b.is_finite() => format!("{:+.2}%", 100.0 * (b / c - 1.0)),
            _ => "-".to_string(),
        };
        cells.push([
            p.index.to_string(),
            p.scene.clone(),
            if formats {
                format!("{}/{}", p.draw_order, p.texture_format)
            } else {
                p.draw_order.to_string()
            },
            p.config.clone(),
            p.dispatch.clone(),
            p.policy.clone(),
            if c.is_finite() {
                format!("{c:.0}")
            } else {
                "-".into()
            },
            speedup,
        ]);
    }
    let mut width = [0usize; 8];
    for row in &cells {
        for (w, c) in width.iter_mut().zip(row) {
            *w = (*w).max(c.chars().count());
        }
    }
    let mut s = String::new();
    for row in &cells {
        let mut line = String::new();
        for (i, (c, w)) in row.iter().zip(width).enumerate() {
            let sep = if i == 0 { "" } else { "  " };
            if i == 0 || i >= 6 {
                let _ = write!(line, "{sep}{c:>w$}");
            } else {
                let _ = write!(line, "{sep}{c:<w$}");
            }
        }
        s.push_str(line.trim_end());
        s.push('\n');
    }
    let also = if formats { ", texture format" } else { "" };
    let _ = writeln!(
        s,
        "speedup = {first_policy} cycles / cycles - 1 on the same scene, draw order{also}, config \
         and dispatch"
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::cache::tests::stats_of;
    use crate::study::sweep::Sweep;
    use std::path::Path;

    fn sweep_points() -> Vec<SweepPoint> {
        let known = vec!["procedural-plane".to_string()];
        Sweep::parse(
            "scenes = [\"procedural-plane\"]\npolicies = [\"baseline\", \"fullpriority\", \"wasp:0:3\"]\n[[configs]]\nname = \"a\"\nbase = \"paper\"\n",
            "s.toml",
            Path::new("/"),
            &known,
        )
        .unwrap()
        .points()
        .unwrap()
    }

    fn record(p: &Point, key: &str, binary: &str, cycles: u64) -> PointRecord {
        PointRecord {
            key: key.into(),
            point: p.clone(),
            binary: binary.into(),
            stats: stats_of(cycles),
        }
    }

    #[test]
    fn repeats_collapse_and_disagreements_are_errors() {
        let pts = sweep_points();
        let a = record(&pts[0].point, "k1", "b", 100);
        let alias = record(&pts[1].point, "k1", "b", 100);
        let v = combine(vec![a.clone(), a.clone(), alias.clone()]).unwrap();
        assert_eq!(v, vec![a.clone(), alias]);
        let e = combine(vec![a.clone(), record(&pts[0].point, "k1", "b", 101)]).unwrap_err();
        assert!(e.starts_with("two records of key k1 disagree"), "{e}");
        assert_eq!(mixed_builds(&[&a, &a]), None);
        let other = record(&pts[2].point, "k2", "c", 5);
        let w = mixed_builds(&[&a, &other]).unwrap();
        assert!(
            w.starts_with("the results come from 2 different builds"),
            "{w}"
        );
    }

    #[test]
    fn points_are_found_by_key_of_any_build_or_by_description() {
        let pts = sweep_points();
        let d = Scenes::default().def("procedural-plane").unwrap().clone();
        let id = scene_identity(&d);
        // Point 1 ran under an older build (found by that build's key, even
        // stored under another description); point 3 by its description;
        // point 2 is missing.
        let old = record(
            &Point::new("procedural-plane", "paper", &[]),
            &point_key("old-build", &id, &pts[0].machine),
            "old-build",
            100,
        );
        let by_point = record(&pts[2].point, "unrelated", binary_id(), 90);
        let records = vec![old.clone(), by_point.clone()];
        let m = match_points(&pts, &records).unwrap();
        assert_eq!(m, vec![Some(&old), None, Some(&by_point)]);
        let missing: Vec<usize> = pts
            .iter()
            .zip(&m)
            .filter(|(_, r)| r.is_none())
            .map(|(p, _)| p.index)
            .collect();
        assert_eq!(
            missing_message(&missing, pts.len(), "/s.toml", "/out"),
            "1 of 3 points have no result: 2; run them with `wasp sweep /s.toml --out /out \
             --point N`"
        );
    }

    #[test]
    fn results_have_the_sweep_columns_then_the_statistics() {
        let pts = sweep_points();
        let r0 = record(&pts[0].point, "k0", "b", 200);
        let mut r2 = record(&pts[2].point, "k2", "b", 160);
        r2.stats.prefetch = None;
        r2.stats.measured_cf_mean = Some(1.5);
        r2.stats.workload = "x,y".into();
        let rows = vec![(&pts[0], &r0), (&pts[2], &r2)];
        let csv = results_csv(&rows);
        let lines: Vec<&str> = csv.lines().collect();
        let head: Vec<&str> = lines[0].split(',').collect();
        let col = |name: &str| head.iter().position(|h| *h == name).unwrap();
        assert_eq!(head[..6], SWEEP_COLUMNS);
        assert_eq!(head[6..8], ["avg_warps_per_core", "block_reuse"]);
        assert!(col("cycles") < col("l0.misses") && col("l0.misses") < col("stats.policy"));
        assert!(lines[1].starts_with("1,a,shared-tile,baseline,procedural-plane,as-loaded,"));
        // The workload is the last column; only the second row's is quoted.
        assert!(lines[2].ends_with(",\"x,y\""), "{}", lines[2]);
        let (a, b): (Vec<&str>, Vec<&str>) =
            (lines[1].split(',').collect(), lines[2].split(',').collect());
        assert_eq!((a[col("cycles")], b[col("cycles")]), ("200", "160"));
        assert_eq!(a[col("stats.policy")], "wasp:0:3");
        assert_eq!(
            (a[col("measured_cf_mean")], b[col("measured_cf_mean")]),
            ("", "1.5")
        );
        let json: serde_json::Value = serde_json::from_str(&results_json(&rows)).unwrap();
        assert_eq!(json[1]["point"], 3);
        assert_eq!(json[1]["policy"], "wasp:0:3");
        assert_eq!(json[1]["stats"]["cycles"], 160);
        assert_eq!(json[1]["sets"][0], "scheduler.policy=\"wasp:0:3\"");
        let t = results_table(&rows, "baseline");
        let lines: Vec<&str> = t.lines().collect();
        assert!(lines[0].starts_with("point  scene"), "{t}");
        assert!(lines[1].ends_with(" 200   +0.00%"), "{t}");
        assert!(lines[2].ends_with("160  +25.00%"), "{t}");
        // Without its reference, a point has no speedup.
        let t = results_table(&rows[1..], "baseline");
        assert!(t.lines().nth(1).unwrap().ends_with("160        -"), "{t}");
    }

    #[test]
    fn a_stored_record_reads_back_the_same() {
        let pts = sweep_points();
        let mut r = record(&pts[0].point, "k", "b", 1);
        r.stats.cf = 0.1 + 0.2;
        let s = as_stored(&r);
        assert_eq!(as_stored(&s), s);
        assert_eq!(s.key, "k");
    }
}
