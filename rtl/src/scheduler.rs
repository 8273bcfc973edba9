//! The warp launch scheduler of one core: the split input queue, the
//! subset comparator on its input, the free-MSHR register, the non-blocked
//! priority-warp counter, the decision datapath, the launch policy and the
//! launch rule for a closed gate ([`LaunchRule`]).
//!
//! One cycle, two phases:
//! 1. [`LaunchScheduler::decide`] reads only current register values (Q)
//!    and returns which FIFO to launch from; [`LaunchScheduler::launch`]
//!    pops that warp if the core can take it this cycle.
//! 2. [`LaunchScheduler::clock`] takes the cycle's MSHR and priority-warp
//!    events and loads the registers (D -> Q). The launch of this cycle is
//!    counted by the scheduler itself.
//!
//! A decision in cycle t therefore sees the events of cycles up to t-1.

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

/// The launch scheduler of one core, holding warp tickets of type `T`.
#[derive(Debug)]
pub struct LaunchScheduler<T> {
    queue: SplitQueue<T>,
    subset: Box<dyn PrioritySubset>,
    // The subset comparator's answers for in-tile coordinates, with the
    // policy's use of the priority FIFO folded in (empty for the baseline):
    // `classify` without a virtual call.
    priority_table: SubsetTable,
    free_mshrs: FreeMshrReg,
    nonblocked: NonblockedCounter,
    policy: Box<dyn LaunchPolicy>,
    // The policy's constants, read once at construction: a policy is
    // fixed wiring (its methods take `&self` and the scheduler owns it), so
    // they cannot change, and the per-cycle paths need not ask it again.
    uses_priority_queue: bool,
    datapath: Option<WaspDatapath>,
    gate: PriorityGate,
    rule: LaunchRule,
    // The CF meter, for a policy whose CF is measured (`wasp-m`).
    meter: Option<CfMeter>,
    // Signals of the current cycle, for the waveform.
    decision: LaunchDecision,
    launched: Option<QueueClass>,
}

impl<T: Copy> LaunchScheduler<T> {
    /// A scheduler in its reset state, launching under `rule` when the
    /// policy's gate is closed and only a priority warp waits.
    pub fn new(
        queue_capacity: usize,
        subset: Box<dyn PrioritySubset>,
        free_mshrs: FreeMshrReg,
        policy: Box<dyn LaunchPolicy>,
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
            policy,
            decision: LaunchDecision {
                select: None,
                datapath: None,
                held: false,
            },
            launched: None,
        }
    }

    /// The policy.
    pub fn policy(&self) -> &dyn LaunchPolicy {
        self.policy.as_ref()
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

    /// Phase 1: the policy's choice from the current register values.
    pub fn decide(&mut self) -> LaunchDecision {
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
        let select = self.gate.select(self.rule, &view);
        let held = self.rule == LaunchRule::Hold && self.gate.rule_decides(&view);
        let decision = LaunchDecision {
            select,
            datapath,
            held,
        };
        self.decision = decision;
        decision
    }

    /// Phase 1, continued: pop the chosen warp, when the core can take one
    /// this cycle (`enable`). At most one launch per cycle.
    pub fn launch(&mut self, decision: LaunchDecision, enable: bool) -> Option<(T, QueueClass)> {
        let class = decision.select.filter(|_| enable)?;
        let t = self.queue.pop(class)?;
        self.launched = Some(class);
        Some((t, class))
    }

    /// Phase 2: load the registers with this cycle's events. The priority
    /// launch of this cycle (if any) is added to `prio` here.
    #[inline]
    pub fn clock(&mut self, mshr: MshrEvents, prio: PriorityEvents) -> Result<(), RegisterFault> {
        let prio = PriorityEvents {
            // An OR gate (`|`, no short circuit: both inputs are ready).
            launched: prio.launched | (self.launched == Some(QueueClass::Priority)),
            ..prio
        };
        let free = self.free_mshrs.next(mshr)?;
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

    /// Forget this cycle's launch signal (call after tracing, before the
    /// next cycle's phase 1).
    pub fn end_cycle(&mut self) {
        self.launched = None;
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
mod tests {
    use super::*;
    use crate::datapath::{Cf, Threshold, WaspDatapath};
    use crate::policy::{PolicySpec, Wasp};
    use crate::subset::{Explicit, Mesh};

    #[test]
    fn launch_signal_encoding_and_traced_signals() {
        assert_eq!(launch_code(None), 0);
        assert_eq!(launch_code(Some(QueueClass::Regular)), 1);
        assert_eq!(launch_code(Some(QueueClass::Priority)), 2);
        let mut s = LaunchScheduler::new(
            4,
            Box::new(Mesh::new(4).unwrap()),
            FreeMshrReg::with_capacity(6).unwrap(),
            PolicySpec::wasp(1).build(6).unwrap(),
            LaunchRule::Hold,
        );
        s.enqueue(7, 0, 0).unwrap();
        s.enqueue(8, 1, 0).unwrap();
        let d = s.decide();
        assert_eq!(s.launch(d, true), Some((7, QueueClass::Priority)));
        let names: Vec<(String, u32, u64)> = crate::recorder::signals_of(&s);
        assert_eq!(
            names,
            vec![
                ("free_mshrs".to_string(), 5, 6),
                ("nonblocked_priority".to_string(), 7, 0),
                ("cf_product".to_string(), 10, 0),
                ("real_free_mshrs".to_string(), 11, 6),
                ("priority_over_regular".to_string(), 1, 1),
                ("launch".to_string(), 2, 2),
                ("prio_queue_occupancy".to_string(), 3, 0),
                ("regular_queue_occupancy".to_string(), 3, 1),
            ]
        );
    }

    #[test]
    fn baseline_keeps_scanline_order_through_the_split_queue() {
        let mut s = LaunchScheduler::new(
            8,
            Box::new(Mesh::new(4).unwrap()),
            FreeMshrReg::with_capacity(4).unwrap(),
            PolicySpec::Baseline.build(4).unwrap(),
            LaunchRule::Hold,
        );
        for i in 0..8u32 {
            assert_eq!(s.enqueue(i, i, 0), Ok(QueueClass::Regular));
        }
        assert_eq!(s.enqueue(99, 0, 0), Err(99));
        let mut order = vec![];
        while let Some((w, _)) = {
            let d = s.decide();
            s.launch(d, true)
        } {
            order.push(w);
            s.clock(MshrEvents::default(), PriorityEvents::default())
                .unwrap();
            s.end_cycle();
        }
        assert_eq!(order, (0..8).collect::<Vec<_>>());
    }

    #[test]
    fn wasp_launches_priority_then_regular_as_mshrs_fill() {
        let dp = WaspDatapath {
            cf: Cf::ONE,
            threshold: Threshold::new(1).unwrap(),
        };
        let mut s = LaunchScheduler::new(
            16,
            Box::new(Explicit::new([(0, 0), (5, 0), (10, 0)])),
            FreeMshrReg::with_capacity(3).unwrap(),
            Box::new(Wasp::new(dp)),
            LaunchRule::Hold,
        );
        for i in 0..15u32 {
            s.enqueue(i, i, 0).unwrap();
        }
        // Cycle 1: 3 free, nothing in flight: priority W0.
        let d = s.decide();
        assert_eq!(d.datapath.unwrap().real_free.get(), 3);
        assert_eq!(s.launch(d, true), Some((0, QueueClass::Priority)));
        // W0 launched and blocked on its miss in the same cycle.
        s.clock(
            MshrEvents {
                allocs: 1,
                replies: 0,
            },
            PriorityEvents {
                blocked: 1,
                ..Default::default()
            },
        )
        .unwrap();
        s.end_cycle();
        assert_eq!(s.nonblocked().count().get(), 0);
        // Cycle 2: 2 free > 1: priority W5.
        let d = s.decide();
        assert_eq!(s.launch(d, true), Some((5, QueueClass::Priority)));
        s.clock(
            MshrEvents {
                allocs: 1,
                replies: 0,
            },
            PriorityEvents {
                blocked: 1,
                ..Default::default()
            },
        )
        .unwrap();
        s.end_cycle();
        // Cycle 3: 1 free, not > 1: regular W1.
        let d = s.decide();
        assert!(!d.datapath.unwrap().priority_over_regular);
        assert_eq!(s.launch(d, true), Some((1, QueueClass::Regular)));
    }

    #[test]
    fn classify_is_the_policy_gate_and_the_subset_comparator_everywhere() {
        use crate::subset::SubsetSpec;
        for policy in ["baseline", "fullpriority", "freemshr:2", "wasp:1"] {
            let spec: PolicySpec = policy.parse().unwrap();
            let subsets = || {
                let mut v: Vec<Box<dyn PrioritySubset>> =
                    SubsetSpec::all().iter().map(|s| s.build(32)).collect();
                v.push(Box::new(Explicit::new([(0, 0), (33, 1), (2, 40)])));
                v
            };
            for (subset, reference) in subsets().into_iter().zip(subsets()) {
                let name = subset.name();
                let s = LaunchScheduler::<u32>::new(
                    4,
                    subset,
                    FreeMshrReg::with_capacity(4).unwrap(),
                    spec.build(4).unwrap(),
                    LaunchRule::Hold,
                );
                for y in (0..48).chain([u32::MAX]) {
                    for x in (0..48).chain([u32::MAX]) {
                        let want = if spec != PolicySpec::Baseline && reference.is_priority(x, y) {
                            QueueClass::Priority
                        } else {
                            QueueClass::Regular
                        };
                        assert_eq!(s.classify(x, y), want, "{policy} {name} ({x},{y})");
                    }
                }
            }
        }
    }

    #[test]
    fn no_launch_when_disabled() {
        let mut s = LaunchScheduler::new(
            4,
            Box::new(Mesh::new(4).unwrap()),
            FreeMshrReg::with_capacity(4).unwrap(),
            PolicySpec::FullPriority.build(4).unwrap(),
            LaunchRule::Hold,
        );
        s.enqueue(7u32, 0, 0).unwrap();
        let d = s.decide();
        assert_eq!(d.select, Some(QueueClass::Priority));
        assert_eq!(s.launch(d, false), None);
        assert_eq!(s.queue().len(), 1);
    }

    /// WaSP at threshold 1 with 3 MSHRs: two priority warps launch and
    /// block on a miss each, leaving 1 free (not > 1). With only priority
    /// warps waiting, `hold` launches nothing and says so; `launch`
    /// launches the next priority warp.
    #[test]
    fn closed_gate_holds_or_launches_by_rule() {
        for rule in LaunchRule::ALL {
            let dp = WaspDatapath {
                cf: Cf::ONE,
                threshold: Threshold::new(1).unwrap(),
            };
            let mut s = LaunchScheduler::new(
                16,
                Box::new(Explicit::new([(0, 0), (1, 0), (2, 0)])),
                FreeMshrReg::with_capacity(3).unwrap(),
                Box::new(Wasp::new(dp)),
                rule,
            );
            assert_eq!(s.launch_rule(), rule);
            for i in 0..3u32 {
                assert_eq!(s.enqueue(i, i, 0), Ok(QueueClass::Priority));
            }
            for w in 0..2u32 {
                let d = s.decide();
                assert!(!d.held);
                assert_eq!(s.launch(d, true), Some((w, QueueClass::Priority)));
                s.clock(
                    MshrEvents {
                        allocs: 1,
                        replies: 0,
                    },
                    PriorityEvents {
                        blocked: 1,
                        ..Default::default()
                    },
                )
                .unwrap();
                s.end_cycle();
            }
            let d = s.decide();
            assert!(!d.datapath.unwrap().priority_over_regular);
            match rule {
                LaunchRule::Hold => {
                    assert!(d.held);
                    assert_eq!(d.select, None);
                    assert_eq!(s.launch(d, true), None);
                    assert_eq!(s.queue().len(), 1);
                }
                LaunchRule::Launch => {
                    assert!(!d.held);
                    assert_eq!(s.launch(d, true), Some((2, QueueClass::Priority)));
                    assert_eq!(s.queue().len(), 0);
                }
            }
        }
    }

    #[test]
    fn the_rule_does_not_change_the_baseline() {
        let mut runs = vec![];
        for rule in LaunchRule::ALL {
            let mut s = LaunchScheduler::new(
                8,
                Box::new(Mesh::new(4).unwrap()),
                FreeMshrReg::with_capacity(4).unwrap(),
                PolicySpec::Baseline.build(4).unwrap(),
                rule,
            );
            for i in 0..8u32 {
                s.enqueue(i, i % 2 * 4, 0).unwrap();
            }
            let mut order = vec![];
            loop {
                let d = s.decide();
                assert!(!d.held);
                let Some((w, class)) = s.launch(d, true) else {
                    break;
                };
                order.push((w, class));
                s.clock(MshrEvents::default(), PriorityEvents::default())
                    .unwrap();
                s.end_cycle();
            }
            runs.push(order);
        }
        assert_eq!(runs[0], runs[1]);
        assert_eq!(runs[0].len(), 8);
    }

    #[test]
    fn a_measured_cf_replaces_the_constant_after_a_window() {
        // wasp-m:1 starts at CF 2.5, measures 3 over a window of 16 priority
        // launches, and then decides differently from wasp:1 (CF 2.5).
        let build = || {
            LaunchScheduler::<u32>::new(
                64,
                Box::new(Mesh::new(4).unwrap()),
                FreeMshrReg::with_capacity(16).unwrap(),
                PolicySpec::WaspMeasured { threshold: 1 }.build(16).unwrap(),
                LaunchRule::Hold,
            )
        };
        let mut s = build();
        assert_eq!(s.cf_meter().unwrap().cf(), Cf::PAPER);
        // A window: 16 priority launches, 3 misses each cycle (clamped input
        // saturates the accumulator at 127: CF 7.75).
        for _ in 0..16 {
            s.clock(
                MshrEvents::default(),
                PriorityEvents {
                    launched: true,
                    misses: 9,
                    ..Default::default()
                },
            )
            .unwrap();
            // Each launched warp blocks at once, so the counter stays 0.
            s.clock(
                MshrEvents::default(),
                PriorityEvents {
                    blocked: 1,
                    ..Default::default()
                },
            )
            .unwrap();
        }
        assert_eq!(
            s.cf_meter().unwrap().cf().quarters(),
            12,
            "48 misses / 16 warps = 3"
        );
        // Same state, constant CF 2.5 against the measured 3: at 3 non-blocked
        // warps and 7 free, 7 - 7 = 0 (2.5 x 3 = 7.5 -> 7) is not above 1,
        // and neither is 7 - 9; at 2 warps: 7 - 5 = 2 > 1 but 7 - 6 = 1 is not.
        let mut c = LaunchScheduler::<u32>::new(
            64,
            Box::new(Mesh::new(4).unwrap()),
            FreeMshrReg::with_capacity(16).unwrap(),
            PolicySpec::wasp(1).build(16).unwrap(),
            LaunchRule::Hold,
        );
        for sched in [&mut s as &mut LaunchScheduler<u32>, &mut c] {
            sched
                .clock(
                    MshrEvents {
                        allocs: 9,
                        replies: 0,
                    },
                    PriorityEvents {
                        launched: true,
                        ..Default::default()
                    },
                )
                .unwrap();
            sched
                .clock(
                    MshrEvents::default(),
                    PriorityEvents {
                        launched: true,
                        ..Default::default()
                    },
                )
                .unwrap();
            sched.enqueue(1, 0, 0).unwrap();
            assert_eq!(sched.free_mshrs().free().get(), 7);
            assert_eq!(sched.nonblocked().count().get(), 2);
        }
        assert_eq!(c.decide().select, Some(QueueClass::Priority), "7 - 5 > 1");
        assert_eq!(s.decide().select, None, "7 - 6 = 1 is not above 1: hold");
    }
}
