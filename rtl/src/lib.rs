//! wasp-rtl: the WaSP warp scheduler at register-transfer granularity.
//!
//! Each block is a struct of fixed-width registers with a pure next-state
//! function (small control blocks) or an explicit two-phase interface
//! (queues): outputs are computed from current state, then the clock edge
//! loads the next state. Every block exposes its signals through
//! [`wasp_waves::Traceable`].
//!
//! | block | paper |
//! |---|---|
//! | [`free_mshr::FreeMshrReg`] | the 5-bit register of free MSHRs |
//! | [`nonblocked::NonblockedCounter`] | the 7-bit count of non-blocked priority warps |
//! | [`datapath::WaspDatapath`] | multiply by 2.5 (shift-add), subtract, compare |
//! | [`subset::Mesh`] | the two-bit comparator of Mesh4 (and Mesh2/8/16) |
//! | [`queue::SplitQueue`] | the input queue split into priority and regular FIFOs |
//! | [`policy`] | Baseline, Fullpriority, FreeMSHR-N, WaSP; the launch rule for a closed gate ([`policy::LaunchRule`]) |
//! | [`scheduler::LaunchScheduler`] | all of the above, one per core |

pub mod cf_meter;
pub mod cost;
pub mod datapath;
pub mod free_mshr;
pub mod nonblocked;
pub mod policy;
pub mod queue;
pub mod scheduler;
pub mod subset;
pub mod uint;

use std::fmt;

/// An event that would take a register outside its legal range. Hardware
/// would wrap; the model stops and reports it instead.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RegisterFault {
    /// Hardware name of the register.
    pub register: &'static str,
    /// Its value before the event.
    pub value: u32,
    /// The value the event asked for.
    pub attempted: i32,
    /// The largest legal value.
    pub limit: u32,
}

impl fmt::Display for RegisterFault {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "register `{}` would leave its range: {} -> {} (legal 0..={})",
            self.register, self.value, self.attempted, self.limit
        )
    }
}

impl std::error::Error for RegisterFault {}

/// A tracer that records every signal, for the blocks' tests.
#[cfg(test)]
pub(crate) mod recorder {
    use wasp_waves::Tracer;

    /// Every `signal` call as (scope path + name, width, value).
    #[derive(Default)]
    pub(crate) struct Recorder {
        scope: Vec<String>,
        pub(crate) signals: Vec<(String, u32, u64)>,
    }

    impl Tracer for Recorder {
        fn push_scope(&mut self, name: &str) {
            self.scope.push(name.to_string());
        }
        fn pop_scope(&mut self) {
            self.scope.pop();
        }
        fn signal(&mut self, name: &str, width: u32, value: u64) {
            let mut path = self.scope.join(".");
            if !path.is_empty() {
                path.push('.');
            }
            path.push_str(name);
            self.signals.push((path, width, value));
        }
    }

    /// The signals `block` names, in order.
    pub(crate) fn signals_of(block: &impl wasp_waves::Traceable) -> Vec<(String, u32, u64)> {
        let mut r = Recorder::default();
        block.trace(&mut r);
        r.signals
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn register_fault_reads_well() {
        let f = RegisterFault {
            register: "free_mshrs",
            value: 31,
            attempted: 32,
            limit: 31,
        };
        assert_eq!(
            f.to_string(),
            "register `free_mshrs` would leave its range: 31 -> 32 (legal 0..=31)"
        );
    }
}
