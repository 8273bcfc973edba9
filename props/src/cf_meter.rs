//! (l) The CF meter of the measured-CF variant (`wasp-m`, beyond the
//! paper) follows its specification exactly and never leaves its registers'
//! ranges.
//!
//! Specification, in unbounded arithmetic, for launches `l` (0..=15),
//! accumulator `a` (0..=127), CF register `q` (quarters, 0..=31) and one
//! cycle's input (a priority launch, `m` primary misses of priority warps,
//! 0..=3): `a' = min(a + m, 127)`; without a launch the launch count and CF
//! hold; with a launch, the 16th of the window (`l = 15`) loads
//! `q' = a' / 4` (misses per launched warp in quarters) and clears `l` and
//! `a`, any other adds one to `l`. The CF register can therefore hold any
//! value the datapath's 5-bit CF input takes and never more.

use crate::cex::{ensure, Cex};
use wasp_rtl::cf_meter::{CfMeter, MeterEvents, WINDOW};
use wasp_rtl::datapath::Cf;
use wasp_rtl::uint::UInt;

/// Property name used in counterexamples.
pub const PROP: &str = "(l) CF meter";

/// The meter at the given register values (`None` outside their ranges).
pub fn meter_at(launches: u32, acc: u32, cf_q: u32) -> Option<CfMeter> {
    CfMeter::from_registers(launches, acc, Cf::from_quarters(cf_q)?)
}

/// (l) One state and one input: `next` is exactly the specification.
pub fn cf_meter_next_exact(m: CfMeter, launched: bool, misses: u32) -> Result<(), Cex> {
    let (l, a, q) = (m.launches().get(), m.acc().get(), m.cf().quarters());
    let cex = |what| {
        Cex::new(PROP, what)
            .with("launches", l as i64)
            .with("acc", a as i64)
            .with("cf_q", q as i64)
            .with("launched", launched as i64)
            .with("misses", misses as i64)
    };
    let Some(misses_in) = UInt::new(misses) else {
        return Ok(()); // not an input of the 2-bit port
    };
    let acc = (a + misses).min(127);
    let (l2, a2, q2) = match (launched, l + 1 == WINDOW) {
        (false, _) => (l, acc, q),
        (true, true) => (0, 0, acc / 4),
        (true, false) => (l + 1, acc, q),
    };
    let n = m.next(MeterEvents {
        launched,
        misses: misses_in,
    });
    let got = (n.launches().get(), n.acc().get(), n.cf().quarters());
    ensure(got == (l2, a2, q2), || {
        cex("next state differs from the specification")
            .with("expected_launches", l2 as i64)
            .with("expected_acc", a2 as i64)
            .with("expected_cf_q", q2 as i64)
            .with("got_launches", got.0 as i64)
            .with("got_acc", got.1 as i64)
            .with("got_cf_q", got.2 as i64)
    })?;
    ensure(q2 <= 31 && a2 <= 127 && l2 < WINDOW, || {
        cex("a register leaves its range")
    })
}

#[cfg(any(kani, feature = "kani-shim"))]
mod proofs {
    use super::*;

    /// Twin: `tests::exhaustive_cf_meter`.
    #[kani::proof]
    fn proof_cf_meter_next_exact() {
        let l: u8 = kani::any_where(|l: &u8| u32::from(*l) < WINDOW);
        let a: u8 = kani::any_where(|a: &u8| *a <= 127);
        let q: u8 = kani::any_where(|q: &u8| *q <= 31);
        let m = meter_at(l.into(), a.into(), q.into()).unwrap();
        let misses: u8 = kani::any_where(|m: &u8| *m <= 3);
        assert!(cf_meter_next_exact(m, kani::any(), misses.into()).is_ok());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cex::check;

    /// Every state (16 x 128 x 32) x launched x misses 0..=3: 524,288
    /// points, the whole domain.
    #[test]
    fn exhaustive_cf_meter() {
        let mut points = 0u32;
        for l in 0..WINDOW {
            for a in 0..=127 {
                for q in 0..=31 {
                    let m = meter_at(l, a, q).expect("every register value");
                    for launched in [false, true] {
                        for misses in 0..=3 {
                            check(cf_meter_next_exact(m, launched, misses));
                            points += 1;
                        }
                    }
                }
            }
        }
        assert_eq!(points, 16 * 128 * 32 * 2 * 4);
    }

    #[test]
    fn out_of_range_registers_are_not_states() {
        assert!(meter_at(16, 0, 0).is_none());
        assert!(meter_at(0, 128, 0).is_none());
        assert!(meter_at(0, 0, 32).is_none());
    }
}
