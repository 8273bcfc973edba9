//! Building the memory system from its configuration: every core's L0
//! (when present) and L1 with their queues sized from the MSHR counts, the
//! prefetch queues, the shared L2 and the DRAM.

use super::{CoreMem, MemorySystem};
use crate::mem::cache::Cache;
use crate::mem::config::{MemConfig, MemConfigError};
use crate::mem::dram::Dram;
use crate::mem::prefetch::PrefetchQueue;
use crate::mem::ring::Ring;

impl MemorySystem {
    /// An empty hierarchy (all caches invalid, all DRAM banks closed), or an
    /// error naming the first value that cannot be modelled.
    pub fn new(cfg: &MemConfig) -> Result<Self, MemConfigError> {
        cfg.check()?;
        let first = cfg.scheduler_level();
        let n_cores = cfg.cores as usize;
        let mut cores = Vec::with_capacity(n_cores);
        for _ in 0..n_cores {
            let l0 = cfg.l0.as_ref().map(Cache::new).transpose()?;
            let mut l1 = Cache::new(&cfg.l1)?;
            if cfg.prefetch.enabled() {
                l1.enable_prefetch_marks();
            }
            let l1_mshrs = cfg.l1.mshrs as usize;
            let l0_mshrs = cfg.l0.map_or(0, |c| c.mshrs as usize);
            // Bound on tags completing at once: every hit still in its latency
            // plus every target of every MSHR entry.
            let completing = first.ports as usize * first.hit_latency as usize
                + first.mshrs as usize * (1 + first.max_merged as usize);
            cores.push(CoreMem {
                l0,
                l1,
                to_l1: Ring::with_capacity(l0_mshrs),
                to_l2: Ring::with_capacity(l1_mshrs),
                to_l0: Ring::with_capacity(l0_mshrs),
                completing: Ring::with_capacity(completing),
                ready: Vec::with_capacity(completing),
                // At most one event per MSHR entry of the L0 and the L1 in
                // a tick.
                misses: Vec::with_capacity(if cfg.report_misses {
                    l0_mshrs + l1_mshrs
                } else {
                    0
                }),
                active: false,
            });
        }
        let pf = (0..n_cores)
            .map(|_| PrefetchQueue::new(cfg.prefetch.queue as usize, cfg.prefetch.queue_filter))
            .collect();
        Ok(MemorySystem {
            cfg: cfg.clone(),
            cores,
            pf,
            l2: Cache::new(&cfg.l2)?,
            report_misses: cfg.report_misses,
            to_l1: Ring::with_capacity(n_cores * cfg.l1.mshrs as usize),
            l2_order: Vec::with_capacity(n_cores),
            dram: Dram::new(&cfg.dram, cfg.ideal_memory, cfg.l2.mshrs),
            texmap: None,
            now: 0,
            ticks: 0,
            ticked_until: 0,
        })
    }
}
