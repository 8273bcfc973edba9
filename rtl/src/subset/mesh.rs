//! Mesh-k: the top-left quad of every k x k block of quads.
//!
//! For k = 2^b the check is a b-bit comparator on each coordinate: the low
//! b bits of the in-tile quad x and y are all zero. Mesh4 is the paper's
//! choice: a two-bit check on x and on y, selecting 1/16 of the tile.

use super::PrioritySubset;
use crate::uint::UInt;

/// Width of an in-tile quad coordinate the comparator looks at (32 quads).
pub const QUAD_COORD_BITS: u32 = 5;

/// The Mesh-k comparator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mesh {
    low_bits: u32,
}

impl Mesh {
    /// Mesh-k for k in {2, 4, 8, 16}.
    pub fn new(k: u32) -> Option<Self> {
        match k {
            2 | 4 | 8 | 16 => Some(Self {
                low_bits: k.trailing_zeros(),
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
}

impl PrioritySubset for Mesh {
    fn name(&self) -> String {
        format!("mesh{}", self.k())
    }

    #[inline]
    fn is_priority(&self, qx: u32, qy: u32) -> bool {
        let x = UInt::<QUAD_COORD_BITS>::masked(qx);
        let y = UInt::<QUAD_COORD_BITS>::masked(qy);
        let b = self.low_bits as usize;
        x.bits()[..b].not_any() && y.bits()[..b].not_any()
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
    fn only_powers_of_two_up_to_16() {
        assert!(Mesh::new(3).is_none());
        assert!(Mesh::new(32).is_none());
        assert_eq!(Mesh::new(16).unwrap().name(), "mesh16");
    }
}
