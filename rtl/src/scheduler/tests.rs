//! Tests of the launch scheduler: the launch signal's encoding and traced
//! signals, scanline order under the baseline, WaSP's priority-then-regular
//! launches, the classification, a disabled core, the closed-gate rule, the
//! measured CF, the quiet edge and a step as phase one then the edge.

use super::*;
use crate::datapath::{Cf, Threshold, WaspDatapath};
use crate::policy::{PolicySpec, Wasp};
use crate::subset::{Explicit, Mesh};

/// The edge of a cycle in which one warp took a miss and, if it is a
/// priority warp, blocked on it.
fn miss_and_block() -> EdgeEvents {
    EdgeEvents {
        mshr: MshrEvents {
            allocs: 1,
            replies: 0,
        },
        prio: PriorityEvents {
            blocked: 1,
            ..Default::default()
        },
    }
}

/// The edge of a cycle with only priority-warp events.
fn prio_only(prio: PriorityEvents) -> EdgeEvents {
    EdgeEvents {
        mshr: MshrEvents::default(),
        prio,
    }
}

#[test]
fn launch_signal_encoding_and_traced_signals() {
    assert_eq!(launch_code(None), 0);
    assert_eq!(launch_code(Some(QueueClass::Regular)), 1);
    assert_eq!(launch_code(Some(QueueClass::Priority)), 2);
    let mut s = LaunchScheduler::new(
        4,
        Box::new(Mesh::new(4).unwrap()),
        FreeMshrReg::with_capacity(6).unwrap(),
        PolicySpec::wasp(1).build(6).unwrap().as_ref(),
        LaunchRule::Hold,
    );
    s.enqueue(7, 0, 0).unwrap();
    s.enqueue(8, 1, 0).unwrap();
    assert_eq!(s.launch(true).warp, Some((7, QueueClass::Priority)));
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
        PolicySpec::Baseline.build(4).unwrap().as_ref(),
        LaunchRule::Hold,
    );
    for i in 0..8u32 {
        assert_eq!(s.enqueue(i, i, 0), Ok(QueueClass::Regular));
    }
    assert_eq!(s.enqueue(99, 0, 0), Err(99));
    let mut order = vec![];
    let cycle = StepInputs {
        enable: true,
        events: EdgeEvents::default(),
    };
    while let Some((w, _)) = s.step(cycle).unwrap().warp {
        order.push(w);
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
        &Wasp::new(dp),
        LaunchRule::Hold,
    );
    for i in 0..15u32 {
        s.enqueue(i, i, 0).unwrap();
    }
    // Cycle 1: 3 free, nothing in flight: priority W0.
    let l = s.launch(true);
    assert_eq!(l.decision.datapath.unwrap().real_free.get(), 3);
    assert_eq!(l.warp, Some((0, QueueClass::Priority)));
    // W0 launched and blocked on its miss in the same cycle.
    s.clock(miss_and_block()).unwrap();
    assert_eq!(s.nonblocked().count().get(), 0);
    // Cycle 2: 2 free > 1: priority W5.
    assert_eq!(s.launch(true).warp, Some((5, QueueClass::Priority)));
    s.clock(miss_and_block()).unwrap();
    // Cycle 3: 1 free, not > 1: regular W1.
    let l = s.launch(true);
    assert!(!l.decision.datapath.unwrap().priority_over_regular);
    assert_eq!(l.warp, Some((1, QueueClass::Regular)));
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
                spec.build(4).unwrap().as_ref(),
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
        PolicySpec::FullPriority.build(4).unwrap().as_ref(),
        LaunchRule::Hold,
    );
    s.enqueue(7u32, 0, 0).unwrap();
    let l = s.launch(false);
    assert_eq!(l.decision.select, Some(QueueClass::Priority));
    assert_eq!(l.warp, None);
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
            &Wasp::new(dp),
            rule,
        );
        assert_eq!(s.launch_rule(), rule);
        for i in 0..3u32 {
            assert_eq!(s.enqueue(i, i, 0), Ok(QueueClass::Priority));
        }
        for w in 0..2u32 {
            let l = s.launch(true);
            assert!(!l.decision.held);
            assert_eq!(l.warp, Some((w, QueueClass::Priority)));
            s.clock(miss_and_block()).unwrap();
        }
        let l = s.launch(true);
        let d = l.decision;
        assert!(!d.datapath.unwrap().priority_over_regular);
        match rule {
            LaunchRule::Hold => {
                assert!(d.held);
                assert_eq!(d.select, None);
                assert_eq!(l.warp, None);
                assert_eq!(s.queue().len(), 1);
            }
            LaunchRule::Launch => {
                assert!(!d.held);
                assert_eq!(l.warp, Some((2, QueueClass::Priority)));
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
            PolicySpec::Baseline.build(4).unwrap().as_ref(),
            rule,
        );
        for i in 0..8u32 {
            s.enqueue(i, i % 2 * 4, 0).unwrap();
        }
        let mut order = vec![];
        loop {
            let out = s
                .step(StepInputs {
                    enable: true,
                    events: EdgeEvents::default(),
                })
                .unwrap();
            assert!(!out.held);
            let Some((w, class)) = out.warp else {
                break;
            };
            order.push((w, class));
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
            PolicySpec::WaspMeasured { threshold: 1 }
                .build(16)
                .unwrap()
                .as_ref(),
            LaunchRule::Hold,
        )
    };
    let mut s = build();
    assert_eq!(s.cf_meter().unwrap().cf(), Cf::PAPER);
    // A window: 16 priority launches, 3 misses each cycle (clamped input
    // saturates the accumulator at 127: CF 7.75).
    for _ in 0..16 {
        s.clock(prio_only(PriorityEvents {
            launched: true,
            misses: 9,
            ..Default::default()
        }))
        .unwrap();
        // Each launched warp blocks at once, so the counter stays 0.
        s.clock(prio_only(PriorityEvents {
            blocked: 1,
            ..Default::default()
        }))
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
        PolicySpec::wasp(1).build(16).unwrap().as_ref(),
        LaunchRule::Hold,
    );
    for sched in [&mut s as &mut LaunchScheduler<u32>, &mut c] {
        let launched = PriorityEvents {
            launched: true,
            ..Default::default()
        };
        sched
            .clock(EdgeEvents {
                mshr: MshrEvents {
                    allocs: 9,
                    replies: 0,
                },
                prio: launched,
            })
            .unwrap();
        sched.clock(prio_only(launched)).unwrap();
        sched.enqueue(1, 0, 0).unwrap();
        assert_eq!(sched.free_mshrs().free().get(), 7);
        assert_eq!(sched.nonblocked().count().get(), 2);
    }
    assert_eq!(
        c.launch(true).decision.select,
        Some(QueueClass::Priority),
        "7 - 5 > 1"
    );
    assert_eq!(
        s.launch(true).decision.select,
        None,
        "7 - 6 = 1 is not above 1: hold"
    );
}

/// A quiet edge is the edge of no events: two schedulers, one given
/// [`LaunchScheduler::clock_quiet`] in the cycles without events (and
/// [`LaunchScheduler::clock`] when it refuses), one always `clock`,
/// keep the same registers, meter and waveform signals on random
/// cycles in which events are rare.
#[test]
fn a_quiet_edge_is_the_edge_of_no_events() {
    use proptest::prelude::*;
    let cycle = (
        prop::option::of((0u32..8, 0u32..8)),
        any::<bool>(),
        (0u8..6, 0u8..2, 0u8..2, 0u8..2, 0u8..2, 0u8..4),
    );
    let policies = ["baseline", "fullpriority", "wasp:1", "wasp-m:1"];
    proptest!(|(p in 0..policies.len(), cycles in prop::collection::vec(cycle, 1..60))| {
        let spec: PolicySpec = policies[p].parse().unwrap();
        let build = || {
            LaunchScheduler::<u32>::new(
                4,
                Box::new(Mesh::new(4).unwrap()),
                FreeMshrReg::with_capacity(4).unwrap(),
                spec.build(4).unwrap().as_ref(),
                LaunchRule::Launch,
            )
        };
        let (mut a, mut b) = (build(), build());
        let mut in_flight = 0u8;
        let mut quiet = 0;
        for (i, (push, enable, (kind, alloc, reply, blocked, finished, misses))) in
            cycles.into_iter().enumerate()
        {
            if let Some((x, y)) = push {
                prop_assert_eq!(a.enqueue(i as u32, x, y), b.enqueue(i as u32, x, y));
            }
            if enable {
                prop_assert_eq!(a.launch(true), b.launch(true));
            }
            // Events in one cycle of three at most.
            let events = if kind > 1 {
                EdgeEvents::default()
            } else {
                let reply = reply.min(in_flight);
                let alloc = alloc.min(a.free_mshrs().free().get() as u8 + reply);
                in_flight = in_flight + alloc - reply;
                EdgeEvents {
                    mshr: MshrEvents { allocs: alloc, replies: reply },
                    prio: PriorityEvents {
                        blocked: blocked.min(a.nonblocked().count().get() as u8),
                        finished: finished.min(a.nonblocked().count().get() as u8),
                        misses,
                        ..Default::default()
                    },
                }
            };
            let clocked = if events == EdgeEvents::default() && a.clock_quiet() {
                quiet += 1;
                Ok(())
            } else {
                a.clock(events)
            };
            prop_assert_eq!(clocked, b.clock(events));
            prop_assert_eq!(a.free_mshrs(), b.free_mshrs());
            prop_assert_eq!(a.nonblocked(), b.nonblocked());
            prop_assert_eq!(a.cf_meter(), b.cf_meter());
            prop_assert_eq!(
                crate::recorder::signals_of(&a),
                crate::recorder::signals_of(&b)
            );
        }
        let _ = quiet;
    });
}

/// `step` is phase 1 (when a warp can launch) then the edge: two
/// schedulers, one stepped and one driven phase by phase, give the same
/// launches, registers and waveform signals on random cycles.
#[test]
fn a_step_is_phase_one_then_the_edge() {
    use proptest::prelude::*;
    let cycle = (
        prop::option::of((0u32..8, 0u32..8)),
        any::<bool>(),
        (0u8..2, 0u8..2, 0u8..2, 0u8..2, 0u8..2),
    );
    let policies = [
        "baseline",
        "fullpriority",
        "freemshr:2",
        "wasp:1",
        "wasp-m:1",
    ];
    proptest!(|(p in 0..policies.len(), rule in any::<bool>(), cycles in prop::collection::vec(cycle, 1..40))| {
        let spec: PolicySpec = policies[p].parse().unwrap();
        let rule = if rule { LaunchRule::Launch } else { LaunchRule::Hold };
        let build = || {
            LaunchScheduler::<u32>::new(
                4,
                Box::new(Mesh::new(4).unwrap()),
                FreeMshrReg::with_capacity(4).unwrap(),
                spec.build(4).unwrap().as_ref(),
                rule,
            )
        };
        let (mut a, mut b) = (build(), build());
        let mut in_flight = 0u8;
        for (i, (push, enable, (alloc, reply, blocked, unblocked, finished))) in
            cycles.into_iter().enumerate()
        {
            if let Some((x, y)) = push {
                prop_assert_eq!(a.enqueue(i as u32, x, y), b.enqueue(i as u32, x, y));
            }
            // Legal MSHR events: replies only for entries in flight,
            // allocations only into free ones.
            let reply = reply.min(in_flight);
            let alloc = alloc.min(a.free_mshrs().free().get() as u8 + reply);
            in_flight = in_flight + alloc - reply;
            let events = EdgeEvents {
                mshr: MshrEvents { allocs: alloc, replies: reply },
                prio: PriorityEvents {
                    blocked: blocked.min(a.nonblocked().count().get() as u8),
                    unblocked: unblocked.min(blocked),
                    finished: finished.min(a.nonblocked().count().get() as u8),
                    ..Default::default()
                },
            };
            let stepped = a.step(StepInputs { enable, events });
            let both = b.queue().has(QueueClass::Priority) && b.queue().has(QueueClass::Regular);
            let phased = if enable && !b.queue().is_empty() {
                Some(b.launch(true))
            } else {
                None
            };
            let clocked = b.clock(events);
            prop_assert_eq!(stepped.is_ok(), clocked.is_ok());
            let Ok(out) = stepped else { return Ok(()) };
            prop_assert_eq!(out.warp, phased.and_then(|l| l.warp));
            prop_assert_eq!(out.held, phased.is_some_and(|l| l.decision.held));
            prop_assert_eq!(out.both_waiting, phased.is_some() && both);
            prop_assert_eq!(a.free_mshrs(), b.free_mshrs());
            prop_assert_eq!(a.nonblocked(), b.nonblocked());
            prop_assert_eq!(
                crate::recorder::signals_of(&a),
                crate::recorder::signals_of(&b)
            );
        }
    });
}
