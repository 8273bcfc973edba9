//! The MSHR file of one cache: a small array of entries, each tracking one
//! outstanding primary miss (its block) and the targets waiting for it.
//!
//! Life of an entry: free -> *pending* (allocated by a primary miss; secondary
//! misses merge their targets into it) -> *held* (its reply arrived in cycle
//! `r`; the targets are delivered at `r`, the entry stays occupied through
//! `r + 1`) -> free again from cycle `r + 2`.
//!
//! Storage is flat and preallocated: no allocation after construction.
//! Lookups are linear searches over the pending entries (a handful to a few
//! dozen, like the CAM of a hardware MSHR file).

use std::collections::VecDeque;

/// Cycles an entry stays occupied after the cycle of its reply.
pub const MSHR_HOLD_CYCLES: u64 = 1;

/// One MSHR file.
#[derive(Debug, Clone)]
pub struct MshrFile {
    capacity: u32,
    /// Targets per entry: the primary miss plus `max_merged` secondary ones.
    slots: u32,
    /// Block of each entry (meaningful while pending or held).
    block: Vec<u64>,
    /// Targets recorded in each entry.
    count: Vec<u32>,
    /// `capacity * slots` target values (their meaning belongs to the cache's
    /// owner: a core's tag, a core number, ...).
    targets: Vec<u32>,
    /// Cycle each target was accepted, parallel to `targets`.
    issued: Vec<u64>,
    /// Sum of the acceptance cycles of each entry's targets.
    issued_sum: Vec<u64>,
    /// Pending entries as `(block, entry)`, unordered (swap-removed on fill).
    pending: Vec<(u64, u32)>,
    /// Free entries, used as a stack (deterministic reuse order).
    free: Vec<u32>,
    /// Held entries as `(first cycle free, entry)`, in fill order, hence sorted.
    held: VecDeque<(u64, u32)>,
}

/// Result of trying to merge a secondary miss.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Merge {
    /// Merged into the pending entry for the block.
    Merged,
    /// A pending entry exists but its target list is full.
    Full,
    /// No entry is pending for the block.
    NotPending,
}

impl MshrFile {
    /// An empty file of `capacity` entries, each holding `1 + max_merged` targets.
    pub fn new(capacity: u32, max_merged: u32) -> Self {
        let slots = max_merged + 1;
        let n = capacity as usize;
        MshrFile {
            capacity,
            slots,
            block: vec![0; n],
            count: vec![0; n],
            targets: vec![0; n * slots as usize],
            issued: vec![0; n * slots as usize],
            issued_sum: vec![0; n],
            pending: Vec::with_capacity(n),
            free: (0..capacity).rev().collect(),
            held: VecDeque::with_capacity(n),
        }
    }

    /// Free every held entry whose hold has ended by cycle `now`.
    #[inline]
    pub fn release(&mut self, now: u64) {
        while let Some(&(at, e)) = self.held.front() {
            if at > now {
                break;
            }
            self.held.pop_front();
            self.free.push(e);
        }
    }

    /// Number of entries.
    #[inline]
    pub fn capacity(&self) -> u32 {
        self.capacity
    }

    /// Entries occupied (pending or held).
    #[inline]
    pub fn occupied(&self) -> u32 {
        self.capacity - self.free.len() as u32
    }

    /// Entries awaiting their reply.
    #[inline]
    pub fn outstanding(&self) -> u32 {
        self.pending.len() as u32
    }

    /// No entry can be allocated.
    #[inline]
    pub fn is_full(&self) -> bool {
        self.free.is_empty()
    }

    /// Whether an entry is pending for `block`.
    #[inline]
    pub fn is_pending(&self, block: u64) -> bool {
        self.pending.iter().any(|&(b, _)| b == block)
    }

    /// Add a secondary-miss target to the pending entry of `block`, if any.
    #[inline]
    pub fn merge(&mut self, block: u64, target: u32, now: u64) -> Merge {
        let Some(&(_, e)) = self.pending.iter().find(|&&(b, _)| b == block) else {
            return Merge::NotPending;
        };
        let e = e as usize;
        let n = self.count[e];
        if n >= self.slots {
            return Merge::Full;
        }
        let slot = e * self.slots as usize + n as usize;
        self.targets[slot] = target;
        self.issued[slot] = now;
        self.issued_sum[e] += now;
        self.count[e] = n + 1;
        Merge::Merged
    }

    /// Allocate an entry for a primary miss on `block`. The caller has checked
    /// that the file is not full and no entry is pending for `block`.
    #[inline]
    pub fn allocate(&mut self, block: u64, target: u32, now: u64) {
        debug_assert!(!self.is_pending(block));
        let e = self.free.pop().expect("MSHR allocate on a full file");
        let i = e as usize;
        self.block[i] = block;
        self.count[i] = 1;
        let slot = i * self.slots as usize;
        self.targets[slot] = target;
        self.issued[slot] = now;
        self.issued_sum[i] = now;
        self.pending.push((block, e));
    }

    /// The reply for `block` arrived in cycle `now`: the entry becomes held
    /// until `now + MSHR_HOLD_CYCLES` (inclusive). Returns the entry, whose
    /// targets are then read with [`MshrFile::targets`], or `None` when no
    /// entry was pending for `block`.
    #[inline]
    pub fn complete(&mut self, block: u64, now: u64) -> Option<u32> {
        let pos = self.pending.iter().position(|&(b, _)| b == block)?;
        let (_, e) = self.pending.swap_remove(pos);
        debug_assert!(self
            .held
            .back()
            .map_or(true, |&(at, _)| at <= now + 1 + MSHR_HOLD_CYCLES));
        self.held.push_back((now + 1 + MSHR_HOLD_CYCLES, e));
        Some(e)
    }

    /// The targets of entry `e` and the cycles they were accepted, in
    /// acceptance order (primary first).
    #[inline]
    pub fn targets(&self, e: u32) -> (&[u32], &[u64]) {
        let i = e as usize;
        let start = i * self.slots as usize;
        let end = start + self.count[i] as usize;
        (&self.targets[start..end], &self.issued[start..end])
    }

    /// Sum over the targets of entry `e` of the cycles from their
    /// acceptance to `now` (not before any of them).
    #[inline]
    pub fn wait_sum(&self, e: u32, now: u64) -> u64 {
        let i = e as usize;
        u64::from(self.count[i]) * now - self.issued_sum[i]
    }

    /// Block of entry `e`.
    #[inline]
    pub fn block(&self, e: u32) -> u64 {
        self.block[e as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn allocate_merge_complete_release() {
        let mut m = MshrFile::new(2, 1);
        assert_eq!((m.occupied(), m.outstanding(), m.is_full()), (0, 0, false));
        m.allocate(10, 100, 1);
        assert!(m.is_pending(10));
        assert_eq!(m.merge(10, 101, 2), Merge::Merged);
        assert_eq!(m.merge(10, 102, 3), Merge::Full);
        assert_eq!(m.merge(11, 103, 3), Merge::NotPending);
        m.allocate(11, 104, 3);
        assert!(m.is_full());
        assert_eq!(m.outstanding(), 2);

        let e = m.complete(10, 8).unwrap();
        assert_eq!(m.block(e), 10);
        assert_eq!(m.targets(e), (&[100, 101][..], &[1, 2][..]));
        assert_eq!(m.wait_sum(e, 8), (8 - 1) + (8 - 2));
        assert!(!m.is_pending(10));
        assert_eq!((m.occupied(), m.outstanding()), (2, 1));
        // Held through cycle 9, free from 10.
        m.release(9);
        assert!(m.is_full());
        m.release(10);
        assert!(!m.is_full());
        assert_eq!(m.occupied(), 1);
        assert_eq!(m.complete(10, 11), None);
    }

    #[test]
    fn reuse_order_is_deterministic() {
        let run = || {
            let mut m = MshrFile::new(3, 0);
            let mut order = Vec::new();
            for (i, b) in [5u64, 6, 7].into_iter().enumerate() {
                m.allocate(b, i as u32, 0);
            }
            m.complete(6, 1);
            m.complete(5, 1);
            m.release(3);
            m.allocate(8, 9, 3);
            m.allocate(9, 9, 3);
            for b in [8, 9] {
                let e = m.complete(b, 4).unwrap();
                order.push(e);
            }
            order
        };
        assert_eq!(run(), run());
    }
}
