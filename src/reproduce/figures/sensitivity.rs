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
        let marks = paper_marks(w.width, &p.warps);
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

/// The paper's marks on the sensitivity figure of pipeline width `width`
/// (on WaSP's series), at those of its warp counts that `warps` has.
fn paper_marks(width: u32, warps: &[u32]) -> Vec<PaperValue> {
    let marks = match width {
        2 => vec![
            (
                32,
                paper::WIDTH2_WASP32_OVER_BEST.value,
                "WaSP@32 matches the baseline@48",
            ),
            (
                paper::WIDTH2_BEST_WARPS,
                paper::WIDTH2_WASP_GAIN.value,
                "WaSP about +2% at 48",
            ),
        ],
        4 => vec![
            (64, paper::WIDTH4_WASP_GAIN.value, "WaSP +4% at 64"),
            (
                48,
                paper::WIDTH4_WASP48_OVER_BEST.value,
                "WaSP@48 +2% over the baseline@64",
            ),
        ],
        _ => Vec::new(),
    };
    marks
        .into_iter()
        .filter_map(|(k, value, label)| {
            Some(PaperValue {
                series: Some(1),
                category: Some(warps.iter().position(|&x| x == k)?),
                value,
                label: label.into(),
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_paper_marks_sit_on_the_warp_counts_run() {
        let at = |width, warps: &[u32]| {
            paper_marks(width, warps)
                .into_iter()
                .map(|m| (m.series, m.category, m.label))
                .collect::<Vec<_>>()
        };
        assert_eq!(
            at(2, &[16, 32, 48, 64]),
            [
                (Some(1), Some(1), "WaSP@32 matches the baseline@48".into()),
                (Some(1), Some(2), "WaSP about +2% at 48".into()),
            ]
        );
        assert_eq!(
            at(4, &[32, 48, 64]),
            [
                (Some(1), Some(2), "WaSP +4% at 64".into()),
                (Some(1), Some(1), "WaSP@48 +2% over the baseline@64".into()),
            ]
        );
        assert_eq!(at(4, &[32, 64]).len(), 1, "48 not run: no mark there");
        assert!(at(3, &[32, 48, 64]).is_empty());
        assert_eq!(
            paper_marks(2, &[32])[0].value,
            paper::WIDTH2_WASP32_OVER_BEST.value
        );
    }
}
