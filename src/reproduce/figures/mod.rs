//! The numbers of each figure of the reproduction, from a run's results:
//! per scene (3D games, then 2D games, then procedural scenes) and the
//! group means, with the paper's value where it states one.
//!
//! A figure here is data only; [`super::report`] draws it and writes it as
//! CSV. Speedups are `baseline cycles / cycles - 1`; changes are
//! `x / base - 1`; means are arithmetic means over the group's scenes,
//! "games" being the 3D and 2D scenes together (the paper's suite is games
//! only).

use super::paper::{self, Claim};
use super::plan::{Group, Plan};
use crate::study::cache::PointRecord;
use crate::study::point::Point;
use crate::study::runner::Outcome;
use wasp_rtl::policy::PolicySpec;
use wasp_sim::config::Dispatch;

/// A series: a value per category.
#[derive(Clone, Debug, PartialEq)]
pub struct SeriesData {
    /// Legend name.
    pub name: String,
    /// Values (None: missing).
    pub values: Vec<Option<f64>>,
}

/// A paper value drawn beside ours.
#[derive(Clone, Debug, PartialEq)]
pub struct PaperValue {
    /// The series it belongs to (None: the whole figure).
    pub series: Option<usize>,
    /// The category (or x index) it applies to (None: all).
    pub category: Option<usize>,
    /// The value.
    pub value: f64,
    /// Label.
    pub label: String,
}

/// Bars over categories, or lines over x.
#[derive(Clone, Debug, PartialEq)]
pub enum Kind {
    /// Grouped bars, one group per category.
    Bars,
    /// Lines over numeric x (the categories are the tick labels).
    Lines {
        /// x of each category.
        x: Vec<f64>,
        /// x axis label.
        x_label: String,
    },
}

/// One figure's data.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    /// File stem (`speedup.shared-tile`).
    pub id: String,
    /// Title.
    pub title: String,
    /// One line under the title.
    pub subtitle: String,
    /// y axis label.
    pub y_label: String,
    /// Bars or lines.
    pub kind: Kind,
    /// Categories (scenes then means) or x tick labels.
    pub categories: Vec<String>,
    /// Series.
    pub series: Vec<SeriesData>,
    /// The paper's values.
    pub paper: Vec<PaperValue>,
    /// Values are fractions shown as percent.
    pub percent: bool,
    /// A reference line.
    pub reference: Option<f64>,
    /// Category indices before which a separator is drawn.
    pub separators: Vec<usize>,
    /// Categories drawn emphasised (the means).
    pub highlight: Vec<usize>,
    /// What the figure shows, for the report.
    pub caption: String,
}

/// The scenes in figure order and the mean columns after them.
pub struct Axis {
    /// Scene names in order (3D, 2D, procedural; by name within).
    pub scenes: Vec<String>,
    /// Each scene's group.
    pub groups: Vec<Group>,
    /// The mean columns: label and the scene indices it averages.
    pub means: Vec<(String, Vec<usize>)>,
}

impl Axis {
    /// The axis of a plan.
    pub fn new(plan: &Plan) -> Axis {
        let mut s: Vec<(Group, String)> = plan
            .scenes
            .iter()
            .map(|x| (x.group, x.name.clone()))
            .collect();
        s.sort();
        let groups: Vec<Group> = s.iter().map(|x| x.0).collect();
        let idx = |f: &dyn Fn(Group) -> bool| -> Vec<usize> {
            (0..groups.len()).filter(|&i| f(groups[i])).collect()
        };
        let mut means = Vec::new();
        let games = idx(&|g| g != Group::Procedural);
        for (label, v) in [
            ("mean 3D", idx(&|g| g == Group::ThreeD)),
            ("mean 2D", idx(&|g| g == Group::TwoD)),
            ("mean games", games),
            ("mean procedural", idx(&|g| g == Group::Procedural)),
        ] {
            if !v.is_empty() {
                means.push((label.to_string(), v));
            }
        }
        Axis {
            scenes: s.into_iter().map(|x| x.1).collect(),
            groups,
            means,
        }
    }

    /// Scene names, then mean labels.
    pub fn categories(&self) -> Vec<String> {
        let mut c = self.scenes.clone();
        c.extend(self.means.iter().map(|m| m.0.clone()));
        c
    }

    /// Per-scene values extended with the means (a mean skips missing
    /// scenes; None if all are missing).
    pub fn with_means(&self, v: Vec<Option<f64>>) -> Vec<Option<f64>> {
        let mut out = v.clone();
        for (_, idx) in &self.means {
            out.push(mean(idx.iter().filter_map(|&i| v[i])));
        }
        out
    }

    /// The mean columns' separator and highlight.
    fn marks(&self) -> (Vec<usize>, Vec<usize>) {
        let n = self.scenes.len();
        let mut sep: Vec<usize> = Vec::new();
        for i in 1..n {
            if self.groups[i] != self.groups[i - 1] {
                sep.push(i);
            }
        }
        sep.push(n);
        (sep, (n..n + self.means.len()).collect())
    }
}

/// Arithmetic mean (None for no values).
pub fn mean(v: impl Iterator<Item = f64>) -> Option<f64> {
    let (s, n) = v.fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
    (n > 0).then(|| s / n as f64)
}

/// `base cycles / x cycles - 1`.
pub fn speedup(base: &PointRecord, x: &PointRecord) -> f64 {
    base.cycles() / x.cycles() - 1.0
}

/// `x / base - 1` of a statistic.
pub fn change(base: &PointRecord, x: &PointRecord, path: &str) -> Option<f64> {
    let (b, v) = (base.get(path)?, x.get(path)?);
    (b != 0.0).then(|| v / b - 1.0)
}

/// Builds the figures of one machine from the results.
pub struct Figures<'a> {
    /// The plan.
    pub plan: &'a Plan,
    /// The results.
    pub out: &'a Outcome,
    /// The axis.
    pub axis: Axis,
}

fn fmt_claim(v: f64) -> String {
    format!("{:+.1}%", 100.0 * v)
}

fn pct(v: f64) -> String {
    format!("{:+.1}%", 100.0 * v)
}

impl<'a> Figures<'a> {
    /// Figures of `plan` from `out`.
    pub fn new(plan: &'a Plan, out: &'a Outcome) -> Self {
        Figures {
            plan,
            out,
            axis: Axis::new(plan),
        }
    }

    fn get(&self, p: &Point) -> Option<&PointRecord> {
        self.out.get(p)
    }

    /// Per scene: f(record of a(scene), record of b(scene)).
    fn pair(
        &self,
        a: impl Fn(&str) -> Point,
        b: impl Fn(&str) -> Point,
        f: impl Fn(&PointRecord, &PointRecord) -> Option<f64>,
    ) -> Vec<Option<f64>> {
        let v = self
            .axis
            .scenes
            .iter()
            .map(|s| match (self.get(&a(s)), self.get(&b(s))) {
                (Some(x), Some(y)) => f(x, y),
                _ => None,
            })
            .collect();
        self.axis.with_means(v)
    }

    /// Per scene: f(record of a(scene)).
    fn single(
        &self,
        a: impl Fn(&str) -> Point,
        f: impl Fn(&PointRecord) -> Option<f64>,
    ) -> Vec<Option<f64>> {
        let v = self
            .axis
            .scenes
            .iter()
            .map(|s| self.get(&a(s)).and_then(&f))
            .collect();
        self.axis.with_means(v)
    }

    fn bars(&self, id: String, title: &str, subtitle: String, y_label: &str) -> Figure {
        let (separators, highlight) = self.axis.marks();
        Figure {
            id,
            title: title.to_string(),
            subtitle,
            y_label: y_label.to_string(),
            kind: Kind::Bars,
            categories: self.axis.categories(),
            series: Vec::new(),
            paper: Vec::new(),
            percent: true,
            reference: Some(0.0),
            separators,
            highlight,
            caption: String::new(),
        }
    }

    fn paper_line(&self, series: Option<usize>, c: Claim, what: &str) -> PaperValue {
        PaperValue {
            series,
            category: None,
            value: c.value,
            label: format!("{what} {} ({})", fmt_claim(c.value), c.source),
        }
    }

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
        for (label, idx) in &self.axis.means {
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
            reference: Some(0.0),
            separators: Vec::new(),
            highlight: Vec::new(),
            caption: format!(
                "How the threshold was chosen: the shipped {chosen} is the best suite geomean of \
                 the calibration sweep (docs/calibration.md), one value for every scene. The \
                 paper tunes it too (\"We vary some parameters in the scheduling heuristic to \
                 explain how we fine tuned the parameters\") without giving the value."
            ),
        }
    }

    /// Percentage of time the L0 is stalled (Figure 10).
    pub fn l0_stall(&self, d: Dispatch) -> Figure {
        let p = self.plan;
        let mut f = self.bars(
            format!("l0-stall.{d}"),
            "Share of time the L0 is stalled",
            format!("{d} machine, mean over cores"),
            "L0 stalled",
        );
        f.reference = None;
        for pol in [
            PolicySpec::Baseline,
            PolicySpec::FullPriority,
            PolicySpec::FreeMshr(10),
            p.wasp,
        ] {
            f.series.push(SeriesData {
                name: pol.to_string(),
                values: self.single(
                    |s| p.policy_point(s, d, pol),
                    |r| r.get("l0.stall_fraction"),
                ),
            });
        }
        f.caption = "Cycles in which the L0 refuses accesses for want of an MSHR, over all \
                     cycles: the stalls Fullpriority adds and WaSP's gate avoids (Figure 10)."
            .into();
        f
    }

    /// Change of L1 and L2 misses under WaSP (Figure 12).
    pub fn misses(&self, d: Dispatch) -> Figure {
        let p = self.plan;
        let mut f = self.bars(
            format!("misses.{d}"),
            "Change in L1 and L2 misses under WaSP",
            format!("{d} machine, {} over the baseline", p.wasp),
            "change in misses",
        );
        for (name, path) in [("L1 misses", "l1.misses"), ("L2 misses", "l2.misses")] {
            f.series.push(SeriesData {
                name: name.into(),
                values: self.pair(
                    |s| p.policy_point(s, d, PolicySpec::Baseline),
                    |s| p.policy_point(s, d, p.wasp),
                    |b, x| change(b, x, path),
                ),
            });
        }
        f.paper
            .push(self.paper_line(None, paper::MISS_CHANGE, "unchanged"));
        f.caption = "WaSP reorders warps inside a tile; the tile's working set fits the L1 and \
                     L2, so the paper sees no change in their misses."
            .into();
        f
    }

    /// Average memory latency: all warps, priority and regular (Figure 13).
    pub fn latency(&self, d: Dispatch) -> Figure {
        let p = self.plan;
        let mut f = self.bars(
            format!("latency.{d}"),
            "Average memory latency of warps",
            format!("{d} machine"),
            "cycles",
        );
        f.percent = false;
        f.reference = None;
        let base = |s: &str| p.policy_point(s, d, PolicySpec::Baseline);
        let wasp = |s: &str| p.policy_point(s, d, p.wasp);
        for (name, point, path) in [
            (
                "baseline, all",
                &base as &dyn Fn(&str) -> Point,
                "memory_latency.all",
            ),
            ("WaSP, all", &wasp, "memory_latency.all"),
            ("WaSP, priority warps", &wasp, "memory_latency.priority"),
            ("WaSP, regular warps", &wasp, "memory_latency.regular"),
        ] {
            f.series.push(SeriesData {
                name: name.into(),
                values: self.single(point, |r| r.get(path)),
            });
        }
        f.caption = "Mean cycles a warp's texture accesses wait for memory. The paper: \"The \
                     average memory latency for priority warps notably exceeds that of regular \
                     warps\"."
            .into();
        f
    }

    /// Change in average memory latency under WaSP (Figure 13, -9%).
    pub fn latency_change(&self, d: Dispatch) -> Figure {
        let p = self.plan;
        let mut f = self.bars(
            format!("latency-change.{d}"),
            "Change in average memory latency under WaSP",
            format!("{d} machine, {} over the baseline", p.wasp),
            "change in latency",
        );
        f.series.push(SeriesData {
            name: "memory latency".into(),
            values: self.pair(
                |s| p.policy_point(s, d, PolicySpec::Baseline),
                |s| p.policy_point(s, d, p.wasp),
                |b, x| change(b, x, "memory_latency.all"),
            ),
        });
        f.paper
            .push(self.paper_line(Some(0), paper::LATENCY_CHANGE, "mean"));
        f.caption = "The prefetching effect WaSP is built for: regular warps find their blocks \
                     already requested."
            .into();
        f
    }

    /// Change in total energy under WaSP (Figure 14).
    pub fn energy(&self, d: Dispatch) -> Figure {
        let p = self.plan;
        let mut f = self.bars(
            format!("energy.{d}"),
            "Change in total GPU energy under WaSP",
            format!("{d} machine, {} over the baseline", p.wasp),
            "change in energy",
        );
        f.series.push(SeriesData {
            name: "energy".into(),
            values: self.pair(
                |s| p.policy_point(s, d, PolicySpec::Baseline),
                |s| p.policy_point(s, d, p.wasp),
                |b, x| change(b, x, "energy.total_nj"),
            ),
        });
        f.paper
            .push(self.paper_line(Some(0), paper::ENERGY_CHANGE, "mean"));
        f.caption = "Dynamic energy of instructions, caches and DRAM plus static energy over the \
                     run (docs/model.md)."
            .into();
        f
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

    /// Lead of priority warps and occupancy per policy (beyond the paper).
    pub fn lead(&self, d: Dispatch) -> Figure {
        let p = self.plan;
        let mut f = self.bars(
            format!("lead.{d}"),
            "Lead of priority warps: raster position minus launch rank",
            format!("{d} machine, mean over priority warps"),
            "warps launched ahead",
        );
        f.percent = false;
        for &pol in p.policies.iter().skip(1) {
            f.series.push(SeriesData {
                name: pol.to_string(),
                values: self.single(
                    |s| p.policy_point(s, d, pol),
                    |r| r.get("priority_lead.mean"),
                ),
            });
        }
        f.caption = "How far ahead of their raster order the priority warps launch (positive: \
                     earlier). The paper assumes they lead; this measures it."
            .into();
        f
    }

    /// Mean resident warps per core, and the fill and drain shares of a
    /// tile, per policy (beyond the paper).
    pub fn occupancy(&self, d: Dispatch) -> Figure {
        let p = self.plan;
        let mut f = self.bars(
            format!("occupancy.{d}"),
            "Mean warps resident per core",
            format!("{d} machine, of {} warp slots", 64),
            "warps",
        );
        f.percent = false;
        f.reference = None;
        for &pol in &p.policies {
            f.series.push(SeriesData {
                name: pol.to_string(),
                values: self.single(|s| p.policy_point(s, d, pol), |r| r.get("occupancy.mean")),
            });
        }
        f.caption = "Cores sit below their 64 slots while a tile fills and drains; the \
                     timelines below show it cycle by cycle."
            .into();
        f
    }

    /// The mean over games of the per-scene speedup of `pol` at `k` warps
    /// over the baseline at `best` warps (width `w`).
    pub fn sensitivity_speedup(
        &self,
        d: Dispatch,
        w: &super::plan::Width,
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
    /// over games (each scene against its own baseline at the first count).
    pub fn best_warps(&self, d: Dispatch, w: &super::plan::Width) -> Option<u32> {
        let p = self.plan;
        let first = *p.warps.first()?;
        p.warps
            .iter()
            .filter_map(|&k| {
                self.sensitivity_speedup(d, w, k, PolicySpec::Baseline, first)
                    .map(|v| (k, v))
            })
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(k, _)| k)
    }

    /// The warp count the sensitivity figure is relative to: the paper's
    /// optimum of the width (so that the paper's marks compare like with
    /// like), else our best.
    pub fn reference_warps(&self, d: Dispatch, w: &super::plan::Width) -> Option<u32> {
        if self.plan.warps.contains(&w.paper_best_warps) {
            Some(w.paper_best_warps)
        } else {
            self.best_warps(d, w)
        }
    }

    /// Sensitivity: speedup of the baseline and WaSP at each warp count
    /// over the baseline at the paper's optimum count of the width (Figure
    /// 8), mean over games.
    pub fn sensitivity(&self, d: Dispatch, w: &super::plan::Width) -> Option<Figure> {
        let p = self.plan;
        let best = self.best_warps(d, w)?;
        let reference = self.reference_warps(d, w)?;
        let rel = |k: u32, pol: PolicySpec| self.sensitivity_speedup(d, w, k, pol, reference);
        let x: Vec<f64> = p.warps.iter().map(|&k| f64::from(k)).collect();
        let series = vec![
            SeriesData {
                name: "baseline".into(),
                values: p
                    .warps
                    .iter()
                    .map(|&k| rel(k, PolicySpec::Baseline))
                    .collect(),
            },
            SeriesData {
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
                 paper's optimum); our best baseline: {best} warps"
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
            reference: Some(0.0),
            separators: Vec::new(),
            highlight: Vec::new(),
            caption: format!(
                "Width {} ({}): every warp count runs the same machine with `core.max_warps` \
                 and `core.input_queue` set to it.",
                w.width, w.config
            ),
        })
    }
}

/// Subset size ratio of MeshN: one quad in N x N.
pub fn size_ratio(n: u32) -> String {
    format!("1/{}", n * n)
}

/// Percent text for tables (`-` for None).
pub fn pct_opt(v: Option<f64>) -> String {
    v.map_or("-".into(), pct)
}

/// The scene characterisation figures (no machine): Min_Estimate1, CF and
/// Min_Estimate2 (Figure 4), and the footprint ratios (Figures 11 and 15).
pub fn scene_figures(plan: &Plan, out: &Outcome) -> Vec<Figure> {
    let axis = Axis::new(plan);
    let (separators, highlight) = axis.marks();
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
        reference: None,
        separators,
        highlight,
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn means_skip_missing_scenes() {
        assert_eq!(mean([1.0, 2.0, 6.0].into_iter()), Some(3.0));
        assert_eq!(mean(std::iter::empty()), None);
        let axis = Axis {
            scenes: vec!["a".into(), "b".into(), "c".into()],
            groups: vec![Group::ThreeD, Group::ThreeD, Group::TwoD],
            means: vec![
                ("mean 3D".into(), vec![0, 1]),
                ("mean games".into(), vec![0, 1, 2]),
            ],
        };
        assert_eq!(
            axis.with_means(vec![Some(1.0), None, Some(3.0)]),
            [Some(1.0), None, Some(3.0), Some(1.0), Some(2.0)]
        );
        let (sep, hi) = axis.marks();
        assert_eq!(sep, [2, 3]);
        assert_eq!(hi, [3, 4]);
    }

    #[test]
    fn speedups_and_changes() {
        let r = |c: u64, l: f64| PointRecord {
            key: String::new(),
            point: Point::new("s", "paper", &[]),
            binary: String::new(),
            stats: serde_json::json!({"cycles": c, "memory_latency": {"all": l}}),
        };
        let (b, x) = (r(110, 100.0), r(100, 91.0));
        assert!((speedup(&b, &x) - 0.1).abs() < 1e-12);
        assert!((change(&b, &x, "memory_latency.all").unwrap() + 0.09).abs() < 1e-12);
        assert_eq!(change(&r(1, 0.0), &x, "memory_latency.all"), None);
        assert_eq!(change(&b, &x, "nothing"), None);
    }
}
