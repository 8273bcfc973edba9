//! The memory system's read-outs, off the hot path: its counters
//! ([`MemStats`]), the misses outstanding, the DRAM FIFO's depth, the
//! restart of the peak counters at a frame's start, and the waveform
//! signals of each level.

use super::MemorySystem;
use crate::mem::cache::{bits_for, Cache};
use crate::mem::prefetch::PrefetchStats;
use crate::mem::stats::{CacheStats, CoreMemStats, MemStats};
use wasp_waves::Tracer;

impl MemorySystem {
    /// Requests waiting in the DRAM's FIFO.
    pub fn dram_queued(&self) -> usize {
        self.dram.queued()
    }

    /// Misses outstanding now (MSHR entries awaiting their reply):
    /// `[L0, L1, L2]`, L0 and L1 summed over the cores.
    pub fn outstanding(&self) -> [u32; 3] {
        let mut o = [0, 0, self.l2.mshr_outstanding()];
        for c in &self.cores {
            o[0] += c.l0.as_ref().map_or(0, |l0| l0.mshr_outstanding());
            o[1] += c.l1.mshr_outstanding();
        }
        o
    }

    /// Restart the counters that keep a peak (the DRAM FIFO's and the
    /// prefetch queues' largest depth) at their present value: a frame
    /// begins, and its peaks are its own. Sums need no restart: a frame's
    /// are [`MemStats::since`] the reading at its start.
    pub fn restart_peaks(&mut self) {
        self.dram.restart_max_queue();
        for q in &mut self.pf {
            q.restart_max_len();
        }
    }

    /// Counters of every level so far.
    pub fn stats(&self) -> MemStats {
        // Every cache lives through every tick. The occupancy integrals run
        // through the last tick; cycles not ticked were idle (nothing
        // occupied) and add nothing.
        let with_cycles = |c: &Cache| c.stats_until(self.ticked_until, self.ticks);
        let per_core: Vec<CoreMemStats> = self
            .cores
            .iter()
            .map(|c| CoreMemStats {
                l0: c.l0.as_ref().map(with_cycles),
                l1: with_cycles(&c.l1),
            })
            .collect();
        let mut l0 = self.cfg.l0.map(|_| CacheStats::default());
        let mut l1 = CacheStats::default();
        for c in &per_core {
            if let (Some(sum), Some(s)) = (l0.as_mut(), c.l0.as_ref()) {
                sum.add(s);
            }
            l1.add(&c.l1);
        }
        MemStats {
            l0,
            l1,
            l2: with_cycles(&self.l2),
            dram: *self.dram.stats(),
            per_core,
            prefetch: self.prefetch_stats(),
        }
    }

    /// The prefetch counters of every core, summed (all zero without a
    /// prefetcher).
    pub fn prefetch_stats(&self) -> PrefetchStats {
        let mut sum = PrefetchStats::default();
        for (c, pf) in self.cores.iter().zip(&self.pf) {
            sum.add(&PrefetchStats {
                queue: *pf.counts(),
                lines: c.l1.prefetch_counts(),
                unused_at_end: c.l1.prefetch_unused(),
            });
        }
        sum
    }

    /// Signals of `core`'s private levels in the last cycle: scopes `l0` (when
    /// present) and `l1`, each with the cache's signals (see
    /// [`Cache::trace`]) plus `miss_queue`, its requests waiting for the next
    /// level. The caller opens the core's scope.
    pub fn trace<T: Tracer + ?Sized>(&self, core: usize, t: &mut T) {
        let c = &self.cores[core];
        if let Some(l0) = &c.l0 {
            t.push_scope("l0");
            l0.trace(self.now, t);
            let w = bits_for(u64::from(l0.mshr_capacity()));
            t.signal("miss_queue", w, c.to_l1.len() as u64);
            t.pop_scope();
        }
        t.push_scope("l1");
        c.l1.trace(self.now, t);
        let w = bits_for(u64::from(c.l1.mshr_capacity()));
        t.signal("miss_queue", w, c.to_l2.len() as u64);
        if self.cfg.prefetch.enabled() {
            t.signal("prefetch_queue", 16, self.pf[core].len().min(0xffff) as u64);
        }
        t.pop_scope();
    }

    /// Signals of the shared levels in the last cycle: scopes `l2` (the
    /// cache's signals) and `dram` (FIFO depth, requests in flight, requests
    /// accepted). The caller opens the enclosing scope.
    pub fn trace_shared<T: Tracer + ?Sized>(&self, t: &mut T) {
        t.push_scope("l2");
        self.l2.trace(self.now, t);
        t.pop_scope();
        t.push_scope("dram");
        self.dram.trace(self.now, t);
        t.pop_scope();
    }
}
