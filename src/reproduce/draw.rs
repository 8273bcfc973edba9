//! Draws a [`Figure`] with [`crate::charts`] as `ID.png` and `ID.svg`.
//!
//! Line figures put their points at evenly spaced positions labelled with
//! the categories (warp counts 28, 32, 48, 64, 128 read better evenly
//! spaced than on a linear axis).

use super::figures::{Figure, Kind, PaperValue};
use crate::charts::{draw_bars, draw_lines, BarChart, LineChart, PaperMark, Series};
use std::path::Path;

fn marks(v: &[PaperValue]) -> Vec<PaperMark> {
    v.iter()
        .map(|p| {
            let label = format!("paper: {}", p.label);
            match p.category {
                None => PaperMark::all(p.series, p.value, label),
                Some(c) => PaperMark::at(p.series, c, p.value, label),
            }
        })
        .collect()
}

fn series(f: &Figure) -> Vec<Series> {
    f.series
        .iter()
        .map(|s| Series::new(s.name.clone(), s.values.clone()))
        .collect()
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
                    ..BarChart::new(&f.title, &f.y_label, f.categories.clone())
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
                    ..LineChart::new(
                        &f.title,
                        x_label,
                        &f.y_label,
                        (0..f.categories.len()).map(|i| i as f64).collect(),
                    )
                },
                &path,
            )?,
        }
    }
    Ok(())
}
