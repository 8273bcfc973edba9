//! The named choices of the machine configuration: how tiles reach the
//! cores, how the filter and the texture latency add up, what happens to
//! the colour buffer after a tile, which miss blocks a warp, in which
//! order the issue stage visits ready warps.

use serde::{Deserialize, Serialize};

/// How the tiles of a frame reach the cores.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Dispatch {
    /// The paper's machine: one tile at a time for the whole GPU, one
    /// rasterizer and Early-Z stage, each surviving quad sent to the core
    /// its screen position names, a barrier between tiles.
    SharedTile,
    /// Each core takes a whole tile of its own when it is idle and
    /// rasterizes it with its own rasterizer (tiles run out of phase).
    PerCoreTile,
}

impl std::fmt::Display for Dispatch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Dispatch::SharedTile => "shared-tile",
            Dispatch::PerCoreTile => "per-core-tile",
        })
    }
}

impl std::str::FromStr for Dispatch {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "shared-tile" => Ok(Dispatch::SharedTile),
            "per-core-tile" => Ok(Dispatch::PerCoreTile),
            _ => Err(format!(
                "unknown dispatch `{s}` (expected shared-tile or per-core-tile)"
            )),
        }
    }
}

/// How a texture instruction's filter pass and the texture unit's
/// pipeline latency (`core.texture_latency`) add up. The core has one
/// filter unit, which serves texture instructions in the order their last
/// block arrives: an instruction whose data arrives at cycle `a` starts
/// filtering at `s = max(a, filter free)` and holds the filter for its
/// `f` filter cycles (bilinear or trilinear), so the filter is free again
/// at `s + f`. With `L = max(texture_latency, 1)` the warp wakes at:
///
/// * `overlap`: `max(s + f, a + L)`: the filter pass is part of the
///   pipeline latency, so an idle filter adds nothing until `f > L`; only a
///   busy filter (queueing) or a long pass delays the warp;
/// * `serial`: `s + f + L`: the latency comes after the filter pass.
///
/// With both filter cycles 0 the two are the same: `a + L`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FilterTiming {
    /// `max(s + f, a + L)` (wasp).
    Overlap,
    /// `s + f + L`.
    Serial,
}

impl std::fmt::Display for FilterTiming {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            FilterTiming::Overlap => "overlap",
            FilterTiming::Serial => "serial",
        })
    }
}

/// What happens to the colour buffer when a tile has retired.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ColorFlush {
    /// Double-buffered colour buffer: the tile's lines are written to main
    /// memory while the next tile renders.
    Overlap,
    /// One colour buffer: the next tile starts when the last line of the
    /// flush has entered main memory.
    Blocking,
    /// No flush traffic (the model before the flush existed; for studies).
    None,
}

impl std::fmt::Display for ColorFlush {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            ColorFlush::Overlap => "overlap",
            ColorFlush::Blocking => "blocking",
            ColorFlush::None => "none",
        })
    }
}

/// Which miss marks a warp *blocked*, the paper's long-latency state
/// ("warps are marked as blocked when they encounter a long-latency miss",
/// Section IV-C). The paper does not say at which level (wasp's choice,
/// `scheduler.blocked_on`). The core applies the rule (`gpu/core/blocked.rs`)
/// to its accesses' results and the miss events the memory system reports
/// ([`MemorySystem::take_miss_events`](crate::mem::MemorySystem::take_miss_events)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum BlockedOn {
    /// Any miss (primary or secondary) in the scheduler-level cache (L0 when
    /// present, else L1), known at the access: even an L0 miss that the
    /// 1-cycle L1 answers.
    FirstLevel,
    /// A request that misses in the core's L1 (primary or merged into an L1
    /// MSHR entry): it leaves the core for the L2 and takes at least the L2's
    /// latency. The same as `FirstLevel` without an L0.
    #[default]
    L1Miss,
    /// A request that misses in the L2 (primary or merged into an L2 MSHR
    /// entry): it goes to main memory.
    Dram,
}

impl BlockedOn {
    /// Every rule, in order of the level.
    pub const ALL: [BlockedOn; 3] = [BlockedOn::FirstLevel, BlockedOn::L1Miss, BlockedOn::Dram];

    /// Whether the rule needs the memory system's miss events: the access's
    /// own result tells a first-level miss, and, without an L0, an L1 miss.
    pub fn reads_miss_events(self, has_l0: bool) -> bool {
        match self {
            BlockedOn::FirstLevel => false,
            BlockedOn::L1Miss => has_l0,
            BlockedOn::Dram => true,
        }
    }
}

impl std::fmt::Display for BlockedOn {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            BlockedOn::FirstLevel => "first-level",
            BlockedOn::L1Miss => "l1-miss",
            BlockedOn::Dram => "dram",
        })
    }
}

impl std::str::FromStr for BlockedOn {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        BlockedOn::ALL
            .into_iter()
            .find(|b| b.to_string() == s)
            .ok_or_else(|| {
                format!("unknown blocked_on {s:?}: expected first-level, l1-miss or dram")
            })
    }
}

/// The order in which the issue stage visits ready warps (`core.issue`).
/// The paper does not say (wasp's choice: `lrr`, the order of the model
/// before the option existed). docs/machine.md, "Issue order", defines
/// both.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum IssueOrder {
    /// Loose round-robin: every slot from the one after the last pick of
    /// the last issuing cycle, ascending, wrapping (`gpu/core/issue/lrr.rs`).
    #[default]
    Lrr,
    /// Greedy-then-oldest: the slots that issued in the last issuing cycle
    /// first, then every other slot, each group oldest first by launch
    /// cycle (`gpu/core/issue/gto.rs`).
    Gto,
}

impl IssueOrder {
    /// Every order.
    pub const ALL: [IssueOrder; 2] = [IssueOrder::Lrr, IssueOrder::Gto];
}

impl std::fmt::Display for IssueOrder {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            IssueOrder::Lrr => "lrr",
            IssueOrder::Gto => "gto",
        })
    }
}

impl std::str::FromStr for IssueOrder {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        IssueOrder::ALL
            .into_iter()
            .find(|o| o.to_string() == s)
            .ok_or_else(|| format!("unknown issue order {s:?}: expected lrr or gto"))
    }
}

/// What the texture caches (L0 and L1) hold of a compressed texture
/// (`memory.texture_cache`); the sources disagree (docs/textures.md, "What
/// the texture cache holds"), so both are modelled (wasp: `compressed` by
/// default, the model before the option existed).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum TextureCache {
    /// Every level (L0, L1, L2) and DRAM hold the stored (compressed)
    /// lines the trace lists; the texture unit decompresses after the L0.
    #[default]
    Compressed,
    /// The L0 and L1 hold decoded RGBA8 lines (the trace lists them and
    /// maps them, `texture-lines decoded`); an L1 miss asks the L2 for the
    /// compressed line holding its texels, so the L2 and DRAM hold and
    /// move compressed lines.
    Decompressed,
}

impl TextureCache {
    /// Every choice.
    pub const ALL: [TextureCache; 2] = [TextureCache::Compressed, TextureCache::Decompressed];
}

impl std::fmt::Display for TextureCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            TextureCache::Compressed => "compressed",
            TextureCache::Decompressed => "decompressed",
        })
    }
}

impl std::str::FromStr for TextureCache {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        TextureCache::ALL
            .into_iter()
            .find(|o| o.to_string() == s)
            .ok_or_else(|| {
                format!("unknown texture cache {s:?}: expected compressed or decompressed")
            })
    }
}
