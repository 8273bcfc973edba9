//! What each prefetcher adds to a core, for `wasp cost`: flip-flops and
//! logic as [`Item`]s (priced by [`GateRules`](wasp_rtl::cost::GateRules)
//! like WaSP's own inventory) and SRAM bits.
//!
//! Counted: the storage and logic a prefetch needs to exist. Not counted:
//! the instruments of the run statistics (the "prefetched, not yet used"
//! line bits, the MSHR entries' prefetch state), which only measure it;
//! and, for the raster prefetcher, the texture address unit itself, which
//! its design moves ahead of the input FIFO (Igehy et al. 1998) rather
//! than adds. An L1 MSHR entry with no target is an ordinary entry whose
//! target count is 0: no new storage. The duplicate filter's equality
//! compares are priced as magnitude comparators, an upper bound.

use super::PrefetchKind;
use wasp_rtl::cost::{bits_for, Item, Part};

/// Bits of a 64-byte block address: the paper's 1 GiB main memory
/// (Table II) is 2^30 bytes, 2^24 blocks.
pub const BLOCK_ADDRESS_BITS: u32 = 24;

/// GE per SRAM bit: a 6-transistor cell, 1.5 GE, periphery not counted
/// (the register-file rule of `wasp cost`).
pub const SRAM_GE_PER_BIT: f64 = 1.5;

/// The longest oracle list of one core for one tile on the 16 shipped
/// scenes (shared-tile dispatch, the shipped core map): the
/// `prefetch.longest_queue` of `wasp run --set prefetch.kind=oracle-tile`
/// on each scene's trace (`scripts/prefetch.sh`), the largest over the
/// scenes, stk-blackforest-start's (the others: 121 to 2504;
/// docs/machine.md, "Prefetchers").
pub const ORACLE_LONGEST_LIST: u32 = 3319;

/// SRAM a prefetcher needs.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct SramItem {
    /// Block.
    pub block: &'static str,
    /// What it holds.
    pub purpose: String,
    /// Bits.
    pub bits: u64,
}

/// One prefetcher's hardware per core.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Inventory {
    /// The prefetcher.
    pub kind: PrefetchKind,
    /// Flip-flops and logic.
    pub items: Vec<Item>,
    /// SRAM.
    pub sram: Vec<SramItem>,
    /// What the inventory means.
    pub note: String,
}

fn item(block: &'static str, purpose: impl Into<String>, part: Part) -> Item {
    Item {
        block,
        purpose: purpose.into(),
        part,
    }
}

/// What both kinds add at the L1: the reserve test on the free-MSHR count
/// and the port's second address source.
fn l1_items(l1_mshrs: u32) -> Vec<Item> {
    vec![
        item(
            "prefetch_issue",
            "free L1 MSHRs > l1_reserve",
            Part::Comparator {
                bits: bits_for(l1_mshrs),
            },
        ),
        item(
            "prefetch_issue",
            "L1 port address: demand, else prefetch",
            Part::Mux2 {
                bits: BLOCK_ADDRESS_BITS,
            },
        ),
    ]
}

/// The raster prefetcher with a queue of `queue` entries (`filter`: the
/// duplicate filter) in front of an L1 of `l1_mshrs` MSHRs.
pub fn raster_inventory(queue: u32, filter: bool, l1_mshrs: u32) -> Inventory {
    let ptr = bits_for(queue.saturating_sub(1));
    let mut items = vec![
        item(
            "prefetch_queue",
            format!("{queue} x ({BLOCK_ADDRESS_BITS}-bit block address + valid)"),
            Part::Register {
                bits: queue * (BLOCK_ADDRESS_BITS + 1),
            },
        ),
        item(
            "prefetch_queue",
            "head pointer",
            Part::Register { bits: ptr },
        ),
        item(
            "prefetch_queue",
            "tail pointer",
            Part::Register { bits: ptr },
        ),
        item(
            "prefetch_queue",
            "occupancy counter",
            Part::Register {
                bits: bits_for(queue),
            },
        ),
        item(
            "prefetch_queue",
            "pointer increments",
            Part::Adder { bits: 2 * ptr },
        ),
    ];
    if filter {
        items.push(item(
            "duplicate_filter",
            format!("{queue} x {BLOCK_ADDRESS_BITS}-bit compares (as magnitude: upper bound)"),
            Part::Comparator {
                bits: queue * BLOCK_ADDRESS_BITS,
            },
        ));
        items.push(item(
            "duplicate_filter",
            "any match",
            Part::ZeroDetect { bits: queue },
        ));
    }
    items.extend(l1_items(l1_mshrs));
    Inventory {
        kind: PrefetchKind::Raster,
        items,
        sram: Vec::new(),
        note: "a design: the texture address unit runs at rasterization (moved ahead of the \
               input FIFO, as in Igehy et al. 1998; not counted), its block addresses wait in \
               the queue"
            .into(),
    }
}

/// The oracle with lists of up to `list` entries, in front of an L1 of
/// `l1_mshrs` MSHRs.
pub fn oracle_inventory(list: u32, l1_mshrs: u32) -> Inventory {
    let mut items = vec![item(
        "oracle_list",
        "read pointer",
        Part::Register {
            bits: bits_for(list.saturating_sub(1)),
        },
    )];
    items.extend(l1_items(l1_mshrs));
    Inventory {
        kind: PrefetchKind::OracleTile,
        items,
        sram: vec![SramItem {
            block: "oracle_list",
            purpose: format!("{list} x {BLOCK_ADDRESS_BITS}-bit block addresses (longest list)"),
            bits: u64::from(list) * u64::from(BLOCK_ADDRESS_BITS),
        }],
        note: "a bound, not a design: the list is the whole tile's texture footprint, known \
               before its first quad is shaded, which only the trace knows"
            .into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use wasp_rtl::cost::GateRules;

    #[test]
    fn the_raster_queue_is_priced_per_entry() {
        let r = GateRules::default();
        let a = raster_inventory(32, true, 16);
        // 32 x 25 bits, two 5-bit pointers, a 6-bit count.
        assert_eq!(GateRules::register_bits(&a.items), 32 * 25 + 5 + 5 + 6);
        let b = raster_inventory(32, false, 16);
        let filter = r.total_ge(&a.items) - r.total_ge(&b.items);
        assert_eq!(filter, 32.0 * 24.0 * 4.0 + 32.0);
        assert!(a.sram.is_empty());
        let big = raster_inventory(64, true, 16);
        assert!(r.total_ge(&big.items) > 1.9 * r.total_ge(&a.items) - 200.0);
    }

    #[test]
    fn the_oracle_list_is_sram_of_block_addresses() {
        let o = oracle_inventory(1000, 16);
        assert_eq!(o.sram[0].bits, 24_000);
        assert_eq!(GateRules::register_bits(&o.items), 10);
        assert!(o.note.contains("bound"));
    }
}
