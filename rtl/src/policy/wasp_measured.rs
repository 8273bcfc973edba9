//! WaSP with a measured CF (`wasp-m:T`, beyond the paper): the same gate
//! as [`super::Wasp`], `Real_freeMSHRs > threshold`, but the datapath's
//! multiplier reads the core's CF meter ([`crate::cf_meter`]) instead of a
//! wired constant. The meter starts at the paper's 2.5 and loads misses per
//! launched priority warp every 16 priority launches.

use super::{LaunchPolicy, PriorityGate};
use crate::datapath::{Cf, Threshold, WaspDatapath};

/// WaSP with the CF meter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WaspMeasured {
    threshold: Threshold,
}

impl WaspMeasured {
    /// The variant with the given threshold.
    pub fn new(threshold: Threshold) -> Self {
        Self { threshold }
    }
}

impl LaunchPolicy for WaspMeasured {
    fn name(&self) -> String {
        format!("wasp-m:{}", self.threshold)
    }
    /// The datapath with the meter's reset value as CF; the scheduler
    /// replaces the CF with the meter's register every cycle.
    fn datapath(&self) -> Option<WaspDatapath> {
        Some(WaspDatapath {
            cf: Cf::PAPER,
            threshold: self.threshold,
        })
    }
    fn measures_cf(&self) -> bool {
        true
    }
    /// Open while the datapath's `priority_over_regular` is set.
    fn gate(&self) -> PriorityGate {
        PriorityGate::Datapath
    }
}
