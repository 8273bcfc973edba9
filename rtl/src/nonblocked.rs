//! The 7-bit non-blocked priority-warp counter.
//!
//! Counts the priority warps in the core that are launched, not blocked on a
//! long-latency miss, and not finished. Each such warp is expected to make
//! about CF more misses before it blocks, which is what WaSP subtracts from
//! the free MSHRs.
//!
//! Events in one cycle: at most one launch (the core launches one warp per
//! cycle), any number of blocks, unblocks and finishes. A warp that finishes
//! while blocked never counted, so only finishes of non-blocked priority
//! warps are reported here.

use crate::uint::UInt;
use crate::RegisterFault;
use wasp_waves::{Traceable, Tracer};

/// Width of the counter (the paper's "7-bit register").
pub const NONBLOCKED_BITS: u32 = 7;

/// The counter value type.
pub type NonblockedCount = UInt<NONBLOCKED_BITS>;

/// Priority-warp events of one cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PriorityEvents {
    /// A priority warp was launched into the core this cycle.
    pub launched: bool,
    /// Non-blocked priority warps that blocked on a long-latency miss.
    pub blocked: u8,
    /// Blocked priority warps whose data arrived.
    pub unblocked: u8,
    /// Non-blocked priority warps that finished (left the core).
    pub finished: u8,
    /// Primary misses (MSHR allocations) made by priority warps. The
    /// counter ignores them; the CF meter of `wasp-m` reads them.
    pub misses: u8,
}

/// The non-blocked priority-warp counter.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct NonblockedCounter {
    count: NonblockedCount,
}

impl NonblockedCounter {
    /// Reset state: zero.
    pub const fn reset() -> Self {
        Self {
            count: NonblockedCount::ZERO,
        }
    }

    /// Current value (the Q output).
    #[inline]
    pub const fn count(&self) -> NonblockedCount {
        self.count
    }

    /// Next state after one cycle of `ev`.
    ///
    /// Legal events (a warp can only block or finish if it was counted, and
    /// the core never holds more warps than the counter can count) keep the
    /// value in range; anything else is a [`RegisterFault`], never a wrap.
    #[inline]
    pub fn next(&self, ev: PriorityEvents) -> Result<Self, RegisterFault> {
        let v = self.count.get() as i32 + ev.launched as i32 + ev.unblocked as i32
            - ev.blocked as i32
            - ev.finished as i32;
        // A negative `v` reads as at least 2^31 unsigned, so the 7-bit range
        // check refuses it too.
        match NonblockedCount::new(v as u32) {
            Some(c) => Ok(Self { count: c }),
            _ => Err(RegisterFault {
                register: "nonblocked_priority",
                value: self.count.get(),
                attempted: v,
                limit: NonblockedCount::MAX.get(),
            }),
        }
    }
}

impl Traceable for NonblockedCounter {
    fn trace<T: Tracer + ?Sized>(&self, t: &mut T) {
        t.signal(
            "nonblocked_priority",
            NONBLOCKED_BITS,
            self.count.get() as u64,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn traces_its_counter() {
        let c = NonblockedCounter::reset()
            .next(PriorityEvents {
                launched: true,
                ..Default::default()
            })
            .unwrap();
        assert_eq!(
            crate::recorder::signals_of(&c),
            vec![("nonblocked_priority".to_string(), 7, 1)]
        );
    }

    #[test]
    fn launch_block_unblock_finish() {
        let c = NonblockedCounter::reset();
        let c = c
            .next(PriorityEvents {
                launched: true,
                ..Default::default()
            })
            .unwrap();
        assert_eq!(c.count().get(), 1);
        let c = c
            .next(PriorityEvents {
                blocked: 1,
                ..Default::default()
            })
            .unwrap();
        assert_eq!(c.count().get(), 0);
        let c = c
            .next(PriorityEvents {
                unblocked: 1,
                launched: true,
                ..Default::default()
            })
            .unwrap();
        assert_eq!(c.count().get(), 2);
        let c = c
            .next(PriorityEvents {
                finished: 2,
                ..Default::default()
            })
            .unwrap();
        assert_eq!(c.count().get(), 0);
    }

    #[test]
    fn underflow_and_overflow_are_faults() {
        let c = NonblockedCounter::reset();
        assert!(c
            .next(PriorityEvents {
                blocked: 1,
                ..Default::default()
            })
            .is_err());
        let mut c = NonblockedCounter::reset();
        for _ in 0..127 {
            c = c
                .next(PriorityEvents {
                    launched: true,
                    ..Default::default()
                })
                .unwrap();
        }
        assert_eq!(c.count().get(), 127);
        let e = c
            .next(PriorityEvents {
                launched: true,
                ..Default::default()
            })
            .unwrap_err();
        assert_eq!(e.attempted, 128);
        assert_eq!(e.limit, 127);
    }

    /// `next` as first written: clamp at zero, then a separate sign check.
    fn next_clamped(
        c: NonblockedCounter,
        ev: PriorityEvents,
    ) -> Result<NonblockedCounter, RegisterFault> {
        let v = c.count().get() as i32 + ev.launched as i32 + ev.unblocked as i32
            - ev.blocked as i32
            - ev.finished as i32;
        match NonblockedCount::new(v.max(0) as u32) {
            Some(count) if v >= 0 => Ok(NonblockedCounter { count }),
            _ => Err(RegisterFault {
                register: "nonblocked_priority",
                value: c.count().get(),
                attempted: v,
                limit: NonblockedCount::MAX.get(),
            }),
        }
    }

    #[test]
    fn unsigned_range_check_equals_the_clamped_one_everywhere() {
        // Every counter value against every launch, unblock and block
        // count, and every finish count on its own (blocks and finishes
        // enter the sum the same way).
        for v in 0..=NonblockedCount::MAX.get() {
            let c = NonblockedCounter {
                count: NonblockedCount::new(v).unwrap(),
            };
            for launched in [false, true] {
                for unblocked in 0..=u8::MAX {
                    for blocked in 0..=u8::MAX {
                        let ev = PriorityEvents {
                            launched,
                            blocked,
                            unblocked,
                            finished: 0,
                            misses: 0,
                        };
                        assert_eq!(c.next(ev), next_clamped(c, ev), "{c:?} {ev:?}");
                    }
                }
                for finished in 0..=u8::MAX {
                    let ev = PriorityEvents {
                        launched,
                        finished,
                        ..Default::default()
                    };
                    assert_eq!(c.next(ev), next_clamped(c, ev), "{c:?} {ev:?}");
                }
            }
        }
    }
}
