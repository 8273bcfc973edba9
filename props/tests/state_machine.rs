//! Reference-model testing with `proptest-state-machine`: the RTL launch
//! scheduler (split queue with the Mesh4 comparator, 5-bit free-MSHR
//! register, 7-bit non-blocked counter, x CF datapath, WaSP select) is
//! driven cycle by cycle with random legal events and compared after every
//! cycle with an unbounded reference model: exact integers, two ideal
//! FIFOs, the WaSP rule evaluated as the real-number inequality, under
//! either launch rule (`hold` or `launch`). A failing case shrinks to a
//! minimal cycle sequence.

use proptest::prelude::*;
use proptest_state_machine::{prop_state_machine, ReferenceStateMachine, StateMachineTest};
use std::collections::VecDeque;
use wasp_rtl::datapath::{Cf, Threshold, WaspDatapath};
use wasp_rtl::free_mshr::{FreeMshrReg, MshrEvents};
use wasp_rtl::nonblocked::PriorityEvents;
use wasp_rtl::policy::{LaunchRule, Wasp};
use wasp_rtl::queue::QueueClass;
use wasp_rtl::scheduler::{EdgeEvents, LaunchScheduler, StepInputs};
use wasp_rtl::subset::Mesh;

/// The reference: unbounded counters and queues.
#[derive(Clone, Debug)]
struct Model {
    mshrs: i64,
    queue_cap: usize,
    threshold: i64,
    cf_quarters: i64,
    /// A closed gate with only priority warps waiting launches one.
    launch: bool,
    /// MSHR entries allocated and not yet replied.
    outstanding: i64,
    /// Priority warps in the core, not blocked, not finished.
    nonblocked: i64,
    /// Priority warps in the core, blocked.
    blocked: i64,
    prio: VecDeque<u32>,
    regular: VecDeque<u32>,
    next_id: u32,
    /// What the last cycle launched (for the SUT to compare).
    last_launch: Option<(u32, QueueClass)>,
    last_push_accepted: Option<bool>,
}

/// One clock cycle of inputs.
#[derive(Clone, Debug)]
struct Cycle {
    /// A quad arriving from the rasterizer, at in-tile (x, y).
    push: Option<(u32, u32)>,
    /// The core has a free slot and takes a warp if one is chosen.
    enable: bool,
    allocs: u8,
    replies: u8,
    block: u8,
    unblock: u8,
    finish: u8,
}

impl Model {
    fn mesh4(x: u32, y: u32) -> bool {
        x.is_multiple_of(4) && y.is_multiple_of(4)
    }

    /// The exact WaSP condition on the current counters.
    fn priority_over_regular(&self) -> bool {
        let free = self.mshrs - self.outstanding;
        4 * free - self.cf_quarters * self.nonblocked > 4 * self.threshold
    }
}

struct SchedulerRef;

impl ReferenceStateMachine for SchedulerRef {
    type State = Model;
    type Transition = Cycle;

    fn init_state() -> BoxedStrategy<Model> {
        (1i64..=31, 1usize..=12, 0u32..=31, any::<bool>())
            .prop_flat_map(|(mshrs, queue_cap, q, launch)| {
                (
                    Just(mshrs),
                    Just(queue_cap),
                    0..mshrs,
                    Just(q as i64),
                    Just(launch),
                )
            })
            .prop_map(|(mshrs, queue_cap, threshold, cf_quarters, launch)| Model {
                mshrs,
                queue_cap,
                threshold,
                cf_quarters,
                launch,
                outstanding: 0,
                nonblocked: 0,
                blocked: 0,
                prio: VecDeque::new(),
                regular: VecDeque::new(),
                next_id: 0,
                last_launch: None,
                last_push_accepted: None,
            })
            .boxed()
    }

    fn transitions(s: &Model) -> BoxedStrategy<Cycle> {
        // Legal events only: replies of outstanding entries, allocations of
        // free ones, blocks/finishes of counted warps, unblocks of blocked.
        let outstanding = s.outstanding as u8;
        let free = (s.mshrs - s.outstanding) as u8;
        let nb = s.nonblocked.min(8) as u8;
        let blocked = s.blocked.min(8) as u8;
        (
            prop::option::weighted(0.7, (0u32..8, 0u32..8)),
            any::<bool>(),
            0..=outstanding.min(3),
            0..=nb,
            0..=blocked,
        )
            .prop_flat_map(move |(push, enable, replies, block, unblock)| {
                (
                    Just(push),
                    Just(enable),
                    0..=(free + replies).min(3),
                    Just(replies),
                    Just(block),
                    Just(unblock),
                    0..=(nb - block),
                )
            })
            .prop_map(
                |(push, enable, allocs, replies, block, unblock, finish)| Cycle {
                    push,
                    enable,
                    allocs,
                    replies,
                    block,
                    unblock,
                    finish,
                },
            )
            .boxed()
    }

    /// Legality, re-checked while shrinking removes cycles.
    fn preconditions(s: &Model, c: &Cycle) -> bool {
        let replies = c.replies as i64;
        replies <= s.outstanding
            && (c.allocs as i64) <= s.mshrs - s.outstanding + replies
            && (c.block as i64) + (c.finish as i64) <= s.nonblocked
            && (c.unblock as i64) <= s.blocked
    }

    fn apply(mut s: Model, c: &Cycle) -> Model {
        // Raster enqueue first (the core rasterizes before it launches).
        s.last_push_accepted = c.push.map(|(x, y)| {
            if s.prio.len() + s.regular.len() >= s.queue_cap {
                return false;
            }
            let id = s.next_id;
            s.next_id += 1;
            if Self::is_prio(x, y) {
                s.prio.push_back(id);
            } else {
                s.regular.push_back(id);
            }
            true
        });
        // Decide on this cycle's register values, then launch.
        let class = if s.priority_over_regular() && !s.prio.is_empty() {
            Some(QueueClass::Priority)
        } else if !s.regular.is_empty() {
            Some(QueueClass::Regular)
        } else if s.launch && !s.prio.is_empty() {
            Some(QueueClass::Priority)
        } else {
            None
        };
        s.last_launch = match (class, c.enable) {
            (Some(QueueClass::Priority), true) => {
                s.prio.pop_front().map(|w| (w, QueueClass::Priority))
            }
            (Some(QueueClass::Regular), true) => {
                s.regular.pop_front().map(|w| (w, QueueClass::Regular))
            }
            _ => None,
        };
        let launched_prio = matches!(s.last_launch, Some((_, QueueClass::Priority))) as i64;
        // Clock edge.
        s.outstanding += c.allocs as i64 - c.replies as i64;
        s.nonblocked += launched_prio + c.unblock as i64 - c.block as i64 - c.finish as i64;
        s.blocked += c.block as i64 - c.unblock as i64;
        s
    }
}

impl SchedulerRef {
    fn is_prio(x: u32, y: u32) -> bool {
        Model::mesh4(x, y)
    }
}

struct SchedulerTest;

struct Sut {
    sched: LaunchScheduler<u32>,
    next_id: u32,
}

impl StateMachineTest for SchedulerTest {
    type SystemUnderTest = Sut;
    type Reference = SchedulerRef;

    fn init_test(s: &Model) -> Sut {
        let dp = WaspDatapath {
            cf: Cf::from_quarters(s.cf_quarters as u32).unwrap(),
            threshold: Threshold::new(s.threshold as u32).unwrap(),
        };
        Sut {
            sched: LaunchScheduler::new(
                s.queue_cap,
                Box::new(Mesh::new(4).unwrap()),
                FreeMshrReg::with_capacity(s.mshrs as u32).unwrap(),
                &Wasp::new(dp),
                if s.launch {
                    LaunchRule::Launch
                } else {
                    LaunchRule::Hold
                },
            ),
            next_id: 0,
        }
    }

    fn apply(mut sut: Sut, after: &Model, c: Cycle) -> Sut {
        if let Some((x, y)) = c.push {
            let accepted = sut.sched.enqueue(sut.next_id, x, y).is_ok();
            if accepted {
                sut.next_id += 1;
            }
            assert_eq!(Some(accepted), after.last_push_accepted, "push refusal");
        }
        // One call a cycle: the reference chose the cycle's events before
        // it, so they do not depend on the launch.
        let out = sut
            .sched
            .step(StepInputs {
                enable: c.enable,
                events: EdgeEvents {
                    mshr: MshrEvents {
                        allocs: c.allocs,
                        replies: c.replies,
                    },
                    prio: PriorityEvents {
                        launched: false,
                        blocked: c.block,
                        unblocked: c.unblock,
                        finished: c.finish,
                        misses: 0,
                    },
                },
            })
            .expect("legal events never fault");
        assert_eq!(out.warp, after.last_launch, "launch (warp, queue)");
        sut
    }

    fn check_invariants(sut: &Sut, s: &Model) {
        assert_eq!(
            sut.sched.free_mshrs().free().get() as i64,
            s.mshrs - s.outstanding,
            "free-MSHR register = capacity - outstanding"
        );
        assert_eq!(
            sut.sched.nonblocked().count().get() as i64,
            s.nonblocked,
            "non-blocked counter = launched, unblocked, unfinished priority warps"
        );
        let q = sut.sched.queue();
        assert_eq!(q.occupancy(QueueClass::Priority), s.prio.len());
        assert_eq!(q.occupancy(QueueClass::Regular), s.regular.len());
        assert!(q.len() <= s.queue_cap);
        assert_eq!(q.peek(QueueClass::Priority), s.prio.front());
        assert_eq!(q.peek(QueueClass::Regular), s.regular.front());
    }
}

prop_state_machine! {
    #![proptest_config(ProptestConfig {
        cases: 128,
        max_shrink_iters: 4096,
        .. ProptestConfig::default()
    })]

    /// Up to 200 cycles per case against the unbounded reference.
    #[test]
    fn scheduler_matches_the_reference_model(sequential 1..200 => SchedulerTest);
}
