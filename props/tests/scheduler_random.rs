//! Random long event sequences through the launch scheduler, every policy,
//! against the reference model of `wasp_props::scheduler`: every cycle the
//! registers equal the model's unbounded counters, no `RegisterFault`
//! occurs under legal events, the queue conserves warps, launches follow the
//! ideal FIFOs and the exact policy rule, and (a) holds for WaSP.
//!
//! `PROPTEST_CASES` sets the cases per test (default 64); every case runs
//! 1000 cycles.

use proptest::prelude::*;
use proptest::test_runner::Config;
use wasp_props::scheduler::{run, CycleChoice, CycleEvents, SchedConfig, SchedulerCheck};
use wasp_rtl::free_mshr::MshrEvents;
use wasp_rtl::nonblocked::PriorityEvents;
use wasp_rtl::policy::{LaunchRule, PolicySpec};
use wasp_rtl::subset::SubsetSpec;

const CYCLES: usize = 1000;

fn cases() -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(64)
}

fn subset() -> impl Strategy<Value = SubsetSpec> {
    prop_oneof![
        prop::sample::select(vec![2u32, 4, 8, 16]).prop_map(SubsetSpec::Mesh),
        Just(SubsetSpec::HorizontalLines),
        Just(SubsetSpec::VerticalLines),
        Just(SubsetSpec::Top16),
        any::<u64>().prop_map(SubsetSpec::Random),
    ]
}

/// Zero most of the time (180/256), 1 or 2 often, any `u8` sometimes
/// (16/256), from two random bytes; the check reduces it to a legal value.
/// Rare enough that warps accumulate in the core and MSHRs fill.
fn count(sel: u8, raw: u8) -> u8 {
    match sel {
        0..=179 => 0,
        180..=239 => 1 + raw % 2,
        _ => raw,
    }
}

/// One cycle's choices from 16 random bytes (cheap to generate and to
/// shrink): a warp offered 80% of the time at random in-tile coordinates,
/// launch wanted 70% of the time, event counts by [`count`].
fn choice_from(b: [u8; 16]) -> CycleChoice {
    CycleChoice {
        enqueue: (b[0] < 205).then_some(((b[1] % 32) as u32, (b[2] % 32) as u32)),
        enable: b[3] < 179,
        allocs: count(b[4], b[5]),
        replies: count(b[6], b[7]),
        blocked: count(b[8], b[9]),
        unblocked: count(b[10], b[11]),
        finished: count(b[12], b[13]),
        regular_finished: count(b[14], b[15]),
    }
}

fn choice() -> impl Strategy<Value = CycleChoice> {
    any::<[u8; 16]>().prop_map(choice_from)
}

fn choices() -> impl Strategy<Value = Vec<CycleChoice>> {
    prop::collection::vec(choice(), CYCLES)
}

/// A configuration for `policy(mshrs)`: MSHRs 1..=31, queue 1..=64,
/// warp slots 1..=127.
fn config(policy: impl Fn(u32) -> BoxedStrategy<PolicySpec>) -> impl Strategy<Value = SchedConfig> {
    (1u32..=31, 1usize..=64, 1u32..=127, subset(), any::<bool>()).prop_flat_map(
        move |(mshrs, queue_capacity, max_warps, subset, launch)| {
            policy(mshrs).prop_map(move |policy| SchedConfig {
                policy,
                launch_rule: if launch {
                    LaunchRule::Launch
                } else {
                    LaunchRule::Hold
                },
                subset: subset.clone(),
                mshrs,
                queue_capacity,
                max_warps,
            })
        },
    )
}

fn wasp(mshrs: u32) -> BoxedStrategy<PolicySpec> {
    (0..mshrs, 0u32..=31)
        .prop_map(|(threshold, q)| PolicySpec::Wasp {
            threshold,
            cf: q as f64 / 4.0,
        })
        .boxed()
}

fn check(cfg: &SchedConfig, cs: &[CycleChoice]) -> Result<(), TestCaseError> {
    run(cfg, cs).map_err(|c| TestCaseError::fail(format!("{cfg:?}: {c}")))
}

proptest! {
    #![proptest_config(Config {
        cases: cases(),
        // A failing 1000-cycle case shrinks for at most this many steps.
        max_shrink_iters: 512,
        ..Config::default()
    })]

    #[test]
    fn random_wasp(cfg in config(wasp), cs in choices()) {
        check(&cfg, &cs)?;
    }

    #[test]
    fn random_wasp_paper_cf(
        cfg in config(|m| (0..m).prop_map(PolicySpec::wasp).boxed()),
        cs in choices(),
    ) {
        check(&cfg, &cs)?;
    }

    #[test]
    fn random_baseline(cfg in config(|_| Just(PolicySpec::Baseline).boxed()), cs in choices()) {
        check(&cfg, &cs)?;
    }

    #[test]
    fn random_fullpriority(
        cfg in config(|_| Just(PolicySpec::FullPriority).boxed()),
        cs in choices(),
    ) {
        check(&cfg, &cs)?;
    }

    #[test]
    fn random_freemshr(
        cfg in config(|m| (0..=m).prop_map(PolicySpec::FreeMshr).boxed()),
        cs in choices(),
    ) {
        check(&cfg, &cs)?;
    }

    /// After a random legal prefix, one illegal event whose exact result
    /// leaves a register's range: the clock faults and both registers keep
    /// their values.
    #[test]
    fn random_illegal_event_faults(
        cfg in config(wasp),
        cs in prop::collection::vec(choice(), 0..200),
        kind in 0u8..4,
        extra in 1u8..=255,
        last in choice(),
    ) {
        let mut s = SchedulerCheck::new(&cfg).map_err(TestCaseError::fail)?;
        for c in &cs {
            s.cycle(c).map_err(|c| TestCaseError::fail(c.to_string()))?;
        }
        s.front(last.enqueue, last.enable).map_err(|c| TestCaseError::fail(c.to_string()))?;
        let m = &s.model;
        let (free, in_flight) = (m.free(), m.in_flight);
        let (nb, blocked) = (m.nonblocked, m.blocked);
        let sat = |v: i64| v.clamp(0, 255) as u8;
        let ev = match kind {
            // More allocations than free entries (no replies).
            0 => CycleEvents {
                mshr: MshrEvents { allocs: sat(free + extra as i64), replies: 0 },
                ..Default::default()
            },
            // More replies than entries in flight (no allocations).
            1 => CycleEvents {
                mshr: MshrEvents { allocs: 0, replies: sat(in_flight + extra as i64) },
                ..Default::default()
            },
            // More priority warps leave than are non-blocked (+ launch).
            2 => CycleEvents {
                prio: PriorityEvents {
                    finished: sat(nb + 1 + extra as i64),
                    ..Default::default()
                },
                ..Default::default()
            },
            // More unblocks than the 7-bit counter can count.
            _ => CycleEvents {
                prio: PriorityEvents {
                    unblocked: sat((128 - nb).max(blocked + 1) + extra as i64),
                    ..Default::default()
                },
                ..Default::default()
            },
        };
        prop_assume!(!s.legal(&ev));
        let before = (s.sched.free_mshrs(), s.sched.nonblocked());
        let r = s.back(ev).map_err(|c| TestCaseError::fail(c.to_string()))?;
        // Each event above asks for a value outside its register's range
        // (free < 0, free > capacity, count < 0, count > 127).
        let f = r.ok_or_else(|| TestCaseError::fail(format!("no fault for {ev:?}")))?;
        prop_assert_eq!(before, (s.sched.free_mshrs(), s.sched.nonblocked()));
        prop_assert!(f.attempted < 0 || f.attempted as u32 > f.limit, "{:?}", f);
    }
}

/// A fixed long run of each policy (deterministic, for a quick smoke).
#[test]
fn long_deterministic_runs() {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let cs: Vec<CycleChoice> = (0..5000)
        .map(|i| {
            let (r, r2) = (next(), next());
            let b = |i: u32| ((r >> (8 * i)) & 0xff) as u8;
            let b2 = |i: u32| ((r2 >> (8 * i)) & 0xff) as u8;
            CycleChoice {
                enqueue: (b(0) < 200).then_some(((b(1) % 32) as u32, (b(2) % 32) as u32)),
                // Launch rarely in every fifth stretch of 200 cycles, so
                // that the queue fills up.
                enable: b(3) < if i / 200 % 5 == 0 { 20 } else { 200 },
                allocs: b(4) % 3,
                replies: b(5) % 3,
                blocked: (b(6) < 40) as u8,
                unblocked: (b(7) < 60) as u8,
                finished: (b2(0) < 20) as u8,
                regular_finished: b2(1) % 3,
            }
        })
        .collect();
    for policy in [
        PolicySpec::Baseline,
        PolicySpec::FullPriority,
        PolicySpec::FreeMshr(10),
        PolicySpec::wasp(4),
        PolicySpec::Wasp {
            threshold: 2,
            cf: 1.0,
        },
    ] {
        let cfg = SchedConfig {
            policy,
            launch_rule: LaunchRule::Hold,
            subset: SubsetSpec::Mesh(4),
            mshrs: 16,
            queue_capacity: 64,
            max_warps: 64,
        };
        let mut s = SchedulerCheck::new(&cfg).unwrap();
        for c in &cs {
            if let Err(c) = s.cycle(c) {
                panic!("{policy}: {c}");
            }
        }
        // Not vacuous: the run launched, filled the queue and the MSHRs, and
        // (for the rules with a condition) held priority warps back.
        let cov = s.coverage;
        assert!(cov.regular_launches > 100, "{policy}: {cov:?}");
        assert!(cov.queue_full_refusals > 0, "{policy}: {cov:?}");
        assert!(cov.no_free_mshr > 0, "{policy}: {cov:?}");
        if policy != PolicySpec::Baseline {
            assert!(cov.priority_launches > 10, "{policy}: {cov:?}");
            assert!(cov.max_nonblocked >= 3, "{policy}: {cov:?}");
        }
        if matches!(policy, PolicySpec::FreeMshr(_) | PolicySpec::Wasp { .. }) {
            assert!(cov.priority_held_back > 0, "{policy}: {cov:?}");
        }
        eprintln!("{policy}: {cov:?}");
    }
}
