//! Hardware inventory of the WaSP additions, straight from the blocks'
//! own widths.
//!
//! Each block lists the storage and logic WaSP adds to a baseline core:
//! registers (bits), adders/subtractors, comparators, zero detectors and
//! multiplexers, each with its width. [`GateRules`] turns an inventory into
//! gate equivalents (GE, one GE = one 2-input NAND = 4 transistors) with
//! stated counting rules, so a designer can check the paper's claim ("a
//! two-bit comparator per core, a 5-bit register, a 7-bit register, a
//! multiplier and a comparator") and compare it with a synthesis run.

use crate::datapath::{Cf, WaspDatapath, ACC_BITS, PRODUCT_BITS, REAL_FREE_BITS, THRESHOLD_BITS};
use crate::free_mshr::FREE_MSHR_BITS;
use crate::nonblocked::NONBLOCKED_BITS;
use crate::subset::Mesh;
use serde::Serialize;

/// Kinds of hardware.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case", tag = "kind")]
pub enum Part {
    /// A register of `bits` flip-flops.
    Register {
        /// Width.
        bits: u32,
    },
    /// An adder or subtractor of `bits` (ripple of full adders).
    Adder {
        /// Width.
        bits: u32,
    },
    /// A magnitude comparator of `bits`.
    Comparator {
        /// Width.
        bits: u32,
    },
    /// An all-zero detector over `bits` inputs.
    ZeroDetect {
        /// Inputs.
        bits: u32,
    },
    /// A 2:1 multiplexer of `bits`.
    Mux2 {
        /// Width.
        bits: u32,
    },
}

/// One line of an inventory.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Item {
    /// Block (hardware name).
    pub block: &'static str,
    /// What the part is for.
    pub purpose: String,
    /// The part.
    pub part: Part,
}

fn item(block: &'static str, purpose: impl Into<String>, part: Part) -> Item {
    Item {
        block,
        purpose: purpose.into(),
        part,
    }
}

/// Bits to hold `0..=n`.
pub fn bits_for(n: u32) -> u32 {
    (u32::BITS - n.leading_zeros()).max(1)
}

/// The free-MSHR register: the register and its +allocs/-replies update.
pub fn free_mshr_inventory() -> Vec<Item> {
    vec![
        item(
            "free_mshrs",
            "free-MSHR register",
            Part::Register {
                bits: FREE_MSHR_BITS,
            },
        ),
        item(
            "free_mshrs",
            "update: + replies",
            Part::Adder {
                bits: FREE_MSHR_BITS,
            },
        ),
        item(
            "free_mshrs",
            "update: - allocations",
            Part::Adder {
                bits: FREE_MSHR_BITS,
            },
        ),
    ]
}

/// The non-blocked priority-warp counter and its update.
pub fn nonblocked_inventory() -> Vec<Item> {
    vec![
        item(
            "nonblocked_priority",
            "non-blocked priority-warp counter",
            Part::Register {
                bits: NONBLOCKED_BITS,
            },
        ),
        item(
            "nonblocked_priority",
            "update: + launch + unblocks",
            Part::Adder {
                bits: NONBLOCKED_BITS,
            },
        ),
        item(
            "nonblocked_priority",
            "update: - blocks - finishes",
            Part::Adder {
                bits: NONBLOCKED_BITS,
            },
        ),
    ]
}

/// The decision datapath for its CF: one adder per partial product beyond
/// the first (the shift-add multiplier), the subtractor, the comparator,
/// and the threshold register.
pub fn datapath_inventory(dp: &WaspDatapath) -> Vec<Item> {
    let mut v = Vec::new();
    let partials = dp.cf.partial_products();
    // Width of the sum actually needed: 7-bit count times q.
    let sum_bits = bits_for(((1u32 << NONBLOCKED_BITS) - 1) * dp.cf.quarters()).min(ACC_BITS);
    for i in 1..partials {
        v.push(item(
            "cf_multiplier",
            format!("shift-add x{} (partial product {})", dp.cf.value(), i + 1),
            Part::Adder { bits: sum_bits },
        ));
    }
    v.push(item(
        "real_free_mshrs",
        format!("subtractor free_mshrs - {PRODUCT_BITS}-bit product"),
        Part::Adder {
            bits: REAL_FREE_BITS,
        },
    ));
    v.push(item(
        "priority_over_regular",
        "comparator real_free_mshrs > threshold",
        Part::Comparator {
            bits: REAL_FREE_BITS,
        },
    ));
    v.push(item(
        "threshold",
        "threshold register",
        Part::Register {
            bits: THRESHOLD_BITS,
        },
    ));
    v
}

/// The Mesh-k comparator on the enqueue path.
pub fn mesh_inventory(mesh: &Mesh) -> Vec<Item> {
    vec![item(
        "mesh_comparator",
        format!(
            "{}-bit zero check of quad x and y ({})",
            mesh.comparator_bits(),
            mesh_name(mesh)
        ),
        Part::ZeroDetect {
            bits: 2 * mesh.comparator_bits(),
        },
    )]
}

fn mesh_name(m: &Mesh) -> String {
    use crate::subset::PrioritySubset;
    m.name()
}

/// What splitting a `capacity`-entry queue into two FIFOs adds: the second
/// head/tail pointer pair and occupancy counter, and the launch select
/// (the storage itself is unchanged).
pub fn split_queue_inventory(capacity: u32) -> Vec<Item> {
    let ptr = bits_for(capacity.saturating_sub(1));
    let occ = bits_for(capacity);
    vec![
        item(
            "input_queue",
            "second FIFO head pointer",
            Part::Register { bits: ptr },
        ),
        item(
            "input_queue",
            "second FIFO tail pointer",
            Part::Register { bits: ptr },
        ),
        item(
            "input_queue",
            "second FIFO occupancy counter",
            Part::Register { bits: occ },
        ),
        item(
            "input_queue",
            "second FIFO pointer increments",
            Part::Adder { bits: ptr },
        ),
        item(
            "launch_select",
            "priority/regular read select",
            Part::Mux2 { bits: ptr },
        ),
    ]
}

/// Everything WaSP adds to one core.
pub fn core_inventory(dp: &WaspDatapath, mesh: &Mesh, queue_capacity: u32) -> Vec<Item> {
    let mut v = Vec::new();
    v.extend(mesh_inventory(mesh));
    v.extend(free_mshr_inventory());
    v.extend(nonblocked_inventory());
    v.extend(datapath_inventory(dp));
    v.extend(split_queue_inventory(queue_capacity));
    v
}

/// What the measured-CF variant adds beyond the paper's WaSP: the CF meter's
/// registers and update logic ([`crate::cf_meter`]), and a multiplier for a
/// CF that is no longer a wired constant: five partial products `n << i`,
/// each gated by bit `i` of the CF register (counted as a 2:1 mux per bit, an
/// upper bound for an AND gate), summed by four 12-bit adders. The constant
/// multiplier of [`datapath_inventory`] is then not needed:
/// [`constant_multiplier_inventory`] lists what it replaces.
pub fn measured_cf_inventory() -> Vec<Item> {
    use crate::cf_meter::{ACC_BITS as METER_ACC_BITS, WINDOW_BITS};
    let mut v = vec![
        item(
            "cf_meter",
            "priority launches in the window",
            Part::Register { bits: WINDOW_BITS },
        ),
        item(
            "cf_meter",
            "launch counter increment",
            Part::Adder { bits: WINDOW_BITS },
        ),
        item(
            "cf_meter",
            "window end: launch counter all ones",
            Part::ZeroDetect { bits: WINDOW_BITS },
        ),
        item(
            "cf_meter",
            "priority-warp misses in the window",
            Part::Register {
                bits: METER_ACC_BITS,
            },
        ),
        item(
            "cf_meter",
            "miss accumulator add",
            Part::Adder {
                bits: METER_ACC_BITS,
            },
        ),
        item(
            "cf_meter",
            "miss accumulator saturation",
            Part::Mux2 {
                bits: METER_ACC_BITS,
            },
        ),
        item(
            "cf_meter",
            "CF register (quarters), loaded acc >> 2",
            Part::Register { bits: 5 },
        ),
    ];
    for i in 0..5 {
        v.push(item(
            "cf_multiplier",
            format!("partial product n << {i} gated by CF bit {i}"),
            Part::Mux2 { bits: ACC_BITS },
        ));
    }
    for i in 1..5 {
        v.push(item(
            "cf_multiplier",
            format!("variable shift-add, partial product {}", i + 1),
            Part::Adder { bits: ACC_BITS },
        ));
    }
    v
}

/// The constant-CF multiplier's adders of [`datapath_inventory`] (what the
/// measured-CF variant's variable multiplier replaces).
pub fn constant_multiplier_inventory(dp: &WaspDatapath) -> Vec<Item> {
    datapath_inventory(dp)
        .into_iter()
        .filter(|i| i.block == "cf_multiplier")
        .collect()
}

/// Gate-equivalent counting rules (one GE = one 2-input NAND).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct GateRules {
    /// GE per flip-flop with load enable.
    pub flip_flop: f64,
    /// GE per full-adder bit.
    pub full_adder: f64,
    /// GE per comparator bit (a subtractor's carry chain).
    pub comparator_bit: f64,
    /// GE per input of a zero detector (a NOR/AND tree).
    pub zero_detect_input: f64,
    /// GE per 2:1 mux bit.
    pub mux2_bit: f64,
    /// Transistors per GE (static CMOS NAND2).
    pub transistors_per_ge: f64,
}

impl Default for GateRules {
    /// Textbook static-CMOS figures: a D flip-flop with enable ~ 6 GE
    /// (4.5 for the flop, 1.5 for the enable mux), a full adder ~ 6 GE
    /// (two XORs at 2 GE, carry logic 2 GE), a comparator bit ~ 4 GE (the
    /// carry/borrow chain of a subtractor without the sum XOR), a zero
    /// detector ~ 1 GE per input (a NOR tree), a 2:1 mux ~ 2.5 GE per bit,
    /// 4 transistors per GE.
    fn default() -> Self {
        Self {
            flip_flop: 6.0,
            full_adder: 6.0,
            comparator_bit: 4.0,
            zero_detect_input: 1.0,
            mux2_bit: 2.5,
            transistors_per_ge: 4.0,
        }
    }
}

impl GateRules {
    /// GE of one part.
    pub fn ge(&self, p: &Part) -> f64 {
        match *p {
            Part::Register { bits } => bits as f64 * self.flip_flop,
            Part::Adder { bits } => bits as f64 * self.full_adder,
            Part::Comparator { bits } => bits as f64 * self.comparator_bit,
            Part::ZeroDetect { bits } => bits as f64 * self.zero_detect_input,
            Part::Mux2 { bits } => bits as f64 * self.mux2_bit,
        }
    }

    /// Flip-flop bits of an inventory.
    pub fn register_bits(items: &[Item]) -> u32 {
        items
            .iter()
            .map(|i| match i.part {
                Part::Register { bits } => bits,
                _ => 0,
            })
            .sum()
    }

    /// Total GE of an inventory.
    pub fn total_ge(&self, items: &[Item]) -> f64 {
        items.iter().map(|i| self.ge(&i.part)).sum()
    }
}

/// The paper's datapath: CF 2.5 and the given threshold.
pub fn paper_datapath(threshold: u32) -> WaspDatapath {
    WaspDatapath {
        cf: Cf::PAPER,
        threshold: crate::datapath::Threshold::masked(threshold),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paper_claim_parts_are_all_there() {
        let inv = core_inventory(&paper_datapath(4), &Mesh::new(4).unwrap(), 64);
        let has = |block: &str, part: Part| inv.iter().any(|i| i.block == block && i.part == part);
        assert!(has("mesh_comparator", Part::ZeroDetect { bits: 4 }));
        assert!(has("free_mshrs", Part::Register { bits: 5 }));
        assert!(has("nonblocked_priority", Part::Register { bits: 7 }));
        assert!(has("priority_over_regular", Part::Comparator { bits: 11 }));
        // CF = 2.5 = q 10 = 0b01010: two partial products, one adder of
        // 127 x 10 = 1270 -> 11 bits.
        let mult: Vec<&Item> = inv.iter().filter(|i| i.block == "cf_multiplier").collect();
        assert_eq!(mult.len(), 1);
        assert_eq!(mult[0].part, Part::Adder { bits: 11 });
        // The descriptions name what a reader looks for.
        let mesh = inv.iter().find(|i| i.block == "mesh_comparator").unwrap();
        assert_eq!(mesh.purpose, "2-bit zero check of quad x and y (mesh4)");
        assert_eq!(mult[0].purpose, "shift-add x2.5 (partial product 2)");
    }

    #[test]
    fn counting_rules() {
        let r = GateRules::default();
        let inv = free_mshr_inventory();
        assert_eq!(GateRules::register_bits(&inv), 5);
        assert_eq!(r.total_ge(&inv), 5.0 * 6.0 + 2.0 * 5.0 * 6.0);
        assert_eq!(bits_for(64), 7);
        assert_eq!(bits_for(63), 6);
        let q = split_queue_inventory(64);
        assert_eq!(GateRules::register_bits(&q), 6 + 6 + 7);
    }

    #[test]
    fn every_part_is_priced_by_its_rule() {
        let r = GateRules::default();
        assert_eq!(r.ge(&Part::Register { bits: 3 }), 18.0);
        assert_eq!(r.ge(&Part::Adder { bits: 3 }), 18.0);
        assert_eq!(r.ge(&Part::Comparator { bits: 3 }), 12.0);
        assert_eq!(r.ge(&Part::ZeroDetect { bits: 3 }), 3.0);
        assert_eq!(r.ge(&Part::Mux2 { bits: 3 }), 7.5);
        // Rules are the user's to change: every rule scales its part.
        let r = GateRules {
            zero_detect_input: 2.0,
            ..GateRules::default()
        };
        assert_eq!(r.ge(&Part::ZeroDetect { bits: 3 }), 6.0);
    }

    #[test]
    fn paper_core_totals() {
        // The figures `wasp cost` reports for the paper's core (width 4,
        // 64 warps, Mesh4, CF 2.5, threshold 4).
        let r = GateRules::default();
        let inv = core_inventory(&paper_datapath(4), &Mesh::new(4).unwrap(), 64);
        assert_eq!(GateRules::register_bits(&inv), 36);
        assert_eq!(r.total_ge(&inv), 591.0);
    }

    #[test]
    fn cf_one_needs_no_adder() {
        let dp = WaspDatapath {
            cf: Cf::ONE,
            threshold: crate::datapath::Threshold::ZERO,
        };
        assert!(!datapath_inventory(&dp)
            .iter()
            .any(|i| i.block == "cf_multiplier"));
    }

    #[test]
    fn measured_cf_adds_the_meter_and_a_variable_multiplier() {
        let items = measured_cf_inventory();
        // 4-bit launch counter, 7-bit accumulator, 5-bit CF register.
        assert_eq!(GateRules::register_bits(&items), 16);
        let adders = items
            .iter()
            .filter(|i| i.block == "cf_multiplier" && matches!(i.part, Part::Adder { .. }))
            .count();
        assert_eq!(adders, 4, "five partial products need four adders");
        // CF 2.5 (q = 0b01010) has two partial products: one adder replaced.
        let replaced = constant_multiplier_inventory(&paper_datapath(4));
        assert_eq!(replaced.len(), 1);
        let r = GateRules::default();
        assert!(r.total_ge(&items) > r.total_ge(&replaced));
    }
}
