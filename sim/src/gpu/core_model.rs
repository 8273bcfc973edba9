//! What the GPU asks of a shader core: the contract that the fast core
//! ([`ShaderCore`]) keeps, and that its plain twin (`core/plain.rs`, the
//! reference the lockstep tests compare it with) keeps too.
//!
//! The GPU ([`Gpu`](super::Gpu)) is generic over it, so the cycle loop,
//! the dispatch modes and the shared rasterizer drive either core; the
//! fast path is monomorphised and pays nothing for it.
//!
//! One cycle, as the GPU calls it:
//! 1. tile dispatch: [`assign_tile`](CoreModel::assign_tile) (per-core
//!    tile) or [`begin_shared_tile`](CoreModel::begin_shared_tile) and
//!    [`push_quad`](CoreModel::push_quad) from the shared rasterizer;
//! 2. [`evaluate`](CoreModel::evaluate): phase 1 (wake-ups, raster, launch,
//!    issue, LDST), saying whether a stage made progress;
//! 3. the memory system ticks;
//! 4. [`complete`](CoreModel::complete): phase 2 (blocking, completions,
//!    the scheduler's clock edge), saying whether data returned;
//! 5. the waveform samples the core ([`Traceable`]), then
//!    [`end_cycle`](CoreModel::end_cycle) (and, under shared-tile
//!    dispatch, [`end_shared_tile`](CoreModel::end_shared_tile) once every
//!    core is [`drained`](CoreModel::drained)).

use super::core::{CoreParams, CoreSnapshot, CoreStats, ShaderCore, WarpRecord};
use super::SimError;
use crate::mem::MemorySystem;
use crate::trace::{Tile, Trace};
use wasp_rtl::policy::{LaunchPolicy, LaunchRule};
use wasp_rtl::subset::PrioritySubset;
use wasp_waves::Traceable;

/// A shader core as the GPU drives it (see the module docs for the order
/// of the calls in a cycle).
pub trait CoreModel: Traceable + Sized {
    /// A core in its reset state, its scheduler wired for `policy`.
    fn build(
        id: usize,
        p: &CoreParams,
        policy: &dyn LaunchPolicy,
        rule: LaunchRule,
        subset: Box<dyn PrioritySubset>,
    ) -> Self;
    /// The core's tile (its index in the trace), if any.
    fn tile(&self) -> Option<usize>;
    /// Whether the core has no tile.
    fn idle(&self) -> bool;
    /// Give the core tile `index`, `tile`, to rasterize itself
    /// (per-core-tile dispatch; the core must be idle).
    fn assign_tile(&mut self, index: usize, tile: &Tile);
    /// Open tile `tile` for the core (shared-tile dispatch).
    fn begin_shared_tile(&mut self, tile: usize);
    /// Offer quad `quad` at in-tile (x, y) to the input queue; `false`
    /// when its FIFO is full.
    fn push_quad(&mut self, quad: u32, x: u32, y: u32) -> bool;
    /// Every slot of the input queue is taken: [`push_quad`](Self::push_quad)
    /// refuses any quad until a warp launches.
    fn input_full(&self) -> bool;
    /// Surviving quads of its own tile its rasterizer has put in the input
    /// queue so far (per-core-tile dispatch; they are quads `0..n` in
    /// rasterization order).
    fn quads_entered(&self) -> u32;
    /// Nothing of the open tile is queued, resident or in the LDST unit.
    fn drained(&self) -> bool;
    /// Close the open tile (shared-tile dispatch; the core is drained).
    fn end_shared_tile(&mut self);
    /// Primary misses at the scheduler-level cache since the tile began.
    fn tile_misses(&self) -> u64;
    /// The warp launched in the last evaluated cycle: (quad, priority).
    fn launched_now(&self) -> Option<(u32, bool)>;
    /// The core's counters.
    fn stats(&self) -> &CoreStats;
    /// Set every counter to zero, the core's state unchanged (a frame
    /// begins; the core is idle).
    fn reset_stats(&mut self);
    /// No stage can make progress in cycle `now` (asked before it runs):
    /// a cycle of an idle core changes nothing but its counters.
    fn is_idle(&self, now: u64) -> bool;
    /// Phase 1 of cycle `now`; whether a stage made progress (a warp
    /// launched, issued or retired, a block presented, a quad
    /// rasterized).
    fn evaluate(&mut self, now: u64, trace: &Trace, mem: &mut MemorySystem) -> bool;
    /// Phase 2 of cycle `now`; whether data returned.
    fn complete(&mut self, now: u64, mem: &mut MemorySystem) -> Result<bool, SimError>;
    /// End of cycle; whether the core's own tile finished.
    fn end_cycle(&mut self) -> bool;
    /// The core's state in words (for the watchdog).
    fn describe(&self, trace: &Trace) -> String;
    /// Start recording every warp.
    fn record_warps(&mut self);
    /// The warp records so far.
    fn take_records(&mut self) -> Vec<WarpRecord>;
    /// Warps in flight.
    fn active(&self) -> u32;
    /// The observable state (see [`CoreSnapshot`]).
    fn snapshot(&self) -> CoreSnapshot;
}

/// The fast core keeps the contract with its own methods.
impl CoreModel for ShaderCore {
    fn build(
        id: usize,
        p: &CoreParams,
        policy: &dyn LaunchPolicy,
        rule: LaunchRule,
        subset: Box<dyn PrioritySubset>,
    ) -> Self {
        ShaderCore::new(id, p, policy, rule, subset)
    }
    #[inline]
    fn tile(&self) -> Option<usize> {
        ShaderCore::tile(self)
    }
    #[inline]
    fn idle(&self) -> bool {
        ShaderCore::idle(self)
    }
    fn assign_tile(&mut self, index: usize, tile: &Tile) {
        ShaderCore::assign_tile(self, index, tile)
    }
    fn begin_shared_tile(&mut self, tile: usize) {
        ShaderCore::begin_shared_tile(self, tile)
    }
    #[inline]
    fn push_quad(&mut self, quad: u32, x: u32, y: u32) -> bool {
        ShaderCore::push_quad(self, quad, x, y)
    }
    #[inline]
    fn input_full(&self) -> bool {
        ShaderCore::input_full(self)
    }
    #[inline]
    fn quads_entered(&self) -> u32 {
        ShaderCore::quads_entered(self)
    }
    #[inline]
    fn drained(&self) -> bool {
        ShaderCore::drained(self)
    }
    fn end_shared_tile(&mut self) {
        ShaderCore::end_shared_tile(self)
    }
    #[inline]
    fn tile_misses(&self) -> u64 {
        ShaderCore::tile_misses(self)
    }
    #[inline]
    fn launched_now(&self) -> Option<(u32, bool)> {
        ShaderCore::launched_now(self)
    }
    #[inline]
    fn stats(&self) -> &CoreStats {
        ShaderCore::stats(self)
    }
    fn reset_stats(&mut self) {
        ShaderCore::reset_stats(self)
    }
    fn is_idle(&self, now: u64) -> bool {
        ShaderCore::is_idle(self, now)
    }
    #[inline(always)]
    fn evaluate(&mut self, now: u64, trace: &Trace, mem: &mut MemorySystem) -> bool {
        ShaderCore::evaluate(self, now, trace, mem)
    }
    #[inline(always)]
    fn complete(&mut self, now: u64, mem: &mut MemorySystem) -> Result<bool, SimError> {
        ShaderCore::complete(self, now, mem)
    }
    #[inline]
    fn end_cycle(&mut self) -> bool {
        ShaderCore::end_cycle(self)
    }
    fn describe(&self, trace: &Trace) -> String {
        ShaderCore::describe(self, trace)
    }
    fn record_warps(&mut self) {
        ShaderCore::record_warps(self)
    }
    fn take_records(&mut self) -> Vec<WarpRecord> {
        ShaderCore::take_records(self)
    }
    #[inline]
    fn active(&self) -> u32 {
        ShaderCore::active(self)
    }
    fn snapshot(&self) -> CoreSnapshot {
        ShaderCore::snapshot(self)
    }
}
