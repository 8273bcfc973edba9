//! The map's figures, each written as `figures/ID.png` and `ID.svg` and
//! its numbers as `data/ID.csv`:
//!
//! - `map-tornado`: WaSP's speedup range per knob on the 3D and 2D scenes;
//! - `map-warps`: WaSP's and the oracle's speedup against warps per core;
//! - `map-grid.GROUP`: WaSP's speedup over the grid of the two knobs that
//!   move it most;
//! - `map-area`: cycles against register-file bits for the baseline and
//!   WaSP across warp counts, with the paper's highlighted pairs.

use super::data::GROUPS;
use super::knobs::Variant;
use super::plan::MapPlan;
use super::table::MapTable;
use crate::charts::{
    draw_heatmap, draw_tornado, draw_xy, HeatMap, Highlight, Key, Span, TornadoChart, TornadoRow,
    TornadoSeries, XyChart, XySeries,
};
use crate::reproduce::figures::{group_key, mean};
use crate::reproduce::plan::{Group, Plan, Width};
use crate::study::cache::write_atomic;
use crate::study::runner::Outcome;
use std::path::Path;
use wasp_rtl::policy::PolicySpec;
use wasp_sim::cost::RfParams;
use wasp_sim::stats::csv_text;

/// A drawn figure: its id and title, for the report.
pub struct Drawn {
    /// File stem under `figures/` and `data/`.
    pub id: String,
    /// Title.
    pub title: String,
}

fn both(id: &str, dir: &Path, draw: impl Fn(&Path) -> Result<(), String>) -> Result<(), String> {
    for ext in ["png", "svg"] {
        draw(&dir.join(format!("{id}.{ext}")))?;
    }
    Ok(())
}

fn gi(g: Group) -> usize {
    GROUPS.iter().position(|&x| x == g).unwrap_or(0)
}

/// The tornado chart of WaSP's range per knob (3D and 2D scenes).
pub fn tornado(t: &MapTable, figs: &Path, data: &Path) -> Result<Option<Drawn>, String> {
    let groups = [Group::ThreeD, Group::TwoD];
    let rows: Vec<TornadoRow> = t
        .knobs
        .iter()
        .filter(|k| k.rows.len() > 1)
        .map(|k| TornadoRow {
            parameter: k.label.clone(),
            spans: groups
                .iter()
                .map(|&g| {
                    k.wasp_range[gi(g)].as_ref().map(|r| Span {
                        low: (r.low.1, r.low.0.clone()),
                        high: (r.high.1, r.high.0.clone()),
                    })
                })
                .collect(),
        })
        .filter(|r| r.spans.iter().any(Option::is_some))
        .collect();
    if rows.is_empty() {
        return Ok(None);
    }
    let chart = TornadoChart {
        title: "What moves WaSP's gain".into(),
        subtitle: "each knob over its range, the others shipped; mean over each group's scenes"
            .into(),
        x_label: "WaSP's speedup over the baseline of the same machine".into(),
        series: groups
            .iter()
            .map(|&g| TornadoSeries {
                key: group_key(g),
                name: format!("{} scenes", g.label()),
                reference: t.shipped.of(g).wasp,
            })
            .collect(),
        rows: rows.clone(),
        reference_label: "shipped machine".into(),
        percent: true,
    };
    let id = "map-tornado";
    both(id, figs, |p| draw_tornado(&chart, p))?;
    let header = ["knob", "group", "low", "low_at", "high", "high_at"].map(String::from);
    let records = rows.iter().flat_map(|r| {
        groups.iter().zip(&r.spans).filter_map(|(g, s)| {
            let s = s.as_ref()?;
            Some([
                r.parameter.clone(),
                g.label().to_string(),
                s.low.0.to_string(),
                s.low.1.clone(),
                s.high.0.to_string(),
                s.high.1.clone(),
            ])
        })
    });
    let csv = csv_text(std::iter::once(header).chain(records));
    write_atomic(&data.join(format!("{id}.csv")), &csv)?;
    Ok(Some(Drawn {
        id: id.into(),
        title: chart.title,
    }))
}

/// WaSP's and the oracle's speedup against warps per core.
pub fn warps(t: &MapTable, figs: &Path, data: &Path) -> Result<Option<Drawn>, String> {
    let Some(k) = t.knobs.iter().find(|k| k.id == "warps") else {
        return Ok(None);
    };
    let mut series = Vec::new();
    for (v, key, name) in [
        (Variant::Wasp, Key::Wasp, "WaSP"),
        (Variant::Oracle, Key::Oracle, "oracle bound"),
    ] {
        for g in [Group::ThreeD, Group::TwoD] {
            let points: Vec<(f64, f64, String)> = k
                .rows
                .iter()
                .filter_map(|r| {
                    let x: f64 = r.value.parse().ok()?;
                    Some((x, r.of(g).speedup(v)?, r.value.clone()))
                })
                .collect();
            if points.is_empty() {
                continue;
            }
            series.push(XySeries {
                key,
                name: format!("{name}, {} scenes", g.label()),
                points: points.iter().map(|p| (p.0, p.1)).collect(),
                labels: Vec::new(),
            });
        }
    }
    if series.is_empty() {
        return Ok(None);
    }
    let chart = XyChart {
        title: "WaSP and the oracle bound against warps per core".into(),
        subtitle: "speedup over the baseline with as many warps (input queue 64), mean per group"
            .into(),
        x_label: "warp slots per core".into(),
        y_label: "speedup over the baseline".into(),
        series,
        highlights: Vec::new(),
        percent: true,
        reference: Some(0.0),
    };
    let id = "map-warps";
    both(id, figs, |p| draw_xy(&chart, p))?;
    write_atomic(&data.join(format!("{id}.csv")), &xy_csv(&chart))?;
    Ok(Some(Drawn {
        id: id.into(),
        title: chart.title,
    }))
}

fn xy_csv(c: &XyChart) -> String {
    let rows = c.series.iter().flat_map(|x| {
        x.points
            .iter()
            .map(|p| [x.name.clone(), p.0.to_string(), p.1.to_string()])
    });
    csv_text(std::iter::once(["series", "x", "y"].map(String::from)).chain(rows))
}

/// The grid of the two knobs that move WaSP most, one heat map per group.
pub fn grid(
    map: &MapPlan,
    t: &MapTable,
    groups: &[Group],
    figs: &Path,
) -> Result<Vec<Drawn>, String> {
    let Some((a, b, cells)) = &t.grid else {
        return Ok(Vec::new());
    };
    let (ka, kb) = (&map.knobs[*a], &map.knobs[*b]);
    let (ys, xs) = (ka.values_for(map.quick), kb.values_for(map.quick));
    let mut out = Vec::new();
    for &g in groups {
        let values: Vec<Vec<Option<f64>>> = ys
            .iter()
            .map(|y| {
                xs.iter()
                    .map(|x| {
                        cells
                            .iter()
                            .find(|r| r.value == format!("{y}, {x}"))
                            .and_then(|r| r.of(g).wasp)
                    })
                    .collect()
            })
            .collect();
        if values.iter().flatten().all(Option::is_none) {
            continue;
        }
        let chart = HeatMap {
            title: format!(
                "WaSP over {} and {}, {} scenes",
                ka.label,
                kb.label,
                g.label()
            ),
            subtitle: "speedup over the baseline of the same machine, mean over the group".into(),
            x_label: kb.label.into(),
            y_label: ka.label.into(),
            x: xs.iter().map(|s| s.to_string()).collect(),
            y: ys.iter().map(|s| s.to_string()).collect(),
            values,
            percent: true,
            scale_label: "WaSP's speedup".into(),
        };
        let id = format!("map-grid.{}", g.label());
        both(&id, figs, |p| draw_heatmap(&chart, p))?;
        out.push(Drawn {
            id,
            title: chart.title,
        });
    }
    Ok(out)
}

/// One point of the area-performance figure.
struct AreaPoint {
    warps: u32,
    bits: f64,
    cycles: f64,
}

/// The baseline's and WaSP's cycles at each warp count of width `w`, mean
/// over games of `cycles / cycles of the baseline at the paper's optimum
/// - 1`, against the register-file bits of one core.
fn area_series(plan: &Plan, out: &Outcome, w: &Width, pol: PolicySpec) -> Vec<AreaPoint> {
    let Ok(cfg) = crate::study::point::base_config(w.config) else {
        return Vec::new();
    };
    let rf = RfParams::for_config(&cfg);
    let per_warp = f64::from(rf.threads_per_warp * rf.registers_per_thread * rf.register_bits);
    let d = wasp_sim::config::Dispatch::SharedTile;
    let games = plan.scenes.iter().filter(|s| s.group != Group::Procedural);
    let names: Vec<&str> = games.map(|s| s.name.as_str()).collect();
    plan.warps
        .iter()
        .filter_map(|&k| {
            let c = mean(names.iter().filter_map(|s| {
                let base =
                    plan.sensitivity_point(s, d, w, w.paper_best_warps, PolicySpec::Baseline);
                let x = plan.sensitivity_point(s, d, w, k, pol);
                Some(out.get(&x)?.cycles() / out.get(&base)?.cycles() - 1.0)
            }))?;
            Some(AreaPoint {
                warps: k,
                bits: per_warp * f64::from(k),
                cycles: c,
            })
        })
        .collect()
}

/// Cycles against register-file bits (from `wasp cost`'s register-file
/// parameters) for the baseline and WaSP at every warp count of the
/// sensitivity study, the paper's highlighted pairs ringed.
pub fn area(plan: &Plan, out: &Outcome, figs: &Path, data: &Path) -> Result<Option<Drawn>, String> {
    let mut series = Vec::new();
    let mut highlights = Vec::new();
    for w in &plan.widths {
        let (wasp_k, base_k) = if w.width == 2 { (32, 48) } else { (48, 64) };
        let mut idx = [None, None];
        for (i, (pol, name)) in [(PolicySpec::Baseline, "baseline"), (plan.wasp, "WaSP")]
            .into_iter()
            .enumerate()
        {
            let pts = area_series(plan, out, w, pol);
            if pts.is_empty() {
                continue;
            }
            let want = if i == 0 { base_k } else { wasp_k };
            let at = pts.iter().position(|p| p.warps == want);
            series.push(XySeries {
                key: pol.into(),
                name: format!("{name}, width {}", w.width),
                points: pts.iter().map(|p| (p.bits / 8192.0, p.cycles)).collect(),
                labels: pts.iter().map(|p| p.warps.to_string()).collect(),
            });
            idx[i] = at.map(|a| (series.len() - 1, a));
        }
        if let [Some(b), Some(x)] = idx {
            highlights.push(Highlight {
                points: vec![x, b],
                caption: format!(
                    "paper, width {}: WaSP@{wasp_k} {} the baseline@{base_k}",
                    w.width,
                    if w.width == 2 { "matches" } else { "beats" }
                ),
            });
        }
    }
    if series.is_empty() {
        return Ok(None);
    }
    let chart = XyChart {
        title: "Area and performance: cycles against register-file size".into(),
        subtitle: "mean over games of cycles against the baseline at the paper's optimum warp \
                   count of the width; points labelled with warps per core"
            .into(),
        x_label: "register file per core (KiB)".into(),
        y_label: "cycles against the baseline at the paper's optimum".into(),
        series,
        highlights,
        percent: true,
        reference: Some(0.0),
    };
    let id = "map-area";
    both(id, figs, |p| draw_xy(&chart, p))?;
    write_atomic(&data.join(format!("{id}.csv")), &xy_csv(&chart))?;
    Ok(Some(Drawn {
        id: id.into(),
        title: chart.title,
    }))
}
