//! The bullets on WaSP's speedup and what explains it: the speedup against
//! the paper's and the headroom of ideal memory, each group's instruments
//! (occupancy, the rasterizer, the priority warps' lead, the gate, the L0
//! stalls), a faster Early-Z, and the second machine's fuller cores.

use super::{
    backpressure, gate_closed, l0_stalled, lead, occupancy, raster_busy, rejected_share, Notes,
    Stat,
};
use crate::reproduce::figures::Figures;
use crate::reproduce::headline::group_values;
use crate::reproduce::paper;
use crate::reproduce::plan::Group;
use crate::reproduce::prose::{
    faster_or_slower, lead_text, num, pct, relation, share, speedup_against_paper, Relation,
    CHANGE_TOL,
};
use crate::study::point::Point;
use std::fmt::Write as _;
use wasp_rtl::policy::PolicySpec;
use wasp_sim::config::{Dispatch, MachineConfig};

/// WaSP's speedup against the paper's, and against the headroom ideal
/// memory leaves.
pub(super) fn speedup_note(md: &mut String, n: &Notes) {
    let m = n.wasp_gain();
    let motivation = n.figures.motivation(n.machine);
    let ideal = group_values(&motivation, 0);
    let mostly = |g| crate::reproduce::answer::dominance_note(n.figures, &motivation, 0, g);
    let verdict = m[0].map_or("no measurement".into(), |v| {
        speedup_against_paper(v, paper::WASP_SPEEDUP.value)
    });
    let over: Vec<String> = [(1, "3D"), (2, "2D")]
        .iter()
        .filter_map(|&(i, g)| {
            let (w, i) = (m[i]?, ideal[i]?);
            (w > i + CHANGE_TOL).then(|| format!("{g} ({} against {})", pct(Some(w)), pct(Some(i))))
        })
        .collect();
    let headroom = if over.is_empty() {
        format!(
            "WaSP's speedup stays within the headroom memory leaves: ideal memory makes the \
             baseline {}{} on 3D scenes and {}{} on 2D ones.",
            faster_or_slower(ideal[1]),
            mostly(Group::ThreeD),
            faster_or_slower(ideal[2]),
            mostly(Group::TwoD)
        )
    } else {
        format!(
            "WaSP gains more than ideal memory on {} scenes, so part of its gain does not \
             come from hiding memory latency.",
            over.join(" and ")
        )
    };
    let _ = writeln!(
        md,
        "- **WaSP speedup** ({} on games: {} 3D, {} 2D; paper {}): {verdict}. {headroom}",
        pct(m[0]),
        pct(m[1]),
        pct(m[2]),
        pct(Some(paper::WASP_SPEEDUP.value))
    );
}

/// The instruments of one group: occupancy, the rasterizer, the priority
/// warps' lead, the gate and the L0 stalls.
pub(super) fn group_note(md: &mut String, n: &Notes, g: Group) {
    let base = |s: &str| n.base(s);
    let wasp = |s: &str| n.wasp(s);
    let st = |p: &dyn Fn(&str) -> Point, f: Stat| n.group_stat(g, p, f);
    let slots = MachineConfig::paper().core.max_warps;
    let (raster, held) = match n.machine {
        Dispatch::SharedTile => ("the single rasterizer is", "it"),
        Dispatch::PerCoreTile => ("the cores' rasterizers are on average", "them"),
    };
    let _ = writeln!(
        md,
        "  On {} scenes the baseline holds {} of {slots} warps per core; {raster} busy {} of the \
         cycles, {} of the quads are rejected by Early-Z (they cost a raster slot and launch no \
         warp), and a full core queue holds {held} back in {} of the cycles; WaSP's priority warps \
         launch {} their raster order, its gate keeps the waiting priority warp back in {} of \
         the launches where both FIFOs wait; the L0 is stalled {} of the time under the \
         baseline and {} under WaSP.",
        g.label(),
        num(st(&base, &occupancy)),
        share(st(&base, &raster_busy)),
        share(st(&base, &rejected_share)),
        share(st(&base, &backpressure)),
        lead_text(st(&wasp, &lead)),
        share(st(&wasp, &gate_closed)),
        share(st(&base, &l0_stalled)),
        share(st(&wasp, &l0_stalled))
    );
}

/// Whether a faster Early-Z (the last of the plan's rates) moves WaSP's
/// gain or only the scenes' speed.
pub(super) fn early_z_note(md: &mut String, n: &Notes) {
    let Some(&k) = n.plan.early_z.last() else {
        return;
    };
    let (plan, d) = (n.plan, n.machine);
    let early_z = n.figures.early_z(d);
    let (shipped, fast) = (
        group_values(&early_z, 0),
        group_values(&early_z, early_z.series.len() - 1),
    );
    let fast_base = |s: &str| plan.early_z_point(s, d, k, PolicySpec::Baseline);
    let fast_wasp = |s: &str| plan.early_z_point(s, d, k, plan.wasp);
    let base_gain = n.figures.early_z_gain(d, k, Group::ThreeD);
    let moved = match (base_gain, shipped[1], fast[1]) {
        (Some(speed), Some(a), Some(b)) => early_z_reading(
            relation(speed, 0.0, CHANGE_TOL) != Relation::Same,
            relation(b, a, CHANGE_TOL),
        ),
        _ => "there are too few points to say what it moves",
    };
    let _ = writeln!(
        md,
        "  The rasterizer is tested rather than assumed to be the cause: with a coarse \
         Early-Z disposing of {k} rejected quads a slot, the 3D baseline runs {} and holds {} \
         warps per core, and WaSP's speedup is {} on 3D scenes ({} with the shipped rate) and {} \
         on 2D ({}); its priority warps launch {} their raster order. The rate at which Early-Z \
         rejects quads is a wasp choice (`raster.rejected_per_slot`, docs/machine.md): {moved}.",
        faster_or_slower(base_gain),
        num(n.group_stat(Group::ThreeD, &fast_base, &occupancy)),
        pct(fast[1]),
        pct(shipped[1]),
        pct(fast[2]),
        pct(shipped[2]),
        lead_text(n.group_stat(Group::ThreeD, &fast_wasp, &lead))
    );
}

/// What a faster Early-Z does to the 3D scenes: whether it moves their
/// speed (`speed_moved`, the baseline's) and how it moves WaSP's speedup on
/// them (`wasp`: with the faster rate against the shipped one).
fn early_z_reading(speed_moved: bool, wasp: Relation) -> &'static str {
    match (speed_moved, wasp) {
        (true, Relation::Same) => "it moves the 3D scenes' speed, not WaSP's speedup on them",
        (true, Relation::Above) => {
            "it moves the 3D scenes' speed and raises WaSP's speedup on them"
        }
        (true, Relation::Below) => {
            "it moves the 3D scenes' speed and lowers WaSP's speedup on them"
        }
        (false, Relation::Same) => {
            "it moves neither the 3D scenes' speed nor WaSP's speedup on them"
        }
        (false, Relation::Above) => {
            "it barely moves the 3D scenes' speed but raises WaSP's speedup on them"
        }
        (false, Relation::Below) => {
            "it barely moves the 3D scenes' speed but lowers WaSP's speedup on them"
        }
    }
}

/// The second machine: are its cores fuller, and does WaSP gain more there?
pub(super) fn other_machine_note(md: &mut String, n: &Notes, od: Dispatch, ox: &Figures) {
    let other = Notes {
        plan: n.plan,
        out: n.out,
        figures: ox,
        machine: od,
    };
    let occ = |notes: &Notes| notes.games_stat(&|s| notes.base(s), &occupancy);
    let (here, there) = (occ(n), occ(&other));
    let (gain_here, gain_there) = (n.wasp_gain(), other.wasp_gain());
    let reading = match (here, there, gain_here[1], gain_there[1]) {
        (Some(a), Some(b), Some(g1), Some(g2)) if b > a => match relation(g2, g1, CHANGE_TOL) {
            Relation::Above => format!(
                "its fuller cores raise WaSP's 3D speedup ({} against {}): occupancy explains \
                     part of the 3D result",
                pct(Some(g2)),
                pct(Some(g1))
            ),
            _ => format!(
                "its fuller cores do not raise WaSP's 3D speedup ({} against {}): occupancy \
                     does not explain the 3D result",
                pct(Some(g2)),
                pct(Some(g1))
            ),
        },
        (Some(_), Some(_), _, _) => {
            "its cores are not fuller than the first machine's, so it does not test occupancy"
                .into()
        }
        _ => "there are too few points to compare the machines".into(),
    };
    let _ = writeln!(
        md,
        "  On the {od} machine the baseline's cores hold {} warps on average ({} on the {}), and \
         WaSP's speedup is {} on games ({} 3D, {} 2D): {reading}.",
        num(there),
        num(here),
        n.machine,
        pct(gain_there[0]),
        pct(gain_there[1]),
        pct(gain_there[2])
    );
}
