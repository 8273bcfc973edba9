//! The sensitivity of one machine to its warp slots at each pipeline width
//! (Figure 8): the speedups at each warp count over a reference count, and
//! the best and reference counts.

use super::axis::mean;
use super::figure::{Figure, Kind, PaperValue, SeriesData};
use super::numbers::speedup;
use super::Figures;
use crate::palette::Key;
use crate::reproduce::paper;
use crate::reproduce::plan::Width;
use wasp_rtl::policy::PolicySpec;
use wasp_sim::config::Dispatch;

/// The fastest baseline warp count of a sensitivity sweep and the range it
/// was found in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BestWarps {
    /// The fastest count measured.
    pub warps: u32,
    /// The smallest count measured.
    pub lowest: u32,
    /// The largest count measured.
    pub highest: u32,
}

impl BestWarps {
    /// At the largest count measured: the sweep ends before any optimum.
    pub fn at_edge(&self) -> bool {
        self.warps == self.highest && self.lowest < self.highest
    }

    /// "best at 48 warps (of 28-128)" or "fastest at the largest count
    /// measured, 64 (of 32-64): still rising".
    pub fn describe(&self) -> String {
        if self.at_edge() {
            format!(
                "fastest at the largest count measured, {} warps (of {}-{}): still rising, \
                 no optimum within the range",
                self.warps, self.lowest, self.highest
            )
        } else {
            format!(
                "best at {} warps (of {}-{})",
                self.warps, self.lowest, self.highest
            )
        }
    }

    /// The table's short form: "48", or ">= 64 (edge of 32-64)".
    pub fn short(&self) -> String {
        if self.at_edge() {
            format!(
                ">= {} (edge of {}-{})",
                self.warps, self.lowest, self.highest
            )
        } else {
            self.warps.to_string()
        }
    }
}

impl Figures<'_> {
    /// The mean over games of the per-scene speedup of `pol` at `k` warps
    /// over the baseline at `best` warps (width `w`).
    pub fn sensitivity_speedup(
        &self,
        d: Dispatch,
        w: &Width,
        k: u32,
        pol: PolicySpec,
        best: u32,
    ) -> Option<f64> {
        let p = self.plan;
        let idx = &self.axis.means.iter().find(|m| m.0 == "mean games")?.1;
        mean(idx.iter().filter_map(|&i| {
            let s = &self.axis.scenes[i];
            let b = self.get(&p.sensitivity_point(s, d, w, best, PolicySpec::Baseline))?;
            let x = self.get(&p.sensitivity_point(s, d, w, k, pol))?;
            Some(speedup(b, x))
        }))
    }

    /// The best baseline warp count of width `w`: the highest mean speedup
    /// over games (each scene against its own baseline at the first count),
    /// with the range measured, so that a best count at the edge of the
    /// range is never reported as an optimum.
    pub fn best_warps(&self, d: Dispatch, w: &Width) -> Option<BestWarps> {
        let p = self.plan;
        let first = *p.warps.first()?;
        let best = p
            .warps
            .iter()
            .filter_map(|&k| {
                self.sensitivity_speedup(d, w, k, PolicySpec::Baseline, first)
                    .map(|v| (k, v))
            })
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(k, _)| k)?;
        Some(BestWarps {
            warps: best,
            lowest: first,
            highest: *p.warps.iter().max()?,
        })
    }

    /// The warp count the sensitivity figure is relative to: the paper's
    /// optimum of the width (so that the paper's marks compare like with
    /// like), else our best.
    pub fn reference_warps(&self, d: Dispatch, w: &Width) -> Option<u32> {
        if self.plan.warps.contains(&w.paper_best_warps) {
            Some(w.paper_best_warps)
        } else {
            self.best_warps(d, w).map(|b| b.warps)
        }
    }

    /// Sensitivity: speedup of the baseline and WaSP at each warp count
    /// over the baseline at the paper's optimum count of the width (Figure
    /// 8), mean over games.
    pub fn sensitivity(&self, d: Dispatch, w: &Width) -> Option<Figure> {
        let p = self.plan;
        let best = self.best_warps(d, w)?;
        let reference = self.reference_warps(d, w)?;
        let rel = |k: u32, pol: PolicySpec| self.sensitivity_speedup(d, w, k, pol, reference);
        let x: Vec<f64> = p.warps.iter().map(|&k| f64::from(k)).collect();
        let series = vec![
            SeriesData {
                key: Key::Baseline,
                name: "baseline".into(),
                values: p
                    .warps
                    .iter()
                    .map(|&k| rel(k, PolicySpec::Baseline))
                    .collect(),
            },
            SeriesData {
                key: p.wasp.into(),
                name: p.wasp.to_string(),
                values: p.warps.iter().map(|&k| rel(k, p.wasp)).collect(),
            },
        ];
        let at = |k: u32| p.warps.iter().position(|&x| x == k);
        let mut marks = Vec::new();
        if w.width == 2 {
            if let Some(i) = at(32) {
                marks.push(PaperValue {
                    series: Some(1),
                    category: Some(i),
                    value: paper::WIDTH2_WASP32_OVER_BEST.value,
                    label: "WaSP@32 matches the baseline@48".into(),
                });
            }
            if let Some(i) = at(paper::WIDTH2_BEST_WARPS) {
                marks.push(PaperValue {
                    series: Some(1),
                    category: Some(i),
                    value: paper::WIDTH2_WASP_GAIN.value,
                    label: "WaSP about +2% at 48".into(),
                });
            }
        } else if w.width == 4 {
            if let Some(i) = at(64) {
                marks.push(PaperValue {
                    series: Some(1),
                    category: Some(i),
                    value: paper::WIDTH4_WASP_GAIN.value,
                    label: "WaSP +4% at 64".into(),
                });
            }
            if let Some(i) = at(48) {
                marks.push(PaperValue {
                    series: Some(1),
                    category: Some(i),
                    value: paper::WIDTH4_WASP48_OVER_BEST.value,
                    label: "WaSP@48 +2% over the baseline@64".into(),
                });
            }
        }
        Some(Figure {
            id: format!("sensitivity-width{}.{d}", w.width),
            title: format!("Sensitivity at pipeline width {}", w.width),
            subtitle: format!(
                "{d} machine, mean over games, over the baseline at {reference} warps (the \
                 paper's optimum); our baseline: {}",
                best.describe()
            ),
            y_label: format!("speedup over the baseline at {reference} warps"),
            kind: Kind::Lines {
                x,
                x_label: "warp slots per core".into(),
            },
            categories: p.warps.iter().map(|k| k.to_string()).collect(),
            series,
            paper: marks,
            percent: true,
            signed: true,
            reference: Some(0.0),
            separators: Vec::new(),
            highlight: Vec::new(),
            groups: Vec::new(),
            caption: format!(
                "Width {} ({}): every warp count runs the same machine with `core.max_warps` \
                 and `core.input_queue` set to it.",
                w.width, w.config
            ),
        })
    }
}
