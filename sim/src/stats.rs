//! Statistics of a run: JSON (serde), CSV and a readable table.
//!
//! Field names follow the paper's words: `cycles`, `ipc`, per cache level
//! `accesses`, `hits`, `misses`, `secondary_misses`, `stall_cycles`, DRAM
//! requests, the average memory latency per warp (all, priority, regular),
//! the average number of outstanding misses, the priority subset's texture
//! footprint ratio and size ratio, Min_Estimate1, CF, Min_Estimate2 and the
//! energy of the event-energy model.

use crate::config::{
    BlockedOn, ColorFlush, CoreMap, Dispatch, FilterTiming, IssueOrder, MachineConfig, TextureCache,
};
use crate::gpu::{CoreStats, LeadStats, RasterStats, RunCounters, TileRecord, TileTimingStats};
use crate::mem::{CacheStats, MemStats};
use crate::trace::{mean_footprint_ratio_of, Trace};
use serde::{Deserialize, Serialize};
use wasp_rtl::policy::{LaunchRule, PolicySpec};

mod frames;
mod labels;
mod prefetch;
pub use frames::{FrameLevel, FrameRecord};
pub use labels::{DramModelLabel, SubsetLabel};
pub use prefetch::PrefetchReport;

/// One cache level's counters, summed over cores.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
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
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
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

impl DramSummary {
    fn of(cfg: &MachineConfig, mem: &MemStats, cycles: u64) -> Self {
        let d = &mem.dram;
        DramSummary {
            requests: d.requests,
            row_hits: d.row_hits,
            row_misses: d.row_misses,
            avg_latency: d.avg_latency(),
            avg_queue_wait: if d.requests == 0 {
                0.0
            } else {
                d.queue_wait_sum as f64 / d.requests as f64
            },
            max_queue: d.max_queue,
            writes: d.writes,
            row_conflicts: d.row_conflicts,
            activates: d.activates,
            bus_utilization: if cfg.dram.model == crate::mem::DramModel::Banked {
                d.bus_busy_cycles as f64 / (cycles.max(1) * u64::from(cfg.dram.channels)) as f64
            } else {
                0.0
            },
        }
    }
}

/// Average memory latency per warp: the mean over warps of each warp's mean
/// texture-instruction latency (cycles from entering the LDST queue to the
/// last block's arrival).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct LatencyStats {
    /// All warps with at least one texture instruction.
    pub all: f64,
    /// Priority warps.
    pub priority: f64,
    /// Regular warps.
    pub regular: f64,
}

impl LatencyStats {
    fn of(cores: &[CoreStats]) -> Self {
        let lat = |i: usize| -> (f64, u64) {
            (
                cores.iter().map(|c| c.warp_latency_sum[i]).sum(),
                cores.iter().map(|c| c.warps_with_tex[i]).sum(),
            )
        };
        let (rs, rn) = lat(0);
        let (ps, pn) = lat(1);
        LatencyStats {
            all: mean(rs + ps, rn + pn),
            priority: mean(ps, pn),
            regular: mean(rs, rn),
        }
    }
}

/// Blocked episodes: texture instructions whose warp became blocked (the
/// paper's long-latency state) under the run's `blocked_on` rule.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
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

impl BlockedStats {
    fn of(cores: &[CoreStats], tex_instructions: u64) -> Self {
        let ep = |i: usize| total(cores, |c| c.blocked_episodes[i]);
        let cy = |i: usize| total(cores, |c| c.blocked_cycles[i]) as f64;
        BlockedStats {
            episodes: ep(0) + ep(1),
            priority_episodes: ep(1),
            episode_share: mean((ep(0) + ep(1)) as f64, tex_instructions),
            mean_cycles: mean(cy(0) + cy(1), ep(0) + ep(1)),
            priority_mean_cycles: mean(cy(1), ep(1)),
        }
    }
}

/// The priority subset and what it covers.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SubsetStats {
    /// The subset, and whether the policy uses it (written
    /// `mesh4 (unused by the baseline)` when it does not).
    pub subset: SubsetLabel,
    /// Fraction of a full tile's quads the subset selects.
    pub subset_size_ratio: f64,
    /// Mean over tiles of (blocks the subset's warps touch / blocks the tile
    /// touches).
    pub texture_footprint_ratio: f64,
    /// Priority warps launched.
    pub priority_warps: u64,
}

impl SubsetStats {
    fn of(cfg: &MachineConfig, trace: &Trace, frame: usize, cores: &[CoreStats]) -> Self {
        let spec = &cfg.scheduler.subset;
        let side = cfg.quads_per_side();
        let subset = spec.build(side);
        SubsetStats {
            subset: SubsetLabel {
                spec: spec.clone(),
                used: cfg.scheduler.policy != PolicySpec::Baseline,
            },
            subset_size_ratio: subset.size_ratio(side),
            texture_footprint_ratio: mean_footprint_ratio_of(trace.frame_tiles(frame), |x, y| {
                subset.is_priority(x, y)
            }),
            priority_warps: total(cores, |c| c.priority_launches),
        }
    }
}

/// Energy by the event-energy model, in nanojoules.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
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

impl EnergyStats {
    /// The energy of a run of `cycles` on `cores` cores with
    /// `instructions` warp instructions, `tex` of them texture ones.
    fn of(
        cfg: &MachineConfig,
        mem: &MemStats,
        cores: u64,
        instructions: u64,
        tex: u64,
        cycles: u64,
    ) -> Self {
        let e = &cfg.energy;
        let alu_instr = instructions - tex;
        let l0_acc = mem.l0.map(|s| s.accesses).unwrap_or(0);
        let alu_nj = alu_instr as f64 * e.alu_instruction_pj / 1000.0;
        let texture_nj = tex as f64 * e.texture_instruction_pj / 1000.0;
        let l0_nj = l0_acc as f64 * e.l0_access_pj / 1000.0;
        // Prefetch lookups read the L1's tags like any access.
        let l1_nj = (mem.l1.accesses + mem.prefetch.queue.issued) as f64 * e.l1_access_pj / 1000.0;
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
        let static_nj =
            (e.core_static_mw * cores as f64 + e.uncore_static_mw) * 1e-3 * seconds * 1e9;
        let total_nj = alu_nj + texture_nj + l0_nj + l1_nj + l2_nj + dram_nj + static_nj;
        EnergyStats {
            alu_nj,
            texture_nj,
            l0_nj,
            l1_nj,
            l2_nj,
            dram_nj,
            static_nj,
            total_nj,
        }
    }
}

/// Occupancy: warps resident per core per cycle.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
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
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FilterStats {
    /// Filter cycles per bilinear (or nearest) quad-sample.
    pub cycles_bilinear: u32,
    /// Filter cycles per trilinear quad-sample.
    pub cycles_trilinear: u32,
    /// How the filter pass and `texture_latency` add up (`overlap` or
    /// `serial`).
    pub timing: FilterTiming,
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

impl FilterStats {
    fn of(cfg: &MachineConfig, cores: &[CoreStats], cycles: u64) -> Self {
        let tex = total(cores, |c| c.tex_instructions);
        let tri = total(cores, |c| c.tri_tex_instructions);
        let busy = total(cores, |c| c.filter_busy_cycles);
        let wait = total(cores, |c| c.filter_wait_cycles);
        FilterStats {
            cycles_bilinear: cfg.core.filter_cycles_bilinear,
            cycles_trilinear: cfg.core.filter_cycles_trilinear,
            timing: cfg.core.filter_timing,
            trilinear_instructions: tri,
            trilinear_share: mean(tri as f64, tex),
            busy_cycles: busy,
            busy_fraction: mean(busy as f64, cycles * cores.len() as u64),
            wait_cycles: wait,
            avg_wait: mean(wait as f64, tex),
        }
    }
}

/// How the launch policy's gate chose between the two FIFOs, over the
/// launches made while warps waited in both (summed over cores).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
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
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RunStats {
    /// Machine name.
    pub machine: String,
    /// Input FIFO entries per core (`core.input_queue`), for the table's
    /// header; not in the JSON or CSV, whose fields predate it (so read
    /// back from JSON as 0).
    #[serde(skip)]
    pub input_queue: u32,
    /// Workload (from the trace; synthetic workloads say so).
    pub workload: String,
    /// Launch policy.
    pub policy: PolicySpec,
    /// Launch rule for a closed gate (`hold` or `launch`,
    /// `scheduler.launch_rule`).
    pub launch_rule: LaunchRule,
    /// Dispatch mode (`shared-tile` or `per-core-tile`).
    pub dispatch: Dispatch,
    /// Quad-to-core map (shared-tile).
    pub core_map: CoreMap,
    /// Colour-buffer flush.
    pub color_flush: ColorFlush,
    /// Main-memory model and its timing.
    pub dram_model: DramModelLabel,
    /// Zero-latency main memory.
    pub ideal_memory: bool,
    /// Which miss blocks a warp (`scheduler.blocked_on`).
    pub blocked_on: BlockedOn,
    /// The issue order (`core.issue`). Left out of the JSON and the table
    /// under the default, `lrr`, so that their outputs are those of the
    /// model before the option existed; a run that names no issue order
    /// ran `lrr`.
    #[serde(default, skip_serializing_if = "is_default")]
    pub issue: IssueOrder,
    /// What the texture caches hold (`memory.texture_cache`). Left out of
    /// the JSON and the table under the default, `compressed`, so that
    /// their outputs are those of the model before the option existed.
    #[serde(default, skip_serializing_if = "is_default")]
    pub texture_cache: TextureCache,
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
    /// The prefetcher and its requests (absent without one, `prefetch.kind
    /// = "none"`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub prefetch: Option<PrefetchReport>,
    /// Every tile: start, end, fill, drain, peak occupancy, primary misses.
    /// (Of a trace of several frames, the last frame's tiles, their
    /// cycles counted from the run's start.) Study records leave it out
    /// (and read it back empty).
    #[serde(default)]
    pub per_tile: Vec<TileRecord>,
    /// Of a trace of several frames, one record per frame run, in order;
    /// everything else in the report is the last frame's. Empty (and left
    /// out of the JSON) for a one-frame trace.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub frames: Vec<FrameRecord>,
}

/// Whether `x` is its type's default (left out of the JSON).
fn is_default<T: Default + PartialEq>(x: &T) -> bool {
    *x == T::default()
}

/// A counter summed over the cores.
fn total(cores: &[CoreStats], f: impl Fn(&CoreStats) -> u64) -> u64 {
    cores.iter().map(f).sum()
}

fn mean(sum: f64, n: u64) -> f64 {
    if n == 0 {
        0.0
    } else {
        sum / n as f64
    }
}

impl RunStats {
    /// Gather the statistics of a finished run of a one-frame trace (of
    /// its last frame, for several).
    pub fn collect(cfg: &MachineConfig, trace: &Trace, counters: RunCounters) -> Self {
        Self::collect_frame(cfg, trace, trace.frame_count() - 1, counters)
    }

    /// Gather the statistics of frame `frame` of `trace` from its
    /// counters (the workload figures are the frame's own). The
    /// [`frames`](Self::frames) records are left empty.
    pub fn collect_frame(
        cfg: &MachineConfig,
        trace: &Trace,
        frame: usize,
        counters: RunCounters,
    ) -> Self {
        let RunCounters {
            cycles,
            cores,
            mem,
            instruments: inst,
        } = counters;
        let (cores, mem) = (&cores[..], &mem);
        let n = cores.len() as u64;
        let sum = |f: fn(&CoreStats) -> u64| total(cores, f);
        let instructions = sum(|c| c.instructions);
        let tex = sum(|c| c.tex_instructions);
        let ts = trace.frame_stats(frame);
        let sched = &cfg.scheduler;
        RunStats {
            machine: cfg.name.clone(),
            input_queue: cfg.core.input_queue,
            workload: trace.header().workload.clone(),
            policy: sched.policy,
            launch_rule: sched.launch_rule,
            dispatch: cfg.raster.dispatch,
            core_map: cfg.raster.core_map,
            color_flush: cfg.raster.color_flush,
            dram_model: DramModelLabel::of(&cfg.dram),
            ideal_memory: cfg.memory.ideal,
            blocked_on: sched.blocked_on,
            issue: cfg.core.issue,
            texture_cache: cfg.memory.texture_cache,
            cycles,
            ipc: instructions as f64 / cycles.max(1) as f64,
            warps: sum(|c| c.warps_finished),
            instructions,
            tex_instructions: tex,
            filter: FilterStats::of(cfg, cores, cycles),
            tiles: inst.tiles,
            l0: mem.l0.as_ref().map(|s| LevelStats::of(s, n, cycles)),
            l1: LevelStats::of(&mem.l1, n, cycles),
            l2: LevelStats::of(&mem.l2, 1, cycles),
            dram: DramSummary::of(cfg, mem, cycles),
            memory_latency: LatencyStats::of(cores),
            avg_warps_per_core: sum(|c| c.occupancy_sum) as f64 / (cycles.max(1) * n.max(1)) as f64,
            occupancy: OccupancyStats::of(cores, cfg.core.max_warps),
            raster: inst.raster,
            priority_lead: inst.priority_lead,
            tile_timing: inst.tile_timing,
            held_cycles: sum(|c| c.held_cycles),
            held_cycles_per_core: cores.iter().map(|c| c.held_cycles).collect(),
            gate: GateStats::new(sum(|c| c.both_waiting), sum(|c| c.regular_first)),
            measured_cf_mean: {
                let samples = sum(|c| c.cf_samples);
                (samples > 0).then(|| sum(|c| c.cf_quarters_sum) as f64 / 4.0 / samples as f64)
            },
            blocked: BlockedStats::of(cores, tex),
            subset: SubsetStats::of(cfg, trace, frame, cores),
            mem_instr_ratio: ts.mem_instr_ratio,
            min_estimate1: ts.min_estimate1,
            cf: ts.cf,
            min_estimate2: ts.min_estimate2,
            block_reuse: ts.reuse,
            energy: EnergyStats::of(cfg, mem, n, instructions, tex, cycles),
            prefetch: PrefetchReport::of(cfg, &mem.prefetch),
            per_tile: inst.per_tile,
            frames: Vec::new(),
        }
    }

    /// The statistics as pretty JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).expect("stats serialize") + "\n"
    }
}

mod csv;
mod table;
pub use csv::{csv_records, csv_table, csv_text, flatten};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mem::{DramModel, PrefetchKind};
    use crate::run::{simulate, RunOptions};

    /// The statistics of the tiny trace on `cfg`.
    fn tiny(mut cfg: MachineConfig) -> RunStats {
        let p = concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/traces/tiny.trace");
        let t = Trace::read(p).unwrap();
        cfg.gpu.tile_size = t.header().tile;
        simulate(&cfg, &t, &RunOptions::default(), &mut |_, _| {}).unwrap()
    }

    #[test]
    fn statistics_read_back_from_their_json() {
        let shipped = tiny(MachineConfig::paper());
        let mut cfg = MachineConfig::paper();
        cfg.scheduler.policy = PolicySpec::WaspMeasured { threshold: 0 };
        cfg.scheduler.launch_rule = LaunchRule::Launch;
        cfg.scheduler.blocked_on = BlockedOn::FirstLevel;
        cfg.core.issue = IssueOrder::Gto;
        cfg.core.filter_timing = FilterTiming::Serial;
        cfg.prefetch.kind = PrefetchKind::Raster;
        cfg.dram.model = DramModel::Fixed;
        cfg.raster.core_map = CoreMap::RowMajor { block: 2 };
        let mut other = tiny(cfg);
        // Fields the tiny trace cannot set: several frames, decoded lines.
        other.frames = vec![
            FrameRecord::of(0, 0, &other),
            FrameRecord::of(1, other.cycles, &other),
        ];
        other.texture_cache = TextureCache::Decompressed;
        let mut baseline = MachineConfig::paper();
        baseline.scheduler.policy = PolicySpec::Baseline;
        baseline.raster.dispatch = Dispatch::PerCoreTile;
        baseline.raster.color_flush = ColorFlush::Blocking;
        baseline.memory.ideal = true;
        for s in [shipped, other, tiny(baseline)] {
            let text = s.to_json();
            let back: RunStats = serde_json::from_str(&text).unwrap();
            // All but the input queue, which the JSON leaves out.
            assert_eq!(
                back,
                RunStats {
                    input_queue: 0,
                    ..s.clone()
                }
            );
            assert_eq!(back.to_json(), text);
        }
    }

    #[test]
    fn descriptive_fields_are_written_as_their_names() {
        let mut s = tiny(MachineConfig::paper());
        s.policy = PolicySpec::Baseline;
        s.subset.subset.used = false;
        s.issue = IssueOrder::Gto;
        let v = serde_json::to_value(&s).unwrap();
        assert_eq!(v["policy"], "baseline");
        assert_eq!(v["launch_rule"], "hold");
        assert_eq!(v["dispatch"], "shared-tile");
        assert_eq!(v["core_map"], "latin:8");
        assert_eq!(v["color_flush"], "overlap");
        assert_eq!(v["blocked_on"], "l1-miss");
        assert_eq!(v["issue"], "gto");
        assert_eq!(v["filter"]["timing"], "overlap");
        assert_eq!(v["subset"]["subset"], "mesh4 (unused by the baseline)");
        assert!(v["dram_model"].as_str().unwrap().starts_with("banked: "));
        // The defaults of options added later are left out.
        assert!(v.get("texture_cache").is_none());
        s.issue = IssueOrder::Lrr;
        assert!(serde_json::to_value(&s).unwrap().get("issue").is_none());
        // A name the model does not know is an error naming it.
        let text = s.to_json().replace("\"l1-miss\"", "\"l3-miss\"");
        let e = serde_json::from_str::<RunStats>(&text).unwrap_err();
        assert!(e.to_string().contains("l3-miss"), "{e}");
    }
}
