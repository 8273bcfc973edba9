//! The sensitivity bullet of a pipeline width: where the baseline is
//! fastest, what the extra warp slots change, and the paper's claim that
//! WaSP with fewer warps matches the baseline at its optimum.

use super::{backpressure, occupancy, Notes, Stat};
use crate::reproduce::headline::fewer_warps_claim;
use crate::reproduce::paper;
use crate::reproduce::plan::Width;
use crate::reproduce::prose::{num, pct, relation, speedup_against_paper, Relation, CHANGE_TOL};
use std::fmt::Write as _;
use wasp_rtl::policy::PolicySpec;
use wasp_sim::config::Dispatch;

/// The sensitivity bullet of one width: where the baseline is fastest
/// (never an optimum at the edge of the range measured), what the extra
/// warp slots change in the instruments (occupancy, raster back-pressure),
/// and WaSP with fewer warps and at the paper's optimum against the
/// baseline there.
pub(super) fn sensitivity_note(md: &mut String, n: &Notes, w: &Width) {
    let (plan, x, d) = (n.plan, n.figures, n.machine);
    let Some(best) = x.best_warps(d, w) else {
        return;
    };
    let opt = w.paper_best_warps;
    let mut text = format!(
        "- **Sensitivity, width {}** (paper: optimum at {opt} warps): the baseline is {}",
        w.width,
        best.describe()
    );
    if plan.warps.contains(&opt) && best.warps != opt {
        let at_best = x.sensitivity_speedup(d, w, best.warps, PolicySpec::Baseline, opt);
        let _ = write!(
            text,
            "; at {} warps it is {} against {opt} warps",
            best.warps,
            pct(at_best)
        );
    }
    text.push('.');
    if best.lowest < best.highest {
        text.push_str(&slots_reading(n, w, best.lowest, best.highest));
    }
    if plan.warps.contains(&opt) {
        text.push_str(&fewer_warps_reading(n, w));
        let paper_gain = if w.width == 2 {
            paper::WIDTH2_WASP_GAIN
        } else {
            paper::WIDTH4_WASP_GAIN
        };
        let wasp_opt = x.sensitivity_speedup(d, w, opt, plan.wasp, opt);
        let verdict = wasp_opt.map_or("no measurement".into(), |v| {
            speedup_against_paper(v, paper_gain.value)
        });
        let _ = write!(text, " WaSP at {opt} warps: {}, {verdict}.", pct(wasp_opt));
    }
    let _ = writeln!(md, "{text}");
}

/// What the warp slots from `lo` to `hi` change in the baseline's cores
/// and the rasterizer's back-pressure.
fn slots_reading(n: &Notes, w: &Width, lo: u32, hi: u32) -> String {
    let games = |k: u32, f: Stat| {
        let point = |s: &str| {
            n.plan
                .sensitivity_point(s, n.machine, w, k, PolicySpec::Baseline)
        };
        n.games_stat(&point, f)
    };
    let (p_lo, p_hi) = (games(lo, &backpressure), games(hi, &backpressure));
    let reading = match (p_lo, p_hi) {
        (Some(a), Some(b)) => match relation(a, b, 0.02) {
            Relation::Above => {
                ": part of what the extra slots buy is room for quads that the in-order \
                 rasterizer could not otherwise hand out, not only latency hidden"
            }
            Relation::Same => {
                ": the rasterizer is held back about as often at both counts, so the extra \
                 slots act by hiding latency"
            }
            Relation::Below => {
                ": the rasterizer is held back more often with the extra slots, so they do \
                 not act by making room for its quads"
            }
        },
        _ => "",
    };
    let pc = |v: Option<f64>| v.map_or("-".into(), |x| format!("{:.0}%", 100.0 * x));
    let raster = match n.machine {
        Dispatch::SharedTile => "the single rasterizer",
        Dispatch::PerCoreTile => "a core's rasterizer",
    };
    format!(
        " From {lo} to {hi} warps (input queue as deep as the warp slots) the baseline's \
         cores hold {} and {} warps on average, and a full core queue holds {raster} back in \
         {} and {} of the cycles (mean of the 3D and 2D means){reading}.",
        num(games(lo, &occupancy)),
        num(games(hi, &occupancy)),
        pc(p_lo),
        pc(p_hi)
    )
}

/// The paper's register-file claim at a width (WaSP with fewer warps at
/// least matches the baseline at the optimum) against ours.
fn fewer_warps_reading(n: &Notes, w: &Width) -> String {
    let (k, claim) = fewer_warps_claim(w);
    let opt = w.paper_best_warps;
    if !n.plan.warps.contains(&k) {
        return String::new();
    }
    let v = n
        .figures
        .sensitivity_speedup(n.machine, w, k, n.plan.wasp, opt);
    let paper_says = if w.width == 2 {
        format!("the paper: WaSP@{k} matches the baseline@{opt}")
    } else {
        format!(
            "the paper: WaSP@{k} is {} over the baseline@{opt}",
            pct(Some(claim.value))
        )
    };
    let verdict = match v {
        Some(v) if v >= -CHANGE_TOL => format!(
            "it matches or beats it, as the paper reports, so the register file of {} warps \
             that `wasp cost` prices is saved here too",
            opt - k
        ),
        Some(_) => format!(
            "it does not match it, unlike the paper, so the register file of {} warps that \
             `wasp cost` prices as saved is not saved on these scenes",
            opt - k
        ),
        None => "no measurement".into(),
    };
    format!(
        " WaSP at {k} warps against the baseline at {opt}: {} ({paper_says}): {verdict}.",
        pct(v)
    )
}
