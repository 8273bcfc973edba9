//! The MSHR file of one cache: a small array of entries, each tracking one
//! outstanding primary miss (its block) and the targets waiting for it.
//!
//! Life of an entry: free -> *pending* (allocated by a primary miss; secondary
//! misses merge their targets into it) -> *held* (its reply arrived in cycle
//! `r`; the targets are delivered at `r`, the entry stays occupied through
//! `r + 1`) -> free again from cycle `r + 2`.
//!
//! Storage is flat and preallocated: no allocation after construction.
//! Lookups by block are linear searches over the pending entries' blocks,
//! kept dense (a handful to a few dozen, like the CAM of a hardware MSHR
//! file). An owner that remembers the entry [`MshrFile::allocate`] returned
//! completes it by index, with no search.

/// Cycles an entry stays occupied after the cycle of its reply.
pub const MSHR_HOLD_CYCLES: u64 = 1;

/// One MSHR file.
#[derive(Debug, Clone)]
pub struct MshrFile {
    capacity: u32,
    /// Targets per entry: the primary miss plus `max_merged` secondary ones.
    slots: u32,
    /// Targets recorded in each entry.
    count: Box<[u32]>,
    /// `capacity * slots` target values (their meaning belongs to the cache's
    /// owner: a core's tag, an MSHR entry of the level above, a core number).
    targets: Box<[u32]>,
    /// Sum of the acceptance cycles of each entry's targets.
    issued_sum: Box<[u64]>,
    /// Blocks of the pending entries in `pending_block[..outstanding]`,
    /// unordered (swap-removed on completion), their entries alongside in
    /// `pending_entry`.
    pending_block: Box<[u64]>,
    pending_entry: Box<[u32]>,
    /// Position in `pending_block` of each pending entry.
    pending_pos: Box<[u32]>,
    outstanding: u32,
    /// Free entries in `free[..free_len]`, used as a stack (deterministic
    /// reuse order).
    free: Box<[u32]>,
    free_len: u32,
    /// Held entries as `(first cycle free, entry)`, a ring of `held_len`
    /// entries from `held_head`, in fill order, hence sorted.
    held: Box<[(u64, u32)]>,
    held_head: u32,
    held_len: u32,
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
            count: vec![0; n].into(),
            targets: vec![0; n * slots as usize].into(),
            issued_sum: vec![0; n].into(),
            pending_block: vec![0; n].into(),
            pending_entry: vec![0; n].into(),
            pending_pos: vec![0; n].into(),
            outstanding: 0,
            free: (0..capacity).rev().collect(),
            free_len: capacity,
            held: vec![(0, 0); n].into(),
            held_head: 0,
            held_len: 0,
        }
    }

    /// Free every held entry whose hold has ended by cycle `now`.
    #[inline]
    pub fn release(&mut self, now: u64) {
        while self.held_len > 0 {
            let (at, e) = self.held[self.held_head as usize];
            if at > now {
                break;
            }
            self.held_head += 1;
            if self.held_head == self.capacity {
                self.held_head = 0;
            }
            self.held_len -= 1;
            self.free[self.free_len as usize] = e;
            self.free_len += 1;
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
        self.capacity - self.free_len
    }

    /// Entries awaiting their reply.
    #[inline]
    pub fn outstanding(&self) -> u32 {
        self.outstanding
    }

    /// No entry can be allocated.
    #[inline]
    pub fn is_full(&self) -> bool {
        self.free_len == 0
    }

    /// The pending entry for `block`, if any.
    #[inline]
    pub fn find(&self, block: u64) -> Option<u32> {
        let pending = &self.pending_block[..self.outstanding as usize];
        let pos = pending.iter().position(|&b| b == block)?;
        Some(self.pending_entry[pos])
    }

    /// Whether an entry is pending for `block`.
    #[inline]
    pub fn is_pending(&self, block: u64) -> bool {
        self.find(block).is_some()
    }

    /// Block of pending entry `e`.
    #[inline]
    pub fn block(&self, e: u32) -> u64 {
        let pos = self.pending_pos[e as usize] as usize;
        debug_assert!(pos < self.outstanding as usize && self.pending_entry[pos] == e);
        self.pending_block[pos]
    }

    /// Add a secondary-miss target to the pending entry of `block`, if any.
    #[inline]
    pub fn merge(&mut self, block: u64, target: u32, now: u64) -> Merge {
        let Some(e) = self.find(block) else {
            return Merge::NotPending;
        };
        let e = e as usize;
        let n = self.count[e];
        if n >= self.slots {
            return Merge::Full;
        }
        self.targets[e * self.slots as usize + n as usize] = target;
        self.issued_sum[e] += now;
        self.count[e] = n + 1;
        Merge::Merged
    }

    /// Allocate an entry for a primary miss on `block` and return it. The
    /// caller has checked that the file is not full and no entry is pending
    /// for `block`.
    #[inline]
    pub fn allocate(&mut self, block: u64, target: u32, now: u64) -> u32 {
        debug_assert!(!self.is_pending(block));
        assert!(self.free_len > 0, "MSHR allocate on a full file");
        self.free_len -= 1;
        let e = self.free[self.free_len as usize];
        let i = e as usize;
        self.count[i] = 1;
        self.targets[i * self.slots as usize] = target;
        self.issued_sum[i] = now;
        let pos = self.outstanding;
        self.pending_block[pos as usize] = block;
        self.pending_entry[pos as usize] = e;
        self.pending_pos[i] = pos;
        self.outstanding = pos + 1;
        e
    }

    /// The reply for pending entry `e` arrived in cycle `now`: the entry
    /// becomes held until `now + MSHR_HOLD_CYCLES` (inclusive). Returns its
    /// block; its targets are then read with [`MshrFile::targets`].
    #[inline]
    pub fn complete(&mut self, e: u32, now: u64) -> u64 {
        let pos = self.pending_pos[e as usize] as usize;
        debug_assert!(pos < self.outstanding as usize && self.pending_entry[pos] == e);
        let block = self.pending_block[pos];
        // Swap-remove position `pos` of the dense pending list.
        self.outstanding -= 1;
        let last = self.outstanding as usize;
        let moved = self.pending_entry[last];
        self.pending_block[pos] = self.pending_block[last];
        self.pending_entry[pos] = moved;
        self.pending_pos[moved as usize] = pos as u32;
        // Fills come in cycle order, so the ring stays sorted.
        let free_at = now + 1 + MSHR_HOLD_CYCLES;
        debug_assert!(self.held_len < self.capacity);
        let mut tail = self.held_head + self.held_len;
        if tail >= self.capacity {
            tail -= self.capacity;
        }
        self.held[tail as usize] = (free_at, e);
        self.held_len += 1;
        block
    }

    /// The targets of entry `e`, in acceptance order (primary first).
    #[inline]
    pub fn targets(&self, e: u32) -> &[u32] {
        let i = e as usize;
        let start = i * self.slots as usize;
        &self.targets[start..start + self.count[i] as usize]
    }

    /// Sum over the targets of entry `e` of the cycles from their
    /// acceptance to `now` (not before any of them).
    #[inline]
    pub fn wait_sum(&self, e: u32, now: u64) -> u64 {
        let i = e as usize;
        u64::from(self.count[i]) * now - self.issued_sum[i]
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
        assert_eq!(m.merge(10, 101, 2), Merge::Merged);
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
