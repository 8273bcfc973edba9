//! The WaSP decision datapath: multiply by CF, subtract, compare.
//!
//! ```text
//! Real_freeMSHRs       = free_mshrs - CF x nonblocked_priority
//! Priority_over_regular = Real_freeMSHRs > Threshold
//! ```
//!
//! CF is a fixed-point constant in quarter steps, `CF = q / 4` with a 5-bit
//! `q` (0 to 7.75); the paper's CF = 2.5 is `q = 10 = 0b01010`. The
//! multiplier is a shift-add: one partial product `n << i` for each set bit
//! `i` of `q`, summed in a 12-bit adder, then shifted right by two. For
//! CF = 2.5 that is `((n << 1) + (n << 3)) >> 2 = (n << 1) + (n >> 1)
//! = floor(2.5 n)`, the paper's circuit.
//!
//! The shift-add sums `n << i` over the set bits `i` of `q` modulo 2^12,
//! which is `n x q` modulo 2^12: [`WaspDatapath::eval`] computes it as one
//! multiplication ([`multiply`]), and [`shift_add_multiply`] keeps the
//! partial products as the reference; the tests check the two agree for
//! every 7-bit count and 5-bit `q`.
//!
//! Truncating the product is exact for the decision: `free - T` is an
//! integer, and for an integer `x` and a real `y`, `x > y` iff
//! `x > floor(y)`. The subtractor is 11 bits wide, two's complement: the
//! widest operands (free = 31, product = floor(127 x 31 / 4) = 984) give
//! -984..=31, inside -1024..=1023, so it never wraps. `wasp-props` checks
//! both claims over every register value, CF and threshold.

use crate::free_mshr::FreeMshrs;
use crate::nonblocked::NonblockedCount;
use crate::uint::{SInt, UInt};
use wasp_waves::{Traceable, Tracer};

/// Width of the shift-add accumulator: 7-bit count times 5-bit `q`.
pub const ACC_BITS: u32 = 12;
/// Width of the product after the `>> 2`.
pub const PRODUCT_BITS: u32 = 10;
/// Width of the signed subtractor and comparator.
pub const REAL_FREE_BITS: u32 = 11;
/// Width of the threshold register.
pub const THRESHOLD_BITS: u32 = 5;

/// The CF multiplier constant, in quarters (`CF = q / 4`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Cf(UInt<5>);

/// The threshold register value.
pub type Threshold = UInt<THRESHOLD_BITS>;

impl Cf {
    /// CF = 2.5, the paper's measured average blocks per warp.
    pub const PAPER: Cf = Cf(UInt::<5>::masked(10));
    /// CF = 1, one access per warp (the worked example).
    pub const ONE: Cf = Cf(UInt::<5>::masked(4));

    /// CF from its quarter count; `None` above 31 (7.75).
    pub const fn from_quarters(q: u32) -> Option<Cf> {
        match UInt::<5>::new(q) {
            Some(v) => Some(Cf(v)),
            None => None,
        }
    }

    /// CF from a decimal value; `None` unless it is a multiple of 0.25 in
    /// 0..=7.75.
    pub fn from_f64(cf: f64) -> Option<Cf> {
        let q = cf * 4.0;
        if !q.is_finite() || q < 0.0 || q.fract() != 0.0 || q > 31.0 {
            return None;
        }
        Cf::from_quarters(q as u32)
    }

    /// The quarter count `q`.
    pub const fn quarters(self) -> u32 {
        self.0.get()
    }

    /// CF as a decimal value.
    pub fn value(self) -> f64 {
        self.0.get() as f64 / 4.0
    }

    /// Number of partial products (set bits of `q`): adders = this minus 1.
    pub fn partial_products(self) -> u32 {
        self.0.bits().count_ones() as u32
    }
}

/// Signals of the datapath for one evaluation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DatapathOut {
    /// `floor(CF x nonblocked_priority)`.
    pub product: UInt<PRODUCT_BITS>,
    /// `free_mshrs - product`, signed.
    pub real_free: SInt<REAL_FREE_BITS>,
    /// `real_free > threshold`.
    pub priority_over_regular: bool,
}

/// The combinational decision datapath with its two constants.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WaspDatapath {
    /// The CF constant wired into the shift-add.
    pub cf: Cf,
    /// The threshold register.
    pub threshold: Threshold,
}

impl WaspDatapath {
    /// Evaluate the datapath on the two register outputs.
    #[inline]
    pub fn eval(&self, free: FreeMshrs, nonblocked: NonblockedCount) -> DatapathOut {
        let product = multiply(nonblocked, self.cf);
        let real_free = subtract(free, product);
        DatapathOut {
            product,
            real_free,
            priority_over_regular: compare_greater(real_free, self.threshold),
        }
    }
}

/// `floor(n x q / 4)` as a shift-add over the set bits of `q`.
#[inline]
pub fn shift_add_multiply(n: NonblockedCount, cf: Cf) -> UInt<PRODUCT_BITS> {
    let n_acc = UInt::<ACC_BITS>::masked(n.get());
    let q = cf.0.get();
    let mut acc = UInt::<ACC_BITS>::ZERO;
    for i in 0..5 {
        if (q >> i) & 1 == 1 {
            acc = acc.wrapping_add(n_acc.shl(i));
        }
    }
    UInt::<PRODUCT_BITS>::masked(acc.shr(2).get())
}

/// `floor(n x q / 4)` in closed form: the 12-bit accumulator holds
/// `n x q mod 2^12`, shifted right by two. The same function as
/// [`shift_add_multiply`] (a sum of the partial products `n << i` over the
/// set bits of `q` is `n x q`, and both reduce modulo 2^12).
#[inline]
pub fn multiply(n: NonblockedCount, cf: Cf) -> UInt<PRODUCT_BITS> {
    let acc = UInt::<ACC_BITS>::masked(n.get() * cf.0.get());
    UInt::<PRODUCT_BITS>::masked(acc.shr(2).get())
}

/// The 11-bit two's complement subtractor `free - product`.
#[inline]
pub fn subtract(free: FreeMshrs, product: UInt<PRODUCT_BITS>) -> SInt<REAL_FREE_BITS> {
    SInt::<REAL_FREE_BITS>::wrapped(free.get() as i64 - product.get() as i64)
}

/// The signed comparator `real_free > threshold` (threshold zero-extended).
#[inline]
pub fn compare_greater(real_free: SInt<REAL_FREE_BITS>, threshold: Threshold) -> bool {
    real_free.get() > threshold.get() as i32
}

impl Traceable for DatapathOut {
    fn trace<T: Tracer + ?Sized>(&self, t: &mut T) {
        t.signal("cf_product", PRODUCT_BITS, self.product.get() as u64);
        t.signal(
            "real_free_mshrs",
            REAL_FREE_BITS,
            self.real_free.to_bits() as u64,
        );
        t.bit("priority_over_regular", self.priority_over_regular);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn n(v: u32) -> NonblockedCount {
        NonblockedCount::new(v).unwrap()
    }

    #[test]
    fn traces_product_difference_and_decision() {
        // 3 free, 2 non-blocked x 2.5 = 5: real -2 (11-bit two's complement
        // 0x7fe), not above threshold 0.
        let dp = WaspDatapath {
            cf: Cf::PAPER,
            threshold: Threshold::ZERO,
        };
        let out = dp.eval(FreeMshrs::new(3).unwrap(), n(2));
        assert_eq!(
            crate::recorder::signals_of(&out),
            vec![
                ("cf_product".to_string(), 10, 5),
                ("real_free_mshrs".to_string(), 11, 0x7fe),
                ("priority_over_regular".to_string(), 1, 0),
            ]
        );
    }

    #[test]
    fn paper_cf_is_the_papers_shift_add() {
        for v in 0..=127u32 {
            let paper = (v << 1) + (v >> 1);
            assert_eq!(shift_add_multiply(n(v), Cf::PAPER).get(), paper, "n={v}");
        }
        assert_eq!(Cf::PAPER.value(), 2.5);
        assert_eq!(Cf::PAPER.partial_products(), 2);
    }

    #[test]
    fn closed_form_product_is_the_shift_add_everywhere() {
        for q in 0..=31u32 {
            let cf = Cf::from_quarters(q).unwrap();
            for v in 0..=NonblockedCount::MAX.get() {
                assert_eq!(
                    multiply(n(v), cf),
                    shift_add_multiply(n(v), cf),
                    "n={v} q={q}"
                );
            }
        }
    }

    #[test]
    fn cf_parsing() {
        assert_eq!(Cf::from_f64(2.5), Some(Cf::PAPER));
        assert_eq!(Cf::from_f64(1.0), Some(Cf::ONE));
        assert_eq!(Cf::from_f64(2.3), None);
        assert_eq!(Cf::from_f64(8.0), None);
        assert_eq!(Cf::from_f64(-0.25), None);
        assert_eq!(Cf::from_f64(f64::NAN), None);
        assert_eq!(Cf::from_f64(7.75).map(Cf::quarters), Some(31));
    }

    #[test]
    fn widest_operands_do_not_wrap() {
        let max_cf = Cf::from_quarters(31).unwrap();
        let out = WaspDatapath {
            cf: max_cf,
            threshold: Threshold::ZERO,
        }
        .eval(FreeMshrs::ZERO, NonblockedCount::MAX);
        assert_eq!(out.product.get(), 984);
        assert_eq!(out.real_free.get(), -984);
        assert!(!out.priority_over_regular);
    }

    #[test]
    fn decision_examples() {
        let dp = WaspDatapath {
            cf: Cf::PAPER,
            threshold: Threshold::new(4).unwrap(),
        };
        // 16 free, 4 non-blocked priority warps: 16 - 10 = 6 > 4.
        let o = dp.eval(FreeMshrs::new(16).unwrap(), n(4));
        assert_eq!(o.real_free.get(), 6);
        assert!(o.priority_over_regular);
        // 16 free, 5 warps: 16 - 12.5 = 3.5, not > 4 (hardware: 16 - 12 = 4).
        let o = dp.eval(FreeMshrs::new(16).unwrap(), n(5));
        assert_eq!(o.real_free.get(), 4);
        assert!(!o.priority_over_regular);
    }
}
