//! The types a harness can draw: each is a finite domain of `DOMAIN`
//! values numbered by a code `0..DOMAIN`, the explorer picks codes.

use std::fmt::Debug;

/// A type `kani::any()` can draw (the shim's counterpart of Kani's
/// `Arbitrary`): every value of the type, numbered.
pub trait Arbitrary: Sized + Debug {
    /// How many values the type has.
    const DOMAIN: u128;
    /// The value numbered `code` (`code < DOMAIN`).
    fn from_code(code: u64) -> Self;
}

impl Arbitrary for bool {
    const DOMAIN: u128 = 2;
    fn from_code(code: u64) -> Self {
        code & 1 == 1
    }
}

/// Integers: the code is the value's bit pattern (so a signed type counts
/// 0, 1, .., MAX, MIN, .., -1).
macro_rules! int_domain {
    ($($t:ty => $u:ty),* $(,)?) => {$(
        impl Arbitrary for $t {
            const DOMAIN: u128 = 1u128 << <$u>::BITS;
            fn from_code(code: u64) -> Self {
                code as $u as $t
            }
        }
    )*};
}

int_domain!(
    u8 => u8, u16 => u16, u32 => u32, u64 => u64, usize => usize,
    i8 => u8, i16 => u16, i32 => u32, i64 => u64, isize => usize,
);

/// `Debug` of the value numbered `code` (for a failing case's report).
pub(crate) fn show<T: Arbitrary>(code: u64) -> String {
    format!("{}: {:?}", std::any::type_name::<T>(), T::from_code(code))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_cover_each_domain_once() {
        let all: Vec<i8> = (0..i8::DOMAIN as u64).map(i8::from_code).collect();
        let mut sorted = all.clone();
        sorted.sort_unstable();
        sorted.dedup();
        assert_eq!(sorted.len(), 256);
        assert_eq!((all[0], all[127], all[128], all[255]), (0, 127, -128, -1));
        assert_eq!(u16::DOMAIN, 65536);
        assert_eq!(u64::DOMAIN, 1 << 64);
        assert_eq!(u64::from_code(u64::MAX), u64::MAX);
        assert!(!bool::from_code(0) && bool::from_code(1));
        assert_eq!(show::<i16>(0xffff), "i16: -1");
    }
}
