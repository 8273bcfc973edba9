//! The LDST unit: a queue of `core.ldst_queue` texture instructions. Each
//! cycle the oldest presents its unique blocks to the first cache level,
//! in order, until the cache refuses one (its ports used or its MSHRs
//! full); then the next oldest, and so on. A block taken counts down in
//! its warp when its data returns (the completion stage).
//!
//! At each access the core's rule of which miss blocks a warp
//! ([`BlockedRule`]) sees the result, and under `wasp-m` a primary miss of
//! a priority warp counts for the CF meter.

use super::blocked::BlockedRule;
use super::warp::Warps;
use super::Notes;
use crate::mem::{Access, MemorySystem};
use crate::trace::Tile;
use std::collections::VecDeque;

/// A texture instruction in the LDST unit: its blocks are `next..end` of
/// the tile's block accesses.
#[derive(Clone, Copy, Debug)]
pub(super) struct LdstEntry {
    /// The warp's slot.
    pub(super) slot: u8,
    /// Next block to present.
    pub(super) next: u32,
    /// One past its last block.
    pub(super) end: u32,
}

/// The LDST unit of core `core`.
#[derive(Clone, Debug)]
pub(super) struct Ldst {
    core: usize,
    /// Texture instructions it holds.
    cap: usize,
    /// Count the primary misses of priority warps for the CF meter
    /// (`wasp-m`).
    count_priority_misses: bool,
    /// The oldest instruction, whose blocks are being presented (when
    /// `len > 0`), apart from the others for the hot path.
    cur: LdstEntry,
    /// The others, in order.
    wait: VecDeque<LdstEntry>,
    len: usize,
}

impl Ldst {
    /// An empty unit of core `core` holding `cap` instructions.
    pub(super) fn new(core: usize, cap: usize, count_priority_misses: bool) -> Self {
        Ldst {
            core,
            cap,
            count_priority_misses,
            cur: LdstEntry {
                slot: 0,
                next: 0,
                end: 0,
            },
            wait: VecDeque::with_capacity(cap),
            len: 0,
        }
    }

    /// Instructions held.
    #[inline]
    pub(super) fn len(&self) -> usize {
        self.len
    }

    /// Instructions it can hold.
    pub(super) fn cap(&self) -> usize {
        self.cap
    }

    /// Whether it has room for an instruction.
    #[inline(always)]
    pub(super) fn can_accept(&self) -> bool {
        self.len < self.cap
    }

    /// A texture instruction enters (there is room).
    #[inline]
    pub(super) fn accept(&mut self, e: LdstEntry) {
        debug_assert!(self.can_accept());
        if self.len == 0 {
            self.cur = e;
        } else {
            self.wait.push_back(e);
        }
        self.len += 1;
    }

    /// It holds no instruction.
    #[inline]
    pub(super) fn is_idle(&self) -> bool {
        self.len == 0
    }

    /// Cycle `now`: present the blocks of `tile` to the first level of
    /// `mem`; `blocked` sees every result and blocks the warps it names in
    /// `warps`. Returns whether a block was taken (the unit's progress).
    #[inline(always)]
    pub(super) fn run(
        &mut self,
        now: u64,
        tile: &Tile,
        mem: &mut MemorySystem,
        warps: &mut Warps,
        blocked: &mut BlockedRule,
        notes: &mut Notes,
    ) -> bool {
        if self.len == 0 {
            return false;
        }
        let blocks = tile.block_accesses();
        // The unit is the only one to present blocks: the cycle's count is
        // its progress.
        debug_assert_eq!(notes.signals.ldst_presented, 0);
        loop {
            let e = &mut self.cur;
            while e.next < e.end {
                let (r, entry) =
                    mem.access_entry(now, self.core, blocks[e.next as usize], e.slot as u32);
                if !r.accepted() {
                    notes.signals.ldst_refused = true;
                    return notes.signals.ldst_presented > 0;
                }
                e.next += 1;
                notes.signals.ldst_presented += 1;
                let s = e.slot as usize;
                if self.count_priority_misses && r == Access::Miss && warps.get(s).priority {
                    notes.prio.misses = notes.prio.misses.saturating_add(1);
                }
                if blocked.at_access(r, entry, s) {
                    warps.block(s, now, notes);
                }
            }
            self.len -= 1;
            match self.wait.pop_front() {
                Some(n) => self.cur = n,
                None => return notes.signals.ldst_presented > 0,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    //! The unit alone on the memory system, and its intake in a one-core
    //! machine, cycle by cycle.
    use super::super::testkit::{cycles, one_core, trace};
    use super::super::warp::Warp;
    use super::*;
    use crate::config::BlockedOn;
    use crate::mem::MemConfig;
    use crate::trace::Instr;

    /// Blocks go out in order, one a cycle through the width-2 machine's
    /// one L1 port, until the cache refuses; the unit's progress is
    /// whether a block went. A first-level miss blocks the warp.
    #[test]
    fn blocks_go_in_order_until_the_cache_refuses() {
        let mut mem = MemorySystem::new(&MemConfig::paper(false)).unwrap();
        let t = trace(&[(0, 0)], &[Instr::Tex(&[1, 2, 3])]);
        let tile = &t.tiles()[0];
        let mut warps = Warps::new(4);
        warps.occupy(
            0,
            Warp {
                pending: 3,
                ..Warp::default()
            },
        );
        let mut rule = BlockedRule::new(BlockedOn::FirstLevel, false, 16, 16);
        let mut notes = super::super::Notes::new(4);
        let mut u = Ldst::new(0, 2, false);
        assert!(u.is_idle() && u.can_accept());
        u.accept(LdstEntry {
            slot: 0,
            next: 0,
            end: 3,
        });
        assert!(!u.is_idle() && u.can_accept() && u.len() == 1);
        for now in 0..3 {
            notes.signals = Default::default();
            assert!(u.run(now, tile, &mut mem, &mut warps, &mut rule, &mut notes));
            assert_eq!(notes.signals.ldst_presented, 1, "cycle {now}");
            assert_eq!(notes.signals.ldst_refused, now < 2, "cycle {now}");
            mem.tick(now);
        }
        assert!(u.is_idle() && warps.get(0).blocked);
        notes.signals = Default::default();
        assert!(!u.run(3, tile, &mut mem, &mut warps, &mut rule, &mut notes));
    }

    /// One texture instruction enters the LDST unit a cycle.
    #[test]
    fn one_texture_instruction_a_cycle() {
        let quads: Vec<(u32, u32)> = (0..4).flat_map(|y| (0..4).map(move |x| (x, y))).collect();
        let run = cycles(
            &one_core(4, 16, 1),
            &trace(&quads, &[Instr::Tex(&[1]), Instr::Tex(&[2, 3])]),
        );
        assert!(run.windows(2).all(|w| w[1].0[1] - w[0].0[1] <= 1));
        assert_eq!(run.last().unwrap().0[1], 32);
        assert!(
            run.iter().all(|(_, s)| s.ldst <= 8),
            "the LDST queue's size"
        );
    }
}
