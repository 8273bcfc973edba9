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
pub(crate) mod tests;
