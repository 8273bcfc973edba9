//! The `prefetch` block of a run's statistics: the prefetcher, its limits
//! and what became of its requests (present only when the machine has a
//! prefetcher, so that the shipped machine's output is unchanged).

use crate::config::MachineConfig;
use crate::mem::prefetch::QueueCounts;
use crate::mem::PrefetchStats;
use serde::ser::{Serialize, SerializeStruct, Serializer};
use std::fmt::Write as _;

/// A run's prefetches, summed over the cores.
///
/// Its JSON is flat, in the order the fields are listed here, with the
/// queues' counts in place of `counts` (but `max_len`, which comes last as
/// `longest_queue`).
#[derive(Clone, Debug, PartialEq)]
pub struct PrefetchReport {
    /// `oracle-tile` or `raster`.
    pub kind: String,
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

impl Serialize for PrefetchReport {
    fn serialize<S: Serializer>(&self, ser: S) -> Result<S::Ok, S::Error> {
        let q = &self.counts;
        let mut m = ser.serialize_struct("PrefetchReport", 20)?;
        m.serialize_field("kind", &self.kind)?;
        m.serialize_field("queue", &self.queue)?;
        m.serialize_field("queue_filter", &self.queue_filter)?;
        m.serialize_field("l1_reserve", &self.l1_reserve)?;
        for (name, v) in [
            ("generated", q.generated),
            ("duplicates", q.duplicates),
            ("dropped", q.dropped),
            ("cancelled", q.cancelled),
            ("issued", q.issued),
            ("hits", q.hits),
            ("pending", q.pending),
            ("misses", q.misses),
            ("reserve_waits", q.reserve_waits),
            ("useful", self.useful),
            ("late", self.late),
            ("useless", self.useless),
            ("unused_at_end", self.unused_at_end),
        ] {
            m.serialize_field(name, &v)?;
        }
        m.serialize_field("accuracy", &self.accuracy)?;
        m.serialize_field("late_share", &self.late_share)?;
        m.serialize_field("longest_queue", &q.max_len)?;
        m.end()
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
            kind: cfg.prefetch.kind.to_string(),
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
        assert_eq!(r.kind, "raster");
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
    }
}
