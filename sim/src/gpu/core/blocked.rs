//! Which miss blocks a warp: the core's rule (`scheduler.blocked_on`), the
//! paper's long-latency state ("warps are marked as blocked when they
//! encounter a long-latency miss", Section IV-C) at the level the paper
//! does not name.
//!
//! A warp is blocked from the cycle one of its requests takes the miss
//! the rule names:
//! - `first-level`: a miss (primary or secondary) in the first level (L0,
//!   or L1 without L0), known at the access;
//! - `l1-miss`: a request that misses in the L1 (leaves the core for the
//!   L2). Without an L0 that is the access's own miss; with one, the
//!   request of the L0 MSHR entry the access allocated or merged into
//!   missing in the L1, or a later merge into an entry whose request did;
//! - `dram`: the same one level down: a request that misses in the L2.
//!
//! The rule learns of misses below the first level from the memory
//! system's [`MissEvent`]s, and keeps what it needs to name the warps they
//! block: per first-level MSHR entry, the warp slots whose accesses
//! allocated or merged into it (a slot mask) and whether a miss at the
//! rule's level holds it (then every later merge blocks at once); with an
//! L0 under `dram`, the same per L1 entry over the L0 entries whose
//! requests went into it. An entry's record starts again when it is
//! allocated, by an access or by a prefetch. Tags are warp slots, below
//! 128.

use crate::config::BlockedOn;
use crate::mem::{Access, MemorySystem, MissEvent};

/// How the rule learns of the misses that block.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mode {
    /// The first level's own misses block (`first-level`; `l1-miss`
    /// without an L0).
    AtAccess,
    /// The requests of L0 entries missing in the L1 (`l1-miss` with an
    /// L0).
    L0InL1,
    /// The requests of L1 entries, the first level, missing in the L2
    /// (`dram` without an L0).
    L1InL2,
    /// The requests of L1 entries missing in the L2, and the L0 entries
    /// whose requests went into them (`dram` with an L0).
    L0InL2,
}

/// The rule, for one core.
#[derive(Clone, Debug)]
pub(super) struct BlockedRule {
    mode: Mode,
    /// Per first-level MSHR entry: the slots waiting on it.
    waiting: Box<[u128]>,
    /// Per first-level MSHR entry: a miss at the rule's level holds it.
    marked: Vec<bool>,
    /// Per L1 MSHR entry (with an L0, under `dram`): the L0 entries whose
    /// requests allocated or merged into it.
    l1_waiting: Vec<Vec<u32>>,
    /// Per L1 MSHR entry: its request missed in the L2.
    l1_marked: Vec<bool>,
    /// The memory system's events of the cycle (scratch).
    events: Vec<MissEvent>,
}

impl BlockedRule {
    /// The rule `rule` for a core whose first level has `first_mshrs` MSHR
    /// entries (the L0's with an L0, `has_l0`) and whose L1 has
    /// `l1_mshrs`. The memory system must report its miss events when
    /// [`BlockedOn::reads_miss_events`] says so.
    pub(super) fn new(rule: BlockedOn, has_l0: bool, first_mshrs: u32, l1_mshrs: u32) -> Self {
        let mode = match (rule, has_l0) {
            (BlockedOn::FirstLevel, _) | (BlockedOn::L1Miss, false) => Mode::AtAccess,
            (BlockedOn::L1Miss, true) => Mode::L0InL1,
            (BlockedOn::Dram, false) => Mode::L1InL2,
            (BlockedOn::Dram, true) => Mode::L0InL2,
        };
        debug_assert_eq!(mode != Mode::AtAccess, rule.reads_miss_events(has_l0));
        let (first, l1) = match mode {
            Mode::AtAccess => (0, 0),
            Mode::L0InL1 | Mode::L1InL2 => (first_mshrs as usize, 0),
            Mode::L0InL2 => (first_mshrs as usize, l1_mshrs as usize),
        };
        BlockedRule {
            mode,
            waiting: vec![0; first].into(),
            marked: vec![false; first],
            l1_waiting: vec![Vec::new(); l1],
            l1_marked: vec![false; l1],
            events: Vec::new(),
        }
    }

    /// An access of warp slot `slot` had `result` at the first level, in
    /// MSHR entry `entry` for a miss ([`MemorySystem::access_entry`]):
    /// whether its warp blocks now.
    #[inline(always)]
    pub(super) fn at_access(&mut self, result: Access, entry: u32, slot: usize) -> bool {
        match result {
            Access::Hit | Access::Stall | Access::PortBusy => false,
            _ if self.mode == Mode::AtAccess => true,
            Access::Miss => {
                self.waiting[entry as usize] = 1u128 << (slot & 127);
                self.marked[entry as usize] = false;
                false
            }
            Access::SecondaryMiss => {
                self.waiting[entry as usize] |= 1u128 << (slot & 127);
                self.marked[entry as usize]
            }
        }
    }

    /// The memory system's miss events of `core` in the cycle: the slots
    /// they block (each at most once an episode). Take them before the
    /// cycle's completions.
    #[inline(always)]
    pub(super) fn take_events(&mut self, mem: &mut MemorySystem, core: usize) -> u128 {
        if self.mode == Mode::AtAccess || !mem.has_miss_events(core) {
            return 0;
        }
        self.apply_events(mem, core)
    }

    /// [`take_events`](Self::take_events) when there are some.
    #[inline(never)]
    fn apply_events(&mut self, mem: &mut MemorySystem, core: usize) -> u128 {
        let mut out = 0;
        let out = &mut out;
        mem.take_miss_events(core, &mut self.events);
        for i in 0..self.events.len() {
            match (self.mode, self.events[i]) {
                (Mode::L0InL1, MissEvent::L1 { l0: e, .. })
                | (Mode::L1InL2, MissEvent::L2 { l1: e }) => self.mark(e, out),
                // Below the rule's level.
                (Mode::L0InL1, MissEvent::L2 { .. }) => {}
                (Mode::L0InL2, MissEvent::L1 { l0, l1, merged }) => {
                    let w = &mut self.l1_waiting[l1 as usize];
                    if !merged {
                        w.clear();
                        self.l1_marked[l1 as usize] = false;
                    }
                    w.push(l0);
                    if self.l1_marked[l1 as usize] {
                        self.mark(l0, out);
                    }
                }
                (Mode::L0InL2, MissEvent::L2 { l1 }) => {
                    if !std::mem::replace(&mut self.l1_marked[l1 as usize], true) {
                        for k in 0..self.l1_waiting[l1 as usize].len() {
                            let e = self.l1_waiting[l1 as usize][k];
                            self.mark(e, out);
                        }
                    }
                }
                // A prefetch allocated an L1 entry no warp waits on yet:
                // its record starts afresh.
                (Mode::L1InL2, MissEvent::Prefetch { l1 }) => {
                    self.waiting[l1 as usize] = 0;
                    self.marked[l1 as usize] = false;
                }
                (Mode::L0InL2, MissEvent::Prefetch { l1 }) => {
                    self.l1_waiting[l1 as usize].clear();
                    self.l1_marked[l1 as usize] = false;
                }
                (Mode::L0InL1, MissEvent::Prefetch { .. }) => {}
                (Mode::AtAccess, _) | (Mode::L1InL2, MissEvent::L1 { .. }) => {
                    unreachable!("no events read, or none from an L0 there is not")
                }
            }
        }
        self.events.clear();
        *out
    }

    /// A miss at the rule's level holds first-level entry `e`: every slot
    /// waiting on it blocks, unless one did already.
    fn mark(&mut self, e: u32, out: &mut u128) {
        let e = e as usize;
        if !std::mem::replace(&mut self.marked[e], true) {
            *out |= self.waiting[e];
        }
    }
}

#[cfg(test)]
mod tests {
    //! The rule on the paper's memory system, access by access and cycle
    //! by cycle, and on random hierarchies.
    use super::*;
    use crate::mem::prefetch::PrefetchQueues;
    use crate::mem::{CacheConfig, DramConfig, MemConfig, PrefetchConfig, PrefetchKind};
    use proptest::prelude::*;

    /// (cycle, tag) pairs.
    type Events = Vec<(u64, u32)>;

    /// A core's memory system and its rule.
    struct Rig {
        mem: MemorySystem,
        rule: BlockedRule,
        /// Tags blocked, (cycle, tag), at their access or from events.
        blocked: Events,
        done: Events,
    }

    impl Rig {
        fn new(cfg: MemConfig, rule: BlockedOn) -> Self {
            let cfg = MemConfig {
                report_misses: rule.reads_miss_events(cfg.l0.is_some()),
                ..cfg
            };
            let first = cfg.scheduler_level().mshrs;
            let rule = BlockedRule::new(rule, cfg.l0.is_some(), first, cfg.l1.mshrs);
            Rig {
                mem: MemorySystem::new(&cfg).unwrap(),
                rule,
                blocked: vec![],
                done: vec![],
            }
        }

        fn paper(width4: bool, rule: BlockedOn) -> Self {
            Rig::new(MemConfig::paper(width4), rule)
        }

        fn access(&mut self, now: u64, core: usize, block: u64, tag: u32) -> Access {
            let (r, entry) = self.mem.access_entry(now, core, block, tag);
            if self.rule.at_access(r, entry, tag as usize) {
                self.blocked.push((now, tag));
            }
            r
        }

        /// Tick cycles `from..to`, taking `core`'s events, then its
        /// completions; returns what was blocked and completed since the
        /// last call.
        fn drive(&mut self, core: usize, from: u64, to: u64) -> (Events, Events) {
            let mut buf = Vec::new();
            for now in from..to {
                self.mem.tick(now);
                let slots = self.rule.take_events(&mut self.mem, core);
                self.blocked
                    .extend((0..128).filter(|&s| slots >> s & 1 == 1).map(|s| (now, s)));
                buf.clear();
                self.mem.take_completions(core, &mut buf);
                self.done.extend(buf.iter().map(|&t| (now, t)));
            }
            (
                std::mem::take(&mut self.blocked),
                std::mem::take(&mut self.done),
            )
        }
    }

    #[test]
    fn first_level_misses_block_at_the_access() {
        for width4 in [false, true] {
            let mut r = Rig::paper(width4, BlockedOn::FirstLevel);
            assert_eq!(r.access(0, 0, 77, 1), Access::Miss);
            let (blocked, _) = r.drive(0, 0, 1);
            assert_eq!(blocked, vec![(0, 1)]);
            assert_eq!(r.access(1, 0, 77, 2), Access::SecondaryMiss);
            let (blocked, done) = r.drive(0, 1, 200);
            assert_eq!((blocked, done.len()), (vec![(1, 2)], 2));
            // A hit blocks nothing.
            assert_eq!(r.access(200, 0, 77, 3), Access::Hit);
            assert_eq!(r.drive(0, 200, 201), (vec![], vec![(200, 3)]));
        }
    }

    #[test]
    fn an_l0_miss_blocks_when_the_l1_misses_not_when_it_hits() {
        let mut r = Rig::paper(true, BlockedOn::L1Miss);
        // Cycle 0: tags 1 and 2 (second port) miss and merge in the L0; the
        // L1 looks the block up in cycle 1, misses, and both block.
        assert_eq!(r.access(0, 0, 5, 1), Access::Miss);
        assert_eq!(r.access(0, 0, 5, 2), Access::SecondaryMiss);
        let (blocked, _) = r.drive(0, 0, 3);
        assert_eq!(blocked, vec![(1, 1), (1, 2)]);
        // Cycle 3: a merge into the entry blocks at once.
        assert_eq!(r.access(3, 0, 5, 3), Access::SecondaryMiss);
        let (blocked, done) = r.drive(0, 3, 300);
        assert_eq!(blocked, vec![(3, 3)]);
        assert_eq!(done.iter().map(|d| d.1).collect::<Vec<_>>(), [1, 2, 3]);
        // Evict block 5 from the 8-line L0; then it misses in the L0 and
        // hits in the L1: no block.
        let mut t = 300;
        for b in 100..108 {
            assert!(r.access(t, 0, b, 10).accepted());
            let (_, done) = r.drive(0, t, t + 300);
            assert_eq!(done.len(), 1);
            t += 300;
        }
        assert_eq!(r.access(t, 0, 5, 4), Access::Miss);
        assert_eq!(r.drive(0, t, t + 5), (vec![], vec![(t + 1, 4)]));
    }

    #[test]
    fn without_l0_an_l1_miss_blocks_at_the_access() {
        let mut r = Rig::paper(false, BlockedOn::L1Miss);
        assert_eq!(r.access(0, 0, 5, 1), Access::Miss);
        let (blocked, _) = r.drive(0, 0, 2);
        assert_eq!(blocked, vec![(0, 1)]);
        assert_eq!(r.access(2, 0, 5, 2), Access::SecondaryMiss);
        let (blocked, done) = r.drive(0, 2, 300);
        assert_eq!((blocked, done.len()), (vec![(2, 2)], 2));
        assert_eq!(r.access(300, 0, 5, 3), Access::Hit);
        assert_eq!(r.drive(0, 300, 301), (vec![], vec![(300, 3)]));
    }

    #[test]
    fn under_dram_l2_misses_block_and_l2_hits_do_not() {
        for width4 in [false, true] {
            let extra = u64::from(width4);
            let mut r = Rig::paper(width4, BlockedOn::Dram);
            // The L2 looks the L1's request up one cycle after the L1 miss.
            assert_eq!(r.access(0, 0, 5, 1), Access::Miss);
            let (blocked, _) = r.drive(0, 0, 3 + extra);
            assert_eq!(blocked, vec![(1 + extra, 1)]);
            // A later merge into the held entry (L0's, or L1's without L0)
            // blocks at the merge.
            assert_eq!(r.access(5, 0, 5, 2), Access::SecondaryMiss);
            let (blocked, done) = r.drive(0, 5, 300);
            assert_eq!((blocked, done.len()), (vec![(5, 2)], 2));
            // Core 1 misses in its L1 and hits in the L2: no block under
            // dram, a block under l1-miss.
            assert_eq!(r.access(300, 1, 5, 7), Access::Miss);
            assert_eq!(r.drive(1, 300, 400), (vec![], vec![(318 + extra, 7)]));
        }
        let mut r = Rig::paper(true, BlockedOn::L1Miss);
        assert_eq!(r.access(0, 0, 5, 1), Access::Miss);
        r.drive(0, 0, 300);
        assert_eq!(r.access(300, 1, 5, 7), Access::Miss);
        assert_eq!(r.drive(1, 300, 400), (vec![(301, 7)], vec![(319, 7)]));
    }

    #[test]
    fn under_dram_targets_merged_before_the_l2_miss_block_once() {
        // With an L0, tag 2 merges into the L0 entry in cycle 2, before the
        // L2 misses in that cycle's tick: both block then, once.
        let mut r = Rig::paper(true, BlockedOn::Dram);
        assert_eq!(r.access(0, 0, 9, 1), Access::Miss);
        assert_eq!(r.drive(0, 0, 2).0, vec![]);
        assert_eq!(r.access(2, 0, 9, 2), Access::SecondaryMiss);
        assert_eq!(r.drive(0, 2, 3).0, vec![(2, 1), (2, 2)]);
    }

    fn small_cache(size: u32, ways: u32, hit: u32, mshrs: u32, merged: u32) -> CacheConfig {
        CacheConfig {
            size_bytes: size,
            ways,
            line_bytes: 64,
            hit_latency: hit,
            mshrs,
            max_merged: merged,
            ports: 2,
        }
    }

    fn arb_cache(max_hit: u32) -> impl Strategy<Value = CacheConfig> {
        (0u32..3, 0u32..2, 1..=max_hit, 1u32..5, 0u32..4).prop_map(
            |(size_log, ways_log, hit, mshrs, merged)| {
                small_cache(128 << size_log, 1 << ways_log, hit, mshrs, merged)
            },
        )
    }

    /// Small hierarchies, some with a raster prefetcher (whose L1 entries
    /// the rule must start afresh).
    fn arb_config() -> impl Strategy<Value = MemConfig> {
        (
            proptest::option::of(arb_cache(2)),
            arb_cache(3),
            arb_cache(6),
            (1u32..8, 1u32..12),
            any::<bool>(),
            any::<bool>(),
        )
            .prop_map(|(l0, l1, l2, (hit, miss), ideal_memory, pf)| MemConfig {
                cores: 2,
                l0,
                l1,
                l2,
                dram: DramConfig {
                    row_hit_latency: hit,
                    row_miss_latency: miss,
                    ..DramConfig::default()
                },
                ideal_memory,
                report_misses: false,
                prefetch: PrefetchConfig {
                    kind: if pf {
                        PrefetchKind::Raster
                    } else {
                        PrefetchKind::None
                    },
                    l1_reserve: 0,
                    ..PrefetchConfig::default()
                },
            })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]

        /// Only accepted tags still waiting block, each at most once, and
        /// some do exactly when the rule's level missed. (Tags are warp
        /// slots, so there are at most 128 accesses.)
        #[test]
        fn only_waiting_tags_block_once_and_only_under_a_miss(
            cfg in arb_config(),
            rule in 0usize..3,
            ops in proptest::collection::vec((0u8..4, 0u8..3, 0u64..40), 1..60),
        ) {
            let rule = BlockedOn::ALL[rule];
            let mut r = Rig::new(cfg.clone(), rule);
            let mut accepted: Vec<bool> = Vec::new();
            let mut done: Vec<bool> = Vec::new();
            let mut blocked: Vec<bool> = Vec::new();
            let mut now = 0u64;
            let mut ops = ops.into_iter();
            loop {
                let op = ops.next();
                if let Some((n, count, block)) = op {
                    // A prefetch of a nearby block, when the machine has
                    // a prefetcher.
                    if cfg.prefetch.enabled() {
                        r.mem.prefetch_queue(0).offer(block + 2);
                    }
                    for j in 0..u64::from(count * u8::from(n > 0)) {
                        let tag = accepted.len() as u32;
                        let a = r.access(now, 0, block + j * 7, tag);
                        accepted.push(a.accepted());
                        done.push(false);
                        blocked.push(false);
                    }
                }
                let (b, d) = r.drive(0, now, now + 1);
                for (_, t) in b {
                    let t = t as usize;
                    prop_assert!(accepted[t] && !done[t] && !blocked[t], "tag {}", t);
                    blocked[t] = true;
                }
                for (_, t) in d {
                    done[t as usize] = true;
                }
                now += 1;
                if op.is_none() && r.mem.is_idle() {
                    break;
                }
                prop_assert!(now < 100_000, "no drain");
            }
            let s = r.mem.stats();
            let first = s.l0.unwrap_or(s.l1);
            let missed = match rule {
                BlockedOn::FirstLevel => first.misses + first.secondary_misses > 0,
                BlockedOn::L1Miss => s.l1.misses + s.l1.secondary_misses > 0,
                BlockedOn::Dram => s.l2.misses + s.l2.secondary_misses > 0,
            };
            let any = blocked.iter().any(|&b| b);
            if cfg.prefetch.enabled() {
                // The caches count the prefetches' misses too.
                prop_assert!(!any || missed);
            } else {
                prop_assert_eq!(any, missed);
            }
        }
    }
}
