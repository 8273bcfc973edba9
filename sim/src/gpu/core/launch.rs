//! The launch stage: the input FIFOs and the launch scheduler of the paper
//! (its policy, the free-MSHR register, the non-blocked priority-warp
//! counter), which launches at most one warp a cycle into the lowest free
//! warp slot, and the scheduler's clock edge at the end of the cycle.
//!
//! A quad enters the priority or the regular FIFO, as the subset's
//! comparator says ([`accept`](Launch::accept), from the GPU's rasterizer
//! or the core's own). Each cycle the policy's gate and the launch rule
//! (`scheduler.launch_rule`) choose the FIFO; a cycle in which `hold` keeps
//! a lone priority warp back is a hold idle cycle
//! ([`CoreStats::held_cycles`](super::CoreStats::held_cycles)).

use super::params::CoreParams;
use super::warp::{Warp, Warps};
use super::Notes;
use crate::gpu::SimError;
use crate::mem::SchedCacheMshrs;
use crate::trace::Tile;
use wasp_rtl::free_mshr::{FreeMshrReg, MshrEvents};
use wasp_rtl::nonblocked::PriorityEvents;
use wasp_rtl::policy::{LaunchPolicy, LaunchRule};
use wasp_rtl::queue::QueueClass;
use wasp_rtl::scheduler::{EdgeEvents, LaunchScheduler};
use wasp_rtl::subset::PrioritySubset;

/// The launch stage.
#[derive(Debug)]
pub(super) struct Launch {
    sched: LaunchScheduler<u32>,
    /// The free-MSHR register follows the cache (policies that read it;
    /// the others may watch a cache with more entries than it holds, and
    /// the register then stays at reset).
    track_mshrs: bool,
}

impl Launch {
    /// The stage in its reset state, the scheduler wired for `policy`.
    pub(super) fn new(
        p: &CoreParams,
        policy: &dyn LaunchPolicy,
        rule: LaunchRule,
        subset: Box<dyn PrioritySubset>,
    ) -> Self {
        let free =
            FreeMshrReg::with_capacity(p.watched_mshrs).expect("watched MSHRs fit the register");
        let queue = p.core.input_queue as usize;
        Launch {
            sched: LaunchScheduler::new(queue, subset, free, policy, rule),
            track_mshrs: policy.reads_free_mshrs(),
        }
    }

    /// The scheduler.
    pub(super) fn sched(&self) -> &LaunchScheduler<u32> {
        &self.sched
    }

    /// Whether the free-MSHR register follows the cache.
    pub(super) fn tracks_mshrs(&self) -> bool {
        self.track_mshrs
    }

    /// Quad `quad` at in-tile (x, y) enters the FIFO the subset names;
    /// `false` (and nothing changes) when the input queue or that FIFO is
    /// full, so the rasterizer waits.
    #[inline]
    pub(super) fn accept(&mut self, quad: u32, x: u32, y: u32) -> bool {
        !self.sched.queue().is_full() && self.sched.enqueue(quad, x, y).is_ok()
    }

    /// Nothing to launch: no warp waits, or no slot is free.
    pub(super) fn is_idle(&self, warps: &Warps) -> bool {
        self.sched.queue().is_empty() || warps.free_slot().is_none()
    }

    /// Cycle `now`: launch at most one warp of `tile` into the lowest free
    /// slot of `warps`; the slot of the warp launched, if any (the stage's
    /// progress).
    #[inline(always)]
    pub(super) fn run(
        &mut self,
        now: u64,
        tile: &Tile,
        warps: &mut Warps,
        notes: &mut Notes,
    ) -> Option<usize> {
        let slot = match warps.free_slot() {
            Some(slot) if !self.sched.queue().is_empty() => slot,
            // Nothing can launch: the decision logic is not evaluated (its
            // waveform signals keep their last values, `launch` reads 0).
            _ => return None,
        };
        let both = self.sched.queue().has(QueueClass::Priority)
            && self.sched.queue().has(QueueClass::Regular);
        let launch = self.sched.launch(true);
        let Some((quad, class)) = launch.warp else {
            // A free slot and a waiting warp but no launch: only the
            // launch rule `hold` does that (a closed gate, only priority
            // warps waiting).
            debug_assert!(launch.decision.held);
            notes.stats.held_cycles += u64::from(launch.decision.held);
            return None;
        };
        let stats = &mut notes.stats;
        if both {
            stats.both_waiting += 1;
            stats.regular_first += u64::from(class == QueueClass::Regular);
        }
        let priority = class == QueueClass::Priority;
        let span = tile.quad_span(quad as usize).expect("quad in tile");
        warps.occupy(
            slot,
            Warp {
                quad,
                op: span.op_start,
                n_ops: span.op_start + span.op_len,
                priority,
                blk: span.block_start,
                launched_at: now,
                ..Warp::default()
            },
        );
        stats.warps_launched += 1;
        stats.priority_launches += priority as u64;
        notes.signals.launched = Some((quad, priority));
        Some(slot)
    }

    /// The scheduler's clock edge at the end of a cycle with no events
    /// for its registers: no MSHR event of the watched cache, no
    /// priority-warp event (`notes.prio` empty) and no priority launch.
    /// The registers keep their values, so the free-MSHR register still
    /// agrees with the cache. Returns false, and does nothing, when a
    /// priority warp launched (call [`clock`](Self::clock)).
    #[inline(always)]
    pub(super) fn clock_quiet(&mut self, notes: &mut Notes) -> bool {
        debug_assert_eq!(notes.prio, PriorityEvents::default());
        if !self.sched.clock_quiet() {
            return false;
        }
        if let Some(m) = self.sched.cf_meter() {
            notes.stats.cf_quarters_sum += u64::from(m.cf().quarters());
            notes.stats.cf_samples += 1;
        }
        true
    }

    /// The scheduler's clock edge at the end of cycle `now` of core `core`:
    /// the cycle's MSHR events of the watched cache, `ev`, and its
    /// priority-warp events. Checks the free-MSHR register against the
    /// cache. (Inlined: it runs every cycle, and out of line it costs
    /// its caller the arguments and the result's checks.)
    #[inline(always)]
    pub(super) fn clock(
        &mut self,
        core: usize,
        now: u64,
        ev: SchedCacheMshrs,
        notes: &mut Notes,
    ) -> Result<(), SimError> {
        let mshr = if self.track_mshrs {
            MshrEvents {
                allocs: ev.allocated as u8,
                replies: ev.replied as u8,
            }
        } else {
            MshrEvents::default()
        };
        self.sched
            .clock(EdgeEvents {
                mshr,
                prio: notes.prio,
            })
            .map_err(|fault| SimError::Register {
                core,
                cycle: now,
                fault,
            })?;
        if let Some(m) = self.sched.cf_meter() {
            notes.stats.cf_quarters_sum += u64::from(m.cf().quarters());
            notes.stats.cf_samples += 1;
        }
        // Self-check: the register counts an entry free from its reply.
        let free = self.sched.free_mshrs().free().get();
        if self.track_mshrs && free != ev.free_from_reply() {
            return Err(SimError::Internal(format!(
                "core {core}: free-MSHR register {free} != capacity - outstanding {} at cycle {now}",
                ev.free_from_reply()
            )));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    //! The stage alone, and in a one-core machine, cycle by cycle.
    use super::super::testkit::{cycles, one_core, trace};
    use super::super::Notes;
    use super::*;
    use crate::trace::Instr;
    use wasp_rtl::policy::PolicySpec;
    use wasp_rtl::subset::SubsetSpec;

    /// One warp a cycle into the lowest free slot, none without a free
    /// slot; the FIFO refuses quads when full.
    #[test]
    fn one_launch_a_cycle_while_a_slot_is_free() {
        let mut cfg = one_core(1, 2, 1);
        cfg.core.input_queue = 3;
        let p = CoreParams::new(&cfg);
        let policy = PolicySpec::Baseline.build(16).unwrap();
        let subset = SubsetSpec::Mesh(4).build(cfg.quads_per_side());
        let mut l = Launch::new(&p, policy.as_ref(), LaunchRule::Hold, subset);
        let t = trace(&[(0, 0), (1, 0), (2, 0)], &[Instr::Alu(1)]);
        let tile = &t.tiles()[0];
        let (mut warps, mut notes) = (Warps::new(2), Notes::new(2));
        assert!(l.is_idle(&warps), "no warp waits");
        assert!(l.accept(0, 0, 0) && l.accept(1, 1, 0) && l.accept(2, 2, 0));
        assert!(!l.accept(3, 3, 0), "the FIFO is full");
        assert_eq!(l.run(1, tile, &mut warps, &mut notes), Some(0));
        assert_eq!(l.run(2, tile, &mut warps, &mut notes), Some(1));
        assert!(l.is_idle(&warps), "no free slot");
        assert_eq!(l.run(3, tile, &mut warps, &mut notes), None);
        warps.release(0);
        assert_eq!(l.run(4, tile, &mut warps, &mut notes), Some(0));
        assert_eq!((warps.get(0).quad, warps.get(0).launched_at), (2, 4));
        assert_eq!(notes.stats.warps_launched, 3);
        assert!(l.is_idle(&warps));
    }

    /// At most one warp launches a cycle, into the lowest free slot, and it
    /// issues from the cycle after its launch.
    #[test]
    fn one_launch_a_cycle_into_the_lowest_free_slot() {
        let quads: Vec<(u32, u32)> = (0..4).map(|x| (x, 0)).collect();
        let t = trace(&quads, &[Instr::Alu(2)]);
        let run = cycles(&one_core(4, 8, 1), &t);
        let mut launched = 0;
        for w in run.windows(2) {
            let (a, b) = (&w[0].0, &w[1].0);
            assert!(b[2] - a[2] <= 1, "one launch a cycle");
            if b[2] > a[2] {
                // Warps finish before the launch stage, so the slots the
                // others hold after the cycle are those held at the launch.
                let newest = w[1].1.warps.iter().max_by_key(|v| v.launched).unwrap();
                let held = |s: usize| w[1].1.warps.iter().any(|v| v.slot == s);
                assert!((0..newest.slot).all(held), "the lowest free slot");
                assert!(!newest.ready_alu, "not ready in its launch cycle");
                launched += 1;
            }
        }
        assert_eq!(launched + run[0].0[2], 4);
    }
}
