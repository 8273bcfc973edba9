//! The warp launch scheduler of one core: the split input queue, the
//! subset comparator on its input, the free-MSHR register, the non-blocked
//! priority-warp counter, the decision datapath, the launch policy and the
//! launch rule for a closed gate ([`LaunchRule`]).
//!
//! A value: the policy is wired in at construction (its gate, datapath and
//! CF meter are fields, read without a virtual call), and a cycle has two
//! phases with typed inputs and outputs, as a two-phase RTL simulation
//! evaluates and then clocks:
//! 1. [`LaunchScheduler::launch`] (combinational) reads only current
//!    register values (Q) and the queue, and returns the [`Launch`]: which
//!    FIFO the policy picks and, if the core can take a warp this cycle, the
//!    warp it pops (the FIFO's read port);
//! 2. [`LaunchScheduler::clock`] (the clock edge) loads the registers
//!    (D -> Q) with the cycle's [`EdgeEvents`]. The launch of this cycle
//!    is counted by the scheduler itself.
//!
//! [`LaunchScheduler::step`] is the whole cycle in one call (phase 1 then
//! the edge, `StepInputs -> StepOutputs`), for a caller whose events of a
//! cycle do not depend on that cycle's launch (the scheduler's property
//! tests drive it so). A caller in which a warp launched in cycle t
//! presents its access in cycle t (the worked example, the co-simulation's
//! stimulus) needs the two phases apart, since the events the edge loads
//! then come from that launch. The GPU's shader cores also call the two
//! phases: their launch could be one step with the edge (a launched warp
//! issues from the next cycle), and that form gives the same results and
//! waveforms, but it costs 4% more host instructions per core-cycle
//! (1250 against 1198, `scripts/icount.sh`), so the launch stays in phase
//! 1 beside the issue stage. A caller may skip phase 1 in a cycle where
//! nothing can launch; the edge is clocked every cycle. Warps enter between
//! edges through [`LaunchScheduler::enqueue`] (the queue's write port,
//! before phase 1).
//!
//! A decision in cycle t therefore sees the events of cycles up to t-1.
//! The cycle's signals (decision, launch) stay readable for a waveform
//! until the next cycle's first call.

use crate::cf_meter::{CfMeter, MeterEvents, MISSES_BITS};
use crate::datapath::{DatapathOut, WaspDatapath};
use crate::free_mshr::{FreeMshrReg, MshrEvents};
use crate::nonblocked::{NonblockedCounter, PriorityEvents};
use crate::policy::{LaunchPolicy, LaunchRule, LaunchView, PriorityGate};
use crate::queue::{QueueClass, SplitQueue};
use crate::subset::{PrioritySubset, SubsetTable};
use crate::uint::UInt;
use crate::RegisterFault;
use wasp_waves::{Traceable, Tracer};

/// Encoding of the `launch` signal: 0 none, 1 regular, 2 priority.
pub fn launch_code(c: Option<QueueClass>) -> u64 {
    match c {
        None => 0,
        Some(QueueClass::Regular) => 1,
        Some(QueueClass::Priority) => 2,
    }
}

/// The combinational outputs of one cycle's decision.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LaunchDecision {
    /// Which FIFO the policy picked (`None`: launch nothing).
    pub select: Option<QueueClass>,
    /// The datapath signals, for policies that have the datapath.
    pub datapath: Option<DatapathOut>,
    /// The launch rule held a waiting priority warp: one waits, the gate
    /// is closed, no regular warp waits and the rule is
    /// [`LaunchRule::Hold`] (so `select` is `None`).
    pub held: bool,
}

/// The outputs of phase 1: the decision and the warp it launched.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Launch<T> {
    /// The decision, from the registers' current values.
    pub decision: LaunchDecision,
    /// The warp popped from the selected FIFO and its class (`None` when
    /// nothing is selected or the core cannot take a warp).
    pub warp: Option<(T, QueueClass)>,
}

/// The inputs of the clock edge: the cycle's events from the memory system
/// and the warps.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct EdgeEvents {
    /// MSHR allocations and replies at the scheduler's cache level.
    pub mshr: MshrEvents,
    /// Priority-warp events (the cycle's own priority launch is added by
    /// the scheduler).
    pub prio: PriorityEvents,
}

/// The inputs of one whole cycle ([`LaunchScheduler::step`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StepInputs {
    /// The core can take a warp this cycle (a free warp slot).
    pub enable: bool,
    /// The cycle's events, loaded at its edge.
    pub events: EdgeEvents,
}

/// The outputs of one whole cycle ([`LaunchScheduler::step`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StepOutputs<T> {
    /// The warp launched and its class.
    pub warp: Option<(T, QueueClass)>,
    /// The launch rule held a waiting priority warp back
    /// ([`LaunchDecision::held`]).
    pub held: bool,
    /// Warps waited in both FIFOs at the decision: the policy's gate chose
    /// between them.
    pub both_waiting: bool,
}

/// The launch scheduler of one core, holding warp tickets of type `T`.
#[derive(Debug)]
pub struct LaunchScheduler<T> {
    queue: SplitQueue<T>,
    // The subset comparator, asked only for coordinates beyond its table.
    subset: Box<dyn PrioritySubset>,
    // The subset comparator's answers for in-tile coordinates, with the
    // policy's use of the priority FIFO folded in (empty for the baseline):
    // `classify` without a virtual call.
    priority_table: SubsetTable,
    free_mshrs: FreeMshrReg,
    nonblocked: NonblockedCounter,
    // The policy's wiring, read once at construction: a policy is fixed
    // wiring (its methods take `&self`), so the scheduler keeps its
    // constants and never asks it again.
    uses_priority_queue: bool,
    datapath: Option<WaspDatapath>,
    gate: PriorityGate,
    rule: LaunchRule,
    // The CF meter, for a policy whose CF is measured (`wasp-m`).
    meter: Option<CfMeter>,
    // Signals of the current cycle, for the waveform.
    decision: LaunchDecision,
    launched: Option<QueueClass>,
    // The current cycle's edge has been clocked: the next call begins a
    // new cycle and clears `launched` first.
    edge_passed: bool,
}

impl<T: Copy> LaunchScheduler<T> {
    /// A scheduler in its reset state, wired for `policy`, launching under
    /// `rule` when the policy's gate is closed and only a priority warp
    /// waits.
    pub fn new(
        queue_capacity: usize,
        subset: Box<dyn PrioritySubset>,
        free_mshrs: FreeMshrReg,
        policy: &dyn LaunchPolicy,
        rule: LaunchRule,
    ) -> Self {
        let priority_table = if policy.uses_priority_queue() {
            SubsetTable::of(subset.as_ref())
        } else {
            SubsetTable::empty()
        };
        Self {
            queue: SplitQueue::new(queue_capacity),
            subset,
            priority_table,
            free_mshrs,
            nonblocked: NonblockedCounter::reset(),
            uses_priority_queue: policy.uses_priority_queue(),
            datapath: policy.datapath(),
            gate: policy.gate(),
            rule,
            meter: policy.measures_cf().then(CfMeter::reset),
            decision: LaunchDecision {
                select: None,
                datapath: None,
                held: false,
            },
            launched: None,
            edge_passed: false,
        }
    }

    /// The launch rule for a closed gate.
    pub fn launch_rule(&self) -> LaunchRule {
        self.rule
    }

    /// The CF meter, when the policy measures its CF.
    pub fn cf_meter(&self) -> Option<CfMeter> {
        self.meter
    }

    /// The input queue.
    pub fn queue(&self) -> &SplitQueue<T> {
        &self.queue
    }

    /// The free-MSHR register.
    pub fn free_mshrs(&self) -> FreeMshrReg {
        self.free_mshrs
    }

    /// The non-blocked priority-warp counter.
    pub fn nonblocked(&self) -> NonblockedCounter {
        self.nonblocked
    }

    /// Which class the subset comparator gives the quad at (`qx`, `qy`)
    /// under this policy (always regular for the baseline).
    #[inline]
    pub fn classify(&self, qx: u32, qy: u32) -> QueueClass {
        let priority = match self.priority_table.get(qx, qy) {
            Some(p) => p,
            None => self.uses_priority_queue && self.subset.is_priority(qx, qy),
        };
        if priority {
            QueueClass::Priority
        } else {
            QueueClass::Regular
        }
    }

    /// Enqueue a warp from the rasterizer; `Err(ticket)` back if the queue
    /// is full. Returns the class it was put in.
    #[inline]
    pub fn enqueue(&mut self, ticket: T, qx: u32, qy: u32) -> Result<QueueClass, T> {
        let class = self.classify(qx, qy);
        if self.queue.push(class, ticket) {
            Ok(class)
        } else {
            Err(ticket)
        }
    }

    /// Start a new cycle's signals if the last edge has passed.
    #[inline]
    fn begin_cycle(&mut self) {
        if self.edge_passed {
            self.launched = None;
            self.edge_passed = false;
        }
    }

    /// The policy's choice from the current register values and queue.
    #[inline]
    fn decide(&self) -> LaunchDecision {
        let datapath = self.datapath.map(|dp| {
            // A measured CF replaces the wired constant.
            let dp = match self.meter {
                Some(m) => WaspDatapath { cf: m.cf(), ..dp },
                None => dp,
            };
            dp.eval(self.free_mshrs.free(), self.nonblocked.count())
        });
        let view = LaunchView {
            priority_waiting: self.queue.has(QueueClass::Priority),
            regular_waiting: self.queue.has(QueueClass::Regular),
            free_mshrs: self.free_mshrs.free(),
            datapath,
        };
        LaunchDecision {
            select: self.gate.select(self.rule, &view),
            datapath,
            held: self.rule == LaunchRule::Hold && self.gate.rule_decides(&view),
        }
    }

    /// Phase 1: the policy's decision from the current register values,
    /// and the warp it pops from the selected FIFO when the core can take
    /// one this cycle (`enable`). At most one launch per cycle.
    // Always inlined: one call a core-cycle, and the caller reads only
    // part of the `Launch` it returns (measured with scripts/icount.sh).
    #[inline(always)]
    pub fn launch(&mut self, enable: bool) -> Launch<T> {
        self.begin_cycle();
        let decision = self.decide();
        self.decision = decision;
        let warp = match decision.select.filter(|_| enable) {
            Some(class) => self.queue.pop(class).map(|t| (t, class)),
            None => None,
        };
        self.launched = warp.map(|(_, c)| c);
        Launch { decision, warp }
    }

    /// Phase 2, the clock edge: load the registers with this cycle's
    /// events. The priority launch of this cycle (if any) is added to the
    /// priority events here. On a fault neither register loads.
    #[inline]
    pub fn clock(&mut self, ev: EdgeEvents) -> Result<(), RegisterFault> {
        self.begin_cycle();
        self.edge_passed = true;
        let prio = PriorityEvents {
            // An OR gate (`|`, no short circuit: both inputs are ready).
            launched: ev.prio.launched | (self.launched == Some(QueueClass::Priority)),
            ..ev.prio
        };
        let free = self.free_mshrs.next(ev.mshr)?;
        let nb = self.nonblocked.next(prio)?;
        self.free_mshrs = free;
        self.nonblocked = nb;
        if let Some(m) = &mut self.meter {
            // More misses in one cycle than the 2-bit input holds are
            // clamped to its largest value.
            let max = (1u8 << MISSES_BITS) - 1;
            *m = m.next(MeterEvents {
                launched: prio.launched,
                misses: UInt::masked(u32::from(prio.misses.min(max))),
            });
        }
        Ok(())
    }

    /// The clock edge of a cycle without events (no MSHR event, no
    /// priority-warp event), when no priority warp launched in it: the
    /// same as [`clock`](Self::clock) of [`EdgeEvents::default`], with no
    /// register loaded (each register's next state on no events is its
    /// state); only the cycle's launch signal ends. Returns false, and
    /// does nothing, when a priority warp launched in the cycle (an event
    /// for the registers: the caller clocks them).
    #[inline]
    pub fn clock_quiet(&mut self) -> bool {
        self.begin_cycle();
        if self.launched == Some(QueueClass::Priority) {
            return false;
        }
        self.edge_passed = true;
        true
    }

    /// One whole cycle in one call, for a caller whose events of the cycle
    /// do not depend on its launch: phase 1 when a warp can launch
    /// (`enable` and a warp waiting), then the edge with the cycle's
    /// events. When nothing can launch, the decision logic
    /// is not evaluated: its waveform signals keep their last values,
    /// `launch` reads 0 and the outputs are empty.
    #[inline(always)]
    pub fn step(&mut self, inputs: StepInputs) -> Result<StepOutputs<T>, RegisterFault> {
        let mut out = StepOutputs {
            warp: None,
            held: false,
            both_waiting: false,
        };
        if inputs.enable && !self.queue.is_empty() {
            let both_waiting =
                self.queue.has(QueueClass::Priority) && self.queue.has(QueueClass::Regular);
            let l = self.launch(true);
            out = StepOutputs {
                warp: l.warp,
                held: l.decision.held,
                both_waiting,
            };
        }
        self.clock(inputs.events)?;
        Ok(out)
    }
}

impl<T: Copy> Traceable for LaunchScheduler<T> {
    fn trace<Tr: Tracer + ?Sized>(&self, t: &mut Tr) {
        self.free_mshrs.trace(t);
        self.nonblocked.trace(t);
        match &self.decision.datapath {
            Some(d) => d.trace(t),
            None => DatapathOut {
                product: Default::default(),
                real_free: Default::default(),
                priority_over_regular: false,
            }
            .trace(t),
        }
        if let Some(m) = &self.meter {
            m.trace(t);
        }
        t.signal("launch", 2, launch_code(self.launched));
        self.queue.trace(t);
    }
}

#[cfg(test)]
mod tests;
