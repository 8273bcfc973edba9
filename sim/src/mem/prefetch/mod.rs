//! Texture prefetchers into the cores' L1s: the rivals and the bound of
//! WaSP's "launch early to prefetch" (issue 23), as machine options
//! (`[prefetch]` of the configuration, `prefetch.kind`).
//!
//! | kind | what it requests, and when | where from |
//! |---|---|---|
//! | `none` | nothing (the shipped machine) | |
//! | `oracle-tile` | when a tile opens, every distinct texture block the tile will touch, for each core that will touch it, in order of first use ([`oracle_tile`]) | the trace, read ahead: a bound, not a design |
//! | `raster` | when a quad enters a core's input FIFO, the blocks of its texture instructions, through a bounded queue ([`raster`]) | texture coordinates known at rasterization: Igehy, Eldridge and Proudfoot, "Prefetching in a Texture Cache Architecture" (HWWS 1998) |
//!
//! # What a prefetch does in the memory system (wasp's choices)
//!
//! Both kinds share one path, set out here and in [`queue`]:
//!
//! - Each core has one prefetch queue ([`PrefetchQueue`]) in front of its
//!   L1. The kind decides what enters it; the raster kind's queue holds
//!   `prefetch.queue` block addresses and drops a request that finds it
//!   full (counted), and with `prefetch.queue_filter` skips a block already
//!   queued (gem5's queued prefetcher: "Don't queue redundant prefetches",
//!   32 entries by default). The oracle's queue holds a tile's whole list.
//! - Prefetches enter the L1 *below demand*: demand requests (the L0's
//!   misses at width 4, the LDST unit's accesses at width 2) take the L1's
//!   ports first in every cycle; the queue's head is looked up only on a
//!   port they left free, at most one lookup a free port.
//! - The head is looked up only while more than `prefetch.l1_reserve` of
//!   the L1's MSHRs are free (gem5's `demand_mshr_reserve`, "MSHRs reserved
//!   for demand access", which gem5's cache checks before it pulls a
//!   prefetch from its queue); otherwise it waits. A lookup that hits, or
//!   finds a miss already pending for the block, drops the prefetch. A
//!   miss allocates an L1 MSHR entry with no target (its fill completes
//!   nothing) and travels to the L2 and DRAM like a demand miss: the L1's
//!   request queue, the L2's ports, MSHRs and merging, the DRAM's banks and
//!   buses. The line fills the L1 only (the L0 is not touched).
//! - A later demand miss to a block whose prefetch is in flight merges into
//!   that entry (a secondary miss): the *late* prefetch. Every L1 line a
//!   prefetch filled carries a "prefetched, not yet used" bit
//!   (`marks.rs`): the first demand hit clears it (the prefetch was
//!   *useful*), an eviction with the bit set counts the prefetch *useless*.
//!
//! # The MSHRs each kind uses, and WaSP's register
//!
//! Prefetches hold L1 MSHR entries, at most `l1.mshrs - l1_reserve` of
//! them: the L1's MSHRs are what a miss leaving the core needs, demand or
//! prefetch. At width 4 WaSP's free-MSHR register watches the L0, which
//! prefetches never touch: it sees the prefetches only through the L0
//! misses that wait longer for an L1 MSHR. At width 2 (no L0) the register
//! watches the L1 itself, so prefetch entries are MSHRs it counts as
//! occupied: prefetching closes WaSP's gate earlier. Both are what the
//! hardware would see (a 5-bit count of free entries cannot tell demand
//! from prefetch entries); `docs/machine.md` ("Prefetchers") says more.
//!
//! # What the trace must say
//!
//! A prefetcher that requests a texture block before the shader runs needs
//! the block's address before the shader runs: the texture coordinates
//! must be interpolated attributes, not computed in the shader (a
//! *dependent* texture read cannot be prefetched this way). The trace
//! format marks no dependent read; the front end samples every texture at
//! interpolated UVs, so every texture instruction of its traces is
//! prefetchable, and the model assumes the same of every trace
//! (`tests/traces/FORMAT.md`).

pub mod cost;
pub(crate) mod marks;
pub mod oracle_tile;
pub mod queue;
pub mod raster;

pub use marks::MarkCounts;
pub use queue::{PrefetchQueue, QueueCounts};

pub use super::config::{PrefetchConfig, PrefetchKind, MAX_QUEUE};
use crate::trace::{Tile, Trace};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::ops::Range;

/// What the L1 did with a prefetch presented to it
/// ([`Cache::prefetch`](super::Cache::prefetch)).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PrefetchLookup {
    /// Every port was used this cycle (by demand first): not looked up.
    PortBusy,
    /// At most `l1_reserve` MSHRs free: not looked up, wait.
    NoRoom,
    /// The line is present: the prefetch is dropped.
    Hit,
    /// A miss is pending for the block: the prefetch is dropped.
    Pending,
    /// Allocated this MSHR entry (no target): request the block below.
    Miss(u32),
}

/// Where a prefetcher puts its requests: the per-core prefetch queues
/// (the memory system keeps them, in front of each L1).
pub trait PrefetchQueues {
    /// Core `core`'s queue.
    fn prefetch_queue(&mut self, core: usize) -> &mut PrefetchQueue;
}

/// A prefetcher: what it requests when a tile opens and when a quad
/// enters an input FIFO. Its requests go to the per-core queues, which
/// the memory system serves (the module documentation).
pub trait Prefetcher: fmt::Debug {
    /// The kind.
    fn kind(&self) -> PrefetchKind;

    /// Tile `tile` (its index in the trace) opens: under shared-tile
    /// dispatch for every core (`core` is `None`: the tile fetcher opened
    /// it), under per-core-tile dispatch for the core that took it.
    fn tile_opened(&mut self, tile: usize, core: Option<usize>, queues: &mut dyn PrefetchQueues);

    /// Whether [`quad_entered`](Self::quad_entered) does anything: the GPU
    /// skips the calls otherwise.
    fn watches_quads(&self) -> bool;

    /// Quad `quad` (its index in rasterization order) of `tile` entered
    /// core `core`'s input FIFO.
    fn quad_entered(
        &mut self,
        tile: &Tile,
        quad: usize,
        core: usize,
        queues: &mut dyn PrefetchQueues,
    );
}

/// Quads `quads` (indices in rasterization order) of `tile` entered the
/// input FIFOs, quad (x, y) that of core `core_of(x, y)`: tell `pf`, if
/// it watches quads.
pub fn quads_entered(
    pf: &mut dyn Prefetcher,
    tile: &Tile,
    quads: Range<u32>,
    core_of: impl Fn(u32, u32) -> usize,
    queues: &mut dyn PrefetchQueues,
) {
    if !pf.watches_quads() {
        return;
    }
    for i in quads {
        let q = tile.quad(i as usize).expect("quad in tile");
        pf.quad_entered(tile, i as usize, core_of(q.x(), q.y()), queues);
    }
}

/// The prefetcher of `cfg` for `trace` on `cores` cores, or `None` for
/// `none`. `core_of(x, y)` names the core of in-tile quad (x, y) under
/// shared-tile dispatch; `None` under per-core-tile dispatch (the core
/// that takes a tile shades all of it).
pub fn build(
    cfg: &PrefetchConfig,
    trace: &Trace,
    cores: usize,
    core_of: Option<&dyn Fn(u32, u32) -> usize>,
) -> Option<Box<dyn Prefetcher>> {
    match cfg.kind {
        PrefetchKind::None => None,
        PrefetchKind::OracleTile => Some(Box::new(oracle_tile::OracleTile::new(
            trace, cores, core_of,
        ))),
        PrefetchKind::Raster => Some(Box::new(raster::RasterPrefetcher)),
    }
}

/// A run's prefetch counters, summed over the cores.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct PrefetchStats {
    /// The queues' counters.
    pub queue: QueueCounts,
    /// The L1s' counters of prefetched lines.
    pub lines: MarkCounts,
    /// Lines still marked "prefetched, not yet used" at the end.
    pub unused_at_end: u64,
}

impl PrefetchStats {
    /// The counters since `before`, an earlier reading (`unused_at_end`
    /// is this reading's: lines unused now).
    pub fn since(&self, before: &PrefetchStats) -> PrefetchStats {
        PrefetchStats {
            queue: self.queue.since(&before.queue),
            lines: self.lines.since(&before.lines),
            unused_at_end: self.unused_at_end,
        }
    }

    /// Add `o` into `self`.
    pub fn add(&mut self, o: &PrefetchStats) {
        self.queue.add(&o.queue);
        self.lines.add(&o.lines);
        self.unused_at_end += o.unused_at_end;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kinds_parse_and_print() {
        for k in PrefetchKind::ALL {
            assert_eq!(k.to_string().parse::<PrefetchKind>(), Ok(k));
        }
        let e = "oracle".parse::<PrefetchKind>().unwrap_err();
        assert!(e.contains("none, oracle-tile or raster"), "{e}");
    }

    #[test]
    fn bounds_name_the_field() {
        let mut c = PrefetchConfig::default();
        c.check(16).unwrap();
        c.queue = 0;
        let e = c.check(16).unwrap_err();
        assert!(e.contains("prefetch.queue = 0: must be in 1..=1024"), "{e}");
        c.queue = 1025;
        assert!(c.check(16).is_err());
        c.queue = 32;
        // Off, a reserve above the L1's MSHRs is allowed (a sweep of
        // l1.mshrs must not trip on it) ...
        c.l1_reserve = 20;
        c.check(16).unwrap();
        c.l1_reserve = 4096;
        assert!(c.check(16).is_err());
        // ... on, it must leave a prefetch an MSHR.
        c.kind = PrefetchKind::Raster;
        c.l1_reserve = 16;
        let e = c.check(16).unwrap_err();
        assert!(
            e.contains("prefetch.l1_reserve = 16: must be in 0..=15"),
            "{e}"
        );
        c.l1_reserve = 15;
        c.check(16).unwrap();
    }
}
