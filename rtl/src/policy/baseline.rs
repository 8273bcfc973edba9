//! Baseline: scanline order.
//!
//! Warps are launched in the order the rasterizer produced them. There are
//! no priority warps: every warp goes to the regular FIFO, so the split
//! queue is the baseline's single FIFO.

use super::{LaunchPolicy, PriorityGate};

/// The scanline baseline.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Baseline;

impl LaunchPolicy for Baseline {
    fn name(&self) -> String {
        "baseline".into()
    }
    fn uses_priority_queue(&self) -> bool {
        false
    }
    /// Closed: the next regular warp, if one waits (and none ever waits in
    /// the priority FIFO).
    fn gate(&self) -> PriorityGate {
        PriorityGate::Closed
    }
}
