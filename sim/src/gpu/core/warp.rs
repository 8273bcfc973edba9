//! The warp slots of a core: each warp's record, which slots hold one, and
//! its blocked episodes. Every stage reaches the warps through them.

use super::Notes;

/// Warp slots a core can have (the slot masks' width). The slot array
/// always has this many entries, so that indexing it with a slot number
/// masked to this power of two needs no bounds check.
pub(super) const MAX_SLOTS: usize = 128;

/// A warp in a slot.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Warp {
    /// Index of its quad in the tile.
    pub(super) quad: u32,
    /// Next instruction entry to start, as an index in the tile's
    /// instruction pool (the one in progress is `op - 1`): a wake-up with no
    /// ALU run under way starts entry `op`, or finishes the warp past its
    /// last.
    pub(super) op: u32,
    /// One past its last instruction entry in the pool.
    pub(super) n_ops: u32,
    pub(super) priority: bool,
    pub(super) blocked: bool,
    /// Blocks of the current texture instruction not yet returned.
    pub(super) pending: u32,
    /// Blocks of the current texture instruction (set when it is decoded).
    pub(super) tex_len: u32,
    /// The current texture instruction is trilinear (set when decoded).
    pub(super) tex_tri: bool,
    /// Index in the tile's block accesses of the next texture
    /// instruction's first block.
    pub(super) blk: u32,
    /// Cycle the current texture instruction entered the LDST queue.
    pub(super) tex_start: u64,
    /// Sum of the memory latencies of its texture instructions.
    pub(super) lat_sum: u64,
    /// Texture instructions completed.
    pub(super) tex_done: u32,
    /// Cycle of its launch.
    pub(super) launched_at: u64,
}

/// The warp slots.
#[derive(Debug)]
pub(super) struct Warps {
    /// The warps; a slot holds one when its bit in `free` is 0. Only the
    /// first `n` are used.
    slots: Box<[Warp; MAX_SLOTS]>,
    /// Per slot, the cycle its warp became blocked (meaningful while the
    /// warp is blocked), apart from the warp: only blocking reads it.
    blocked_at: Box<[u64; MAX_SLOTS]>,
    /// Free slots.
    free: u128,
    /// Warps in flight.
    active: u32,
    /// Slots of the core.
    n: usize,
}

impl Warps {
    /// `n` (at most [`MAX_SLOTS`]) empty slots.
    pub(super) fn new(n: usize) -> Self {
        debug_assert!(n <= MAX_SLOTS);
        Warps {
            slots: Box::new([Warp::default(); MAX_SLOTS]),
            blocked_at: Box::new([0; MAX_SLOTS]),
            free: if n == MAX_SLOTS {
                u128::MAX
            } else {
                (1u128 << n) - 1
            },
            active: 0,
            n,
        }
    }

    /// Slots of the core.
    #[inline]
    pub(super) fn slots(&self) -> usize {
        self.n
    }

    /// Warps in flight.
    #[inline]
    pub(super) fn active(&self) -> u32 {
        self.active
    }

    /// Whether slot `s` holds a warp.
    #[inline]
    pub(super) fn holds(&self, s: usize) -> bool {
        self.free >> (s % MAX_SLOTS) & 1 == 0
    }

    /// The warp in slot `s`.
    #[inline(always)]
    pub(super) fn get(&self, s: usize) -> &Warp {
        &self.slots[s % MAX_SLOTS]
    }

    /// The warp in slot `s`, to change it.
    #[inline(always)]
    pub(super) fn get_mut(&mut self, s: usize) -> &mut Warp {
        &mut self.slots[s % MAX_SLOTS]
    }

    /// The lowest free slot, if any.
    #[inline]
    pub(super) fn free_slot(&self) -> Option<usize> {
        (self.free != 0).then(|| self.free.trailing_zeros() as usize)
    }

    /// Put warp `w` in free slot `s`.
    #[inline]
    pub(super) fn occupy(&mut self, s: usize, w: Warp) {
        self.free &= !(1u128 << (s % MAX_SLOTS));
        self.slots[s % MAX_SLOTS] = w;
        self.active += 1;
    }

    /// Empty slot `s` (its warp stays readable until the slot is
    /// occupied again).
    #[inline]
    pub(super) fn release(&mut self, s: usize) {
        self.free |= 1u128 << (s % MAX_SLOTS);
        self.active -= 1;
    }

    /// Start a blocked episode of the warp in slot `s` in cycle `now`
    /// unless it is blocked already: its block cycle, the episode count of
    /// its class, and for a priority warp one `blocked` event for the
    /// non-blocked counter.
    #[inline]
    pub(super) fn block(&mut self, s: usize, now: u64, notes: &mut Notes) {
        let w = &mut self.slots[s % MAX_SLOTS];
        if !w.blocked {
            w.blocked = true;
            self.blocked_at[s % MAX_SLOTS] = now;
            notes.stats.blocked_episodes[w.priority as usize & 1] += 1;
            if w.priority {
                notes.prio.blocked += 1;
            }
        }
    }

    /// End the blocked episode of the warp in slot `s`, if it is in one,
    /// in cycle `now` (its data arrived): its cycles, and for a priority
    /// warp one `unblocked` event.
    #[inline]
    pub(super) fn unblock(&mut self, s: usize, now: u64, notes: &mut Notes) {
        let w = &mut self.slots[s % MAX_SLOTS];
        if w.blocked {
            w.blocked = false;
            notes.stats.blocked_cycles[w.priority as usize & 1] +=
                now - self.blocked_at[s % MAX_SLOTS];
            if w.priority {
                notes.prio.unblocked += 1;
            }
        }
    }

    /// Warps in flight that are blocked.
    pub(super) fn blocked(&self) -> usize {
        (0..self.n)
            .filter(|&s| self.holds(s) && self.slots[s].blocked)
            .count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slots_fill_lowest_first_and_blocked_episodes_count_once() {
        let mut w = Warps::new(3);
        let mut notes = Notes::new(3);
        assert_eq!(w.free_slot(), Some(0));
        let prio = Warp {
            priority: true,
            ..Warp::default()
        };
        w.occupy(0, prio);
        w.occupy(1, Warp::default());
        assert_eq!((w.free_slot(), w.active()), (Some(2), 2));
        w.occupy(2, Warp::default());
        assert_eq!(w.free_slot(), None);
        w.block(0, 10, &mut notes);
        w.block(0, 12, &mut notes);
        w.block(1, 11, &mut notes);
        assert_eq!(notes.stats.blocked_episodes, [1, 1]);
        assert_eq!((notes.prio.blocked, w.blocked()), (1, 2));
        w.unblock(0, 15, &mut notes);
        w.unblock(0, 16, &mut notes);
        w.unblock(2, 16, &mut notes);
        assert_eq!(notes.stats.blocked_cycles, [0, 5]);
        assert_eq!(notes.prio.unblocked, 1);
        w.release(0);
        assert!(w.get(0).priority, "readable until occupied again");
        assert_eq!((w.free_slot(), w.active(), w.holds(0)), (Some(0), 2, false));
    }
}
