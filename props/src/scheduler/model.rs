//! The reference model of one core's launch path: the two FIFOs, the exact
//! register values and the warps in the core, advanced by the cycle's
//! choices.

use crate::counters::{MshrModel, PriorityModel};
use crate::policy::RefPolicy;
use std::collections::VecDeque;
use wasp_rtl::policy::LaunchRule;
use wasp_rtl::queue::QueueClass;
use wasp_rtl::subset::{PrioritySubset, SubsetSpec};

/// The reference model of one core's launch path.
#[derive(Debug)]
pub struct Model {
    /// The exact launch rule.
    pub policy: RefPolicy,
    /// What a closed gate does with a lone waiting priority warp.
    pub rule: LaunchRule,
    pub(super) subset_spec: SubsetSpec,
    pub(super) subset: Box<dyn PrioritySubset>,
    /// Priority FIFO (tickets), oldest first.
    pub priority: VecDeque<u32>,
    /// Regular FIFO (tickets), oldest first.
    pub regular: VecDeque<u32>,
    /// Shared queue slots.
    pub queue_capacity: usize,
    /// MSHR entries.
    pub mshrs: i64,
    /// MSHR entries in flight.
    pub in_flight: i64,
    /// Non-blocked priority warps in the core.
    pub nonblocked: i64,
    /// Blocked priority warps in the core.
    pub blocked: i64,
    /// Regular warps in the core.
    pub regular_in_core: i64,
    /// Warp slots of the core.
    pub max_warps: i64,
    /// The next fresh ticket.
    pub next_ticket: u32,
    /// Warps accepted into the queue.
    pub accepted: u64,
    /// Warps launched.
    pub launched: u64,
}

impl Model {
    /// Free MSHR entries.
    pub fn free(&self) -> i64 {
        self.mshrs - self.in_flight
    }

    /// Warps waiting in the queue.
    pub fn waiting(&self) -> usize {
        self.priority.len() + self.regular.len()
    }

    /// Warps in the core.
    pub fn in_core(&self) -> i64 {
        self.nonblocked + self.blocked + self.regular_in_core
    }

    /// The reference classification of the quad at (`qx`, `qy`).
    pub fn classify(&self, qx: u32, qy: u32) -> QueueClass {
        let prio = self.policy.uses_priority_queue()
            && match self.subset_spec {
                // Mesh-k in arithmetic, independent of the comparator.
                SubsetSpec::Mesh(k) => (qx % 32).is_multiple_of(k) && (qy % 32).is_multiple_of(k),
                _ => self.subset.is_priority(qx, qy),
            };
        if prio {
            QueueClass::Priority
        } else {
            QueueClass::Regular
        }
    }

    pub(super) fn fifo_mut(&mut self, c: QueueClass) -> &mut VecDeque<u32> {
        match c {
            QueueClass::Priority => &mut self.priority,
            QueueClass::Regular => &mut self.regular,
        }
    }

    /// The MSHR part of the model.
    pub fn mshr_model(&self) -> MshrModel {
        MshrModel {
            capacity: self.mshrs as u32,
            in_flight: self.in_flight as u32,
        }
    }

    /// The priority-warp part of the model.
    pub fn priority_model(&self) -> PriorityModel {
        PriorityModel {
            nonblocked: self.nonblocked as u32,
            blocked: self.blocked as u32,
        }
    }

    /// A state key: everything the scheduler's and the model's future
    /// behaviour depends on, except the ticket numbers and the regular
    /// warps in the core (see [`explore_wasp`](super::explore_wasp)).
    pub fn key(&self) -> (usize, usize, i64, i64, i64) {
        (
            self.priority.len(),
            self.regular.len(),
            self.in_flight,
            self.nonblocked,
            self.blocked,
        )
    }
}
