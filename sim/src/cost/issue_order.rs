//! The issue orders' hardware (`core.issue`, `gpu/issue/`) for `wasp
//! cost`: what each order keeps between cycles and the logic that turns
//! the ready warps into its visiting order, per core, for `n` warp slots
//! and a pipeline width `W`.
//!
//! - Loose round-robin keeps a pointer: a `ceil(log2 n)`-bit register, its
//!   update (the last pick + 1), and the pick network that starts at it: a
//!   barrel rotator of the n request lines by the pointer, `W` cascaded
//!   find-first chains (one gate per slot and pick) and the rotator back
//!   to slot numbers.
//! - Greedy-then-oldest keeps an age matrix and the greedy set. The age
//!   matrix has one flip-flop per pair of slots (`n (n - 1) / 2`): which of
//!   the two launched first. A launch writes its slot's row and column in
//!   one cycle (every occupied slot is older), and a warp's exit changes
//!   nothing. Its select needs no comparator: a candidate is the oldest
//!   left when no other remaining candidate is older, an AND-OR over the
//!   `n - 1` others per slot, `W` times in cascade. That is why it is the
//!   form costed here, as in the age-ordered issue queues of out-of-order
//!   CPUs. A per-slot launch stamp needs less storage but must either be
//!   wide enough that no resident warp's stamp wraps, or be renumbered at
//!   every exit (a decrementer and a comparator per slot); its select
//!   compares stamps (`n - 1` comparators per pick). The greedy set is one
//!   flip-flop per slot (the grant lines of the last issuing cycle),
//!   whose candidates take their ports before the age select.
//!
//! The pick network is the issue stage's own logic under either order; it
//! is listed with each so that the two totals compare.

use super::{costed, CostedItem};
use crate::config::{IssueOrder, MachineConfig};
use serde::Serialize;
use wasp_rtl::cost::{bits_for, GateRules, Item, Part};

/// The two orders' inventories for one machine.
#[derive(Clone, Debug, Serialize)]
pub struct IssueOrderCost {
    /// The order the machine runs.
    pub configured: IssueOrder,
    /// Warp slots per core.
    pub slots: u32,
    /// Pipeline width (picks a cycle).
    pub width: u32,
    /// Loose round-robin, per core.
    pub lrr: Vec<CostedItem>,
    /// Greedy-then-oldest, per core.
    pub gto: Vec<CostedItem>,
    /// Flip-flops per core: loose round-robin, greedy-then-oldest.
    pub register_bits: [u32; 2],
    /// GE per core: loose round-robin, greedy-then-oldest.
    pub ge: [f64; 2],
    /// Greedy-then-oldest split as GPGPU-Sim's cores are (W schedulers,
    /// each over n / W slots, one pick each): flip-flops and GE per core.
    pub gto_split: (u32, f64),
}

fn item(block: &'static str, purpose: String, part: Part) -> Item {
    Item {
        block,
        purpose,
        part,
    }
}

/// Loose round-robin over `n` slots, `w` picks a cycle.
pub fn lrr_inventory(n: u32, w: u32) -> Vec<Item> {
    let b = bits_for(n.saturating_sub(1));
    vec![
        item(
            "issue_lrr",
            "round-robin pointer: the slot after the last pick".into(),
            Part::Register { bits: b },
        ),
        item(
            "issue_lrr",
            "pointer update: last pick + 1".into(),
            Part::Adder { bits: b },
        ),
        item(
            "issue_lrr",
            format!("rotate the {n} requests by the pointer"),
            Part::Mux2 { bits: n * b },
        ),
        item(
            "issue_lrr",
            format!("{w} cascaded find-first chains over {n} slots"),
            Part::ZeroDetect { bits: w * n },
        ),
        item(
            "issue_lrr",
            "rotate the grants back to slot numbers".into(),
            Part::Mux2 { bits: n * b },
        ),
    ]
}

/// Greedy-then-oldest over `n` slots, `w` picks a cycle.
pub fn gto_inventory(n: u32, w: u32) -> Vec<Item> {
    let pairs = n * n.saturating_sub(1) / 2;
    vec![
        item(
            "issue_gto",
            format!("age matrix: {n}x{}/2 pairs, which launched first", n - 1),
            Part::Register { bits: pairs },
        ),
        item(
            "issue_gto",
            "launch: write the new slot's row and column".into(),
            Part::Mux2 { bits: pairs },
        ),
        item(
            "issue_gto",
            "greedy set: grants of the last issuing cycle".into(),
            Part::Register { bits: n },
        ),
        item(
            "issue_gto",
            "greedy candidates granted ahead of the age select".into(),
            Part::Mux2 { bits: n },
        ),
        item(
            "issue_gto",
            format!("{w} age selects: no older candidate ({n}x{} in)", n - 1),
            Part::ZeroDetect {
                bits: w * n * n.saturating_sub(1),
            },
        ),
    ]
}

fn totals(items: &[CostedItem]) -> (u32, f64) {
    (
        items.iter().map(|c| c.register_bits).sum(),
        items.iter().map(|c| c.ge).sum(),
    )
}

/// Both orders' inventories for `cfg`'s core (`core.max_warps` slots,
/// `core.pipeline_width` picks).
pub fn issue_order_cost(cfg: &MachineConfig, rules: &GateRules) -> IssueOrderCost {
    let (n, w) = (cfg.core.max_warps, cfg.core.pipeline_width);
    let lrr = costed(lrr_inventory(n, w), rules);
    let gto = costed(gto_inventory(n, w), rules);
    let (lb, lg) = totals(&lrr);
    let (gb, gg) = totals(&gto);
    let (sb, sg) = totals(&costed(gto_inventory(n.div_ceil(w), 1), rules));
    IssueOrderCost {
        configured: cfg.core.issue,
        slots: n,
        width: w,
        lrr,
        gto,
        register_bits: [lb, gb],
        ge: [lg, gg],
        gto_split: (sb * w, sg * f64::from(w)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_paper_machines_issue_orders() {
        let rules = GateRules::default();
        let c = issue_order_cost(&MachineConfig::paper(), &rules);
        assert_eq!((c.slots, c.width, c.configured), (64, 4, IssueOrder::Lrr));
        // A 6-bit pointer; 64 x 63 / 2 age bits and 64 greedy bits.
        assert_eq!(c.register_bits, [6, 2016 + 64]);
        // Split over 4 schedulers of 16 slots: 4 x (120 + 16).
        assert_eq!(c.gto_split.0, 4 * (120 + 16));
        assert!(c.ge[1] > c.ge[0] && c.gto_split.1 < c.ge[1]);
        let w2 = issue_order_cost(&MachineConfig::paper_width2(), &rules);
        assert_eq!(w2.register_bits, [6, 48 * 47 / 2 + 48]);
        // One slot: no pairs, a one-bit pointer.
        let mut one = MachineConfig::paper();
        one.core.max_warps = 1;
        let c = issue_order_cost(&one, &rules);
        assert_eq!(c.register_bits, [1, 1]);
    }
}
