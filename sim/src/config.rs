//! The machine configuration: one TOML file describes the whole GPU, or
//! the fields in which it differs from a shipped machine.
//!
//! `configs/paper.toml` (embedded as [`MachineConfig::paper`]) holds the
//! paper's Table II with its best baseline (pipeline width 4, 64 warps, L0
//! present); `configs/paper-width2.toml` the width-2 machine (no L0, the
//! scheduler watches the L1's MSHRs). Every field is documented in those
//! files and declared once, with its bound, in `config/sections.rs`. A
//! file that sets only some fields is read on top of a base machine
//! ([`file`](mod@file)). Unknown keys are errors, and [`MachineConfig::validate`]
//! refuses every value the model or the scheduler's registers cannot hold,
//! naming the field and the limit.

use crate::mem::{CacheConfig, DramConfig, MemConfig, PrefetchConfig};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::path::Path;
use wasp_rtl::free_mshr::{FREE_MSHR_BITS, FREE_MSHR_MAX};
use wasp_rtl::nonblocked::NONBLOCKED_BITS;

mod choice;
mod core_map;
pub mod file;
mod overrides;
pub mod params;
mod sections;
pub use choice::{BlockedOn, ColorFlush, Dispatch, FilterTiming, IssueOrder, TextureCache};
pub use core_map::{CoreMap, CoreMapTable};
pub use overrides::Override;
pub use sections::{
    limits, CoreConfig, EnergyConfig, GpuConfig, MemoryConfig, RasterConfig, SchedulerConfig,
    SimConfig,
};

/// The paper's machine, as shipped in `configs/paper.toml`.
pub const PAPER_TOML: &str = crate::param::PAPER_TOML;
/// The width-2 machine, as shipped in `configs/paper-width2.toml`.
pub const PAPER_WIDTH2_TOML: &str = include_str!("../../configs/paper-width2.toml");

/// The shipped machines, by the name a file's `extends` gives them.
pub const SHIPPED: [(&str, &str); 2] = [("paper", PAPER_TOML), ("paper-width2", PAPER_WIDTH2_TOML)];

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
    /// Ideal-memory switch and what the texture caches hold.
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

impl fmt::Display for ConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.source, self.message)
    }
}

impl std::error::Error for ConfigError {}

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

    /// Read and validate a TOML file: a whole machine, or a patch onto
    /// the machine its `extends` names (a shipped machine, `paper` or
    /// `paper-width2`, or a file, relative to this one), by default the
    /// paper's (see [`file`](mod@file) and docs/model.md). A file that is not UTF-8
    /// is named with the line and byte column of its first invalid byte.
    pub fn load(path: &Path) -> Result<Self, ConfigError> {
        file::load(path, 0)
    }

    /// Parse and validate TOML text as [`load`](Self::load) reads a file
    /// (an `extends` path is relative to the working directory); `source`
    /// names it in errors, with the line of the key an error is about
    /// (`file.toml:12`).
    pub fn parse(text: &str, source: &str) -> Result<Self, ConfigError> {
        file::read(text, source, None, 0)
    }

    /// The configuration as TOML (what `--config` reads back).
    pub fn to_toml(&self) -> String {
        toml::to_string(self).expect("config serializes")
    }

    /// Quads per tile side.
    pub fn quads_per_side(&self) -> u32 {
        self.gpu.tile_size / 2
    }

    /// The cache whose MSHRs the scheduler watches, with its section name
    /// ([`first_level`](crate::mem::first_level)).
    pub fn scheduler_cache(&self) -> (&'static str, &CacheConfig) {
        crate::mem::first_level(self.l0.as_ref(), &self.l1)
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
            report_misses: self
                .scheduler
                .blocked_on
                .reads_miss_events(self.l0.is_some()),
            prefetch: self.prefetch,
        }
    }

    /// Every check, each error naming the field and the limit: the
    /// declared range of every numeric field, then what involves several
    /// fields (the tile, the raster's share per core, the memory system's
    /// structure, the scheduler's registers).
    pub fn validate(&self) -> Result<(), String> {
        self.gpu.check_bounds("gpu")?;
        self.raster.check_bounds("raster")?;
        self.core.check_bounds("core")?;
        self.scheduler.check_bounds("scheduler")?;
        self.memory.check_bounds("memory")?;
        self.energy.check_bounds("energy")?;
        self.sim.check_bounds("sim")?;
        let ts = self.gpu.tile_size;
        let (lo, hi) = (limits::MIN_TILE_SIZE, limits::MAX_TILE_SIZE);
        if !(lo..=hi).contains(&ts) || !ts.is_power_of_two() {
            return Err(format!(
                "gpu.tile_size = {ts}: must be a power of two in {lo}..={hi} (in-tile quad coordinates are 5-bit: at most {} quads per side)",
                hi / 2
            ));
        }
        if self.raster.dispatch == Dispatch::PerCoreTile
            && !self.raster.quads_per_cycle.is_multiple_of(self.gpu.cores)
        {
            return Err(format!(
                "raster.quads_per_cycle = {}: with raster.dispatch = per-core-tile the rate is split evenly over the {} cores' rasterizers, so it must be a multiple of gpu.cores",
                self.raster.quads_per_cycle, self.gpu.cores
            ));
        }
        self.mem_config().check().map_err(|e| e.to_string())?;
        self.check_registers()
    }

    /// What the scheduler's registers can hold: the free-MSHR register
    /// (5 bits) counts the watched cache's MSHRs for the policies that read
    /// it, the policy's constants fit their registers, and the non-blocked
    /// counter (7 bits) counts every priority warp a core can hold.
    fn check_registers(&self) -> Result<(), String> {
        let (level, sched_cache) = self.scheduler_cache();
        let policy = self.scheduler.policy;
        if policy.reads_free_mshrs() && sched_cache.mshrs > FREE_MSHR_MAX {
            return Err(format!(
                "{level}.mshrs = {}: policy {policy} watches this cache's MSHRs in the {FREE_MSHR_BITS}-bit free-MSHR register, which holds at most {FREE_MSHR_MAX} (baseline and fullpriority do not read it)",
                sched_cache.mshrs
            ));
        }
        policy.build(self.watched_mshrs()).map_err(|e| {
            format!(
                "scheduler.policy: {e} ({level}.mshrs = {})",
                sched_cache.mshrs
            )
        })?;
        // The non-blocked counter counts priority warps in the core: at most
        // one tile's priority quads, and at most the warp slots.
        let subset = &self.scheduler.subset;
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
        Ok(())
    }

    /// The MSHRs the scheduler's free-MSHR register counts: those of the
    /// watched cache ([`scheduler_cache`](Self::scheduler_cache)), at most
    /// what the 5-bit register holds ([`FREE_MSHR_MAX`]; policies that do
    /// not read the register may watch a larger cache).
    pub fn watched_mshrs(&self) -> u32 {
        self.scheduler_cache().1.mshrs.min(FREE_MSHR_MAX)
    }
}

#[cfg(test)]
mod tests;
