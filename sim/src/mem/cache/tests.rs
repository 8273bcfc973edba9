//! Tests of the cache: scripted hits, misses and merges, MSHR and port limits,
//! LRU replacement per set, the tag filter, occupancy, prefetch marks, and the
//! paper's worked example (whose helper the hierarchy's tests share).

use super::*;
use std::collections::VecDeque;

pub(crate) fn cfg(size: u32, ways: u32, mshrs: u32, max_merged: u32, ports: u32) -> CacheConfig {
    CacheConfig {
        size_bytes: size,
        ways,
        line_bytes: 64,
        hit_latency: 1,
        mshrs,
        max_merged,
        ports,
    }
}

#[test]
fn hit_miss_secondary_counts_on_a_script() {
    // 4 sets x 2 ways.
    let mut c = Cache::new(&cfg(512, 2, 4, 4, 4)).unwrap();
    assert_eq!(c.access(1, 7, 0), Lookup::Miss);
    assert_eq!(c.access(1, 7, 1), Lookup::Secondary);
    assert_eq!(c.access(2, 8, 2), Lookup::Miss);
    assert_eq!(c.access(3, 7, 3), Lookup::Secondary);
    assert_eq!(c.fill(5, 7), &[0, 1, 3]);
    assert!(c.contains(7) && !c.is_pending(7));
    assert_eq!(c.access(6, 7, 4), Lookup::Hit);
    assert_eq!(c.access(6, 8, 5), Lookup::Secondary);
    assert_eq!(c.fill(6, 8), &[2, 5]);
    assert_eq!(c.access(7, 8, 6), Lookup::Hit);
    let s = c.stats();
    assert_eq!(
        (s.accesses, s.hits, s.misses, s.secondary_misses, s.fills),
        (7, 2, 2, 3, 2)
    );
    // Waits: block 7 targets at 1,1,3 filled at 5; block 8 at 2,6 filled at 6.
    assert_eq!(s.miss_wait_sum, 4 + 4 + 2 + 4);
    assert_eq!(s.stall_cycles, 0);
}

#[test]
fn full_mshrs_refuse_hits_and_entries_are_held_one_cycle_after_reply() {
    let mut c = Cache::new(&cfg(512, 2, 2, 4, 8)).unwrap();
    assert_eq!(c.access(1, 1, 0), Lookup::Miss);
    c.fill(2, 1); // line 1 present from cycle 3; entry held through 3
    assert_eq!(c.access(3, 1, 1), Lookup::Hit);
    assert_eq!(c.access(3, 2, 2), Lookup::Miss);
    // Both entries occupied (one pending, one held through 3): stall.
    assert_eq!(c.access(3, 1, 3), Lookup::Stall);
    assert_eq!(c.access(3, 1, 4), Lookup::Stall);
    assert!(c.stalled_now());
    assert_eq!(c.mshr_occupied(), 2);
    assert_eq!(c.mshr_outstanding(), 1);
    // Cycle 4: the held entry is free again.
    assert_eq!(c.access(4, 1, 5), Lookup::Hit);
    assert_eq!(c.access(4, 3, 6), Lookup::Miss);
    // Cycle 5: full with two pending misses; a hit to line 1 is refused.
    assert_eq!(c.access(5, 1, 7), Lookup::Stall);
    c.fill(5, 2);
    assert_eq!(c.replied_now(), 1);
    // r + 1 = 6: still full.
    assert_eq!(c.access(6, 1, 8), Lookup::Stall);
    assert_eq!(c.access(6, 2, 9), Lookup::Stall);
    // r + 2 = 7: free.
    assert_eq!(c.access(7, 2, 10), Lookup::Hit);
    let s = c.stats();
    assert_eq!(s.stall_cycles, 3, "cycles 3, 5 and 6, each once");
    assert_eq!(s.stall_refusals, 5);
    assert_eq!(s.port_busy, 0);
}

#[test]
fn merge_limit_and_ports() {
    let mut c = Cache::new(&cfg(512, 2, 4, 1, 2)).unwrap();
    assert_eq!(c.access(1, 5, 0), Lookup::Miss);
    assert_eq!(c.access(1, 5, 1), Lookup::Secondary);
    assert_eq!(c.access(1, 5, 2), Lookup::PortBusy);
    assert_eq!(c.access(2, 5, 2), Lookup::MergeFull);
    // A refused access uses no port.
    assert_eq!(c.access(2, 6, 3), Lookup::Miss);
    assert_eq!(c.access(2, 7, 4), Lookup::Miss);
    assert_eq!(c.access(2, 8, 5), Lookup::PortBusy);
    let s = c.stats();
    assert_eq!((s.merge_stalls, s.port_busy, s.stall_cycles), (1, 2, 0));
    assert_eq!(c.allocated_now(), 2);
}

#[test]
fn lru_evicts_least_recently_used_way() {
    // 1 set x 2 ways: blocks 0, 1, 2 all map to it.
    let mut c = Cache::new(&cfg(128, 2, 4, 4, 4)).unwrap();
    let mut now = 1;
    for b in [0, 1] {
        assert_eq!(c.access(now, b, 0), Lookup::Miss);
        c.fill(now + 1, b);
        now += 3;
    }
    assert_eq!(c.access(now, 0, 0), Lookup::Hit); // 0 is now MRU
    now += 1;
    assert_eq!(c.access(now, 2, 0), Lookup::Miss);
    c.fill(now + 1, 2); // evicts 1
    now += 3;
    assert!(c.contains(0) && c.contains(2) && !c.contains(1));
    assert_eq!(c.access(now, 1, 0), Lookup::Miss);
    c.fill(now + 1, 1); // evicts 0 (2 was used later)
    assert!(c.contains(1) && c.contains(2) && !c.contains(0));
}

#[test]
fn filter_counts_every_line() {
    // 2 sets x 2 ways; blocks 1 and `far` share a filter bucket (and set 1).
    let far = 1 + FILTER_BUCKETS as u64;
    let mut c = Cache::new(&cfg(256, 2, 4, 2, 4)).unwrap();
    let count = |c: &Cache, b: u64| c.filter[bucket(b)];
    assert_eq!(c.access(1, 1, 0), Lookup::Miss);
    assert_eq!(count(&c, 1), 0, "a pending block has no line");
    // Same bucket, other block: still a primary miss, then merged.
    assert_eq!(c.access(1, far, 1), Lookup::Miss);
    assert_eq!(c.access(1, far, 2), Lookup::Secondary);
    assert_eq!(count(&c, far), 0);
    c.fill(2, 1);
    assert_eq!(count(&c, far), 1);
    // A line in the bucket, the other block pending: searched, merged.
    assert_eq!(c.access(2, far, 7), Lookup::Secondary);
    c.fill(2, far);
    assert_eq!(count(&c, 1), 2, "filled lines are counted");
    assert_eq!(c.access(3, far, 3), Lookup::Hit);
    // Blocks 3 and 5 evict 1 and `far` from set 1 (LRU order 1, `far`).
    assert_eq!(c.access(3, 3, 4), Lookup::Miss);
    assert_eq!(c.access(3, 5, 5), Lookup::Miss);
    c.fill(4, 3);
    assert_eq!((count(&c, 1), count(&c, 3)), (1, 1));
    c.fill(4, 5);
    assert_eq!((count(&c, 1), count(&c, 3), count(&c, 5)), (0, 1, 1));
    assert!(!c.contains(1) && !c.contains(far));
    assert_eq!(c.access(6, far, 6), Lookup::Miss);
    // The lines of blocks 3 and 5; pending `far` is not counted.
    assert_eq!(c.filter.iter().sum::<u32>(), 2);
}

#[test]
fn sets_are_indexed_by_low_block_bits() {
    // 2 sets x 1 way: even blocks to set 0, odd to set 1.
    let mut c = Cache::new(&cfg(128, 1, 4, 0, 4)).unwrap();
    c.access(1, 4, 0);
    c.access(1, 5, 0);
    c.fill(2, 4);
    c.fill(2, 5);
    assert!(c.contains(4) && c.contains(5));
    c.access(4, 6, 0);
    c.fill(5, 6);
    assert!(c.contains(6) && c.contains(5) && !c.contains(4));
}

/// Replacement follows a plain LRU model (a recency list per set) on a
/// random script of hits, misses and out-of-order fills.
#[test]
fn replacement_is_lru_per_set() {
    let mut rng = crate::rng::Rng::new(0x2545_f491);
    let mut rnd = |n: u32| rng.below(u64::from(n)) as u32;
    // 2 sets x 4 ways, room for every miss in flight.
    let mut c = Cache::new(&cfg(512, 4, 64, 64, 64)).unwrap();
    let mut model: Vec<Vec<u64>> = vec![Vec::new(); 2];
    let mut pending: Vec<u64> = Vec::new();
    let mut evictions = 0;
    for now in 1..4000u64 {
        for _ in 0..rnd(3) {
            let block = u64::from(rnd(24));
            let set = &mut model[(block % 2) as usize];
            match c.access(now, block, 0) {
                Lookup::Hit => {
                    let p = set.iter().position(|&b| b == block).unwrap();
                    set.remove(p);
                    set.insert(0, block);
                }
                Lookup::Miss => pending.push(block),
                l => assert_eq!(l, Lookup::Secondary),
            }
        }
        for _ in 0..rnd(3) {
            if !pending.is_empty() {
                let block = pending.swap_remove(rnd(pending.len() as u32) as usize);
                c.fill(now, block);
                let set = &mut model[(block % 2) as usize];
                if set.len() == 4 {
                    set.pop();
                    evictions += 1;
                }
                set.insert(0, block);
            }
        }
        for b in 0..24 {
            let want = model[(b % 2) as usize].contains(&b);
            assert_eq!(c.contains(b), want, "block {b} at {now}");
        }
    }
    assert!(evictions > 500);
}

/// The lookups and fills without the marks' tests are the same as
/// with them, on a cache that takes no prefetch (a random script).
#[test]
fn unmarked_lookups_and_fills_match_the_marked_ones() {
    let mut rng = crate::rng::Rng::new(0x51ab_7e01);
    let mut rnd = |n: u32| rng.below(u64::from(n)) as u32;
    let mut a = Cache::new(&cfg(512, 2, 4, 2, 2)).unwrap();
    let mut b = a.clone();
    let mut pending: Vec<u32> = Vec::new();
    for now in 1..3000u64 {
        for _ in 0..rnd(3) {
            let block = u64::from(rnd(20));
            let x = a.access_entry(now, block, now as u32);
            assert_eq!(x, b.access_entry_unmarked(now, block, now as u32));
            if x.0 == Lookup::Miss {
                pending.push(x.1);
            }
        }
        if !pending.is_empty() && rnd(2) == 0 {
            let e = pending.swap_remove(rnd(pending.len() as u32) as usize);
            assert_eq!(a.fill_entry(now, e), b.fill_entry_unmarked(now, e));
        }
    }
    assert_eq!(a.stats(), b.stats());
    assert!(a.stats().hits > 100 && a.stats().secondary_misses > 100);
}

#[test]
fn occupancy_integral() {
    let mut c = Cache::new(&cfg(512, 2, 2, 4, 4)).unwrap();
    c.access(1, 1, 0);
    c.access(2, 2, 0); // full from 2
    c.fill(3, 1); // cycle 3: 1 outstanding, 2 held
                  // cycle 4: the entry of 1 held through 4
    let s = c.stats_until(6, 5); // cycle 5: freed
    assert_eq!(s.mshr_outstanding_sum, 1 + 2 + 1 + 1 + 1);
    assert_eq!(s.mshr_held_sum, 1 + 2 + 2 + 2 + 1);
    assert_eq!(s.mshr_full_cycles, 3);
    assert_eq!(s.cycles, 5);
    // Mid-way, and with an access of the cycle `end` itself.
    let s = c.stats_until(4, 3);
    assert_eq!((s.mshr_outstanding_sum, s.mshr_held_sum), (4, 5));
    c.access(6, 3, 0);
    let s = c.stats_until(6, 5);
    assert_eq!((s.mshr_held_sum, s.mshr_full_cycles), (8, 3));
    assert_eq!(c.stats_until(7, 6).mshr_held_sum, 10);
    assert_eq!(c.stats().mshr_held_sum, 0, "event counters only");
}

#[test]
fn prefetched_lines_count_useful_once_late_when_merged_useless_when_evicted() {
    // 1 set x 2 ways, 4 MSHRs, no reserve.
    let mut c = Cache::new(&cfg(128, 2, 4, 4, 4)).unwrap();
    c.enable_prefetch_marks();
    let PrefetchLookup::Miss(e) = c.prefetch(1, 0, 0) else {
        panic!("a prefetch miss")
    };
    assert_eq!(c.allocated_now(), 1, "the free-MSHR register sees it");
    assert_eq!(c.prefetch(1, 0, 0), PrefetchLookup::Pending);
    assert!(matches!(c.prefetch(1, 2, 0), PrefetchLookup::Miss(_)));
    // A demand miss merges into the prefetch of block 2: late.
    assert_eq!(c.access(2, 2, 7), Lookup::Secondary);
    assert_eq!(c.fill_entry(3, e), &[] as &[u32], "completes nothing");
    assert_eq!(c.fill(3, 2), &[7]);
    assert_eq!(c.prefetch(4, 0, 0), PrefetchLookup::Hit);
    assert_eq!(c.prefetch_unused(), 1);
    assert_eq!(c.access(5, 0, 8), Lookup::Hit);
    assert_eq!(c.access(6, 0, 9), Lookup::Hit);
    let n = c.prefetch_counts();
    assert_eq!((n.useful, n.late, n.useless), (2, 1, 0));
    // Block 4 prefetched, never used, evicted by two demand fills.
    assert!(matches!(c.prefetch(7, 4, 0), PrefetchLookup::Miss(_)));
    c.fill(8, 4);
    for (t, b) in [(9, 6), (11, 8)] {
        assert_eq!(c.access(t, b, 0), Lookup::Miss);
        c.fill(t + 1, b);
    }
    assert!(!c.contains(4));
    assert_eq!(c.prefetch_counts().useless, 1);
    assert_eq!(c.prefetch_unused(), 0);
    // Demand counters never saw a prefetch.
    let s = c.stats();
    assert_eq!((s.accesses, s.misses, s.secondary_misses), (5, 2, 1));
}

#[test]
fn a_prefetch_waits_for_a_free_port_and_room_above_the_reserve() {
    let mut c = Cache::new(&cfg(512, 2, 3, 4, 1)).unwrap();
    c.enable_prefetch_marks();
    assert_eq!(c.access(1, 1, 0), Lookup::Miss);
    assert_eq!(c.prefetch(1, 5, 0), PrefetchLookup::PortBusy);
    assert!(matches!(c.prefetch(2, 5, 1), PrefetchLookup::Miss(_)));
    // Two of three occupied: one free is the reserve of 1.
    assert_eq!(c.prefetch(3, 6, 1), PrefetchLookup::NoRoom);
    assert!(matches!(c.prefetch(3, 6, 0), PrefetchLookup::Miss(_)));
    assert_eq!(c.prefetch(4, 7, 0), PrefetchLookup::NoRoom);
    assert_eq!(c.stats().port_busy, 0, "demand counters untouched");
}

/// The paper's worked example (Section III): a single-level cache with
/// 3 MSHRs in front of a main memory of fixed latency 7; 15 warps, one
/// access each, one warp presented per cycle from cycle 1, a refused warp
/// retried the next cycle. A miss in cycle `t` is answered at `t + 7`.
/// Returns (cycle the last warp finished, stall cycles, hits).
pub(crate) fn worked_example(order: &str) -> (u64, u64, u64) {
    let mut c = Cache::new(&cfg(64 * 64, 4, 3, 16, 1)).unwrap();
    let blocks: Vec<u64> = order.bytes().map(|b| u64::from(b - b'A')).collect();
    let mut replies: VecDeque<(u64, u64)> = VecDeque::new();
    let mut next = 0;
    let mut done = 0;
    let mut finish = 0;
    let mut now = 1;
    while done < blocks.len() {
        if next < blocks.len() {
            match c.access(now, blocks[next], next as u32) {
                Lookup::Hit => {
                    done += 1;
                    finish = now;
                    next += 1;
                }
                Lookup::Miss => {
                    replies.push_back((now + 7, blocks[next]));
                    next += 1;
                }
                Lookup::Secondary => next += 1,
                Lookup::Stall => {}
                other => panic!("unexpected {other:?}"),
            }
        }
        while replies.front().is_some_and(|&(at, _)| at == now) {
            let (_, b) = replies.pop_front().unwrap();
            done += c.fill(now, b).len();
            finish = now;
        }
        now += 1;
        assert!(now < 100);
    }
    (finish, c.stats().stall_cycles, c.stats().hits)
}

#[test]
fn paper_worked_example_scanline_order_takes_18_cycles() {
    assert_eq!(worked_example("AAAAABBBBBCCCCC"), (18, 0, 0));
}

#[test]
fn paper_worked_example_all_priority_first_takes_21_cycles_with_6_stalls() {
    // W0, W5, W10 first, then the rest: every later access hits (in
    // scanline order every non-primary access is a secondary miss).
    assert_eq!(worked_example("ABCAAAABBBBCCCC"), (21, 6, 12));
}

#[test]
fn paper_worked_example_wasp_spacing_takes_16_cycles() {
    // W5 right after W0, W10 delayed until an MSHR is about to free.
    assert_eq!(worked_example("ABAAAABBCBBCCCC").0, 16);
    assert_eq!(worked_example("ABAAAABBCBBCCCC").1, 0);
}
