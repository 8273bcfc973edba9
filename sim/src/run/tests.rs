//! Whole runs of the GPU through [`simulate`](super::simulate): warp
//! conservation under every policy, ALU timing, determinism, ideal memory,
//! the launch rules, the measured CF, MSHR stalls, priority launches, warp
//! records, Early-Z cost, shared-tile and per-core-tile dispatch, colour
//! flushes, timelines, tile-size checks and the watchdog.

use super::*;
use crate::config::BlockedOn;
use crate::config::ColorFlush;
use crate::config::Dispatch;
use crate::synth::{generate, GenParams};
use crate::trace::{Instr, TraceHeader};
use wasp_rtl::policy::{LaunchRule, PolicySpec};

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

pub(super) fn small_synth(seed: u64) -> Trace {
    generate(&GenParams {
        frame_w: 256,
        frame_h: 128,
        seed,
        ..GenParams::default()
    })
    .unwrap()
}

fn run(cfg: &MachineConfig, t: &Trace, policy: &str) -> RunStats {
    simulate(
        &with_policy(cfg, policy),
        t,
        &RunOptions::default(),
        &mut |_, _| {},
    )
    .unwrap()
}

/// `cfg` under `policy`.
fn with_policy(cfg: &MachineConfig, policy: &str) -> MachineConfig {
    let mut c = cfg.clone();
    c.scheduler.policy = policy.parse().unwrap();
    c
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
        let mut c = with_policy(&cfg, p);
        c.memory.ideal = true;
        let ideal = simulate(&c, &t, &RunOptions::default(), &mut |_, _| {}).unwrap();
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
        let mut c = with_policy(&cfg, policy);
        c.scheduler.launch_rule = rule;
        simulate(&c, &t, &RunOptions::default(), &mut |_, _| {}).unwrap()
    };
    let hold = go("wasp:14", LaunchRule::Hold);
    let launch = go("wasp:14", LaunchRule::Launch);
    assert_eq!(
        (hold.launch_rule, launch.launch_rule),
        (LaunchRule::Hold, LaunchRule::Launch)
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
    let go = |policy: &str| run(&cfg, &t, policy);
    let m = go("wasp-m:4");
    let w = go("wasp:4");
    assert_eq!(m.policy, PolicySpec::WaspMeasured { threshold: 4 });
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
    scarce.scheduler.policy = PolicySpec::FullPriority;
    scarce.validate().unwrap();
    let s = run(&scarce, &t, "fullpriority");
    assert!(s.l0.as_ref().unwrap().stall_cycles > 0);
    // Fullpriority does not read the 5-bit free-MSHR register, so the
    // L0 may have more MSHRs than it counts.
    let mut plenty = MachineConfig::paper();
    plenty.scheduler.policy = PolicySpec::FullPriority;
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
        [first.blocked_on, l1.blocked_on, dram.blocked_on],
        BlockedOn::ALL
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
    assert!(w.subset.priority_warps * 16 <= t.quad_count() as u64 + 16 * t.tiles().len() as u64);
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
                    c.raster.core_map = ["latin:2", "rowmajor:1", "latin:8"][map].parse().unwrap();
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
                    c.scheduler.policy = [
                        PolicySpec::Baseline,
                        PolicySpec::FullPriority,
                        PolicySpec::FreeMshr(1),
                        PolicySpec::wasp(t),
                    ][policy];
                    c.scheduler.blocked_on = crate::config::BlockedOn::ALL[rule];
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
                let map = cfg.raster.core_map.table(cfg.quads_per_side(), cfg.gpu.cores);
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
    cfg.raster.dispatch = d;
    simulate(&cfg, t, &RunOptions::default(), &mut |_, _| {}).unwrap()
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

/// With `raster.rejected_per_slot = k` a raster slot disposes of k
/// rejected quads: the hidden trace costs a k-th of the raster cycles,
/// shared or per core, with the same counts.
#[test]
fn a_coarse_early_z_rejects_several_quads_a_slot() {
    let t = hidden_trace(4, 4000, false);
    for d in [Dispatch::SharedTile, Dispatch::PerCoreTile] {
        let one = run_dispatch(&t, d, ColorFlush::None);
        for k in [2u32, 8] {
            let mut cfg = MachineConfig::paper();
            cfg.raster.color_flush = ColorFlush::None;
            cfg.raster.rejected_per_slot = k;
            cfg.raster.dispatch = d;
            let fast = simulate(&cfg, &t, &RunOptions::default(), &mut |_, _| {}).unwrap();
            assert_eq!(
                fast.raster.quads_rejected, one.raster.quads_rejected,
                "{d} {k}"
            );
            assert_eq!(fast.raster.quads_rasterized, one.raster.quads_rasterized);
            assert_eq!(fast.cycles, one.cycles / u64::from(k), "{d} {k}");
        }
    }
    let mut cfg = MachineConfig::paper();
    cfg.raster.rejected_per_slot = 0;
    assert!(cfg
        .validate()
        .unwrap_err()
        .contains("raster.rejected_per_slot"));
}

#[test]
fn shared_tile_dispatch_renders_one_tile_at_a_time() {
    let t = small_synth(13);
    let cfg = MachineConfig::paper();
    let (stats, recs) =
        simulate_recording(&cfg, &t, &RunOptions::default(), &mut |_, _| {}).unwrap();
    assert_eq!(stats.dispatch, Dispatch::SharedTile);
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
    assert_eq!(s.dispatch, Dispatch::PerCoreTile);
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

#[test]
fn the_texture_cache_choice_must_match_the_lines_the_trace_lists() {
    use crate::config::TextureCache;
    // One 16x16-texel level: 4x4 RGBA8 lines at 0, stored as ETC2 RGB in
    // 1x2 lines at 0x1000; warps read lines 0, 1 and 8.
    let decoded = "wasp-trace 4\nworkload w\ntexture-format etc2\ntexture-lines decoded\n\
                   texture-level 0 4 4 1000 1 2 4 2\nframe 8 8 tile 8\ntile 0 0\n\
                   q 0 0 t0,1 a2\nq 1 0 t8 a1\nend\n";
    let t = Trace::parse(decoded, "d").unwrap();
    let mut cfg = cfg_for(&t);
    let e = simulate(&cfg, &t, &RunOptions::default(), &mut |_, _| {}).unwrap_err();
    assert!(e.to_string().contains("texture-lines decoded"), "{e}");
    cfg.memory.texture_cache = TextureCache::Decompressed;
    let s = simulate(&cfg, &t, &RunOptions::default(), &mut |_, _| {}).unwrap();
    assert_eq!(s.warps, 2);
    assert_eq!(s.texture_cache, crate::config::TextureCache::Decompressed);
    // Three decoded lines in the L1, two stored lines below it.
    assert_eq!((s.l1.misses, s.dram.requests), (3, 2));
    // A trace of stored compressed lines needs compressed caches; an
    // RGBA8 trace runs under both (its lines are decoded and stored).
    let stored = decoded.replace(
        "texture-lines decoded\ntexture-level 0 4 4 1000 1 2 4 2\n",
        "",
    );
    let t = Trace::parse(&stored, "s").unwrap();
    let e = simulate(&cfg, &t, &RunOptions::default(), &mut |_, _| {}).unwrap_err();
    assert!(
        e.to_string().contains("--texture-cache decompressed"),
        "{e}"
    );
    let rgba8 = stored.replace("texture-format etc2\n", "");
    let t = Trace::parse(&rgba8, "r").unwrap();
    let s = simulate(&cfg, &t, &RunOptions::default(), &mut |_, _| {}).unwrap();
    assert_eq!((s.l1.misses, s.dram.requests), (3, 3));
}
