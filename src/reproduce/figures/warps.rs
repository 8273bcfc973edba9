//! How the warps of one machine are launched and resident, per policy
//! (beyond the paper): the lead of priority warps and the occupancy.

use super::figure::{Figure, SeriesData};
use super::Figures;
use wasp_sim::config::Dispatch;

impl Figures<'_> {
    /// Lead of priority warps per policy (beyond the paper).
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
                key: pol.into(),
                name: pol.to_string(),
                values: self.single(
                    |s| p.policy_point(s, d, pol),
                    |r| Some(r.stats.priority_lead.mean),
                ),
            });
        }
        f.caption = "How far ahead of their raster order the priority warps launch (positive: \
                     earlier). The paper assumes they lead; this measures it."
            .into();
        f
    }

    /// Mean resident warps per core, per policy (beyond the paper).
    pub fn occupancy(&self, d: Dispatch) -> Figure {
        let p = self.plan;
        // The machine's warp slots, as its runs report them.
        let slots = self
            .single(
                |s| p.policy_point(s, d, p.policies[0]),
                |r| Some(f64::from(r.stats.occupancy.max_warps)),
            )
            .into_iter()
            .flatten()
            .next()
            .map_or("?".to_string(), |n| n.to_string());
        let mut f = self.bars(
            format!("occupancy.{d}"),
            "Mean warps resident per core",
            format!("{d} machine, of {slots} warp slots"),
            "warps",
        );
        f.percent = false;
        f.reference = None;
        for &pol in &p.policies {
            f.series.push(SeriesData {
                key: pol.into(),
                name: pol.to_string(),
                values: self.single(
                    |s| p.policy_point(s, d, pol),
                    |r| Some(r.stats.occupancy.mean),
                ),
            });
        }
        f.caption = format!(
            "Cores sit below their {slots} slots while a tile fills and drains; the \
             timelines below show it cycle by cycle."
        );
        f
    }
}
