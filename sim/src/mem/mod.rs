//! Memory hierarchy of the GPU model: per-core L0 (optional, pipeline width 4)
//! and L1 texture caches, an L2 shared by all cores, and an open-row DRAM (or
//! an ideal zero-latency memory).
//!
//! All addresses are 64-byte block numbers (byte address / 64). The caches
//! are read-only (textures): no writes, no write-backs.
//!
//! # Use
//!
//! ```
//! use wasp_sim::mem::{Access, MemConfig, MemorySystem};
//! let mut mem = MemorySystem::new(&MemConfig::paper(false)).unwrap();
//! let mut done = Vec::new();
//! assert_eq!(mem.access(0, 0, 1234, 7), Access::Miss);
//! let mut now = 0;
//! while done.is_empty() {
//!     mem.tick(now);
//!     mem.take_completions(0, &mut done);
//!     now += 1;
//! }
//! // L1 (1) + L2 (18) + DRAM row miss (100) cycles, counting the access cycle.
//! assert_eq!((done, now - 1), (vec![7], 118));
//! ```
//!
//! # Cycle protocol
//!
//! In each cycle `now`: the cores call [`MemorySystem::access`], then the
//! owner calls [`MemorySystem::tick`] once, then reads miss events
//! (before completions), completions, MSHR events and traces. Within `tick` the order is fixed: L1s take L0 requests,
//! the L2 takes L1 requests (round robin over cores), the DRAM accepts
//! requests, then replies due in `now` fill the L2, the L1s and the L0s, and
//! tags due in `now` complete. Accesses to a level in a cycle are therefore
//! looked up before that cycle's fills of the level.
//!
//! # Timing model
//!
//! Every level has a latency `h` (the L0/L1 `hit_latency` of 1, the L2's 18,
//! the DRAM row-hit 50 / row-miss 100 cycles). Times below count the access
//! cycle `t` itself, so an access "taking n cycles" completes in cycle
//! `t + n - 1` and its warp can continue in `t + n`.
//!
//! - A hit takes `h` cycles (a 1-cycle L1 answers in the cycle of the access).
//! - A primary miss allocates an MSHR entry; its request is presented to the
//!   next level from the next cycle on, oldest first, retried every cycle
//!   while that level refuses it (the refusal is counted at that level).
//! - On the way back, the reply reaching a level in cycle `r` fills it at `r`
//!   (an access from `r + 1` hits), hands its targets on at `r`, and the data
//!   reaches the level above (or the core) after that level's `h`, i.e. in
//!   cycle `r + h - 1`. So each level's latency is paid once per access,
//!   whether it hits or misses there, and the forward hop is included in it.
//! - The DRAM answers a request accepted in cycle `p` in `p + L - 1`
//!   (`requests_per_cycle` accepted per cycle from a FIFO, from the cycle
//!   after the L2 miss): without FIFO wait, `L` cycles after the L2 miss.
//!
//! End to end, with the paper's parameters and no queueing:
//!
//! | access (width 2, no L0)      | cycles | completes at |
//! |------------------------------|--------|--------------|
//! | L1 hit                       | 1      | `t`          |
//! | L1 miss, L2 hit              | 19     | `t + 18`     |
//! | L2 miss, DRAM row hit        | 69     | `t + 68`     |
//! | L2 miss, DRAM row miss       | 119    | `t + 118`    |
//! | L2 miss, ideal memory        | 19     | `t + 18`     |
//!
//! With an L0 (width 4) an L0 hit takes 1 cycle and every other row takes one
//! more (the L0's cycle).
//!
//! # Cache stalls and MSHRs
//!
//! A cache whose MSHRs are all occupied accepts no access, hits included
//! (the paper's cache stall); the access returns [`Access::Stall`] and is
//! retried by the requester. A miss to a block with a pending MSHR entry is a
//! secondary miss and merges into it (up to `max_merged`; beyond, the access
//! is refused and counted in `merge_stalls`, not in `stall_cycles`). An entry
//! whose reply arrives in cycle `r` delivers all its targets at `r` and stays
//! occupied through `r + 1`: it can be allocated again from `r + 2`. This is
//! the rule under which the paper's worked example (Section III: 3 MSHRs,
//! memory latency 7, blocks A B C) takes 18 cycles in scanline order and 21
//! cycles with 6 stall cycles with the priority warps first; both are tests
//! here, at the cache level and through the whole hierarchy.
//!
//! The WaSP scheduler's 5-bit free-MSHR register counts an entry free from
//! its reply; [`MemorySystem::mshr_events`] gives it what it needs.
//!
//! # Miss events
//!
//! Which miss blocks a warp is the core's rule (`scheduler.blocked_on`).
//! For it the memory system reports, when [`MemConfig::report_misses`]
//! asks, what became of a core's requests at the next level
//! ([`MissEvent`], [`MemorySystem::take_miss_events`]): an L0 MSHR entry's
//! request that missed in the L1 (allocating an L1 entry or merging into
//! one), an L1 entry's request that missed in the L2. With the first-level
//! MSHR entry [`MemorySystem::access_entry`] gives for each access, that is
//! all a core needs to know which of its warps wait on a miss at which
//! level. The events change no timing.
//!
//! # Choices of wasp, not of the paper
//!
//! See [`MemConfig::paper`] for the defaults (MSHR counts, merge limits,
//! ports, L0 associativity, DRAM banks and rows). Further modelling choices:
//! allocate on fill with LRU replacement per set (a pending miss owns no way;
//! the fill evicts the LRU valid line whatever is pending); head-of-line
//! blocking in the request queue between two levels; the L2 arbitrates among
//! cores round robin, starting with core `now % cores`; main memory is
//! one of two models ([`dram`]): banked (channels, banks with busy time,
//! command timing, data buses; the shipped configs) or fixed (two latencies,
//! no bank busy time); in both a bank with no open row counts as a row miss;
//! ideal
//! memory answers L2 misses in the cycle of the miss with no bandwidth limit.

pub mod cache;
pub mod config;
pub mod dram;
pub mod hierarchy;
pub mod mshr;
pub mod prefetch;
mod ring;
pub mod stats;

pub use cache::{Cache, Lookup};
pub use config::{
    first_level, CacheConfig, DramConfig, DramModel, MemConfig, MemConfigError, BLOCK_BYTES,
};
pub use hierarchy::{Access, MemorySystem, MissEvent, MshrFileView, SchedCacheMshrs};
pub use mshr::MSHR_HOLD_CYCLES;
pub use prefetch::{PrefetchConfig, PrefetchKind, PrefetchStats};
pub use stats::{CacheStats, CoreMemStats, DramStats, MemStats};
