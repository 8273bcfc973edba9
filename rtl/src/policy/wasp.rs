//! WaSP: a priority warp (if one waits) when `Real_freeMSHRs > threshold`,
//! else a regular warp.
//!
//! When the datapath says regular and no regular warp waits, the
//! [`LaunchRule`](super::LaunchRule) decides. Under `hold` (the paper's
//! rule, the default) nothing is launched: a priority warp is never
//! launched with `Real_freeMSHRs <= threshold`. This cannot starve as long
//! as the threshold is below the MSHR count (checked when the policy is
//! built): once the priority warps in the core block or finish and the
//! misses are answered, `Real_freeMSHRs` returns to the capacity. Under
//! `launch` the waiting priority warp launches instead (work-conserving).

use super::{LaunchPolicy, PriorityGate};
use crate::datapath::WaspDatapath;

/// The WaSP launch rule.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Wasp {
    datapath: WaspDatapath,
}

impl Wasp {
    /// WaSP with the given datapath constants.
    pub fn new(datapath: WaspDatapath) -> Self {
        Self { datapath }
    }
}

impl LaunchPolicy for Wasp {
    fn name(&self) -> String {
        let cf = self.datapath.cf.value();
        if cf == 2.5 {
            format!("wasp:{}", self.datapath.threshold)
        } else {
            format!("wasp:{}:{}", self.datapath.threshold, cf)
        }
    }
    fn datapath(&self) -> Option<WaspDatapath> {
        Some(self.datapath)
    }
    /// Open while the datapath's `priority_over_regular` is set.
    fn gate(&self) -> PriorityGate {
        PriorityGate::Datapath
    }
}
