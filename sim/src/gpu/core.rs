//! One shader core, made of stages. Each stage is one file with its own
//! tests, and each has the same shape (MGPUSim's compute-unit parts are
//! the model): it takes work when it has room (`can_accept`, `accept`), it
//! runs once a cycle and says whether it made progress (`run(now) ->
//! bool`: moved work on, not merely counted), and it says when it has
//! nothing to do (`is_idle`):
//! - the core's own rasterizer ([`raster`], per-core-tile dispatch): up to
//!   its share of `raster.quads_per_cycle` quads of its tile into the input
//!   FIFOs (under shared-tile dispatch the GPU's one rasterizer fills them
//!   instead, [`ShaderCore::push_quad`], `gpu/raster.rs`);
//! - launch ([`launch`]): one warp a cycle from the FIFO the policy and
//!   the launch rule choose, into the lowest free warp slot;
//! - issue ([`issue`]): the warps' wake-ups, then up to `pipeline_width`
//!   ready warps issue one instruction each, in the order `core.issue`
//!   names (loose round-robin or greedy-then-oldest); a texture
//!   instruction enters the LDST unit (one per cycle, if it has room);
//! - LDST ([`ldst`]): the oldest texture instruction presents its unique
//!   blocks to the first cache level, in order, until the cache refuses;
//! - completion ([`complete`], phase 2, after the memory system ticked):
//!   the warps a long-latency miss blocks, then the data that returned;
//! - the texture filter ([`filter`]): a warp whose data arrived passes it,
//!   in order of arrival, and comes back to the issue stage.
//!
//! The warp slots ([`warp`]) are the core's, shared by the stages. Per
//! cycle `now`, phase 1 ([`ShaderCore::evaluate`]) runs the wake-ups, the
//! own rasterizer, launch, issue and LDST; then the memory system ticks;
//! phase 2 ([`ShaderCore::complete`]) runs the completion stage and clocks
//! the scheduler's registers with the cycle's MSHR and priority-warp
//! events. Both phases return whether any stage made progress: the GPU's
//! watchdog reads that, and [`ShaderCore::is_idle`] says beforehand that
//! none can.
//!
//! A warp is *blocked* (the paper's long-latency state: "warps are marked
//! as blocked when they encounter a long-latency miss", Section IV-C) from
//! the cycle one of its requests of a texture instruction takes the miss
//! that `scheduler.blocked_on` names until its last block arrives
//! ([`blocked`]). Each blocked episode of a priority warp counts once in
//! the non-blocked counter's events. A blocked warp cannot issue: each
//! warp's instructions depend on the previous one, so nothing else of it
//! is fetched meanwhile; a warp waiting on shorter misses cannot issue
//! either, but counts as not blocked.

use crate::mem::MemorySystem;
use crate::trace::{Tile, Trace};
use wasp_rtl::nonblocked::PriorityEvents;
use wasp_rtl::policy::{LaunchPolicy, LaunchRule};
use wasp_rtl::subset::PrioritySubset;

mod blocked;
mod complete;
mod filter;
mod issue;
mod launch;
mod ldst;
mod mask;
mod observe;
mod params;
#[cfg(test)]
pub(crate) mod plain;
pub(crate) mod raster;
mod stats;
#[cfg(test)]
mod testkit;
mod warp;
mod wheel;
pub use observe::{CoreSnapshot, WarpView};
pub use params::CoreParams;
pub use stats::{CoreStats, WarpRecord};

use blocked::BlockedRule;
use complete::{Complete, Downstream};
use filter::Filter;
use issue::Issue;
use launch::Launch;
use ldst::Ldst;
use raster::OwnRaster;
use warp::Warps;

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

/// What the stages note as they run: the core's counters, the cycle's
/// signals for the waveform, and the cycle's priority-warp events for the
/// scheduler's edge.
#[derive(Debug)]
struct Notes {
    stats: CoreStats,
    signals: CoreSignals,
    prio: PriorityEvents,
}

impl Notes {
    /// Nothing noted, for a core of `slots` warp slots.
    fn new(slots: usize) -> Self {
        Notes {
            stats: CoreStats {
                occupancy_hist: vec![0; slots + 1],
                ..CoreStats::default()
            },
            signals: CoreSignals::default(),
            prio: PriorityEvents::default(),
        }
    }
}

/// One shader core.
#[derive(Debug)]
pub struct ShaderCore {
    id: usize,
    warps: Warps,
    /// The core's own rasterizer; `None` under shared-tile dispatch.
    raster: Option<OwnRaster>,
    launch: Launch,
    issue: Issue,
    ldst: Ldst,
    filter: Filter,
    complete: Complete,
    /// Which miss blocks a warp.
    blocked: BlockedRule,
    /// Index of the current tile in the trace.
    tile: Option<usize>,
    /// Primary misses at the scheduler-level cache since the tile began.
    tile_misses: u64,
    notes: Notes,
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
        let n = p.slots();
        Self {
            id,
            warps: Warps::new(n),
            raster: (!p.external_raster)
                .then(|| OwnRaster::new(p.raster_rate, p.rejected_per_slot)),
            launch: Launch::new(p, policy, rule, subset),
            issue: Issue::new(&p.core),
            ldst: Ldst::new(id, p.core.ldst_queue as usize, policy.measures_cf()),
            filter: Filter::new(&p.core),
            complete: Complete::new(id),
            blocked: p.blocked_rule(),
            tile: None,
            tile_misses: 0,
            notes: Notes::new(n),
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
    pub fn assign_tile(&mut self, index: usize, tile: &Tile) {
        debug_assert!(self.tile.is_none());
        self.tile = Some(index);
        self.raster
            .as_mut()
            .expect("per-core-tile dispatch")
            .start(tile);
        self.tile_misses = 0;
    }

    /// The GPU opens tile `tile` for every core (shared-tile dispatch): its
    /// quads arrive through [`push_quad`](Self::push_quad).
    pub fn begin_shared_tile(&mut self, tile: usize) {
        debug_assert!(self.tile.is_none() && self.raster.is_none());
        self.tile = Some(tile);
        self.tile_misses = 0;
    }

    /// The GPU's rasterizer offers quad `quad` of the open tile at in-tile
    /// position (x, y): it enters the priority or regular FIFO, or, when
    /// that FIFO is full, is refused (`false`: the rasterizer waits).
    #[inline]
    pub fn push_quad(&mut self, quad: u32, x: u32, y: u32) -> bool {
        self.launch.accept(quad, x, y)
    }

    /// Every slot of the input queue is taken: [`push_quad`](Self::push_quad)
    /// refuses any quad until a warp launches.
    #[inline]
    pub fn input_full(&self) -> bool {
        self.launch.sched().queue().is_full()
    }

    /// Surviving quads of its own tile the core's rasterizer has put in
    /// the input queue so far (per-core-tile dispatch).
    #[inline]
    pub fn quads_entered(&self) -> u32 {
        self.raster.as_ref().map_or(0, |r| r.delivered())
    }

    /// Nothing of the open tile is queued, resident or in the LDST unit.
    pub fn drained(&self) -> bool {
        self.warps.active() == 0 && self.ldst.is_idle() && self.launch.sched().queue().is_empty()
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
        self.notes.signals.launched
    }

    /// The core's counters.
    pub fn stats(&self) -> &CoreStats {
        &self.notes.stats
    }

    /// Set every counter to zero (a frame begins; the core's state stays).
    pub fn reset_stats(&mut self) {
        self.notes.stats = self.notes.stats.cleared();
    }

    /// No stage of the core can make progress in cycle `now` (before it
    /// runs): no tile, or every stage idle and no data outstanding.
    pub fn is_idle(&self, now: u64) -> bool {
        self.tile.is_none()
            || (self.raster.as_ref().is_none_or(OwnRaster::is_idle)
                && self.launch.is_idle(&self.warps)
                && self.issue.is_idle(now, &self.ldst)
                && self.ldst.is_idle()
                && Complete::is_idle(&self.warps)
                && self.filter.is_idle(now))
    }

    /// Phase 1 of cycle `now`; whether a stage made progress.
    #[inline(always)]
    pub fn evaluate(&mut self, now: u64, trace: &Trace, mem: &mut MemorySystem) -> bool {
        let notes = &mut self.notes;
        notes.signals = CoreSignals::default();
        notes.prio = PriorityEvents::default();
        let Some(ti) = self.tile else {
            notes.stats.idle_cycles += 1;
            notes.stats.occupancy_hist[0] += 1;
            return false;
        };
        if self.warps.active() == 0
            && self.launch.sched().queue().is_empty()
            && self.raster.as_ref().is_none_or(OwnRaster::is_idle)
        {
            // No warp, none waiting to launch, none to rasterize: no stage
            // can do anything in the cycle (no wake-up is due without a
            // warp), which only counts.
            self.notes.stats.occupancy_hist[0] += 1;
            debug_assert!(self.is_idle(now));
            return false;
        }
        let tile = &trace.tiles()[ti];
        let done = self.issue.wake(now, tile, &mut self.warps);
        let mut progress = done != 0 && self.retire(done, now);
        if let Some(r) = self.raster.as_mut() {
            let launch = &mut self.launch;
            progress |= r.run(tile, &mut self.notes.stats, |i, x, y| {
                launch.accept(i, x, y)
            });
        }
        if let Some(slot) = self.launch.run(now, tile, &mut self.warps, &mut self.notes) {
            self.issue.launched(now, slot);
            progress = true;
        }
        progress |= self
            .issue
            .run(now, tile, &mut self.warps, &mut self.ldst, &mut self.notes);
        progress |= self.ldst.run(
            now,
            tile,
            mem,
            &mut self.warps,
            &mut self.blocked,
            &mut self.notes,
        );
        let active = self.warps.active();
        self.notes.stats.occupancy_sum += u64::from(active);
        self.notes.stats.occupancy_hist[active as usize] += 1;
        progress
    }

    /// The warps of the slots of `done` are past their last instruction:
    /// they leave the core. Returns true (a warp retired).
    fn retire(&mut self, mut done: u128, now: u64) -> bool {
        while done != 0 {
            let s = done.trailing_zeros() as usize;
            done &= done - 1;
            self.warps.release(s);
            let w = self.warps.get(s);
            let notes = &mut self.notes;
            notes.stats.warps_finished += 1;
            notes.signals.finished += 1;
            if w.priority && !w.blocked {
                notes.prio.finished += 1;
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
                notes.stats.warp_latency_sum[c] += w.lat_sum as f64 / w.tex_done as f64;
                notes.stats.warps_with_tex[c] += 1;
            }
        }
        true
    }

    /// Phase 2 of cycle `now`: the completion stage, then the scheduler's
    /// clock edge; whether data returned.
    #[inline(always)]
    pub fn complete(
        &mut self,
        now: u64,
        mem: &mut MemorySystem,
    ) -> Result<bool, crate::gpu::SimError> {
        // Most cycles nothing reaches the core: no block returns, no miss
        // is reported, and neither the watched cache's MSHRs nor the
        // priority warps give the scheduler's registers an event.
        if self.notes.prio == PriorityEvents::default()
            && mem.nothing_for(self.id)
            && self.launch.clock_quiet(&mut self.notes)
        {
            return Ok(false);
        }
        self.complete_events(now, mem)
    }

    /// [`complete`](Self::complete) of a cycle with events (kept out of
    /// line: the quiet cycles' test then costs its caller no call).
    #[inline(never)]
    fn complete_events(
        &mut self,
        now: u64,
        mem: &mut MemorySystem,
    ) -> Result<bool, crate::gpu::SimError> {
        let progress = self.complete.run(
            now,
            mem,
            &mut self.warps,
            Downstream {
                blocked: &mut self.blocked,
                filter: &mut self.filter,
                issue: &mut self.issue,
            },
            &mut self.notes,
        )?;
        let ev = mem.mshr_events(self.id);
        self.tile_misses += u64::from(ev.allocated);
        self.launch.clock(self.id, now, ev, &mut self.notes)?;
        Ok(progress)
    }

    /// End of cycle: release the tile when every warp of it has finished
    /// (fill and drain; per-core-tile dispatch). Returns whether a tile
    /// finished.
    pub fn end_cycle(&mut self) -> bool {
        let Some(raster) = self.raster.as_ref() else {
            return false;
        };
        if self.tile.is_some() && raster.is_idle() && self.drained() {
            self.tile = None;
            self.notes.stats.tiles += 1;
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
        self.warps.active()
    }
}
