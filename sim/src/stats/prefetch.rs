//! The `prefetch` block of a run's statistics: the prefetcher, its limits
//! and what became of its requests (present only when the machine has a
//! prefetcher, so that the shipped machine's output is unchanged).

use crate::config::MachineConfig;
use crate::mem::PrefetchStats;
use serde::Serialize;
use std::fmt::Write as _;

/// A run's prefetches, summed over the cores.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PrefetchReport {
    /// `oracle-tile` or `raster`.
    pub kind: String,
    /// Entries of the raster prefetcher's queue per core.
    pub queue: u32,
    /// The queue skips blocks already queued.
    pub queue_filter: bool,
    /// L1 MSHRs kept free for demand.
    pub l1_reserve: u32,
    /// Requests generated.
    pub generated: u64,
    /// Skipped: the block was already queued.
    pub duplicates: u64,
    /// Dropped: the queue was full.
    pub dropped: u64,
    /// Discarded unissued when the core's next tile opened (the oracle).
    pub cancelled: u64,
    /// Looked up in the L1.
    pub issued: u64,
    /// Of them, the line was present (dropped at the L1).
    pub hits: u64,
    /// Of them, a miss was already pending (dropped at the L1).
    pub pending: u64,
    /// Of them, missed and went to the L2 (an L1 MSHR each).
    pub misses: u64,
    /// Cycles a queue's head waited for L1 MSHRs above the reserve.
    pub reserve_waits: u64,
    /// Prefetch misses a demand access used (hit the line or merged into
    /// the entry), each once.
    pub useful: u64,
    /// Of them, a demand miss merged into the prefetch in flight (late).
    pub late: u64,
    /// Prefetched lines evicted before any demand use.
    pub useless: u64,
    /// Prefetched lines never used by the end of the run.
    pub unused_at_end: u64,
    /// useful / misses.
    pub accuracy: f64,
    /// late / useful.
    pub late_share: f64,
    /// Most requests one core's queue held at once (for the oracle: its
    /// longest list).
    pub longest_queue: u64,
}

impl PrefetchReport {
    /// The report of `cfg`'s prefetcher, or `None` without one.
    pub fn of(cfg: &MachineConfig, s: &PrefetchStats) -> Option<Self> {
        if !cfg.prefetch.enabled() {
            return None;
        }
        let q = &s.queue;
        let l = &s.lines;
        let ratio = |a: u64, b: u64| if b == 0 { 0.0 } else { a as f64 / b as f64 };
        Some(PrefetchReport {
            kind: cfg.prefetch.kind.to_string(),
            queue: cfg.prefetch.queue,
            queue_filter: cfg.prefetch.queue_filter,
            l1_reserve: cfg.prefetch.l1_reserve,
            generated: q.generated,
            duplicates: q.duplicates,
            dropped: q.dropped,
            cancelled: q.cancelled,
            issued: q.issued,
            hits: q.hits,
            pending: q.pending,
            misses: q.misses,
            reserve_waits: q.reserve_waits,
            useful: l.useful,
            late: l.late,
            useless: l.useless,
            unused_at_end: s.unused_at_end,
            accuracy: ratio(l.useful, q.misses),
            late_share: ratio(l.late, l.useful),
            longest_queue: q.max_len,
        })
    }

    /// Two lines of the run table.
    pub fn table_lines(&self, s: &mut String) {
        let _ = writeln!(
            s,
            "prefetch {} (queue {}{}, L1 reserve {}): {} generated, {} duplicates, {} dropped (queue full), {} cancelled, longest queue {}",
            self.kind,
            self.queue,
            if self.queue_filter { " filtered" } else { "" },
            self.l1_reserve,
            self.generated,
            self.duplicates,
            self.dropped,
            self.cancelled,
            self.longest_queue
        );
        let _ = writeln!(
            s,
            "prefetch L1 lookups {}: {} hits, {} pending, {} misses ({} reserve waits); useful {} ({:.1}% of misses, {} late), useless {}, unused at end {}",
            self.issued,
            self.hits,
            self.pending,
            self.misses,
            self.reserve_waits,
            self.useful,
            100.0 * self.accuracy,
            self.late,
            self.useless,
            self.unused_at_end
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mem::{PrefetchKind, PrefetchStats};

    #[test]
    fn absent_without_a_prefetcher_and_ratios_from_the_counts() {
        let mut cfg = MachineConfig::paper();
        let mut s = PrefetchStats::default();
        assert!(PrefetchReport::of(&cfg, &s).is_none());
        cfg.prefetch.kind = PrefetchKind::Raster;
        s.queue.misses = 8;
        s.lines.useful = 6;
        s.lines.late = 3;
        let r = PrefetchReport::of(&cfg, &s).unwrap();
        assert_eq!(r.kind, "raster");
        assert_eq!((r.accuracy, r.late_share), (0.75, 0.5));
        let mut t = String::new();
        r.table_lines(&mut t);
        assert!(t.contains("prefetch raster (queue 32 filtered, L1 reserve 4)"));
        assert!(t.contains("useful 6 (75.0% of misses, 3 late)"));
    }
}
