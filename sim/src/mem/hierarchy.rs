//! The memory hierarchy of the GPU: per-core L0 (optional) and L1 texture
//! caches, a shared L2, main memory, and the queues and delays between them.
//! See the [module docs](super) for the timing model.

use super::cache::{Cache, Lookup};
use super::config::MemConfig;
use super::dram::Dram;
use super::prefetch::{PrefetchQueue, PrefetchQueues};
use super::ring::Ring;
use crate::trace::TextureMap;

mod answers;
mod build;
#[cfg(test)]
mod lockstep;
mod observe;
mod readout;
pub use answers::{Access, MissEvent, SchedCacheMshrs};
pub use observe::MshrFileView;

/// A request waiting to be presented to the next level.
#[derive(Debug, Clone, Copy, Default)]
struct Request {
    /// First cycle it may be presented.
    ready: u64,
    block: u64,
    /// The requesting cache's MSHR entry for the block.
    entry: u32,
}

/// A reply of the L1 arriving at the L0 at a given cycle, for the L0's MSHR
/// entry `entry` (the L0 requests carry their entry, which the L1 keeps as
/// its target).
#[derive(Debug, Clone, Copy, Default)]
struct Delivery {
    at: u64,
    entry: u32,
}

/// A core's private levels and the queues around them.
#[derive(Debug, Clone)]
struct CoreMem {
    l0: Option<Cache>,
    l1: Cache,
    /// L0 primary misses waiting to be presented to the L1 (only with L0).
    to_l1: Ring<Request>,
    /// L1 primary misses waiting to be presented to the L2.
    to_l2: Ring<Request>,
    /// Replies of the L1 travelling to the L0 (only with L0).
    to_l0: Ring<Delivery>,
    /// Tags and the cycle they complete, in completion-cycle order.
    completing: Ring<(u64, u32)>,
    /// Tags completed and not yet taken.
    ready: Vec<u32>,
    /// Miss events of the core's requests not yet taken.
    misses: Vec<MissEvent>,
    /// Not quiet at the start of the current tick (tick scratch).
    active: bool,
}

impl CoreMem {
    #[inline]
    fn first_level(&self) -> &Cache {
        super::config::first_level(self.l0.as_ref(), &self.l1).1
    }

    /// No MSHR entry occupied and nothing queued or completing, queued
    /// prefetches aside (the tick checks those itself): a tick has nothing
    /// to do for this core (its caches' per-cycle values are then simply
    /// not advanced; readers check the cycle they describe).
    #[inline]
    fn is_quiet(&self) -> bool {
        self.l1.mshr_occupied() == 0
            && self.l0.as_ref().is_none_or(|l0| l0.mshr_occupied() == 0)
            && self.to_l1.is_empty()
            && self.to_l2.is_empty()
            && self.to_l0.is_empty()
            && self.completing.is_empty()
    }
}

/// Cycle `now`'s prefetch step of core `c` and its queue `pf`, after the
/// cycle's demand lookups of its L1: the queue's head goes to the L1 on
/// the ports demand left free, above the MSHR reserve; each miss's request
/// joins the L1's queue to the L2 like a demand miss's (see
/// `mem/prefetch`).
#[inline(never)]
fn prefetch_step(now: u64, c: &mut CoreMem, pf: &mut PrefetchQueue, report: bool, reserve: u32) {
    let CoreMem {
        l1, to_l2, misses, ..
    } = c;
    pf.issue(
        |block| l1.prefetch(now, block, reserve),
        |block, entry| {
            to_l2.push_back(Request {
                ready: now + 1,
                block,
                entry,
            });
            // A new L1 entry no warp waits on yet: the cores' rule starts
            // its record afresh.
            if report {
                misses.push(MissEvent::Prefetch { l1: entry });
            }
        },
    );
}

/// The L1's reply for L0 MSHR entry `entry` reaches the L0 in cycle `now`:
/// fill it, and its targets complete after the L0's hit latency.
#[inline(always)]
fn fill_l0(
    l0: &mut Cache,
    completing: &mut Ring<(u64, u32)>,
    ready: &mut Vec<u32>,
    now: u64,
    entry: u32,
) {
    let at = now + u64::from(l0.config().hit_latency) - 1;
    complete_all(
        completing,
        ready,
        now,
        at,
        l0.fill_entry_unmarked(now, entry),
    );
}

/// Record that `tags` complete in cycle `at` (never before `now`), in
/// order: straight into `ready` when due now and nothing earlier is
/// waiting, else behind what waits. One decision serves them all: after
/// the first tag goes to `ready` (or to `completing`) so do the others.
#[inline(always)]
fn complete_all(
    completing: &mut Ring<(u64, u32)>,
    ready: &mut Vec<u32>,
    now: u64,
    at: u64,
    tags: &[u32],
) {
    if at <= now && completing.is_empty() {
        ready.extend(tags.iter().copied());
    } else {
        for &tag in tags {
            completing.push_back((at, tag));
        }
    }
}

/// Move the tags of `from` to the end of `out`, leaving `from` empty. The
/// usual case, an empty `out`, hands over the buffer instead of copying it.
#[inline]
fn hand_over(from: &mut Vec<u32>, out: &mut Vec<u32>) {
    if out.is_empty() {
        std::mem::swap(out, from);
    } else {
        out.extend_from_slice(from);
        from.clear();
    }
}

/// The L2 target of L1 entry `entry` of core `core` when the L1s hold
/// decoded lines (one L2 line then serves several L1 entries of a core).
#[inline]
fn l2_target(core: u32, entry: u32, l1_mshrs: u32) -> u32 {
    core * l1_mshrs + entry
}

/// The stored line and L2 target of core `core`'s L1 request `r` when the
/// L1s hold decoded lines (`map`).
#[inline(never)]
fn l2_request(map: &TextureMap, r: Request, core: u32, l1_mshrs: u32) -> (u64, u32) {
    (
        map.stored(r.block).unwrap_or(r.block),
        l2_target(core, r.entry, l1_mshrs),
    )
}

/// L2 reply to the L1 of a core.
#[derive(Debug, Clone, Copy, Default)]
struct L2Reply {
    at: u64,
    core: u32,
    block: u64,
}

/// The memory hierarchy.
///
/// Per cycle `now` the owner calls, in this order: [`access`](Self::access)
/// for that cycle's accesses (any cores, any order; the order within a core
/// is the order of its ports), [`tick`](Self::tick) once, then any of
/// [`take_miss_events`](Self::take_miss_events),
/// [`take_completions`](Self::take_completions),
/// [`mshr_events`](Self::mshr_events), [`trace`](Self::trace). Cycles must
/// not go backwards and `tick` should be called for every cycle; cycles in
/// which [`is_idle`](Self::is_idle) holds and no access is made may be
/// skipped without changing any timing (only the `cycles` counters of
/// [`stats`](Self::stats), which count ticks, see the difference).
///
/// Steady state allocates nothing: every queue is preallocated to its bound
/// (the MSHR counts), the MSHR files and tag arrays are flat vectors, and
/// replies travel in FIFOs sorted by construction (fixed latency per link).
#[derive(Debug, Clone)]
pub struct MemorySystem {
    cfg: MemConfig,
    cores: Vec<CoreMem>,
    l2: Cache,
    /// Each core's prefetch queue, in front of its L1 (`mem/prefetch`;
    /// never filled without a prefetcher).
    pf: Vec<PrefetchQueue>,
    /// Record [`MissEvent`]s.
    report_misses: bool,
    /// L2 hits and L2 fill deliveries travelling to the L1s, in cycle order.
    to_l1: Ring<L2Reply>,
    /// Cores taking part in the L2 arbitration of the current tick, in
    /// round-robin order (tick scratch, `cores` long at most).
    l2_order: Vec<u32>,
    dram: Dram,
    /// With L0/L1 texture caches holding decoded lines
    /// ([`map_texture_lines`](Self::map_texture_lines)): the map from a
    /// decoded (RGBA8) line to the stored line the L2 holds. `None`: every
    /// level holds the lines the trace lists.
    texmap: Option<TextureMap>,
    /// Last cycle seen.
    now: u64,
    /// Calls of `tick` so far (the `cycles` of every cache's stats).
    ticks: u64,
    /// The cycle after the last tick (0 before the first): the end of the
    /// cycles the MSHR occupancy integrals of [`stats`](Self::stats) cover.
    ticked_until: u64,
}

impl MemorySystem {
    /// The configuration.
    pub fn config(&self) -> &MemConfig {
        &self.cfg
    }

    /// Make the L0s and L1s hold decoded texture lines (the blocks the
    /// cores present) and the L2 and DRAM the stored (compressed) lines
    /// `map` gives for them (`memory.texture_cache = "decompressed"`): an
    /// L1 miss asks the L2 for the stored line holding its texels, so
    /// several L1 lines share one L2 line. An L1 miss whose stored line is
    /// already pending in the L2 merges into its entry as any secondary
    /// miss does (up to `l2.max_merged` targets, then the request waits),
    /// and the L2's reply fills each waiting L1 entry with its own line.
    /// A block the map does not cover goes to the L2 unchanged (the trace
    /// reader refuses such blocks in a decoded-lines trace). Call before
    /// the first access.
    pub fn map_texture_lines(&mut self, map: TextureMap) {
        self.texmap = Some(map);
    }

    /// Number of cores.
    pub fn cores(&self) -> usize {
        self.cores.len()
    }

    /// Present one access of core `core` for `block` to its first level (L0
    /// if present, else L1) in cycle `now`. `tag` is the requester's id,
    /// returned by [`take_completions`](Self::take_completions) exactly once
    /// if the access is accepted; a refused access leaves no trace but its
    /// counters and must be presented again. Panics if `core` is out of range.
    #[inline(always)]
    pub fn access(&mut self, now: u64, core: usize, block: u64, tag: u32) -> Access {
        self.access_entry(now, core, block, tag).0
    }

    /// [`access`](Self::access), with the first level's MSHR entry that a
    /// miss allocated or a secondary miss merged into (0 for other
    /// results): the entry the [`MissEvent`]s of its request name.
    #[inline(always)]
    pub fn access_entry(&mut self, now: u64, core: usize, block: u64, tag: u32) -> (Access, u32) {
        debug_assert!(now >= self.now, "access in a past cycle");
        self.now = now;
        let c = &mut self.cores[core];
        // The L0 never takes a prefetch: its lookups skip the marks.
        let (first, queue, lookup) = match c.l0.as_mut() {
            Some(l0) => {
                let lookup = l0.access_entry_unmarked(now, block, tag);
                (l0, &mut c.to_l1, lookup)
            }
            None => {
                let lookup = c.l1.access_entry(now, block, tag);
                (&mut c.l1, &mut c.to_l2, lookup)
            }
        };
        match lookup {
            (Lookup::Hit, _) => {
                let at = now + u64::from(first.config().hit_latency) - 1;
                complete_all(&mut c.completing, &mut c.ready, now, at, &[tag]);
                (Access::Hit, 0)
            }
            (Lookup::Miss, entry) => {
                queue.push_back(Request {
                    ready: now + 1,
                    block,
                    entry,
                });
                (Access::Miss, entry)
            }
            (Lookup::Secondary, entry) => (Access::SecondaryMiss, entry),
            (Lookup::Stall | Lookup::MergeFull, _) => (Access::Stall, 0),
            (Lookup::PortBusy, _) => (Access::PortBusy, 0),
        }
    }

    /// Advance everything by cycle `now`, after that cycle's accesses, in
    /// five steps:
    /// 1. `requests_to_l1`: the L1s take L0
    ///    requests, then, with a prefetcher, the heads of the prefetch
    ///    queues on the ports left (`prefetch_tick`);
    /// 2. `requests_to_l2`: the L2 takes L1
    ///    requests, round robin over cores;
    /// 3. `dram_to_l2`: the DRAM accepts requests and
    ///    its replies due at `now` fill the L2;
    /// 4. `l2_to_l1`: L2 replies due at `now` fill the
    ///    L1s;
    /// 5. `l1_to_l0`: L1 replies due at `now` fill the
    ///    L0s, and tags completing at `now` become available to
    ///    [`take_completions`](Self::take_completions).
    pub fn tick(&mut self, now: u64) {
        self.tick_steps::<true>(now);
    }

    /// [`tick`](Self::tick) without its shortcuts: the plain reference the
    /// lockstep tests (`hierarchy/lockstep.rs`) compare it with.
    #[cfg(test)]
    pub(crate) fn tick_plain(&mut self, now: u64) {
        self.tick_steps::<false>(now);
    }

    /// The five steps of a tick. With `SHORTCUTS` (the fast form) a step
    /// skips what cannot change anything, which the plain form
    /// (`SHORTCUTS` false) does not:
    /// - a quiet core (no MSHR occupied, nothing queued or completing) is
    ///   left out of steps 1 and 5 (it stays quiet through the tick: an L2
    ///   reply only goes to a core with an L1 MSHR entry pending);
    /// - the L2's candidates are found while step 1 visits the cores,
    ///   instead of by a scan from core `now % cores`;
    /// - an L1 hit due at `now` with no earlier reply queued for its L0
    ///   fills the L0 at once (no L0 access happens within a tick and the
    ///   L0's fills keep their order, so nothing can tell);
    /// - step 5 is skipped when no core has a reply or a tag queued.
    #[inline(always)]
    fn tick_steps<const SHORTCUTS: bool>(&mut self, now: u64) {
        debug_assert!(now >= self.now, "tick in a past cycle");
        self.now = now;
        self.ticks += 1;
        self.ticked_until = now + 1;
        let queued = self.requests_to_l1::<SHORTCUTS>(now);
        // Prefetches on the L1 ports demand left (their requests are ready
        // for the L2 from the next cycle, so step 2's candidates stand).
        if self.cfg.prefetch.enabled() {
            self.prefetch_tick(now);
        }
        self.requests_to_l2(now);
        self.dram_to_l2(now);
        let filled = self.l2_to_l1(now);
        if !SHORTCUTS || queued || filled {
            self.l1_to_l0::<SHORTCUTS>(now);
        }
    }

    /// Step 1: every core's MSHR occupancy made current, and its L0
    /// misses presented to its L1 in order until the L1 refuses one (the
    /// cores' private levels are independent). Cores whose L2 request is
    /// ready become the candidates of step 2, in `l2_order`, round robin
    /// from core `now % cores`. Returns whether some core has an L1 reply
    /// or a tag completing queued.
    ///
    /// (One pass over the cores does all of it, the L2's candidates
    /// included, because it runs every cycle; only their order is put right
    /// after it, by [`Self::order_l2_candidates`], at no cost. Moving the
    /// L0's loop into a function of its own, inlined, costs 3.6 host
    /// instructions per core-cycle, `scripts/icount.sh`.)
    #[inline(always)]
    fn requests_to_l1<const SHORTCUTS: bool>(&mut self, now: u64) -> bool {
        let report = self.report_misses;
        let first = (now % self.cores.len() as u64) as usize;
        self.l2_order.clear();
        // Candidates before core `first` in index order, moved behind the
        // others at the end.
        let mut wrapped = 0;
        let mut queued = false;
        // An L1 hit of this tick is due at `l1_reply`, now when `l1_direct`.
        let l1_reply = now + u64::from(self.cfg.l1.hit_latency) - 1;
        let l1_direct = SHORTCUTS && l1_reply <= now;
        for (k, c) in self.cores.iter_mut().enumerate() {
            c.active = !SHORTCUTS || !c.is_quiet();
            if !c.active {
                continue;
            }
            // Only the MSHR occupancy must be current for the readers; the
            // per-cycle values move to `now` with the first access or fill
            // of the cycle (readers check the cycle they describe, and read
            // zero before it).
            c.l1.release(now);
            if let Some(l0) = c.l0.as_mut() {
                l0.release(now);
                while let Some(&r) = c.to_l1.front() {
                    if r.ready > now {
                        break;
                    }
                    // The L1's target is the L0 entry to fill.
                    match c.l1.access_entry(now, r.block, r.entry) {
                        // Due now with nothing ahead of it in `to_l0`: fill
                        // the L0 at once, in the same order as through the
                        // queue.
                        (Lookup::Hit, _) if l1_direct && c.to_l0.is_empty() => {
                            fill_l0(l0, &mut c.completing, &mut c.ready, now, r.entry);
                        }
                        (Lookup::Hit, _) => c.to_l0.push_back(Delivery {
                            at: l1_reply,
                            entry: r.entry,
                        }),
                        (Lookup::Miss, entry) => {
                            c.to_l2.push_back(Request {
                                ready: now + 1,
                                block: r.block,
                                entry,
                            });
                            if report {
                                c.misses.push(MissEvent::L1 {
                                    l0: r.entry,
                                    l1: entry,
                                    merged: false,
                                });
                            }
                        }
                        (Lookup::Secondary, entry) => {
                            if report {
                                c.misses.push(MissEvent::L1 {
                                    l0: r.entry,
                                    l1: entry,
                                    merged: true,
                                });
                            }
                        }
                        (Lookup::Stall | Lookup::MergeFull | Lookup::PortBusy, _) => break,
                    }
                    c.to_l1.drop_front();
                }
            }
            if SHORTCUTS && c.to_l2.front().is_some_and(|r| r.ready <= now) {
                self.l2_order.push(k as u32);
                if k < first {
                    wrapped += 1;
                }
            }
            queued |= !c.to_l0.is_empty() | !c.completing.is_empty();
        }
        self.order_l2_candidates::<SHORTCUTS>(now, first, wrapped);
        queued
    }

    /// The end of step 1: `l2_order` made the cores whose L2 request is
    /// ready in cycle `now`, round robin from core `first`. With shortcuts
    /// the pass over the cores has listed them in index order, `wrapped` of
    /// them before `first`, which move behind the others; without, they are
    /// listed here.
    #[inline(always)]
    fn order_l2_candidates<const SHORTCUTS: bool>(
        &mut self,
        now: u64,
        first: usize,
        wrapped: usize,
    ) {
        if !SHORTCUTS {
            let ready = |c: &CoreMem| c.to_l2.front().is_some_and(|r| r.ready <= now);
            let cores = &self.cores;
            let order = (first..cores.len()).chain(0..first);
            self.l2_order
                .extend(order.filter(|&k| ready(&cores[k])).map(|k| k as u32));
        } else if wrapped > 0 {
            self.l2_order.rotate_left(wrapped);
        }
    }

    /// Step 2: L1 misses to the L2, in rounds over the candidates (core
    /// `now % cores` first, so the order does not depend on which cycles
    /// were ticked), one ready head per core per round, until the L2's
    /// ports are used or no head can go. A core leaves the rounds when the
    /// L2 refuses its head (MSHRs full or merge full) or its next head is
    /// not ready.
    ///
    /// When the L1s hold decoded lines ([`map_texture_lines`](Self::
    /// map_texture_lines)) the L2 is asked for the stored line and its
    /// target names the L1 entry to fill ([`l2_request`]).
    #[inline(always)]
    fn requests_to_l2(&mut self, now: u64) {
        let report = self.report_misses;
        let l2_reply = now + u64::from(self.l2.config().hit_latency) - 1;
        'arbitrate: while !self.l2_order.is_empty() {
            let mut kept = 0;
            for i in 0..self.l2_order.len() {
                let core = self.l2_order[i];
                let c = &mut self.cores[core as usize];
                let Some(&r) = c.to_l2.front() else {
                    unreachable!("an L2 candidate has a request")
                };
                // With decoded lines in the L1s the L2 sees the stored line,
                // and its target names the L1 entry to fill.
                let (block, target) = match &self.texmap {
                    None => (r.block, core),
                    Some(map) => l2_request(map, r, core, self.cfg.l1.mshrs),
                };
                match self.l2.access_entry_unmarked(now, block, target) {
                    (Lookup::Hit, _) => self.to_l1.push_back(L2Reply {
                        at: l2_reply,
                        core,
                        block: r.block,
                    }),
                    (Lookup::Miss, entry) => {
                        self.dram.request(now, block, entry);
                        if report {
                            c.misses.push(MissEvent::L2 { l1: r.entry });
                        }
                    }
                    (Lookup::Secondary, _) => {
                        if report {
                            c.misses.push(MissEvent::L2 { l1: r.entry });
                        }
                    }
                    (Lookup::PortBusy, _) => break 'arbitrate,
                    (Lookup::Stall | Lookup::MergeFull, _) => continue,
                }
                c.to_l2.drop_front();
                if c.to_l2.front().is_some_and(|r| r.ready <= now) {
                    self.l2_order[kept] = core;
                    kept += 1;
                }
            }
            self.l2_order.truncate(kept);
        }
    }

    /// Step 3: main memory accepts requests, and its replies due at `now`
    /// fill the L2; their targets travel on to the L1s.
    #[inline(always)]
    fn dram_to_l2(&mut self, now: u64) {
        let l2_reply = now + u64::from(self.l2.config().hit_latency) - 1;
        self.dram.accept(now);
        while let Some(entry) = self.dram.pop_reply(now) {
            if self.texmap.is_some() {
                self.fill_l2_decoded(now, entry, l2_reply);
                continue;
            }
            let block = self.l2.pending_block(entry);
            for &core in self.l2.fill_entry_unmarked(now, entry) {
                self.to_l1.push_back(L2Reply {
                    at: l2_reply,
                    core,
                    block,
                });
            }
        }
        // Keep the L2's MSHR occupancy current for its readers.
        self.l2.release(now);
    }

    /// Step 3's fill of L2 entry `entry` when the L1s hold decoded lines:
    /// each target is an L1 entry ([`l2_target`]) waiting for its own
    /// decoded line, which the reply carries up.
    #[inline(never)]
    fn fill_l2_decoded(&mut self, now: u64, entry: u32, l2_reply: u64) {
        let l1_mshrs = self.cfg.l1.mshrs;
        for &t in self.l2.fill_entry_unmarked(now, entry) {
            let (core, e) = (t / l1_mshrs, t % l1_mshrs);
            self.to_l1.push_back(L2Reply {
                at: l2_reply,
                core,
                block: self.cores[core as usize].l1.pending_block(e),
            });
        }
    }

    /// Step 4: L2 replies due at `now` fill the L1s; their targets go on to
    /// the L0 (each the MSHR entry of one L0 miss) or, without L0,
    /// complete. Returns whether any reply arrived.
    #[inline(always)]
    fn l2_to_l1(&mut self, now: u64) -> bool {
        let has_l0 = self.cfg.l0.is_some();
        let mut filled = false;
        while let Some(r) = self.to_l1.pop_front_if(|r| r.at <= now) {
            let c = &mut self.cores[r.core as usize];
            let at = now + u64::from(c.l1.config().hit_latency) - 1;
            let targets = c.l1.fill(now, r.block);
            filled = true;
            if has_l0 {
                for &entry in targets {
                    c.to_l0.push_back(Delivery { at, entry });
                }
            } else {
                complete_all(&mut c.completing, &mut c.ready, now, at, targets);
            }
        }
        filled
    }

    /// Step 5: L1 replies due at `now` fill the L0s; tags due at `now`
    /// complete. (A core quiet at the start of the tick has neither.)
    #[inline(always)]
    fn l1_to_l0<const SHORTCUTS: bool>(&mut self, now: u64) {
        for c in &mut self.cores {
            if SHORTCUTS && !c.active {
                continue;
            }
            if let Some(l0) = c.l0.as_mut() {
                while let Some(d) = c.to_l0.pop_front_if(|d| d.at <= now) {
                    fill_l0(l0, &mut c.completing, &mut c.ready, now, d.entry);
                }
            }
            while let Some((_, tag)) = c.completing.pop_front_if(|&(at, _)| at <= now) {
                c.ready.push(tag);
            }
        }
    }

    /// Append to `out` the tags of `core` completed by the last
    /// [`tick`](Self::tick) (and any not taken before), in completion order:
    /// by completion cycle, then hits in access order before fills, fills in
    /// the order they arrived, each fill's targets in access order.
    #[inline]
    pub fn take_completions(&mut self, core: usize, out: &mut Vec<u32>) {
        hand_over(&mut self.cores[core].ready, out);
    }

    /// Whether `core` has [`MissEvent`]s not taken.
    #[inline]
    pub fn has_miss_events(&self, core: usize) -> bool {
        !self.cores[core].misses.is_empty()
    }

    /// Append to `out` the [`MissEvent`]s of `core`'s requests since they
    /// were last taken, in the order they happened (none unless
    /// [`MemConfig::report_misses`]). A core that takes them before its
    /// completions of the cycle sees every miss of a request before the
    /// request's data.
    #[inline]
    pub fn take_miss_events(&mut self, core: usize, out: &mut Vec<MissEvent>) {
        let from = &mut self.cores[core].misses;
        if out.is_empty() {
            std::mem::swap(out, from);
        } else {
            out.append(from);
        }
    }

    /// Nothing of the last cycle for `core`: no tag completed and not
    /// taken, no [`MissEvent`] not taken, and its scheduler-level cache
    /// allocated and filled no MSHR entry in the cycle (its
    /// [`mshr_events`](Self::mshr_events) count none).
    #[inline(always)]
    pub fn nothing_for(&self, core: usize) -> bool {
        let c = &self.cores[core];
        let f = c.first_level();
        c.ready.is_empty()
            && c.misses.is_empty()
            && (f.cycle() != self.now || f.allocated_now() | f.replied_now() == 0)
    }

    /// The scheduler-level cache's MSHR events of `core` in the last cycle.
    #[inline]
    pub fn mshr_events(&self, core: usize) -> SchedCacheMshrs {
        let f = self.cores[core].first_level();
        let current = f.cycle() == self.now;
        SchedCacheMshrs {
            capacity: f.mshr_capacity(),
            allocated: if current { f.allocated_now() } else { 0 },
            replied: if current { f.replied_now() } else { 0 },
            occupied: f.mshr_occupied(),
            outstanding: f.mshr_outstanding(),
        }
    }

    /// Nothing in flight anywhere: no MSHR entry occupied (awaiting its
    /// reply or in the cycle after it), no request or reply travelling, no
    /// prefetch queued, no tag completing or completed and not taken.
    /// While this holds, ticks change nothing but the tick count. (Miss
    /// events not taken do not count: they are notices, not work in
    /// flight.)
    pub fn is_idle(&self) -> bool {
        self.cores
            .iter()
            .all(|c| c.is_quiet() && c.ready.is_empty())
            && self.pf.iter().all(PrefetchQueue::is_empty)
            && self.l2.mshr_occupied() == 0
            && self.to_l1.is_empty()
            && self.dram.is_idle()
    }

    /// A 64-byte line write of the colour-buffer flush to main memory in
    /// cycle `now` (see [`Dram::write`]): it bypasses the caches.
    pub fn write_back(&mut self, now: u64, block: u64) {
        self.dram.write(now, block);
    }
}

impl MemorySystem {
    /// Step 1's prefetches: every core with a prefetch queued, after the
    /// cycle's demand lookups (see [`prefetch_step`]).
    #[inline(never)]
    fn prefetch_tick(&mut self, now: u64) {
        let reserve = self.cfg.prefetch.l1_reserve;
        for (c, pf) in self.cores.iter_mut().zip(&mut self.pf) {
            if !pf.is_empty() {
                prefetch_step(now, c, pf, self.report_misses, reserve);
            }
        }
    }
}

/// The memory system keeps the prefetch queues, one in front of each L1.
impl PrefetchQueues for MemorySystem {
    fn prefetch_queue(&mut self, core: usize) -> &mut PrefetchQueue {
        &mut self.pf[core]
    }
}

#[cfg(test)]
mod tests;
