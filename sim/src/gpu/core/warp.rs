//! A warp in a slot of the fast core, and the start of its blocked
//! episodes.

use wasp_rtl::nonblocked::PriorityEvents;

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

/// Start a blocked episode of warp `w` in cycle `now` unless it is blocked
/// already: its block cycle, the episode count of its class, and for a
/// priority warp one `blocked` event for the non-blocked counter.
#[inline]
pub(super) fn block_warp(
    w: &mut Warp,
    blocked_at: &mut u64,
    episodes: &mut [u64; 2],
    prio: &mut PriorityEvents,
    now: u64,
) {
    if !w.blocked {
        w.blocked = true;
        *blocked_at = now;
        episodes[w.priority as usize & 1] += 1;
        if w.priority {
            prio.blocked += 1;
        }
    }
}
