//! FreeMSHR-N: a priority warp only while at least N MSHRs are free.
//!
//! The paper's Freemshr10 is N = 10. Unlike WaSP it ignores the misses that
//! priority warps already in the core are about to make. With fewer than N
//! free and no regular warp waiting, the [`LaunchRule`](super::LaunchRule)
//! decides (nothing under `hold`).

use super::{LaunchPolicy, PriorityGate};
use crate::free_mshr::FreeMshrs;

/// FreeMSHR-N.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FreeMshrN {
    n: FreeMshrs,
}

impl FreeMshrN {
    /// Launch priority warps while `free_mshrs >= n`.
    pub fn new(n: FreeMshrs) -> Self {
        Self { n }
    }
}

impl LaunchPolicy for FreeMshrN {
    fn name(&self) -> String {
        format!("freemshr:{}", self.n)
    }
    fn reads_free_mshrs(&self) -> bool {
        true
    }
    /// Open while `free_mshrs >= N`.
    fn gate(&self) -> PriorityGate {
        PriorityGate::FreeMshrsAtLeast(self.n)
    }
}
