//! Fullpriority: every priority warp of a tile before any regular warp.

use super::{LaunchPolicy, PriorityGate};

/// The paper's Fullpriority heuristic.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FullPriority;

impl LaunchPolicy for FullPriority {
    fn name(&self) -> String {
        "fullpriority".into()
    }
    /// Open: a waiting priority warp always goes first.
    fn gate(&self) -> PriorityGate {
        PriorityGate::Open
    }
}
