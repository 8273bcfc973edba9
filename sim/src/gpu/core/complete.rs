//! The completion stage, phase 2 of a core's cycle, after the memory
//! system ticked: the warps a long-latency miss blocks (the memory
//! system's miss events through the core's rule, [`BlockedRule`]), then
//! the data that returned: a warp whose last block of its texture
//! instruction arrived is unblocked, passes the filter unit ([`Filter`])
//! and comes back to the issue stage when its data is filtered.

use super::blocked::BlockedRule;
use super::filter::Filter;
use super::issue::Issue;
use super::warp::{Warps, MAX_SLOTS};
use super::Notes;
use crate::gpu::SimError;
use crate::mem::MemorySystem;

/// The completion stage of core `core`.
#[derive(Clone, Debug)]
pub(super) struct Complete {
    core: usize,
    /// The tags that completed in the cycle (scratch).
    arrived: Vec<u32>,
}

/// The stages the completion stage hands warps to, and the rule it
/// applies.
pub(super) struct Downstream<'a> {
    pub(super) blocked: &'a mut BlockedRule,
    pub(super) filter: &'a mut Filter,
    pub(super) issue: &'a mut Issue,
}

impl Complete {
    /// The stage of core `core`.
    pub(super) fn new(core: usize) -> Self {
        Complete {
            core,
            arrived: Vec::new(),
        }
    }

    /// No data can return: no warp waits for a block.
    pub(super) fn is_idle(warps: &Warps) -> bool {
        (0..warps.slots()).all(|s| !warps.holds(s) || warps.get(s).pending == 0)
    }

    /// Phase 2 of cycle `now`: block the warps this cycle's misses block,
    /// then take the completions of `mem`. Returns whether data returned
    /// (the stage's progress).
    #[inline(always)]
    pub(super) fn run(
        &mut self,
        now: u64,
        mem: &mut MemorySystem,
        warps: &mut Warps,
        to: Downstream<'_>,
        notes: &mut Notes,
    ) -> Result<bool, SimError> {
        let core = self.core;
        // Before the completions: a miss always precedes its data.
        let mut slots = to.blocked.take_events(mem, core);
        while slots != 0 {
            let s = slots.trailing_zeros() as usize;
            slots &= slots - 1;
            waiting(core, warps, s, "long-latency report", now)?;
            warps.block(s, now, notes);
        }
        self.arrived.clear();
        mem.take_completions(core, &mut self.arrived);
        for &tag in &self.arrived {
            let s = tag as usize;
            waiting(core, warps, s, "completion", now)?;
            let w = warps.get_mut(s);
            w.pending -= 1;
            if w.pending == 0 {
                w.lat_sum += now - w.tex_start;
                w.tex_done += 1;
                let tri = w.tex_tri;
                warps.unblock(s, now, notes);
                // The filter unit serves the instructions in order of data
                // arrival (completion order within a cycle).
                let at = to.filter.accept(now, tri, &mut notes.stats);
                to.issue.accept(now, at, s);
            }
        }
        Ok(!self.arrived.is_empty())
    }
}

/// The warp in slot `s` of core `core` waits for a block (an empty slot
/// waits for none), or the model is wrong.
#[inline(always)]
fn waiting(core: usize, warps: &Warps, s: usize, what: &str, now: u64) -> Result<(), SimError> {
    if s < MAX_SLOTS && warps.get(s).pending > 0 {
        return Ok(());
    }
    Err(SimError::Internal(format!(
        "core {core}: {what} for slot {s}, which waits for no block, at cycle {now}"
    )))
}

#[cfg(test)]
mod tests {
    //! The stage alone on the memory system.
    use super::super::testkit::{one_core, trace};
    use super::super::warp::Warp;
    use super::super::Notes;
    use super::*;
    use crate::config::BlockedOn;
    use crate::mem::{Access, MemConfig};
    use crate::trace::Instr;

    /// A warp's two blocks return; at the last its data passes the filter
    /// and the warp comes back to the issue stage. A completion for a slot
    /// that waits for nothing is a model error.
    #[test]
    fn the_last_block_sends_the_warp_through_the_filter_to_issue() {
        let cfg = one_core(1, 4, 1);
        let mut mem = MemorySystem::new(&MemConfig::paper(false)).unwrap();
        let mut warps = Warps::new(4);
        warps.occupy(
            2,
            Warp {
                pending: 2,
                tex_tri: true,
                ..Warp::default()
            },
        );
        let mut rule = BlockedRule::new(BlockedOn::FirstLevel, false, 16, 16);
        let mut filter = Filter::new(&cfg.core);
        let mut issue = Issue::new(&cfg.core);
        let mut notes = Notes::new(4);
        let mut stage = Complete::new(0);
        assert!(!Complete::is_idle(&warps));
        // Block 7 misses; the second access merges into its entry: both
        // come back with its fill.
        let mut arrived_at = None;
        for now in 0..400 {
            match now {
                0 => assert_eq!(mem.access(0, 0, 7, 2), Access::Miss),
                1 => assert_eq!(mem.access(1, 0, 7, 2), Access::SecondaryMiss),
                _ => {}
            }
            mem.tick(now);
            let to = Downstream {
                blocked: &mut rule,
                filter: &mut filter,
                issue: &mut issue,
            };
            if stage
                .run(now, &mut mem, &mut warps, to, &mut notes)
                .unwrap()
            {
                arrived_at.get_or_insert(now);
            }
        }
        let a = arrived_at.expect("the data returned");
        assert!(Complete::is_idle(&warps));
        assert_eq!((warps.get(2).tex_done, warps.get(2).lat_sum), (1, a));
        // Trilinear: 2 filter cycles from `a`, overlapping the latency 4.
        let t = trace(&[(0, 0)], &[Instr::Alu(1)]);
        let wake = (a + 1..a + 10).find(|&c| issue.wake(c, &t.tiles()[0], &mut warps) != 0);
        assert_eq!(wake, Some(a + 4), "past its last instruction at a + 4");
        // Nothing waits now: a completion for slot 2 is an error.
        assert_eq!(mem.access(500, 0, 8, 2), Access::Miss);
        let err = (500..900).find_map(|now| {
            mem.tick(now);
            let to = Downstream {
                blocked: &mut rule,
                filter: &mut filter,
                issue: &mut issue,
            };
            stage.run(now, &mut mem, &mut warps, to, &mut notes).err()
        });
        let err = err.expect("an error").to_string();
        assert!(err.contains("completion for slot 2"), "{err}");
    }
}
