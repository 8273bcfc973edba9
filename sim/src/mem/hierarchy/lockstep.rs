//! The tick's shortcuts against the plain tick, in lockstep:
//! [`MemorySystem::tick`] and [`MemorySystem::tick_plain`] are the one
//! implementation with its shortcuts on and off (skipping quiet cores,
//! finding the L2's candidates while visiting the cores, filling an L0
//! directly, skipping step 5). Two systems, one ticked each way, are given
//! the same accesses, and everything an owner can observe is compared
//! every cycle.

use super::tests::arb_config;
use super::*;
use crate::mem::prefetch::PrefetchQueues;
use proptest::prelude::*;

/// Two systems, one ticked fast and one plainly, given the same
/// accesses (`ops`: idle cycle when 0, else accesses per core and a
/// base block) until drained; everything observable must agree every
/// cycle: access results, MSHR views, miss events,
/// completions, and the statistics at the end.
fn lockstep(cfg: &MemConfig, ops: &[(u8, u8, u64)]) -> Result<u64, TestCaseError> {
    let mut fast = MemorySystem::new(cfg).unwrap();
    let mut plain = fast.clone();
    let n = cfg.cores as usize;
    let (mut a, mut b) = (Vec::new(), Vec::new());
    let mut tag = 0u32;
    let mut ops = ops.iter();
    let mut draining = false;
    let mut now = 0u64;
    loop {
        if !draining {
            match ops.next() {
                Some(&(0, _, _)) => {}
                Some(&(_, count, block)) => {
                    for k in 0..n {
                        // A prefetch too, when the machine has a
                        // prefetcher: queued on both, served by each tick
                        // on the ports demand leaves.
                        if cfg.prefetch.enabled() {
                            let blk = block + 3 + k as u64 * 5;
                            fast.prefetch_queue(k).offer(blk);
                            plain.prefetch_queue(k).offer(blk);
                        }
                        for j in 0..u64::from(count) {
                            let blk = block + j * 7 + k as u64;
                            let (x, y) = (
                                fast.access(now, k, blk, tag),
                                plain.access(now, k, blk, tag),
                            );
                            prop_assert_eq!(x, y, "access of tag {} at cycle {}", tag, now);
                            tag += 1;
                        }
                    }
                }
                None => draining = true,
            }
        }
        fast.tick(now);
        plain.tick_plain(now);
        for k in 0..n {
            prop_assert_eq!(
                fast.mshr_events(k),
                plain.mshr_events(k),
                "core {} cycle {}",
                k,
                now
            );
            let (mut ea, mut eb) = (Vec::new(), Vec::new());
            fast.take_miss_events(k, &mut ea);
            plain.take_miss_events(k, &mut eb);
            prop_assert_eq!(&ea, &eb, "miss events, core {} cycle {}", k, now);
            a.clear();
            b.clear();
            fast.take_completions(k, &mut a);
            plain.take_completions(k, &mut b);
            prop_assert_eq!(&a, &b, "completions, core {} cycle {}", k, now);
        }
        now += 1;
        if draining && fast.is_idle() {
            prop_assert!(plain.is_idle());
            break;
        }
        prop_assert!(now < 100_000, "no drain");
    }
    prop_assert_eq!(fast.stats(), plain.stats());
    if cfg.prefetch.enabled() {
        prop_assert_eq!(fast.prefetch_stats(), plain.prefetch_stats());
    }
    Ok(now)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn the_plain_tick_is_the_fast_one(
        cfg in arb_config(),
        ops in proptest::collection::vec((0u8..4, 0u8..3, 0u64..40), 1..300),
    ) {
        lockstep(&cfg, &ops)?;
    }
}

#[test]
fn the_plain_tick_is_the_fast_one_on_the_papers_machines() {
    // A texture-like load: bursts of accesses to a sliding window of
    // blocks, on the shipped hierarchy with and without L0.
    let ops: Vec<(u8, u8, u64)> = (0..3000u64)
        .map(|i| {
            (
                (i % 5 != 0) as u8,
                (1 + i % 2) as u8,
                (i / 16) * 3 + (i * 7919) % 11,
            )
        })
        .collect();
    for width4 in [false, true] {
        let mut cfg = MemConfig {
            report_misses: true,
            ..MemConfig::paper(width4)
        };
        let cycles = lockstep(&cfg, &ops).unwrap();
        assert!(cycles > 3000, "{cycles}");
        cfg.prefetch.kind = crate::mem::PrefetchKind::Raster;
        let cycles = lockstep(&cfg, &ops).unwrap();
        assert!(cycles > 3000, "{cycles}");
    }
}
