//! What the memory hierarchy answers a core: the fate of an access it
//! presents ([`Access`]), the MSHR counts of its scheduler-level cache that
//! the WaSP scheduler's free-MSHR register sees ([`SchedCacheMshrs`]), and
//! the miss events that tell which of its warps wait at which level
//! ([`MissEvent`]).

#[cfg(doc)]
use super::MemorySystem;
#[cfg(doc)]
use crate::mem::config::MemConfig;

/// What happened to one access presented by a core.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Access {
    /// Hit in the core's first level; completes after its hit latency.
    Hit,
    /// Primary miss: an MSHR entry was allocated, the block is requested
    /// below; completes when the fill arrives.
    Miss,
    /// Merged into the MSHR entry of an earlier miss to the same block;
    /// completes with that entry's fill.
    SecondaryMiss,
    /// Refused, retry later: every MSHR of the first level is occupied (cache
    /// stall; counted in `stall_cycles`), or the block's MSHR entry cannot
    /// merge another target (counted in `merge_stalls`).
    Stall,
    /// Refused, retry later: every port of the first level was used this cycle.
    PortBusy,
}

impl Access {
    /// The access was taken and its tag will be returned exactly once by
    /// [`MemorySystem::take_completions`]; otherwise it must be retried.
    #[inline]
    pub fn accepted(self) -> bool {
        matches!(self, Access::Hit | Access::Miss | Access::SecondaryMiss)
    }
}

/// What the WaSP scheduler's free-MSHR register sees of the scheduler-level
/// cache (L0 when present, else L1) of one core, for the last cycle given to
/// [`MemorySystem::access`] or [`MemorySystem::tick`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SchedCacheMshrs {
    /// MSHR entries of the cache.
    pub capacity: u32,
    /// Entries allocated (primary misses) in this cycle.
    pub allocated: u32,
    /// Entries whose reply (fill) arrived in this cycle.
    pub replied: u32,
    /// Entries occupied as the cache sees them: awaiting a reply, or in the
    /// cycle after their reply. The cache stalls when this equals `capacity`.
    pub occupied: u32,
    /// Entries awaiting their reply (outstanding misses).
    pub outstanding: u32,
}

impl SchedCacheMshrs {
    /// Free entries as the scheduler's register counts them (an entry is free
    /// from its reply): `capacity - outstanding`.
    #[inline]
    pub fn free_from_reply(&self) -> u32 {
        self.capacity - self.outstanding
    }

    /// Free entries as the cache sees them: `capacity - occupied`.
    #[inline]
    pub fn free(&self) -> u32 {
        self.capacity - self.occupied
    }
}

/// What became of the request of one of a core's MSHR entries at the next
/// level, when it missed there: the events a core needs to know which of
/// its warps wait on a miss at which level (its rule of which miss blocks
/// a warp, `scheduler.blocked_on`). Reported only when
/// [`MemConfig::report_misses`] asks, in the order they happen, by
/// [`MemorySystem::take_miss_events`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MissEvent {
    /// The request of L0 MSHR entry `l0` missed in the L1: it allocated L1
    /// MSHR entry `l1` (`merged` false) or merged into it.
    L1 {
        /// The L0 entry.
        l0: u32,
        /// The L1 entry it allocated or merged into.
        l1: u32,
        /// It merged into a pending entry.
        merged: bool,
    },
    /// The request of L1 MSHR entry `l1` missed in the L2 (allocating an
    /// L2 entry or merging into one).
    L2 {
        /// The L1 entry.
        l1: u32,
    },
    /// A prefetch allocated L1 MSHR entry `l1`: no access waits on it yet.
    Prefetch {
        /// The L1 entry.
        l1: u32,
    },
}
