//! The 5-bit free-MSHR register.
//!
//! WaSP reads the number of free MSHR entries of the scheduler-level cache
//! (the L0 at pipeline width 4, the L1 at width 2). The register is reset to
//! the MSHR capacity; each cycle it loses the entries the cache allocated and
//! gains the entries whose reply arrived. It counts an entry free from the
//! cycle of its reply (the cache may keep the entry held one cycle longer
//! while it writes the line; see the worked example in `wasp-sim`). It is a
//! clocked register: a launch decision in cycle t sees the events of cycles
//! up to t-1.

use crate::uint::UInt;
use crate::RegisterFault;
use wasp_waves::{Traceable, Tracer};

/// Width of the free-MSHR register (the paper's "5-bit register").
pub const FREE_MSHR_BITS: u32 = 5;

/// The largest value the register holds: the most MSHRs it can count.
pub const FREE_MSHR_MAX: u32 = (1 << FREE_MSHR_BITS) - 1;

/// The free-MSHR register value type.
pub type FreeMshrs = UInt<FREE_MSHR_BITS>;

/// What the scheduler-level cache did with its MSHR file in one cycle.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MshrEvents {
    /// Entries allocated this cycle (primary misses).
    pub allocs: u8,
    /// Entries whose reply arrived this cycle.
    pub replies: u8,
}

/// The free-MSHR register: its value and the capacity it was reset to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FreeMshrReg {
    free: FreeMshrs,
    capacity: FreeMshrs,
}

impl FreeMshrReg {
    /// Reset state: every entry free.
    pub const fn reset(capacity: FreeMshrs) -> Self {
        Self {
            free: capacity,
            capacity,
        }
    }

    /// Reset for a capacity given as an integer; `None` if the 5-bit register
    /// cannot hold it.
    pub fn with_capacity(capacity: u32) -> Option<Self> {
        FreeMshrs::new(capacity).map(Self::reset)
    }

    /// Current value (the Q output).
    #[inline]
    pub const fn free(&self) -> FreeMshrs {
        self.free
    }

    /// The capacity the register was reset to.
    #[inline]
    pub const fn capacity(&self) -> FreeMshrs {
        self.capacity
    }

    /// Entries counted as in use: capacity - free.
    #[inline]
    pub const fn in_use(&self) -> u32 {
        self.capacity.get() - self.free.get()
    }

    /// Next state (the D input) after one cycle of `ev`.
    ///
    /// Legal events keep the value in `0..=capacity`: a cache cannot allocate
    /// more entries than are free, nor reply to more than are in use. An
    /// illegal event is reported as a [`RegisterFault`], never wrapped.
    #[inline]
    pub fn next(&self, ev: MshrEvents) -> Result<Self, RegisterFault> {
        let v = self.free.get() as i32 - ev.allocs as i32 + ev.replies as i32;
        // `v < 0 || v > capacity` as one unsigned compare: a negative `v`
        // reads as at least 2^31, above any 5-bit capacity.
        if v as u32 > self.capacity.get() {
            return Err(RegisterFault {
                register: "free_mshrs",
                value: self.free.get(),
                attempted: v,
                limit: self.capacity.get(),
            });
        }
        Ok(Self {
            free: FreeMshrs::masked(v as u32),
            capacity: self.capacity,
        })
    }

    /// Whether `ev` is legal in this state: at most `free` allocations (after
    /// this cycle's replies) and at most `in_use` replies.
    pub fn legal(&self, ev: MshrEvents) -> bool {
        (ev.replies as u32) <= self.in_use()
            && (ev.allocs as u32) <= self.free.get() + ev.replies as u32
    }
}

impl Traceable for FreeMshrReg {
    fn trace<T: Tracer + ?Sized>(&self, t: &mut T) {
        t.signal("free_mshrs", FREE_MSHR_BITS, self.free.get() as u64);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn traces_its_register() {
        let r = FreeMshrReg::with_capacity(13).unwrap();
        assert_eq!(
            crate::recorder::signals_of(&r),
            vec![("free_mshrs".to_string(), 5, 13)]
        );
    }

    #[test]
    fn allocate_and_release() {
        let r = FreeMshrReg::with_capacity(3).unwrap();
        let r = r
            .next(MshrEvents {
                allocs: 1,
                replies: 0,
            })
            .unwrap();
        assert_eq!(r.free().get(), 2);
        assert_eq!(r.in_use(), 1);
        let r = r
            .next(MshrEvents {
                allocs: 1,
                replies: 1,
            })
            .unwrap();
        assert_eq!(r.free().get(), 2);
        let r = r
            .next(MshrEvents {
                allocs: 0,
                replies: 1,
            })
            .unwrap();
        assert_eq!(r.free().get(), 3);
    }

    #[test]
    fn capacity_must_fit_five_bits() {
        assert!(FreeMshrReg::with_capacity(31).is_some());
        assert!(FreeMshrReg::with_capacity(32).is_none());
    }

    #[test]
    fn illegal_events_are_faults_not_wraps() {
        let r = FreeMshrReg::with_capacity(2).unwrap();
        let e = r
            .next(MshrEvents {
                allocs: 3,
                replies: 0,
            })
            .unwrap_err();
        assert_eq!(e.register, "free_mshrs");
        assert_eq!(e.attempted, -1);
        assert!(r
            .next(MshrEvents {
                allocs: 0,
                replies: 1
            })
            .is_err());
        assert!(!r.legal(MshrEvents {
            allocs: 0,
            replies: 1
        }));
    }

    /// `next` as first written, with a signed two-sided range check.
    fn next_two_sided(r: &FreeMshrReg, ev: MshrEvents) -> Result<FreeMshrReg, RegisterFault> {
        let v = r.free().get() as i32 - ev.allocs as i32 + ev.replies as i32;
        if v < 0 || v > r.capacity().get() as i32 {
            return Err(RegisterFault {
                register: "free_mshrs",
                value: r.free().get(),
                attempted: v,
                limit: r.capacity().get(),
            });
        }
        Ok(FreeMshrReg {
            free: FreeMshrs::masked(v as u32),
            capacity: r.capacity(),
        })
    }

    #[test]
    fn one_sided_range_check_equals_the_two_sided_one_everywhere() {
        // Every reachable register state and every event pair.
        for cap in 0..=FreeMshrs::MAX.get() {
            for free in 0..=cap {
                let r = FreeMshrReg::with_capacity(cap)
                    .unwrap()
                    .next(MshrEvents {
                        allocs: (cap - free) as u8,
                        replies: 0,
                    })
                    .unwrap();
                assert_eq!(r.free().get(), free);
                for allocs in 0..=u8::MAX {
                    for replies in 0..=u8::MAX {
                        let ev = MshrEvents { allocs, replies };
                        assert_eq!(r.next(ev), next_two_sided(&r, ev), "{r:?} {ev:?}");
                    }
                }
            }
        }
    }
}
