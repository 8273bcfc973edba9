//! One shader core: raster input, launch scheduler, warp slots, issue,
//! the LDST unit and the texture unit.
//!
//! Per cycle `now` (phase 1, combinational from current state):
//! 1. wake-ups: warps whose ALU result or texture data is ready become
//!    ready to issue, or finish if their program is done;
//! 2. raster (per-core-tile dispatch only): the core's own rasterizer
//!    produces up to its share of `raster.quads_per_cycle` quads of its
//!    tile; Early-Z-rejected quads take their slot and go nowhere, the others
//!    enter the input queue (the subset comparator picks the FIFO). Under
//!    shared-tile dispatch the GPU's one rasterizer fills the queue instead
//!    ([`ShaderCore::push_quad`], `gpu/raster.rs`);
//! 3. launch: one warp per cycle from the FIFO the policy selects under
//!    the launch rule (`scheduler.launch_rule`), if a warp slot is free; a
//!    cycle in which `hold` keeps a lone priority warp back is a hold idle
//!    cycle ([`CoreStats::held_cycles`]);
//! 4. issue: up to `pipeline_width` ready warps issue one instruction each,
//!    in loose round-robin order; a texture instruction enters the LDST
//!    queue (one per cycle, if it has room);
//! 5. LDST: the oldest texture instruction presents its unique blocks to the
//!    first cache level, in order, until the cache refuses (ports used or
//!    MSHRs full).
//!
//! Then the memory system ticks, and (phase 2) the warps whose requests began
//! to wait on a long-latency miss are marked blocked, then completions
//! arrive: a warp whose last block arrived enters the core's one filter
//! unit, in order of arrival, and wakes when its filter pass and the texture
//! latency are done (`core.filter_timing`: `max(s + f, a + L)` or
//! `s + f + L` for arrival `a`, filter start `s = max(a, filter free)`,
//! filter cycles `f` and `L = max(texture_latency, 1)`; with no filter
//! cycles, `a + L`). The scheduler's registers are clocked with the cycle's
//! MSHR and priority-warp events.
//!
//! A warp is *blocked* (the paper's long-latency state: "warps are marked as
//! blocked when they encounter a long-latency miss", Section IV-C) from the
//! cycle one of its requests of a texture instruction takes the miss that
//! `scheduler.blocked_on` names until its last block arrives:
//! - `first-level`: a miss in the first level (L0, or L1 without L0), seen
//!   by the LDST unit at the access (phase 1);
//! - `l1-miss`: a miss in the L1 (a request leaving the core), which the
//!   memory system reports ([`MemorySystem::take_long_latency`]) in the
//!   cycle of the L1 lookup (phase 2);
//! - `dram`: a miss in the L2, reported the same way.
//!
//! Each blocked episode of a priority warp counts once in the non-blocked
//! counter's events. A blocked warp cannot issue: each warp's instructions
//! depend on the previous one, so nothing else of it is fetched meanwhile;
//! a warp waiting on shorter misses cannot issue either, but counts as not
//! blocked.

use crate::gpu::raster_cursor::RasterCursor;
use crate::mem::{Access, MemorySystem};
use crate::trace::{OpKind, Tile, Trace};
use issue::{pick, Picks};
use mask::SlotMask;
use std::collections::VecDeque;
use wasp_rtl::free_mshr::FreeMshrReg;
use wasp_rtl::nonblocked::PriorityEvents;
use wasp_rtl::policy::{LaunchPolicy, LaunchRule};
use wasp_rtl::queue::QueueClass;
use wasp_rtl::scheduler::LaunchScheduler;
use wasp_rtl::subset::PrioritySubset;
use wheel::WakeWheel;

mod blocked;
mod complete;
mod issue;
mod mask;
mod observe;
mod params;
#[cfg(test)]
pub(crate) mod plain;
mod stats;
#[cfg(test)]
mod testkit;
mod warp;
mod wheel;
pub use observe::{CoreSnapshot, WarpView};
pub use params::CoreParams;
pub use stats::{CoreStats, WarpRecord};
use warp::{block_warp, Warp};

/// Warp slots a core can have (the slot masks' width). The slot array
/// always has this many entries, so that indexing it with a slot number
/// masked to this power of two needs no bounds check.
const MAX_SLOTS: usize = 128;

/// A texture instruction in the LDST unit: its blocks are
/// `next..end` of the tile's block accesses.
#[derive(Clone, Copy, Debug)]
struct LdstEntry {
    slot: u8,
    /// Next block to present.
    next: u32,
    /// One past its last block.
    end: u32,
}

/// Per-cycle signals of the core, for the waveform.
#[derive(Clone, Copy, Debug, Default)]
struct CoreSignals {
    issued: u32,
    tex_issued: bool,
    ldst_presented: u32,
    ldst_refused: bool,
    finished: u32,
    /// The warp launched in the cycle: (quad index, priority).
    launched: Option<(u32, bool)>,
}

/// One shader core.
#[derive(Debug)]
pub struct ShaderCore {
    id: usize,
    p: CoreParams,
    /// First cycle the filter unit is free.
    filter_free: u64,
    sched: LaunchScheduler<u32>,
    /// Whether the free-MSHR register follows the cache (policies that
    /// read it).
    track_mshrs: bool,
    /// Whether the scheduler has a CF meter (`wasp-m`): primary misses of
    /// priority warps are then counted for it.
    measures_cf: bool,
    /// Which miss blocks a warp.
    blocked: blocked::BlockedRule,
    /// Warp slots; a slot holds a warp when its bit in `free_slots` is 0.
    /// Only the first `p.slots()` are used.
    slots: Box<[Warp; MAX_SLOTS]>,
    /// Per slot, the cycle its warp became blocked (meaningful while the
    /// warp is blocked), apart from the warp like `alu_left`.
    blocked_at: Box<[u64; MAX_SLOTS]>,
    /// Per slot, the ALU instructions left in the warp's current ALU run
    /// (0: not started), apart from the rest of the warp: the issue stage
    /// counts a run down without touching the warp.
    alu_left: Box<[u32; MAX_SLOTS]>,
    free_slots: u128,
    /// Warps ready to issue an ALU instruction.
    ready: u128,
    /// Warps ready to issue a texture instruction (to the LDST queue).
    ready_tex: u128,
    /// Wake-ups ([`WakeWheel`]): due ones (the core looks at the warp's
    /// next instruction entry) and ready ones (warps in the middle of an
    /// ALU run join the ready set as a whole mask, with no per-warp look).
    wakes: WakeWheel,
    /// The LDST unit's texture instructions, `ldst_len` of them: the
    /// oldest, whose blocks are being presented, then the others in order.
    ldst_cur: LdstEntry,
    ldst_wait: VecDeque<LdstEntry>,
    ldst_len: usize,
    /// Index of the current tile in the trace.
    tile: Option<usize>,
    /// Where its own rasterizer is in the tile (per-core-tile dispatch).
    cursor: RasterCursor,
    /// Primary misses at the scheduler-level cache since the tile began.
    tile_misses: u64,
    active: u32,
    rr: u32,
    prio: PriorityEvents,
    signals: CoreSignals,
    last_progress: u64,
    stats: CoreStats,
    /// Per-warp records, when asked for.
    records: Option<Vec<WarpRecord>>,
}

impl ShaderCore {
    /// A core in its reset state.
    pub fn new(
        id: usize,
        p: &CoreParams,
        policy: &dyn LaunchPolicy,
        rule: LaunchRule,
        subset: Box<dyn PrioritySubset>,
    ) -> Self {
        // Policies that do not read the free-MSHR register may watch a cache
        // with more entries than it holds; the register then stays at reset.
        let track_mshrs = policy.reads_free_mshrs();
        let measures_cf = policy.measures_cf();
        let free =
            FreeMshrReg::with_capacity(p.watched_mshrs).expect("watched MSHRs fit the register");
        let n = p.slots();
        debug_assert!(n <= MAX_SLOTS);
        let queue = p.core.input_queue as usize;
        Self {
            id,
            p: *p,
            filter_free: 0,
            sched: LaunchScheduler::new(queue, subset, free, policy, rule),
            track_mshrs,
            measures_cf,
            blocked: p.blocked_rule(),
            slots: Box::new([Warp::default(); MAX_SLOTS]),
            alu_left: Box::new([0; MAX_SLOTS]),
            blocked_at: Box::new([0; MAX_SLOTS]),
            free_slots: if n == 128 {
                u128::MAX
            } else {
                (1u128 << n) - 1
            },
            ready: 0,
            ready_tex: 0,
            wakes: WakeWheel::new(),
            ldst_cur: LdstEntry {
                slot: 0,
                next: 0,
                end: 0,
            },
            ldst_wait: VecDeque::with_capacity(p.core.ldst_queue as usize),
            ldst_len: 0,
            tile: None,
            cursor: RasterCursor::default(),
            tile_misses: 0,
            active: 0,
            rr: 0,
            prio: PriorityEvents::default(),
            signals: CoreSignals::default(),
            last_progress: 0,
            stats: CoreStats {
                occupancy_hist: vec![0; n + 1],
                ..CoreStats::default()
            },
            records: None,
        }
    }

    /// The core's tile (its index in the trace), if any.
    #[inline]
    pub fn tile(&self) -> Option<usize> {
        self.tile
    }

    /// Whether the core has no tile.
    pub fn idle(&self) -> bool {
        self.tile.is_none()
    }

    /// Give the core tile `index` of the trace, `tile`, to rasterize itself
    /// (per-core-tile dispatch; the core must be idle).
    pub fn assign_tile(&mut self, index: usize, tile: &Tile, now: u64) {
        debug_assert!(self.tile.is_none() && !self.p.external_raster);
        self.tile = Some(index);
        self.cursor = RasterCursor::start(tile);
        self.tile_misses = 0;
        self.last_progress = now;
    }

    /// The GPU opens tile `tile` for every core (shared-tile dispatch): its
    /// quads arrive through [`push_quad`](Self::push_quad).
    pub fn begin_shared_tile(&mut self, tile: usize, now: u64) {
        debug_assert!(self.tile.is_none() && self.p.external_raster);
        self.tile = Some(tile);
        self.cursor = RasterCursor::default();
        self.tile_misses = 0;
        self.last_progress = now;
    }

    /// The GPU's rasterizer offers quad `quad` of the open tile at in-tile
    /// position (x, y): it enters the priority or regular FIFO, or, when
    /// that FIFO is full, is refused (`false`: the rasterizer waits).
    #[inline]
    pub fn push_quad(&mut self, quad: u32, x: u32, y: u32) -> bool {
        !self.sched.queue().is_full() && self.sched.enqueue(quad, x, y).is_ok()
    }

    /// Nothing of the open tile is queued, resident or in the LDST unit.
    pub fn drained(&self) -> bool {
        self.active == 0 && self.ldst_len == 0 && self.sched.queue().is_empty()
    }

    /// The GPU closes the open tile (shared-tile dispatch; the core must be
    /// [`drained`](Self::drained)).
    pub fn end_shared_tile(&mut self) {
        debug_assert!(self.drained());
        self.tile = None;
    }

    /// Primary misses at the scheduler-level cache since the core's tile
    /// began.
    pub fn tile_misses(&self) -> u64 {
        self.tile_misses
    }

    /// The warp launched in the last evaluated cycle: (quad index,
    /// priority).
    #[inline]
    pub fn launched_now(&self) -> Option<(u32, bool)> {
        self.signals.launched
    }

    /// The core's counters.
    pub fn stats(&self) -> &CoreStats {
        &self.stats
    }

    /// The last cycle the core made progress.
    pub fn last_progress(&self) -> u64 {
        self.last_progress
    }

    /// Phase 1 of cycle `now`.
    pub fn evaluate(&mut self, now: u64, trace: &Trace, mem: &mut MemorySystem) {
        self.signals = CoreSignals::default();
        self.prio = PriorityEvents::default();
        let Some(ti) = self.tile else {
            self.stats.idle_cycles += 1;
            self.stats.occupancy_hist[0] += 1;
            return;
        };
        let tile = &trace.tiles()[ti];
        self.wakeups(now, tile);
        if !self.p.external_raster {
            self.raster(tile);
        }
        self.launch(now, tile);
        self.issue(now, tile);
        self.ldst(now, tile, mem);
        self.stats.occupancy_sum += self.active as u64;
        self.stats.occupancy_hist[self.active as usize] += 1;
    }

    fn progress(&mut self, now: u64) {
        self.last_progress = now;
    }

    /// Every slot fits in a `u64` mask (the hot loops then use `u64`).
    #[inline]
    fn narrow(&self) -> bool {
        self.p.core.max_warps <= 64
    }

    /// Wake warp `slot` at cycle `at` (> the current cycle).
    #[inline]
    fn schedule(&mut self, now: u64, at: u64, slot: usize) {
        self.wakes.schedule(now, at, slot);
    }

    fn wakeups(&mut self, now: u64, tile: &Tile) {
        if self.narrow() {
            self.wake_due::<u64>(now, tile);
        } else {
            self.wake_due::<u128>(now, tile);
        }
    }

    /// The wake-ups due at `now`, on masks of width `M` (every slot fits).
    #[inline(always)]
    fn wake_due<M: SlotMask>(&mut self, now: u64, tile: &Tile) {
        let (ready_now, due_now) = self.wakes.take(now);
        self.ready |= ready_now;
        let mut due = M::from_wide(due_now);
        let mut ready = M::ZERO;
        let mut ready_tex = M::ZERO;
        while due != M::ZERO {
            let s = due.lowest();
            due = due.without_lowest();
            let w = &mut self.slots[s % MAX_SLOTS];
            if self.alu_left[s % MAX_SLOTS] > 0 {
                // In an ALU run (a latency beyond the wheels' reach).
                ready |= M::bit(s);
            } else if w.op >= w.n_ops {
                let w = *w;
                self.finish(s, &w, now);
                self.progress(now);
            } else {
                // Starting a new instruction entry: decode it once.
                match tile.op_kind(w.op as usize).expect("op in program") {
                    OpKind::Alu(n) => {
                        self.alu_left[s % MAX_SLOTS] = n;
                        ready |= M::bit(s);
                    }
                    OpKind::Tex { len, tri } => {
                        w.tex_len = len;
                        w.tex_tri = tri;
                        ready_tex |= M::bit(s);
                    }
                }
                w.op += 1;
            }
        }
        self.ready |= ready.to_wide();
        self.ready_tex |= ready_tex.to_wide();
    }

    fn finish(&mut self, s: usize, w: &Warp, now: u64) {
        self.free_slots |= 1u128 << s;
        self.active -= 1;
        self.stats.warps_finished += 1;
        self.signals.finished += 1;
        if w.priority && !w.blocked {
            self.prio.finished += 1;
        }
        if let (Some(r), Some(tile)) = (self.records.as_mut(), self.tile) {
            r.push(WarpRecord {
                tile: tile as u32,
                quad: w.quad,
                core: self.id as u32,
                priority: w.priority,
                mem_latency: (w.tex_done > 0).then(|| w.lat_sum as f64 / w.tex_done as f64),
                launched: w.launched_at,
                finished: now,
            });
        }
        if w.tex_done > 0 {
            let c = w.priority as usize;
            self.stats.warp_latency_sum[c] += w.lat_sum as f64 / w.tex_done as f64;
            self.stats.warps_with_tex[c] += 1;
        }
    }

    fn raster(&mut self, tile: &Tile) {
        let sched = &mut self.sched;
        self.cursor.own_cycle(
            tile,
            self.p.raster_rate,
            self.p.rejected_per_slot,
            &mut self.stats.quads_rasterized,
            &mut self.stats.quads_rejected,
            |i, x, y| !sched.queue().is_full() && sched.enqueue(i, x, y).is_ok(),
        );
    }

    fn launch(&mut self, now: u64, tile: &Tile) {
        let have_slot = self.free_slots != 0;
        let waiting = !self.sched.queue().is_empty();
        if !(have_slot && waiting) {
            // Nothing can launch: the decision logic is not evaluated (its
            // waveform signals keep their last values, `launch` reads 0).
            return;
        }
        let both = self.sched.queue().has(QueueClass::Priority)
            && self.sched.queue().has(QueueClass::Regular);
        let launch = self.sched.launch(have_slot);
        match launch.warp {
            Some((quad, class)) => {
                if both {
                    self.stats.both_waiting += 1;
                    self.stats.regular_first += u64::from(class == QueueClass::Regular);
                }
                let s = self.free_slots.trailing_zeros() as usize;
                self.free_slots &= !(1u128 << s);
                let priority = class == QueueClass::Priority;
                let span = tile.quad_span(quad as usize).expect("quad in tile");
                self.alu_left[s % MAX_SLOTS] = 0;
                self.slots[s % MAX_SLOTS] = Warp {
                    quad,
                    op: span.op_start,
                    n_ops: span.op_start + span.op_len,
                    priority,
                    blocked: false,
                    pending: 0,
                    tex_len: 0,
                    tex_tri: false,
                    blk: span.block_start,
                    tex_start: 0,
                    lat_sum: 0,
                    tex_done: 0,
                    launched_at: now,
                };
                // The warp can issue from the next cycle.
                self.schedule(now, now + 1, s);
                self.active += 1;
                self.stats.warps_launched += 1;
                self.stats.priority_launches += priority as u64;
                self.signals.launched = Some((quad, priority));
                self.progress(now);
            }
            None => {
                // A free slot and a waiting warp but no launch: only the
                // launch rule `hold` does that (a closed gate, only
                // priority warps waiting).
                debug_assert!(launch.decision.held);
                self.stats.held_cycles += u64::from(launch.decision.held);
            }
        }
    }

    fn issue(&mut self, now: u64, tile: &Tile) {
        if self.narrow() {
            self.issue_with::<u64>(now, tile);
        } else {
            self.issue_with::<u128>(now, tile);
        }
    }

    /// Issue on masks of width `M` (every slot fits).
    ///
    /// The picks are found first ([`pick`], checked against its plain
    /// reference; each ALU pick counts its run down), then the ALU picks
    /// are put on the wake-up wheels as whole masks: those with more of
    /// their run to go on the ready wheel, those that ended it on the wheel
    /// that looks at them.
    #[inline(always)]
    fn issue_with<M: SlotMask>(&mut self, now: u64, tile: &Tile) {
        let tex_ok = self.ldst_len < self.p.core.ldst_queue as usize;
        let ready = M::from_wide(self.ready);
        let tex_cand = if tex_ok {
            M::from_wide(self.ready_tex)
        } else {
            M::ZERO
        };
        // Each ALU pick counts its run down; those that end it wait on the
        // wheel that looks at their next instruction.
        let alu_left = &mut self.alu_left;
        let Picks {
            alu,
            run_end,
            tex,
            issued,
            last,
        } = pick(ready, tex_cand, self.rr, self.p.core.pipeline_width, |s| {
            let left = &mut alu_left[s % MAX_SLOTS];
            *left -= 1;
            *left == 0
        });
        self.signals.issued = issued;
        self.signals.tex_issued = tex.is_some();
        if issued == 0 {
            return;
        }
        self.rr = if last + 1 >= self.p.core.max_warps {
            0
        } else {
            last + 1
        };
        self.stats.instructions += u64::from(issued);
        self.progress(now);
        self.ready = (ready & !alu).to_wide();
        let at = now + u64::from(self.p.core.alu_latency);
        if WakeWheel::reaches(now, at) {
            // Mid-run warps are ready again at `at`, nothing to decide.
            self.wakes
                .schedule_masks(at, (alu & !run_end).to_wide(), run_end.to_wide());
        } else {
            let mut m = alu;
            while m != M::ZERO {
                let s = m.lowest();
                m = m.without_lowest();
                self.schedule(now, at, s);
            }
        }
        if let Some(s) = tex {
            let w = &mut self.slots[s % MAX_SLOTS];
            let end = w.blk + w.tex_len;
            debug_assert_eq!(
                tile.op_kind(w.op as usize - 1),
                Some(OpKind::Tex {
                    len: w.tex_len,
                    tri: w.tex_tri
                }),
                "ready_tex warps wait on a texture instruction"
            );
            w.pending = w.tex_len;
            w.tex_start = now;
            let e = LdstEntry {
                slot: s as u8,
                next: w.blk,
                end,
            };
            if self.ldst_len == 0 {
                self.ldst_cur = e;
            } else {
                self.ldst_wait.push_back(e);
            }
            self.ldst_len += 1;
            w.blk = end;
            self.ready_tex &= !(1u128 << s);
            self.stats.tex_instructions += 1;
            self.stats.tri_tex_instructions += u64::from(w.tex_tri);
        }
    }

    fn ldst(&mut self, now: u64, tile: &Tile, mem: &mut MemorySystem) {
        if self.ldst_len == 0 {
            return;
        }
        let blocks = tile.block_accesses();
        loop {
            let e = &mut self.ldst_cur;
            while e.next < e.end {
                let (r, entry) =
                    mem.access_entry(now, self.id, blocks[e.next as usize], e.slot as u32);
                if !r.accepted() {
                    self.signals.ldst_refused = true;
                    return;
                }
                e.next += 1;
                self.signals.ldst_presented += 1;
                self.last_progress = now;
                if self.measures_cf
                    && r == Access::Miss
                    && self.slots[e.slot as usize % MAX_SLOTS].priority
                {
                    self.prio.misses = self.prio.misses.saturating_add(1);
                }
                if self.blocked.at_access(r, entry, e.slot as usize) {
                    let s = e.slot as usize % MAX_SLOTS;
                    block_warp(
                        &mut self.slots[s],
                        &mut self.blocked_at[s],
                        &mut self.stats.blocked_episodes,
                        &mut self.prio,
                        now,
                    );
                }
            }
            self.ldst_len -= 1;
            match self.ldst_wait.pop_front() {
                Some(n) => self.ldst_cur = n,
                None => return,
            }
        }
    }

    /// End of cycle: release the tile when every warp of it has finished
    /// (fill and drain). Returns whether a tile finished.
    pub fn end_cycle(&mut self) -> bool {
        if self.tile.is_none() || self.p.external_raster {
            return false;
        }
        if self.cursor.done()
            && self.sched.queue().is_empty()
            && self.active == 0
            && self.ldst_len == 0
        {
            self.tile = None;
            self.stats.tiles += 1;
            return true;
        }
        false
    }

    /// Start recording every warp (see [`WarpRecord`]).
    pub fn record_warps(&mut self) {
        self.records = Some(Vec::new());
    }

    /// The records so far.
    pub fn take_records(&mut self) -> Vec<WarpRecord> {
        self.records.take().unwrap_or_default()
    }

    /// Warps in flight (launched, not finished).
    pub fn active(&self) -> u32 {
        self.active
    }
}

#[cfg(test)]
mod tests {
    //! The launch and issue stages and the LDST unit's intake on one core,
    //! cycle by cycle.
    use super::testkit::{cfg, trace, OVERLAP};
    use crate::config::MachineConfig;
    use crate::gpu::Gpu;
    use crate::trace::{Instr, Trace};

    /// A one-core machine (the paper's otherwise) with `width`, `warps`
    /// slots and ALU latency `alu`.
    fn one_core(width: u32, warps: u32, alu: u32) -> MachineConfig {
        let mut c = cfg(1, 2, OVERLAP);
        c.gpu.cores = 1;
        c.raster.quads_per_cycle = 4;
        c.core.pipeline_width = width;
        c.core.max_warps = warps;
        c.core.alu_latency = alu;
        c.validate().unwrap();
        c
    }

    /// Each cycle's counters of core 0 (instructions, texture
    /// instructions, warps launched) and its snapshot, to the end.
    fn cycles(c: &MachineConfig, t: &Trace) -> Vec<([u64; 3], super::CoreSnapshot)> {
        let mut gpu = Gpu::new(c, t).unwrap();
        let mut out = vec![];
        while !gpu.done() {
            gpu.step().unwrap();
            let core = &gpu.cores()[0];
            let s = core.stats();
            out.push((
                [s.instructions, s.tex_instructions, s.warps_launched],
                core.snapshot(),
            ));
        }
        out
    }

    /// At most one warp launches a cycle, into the lowest free slot, and it
    /// issues from the cycle after its launch.
    #[test]
    fn one_launch_a_cycle_into_the_lowest_free_slot() {
        let quads: Vec<(u32, u32)> = (0..4).map(|x| (x, 0)).collect();
        let t = trace(&quads, &[Instr::Alu(2)]);
        let run = cycles(&one_core(4, 8, 1), &t);
        let mut launched = 0;
        for w in run.windows(2) {
            let (a, b) = (&w[0].0, &w[1].0);
            assert!(b[2] - a[2] <= 1, "one launch a cycle");
            if b[2] > a[2] {
                // Warps finish before the launch stage, so the slots the
                // others hold after the cycle are those held at the launch.
                let newest = w[1].1.warps.iter().max_by_key(|v| v.launched).unwrap();
                let held = |s: usize| w[1].1.warps.iter().any(|v| v.slot == s);
                assert!((0..newest.slot).all(held), "the lowest free slot");
                assert!(!newest.ready_alu, "not ready in its launch cycle");
                launched += 1;
            }
        }
        assert_eq!(launched + run[0].0[2], 4);
    }

    /// Issue takes at most `pipeline_width` instructions a cycle, and a warp
    /// in an ALU run issues once every `alu_latency` cycles.
    #[test]
    fn issue_keeps_the_width_and_the_alu_latency() {
        let quads: Vec<(u32, u32)> = (0..4).flat_map(|y| (0..4).map(move |x| (x, y))).collect();
        for (width, alu) in [(1, 1), (2, 3), (4, 5)] {
            let run = cycles(&one_core(width, 16, alu), &trace(&quads, &[Instr::Alu(6)]));
            let per_cycle: Vec<u64> = run.windows(2).map(|w| w[1].0[0] - w[0].0[0]).collect();
            assert!(per_cycle.iter().all(|&n| n <= u64::from(width)));
            assert_eq!(run.last().unwrap().0[0], 16 * 6);
            // A lone warp: its six instructions `alu` cycles apart.
            let lone = cycles(
                &one_core(width, 16, alu),
                &trace(&[(0, 0)], &[Instr::Alu(6)]),
            );
            let at: Vec<usize> = lone
                .windows(2)
                .enumerate()
                .filter(|(_, w)| w[1].0[0] > w[0].0[0])
                .map(|(i, _)| i)
                .collect();
            assert_eq!(at.len(), 6 - usize::from(lone[0].0[0] > 0));
            assert!(at.windows(2).all(|d| d[1] - d[0] == alu as usize));
        }
    }

    /// One texture instruction enters the LDST unit a cycle.
    #[test]
    fn one_texture_instruction_a_cycle() {
        let quads: Vec<(u32, u32)> = (0..4).flat_map(|y| (0..4).map(move |x| (x, y))).collect();
        let run = cycles(
            &one_core(4, 16, 1),
            &trace(&quads, &[Instr::Tex(&[1]), Instr::Tex(&[2, 3])]),
        );
        assert!(run.windows(2).all(|w| w[1].0[1] - w[0].0[1] <= 1));
        assert_eq!(run.last().unwrap().0[1], 32);
        assert!(
            run.iter().all(|(_, s)| s.ldst <= 8),
            "the LDST queue's size"
        );
    }
}
