//! The figures of the scenes themselves, the same on every machine:
//! Min_Estimate1, CF and Min_Estimate2 (Figure 4) and the footprint ratios
//! of the priority subsets (Figures 11 and 15).

use super::axis::Axis;
use super::figure::{Figure, Kind, PaperValue, SeriesData};
use super::numbers::size_ratio;
use crate::reproduce::paper;
use crate::reproduce::plan::Plan;
use crate::study::runner::Outcome;

/// The scene characterisation figures (no machine): Min_Estimate1, CF and
/// Min_Estimate2 (Figure 4), and the footprint ratios (Figures 11 and 15).
pub fn scene_figures(plan: &Plan, out: &Outcome) -> Vec<Figure> {
    let axis = Axis::new(plan);
    let (separators, highlight, groups) = axis.marks();
    let per = |f: &dyn Fn(&wasp_frontend::characterize::Characterization) -> Option<f64>| {
        let v = axis
            .scenes
            .iter()
            .map(|s| out.scenes.get(s).and_then(f))
            .collect();
        axis.with_means(v)
    };
    let fp = |name: &'static str| {
        move |c: &wasp_frontend::characterize::Characterization| {
            c.footprints
                .iter()
                .find(|f| f.subset == name || f.subset.starts_with(&format!("{name}:")))
                .map(|f| f.footprint_ratio)
        }
    };
    let base = Figure {
        id: String::new(),
        title: String::new(),
        subtitle: "per scene, 64x64-pixel tiles".into(),
        y_label: String::new(),
        kind: Kind::Bars,
        categories: axis.categories(),
        series: Vec::new(),
        paper: Vec::new(),
        percent: false,
        signed: false,
        reference: None,
        separators,
        highlight,
        groups,
        caption: String::new(),
    };
    let mut estimates = Figure {
        id: "subset-size".into(),
        title: "Priority subset size: Min_Estimate1 and Min_Estimate2".into(),
        y_label: "fraction of a tile's warps".into(),
        series: vec![
            SeriesData {
                name: "Min_Estimate1 (unique blocks / warps)".into(),
                values: per(&|c| Some(c.min_estimate1)),
            },
            SeriesData {
                name: "Min_Estimate2 (/ CF)".into(),
                values: per(&|c| Some(c.min_estimate2)),
            },
        ],
        caption: "The paper's Figure 4: the smallest subset that could hold a tile's footprint, \
                  from which it picks 1/16 (Mesh4)."
            .into(),
        ..base.clone()
    };
    estimates.paper = vec![
        PaperValue {
            series: Some(0),
            category: None,
            value: paper::MIN_ESTIMATE1.value,
            label: format!("Min_Estimate1 mean {}", paper::MIN_ESTIMATE1.value),
        },
        PaperValue {
            series: Some(1),
            category: None,
            value: paper::MIN_ESTIMATE2.value,
            label: "its pick for Min_Estimate2, 1/16".into(),
        },
    ];
    let cf = Figure {
        id: "cf".into(),
        title: "CF: distinct texture blocks per warp".into(),
        y_label: "blocks per warp".into(),
        series: vec![SeriesData {
            name: "CF".into(),
            values: per(&|c| Some(c.cf)),
        }],
        paper: vec![PaperValue {
            series: Some(0),
            category: None,
            value: paper::CF.value,
            label: format!("CF mean {}", paper::CF.value),
        }],
        caption: "Section III-B's CF, the x CF of WaSP's datapath.".into(),
        ..base.clone()
    };
    let subsets = ["top16", "hlines", "vlines", "mesh4", "random"];
    let mut footprint = Figure {
        id: "footprint".into(),
        title: "Texture footprint ratio of each priority subset".into(),
        y_label: "subset's unique blocks / tile's".into(),
        caption: "Figure 11: the share of a tile's texture blocks the subset's warps touch; \
                  dashed lines are the paper's means."
            .into(),
        ..base.clone()
    };
    for (i, s) in subsets.iter().enumerate() {
        footprint.series.push(SeriesData {
            name: (*s).into(),
            values: per(&fp(s)),
        });
        if let Some(v) = paper::footprint(s) {
            footprint.paper.push(PaperValue {
                series: Some(i),
                category: None,
                value: v,
                label: format!("{s} {v}"),
            });
        }
    }
    let mut meshes = Figure {
        id: "footprint-mesh".into(),
        title: "Texture footprint ratio per Mesh size".into(),
        y_label: "subset's unique blocks / tile's".into(),
        caption: "Figure 15: larger meshes select fewer warps (size ratio 1/N^2) and cover \
                  less of the footprint."
            .into(),
        ..base
    };
    for (i, n) in plan.meshes.iter().enumerate() {
        let name: &'static str = match n {
            2 => "mesh2",
            4 => "mesh4",
            8 => "mesh8",
            _ => "mesh16",
        };
        meshes.series.push(SeriesData {
            name: format!("Mesh{n} (size ratio {})", size_ratio(*n)),
            values: per(&fp(name)),
        });
        if let Some(v) = paper::footprint(name) {
            meshes.paper.push(PaperValue {
                series: Some(i),
                category: None,
                value: v,
                label: format!("Mesh{n} {v}"),
            });
        }
    }
    vec![estimates, cf, footprint, meshes]
}
