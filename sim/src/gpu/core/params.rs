//! What a shader core is built from: its section of the machine
//! configuration as declared there, and what the rest of the machine
//! decides for it.

use crate::config::{BlockedOn, CoreConfig, Dispatch, MachineConfig};

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
    /// MSHRs of its L0, if it has one.
    pub l0_mshrs: Option<u32>,
    /// MSHRs of its L1.
    pub l1_mshrs: u32,
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
            l0_mshrs: cfg.l0.map(|l0| l0.mshrs),
            l1_mshrs: cfg.l1.mshrs,
        }
    }

    /// The core's rule of which miss blocks a warp.
    pub(super) fn blocked_rule(&self) -> super::blocked::BlockedRule {
        let (_, first) = crate::mem::first_level(self.l0_mshrs, self.l1_mshrs);
        super::blocked::BlockedRule::new(
            self.blocked_on,
            self.l0_mshrs.is_some(),
            first,
            self.l1_mshrs,
        )
    }

    /// Warp slots.
    #[inline]
    pub fn slots(&self) -> usize {
        self.core.max_warps as usize
    }
}
