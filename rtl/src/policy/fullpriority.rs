//! Fullpriority: every priority warp of a tile before any regular warp.

use super::{LaunchPolicy, LaunchView};
use crate::queue::QueueClass;

/// The paper's Fullpriority heuristic.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FullPriority;

impl LaunchPolicy for FullPriority {
    fn name(&self) -> String {
        "fullpriority".into()
    }
    fn select(&self, v: &LaunchView) -> Option<QueueClass> {
        if v.priority_waiting {
            Some(QueueClass::Priority)
        } else if v.regular_waiting {
            Some(QueueClass::Regular)
        } else {
            None
        }
    }
}
