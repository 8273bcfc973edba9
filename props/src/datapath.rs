//! (b) The shift-add datapath equals the exact rational comparison.
//!
//! The paper's rule is `Real_freeMSHRs = free - CF x n > T` over the reals.
//! With `CF = q / 4` and everything multiplied by 4 it is the integer
//! comparison `4 free - q n > 4 T`, which [`exact_priority`] computes in
//! `i64` (no width, no rounding). The hardware computes
//! `floor(q n / 4)` by shift-add in a 12-bit accumulator, subtracts it from
//! `free` in an 11-bit two's complement subtractor and compares with the
//! zero-extended threshold. The properties here say that, for every
//! register value, CF and threshold, each stage equals its exact
//! counterpart: nothing wraps, and truncating the product does not change
//! the decision.

use crate::cex::{ensure, Cex};
use wasp_rtl::datapath::{
    compare_greater, shift_add_multiply, subtract, Cf, Threshold, WaspDatapath, ACC_BITS,
    PRODUCT_BITS, REAL_FREE_BITS,
};
use wasp_rtl::free_mshr::FreeMshrs;
use wasp_rtl::nonblocked::NonblockedCount;
use wasp_rtl::uint::{SInt, UInt};

/// Property name used in counterexamples.
pub const PROP: &str = "(b) datapath";

/// The exact real-number WaSP condition `free - (q/4) n > T`, scaled by 4
/// to stay in integers: `4 free - q n > 4 T`.
#[inline]
pub const fn exact_priority(free: i64, nonblocked: i64, quarters: i64, threshold: i64) -> bool {
    4 * free - quarters * nonblocked > 4 * threshold
}

/// `floor(q n / 4)` for non-negative `q`, `n`, exactly.
#[inline]
pub const fn exact_product(nonblocked: i64, quarters: i64) -> i64 {
    (quarters * nonblocked).div_euclid(4)
}

/// The whole datapath against the exact arithmetic, for one point of the
/// domain (free x nonblocked x CF x threshold, all register values):
///
/// * `q n` fits the 12-bit shift-add accumulator (so it cannot wrap);
/// * `product == floor(q n / 4)`;
/// * the exact `free - floor(q n / 4)` fits the 11-bit subtractor, and
///   `real_free` equals it (so the subtractor did not wrap);
/// * `priority_over_regular == (4 free - q n > 4 T)`.
pub fn datapath_exact(
    free: FreeMshrs,
    nonblocked: NonblockedCount,
    cf: Cf,
    threshold: Threshold,
) -> Result<(), Cex> {
    let f = free.get() as i64;
    let n = nonblocked.get() as i64;
    let q = cf.quarters() as i64;
    let t = threshold.get() as i64;
    let cex = |what| {
        Cex::new(PROP, what)
            .with("free", f)
            .with("nonblocked", n)
            .with("cf_quarters", q)
            .with("threshold", t)
    };
    ensure(q * n < (1i64 << ACC_BITS), || {
        cex("q x n does not fit the 12-bit shift-add accumulator").with("q_times_n", q * n)
    })?;
    let out = WaspDatapath { cf, threshold }.eval(free, nonblocked);
    let product = exact_product(n, q);
    ensure(out.product.get() as i64 == product, || {
        cex("product differs from floor(q n / 4)")
            .with("expected", product)
            .with("got", out.product.get() as i64)
    })?;
    let real = f - product;
    ensure(
        real >= SInt::<REAL_FREE_BITS>::MIN as i64 && real <= SInt::<REAL_FREE_BITS>::MAX as i64,
        || cex("exact Real_freeMSHRs does not fit the 11-bit subtractor").with("exact", real),
    )?;
    ensure(out.real_free.get() as i64 == real, || {
        cex("real_free differs from free - floor(q n / 4) (subtractor wrapped?)")
            .with("expected", real)
            .with("got", out.real_free.get() as i64)
    })?;
    let exact = exact_priority(f, n, q, t);
    ensure(out.priority_over_regular == exact, || {
        cex("priority_over_regular differs from 4 free - q n > 4 T")
            .with("expected", exact as i64)
            .with("got", out.priority_over_regular as i64)
    })
}

/// The shift-add multiplier alone, for one `n` and `q`:
/// `shift_add_multiply(n, q) == floor(q n / 4)`.
pub fn shift_add_exact(nonblocked: NonblockedCount, cf: Cf) -> Result<(), Cex> {
    let n = nonblocked.get() as i64;
    let q = cf.quarters() as i64;
    let got = shift_add_multiply(nonblocked, cf).get() as i64;
    let want = exact_product(n, q);
    ensure(got == want, || {
        Cex::new(PROP, "shift-add product differs from floor(q n / 4)")
            .with("nonblocked", n)
            .with("cf_quarters", q)
            .with("expected", want)
            .with("got", got)
    })
}

/// For the paper's CF = 2.5 (`q = 10`), the product is the paper's circuit
/// `(n << 1) + (n >> 1)`, and 2.5 parses to `q = 10`.
pub fn paper_cf_is_shift_add(nonblocked: NonblockedCount) -> Result<(), Cex> {
    let n = nonblocked.get();
    let cex = |what| Cex::new(PROP, what).with("nonblocked", n as i64);
    ensure(Cf::PAPER.quarters() == 10, || {
        cex("Cf::PAPER is not q = 10")
    })?;
    ensure(Cf::from_f64(2.5) == Some(Cf::PAPER), || {
        cex("CF 2.5 does not parse to Cf::PAPER")
    })?;
    let got = shift_add_multiply(nonblocked, Cf::PAPER).get();
    let paper = (n << 1) + (n >> 1);
    ensure(got == paper, || {
        cex("product for q = 10 differs from (n << 1) + (n >> 1)")
            .with("expected", paper as i64)
            .with("got", got as i64)
    })
}

/// The 11-bit subtractor over its whole input domain (any 5-bit `free`, any
/// 10-bit product): the result is the exact difference, never wrapped.
pub fn subtractor_exact(free: FreeMshrs, product: UInt<PRODUCT_BITS>) -> Result<(), Cex> {
    let want = free.get() as i64 - product.get() as i64;
    let got = subtract(free, product).get() as i64;
    ensure(got == want, || {
        Cex::new(
            PROP,
            "subtractor result differs from free - product (wrapped)",
        )
        .with("free", free.get() as i64)
        .with("product", product.get() as i64)
        .with("expected", want)
        .with("got", got)
    })
}

/// The comparator over its whole input domain (any 11-bit signed
/// `real_free`, any 5-bit threshold): `compare_greater == (real > T)`.
pub fn comparator_exact(real_free: SInt<REAL_FREE_BITS>, threshold: Threshold) -> Result<(), Cex> {
    let want = real_free.get() as i64 > threshold.get() as i64;
    let got = compare_greater(real_free, threshold);
    ensure(got == want, || {
        Cex::new(PROP, "comparator differs from real_free > threshold")
            .with("real_free", real_free.get() as i64)
            .with("threshold", threshold.get() as i64)
            .with("expected", want as i64)
            .with("got", got as i64)
    })
}

#[cfg(any(kani, feature = "kani-shim"))]
mod proofs {
    use super::*;

    fn any_free() -> FreeMshrs {
        let v: u8 = kani::any_where(|v: &u8| *v <= 31);
        FreeMshrs::masked(v as u32)
    }

    fn any_nonblocked() -> NonblockedCount {
        let v: u8 = kani::any_where(|v: &u8| *v <= 127);
        NonblockedCount::masked(v as u32)
    }

    fn any_cf() -> Cf {
        let q: u8 = kani::any_where(|q: &u8| *q <= 31);
        Cf::from_quarters(q as u32).unwrap()
    }

    fn any_threshold() -> Threshold {
        let t: u8 = kani::any_where(|t: &u8| *t <= 31);
        Threshold::masked(t as u32)
    }

    /// Twin: `tests::exhaustive_datapath_exact_q0_to_15` and `_q16_to_31`.
    #[kani::proof]
    #[kani::unwind(7)]
    fn proof_datapath_exact() {
        assert!(datapath_exact(any_free(), any_nonblocked(), any_cf(), any_threshold()).is_ok());
    }

    /// Twin: `tests::exhaustive_shift_add`.
    #[kani::proof]
    #[kani::unwind(7)]
    fn proof_shift_add_exact() {
        assert!(shift_add_exact(any_nonblocked(), any_cf()).is_ok());
    }

    /// Twin: `tests::exhaustive_paper_cf`.
    #[kani::proof]
    #[kani::unwind(7)]
    fn proof_paper_cf_is_shift_add() {
        assert!(paper_cf_is_shift_add(any_nonblocked()).is_ok());
    }

    /// Twin: `tests::exhaustive_subtractor`.
    #[kani::proof]
    fn proof_subtractor_exact() {
        let p: u16 = kani::any_where(|p: &u16| *p <= 1023);
        assert!(subtractor_exact(any_free(), UInt::<PRODUCT_BITS>::masked(p as u32)).is_ok());
    }

    /// Twin: `tests::exhaustive_comparator`.
    #[kani::proof]
    fn proof_comparator_exact() {
        let r: i16 = kani::any_where(|r: &i16| (-1024..=1023).contains(r));
        let real = SInt::<REAL_FREE_BITS>::new(r as i32).unwrap();
        assert!(comparator_exact(real, any_threshold()).is_ok());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cex::check;

    /// Every free (0..=31) x nonblocked (0..=127) x q (0..=31) x T (0..=31):
    /// 4,194,304 points, split by CF into two tests so that the test harness
    /// runs them on both cores.
    fn datapath_for_quarters(qs: std::ops::RangeInclusive<u32>) -> u64 {
        let mut points = 0u64;
        for q in qs {
            let cf = Cf::from_quarters(q).unwrap();
            for t in 0..=Threshold::MAX.get() {
                let th = Threshold::masked(t);
                for n in 0..=NonblockedCount::MAX.get() {
                    let nb = NonblockedCount::masked(n);
                    for f in 0..=FreeMshrs::MAX.get() {
                        check(datapath_exact(FreeMshrs::masked(f), nb, cf, th));
                        points += 1;
                    }
                }
            }
        }
        points
    }

    #[test]
    fn exhaustive_datapath_exact_q0_to_15() {
        assert_eq!(datapath_for_quarters(0..=15), 16 * 128 * 32 * 32);
    }

    #[test]
    fn exhaustive_datapath_exact_q16_to_31() {
        assert_eq!(datapath_for_quarters(16..=31), 16 * 128 * 32 * 32);
    }

    /// Every nonblocked (0..=127) x q (0..=31).
    #[test]
    fn exhaustive_shift_add() {
        for q in 0..=31 {
            for n in 0..=127 {
                check(shift_add_exact(
                    NonblockedCount::masked(n),
                    Cf::from_quarters(q).unwrap(),
                ));
            }
        }
    }

    /// Every nonblocked (0..=127).
    #[test]
    fn exhaustive_paper_cf() {
        for n in 0..=127 {
            check(paper_cf_is_shift_add(NonblockedCount::masked(n)));
        }
    }

    /// Every free (0..=31) x product (0..=1023).
    #[test]
    fn exhaustive_subtractor() {
        for f in 0..=31 {
            for p in 0..=UInt::<PRODUCT_BITS>::MAX.get() {
                check(subtractor_exact(
                    FreeMshrs::masked(f),
                    UInt::<PRODUCT_BITS>::masked(p),
                ));
            }
        }
    }

    /// Every real_free (-1024..=1023) x T (0..=31).
    #[test]
    fn exhaustive_comparator() {
        for r in SInt::<REAL_FREE_BITS>::MIN..=SInt::<REAL_FREE_BITS>::MAX {
            for t in 0..=31 {
                check(comparator_exact(
                    SInt::<REAL_FREE_BITS>::new(r).unwrap(),
                    Threshold::masked(t),
                ));
            }
        }
    }

    #[test]
    fn counterexamples_are_reported() {
        // Spot-check that a wrong expectation would be reported: the exact
        // rule is strict (16 - 12.5 = 3.5 is not > 4; 16 - 10 = 6 is).
        assert!(!exact_priority(16, 5, 10, 4));
        assert!(exact_priority(16, 4, 10, 4));
        assert!(!exact_priority(5, 0, 10, 5));
        assert_eq!(exact_product(127, 31), 984);
    }
}
