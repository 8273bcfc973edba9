//! SplitMix64 (Steele, Lea and Flood), the one copy of it in the
//! workspace.
//!
//! Several crates need the same small seedable generator: the trace
//! crate seeds xoshiro256** with it, the RTL's random priority subset
//! shuffles with it, the Kani shim samples harness inputs with it and the
//! co-simulation tests draw their stimulus from it. Those crates sit side
//! by side at the bottom of the layering (rtl, trace) or stand alone (the
//! Kani shim), so none may depend on another: this crate, with no
//! dependency of its own, sits below them all.
//!
//! Everything is wrapping `u64` arithmetic, so a seed gives the same
//! sequence on every platform. It is not a cryptographic generator.
#![no_std]

/// The increment of SplitMix64's counter (the 64-bit golden ratio).
pub const GAMMA: u64 = 0x9e37_79b9_7f4a_7c15;

/// One step of SplitMix64: advances `state` by [`GAMMA`] and returns the
/// next output.
///
/// Seeded with 0, the first outputs are the published reference values
/// `0xe220a8397b1dcdaf, 0x6e789e6aa1b965f4, 0x06c45d188009454f,
/// 0xf88bb8a8724c81ec` (checked in the tests).
#[inline]
pub fn splitmix64(state: &mut u64) -> u64 {
    *state = state.wrapping_add(GAMMA);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A SplitMix64 generator: its state and [`splitmix64`] as a method.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    /// A generator whose state is `seed`.
    pub const fn new(seed: u64) -> Self {
        SplitMix64(seed)
    }

    /// The next 64 random bits.
    #[inline]
    pub fn next_u64(&mut self) -> u64 {
        splitmix64(&mut self.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_the_published_reference_for_seed_0() {
        let mut s = 0u64;
        let out = [(); 4].map(|_| splitmix64(&mut s));
        assert_eq!(
            out,
            [
                0xe220_a839_7b1d_cdaf,
                0x6e78_9e6a_a1b9_65f4,
                0x06c4_5d18_8009_454f,
                0xf88b_b8a8_724c_81ec
            ]
        );
        assert_eq!(s, GAMMA.wrapping_mul(4));
    }

    #[test]
    fn the_generator_is_the_step() {
        let (mut g, mut s) = (SplitMix64::new(12345), 12345u64);
        for _ in 0..100 {
            assert_eq!(g.next_u64(), splitmix64(&mut s));
        }
    }
}
