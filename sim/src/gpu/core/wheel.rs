//! The shader core's wake-ups: at which cycle each warp slot looks at its
//! next instruction again.
//!
//! Two kinds of wake-up: *due* (the core looks at the warp: its next
//! instruction entry, or its end) and *ready* (a warp in the middle of an
//! ALU run, known to issue another ALU instruction: it joins the ready set
//! as it is). The core asks once per cycle, in cycle order, for the slots
//! of the current cycle.
//!
//! [`WakeWheel`] is the fast form: a timing wheel of [`WHEEL`] cycles of
//! 128-bit slot masks (two 64-bit halves, so setting a bit is a 64-bit
//! shift), and a heap for the rare wake-ups beyond its reach, moved onto
//! the wheel as they come within it. [`PlainWakeups`] (tests) keeps a map
//! from cycle to masks; the tests run both on random schedules.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Cycles the wheel reaches (a power of two).
pub(crate) const WHEEL: usize = 64;

/// The timing wheel of wake-ups.
#[derive(Clone, Debug)]
pub(crate) struct WakeWheel {
    /// Due wake-ups by cycle modulo [`WHEEL`].
    due: [[u64; 2]; WHEEL],
    /// Ready wake-ups by cycle modulo [`WHEEL`].
    ready: [[u64; 2]; WHEEL],
    /// Due wake-ups further than the wheel reaches.
    far: BinaryHeap<Reverse<(u64, u8)>>,
}

impl WakeWheel {
    /// No wake-ups.
    pub(crate) fn new() -> Self {
        WakeWheel {
            due: [[0; 2]; WHEEL],
            ready: [[0; 2]; WHEEL],
            far: BinaryHeap::new(),
        }
    }

    /// Wake `slot` (< 128) due at cycle `at` (> `now`, the current cycle).
    #[inline]
    pub(crate) fn schedule(&mut self, now: u64, at: u64, slot: usize) {
        if at - now < WHEEL as u64 {
            self.due[(at as usize) & (WHEEL - 1)][(slot >> 6) & 1] |= 1u64 << (slot & 63);
        } else {
            self.far.push(Reverse((at, slot as u8)));
        }
    }

    /// Whether masks for cycle `at` can go on the wheel from cycle `now`.
    #[inline]
    pub(crate) fn reaches(now: u64, at: u64) -> bool {
        at - now < WHEEL as u64
    }

    /// Wake the slots of `ready` as ready and those of `due` as due at
    /// cycle `at`, which [`WakeWheel::reaches`].
    #[inline(always)]
    pub(crate) fn schedule_masks(&mut self, at: u64, ready: u128, due: u128) {
        let i = (at as usize) & (WHEEL - 1);
        self.ready[i][0] |= ready as u64;
        self.ready[i][1] |= (ready >> 64) as u64;
        self.due[i][0] |= due as u64;
        self.due[i][1] |= (due >> 64) as u64;
    }

    /// Whether cycle `now` has a wake-up ([`take`](Self::take) would
    /// return one), without taking it.
    pub(crate) fn has_any(&self, now: u64) -> bool {
        let i = (now as usize) & (WHEEL - 1);
        self.ready[i] != [0; 2]
            || self.due[i] != [0; 2]
            || self.far.peek().is_some_and(|&Reverse((t, _))| t == now)
    }

    /// The wake-ups of cycle `now`, as (ready, due) slot masks, taken off
    /// the wheel. Called once for every cycle, in order.
    #[inline(always)]
    pub(crate) fn take(&mut self, now: u64) -> (u128, u128) {
        while let Some(&Reverse((t, slot))) = self.far.peek() {
            if t - now >= WHEEL as u64 {
                break;
            }
            self.far.pop();
            let slot = slot as usize;
            self.due[(t as usize) & (WHEEL - 1)][(slot >> 6) & 1] |= 1u64 << (slot & 63);
        }
        let i = (now as usize) & (WHEEL - 1);
        let [lo, hi] = std::mem::take(&mut self.ready[i]);
        let ready = u128::from(lo) | u128::from(hi) << 64;
        let [lo, hi] = std::mem::take(&mut self.due[i]);
        (ready, u128::from(lo) | u128::from(hi) << 64)
    }
}

/// [`WakeWheel`] as a map from cycle to masks: the plain reference.
#[cfg(test)]
#[derive(Clone, Debug, Default)]
pub(crate) struct PlainWakeups {
    at: std::collections::BTreeMap<u64, (u128, u128)>,
}

#[cfg(test)]
impl PlainWakeups {
    pub(crate) fn schedule(&mut self, _now: u64, at: u64, slot: usize) {
        self.at.entry(at).or_default().1 |= 1u128 << slot;
    }

    pub(crate) fn schedule_masks(&mut self, at: u64, ready: u128, due: u128) {
        let e = self.at.entry(at).or_default();
        e.0 |= ready;
        e.1 |= due;
    }

    pub(crate) fn take(&mut self, now: u64) -> (u128, u128) {
        self.at.remove(&now).unwrap_or((0, 0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// One cycle's scheduling: (delay, slot, as a mask of ready slots?).
    type Plan = Vec<(u64, usize, bool)>;

    fn run(plans: &[Plan]) -> Result<(), TestCaseError> {
        let (mut fast, mut plain) = (WakeWheel::new(), PlainWakeups::default());
        let last = plans.len() as u64 + 400;
        for now in 0..last {
            let any = fast.has_any(now);
            let got = fast.take(now);
            prop_assert_eq!(any, got != (0, 0), "cycle {}", now);
            prop_assert_eq!(got, plain.take(now), "cycle {}", now);
            for &(delay, slot, masked) in plans.get(now as usize).into_iter().flatten() {
                let at = now + delay;
                if masked && WakeWheel::reaches(now, at) {
                    let (r, d) = (1u128 << slot, 1u128 << ((slot + 1) % 128));
                    fast.schedule_masks(at, r, d);
                    plain.schedule_masks(at, r, d);
                } else {
                    fast.schedule(now, at, slot);
                    plain.schedule(now, at, slot);
                }
            }
        }
        prop_assert!(plain.at.is_empty());
        prop_assert_eq!(fast.take(last), (0, 0));
        Ok(())
    }

    proptest! {
        #[test]
        fn the_wheel_wakes_what_the_plain_map_wakes(
            plans in prop::collection::vec(
                prop::collection::vec((1u64..300, 0usize..128, any::<bool>()), 0..6),
                1..120,
            )
        ) {
            run(&plans)?;
        }
    }

    #[test]
    fn far_wake_ups_come_back_at_their_cycle() {
        let mut w = WakeWheel::new();
        w.schedule(0, 1000, 127);
        w.schedule(0, 64, 3);
        w.schedule(0, 63, 2);
        for now in 1..=1000 {
            let got = w.take(now);
            let want = match now {
                63 => (0, 1 << 2),
                64 => (0, 1 << 3),
                1000 => (0, 1 << 127),
                _ => (0, 0),
            };
            assert_eq!(got, want, "cycle {now}");
        }
    }
}
