//! How the warps of one machine are launched and resident, per policy
//! (beyond the paper): the lead of priority warps and the occupancy.

use super::figure::{Figure, SeriesData};
use super::Figures;
use wasp_sim::config::Dispatch;

impl Figures<'_> {
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
}
