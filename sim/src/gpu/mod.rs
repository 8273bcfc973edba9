//! The GPU: shader cores, the tile dispatcher and the memory hierarchy,
//! clocked by one cycle loop.
//!
//! Tiles are taken in trace order (the front end emits them in Z-order);
//! each idle core takes the next tile, lowest core index first, and renders
//! all of it before taking another (fill and drain). A run ends when every
//! tile is rendered and the memory system is idle.

mod core;
mod mask;

pub use self::core::{CoreParams, CoreSnapshot, CoreStats, ShaderCore, WarpRecord, WarpView};

use crate::config::MachineConfig;
use crate::mem::MemorySystem;
use crate::stats::RunStats;
use crate::trace::Trace;
use std::fmt;
use wasp_rtl::policy::PolicySpec;
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
    /// Override `scheduler.subset`.
    pub subset: Option<SubsetSpec>,
    /// Override `memory.ideal`.
    pub ideal_memory: Option<bool>,
    /// Sample the waveform only in `from..=to`.
    pub vcd_window: Option<(u64, u64)>,
    /// Record every warp (see [`WarpRecord`]).
    pub record_warps: bool,
}

impl RunOptions {
    /// The configuration with the overrides applied, validated.
    pub fn apply(&self, cfg: &MachineConfig) -> Result<MachineConfig, SimError> {
        let mut c = cfg.clone();
        if let Some(p) = self.policy {
            c.scheduler.policy = p.to_string();
        }
        if let Some(s) = &self.subset {
            c.scheduler.subset = s.to_string();
        }
        if let Some(i) = self.ideal_memory {
            c.memory.ideal = i;
        }
        c.validate().map_err(SimError::Config)?;
        Ok(c)
    }
}

/// The assembled GPU.
pub struct Gpu<'t> {
    cfg: MachineConfig,
    trace: &'t Trace,
    cores: Vec<ShaderCore>,
    mem: MemorySystem,
    next_tile: usize,
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
        let (_, sc) = cfg.scheduler_cache();
        let params = CoreParams {
            width: cfg.core.pipeline_width,
            max_warps: cfg.core.max_warps,
            input_queue: cfg.core.input_queue,
            raster_rate: cfg.core.raster_quads_per_cycle,
            alu_latency: cfg.core.alu_latency,
            texture_latency: cfg.core.texture_latency,
            ldst_queue: cfg.core.ldst_queue,
            sched_mshrs: sc.mshrs,
        };
        let side = cfg.quads_per_side();
        let mut cores = Vec::with_capacity(cfg.gpu.cores as usize);
        for id in 0..cfg.gpu.cores as usize {
            let p = policy.build(sc.mshrs.min(31)).map_err(SimError::Config)?;
            cores.push(ShaderCore::new(id, params, p, subset.build(side)));
        }
        let mem =
            MemorySystem::new(&cfg.mem_config()).map_err(|e| SimError::Config(e.to_string()))?;
        Ok(Self {
            cfg: cfg.clone(),
            trace,
            cores,
            mem,
            next_tile: 0,
            tiles_done: 0,
            now: 0,
            scratch: Vec::with_capacity(64),
        })
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

    /// Whether every tile is rendered and the memory system is idle.
    pub fn done(&self) -> bool {
        self.next_tile >= self.trace.tiles().len()
            && self.cores.iter().all(|c| c.idle())
            && self.mem.is_idle()
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
        // One pass per phase over the cores. A core's tile assignment
        // depends only on its own idleness (tiles are released at the end of
        // a cycle), so taking tiles in core order within the evaluate pass
        // is the same as taking them all first.
        let tiles = self.trace.tiles();
        for c in self.cores.iter_mut() {
            if c.idle() && self.next_tile < tiles.len() {
                c.assign_tile(self.next_tile, tiles[self.next_tile].quad_count(), now);
                self.next_tile += 1;
            }
            c.evaluate(now, self.trace, &mut self.mem);
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
                for c in self.cores.iter_mut() {
                    self.tiles_done += usize::from(c.end_cycle());
                }
            }
            _ => {
                // A core's end of cycle touches only itself: it can follow
                // its completions directly.
                for c in self.cores.iter_mut() {
                    c.complete(now, &mut self.mem, &mut self.scratch)?;
                    self.tiles_done += usize::from(c.end_cycle());
                }
            }
        }
        self.watchdog()
    }

    fn watchdog(&self) -> Result<(), SimError> {
        // Checked every 256 cycles: the limit is a coarse bound anyway.
        if self.now % 256 != 0 {
            return Ok(());
        }
        let limit = self.cfg.sim.watchdog_cycles;
        let last = self
            .cores
            .iter()
            .filter(|c| !c.idle())
            .map(|c| c.last_progress())
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

    /// Every signal of the GPU: one scope per core (its scheduler, warps,
    /// LDST and private caches), then the shared L2 and DRAM.
    pub fn trace_signals<T: Tracer + ?Sized>(&self, t: &mut T) {
        use wasp_waves::Traceable;
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
            if self.now % 4096 == 0 {
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
        Ok(RunStats::collect(
            &self.cfg,
            self.trace,
            self.now,
            &core_stats,
            &self.mem.stats(),
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
        let plain = run(&cfg, &t, "wasp:4");
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
                1u32..=6,
                1u32..=8,
                1u32..=4,
                1u32..=8,
                0usize..4,
                any::<bool>(),
                1u32..=3,
            )
                .prop_map(|(mshrs, warps, width, queue, policy, l0, cores)| {
                    let mut c = if l0 {
                        MachineConfig::paper()
                    } else {
                        MachineConfig::paper_width2()
                    };
                    c.gpu.tile_size = 8;
                    c.gpu.cores = cores;
                    c.core.max_warps = warps;
                    c.core.pipeline_width = width;
                    c.core.input_queue = queue;
                    c.l1.mshrs = mshrs.max(2);
                    if let Some(l0) = c.l0.as_mut() {
                        l0.mshrs = mshrs;
                    }
                    let t = mshrs - 1;
                    c.scheduler.policy = ["baseline", "fullpriority", "freemshr:1", "wasp"][policy]
                        .replace("wasp", &format!("wasp:{t}"));
                    c.sim.watchdog_cycles = 20_000;
                    c.validate().unwrap();
                    c
                })
        }

        proptest! {
            #![proptest_config(ProptestConfig { cases: 48, .. ProptestConfig::default() })]

            /// Every cycle: no cache holds more MSHR entries than it has;
            /// the run ends with every warp finished within a bound
            /// (bounded liveness); a core starts no warp of a tile before
            /// the previous tile's warps all finished (fill and drain).
            #[test]
            fn invariants_hold_on_random_machines(cfg in arb_config(), trace in arb_trace()) {
                let mut gpu = Gpu::new(&cfg, &trace).unwrap();
                gpu.record_warps();
                let (_, sc) = cfg.scheduler_cache();
                let instrs = trace.instr_count();
                let bound = 200 + instrs * 400;
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
            }
        }
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
