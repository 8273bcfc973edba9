//! REPORT.md's "Why the numbers differ": a bullet for each of the paper's
//! claims, with the instruments that explain our number, measured on the
//! first machine of the run.
//!
//! Every comparison is worded from the numbers of the run (through
//! [`super::prose`]): a bullet says whether ours go the paper's way or
//! not, and draws a conclusion only when the data supports it.

mod memory;
mod sensitivity;
mod speed;
mod workload;

use super::figures::mean;
use super::figures::Figures;
use super::headline::{group_values, series_index};
use super::plan::{Group, Plan};
use crate::study::cache::PointRecord;
use crate::study::point::Point;
use crate::study::runner::Outcome;
use memory::{energy_note, fullpriority_note, latency_note, misses_note};
use sensitivity::sensitivity_note;
use speed::{early_z_note, group_note, other_machine_note, speedup_note};
use std::fmt::Write as _;
use wasp_rtl::policy::PolicySpec;
use wasp_sim::config::{Dispatch, MachineConfig};
use workload::{cf_note, footprint_note};

/// A statistic of a point record.
type Stat<'a> = &'a dyn Fn(&PointRecord) -> Option<f64>;

/// What the bullets of one machine read from.
struct Notes<'a> {
    plan: &'a Plan,
    out: &'a Outcome,
    figures: &'a Figures<'a>,
    machine: Dispatch,
}

impl Notes<'_> {
    fn base(&self, s: &str) -> Point {
        self.plan
            .policy_point(s, self.machine, PolicySpec::Baseline)
    }

    fn wasp(&self, s: &str) -> Point {
        self.plan.policy_point(s, self.machine, self.plan.wasp)
    }

    /// Mean of a statistic over the scenes of a group for one point kind.
    fn group_stat(&self, group: Group, point: &dyn Fn(&str) -> Point, f: Stat) -> Option<f64> {
        mean(
            self.figures
                .axis
                .scenes
                .iter()
                .zip(&self.figures.axis.groups)
                .filter(|(_, g)| **g == group)
                .filter_map(|(s, _)| self.figures.out.get(&point(s)).and_then(f)),
        )
    }

    /// The mean of the 3D and 2D means of a statistic.
    fn games_stat(&self, point: &dyn Fn(&str) -> Point, f: Stat) -> Option<f64> {
        let v: Vec<f64> = [Group::ThreeD, Group::TwoD]
            .iter()
            .filter_map(|&g| self.group_stat(g, point, f))
            .collect();
        mean(v.into_iter())
    }

    /// WaSP's speedup over the baseline: games, 3D, 2D, procedural.
    fn wasp_gain(&self) -> [Option<f64>; 4] {
        let heuristics = self.figures.heuristics(self.machine);
        group_values(
            &heuristics,
            series_index(&heuristics, &self.plan.wasp.to_string()),
        )
    }
}

/// The rasterizer's share of cycles busy: the quads it produced (Early-Z
/// rejected ones included) over quads_per_cycle x cycles.
fn raster_busy(r: &PointRecord) -> Option<f64> {
    let q = r.stats.raster.quads_rasterized as f64;
    let qpc = f64::from(MachineConfig::paper().raster.quads_per_cycle);
    Some(q / (qpc * r.cycles()))
}

/// The share of the quads rasterized that Early-Z rejected.
fn rejected_share(r: &PointRecord) -> Option<f64> {
    let raster = &r.stats.raster;
    let (x, y) = (raster.quads_rejected as f64, raster.quads_rasterized as f64);
    (y > 0.0).then(|| x / y)
}

/// The share of the cycles a full core queue held the rasterizer back.
fn backpressure(r: &PointRecord) -> Option<f64> {
    Some(r.stats.raster.backpressure_cycles as f64 / r.cycles())
}

fn occupancy(r: &PointRecord) -> Option<f64> {
    Some(r.stats.occupancy.mean)
}

fn lead(r: &PointRecord) -> Option<f64> {
    Some(r.stats.priority_lead.mean)
}

fn gate_closed(r: &PointRecord) -> Option<f64> {
    Some(r.stats.gate.closed_share)
}

fn l0_stalled(r: &PointRecord) -> Option<f64> {
    Some(r.stats.l0.as_ref()?.stall_fraction)
}

/// The section: its bullets for the first machine of the run.
pub fn why(md: &mut String, plan: &Plan, out: &Outcome, machines: &[(Dispatch, Figures)]) {
    let _ = writeln!(md, "\n## Why the numbers differ\n");
    let Some((machine, figures)) = machines.first() else {
        return;
    };
    let n = Notes {
        plan,
        out,
        figures,
        machine: *machine,
    };
    let _ = writeln!(
        md,
        "Measured on the first machine of the table ({machine}); the instruments are means over the \
         group's scenes.\n"
    );
    speedup_note(md, &n);
    for g in [Group::ThreeD, Group::TwoD] {
        group_note(md, &n, g);
    }
    early_z_note(md, &n);
    let _ = writeln!(
        md,
        "  The paper reports neither its rasterizer's rate nor its cores' occupancy, nor how \
         far its priority warps run ahead; its memory system's parameters (MSHR counts, \
         DRAMSim2 configuration) are not published in full either: ours are calibrated once \
         for the suite (docs/calibration.md)."
    );
    if let Some((od, ox)) = machines.get(1) {
        other_machine_note(md, &n, *od, ox);
    }
    fullpriority_note(md, &n);
    latency_note(md, &n);
    energy_note(md, &n);
    misses_note(md, &n);
    footprint_note(md, &n);
    cf_note(md, &n);
    super::rgba8::note(md, plan, out);
    for w in &plan.widths {
        sensitivity_note(md, &n, w);
    }
}

#[cfg(test)]
mod tests;
