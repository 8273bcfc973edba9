//! Statistics of a run: JSON (serde), CSV and a readable table.
//!
//! Field names follow the paper's words: `cycles`, `ipc`, per cache level
//! `accesses`, `hits`, `misses`, `secondary_misses`, `stall_cycles`, DRAM
//! requests, the average memory latency per warp (all, priority, regular),
//! the average number of outstanding misses, the priority subset's texture
//! footprint ratio and size ratio, Min_Estimate1, CF, Min_Estimate2 and the
//! energy of the event-energy model.

use crate::config::MachineConfig;
use crate::gpu::{CoreStats, LeadStats, RasterStats, RunCounters, TileRecord, TileTimingStats};
use crate::mem::CacheStats;
use crate::trace::{mean_footprint_ratio, Trace};
use serde::Serialize;
use std::fmt::Write as _;

/// One cache level's counters, summed over cores.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LevelStats {
    /// Accesses accepted.
    pub accesses: u64,
    /// Hits.
    pub hits: u64,
    /// Primary misses.
    pub misses: u64,
    /// Secondary misses (merged into an MSHR entry).
    pub secondary_misses: u64,
    /// Cycles in which the level refused an access because every MSHR was
    /// occupied (summed over the level's instances).
    pub stall_cycles: u64,
    /// Accesses refused because one MSHR entry could merge no more.
    pub merge_stalls: u64,
    /// Stall cycles / (cycles x instances): the fraction of time stalled.
    pub stall_fraction: f64,
    /// Average outstanding misses (MSHR entries awaiting a reply) per
    /// instance per cycle.
    pub avg_outstanding_misses: f64,
}

impl LevelStats {
    fn of(s: &CacheStats, instances: u64, cycles: u64) -> Self {
        let denom = (instances * cycles).max(1) as f64;
        Self {
            accesses: s.accesses,
            hits: s.hits,
            misses: s.misses,
            secondary_misses: s.secondary_misses,
            stall_cycles: s.stall_cycles,
            merge_stalls: s.merge_stalls,
            stall_fraction: s.stall_cycles as f64 / denom,
            avg_outstanding_misses: s.mshr_outstanding_sum as f64 / denom,
        }
    }
}

/// Main-memory counters.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DramSummary {
    /// Requests served.
    pub requests: u64,
    /// Row hits.
    pub row_hits: u64,
    /// Row misses.
    pub row_misses: u64,
    /// Average request latency in cycles (queueing included).
    pub avg_latency: f64,
    /// Average cycles a read waited in the queue before its first command
    /// (fixed model: before acceptance).
    pub avg_queue_wait: f64,
    /// Most requests queued at once.
    pub max_queue: u64,
    /// Line writes (the colour-buffer flush).
    pub writes: u64,
    /// Banked model: row misses that had to close another row first.
    pub row_conflicts: u64,
    /// Banked model: ACTIVATE commands.
    pub activates: u64,
    /// Banked model: share of the data buses' cycles carrying data (reads
    /// and writes), over the run's cycles and all channels; 0 in the fixed
    /// model.
    pub bus_utilization: f64,
}

/// Average memory latency per warp: the mean over warps of each warp's mean
/// texture-instruction latency (cycles from entering the LDST queue to the
/// last block's arrival).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct LatencyStats {
    /// All warps with at least one texture instruction.
    pub all: f64,
    /// Priority warps.
    pub priority: f64,
    /// Regular warps.
    pub regular: f64,
}

/// Blocked episodes: texture instructions whose warp became blocked (the
/// paper's long-latency state) under the run's `blocked_on` rule.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BlockedStats {
    /// Episodes, all warps.
    pub episodes: u64,
    /// Episodes of priority warps.
    pub priority_episodes: u64,
    /// Texture instructions whose warp became blocked, as a share of all.
    pub episode_share: f64,
    /// Mean cycles from the cycle a warp became blocked to the cycle its
    /// last block arrived, over all episodes.
    pub mean_cycles: f64,
    /// The same over the priority warps' episodes.
    pub priority_mean_cycles: f64,
}

/// The priority subset and what it covers.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SubsetStats {
    /// Subset name.
    pub subset: String,
    /// Fraction of a full tile's quads the subset selects.
    pub subset_size_ratio: f64,
    /// Mean over tiles of (blocks the subset's warps touch / blocks the tile
    /// touches).
    pub texture_footprint_ratio: f64,
    /// Priority warps launched.
    pub priority_warps: u64,
}

/// Energy by the event-energy model, in nanojoules.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EnergyStats {
    /// ALU instructions.
    pub alu_nj: f64,
    /// Texture unit.
    pub texture_nj: f64,
    /// L0 accesses.
    pub l0_nj: f64,
    /// L1 accesses.
    pub l1_nj: f64,
    /// L2 accesses.
    pub l2_nj: f64,
    /// DRAM accesses.
    pub dram_nj: f64,
    /// Static energy over the run's time.
    pub static_nj: f64,
    /// Everything.
    pub total_nj: f64,
}

/// Occupancy: warps resident per core per cycle.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct OccupancyStats {
    /// Warp slots per core.
    pub max_warps: u32,
    /// Mean resident warps per core per cycle.
    pub mean: f64,
    /// The mean of each core.
    pub per_core_mean: Vec<f64>,
    /// Share of core-cycles with fewer than 25% of the slots occupied.
    pub below_quarter: f64,
    /// Share of core-cycles with fewer than 50% of the slots occupied.
    pub below_half: f64,
    /// Core-cycles by resident warps: entry `n` counts the core-cycles with
    /// `n` warps resident (summed over cores).
    pub histogram: Vec<u64>,
    /// The same histogram for each core.
    pub per_core_histogram: Vec<Vec<u64>>,
}

impl OccupancyStats {
    fn of(cores: &[CoreStats], max_warps: u32) -> Self {
        let mut histogram = vec![0u64; max_warps as usize + 1];
        for c in cores {
            for (h, x) in histogram.iter_mut().zip(&c.occupancy_hist) {
                *h += x;
            }
        }
        let total: u64 = histogram.iter().sum();
        let weighted: u64 = histogram
            .iter()
            .enumerate()
            .map(|(n, c)| n as u64 * c)
            .sum();
        let below = |frac_num: u32, frac_den: u32| {
            // n < max * num / den  <=>  n * den < max * num.
            let k: u64 = histogram
                .iter()
                .enumerate()
                .filter(|(n, _)| {
                    (*n as u64) * u64::from(frac_den) < u64::from(max_warps * frac_num)
                })
                .map(|(_, c)| c)
                .sum();
            mean(k as f64, total)
        };
        OccupancyStats {
            max_warps,
            mean: mean(weighted as f64, total),
            per_core_mean: cores
                .iter()
                .map(|c| {
                    let t: u64 = c.occupancy_hist.iter().sum();
                    let w: u64 = c
                        .occupancy_hist
                        .iter()
                        .enumerate()
                        .map(|(n, x)| n as u64 * x)
                        .sum();
                    mean(w as f64, t)
                })
                .collect(),
            below_quarter: below(1, 4),
            below_half: below(1, 2),
            histogram,
            per_core_histogram: cores.iter().map(|c| c.occupancy_hist.clone()).collect(),
        }
    }
}

/// The texture filter unit: its configuration (`core.filter_*`) and what
/// it did, summed over the cores.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct FilterStats {
    /// Filter cycles per bilinear (or nearest) quad-sample.
    pub cycles_bilinear: u32,
    /// Filter cycles per trilinear quad-sample.
    pub cycles_trilinear: u32,
    /// How the filter pass and `texture_latency` add up (`overlap` or
    /// `serial`).
    pub timing: String,
    /// Trilinear texture instructions run.
    pub trilinear_instructions: u64,
    /// Trilinear / all texture instructions.
    pub trilinear_share: f64,
    /// Cycles the filter units were busy, summed over cores.
    pub busy_cycles: u64,
    /// busy_cycles / (cycles x cores).
    pub busy_fraction: f64,
    /// Cycles texture data waited for a busy filter unit, summed over
    /// texture instructions.
    pub wait_cycles: u64,
    /// wait_cycles / texture instructions.
    pub avg_wait: f64,
}

/// How the launch policy's gate chose between the two FIFOs, over the
/// launches made while warps waited in both (summed over cores).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GateStats {
    /// Launches with warps waiting in the priority and the regular FIFO.
    pub both_waiting: u64,
    /// Of those, launches of the regular warp (the gate closed).
    pub regular_first: u64,
    /// regular_first / both_waiting (0 with none).
    pub closed_share: f64,
}

impl GateStats {
    /// The statistics of `both` such launches, `regular` of them regular.
    pub fn new(both: u64, regular: u64) -> Self {
        GateStats {
            both_waiting: both,
            regular_first: regular,
            closed_share: if both == 0 {
                0.0
            } else {
                regular as f64 / both as f64
            },
        }
    }
}

/// Everything a run reports.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RunStats {
    /// Machine name.
    pub machine: String,
    /// Workload (from the trace; synthetic workloads say so).
    pub workload: String,
    /// Launch policy.
    pub policy: String,
    /// Launch rule for a closed gate (`hold` or `launch`,
    /// `scheduler.launch_rule`).
    pub launch_rule: String,
    /// Dispatch mode (`shared-tile` or `per-core-tile`).
    pub dispatch: String,
    /// Quad-to-core map (shared-tile).
    pub core_map: String,
    /// Colour-buffer flush.
    pub color_flush: String,
    /// Main-memory model ([`DramConfig::describe`](crate::mem::DramConfig::describe)).
    #[serde(default)]
    pub dram_model: String,
    /// Zero-latency main memory.
    pub ideal_memory: bool,
    /// Which miss blocks a warp (`scheduler.blocked_on`).
    pub blocked_on: String,
    /// GPU cycles until every tile is rendered and memory is idle.
    pub cycles: u64,
    /// Warp instructions per GPU cycle.
    pub ipc: f64,
    /// Warps (quads) run.
    pub warps: u64,
    /// Warp instructions.
    pub instructions: u64,
    /// Texture instructions.
    pub tex_instructions: u64,
    /// The texture filter unit.
    pub filter: FilterStats,
    /// Tiles rendered.
    pub tiles: u64,
    /// Per-core L0 (absent without L0).
    pub l0: Option<LevelStats>,
    /// Per-core L1.
    pub l1: LevelStats,
    /// Shared L2.
    pub l2: LevelStats,
    /// Main memory.
    pub dram: DramSummary,
    /// Average memory latency per warp.
    pub memory_latency: LatencyStats,
    /// Average warps in a core per cycle.
    pub avg_warps_per_core: f64,
    /// Occupancy in detail.
    pub occupancy: OccupancyStats,
    /// The raster pipeline.
    pub raster: RasterStats,
    /// The lead of priority warps over the quads rasterized before them.
    pub priority_lead: LeadStats,
    /// Fill, drain and misses per tile, as means.
    pub tile_timing: TileTimingStats,
    /// Hold idle core-cycles, summed over cores: cycles in which a core
    /// launched nothing although a priority warp waited and it had a free
    /// warp slot (the launch rule `hold` held it; 0 under `launch`).
    pub held_cycles: u64,
    /// The same per core.
    pub held_cycles_per_core: Vec<u64>,
    /// How the policy's gate chose when warps waited in both FIFOs.
    pub gate: GateStats,
    /// `wasp-m`: the mean over cores and cycles of the CF meter's register
    /// (the measured CF the datapath used); absent for other policies.
    pub measured_cf_mean: Option<f64>,
    /// Blocked episodes and their length.
    pub blocked: BlockedStats,
    /// The priority subset.
    pub subset: SubsetStats,
    /// Memory-instruction ratio of the workload.
    pub mem_instr_ratio: f64,
    /// Min_Estimate1: unique blocks in tile / warps in tile.
    pub min_estimate1: f64,
    /// CF measured: distinct blocks per warp.
    pub cf: f64,
    /// Min_Estimate2: Min_Estimate1 / CF.
    pub min_estimate2: f64,
    /// Memory-block reuse in tile.
    pub block_reuse: f64,
    /// Energy.
    pub energy: EnergyStats,
    /// Every tile: start, end, fill, drain, peak occupancy, primary misses.
    pub per_tile: Vec<TileRecord>,
}

fn mean(sum: f64, n: u64) -> f64 {
    if n == 0 {
        0.0
    } else {
        sum / n as f64
    }
}

impl RunStats {
    /// Gather the statistics of a finished run.
    pub fn collect(cfg: &MachineConfig, trace: &Trace, counters: RunCounters) -> Self {
        let RunCounters {
            cycles,
            cores,
            mem,
            instruments: inst,
        } = counters;
        let (cores, mem) = (&cores[..], &mem);
        let n = cores.len() as u64;
        let sum = |f: &dyn Fn(&CoreStats) -> u64| cores.iter().map(f).sum::<u64>();
        let instructions = sum(&|c| c.instructions);
        let tex = sum(&|c| c.tex_instructions);
        let tri = sum(&|c| c.tri_tex_instructions);
        let filter_busy = sum(&|c| c.filter_busy_cycles);
        let filter_wait = sum(&|c| c.filter_wait_cycles);
        let lat = |i: usize| -> (f64, u64) {
            (
                cores.iter().map(|c| c.warp_latency_sum[i]).sum(),
                cores.iter().map(|c| c.warps_with_tex[i]).sum(),
            )
        };
        let (rs, rn) = lat(0);
        let (ps, pn) = lat(1);
        let ts = trace.stats();
        let subset_spec = &cfg.scheduler.subset;
        let side = cfg.quads_per_side();
        let subset = subset_spec.build(side);
        let uses_priority = cfg.scheduler.policy != wasp_rtl::policy::PolicySpec::Baseline;
        let footprint = mean_footprint_ratio(trace, |x, y| subset.is_priority(x, y));
        let e = &cfg.energy;
        let alu_instr = instructions - tex;
        let l0_acc = mem.l0.map(|s| s.accesses).unwrap_or(0);
        let alu_nj = alu_instr as f64 * e.alu_instruction_pj / 1000.0;
        let texture_nj = tex as f64 * e.texture_instruction_pj / 1000.0;
        let l0_nj = l0_acc as f64 * e.l0_access_pj / 1000.0;
        let l1_nj = mem.l1.accesses as f64 * e.l1_access_pj / 1000.0;
        let l2_nj = mem.l2.accesses as f64 * e.l2_access_pj / 1000.0;
        // Writes (the colour-buffer flush) cost like reads: a row hit's
        // transfer, plus activation for those that opened their row.
        let dram_hits = mem.dram.row_hits + (mem.dram.writes - mem.dram.write_row_misses);
        let dram_misses = mem.dram.row_misses + mem.dram.write_row_misses;
        let dram_nj = if cfg.memory.ideal {
            0.0
        } else {
            (dram_hits as f64 * e.dram_row_hit_pj + dram_misses as f64 * e.dram_row_miss_pj)
                / 1000.0
        };
        // mW x seconds = mJ; cycles / (MHz x 1e6) seconds; in nJ: x 1e6.
        let seconds = cycles as f64 / (cfg.gpu.frequency_mhz as f64 * 1e6);
        let static_nj = (e.core_static_mw * n as f64 + e.uncore_static_mw) * 1e-3 * seconds * 1e9;
        let total_nj = alu_nj + texture_nj + l0_nj + l1_nj + l2_nj + dram_nj + static_nj;
        RunStats {
            machine: cfg.name.clone(),
            workload: trace.header().workload.clone(),
            policy: cfg.scheduler.policy.to_string(),
            launch_rule: cfg.scheduler.launch_rule.to_string(),
            dispatch: cfg.raster.dispatch.to_string(),
            core_map: cfg.raster.core_map.to_string(),
            color_flush: cfg.raster.color_flush.to_string(),
            dram_model: cfg.dram.describe(),
            ideal_memory: cfg.memory.ideal,
            blocked_on: cfg.scheduler.blocked_on.to_string(),
            cycles,
            ipc: instructions as f64 / cycles.max(1) as f64,
            warps: sum(&|c| c.warps_finished),
            instructions,
            tex_instructions: tex,
            filter: FilterStats {
                cycles_bilinear: cfg.core.filter_cycles_bilinear,
                cycles_trilinear: cfg.core.filter_cycles_trilinear,
                timing: cfg.core.filter_timing.to_string(),
                trilinear_instructions: tri,
                trilinear_share: mean(tri as f64, tex),
                busy_cycles: filter_busy,
                busy_fraction: mean(filter_busy as f64, cycles * n),
                wait_cycles: filter_wait,
                avg_wait: mean(filter_wait as f64, tex),
            },
            tiles: inst.tiles,
            l0: mem.l0.as_ref().map(|s| LevelStats::of(s, n, cycles)),
            l1: LevelStats::of(&mem.l1, n, cycles),
            l2: LevelStats::of(&mem.l2, 1, cycles),
            dram: DramSummary {
                requests: mem.dram.requests,
                row_hits: mem.dram.row_hits,
                row_misses: mem.dram.row_misses,
                avg_latency: mem.dram.avg_latency(),
                avg_queue_wait: if mem.dram.requests == 0 {
                    0.0
                } else {
                    mem.dram.queue_wait_sum as f64 / mem.dram.requests as f64
                },
                max_queue: mem.dram.max_queue,
                writes: mem.dram.writes,
                row_conflicts: mem.dram.row_conflicts,
                activates: mem.dram.activates,
                bus_utilization: if cfg.dram.model == crate::mem::DramModel::Banked {
                    mem.dram.bus_busy_cycles as f64
                        / (cycles.max(1) * u64::from(cfg.dram.channels)) as f64
                } else {
                    0.0
                },
            },
            memory_latency: LatencyStats {
                all: mean(rs + ps, rn + pn),
                priority: mean(ps, pn),
                regular: mean(rs, rn),
            },
            avg_warps_per_core: sum(&|c| c.occupancy_sum) as f64
                / (cycles.max(1) * n.max(1)) as f64,
            occupancy: OccupancyStats::of(cores, cfg.core.max_warps),
            raster: inst.raster,
            priority_lead: inst.priority_lead,
            tile_timing: inst.tile_timing,
            held_cycles: sum(&|c| c.held_cycles),
            held_cycles_per_core: cores.iter().map(|c| c.held_cycles).collect(),
            gate: GateStats::new(sum(&|c| c.both_waiting), sum(&|c| c.regular_first)),
            measured_cf_mean: {
                let n = sum(&|c| c.cf_samples);
                (n > 0).then(|| sum(&|c| c.cf_quarters_sum) as f64 / 4.0 / n as f64)
            },
            blocked: {
                let ep = |i: usize| sum(&|c| c.blocked_episodes[i]);
                let cy = |i: usize| sum(&|c| c.blocked_cycles[i]) as f64;
                BlockedStats {
                    episodes: ep(0) + ep(1),
                    priority_episodes: ep(1),
                    episode_share: mean((ep(0) + ep(1)) as f64, tex),
                    mean_cycles: mean(cy(0) + cy(1), ep(0) + ep(1)),
                    priority_mean_cycles: mean(cy(1), ep(1)),
                }
            },
            subset: SubsetStats {
                subset: if uses_priority {
                    subset_spec.to_string()
                } else {
                    format!("{subset_spec} (unused by the baseline)")
                },
                subset_size_ratio: subset.size_ratio(side),
                texture_footprint_ratio: footprint,
                priority_warps: sum(&|c| c.priority_launches),
            },
            mem_instr_ratio: ts.mem_instr_ratio,
            min_estimate1: ts.min_estimate1,
            cf: ts.cf,
            min_estimate2: ts.min_estimate2,
            block_reuse: ts.reuse,
            energy: EnergyStats {
                alu_nj,
                texture_nj,
                l0_nj,
                l1_nj,
                l2_nj,
                dram_nj,
                static_nj,
                total_nj,
            },
            per_tile: inst.per_tile,
        }
    }

    /// The statistics as pretty JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("stats serialize") + "\n"
    }

    /// Flat `key,value` CSV rows (nested names joined with `.`; a list of
    /// numbers, such as a histogram, is one field of values joined by `;`,
    /// a list of records or lists is numbered:
    /// `priority_lead.histogram.3.count`, `occupancy.per_core_histogram.2`).
    /// The per-tile records are left out: they are in the JSON.
    pub fn to_csv_rows(&self) -> Vec<(String, String)> {
        let mut v = serde_json::to_value(self).expect("stats serialize");
        if let Some(m) = v.as_object_mut() {
            m.remove("per_tile");
        }
        let mut rows = Vec::new();
        flatten("", &v, &mut rows);
        rows
    }

    /// CSV with a header line and one line of values (several runs can be
    /// joined under one header with [`csv_table`]).
    pub fn to_csv(&self) -> String {
        csv_table(std::slice::from_ref(self))
    }

    /// A readable table.
    pub fn to_table(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "machine {}  |  workload {}", self.machine, self.workload);
        let _ = writeln!(
            s,
            "policy {}  launch rule {}  subset {}  ideal memory {}",
            self.policy, self.launch_rule, self.subset.subset, self.ideal_memory
        );
        let _ = writeln!(
            s,
            "dispatch {}  core map {}  colour flush {}  dram {}",
            self.dispatch, self.core_map, self.color_flush, self.dram_model
        );
        let _ = writeln!(
            s,
            "cycles {}  ipc {:.3}  warps {}  instructions {} ({} texture)  tiles {}",
            self.cycles, self.ipc, self.warps, self.instructions, self.tex_instructions, self.tiles
        );
        let f = &self.filter;
        let _ = writeln!(
            s,
            "filter {}/{} cycles ({})  trilinear {} ({:.1}%)  busy {:.2}%  wait {:.2} cycles/instr",
            f.cycles_bilinear,
            f.cycles_trilinear,
            f.timing,
            f.trilinear_instructions,
            100.0 * f.trilinear_share,
            100.0 * f.busy_fraction,
            f.avg_wait
        );
        let _ = writeln!(
            s,
            "{:<6}{:>12}{:>12}{:>10}{:>12}{:>10}{:>9}{:>13}",
            "level", "accesses", "hits", "misses", "secondary", "stalls", "stall%", "outstanding"
        );
        let mut level = |name: &str, l: &LevelStats| {
            let _ = writeln!(
                s,
                "{:<6}{:>12}{:>12}{:>10}{:>12}{:>10}{:>8.2}%{:>13.2}",
                name,
                l.accesses,
                l.hits,
                l.misses,
                l.secondary_misses,
                l.stall_cycles,
                100.0 * l.stall_fraction,
                l.avg_outstanding_misses
            );
        };
        if let Some(l0) = &self.l0 {
            level("l0", l0);
        }
        level("l1", &self.l1);
        level("l2", &self.l2);
        let _ = writeln!(
            s,
            "dram requests {} (row hits {}, row misses {}), avg latency {:.1} cycles",
            self.dram.requests, self.dram.row_hits, self.dram.row_misses, self.dram.avg_latency
        );
        let _ = writeln!(
            s,
            "memory latency per warp: all {:.1}, priority {:.1}, regular {:.1} cycles",
            self.memory_latency.all, self.memory_latency.priority, self.memory_latency.regular
        );
        let _ = writeln!(
            s,
            "warps per core {:.1} of {} (below 25%: {:.1}% of core-cycles, below 50%: {:.1}%); priority warps {}",
            self.avg_warps_per_core,
            self.occupancy.max_warps,
            100.0 * self.occupancy.below_quarter,
            100.0 * self.occupancy.below_half,
            self.subset.priority_warps,
        );
        let per_core: Vec<String> = self
            .held_cycles_per_core
            .iter()
            .map(u64::to_string)
            .collect();
        let _ = writeln!(
            s,
            "hold idle core-cycles {} (per core {}): a free slot, a priority warp waiting, nothing launched",
            self.held_cycles,
            per_core.join(" ")
        );
        let _ = writeln!(
            s,
            "gate: {} launches with both FIFOs waiting, {} of them regular ({:.1}%: the priority warp waited)",
            self.gate.both_waiting,
            self.gate.regular_first,
            100.0 * self.gate.closed_share
        );
        let b = &self.blocked;
        let _ = writeln!(
            s,
            "blocked on {}: {} episodes ({:.1}% of texture instructions; {} of priority warps), mean {:.1} cycles (priority {:.1})",
            self.blocked_on,
            b.episodes,
            100.0 * b.episode_share,
            b.priority_episodes,
            b.mean_cycles,
            b.priority_mean_cycles
        );
        let r = &self.raster;
        let _ = writeln!(
            s,
            "raster: {} quads ({} rejected by Early-Z), back-pressure {} cycles, barrier wait {} cycles, {} colour lines flushed",
            r.quads_rasterized, r.quads_rejected, r.backpressure_cycles, r.barrier_cycles, r.flush_lines
        );
        let t = &self.tile_timing;
        let _ = writeln!(
            s,
            "tiles: {:.0} cycles each on average, fill {:.0} ({:.1}%), drain {:.0} ({:.1}%), {:.0} primary misses",
            t.mean_cycles,
            t.mean_fill,
            100.0 * t.fill_share,
            t.mean_drain,
            100.0 * t.drain_share,
            t.mean_primary_misses
        );
        let l = &self.priority_lead;
        if l.priority_warps > 0 {
            let _ = writeln!(
                s,
                "priority lead: mean {:+.1} positions, {:.1}% ahead, {:.1}% after a regular warp of their subtile",
                l.mean,
                100.0 * l.ahead_share,
                100.0 * l.after_subtile_regular_share
            );
        }
        let _ = writeln!(
            s,
            "subset size ratio {:.4}, texture footprint ratio {:.3}",
            self.subset.subset_size_ratio, self.subset.texture_footprint_ratio
        );
        let _ = writeln!(
            s,
            "workload: mem-instr ratio {:.3}, block reuse {:.1}, CF {:.2}, Min_Estimate1 {:.3}, Min_Estimate2 {:.3}",
            self.mem_instr_ratio, self.block_reuse, self.cf, self.min_estimate1, self.min_estimate2
        );
        let e = &self.energy;
        let _ = writeln!(
            s,
            "energy {:.1} uJ (alu {:.1}, texture {:.1}, l0 {:.1}, l1 {:.1}, l2 {:.1}, dram {:.1}, static {:.1})",
            e.total_nj / 1000.0,
            e.alu_nj / 1000.0,
            e.texture_nj / 1000.0,
            e.l0_nj / 1000.0,
            e.l1_nj / 1000.0,
            e.l2_nj / 1000.0,
            e.dram_nj / 1000.0,
            e.static_nj / 1000.0
        );
        s
    }
}

/// Flatten a JSON value into `key,value` CSV fields under `prefix`: nested
/// names joined with `.`, a list of plain values one field joined by `;`, a
/// list of records or lists numbered (the rows of [`RunStats::to_csv_rows`]).
pub fn flatten(prefix: &str, v: &serde_json::Value, out: &mut Vec<(String, String)>) {
    match v {
        serde_json::Value::Object(m) => {
            for (k, x) in m {
                let key = if prefix.is_empty() {
                    k.clone()
                } else {
                    format!("{prefix}.{k}")
                };
                flatten(&key, x, out);
            }
        }
        serde_json::Value::Null => out.push((prefix.to_string(), String::new())),
        serde_json::Value::String(s) => out.push((prefix.to_string(), csv_field(s))),
        serde_json::Value::Array(items)
            if items.iter().all(|x| !x.is_object() && !x.is_array()) =>
        {
            let joined: Vec<String> = items.iter().map(|x| x.to_string()).collect();
            out.push((prefix.to_string(), csv_field(&joined.join(";"))));
        }
        serde_json::Value::Array(items) => {
            for (i, x) in items.iter().enumerate() {
                flatten(&format!("{prefix}.{i}"), x, out);
            }
        }
        other => out.push((prefix.to_string(), other.to_string())),
    }
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// Several runs as one CSV table (header from the first run's fields).
pub fn csv_table(runs: &[RunStats]) -> String {
    let mut s = String::new();
    let Some(first) = runs.first() else {
        return s;
    };
    let header: Vec<String> = first.to_csv_rows().into_iter().map(|(k, _)| k).collect();
    s.push_str(&header.join(","));
    s.push('\n');
    for r in runs {
        let rows = r.to_csv_rows();
        let vals: Vec<String> = header
            .iter()
            .map(|k| {
                rows.iter()
                    .find(|(rk, _)| rk == k)
                    .map(|(_, v)| v.clone())
                    .unwrap_or_default()
            })
            .collect();
        s.push_str(&vals.join(","));
        s.push('\n');
    }
    s
}
