//! The sections of the machine configuration, each parameter declared once:
//! its description, its bound and its type (see [`crate::param`]). The
//! shipped files (`configs/*.toml`) give every value with its source.

use super::choice::{BlockedOn, ColorFlush, Dispatch, FilterTiming, IssueOrder, TextureCache};
use super::core_map::CoreMap;
use crate::param::section;
use limits::*;
use serde::{Deserialize, Serialize};
use wasp_rtl::policy::{LaunchRule, PolicySpec};
use wasp_rtl::subset::SubsetSpec;

/// Limits the model enforces: every numeric field of the machine
/// configuration has an upper bound that makes sense for the mobile GPU it
/// describes and keeps memory and run time bounded (docs/machine.md,
/// "Configuration bounds", lists them all; the memory system's are in
/// [`crate::mem::config::bounds`]).
pub mod limits {
    /// Smallest tile side, pixels.
    pub const MIN_TILE_SIZE: u32 = 4;
    /// Largest tile side, pixels: in-tile quad coordinates are 5-bit.
    pub const MAX_TILE_SIZE: u32 = 64;
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

section! {
    /// Global GPU parameters.
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
    pub struct GpuConfig {
        /// Shader cores, each with its own L0/L1 texture caches.
        #[range(1..=MAX_CORES)]
        pub cores: u32,
        /// Clock frequency in MHz (for energy and time conversions).
        #[range(1..=MAX_FREQUENCY_MHZ)]
        pub frequency_mhz: u32,
        /// Tile side in pixels; quads per tile side = tile_size / 2. A
        /// power of two in [`MIN_TILE_SIZE`]..=[`MAX_TILE_SIZE`] (in-tile
        /// quad coordinates are 5-bit), checked by
        /// [`MachineConfig::validate`](super::MachineConfig::validate).
        #[bound(MIN_TILE_SIZE..=MAX_TILE_SIZE, "a power of two")]
        pub tile_size: u32,
    }
}

section! {
    /// One shader core.
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
    pub struct CoreConfig {
        /// Instructions issued per cycle (from different warps).
        #[range(1..=MAX_WIDTH)]
        pub pipeline_width: u32,
        /// Warp slots.
        #[range(1..=MAX_WARPS, " (the paper sweeps 28..=128)")]
        pub max_warps: u32,
        /// Entries of the input queue (the baseline's single FIFO; WaSP
        /// splits it into priority and regular FIFOs of the same total
        /// size).
        #[range(1..=MAX_QUEUE)]
        pub input_queue: u32,
        /// Cycles from issuing an ALU instruction to the warp's next issue.
        #[range(1..=MAX_LATENCY)]
        pub alu_latency: u32,
        /// Cycles the texture unit needs after the last block of a texture
        /// instruction arrives (address generation and filtering): its
        /// pipeline latency, which `filter_timing` combines with the
        /// filter's rate.
        #[range(0..=MAX_LATENCY)]
        pub texture_latency: u32,
        /// Cycles the core's one filter unit is busy with a bilinear (or
        /// nearest) quad-sample: its issue interval (0: no rate limit).
        #[range(0..=MAX_FILTER_CYCLES, " (0: no filter rate limit)")]
        pub filter_cycles_bilinear: u32,
        /// Cycles the filter unit is busy with a trilinear quad-sample (two
        /// mip levels; 0: no rate limit).
        #[range(0..=MAX_FILTER_CYCLES, " (0: no filter rate limit)")]
        pub filter_cycles_trilinear: u32,
        /// How the filter's cycles and `texture_latency` add up (see
        /// [`FilterTiming`]).
        pub filter_timing: FilterTiming,
        /// Texture instructions the LDST unit can hold (its queue).
        #[range(1..=MAX_LDST_QUEUE)]
        pub ldst_queue: u32,
        /// 32-bit registers per thread; a warp (a quad) has 4 threads.
        /// Sizes the register file that `wasp cost` sets against WaSP's
        /// hardware.
        #[range(1..=MAX_REGISTERS_PER_THREAD)]
        pub registers_per_thread: u32,
        /// The order in which the issue stage visits ready warps: `lrr`
        /// (loose round-robin) or `gto` (greedy-then-oldest); see
        /// [`IssueOrder`]. A file without the key has `lrr`, the order
        /// before the key existed.
        #[serde(default)]
        pub issue: IssueOrder,
    }
}

impl CoreConfig {
    /// Filter cycles of a quad-sample, trilinear or not.
    #[inline]
    pub fn filter_cycles(&self, trilinear: bool) -> u32 {
        if trilinear {
            self.filter_cycles_trilinear
        } else {
            self.filter_cycles_bilinear
        }
    }
}

section! {
    /// The raster pipeline: tile fetcher, rasterizer and Early-Z, and the
    /// dispatch of quads to the cores.
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
    pub struct RasterConfig {
        /// `shared-tile` (the paper's machine) or `per-core-tile`.
        pub dispatch: Dispatch,
        /// Quads the GPU rasterizes per cycle, Early-Z-rejected quads
        /// included. Shared-tile: the one rasterizer's rate; per-core-tile:
        /// split evenly over the cores' rasterizers (must divide by the
        /// core count).
        #[range(1..=MAX_QUADS_PER_CYCLE)]
        pub quads_per_cycle: u32,
        /// Early-Z-rejected quads that one raster slot disposes of: 1 (the
        /// default) charges each rejected quad a full slot, as the paper's
        /// pipeline order reads (the rasterizer produces every quad, then
        /// the Early-Z test discards it); larger values model a coarse
        /// (hierarchical) depth test rejecting several quads at once.
        #[range(1..=MAX_REJECTED_PER_SLOT)]
        #[serde(default = "one")]
        pub rejected_per_slot: u32,
        /// Which core shades a quad, by its in-tile position (shared-tile):
        /// `latin:B` or `rowmajor:B` over blocks of BxB quads (see
        /// [`CoreMap`]).
        pub core_map: CoreMap,
        /// The colour-buffer flush after each tile.
        pub color_flush: ColorFlush,
    }
}

fn one() -> u32 {
    1
}

section! {
    /// The launch scheduler.
    #[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
    pub struct SchedulerConfig {
        /// Launch policy: `baseline`, `fullpriority`, `freemshr:N`,
        /// `wasp[:threshold[:cf]]`, `wasp-m[:threshold]` (see
        /// [`PolicySpec`]; its numbers are checked against the watched
        /// cache's MSHRs by [`MachineConfig::validate`](super::MachineConfig::validate)).
        pub policy: PolicySpec,
        /// Priority subset: `mesh2|4|8|16`, `hlines`, `vlines`, `top16`,
        /// `random[:seed]`.
        pub subset: SubsetSpec,
        /// What a core launches when a priority warp waits, the policy's
        /// gate is closed and no regular warp waits: `hold` (nothing; the
        /// paper's rule) or `launch` (that priority warp;
        /// work-conserving). See [`LaunchRule`].
        pub launch_rule: LaunchRule,
        /// Which miss blocks a warp (the paper's long-latency miss, at a
        /// level the paper does not name): `first-level`, `l1-miss` or
        /// `dram` (see [`BlockedOn`]).
        pub blocked_on: BlockedOn,
    }
}

section! {
    /// Main memory and the ideal-memory switch; what the texture caches
    /// hold.
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
    pub struct MemoryConfig {
        /// Zero-latency main memory (the paper's motivation figure).
        pub ideal: bool,
        /// What the L0 and L1 texture caches hold of a compressed texture:
        /// `compressed` (its stored lines, as every level below) or
        /// `decompressed` (decoded RGBA8 lines; the L2 and DRAM keep the
        /// compressed ones): see [`TextureCache`]. A file without the key
        /// has `compressed`, the model before the key existed.
        #[serde(default)]
        pub texture_cache: TextureCache,
    }
}

section! {
    /// The event-energy model: energy per event and static power. Figures
    /// and their sources are stated in the config file.
    #[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
    pub struct EnergyConfig {
        /// Energy of one ALU instruction of one warp (4 lanes), pJ.
        #[range(0.0..=MAX_EVENT_PJ)]
        pub alu_instruction_pj: f64,
        /// Energy of one texture instruction in the texture unit (address
        /// generation and filtering for 4 pixels), pJ.
        #[range(0.0..=MAX_EVENT_PJ)]
        pub texture_instruction_pj: f64,
        /// One L0 access, pJ.
        #[range(0.0..=MAX_EVENT_PJ)]
        pub l0_access_pj: f64,
        /// One L1 access, pJ.
        #[range(0.0..=MAX_EVENT_PJ)]
        pub l1_access_pj: f64,
        /// One L2 access, pJ.
        #[range(0.0..=MAX_EVENT_PJ)]
        pub l2_access_pj: f64,
        /// One 64-byte DRAM access that hits the open row, pJ.
        #[range(0.0..=MAX_EVENT_PJ)]
        pub dram_row_hit_pj: f64,
        /// One 64-byte DRAM access that opens a row, pJ.
        #[range(0.0..=MAX_EVENT_PJ)]
        pub dram_row_miss_pj: f64,
        /// Static (leakage and clock) power of one core with its caches, mW.
        #[range(0.0..=MAX_STATIC_MW)]
        pub core_static_mw: f64,
        /// Static power of the L2 and memory controller, mW.
        #[range(0.0..=MAX_STATIC_MW)]
        pub uncore_static_mw: f64,
    }
}

section! {
    /// Simulation controls.
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
    pub struct SimConfig {
        /// Stop a run that makes no forward progress (no launch, issue,
        /// reply or completion) for this many cycles, and report the stuck
        /// state.
        #[range(1..=MAX_WATCHDOG_CYCLES, " cycles")]
        pub watchdog_cycles: u64,
        /// Seed for everything random (the random subset, synthetic
        /// traces). Every u64 is a seed.
        pub seed: u64,
    }
}
