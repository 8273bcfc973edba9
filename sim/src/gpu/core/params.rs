//! What a shader core takes from the machine configuration.

use crate::config::FilterTiming;
use crate::gpu::IssueOrder;
use crate::mem::BlockedOn;

/// What a core needs from the configuration.
#[derive(Clone, Copy, Debug)]
pub struct CoreParams {
    /// Instructions issued per cycle.
    pub width: u32,
    /// Warp slots (at most 128).
    pub max_warps: u32,
    /// Input queue entries.
    pub input_queue: u32,
    /// Quads its own rasterizer produces per cycle (per-core-tile
    /// dispatch; unused when `external_raster`).
    pub raster_rate: u32,
    /// Early-Z-rejected quads one of its raster slots disposes of (>= 1).
    pub rejected_per_slot: u32,
    /// The GPU's one rasterizer fills the input queue (shared-tile).
    pub external_raster: bool,
    /// ALU latency.
    pub alu_latency: u32,
    /// Texture unit latency after the data.
    pub texture_latency: u32,
    /// Filter cycles per bilinear quad-sample.
    pub filter_cycles_bilinear: u32,
    /// Filter cycles per trilinear quad-sample.
    pub filter_cycles_trilinear: u32,
    /// How the filter pass and the texture latency add up.
    pub filter_timing: FilterTiming,
    /// LDST queue entries.
    pub ldst_queue: u32,
    /// MSHRs of the scheduler-level cache.
    pub sched_mshrs: u32,
    /// Which miss blocks a warp (the memory system must report the same).
    pub blocked_on: BlockedOn,
    /// The order in which the issue stage visits ready warps.
    pub issue: IssueOrder,
}
