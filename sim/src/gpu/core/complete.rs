//! Phase 2 of a shader core's cycle, after the memory system ticked: the
//! warps a long-latency miss blocks, the memory completions through the
//! filter unit, and the scheduler's clock edge.

use super::{block_warp, ShaderCore, MAX_SLOTS};
use crate::config::FilterTiming;
use crate::gpu::SimError;
use crate::mem::MemorySystem;
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
        self.block_long_latency(now, mem)?;
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
                let f = u64::from(self.p.core.filter_cycles(w.tex_tri));
                let start = now.max(self.filter_free);
                self.filter_free = start + f;
                self.stats.filter_busy_cycles += f;
                self.stats.filter_wait_cycles += start - now;
                let lat = u64::from(self.p.core.texture_latency.max(1));
                let at = if self.p.core.filter_timing == FilterTiming::Overlap {
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

    /// Mark blocked the warps whose requests the memory system's miss
    /// events of this cycle show waiting on a long-latency miss (before
    /// the cycle's completions: a miss always precedes its data).
    #[inline(always)]
    fn block_long_latency(&mut self, now: u64, mem: &mut MemorySystem) -> Result<(), SimError> {
        let mut slots = self.blocked.take_events(mem, self.id);
        while slots != 0 {
            let s = slots.trailing_zeros() as usize;
            slots &= slots - 1;
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

#[cfg(test)]
mod tests {
    //! The texture filter unit: its rate, its order and how it adds to
    //! the texture latency.
    use crate::config::MachineConfig;
    use crate::gpu::core::testkit::{cfg, trace, OVERLAP, SERIAL};
    use crate::gpu::Gpu;
    use crate::run::simulate;
    use crate::run::RunOptions;
    use crate::stats::RunStats;
    use crate::trace::{Instr, Trace};

    /// (launch, finish) of each warp, by quad index, and the statistics.
    fn run(c: &MachineConfig, t: &Trace) -> (Vec<(u64, u64)>, RunStats) {
        let mut gpu = Gpu::new(c, t).unwrap();
        gpu.record_warps();
        while !gpu.done() {
            gpu.step().unwrap();
        }
        let mut r = gpu.take_records();
        r.sort_by_key(|w| w.quad);
        let times = r.iter().map(|w| (w.launched, w.finished)).collect();
        let s = simulate(c, t, &RunOptions::default(), &mut |_, _| {}).unwrap();
        (times, s)
    }

    /// A lone warp: under `overlap` a pass no longer than the texture
    /// latency (4) costs nothing, a longer one its excess; under `serial`
    /// every filter cycle adds.
    #[test]
    fn a_lone_warp_pays_the_filter_pass_beyond_the_latency() {
        let bil = trace(&[(0, 0)], &[Instr::Alu(1), Instr::Tex(&[9]), Instr::Alu(1)]);
        let tri = trace(
            &[(0, 0)],
            &[Instr::Alu(1), Instr::TriTex(&[9]), Instr::Alu(1)],
        );
        let span = |c: &MachineConfig, t: &Trace| {
            let (w, _) = run(c, t);
            w[0].1 - w[0].0
        };
        let base = span(&cfg(0, 0, OVERLAP), &bil);
        assert_eq!(span(&cfg(0, 0, OVERLAP), &tri), base);
        assert_eq!(span(&cfg(0, 0, SERIAL), &tri), base);
        assert_eq!(span(&cfg(1, 2, OVERLAP), &bil), base);
        assert_eq!(span(&cfg(1, 2, OVERLAP), &tri), base);
        assert_eq!(span(&cfg(1, 4, OVERLAP), &tri), base, "f = latency");
        assert_eq!(span(&cfg(1, 7, OVERLAP), &tri), base + 3);
        assert_eq!(span(&cfg(7, 1, OVERLAP), &bil), base + 3);
        assert_eq!(span(&cfg(7, 1, OVERLAP), &tri), base);
        assert_eq!(span(&cfg(1, 2, SERIAL), &bil), base + 1);
        assert_eq!(span(&cfg(1, 2, SERIAL), &tri), base + 2);
        let (_, s) = run(&cfg(1, 7, OVERLAP), &tri);
        assert_eq!(s.filter.busy_cycles, 7);
        assert_eq!(s.filter.wait_cycles, 0);
        assert_eq!(s.filter.trilinear_instructions, 1);
        assert_eq!(
            (s.filter.cycles_bilinear, s.filter.cycles_trilinear),
            (1, 7)
        );
        assert_eq!(s.filter.timing, "overlap");
    }

    /// Quads of one core whose one block arrives in the same cycle (the
    /// first misses, the others merge into its MSHR) queue at the filter:
    /// the k-th waits k filter passes, and finishes a pass after the one
    /// before it once the queue outgrows the latency.
    #[test]
    fn data_arriving_together_queues_at_the_one_filter() {
        // Shared-tile dispatch sends an 8x8-quad block to one core: the 16
        // quads of the 8x8-pixel tile all run on it.
        let quads: Vec<(u32, u32)> = (0..4).flat_map(|y| (0..4).map(move |x| (x, y))).collect();
        let tri = trace(&quads, &[Instr::TriTex(&[9]), Instr::Alu(1)]);
        let (free, s0) = run(&cfg(0, 0, OVERLAP), &tri);
        assert_eq!(s0.filter.wait_cycles, 0);
        assert_eq!(s0.filter.busy_cycles, 0);
        let (w, s) = run(&cfg(1, 8, SERIAL), &tri);
        assert_eq!(s.tex_instructions, 16);
        assert_eq!(s.filter.trilinear_instructions, 16);
        assert!((s.filter.trilinear_share - 1.0).abs() < 1e-12);
        assert_eq!(s.filter.busy_cycles, 16 * 8);
        // Each warp's data arrives when it would have without a filter:
        // it waits for the passes of those before it.
        let mut ends: Vec<u64> = w.iter().map(|x| x.1).collect();
        ends.sort_unstable();
        for pair in ends.windows(2) {
            assert!(pair[1] - pair[0] >= 8, "{ends:?}");
        }
        assert!(
            s.filter.wait_cycles >= 8 * (15 * 16 / 2) / 2,
            "{:?}",
            s.filter
        );
        assert!(
            s.cycles > s0.cycles + 15 * 8,
            "{} vs {}",
            s.cycles,
            s0.cycles
        );
        assert!(s.filter.avg_wait > 0.0 && s.filter.busy_fraction > 0.0);
        // No filter cycles: every warp as without a filter.
        let (w0, _) = run(&cfg(0, 0, SERIAL), &tri);
        assert_eq!(w0, free);
    }

    /// With both filter cycles 0 a trilinear trace runs exactly as the
    /// same trace bilinear, either timing: the marker changes nothing but
    /// the count.
    #[test]
    fn no_filter_cycles_make_trilinear_cost_nothing() {
        let quads: Vec<(u32, u32)> = (0..4).flat_map(|y| (0..4).map(move |x| (x, y))).collect();
        let prog_b = [
            Instr::Alu(2),
            Instr::Tex(&[1, 2]),
            Instr::Alu(1),
            Instr::Tex(&[3]),
        ];
        let prog_t = [
            Instr::Alu(2),
            Instr::TriTex(&[1, 2]),
            Instr::Alu(1),
            Instr::Tex(&[3]),
        ];
        let (b, t) = (trace(&quads, &prog_b), trace(&quads, &prog_t));
        for timing in [OVERLAP, SERIAL] {
            let c = cfg(0, 0, timing);
            let (wb, mut sb) = run(&c, &b);
            let (wt, mut st) = run(&c, &t);
            assert_eq!(wb, wt);
            assert_eq!(
                (
                    sb.filter.trilinear_instructions,
                    st.filter.trilinear_instructions
                ),
                (0, 16)
            );
            sb.filter.trilinear_instructions = 0;
            st.filter.trilinear_instructions = 0;
            sb.filter.trilinear_share = 0.0;
            st.filter.trilinear_share = 0.0;
            assert_eq!(sb.to_json(), st.to_json());
        }
        // With a rate, trilinear costs more than bilinear.
        let c = cfg(1, 8, SERIAL);
        assert!(run(&c, &t).1.cycles > run(&c, &b).1.cycles);
    }
}
