//! The GPU: shader cores, the raster pipeline that feeds them and the
//! memory hierarchy, clocked by one cycle loop.
//!
//! Tiles are taken in trace order (the front end emits them in Z-order).
//! Two dispatch modes (`raster.dispatch`):
//!
//! * **shared-tile** (the paper's machine, `gpu/raster.rs`): one tile at a
//!   time for the whole GPU; one rasterizer places each surviving quad in
//!   the input queue of the core its position names
//!   ([`CoreMap`](crate::config::CoreMap)); no warp
//!   of the next tile launches until every warp of this one has retired on
//!   every core; then the colour buffer is flushed.
//! * **per-core-tile**: each idle core takes the next tile, lowest core
//!   index first, rasterizes it with its own rasterizer and renders all of
//!   it before taking another; tiles run out of phase on the cores.
//!
//! Either way a tile fills and drains. A run ends when every tile is
//! rendered, every colour buffer flushed and the memory system is idle.
//!
//! **Frames.** A trace of several frames runs them in order
//! ([`Gpu::start_frame`], [`Gpu::end_frame`]). A frame ends as a one-frame
//! run ends (every tile of it rendered, every colour buffer flushed, the
//! memory system idle), and the next frame's first tile opens in the next
//! cycle. What carries over from one frame to the next is the state of the
//! memory hierarchy: the contents and replacement order of every cache
//! (L0, L1, L2), the DRAM banks' open rows and timing, the prefetchers'
//! state; and the cores' scheduler state (an idle core keeps its
//! registers, such as WaSP-M's CF meter). Nothing is flushed or
//! invalidated at a frame's end beyond what every tile's end does (its
//! colour buffer's flush to the frame buffer, the tile buffers being
//! per tile). Only the counters restart: each frame's statistics are its
//! own.

mod core;
mod core_model;
#[cfg(test)]
mod lockstep;
mod raster;
mod raster_cursor;
mod tiles;

pub use self::core::{CoreParams, CoreSnapshot, CoreStats, ShaderCore, WarpRecord, WarpView};
pub use self::core_model::CoreModel;
pub use self::raster::{RasterStats, SharedRaster};
pub use self::tiles::{LeadBin, LeadStats, TileRecord, TileTimingStats, TileTracker};

use crate::config::{MachineConfig, TextureCache};
use crate::mem::prefetch::{self, Prefetcher};
use crate::mem::MemStats;
use crate::mem::MemorySystem;
use crate::timeline::{Timeline, TimelineSample};
use crate::trace::{TextureMap, Trace};
use std::fmt;
use wasp_rtl::RegisterFault;
use wasp_waves::{CycleSink, NullTracer, Tracer};

/// Why a run stopped without a result.
#[derive(Debug)]
pub enum SimError {
    /// The configuration or its combination with the trace is invalid.
    Config(String),
    /// A scheduler register would have left its range.
    Register {
        /// Core.
        core: usize,
        /// Cycle.
        cycle: u64,
        /// What happened.
        fault: RegisterFault,
    },
    /// No forward progress for the watchdog's number of cycles.
    Watchdog {
        /// Cycle the watchdog fired.
        cycle: u64,
        /// The stuck state.
        state: String,
    },
    /// A self-check failed (a model bug).
    Internal(String),
    /// Writing the waveform failed.
    Io(std::io::Error),
}

impl fmt::Display for SimError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SimError::Config(m) => write!(f, "{m}"),
            SimError::Register { core, cycle, fault } => {
                write!(f, "core {core}, cycle {cycle}: {fault}")
            }
            SimError::Watchdog { cycle, state } => write!(
                f,
                "watchdog: no forward progress, stopped at cycle {cycle}; stuck state:\n{state}"
            ),
            SimError::Internal(m) => write!(f, "self-check failed: {m}"),
            SimError::Io(e) => write!(f, "writing the waveform: {e}"),
        }
    }
}

impl std::error::Error for SimError {}

/// What the GPU measures beside the cores and caches: the raster pipeline,
/// the tiles, the lead of priority warps.
#[derive(Clone, Debug, PartialEq)]
pub struct RunInstruments {
    /// Tiles rendered.
    pub tiles: u64,
    /// The raster pipeline's counters.
    pub raster: RasterStats,
    /// The lead of priority warps.
    pub priority_lead: LeadStats,
    /// Means over tiles.
    pub tile_timing: TileTimingStats,
    /// Every tile, in trace order.
    pub per_tile: Vec<TileRecord>,
}

/// What a finished run counted, before it becomes a report
/// ([`crate::stats::RunStats::collect`]).
#[derive(Clone, Debug)]
pub struct RunCounters {
    /// Cycles run.
    pub cycles: u64,
    /// Each core's counters.
    pub cores: Vec<CoreStats>,
    /// The memory hierarchy's counters.
    pub mem: MemStats,
    /// The raster pipeline, tiles and priority lead.
    pub instruments: RunInstruments,
}

/// Who feeds the cores.
enum Dispatcher {
    /// Each idle core takes the next tile.
    PerCore {
        /// Next tile to hand out.
        next_tile: usize,
        /// The end of the frame's tiles.
        end: usize,
    },
    /// The GPU's one raster pipeline.
    Shared(SharedRaster),
}

/// The assembled GPU, its shader cores of type `C` (the fast
/// [`ShaderCore`] unless a test asks for its plain twin).
pub struct Gpu<'t, C = ShaderCore> {
    cfg: MachineConfig,
    trace: &'t Trace,
    cores: Vec<C>,
    mem: MemorySystem,
    dispatch: Dispatcher,
    /// The prefetcher into the L1s (`prefetch.kind`), if any.
    prefetch: Option<Box<dyn Prefetcher>>,
    /// One per renderer: the GPU (shared-tile) or each core (per-core).
    trackers: Vec<TileTracker>,
    timeline: Option<Timeline>,
    /// The waveform's scope name of each core (`core0`, ...), made once.
    core_scopes: Vec<String>,
    tiles_done: usize,
    /// The tiles of the frame being run (an index range of the trace's
    /// tiles): nothing at or past its end is dispatched.
    frame: std::ops::Range<usize>,
    /// The cycle before the frame's first one (0 for the first frame).
    frame_start: u64,
    /// `tiles_done` when the frame began.
    frame_tiles_done: usize,
    /// The memory counters when the frame began (`None`: all zero).
    mem_base: Option<MemStats>,
    now: u64,
    /// The last cycle in which a stage of a core or the raster pipeline
    /// made progress, or a tile began or ended (for the watchdog).
    last_progress: u64,
}

/// Tell the prefetcher what the shared raster pipeline did in the cycle:
/// the tile it opened, the quads it placed in input FIFOs.
#[inline(never)]
fn feed_prefetcher(
    pf: &mut dyn Prefetcher,
    r: &SharedRaster,
    opened: Option<usize>,
    tiles: &[crate::trace::Tile],
    mem: &mut MemorySystem,
) {
    if let Some(t) = opened {
        pf.tile_opened(t, None, mem);
    }
    if let Some(t) = r.tile() {
        let core_of = |x, y| r.core_of(x, y);
        prefetch::quads_entered(pf, &tiles[t], r.placed_now(), core_of, mem);
    }
}

/// The map the memory system needs for `cfg.memory.texture_cache`, or the
/// error when the trace lists lines the machine's texture caches do not
/// hold: a decompressed-texel cache needs the decoded lines of a
/// `texture-lines decoded` trace (an RGBA8 trace's lines are both), a
/// compressed-block cache the stored lines of any other trace.
fn texture_map<'a>(
    cfg: &MachineConfig,
    trace: &'a Trace,
) -> Result<Option<&'a TextureMap>, SimError> {
    let h = trace.header();
    let stored = h.texture_format.as_deref().filter(|f| *f != "rgba8");
    match (cfg.memory.texture_cache, &h.texture_map, stored) {
        (TextureCache::Decompressed, Some(map), _) => Ok(Some(map)),
        (TextureCache::Decompressed, None, Some(f)) => Err(SimError::Config(format!(
            "memory.texture_cache = \"decompressed\" needs a trace that lists the decoded (RGBA8) \
             lines of its textures (`texture-lines decoded`), but this trace lists the stored lines \
             of its `texture-format {f}` textures: render it with `--texture-cache decompressed`, \
             or run it with memory.texture_cache = \"compressed\""
        ))),
        (TextureCache::Compressed, Some(_), _) => Err(SimError::Config(
            "the trace lists the decoded (RGBA8) lines of compressed textures (`texture-lines \
             decoded`), which only memory.texture_cache = \"decompressed\" runs: set it, or render \
             the trace without `--texture-cache decompressed` for compressed lines in every cache"
                .to_string(),
        )),
        _ => Ok(None),
    }
}

impl<'t> Gpu<'t> {
    /// Build the GPU for `cfg` (already validated) and `trace`.
    pub fn new(cfg: &MachineConfig, trace: &'t Trace) -> Result<Self, SimError> {
        Self::build(cfg, trace)
    }
}

impl<'t, C: CoreModel> Gpu<'t, C> {
    /// Build the GPU for `cfg` (already validated) and `trace`, with
    /// shader cores of type `C`.
    pub fn build(cfg: &MachineConfig, trace: &'t Trace) -> Result<Self, SimError> {
        if trace.header().tile != cfg.gpu.tile_size {
            return Err(SimError::Config(format!(
                "the trace has {}-pixel tiles but gpu.tile_size is {}",
                trace.header().tile,
                cfg.gpu.tile_size
            )));
        }
        let side = cfg.quads_per_side();
        let params = CoreParams::new(cfg);
        let sched = &cfg.scheduler;
        let wiring = sched
            .policy
            .build(params.watched_mshrs)
            .map_err(SimError::Config)?;
        let cores: Vec<C> = (0..cfg.gpu.cores as usize)
            .map(|id| {
                let subset = sched.subset.build(side);
                C::build(id, &params, wiring.as_ref(), sched.launch_rule, subset)
            })
            .collect();
        let mut mem =
            MemorySystem::new(&cfg.mem_config()).map_err(|e| SimError::Config(e.to_string()))?;
        if let Some(map) = texture_map(cfg, trace)? {
            mem.map_texture_lines(map.clone());
        }
        let (dispatch, trackers) = if params.external_raster {
            let raster = SharedRaster::new(
                cfg.raster.quads_per_cycle,
                cfg.raster.core_map.table(side, cfg.gpu.cores),
                cfg.raster.color_flush,
            )
            .with_rejected_per_slot(cfg.raster.rejected_per_slot);
            (Dispatcher::Shared(raster), vec![TileTracker::new()])
        } else {
            (
                Dispatcher::PerCore {
                    next_tile: 0,
                    end: trace.tiles().len(),
                },
                vec![TileTracker::new(); cfg.gpu.cores as usize],
            )
        };
        let prefetch = match &dispatch {
            Dispatcher::Shared(r) => {
                let core_of = |x: u32, y: u32| r.core_of(x, y);
                prefetch::build(&cfg.prefetch, trace, cores.len(), Some(&core_of))
            }
            Dispatcher::PerCore { .. } => prefetch::build(&cfg.prefetch, trace, cores.len(), None),
        };
        let core_scopes = (0..cores.len()).map(|i| format!("core{i}")).collect();
        Ok(Self {
            cfg: cfg.clone(),
            trace,
            cores,
            mem,
            dispatch,
            prefetch,
            trackers,
            timeline: None,
            core_scopes,
            tiles_done: 0,
            frame: 0..trace.tiles().len(),
            frame_start: 0,
            frame_tiles_done: 0,
            mem_base: None,
            now: 0,
            last_progress: 0,
        })
    }

    /// Record a [`Timeline`] of the cycles `from..=to` (see
    /// [`take_timeline`](Self::take_timeline)).
    pub fn record_timeline(&mut self, from: u64, to: u64) {
        self.timeline = Some(Timeline::new(
            from,
            to,
            self.cores.len(),
            self.cfg.core.max_warps,
            self.cfg.l0.is_some(),
            &self.cfg.raster.dispatch.to_string(),
        ));
    }

    /// The timeline recorded so far, its window cut at the last cycle run.
    pub fn take_timeline(&mut self) -> Option<Timeline> {
        let mut t = self.timeline.take()?;
        t.to = t.to.min(self.now);
        Some(t)
    }

    /// The shader cores.
    pub fn cores(&self) -> &[C] {
        &self.cores
    }

    /// The memory system.
    pub fn mem(&self) -> &MemorySystem {
        &self.mem
    }

    /// Tiles rendered so far.
    pub fn tiles_done(&self) -> usize {
        self.tiles_done
    }

    /// The current cycle.
    pub fn cycle(&self) -> u64 {
        self.now
    }

    /// Start the frame of the trace's tiles `tiles` (a range of
    /// [`Trace::frames`]): only its tiles are dispatched until it is
    /// [`done`](Self::done). The GPU must be done with the previous frame
    /// (or new); the counters restart, the state carries over (see the
    /// module docs). A new GPU runs the whole trace as one frame without
    /// a call.
    pub fn start_frame(&mut self, tiles: std::ops::Range<usize>) {
        debug_assert!(
            self.now == 0 || self.done(),
            "a frame starts on an idle GPU"
        );
        match &mut self.dispatch {
            Dispatcher::PerCore { next_tile, end } => {
                *next_tile = tiles.start;
                *end = tiles.end;
            }
            Dispatcher::Shared(r) => r.start_frame(tiles.clone()),
        }
        self.frame = tiles;
        if self.now == 0 {
            return; // nothing counted yet
        }
        for c in self.cores.iter_mut() {
            c.reset_stats();
        }
        self.trackers = vec![TileTracker::new(); self.trackers.len()];
        self.mem.restart_peaks();
        self.mem_base = Some(self.mem.stats());
        self.frame_start = self.now;
        self.frame_tiles_done = self.tiles_done;
    }

    /// Whether every tile of the frame is rendered (and flushed) and the
    /// memory system is idle.
    pub fn done(&self) -> bool {
        let n = self.frame.end;
        let fed = match &self.dispatch {
            Dispatcher::PerCore { next_tile, .. } => *next_tile >= n,
            Dispatcher::Shared(r) => r.done(n),
        };
        fed && self.cores.iter().all(|c| c.idle()) && self.mem.is_idle()
    }

    /// Advance one cycle. This path is compiled without any tracing hook.
    /// (Kept out of line: one call per cycle costs nothing measurable, and
    /// profiles can then count exactly the cycle loop.)
    #[inline(never)]
    pub fn step(&mut self) -> Result<(), SimError> {
        self.step_impl::<NullTracer, false>(None)
    }

    /// Advance one cycle, sampling every signal into `sink` if given.
    pub fn step_traced<S: CycleSink>(&mut self, sink: Option<&mut S>) -> Result<(), SimError> {
        self.step_impl::<S, true>(sink)
    }

    /// One cycle; with `HOOKS = false` the tracing hook is not compiled in
    /// at all (what `wasp bench` compares against to price the hook).
    #[inline]
    fn step_impl<S: CycleSink, const HOOKS: bool>(
        &mut self,
        sink: Option<&mut S>,
    ) -> Result<(), SimError> {
        self.now += 1;
        let now = self.now;
        let mut progress = match self.dispatch {
            Dispatcher::PerCore { .. } => self.evaluate_per_core(now),
            Dispatcher::Shared(_) => self.evaluate_shared(now),
        };
        self.mem.tick(now);
        match sink {
            Some(s) if HOOKS => {
                for c in self.cores.iter_mut() {
                    progress |= c.complete(now, &mut self.mem)?;
                }
                s.begin_cycle(now);
                self.trace_signals(s);
                s.end_cycle().map_err(SimError::Io)?;
                for i in 0..self.cores.len() {
                    progress |= self.core_end_cycle(i, now);
                }
            }
            _ => {
                // A core's end of cycle touches only itself: it can follow
                // its completions directly.
                for i in 0..self.cores.len() {
                    progress |= self.cores[i].complete(now, &mut self.mem)?;
                    progress |= self.core_end_cycle(i, now);
                }
            }
        }
        progress |= self.close_shared_tile(now);
        if progress {
            self.last_progress = now;
        }
        if self.timeline.as_ref().is_some_and(|tl| tl.covers(now)) {
            self.sample_timeline(now);
        }
        // Checked every 256 cycles: the limit is a coarse bound anyway.
        if now.is_multiple_of(256) {
            self.watchdog()?;
        }
        Ok(())
    }

    /// Phase 1 under per-core-tile dispatch: each idle core takes the next
    /// tile, then every core evaluates. One pass over the cores: a core's
    /// tile assignment depends only on its own idleness (tiles are released
    /// at the end of a cycle), so taking tiles in core order within the
    /// pass is the same as taking them all first. Whether anything made
    /// progress.
    #[inline(always)]
    fn evaluate_per_core(&mut self, now: u64) -> bool {
        let Dispatcher::PerCore { next_tile, end } = &mut self.dispatch else {
            unreachable!("per-core-tile dispatch")
        };
        let tiles = self.trace.tiles();
        let mut progress = false;
        let pf_on = self.prefetch.is_some();
        for (i, c) in self.cores.iter_mut().enumerate() {
            if c.idle() && *next_tile < *end {
                c.assign_tile(*next_tile, &tiles[*next_tile]);
                self.trackers[i].start(*next_tile as u32, Some(i as u32), now);
                if let Some(tl) = self.timeline.as_mut() {
                    tl.mark(now, *next_tile as u32, Some(i as u32), true);
                }
                if let Some(pf) = self.prefetch.as_deref_mut() {
                    pf.tile_opened(*next_tile, Some(i), &mut self.mem);
                }
                *next_tile += 1;
                progress = true;
            }
            let entered = if pf_on { c.quads_entered() } else { 0 };
            progress |= c.evaluate(now, self.trace, &mut self.mem);
            if pf_on {
                if let (Some(pf), Some(t)) = (self.prefetch.as_deref_mut(), c.tile()) {
                    let quads = entered..c.quads_entered();
                    prefetch::quads_entered(pf, &tiles[t], quads, |_, _| i, &mut self.mem);
                }
            }
            if let Some((q, prio)) = c.launched_now() {
                let quad = tiles[c.tile().expect("launching")].quad(q as usize);
                let quad = quad.expect("quad in tile");
                let t = &mut self.trackers[i];
                t.launch(now, q, quad.x(), quad.y(), prio);
                // Occupancy rises only at a launch: its peak is found
                // there.
                t.resident(now, c.active());
            }
        }
        progress
    }

    /// Phase 1 under shared-tile dispatch: the raster pipeline, then every
    /// core. Whether anything made progress.
    #[inline(always)]
    fn evaluate_shared(&mut self, now: u64) -> bool {
        let Dispatcher::Shared(r) = &mut self.dispatch else {
            unreachable!("shared-tile dispatch")
        };
        let cycle = r.evaluate(now, self.trace, &mut self.cores, &mut self.mem);
        let mut progress = cycle.progress;
        if let Some(pf) = self.prefetch.as_deref_mut() {
            let opened = cycle.opened.map(|t| t as usize);
            feed_prefetcher(pf, r, opened, self.trace.tiles(), &mut self.mem);
        }
        if let Some(t) = cycle.opened {
            self.trackers[0].start(t, None, now);
            if let Some(tl) = self.timeline.as_mut() {
                tl.mark(now, t, None, true);
            }
        }
        let tile = r.tile().map(|t| &self.trace.tiles()[t]);
        let mut launched = false;
        for c in self.cores.iter_mut() {
            progress |= c.evaluate(now, self.trace, &mut self.mem);
            if let (Some((q, prio)), Some(tile)) = (c.launched_now(), tile) {
                let quad = tile.quad(q as usize).expect("quad in tile");
                self.trackers[0].launch(now, q, quad.x(), quad.y(), prio);
                launched = true;
            }
        }
        if launched {
            // Occupancy rises only at a launch: its peak is found there.
            let resident = self.cores.iter().map(|c| c.active()).sum();
            self.trackers[0].resident(now, resident);
        }
        progress
    }

    /// Under shared-tile dispatch, the tile barrier at the end of the
    /// cycle: whether the open tile closed.
    #[inline(always)]
    fn close_shared_tile(&mut self, now: u64) -> bool {
        let Dispatcher::Shared(r) = &mut self.dispatch else {
            return false;
        };
        let Some(t) = r.end_cycle(self.trace, &mut self.cores) else {
            return false;
        };
        let misses = self.cores.iter().map(|c| c.tile_misses()).sum();
        self.trackers[0].finish(now, misses);
        self.tiles_done += 1;
        if let Some(tl) = self.timeline.as_mut() {
            tl.mark(now, t as u32, None, false);
        }
        true
    }

    /// A core's end of cycle; under per-core-tile dispatch, its tile's
    /// end. Whether its tile ended.
    #[inline(always)]
    fn core_end_cycle(&mut self, i: usize, now: u64) -> bool {
        let c = &mut self.cores[i];
        let tile = c.tile();
        if !c.end_cycle() {
            return false;
        }
        self.tiles_done += 1;
        let misses = c.tile_misses();
        self.trackers[i].finish(now, misses);
        if let Some(tl) = self.timeline.as_mut() {
            tl.mark(
                now,
                tile.expect("a finished tile") as u32,
                Some(i as u32),
                false,
            );
        }
        true
    }

    fn sample_timeline(&mut self, now: u64) {
        let Some(tl) = self.timeline.as_mut() else {
            return;
        };
        tl.samples.push(TimelineSample {
            cycle: now,
            resident: self.cores.iter().map(|c| c.active()).collect(),
            outstanding: self.mem.outstanding(),
            priority_launches: self
                .cores
                .iter()
                .map(|c| u32::from(c.launched_now().is_some_and(|(_, p)| p)))
                .collect(),
        });
    }

    /// The last cycle in which a stage of a core or the raster pipeline
    /// made progress, or a tile began or ended.
    pub fn last_progress(&self) -> u64 {
        self.last_progress
    }

    /// Stop a run in which nothing made progress for
    /// `sim.watchdog_cycles` while a core has a tile or the raster
    /// pipeline has work.
    #[inline(never)]
    fn watchdog(&self) -> Result<(), SimError> {
        let rastering = match &self.dispatch {
            Dispatcher::Shared(r) => !r.done(self.frame.end),
            Dispatcher::PerCore { .. } => false,
        };
        let busy = rastering || self.cores.iter().any(|c| !c.idle());
        if busy && self.now - self.last_progress > self.cfg.sim.watchdog_cycles {
            let state: Vec<String> = self.cores.iter().map(|c| c.describe(self.trace)).collect();
            return Err(SimError::Watchdog {
                cycle: self.now,
                state: state.join("\n"),
            });
        }
        Ok(())
    }

    /// Every signal of the GPU: the raster pipeline (`raster`, under
    /// shared-tile dispatch), one scope per core (its scheduler, warps,
    /// LDST and private caches), then the shared L2 and DRAM.
    pub fn trace_signals<T: Tracer + ?Sized>(&self, t: &mut T) {
        use wasp_waves::Traceable;
        if let Dispatcher::Shared(r) = &self.dispatch {
            t.push_scope("raster");
            r.trace(t);
            t.pop_scope();
        }
        for (i, c) in self.cores.iter().enumerate() {
            t.push_scope(&self.core_scopes[i]);
            c.trace(t);
            self.mem.trace(i, t);
            t.pop_scope();
        }
        self.mem.trace_shared(t);
    }

    /// Record every warp from now on.
    pub fn record_warps(&mut self) {
        for c in self.cores.iter_mut() {
            c.record_warps();
        }
    }

    /// The warp records so far, ordered by tile and quad.
    pub fn take_records(&mut self) -> Vec<WarpRecord> {
        let mut all: Vec<WarpRecord> = self
            .cores
            .iter_mut()
            .flat_map(|c| c.take_records())
            .collect();
        all.sort_by_key(|r| (r.tile, r.quad));
        all
    }

    /// The counters of a run that is [`Gpu::done`], after checking that
    /// every warp and quad of the trace (of its last frame) went through.
    pub fn finish(self) -> Result<RunCounters, SimError> {
        self.end_frame()
    }

    /// The counters of the frame that is [`Gpu::done`] (since
    /// [`start_frame`](Self::start_frame)), after checking that every
    /// warp and quad of its tiles went through. Its cycles are those of
    /// the frame; tile records keep the run's cycles.
    pub fn end_frame(&self) -> Result<RunCounters, SimError> {
        let launched: u64 = self.cores.iter().map(|c| c.stats().warps_launched).sum();
        let finished: u64 = self.cores.iter().map(|c| c.stats().warps_finished).sum();
        let tiles = &self.trace.tiles()[self.frame.clone()];
        let quads = tiles.iter().map(|t| t.quad_count() as u64).sum::<u64>();
        if launched != quads || finished != quads {
            return Err(SimError::Internal(format!(
                "warps not conserved: {quads} quads in the trace, {launched} launched, {finished} finished"
            )));
        }
        let core_stats: Vec<CoreStats> = self.cores.iter().map(|c| c.stats().clone()).collect();
        let raster = match &self.dispatch {
            Dispatcher::Shared(r) => r.stats().clone(),
            Dispatcher::PerCore { .. } => RasterStats {
                quads_rasterized: core_stats.iter().map(|c| c.quads_rasterized).sum(),
                quads_rejected: core_stats.iter().map(|c| c.quads_rejected).sum(),
                ..RasterStats::default()
            },
        };
        let expect_raster = quads + tiles.iter().map(|t| t.rejected_count()).sum::<u64>();
        if raster.quads_rasterized != expect_raster {
            return Err(SimError::Internal(format!(
                "quads not conserved: {expect_raster} in the trace (rejected ones included), {} rasterized",
                raster.quads_rasterized
            )));
        }
        let mut per_tile: Vec<TileRecord> = self
            .trackers
            .iter()
            .flat_map(|t| t.records().iter().cloned())
            .collect();
        per_tile.sort_by_key(|r| r.tile);
        let instruments = RunInstruments {
            tiles: (self.tiles_done - self.frame_tiles_done) as u64,
            raster,
            priority_lead: TileTracker::lead_stats(&self.trackers),
            tile_timing: TileTracker::timing(&per_tile),
            per_tile,
        };
        let mem = match &self.mem_base {
            None => self.mem.stats(),
            Some(base) => self.mem.stats().since(base),
        };
        Ok(RunCounters {
            cycles: self.now - self.frame_start,
            cores: core_stats,
            mem,
            instruments,
        })
    }
}
