//! What the policies do to the memory system and the energy of one
//! machine: L0 stalls (Figure 10), L1 and L2 misses (Figure 12), memory
//! latency (Figure 13) and energy (Figure 14).

use super::figure::{Figure, SeriesData};
use super::numbers::change;
use super::Figures;
use crate::palette::Key;
use crate::reproduce::paper;
use crate::study::point::Point;
use wasp_rtl::policy::PolicySpec;
use wasp_sim::config::Dispatch;
use wasp_sim::stats::{LatencyStats, RunStats};

impl Figures<'_> {
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
        f.signed = false;
        for pol in [
            PolicySpec::Baseline,
            PolicySpec::FullPriority,
            PolicySpec::FreeMshr(10),
            p.wasp,
        ] {
            f.series.push(SeriesData {
                key: pol.into(),
                name: pol.to_string(),
                values: self.single(
                    |s| p.policy_point(s, d, pol),
                    |r| Some(r.stats.l0.as_ref()?.stall_fraction),
                ),
            });
        }
        f.caption = "Cycles in which the L0 refuses accesses for want of an MSHR, over all \
                     cycles. The paper's Figure 10: Fullpriority adds stalls and WaSP's gate \
                     avoids them (\"Why the numbers differ\" says whether ours do)."
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
        let l1: fn(&RunStats) -> f64 = |s| s.l1.misses as f64;
        let l2: fn(&RunStats) -> f64 = |s| s.l2.misses as f64;
        for (name, stat) in [("L1 misses", l1), ("L2 misses", l2)] {
            f.series.push(SeriesData {
                key: Key::Other,
                name: name.into(),
                values: self.pair(
                    |s| p.policy_point(s, d, PolicySpec::Baseline),
                    |s| p.policy_point(s, d, p.wasp),
                    |b, x| change(b, x, stat),
                ),
            });
        }
        f.paper
            .push(self.paper_line(None, paper::MISS_CHANGE, "unchanged"));
        f.caption = "WaSP reorders warps inside a tile; the paper sees no change in L1 and L2 \
                     misses."
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
        let all: fn(&LatencyStats) -> f64 = |l| l.all;
        let priority: fn(&LatencyStats) -> f64 = |l| l.priority;
        let regular: fn(&LatencyStats) -> f64 = |l| l.regular;
        for (key, name, point, stat) in [
            (
                Key::Baseline,
                "baseline, all",
                &base as &dyn Fn(&str) -> Point,
                all,
            ),
            (Key::Wasp, "WaSP, all", &wasp, all),
            (Key::Wasp, "WaSP, priority warps", &wasp, priority),
            (Key::Wasp, "WaSP, regular warps", &wasp, regular),
        ] {
            f.series.push(SeriesData {
                key,
                name: name.into(),
                values: self.single(point, |r| Some(stat(&r.stats.memory_latency))),
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
            key: Key::Other,
            name: "memory latency".into(),
            values: self.pair(
                |s| p.policy_point(s, d, PolicySpec::Baseline),
                |s| p.policy_point(s, d, p.wasp),
                |b, x| change(b, x, |s| s.memory_latency.all),
            ),
        });
        f.paper
            .push(self.paper_line(Some(0), paper::LATENCY_CHANGE, "mean"));
        f.caption = "What WaSP is built for, in the paper: regular warps find their blocks \
                     already requested by the priority warps, so the mean latency falls."
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
            key: Key::Other,
            name: "energy".into(),
            values: self.pair(
                |s| p.policy_point(s, d, PolicySpec::Baseline),
                |s| p.policy_point(s, d, p.wasp),
                |b, x| change(b, x, |s| s.energy.total_nj),
            ),
        });
        f.paper
            .push(self.paper_line(Some(0), paper::ENERGY_CHANGE, "mean"));
        f.caption = "Dynamic energy of instructions, caches and DRAM plus static energy over the \
                     run (docs/model.md)."
            .into();
        f
    }
}
