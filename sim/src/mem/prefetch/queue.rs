//! One core's prefetch queue: block addresses waiting for a free L1 port
//! and an L1 MSHR above the demand reserve.
//!
//! A request offered to a full queue is dropped; with the filter on, a
//! request for a block already queued is skipped (a compare against every
//! entry, as a small hardware queue's CAM does). Each cycle, after the
//! cycle's demand lookups, [`PrefetchQueue::issue`] presents the head to
//! the L1 while the L1 takes it: a hit or a pending miss drops the head,
//! a miss allocates an MSHR entry and sends the block below, and a busy
//! port or MSHRs at the reserve leave it for a later cycle (in order: the
//! head blocks the queue, like the L1's own request queue).

use super::PrefetchLookup;
use serde::{Deserialize, Serialize};
use std::collections::VecDeque;

/// What a queue did, summed over a run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct QueueCounts {
    /// Requests the prefetcher generated (offered or listed).
    pub generated: u64,
    /// Of them, skipped because the block was already queued.
    pub duplicates: u64,
    /// Of them, dropped because the queue was full.
    pub dropped: u64,
    /// Queued requests discarded unissued when the next tile's list
    /// replaced them (the oracle).
    pub cancelled: u64,
    /// Requests looked up in the L1.
    pub issued: u64,
    /// Of them, found their line present (dropped at the L1).
    pub hits: u64,
    /// Of them, found a miss already pending for the block (dropped at the
    /// L1).
    pub pending: u64,
    /// Of them, missed: an L1 MSHR entry, a request to the L2.
    pub misses: u64,
    /// Cycles the head waited because at most `l1_reserve` L1 MSHRs were
    /// free.
    pub reserve_waits: u64,
    /// Most requests queued at once.
    pub max_len: u64,
}

impl QueueCounts {
    /// Add `o` into `self` (`max_len`: the larger).
    pub fn add(&mut self, o: &QueueCounts) {
        self.generated += o.generated;
        self.duplicates += o.duplicates;
        self.dropped += o.dropped;
        self.cancelled += o.cancelled;
        self.issued += o.issued;
        self.hits += o.hits;
        self.pending += o.pending;
        self.misses += o.misses;
        self.reserve_waits += o.reserve_waits;
        self.max_len = self.max_len.max(o.max_len);
    }

    /// The counts since `before` (an earlier reading of the same queue);
    /// `max_len` is this reading's (restarted when `before` was taken).
    pub fn since(&self, before: &QueueCounts) -> QueueCounts {
        QueueCounts {
            generated: self.generated - before.generated,
            duplicates: self.duplicates - before.duplicates,
            dropped: self.dropped - before.dropped,
            cancelled: self.cancelled - before.cancelled,
            issued: self.issued - before.issued,
            hits: self.hits - before.hits,
            pending: self.pending - before.pending,
            misses: self.misses - before.misses,
            reserve_waits: self.reserve_waits - before.reserve_waits,
            max_len: self.max_len,
        }
    }
}

/// One core's prefetch queue.
#[derive(Clone, Debug, Default)]
pub struct PrefetchQueue {
    q: VecDeque<u64>,
    /// Entries [`offer`](Self::offer) may fill.
    capacity: usize,
    /// Skip a block already queued.
    filter: bool,
    counts: QueueCounts,
}

impl PrefetchQueue {
    /// Restart the `max_len` counter at the entries queued now (a frame
    /// begins).
    pub fn restart_max_len(&mut self) {
        self.counts.max_len = self.q.len() as u64;
    }

    /// An empty queue of `capacity` entries (allocated now), skipping
    /// blocks already queued when `filter` holds.
    pub fn new(capacity: usize, filter: bool) -> Self {
        PrefetchQueue {
            q: VecDeque::with_capacity(capacity),
            capacity,
            filter,
            counts: QueueCounts::default(),
        }
    }

    /// Make room for lists of up to `n` requests
    /// ([`replace`](Self::replace)) without allocating later.
    pub fn reserve(&mut self, n: usize) {
        self.q.reserve(n.saturating_sub(self.q.len()));
    }

    /// Nothing queued.
    #[inline(always)]
    pub fn is_empty(&self) -> bool {
        self.q.is_empty()
    }

    /// Requests queued.
    pub fn len(&self) -> usize {
        self.q.len()
    }

    /// The counters so far.
    pub fn counts(&self) -> &QueueCounts {
        &self.counts
    }

    /// Offer a request for `block` (the raster prefetcher): queued,
    /// skipped as a duplicate, or dropped when the queue is full.
    pub fn offer(&mut self, block: u64) {
        self.counts.generated += 1;
        if self.filter && self.q.contains(&block) {
            self.counts.duplicates += 1;
        } else if self.q.len() >= self.capacity {
            self.counts.dropped += 1;
        } else {
            self.q.push_back(block);
            self.counts.max_len = self.counts.max_len.max(self.q.len() as u64);
        }
    }

    /// Replace what is queued by `list`, in order, whatever its length
    /// (the oracle's list for a tile; what it replaces is counted
    /// cancelled).
    pub fn replace(&mut self, list: &[u64]) {
        self.counts.cancelled += self.q.len() as u64;
        self.counts.generated += list.len() as u64;
        self.q.clear();
        self.q.extend(list.iter().copied());
        self.counts.max_len = self.counts.max_len.max(self.q.len() as u64);
    }

    /// Cycle `now`'s prefetch lookups, after the cycle's demand lookups:
    /// present the head to the L1 through `lookup` until the L1 takes no
    /// more (a busy port, or MSHRs at the reserve) or the queue is empty.
    /// Each miss's block and MSHR entry go to `send`.
    #[inline]
    pub fn issue(
        &mut self,
        mut lookup: impl FnMut(u64) -> PrefetchLookup,
        mut send: impl FnMut(u64, u32),
    ) {
        while let Some(&block) = self.q.front() {
            match lookup(block) {
                PrefetchLookup::PortBusy => return,
                PrefetchLookup::NoRoom => {
                    self.counts.reserve_waits += 1;
                    return;
                }
                PrefetchLookup::Hit => self.counts.hits += 1,
                PrefetchLookup::Pending => self.counts.pending += 1,
                PrefetchLookup::Miss(entry) => {
                    self.counts.misses += 1;
                    send(block, entry);
                }
            }
            self.counts.issued += 1;
            self.q.pop_front();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mem::cache::tests::cfg;
    use crate::mem::cache::{Cache, Lookup};

    #[test]
    fn a_full_queue_drops_and_counts() {
        let mut q = PrefetchQueue::new(3, false);
        for b in [1, 2, 3, 4, 5] {
            q.offer(b);
        }
        assert_eq!(q.len(), 3);
        let c = q.counts();
        assert_eq!(
            (c.generated, c.dropped, c.duplicates, c.max_len),
            (5, 2, 0, 3)
        );
        // Without the filter a repeat takes an entry of its own.
        let mut q = PrefetchQueue::new(3, false);
        q.offer(7);
        q.offer(7);
        assert_eq!(q.len(), 2);
    }

    #[test]
    fn the_filter_skips_blocks_already_queued_only() {
        let mut q = PrefetchQueue::new(4, true);
        for b in [1, 2, 1, 3, 2, 4, 5, 1] {
            q.offer(b);
        }
        // 1 2 3 4 queued; the repeats of 1 (twice) and 2 skipped; 5
        // dropped.
        let c = *q.counts();
        assert_eq!((c.generated, c.duplicates, c.dropped), (8, 3, 1));
        assert_eq!(q.q.iter().copied().collect::<Vec<_>>(), vec![1, 2, 3, 4]);
        // Once issued, a block may be queued again.
        q.issue(|_| PrefetchLookup::Hit, |_, _| {});
        q.offer(1);
        assert_eq!(q.len(), 1);
    }

    #[test]
    fn replace_keeps_the_order_and_cancels_what_was_left() {
        let mut q = PrefetchQueue::new(0, false);
        q.reserve(8);
        q.replace(&[9, 4, 6]);
        let mut seen = Vec::new();
        let mut n = 0;
        q.issue(
            |b| {
                seen.push(b);
                n += 1;
                if n == 2 {
                    PrefetchLookup::PortBusy
                } else {
                    PrefetchLookup::Miss(0)
                }
            },
            |_, _| {},
        );
        assert_eq!(seen, vec![9, 4]);
        q.replace(&[1, 2, 3, 5, 8, 13]);
        let c = q.counts();
        assert_eq!((c.generated, c.cancelled, c.issued, c.misses), (9, 2, 1, 1));
        assert_eq!(c.max_len, 6);
    }

    /// Through a real L1 of one port: demand takes the port first; the
    /// prefetch goes on a free port only, at most one per free port; a
    /// hit and a pending miss drop it; MSHRs at the reserve hold it back
    /// without a lookup.
    #[test]
    fn prefetches_use_ports_demand_left_and_honour_the_reserve() {
        let mut l1 = Cache::new(&cfg(4096, 4, 4, 4, 1)).unwrap();
        l1.enable_prefetch_marks();
        let mut q = PrefetchQueue::new(8, true);
        for b in [10, 11, 12, 13] {
            q.offer(b);
        }
        let mut sent = Vec::new();
        let reserve = 2;
        // Cycle 1: a demand access takes the one port.
        assert_eq!(l1.access(1, 50, 0), Lookup::Miss);
        q.issue(|b| l1.prefetch(1, b, reserve), |b, e| sent.push((b, e)));
        assert!(sent.is_empty() && q.len() == 4);
        // Cycle 2: the port is free: one prefetch, then the port is busy.
        q.issue(|b| l1.prefetch(2, b, reserve), |b, e| sent.push((b, e)));
        assert_eq!(sent.len(), 1);
        assert_eq!(sent[0].0, 10);
        // Cycle 3: 4 MSHRs, 2 occupied (50, 10): 2 free is the reserve.
        q.issue(|b| l1.prefetch(3, b, reserve), |b, e| sent.push((b, e)));
        assert_eq!((sent.len(), q.counts().reserve_waits), (1, 1));
        // The waiting prefetch used no port: a demand access still can.
        assert_eq!(l1.access(3, 60, 1), Lookup::Miss);
        // Block 10 arrives; its entry frees at 6. Block 11 is demanded
        // meanwhile (pending when the prefetch comes).
        l1.fill(4, 10);
        l1.fill(4, 50);
        assert_eq!(l1.access(5, 11, 2), Lookup::Miss);
        q.issue(|b| l1.prefetch(6, b, reserve), |b, e| sent.push((b, e)));
        // 60 and 11 pending: 2 free again, still the reserve.
        assert_eq!(sent.len(), 1);
        l1.fill(7, 60);
        q.issue(|b| l1.prefetch(9, b, reserve), |b, e| sent.push((b, e)));
        // 11 pending: dropped (one port: that was the cycle's lookup).
        let c = *q.counts();
        assert_eq!((c.pending, c.misses, q.len()), (1, 1, 2));
        q.issue(|b| l1.prefetch(10, b, reserve), |b, e| sent.push((b, e)));
        assert_eq!(sent.last().unwrap().0, 12);
        l1.fill(10, 11);
        l1.fill(10, 12);
        // A prefetch of a present line is dropped at the L1.
        q.offer(10);
        q.issue(|b| l1.prefetch(12, b, reserve), |b, e| sent.push((b, e)));
        assert_eq!(sent.last().unwrap().0, 13);
        q.issue(|b| l1.prefetch(13, b, reserve), |b, e| sent.push((b, e)));
        let c = *q.counts();
        assert_eq!((c.hits, c.pending, c.misses, c.issued), (1, 1, 3, 5));
        assert_eq!(c.reserve_waits, 2);
        assert!(q.is_empty());
    }
}
