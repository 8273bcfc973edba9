//! The `prefetch` block of a run's statistics: the prefetcher, its limits
//! and what became of its requests (present only when the machine has a
//! prefetcher, so that the shipped machine's output is unchanged).

use crate::config::MachineConfig;
use crate::mem::prefetch::QueueCounts;
use crate::mem::PrefetchKind;
use crate::mem::PrefetchStats;
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;

/// A run's prefetches, summed over the cores.
///
/// Its JSON is flat, in the order the fields are listed here, with the
/// queues' counts in place of `counts` (but `max_len`, which comes last as
/// `longest_queue`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(into = "FlatReport", from = "FlatReport")]
pub struct PrefetchReport {
    /// `oracle-tile` or `raster`.
    pub kind: PrefetchKind,
    /// Entries of the raster prefetcher's queue per core.
    pub queue: u32,
    /// The queue skips blocks already queued.
    pub queue_filter: bool,
    /// L1 MSHRs kept free for demand.
    pub l1_reserve: u32,
    /// What the queues did: requests generated, skipped as duplicates,
    /// dropped (queue full), cancelled (the oracle's next tile), looked up
    /// in the L1 and what the L1 found, reserve waits, and the most
    /// requests one core's queue held at once (for the oracle: its longest
    /// list).
    pub counts: QueueCounts,
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
}

/// [`PrefetchReport`] as its JSON writes it: flat, the queues' counts in
/// place of `counts`, the longest queue last.
#[derive(Serialize, Deserialize)]
struct FlatReport {
    kind: PrefetchKind,
    queue: u32,
    queue_filter: bool,
    l1_reserve: u32,
    generated: u64,
    duplicates: u64,
    dropped: u64,
    cancelled: u64,
    issued: u64,
    hits: u64,
    pending: u64,
    misses: u64,
    reserve_waits: u64,
    useful: u64,
    late: u64,
    useless: u64,
    unused_at_end: u64,
    accuracy: f64,
    late_share: f64,
    longest_queue: u64,
}

impl From<PrefetchReport> for FlatReport {
    fn from(r: PrefetchReport) -> Self {
        let q = r.counts;
        FlatReport {
            kind: r.kind,
            queue: r.queue,
            queue_filter: r.queue_filter,
            l1_reserve: r.l1_reserve,
            generated: q.generated,
            duplicates: q.duplicates,
            dropped: q.dropped,
            cancelled: q.cancelled,
            issued: q.issued,
            hits: q.hits,
            pending: q.pending,
            misses: q.misses,
            reserve_waits: q.reserve_waits,
            useful: r.useful,
            late: r.late,
            useless: r.useless,
            unused_at_end: r.unused_at_end,
            accuracy: r.accuracy,
            late_share: r.late_share,
            longest_queue: q.max_len,
        }
    }
}

impl From<FlatReport> for PrefetchReport {
    fn from(f: FlatReport) -> Self {
        PrefetchReport {
            kind: f.kind,
            queue: f.queue,
            queue_filter: f.queue_filter,
            l1_reserve: f.l1_reserve,
            counts: QueueCounts {
                generated: f.generated,
                duplicates: f.duplicates,
                dropped: f.dropped,
                cancelled: f.cancelled,
                issued: f.issued,
                hits: f.hits,
                pending: f.pending,
                misses: f.misses,
                reserve_waits: f.reserve_waits,
                max_len: f.longest_queue,
            },
            useful: f.useful,
            late: f.late,
            useless: f.useless,
            unused_at_end: f.unused_at_end,
            accuracy: f.accuracy,
            late_share: f.late_share,
        }
    }
}

impl PrefetchReport {
    /// The report of `cfg`'s prefetcher, or `None` without one.
    pub fn of(cfg: &MachineConfig, s: &PrefetchStats) -> Option<Self> {
        if !cfg.prefetch.enabled() {
            return None;
        }
        let l = &s.lines;
        let ratio = |a: u64, b: u64| if b == 0 { 0.0 } else { a as f64 / b as f64 };
        Some(PrefetchReport {
            kind: cfg.prefetch.kind,
            queue: cfg.prefetch.queue,
            queue_filter: cfg.prefetch.queue_filter,
            l1_reserve: cfg.prefetch.l1_reserve,
            counts: s.queue,
            useful: l.useful,
            late: l.late,
            useless: l.useless,
            unused_at_end: s.unused_at_end,
            accuracy: ratio(l.useful, s.queue.misses),
            late_share: ratio(l.late, l.useful),
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
            self.counts.generated,
            self.counts.duplicates,
            self.counts.dropped,
            self.counts.cancelled,
            self.counts.max_len
        );
        let _ = writeln!(
            s,
            "prefetch L1 lookups {}: {} hits, {} pending, {} misses ({} reserve waits); useful {} ({:.1}% of misses, {} late), useless {}, unused at end {}",
            self.counts.issued,
            self.counts.hits,
            self.counts.pending,
            self.counts.misses,
            self.counts.reserve_waits,
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
        assert_eq!(r.kind, PrefetchKind::Raster);
        assert_eq!((r.accuracy, r.late_share), (0.75, 0.5));
        let mut t = String::new();
        r.table_lines(&mut t);
        assert!(t.contains("prefetch raster (queue 32 filtered, L1 reserve 4)"));
        assert!(t.contains("useful 6 (75.0% of misses, 3 late)"));
    }

    #[test]
    fn json_is_flat_with_the_longest_queue_last() {
        let mut cfg = MachineConfig::paper();
        cfg.prefetch.kind = PrefetchKind::Raster;
        let mut s = PrefetchStats::default();
        s.queue.generated = 9;
        s.queue.max_len = 5;
        let r = PrefetchReport::of(&cfg, &s).unwrap();
        assert_eq!(
            serde_json::to_string(&r).unwrap(),
            "{\"kind\":\"raster\",\"queue\":32,\"queue_filter\":true,\"l1_reserve\":4,\
             \"generated\":9,\"duplicates\":0,\"dropped\":0,\"cancelled\":0,\"issued\":0,\
             \"hits\":0,\"pending\":0,\"misses\":0,\"reserve_waits\":0,\"useful\":0,\
             \"late\":0,\"useless\":0,\"unused_at_end\":0,\"accuracy\":0.0,\
             \"late_share\":0.0,\"longest_queue\":5}"
        );
        let text = serde_json::to_string(&r).unwrap();
        assert_eq!(serde_json::from_str::<PrefetchReport>(&text).unwrap(), r);
    }
}
