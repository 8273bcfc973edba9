//! Counters of the memory hierarchy.
//!
//! Every counter is a plain `u64` updated on the event it names; the MSHR
//! occupancy integrals count, for every ticked cycle, the occupancy after that
//! cycle's accesses and fills (kept per MSHR entry as it is filled and freed,
//! not per cycle; a cycle not ticked is idle and adds nothing). Summing over cores adds every field, so
//! `cycles` of a summed level is core-cycles and the averages stay per cache.

use super::prefetch::PrefetchStats;
use serde::{Deserialize, Serialize};

/// Counters of one cache (or of one level summed over cores).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct CacheStats {
    /// Accepted accesses: `hits + misses + secondary_misses`.
    pub accesses: u64,
    /// Accepted accesses that found their line.
    pub hits: u64,
    /// Primary misses: an MSHR entry was allocated and a request sent below.
    pub misses: u64,
    /// Misses merged into an existing MSHR entry.
    pub secondary_misses: u64,
    /// Cycles in which this cache refused at least one access because all of
    /// its MSHRs were occupied (cache stall), each cycle counted once.
    pub stall_cycles: u64,
    /// Accesses refused because all MSHRs were occupied (a requester that
    /// retries every cycle is counted every cycle).
    pub stall_refusals: u64,
    /// Secondary misses refused because their MSHR entry already held
    /// `1 + max_merged` targets. Not counted in `stall_cycles`.
    pub merge_stalls: u64,
    /// Accesses refused because every port was used in that cycle.
    pub port_busy: u64,
    /// Fills (replies from below), one per primary miss once it returns.
    pub fills: u64,
    /// Sum over every miss target (primary and secondary) of the cycles from
    /// its access to the fill of its line at this level.
    pub miss_wait_sum: u64,
    /// Sum over ticked cycles of MSHR entries held (awaiting a reply, or in
    /// the cycle after their reply).
    pub mshr_held_sum: u64,
    /// Sum over ticked cycles of MSHR entries awaiting their reply
    /// (outstanding misses).
    pub mshr_outstanding_sum: u64,
    /// Ticked cycles that ended with every MSHR held.
    pub mshr_full_cycles: u64,
    /// Ticked cycles (core-cycles once summed over cores).
    pub cycles: u64,
}

impl CacheStats {
    /// Add every counter of `o` into `self`.
    pub fn add(&mut self, o: &CacheStats) {
        self.accesses += o.accesses;
        self.hits += o.hits;
        self.misses += o.misses;
        self.secondary_misses += o.secondary_misses;
        self.stall_cycles += o.stall_cycles;
        self.stall_refusals += o.stall_refusals;
        self.merge_stalls += o.merge_stalls;
        self.port_busy += o.port_busy;
        self.fills += o.fills;
        self.miss_wait_sum += o.miss_wait_sum;
        self.mshr_held_sum += o.mshr_held_sum;
        self.mshr_outstanding_sum += o.mshr_outstanding_sum;
        self.mshr_full_cycles += o.mshr_full_cycles;
        self.cycles += o.cycles;
    }

    /// The counters since `before`, an earlier reading of the same cache
    /// (every field is a sum over events or cycles).
    pub fn since(&self, before: &CacheStats) -> CacheStats {
        CacheStats {
            accesses: self.accesses - before.accesses,
            hits: self.hits - before.hits,
            misses: self.misses - before.misses,
            secondary_misses: self.secondary_misses - before.secondary_misses,
            stall_cycles: self.stall_cycles - before.stall_cycles,
            stall_refusals: self.stall_refusals - before.stall_refusals,
            merge_stalls: self.merge_stalls - before.merge_stalls,
            port_busy: self.port_busy - before.port_busy,
            fills: self.fills - before.fills,
            miss_wait_sum: self.miss_wait_sum - before.miss_wait_sum,
            mshr_held_sum: self.mshr_held_sum - before.mshr_held_sum,
            mshr_outstanding_sum: self.mshr_outstanding_sum - before.mshr_outstanding_sum,
            mshr_full_cycles: self.mshr_full_cycles - before.mshr_full_cycles,
            cycles: self.cycles - before.cycles,
        }
    }

    /// Hits over accepted accesses (0 when there were none).
    pub fn hit_rate(&self) -> f64 {
        ratio(self.hits, self.accesses)
    }

    /// Average number of outstanding misses per cycle.
    pub fn avg_outstanding(&self) -> f64 {
        ratio(self.mshr_outstanding_sum, self.cycles)
    }

    /// Fraction of cycles with at least one cache-stall refusal.
    pub fn stall_fraction(&self) -> f64 {
        ratio(self.stall_cycles, self.cycles)
    }

    /// Average cycles a miss target (primary or secondary) waited for its fill.
    pub fn avg_miss_wait(&self) -> f64 {
        ratio(self.miss_wait_sum, self.misses + self.secondary_misses)
    }
}

/// Counters of main memory.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct DramStats {
    /// Requests received from the L2 (one per L2 primary miss).
    pub requests: u64,
    /// Requests accepted to an open row. Zero with ideal memory.
    pub row_hits: u64,
    /// Requests that had to open their row. Zero with ideal memory.
    pub row_misses: u64,
    /// Sum over requests of the cycles from the L2 miss to the reply reaching
    /// the L2 (FIFO wait included; zero with ideal memory).
    pub latency_sum: u64,
    /// Sum over requests of the cycles spent waiting in the FIFO beyond the
    /// earliest cycle they could be accepted.
    pub queue_wait_sum: u64,
    /// Largest FIFO depth seen.
    pub max_queue: u64,
    /// Line writes received (the colour-buffer flush): they take the FIFO
    /// and an acceptance slot like a read, open their row, and get no reply.
    /// Not counted in `requests`, `row_hits`, `row_misses` or the latency.
    #[serde(default)]
    pub writes: u64,
    /// Of the writes, those that had to open their row.
    #[serde(default)]
    pub write_row_misses: u64,
    /// Banked model: of the `row_misses`, those that found another row open
    /// and had to precharge it first (zero in the fixed model).
    #[serde(default)]
    pub row_conflicts: u64,
    /// Banked model: of the `write_row_misses`, those that had to precharge
    /// another row first.
    #[serde(default)]
    pub write_row_conflicts: u64,
    /// Banked model: ACTIVATE commands issued.
    #[serde(default)]
    pub activates: u64,
    /// Banked model: PRECHARGE commands issued.
    #[serde(default)]
    pub precharges: u64,
    /// Banked model: cycles the shared data bus carried data (reads and
    /// writes, `t_burst` a line). Divided by the run's cycles it is the bus
    /// utilisation.
    #[serde(default)]
    pub bus_busy_cycles: u64,
}

impl DramStats {
    /// The counters since `before`, an earlier reading; `max_queue` is
    /// this reading's (restarted when `before` was taken, see
    /// `MemorySystem::restart_peaks`).
    pub fn since(&self, before: &DramStats) -> DramStats {
        DramStats {
            requests: self.requests - before.requests,
            row_hits: self.row_hits - before.row_hits,
            row_misses: self.row_misses - before.row_misses,
            latency_sum: self.latency_sum - before.latency_sum,
            queue_wait_sum: self.queue_wait_sum - before.queue_wait_sum,
            max_queue: self.max_queue,
            writes: self.writes - before.writes,
            write_row_misses: self.write_row_misses - before.write_row_misses,
            row_conflicts: self.row_conflicts - before.row_conflicts,
            write_row_conflicts: self.write_row_conflicts - before.write_row_conflicts,
            activates: self.activates - before.activates,
            precharges: self.precharges - before.precharges,
            bus_busy_cycles: self.bus_busy_cycles - before.bus_busy_cycles,
        }
    }

    /// Average cycles from an L2 miss to its reply.
    pub fn avg_latency(&self) -> f64 {
        ratio(self.latency_sum, self.requests)
    }
}

/// Per-core counters of the private levels.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct CoreMemStats {
    /// The core's L0 (absent without L0).
    pub l0: Option<CacheStats>,
    /// The core's L1.
    pub l1: CacheStats,
}

/// Counters of the whole hierarchy.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct MemStats {
    /// All L0s summed (absent without L0).
    pub l0: Option<CacheStats>,
    /// All L1s summed.
    pub l1: CacheStats,
    /// The shared L2.
    pub l2: CacheStats,
    /// Main memory.
    pub dram: DramStats,
    /// Each core's private levels, in core order.
    pub per_core: Vec<CoreMemStats>,
    /// The prefetchers' counters, summed over the cores (zero without one).
    #[serde(default)]
    pub prefetch: PrefetchStats,
}

impl MemStats {
    /// The counters since `before`, an earlier reading of the same
    /// hierarchy (what one frame of a run did; see [`CacheStats::since`],
    /// [`DramStats::since`] and [`PrefetchStats::since`]).
    pub fn since(&self, before: &MemStats) -> MemStats {
        let opt = |a: &Option<CacheStats>, b: &Option<CacheStats>| match (a, b) {
            (Some(a), Some(b)) => Some(a.since(b)),
            (a, _) => *a,
        };
        MemStats {
            l0: opt(&self.l0, &before.l0),
            l1: self.l1.since(&before.l1),
            l2: self.l2.since(&before.l2),
            dram: self.dram.since(&before.dram),
            per_core: self
                .per_core
                .iter()
                .zip(&before.per_core)
                .map(|(a, b)| CoreMemStats {
                    l0: opt(&a.l0, &b.l0),
                    l1: a.l1.since(&b.l1),
                })
                .collect(),
            prefetch: self.prefetch.since(&before.prefetch),
        }
    }
}

fn ratio(num: u64, den: u64) -> f64 {
    if den == 0 {
        0.0
    } else {
        num as f64 / den as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn add_sums_every_field_and_ratios_handle_zero() {
        let a = CacheStats {
            accesses: 10,
            hits: 6,
            misses: 3,
            secondary_misses: 1,
            stall_cycles: 2,
            stall_refusals: 4,
            merge_stalls: 1,
            port_busy: 5,
            fills: 3,
            miss_wait_sum: 20,
            mshr_held_sum: 30,
            mshr_outstanding_sum: 25,
            mshr_full_cycles: 2,
            cycles: 50,
        };
        let mut s = CacheStats::default();
        assert_eq!(s.hit_rate(), 0.0);
        assert_eq!(s.avg_outstanding(), 0.0);
        s.add(&a);
        s.add(&a);
        assert_eq!(s.accesses, 20);
        assert_eq!(s.cycles, 100);
        assert_eq!(s.mshr_full_cycles, 4);
        assert!((s.hit_rate() - 0.6).abs() < 1e-12);
        assert!((s.avg_outstanding() - 0.5).abs() < 1e-12);
        assert!((s.stall_fraction() - 0.04).abs() < 1e-12);
        assert!((s.avg_miss_wait() - 5.0).abs() < 1e-12);
        let d = DramStats {
            requests: 4,
            latency_sum: 300,
            ..Default::default()
        };
        assert!((d.avg_latency() - 75.0).abs() < 1e-12);
    }
}
