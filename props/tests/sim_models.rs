//! Reference-model testing of the blocks around the scheduler, with long
//! random runs where the exhaustive twins stop at a depth:
//!
//! * `proptest-state-machine` drives a `wasp-sim` cache (its MSHR file,
//!   ports and lines) with random access / fill / next-cycle sequences
//!   against the unbounded [`CacheModel`], comparing after every operation
//!   (property (f)); a failure shrinks to a minimal operation sequence;
//! * proptest runs random small GPUs (1-2 cores, 1-4 warp slots, every
//!   policy, L0 or not) on random traces of up to two tiles of up to eight
//!   quads, checking properties (g)-(k) every cycle
//!   ([`wasp_props::machine::run_checked`]).

use proptest::prelude::*;
use proptest_state_machine::{prop_state_machine, ReferenceStateMachine, StateMachineTest};
use wasp_props::machine::{run_checked, SmallMachine};
use wasp_props::mshr_file::{cache_step, small_cache, CacheModel, CacheOp, BLOCKS};
use wasp_rtl::policy::LaunchRule;
use wasp_sim::config::BlockedOn;
use wasp_sim::mem::Cache;
use wasp_sim::trace::{Instr, Trace, TraceHeader};

struct CacheRef;

impl ReferenceStateMachine for CacheRef {
    type State = CacheModel;
    type Transition = CacheOp;

    fn init_state() -> BoxedStrategy<CacheModel> {
        (1u32..=6, 0u32..=3, 1u32..=3)
            .prop_map(|(mshrs, merged, ports)| CacheModel::new(&small_cache(mshrs, merged, ports)))
            .boxed()
    }

    fn transitions(_: &CacheModel) -> BoxedStrategy<CacheOp> {
        prop_oneof![
            4 => (0..BLOCKS).prop_map(CacheOp::Access),
            2 => (0..BLOCKS).prop_map(CacheOp::Fill),
            2 => Just(CacheOp::Tick),
        ]
        .boxed()
    }

    fn preconditions(s: &CacheModel, op: &CacheOp) -> bool {
        match op {
            CacheOp::Fill(b) => s.pending.contains_key(b),
            _ => true,
        }
    }

    fn apply(mut s: CacheModel, op: &CacheOp) -> CacheModel {
        s.step(*op);
        s
    }
}

struct CacheSut {
    cache: Cache,
    model: CacheModel,
}

struct CacheTest;

impl StateMachineTest for CacheTest {
    type SystemUnderTest = CacheSut;
    type Reference = CacheRef;

    fn init_test(s: &CacheModel) -> CacheSut {
        let cfg = small_cache(s.capacity, s.targets - 1, s.ports);
        CacheSut {
            cache: Cache::new(&cfg).unwrap(),
            model: s.clone(),
        }
    }

    fn apply(mut sut: CacheSut, after: &CacheModel, op: CacheOp) -> CacheSut {
        if let Err(e) = cache_step(&mut sut.cache, &mut sut.model, op) {
            panic!("{e}");
        }
        assert_eq!(&sut.model, after, "the SUT's model copy left the reference");
        sut
    }

    fn check_invariants(sut: &CacheSut, s: &CacheModel) {
        assert!(sut.cache.mshr_occupied() <= sut.cache.mshr_capacity());
        assert_eq!(sut.cache.mshr_occupied(), s.occupied());
    }
}

prop_state_machine! {
    #![proptest_config(ProptestConfig {
        cases: 64,
        .. ProptestConfig::default()
    })]

    #[test]
    fn cache_matches_the_reference_model(sequential 1..400 => CacheTest);
}

fn arb_machine() -> impl Strategy<Value = SmallMachine> {
    (
        any::<bool>(),
        1u32..=2,
        1u32..=4,
        1u32..=2,
        1u32..=4,
        1u32..=3,
        0u32..=2,
        0usize..5,
        any::<bool>(),
        any::<bool>(),
        0usize..3,
    )
        .prop_map(
            |(l0, cores, warps, width, queue, mshrs, merged, policy, mesh2, launch, rule)| {
                SmallMachine {
                    l0,
                    cores,
                    warps,
                    width,
                    queue,
                    mshrs,
                    max_merged: merged,
                    policy: [
                        "baseline",
                        "fullpriority",
                        "freemshr:1",
                        "wasp:0",
                        "wasp:0:1",
                    ][policy],
                    launch_rule: if launch {
                        LaunchRule::Launch
                    } else {
                        LaunchRule::Hold
                    },
                    subset: if mesh2 { "mesh2" } else { "mesh4" },
                    ideal: false,
                    blocked_on: BlockedOn::ALL[rule],
                }
            },
        )
}

/// Up to two tiles of up to eight quads, each quad at any position of the
/// 4x4-quad tile (positions may repeat: one warp per fragment) running an
/// ALU run and up to two texture instructions over a 6-block pool.
fn arb_trace() -> impl Strategy<Value = Trace> {
    let quad = (
        0u32..4,
        0u32..4,
        prop::collection::vec((1u32..4, prop::collection::btree_set(0u64..6, 1..3)), 0..3),
    );
    let tile = prop::collection::vec(quad, 1..9);
    prop::collection::vec(tile, 1..3).prop_map(|tiles| {
        let mut b = Trace::builder(TraceHeader::new("props:random", 16, 8, 8)).unwrap();
        for (t, quads) in tiles.iter().enumerate() {
            b.begin_tile(t as u32, 0).unwrap();
            for (x, y, prog) in quads {
                let blocks: Vec<Vec<u64>> = prog
                    .iter()
                    .map(|(_, s)| s.iter().map(|b| 0x200 + b).collect())
                    .collect();
                let mut ops = vec![Instr::Alu(1)];
                for ((alu, _), bl) in prog.iter().zip(&blocks) {
                    ops.push(Instr::Tex(bl));
                    ops.push(Instr::Alu(*alu));
                }
                b.quad(*x, *y, &ops).unwrap();
            }
            b.end_tile().unwrap();
        }
        b.finish().unwrap()
    })
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 128,
        .. ProptestConfig::default()
    })]

    #[test]
    fn random_small_gpus_keep_every_machine_property(m in arb_machine(), t in arb_trace()) {
        let cfg = m.config();
        prop_assume!(cfg.validate().is_ok());
        if let Err(e) = run_checked(&cfg, &t) {
            panic!("{e}\nmachine {m:?}");
        }
    }
}
