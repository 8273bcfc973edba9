//! The GPU: shader cores, the raster pipeline that feeds them and the
//! memory hierarchy, clocked by one cycle loop.
//!
//! Tiles are taken in trace order (the front end emits them in Z-order).
//! Two dispatch modes (`raster.dispatch`):
//!
//! * **shared-tile** (the paper's machine, `gpu/raster.rs`): one tile at a
//!   time for the whole GPU; one rasterizer places each surviving quad in
//!   the input queue of the core its position names ([`CoreMap`]); no warp
//!   of the next tile launches until every warp of this one has retired on
//!   every core; then the colour buffer is flushed.
//! * **per-core-tile**: each idle core takes the next tile, lowest core
//!   index first, rasterizes it with its own rasterizer and renders all of
//!   it before taking another; tiles run out of phase on the cores.
//!
//! Either way a tile fills and drains. A run ends when every tile is
//! rendered, every colour buffer flushed and the memory system is idle.

mod core;
mod core_map;
mod mask;
mod raster;
mod tiles;

pub use self::core::{CoreParams, CoreSnapshot, CoreStats, ShaderCore, WarpRecord, WarpView};
pub use self::core_map::{CoreMap, CoreMapTable};
pub use self::raster::{RasterStats, SharedRaster};
pub use self::tiles::{LeadBin, LeadStats, TileRecord, TileTimingStats, TileTracker};

use crate::config::{Dispatch, MachineConfig};
use crate::mem::MemorySystem;
use crate::stats::{RunInstruments, RunStats};
use crate::timeline::{Timeline, TimelineSample};
use crate::trace::Trace;
use std::fmt;
use wasp_rtl::policy::{LaunchRule, PolicySpec};
use wasp_rtl::subset::SubsetSpec;
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

/// Options of one run beyond the machine configuration.
#[derive(Clone, Debug, Default)]
pub struct RunOptions {
    /// Override `scheduler.policy`.
    pub policy: Option<PolicySpec>,
    /// Override `scheduler.launch_rule`.
    pub launch_rule: Option<LaunchRule>,
    /// Override `scheduler.subset`.
    pub subset: Option<SubsetSpec>,
    /// Override `memory.ideal`.
    pub ideal_memory: Option<bool>,
    /// Sample the waveform only in `from..=to`.
    pub vcd_window: Option<(u64, u64)>,
    /// Record every warp (see [`WarpRecord`]).
    pub record_warps: bool,
    /// Override `raster.dispatch`.
    pub dispatch: Option<Dispatch>,
    /// Record a [`Timeline`] of the cycles `from..=to`.
    pub timeline: Option<(u64, u64)>,
}

impl RunOptions {
    /// The configuration with the overrides applied, validated.
    pub fn apply(&self, cfg: &MachineConfig) -> Result<MachineConfig, SimError> {
        let mut c = cfg.clone();
        if let Some(p) = self.policy {
            c.scheduler.policy = p.to_string();
        }
        if let Some(r) = self.launch_rule {
            c.scheduler.launch_rule = r.to_string();
        }
        if let Some(s) = &self.subset {
            c.scheduler.subset = s.to_string();
        }
        if let Some(i) = self.ideal_memory {
            c.memory.ideal = i;
        }
        if let Some(d) = self.dispatch {
            c.raster.dispatch = d;
        }
        c.validate().map_err(SimError::Config)?;
        Ok(c)
    }
}

/// Who feeds the cores.
enum Dispatcher {
    /// Each idle core takes the next tile.
    PerCore {
        /// Next tile to hand out.
        next_tile: usize,
    },
    /// The GPU's one raster pipeline.
    Shared(SharedRaster),
}

/// The assembled GPU.
pub struct Gpu<'t> {
    cfg: MachineConfig,
    trace: &'t Trace,
    cores: Vec<ShaderCore>,
    mem: MemorySystem,
    dispatch: Dispatcher,
    /// One per renderer: the GPU (shared-tile) or each core (per-core).
    trackers: Vec<TileTracker>,
    timeline: Option<Timeline>,
    tiles_done: usize,
    now: u64,
    scratch: Vec<u32>,
}

impl<'t> Gpu<'t> {
    /// Build the GPU for `cfg` (already validated) and `trace`.
    pub fn new(cfg: &MachineConfig, trace: &'t Trace) -> Result<Self, SimError> {
        if trace.header().tile != cfg.gpu.tile_size {
            return Err(SimError::Config(format!(
                "the trace has {}-pixel tiles but gpu.tile_size is {}",
                trace.header().tile,
                cfg.gpu.tile_size
            )));
        }
        let policy = cfg.policy().map_err(SimError::Config)?;
        let subset = cfg.subset().map_err(SimError::Config)?;
        let rule = cfg.launch_rule().map_err(SimError::Config)?;
        let (_, sc) = cfg.scheduler_cache();
        let shared = cfg.raster.dispatch == Dispatch::SharedTile;
        let params = CoreParams {
            width: cfg.core.pipeline_width,
            max_warps: cfg.core.max_warps,
            input_queue: cfg.core.input_queue,
            raster_rate: cfg.raster.quads_per_cycle / cfg.gpu.cores,
            external_raster: shared,
            alu_latency: cfg.core.alu_latency,
            texture_latency: cfg.core.texture_latency,
            filter_cycles_bilinear: cfg.core.filter_cycles_bilinear,
            filter_cycles_trilinear: cfg.core.filter_cycles_trilinear,
            filter_timing: cfg.core.filter_timing,
            ldst_queue: cfg.core.ldst_queue,
            sched_mshrs: sc.mshrs,
            blocked_on: cfg.scheduler.blocked_on,
        };
        let side = cfg.quads_per_side();
        let mut cores = Vec::with_capacity(cfg.gpu.cores as usize);
        for id in 0..cfg.gpu.cores as usize {
            let p = policy.build(sc.mshrs.min(31)).map_err(SimError::Config)?;
            cores.push(ShaderCore::new(id, params, p, rule, subset.build(side)));
        }
        let mem =
            MemorySystem::new(&cfg.mem_config()).map_err(|e| SimError::Config(e.to_string()))?;
        let (dispatch, trackers) = if shared {
            let map = cfg.core_map().map_err(SimError::Config)?;
            let raster = SharedRaster::new(
                cfg.raster.quads_per_cycle,
                map.table(side, cfg.gpu.cores),
                cfg.raster.color_flush,
            );
            (Dispatcher::Shared(raster), vec![TileTracker::new()])
        } else {
            (
                Dispatcher::PerCore { next_tile: 0 },
                vec![TileTracker::new(); cfg.gpu.cores as usize],
            )
        };
        Ok(Self {
            cfg: cfg.clone(),
            trace,
            cores,
            mem,
            dispatch,
            trackers,
            timeline: None,
            tiles_done: 0,
            now: 0,
            scratch: Vec::with_capacity(64),
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
    pub fn cores(&self) -> &[ShaderCore] {
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

    /// Whether every tile is rendered (and flushed) and the memory system
    /// is idle.
    pub fn done(&self) -> bool {
        let n = self.trace.tiles().len();
        let fed = match &self.dispatch {
            Dispatcher::PerCore { next_tile } => *next_tile >= n,
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
        let tiles = self.trace.tiles();
        match &mut self.dispatch {
            Dispatcher::PerCore { next_tile } => {
                // One pass per phase over the cores. A core's tile
                // assignment depends only on its own idleness (tiles are
                // released at the end of a cycle), so taking tiles in core
                // order within the evaluate pass is the same as taking them
                // all first.
                for (i, c) in self.cores.iter_mut().enumerate() {
                    if c.idle() && *next_tile < tiles.len() {
                        c.assign_tile(*next_tile, &tiles[*next_tile], now);
                        self.trackers[i].start(*next_tile as u32, Some(i as u32), now);
                        if let Some(tl) = self.timeline.as_mut() {
                            tl.mark(now, *next_tile as u32, Some(i as u32), true);
                        }
                        *next_tile += 1;
                    }
                    c.evaluate(now, self.trace, &mut self.mem);
                    if let Some((q, prio)) = c.launched_now() {
                        let quad = tiles[c.tile().expect("launching")].quad(q as usize);
                        let quad = quad.expect("quad in tile");
                        let t = &mut self.trackers[i];
                        t.launch(now, q, quad.x(), quad.y(), prio);
                        // Occupancy rises only at a launch: its peak is
                        // found there.
                        t.resident(now, c.active());
                    }
                }
            }
            Dispatcher::Shared(r) => {
                let opened = r.evaluate(now, self.trace, &mut self.cores, &mut self.mem);
                if let Some(t) = opened {
                    self.trackers[0].start(t as u32, None, now);
                    if let Some(tl) = self.timeline.as_mut() {
                        tl.mark(now, t as u32, None, true);
                    }
                }
                let tile = r.tile().map(|t| &tiles[t]);
                let mut launched = false;
                for c in self.cores.iter_mut() {
                    c.evaluate(now, self.trace, &mut self.mem);
                    if let (Some((q, prio)), Some(tile)) = (c.launched_now(), tile) {
                        let quad = tile.quad(q as usize).expect("quad in tile");
                        self.trackers[0].launch(now, q, quad.x(), quad.y(), prio);
                        launched = true;
                    }
                }
                if launched {
                    // Occupancy rises only at a launch: its peak is found
                    // there.
                    let resident = self.cores.iter().map(|c| c.active()).sum();
                    self.trackers[0].resident(now, resident);
                }
            }
        }
        self.mem.tick(now);
        match sink {
            Some(s) if HOOKS => {
                for c in self.cores.iter_mut() {
                    c.complete(now, &mut self.mem, &mut self.scratch)?;
                }
                s.begin_cycle(now);
                self.trace_signals(s);
                s.end_cycle().map_err(SimError::Io)?;
                for i in 0..self.cores.len() {
                    self.core_end_cycle(i, now);
                }
            }
            _ => {
                // A core's end of cycle touches only itself: it can follow
                // its completions directly.
                for i in 0..self.cores.len() {
                    self.cores[i].complete(now, &mut self.mem, &mut self.scratch)?;
                    self.core_end_cycle(i, now);
                }
            }
        }
        if let Dispatcher::Shared(r) = &mut self.dispatch {
            if let Some(t) = r.end_cycle(self.trace, &mut self.cores, now) {
                let misses = self.cores.iter().map(|c| c.tile_misses()).sum();
                self.trackers[0].finish(now, misses);
                self.tiles_done += 1;
                if let Some(tl) = self.timeline.as_mut() {
                    tl.mark(now, t as u32, None, false);
                }
            }
        }
        if self.timeline.as_ref().is_some_and(|tl| tl.covers(now)) {
            self.sample_timeline(now);
        }
        self.watchdog()
    }

    /// A core's end of cycle; under per-core-tile dispatch, its tile's
    /// end.
    #[inline(always)]
    fn core_end_cycle(&mut self, i: usize, now: u64) {
        let c = &mut self.cores[i];
        let tile = c.tile();
        if c.end_cycle() {
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
        }
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

    fn watchdog(&self) -> Result<(), SimError> {
        // Checked every 256 cycles: the limit is a coarse bound anyway.
        if !self.now.is_multiple_of(256) {
            return Ok(());
        }
        let limit = self.cfg.sim.watchdog_cycles;
        let raster = match &self.dispatch {
            Dispatcher::Shared(r) if !r.done(self.trace.tiles().len()) => Some(r.last_progress()),
            _ => None,
        };
        let last = self
            .cores
            .iter()
            .filter(|c| !c.idle())
            .map(|c| c.last_progress())
            .chain(raster)
            .max();
        if let Some(last) = last {
            if self.now.saturating_sub(last) > limit {
                let state: Vec<String> =
                    self.cores.iter().map(|c| c.describe(self.trace)).collect();
                return Err(SimError::Watchdog {
                    cycle: self.now,
                    state: state.join("\n"),
                });
            }
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
            t.push_scope(&format!("core{i}"));
            c.trace(t);
            self.mem.trace(i, t);
            t.pop_scope();
        }
        self.mem.trace_shared(t);
    }

    /// Run to the end and return the statistics. `progress` is called every
    /// few thousand cycles with (tiles done, tiles total).
    pub fn run<S: CycleSink>(
        mut self,
        mut sink: Option<&mut S>,
        window: Option<(u64, u64)>,
        progress: &mut dyn FnMut(usize, usize),
    ) -> Result<RunStats, SimError> {
        let total = self.trace.tiles().len();
        while !self.done() {
            let next = self.now + 1;
            let sample = match window {
                Some((from, to)) => next >= from && next <= to,
                None => true,
            };
            if sample && sink.is_some() {
                self.step_traced(sink.as_deref_mut())?;
            } else {
                self.step()?;
            }
            if self.now.is_multiple_of(4096) {
                progress(self.tiles_done, total);
            }
        }
        progress(self.tiles_done, total);
        self.finish()
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

    fn finish(self) -> Result<RunStats, SimError> {
        let launched: u64 = self.cores.iter().map(|c| c.stats().warps_launched).sum();
        let finished: u64 = self.cores.iter().map(|c| c.stats().warps_finished).sum();
        let quads = self.trace.quad_count() as u64;
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
        let expect_raster = quads + self.trace.rejected_count();
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
            tiles: self.tiles_done as u64,
            raster,
            priority_lead: TileTracker::lead_stats(&self.trackers),
            tile_timing: TileTracker::timing(&per_tile),
            per_tile,
        };
        Ok(RunStats::collect(
            &self.cfg,
            self.trace,
            self.now,
            &core_stats,
            &self.mem.stats(),
            instruments,
        ))
    }
}

/// Run `trace` on `cfg` with `opts`, no waveform.
pub fn simulate(
    cfg: &MachineConfig,
    trace: &Trace,
    opts: &RunOptions,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<RunStats, SimError> {
    let cfg = opts.apply(cfg)?;
    Gpu::new(&cfg, trace)?.run::<NullTracer>(None, None, progress)
}

/// Run `trace` on `cfg` with `opts` and return the statistics with the
/// [`Timeline`] of the window `opts.timeline` (the whole run without one).
pub fn simulate_timeline(
    cfg: &MachineConfig,
    trace: &Trace,
    opts: &RunOptions,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<(RunStats, Timeline), SimError> {
    let cfg = opts.apply(cfg)?;
    let mut gpu = Gpu::new(&cfg, trace)?;
    let (from, to) = opts.timeline.unwrap_or((0, u64::MAX));
    gpu.record_timeline(from, to);
    let total = trace.tiles().len();
    while !gpu.done() {
        gpu.step()?;
        if gpu.cycle() % 4096 == 0 {
            progress(gpu.tiles_done(), total);
        }
        if gpu.cycle() > to {
            // The window is recorded; the rest of the run needs no samples.
            break;
        }
    }
    let timeline = gpu.take_timeline().expect("recording");
    while !gpu.done() {
        gpu.step()?;
        if gpu.cycle() % 4096 == 0 {
            progress(gpu.tiles_done(), total);
        }
    }
    progress(gpu.tiles_done(), total);
    Ok((gpu.finish()?, timeline))
}

/// Run `trace` on `cfg` with `opts` and return the statistics with one
/// record per warp (for heat maps).
pub fn simulate_recording(
    cfg: &MachineConfig,
    trace: &Trace,
    opts: &RunOptions,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<(RunStats, Vec<WarpRecord>), SimError> {
    let cfg = opts.apply(cfg)?;
    let mut gpu = Gpu::new(&cfg, trace)?;
    gpu.record_warps();
    let total = trace.tiles().len();
    while !gpu.done() {
        gpu.step()?;
        if gpu.cycle() % 4096 == 0 {
            progress(gpu.tiles_done(), total);
        }
    }
    progress(gpu.tiles_done(), total);
    let records = gpu.take_records();
    Ok((gpu.finish()?, records))
}

/// Run `trace` on `cfg` with `opts`, sampling the waveform into `sink`.
/// Returns the statistics and the last cycle.
pub fn simulate_traced<S: CycleSink>(
    cfg: &MachineConfig,
    trace: &Trace,
    opts: &RunOptions,
    sink: &mut S,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<RunStats, SimError> {
    let cfg = opts.apply(cfg)?;
    Gpu::new(&cfg, trace)?.run(Some(sink), opts.vcd_window, progress)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::ColorFlush;
    use crate::mem::BlockedOn;
    use crate::synth::{generate, GenParams};
    use crate::trace::{Instr, TraceHeader};

    fn tiny() -> Trace {
        let p = concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/traces/tiny.trace");
        Trace::read(p).unwrap()
    }

    fn cfg_for(trace: &Trace) -> MachineConfig {
        let mut c = MachineConfig::paper();
        c.gpu.tile_size = trace.header().tile;
        c.validate().unwrap();
        c
    }

    fn small_synth(seed: u64) -> Trace {
        generate(&GenParams {
            frame_w: 256,
            frame_h: 128,
            seed,
            ..GenParams::default()
        })
        .unwrap()
    }

    fn run(cfg: &MachineConfig, t: &Trace, policy: &str) -> RunStats {
        let opts = RunOptions {
            policy: Some(policy.parse().unwrap()),
            ..Default::default()
        };
        simulate(cfg, t, &opts, &mut |_, _| {}).unwrap()
    }

    const POLICIES: [&str; 4] = ["baseline", "fullpriority", "freemshr:10", "wasp:4"];

    #[test]
    fn every_policy_conserves_warps_on_the_tiny_trace() {
        let t = tiny();
        let cfg = cfg_for(&t);
        for p in POLICIES {
            let s = run(&cfg, &t, p);
            assert_eq!(s.warps, t.quad_count() as u64, "{p}");
            assert_eq!(s.instructions, t.instr_count(), "{p}");
            assert_eq!(s.tex_instructions, t.tex_count(), "{p}");
            assert_eq!(s.tiles, t.tiles().len() as u64);
            assert!(s.cycles > 0);
            // Every block access reached the first level exactly once.
            let l0 = s.l0.as_ref().unwrap();
            let accesses: u64 = t
                .tiles()
                .iter()
                .map(|x| x.block_accesses().len() as u64)
                .sum();
            assert_eq!(l0.accesses, accesses, "{p}");
            assert_eq!(l0.hits + l0.misses + l0.secondary_misses, accesses);
        }
    }

    /// One warp running ALU runs alone: each instruction waits the ALU
    /// latency for the previous one, on the wake-up wheels or beyond them
    /// (latencies of 64 cycles and more take the far queue), and a run
    /// split in two entries costs the same as one.
    #[test]
    fn a_lone_warp_waits_the_alu_latency_per_instruction() {
        let lone = |program: &[Instr]| {
            let mut b = Trace::builder(TraceHeader::new("lone", 8, 8, 8)).unwrap();
            b.begin_tile(0, 0).unwrap();
            b.quad(0, 0, program).unwrap();
            b.end_tile().unwrap();
            b.finish().unwrap()
        };
        let one = lone(&[Instr::Alu(5)]);
        let split = lone(&[Instr::Alu(2), Instr::Alu(3)]);
        for latency in [1u32, 4, 63, 64, 65, 200] {
            let mut cfg = cfg_for(&one);
            cfg.core.alu_latency = latency;
            cfg.validate().unwrap();
            for t in [&one, &split] {
                let mut gpu = Gpu::new(&cfg, t).unwrap();
                gpu.record_warps();
                while !gpu.done() {
                    gpu.step().unwrap();
                }
                let r = gpu.take_records();
                assert_eq!(r.len(), 1);
                // Issue the cycle after launch, then 5 instructions each
                // followed by the latency; the finish is seen at the
                // last wake-up.
                assert_eq!(
                    r[0].finished - r[0].launched,
                    1 + 5 * u64::from(latency),
                    "alu_latency {latency}"
                );
            }
        }
    }

    #[test]
    fn runs_are_deterministic() {
        let t = small_synth(3);
        let cfg = MachineConfig::paper();
        let a = run(&cfg, &t, "wasp:4").to_json();
        let b = run(&cfg, &t, "wasp:4").to_json();
        assert_eq!(a, b);
    }

    #[test]
    fn ideal_memory_is_never_slower() {
        let t = small_synth(5);
        let cfg = MachineConfig::paper();
        for p in POLICIES {
            let real = run(&cfg, &t, p);
            let ideal = simulate(
                &cfg,
                &t,
                &RunOptions {
                    policy: Some(p.parse().unwrap()),
                    ideal_memory: Some(true),
                    ..Default::default()
                },
                &mut |_, _| {},
            )
            .unwrap();
            assert!(
                ideal.cycles <= real.cycles,
                "{p}: {} > {}",
                ideal.cycles,
                real.cycles
            );
            assert_eq!(ideal.dram.avg_latency, 0.0, "ideal memory answers at once");
        }
    }

    /// WaSP at threshold 14 of 16 L0 MSHRs closes its gate often; under
    /// `hold` a core then idles whenever only priority warps wait, under
    /// `launch` it never does. The baseline never holds and is the same
    /// under both rules.
    #[test]
    fn launch_rule_hold_idles_and_launch_does_not() {
        let t = small_synth(3);
        let cfg = MachineConfig::paper();
        let go = |policy: &str, rule: LaunchRule| {
            let opts = RunOptions {
                policy: Some(policy.parse().unwrap()),
                launch_rule: Some(rule),
                ..Default::default()
            };
            simulate(&cfg, &t, &opts, &mut |_, _| {}).unwrap()
        };
        let hold = go("wasp:14", LaunchRule::Hold);
        let launch = go("wasp:14", LaunchRule::Launch);
        assert_eq!(
            (hold.launch_rule.as_str(), launch.launch_rule.as_str()),
            ("hold", "launch")
        );
        assert!(hold.held_cycles > 0, "{}", hold.held_cycles);
        assert_eq!(
            hold.held_cycles,
            hold.held_cycles_per_core.iter().sum::<u64>()
        );
        assert_eq!(hold.held_cycles_per_core.len(), cfg.gpu.cores as usize);
        assert_eq!(launch.held_cycles, 0);
        assert!(launch.held_cycles_per_core.iter().all(|&h| h == 0));
        for s in [&hold, &launch] {
            assert_eq!(s.warps, t.quad_count() as u64);
        }
        assert_ne!(hold.cycles, launch.cycles);
        let base_hold = go("baseline", LaunchRule::Hold);
        let base_launch = go("baseline", LaunchRule::Launch);
        assert_eq!(base_hold.held_cycles, 0);
        assert_eq!(base_hold.cycles, base_launch.cycles);
        assert_eq!(base_hold.per_tile, base_launch.per_tile);
    }

    #[test]
    fn the_measured_cf_variant_runs_and_reports_its_cf() {
        let t = small_synth(3);
        let cfg = MachineConfig::paper();
        let go = |policy: &str| {
            let opts = RunOptions {
                policy: Some(policy.parse().unwrap()),
                ..Default::default()
            };
            simulate(&cfg, &t, &opts, &mut |_, _| {}).unwrap()
        };
        let m = go("wasp-m:4");
        let w = go("wasp:4");
        assert_eq!(m.policy, "wasp-m:4");
        assert_eq!(m.warps, t.quad_count() as u64);
        assert_eq!(w.measured_cf_mean, None);
        let cf = m.measured_cf_mean.expect("wasp-m reports its CF");
        // The meter starts at 2.5 and loads misses per priority warp: some
        // window ended, so the mean moved off the reset value, inside the
        // register's range.
        assert!(cf > 0.0 && cf <= 7.75 && cf != 2.5, "{cf}");
        assert!(m.subset.priority_warps > 16);
        assert_ne!(m.cycles, w.cycles);
    }

    #[test]
    fn scarce_mshrs_stall_and_plentiful_do_not() {
        let t = small_synth(7);
        let mut scarce = MachineConfig::paper();
        scarce.l0.as_mut().unwrap().mshrs = 2;
        scarce.scheduler.policy = "fullpriority".into();
        scarce.validate().unwrap();
        let s = run(&scarce, &t, "fullpriority");
        assert!(s.l0.as_ref().unwrap().stall_cycles > 0);
        // Fullpriority does not read the 5-bit free-MSHR register, so the
        // L0 may have more MSHRs than it counts.
        let mut plenty = MachineConfig::paper();
        plenty.scheduler.policy = "fullpriority".into();
        plenty.l0.as_mut().unwrap().mshrs = 256;
        plenty.l1.mshrs = 256;
        plenty.l2.mshrs = 1024;
        let s = run(&plenty, &t, "fullpriority");
        assert_eq!(s.l0.as_ref().unwrap().stall_cycles, 0);
        assert_eq!(s.l1.stall_cycles, 0);
    }

    /// `run` under blocking rule `rule`.
    fn run_blocked(cfg: &MachineConfig, t: &Trace, policy: &str, rule: BlockedOn) -> RunStats {
        let mut c = cfg.clone();
        c.scheduler.blocked_on = rule;
        run(&c, t, policy)
    }

    /// The stats without the field naming the rule.
    fn json_without_rule(s: &RunStats) -> String {
        let mut v = serde_json::to_value(s).unwrap();
        v.as_object_mut().unwrap().remove("blocked_on");
        v.to_string()
    }

    #[test]
    fn l1_miss_blocks_fewer_warps_than_first_level_and_dram_fewer_still() {
        let t = small_synth(3);
        let cfg = MachineConfig::paper();
        let [first, l1, dram] = BlockedOn::ALL.map(|r| run_blocked(&cfg, &t, "wasp:4", r));
        assert_eq!(
            [&first.blocked_on, &l1.blocked_on, &dram.blocked_on],
            ["first-level", "l1-miss", "dram"]
        );
        // Every L0 miss blocks under first-level; only those the L1 misses
        // under l1-miss; only L2 misses under dram.
        assert!(
            first.blocked.episodes > l1.blocked.episodes,
            "{:?} {:?}",
            first.blocked,
            l1.blocked
        );
        assert!(
            l1.blocked.episodes >= dram.blocked.episodes,
            "{:?} {:?}",
            l1.blocked,
            dram.blocked
        );
        assert!(dram.blocked.episodes > 0);
        // Longer misses: longer episodes.
        assert!(l1.blocked.mean_cycles > first.blocked.mean_cycles);
        for s in [&first, &l1, &dram] {
            assert!(s.blocked.priority_episodes <= s.blocked.episodes);
            assert!(s.blocked.episodes <= s.tex_instructions);
        }
        // The rule is WaSP's input only: the baseline runs the same (all
        // but the blocked episodes it counts).
        let [a, b, c] = BlockedOn::ALL.map(|r| {
            let mut v = serde_json::to_value(run_blocked(&cfg, &t, "baseline", r)).unwrap();
            let m = v.as_object_mut().unwrap();
            m.remove("blocked_on");
            m.remove("blocked");
            v.to_string()
        });
        assert_eq!(a, b);
        assert_eq!(a, c);
    }

    #[test]
    fn without_l0_first_level_and_l1_miss_coincide() {
        let t = small_synth(5);
        let cfg = MachineConfig::paper_width2();
        for p in ["wasp:4", "wasp:2:1.5", "freemshr:10"] {
            let a = run_blocked(&cfg, &t, p, BlockedOn::FirstLevel);
            let b = run_blocked(&cfg, &t, p, BlockedOn::L1Miss);
            assert!(a.blocked.episodes > 0);
            assert_eq!(json_without_rule(&a), json_without_rule(&b), "{p}");
        }
    }

    #[test]
    fn width2_machine_schedules_on_the_l1() {
        let t = small_synth(9);
        let cfg = MachineConfig::paper_width2();
        for p in POLICIES {
            let s = run(&cfg, &t, p);
            assert!(s.l0.is_none());
            assert_eq!(s.warps, t.quad_count() as u64);
        }
    }

    #[test]
    fn baseline_launches_no_priority_warp_and_wasp_does() {
        let t = small_synth(11);
        let cfg = MachineConfig::paper();
        assert_eq!(run(&cfg, &t, "baseline").subset.priority_warps, 0);
        let w = run(&cfg, &t, "wasp:4");
        assert!(w.subset.priority_warps > 0);
        // Mesh4 selects at most 1/16 of the quads (partial tiles have fewer).
        assert!(
            w.subset.priority_warps * 16 <= t.quad_count() as u64 + 16 * t.tiles().len() as u64
        );
    }

    #[test]
    fn records_cover_every_warp_once() {
        let t = tiny();
        let cfg = cfg_for(&t);
        let (stats, recs) =
            simulate_recording(&cfg, &t, &RunOptions::default(), &mut |_, _| {}).unwrap();
        assert_eq!(recs.len() as u64, stats.warps);
        let plain = run(&cfg, &t, "wasp:0:3");
        assert_eq!(plain, stats, "recording does not change the run");
        for r in &recs {
            assert!(r.finished > r.launched);
            assert!(
                r.mem_latency.is_some_and(|l| l >= 1.0),
                "every tiny quad samples"
            );
        }
        let mut keys: Vec<(u32, u32)> = recs.iter().map(|r| (r.tile, r.quad)).collect();
        keys.dedup();
        assert_eq!(keys.len(), recs.len());
    }

    mod random_machines {
        use super::*;
        use proptest::prelude::*;

        /// A random trace of 8x8-pixel tiles (4x4 quads) whose texture
        /// instructions draw from a small block pool, so misses merge.
        fn arb_trace() -> impl Strategy<Value = Trace> {
            let quad = (
                prop::collection::vec((1u32..4, prop::collection::btree_set(0u64..24, 1..4)), 1..4),
                any::<bool>(),
            );
            let tile = prop::collection::vec(prop::option::of(quad), 16);
            prop::collection::vec(tile, 1..5).prop_map(|tiles| {
                let mut b = Trace::builder(TraceHeader::new("random:proptest", 32, 32, 8)).unwrap();
                for (ti, quads) in tiles.iter().enumerate() {
                    let (tx, ty) = (ti as u32 % 4, ti as u32 / 4);
                    let mut any = false;
                    for (qi, q) in quads.iter().enumerate() {
                        let Some((prog, tail_alu)) = q else { continue };
                        if !any {
                            b.begin_tile(tx, ty).unwrap();
                            any = true;
                        }
                        let mut ops: Vec<Instr> = Vec::new();
                        let blocks: Vec<Vec<u64>> = prog
                            .iter()
                            .map(|(_, s)| s.iter().map(|x| x + 1000 * ti as u64 % 3).collect())
                            .collect();
                        for ((alu, _), bl) in prog.iter().zip(&blocks) {
                            ops.push(Instr::Alu(*alu));
                            ops.push(Instr::Tex(bl));
                        }
                        if *tail_alu {
                            ops.push(Instr::Alu(2));
                        }
                        b.quad(qi as u32 % 4, qi as u32 / 4, &ops).unwrap();
                    }
                    if any {
                        b.end_tile().unwrap();
                    }
                }
                if b.tile_count() == 0 {
                    b.begin_tile(0, 0).unwrap();
                    b.quad(0, 0, &[Instr::Alu(1)]).unwrap();
                    b.end_tile().unwrap();
                }
                b.finish().unwrap()
            })
        }

        fn arb_config() -> impl Strategy<Value = MachineConfig> {
            (
                (1u32..=6, 1u32..=8, 1u32..=4, 1u32..=8),
                (0usize..4, any::<bool>(), 1u32..=3, any::<bool>()),
                (1u32..=3, 0usize..3, 0usize..3, 0usize..3),
            )
                .prop_map(
                    |(
                        (mshrs, warps, width, queue),
                        (policy, l0, cores, shared),
                        (rate, map, flush, rule),
                    )| {
                        let mut c = if l0 {
                            MachineConfig::paper()
                        } else {
                            MachineConfig::paper_width2()
                        };
                        c.gpu.tile_size = 8;
                        c.gpu.cores = cores;
                        c.raster.dispatch = if shared {
                            Dispatch::SharedTile
                        } else {
                            Dispatch::PerCoreTile
                        };
                        c.raster.quads_per_cycle = rate * cores;
                        c.raster.core_map = ["latin:2", "rowmajor:1", "latin:8"][map].into();
                        c.raster.color_flush =
                            [ColorFlush::Overlap, ColorFlush::Blocking, ColorFlush::None][flush];
                        c.core.max_warps = warps;
                        c.core.pipeline_width = width;
                        c.core.input_queue = queue;
                        c.l1.mshrs = mshrs.max(2);
                        if let Some(l0) = c.l0.as_mut() {
                            l0.mshrs = mshrs;
                        }
                        let t = mshrs - 1;
                        c.scheduler.policy = ["baseline", "fullpriority", "freemshr:1", "wasp"]
                            [policy]
                            .replace("wasp", &format!("wasp:{t}"));
                        c.scheduler.blocked_on = crate::mem::BlockedOn::ALL[rule];
                        c.sim.watchdog_cycles = 20_000;
                        c.validate().unwrap();
                        c
                    },
                )
        }

        proptest! {
            #![proptest_config(ProptestConfig { cases: 48, .. ProptestConfig::default() })]

            /// Every cycle: no cache holds more MSHR entries than it has;
            /// the run ends with every warp finished within a bound
            /// (bounded liveness); a core starts no warp of a tile before
            /// the previous tile's warps all finished (fill and drain);
            /// under shared-tile dispatch no core starts a warp of a tile
            /// before every core has finished the previous tile (the tile
            /// barrier), tiles run in trace order, and every warp runs on
            /// the core the map names for its position (no quad lost,
            /// duplicated or misplaced by back-pressure).
            #[test]
            fn invariants_hold_on_random_machines(cfg in arb_config(), trace in arb_trace()) {
                let mut gpu = Gpu::new(&cfg, &trace).unwrap();
                gpu.record_warps();
                let (_, sc) = cfg.scheduler_cache();
                let instrs = trace.instr_count();
                let raster = trace.quad_count() as u64 + trace.rejected_count();
                let flush = 4 * 64 * trace.tiles().len() as u64;
                let bound = 200 + instrs * 400 + raster + flush;
                while !gpu.done() {
                    gpu.step().unwrap();
                    prop_assert!(gpu.cycle() <= bound, "no finish within {bound} cycles");
                    for core in 0..cfg.gpu.cores as usize {
                        let ev = gpu.mem().mshr_events(core);
                        prop_assert!(ev.occupied <= sc.mshrs);
                        prop_assert!(ev.outstanding <= ev.occupied);
                    }
                }
                let records = gpu.take_records();
                prop_assert_eq!(records.len(), trace.quad_count());
                for core in 0..cfg.gpu.cores {
                    let mut tiles: Vec<(u64, u64)> = Vec::new();
                    let mut per_tile = std::collections::BTreeMap::<u32, (u64, u64)>::new();
                    for r in records.iter().filter(|r| r.core == core) {
                        let e = per_tile.entry(r.tile).or_insert((u64::MAX, 0));
                        e.0 = e.0.min(r.launched);
                        e.1 = e.1.max(r.finished);
                    }
                    tiles.extend(per_tile.values().copied());
                    tiles.sort_unstable();
                    for w in tiles.windows(2) {
                        prop_assert!(w[0].1 <= w[1].0, "tile started before the previous drained: {:?}", w);
                    }
                }
                if cfg.raster.dispatch == Dispatch::SharedTile {
                    let map = cfg.core_map().unwrap().table(cfg.quads_per_side(), cfg.gpu.cores);
                    let mut span = std::collections::BTreeMap::<u32, (u64, u64)>::new();
                    for r in &records {
                        let e = span.entry(r.tile).or_insert((u64::MAX, 0));
                        e.0 = e.0.min(r.launched);
                        e.1 = e.1.max(r.finished);
                        let q = trace.tiles()[r.tile as usize].quad(r.quad as usize).unwrap();
                        prop_assert_eq!(r.core as usize, map.core(q.x(), q.y()), "warp on the wrong core");
                    }
                    let spans: Vec<(u32, (u64, u64))> = span.into_iter().collect();
                    for w in spans.windows(2) {
                        prop_assert!(w[0].1 .1 < w[1].1 .0, "tile {} launched at {} before tile {} retired at {}", w[1].0, w[1].1 .0, w[0].0, w[0].1 .1);
                    }
                }
            }
        }
    }

    /// A trace of one-warp tiles with many Early-Z-rejected quads each.
    fn hidden_trace(tiles: u32, rejected: u32, with_warp: bool) -> Trace {
        let mut b = Trace::builder(TraceHeader::new("hidden", 64 * tiles, 64, 64)).unwrap();
        for t in 0..tiles {
            b.begin_tile(t, 0).unwrap();
            if rejected > 0 {
                b.rejected(rejected).unwrap();
            }
            if with_warp {
                b.quad(0, 0, &[Instr::Alu(1)]).unwrap();
            }
            b.end_tile().unwrap();
        }
        b.finish().unwrap()
    }

    fn run_dispatch(t: &Trace, d: Dispatch, flush: ColorFlush) -> RunStats {
        let mut cfg = MachineConfig::paper();
        cfg.raster.color_flush = flush;
        simulate(
            &cfg,
            t,
            &RunOptions {
                dispatch: Some(d),
                ..Default::default()
            },
            &mut |_, _| {},
        )
        .unwrap()
    }

    /// The rasterizer spends a slot on every quad Early-Z rejects: a trace
    /// whose quads are all rejected costs raster cycles in proportion to
    /// its quads (4 a cycle on the paper's machine), shared or per core.
    #[test]
    fn rejected_quads_cost_raster_cycles_in_proportion() {
        for d in [Dispatch::SharedTile, Dispatch::PerCoreTile] {
            let small = run_dispatch(&hidden_trace(4, 4000, false), d, ColorFlush::None);
            let big = run_dispatch(&hidden_trace(4, 8000, false), d, ColorFlush::None);
            assert_eq!(small.warps, 0);
            assert_eq!(small.raster.quads_rejected, 16_000, "{d}");
            assert_eq!(big.raster.quads_rasterized, 32_000, "{d}");
            match d {
                // One tile at a time: 4000 quads / 4 a cycle each; the next
                // tile's first quads are rasterized in the cycle after a
                // barrier.
                Dispatch::SharedTile => {
                    assert_eq!(small.cycles, 4 * 1000, "{d}");
                    assert_eq!(big.cycles, 4 * 2000, "{d}");
                    assert_eq!(small.per_tile[1].start, 1001);
                }
                // Four tiles at once, one quad a cycle each.
                Dispatch::PerCoreTile => {
                    assert_eq!(small.cycles, 4000, "{d}");
                    assert_eq!(big.cycles, 8000, "{d}");
                }
            }
        }
    }

    #[test]
    fn shared_tile_dispatch_renders_one_tile_at_a_time() {
        let t = small_synth(13);
        let cfg = MachineConfig::paper();
        let (stats, recs) =
            simulate_recording(&cfg, &t, &RunOptions::default(), &mut |_, _| {}).unwrap();
        assert_eq!(stats.dispatch, "shared-tile");
        assert_eq!(stats.tiles, t.tiles().len() as u64);
        assert_eq!(stats.per_tile.len(), t.tiles().len());
        // Every core shades part of every tile (the map spreads the tile).
        for tile in 0..t.tiles().len() as u32 {
            let mut cores: Vec<u32> = recs
                .iter()
                .filter(|r| r.tile == tile)
                .map(|r| r.core)
                .collect();
            cores.sort_unstable();
            cores.dedup();
            assert_eq!(cores, vec![0, 1, 2, 3], "tile {tile}");
        }
        // Tiles in trace order, each after the previous one's barrier.
        for w in stats.per_tile.windows(2) {
            assert!(w[0].end < w[1].start, "{:?}", w);
            assert_eq!(w[0].tile + 1, w[1].tile);
        }
        // A full tile's colour buffer: 64 rows of 4 lines.
        assert_eq!(stats.raster.flush_lines, 256 * stats.tiles);
        assert!(stats.tile_timing.mean_fill > 0.0);
        assert!(stats.tile_timing.mean_drain > 0.0);
        let h: u64 = stats.occupancy.histogram.iter().sum();
        assert_eq!(h, stats.cycles * 4, "one histogram entry per core-cycle");
    }

    #[test]
    fn a_blocking_flush_delays_the_next_tile() {
        let t = hidden_trace(3, 0, true);
        let overlap = run_dispatch(&t, Dispatch::SharedTile, ColorFlush::Overlap);
        let blocking = run_dispatch(&t, Dispatch::SharedTile, ColorFlush::Blocking);
        let none = run_dispatch(&t, Dispatch::SharedTile, ColorFlush::None);
        assert_eq!(none.raster.flush_lines, 0);
        assert_eq!(overlap.raster.flush_lines, 3 * 256);
        assert_eq!(blocking.raster.flush_lines, 3 * 256);
        // Blocking: each tile after the first waits for 256 lines, one a
        // cycle.
        let gap = |s: &RunStats| s.per_tile[1].start - s.per_tile[0].end;
        assert_eq!(gap(&overlap), 1);
        assert_eq!(gap(&blocking), 256);
        // The run ends when the last flush has reached the DRAM. The banked
        // DRAM takes a line per t_burst = 6 cycles a channel (4 channels):
        // slower than the flush's line a cycle, so the writes queue and the
        // run lasts about 3 x 256 x 6 / 4 cycles whether the tiles wait for
        // their flush or not. With overlap the last tile starts earlier, so
        // the run never ends later.
        assert!(blocking.cycles >= overlap.cycles);
        let drain = 3 * 256 * 6 / 4;
        assert!(overlap.cycles >= drain, "{} < {drain}", overlap.cycles);
        // The writes reach the DRAM either way, and cost energy.
        assert!(overlap.energy.dram_nj > none.energy.dram_nj);
    }

    #[test]
    fn per_core_dispatch_is_still_available() {
        let t = small_synth(17);
        let s = run_dispatch(&t, Dispatch::PerCoreTile, ColorFlush::Overlap);
        assert_eq!(s.dispatch, "per-core-tile");
        assert_eq!(s.warps, t.quad_count() as u64);
        assert_eq!(s.per_tile.len(), t.tiles().len());
        assert!(s.per_tile.iter().all(|r| r.core.is_some()));
    }

    #[test]
    fn the_timeline_covers_its_window() {
        let t = small_synth(19);
        let cfg = MachineConfig::paper();
        let opts = RunOptions {
            timeline: Some((100, 600)),
            ..Default::default()
        };
        let (stats, tl) = simulate_timeline(&cfg, &t, &opts, &mut |_, _| {}).unwrap();
        assert_eq!(stats, simulate(&cfg, &t, &opts, &mut |_, _| {}).unwrap());
        assert_eq!(tl.samples.len(), 501);
        assert_eq!(tl.samples[0].cycle, 100);
        assert_eq!(tl.samples[500].cycle, 600);
        assert!(tl.samples.iter().all(|s| s.resident.len() == 4));
        assert!(tl
            .samples
            .iter()
            .all(|s| s.resident.iter().all(|&r| r <= 64)));
        assert!(tl.marks.iter().all(|m| tl.covers(m.cycle)));
        let launches: u32 = tl
            .samples
            .iter()
            .flat_map(|s| s.priority_launches.iter())
            .sum();
        assert!(launches > 0, "wasp:4 launches priority warps");
    }

    #[test]
    fn trace_tile_size_must_match() {
        let t = tiny();
        let cfg = MachineConfig::paper();
        let e = simulate(&cfg, &t, &RunOptions::default(), &mut |_, _| {}).unwrap_err();
        assert!(e.to_string().contains("tile_size"), "{e}");
    }

    #[test]
    fn watchdog_reports_the_stuck_state() {
        // A texture latency far above the watchdog limit: the warps wait
        // longer than the watchdog allows.
        let t = tiny();
        let mut cfg = cfg_for(&t);
        cfg.core.texture_latency = 5000;
        cfg.sim.watchdog_cycles = 100;
        let e = simulate(&cfg, &t, &RunOptions::default(), &mut |_, _| {}).unwrap_err();
        let msg = e.to_string();
        assert!(msg.contains("watchdog") && msg.contains("core 0"), "{msg}");
    }
}
