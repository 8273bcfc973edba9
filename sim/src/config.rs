//! The machine configuration: one TOML file describes the whole GPU.
//!
//! `configs/paper.toml` (embedded as [`MachineConfig::paper`]) holds the
//! paper's Table II with its best baseline (pipeline width 4, 64 warps, L0
//! present); `configs/paper-width2.toml` the width-2 machine (no L0, the
//! scheduler watches the L1's MSHRs). Every field is documented in those
//! files. Unknown keys are errors, and [`MachineConfig::validate`] refuses
//! every value the model or the scheduler's registers cannot hold, naming
//! the field and the limit.

pub use crate::gpu::IssueOrder;
use crate::mem::config::check_range;
use crate::mem::{BlockedOn, CacheConfig, DramConfig, MemConfig, PrefetchConfig};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::path::Path;
use wasp_rtl::free_mshr::FREE_MSHR_BITS;
use wasp_rtl::nonblocked::NONBLOCKED_BITS;
use wasp_rtl::policy::{LaunchRule, PolicySpec};
use wasp_rtl::subset::SubsetSpec;

/// The paper's machine, as shipped in `configs/paper.toml`.
pub const PAPER_TOML: &str = include_str!("../../configs/paper.toml");
/// The width-2 machine, as shipped in `configs/paper-width2.toml`.
pub const PAPER_WIDTH2_TOML: &str = include_str!("../../configs/paper-width2.toml");

/// Global GPU parameters.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GpuConfig {
    /// Shader cores, each with its own L0/L1 texture caches.
    pub cores: u32,
    /// Clock frequency in MHz (for energy and time conversions).
    pub frequency_mhz: u32,
    /// Tile side in pixels; quads per tile side = tile_size / 2.
    pub tile_size: u32,
}

/// One shader core.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CoreConfig {
    /// Instructions issued per cycle (from different warps).
    pub pipeline_width: u32,
    /// Warp slots.
    pub max_warps: u32,
    /// Entries of the input queue (the baseline's single FIFO; WaSP splits
    /// it into priority and regular FIFOs of the same total size).
    pub input_queue: u32,
    /// Cycles from issuing an ALU instruction to the warp's next issue.
    pub alu_latency: u32,
    /// Cycles the texture unit needs after the last block of a texture
    /// instruction arrives (address generation and filtering): its
    /// pipeline latency, which [`CoreConfig::filter_timing`] combines with
    /// the filter's rate.
    pub texture_latency: u32,
    /// Cycles the core's one filter unit is busy with a bilinear (or
    /// nearest) quad-sample: its issue interval (0: no rate limit).
    pub filter_cycles_bilinear: u32,
    /// Cycles the filter unit is busy with a trilinear quad-sample (two
    /// mip levels; 0: no rate limit).
    pub filter_cycles_trilinear: u32,
    /// How the filter's cycles and `texture_latency` add up (see
    /// [`FilterTiming`]).
    pub filter_timing: FilterTiming,
    /// Texture instructions the LDST unit can hold (its queue).
    pub ldst_queue: u32,
    /// 32-bit registers per thread; a warp (a quad) has 4 threads. Sizes the
    /// register file that `wasp cost` sets against WaSP's hardware.
    pub registers_per_thread: u32,
    /// The order in which the issue stage visits ready warps: `lrr` (loose
    /// round-robin) or `gto` (greedy-then-oldest); see [`IssueOrder`]. A
    /// file without the key has `lrr`, the order before the key existed.
    #[serde(default)]
    pub issue: IssueOrder,
}

/// How the tiles of a frame reach the cores.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Dispatch {
    /// The paper's machine: one tile at a time for the whole GPU, one
    /// rasterizer and Early-Z stage, each surviving quad sent to the core
    /// its screen position names, a barrier between tiles.
    SharedTile,
    /// Each core takes a whole tile of its own when it is idle and
    /// rasterizes it with its own rasterizer (tiles run out of phase).
    PerCoreTile,
}

impl std::fmt::Display for Dispatch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Dispatch::SharedTile => "shared-tile",
            Dispatch::PerCoreTile => "per-core-tile",
        })
    }
}

impl std::str::FromStr for Dispatch {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "shared-tile" => Ok(Dispatch::SharedTile),
            "per-core-tile" => Ok(Dispatch::PerCoreTile),
            _ => Err(format!(
                "unknown dispatch `{s}` (expected shared-tile or per-core-tile)"
            )),
        }
    }
}

/// How a texture instruction's filter pass and the texture unit's
/// pipeline latency (`core.texture_latency`) add up. The core has one
/// filter unit, which serves texture instructions in the order their last
/// block arrives: an instruction whose data arrives at cycle `a` starts
/// filtering at `s = max(a, filter free)` and holds the filter for its
/// `f` filter cycles (bilinear or trilinear), so the filter is free again
/// at `s + f`. With `L = max(texture_latency, 1)` the warp wakes at:
///
/// * `overlap`: `max(s + f, a + L)`: the filter pass is part of the
///   pipeline latency, so an idle filter adds nothing until `f > L`; only a
///   busy filter (queueing) or a long pass delays the warp;
/// * `serial`: `s + f + L`: the latency comes after the filter pass.
///
/// With both filter cycles 0 the two are the same: `a + L`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FilterTiming {
    /// `max(s + f, a + L)` (wasp).
    Overlap,
    /// `s + f + L`.
    Serial,
}

impl std::fmt::Display for FilterTiming {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            FilterTiming::Overlap => "overlap",
            FilterTiming::Serial => "serial",
        })
    }
}

/// What happens to the colour buffer when a tile has retired.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ColorFlush {
    /// Double-buffered colour buffer: the tile's lines are written to main
    /// memory while the next tile renders.
    Overlap,
    /// One colour buffer: the next tile starts when the last line of the
    /// flush has entered main memory.
    Blocking,
    /// No flush traffic (the model before the flush existed; for studies).
    None,
}

impl std::fmt::Display for ColorFlush {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            ColorFlush::Overlap => "overlap",
            ColorFlush::Blocking => "blocking",
            ColorFlush::None => "none",
        })
    }
}

/// The raster pipeline: tile fetcher, rasterizer and Early-Z, and the
/// dispatch of quads to the cores.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RasterConfig {
    /// `shared-tile` (the paper's machine) or `per-core-tile`.
    pub dispatch: Dispatch,
    /// Quads the GPU rasterizes per cycle, Early-Z-rejected quads included.
    /// Shared-tile: the one rasterizer's rate; per-core-tile: split evenly
    /// over the cores' rasterizers (must divide by the core count).
    pub quads_per_cycle: u32,
    /// Early-Z-rejected quads that one raster slot disposes of: 1 (the
    /// default) charges each rejected quad a full slot, as the paper's
    /// pipeline order reads (the rasterizer produces every quad, then the
    /// Early-Z test discards it); larger values model a coarse
    /// (hierarchical) depth test rejecting several quads at once.
    #[serde(default = "one")]
    pub rejected_per_slot: u32,
    /// Which core shades a quad, by its in-tile position (shared-tile):
    /// `latin:B` or `rowmajor:B` over blocks of BxB quads (see
    /// [`crate::gpu::CoreMap`]).
    pub core_map: String,
    /// The colour-buffer flush after each tile.
    pub color_flush: ColorFlush,
}

fn one() -> u32 {
    1
}

/// The launch scheduler.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SchedulerConfig {
    /// Launch policy: `baseline`, `fullpriority`, `freemshr:N`,
    /// `wasp[:threshold[:cf]]`.
    pub policy: String,
    /// Priority subset: `mesh2|4|8|16`, `hlines`, `vlines`, `top16`,
    /// `random[:seed]`.
    pub subset: String,
    /// What a core launches when a priority warp waits, the policy's gate
    /// is closed and no regular warp waits: `hold` (nothing; the paper's
    /// rule) or `launch` (that priority warp; work-conserving). See
    /// [`LaunchRule`].
    pub launch_rule: String,
    /// Which miss blocks a warp (the paper's long-latency miss, at a level
    /// the paper does not name): `first-level`, `l1-miss` or `dram` (see
    /// [`BlockedOn`]).
    pub blocked_on: BlockedOn,
}

/// Main memory and the ideal-memory switch.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MemoryConfig {
    /// Zero-latency main memory (the paper's motivation figure).
    pub ideal: bool,
}

/// The event-energy model: energy per event and static power. Figures and
/// their sources are stated in the config file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnergyConfig {
    /// Energy of one ALU instruction of one warp (4 lanes), pJ.
    pub alu_instruction_pj: f64,
    /// Energy of one texture instruction in the texture unit (address
    /// generation and filtering for 4 pixels), pJ.
    pub texture_instruction_pj: f64,
    /// One L0 access, pJ.
    pub l0_access_pj: f64,
    /// One L1 access, pJ.
    pub l1_access_pj: f64,
    /// One L2 access, pJ.
    pub l2_access_pj: f64,
    /// One 64-byte DRAM access that hits the open row, pJ.
    pub dram_row_hit_pj: f64,
    /// One 64-byte DRAM access that opens a row, pJ.
    pub dram_row_miss_pj: f64,
    /// Static (leakage and clock) power of one core with its caches, mW.
    pub core_static_mw: f64,
    /// Static power of the L2 and memory controller, mW.
    pub uncore_static_mw: f64,
}

/// Simulation controls.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SimConfig {
    /// Stop a run that makes no forward progress (no launch, issue, reply
    /// or completion) for this many cycles, and report the stuck state.
    pub watchdog_cycles: u64,
    /// Seed for everything random (the random subset, synthetic traces).
    pub seed: u64,
}

/// The whole machine.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MachineConfig {
    /// A name for reports.
    pub name: String,
    /// Global parameters.
    pub gpu: GpuConfig,
    /// The raster pipeline and the dispatch of quads to cores.
    pub raster: RasterConfig,
    /// The shader core.
    pub core: CoreConfig,
    /// The launch scheduler.
    pub scheduler: SchedulerConfig,
    /// Per-core L0 texture cache (absent at pipeline width 2).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub l0: Option<CacheConfig>,
    /// Per-core L1 texture cache.
    pub l1: CacheConfig,
    /// Shared L2.
    pub l2: CacheConfig,
    /// Main memory (banked or fixed-latency open-row DRAM).
    pub dram: DramConfig,
    /// Ideal-memory switch.
    pub memory: MemoryConfig,
    /// The prefetcher into the L1s (`none` when the section is absent).
    #[serde(default)]
    pub prefetch: PrefetchConfig,
    /// Energy model.
    pub energy: EnergyConfig,
    /// Simulation controls.
    pub sim: SimConfig,
}

/// A configuration error: where, and what was expected.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ConfigError {
    /// The file (or `<embedded paper.toml>`).
    pub source: String,
    /// The message, naming the field.
    pub message: String,
}

/// The 1-based line and byte column of byte `at` of `bytes`.
fn line_and_column(bytes: &[u8], at: usize) -> (usize, usize) {
    let before = &bytes[..at];
    let line = before.iter().filter(|&&b| b == b'\n').count() + 1;
    let start = before
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |i| i + 1);
    (line, at - start + 1)
}

impl fmt::Display for ConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.source, self.message)
    }
}

impl std::error::Error for ConfigError {}

/// Limits the model enforces: every numeric field of the machine
/// configuration has an upper bound that makes sense for the mobile GPU it
/// describes and keeps memory and run time bounded (docs/machine.md,
/// "Configuration bounds", lists them all; the memory system's are in
/// [`crate::mem::config::bounds`]).
pub mod limits {
    /// Largest pipeline width.
    pub const MAX_WIDTH: u32 = 16;
    /// Largest warp-slot count (the paper's sweep goes to 128).
    pub const MAX_WARPS: u32 = 128;
    /// Largest core count.
    pub const MAX_CORES: u32 = 64;
    /// Highest clock frequency, MHz (mobile GPUs run below 1.5 GHz).
    pub const MAX_FREQUENCY_MHZ: u32 = 10_000;
    /// Largest input queue.
    pub const MAX_QUEUE: u32 = 4096;
    /// Largest latency of any fixed pipeline stage.
    pub const MAX_LATENCY: u32 = 10_000;
    /// Most filter cycles per quad-sample.
    pub const MAX_FILTER_CYCLES: u32 = 1_000;
    /// Most quads rasterized per cycle by the GPU.
    pub const MAX_QUADS_PER_CYCLE: u32 = 256;
    /// Most Early-Z-rejected quads one raster slot disposes of (a 32x32-quad
    /// tile at once).
    pub const MAX_REJECTED_PER_SLOT: u32 = 1024;
    /// Largest LDST queue.
    pub const MAX_LDST_QUEUE: u32 = 1024;
    /// Most 32-bit registers per thread (GPUs address at most 255).
    pub const MAX_REGISTERS_PER_THREAD: u32 = 1024;
    /// Longest watchdog: a run stopped after 10^9 cycles without progress
    /// has spent minutes of host time spinning.
    pub const MAX_WATCHDOG_CYCLES: u64 = 1_000_000_000;
    /// Largest energy of one event, pJ: 1 uJ (a DRAM access is a few nJ).
    pub const MAX_EVENT_PJ: f64 = 1_000_000.0;
    /// Largest static power, mW: 100 W.
    pub const MAX_STATIC_MW: f64 = 100_000.0;
}

impl MachineConfig {
    /// The paper's machine (`configs/paper.toml`).
    pub fn paper() -> Self {
        Self::parse(PAPER_TOML, "<embedded configs/paper.toml>").expect("shipped config is valid")
    }

    /// The width-2 machine (`configs/paper-width2.toml`).
    pub fn paper_width2() -> Self {
        Self::parse(PAPER_WIDTH2_TOML, "<embedded configs/paper-width2.toml>")
            .expect("shipped config is valid")
    }

    /// Read and validate a TOML file. A file that is not UTF-8 is named with
    /// the line and byte column of its first invalid byte.
    pub fn load(path: &Path) -> Result<Self, ConfigError> {
        let source = path.display().to_string();
        let bytes = std::fs::read(path).map_err(|e| ConfigError {
            source: source.clone(),
            message: format!("cannot read: {e}"),
        })?;
        let text = std::str::from_utf8(&bytes).map_err(|e| {
            let at = e.valid_up_to();
            let (line, column) = line_and_column(&bytes, at);
            ConfigError {
                source: format!("{source}:{line}:{column}"),
                message: format!(
                    "byte 0x{:02x} is not UTF-8 (line {line}, byte column {column}); a \
                     configuration is UTF-8 TOML text",
                    bytes[at]
                ),
            }
        })?;
        Self::parse(text, &source)
    }

    /// Parse and validate TOML text; `source` names it in errors.
    pub fn parse(text: &str, source: &str) -> Result<Self, ConfigError> {
        let cfg: MachineConfig = toml::from_str(text).map_err(|e| ConfigError {
            source: source.to_string(),
            message: e.to_string().trim_end().to_string(),
        })?;
        cfg.validate().map_err(|message| ConfigError {
            source: source.to_string(),
            message,
        })?;
        Ok(cfg)
    }

    /// The configuration as TOML (what `--config` reads back).
    pub fn to_toml(&self) -> String {
        toml::to_string(self).expect("config serializes")
    }

    /// The parsed launch policy.
    pub fn policy(&self) -> Result<PolicySpec, String> {
        self.scheduler
            .policy
            .parse()
            .map_err(|e| format!("scheduler.policy: {e}"))
    }

    /// The parsed launch rule for a closed gate.
    pub fn launch_rule(&self) -> Result<LaunchRule, String> {
        self.scheduler
            .launch_rule
            .parse()
            .map_err(|e| format!("scheduler.launch_rule: {e}"))
    }

    /// The parsed priority subset.
    pub fn subset(&self) -> Result<SubsetSpec, String> {
        self.scheduler
            .subset
            .parse()
            .map_err(|e| format!("scheduler.subset: {e}"))
    }

    /// The parsed quad-to-core map.
    pub fn core_map(&self) -> Result<crate::gpu::CoreMap, String> {
        self.raster
            .core_map
            .parse()
            .map_err(|e| format!("raster.core_map: {e}"))
    }

    /// Quads per tile side.
    pub fn quads_per_side(&self) -> u32 {
        self.gpu.tile_size / 2
    }

    /// The cache whose MSHRs the scheduler watches, with its section name.
    pub fn scheduler_cache(&self) -> (&'static str, &CacheConfig) {
        match &self.l0 {
            Some(l0) => ("l0", l0),
            None => ("l1", &self.l1),
        }
    }

    /// The memory-system part of the configuration.
    pub fn mem_config(&self) -> MemConfig {
        MemConfig {
            cores: self.gpu.cores,
            l0: self.l0,
            l1: self.l1,
            l2: self.l2,
            dram: self.dram,
            ideal_memory: self.memory.ideal,
            blocked_on: self.scheduler.blocked_on,
            prefetch: self.prefetch,
        }
    }

    /// Every check, each error naming the field and the limit.
    pub fn validate(&self) -> Result<(), String> {
        let range = check_range;
        range(
            "gpu.cores",
            self.gpu.cores as u64,
            1,
            limits::MAX_CORES as u64,
            "",
        )?;
        range(
            "gpu.frequency_mhz",
            self.gpu.frequency_mhz as u64,
            1,
            limits::MAX_FREQUENCY_MHZ as u64,
            "",
        )?;
        let ts = self.gpu.tile_size;
        if !(4..=64).contains(&ts) || !ts.is_power_of_two() {
            return Err(format!(
                "gpu.tile_size = {ts}: must be a power of two in 4..=64 (in-tile quad coordinates are 5-bit: at most 32 quads per side)"
            ));
        }
        range(
            "core.pipeline_width",
            self.core.pipeline_width as u64,
            1,
            limits::MAX_WIDTH as u64,
            "",
        )?;
        range(
            "core.max_warps",
            self.core.max_warps as u64,
            1,
            limits::MAX_WARPS as u64,
            " (the paper sweeps 28..=128)",
        )?;
        range(
            "core.input_queue",
            self.core.input_queue as u64,
            1,
            limits::MAX_QUEUE as u64,
            "",
        )?;
        range(
            "raster.quads_per_cycle",
            self.raster.quads_per_cycle as u64,
            1,
            limits::MAX_QUADS_PER_CYCLE as u64,
            "",
        )?;
        range(
            "raster.rejected_per_slot",
            self.raster.rejected_per_slot as u64,
            1,
            limits::MAX_REJECTED_PER_SLOT as u64,
            "",
        )?;
        if self.raster.dispatch == Dispatch::PerCoreTile
            && !self.raster.quads_per_cycle.is_multiple_of(self.gpu.cores)
        {
            return Err(format!(
                "raster.quads_per_cycle = {}: with raster.dispatch = per-core-tile the rate is split evenly over the {} cores' rasterizers, so it must be a multiple of gpu.cores",
                self.raster.quads_per_cycle, self.gpu.cores
            ));
        }
        self.core_map()?;
        range(
            "core.alu_latency",
            self.core.alu_latency as u64,
            1,
            limits::MAX_LATENCY as u64,
            "",
        )?;
        range(
            "core.texture_latency",
            self.core.texture_latency as u64,
            0,
            limits::MAX_LATENCY as u64,
            "",
        )?;
        range(
            "core.filter_cycles_bilinear",
            self.core.filter_cycles_bilinear as u64,
            0,
            limits::MAX_FILTER_CYCLES as u64,
            " (0: no filter rate limit)",
        )?;
        range(
            "core.filter_cycles_trilinear",
            self.core.filter_cycles_trilinear as u64,
            0,
            limits::MAX_FILTER_CYCLES as u64,
            " (0: no filter rate limit)",
        )?;
        range(
            "core.ldst_queue",
            self.core.ldst_queue as u64,
            1,
            limits::MAX_LDST_QUEUE as u64,
            "",
        )?;
        range(
            "core.registers_per_thread",
            self.core.registers_per_thread as u64,
            1,
            limits::MAX_REGISTERS_PER_THREAD as u64,
            "",
        )?;
        range(
            "sim.watchdog_cycles",
            self.sim.watchdog_cycles,
            1,
            limits::MAX_WATCHDOG_CYCLES,
            " cycles",
        )?;

        self.mem_config().check().map_err(|e| e.to_string())?;
        let (level, sched_cache) = self.scheduler_cache();
        let reg_max = (1u32 << FREE_MSHR_BITS) - 1;
        let policy = self.policy()?;
        if policy.reads_free_mshrs() && sched_cache.mshrs > reg_max {
            return Err(format!(
                "{level}.mshrs = {}: policy {policy} watches this cache's MSHRs in the {FREE_MSHR_BITS}-bit free-MSHR register, which holds at most {reg_max} (baseline and fullpriority do not read it)",
                sched_cache.mshrs
            ));
        }
        let subset = self.subset()?;
        self.launch_rule()?;
        policy.build(sched_cache.mshrs.min(reg_max)).map_err(|e| {
            format!(
                "scheduler.policy: {e} ({level}.mshrs = {})",
                sched_cache.mshrs
            )
        })?;
        // The non-blocked counter counts priority warps in the core: at most
        // one tile's priority quads, and at most the warp slots.
        let side = self.quads_per_side();
        let per_tile = subset.build(side).size_ratio(side) * (side * side) as f64;
        let max_prio = (per_tile.round() as u32).min(self.core.max_warps);
        let counter_max = (1u32 << NONBLOCKED_BITS) - 1;
        if max_prio > counter_max {
            return Err(format!(
                "core.max_warps = {} with scheduler.subset = {subset}: up to {max_prio} priority warps could be in a core, but the {NONBLOCKED_BITS}-bit non-blocked priority-warp counter holds at most {counter_max}",
                self.core.max_warps
            ));
        }
        let e = &self.energy;
        for (field, v) in [
            ("energy.alu_instruction_pj", e.alu_instruction_pj),
            ("energy.texture_instruction_pj", e.texture_instruction_pj),
            ("energy.l0_access_pj", e.l0_access_pj),
            ("energy.l1_access_pj", e.l1_access_pj),
            ("energy.l2_access_pj", e.l2_access_pj),
            ("energy.dram_row_hit_pj", e.dram_row_hit_pj),
            ("energy.dram_row_miss_pj", e.dram_row_miss_pj),
            ("energy.core_static_mw", e.core_static_mw),
            ("energy.uncore_static_mw", e.uncore_static_mw),
        ] {
            let hi = if field.ends_with("_mw") {
                limits::MAX_STATIC_MW
            } else {
                limits::MAX_EVENT_PJ
            };
            if !v.is_finite() || !(0.0..=hi).contains(&v) {
                return Err(format!(
                    "{field} = {v}: must be a finite number in 0..={hi}"
                ));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests;
