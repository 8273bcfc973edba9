//! Phase 2 of a shader core's cycle, after the memory system ticked: the
//! warps a long-latency miss blocks, the memory completions through the
//! filter unit, and the scheduler's clock edge.

use super::{block_warp, ShaderCore, MAX_SLOTS};
use crate::gpu::SimError;
use crate::mem::{BlockedOn, MemorySystem};
use wasp_rtl::free_mshr::MshrEvents;
use wasp_rtl::scheduler::EdgeEvents;

impl ShaderCore {
    /// Phase 2 of cycle `now`: take the memory completions, then clock the
    /// scheduler's registers.
    pub fn complete(
        &mut self,
        now: u64,
        mem: &mut MemorySystem,
        scratch: &mut Vec<u32>,
    ) -> Result<(), SimError> {
        if self.blocked_on != BlockedOn::FirstLevel {
            self.block_long_latency(now, mem)?;
        }
        scratch.clear();
        mem.take_completions(self.id, scratch);
        for &tag in scratch.iter() {
            let s = tag as usize;
            let w = &mut self.slots[s % MAX_SLOTS];
            // An empty slot, or a warp with every block already back.
            if w.pending == 0 || s >= MAX_SLOTS {
                return Err(SimError::Internal(format!(
                    "core {}: completion for slot {s}, which waits for no block, at cycle {now}",
                    self.id
                )));
            }
            w.pending -= 1;
            if w.pending == 0 {
                let lat = now - w.tex_start;
                w.lat_sum += lat;
                w.tex_done += 1;
                if w.blocked {
                    w.blocked = false;
                    self.stats.blocked_cycles[w.priority as usize & 1] +=
                        now - self.blocked_at[s % MAX_SLOTS];
                    if w.priority {
                        self.prio.unblocked += 1;
                    }
                }
                // The filter unit serves the instructions in order of data
                // arrival (completion order within a cycle).
                let f = self.filter_cycles[w.tex_tri as usize];
                let start = now.max(self.filter_free);
                self.filter_free = start + f;
                self.stats.filter_busy_cycles += f;
                self.stats.filter_wait_cycles += start - now;
                let lat = self.texture_latency.max(1);
                let at = if self.filter_overlap {
                    (start + f).max(now + lat)
                } else {
                    start + f + lat
                };
                self.schedule(now, at, s);
            }
        }
        if !scratch.is_empty() {
            self.last_progress = now;
        }
        let ev = mem.mshr_events(self.id);
        self.tile_misses += u64::from(ev.allocated);
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
                prio: self.prio,
            })
            .map_err(|e| SimError::Register {
                core: self.id,
                cycle: now,
                fault: e,
            })?;
        if let Some(m) = self.sched.cf_meter() {
            self.stats.cf_quarters_sum += u64::from(m.cf().quarters());
            self.stats.cf_samples += 1;
        }
        // Self-check: the register counts an entry free from its reply.
        let free = self.sched.free_mshrs().free().get();
        if self.track_mshrs && free != ev.free_from_reply() {
            return Err(SimError::Internal(format!(
                "core {}: free-MSHR register {free} != capacity - outstanding {} at cycle {now}",
                self.id,
                ev.free_from_reply()
            )));
        }
        Ok(())
    }

    /// Mark blocked the warps whose requests the memory system reports
    /// waiting on a long-latency miss in this cycle (before the cycle's
    /// completions: a report always precedes its tag's completion).
    fn block_long_latency(&mut self, now: u64, mem: &mut MemorySystem) -> Result<(), SimError> {
        self.long.clear();
        mem.take_long_latency(self.id, &mut self.long);
        for &tag in &self.long {
            let s = tag as usize;
            let w = &mut self.slots[s % MAX_SLOTS];
            if w.pending == 0 || s >= MAX_SLOTS {
                return Err(SimError::Internal(format!(
                    "core {}: long-latency report for slot {s}, which waits for no block, at cycle {now}",
                    self.id
                )));
            }
            block_warp(
                w,
                &mut self.blocked_at[s % MAX_SLOTS],
                &mut self.stats.blocked_episodes,
                &mut self.prio,
                now,
            );
        }
        Ok(())
    }
}
