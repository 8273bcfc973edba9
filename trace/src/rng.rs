//! A small deterministic pseudo-random number generator.
//!
//! [`Rng`] is xoshiro256** (Blackman and Vigna) whose 256-bit state is filled
//! from a 64-bit seed by SplitMix64 (Steele, Lea and Flood), the seeding the
//! xoshiro authors recommend. Everything here is integer arithmetic on `u64`
//! with wrapping operations, plus one exact conversion to `f64`, so a seed
//! gives the same sequence on every platform, compiler and optimisation
//! level. Workloads, random priority subsets and anything else in the model
//! that needs randomness draw from it, so a run is reproducible from its
//! seeds alone.
//!
//! It is not a cryptographic generator.

/// One step of SplitMix64 (from `wasp-splitmix`, the workspace's one copy).
pub use wasp_splitmix::splitmix64;

/// xoshiro256** seeded through SplitMix64. Deterministic across platforms.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rng {
    s: [u64; 4],
}

impl Rng {
    /// A generator whose state is the first four SplitMix64 outputs for
    /// `seed`. Every seed, 0 included, gives a valid (non-zero) state.
    pub fn new(seed: u64) -> Rng {
        let mut sm = seed;
        let s = [
            splitmix64(&mut sm),
            splitmix64(&mut sm),
            splitmix64(&mut sm),
            splitmix64(&mut sm),
        ];
        // SplitMix64 is a bijection of its counter, so four consecutive
        // outputs are never all zero; guard anyway, the all-zero state is
        // xoshiro's only fixed point.
        if s == [0; 4] {
            return Rng { s: [1, 0, 0, 0] };
        }
        Rng { s }
    }

    /// A generator for the numbered sub-stream `stream` of `seed`: a
    /// different, reproducible sequence for each (seed, stream) pair, so one
    /// part of a generator can draw numbers without shifting another's.
    pub fn with_stream(seed: u64, stream: u64) -> Rng {
        let mut sm = stream ^ 0x6a09_e667_f3bc_c909;
        let mixed = splitmix64(&mut sm);
        Rng::new(seed ^ mixed)
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        let s = &mut self.s;
        let result = s[1].wrapping_mul(5).rotate_left(7).wrapping_mul(9);
        let t = s[1] << 17;
        s[2] ^= s[0];
        s[3] ^= s[1];
        s[1] ^= s[2];
        s[0] ^= s[3];
        s[2] ^= t;
        s[3] = s[3].rotate_left(45);
        result
    }

    /// A uniform integer in `0..n`, without modulo bias (Lemire's
    /// multiply-and-reject method).
    ///
    /// # Panics
    /// If `n == 0` (the range is empty).
    pub fn below(&mut self, n: u64) -> u64 {
        assert!(n > 0, "Rng::below(0): empty range");
        // Reject the low products that would make some results more likely.
        let threshold = n.wrapping_neg() % n; // (2^64 - n) mod n
        loop {
            let m = u128::from(self.next_u64()) * u128::from(n);
            if (m as u64) >= threshold {
                return (m >> 64) as u64;
            }
        }
    }

    /// A uniform integer in `lo..=hi`.
    ///
    /// # Panics
    /// If `lo > hi`.
    pub fn range_inclusive(&mut self, lo: u64, hi: u64) -> u64 {
        assert!(lo <= hi, "Rng::range_inclusive: lo > hi");
        match (hi - lo).checked_add(1) {
            Some(span) => lo + self.below(span),
            None => self.next_u64(), // the full u64 range
        }
    }

    /// A uniform `f64` in `[0, 1)`: the top 53 bits of [`Rng::next_u64`]
    /// scaled by 2^-53 (exact, so identical on every platform).
    pub fn f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// A uniform `f64` in `[lo, hi)` (`lo` when `lo == hi`).
    pub fn range_f64(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.f64()
    }

    /// True with probability `p` (clamped to `[0, 1]`).
    pub fn chance(&mut self, p: f64) -> bool {
        self.f64() < p
    }

    /// Shuffles `items` in place (Fisher-Yates), every permutation equally
    /// likely.
    pub fn shuffle<T>(&mut self, items: &mut [T]) {
        for i in (1..items.len()).rev() {
            let j = self.below(i as u64 + 1) as usize;
            items.swap(i, j);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Pinned first outputs of `Rng::new(0)` and `Rng::new(1)`. These values
    /// were produced by this implementation once and pinned here so that any
    /// change to the generator (which would silently change every synthetic
    /// workload) fails this test. The state for seed 0 is the SplitMix64
    /// reference sequence (checked in `wasp-splitmix`); the outputs agree with independent
    /// public implementations of the same construction (xoshiro256** seeded
    /// by SplitMix64), e.g. `0x99ec5f36cb75f2b4` first for seed 0 and
    /// `0xb3f2af6d0fc710c5` first for seed 1.
    #[test]
    fn pinned_first_outputs() {
        let mut r = Rng::new(0);
        let out: Vec<u64> = (0..4).map(|_| r.next_u64()).collect();
        assert_eq!(out, PINNED_SEED_0);
        let mut r = Rng::new(1);
        assert_eq!(r.next_u64(), PINNED_SEED_1_FIRST);
    }

    const PINNED_SEED_0: [u64; 4] = [
        0x99ec_5f36_cb75_f2b4,
        0xbf6e_1f78_4956_452a,
        0x1a5f_849d_4933_e6e0,
        0x6aa5_94f1_262d_2d2c,
    ];
    const PINNED_SEED_1_FIRST: u64 = 0xb3f2_af6d_0fc7_10c5;

    #[test]
    fn xoshiro_step_matches_reference_algorithm_by_hand() {
        // First output of xoshiro256** is rotl(s1 * 5, 7) * 9 of the seeded state.
        let mut sm = 0u64;
        let s: Vec<u64> = (0..4).map(|_| splitmix64(&mut sm)).collect();
        let expected = s[1].wrapping_mul(5).rotate_left(7).wrapping_mul(9);
        assert_eq!(Rng::new(0).next_u64(), expected);
    }

    #[test]
    fn same_seed_same_sequence_different_seed_different_sequence() {
        let a: Vec<u64> = {
            let mut r = Rng::new(7);
            (0..100).map(|_| r.next_u64()).collect()
        };
        let b: Vec<u64> = {
            let mut r = Rng::new(7);
            (0..100).map(|_| r.next_u64()).collect()
        };
        let c: Vec<u64> = {
            let mut r = Rng::new(8);
            (0..100).map(|_| r.next_u64()).collect()
        };
        assert_eq!(a, b);
        assert_ne!(a, c);
        assert_ne!(
            Rng::with_stream(7, 0).next_u64(),
            Rng::with_stream(7, 1).next_u64()
        );
        assert_eq!(
            Rng::with_stream(7, 3).next_u64(),
            Rng::with_stream(7, 3).next_u64()
        );
    }

    #[test]
    fn below_stays_in_range_and_covers_it() {
        let mut r = Rng::new(1);
        let mut seen = [0u32; 7];
        for _ in 0..7000 {
            let v = r.below(7);
            assert!(v < 7);
            seen[v as usize] += 1;
        }
        // Each value expected 1000 times; a fair generator stays well inside.
        assert!(seen.iter().all(|&c| (850..1150).contains(&c)), "{seen:?}");
        assert_eq!(r.below(1), 0);
        let big = u64::MAX - 3;
        for _ in 0..100 {
            assert!(r.below(big) < big);
        }
        for _ in 0..100 {
            let v = r.range_inclusive(10, 12);
            assert!((10..=12).contains(&v));
        }
        let _ = r.range_inclusive(0, u64::MAX);
    }

    #[test]
    #[should_panic(expected = "empty range")]
    fn below_zero_panics() {
        Rng::new(0).below(0);
    }

    #[test]
    fn f64_in_unit_interval_with_plausible_mean() {
        let mut r = Rng::new(3);
        let n = 20_000;
        let mut sum = 0.0;
        for _ in 0..n {
            let x = r.f64();
            assert!((0.0..1.0).contains(&x));
            sum += x;
        }
        let mean = sum / n as f64;
        assert!((mean - 0.5).abs() < 0.01, "mean {mean}");
        let y = r.range_f64(2.0, 4.0);
        assert!((2.0..4.0).contains(&y));
    }

    #[test]
    fn shuffle_is_a_permutation_and_deterministic() {
        let mut a: Vec<u32> = (0..50).collect();
        let mut b = a.clone();
        Rng::new(9).shuffle(&mut a);
        Rng::new(9).shuffle(&mut b);
        assert_eq!(a, b);
        assert_ne!(a, (0..50).collect::<Vec<_>>());
        let mut sorted = a.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..50).collect::<Vec<_>>());
        let mut empty: [u8; 0] = [];
        Rng::new(0).shuffle(&mut empty);
    }
}
