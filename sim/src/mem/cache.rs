//! One set-associative, read-only, allocate-on-fill cache with an MSHR file.
//!
//! The cache decides what an access is (hit, primary miss, secondary miss or
//! refused) and records the line when its fill arrives; moving requests and
//! replies between levels, and the latencies of doing so, belong to
//! [`MemorySystem`](super::MemorySystem).
//!
//! Rules, in the order they are applied to an access in cycle `now`:
//! 1. every port already used this cycle -> [`Lookup::PortBusy`];
//! 2. every MSHR occupied -> [`Lookup::Stall`], whatever the access would
//!    have been, hits included (the paper's cache stall);
//! 3. line present -> [`Lookup::Hit`] (refreshes its LRU position);
//! 4. MSHR entry pending for the block -> [`Lookup::Secondary`] (merged), or
//!    [`Lookup::MergeFull`] when the entry already has `1 + max_merged`
//!    targets;
//! 5. otherwise -> [`Lookup::Miss`]: an MSHR entry is allocated.
//!
//! Refused accesses use no port. Fills: a fill in cycle `r` writes the line at
//! `r` (accesses from `r + 1` hit; accesses earlier in cycle `r` itself, which
//! the owner processes before fills, merge and are delivered at `r`), returns
//! the waiting targets, and the MSHR entry stays occupied through `r + 1`.
//! Replacement: the victim is an invalid way if any, else the least recently
//! used line of the set (lines are allocated only at fill, so a pending miss
//! never owns a way; the LRU valid line is evicted whatever is pending).
//!
//! Speed: a small counting filter over the blocks present lets most misses
//! of a small cache skip the tag search, and the MSHR file's own filter over
//! the pending blocks lets most primary misses skip the MSHR search; they
//! change no decision. Each set keeps its valid ways in recency order (a
//! doubly linked list), so the LRU victim is found without a scan.

use super::config::{CacheConfig, MemConfigError};
use super::mshr::{Merge, MshrFile};
use super::prefetch::marks::PrefetchMarks;
use super::prefetch::{MarkCounts, PrefetchLookup};
use super::stats::CacheStats;
use wasp_waves::Tracer;

/// Tag value of an invalid way (no block number reaches it: block numbers are
/// byte addresses divided by 64).
const INVALID: u64 = u64::MAX;

/// Buckets of the presence filter (see `Cache::filter`).
const FILTER_BUCKETS: usize = 256;

/// Bucket of `block` in the presence filter.
#[inline(always)]
fn bucket(block: u64) -> usize {
    (block % FILTER_BUCKETS as u64) as usize
}

/// What a cache did with one access.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Lookup {
    /// The line is present.
    Hit,
    /// Primary miss: an MSHR entry was allocated; the owner must send a
    /// request for the block to the next level.
    Miss,
    /// Merged into the pending MSHR entry for the block.
    Secondary,
    /// Refused: every MSHR is occupied (cache stall).
    Stall,
    /// Refused: the pending entry for the block cannot take another target.
    MergeFull,
    /// Refused: every port was already used this cycle.
    PortBusy,
}

impl Lookup {
    /// The access was taken (it will complete); otherwise it must be retried.
    #[inline]
    pub fn accepted(self) -> bool {
        matches!(self, Lookup::Hit | Lookup::Miss | Lookup::Secondary)
    }
}

/// One cache.
#[derive(Debug, Clone)]
pub struct Cache {
    cfg: CacheConfig,
    set_mask: u64,
    ways: usize,
    /// `sets * ways` tags (the full block number), [`INVALID`] when empty.
    tags: Vec<u64>,
    /// Recency order of each set's valid ways.
    order: Vec<SetOrder>,
    /// `sets * ways` links of that order.
    links: Vec<Link>,
    /// Presence filter: per bucket of block numbers, the blocks of the bucket
    /// that have a line. An access whose bucket is empty is a miss without
    /// searching the set (most misses of a small cache like the L0, primary
    /// or secondary: a pending block has no line).
    filter: [u32; FILTER_BUCKETS],
    mshr: MshrFile,
    /// The cycle the per-cycle fields below describe.
    cycle: u64,
    ports_used: u32,
    allocated: u32,
    replied: u32,
    hits_now: u32,
    stalled: bool,
    stats: CacheStats,
    /// Prefetched lines and entries (an L1 that takes prefetches; empty
    /// and never touched otherwise).
    marks: PrefetchMarks,
}

impl Cache {
    /// An empty cache, or an error when `cfg` cannot be modelled.
    pub fn new(cfg: &CacheConfig) -> Result<Self, MemConfigError> {
        cfg.check("cache")?;
        let sets = cfg.sets() as usize;
        let ways = cfg.ways as usize;
        Ok(Cache {
            cfg: *cfg,
            set_mask: sets as u64 - 1,
            ways,
            tags: vec![INVALID; sets * ways],
            order: vec![SetOrder::default(); sets],
            links: vec![Link::default(); sets * ways],
            filter: [0; FILTER_BUCKETS],
            mshr: MshrFile::new(cfg.mshrs, cfg.max_merged),
            cycle: 0,
            ports_used: 0,
            allocated: 0,
            replied: 0,
            hits_now: 0,
            stalled: false,
            stats: CacheStats::default(),
            marks: PrefetchMarks::default(),
        })
    }

    /// Let the cache take prefetches ([`Cache::prefetch`]) and keep the
    /// marks that tell whether each was useful ([`Cache::prefetch_counts`]).
    pub fn enable_prefetch_marks(&mut self) {
        self.marks = PrefetchMarks::new(self.tags.len(), self.cfg.mshrs as usize);
    }

    /// The configuration.
    #[inline]
    pub fn config(&self) -> &CacheConfig {
        &self.cfg
    }

    /// Move to cycle `now` (no-op when already there): per-cycle counters
    /// restart and MSHR entries whose hold has ended are freed. Cycles must
    /// not go backwards.
    #[inline]
    pub fn advance(&mut self, now: u64) {
        if now == self.cycle {
            return;
        }
        debug_assert!(now > self.cycle, "cache cycle went backwards");
        self.cycle = now;
        self.ports_used = 0;
        self.allocated = 0;
        self.replied = 0;
        self.hits_now = 0;
        self.stalled = false;
        self.mshr.release(now);
    }

    /// Present one access for `block` in cycle `now`. `target` is stored in
    /// the MSHR entry on a (primary or secondary) miss and handed back by
    /// [`Cache::fill`].
    #[inline(always)]
    pub fn access(&mut self, now: u64, block: u64, target: u32) -> Lookup {
        self.access_entry(now, block, target).0
    }

    /// [`Cache::access`], also returning the MSHR entry allocated when the
    /// lookup is [`Lookup::Miss`], or merged into when it is
    /// [`Lookup::Secondary`] (meaningless otherwise), for
    /// [`Cache::fill_entry`].
    #[inline(always)]
    pub fn access_entry(&mut self, now: u64, block: u64, target: u32) -> (Lookup, u32) {
        self.access_with::<true>(now, block, target)
    }

    /// [`Cache::access_entry`] for a cache that never takes a prefetch
    /// (the L0, the L2): the same lookup without the prefetch marks' tests,
    /// which the L0's accesses, the model's hottest path, do not carry.
    #[inline(always)]
    pub fn access_entry_unmarked(&mut self, now: u64, block: u64, target: u32) -> (Lookup, u32) {
        debug_assert!(
            !self.marks.live(),
            "a cache with prefetches keeps its marks"
        );
        self.access_with::<false>(now, block, target)
    }

    /// The lookup, keeping the prefetch marks when `MARKS` (a demand hit
    /// is the first use of a prefetched line, a merge into a prefetch's
    /// entry makes it late).
    #[inline(always)]
    fn access_with<const MARKS: bool>(
        &mut self,
        now: u64,
        block: u64,
        target: u32,
    ) -> (Lookup, u32) {
        self.advance(now);
        if self.ports_used >= self.cfg.ports {
            self.stats.port_busy += 1;
            return (Lookup::PortBusy, 0);
        }
        if self.mshr.is_full() {
            if !self.stalled {
                self.stalled = true;
                self.stats.stall_cycles += 1;
            }
            self.stats.stall_refusals += 1;
            return (Lookup::Stall, 0);
        }
        if self.filter[bucket(block)] != 0 {
            let set = self.set_of(block);
            let base = set * self.ways;
            if let Some(w) = find_way(&self.tags[base..base + self.ways], block) {
                self.touch(set, base, w as u32);
                if MARKS && self.marks.live() {
                    self.marks.hit(base + w);
                }
                self.ports_used += 1;
                self.hits_now += 1;
                self.stats.accesses += 1;
                self.stats.hits += 1;
                return (Lookup::Hit, 0);
            }
        }
        debug_assert!(!self.contains(block));
        match self.mshr.merge(block, target, now) {
            Merge::Merged(e) => {
                if MARKS && self.marks.live() {
                    self.marks.merged(e);
                }
                self.ports_used += 1;
                self.stats.accesses += 1;
                self.stats.secondary_misses += 1;
                return (Lookup::Secondary, e);
            }
            Merge::Full => {
                self.stats.merge_stalls += 1;
                return (Lookup::MergeFull, 0);
            }
            Merge::NotPending => {}
        }
        debug_assert!(!self.mshr.is_pending(block));
        let e = self.mshr.allocate(block, target, now);
        self.ports_used += 1;
        self.allocated += 1;
        self.stats.accesses += 1;
        self.stats.misses += 1;
        (Lookup::Miss, e)
    }

    /// The reply for `block` arrived in cycle `now`: write the line (evicting
    /// the LRU line of its set if needed) and return the targets that waited
    /// for it, primary first. Returns an empty slice if no miss was pending
    /// for `block` (which the hierarchy never does).
    #[inline]
    pub fn fill(&mut self, now: u64, block: u64) -> &[u32] {
        let Some(e) = self.mshr.find(block) else {
            debug_assert!(false, "fill of block {block} without a pending miss");
            self.advance(now);
            return &[];
        };
        self.fill_entry(now, e)
    }

    /// [`Cache::fill`] of the block of MSHR entry `e`, which must be pending
    /// (as returned by [`Cache::access_entry`] for a miss not yet filled):
    /// no search for the entry.
    #[inline(always)]
    pub fn fill_entry(&mut self, now: u64, e: u32) -> &[u32] {
        self.fill_with::<true>(now, e)
    }

    /// [`Cache::fill_entry`] for a cache that never takes a prefetch (see
    /// [`Cache::access_entry_unmarked`]).
    #[inline(always)]
    pub fn fill_entry_unmarked(&mut self, now: u64, e: u32) -> &[u32] {
        debug_assert!(
            !self.marks.live(),
            "a cache with prefetches keeps its marks"
        );
        self.fill_with::<false>(now, e)
    }

    /// The fill, keeping the prefetch marks when `MARKS`.
    #[inline(always)]
    fn fill_with<const MARKS: bool>(&mut self, now: u64, e: u32) -> &[u32] {
        self.advance(now);
        let block = self.mshr.complete(e, now);
        self.replied += 1;
        self.stats.fills += 1;
        let set = self.set_of(block);
        let base = set * self.ways;
        debug_assert!(
            !self.tags[base..base + self.ways].contains(&block),
            "fill of a block already present"
        );
        // The victim: the first invalid way, else the least recently used.
        // Lines are never invalidated and each fill takes the first invalid
        // way, so the valid ways are `0..valid`.
        let o = self.order[set];
        let way = if (o.valid as usize) < self.ways {
            let w = o.valid;
            self.order[set].valid = w + 1;
            if w == 0 {
                self.order[set].mru = 0;
                self.order[set].lru = 0;
            } else {
                self.links[base + o.mru as usize].newer = w;
                self.links[base + w as usize].older = o.mru;
                self.order[set].mru = w;
            }
            w as usize
        } else {
            self.touch(set, base, o.lru);
            o.lru as usize
        };
        debug_assert_eq!(
            Some(way),
            self.tags[base..base + self.ways]
                .iter()
                .position(|&t| t == INVALID)
                .or(Some(way)),
            "an invalid way is the victim when there is one"
        );
        let evicted = self.tags[base + way];
        if evicted != INVALID {
            self.filter[bucket(evicted)] -= 1;
        }
        if MARKS && self.marks.live() {
            self.marks.evicted(base + way);
            self.marks.filled(e, base + way);
        }
        self.filter[bucket(block)] += 1;
        self.tags[base + way] = block;
        self.stats.miss_wait_sum += self.mshr.wait_sum(e, now);
        self.mshr.targets(e)
    }

    /// A prefetch of `block` in cycle `now`, below demand (see
    /// `mem/prefetch`): not looked up while every port is used or at most
    /// `reserve` MSHRs are free; else one port: a present line or a
    /// pending miss drops it (no recency change, no demand counter), a
    /// miss allocates an MSHR entry with no target. Needs
    /// [`Cache::enable_prefetch_marks`].
    pub fn prefetch(&mut self, now: u64, block: u64, reserve: u32) -> PrefetchLookup {
        self.advance(now);
        if self.ports_used >= self.cfg.ports {
            return PrefetchLookup::PortBusy;
        }
        if self.mshr.free() <= reserve {
            return PrefetchLookup::NoRoom;
        }
        self.ports_used += 1;
        if self.filter[bucket(block)] != 0 && self.contains(block) {
            return PrefetchLookup::Hit;
        }
        if self.mshr.is_pending(block) {
            return PrefetchLookup::Pending;
        }
        let e = self.mshr.allocate_untargeted(block, now);
        self.allocated += 1;
        self.marks.allocated(e);
        PrefetchLookup::Miss(e)
    }

    /// What became of the prefetches this cache took.
    pub fn prefetch_counts(&self) -> MarkCounts {
        self.marks.counts()
    }

    /// Lines filled by a prefetch and not used by a demand access yet.
    pub fn prefetch_unused(&self) -> u64 {
        self.marks.unused()
    }

    /// Whether the line of `block` is present (no side effect).
    pub fn contains(&self, block: u64) -> bool {
        let base = self.set_base(block);
        find_way(&self.tags[base..base + self.ways], block).is_some()
    }

    /// Block of MSHR entry `e`, which must be pending.
    #[inline]
    pub fn pending_block(&self, e: u32) -> u64 {
        self.mshr.block(e)
    }

    /// The targets of pending MSHR entry `e` so far, in acceptance order
    /// (primary first).
    #[inline]
    pub fn pending_targets(&self, e: u32) -> &[u32] {
        self.mshr.targets(e)
    }

    /// Whether a miss for `block` is awaiting its reply.
    pub fn is_pending(&self, block: u64) -> bool {
        self.mshr.is_pending(block)
    }

    /// Free the MSHR entries whose hold has ended by cycle `now`, leaving
    /// the per-cycle values alone: what [`Cache::advance`] does for the
    /// MSHR occupancy, for an owner that reads it every cycle.
    #[inline]
    pub fn release(&mut self, now: u64) {
        self.mshr.release(now);
    }

    /// MSHR entries.
    #[inline]
    pub fn mshr_capacity(&self) -> u32 {
        self.mshr.capacity()
    }

    /// MSHR entries occupied (pending or in the cycle after their reply).
    #[inline]
    pub fn mshr_occupied(&self) -> u32 {
        self.mshr.occupied()
    }

    /// MSHR entries awaiting their reply.
    #[inline]
    pub fn mshr_outstanding(&self) -> u32 {
        self.mshr.outstanding()
    }

    /// MSHR entries allocated in the current cycle.
    #[inline]
    pub fn allocated_now(&self) -> u32 {
        self.allocated
    }

    /// Fills (MSHR replies) in the current cycle.
    #[inline]
    pub fn replied_now(&self) -> u32 {
        self.replied
    }

    /// Whether an access was refused for full MSHRs in the current cycle.
    #[inline]
    pub fn stalled_now(&self) -> bool {
        self.stalled
    }

    /// The cycle the per-cycle values describe.
    #[inline]
    pub fn cycle(&self) -> u64 {
        self.cycle
    }

    /// Event counters so far; the MSHR occupancy integrals and `cycles`
    /// read as zero here (see [`Cache::stats_until`]).
    #[inline]
    pub fn stats(&self) -> &CacheStats {
        &self.stats
    }

    /// Every counter, with the MSHR occupancy integrals over the cycles
    /// before `end` (each cycle's occupancy after that cycle's accesses and
    /// fills) and `cycles` set to `cycles`. `end` is the cycle after the
    /// last one the owner has finished; it must not be before the cycle of
    /// any access or fill so far, except accesses of cycle `end` itself.
    pub fn stats_until(&self, end: u64, cycles: u64) -> CacheStats {
        let i = self.mshr.integrals(end);
        CacheStats {
            mshr_held_sum: i.occupied,
            mshr_outstanding_sum: i.outstanding,
            mshr_full_cycles: i.full,
            cycles,
            ..self.stats
        }
    }

    /// Signals of this cache in cycle `now`: MSHR entries occupied and
    /// pending, allocations and replies in the cycle, the full and stall bits
    /// and the hits taken. Per-cycle values read as zero when the cache was
    /// not advanced to `now` (nothing happened to it).
    pub fn trace<T: Tracer + ?Sized>(&self, now: u64, t: &mut T) {
        let wm = bits_for(u64::from(self.mshr.capacity()));
        let wp = bits_for(u64::from(self.cfg.ports));
        let cur = self.cycle == now;
        let this_cycle = |v: u32| if cur { u64::from(v) } else { 0 };
        t.signal("mshr_used", wm, u64::from(self.mshr.occupied()));
        t.signal("mshr_pending", wm, u64::from(self.mshr.outstanding()));
        t.signal("mshr_alloc", wp, this_cycle(self.allocated));
        t.signal("mshr_reply", wm, this_cycle(self.replied));
        t.signal("mshr_full", 1, u64::from(self.mshr.is_full()));
        t.signal("stall", 1, u64::from(cur && self.stalled));
        t.signal("hits", wp, this_cycle(self.hits_now));
    }

    #[inline]
    fn set_base(&self, block: u64) -> usize {
        (block & self.set_mask) as usize * self.ways
    }

    #[inline]
    fn set_of(&self, block: u64) -> usize {
        (block & self.set_mask) as usize
    }

    /// Make valid way `w` of `set` (whose ways start at `base`) the most
    /// recently used.
    #[inline(always)]
    fn touch(&mut self, set: usize, base: usize, w: u32) {
        let o = &mut self.order[set];
        if o.mru == w {
            return;
        }
        // Unlink `w` (it has a newer neighbour: it is not the MRU) ...
        let Link { older, newer } = self.links[base + w as usize];
        self.links[base + newer as usize].older = older;
        if o.lru == w {
            o.lru = newer;
        } else {
            self.links[base + older as usize].newer = newer;
        }
        // ... and put it first.
        self.links[base + o.mru as usize].newer = w;
        self.links[base + w as usize].older = o.mru;
        o.mru = w;
    }
}

/// The valid ways of one set, `0..valid`, from the most (`mru`) to the least
/// (`lru`) recently used through [`Link`]s; `mru` and `lru` are meaningful
/// once `valid > 0`.
#[derive(Debug, Clone, Copy, Default)]
struct SetOrder {
    mru: u32,
    lru: u32,
    valid: u32,
}

/// Neighbours of a valid way in its set's recency order (way indices; the
/// `newer` of the MRU and the `older` of the LRU are meaningless).
#[derive(Debug, Clone, Copy, Default)]
struct Link {
    older: u32,
    newer: u32,
}

/// Way of `set` holding `block` (tags are distinct within a set: a line
/// is allocated only by the fill of a block not present).
#[inline]
fn find_way(set: &[u64], block: u64) -> Option<usize> {
    set.iter().position(|&t| t == block)
}

/// Bits needed to hold every value in `0..=max` (at least 1).
#[inline]
pub(crate) fn bits_for(max: u64) -> u32 {
    (64 - max.leading_zeros()).max(1)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use std::collections::VecDeque;

    pub(crate) fn cfg(
        size: u32,
        ways: u32,
        mshrs: u32,
        max_merged: u32,
        ports: u32,
    ) -> CacheConfig {
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
}
