//! (g)-(j) Properties of the assembled GPU (`wasp_sim::gpu::Gpu`), checked
//! after every cycle through the cores' and the memory system's observation
//! ports (`ShaderCore::snapshot`, `MemorySystem::mshr_files`):
//!
//! * (g) every MSHR file of every cache (L0, L1, L2) holds at most its
//!   capacity, and no more entries await a reply than are occupied;
//! * (h) each core's 5-bit free-MSHR register equals the capacity of its
//!   scheduler-level cache (L0 when present, else L1) minus the entries of
//!   that cache awaiting their reply (the register counts an entry free from
//!   its reply), for every policy that reads the register;
//! * (i) each core's 7-bit non-blocked counter equals the number of its
//!   warp slots holding a priority warp that is not blocked (launched,
//!   unblocked, unfinished), and the slots hold exactly the core's active
//!   warps;
//! * (j) fill and drain: every warp in a core was launched while the core
//!   held the tile it holds now (so a core never starts a tile's warps
//!   before the previous tile's warps finished), and a core without a tile
//!   holds no warp, queued quad or texture instruction;
//! * (k) bounded liveness: every warp finishes within
//!   [`MachineModel::warp_bound`] cycles of its launch and the whole run
//!   within [`MachineModel::run_bound`] cycles; at the end every quad of the
//!   trace finished exactly once, and per core the tiles' lifetimes (first
//!   launch to last finish) do not overlap.
//!
//! The model is independent of the core's own bookkeeping: warps are
//! identified by (slot, launch cycle) when they first appear, and the tile
//! each launched under is remembered by the checker, not read back.

use crate::cex::{ensure, Cex};
use std::collections::{BTreeMap, BTreeSet};
use wasp_sim::config::BlockedOn;
use wasp_sim::config::MachineConfig;
use wasp_sim::gpu::{CoreSnapshot, Gpu, WarpRecord};
use wasp_sim::mem::MshrFileView;
use wasp_sim::trace::{Instr, Trace, TraceHeader};

/// Property name used in counterexamples.
pub const PROP: &str = "(g)-(k) GPU";

/// The checker's model of a running GPU.
#[derive(Clone, Debug)]
pub struct MachineModel {
    /// Per core: warps seen, (slot, launch cycle) -> tile launched under.
    warps: Vec<BTreeMap<(usize, u64), usize>>,
    /// A warp finishes within this many cycles of its launch.
    pub warp_bound: u64,
    /// The run ends within this many cycles.
    pub run_bound: u64,
    /// Warps seen launching.
    pub launches: u64,
    /// Priority warps seen launching.
    pub priority_launches: u64,
    /// Cycles in which some core's scheduler-level cache had every MSHR
    /// occupied.
    pub full_cycles: u64,
    /// Most warps in one core at once.
    pub max_active: u32,
}

impl MachineModel {
    /// The model for `trace` on `cores` cores. Liveness bound: with `I` the
    /// trace's instructions, every warp finishes within `200 + 300 I`
    /// cycles of its launch, and the run within the same bound (the bound
    /// is loose on purpose: it must hold for every machine of the domain,
    /// memory latencies included).
    pub fn new(trace: &Trace, cores: usize) -> Self {
        let b = 200 + 300 * trace.instr_count();
        Self {
            warps: vec![BTreeMap::new(); cores],
            warp_bound: b,
            run_bound: b,
            launches: 0,
            priority_launches: 0,
            full_cycles: 0,
            max_active: 0,
        }
    }
}

/// Check the GPU after a cycle against the model and update it.
pub fn machine_cycle(gpu: &Gpu<'_>, model: &mut MachineModel) -> Result<(), Cex> {
    let now = gpu.cycle();
    let files = gpu.mem().mshr_files();
    let at = |what| Cex::new(PROP, what).with("cycle", now as i64);
    ensure(now <= model.run_bound, || {
        at("(k) the run did not end within its bound").with("bound", model.run_bound as i64)
    })?;
    for f in &files {
        check_mshr_file(f, now)?;
    }
    let mut any_full = false;
    for (i, core) in gpu.cores().iter().enumerate() {
        let s = core.snapshot();
        let first = files
            .iter()
            .find(|f| f.core == Some(i) && f.level == "l0")
            .or_else(|| files.iter().find(|f| f.core == Some(i) && f.level == "l1"))
            .ok_or_else(|| at("(h) no scheduler-level cache").with("core", i as i64))?;
        any_full |= first.occupied == first.capacity;
        check_counters(&s, first, now, i)?;
        model.max_active = model.max_active.max(s.active);
        track_warps(&s, now, i, model)?;
    }
    model.full_cycles += u64::from(any_full);
    Ok(())
}

/// (g): an MSHR file holds at most its capacity, and no more entries await
/// a reply than are occupied.
fn check_mshr_file(f: &MshrFileView, now: u64) -> Result<(), Cex> {
    let cex = |what| {
        Cex::new(PROP, what)
            .with("cycle", now as i64)
            .with("core", f.core.map_or(-1, |c| c as i64))
            .with("capacity", i64::from(f.capacity))
            .with("occupied", i64::from(f.occupied))
            .with("outstanding", i64::from(f.outstanding))
    };
    ensure(f.occupied <= f.capacity, || {
        cex("(g) MSHR occupancy exceeds the capacity")
    })?;
    ensure(f.outstanding <= f.occupied, || {
        cex("(g) more entries await a reply than are occupied")
    })
}

/// (h) and (i) for core `i` (snapshot `s`, scheduler-level cache
/// `first`): its free-MSHR register, its non-blocked counter, its slots.
fn check_counters(s: &CoreSnapshot, first: &MshrFileView, now: u64, i: usize) -> Result<(), Cex> {
    let cex = |what| {
        Cex::new(PROP, what)
            .with("cycle", now as i64)
            .with("core", i as i64)
    };
    if s.tracks_free_mshrs {
        let want = i64::from(first.capacity) - i64::from(first.outstanding);
        ensure(i64::from(s.free_mshrs) == want, || {
            cex("(h) free-MSHR register != capacity - outstanding")
                .with("register", i64::from(s.free_mshrs))
                .with("expected", want)
        })?;
    }
    let nonblocked = s.warps.iter().filter(|w| w.priority && !w.blocked).count();
    ensure(s.nonblocked as usize == nonblocked, || {
        cex("(i) non-blocked counter != unblocked priority warps in the slots")
            .with("counter", i64::from(s.nonblocked))
            .with("expected", nonblocked as i64)
    })?;
    ensure(
        s.warps.len() == s.active as usize && s.warps.len() <= s.slots,
        || {
            cex("(i) the slots do not hold the active warps")
                .with("occupied_slots", s.warps.len() as i64)
                .with("active", i64::from(s.active))
        },
    )?;
    Ok(())
}

/// (j) and (k) for core `i`'s warps: a core without a tile holds no work;
/// a warp new to the model launched this cycle, under the core's tile
/// (remembered); a known warp is still under the tile it launched under;
/// every warp is within its bound. Warps gone from the slots are
/// forgotten.
fn track_warps(s: &CoreSnapshot, now: u64, i: usize, model: &mut MachineModel) -> Result<(), Cex> {
    let cex = |what| {
        Cex::new(PROP, what)
            .with("cycle", now as i64)
            .with("core", i as i64)
    };
    if s.tile.is_none() {
        ensure(
            s.warps.is_empty() && s.queued == [0, 0] && s.ldst == 0,
            || cex("(j) a core without a tile holds work"),
        )?;
    }
    let seen = &mut model.warps[i];
    let mut present = BTreeSet::new();
    for w in &s.warps {
        let key = (w.slot, w.launched);
        present.insert(key);
        match seen.get(&key) {
            None => {
                ensure(w.launched == now, || {
                    cex("(j) a warp appeared that did not launch this cycle")
                        .with("slot", w.slot as i64)
                        .with("launched", w.launched as i64)
                })?;
                let tile = s
                    .tile
                    .ok_or_else(|| cex("(j) a warp launched without a tile"))?;
                seen.insert(key, tile);
                model.launches += 1;
                model.priority_launches += u64::from(w.priority);
            }
            Some(&tile) => {
                ensure(s.tile == Some(tile), || {
                    cex("(j) a warp of an earlier tile is still in the core")
                        .with("warp_tile", tile as i64)
                        .with("core_tile", s.tile.map_or(-1, |t| t as i64))
                })?;
            }
        }
        ensure(now - w.launched <= model.warp_bound, || {
            cex("(k) a warp did not finish within its bound")
                .with("launched", w.launched as i64)
                .with("bound", model.warp_bound as i64)
        })?;
    }
    seen.retain(|k, _| present.contains(k));
    Ok(())
}

/// Check the end of a run: every quad finished exactly once, as many as the
/// model saw launch, and per core the tiles' lifetimes do not overlap.
pub fn machine_end(trace: &Trace, records: &[WarpRecord], model: &MachineModel) -> Result<(), Cex> {
    let quads = trace.quad_count();
    let distinct: BTreeSet<(u32, u32)> = records.iter().map(|r| (r.tile, r.quad)).collect();
    ensure(
        records.len() == quads && distinct.len() == quads && model.launches == quads as u64,
        || {
            Cex::new(PROP, "(k) not every quad finished exactly once")
                .with("quads", quads as i64)
                .with("records", records.len() as i64)
                .with("distinct", distinct.len() as i64)
                .with("launches_seen", model.launches as i64)
        },
    )?;
    let mut life: BTreeMap<(u32, u32), (u64, u64)> = BTreeMap::new();
    for r in records {
        let e = life.entry((r.core, r.tile)).or_insert((u64::MAX, 0));
        e.0 = e.0.min(r.launched);
        e.1 = e.1.max(r.finished);
    }
    let mut per_core: BTreeMap<u32, Vec<(u64, u64)>> = BTreeMap::new();
    for (&(core, _), &span) in &life {
        per_core.entry(core).or_default().push(span);
    }
    for (core, mut spans) in per_core {
        spans.sort_unstable();
        for w in spans.windows(2) {
            ensure(w[0].1 <= w[1].0, || {
                Cex::new(PROP, "(j) a tile started before the previous one drained")
                    .with("core", i64::from(core))
                    .with("previous_last_finish", w[0].1 as i64)
                    .with("next_first_launch", w[1].0 as i64)
            })?;
        }
    }
    Ok(())
}

/// Run `trace` on `cfg` to the end, checking every cycle; returns the model
/// (for its coverage counters).
pub fn run_checked(cfg: &MachineConfig, trace: &Trace) -> Result<MachineModel, Cex> {
    let sim_err = |what| Cex::new(PROP, what);
    let mut gpu = Gpu::new(cfg, trace).map_err(|_| sim_err("the machine was refused"))?;
    gpu.record_warps();
    let mut model = MachineModel::new(trace, cfg.gpu.cores as usize);
    while !gpu.done() {
        gpu.step().map_err(|_| {
            sim_err("the simulator reported an error").with("cycle", gpu.cycle() as i64)
        })?;
        machine_cycle(&gpu, &mut model)?;
    }
    machine_end(trace, &gpu.take_records(), &model)?;
    Ok(model)
}

/// A small machine of the domain.
#[derive(Clone, Copy, Debug)]
pub struct SmallMachine {
    /// L0 present (the scheduler watches it), else the L1.
    pub l0: bool,
    /// Shader cores.
    pub cores: u32,
    /// Warp slots per core.
    pub warps: u32,
    /// Issue width.
    pub width: u32,
    /// Input queue entries.
    pub queue: u32,
    /// MSHRs of the scheduler-level cache.
    pub mshrs: u32,
    /// Secondary misses per MSHR entry of the scheduler-level cache.
    pub max_merged: u32,
    /// Launch policy.
    pub policy: &'static str,
    /// The launch rule for a closed gate.
    pub launch_rule: wasp_rtl::policy::LaunchRule,
    /// Priority subset.
    pub subset: &'static str,
    /// Zero-latency main memory.
    pub ideal: bool,
    /// Which miss blocks a warp.
    pub blocked_on: BlockedOn,
}

impl SmallMachine {
    /// The machine configuration: 8x8-pixel tiles (4x4 quads), short
    /// latencies (L2 2 cycles, DRAM 3/6), small caches.
    pub fn config(&self) -> MachineConfig {
        let mut c = if self.l0 {
            MachineConfig::paper()
        } else {
            MachineConfig::paper_width2()
        };
        c.name = "props-small".into();
        c.gpu.tile_size = 8;
        c.gpu.cores = self.cores;
        c.core.max_warps = self.warps;
        c.core.pipeline_width = self.width;
        c.core.input_queue = self.queue;
        c.core.alu_latency = 2;
        c.core.texture_latency = 1;
        c.core.ldst_queue = 2;
        let first = match c.l0.as_mut() {
            Some(l0) => {
                c.l1.mshrs = 2;
                l0
            }
            None => &mut c.l1,
        };
        first.mshrs = self.mshrs;
        first.max_merged = self.max_merged;
        c.l2.hit_latency = 2;
        c.l2.mshrs = 4;
        c.dram.row_hit_latency = 3;
        c.dram.row_miss_latency = 6;
        c.memory.ideal = self.ideal;
        c.scheduler.policy = self.policy.parse().expect("a policy");
        c.scheduler.launch_rule = self.launch_rule;
        c.scheduler.subset = self.subset.parse().expect("a subset");
        c.scheduler.blocked_on = self.blocked_on;
        c.sim.watchdog_cycles = 100_000;
        c
    }
}

/// Shader programs of the domain (block numbers are offsets from 0x100).
pub const PROGRAMS: usize = 5;

/// Quad positions in a tile, in launch order: with Mesh2 the first and
/// third are priority quads, the second regular.
pub const POSITIONS: [(u32, u32); 3] = [(0, 0), (1, 0), (2, 0)];

fn program(p: usize, out: &mut Vec<Instr<'static>>) {
    const B0: &[u64] = &[0x100];
    const B1: &[u64] = &[0x101];
    const B01: &[u64] = &[0x100, 0x101];
    const B2: &[u64] = &[0x102];
    out.clear();
    match p % PROGRAMS {
        0 => out.push(Instr::Alu(1)),
        1 => out.push(Instr::Tex(B0)),
        2 => out.push(Instr::Tex(B1)),
        3 => out.extend([Instr::Tex(B01), Instr::Alu(1)]),
        _ => out.extend([Instr::Alu(2), Instr::Tex(B2)]),
    }
}

/// A trace of 8x8-pixel tiles on a 16x8 frame: `tiles[t]` lists the
/// programs of tile `t`'s quads (at [`POSITIONS`]). Tiles with no quad are
/// left out.
pub fn small_trace(tiles: &[&[usize]]) -> Trace {
    let mut b = Trace::builder(TraceHeader::new("props:small", 16, 8, 8)).expect("header");
    let mut ops = Vec::new();
    for (t, quads) in tiles.iter().enumerate().take(2) {
        if quads.is_empty() {
            continue;
        }
        b.begin_tile(t as u32, 0).expect("tile");
        for (q, &p) in quads.iter().enumerate().take(POSITIONS.len()) {
            program(p, &mut ops);
            let (x, y) = POSITIONS[q];
            b.quad(x, y, &ops).expect("quad");
        }
        b.end_tile().expect("end");
    }
    b.finish().expect("trace")
}

#[cfg(any(kani, feature = "kani-shim"))]
mod proofs {
    use super::*;

    /// Every machine property over one tile of two quads with any
    /// programs of the domain, on a one-core WaSP machine with one L0 MSHR
    /// (threshold 0), either launch rule and two warp slots; the run ends within the liveness
    /// bound, so the unwinding covers it. Twin:
    /// `tests::exhaustive_one_tile_up_to_three_quads`.
    #[kani::proof]
    #[kani::unwind(40)]
    fn proof_machine_two_quads() {
        let a: u8 = kani::any_where(|p: &u8| usize::from(*p) < PROGRAMS);
        let b: u8 = kani::any_where(|p: &u8| usize::from(*p) < PROGRAMS);
        let launch: bool = kani::any();
        let quads = [usize::from(a), usize::from(b)];
        let trace = small_trace(&[&quads]);
        let m = SmallMachine {
            l0: true,
            cores: 1,
            warps: 2,
            width: 2,
            queue: 2,
            mshrs: 1,
            max_merged: 1,
            policy: "wasp:0",
            launch_rule: if launch {
                wasp_rtl::policy::LaunchRule::Launch
            } else {
                wasp_rtl::policy::LaunchRule::Hold
            },
            subset: "mesh2",
            ideal: false,
            blocked_on: BlockedOn::L1Miss,
        };
        assert!(run_checked(&m.config(), &trace).is_ok());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use wasp_rtl::policy::LaunchRule;

    fn launch(m: SmallMachine) -> SmallMachine {
        SmallMachine {
            launch_rule: LaunchRule::Launch,
            ..m
        }
    }

    fn m(
        l0: bool,
        cores: u32,
        warps: u32,
        width: u32,
        mshrs: u32,
        policy: &'static str,
    ) -> SmallMachine {
        SmallMachine {
            l0,
            cores,
            warps,
            width,
            queue: 2,
            mshrs,
            max_merged: 1,
            policy,
            launch_rule: LaunchRule::Hold,
            subset: "mesh2",
            ideal: false,
            blocked_on: BlockedOn::L1Miss,
        }
    }

    /// The machines of the one-tile domain.
    fn machines() -> Vec<SmallMachine> {
        vec![
            m(true, 1, 2, 2, 1, "wasp:0"),
            m(true, 1, 3, 1, 2, "wasp:1"),
            m(false, 1, 1, 1, 1, "fullpriority"),
            m(false, 1, 3, 2, 2, "freemshr:1"),
            m(true, 2, 2, 2, 1, "baseline"),
            SmallMachine {
                queue: 1,
                max_merged: 0,
                subset: "mesh4",
                ..m(true, 1, 3, 2, 2, "wasp:1:2.5")
            },
            SmallMachine {
                ideal: true,
                ..m(false, 1, 2, 2, 1, "wasp:0")
            },
            // The work-conserving launch rule.
            launch(m(true, 1, 2, 2, 1, "wasp:0")),
            launch(m(true, 1, 3, 1, 2, "wasp:1")),
            launch(m(false, 1, 3, 2, 2, "freemshr:1")),
        ]
    }

    /// Every program sequence of `1..=max` quads.
    fn tiles_up_to(max: usize) -> Vec<Vec<usize>> {
        let mut all: Vec<Vec<usize>> = vec![vec![]];
        let mut out = Vec::new();
        for _ in 0..max {
            all = all
                .iter()
                .flat_map(|t| {
                    (0..PROGRAMS).map(move |p| {
                        let mut t = t.clone();
                        t.push(p);
                        t
                    })
                })
                .collect();
            out.extend(all.iter().cloned());
        }
        out
    }

    #[test]
    fn exhaustive_one_tile_up_to_three_quads() {
        let tiles = tiles_up_to(3);
        assert_eq!(tiles.len(), 5 + 25 + 125);
        let (mut runs, mut prio, mut full, mut max_active) = (0, 0, 0, 0);
        // Every machine under every blocking rule: (i) holds whichever miss
        // blocks a warp.
        let all = machines()
            .into_iter()
            .flat_map(|m| BlockedOn::ALL.map(|blocked_on| SmallMachine { blocked_on, ..m }));
        for mach in all {
            let cfg = mach.config();
            cfg.validate().unwrap();
            for t in &tiles {
                let trace = small_trace(&[t]);
                let model = run_checked(&cfg, &trace)
                    .unwrap_or_else(|e| panic!("{e}\nmachine {mach:?}\nprograms {t:?}"));
                runs += 1;
                prio += model.priority_launches;
                full += model.full_cycles;
                max_active = max_active.max(model.max_active);
            }
        }
        // Not vacuous: priority warps launched, MSHR files filled up, cores
        // held several warps at once.
        assert_eq!(runs, 3 * 10 * 155);
        assert!(
            prio > 500 && full > 500 && max_active == 3,
            "{prio} {full} {max_active}"
        );
    }

    #[test]
    fn exhaustive_two_tiles_up_to_two_quads_each() {
        let tiles = tiles_up_to(2);
        let machines = [
            m(true, 1, 2, 2, 1, "wasp:0"),
            m(true, 2, 2, 1, 1, "fullpriority"),
            m(false, 1, 2, 2, 2, "baseline"),
            launch(m(true, 1, 2, 2, 1, "wasp:0")),
        ];
        let mut runs = 0;
        for mach in machines {
            let cfg = mach.config();
            for a in &tiles {
                for b in &tiles {
                    let trace = small_trace(&[a, b]);
                    run_checked(&cfg, &trace)
                        .unwrap_or_else(|e| panic!("{e}\nmachine {mach:?}\nprograms {a:?} {b:?}"));
                    runs += 1;
                }
            }
        }
        assert_eq!(runs, 4 * 30 * 30);
    }

    #[test]
    fn a_broken_model_is_caught() {
        // The checker is not blind: a model that thinks a warp launched
        // under another tile, or with a liveness bound too small, fails.
        let cfg = m(true, 1, 2, 2, 1, "wasp:0").config();
        let trace = small_trace(&[&[1, 3], &[4]]);
        let mut gpu = Gpu::new(&cfg, &trace).unwrap();
        let mut model = MachineModel::new(&trace, 1);
        model.warp_bound = 3;
        let mut err = None;
        while !gpu.done() && err.is_none() {
            gpu.step().unwrap();
            err = machine_cycle(&gpu, &mut model).err();
        }
        let e = err.expect("a 3-cycle bound must fail");
        assert_eq!(e.what(), "(k) a warp did not finish within its bound");

        let mut gpu = Gpu::new(&cfg, &trace).unwrap();
        let mut model = MachineModel::new(&trace, 1);
        let mut err = None;
        while !gpu.done() && err.is_none() {
            gpu.step().unwrap();
            // Forget which tile each warp launched under, as if every warp
            // had launched under tile 7.
            for w in model.warps[0].values_mut() {
                *w = 7;
            }
            err = machine_cycle(&gpu, &mut model).err();
        }
        let e = err.expect("a wrong tile must fail");
        assert_eq!(
            e.what(),
            "(j) a warp of an earlier tile is still in the core"
        );
    }

    #[test]
    fn end_check_catches_overlapping_tiles_and_lost_quads() {
        let trace = small_trace(&[&[0], &[0]]);
        let rec = |tile, launched, finished| WarpRecord {
            tile,
            quad: 0,
            core: 0,
            priority: false,
            mem_latency: None,
            launched,
            finished,
        };
        let mut model = MachineModel::new(&trace, 1);
        model.launches = 2;
        assert!(machine_end(&trace, &[rec(0, 1, 5), rec(1, 5, 9)], &model).is_ok());
        let e = machine_end(&trace, &[rec(0, 1, 5), rec(1, 4, 9)], &model).unwrap_err();
        assert_eq!(
            e.what(),
            "(j) a tile started before the previous one drained"
        );
        let e = machine_end(&trace, &[rec(0, 1, 5)], &model).unwrap_err();
        assert_eq!(e.what(), "(k) not every quad finished exactly once");
    }
}
