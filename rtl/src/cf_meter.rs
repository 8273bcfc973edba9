//! The CF meter: a measured CF for a WaSP variant (beyond the paper).
//!
//! The paper fixes CF, the misses a non-blocked priority warp is expected
//! to make, at a suite average: "Each of the non-blocked priority warps has
//! a high probability of generating CF number of misses. As mentioned
//! before, the average value of CF obtained for our benchmark suite is 2.5"
//! (Section IV-C). A scene whose warps touch more blocks (the shipped 3D
//! scenes measure 3.3 to 5.1 unique blocks per warp) then under-estimates
//! what its priority warps will take, and one whose blocks other warps
//! already fetched over-estimates it. The meter measures misses per
//! launched priority warp on line instead, per core:
//!
//! ```text
//! every cycle:  acc      <= sat7(acc + misses)          (misses: primary
//!                                                         misses by priority
//!                                                         warps this cycle)
//! on a launch:  launches <= launches + 1
//!   the 16th:   cf_q     <= (acc + misses) >> 2         (quarters of a miss
//!               launches <= 0, acc <= 0                   per launched warp)
//! ```
//!
//! A window is 16 priority-warp launches: under Mesh4 a 64x64-pixel tile
//! has 64 priority quads, 16 per core of the four, so a window is about
//! one tile's priority warps on a core. `acc / 16` misses per launched
//! warp, in the datapath's quarter steps, is `acc / 4`: a shift, no
//! divider. The 7-bit accumulator saturates at 127, so the CF register
//! never exceeds `127 >> 2 = 31` (7.75), its 5-bit range. The CF register
//! resets to the paper's 2.5 and keeps its value between windows.
//!
//! Registers: 4-bit launch counter, 7-bit accumulator, 5-bit CF: 16 bits.

use crate::datapath::Cf;
use crate::uint::UInt;
use wasp_waves::{Traceable, Tracer};

/// Width of the launch counter: a window of `2^4 = 16` launches.
pub const WINDOW_BITS: u32 = 4;
/// Priority-warp launches per window.
pub const WINDOW: u32 = 1 << WINDOW_BITS;
/// Width of the miss accumulator.
pub const ACC_BITS: u32 = 7;
/// Width of the misses-per-cycle input (at most 3 primary misses a cycle:
/// the scheduler-level cache has at most 3 ports in any shipped machine,
/// and the core clamps larger counts, which only makes the meter
/// saturate sooner).
pub const MISSES_BITS: u32 = 2;

/// One cycle's inputs of the meter.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MeterEvents {
    /// A priority warp was launched into the core this cycle.
    pub launched: bool,
    /// Primary misses (MSHR allocations) made by priority warps this cycle.
    pub misses: UInt<MISSES_BITS>,
}

/// The CF meter's registers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CfMeter {
    launches: UInt<WINDOW_BITS>,
    acc: UInt<ACC_BITS>,
    cf: Cf,
}

impl Default for CfMeter {
    fn default() -> Self {
        Self::reset()
    }
}

impl CfMeter {
    /// Reset state: an empty window and CF = 2.5 (the paper's constant).
    pub const fn reset() -> Self {
        Self {
            launches: UInt::<WINDOW_BITS>::ZERO,
            acc: UInt::<ACC_BITS>::ZERO,
            cf: Cf::PAPER,
        }
    }

    /// A meter holding the given register values; `None` if a value does
    /// not fit its register (launches 4 bits, accumulator 7 bits).
    pub fn from_registers(launches: u32, acc: u32, cf: Cf) -> Option<Self> {
        Some(Self {
            launches: UInt::new(launches)?,
            acc: UInt::new(acc)?,
            cf,
        })
    }

    /// The CF register (the datapath's multiplier input).
    #[inline]
    pub const fn cf(&self) -> Cf {
        self.cf
    }

    /// Launches counted in the current window.
    pub const fn launches(&self) -> UInt<WINDOW_BITS> {
        self.launches
    }

    /// Misses accumulated in the current window.
    pub const fn acc(&self) -> UInt<ACC_BITS> {
        self.acc
    }

    /// Next state after one cycle of `ev`. Total: every input is legal.
    #[inline]
    pub fn next(&self, ev: MeterEvents) -> Self {
        let acc = self
            .acc
            .saturating_add(UInt::<ACC_BITS>::masked(ev.misses.get()));
        if !ev.launched {
            return Self { acc, ..*self };
        }
        if self.launches.get() == WINDOW - 1 {
            let q = acc.shr(2).get();
            Self {
                launches: UInt::<WINDOW_BITS>::ZERO,
                acc: UInt::<ACC_BITS>::ZERO,
                // acc <= 127, so q <= 31: the register always holds it.
                cf: Cf::from_quarters(q).unwrap_or(self.cf),
            }
        } else {
            Self {
                launches: self.launches.wrapping_add(UInt::<WINDOW_BITS>::masked(1)),
                acc,
                cf: self.cf,
            }
        }
    }
}

impl Traceable for CfMeter {
    fn trace<T: Tracer + ?Sized>(&self, t: &mut T) {
        t.push_scope("cf_meter");
        t.signal("launches", WINDOW_BITS, self.launches.get() as u64);
        t.signal("acc", ACC_BITS, self.acc.get() as u64);
        t.signal("cf_q", 5, self.cf.quarters() as u64);
        t.pop_scope();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The meter in plain integers: the specification the registers are
    /// checked against.
    fn reference(
        launches: u32,
        acc: u32,
        cf_q: u32,
        launched: bool,
        misses: u32,
    ) -> (u32, u32, u32) {
        let acc = (acc + misses).min(127);
        if !launched {
            (launches, acc, cf_q)
        } else if launches + 1 == WINDOW {
            (0, 0, acc / 4)
        } else {
            (launches + 1, acc, cf_q)
        }
    }

    fn at(launches: u32, acc: u32, cf_q: u32) -> CfMeter {
        CfMeter {
            launches: UInt::new(launches).unwrap(),
            acc: UInt::new(acc).unwrap(),
            cf: Cf::from_quarters(cf_q).unwrap(),
        }
    }

    #[test]
    fn matches_the_reference_in_every_state_and_input() {
        for launches in 0..WINDOW {
            for acc in 0..128 {
                for cf_q in 0..32 {
                    let m = at(launches, acc, cf_q);
                    for launched in [false, true] {
                        for misses in 0..4 {
                            let n = m.next(MeterEvents {
                                launched,
                                misses: UInt::new(misses).unwrap(),
                            });
                            let (l, a, q) = reference(launches, acc, cf_q, launched, misses);
                            assert_eq!(
                                (n.launches().get(), n.acc().get(), n.cf().quarters()),
                                (l, a, q),
                                "state ({launches}, {acc}, {cf_q}), launched {launched}, misses {misses}"
                            );
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn a_window_of_40_misses_over_16_launches_measures_cf_2_5() {
        let mut m = CfMeter::reset();
        // Change the register first so the measurement is seen to load it.
        for _ in 0..WINDOW {
            m = m.next(MeterEvents {
                launched: true,
                misses: UInt::new(3).unwrap(),
            });
        }
        assert_eq!(m.cf().value(), 3.0, "48 misses over 16 launches");
        let misses = [3u32, 2, 3, 2, 3, 2, 3, 2, 3, 2, 3, 2, 3, 2, 3, 2]; // 40
        for (i, &k) in misses.iter().enumerate() {
            let before = m.cf();
            m = m.next(MeterEvents {
                launched: true,
                misses: UInt::new(k).unwrap(),
            });
            if i + 1 < misses.len() {
                assert_eq!(m.cf(), before, "CF holds inside a window");
            }
        }
        assert_eq!(m.cf().value(), 2.5);
        assert_eq!((m.launches().get(), m.acc().get()), (0, 0));
    }

    #[test]
    fn misses_between_launches_count_and_the_accumulator_saturates() {
        let mut m = CfMeter::reset();
        for _ in 0..100 {
            m = m.next(MeterEvents {
                launched: false,
                misses: UInt::new(3).unwrap(),
            });
        }
        assert_eq!(m.acc().get(), 127);
        assert_eq!(m.cf(), Cf::PAPER, "no launch, no measurement");
        for _ in 0..WINDOW {
            m = m.next(MeterEvents {
                launched: true,
                misses: UInt::ZERO,
            });
        }
        assert_eq!(m.cf().quarters(), 31, "saturated: 127 >> 2");
    }

    #[test]
    fn traces_its_three_registers() {
        let m = CfMeter::reset();
        assert_eq!(
            crate::recorder::signals_of(&m),
            vec![
                ("cf_meter.launches".to_string(), 4, 0),
                ("cf_meter.acc".to_string(), 7, 0),
                ("cf_meter.cf_q".to_string(), 5, 10),
            ]
        );
    }
}
