//! What a shader core is built from: its section of the machine
//! configuration as declared there, and what the rest of the machine
//! decides for it.

use crate::config::{CoreConfig, Dispatch, MachineConfig};
use crate::mem::BlockedOn;

/// What a core is built from.
#[derive(Clone, Copy, Debug)]
pub struct CoreParams {
    /// The `[core]` section.
    pub core: CoreConfig,
    /// The GPU's one rasterizer fills the input queue (shared-tile
    /// dispatch); otherwise the core rasterizes its own tiles.
    pub external_raster: bool,
    /// Quads its own rasterizer produces per cycle: its share of
    /// `raster.quads_per_cycle` (per-core-tile dispatch).
    pub raster_rate: u32,
    /// Early-Z-rejected quads one of its raster slots disposes of
    /// (`raster.rejected_per_slot`).
    pub rejected_per_slot: u32,
    /// MSHRs the free-MSHR register counts
    /// ([`MachineConfig::watched_mshrs`]).
    pub watched_mshrs: u32,
    /// Which miss blocks a warp (`scheduler.blocked_on`).
    pub blocked_on: BlockedOn,
}

impl CoreParams {
    /// The parameters of every core of the (validated) machine `cfg`.
    pub fn new(cfg: &MachineConfig) -> Self {
        CoreParams {
            core: cfg.core,
            external_raster: cfg.raster.dispatch == Dispatch::SharedTile,
            raster_rate: cfg.raster.quads_per_cycle / cfg.gpu.cores,
            rejected_per_slot: cfg.raster.rejected_per_slot,
            watched_mshrs: cfg.watched_mshrs(),
            blocked_on: cfg.scheduler.blocked_on,
        }
    }

    /// Warp slots.
    #[inline]
    pub fn slots(&self) -> usize {
        self.core.max_warps as usize
    }
}
