//! Mesh-k: the top-left quad of every k x k block of quads.
//!
//! For k = 2^b the check is a b-bit comparator on each coordinate: the low
//! b bits of the in-tile quad x and y are all zero. Mesh4 is the paper's
//! choice: a two-bit check on x and on y, selecting 1/16 of the tile.
//!
//! The comparator is a NOR over `2b` wires. [`Mesh::is_priority_bits`]
//! spells it out bit by bit on the 5-bit coordinate registers;
//! [`PrioritySubset::is_priority`] (called for every enqueued warp) is the
//! same function as one AND with the mask of the low b bits, `(x | y) &
//! (k - 1) == 0`. The tests check the two agree on every pair of 5-bit
//! coordinates and every k.

use super::PrioritySubset;
use crate::uint::UInt;

/// Width of an in-tile quad coordinate the comparator looks at (32 quads).
pub const QUAD_COORD_BITS: u32 = 5;

/// The Mesh-k comparator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mesh {
    low_bits: u32,
    /// The comparator's wires as a mask: the low `low_bits` bits set
    /// (`k - 1`).
    low_mask: u32,
}

impl Mesh {
    /// Mesh-k for k in {2, 4, 8, 16}.
    pub fn new(k: u32) -> Option<Self> {
        match k {
            2 | 4 | 8 | 16 => Some(Self {
                low_bits: k.trailing_zeros(),
                low_mask: k - 1,
            }),
            _ => None,
        }
    }

    /// k.
    pub fn k(&self) -> u32 {
        1 << self.low_bits
    }

    /// Width of the comparator on each coordinate (2 for Mesh4).
    pub fn comparator_bits(&self) -> u32 {
        self.low_bits
    }

    /// The comparator bit by bit: the low b bits of the 5-bit x and y
    /// registers are all zero. The reference form of
    /// [`PrioritySubset::is_priority`].
    pub fn is_priority_bits(&self, qx: u32, qy: u32) -> bool {
        let x = UInt::<QUAD_COORD_BITS>::masked(qx);
        let y = UInt::<QUAD_COORD_BITS>::masked(qy);
        let b = self.low_bits as usize;
        x.bits()[..b].not_any() && y.bits()[..b].not_any()
    }
}

impl PrioritySubset for Mesh {
    fn name(&self) -> String {
        format!("mesh{}", self.k())
    }

    /// The low b bits of x and y are zero. `k - 1` has no bit at or above
    /// bit 4, so masking the coordinates to their 5-bit registers first
    /// would not change the result.
    #[inline]
    fn is_priority(&self, qx: u32, qy: u32) -> bool {
        (qx | qy) & self.low_mask == 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mesh4_is_the_two_bit_check() {
        let m = Mesh::new(4).unwrap();
        assert_eq!(m.comparator_bits(), 2);
        for y in 0..32 {
            for x in 0..32 {
                assert_eq!(m.is_priority(x, y), x % 4 == 0 && y % 4 == 0, "({x},{y})");
            }
        }
    }

    #[test]
    fn mask_form_is_the_bitwise_comparator_everywhere() {
        // Every k and every pair of 5-bit coordinates, plus coordinates
        // with high bits set (the register drops them in both forms).
        for k in [2, 4, 8, 16] {
            let m = Mesh::new(k).unwrap();
            let mut selected = 0;
            for y in 0..32 {
                for x in 0..32 {
                    let fast = m.is_priority(x, y);
                    assert_eq!(fast, m.is_priority_bits(x, y), "k={k} ({x},{y})");
                    for hi in [32, 1 << 10, 1 << 31] {
                        assert_eq!(m.is_priority(x | hi, y), fast, "k={k} ({x}|{hi},{y})");
                        assert_eq!(m.is_priority_bits(x, y | hi), fast, "k={k} ({x},{y}|{hi})");
                    }
                    selected += fast as u32;
                }
            }
            assert_eq!(selected, 32 * 32 / (k * k), "k={k}");
        }
    }

    #[test]
    fn only_powers_of_two_up_to_16() {
        assert!(Mesh::new(3).is_none());
        assert!(Mesh::new(32).is_none());
        assert_eq!(Mesh::new(16).unwrap().name(), "mesh16");
    }
}
