//! Warp-slot bitmasks of one width, for the core's hot loops.
//!
//! A core keeps its slot sets (free, ready, wake-ups) as `u128` (up to 128
//! warp slots). Most machines have at most 64 slots, where 128-bit shifts,
//! rotations and bit scans cost several host instructions each instead of
//! one; the issue and wake-up loops are therefore written once over
//! [`SlotMask`] and run on `u64` when every slot fits in it.

use std::ops::{BitAnd, BitAndAssign, BitOr, BitOrAssign, Not};

/// A set of warp slots `0..Self::BITS`, one bit per slot.
pub(crate) trait SlotMask:
    Copy
    + Eq
    + BitAnd<Output = Self>
    + BitOr<Output = Self>
    + BitAndAssign
    + BitOrAssign
    + Not<Output = Self>
{
    /// The empty set.
    const ZERO: Self;
    /// Slots the mask can hold.
    const BITS: u32;
    /// The set `{s}` (`s < BITS`).
    fn bit(s: usize) -> Self;
    /// The set `{s}` if `on`, else the empty set (`s < BITS`), without a
    /// branch.
    fn bit_if(s: usize, on: bool) -> Self;
    /// The low `BITS` bits of a `u128` set (the caller guarantees that no
    /// higher bit is set).
    fn from_wide(m: u128) -> Self;
    /// The set as a `u128`.
    fn to_wide(self) -> u128;
    /// The lowest slot of a non-empty set.
    fn lowest(self) -> usize;
    /// The set without its lowest slot.
    fn without_lowest(self) -> Self;
    /// Slot `s` moves to `(s - n) mod BITS` (`n < BITS`).
    fn rotate_right(self, n: u32) -> Self;
}

/// `SlotMask` for a primitive unsigned integer: the same bit operations,
/// only the conversion from the 128-bit form differs.
macro_rules! slot_mask {
    ($t:ty, |$m:ident| $from_wide:expr) => {
        impl SlotMask for $t {
            const ZERO: Self = 0;
            const BITS: u32 = <$t>::BITS;
            #[inline(always)]
            fn bit(s: usize) -> Self {
                1 << s
            }
            #[inline(always)]
            fn bit_if(s: usize, on: bool) -> Self {
                <$t>::from(on) << s
            }
            #[inline(always)]
            fn from_wide($m: u128) -> Self {
                $from_wide
            }
            #[inline(always)]
            fn to_wide(self) -> u128 {
                u128::from(self)
            }
            #[inline(always)]
            fn lowest(self) -> usize {
                self.trailing_zeros() as usize
            }
            #[inline(always)]
            fn without_lowest(self) -> Self {
                self & self.wrapping_sub(1)
            }
            #[inline(always)]
            fn rotate_right(self, n: u32) -> Self {
                <$t>::rotate_right(self, n)
            }
        }
    };
}

slot_mask!(u64, |m| {
    debug_assert!(m >> 64 == 0, "slot above 63 in a 64-slot mask");
    m as u64
});
slot_mask!(u128, |m| m);

/// The slots of `m` in round-robin order from slot `start`: every slot at
/// or above `start` ascending, then the ones below it ascending. (What the
/// core's issue stage visits, by rotating once instead of searching from a
/// moving pointer.)
#[cfg(test)]
fn round_robin<M: SlotMask>(m: M, start: u32) -> Vec<usize> {
    let mut rot = m.rotate_right(start);
    let mut out = Vec::new();
    while rot != M::ZERO {
        let k = rot.lowest();
        rot = rot.without_lowest();
        out.push((k + start as usize) % M::BITS as usize);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn slots_u128(m: u128) -> Vec<usize> {
        (0..128).filter(|&s| m >> s & 1 == 1).collect()
    }

    /// The reference order: repeatedly the first slot at or after a
    /// pointer, else the first slot, the pointer moving past each pick.
    fn reference(m: u128, start: u32, n: u32) -> Vec<usize> {
        let mut cand = m;
        let mut rr = start;
        let mut out = Vec::new();
        while cand != 0 {
            let above = cand & (u128::MAX << rr);
            let pick = if above != 0 { above } else { cand };
            let s = pick.trailing_zeros();
            cand &= !(1u128 << s);
            out.push(s as usize);
            rr = (s + 1) % n;
        }
        out
    }

    #[test]
    fn both_widths_agree_on_bits_and_scans() {
        for s in [0usize, 1, 17, 31, 47, 63] {
            assert_eq!(<u64 as SlotMask>::bit(s).to_wide(), 1u128 << s);
            assert_eq!(<u128 as SlotMask>::bit(s), 1u128 << s);
            assert_eq!(<u64 as SlotMask>::bit(s).lowest(), s);
        }
        assert_eq!(<u128 as SlotMask>::bit(127).lowest(), 127);
        let m: u64 = 0b1011_0100;
        assert_eq!(m.without_lowest(), 0b1011_0000);
        assert_eq!(<u64 as SlotMask>::from_wide(u128::from(m)), m);
        assert_eq!(SlotMask::rotate_right(1u64, 1), 1u64 << 63);
        assert_eq!(SlotMask::rotate_right(1u128, 1), 1u128 << 127);
        assert_eq!(u64::ZERO, 0);
    }

    #[test]
    fn round_robin_matches_the_moving_pointer() {
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        for _ in 0..2000 {
            // xorshift: masks of every density.
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            for n in [1u32, 5, 48, 64] {
                let narrow = if n == 64 { x } else { x & ((1u64 << n) - 1) };
                let thin = narrow & x.rotate_left(11) & x.rotate_left(23);
                for m in [narrow, thin] {
                    let start = (x >> 40) as u32 % n;
                    let want = reference(u128::from(m), start, n);
                    assert_eq!(round_robin(m, start), want, "{m:#x} from {start}");
                    assert_eq!(round_robin(u128::from(m), start), want);
                    assert_eq!(want.len(), slots_u128(u128::from(m)).len());
                }
            }
            let wide = u128::from(x) << 64 | u128::from(x.rotate_left(29));
            for n in [65u32, 100, 128] {
                let m = if n == 128 {
                    wide
                } else {
                    wide & ((1u128 << n) - 1)
                };
                let start = (x >> 20) as u32 % n;
                assert_eq!(round_robin(m, start), reference(m, start, n));
            }
        }
    }

    #[test]
    fn bit_if_is_the_bit_or_nothing() {
        for s in 0..128 {
            assert_eq!(u128::bit_if(s, true), 1u128 << s);
            assert_eq!(u128::bit_if(s, false), 0);
            if s < 64 {
                assert_eq!(u64::bit_if(s, true), u64::bit(s));
                assert_eq!(u64::bit_if(s, false), 0);
            }
        }
    }
}
