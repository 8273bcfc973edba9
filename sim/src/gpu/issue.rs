//! The issue stage's choice: which ready warps issue this cycle, in the
//! order `core.issue` names.
//!
//! Every order keeps the stage's rules: at most `pipeline_width`
//! instructions a cycle, one per warp; a candidate is a warp ready for an
//! ALU instruction, or one waiting on a texture instruction while the LDST
//! unit has room; one texture instruction enters the LDST unit per cycle,
//! so after the first texture pick only ALU-ready warps are taken. The
//! candidates are visited in the order's sequence and each issues until
//! the width is used. The orders differ only in that sequence:
//! - [`lrr`]: loose round-robin over the slots from a pointer
//!   ([`IssueOrder::Lrr`]);
//! - [`gto`]: greedy-then-oldest ([`IssueOrder::Gto`]).
//!
//! Each order is one file with a fast form on slot masks, which the core
//! runs, and a plain form that visits the slots one by one as its text
//! reads; the tests in each file compare the two on random masks. The
//! plain twin of the whole core (`core/plain.rs`) visits its slots in the
//! same terms again.

pub(crate) mod gto;
pub(crate) mod lrr;

use super::mask::SlotMask;
use serde::{Deserialize, Serialize};
use std::fmt;

/// The order in which the issue stage visits ready warps (`core.issue`).
/// The paper does not say (wasp's choice: `lrr`, the order of the model
/// before the option existed). docs/machine.md, "Issue order", defines
/// both.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum IssueOrder {
    /// Loose round-robin: every slot from the one after the last pick of
    /// the last issuing cycle, ascending, wrapping (`gpu/issue/lrr.rs`).
    #[default]
    Lrr,
    /// Greedy-then-oldest: the slots that issued in the last issuing cycle
    /// first, then every other slot, each group oldest first by launch
    /// cycle (`gpu/issue/gto.rs`).
    Gto,
}

impl IssueOrder {
    /// Every order.
    pub const ALL: [IssueOrder; 2] = [IssueOrder::Lrr, IssueOrder::Gto];
}

impl fmt::Display for IssueOrder {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            IssueOrder::Lrr => "lrr",
            IssueOrder::Gto => "gto",
        })
    }
}

impl std::str::FromStr for IssueOrder {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        IssueOrder::ALL
            .into_iter()
            .find(|o| o.to_string() == s)
            .ok_or_else(|| format!("unknown issue order {s:?}: expected lrr or gto"))
    }
}

/// What the issue stage picked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Picks<M> {
    /// Slots issuing an ALU instruction.
    pub alu: M,
    /// Those of `alu` for which the pick callback said their ALU run ends.
    pub run_end: M,
    /// The slot issuing a texture instruction, if any.
    pub tex: Option<usize>,
    /// Instructions issued.
    pub issued: u32,
    /// The last slot picked (meaningful when `issued > 0`).
    pub last: u32,
}

impl<M: SlotMask> Picks<M> {
    /// Nothing picked yet.
    pub(crate) const NONE: Self = Picks {
        alu: M::ZERO,
        run_end: M::ZERO,
        tex: None,
        issued: 0,
        last: 0,
    };

    /// Every slot picked, ALU and texture.
    #[inline(always)]
    pub(crate) fn slots(&self) -> M {
        match self.tex {
            Some(s) => self.alu | M::bit(s),
            None => self.alu,
        }
    }
}

/// One issue order: its pick and the state it keeps between cycles.
pub(crate) trait Order: Sized {
    /// The order's state in a core's [`Issuer`].
    fn state(issuer: &mut Issuer) -> &mut Self;

    /// This cycle's picks from `ready` (ALU-ready slots) and `tex` (slots
    /// whose texture instruction may enter the LDST unit; disjoint from
    /// `ready`), at most `width`; `age(s)` is the launch cycle of the warp
    /// in slot `s`. `on_alu(slot)` is called for each ALU pick in visiting
    /// order and says whether the warp's ALU run ends with this
    /// instruction. The order updates its state for the next cycle.
    fn pick<M: SlotMask>(
        &mut self,
        ready: M,
        tex: M,
        width: u32,
        age: impl Fn(usize) -> u64,
        on_alu: impl FnMut(usize) -> bool,
    ) -> Picks<M>;
}

/// A core's issue order and the state of every order (a pointer and a
/// slot set, a few bytes), so that the core runs one copy of its issue
/// stage per order with the state in place ([`Order::state`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Issuer {
    /// The order the core runs.
    pub(crate) order: IssueOrder,
    lrr: lrr::Lrr,
    gto: gto::Gto,
}

impl Issuer {
    /// `order` in its reset state on a core of `slots` warp slots.
    pub(crate) fn new(order: IssueOrder, slots: usize) -> Self {
        Issuer {
            order,
            lrr: lrr::Lrr::new(slots),
            gto: gto::Gto::default(),
        }
    }
}

impl Order for lrr::Lrr {
    #[inline(always)]
    fn state(issuer: &mut Issuer) -> &mut Self {
        &mut issuer.lrr
    }

    #[inline(always)]
    fn pick<M: SlotMask>(
        &mut self,
        ready: M,
        tex: M,
        width: u32,
        _age: impl Fn(usize) -> u64,
        on_alu: impl FnMut(usize) -> bool,
    ) -> Picks<M> {
        self.pick(ready, tex, width, on_alu)
    }
}

impl Order for gto::Gto {
    #[inline(always)]
    fn state(issuer: &mut Issuer) -> &mut Self {
        &mut issuer.gto
    }

    #[inline(always)]
    fn pick<M: SlotMask>(
        &mut self,
        ready: M,
        tex: M,
        width: u32,
        age: impl Fn(usize) -> u64,
        on_alu: impl FnMut(usize) -> bool,
    ) -> Picks<M> {
        self.pick(ready, tex, width, age, on_alu)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orders_read_back_from_their_names() {
        for o in IssueOrder::ALL {
            assert_eq!(o.to_string().parse::<IssueOrder>(), Ok(o));
        }
        let e = "fifo".parse::<IssueOrder>().unwrap_err();
        assert!(e.contains("expected lrr or gto"), "{e}");
        assert_eq!(IssueOrder::default(), IssueOrder::Lrr);
    }

    #[test]
    fn picks_name_their_slots() {
        let p = Picks::<u64> {
            alu: 0b101,
            run_end: 0,
            tex: Some(4),
            issued: 3,
            last: 4,
        };
        assert_eq!(p.slots(), 0b10101);
        assert_eq!(Picks::<u64>::NONE.slots(), 0);
    }

    /// Cycle in which each of two warps finished, on one core of width 1
    /// with an ALU latency of 1; both run eight ALU instructions, the first
    /// launched a cycle before the second.
    fn finish_cycles(order: IssueOrder) -> [u64; 2] {
        use crate::config::MachineConfig;
        use crate::gpu::Gpu;
        use crate::trace::{Instr, Trace, TraceHeader};
        let mut b = Trace::builder(TraceHeader::new("issue", 8, 8, 8)).unwrap();
        b.begin_tile(0, 0).unwrap();
        for x in 0..2 {
            b.quad(x, 0, &[Instr::Alu(8)]).unwrap();
        }
        b.end_tile().unwrap();
        let t = b.finish().unwrap();
        let mut c = MachineConfig::paper();
        c.gpu.tile_size = 8;
        c.gpu.cores = 1;
        c.raster.quads_per_cycle = 1;
        c.core.pipeline_width = 1;
        c.core.alu_latency = 1;
        c.core.issue = order;
        c.validate().unwrap();
        let mut gpu = Gpu::new(&c, &t).unwrap();
        gpu.record_warps();
        while !gpu.done() {
            gpu.step().unwrap();
        }
        let mut r = gpu.take_records();
        r.sort_by_key(|w| w.quad);
        [r[0].finished, r[1].finished]
    }

    /// Greedy-then-oldest runs the older warp's ALU run back to back;
    /// loose round-robin alternates the two.
    #[test]
    fn the_order_decides_who_runs_first() {
        let [a, b] = finish_cycles(IssueOrder::Gto);
        assert!(b >= a + 7, "gto: the older warp finishes first ({a}, {b})");
        let [a, b] = finish_cycles(IssueOrder::Lrr);
        assert!(a.abs_diff(b) <= 2, "lrr: the two interleave ({a}, {b})");
    }
}
