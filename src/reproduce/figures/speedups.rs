//! The speedup figures of one machine over the scanline baseline: ideal
//! memory (Figure 1), the heuristics (Figure 9), WaSP's threshold, the Mesh
//! subsets (Figure 16) and a faster Early-Z.

use super::axis::mean;
use super::figure::{Figure, Kind, SeriesData};
use super::numbers::{size_ratio, speedup};
use super::Figures;
use crate::palette::Key;
use crate::reproduce::paper;
use crate::reproduce::plan::Group;
use wasp_rtl::policy::PolicySpec;
use wasp_sim::config::Dispatch;

impl Figures<'_> {
    /// The speedup of ideal zero-latency main memory (Figure 1).
    pub fn motivation(&self, d: Dispatch) -> Figure {
        let p = self.plan;
        let mut f = self.bars(
            format!("motivation.{d}"),
            "Speedup with ideal (zero-latency) main memory",
            format!("{d} machine, scanline baseline"),
            "speedup over the baseline",
        );
        f.series.push(SeriesData {
            key: Key::Other,
            name: "ideal memory".into(),
            values: self.pair(
                |s| p.policy_point(s, d, PolicySpec::Baseline),
                |s| p.ideal_point(s, d),
                |b, x| Some(speedup(b, x)),
            ),
        });
        f.caption = "The headroom a perfect memory would give: the paper's Figure 1 (bars only, \
                     no number in its text)."
            .into();
        f
    }

    /// Speedup of each heuristic over the scanline baseline (Figure 9).
    pub fn heuristics(&self, d: Dispatch) -> Figure {
        let p = self.plan;
        let mut f = self.bars(
            format!("speedup.{d}"),
            "Speedup of the heuristics over the scanline baseline",
            format!("{d} machine, Mesh4, width 4, 64 warps"),
            "speedup over the baseline",
        );
        for &pol in p.policies.iter().skip(1) {
            f.series.push(SeriesData {
                key: pol.into(),
                name: pol.to_string(),
                values: self.pair(
                    |s| p.policy_point(s, d, PolicySpec::Baseline),
                    |s| p.policy_point(s, d, pol),
                    |b, x| Some(speedup(b, x)),
                ),
            });
        }
        let idx = |pol: PolicySpec| p.policies.iter().skip(1).position(|&x| x == pol);
        if let Some(i) = idx(PolicySpec::FullPriority) {
            f.paper
                .push(self.paper_line(Some(i), paper::FULLPRIORITY_SPEEDUP, "Fullpriority"));
        }
        if let Some(i) = idx(p.wasp) {
            f.paper
                .push(self.paper_line(Some(i), paper::WASP_SPEEDUP, "WaSP"));
        }
        f.caption = format!(
            "Fullpriority, Freemshr10, WaSP ({}) and the measured-CF variant (beyond the paper) \
             against the scanline baseline; dashed lines are the paper's means.",
            p.wasp
        );
        f
    }

    /// Suite-mean speedup of WaSP over the baseline for each threshold.
    pub fn thresholds(&self, d: Dispatch) -> Figure {
        let p = self.plan;
        let x: Vec<f64> = p.thresholds.iter().map(|&t| f64::from(t)).collect();
        let mut series = Vec::new();
        for ((label, idx), &key) in self.axis.means.iter().zip(&self.axis.mean_keys) {
            let values = p
                .thresholds
                .iter()
                .map(|&t| {
                    let v = self.pair(
                        |s| p.policy_point(s, d, PolicySpec::Baseline),
                        |s| p.threshold_point(s, d, t),
                        |b, x| Some(speedup(b, x)),
                    );
                    mean(idx.iter().filter_map(|&i| v[i]))
                })
                .collect();
            series.push(SeriesData {
                key,
                name: label.clone(),
                values,
            });
        }
        let chosen = match p.wasp {
            PolicySpec::Wasp { threshold, cf } => format!("threshold {threshold} at CF {cf}"),
            other => other.to_string(),
        };
        Figure {
            id: format!("thresholds.{d}"),
            title: "WaSP's threshold: mean speedup over the baseline".into(),
            subtitle: format!("{d} machine; shipped: {chosen}, chosen once for the whole suite"),
            y_label: "mean speedup over the baseline".into(),
            kind: Kind::Lines {
                x: x.clone(),
                x_label: "threshold (Real_freeMSHRs > threshold launches a priority warp)".into(),
            },
            categories: p.thresholds.iter().map(|t| t.to_string()).collect(),
            series,
            paper: Vec::new(),
            percent: true,
            signed: true,
            reference: Some(0.0),
            separators: Vec::new(),
            highlight: Vec::new(),
            groups: Vec::new(),
            caption: format!(
                "How the threshold was chosen: the shipped {chosen} is the best suite geomean of \
                 the calibration sweep (docs/calibration.md), one value for every scene. The \
                 paper tunes it too (\"We vary some parameters in the scheduling heuristic to \
                 explain how we fine tuned the parameters\") without giving the value."
            ),
        }
    }

    /// Speedup of WaSP with each Mesh size (Figure 16).
    pub fn mesh_speedup(&self, d: Dispatch) -> Figure {
        let p = self.plan;
        let mut f = self.bars(
            format!("mesh-speedup.{d}"),
            "Speedup of WaSP with each Mesh subset",
            format!("{d} machine, {} over the baseline", p.wasp),
            "speedup over the baseline",
        );
        for &m in &p.meshes {
            f.series.push(SeriesData {
                key: Key::Other,
                name: format!("Mesh{m} (size ratio {})", size_ratio(m)),
                values: self.pair(
                    |s| p.policy_point(s, d, PolicySpec::Baseline),
                    |s| p.mesh_point(s, d, m),
                    |b, x| Some(speedup(b, x)),
                ),
            });
        }
        f.caption = "The paper: Mesh4 \"emerges as the most optimal choice\"; Mesh2's larger \
                     subset hurts locality, Mesh8 and Mesh16 cover too little."
            .into();
        f
    }

    /// WaSP's speedup when a coarse Early-Z disposes of several rejected
    /// quads a raster slot (beyond the paper: does the raster rate explain
    /// the result?).
    pub fn early_z(&self, d: Dispatch) -> Figure {
        let p = self.plan;
        let mut f = self.bars(
            format!("early-z.{d}"),
            "WaSP's speedup under a faster Early-Z",
            format!(
                "{d} machine, {} over the baseline of the same machine",
                p.wasp
            ),
            "speedup over the baseline",
        );
        for k in std::iter::once(1).chain(p.early_z.iter().copied()) {
            let name = if k == 1 {
                "1 rejected quad a slot (shipped)".to_string()
            } else {
                format!("{k} rejected quads a slot")
            };
            f.series.push(SeriesData {
                key: Key::Other,
                name,
                values: self.pair(
                    |s| p.early_z_point(s, d, k, PolicySpec::Baseline),
                    |s| p.early_z_point(s, d, k, p.wasp),
                    |b, x| Some(speedup(b, x)),
                ),
            });
        }
        f.caption = "`raster.rejected_per_slot`: each Early-Z-rejected quad costs a raster slot \
                     on the shipped machine, as the paper's pipeline order reads; a coarse \
                     (hierarchical) depth test would reject several at once. The paper gives no \
                     rate."
            .into();
        f
    }

    /// The baseline's speedup from a faster Early-Z (k rejected quads a
    /// slot over the shipped 1), mean over the scenes of `g`.
    pub fn early_z_gain(&self, d: Dispatch, k: u32, g: Group) -> Option<f64> {
        let p = self.plan;
        mean(
            self.axis
                .scenes
                .iter()
                .zip(&self.axis.groups)
                .filter(|(_, x)| **x == g)
                .filter_map(|(s, _)| {
                    let one = self.get(&p.early_z_point(s, d, 1, PolicySpec::Baseline))?;
                    let fast = self.get(&p.early_z_point(s, d, k, PolicySpec::Baseline))?;
                    Some(speedup(one, fast))
                }),
        )
    }
}
