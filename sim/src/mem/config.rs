//! Configuration of the memory hierarchy, its defaults (the paper's Table II
//! plus wasp's stated choices) and the structural checks that
//! [`MemorySystem::new`](super::MemorySystem::new) applies.
//!
//! The defaults have one source, `configs/paper.toml` (embedded as
//! [`PAPER_TOML`]): [`MemConfig::paper`],
//! [`DramConfig::default`] and [`PrefetchConfig::default`] read its
//! sections. The file, not a default written beside each field, because it
//! is what users read and copy, it gives every value with its source (paper
//! or wasp), and one struct has a different default in each section it
//! serves (`[l0]`, `[l1]` and `[l2]` are all [`CacheConfig`]s).

use crate::param::{check_range, section, PAPER_TOML};
use serde::{Deserialize, Serialize};
use std::fmt;
use std::sync::OnceLock;

/// Bytes in one memory block. Every address in the memory system is a block
/// number (byte address / 64), and every cache line is one block.
pub const BLOCK_BYTES: u32 = 64;

/// The first level of a core's texture caches, with its section name: the
/// L0 when the core has one, else the L1. Core requests enter it, a
/// `first-level` miss is a miss in it, and the scheduler's free-MSHR register
/// watches its MSHRs. The one place this rule is written: every caller passes
/// its own view of the two levels (configurations, caches, MSHR counts).
#[inline(always)]
pub fn first_level<T>(l0: Option<T>, l1: T) -> (&'static str, T) {
    match l0 {
        Some(l0) => ("l0", l0),
        None => ("l1", l1),
    }
}

/// Upper bound on `mshrs * (1 + max_merged)` for one cache, so that an absurd
/// configuration is refused instead of allocating gigabytes.
const MAX_TARGET_SLOTS: u64 = 1 << 22;

/// Upper bounds of the numeric fields of the memory configuration: what
/// makes sense for a mobile GPU's memory system, generous enough for
/// sweeps, small enough that memory and run time stay bounded (the table in
/// docs/machine.md, "Configuration bounds", lists them with the rest).
pub mod bounds {
    /// Per-core L0 capacity (the paper's is 0.5 KiB): 1 MiB.
    pub const L0_MAX_BYTES: u32 = 1 << 20;
    /// Per-core L1 capacity (the paper's is 64 KiB): 16 MiB.
    pub const L1_MAX_BYTES: u32 = 16 << 20;
    /// Shared L2 capacity (the paper's is 1 MiB): 256 MiB.
    pub const L2_MAX_BYTES: u32 = 256 << 20;
    /// Associativity (a set is searched way by way).
    pub const MAX_WAYS: u32 = 64;
    /// Cache hit latency, DRAM fixed-model latencies and other stage
    /// latencies, in cycles.
    pub const MAX_LATENCY: u32 = 10_000;
    /// MSHRs of one cache.
    pub const MAX_MSHRS: u32 = 4096;
    /// Secondary misses merged into one MSHR entry.
    pub const MAX_MERGED: u32 = 1024;
    /// Ports of one cache.
    pub const MAX_PORTS: u32 = 64;
    /// DRAM channels.
    pub const MAX_CHANNELS: u32 = 16;
    /// DRAM banks (per channel in the banked model; LPDDR4 has 8, DDR5 32).
    pub const MAX_BANKS: u32 = 64;
    /// DRAM row (page) size in bytes (LPDDR4 x16: 2 KiB): 64 KiB.
    pub const MAX_ROW_BYTES: u32 = 64 << 10;
    /// Fixed-model DRAM requests accepted per cycle.
    pub const MAX_REQUESTS_PER_CYCLE: u32 = 64;
    /// Banked-model timing fields (`t_*`), GPU cycles.
    pub const MAX_DRAM_TIMING: u32 = 1000;
    /// Banked-model `controller_latency`, GPU cycles.
    pub const MAX_CONTROLLER_LATENCY: u32 = 10_000;
    /// Banked-model `scheduler_window`.
    pub const MAX_SCHEDULER_WINDOW: u32 = 256;
    /// Host memory the memory system may allocate for its cache arrays,
    /// MSHR target lists and completion queues, over all cores: 1 GiB
    /// (estimated by [`MemConfig::host_bytes`](super::MemConfig::host_bytes)).
    pub const HOST_BYTES_BUDGET: u64 = 1 << 30;
    /// Largest `prefetch.l1_reserve`: below the most MSHRs an L1 can have.
    pub const MAX_L1_RESERVE: u32 = MAX_MSHRS - 1;
    /// The largest `size_bytes` of the cache level `name` (`l0`, `l1`,
    /// otherwise the L2's).
    pub fn max_size_bytes(name: &str) -> u32 {
        match name {
            "l0" => L0_MAX_BYTES,
            "l1" => L1_MAX_BYTES,
            _ => L2_MAX_BYTES,
        }
    }

    /// The bound of `size_bytes` in the section it is read for
    /// ([`max_size_bytes`]), whose error also gives it in MiB.
    pub struct LevelBytes;

    impl crate::param::Limit<u32> for LevelBytes {
        fn at(&self, section: &str) -> u32 {
            max_size_bytes(section)
        }

        fn note(&self, section: &str) -> String {
            let max = max_size_bytes(section);
            format!(" ({} MiB at most)", max as f64 / (1u32 << 20) as f64)
        }
    }
}
use bounds::*;

section! {
    /// One cache level.
    ///
    /// All caches are read-only (texture data), allocate on fill, LRU per set.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
    pub struct CacheConfig {
        /// Capacity in bytes; must be a multiple of `line_bytes * ways`. Its
        /// bound depends on the level ([`bounds::max_size_bytes`]).
        #[range(BLOCK_BYTES..=LevelBytes)]
        pub size_bytes: u32,
        /// Associativity. `ways == size_bytes / line_bytes` is fully
        /// associative. The number of sets must be a power of two.
        #[range(1..=MAX_WAYS)]
        pub ways: u32,
        /// Line size in bytes; must be [`BLOCK_BYTES`] (64).
        #[bound(BLOCK_BYTES..=BLOCK_BYTES, "the memory system's block")]
        pub line_bytes: u32,
        /// Latency in cycles, at least 1. A hit accepted in cycle `t`
        /// completes in cycle `t + hit_latency - 1` (a 1-cycle cache answers
        /// in the cycle of the access). On a miss the same latency is paid on
        /// the way back, between the fill arriving from below and the data
        /// leaving upwards.
        #[range(1..=MAX_LATENCY, " cycles")]
        pub hit_latency: u32,
        /// Miss Status Holding Registers: outstanding primary misses. When all
        /// are occupied the cache accepts no access at all (cache stall).
        #[range(1..=MAX_MSHRS)]
        pub mshrs: u32,
        /// Secondary misses that can merge into one MSHR entry (the entry
        /// holds `1 + max_merged` targets: the primary miss and up to
        /// `max_merged` secondary ones). A further secondary miss is refused
        /// (a merge stall).
        #[range(0..=MAX_MERGED)]
        pub max_merged: u32,
        /// Accesses accepted per cycle from the level above (or from the
        /// core).
        #[range(1..=MAX_PORTS)]
        pub ports: u32,
    }
}

/// Which main-memory model [`Dram`](super::dram::Dram) runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum DramModel {
    /// Open-row latency (`row_hit_latency` / `row_miss_latency`) plus
    /// `requests_per_cycle` acceptances a cycle; no bank busy time, no
    /// data-bus limit. The default.
    #[default]
    Fixed,
    /// Banks with row buffers and ACTIVATE / PRECHARGE / READ / WRITE timing
    /// (`t_rcd`, `t_rp`, `t_ras`, `t_cl`), one shared data bus (`t_burst`
    /// cycles a line), one command a cycle chosen FR-FCFS-lite from the
    /// oldest `scheduler_window` requests, plus `controller_latency`.
    Banked,
}

section! {
    /// Main memory: an open-row DRAM, with a fixed-latency or a banked timing
    /// model (`model`).
    ///
    /// In the fixed model a block maps to bank `block % banks` (interleaving
    /// on the low block address bits) and, inside that bank, to row
    /// `(block / banks) / (row_bytes / 64)`. The banked model first takes the
    /// channel `block % channels`, then does the same with `block / channels`
    /// inside the channel. A request whose row is the bank's open row is a
    /// row hit; any other request (including the first one to a bank) is a
    /// row miss and opens its row.
    ///
    /// Every field is checked whatever the model; `row_hit_latency`,
    /// `row_miss_latency` and `requests_per_cycle` are used only by the fixed
    /// model, the `channels`, `t_*`, `controller_latency` and
    /// `scheduler_window` fields only by the banked one. The banked timings
    /// are in GPU cycles (the memory configuration does not see
    /// `gpu.frequency_mhz`; the shipped configs give the conversion from
    /// nanoseconds).
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
    pub struct DramConfig {
        /// Timing model: `"fixed"` or `"banked"`.
        pub model: DramModel,
        /// Banked model: independent channels, each with `banks` banks, its
        /// own command bus and its own data bus; blocks interleave over
        /// channels on the lowest block-address bits.
        #[range(1..=MAX_CHANNELS)]
        pub channels: u32,
        /// Number of banks (per channel in the banked model).
        #[range(1..=MAX_BANKS)]
        pub banks: u32,
        /// Bytes in one row of one bank; a multiple of 64.
        #[range(BLOCK_BYTES..=MAX_ROW_BYTES)]
        pub row_bytes: u32,
        /// Fixed model: latency of a row hit in cycles (see the module docs
        /// for how it adds to the end-to-end latency).
        #[range(1..=MAX_LATENCY)]
        pub row_hit_latency: u32,
        /// Fixed model: latency of a row miss in cycles.
        #[range(1..=MAX_LATENCY)]
        pub row_miss_latency: u32,
        /// Fixed model: requests accepted per cycle; the others wait in the
        /// DRAM FIFO.
        #[range(1..=MAX_REQUESTS_PER_CYCLE)]
        pub requests_per_cycle: u32,
        /// Banked model: ACTIVATE to READ/WRITE of the opened row (tRCD), in
        /// GPU cycles.
        #[range(1..=MAX_DRAM_TIMING)]
        pub t_rcd: u32,
        /// Banked model: PRECHARGE to the next ACTIVATE of the bank (tRP), in
        /// GPU cycles.
        #[range(1..=MAX_DRAM_TIMING)]
        pub t_rp: u32,
        /// Banked model: ACTIVATE to PRECHARGE of the same bank (tRAS, the
        /// least time a row stays open), in GPU cycles.
        #[range(0..=MAX_DRAM_TIMING)]
        pub t_ras: u32,
        /// Banked model: READ (or WRITE) command to the first data on the bus
        /// (CAS / read latency), in GPU cycles.
        #[range(1..=MAX_DRAM_TIMING)]
        pub t_cl: u32,
        /// Banked model: cycles one 64-byte line occupies the shared data
        /// bus; also the bank's column-command spacing (tCCD) and
        /// read-to-precharge time. Sets the bandwidth: one line per
        /// `t_burst` cycles.
        #[range(1..=MAX_DRAM_TIMING)]
        pub t_burst: u32,
        /// Banked model: fixed controller and interface latency added to
        /// every read reply after its last data beat, in GPU cycles (may be
        /// 0).
        #[range(0..=MAX_CONTROLLER_LATENCY)]
        pub controller_latency: u32,
        /// Banked model: requests at the head of the FIFO the controller's
        /// scheduler may pick from (its transaction queue).
        #[range(1..=MAX_SCHEDULER_WINDOW)]
        pub scheduler_window: u32,
    }
}

impl Default for DramConfig {
    /// The shipped configuration's DRAM values (`configs/paper.toml`: four
    /// x16 LPDDR4-3200 channels with their timings at 600 MHz, and the
    /// paper's 50 / 100 cycles for the fixed model; see the config file for
    /// the sources), but with the **fixed** model selected, whose exact
    /// latencies the memory unit tests rely on. The shipped config selects
    /// the banked model.
    fn default() -> Self {
        DramConfig {
            model: DramModel::Fixed,
            ..paper_memory().dram
        }
    }
}

/// The memory system's sections of `configs/paper.toml`.
#[derive(Deserialize)]
struct PaperMemory {
    gpu: PaperGpu,
    l0: CacheConfig,
    l1: CacheConfig,
    l2: CacheConfig,
    dram: DramConfig,
    memory: PaperIdeal,
    prefetch: PrefetchConfig,
}

/// The keys of `[gpu]` and `[memory]` the memory system reads.
#[derive(Deserialize)]
struct PaperGpu {
    cores: u32,
}

/// `memory.ideal`.
#[derive(Deserialize)]
struct PaperIdeal {
    ideal: bool,
}

/// The memory sections of the shipped machine, read once.
fn paper_memory() -> &'static PaperMemory {
    static PAPER: OnceLock<PaperMemory> = OnceLock::new();
    PAPER.get_or_init(|| toml::from_str(PAPER_TOML).expect("configs/paper.toml is valid"))
}

/// The whole memory hierarchy.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct MemConfig {
    /// GPU cores (each has its own L0 and L1 texture caches), at least 1.
    pub cores: u32,
    /// Per-core L0 texture cache, present at pipeline width 4.
    pub l0: Option<CacheConfig>,
    /// Per-core L1 texture cache.
    pub l1: CacheConfig,
    /// L2 shared by all cores.
    pub l2: CacheConfig,
    /// Main memory.
    pub dram: DramConfig,
    /// Ideal main memory: every L2 miss is answered with zero latency (in the
    /// cycle of the miss, so an L2 miss costs exactly what an L2 hit costs) and
    /// without bandwidth limit. The `dram` parameters are still validated but
    /// otherwise unused. Used for the paper's motivation figure.
    pub ideal_memory: bool,
    /// Record the [`MissEvent`](super::MissEvent)s that the cores' rule of
    /// which miss blocks a warp reads
    /// ([`MemorySystem::take_miss_events`](super::MemorySystem::take_miss_events)).
    /// Changes no timing.
    pub report_misses: bool,
    /// The prefetcher into the L1s (`none` by default).
    #[serde(default)]
    pub prefetch: PrefetchConfig,
}

impl MemConfig {
    /// The memory system of `configs/paper.toml` (the paper's Table II,
    /// with wasp's choices where the paper is silent; the file gives each
    /// value's source): 4 cores, each with a 64 KiB 4-way L1 and, when
    /// `width4`, a 0.5 KiB two-port L0; a 1 MiB 8-way L2 of 18 cycles.
    /// Unlike the file, the DRAM runs the fixed model
    /// ([`DramConfig::default`]), and miss events are recorded.
    pub fn paper(width4: bool) -> Self {
        let p = paper_memory();
        MemConfig {
            cores: p.gpu.cores,
            l0: width4.then_some(p.l0),
            l1: p.l1,
            l2: p.l2,
            dram: DramConfig::default(),
            ideal_memory: p.memory.ideal,
            report_misses: true,
            prefetch: p.prefetch,
        }
    }

    /// The cache the warp scheduler watches ([`first_level`]).
    pub fn scheduler_level(&self) -> &CacheConfig {
        first_level(self.l0.as_ref(), &self.l1).1
    }

    /// Structural checks: every value the memory system cannot model is
    /// refused with a message naming the field.
    pub fn check(&self) -> Result<(), MemConfigError> {
        if self.cores == 0 {
            return Err(MemConfigError::new("cores must be at least 1"));
        }
        if let Some(l0) = &self.l0 {
            l0.check("l0")?;
        }
        self.l1.check("l1")?;
        self.l2.check("l2")?;
        self.dram.check()?;
        self.prefetch.check(self.l1.mshrs).map_err(MemConfigError)?;
        let bytes = self.host_bytes();
        if bytes > HOST_BYTES_BUDGET {
            return Err(MemConfigError(format!(
                "the memory system of gpu.cores = {} would allocate about {} MiB for its cache arrays \
                 (l0/l1/l2.size_bytes), MSHR targets (mshrs x (1 + max_merged)) and completion queues \
                 (ports x hit_latency of the {} cache), more than the budget of {} MiB",
                self.cores,
                bytes >> 20,
                first_level(self.l0.as_ref(), &self.l1).0,
                HOST_BYTES_BUDGET >> 20
            )));
        }
        Ok(())
    }

    /// An estimate of the host memory the memory system allocates: per
    /// cache 16 bytes a line (tag and recency links), 12 a set (its recency
    /// order), 64 an MSHR entry, 4 an MSHR target and 4 KiB of fixed
    /// filters; per core three completion queues of the scheduler-level
    /// cache's `ports x hit_latency + mshrs x (1 + max_merged)` entries
    /// (rounded up to a power of two) of 8 bytes. Valid after the per-cache
    /// checks (bounded fields, so no overflow).
    pub fn host_bytes(&self) -> u64 {
        let cache = |c: &CacheConfig| {
            let sets = c.lines() / u64::from(c.ways.max(1));
            16 * c.lines() + 12 * sets + 64 * u64::from(c.mshrs) + 4 * c.target_slots() + 4096
        };
        let first = self.scheduler_level();
        let completing = (u64::from(first.ports) * u64::from(first.hit_latency)
            + first.target_slots())
        .next_power_of_two();
        let per_core = self.l0.as_ref().map_or(0, cache) + cache(&self.l1) + 3 * 8 * completing;
        u64::from(self.cores)
            .saturating_mul(per_core)
            .saturating_add(cache(&self.l2))
    }
}

impl CacheConfig {
    /// Number of sets (valid only after [`CacheConfig::check`]).
    pub fn sets(&self) -> u32 {
        self.size_bytes / self.line_bytes / self.ways
    }

    /// The declared bounds and the structural checks; `name` (`l0`, `l1`,
    /// `l2`) prefixes the field in the error message (`l1.ways = 0: must be
    /// in 1..=64`).
    pub fn check(&self, name: &str) -> Result<(), MemConfigError> {
        let err = |msg: String| Err(MemConfigError(format!("{name}: {msg}")));
        if self.line_bytes != BLOCK_BYTES {
            return err(format!(
                "line_bytes is {} but the memory system uses {BLOCK_BYTES}-byte blocks",
                self.line_bytes
            ));
        }
        self.check_bounds(name).map_err(MemConfigError)?;
        if !self.size_bytes.is_multiple_of(self.line_bytes) {
            return err(format!(
                "size_bytes {} is not a multiple of line_bytes {}",
                self.size_bytes, self.line_bytes
            ));
        }
        let lines = self.size_bytes / self.line_bytes;
        if self.ways > lines {
            return err(format!("ways {} exceeds the {lines} lines", self.ways));
        }
        if !lines.is_multiple_of(self.ways) {
            return err(format!(
                "{lines} lines do not divide into {} ways",
                self.ways
            ));
        }
        let sets = lines / self.ways;
        if !sets.is_power_of_two() {
            return err(format!("set count {sets} is not a power of two"));
        }
        let slots = self.target_slots();
        if slots > MAX_TARGET_SLOTS {
            return err(format!(
                "mshrs x (1 + max_merged) = {slots} is more than the supported {MAX_TARGET_SLOTS}"
            ));
        }
        Ok(())
    }

    /// Lines of the cache.
    fn lines(&self) -> u64 {
        u64::from(self.size_bytes / self.line_bytes.max(1))
    }

    /// Targets the MSHR file holds: `mshrs x (1 + max_merged)`.
    fn target_slots(&self) -> u64 {
        u64::from(self.mshrs) * (1 + u64::from(self.max_merged))
    }
}

impl DramConfig {
    /// The declared bounds and the structural checks, each error naming
    /// the field (`dram.banks = 0: must be in 1..=64`).
    pub fn check(&self) -> Result<(), MemConfigError> {
        if self.row_hit_latency == 0 || self.row_miss_latency == 0 {
            return Err(MemConfigError(
                "dram: row_hit_latency and row_miss_latency must be at least 1 \
                 (use ideal_memory for a zero-latency memory)"
                    .into(),
            ));
        }
        self.check_bounds("dram").map_err(MemConfigError)?;
        if !self.row_bytes.is_multiple_of(BLOCK_BYTES) {
            return Err(MemConfigError(format!(
                "dram.row_bytes = {}: must be a multiple of {BLOCK_BYTES}",
                self.row_bytes
            )));
        }
        Ok(())
    }
}

/// Most entries of a raster prefetch queue.
pub const MAX_QUEUE: u32 = 1024;

/// Which prefetcher the machine has (`prefetch.kind`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PrefetchKind {
    /// No prefetcher (the shipped machine).
    #[default]
    None,
    /// The bound: a tile's blocks requested when it opens.
    OracleTile,
    /// Each quad's blocks requested when it enters an input FIFO.
    Raster,
}

impl PrefetchKind {
    /// Every kind.
    pub const ALL: [PrefetchKind; 3] = [
        PrefetchKind::None,
        PrefetchKind::OracleTile,
        PrefetchKind::Raster,
    ];
}

impl fmt::Display for PrefetchKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            PrefetchKind::None => "none",
            PrefetchKind::OracleTile => "oracle-tile",
            PrefetchKind::Raster => "raster",
        })
    }
}

impl std::str::FromStr for PrefetchKind {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        PrefetchKind::ALL
            .into_iter()
            .find(|k| k.to_string() == s)
            .ok_or_else(|| {
                format!("unknown prefetch kind {s:?}: expected none, oracle-tile or raster")
            })
    }
}

section! {
    /// The `[prefetch]` section: the prefetcher and the limits every kind
    /// obeys (see [`prefetch`](super::prefetch)).
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
    pub struct PrefetchConfig {
        /// `none` (default), `oracle-tile` or `raster`.
        pub kind: PrefetchKind,
        /// Entries of each core's raster prefetch queue (block addresses).
        /// The oracle's queue holds a tile's list whatever this is.
        #[range(1..=MAX_QUEUE, " entries")]
        pub queue: u32,
        /// Skip a request for a block already in the queue (the raster
        /// kind; the oracle's lists hold each block once anyway).
        pub queue_filter: bool,
        /// L1 MSHRs kept free for demand misses: a prefetch is looked up
        /// only while more than this many are free. Below `l1.mshrs` when a
        /// prefetcher is on ([`PrefetchConfig::check`]).
        #[bound(0..=MAX_L1_RESERVE, "below l1.mshrs with a prefetcher")]
        pub l1_reserve: u32,
    }
}

impl Default for PrefetchConfig {
    /// The `[prefetch]` section of `configs/paper.toml` (which says why):
    /// `none`, with the shipped limits.
    fn default() -> Self {
        paper_memory().prefetch
    }
}

impl PrefetchConfig {
    /// Whether a prefetcher is on.
    #[inline]
    pub fn enabled(&self) -> bool {
        self.kind != PrefetchKind::None
    }

    /// Bounds, each error naming the field: the declared ones (`queue` in
    /// 1..=1024); `l1_reserve` below `l1_mshrs` when a prefetcher is on (a
    /// prefetch needs one MSHR), else below the MSHR bound.
    pub fn check(&self, l1_mshrs: u32) -> Result<(), String> {
        self.check_bounds("prefetch")?;
        if self.enabled() {
            check_range(
                "prefetch.l1_reserve",
                self.l1_reserve.into(),
                0,
                u64::from(l1_mshrs) - 1,
                &format!(
                    " (below l1.mshrs = {l1_mshrs}: prefetch.kind = {} needs an L1 MSHR the reserve leaves free)",
                    self.kind
                ),
            )
        } else {
            check_range(
                "prefetch.l1_reserve",
                self.l1_reserve.into(),
                0,
                MAX_L1_RESERVE.into(),
                "",
            )
        }
    }
}

/// A configuration the memory system cannot model; the message names the
/// offending field.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MemConfigError(pub String);

impl MemConfigError {
    fn new(msg: &str) -> Self {
        MemConfigError(msg.to_string())
    }
}

impl fmt::Display for MemConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "invalid memory configuration: {}", self.0)
    }
}

impl std::error::Error for MemConfigError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paper_defaults_are_valid_and_match_table_ii() {
        for width4 in [false, true] {
            let c = MemConfig::paper(width4);
            c.check().unwrap();
            assert_eq!(c.l0.is_some(), width4);
            assert_eq!(c.cores, 4);
            assert_eq!(
                (c.l1.size_bytes, c.l1.ways, c.l1.line_bytes),
                (65536, 4, 64)
            );
            assert_eq!(c.l1.hit_latency, 1);
            assert_eq!(
                (c.l2.size_bytes, c.l2.ways, c.l2.hit_latency),
                (1 << 20, 8, 18)
            );
            assert!(c.dram.row_hit_latency >= 50 && c.dram.row_miss_latency <= 100);
            assert!(c.scheduler_level().mshrs <= wasp_rtl::free_mshr::FREE_MSHR_MAX);
        }
        let l0 = MemConfig::paper(true).l0.unwrap();
        assert_eq!((l0.size_bytes, l0.ports), (512, 2));
        assert_eq!(l0.sets(), 1);
        assert_eq!(MemConfig::paper(false).l1.sets(), 256);
    }

    #[test]
    fn impossible_values_are_refused_with_a_message() {
        let good = MemConfig::paper(true);
        type Mutate = fn(&mut MemConfig);
        let cases: Vec<(&str, Mutate)> = vec![
            ("cores", |c| c.cores = 0),
            ("l1.size_bytes = 0: must be in 64..=16777216", |c| {
                c.l1.size_bytes = 0
            }),
            ("l1.ways = 0: must be in 1..=64", |c| c.l1.ways = 0),
            ("l2: line_bytes", |c| c.l2.line_bytes = 128),
            ("power of two", |c| c.l1.size_bytes = 3 * 4 * 64),
            ("exceeds", |c| c.l0.as_mut().unwrap().ways = 16),
            ("l0.mshrs = 0", |c| c.l0.as_mut().unwrap().mshrs = 0),
            ("ports", |c| c.l2.ports = 0),
            ("hit_latency", |c| c.l1.hit_latency = 0),
            ("not a multiple", |c| c.l1.size_bytes = 65536 + 32),
            ("divide", |c| c.l1.ways = 3),
            ("l2.max_merged = 4294967295: must be in 0..=1024", |c| {
                c.l2.max_merged = u32::MAX
            }),
            ("mshrs x (1 + max_merged) = 4198400", |c| {
                c.l2.mshrs = 4096;
                c.l2.max_merged = 1024
            }),
            // The memory system alone does not bound the core count (the
            // machine config does: 1..=64), but its budget does.
            ("gpu.cores = 4294967295", |c| c.cores = u32::MAX),
            ("budget of 1024 MiB", |c| {
                c.cores = 64;
                c.l1.size_bytes = 16 << 20;
                c.l1.hit_latency = 10_000;
                c.l1.ports = 64;
                c.l0 = None
            }),
            ("dram.banks = 0: must be in 1..=64", |c| c.dram.banks = 0),
            ("dram.banks = 4294967295: must be in 1..=64", |c| {
                c.dram.banks = u32::MAX
            }),
            (
                "l2.size_bytes = 536870912: must be in 64..=268435456",
                |c| c.l2.size_bytes = 512 << 20,
            ),
            ("l2.ways = 128", |c| c.l2.ways = 128),
            ("dram.row_bytes = 131072: must be in 64..=65536", |c| {
                c.dram.row_bytes = 128 << 10
            }),
            ("dram.row_bytes = 100: must be a multiple of 64", |c| {
                c.dram.row_bytes = 100
            }),
            ("ideal_memory", |c| c.dram.row_hit_latency = 0),
            ("requests_per_cycle", |c| c.dram.requests_per_cycle = 0),
            ("channels = 0: must be in 1..=16", |c| c.dram.channels = 0),
            ("channels = 17", |c| c.dram.channels = 17),
            ("t_rcd = 0: must be in 1..=1000", |c| c.dram.t_rcd = 0),
            ("t_rp = 1001: must be in 1..=1000", |c| c.dram.t_rp = 1001),
            ("t_ras = 1001: must be in 0..=1000", |c| c.dram.t_ras = 1001),
            ("t_cl = 0", |c| c.dram.t_cl = 0),
            ("t_burst = 0", |c| c.dram.t_burst = 0),
            ("controller_latency = 10001: must be in 0..=10000", |c| {
                c.dram.controller_latency = 10_001
            }),
            ("scheduler_window = 0: must be in 1..=256", |c| {
                c.dram.scheduler_window = 0
            }),
            ("scheduler_window = 257", |c| c.dram.scheduler_window = 257),
        ];
        for (needle, mutate) in cases {
            let mut c = good.clone();
            mutate(&mut c);
            let e = c.check().expect_err(needle);
            assert!(e.to_string().contains(needle), "{needle}: {e}");
        }
    }

    #[test]
    fn config_round_trips_through_json() {
        let c = MemConfig::paper(true);
        let s = serde_json::to_string(&c).unwrap();
        let back: MemConfig = serde_json::from_str(&s).unwrap();
        assert_eq!(back, c);
        assert!(s.contains(r#""model":"fixed""#), "{s}");
        let mut b = c.clone();
        b.dram.model = DramModel::Banked;
        let s = serde_json::to_string(&b).unwrap();
        assert!(s.contains(r#""model":"banked""#), "{s}");
        assert_eq!(serde_json::from_str::<MemConfig>(&s).unwrap(), b);
    }
}
