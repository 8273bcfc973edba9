//! The fast shader core against its plain twin, in lockstep: two GPUs on
//! the same configuration and trace, one of [`ShaderCore`]s and one of
//! [`PlainCore`]s, each with its own memory system, step together; after
//! every cycle each core's observable state ([`CoreSnapshot`]: the tile,
//! queue, registers and every warp's slot, state, ALU run, next
//! instruction and blocks outstanding), counters, launch signal and
//! description, the GPUs' last cycle of progress, and the memory system's
//! outstanding requests, must be equal. Before every cycle both say alike
//! which cores are idle, and an idle core's state does not change in the
//! cycle unless the GPU gives it a tile or a quad. At the end the runs'
//! counters, warp records and waveforms must be equal too.
//!
//! [`CoreSnapshot`]: super::CoreSnapshot
//!
//! Run on random small machines and traces (proptest), on the generator's
//! frames, on the shipped traces, and (ignored by default) on every trace
//! in the folder `WASP_LOCKSTEP_TRACES` names, such as the real scenes'
//! traces `scripts/machines.sh` renders; each under both issue orders
//! (`core.issue`).

use super::core::plain::PlainCore;
use super::{CoreModel, Gpu, ShaderCore};
use crate::config::{BlockedOn, Dispatch, FilterTiming, IssueOrder, MachineConfig};
use crate::mem::PrefetchKind;
use crate::trace::{Instr, Trace, TraceHeader};
use proptest::prelude::*;
use wasp_rtl::policy::{LaunchRule, PolicySpec};
use wasp_rtl::subset::SubsetSpec;
use wasp_waves::VcdSink;

/// Step both GPUs to the end, comparing them after every cycle; then
/// compare what they counted. Returns the cycles run.
fn lockstep(cfg: &MachineConfig, trace: &Trace) -> Result<u64, String> {
    let mut fast = Gpu::<ShaderCore>::build(cfg, trace).map_err(|e| e.to_string())?;
    let mut plain = Gpu::<PlainCore>::build(cfg, trace).map_err(|e| e.to_string())?;
    fast.record_warps();
    plain.record_warps();
    while !fast.done() {
        let next = fast.cycle() + 1;
        let idle: Vec<bool> = fast.cores().iter().map(|c| c.is_idle(next)).collect();
        let plain_idle: Vec<bool> = plain.cores().iter().map(|c| c.is_idle(next)).collect();
        if idle != plain_idle {
            return Err(format!(
                "cycle {next}: idle cores {idle:?} (fast), {plain_idle:?} (plain)"
            ));
        }
        let before: Vec<_> = fast.cores().iter().map(|c| c.snapshot()).collect();
        let a = fast.step();
        let b = plain.step();
        let now = fast.cycle();
        match (a, b) {
            (Ok(()), Ok(())) => {}
            (a, b) => return Err(format!("cycle {now}: fast {a:?}, plain {b:?}")),
        }
        compare(&fast, &plain, trace).map_err(|e| format!("cycle {now}: {e}"))?;
        // An idle core changes only by what the GPU gives it: a tile, or a
        // quad from the shared rasterizer (which it may launch at once);
        // and its free-MSHR register follows the watched cache, which
        // prefetches may use meanwhile.
        for (i, c) in fast.cores().iter().enumerate() {
            let mut after = c.snapshot();
            let queued = |q: [usize; 2]| q[0] + q[1];
            let launched = usize::from(c.launched_now().is_some());
            let pushed = queued(after.queued) + launched > queued(before[i].queued);
            let given = after.tile != before[i].tile || pushed;
            after.free_mshrs = before[i].free_mshrs;
            if idle[i] && !given && after != before[i] {
                return Err(format!("cycle {now}: core {i} was idle but changed"));
            }
        }
    }
    if !plain.done() {
        return Err(format!(
            "the fast GPU finished at cycle {}, the plain one did not",
            fast.cycle()
        ));
    }
    let cycles = fast.cycle();
    let (mut wa, mut wb) = (fast.take_records(), plain.take_records());
    wa.sort_by_key(|w| (w.tile, w.quad, w.core));
    wb.sort_by_key(|w| (w.tile, w.quad, w.core));
    if wa != wb {
        return Err("warp records differ".into());
    }
    let a = format!("{:?}", fast.finish().map_err(|e| e.to_string())?);
    let b = format!("{:?}", plain.finish().map_err(|e| e.to_string())?);
    if a != b {
        return Err(format!("run counters differ:\nfast  {a}\nplain {b}"));
    }
    Ok(cycles)
}

fn compare<C: CoreModel, D: CoreModel>(
    fast: &Gpu<'_, C>,
    plain: &Gpu<'_, D>,
    trace: &Trace,
) -> Result<(), String> {
    if fast.last_progress() != plain.last_progress() {
        return Err(format!(
            "last progress at cycle {} (fast) != {} (plain)",
            fast.last_progress(),
            plain.last_progress()
        ));
    }
    if fast.mem().outstanding() != plain.mem().outstanding() {
        return Err(format!(
            "outstanding requests {:?} (fast) != {:?} (plain)",
            fast.mem().outstanding(),
            plain.mem().outstanding()
        ));
    }
    for (i, (a, b)) in fast.cores().iter().zip(plain.cores()).enumerate() {
        let (sa, sb) = (a.snapshot(), b.snapshot());
        if sa != sb {
            return Err(format!("core {i}:\nfast  {sa:?}\nplain {sb:?}"));
        }
        if a.stats() != b.stats() {
            return Err(format!(
                "core {i} counters:\nfast  {:?}\nplain {:?}",
                a.stats(),
                b.stats()
            ));
        }
        let (fa, fb) = (
            (a.launched_now(), a.tile_misses()),
            (b.launched_now(), b.tile_misses()),
        );
        if fa != fb {
            return Err(format!(
                "core {i} (launch, tile misses): fast {fa:?}, plain {fb:?}"
            ));
        }
        if a.describe(trace) != b.describe(trace) {
            return Err(format!(
                "core {i}: {} / {}",
                a.describe(trace),
                b.describe(trace)
            ));
        }
    }
    Ok(())
}

/// The whole run's waveform from a GPU of cores `C`.
fn waveform<C: CoreModel>(cfg: &MachineConfig, trace: &Trace) -> Vec<u8> {
    let mut sink = VcdSink::new(Vec::new(), "gpu");
    let opts = crate::run::RunOptions::default();
    let run = crate::run::run_on::<C, _>(cfg, trace, &opts, Some(&mut sink), &mut |_, _| {});
    sink.finish(run.expect("run").stats.cycles)
        .expect("written")
}

/// A small machine from the drawn knobs.
#[derive(Clone, Debug)]
struct Knobs {
    l0: bool,
    cores: u32,
    warps: u32,
    width: u32,
    queue: u32,
    ldst: u32,
    alu_latency: u32,
    texture_latency: u32,
    filter: (u32, u32, bool),
    mshrs: u32,
    merged: u32,
    policy: &'static str,
    launch: bool,
    mesh2: bool,
    blocked_on: BlockedOn,
    shared: bool,
    raster: (u32, u32),
    issue: IssueOrder,
    /// Prefetcher, L1 reserve, queue entries.
    prefetch: (PrefetchKind, u32, u32),
}

impl Knobs {
    fn config(&self) -> MachineConfig {
        let mut c = if self.l0 {
            MachineConfig::paper()
        } else {
            MachineConfig::paper_width2()
        };
        c.gpu.tile_size = 8;
        c.gpu.cores = self.cores;
        c.core.max_warps = self.warps;
        c.core.pipeline_width = self.width;
        c.core.input_queue = self.queue;
        c.core.ldst_queue = self.ldst;
        c.core.issue = self.issue;
        c.core.alu_latency = self.alu_latency;
        c.core.texture_latency = self.texture_latency;
        c.core.filter_cycles_bilinear = self.filter.0;
        c.core.filter_cycles_trilinear = self.filter.1;
        c.core.filter_timing = if self.filter.2 {
            FilterTiming::Overlap
        } else {
            FilterTiming::Serial
        };
        let (_, first) = crate::mem::first_level(c.l0.as_mut(), &mut c.l1);
        first.mshrs = self.mshrs;
        first.max_merged = self.merged;
        c.l2.hit_latency = 2;
        c.dram.row_hit_latency = 3;
        c.dram.row_miss_latency = 6;
        c.scheduler.policy = self.policy.parse().unwrap();
        c.scheduler.launch_rule = if self.launch {
            LaunchRule::Launch
        } else {
            LaunchRule::Hold
        };
        c.scheduler.subset = SubsetSpec::Mesh(if self.mesh2 { 2 } else { 4 });
        c.scheduler.blocked_on = self.blocked_on;
        c.raster.dispatch = if self.shared {
            Dispatch::SharedTile
        } else {
            Dispatch::PerCoreTile
        };
        c.raster.quads_per_cycle = self.cores * self.raster.0;
        c.raster.rejected_per_slot = self.raster.1;
        c.prefetch.kind = self.prefetch.0;
        c.prefetch.l1_reserve = self.prefetch.1.min(c.l1.mshrs - 1);
        c.prefetch.queue = self.prefetch.2;
        c.sim.watchdog_cycles = 100_000;
        c
    }
}

fn arb_knobs() -> impl Strategy<Value = Knobs> {
    (
        (
            any::<bool>(),
            1u32..=4,
            prop::sample::select(vec![1u32, 2, 3, 5, 8, 64, 65, 128]),
            1u32..=4,
            1u32..=6,
            1u32..=3,
            // Beyond 64 cycles the wake-up wheel hands over to its heap.
            prop::sample::select(vec![1u32, 2, 5, 70]),
            0u32..=4,
        ),
        (
            (0u32..=2, 0u32..=3, any::<bool>()),
            1u32..=4,
            0u32..=2,
            prop::sample::select(vec![
                "baseline",
                "fullpriority",
                "freemshr:1",
                "wasp:0",
                "wasp:0:1",
                "wasp-m:0",
            ]),
            any::<bool>(),
            any::<bool>(),
            prop::sample::select(BlockedOn::ALL.to_vec()),
            any::<bool>(),
            (1u32..=2, 1u32..=3),
            prop::sample::select(IssueOrder::ALL.to_vec()),
            (
                prop::sample::select(PrefetchKind::ALL.to_vec()),
                0u32..=2,
                1u32..=4,
            ),
        ),
    )
        .prop_map(
            |(
                (l0, cores, warps, width, queue, ldst, alu_latency, texture_latency),
                (
                    filter,
                    mshrs,
                    merged,
                    policy,
                    launch,
                    mesh2,
                    blocked_on,
                    shared,
                    raster,
                    issue,
                    prefetch,
                ),
            )| Knobs {
                l0,
                cores,
                warps,
                width,
                queue,
                ldst,
                alu_latency,
                texture_latency,
                filter,
                mshrs,
                merged,
                policy,
                launch,
                mesh2,
                blocked_on,
                shared,
                raster,
                issue,
                prefetch,
            },
        )
}

/// One quad: its position, Early-Z-rejected quads before it, and its
/// program as (ALU run, texture blocks, trilinear) steps.
type QuadDraw = ((u32, u32), u32, Vec<(u32, Vec<u64>, bool)>);

/// Up to three 8x8-pixel tiles of up to twelve quads, positions repeating
/// (overdraw), each running ALU runs and texture instructions of one to
/// three blocks over an eight-block pool; some quads Early-Z-rejected.
fn arb_trace() -> impl Strategy<Value = Trace> {
    let step = (
        1u32..=5,
        prop::collection::btree_set(0u64..8, 1..=3).prop_map(|s| s.into_iter().collect()),
        prop::bool::weighted(0.25),
    );
    let quad = (
        (0u32..4, 0u32..4),
        prop::sample::select(vec![0u32, 0, 0, 1, 3]),
        prop::collection::vec(step, 0..=3),
    );
    let tile = prop::collection::vec(quad, 1..=12);
    prop::collection::vec(tile, 1..=3).prop_map(|tiles: Vec<Vec<QuadDraw>>| {
        let mut b = Trace::builder(TraceHeader::new("lockstep:random", 24, 8, 8)).unwrap();
        for (t, quads) in tiles.iter().enumerate() {
            b.begin_tile(t as u32, 0).unwrap();
            for ((x, y), rejected, prog) in quads {
                if *rejected > 0 {
                    b.rejected(*rejected).unwrap();
                }
                let mut ops = vec![];
                for (alu, blocks, tri) in prog {
                    ops.push(Instr::Alu(*alu));
                    ops.push(if *tri {
                        Instr::TriTex(blocks)
                    } else {
                        Instr::Tex(blocks)
                    });
                }
                ops.push(Instr::Alu(1));
                b.quad(*x, *y, &ops).unwrap();
            }
            b.end_tile().unwrap();
        }
        b.finish().unwrap()
    })
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 192,
        .. ProptestConfig::default()
    })]

    #[test]
    fn fast_and_plain_cores_agree_every_cycle(k in arb_knobs(), t in arb_trace()) {
        let cfg = k.config();
        prop_assume!(cfg.validate().is_ok());
        if let Err(e) = lockstep(&cfg, &t) {
            panic!("{e}\nknobs {k:?}");
        }
    }
}

/// The shipped traces under every policy, both dispatch modes, every
/// blocking rule and both issue orders, on the paper's machine.
#[test]
fn fast_and_plain_cores_agree_on_the_shipped_traces() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/traces");
    let mut runs = 0;
    for name in ["tiny", "overdraw", "synthetic-small"] {
        let trace = Trace::read(dir.join(format!("{name}.trace"))).unwrap();
        for policy in [
            "baseline",
            "fullpriority",
            "freemshr:10",
            "wasp:0:3",
            "wasp-m:0",
        ] {
            for dispatch in [Dispatch::SharedTile, Dispatch::PerCoreTile] {
                for blocked_on in BlockedOn::ALL {
                    for issue in IssueOrder::ALL {
                        let mut cfg = MachineConfig::paper();
                        cfg.gpu.tile_size = trace.header().tile;
                        cfg.scheduler.policy = policy.parse().unwrap();
                        cfg.raster.dispatch = dispatch;
                        cfg.scheduler.blocked_on = blocked_on;
                        cfg.core.issue = issue;
                        cfg.validate().unwrap();
                        if let Err(e) = lockstep(&cfg, &trace) {
                            panic!("{name} {policy} {dispatch} {blocked_on} {issue}: {e}");
                        }
                        runs += 1;
                    }
                }
            }
        }
    }
    assert_eq!(runs, 3 * 5 * 2 * 3 * 2);
}

/// The shipped traces with each prefetcher, under the baseline and WaSP,
/// both dispatch modes, on both machines of the paper (at width 2 the
/// prefetches share the scheduler-level cache's MSHRs).
#[test]
fn fast_and_plain_cores_agree_with_each_prefetcher() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/traces");
    let mut runs = 0;
    for name in ["tiny", "overdraw", "synthetic-small"] {
        let trace = Trace::read(dir.join(format!("{name}.trace"))).unwrap();
        for kind in [PrefetchKind::OracleTile, PrefetchKind::Raster] {
            for machine in [MachineConfig::paper(), MachineConfig::paper_width2()] {
                for policy in ["baseline", "wasp:0:3"] {
                    for dispatch in [Dispatch::SharedTile, Dispatch::PerCoreTile] {
                        let mut cfg = machine.clone();
                        cfg.gpu.tile_size = trace.header().tile;
                        cfg.scheduler.policy = policy.parse().unwrap();
                        cfg.raster.dispatch = dispatch;
                        cfg.prefetch.kind = kind;
                        cfg.validate().unwrap();
                        if let Err(e) = lockstep(&cfg, &trace) {
                            panic!("{name} {kind} {} {policy} {dispatch}: {e}", cfg.name);
                        }
                        runs += 1;
                    }
                }
            }
        }
    }
    assert_eq!(runs, 3 * 2 * 2 * 2 * 2);
}

/// Frames of the workload generator (a few thousand warps each) on both
/// machines of the paper: loose round-robin under both dispatch modes,
/// greedy-then-oldest under the paper's (shared-tile).
#[test]
fn fast_and_plain_cores_agree_on_generated_frames() {
    for seed in 1..=3 {
        let p = crate::synth::GenParams {
            frame_w: 256,
            frame_h: 128,
            seed,
            ..Default::default()
        };
        let trace = crate::synth::generate(&p).unwrap();
        for (machine, policy) in [
            (MachineConfig::paper(), "wasp:0:3"),
            (MachineConfig::paper_width2(), "fullpriority"),
        ] {
            for (dispatch, issue) in [
                (Dispatch::SharedTile, IssueOrder::Lrr),
                (Dispatch::PerCoreTile, IssueOrder::Lrr),
                (Dispatch::SharedTile, IssueOrder::Gto),
            ] {
                let mut cfg = machine.clone();
                cfg.scheduler.policy = policy.parse().unwrap();
                cfg.raster.dispatch = dispatch;
                cfg.core.issue = issue;
                cfg.validate().unwrap();
                let cycles = lockstep(&cfg, &trace)
                    .unwrap_or_else(|e| panic!("seed {seed} {policy} {dispatch} {issue}: {e}"));
                assert!(cycles > 1000, "a frame takes more than {cycles} cycles");
            }
        }
    }
}

/// Both cores draw the same waveform, signal for signal.
#[test]
fn fast_and_plain_cores_draw_the_same_waveform() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/traces");
    let trace = Trace::read(dir.join("overdraw.trace")).unwrap();
    for dispatch in [Dispatch::SharedTile, Dispatch::PerCoreTile] {
        let mut cfg = MachineConfig::paper();
        cfg.gpu.tile_size = trace.header().tile;
        cfg.scheduler.policy = PolicySpec::WaspMeasured { threshold: 0 };
        cfg.raster.dispatch = dispatch;
        cfg.validate().unwrap();
        let a = waveform::<ShaderCore>(&cfg, &trace);
        let b = waveform::<PlainCore>(&cfg, &trace);
        assert!(a.len() > 10_000, "a waveform of {} bytes", a.len());
        assert!(a == b, "the waveforms differ ({dispatch})");
    }
}

/// Every trace in the folder `WASP_LOCKSTEP_TRACES` (for example the 16
/// real scenes' traces in `target/machines/traces`), on the paper's
/// machine under the baseline and WaSP, both dispatch modes and both issue
/// orders; with `WASP_LOCKSTEP_PREFETCH` (a comma-separated list of
/// `prefetch.kind` values, e.g. `raster,oracle-tile`) under each of those
/// prefetchers instead of none.
#[test]
#[ignore = "long: set WASP_LOCKSTEP_TRACES to a folder of traces"]
fn fast_and_plain_cores_agree_on_a_folder_of_traces() {
    let dir = std::env::var("WASP_LOCKSTEP_TRACES").expect("WASP_LOCKSTEP_TRACES names a folder");
    let mut paths: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "trace"))
        .collect();
    paths.sort();
    assert!(!paths.is_empty(), "no .trace file in {dir}");
    let kinds: Vec<PrefetchKind> = match std::env::var("WASP_LOCKSTEP_PREFETCH") {
        Ok(list) => list.split(',').map(|k| k.trim().parse().unwrap()).collect(),
        Err(_) => vec![PrefetchKind::None],
    };
    for path in paths {
        let trace = Trace::read(&path).unwrap();
        for &kind in &kinds {
            for policy in ["baseline", "wasp:0:3"] {
                for dispatch in [Dispatch::SharedTile, Dispatch::PerCoreTile] {
                    for issue in IssueOrder::ALL {
                        let mut cfg = MachineConfig::paper();
                        cfg.gpu.tile_size = trace.header().tile;
                        cfg.scheduler.policy = policy.parse().unwrap();
                        cfg.raster.dispatch = dispatch;
                        cfg.core.issue = issue;
                        cfg.prefetch.kind = kind;
                        cfg.validate().unwrap();
                        let what =
                            format!("{}: {kind} {policy} {dispatch} {issue}", path.display());
                        let cycles =
                            lockstep(&cfg, &trace).unwrap_or_else(|e| panic!("{what}: {e}"));
                        eprintln!("{what}: {cycles} cycles agree");
                    }
                }
            }
        }
    }
}
