//! Baseline: scanline order.
//!
//! Warps are launched in the order the rasterizer produced them. There are
//! no priority warps: every warp goes to the regular FIFO, so the split
//! queue is the baseline's single FIFO.

use super::{LaunchPolicy, LaunchView};
use crate::queue::QueueClass;

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
    fn select(&self, v: &LaunchView) -> Option<QueueClass> {
        v.regular_waiting.then_some(QueueClass::Regular)
    }
}
