//! Draws a [`Figure`] with [`crate::charts`] as `ID.png` and `ID.svg`.
//!
//! Line figures put their points at evenly spaced positions labelled with
//! the categories (warp counts 28, 32, 48, 64, 128 read better evenly
//! spaced than on a linear axis).

use super::figures::{Figure, Kind, PaperValue};
use crate::charts::{draw_bars, draw_lines, BarChart, CategoryGroup, LineChart, PaperMark, Series};
use std::path::Path;

fn marks(v: &[PaperValue]) -> Vec<PaperMark> {
    let mark = |p: &PaperValue| PaperMark {
        series: p.series,
        category: p.category,
        value: p.value,
        label: format!("paper: {}", p.label),
    };
    v.iter().map(mark).collect()
}

fn series(f: &Figure) -> Vec<Series> {
    let series = f.series.iter().map(|s| Series {
        key: s.key,
        name: s.name.clone(),
        values: s.values.clone(),
    });
    series.collect()
}

/// Draw `f` into `dir` as `ID.png` and `ID.svg`.
pub fn figure(f: &Figure, dir: &Path) -> Result<(), String> {
    for ext in ["png", "svg"] {
        let path = dir.join(format!("{}.{ext}", f.id));
        match &f.kind {
            Kind::Bars => draw_bars(
                &BarChart {
                    subtitle: f.subtitle.clone(),
                    series: series(f),
                    paper: marks(&f.paper),
                    percent: f.percent,
                    reference: f.reference,
                    separators: f.separators.clone(),
                    highlight: f.highlight.clone(),
                    groups: (f.groups.iter())
                        .map(|(label, categories)| CategoryGroup {
                            label: label.clone(),
                            categories: categories.clone(),
                        })
                        .collect(),
                    title: f.title.clone(),
                    y_label: f.y_label.clone(),
                    categories: f.categories.clone(),
                },
                &path,
            )?,
            Kind::Lines { x_label, .. } => draw_lines(
                &LineChart {
                    subtitle: f.subtitle.clone(),
                    x_ticks: Some(f.categories.clone()),
                    series: series(f),
                    paper: marks(&f.paper),
                    percent: f.percent,
                    reference: f.reference,
                    title: f.title.clone(),
                    x_label: x_label.clone(),
                    y_label: f.y_label.clone(),
                    x: (0..f.categories.len()).map(|i| i as f64).collect(),
                },
                &path,
            )?,
        }
    }
    Ok(())
}
