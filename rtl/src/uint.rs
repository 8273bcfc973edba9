//! Fixed-width register values.
//!
//! [`UInt<N>`] is an N-bit unsigned value and [`SInt<N>`] an N-bit two's
//! complement value. Every operation says what happens at the edge of the
//! range: `wrapping_*` wraps modulo 2^N as hardware does, `checked_*`
//! returns `None` where hardware would wrap, `saturating_*` clamps. There is
//! no silent overflow: the constructors either mask explicitly
//! ([`UInt::masked`]) or check ([`UInt::new`]).

use bitvec::prelude::*;
use std::fmt;

/// An N-bit unsigned register value, 1 <= N <= 32.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub struct UInt<const N: u32>(u32);

impl<const N: u32> UInt<N> {
    /// Width in bits.
    pub const WIDTH: u32 = {
        assert!(N >= 1 && N <= 32, "UInt width must be 1..=32");
        N
    };
    /// All ones: the largest value the register holds.
    pub const MAX: Self = Self(if N == 32 { u32::MAX } else { (1u32 << N) - 1 });
    /// Zero.
    pub const ZERO: Self = Self(0);

    const MASK: u32 = Self::MAX.0;

    /// The value `v` if it fits in N bits, else `None`.
    #[inline]
    pub const fn new(v: u32) -> Option<Self> {
        let _ = Self::WIDTH;
        if v <= Self::MASK {
            Some(Self(v))
        } else {
            None
        }
    }

    /// The low N bits of `v` (what a hardware register of width N keeps).
    #[inline]
    pub const fn masked(v: u32) -> Self {
        let _ = Self::WIDTH;
        Self(v & Self::MASK)
    }

    /// The value as an integer.
    #[inline]
    pub const fn get(self) -> u32 {
        self.0
    }

    /// Addition modulo 2^N.
    #[inline]
    pub const fn wrapping_add(self, rhs: Self) -> Self {
        Self::masked(self.0.wrapping_add(rhs.0))
    }

    /// Subtraction modulo 2^N.
    #[inline]
    pub const fn wrapping_sub(self, rhs: Self) -> Self {
        Self::masked(self.0.wrapping_sub(rhs.0))
    }

    /// Addition, `None` where an N-bit adder would carry out.
    #[inline]
    pub const fn checked_add(self, rhs: Self) -> Option<Self> {
        match self.0.checked_add(rhs.0) {
            Some(v) => Self::new(v),
            None => None,
        }
    }

    /// Subtraction, `None` where an N-bit subtractor would borrow.
    #[inline]
    pub const fn checked_sub(self, rhs: Self) -> Option<Self> {
        match self.0.checked_sub(rhs.0) {
            Some(v) => Some(Self(v)),
            None => None,
        }
    }

    /// Addition clamped to [`UInt::MAX`].
    #[inline]
    pub const fn saturating_add(self, rhs: Self) -> Self {
        match self.checked_add(rhs) {
            Some(v) => v,
            None => Self::MAX,
        }
    }

    /// Subtraction clamped to zero.
    #[inline]
    pub const fn saturating_sub(self, rhs: Self) -> Self {
        match self.checked_sub(rhs) {
            Some(v) => v,
            None => Self::ZERO,
        }
    }

    /// Zero-extend (or keep) to a wider register; `None` if M < N and the
    /// value does not fit.
    #[inline]
    pub const fn resize<const M: u32>(self) -> Option<UInt<M>> {
        UInt::<M>::new(self.0)
    }

    /// Logical shift left by `s`, keeping the low N bits.
    #[inline]
    pub const fn shl(self, s: u32) -> Self {
        if s >= 32 {
            Self(0)
        } else {
            Self::masked(self.0 << s)
        }
    }

    /// Logical shift right by `s`.
    #[inline]
    pub const fn shr(self, s: u32) -> Self {
        if s >= 32 {
            Self(0)
        } else {
            Self(self.0 >> s)
        }
    }

    /// The bits, least significant first (index 0 is bit 0), as hardware
    /// comparators see them.
    #[inline]
    pub fn bits(&self) -> &BitSlice<u32, Lsb0> {
        &self.0.view_bits::<Lsb0>()[..N as usize]
    }

    /// The bits as a string, most significant first (as VCD writes vectors).
    pub fn to_bin_msb_first(self) -> String {
        self.bits()
            .iter()
            .rev()
            .map(|b| if *b { '1' } else { '0' })
            .collect()
    }
}

impl<const N: u32> fmt::Debug for UInt<N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}'d{}", N, self.0)
    }
}

impl<const N: u32> fmt::Display for UInt<N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.0)
    }
}

/// An N-bit two's complement value, 2 <= N <= 32.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub struct SInt<const N: u32>(i32);

impl<const N: u32> SInt<N> {
    /// Width in bits.
    pub const WIDTH: u32 = {
        assert!(N >= 2 && N <= 32, "SInt width must be 2..=32");
        N
    };
    /// Largest representable value, 2^(N-1) - 1.
    pub const MAX: i32 = if N == 32 {
        i32::MAX
    } else {
        (1i32 << (N - 1)) - 1
    };
    /// Smallest representable value, -2^(N-1).
    pub const MIN: i32 = if N == 32 {
        i32::MIN
    } else {
        -(1i32 << (N - 1))
    };

    /// The value `v` if it is representable in N bits, else `None`.
    #[inline]
    pub const fn new(v: i32) -> Option<Self> {
        let _ = Self::WIDTH;
        if v >= Self::MIN && v <= Self::MAX {
            Some(Self(v))
        } else {
            None
        }
    }

    /// The low N bits of `v`, read as two's complement (what an N-bit
    /// subtractor leaves when its result does not fit).
    #[inline]
    pub const fn wrapped(v: i64) -> Self {
        let _ = Self::WIDTH;
        let shift = 64 - N;
        Self(((v << shift) >> shift) as i32)
    }

    /// The value as an integer.
    #[inline]
    pub const fn get(self) -> i32 {
        self.0
    }

    /// Sign bit.
    #[inline]
    pub const fn is_negative(self) -> bool {
        self.0 < 0
    }

    /// The N-bit pattern as an unsigned number (for waveforms).
    #[inline]
    pub const fn to_bits(self) -> u32 {
        if N == 32 {
            self.0 as u32
        } else {
            (self.0 as u32) & ((1u32 << N) - 1)
        }
    }
}

impl<const N: u32> fmt::Debug for SInt<N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}'sd{}", N, self.0)
    }
}

impl<const N: u32> fmt::Display for SInt<N> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checked_arithmetic_and_text() {
        let a = UInt::<5>::new(20).unwrap();
        let b = UInt::<5>::new(11).unwrap();
        assert_eq!(a.checked_add(b).map(UInt::get), Some(31));
        assert_eq!(a.checked_add(UInt::new(12).unwrap()), None);
        assert_eq!(b.checked_add(b).map(UInt::get), Some(22));
        assert_eq!(a.checked_sub(b).map(UInt::get), Some(9));
        assert_eq!(b.checked_sub(a), None);
        assert_eq!(format!("{a:?} {a}"), "5'd20 20");
        let n = SInt::<11>::new(-3).unwrap();
        assert_eq!(format!("{n:?} {n}"), "11'sd-3 -3");
        assert!(n.is_negative());
        assert!(!SInt::<11>::new(0).unwrap().is_negative());
        assert!(!SInt::<11>::new(1).unwrap().is_negative());
    }

    #[test]
    fn five_bit_register_range_and_edges() {
        assert_eq!(UInt::<5>::MAX.get(), 31);
        assert_eq!(UInt::<5>::new(31).map(|v| v.get()), Some(31));
        assert_eq!(UInt::<5>::new(32), None);
        assert_eq!(UInt::<5>::masked(33).get(), 1);
        let a = UInt::<5>::new(30).unwrap();
        let two = UInt::<5>::new(2).unwrap();
        assert_eq!(a.checked_add(two), None);
        assert_eq!(a.wrapping_add(two).get(), 0);
        assert_eq!(a.saturating_add(two).get(), 31);
        assert_eq!(two.checked_sub(a), None);
        assert_eq!(two.wrapping_sub(a).get(), 4);
        assert_eq!(two.saturating_sub(a).get(), 0);
    }

    #[test]
    fn seven_bit_counter_range() {
        assert_eq!(UInt::<7>::MAX.get(), 127);
        assert_eq!(UInt::<7>::new(128), None);
        let v = UInt::<7>::new(100).unwrap();
        assert_eq!(v.resize::<5>(), None);
        assert_eq!(v.resize::<9>().unwrap().get(), 100);
    }

    #[test]
    fn bit_views_are_lsb_indexed_and_print_msb_first() {
        let v = UInt::<5>::new(0b00110).unwrap();
        let bits: Vec<bool> = v.bits().iter().map(|b| *b).collect();
        assert_eq!(bits, vec![false, true, true, false, false]);
        assert_eq!(v.to_bin_msb_first(), "00110");
        assert_eq!(v.shl(3).get(), 0b10000);
        assert_eq!(v.shr(1).get(), 0b11);
    }

    #[test]
    fn signed_range_and_wrapping() {
        assert_eq!(SInt::<11>::MAX, 1023);
        assert_eq!(SInt::<11>::MIN, -1024);
        assert!(SInt::<11>::new(-1024).is_some());
        assert!(SInt::<11>::new(-1025).is_none());
        assert_eq!(SInt::<5>::wrapped(-17).get(), 15);
        assert_eq!(SInt::<5>::wrapped(16).get(), -16);
        assert_eq!(SInt::<5>::new(-1).unwrap().to_bits(), 0b11111);
        assert!(SInt::<5>::new(-3).unwrap().is_negative());
    }

    #[test]
    fn every_value_round_trips_through_masking() {
        for v in 0..=UInt::<7>::MAX.get() {
            assert_eq!(UInt::<7>::masked(v).get(), v);
            assert_eq!(UInt::<7>::masked(v + 128).get(), v);
        }
    }
}
