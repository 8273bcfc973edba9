//! The core's observation port: a read-only snapshot of the state a
//! property checker compares against its own model (the scheduler's two
//! registers, the warp slots, the tile), like a scan chain read between
//! clock edges. Nothing here is on the simulation's hot path.

use super::ShaderCore;

/// One occupied warp slot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WarpView {
    /// Slot number.
    pub slot: usize,
    /// Index of its quad in the core's tile.
    pub quad: u32,
    /// Launched from the priority FIFO.
    pub priority: bool,
    /// Waiting for a long-latency miss (the paper's blocked state).
    pub blocked: bool,
    /// Cycle of its launch.
    pub launched: u64,
}

/// The observable state of one core after a cycle.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CoreSnapshot {
    /// Index of the core's tile in the trace, if it has one.
    pub tile: Option<usize>,
    /// Quads of the tile rasterized into the input queue so far.
    pub rasterized: u32,
    /// Warps in the priority and regular input FIFOs.
    pub queued: [usize; 2],
    /// The 5-bit free-MSHR register.
    pub free_mshrs: u32,
    /// Whether the register follows the cache (policies that read it).
    pub tracks_free_mshrs: bool,
    /// The 7-bit non-blocked priority-warp counter.
    pub nonblocked: u32,
    /// The core's count of warps in flight.
    pub active: u32,
    /// Warp slots.
    pub slots: usize,
    /// Occupied slots, in slot order.
    pub warps: Vec<WarpView>,
    /// Texture instructions in the LDST queue.
    pub ldst: usize,
}

impl ShaderCore {
    /// Read the core's observable state (see [`CoreSnapshot`]).
    pub fn snapshot(&self) -> CoreSnapshot {
        use wasp_rtl::queue::QueueClass;
        let warps = (0..self.n_slots)
            .filter(|&s| self.free_slots & (1 << s) == 0)
            .map(|s| {
                let w = &self.slots[s];
                WarpView {
                    slot: s,
                    quad: w.quad,
                    priority: w.priority,
                    blocked: w.blocked,
                    launched: w.launched_at,
                }
            })
            .collect();
        let q = self.sched.queue();
        CoreSnapshot {
            tile: self.tile,
            rasterized: self.cursor.next,
            queued: [
                q.occupancy(QueueClass::Priority),
                q.occupancy(QueueClass::Regular),
            ],
            free_mshrs: self.sched.free_mshrs().free().get(),
            tracks_free_mshrs: self.track_mshrs,
            nonblocked: self.sched.nonblocked().count().get(),
            active: self.active,
            slots: self.n_slots,
            warps,
            ldst: self.ldst_len,
        }
    }
}
