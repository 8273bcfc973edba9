//! The memory hierarchy as a whole: end-to-end latencies against the
//! documented table, the paper's worked example through it, MSHR events,
//! refused configurations, blocking reports, ideal memory, determinism,
//! idle-tick skipping and the traced signals.

use super::*;
use crate::mem::config::{CacheConfig, DramConfig};
use crate::mem::prefetch::{PrefetchConfig, PrefetchKind};
use crate::mem::stats::MemStats;
use proptest::prelude::*;
use wasp_waves::Tracer;

fn small_cache(size: u32, ways: u32, hit: u32, mshrs: u32, merged: u32, ports: u32) -> CacheConfig {
    CacheConfig {
        size_bytes: size,
        ways,
        line_bytes: 64,
        hit_latency: hit,
        mshrs,
        max_merged: merged,
        ports,
    }
}

/// Completion cycle of a single access of core 0 to `block` presented at
/// `t` on an otherwise quiet system.
fn single(mem: &mut MemorySystem, t: u64, block: u64) -> u64 {
    let mut out = Vec::new();
    assert!(mem.access(t, 0, block, 99).accepted());
    for now in t..t + 1000 {
        mem.tick(now);
        mem.take_completions(0, &mut out);
        if !out.is_empty() {
            assert_eq!(out, vec![99]);
            return now;
        }
    }
    panic!("no completion");
}

/// Tick from cycle `now` on until idle; the last entries are held for
/// the cycle after their reply, so this takes at most two ticks.
fn settle(mem: &mut MemorySystem, now: u64) {
    for t in now..now + 2 {
        mem.tick(t);
    }
    assert!(mem.is_idle());
}

#[test]
fn end_to_end_latencies_match_the_documented_table() {
    for width4 in [false, true] {
        let extra = u64::from(width4);
        let mut mem = MemorySystem::new(&MemConfig::paper(width4)).unwrap();
        // Block 0: bank 0 row 0, closed bank -> row miss.
        assert_eq!(single(&mut mem, 10, 0), 10 + 118 + extra);
        // Block 8: bank 0 row 0 again -> row hit.
        assert_eq!(single(&mut mem, 200, 8), 200 + 68 + extra);
        // First-level hit.
        assert_eq!(single(&mut mem, 300, 8), 300);
        if width4 {
            // Evict block 8 from the 8-line fully associative L0 with 8
            // other blocks; then 8 is an L0 miss and an L1 hit: 2 cycles.
            let mut t = 400;
            for b in 100..108 {
                t = single(&mut mem, t, b) + 1;
            }
            assert_eq!(single(&mut mem, t, 8), t + 1);
            assert!(!mem.is_idle(), "the L0 entry is held through t + 2");
            settle(&mut mem, t + 2);
        }
        let s = mem.stats();
        // Blocks 100..108 open banks 4-7 and 1-3 (miss) and hit bank 0's row.
        assert_eq!(s.dram.row_misses, if width4 { 1 + 7 } else { 1 });
        assert_eq!(s.dram.row_hits, if width4 { 1 + 1 } else { 1 });
        assert!(mem.is_idle());
    }
    // L1 miss, L2 hit: a second core reads what the first brought in.
    let mut mem = MemorySystem::new(&MemConfig::paper(false)).unwrap();
    single(&mut mem, 0, 5);
    let mut out = Vec::new();
    assert_eq!(mem.access(500, 1, 5, 1), Access::Miss);
    let mut now = 500;
    while out.is_empty() {
        mem.tick(now);
        mem.take_completions(1, &mut out);
        now += 1;
    }
    assert_eq!(now - 1, 500 + 18);
    assert_eq!(mem.stats().l2.hits, 1);
    // Ideal memory: an L2 miss costs an L2 hit.
    let mut cfg = MemConfig::paper(false);
    cfg.ideal_memory = true;
    let mut mem = MemorySystem::new(&cfg).unwrap();
    assert_eq!(single(&mut mem, 7, 42), 7 + 18);
    assert_eq!(mem.stats().dram.requests, 1);
}

/// The worked example through the whole hierarchy: L1 only with 3 MSHRs,
/// a 1-cycle L2 with room to spare and a 6-cycle DRAM make a memory of
/// latency 7 behind a single-level cache (1 + 6 = 7 cycles from the L1
/// miss to the fill).
fn example_config() -> MemConfig {
    MemConfig {
        cores: 1,
        l0: None,
        l1: small_cache(4096, 4, 1, 3, 16, 1),
        l2: small_cache(4096, 4, 1, 16, 16, 1),
        dram: DramConfig {
            banks: 4,
            row_bytes: 2048,
            row_hit_latency: 6,
            row_miss_latency: 6,
            requests_per_cycle: 1,
            ..DramConfig::default()
        },
        ideal_memory: false,
        report_misses: false,
        prefetch: PrefetchConfig::default(),
    }
}

/// One warp per cycle from cycle 1, retried when refused; returns (cycle
/// the last warp finished, L1 stall cycles).
fn hierarchy_example(order: &str) -> (u64, u64) {
    let mut mem = MemorySystem::new(&example_config()).unwrap();
    let blocks: Vec<u64> = order.bytes().map(|b| u64::from(b - b'A')).collect();
    let (mut next, mut done, mut finish) = (0, Vec::new(), 0);
    let mut now = 1;
    while done.len() < blocks.len() {
        if next < blocks.len() && mem.access(now, 0, blocks[next], next as u32).accepted() {
            next += 1;
        }
        mem.tick(now);
        let before = done.len();
        mem.take_completions(0, &mut done);
        if done.len() > before {
            finish = now;
        }
        now += 1;
        assert!(now < 100);
    }
    (finish, mem.stats().l1.stall_cycles)
}

#[test]
fn paper_worked_example_through_the_hierarchy() {
    assert_eq!(hierarchy_example("AAAAABBBBBCCCCC"), (18, 0));
    assert_eq!(hierarchy_example("ABCAAAABBBBCCCC"), (21, 6));
    assert_eq!(hierarchy_example("ABAAAABBCBBCCCC"), (16, 0));
    // The cache-level harness agrees.
    for order in ["AAAAABBBBBCCCCC", "ABCAAAABBBBCCCC", "ABAAAABBCBBCCCC"] {
        let (f, s, _) = crate::mem::cache::tests::worked_example(order);
        assert_eq!((f, s), hierarchy_example(order), "{order}");
    }
}

#[test]
fn mshr_events_follow_allocation_reply_and_hold() {
    let mut mem = MemorySystem::new(&example_config()).unwrap();
    let ev = |m: &MemorySystem| m.mshr_events(0);
    assert_eq!(mem.access(1, 0, 0, 0), Access::Miss);
    assert_eq!(mem.access(1, 0, 1, 1), Access::PortBusy);
    mem.tick(1);
    let e = ev(&mem);
    assert_eq!(
        (
            e.capacity,
            e.allocated,
            e.replied,
            e.occupied,
            e.outstanding
        ),
        (3, 1, 0, 1, 1)
    );
    assert_eq!(mem.access(2, 0, 1, 1), Access::Miss);
    mem.tick(2);
    assert_eq!(mem.access(3, 0, 2, 2), Access::Miss);
    mem.tick(3);
    assert_eq!(
        (
            ev(&mem).occupied,
            ev(&mem).free(),
            ev(&mem).free_from_reply()
        ),
        (3, 0, 0)
    );
    for now in 4..8 {
        assert_eq!(mem.access(now, 0, 0, 9), Access::Stall);
        mem.tick(now);
        assert_eq!(ev(&mem).allocated, 0);
    }
    // Block 0's reply at 8: free for the register, still held by the cache.
    assert_eq!(mem.access(8, 0, 0, 9), Access::Stall);
    mem.tick(8);
    let e = ev(&mem);
    assert_eq!(
        (
            e.replied,
            e.occupied,
            e.outstanding,
            e.free_from_reply(),
            e.free()
        ),
        (1, 3, 2, 1, 0)
    );
    assert_eq!(mem.access(9, 0, 0, 9), Access::Stall);
    mem.tick(9);
    assert_eq!(mem.access(10, 0, 0, 9), Access::Hit);
    mem.tick(10);
    let mut out = Vec::new();
    mem.take_completions(0, &mut out);
    // Hits of a cycle come before that cycle's fills.
    assert_eq!(out, vec![0, 1, 9, 2]);
    let s = mem.stats().l1;
    assert_eq!((s.stall_cycles, s.stall_refusals, s.port_busy), (6, 6, 1));
    // Nothing moves in a cycle without accesses or replies.
    mem.tick(30);
    assert_eq!(
        ev(&mem),
        SchedCacheMshrs {
            capacity: 3,
            ..Default::default()
        }
    );
    assert!(mem.is_idle());
}

#[test]
fn l2_refusals_wait_in_the_l1_queue_and_count_at_the_l2() {
    let mut cfg = example_config();
    cfg.l1.mshrs = 8;
    cfg.l2.mshrs = 2;
    cfg.l2.ports = 4;
    let mut mem = MemorySystem::new(&cfg).unwrap();
    for (i, b) in [10u64, 11, 12, 13].into_iter().enumerate() {
        assert_eq!(mem.access(i as u64, 0, b, i as u32), Access::Miss);
        mem.tick(i as u64);
    }
    let mut out = Vec::new();
    let mut now = 4;
    while out.len() < 4 {
        mem.tick(now);
        mem.take_completions(0, &mut out);
        now += 1;
        assert!(now < 100);
    }
    let s = mem.stats();
    assert_eq!(s.l1.stall_cycles, 0);
    assert!(s.l2.stall_cycles > 0);
    assert_eq!((s.l2.misses, s.dram.requests), (4, 4));
    settle(&mut mem, now);
}

#[test]
fn misses_of_two_cores_merge_at_the_l2() {
    let mut cfg = MemConfig::paper(false);
    cfg.cores = 2;
    let mut mem = MemorySystem::new(&cfg).unwrap();
    assert_eq!(mem.access(0, 0, 77, 1), Access::Miss);
    mem.tick(0);
    assert_eq!(mem.access(1, 1, 77, 2), Access::Miss);
    let (mut a, mut b) = (Vec::new(), Vec::new());
    let mut now = 1;
    while a.is_empty() || b.is_empty() {
        mem.tick(now);
        mem.take_completions(0, &mut a);
        mem.take_completions(1, &mut b);
        now += 1;
    }
    let s = mem.stats();
    assert_eq!(
        (s.l2.misses, s.l2.secondary_misses, s.dram.requests),
        (1, 1, 1)
    );
    assert_eq!(s.per_core[0].l1.misses, 1);
    assert_eq!(s.per_core[1].l1.misses, 1);
    assert_eq!(s.l1.misses, 2);
    assert_eq!(s.l1.cycles, 2 * s.l2.cycles);
}

/// A map of one 16x16-texel level: 4x4 RGBA8 lines from block 0, stored
/// as ETC2 RGB (16x8 texels a line) in 1x2 lines from block 0x1000.
fn etc2_map() -> TextureMap {
    let mut map = TextureMap::new();
    map.push(crate::trace::MapLevel {
        first: 0,
        grid: (4, 4),
        stored_first: 0x1000,
        stored_grid: (1, 2),
        per_line: (4, 2),
    })
    .unwrap();
    map
}

#[test]
fn decoded_lines_in_the_l1s_share_their_stored_line_in_the_l2() {
    let mut cfg = MemConfig::paper(false);
    cfg.cores = 2;
    // Lines 0 and 1 (core 0) and 2 (core 1) lie in the top half of the
    // level: stored line 0x1000. Line 8 is in the bottom half: 0x1001.
    let run = |mapped: bool| {
        let mut mem = MemorySystem::new(&cfg).unwrap();
        if mapped {
            mem.map_texture_lines(etc2_map());
        }
        assert_eq!(mem.access(0, 0, 0, 1), Access::Miss);
        assert_eq!(mem.access(0, 1, 2, 3), Access::Miss);
        mem.tick(0);
        assert_eq!(mem.access(1, 0, 1, 2), Access::Miss);
        assert_eq!(mem.access(1, 1, 8, 4), Access::Miss);
        let (mut a, mut b) = (Vec::new(), Vec::new());
        let mut now = 1;
        while a.len() + b.len() < 4 {
            mem.tick(now);
            mem.take_completions(0, &mut a);
            mem.take_completions(1, &mut b);
            now += 1;
            assert!(now < 10_000, "no progress");
        }
        a.sort_unstable();
        b.sort_unstable();
        assert_eq!((a, b), (vec![1, 2], vec![3, 4]));
        // Each L1 holds its own decoded lines.
        settle(&mut mem, now);
        assert_eq!(mem.access(now + 2, 0, 1, 5), Access::Hit);
        assert_eq!(mem.access(now + 2, 1, 8, 6), Access::Hit);
        mem.stats()
    };
    let s = run(true);
    assert_eq!(s.l1.misses, 4);
    assert_eq!(
        (s.l2.misses, s.l2.secondary_misses, s.dram.requests),
        (2, 2, 2),
        "three L1 lines share one stored line, merged at the L2"
    );
    // Without the map every L1 line is an L2 line of its own.
    let s = run(false);
    assert_eq!((s.l2.misses, s.dram.requests), (4, 4));
}

#[test]
fn new_refuses_impossible_configurations() {
    let mut cfg = MemConfig::paper(true);
    cfg.l2.mshrs = 0;
    let e = MemorySystem::new(&cfg).unwrap_err();
    assert!(
        e.to_string().contains("l2.mshrs = 0: must be in 1..=4096"),
        "{e}"
    );
}

/// Every core presents its stream in order, up to `per_cycle` accesses a
/// cycle, retrying a refused one in the next cycle. Returns the cycle the
/// last tag completed, the completion log `(cycle, core, tag)` and stats.
fn drive(
    cfg: &MemConfig,
    streams: &[Vec<u64>],
    per_cycle: usize,
) -> (u64, Vec<(u64, usize, u32)>, MemStats) {
    let mut mem = MemorySystem::new(cfg).unwrap();
    let mut next = vec![0usize; streams.len()];
    let total: usize = streams.iter().map(Vec::len).sum();
    let mut log = Vec::with_capacity(total);
    let mut buf = Vec::new();
    let mut now = 0;
    while log.len() < total {
        for (k, s) in streams.iter().enumerate() {
            for _ in 0..per_cycle {
                if next[k] < s.len() && mem.access(now, k, s[next[k]], next[k] as u32).accepted() {
                    next[k] += 1;
                } else {
                    break;
                }
            }
        }
        mem.tick(now);
        for k in 0..streams.len() {
            buf.clear();
            mem.take_completions(k, &mut buf);
            log.extend(buf.iter().map(|&t| (now, k, t)));
        }
        now += 1;
        assert!(now < 10_000_000, "no progress");
    }
    settle(&mut mem, now);
    (now - 1, log, mem.stats())
}

/// A texture-like stream: each core walks its own region with reuse.
fn streams(cores: usize, len: usize) -> Vec<Vec<u64>> {
    (0..cores)
        .map(|k| {
            let mut x = 0x9E37_79B9_7F4A_7C15u64.wrapping_mul(k as u64 + 1);
            (0..len)
                .map(|i| {
                    x ^= x << 13;
                    x ^= x >> 7;
                    x ^= x << 17;
                    (k as u64) * 4096 + (i as u64 / 8) + x % 24
                })
                .collect()
        })
        .collect()
}

#[test]
fn miss_events_name_the_entries_whose_requests_missed_below() {
    let mut cfg = MemConfig::paper(true);
    cfg.report_misses = true;
    let mut mem = MemorySystem::new(&cfg).unwrap();
    // Tag 1 allocates L0 entry 0; its request misses in the L1 in cycle 1
    // (allocating L1 entry 0), and the L1's in the L2 in cycle 2.
    assert_eq!(mem.access_entry(0, 0, 5, 1), (Access::Miss, 0));
    assert_eq!(mem.access_entry(0, 0, 5, 2), (Access::SecondaryMiss, 0));
    assert_eq!(mem.access_entry(0, 0, 6, 3), (Access::PortBusy, 0));
    let mut ev = Vec::new();
    let mut log = Vec::new();
    for now in 0..4 {
        mem.tick(now);
        mem.take_miss_events(0, &mut ev);
        log.extend(ev.drain(..).map(|e| (now, e)));
    }
    assert_eq!(
        log,
        vec![
            (
                1,
                MissEvent::L1 {
                    l0: 0,
                    l1: 0,
                    merged: false
                }
            ),
            (2, MissEvent::L2 { l1: 0 })
        ]
    );
    // Core 1 misses in its L1 on the same block: the L2 merges it.
    assert_eq!(mem.access_entry(4, 1, 5, 9), (Access::Miss, 0));
    for now in 4..7 {
        mem.tick(now);
        mem.take_miss_events(1, &mut ev);
        log.extend(ev.drain(..).map(|e| (now, e)));
    }
    assert_eq!(
        log[2..],
        [
            (
                5,
                MissEvent::L1 {
                    l0: 0,
                    l1: 0,
                    merged: false
                }
            ),
            (6, MissEvent::L2 { l1: 0 })
        ]
    );
    // Not asked: nothing.
    cfg.report_misses = false;
    let mut mem = MemorySystem::new(&cfg).unwrap();
    assert_eq!(mem.access(0, 0, 5, 1), Access::Miss);
    for now in 0..200 {
        mem.tick(now);
        mem.take_miss_events(0, &mut ev);
        assert!(ev.is_empty());
    }
}

#[test]
fn ideal_memory_is_never_slower() {
    for width4 in [false, true] {
        let cfg = MemConfig::paper(width4);
        let mut ideal = cfg.clone();
        ideal.ideal_memory = true;
        let s = streams(4, 3000);
        let per_cycle = if width4 { 2 } else { 1 };
        let (real_t, real_log, real_stats) = drive(&cfg, &s, per_cycle);
        let (ideal_t, ideal_log, ideal_stats) = drive(&ideal, &s, per_cycle);
        assert!(
            ideal_t < real_t,
            "width4 {width4}: ideal {ideal_t} vs real {real_t}"
        );
        assert_eq!(real_log.len(), ideal_log.len());
        assert_eq!(ideal_stats.dram.latency_sum, 0);
        assert!(real_stats.dram.requests > 0);
    }
}

#[test]
fn same_inputs_same_outputs() {
    let cfg = MemConfig::paper(true);
    let s = streams(4, 2000);
    let a = drive(&cfg, &s, 2);
    let b = drive(&cfg, &s, 2);
    assert_eq!(a, b);
    // And a fresh system behaves like a cloned one.
    let mem = MemorySystem::new(&cfg).unwrap();
    let mut m2 = mem.clone();
    m2.tick(0);
    assert!(m2.is_idle());
}

#[test]
fn skipping_ticks_while_idle_changes_no_timing() {
    let mut cfg = MemConfig::paper(true);
    cfg.cores = 3;
    let s = streams(3, 200);
    // Bursts of accesses separated by long idle gaps.
    let run = |skip: bool| {
        let mut mem = MemorySystem::new(&cfg).unwrap();
        let mut next = [0usize; 3];
        let mut log = Vec::new();
        let mut buf = Vec::new();
        for now in 0..60_000u64 {
            let burst = now % 2000 < 40;
            if burst {
                for k in 0..3 {
                    if next[k] < s[k].len()
                        && mem.access(now, k, s[k][next[k]], next[k] as u32).accepted()
                    {
                        next[k] += 1;
                    }
                }
            } else if skip && mem.is_idle() {
                continue;
            }
            mem.tick(now);
            for k in 0..3 {
                buf.clear();
                mem.take_completions(k, &mut buf);
                log.extend(buf.iter().map(|&t| (now, k, t)));
            }
        }
        let mut st = mem.stats();
        st.l0 = None;
        st.per_core.clear();
        for c in [&mut st.l1, &mut st.l2] {
            c.cycles = 0;
        }
        (log, st)
    };
    let (a, sa) = run(false);
    let (b, sb) = run(true);
    assert_eq!(a.len(), 600);
    assert_eq!(a, b);
    assert_eq!(sa, sb);
}

/// Records signal names and widths, checks values fit.
#[derive(Default)]
struct Recorder {
    names: Vec<(String, u32)>,
    depth: i32,
}

impl Tracer for Recorder {
    fn push_scope(&mut self, name: &str) {
        self.depth += 1;
        self.names.push((format!("+{name}"), 0));
    }
    fn pop_scope(&mut self) {
        self.depth -= 1;
        self.names.push(("-".into(), 0));
    }
    fn signal(&mut self, name: &str, width: u32, value: u64) {
        assert!((1..=64).contains(&width));
        assert!(
            width == 64 || value >> width == 0,
            "{name} = {value} in {width} bits"
        );
        self.names.push((name.to_string(), width));
    }
}

#[test]
fn trace_visits_the_same_signals_every_cycle_and_values_fit() {
    for width4 in [false, true] {
        let mut cfg = MemConfig::paper(width4);
        cfg.cores = 2;
        let mut mem = MemorySystem::new(&cfg).unwrap();
        let s = streams(2, 400);
        let mut first: Option<Vec<(String, u32)>> = None;
        let mut next = [0usize; 2];
        let mut sink = Vec::new();
        for now in 0..3000u64 {
            for k in 0..2 {
                if next[k] < s[k].len() && mem.access(now, k, s[k][next[k]], 0).accepted() {
                    next[k] += 1;
                }
            }
            mem.tick(now);
            let mut r = Recorder::default();
            for k in 0..2 {
                r.push_scope("core");
                mem.trace(k, &mut r);
                r.pop_scope();
                mem.take_completions(k, &mut sink);
            }
            mem.trace_shared(&mut r);
            assert_eq!(r.depth, 0);
            match &first {
                None => first = Some(r.names),
                Some(f) => assert_eq!(f, &r.names),
            }
        }
        let names = first.unwrap();
        assert!(names.iter().any(|(n, _)| n == "+l0") == width4);
        assert!(names.iter().any(|(n, _)| n == "stall"));
    }
}

pub(super) fn arb_cache(max_hit: u32) -> impl Strategy<Value = CacheConfig> {
    (0u32..3, 0u32..2, 1..=max_hit, 1u32..5, 0u32..4, 1u32..3).prop_map(
        |(size_log, ways_log, hit, mshrs, merged, ports)| {
            small_cache(128 << size_log, 1 << ways_log, hit, mshrs, merged, ports)
        },
    )
}

/// Small random hierarchies (also for the plain twin's tests).
pub(super) fn arb_config() -> impl Strategy<Value = MemConfig> {
    (
        1u32..4,
        proptest::option::of(arb_cache(2)),
        arb_cache(3),
        arb_cache(6),
        (1u32..4, 1u32..4, 1u32..8, 1u32..12, 1u32..3),
        any::<bool>(),
        any::<bool>(),
        (any::<bool>(), 0u32..3, 1u32..6, any::<bool>()),
    )
        .prop_map(
            |(
                cores,
                l0,
                l1,
                l2,
                (banks, rows, hit, miss, rpc),
                ideal_memory,
                report_misses,
                (pf, reserve, queue, filter),
            )| MemConfig {
                cores,
                l0,
                l1,
                l2,
                dram: DramConfig {
                    banks,
                    row_bytes: 64 * rows,
                    row_hit_latency: hit,
                    row_miss_latency: miss,
                    requests_per_cycle: rpc,
                    ..DramConfig::default()
                },
                ideal_memory,
                report_misses,
                prefetch: PrefetchConfig {
                    kind: if pf {
                        PrefetchKind::Raster
                    } else {
                        PrefetchKind::None
                    },
                    queue,
                    queue_filter: filter,
                    l1_reserve: reserve.min(l1.mshrs - 1),
                },
            },
        )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    /// Every accepted access completes exactly once, never before it was
    /// made, refused ones never; MSHR occupancy stays within capacity; the
    /// system drains. Miss events come only when asked for, one per
    /// request that missed below the first level.
    #[test]
    fn accepted_accesses_complete_exactly_once(
        cfg in arb_config(),
        ops in proptest::collection::vec((0u8..4, 0u8..3, 0u64..40), 1..300),
    ) {
        let mut mem = MemorySystem::new(&cfg).unwrap();
        let n = cfg.cores as usize;
        let first = *cfg.scheduler_level();
        // Per tag: Some(access cycle) when accepted.
        let mut accepted: Vec<Option<u64>> = Vec::new();
        let mut completed: Vec<Option<u64>> = Vec::new();
        let mut owner: Vec<usize> = Vec::new();
        let mut events = 0u64;
        let mut buf = Vec::new();
        let mut ev = Vec::new();
        let mut now = 0u64;
        let mut ops = ops.into_iter();
        let mut draining = false;
        loop {
            if !draining {
                match ops.next() {
                    // (idle cycle when 0, accesses per core, block)
                    Some((0, _, _)) => {}
                    Some((_, count, block)) => {
                        for k in 0..n {
                            for j in 0..u64::from(count) {
                                let tag = accepted.len() as u32;
                                let r = mem.access(now, k, block + j * 7 + k as u64, tag);
                                accepted.push(r.accepted().then_some(now));
                                completed.push(None);
                                owner.push(k);
                            }
                        }
                    }
                    None => draining = true,
                }
            }
            mem.tick(now);
            for k in 0..n {
                let e = mem.mshr_events(k);
                prop_assert!(e.occupied <= e.capacity && e.outstanding <= e.occupied);
                prop_assert_eq!(e.capacity, first.mshrs);
                ev.clear();
                mem.take_miss_events(k, &mut ev);
                events += ev.len() as u64;
                buf.clear();
                mem.take_completions(k, &mut buf);
                for &t in &buf {
                    let t = t as usize;
                    prop_assert_eq!(owner[t], k);
                    let at = accepted[t];
                    prop_assert!(at.is_some(), "refused tag {} completed", t);
                    prop_assert!(at.unwrap() + u64::from(first.hit_latency) - 1 <= now);
                    prop_assert!(completed[t].is_none(), "tag {} completed twice", t);
                    completed[t] = Some(now);
                }
            }
            now += 1;
            if draining && mem.is_idle() {
                break;
            }
            prop_assert!(now < 100_000, "no drain");
        }
        for (a, c) in accepted.iter().zip(&completed) {
            prop_assert_eq!(a.is_some(), c.is_some());
        }
        let s = mem.stats();
        let fl = s.l0.unwrap_or(s.l1);
        prop_assert_eq!(fl.accesses, fl.hits + fl.misses + fl.secondary_misses);
        prop_assert_eq!(fl.accesses as usize, accepted.iter().filter(|a| a.is_some()).count());
        prop_assert_eq!(s.l2.misses, s.dram.requests);
        prop_assert_eq!(s.l2.fills, s.l2.misses);
        prop_assert_eq!(s.l1.fills, s.l1.misses);
        // An L1 event per L0 request the L1 missed, an L2 event per L1
        // request the L2 missed.
        let below = s.l2.misses + s.l2.secondary_misses
            + cfg.l0.map_or(0, |_| s.l1.misses + s.l1.secondary_misses);
        prop_assert_eq!(events, if cfg.report_misses { below } else { 0 });
    }
}
