//! The MSHR file of one cache: a small array of entries, each tracking one
//! outstanding primary miss (its block) and the targets waiting for it.
//!
//! Life of an entry: free -> *pending* (allocated by a primary miss; secondary
//! misses merge their targets into it) -> *held* (its reply arrived in cycle
//! `r`; the targets are delivered at `r`, the entry stays occupied through
//! `r + 1`) -> free again from cycle `r + 2`.
//!
//! Storage is flat and preallocated: no allocation after construction.
//! Lookups by block are linear searches over the pending entries, kept dense
//! (a handful to a few dozen, like the CAM of a hardware MSHR file), behind a
//! counting filter: a block whose bucket has no pending entry is not pending,
//! without a search (most lookups of a large, busy file like the L2's find
//! nothing). An owner
//! that remembers the entry [`MshrFile::allocate`] returned completes it by
//! index, with no search. Entries not pending wait in one ring, free ones
//! first, then held ones in fill order: freeing a held entry moves no data.
//!
//! Occupancy integrals (entries occupied, entries outstanding, cycles full,
//! summed over cycles) are kept per event rather than per cycle: an entry
//! allocated in cycle `a` and filled in `r` is outstanding `r - a` cycles
//! (kept as sums of the `r` and the `a`) and occupied `1 + MSHR_HOLD_CYCLES`
//! more; a full period is added when it ends, at the first release.
//! [`MshrFile::integrals`] adds what is still running. A cycle's occupancy is
//! counted after all of that cycle's events (allocations, fills, releases),
//! as an owner sampling it at the end of every cycle would.

/// Cycles an entry stays occupied after the cycle of its reply.
pub const MSHR_HOLD_CYCLES: u64 = 1;

/// Buckets of the pending filter (a power of two).
const PENDING_BUCKETS: usize = 256;

/// Bucket of `block` in the pending filter.
#[inline(always)]
fn pending_bucket(block: u64) -> usize {
    block as usize & (PENDING_BUCKETS - 1)
}

/// Per-entry state.
#[derive(Debug, Clone, Copy, Default)]
struct Entry {
    /// Sum of the acceptance cycles of the entry's targets.
    issued_sum: u64,
    /// First cycle the entry is free again (meaningful while held).
    free_at: u64,
    /// Targets recorded.
    count: u32,
    /// Position in `pending` (meaningful while pending).
    pos: u32,
}

/// One MSHR file.
#[derive(Debug, Clone)]
pub struct MshrFile {
    capacity: u32,
    /// Targets per entry: the primary miss plus `max_merged` secondary ones.
    slots: u32,
    entries: Box<[Entry]>,
    /// `capacity * slots` target values (their meaning belongs to the cache's
    /// owner: a core's tag, an MSHR entry of the level above, a core number).
    targets: Box<[u32]>,
    /// The pending entries as `(block, entry)` in `pending[..outstanding]`,
    /// unordered (swap-removed on completion).
    pending: Box<[(u64, u32)]>,
    outstanding: u32,
    /// Per bucket of block numbers, the pending entries of the bucket.
    pending_filter: Box<[u32; PENDING_BUCKETS]>,
    /// Every entry not pending, in a ring of power-of-two length from
    /// `head`: first the `free` free entries (allocated from the front),
    /// then the `held` held ones in fill order, hence in `free_at` order (a
    /// completed entry joins the back; a released one just changes side).
    order: Box<[u32]>,
    head: u32,
    free: u32,
    held: u32,
    /// `free_at` of the oldest held entry, `u64::MAX` when none is held.
    next_release: u64,
    /// Sum of the allocation cycles of every entry allocated so far
    /// (wrapping, like `fill_sum`: only differences are used).
    alloc_sum: u64,
    /// Sum of the fill cycles of every entry filled so far.
    fill_sum: u64,
    /// Entries filled so far.
    filled: u64,
    /// Cycles full, over the full periods that have ended.
    full_cycles: u64,
    /// First cycle of the current full period (meaningful while full).
    full_since: u64,
}

/// Occupancy of an MSHR file summed over cycles, see [`MshrFile::integrals`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Integrals {
    /// Sum over cycles of the entries occupied (pending or held).
    pub occupied: u64,
    /// Sum over cycles of the entries awaiting their reply.
    pub outstanding: u64,
    /// Cycles with every entry occupied.
    pub full: u64,
}

/// Result of trying to merge a secondary miss.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Merge {
    /// Merged into the pending entry for the block (this entry).
    Merged(u32),
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
        let mut order = vec![0; n.next_power_of_two()];
        for (e, o) in order.iter_mut().take(n).enumerate() {
            *o = e as u32;
        }
        MshrFile {
            capacity,
            slots,
            entries: vec![Entry::default(); n].into(),
            targets: vec![0; n * slots as usize].into(),
            pending: vec![(0, 0); n].into(),
            outstanding: 0,
            pending_filter: Box::new([0; PENDING_BUCKETS]),
            order: order.into(),
            head: 0,
            free: capacity,
            held: 0,
            next_release: u64::MAX,
            alloc_sum: 0,
            fill_sum: 0,
            filled: 0,
            full_cycles: 0,
            full_since: 0,
        }
    }

    /// Index in `order` of the `k`-th entry from `head`.
    #[inline]
    fn ring(&self, k: u32) -> usize {
        (self.head + k) as usize & (self.order.len() - 1)
    }

    /// Free every held entry whose hold has ended by cycle `now`.
    #[inline]
    pub fn release(&mut self, now: u64) {
        if now >= self.next_release {
            self.release_due(now);
        }
    }

    fn release_due(&mut self, now: u64) {
        if self.free == 0 {
            // The full period ends with the first release, due at
            // `next_release`. (Saturating: a caller releasing late, after
            // allocating in a later cycle, must not wrap the count.)
            self.full_cycles += self.next_release.saturating_sub(self.full_since);
        }
        while self.held > 0 {
            let e = self.order[self.ring(self.free)];
            let at = self.entries[e as usize].free_at;
            if at > now {
                self.next_release = at;
                return;
            }
            self.free += 1;
            self.held -= 1;
        }
        self.next_release = u64::MAX;
    }

    /// Number of entries.
    #[inline]
    pub fn capacity(&self) -> u32 {
        self.capacity
    }

    /// Entries occupied (pending or held).
    #[inline]
    pub fn occupied(&self) -> u32 {
        self.capacity - self.free
    }

    /// Entries awaiting their reply.
    #[inline]
    pub fn outstanding(&self) -> u32 {
        self.outstanding
    }

    /// No entry can be allocated.
    #[inline]
    pub fn is_full(&self) -> bool {
        self.free == 0
    }

    /// Entries that can be allocated now (`capacity - occupied`).
    #[inline]
    pub fn free(&self) -> u32 {
        self.free
    }

    /// Position in `pending` of the entry pending for `block`, if any.
    #[inline(always)]
    fn position(&self, block: u64) -> Option<usize> {
        if self.pending_filter[pending_bucket(block)] == 0 {
            return None;
        }
        self.pending[..self.outstanding as usize]
            .iter()
            .position(|&(b, _)| b == block)
    }

    /// The pending entry for `block`, if any.
    #[inline]
    pub fn find(&self, block: u64) -> Option<u32> {
        self.position(block).map(|p| self.pending[p].1)
    }

    /// Whether an entry is pending for `block`.
    #[inline]
    pub fn is_pending(&self, block: u64) -> bool {
        self.position(block).is_some()
    }

    /// Block of pending entry `e`.
    #[inline]
    pub fn block(&self, e: u32) -> u64 {
        let (block, entry) = self.pending[self.entries[e as usize].pos as usize];
        debug_assert_eq!(entry, e, "entry {e} is not pending");
        block
    }

    /// Add a secondary-miss target to the pending entry of `block`, if any.
    #[inline(always)]
    pub fn merge(&mut self, block: u64, target: u32, now: u64) -> Merge {
        let Some(p) = self.position(block) else {
            return Merge::NotPending;
        };
        let e = self.pending[p].1 as usize;
        let entry = &mut self.entries[e];
        let n = entry.count;
        if n >= self.slots {
            return Merge::Full;
        }
        entry.count = n + 1;
        entry.issued_sum += now;
        self.targets[e * self.slots as usize + n as usize] = target;
        Merge::Merged(e as u32)
    }

    /// Allocate an entry for a primary miss on `block` and return it. The
    /// caller has checked that the file is not full and no entry is pending
    /// for `block`.
    #[inline(always)]
    pub fn allocate(&mut self, block: u64, target: u32, now: u64) -> u32 {
        debug_assert!(!self.is_pending(block));
        assert!(self.free > 0, "MSHR allocate on a full file");
        let e = self.order[self.ring(0)];
        self.head = (self.head + 1) & (self.order.len() as u32 - 1);
        self.free -= 1;
        if self.free == 0 {
            self.full_since = now;
        }
        let pos = self.outstanding;
        // (`free_at` is set when the entry is filled.)
        let entry = &mut self.entries[e as usize];
        entry.issued_sum = now;
        entry.count = 1;
        entry.pos = pos;
        self.targets[e as usize * self.slots as usize] = target;
        self.pending[pos as usize] = (block, e);
        self.outstanding = pos + 1;
        self.pending_filter[pending_bucket(block)] += 1;
        self.alloc_sum = self.alloc_sum.wrapping_add(now);
        e
    }

    /// Allocate an entry with no target for a prefetch of `block` (see
    /// `mem/prefetch`): its fill completes nothing, and a later miss to
    /// `block` merges into it as the first target. The caller has checked
    /// that the file is not full and no entry is pending for `block`.
    pub fn allocate_untargeted(&mut self, block: u64, now: u64) -> u32 {
        let e = self.allocate(block, 0, now);
        let entry = &mut self.entries[e as usize];
        entry.count = 0;
        entry.issued_sum = 0;
        e
    }

    /// The reply for pending entry `e` arrived in cycle `now`: the entry
    /// becomes held until `now + MSHR_HOLD_CYCLES` (inclusive). Returns its
    /// block; its targets are then read with [`MshrFile::targets`]. Replies
    /// must come in cycle order.
    #[inline(always)]
    pub fn complete(&mut self, e: u32, now: u64) -> u64 {
        let free_at = now + 1 + MSHR_HOLD_CYCLES;
        let entry = &mut self.entries[e as usize];
        let pos = entry.pos as usize;
        entry.free_at = free_at;
        self.fill_sum = self.fill_sum.wrapping_add(now);
        self.filled += 1;
        let (block, pe) = self.pending[pos];
        debug_assert_eq!(pe, e, "entry {e} is not pending");
        self.pending_filter[pending_bucket(block)] -= 1;
        // Swap-remove position `pos` of the pending list.
        self.outstanding -= 1;
        let last = self.pending[self.outstanding as usize];
        self.pending[pos] = last;
        self.entries[last.1 as usize].pos = pos as u32;
        // Join the held entries at the back of the ring.
        let back = self.ring(self.free + self.held);
        self.order[back] = e;
        if self.held == 0 {
            self.next_release = free_at;
        }
        self.held += 1;
        block
    }

    /// The targets of entry `e`, in acceptance order (primary first).
    #[inline]
    pub fn targets(&self, e: u32) -> &[u32] {
        let start = e as usize * self.slots as usize;
        &self.targets[start..start + self.entries[e as usize].count as usize]
    }

    /// Sum over the targets of entry `e` of the cycles from their
    /// acceptance to `now` (not before any of them).
    #[inline]
    pub fn wait_sum(&self, e: u32, now: u64) -> u64 {
        let entry = &self.entries[e as usize];
        u64::from(entry.count) * now - entry.issued_sum
    }

    /// Occupancy summed over the cycles before `end`, each cycle counted
    /// after its events. `end` must not be before the cycle of any call made
    /// so far but may be before allocations of cycle `end` itself (which
    /// then add nothing); cycles before `end` not given to any call count
    /// the occupancy left by the last call before them.
    pub fn integrals(&self, end: u64) -> Integrals {
        // Outstanding: `r - a` per filled entry, `end - a` per pending one.
        let outstanding = self
            .fill_sum
            .wrapping_add(u64::from(self.outstanding).wrapping_mul(end))
            .wrapping_sub(self.alloc_sum);
        // Occupied beyond that: the hold of every filled entry, the part
        // before `end` for those still held (the file is freed lazily, so
        // some of them may be due already).
        let hold = 1 + MSHR_HOLD_CYCLES;
        let mut occupied = outstanding + (self.filled - u64::from(self.held)) * hold;
        for k in self.free..self.free + self.held {
            let free_at = self.entries[self.order[self.ring(k)] as usize].free_at;
            occupied += hold - free_at.saturating_sub(end).min(hold);
        }
        let mut full = self.full_cycles;
        if self.free == 0 {
            full += self.next_release.min(end).saturating_sub(self.full_since);
        }
        Integrals {
            occupied,
            outstanding,
            full,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn allocate_merge_complete_release() {
        let mut m = MshrFile::new(2, 1);
        assert_eq!((m.occupied(), m.outstanding(), m.is_full()), (0, 0, false));
        let a = m.allocate(10, 100, 1);
        assert!(m.is_pending(10));
        assert_eq!(m.find(10), Some(a));
        assert_eq!(m.merge(10, 101, 2), Merge::Merged(a));
        assert_eq!(m.merge(10, 102, 3), Merge::Full);
        assert_eq!(m.merge(11, 103, 3), Merge::NotPending);
        let b = m.allocate(11, 104, 3);
        assert_ne!(a, b);
        assert!(m.is_full());
        assert_eq!(m.outstanding(), 2);

        assert_eq!(m.complete(a, 8), 10);
        assert_eq!(m.targets(a), &[100, 101]);
        assert_eq!(m.wait_sum(a, 8), (8 - 1) + (8 - 2));
        assert!(!m.is_pending(10));
        assert_eq!(m.find(11), Some(b));
        assert_eq!((m.occupied(), m.outstanding()), (2, 1));
        // Held through cycle 9, free from 10.
        m.release(9);
        assert!(m.is_full());
        m.release(10);
        assert!(!m.is_full());
        assert_eq!(m.occupied(), 1);
        assert_eq!(m.find(10), None);
    }

    #[test]
    fn completing_out_of_order_keeps_every_other_entry_findable() {
        let mut m = MshrFile::new(4, 0);
        let e: Vec<u32> = [5u64, 6, 7, 8]
            .iter()
            .map(|&b| m.allocate(b, b as u32, 0))
            .collect();
        assert_eq!(m.complete(e[1], 1), 6);
        assert_eq!(m.complete(e[0], 1), 5);
        assert_eq!((m.find(7), m.find(8)), (Some(e[2]), Some(e[3])));
        assert_eq!((m.find(5), m.find(6)), (None, None));
        // The held ring wraps: free two, allocate two, complete all.
        m.release(3);
        assert_eq!(m.occupied(), 2);
        let f = m.allocate(9, 9, 3);
        let g = m.allocate(10, 10, 3);
        for (x, b) in [(e[3], 8), (f, 9), (e[2], 7), (g, 10)] {
            assert_eq!(m.complete(x, 4), b);
            assert_eq!(m.targets(x), &[b as u32]);
        }
        assert_eq!((m.outstanding(), m.occupied()), (0, 4));
        m.release(5);
        assert!(m.is_full());
        m.release(6);
        assert_eq!(m.occupied(), 0);
    }

    #[test]
    fn blocks_sharing_a_filter_bucket_are_told_apart() {
        let n = PENDING_BUCKETS as u64;
        let mut m = MshrFile::new(3, 1);
        assert_eq!(pending_bucket(3), pending_bucket(3 + n));
        let a = m.allocate(3, 30, 0);
        assert_eq!((m.find(3), m.find(3 + n)), (Some(a), None));
        assert_eq!(m.merge(3 + n, 31, 0), Merge::NotPending);
        let b = m.allocate(3 + n, 32, 0);
        assert_eq!(m.merge(3 + n, 33, 0), Merge::Merged(b));
        assert_eq!(m.complete(a, 1), 3);
        // The bucket still counts block 3 + n, and only it.
        assert_eq!((m.find(3), m.find(3 + n)), (None, Some(b)));
        assert_eq!(m.merge(3, 34, 1), Merge::NotPending);
        assert_eq!(m.complete(b, 2), 3 + n);
        assert_eq!(m.targets(b), &[32, 33]);
        assert!(!m.is_pending(3) && !m.is_pending(3 + n));
        // A block is pending again after its entry was filled.
        let c = m.allocate(3, 35, 2);
        assert_eq!(m.find(3), Some(c));
    }

    /// The per-event integrals equal sampling every cycle after its events,
    /// at every cycle, on a random script (releases lazily late too).
    #[test]
    fn integrals_match_per_cycle_sampling() {
        let mut rng = crate::rng::Rng::new(0x9e37_79b9);
        let mut rnd = |n: u32| rng.below(u64::from(n)) as u32;
        let mut m = MshrFile::new(4, 2);
        let mut pending: Vec<u32> = Vec::new();
        let mut sampled = Integrals::default();
        let mut next_block = 0;
        for now in 1..3000u64 {
            // Sometimes the file is not touched in a cycle at all.
            if rnd(4) != 0 {
                m.release(now);
                for _ in 0..rnd(3) {
                    if !m.is_full() {
                        next_block += 1;
                        pending.push(m.allocate(next_block, 0, now));
                    }
                }
                for _ in 0..rnd(3) {
                    if !pending.is_empty() {
                        let e = pending.swap_remove(rnd(pending.len() as u32) as usize);
                        m.complete(e, now);
                    }
                }
            }
            // What a sampler advancing the file every cycle would see.
            let mut seen = m.clone();
            seen.release(now);
            sampled.occupied += u64::from(seen.occupied());
            sampled.outstanding += u64::from(seen.outstanding());
            sampled.full += u64::from(seen.is_full());
            assert_eq!(m.integrals(now + 1), sampled, "cycle {now}");
        }
        assert!(sampled.full > 100 && sampled.outstanding > 1000);
    }

    #[test]
    fn an_untargeted_entry_completes_nothing_until_a_miss_merges() {
        let mut m = MshrFile::new(2, 1);
        let a = m.allocate_untargeted(7, 3);
        assert!(m.is_pending(7));
        assert_eq!((m.free(), m.outstanding()), (1, 1));
        assert_eq!(m.targets(a), &[] as &[u32]);
        // The first merge is the entry's first target; `max_merged` = 1
        // still lets a second one in (1 + max_merged targets).
        assert_eq!(m.merge(7, 40, 5), Merge::Merged(a));
        assert_eq!(m.merge(7, 41, 6), Merge::Merged(a));
        assert_eq!(m.merge(7, 42, 6), Merge::Full);
        assert_eq!(m.complete(a, 9), 7);
        assert_eq!(m.targets(a), &[40, 41]);
        // Only the demand targets waited: (9 - 5) + (9 - 6).
        assert_eq!(m.wait_sum(a, 9), 7);
        let b = m.allocate_untargeted(8, 9);
        assert_eq!(m.complete(b, 12), 8);
        assert_eq!((m.targets(b).len(), m.wait_sum(b, 12)), (0, 0));
    }

    #[test]
    fn reuse_order_is_deterministic() {
        let run = || {
            let mut m = MshrFile::new(3, 0);
            let mut order = Vec::new();
            let mut e = Vec::new();
            for (i, b) in [5u64, 6, 7].into_iter().enumerate() {
                e.push(m.allocate(b, i as u32, 0));
            }
            m.complete(e[1], 1);
            m.complete(e[0], 1);
            m.release(3);
            order.push(m.allocate(8, 9, 3));
            order.push(m.allocate(9, 9, 3));
            order
        };
        assert_eq!(run(), run());
    }
}
