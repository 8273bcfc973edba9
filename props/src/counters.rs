//! (c) The 5-bit free-MSHR register and the 7-bit non-blocked counter never
//! wrap.
//!
//! Each register's `next` is specified exactly: with `v` the value the
//! events ask for, computed in unbounded arithmetic, `next` returns
//! `Ok` holding exactly `v` when `v` is in the register's legal range, and
//! otherwise `Err(RegisterFault)` naming the register, its old value, `v`
//! and the limit. A silently wrapped value is therefore impossible.
//!
//! Legal events come from reference models of what the register counts:
//!
//! * [`MshrModel`]: `capacity` MSHR entries, `in_flight` of them allocated.
//!   In one cycle a reply frees an entry that was in flight at the start of
//!   the cycle, and an allocation takes an entry free at the start or freed
//!   by this cycle's replies.
//! * [`PriorityModel`]: the priority warps in the core, each non-blocked or
//!   blocked, at most [`MAX_PRIORITY_WARPS`] = 127 of them (the most a
//!   7-bit counter can count; a core configuration that could hold more
//!   priority warps at once must be rejected by the configuration layer).
//!   In one cycle at most one warp is launched (non-blocked); `unblocked`
//!   blocked warps get their data; `blocked` warps block and `finished`
//!   non-blocked warps leave, each of those being a distinct warp that was
//!   non-blocked at some point of the cycle (launched, non-blocked at the
//!   start, or just unblocked: the worked example reports a blocked warp
//!   whose reply arrives as unblocked and finished in the same cycle).

use crate::cex::{ensure, Cex};
use wasp_rtl::free_mshr::{FreeMshrReg, MshrEvents};
use wasp_rtl::nonblocked::{NonblockedCount, NonblockedCounter, PriorityEvents};

/// Property name used in counterexamples.
pub const PROP: &str = "(c) registers never wrap";

/// The most priority warps a core may hold at once (the 7-bit counter's
/// maximum).
pub const MAX_PRIORITY_WARPS: u32 = 127;

/// Reference model of the MSHR file the free-MSHR register tracks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MshrModel {
    /// Entries in the file.
    pub capacity: u32,
    /// Entries allocated and not yet replied.
    pub in_flight: u32,
}

impl MshrModel {
    /// Free entries.
    pub fn free(&self) -> u32 {
        self.capacity - self.in_flight
    }

    /// Whether `ev` can happen in one cycle from this state.
    pub fn legal(&self, ev: MshrEvents) -> bool {
        let (a, r) = (ev.allocs as u32, ev.replies as u32);
        r <= self.in_flight && a <= self.free() + r
    }

    /// The state after a legal `ev`.
    pub fn next(&self, ev: MshrEvents) -> Self {
        Self {
            capacity: self.capacity,
            in_flight: self.in_flight + ev.allocs as u32 - ev.replies as u32,
        }
    }
}

/// Reference model of the priority warps in a core.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PriorityModel {
    /// Priority warps launched, not blocked, not finished.
    pub nonblocked: u32,
    /// Priority warps blocked on a long-latency miss.
    pub blocked: u32,
}

impl PriorityModel {
    /// Priority warps in the core.
    pub fn in_core(&self) -> u32 {
        self.nonblocked + self.blocked
    }

    /// Whether `ev` can happen in one cycle from this state (see the
    /// module documentation).
    pub fn legal(&self, ev: PriorityEvents) -> bool {
        let l = ev.launched as u32;
        let (b, u, f) = (ev.blocked as u32, ev.unblocked as u32, ev.finished as u32);
        self.in_core() + l <= MAX_PRIORITY_WARPS
            && u <= self.blocked
            && b + f <= self.nonblocked + l + u
    }

    /// The state after a legal `ev`.
    pub fn next(&self, ev: PriorityEvents) -> Self {
        let l = ev.launched as u32;
        let (b, u, f) = (ev.blocked as u32, ev.unblocked as u32, ev.finished as u32);
        Self {
            nonblocked: self.nonblocked + l + u - b - f,
            blocked: self.blocked + b - u,
        }
    }
}

/// The free-MSHR register at `free` of `capacity`, reached from reset by
/// allocating `capacity - free` entries (there is no other way to load it).
pub fn free_mshr_at(capacity: u32, free: u32) -> Option<FreeMshrReg> {
    let r = FreeMshrReg::with_capacity(capacity)?;
    let allocs = u8::try_from(capacity.checked_sub(free)?).ok()?;
    let r = r.next(MshrEvents { allocs, replies: 0 }).ok()?;
    (r.free().get() == free && r.capacity().get() == capacity).then_some(r)
}

/// The non-blocked counter at `count`, reached from reset by one cycle of
/// `count` unblocks.
pub fn counter_at(count: u32) -> Option<NonblockedCounter> {
    let unblocked = u8::try_from(count).ok()?;
    let c = NonblockedCounter::reset()
        .next(PriorityEvents {
            unblocked,
            ..Default::default()
        })
        .ok()?;
    (c.count().get() == count).then_some(c)
}

/// (c) The free-MSHR register, one state and one event (any `u8` counts,
/// legal or not): `next` is `Ok(exactly free - allocs + replies)` when that
/// is in `0..=capacity` and a fault naming the register otherwise; the
/// capacity never changes; `FreeMshrReg::legal` equals the model's
/// legality, and a legal event never faults.
pub fn free_mshr_next_exact(reg: FreeMshrReg, ev: MshrEvents) -> Result<(), Cex> {
    let cap = reg.capacity().get();
    let free = reg.free().get();
    let cex = |what| {
        Cex::new(PROP, what)
            .with("capacity", cap as i64)
            .with("free", free as i64)
            .with("allocs", ev.allocs as i64)
            .with("replies", ev.replies as i64)
    };
    ensure(free <= cap, || cex("free exceeds capacity"))?;
    ensure(reg.in_use() == cap - free, || {
        cex("in_use != capacity - free")
    })?;
    let v = free as i64 - ev.allocs as i64 + ev.replies as i64;
    let in_range = (0..=cap as i64).contains(&v);
    match reg.next(ev) {
        Ok(r) => {
            ensure(in_range, || {
                cex("out-of-range value accepted (would wrap)").with("attempted", v)
            })?;
            ensure(r.free().get() as i64 == v, || {
                cex("next value differs from free - allocs + replies")
                    .with("expected", v)
                    .with("got", r.free().get() as i64)
            })?;
            ensure(r.capacity().get() == cap, || cex("capacity changed"))?;
        }
        Err(e) => {
            ensure(!in_range, || {
                cex("in-range value refused").with("attempted", v)
            })?;
            ensure(
                e.register == "free_mshrs"
                    && e.value == free
                    && e.attempted as i64 == v
                    && e.limit == cap,
                || {
                    cex("fault does not describe the event")
                        .with("fault_value", e.value as i64)
                        .with("fault_attempted", e.attempted as i64)
                        .with("fault_limit", e.limit as i64)
                },
            )?;
        }
    }
    let model = MshrModel {
        capacity: cap,
        in_flight: cap - free,
    };
    let legal = model.legal(ev);
    ensure(reg.legal(ev) == legal, || {
        cex("FreeMshrReg::legal differs from the MSHR model").with("model_legal", legal as i64)
    })?;
    ensure(!legal || in_range, || cex("a legal event leaves the range"))?;
    ensure(!legal || model.next(ev).free() as i64 == v, || {
        cex("model and register disagree")
    })
}

/// (c) The non-blocked counter, one value and one event (any `u8` counts,
/// either `launched`): `next` is `Ok(exactly count + launched + unblocked -
/// blocked - finished)` when that is in `0..=127` and a fault naming the
/// counter otherwise.
pub fn nonblocked_next_exact(counter: NonblockedCounter, ev: PriorityEvents) -> Result<(), Cex> {
    let c = counter.count().get();
    let cex = |what| {
        Cex::new(PROP, what)
            .with("count", c as i64)
            .with("launched", ev.launched as i64)
            .with("blocked", ev.blocked as i64)
            .with("unblocked", ev.unblocked as i64)
            .with("finished", ev.finished as i64)
    };
    let v = c as i64 + ev.launched as i64 + ev.unblocked as i64
        - ev.blocked as i64
        - ev.finished as i64;
    let max = NonblockedCount::MAX.get();
    let in_range = (0..=max as i64).contains(&v);
    match counter.next(ev) {
        Ok(n) => {
            ensure(in_range, || {
                cex("out-of-range value accepted (would wrap)").with("attempted", v)
            })?;
            ensure(n.count().get() as i64 == v, || {
                cex("next value differs from count + launched + unblocked - blocked - finished")
                    .with("expected", v)
                    .with("got", n.count().get() as i64)
            })
        }
        Err(e) => {
            ensure(!in_range, || {
                cex("in-range value refused").with("attempted", v)
            })?;
            ensure(
                e.register == "nonblocked_priority"
                    && e.value == c
                    && e.attempted as i64 == v
                    && e.limit == max,
                || {
                    cex("fault does not describe the event")
                        .with("fault_value", e.value as i64)
                        .with("fault_attempted", e.attempted as i64)
                },
            )
        }
    }
}

/// (c) The non-blocked counter against the priority-warp model: if
/// `counter` holds the model's non-blocked count and `ev` is legal in the
/// model, `next` is `Ok` and holds the model's next non-blocked count.
/// (Vacuously `Ok` for a model state or event that is not legal; `Err` if
/// the counter does not hold the model's count.)
pub fn nonblocked_tracks_model(
    model: PriorityModel,
    counter: NonblockedCounter,
    ev: PriorityEvents,
) -> Result<(), Cex> {
    if model.in_core() > MAX_PRIORITY_WARPS || !model.legal(ev) {
        return Ok(());
    }
    let cex = |what| {
        Cex::new(PROP, what)
            .with("nonblocked", model.nonblocked as i64)
            .with("blocked", model.blocked as i64)
            .with("launched", ev.launched as i64)
            .with("blocked_ev", ev.blocked as i64)
            .with("unblocked", ev.unblocked as i64)
            .with("finished", ev.finished as i64)
    };
    ensure(counter.count().get() == model.nonblocked, || {
        cex("counter does not hold the model's count").with("counter", counter.count().get() as i64)
    })?;
    let want = model.next(ev).nonblocked;
    match counter.next(ev) {
        Ok(n) => ensure(n.count().get() == want, || {
            cex("counter differs from the model")
                .with("expected", want as i64)
                .with("got", n.count().get() as i64)
        }),
        Err(_) => Err(cex("legal event refused (RegisterFault)")),
    }
}

/// Every `u8` value up to `limit`, then the values near the 7-bit and 8-bit
/// edges: 0..=limit, 60..=68, 123..=133, 250..=255.
pub fn edge_counts(limit: u8) -> impl Iterator<Item = u8> + Clone {
    (0..=limit).chain(60..=68).chain(123..=133).chain(250..=255)
}

#[cfg(any(kani, feature = "kani-shim"))]
mod proofs {
    use super::*;

    /// Twin: `tests::exhaustive_free_mshr`.
    #[kani::proof]
    fn proof_free_mshr_next_exact() {
        let cap: u8 = kani::any_where(|c: &u8| *c <= 31);
        let free: u8 = kani::any_where(|f: &u8| *f <= cap);
        let reg = free_mshr_at(cap as u32, free as u32).unwrap();
        let ev = MshrEvents {
            allocs: kani::any(),
            replies: kani::any(),
        };
        assert!(free_mshr_next_exact(reg, ev).is_ok());
    }

    /// Twin: `tests::edge_domain_nonblocked` (the proof covers every `u8`).
    #[kani::proof]
    fn proof_nonblocked_next_exact() {
        let count: u8 = kani::any_where(|c: &u8| *c <= 127);
        let counter = counter_at(count as u32).unwrap();
        let ev = PriorityEvents {
            launched: kani::any(),
            blocked: kani::any(),
            unblocked: kani::any(),
            finished: kani::any(),
            misses: kani::any(),
        };
        assert!(nonblocked_next_exact(counter, ev).is_ok());
    }

    /// Twin: `tests::exhaustive_nonblocked_legal_0_to_48` and `_49_to_127`.
    /// Each count is drawn within the bound `PriorityModel::legal` puts on
    /// it (the same domain as `any()` + `assume(legal)`, which a sampler
    /// would mostly discard); the assumption then removes only a launch
    /// into a full core.
    #[kani::proof]
    fn proof_nonblocked_tracks_model() {
        let nonblocked = u32::from(kani::any_where(|n: &u8| {
            u32::from(*n) <= MAX_PRIORITY_WARPS
        }));
        let blocked = u32::from(kani::any_where(|b: &u8| {
            nonblocked + u32::from(*b) <= MAX_PRIORITY_WARPS
        }));
        let model = PriorityModel {
            nonblocked,
            blocked,
        };
        let launched: bool = kani::any();
        let unblocked: u8 = kani::any_where(|u: &u8| u32::from(*u) <= blocked);
        let avail = nonblocked + u32::from(launched) + u32::from(unblocked);
        let blocked_ev: u8 = kani::any_where(|b: &u8| u32::from(*b) <= avail);
        let finished: u8 = kani::any_where(|f: &u8| u32::from(blocked_ev) + u32::from(*f) <= avail);
        let ev = PriorityEvents {
            launched,
            blocked: blocked_ev,
            unblocked,
            finished,
            misses: kani::any(),
        };
        kani::assume(model.legal(ev));
        let counter = counter_at(model.nonblocked).unwrap();
        assert!(nonblocked_tracks_model(model, counter, ev).is_ok());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cex::check;

    /// Every capacity (0..=31) x free (0..=capacity) x allocs (0..=255) x
    /// replies (0..=255): 528 x 65,536 = 34,603,008 points, split in two
    /// tests by capacity.
    fn free_mshr_caps(caps: std::ops::RangeInclusive<u32>) -> u64 {
        let mut points = 0;
        for cap in caps {
            for free in 0..=cap {
                let reg = free_mshr_at(cap, free).expect("register reaches every value");
                for allocs in 0..=u8::MAX {
                    for replies in 0..=u8::MAX {
                        check(free_mshr_next_exact(reg, MshrEvents { allocs, replies }));
                        points += 1;
                    }
                }
            }
        }
        points
    }

    #[test]
    fn exhaustive_free_mshr_cap0_to_21() {
        // 22 capacities: 1 + 2 + ... + 22 = 253 states.
        assert_eq!(free_mshr_caps(0..=21), 253 * 65536);
    }

    #[test]
    fn exhaustive_free_mshr_cap22_to_31() {
        // 23 + ... + 32 = 275 states.
        assert_eq!(free_mshr_caps(22..=31), 275 * 65536);
    }

    /// Every model state (nonblocked, blocked) with at most 127 priority
    /// warps and every event legal in it. The counter sees only
    /// `nonblocked`; `blocked` only bounds `unblocked`, so for each
    /// (nonblocked, launched, unblocked) the state with `blocked =
    /// unblocked` stands for every state that allows that event (any larger
    /// `blocked` gives the counter the same input). Every (blocked,
    /// finished) split with `blocked + finished <= nonblocked + launched +
    /// unblocked` is enumerated: 68,511,040 (counter, event) points, split
    /// at nonblocked = 48 into two tests of about equal size.
    fn nonblocked_legal(counts: std::ops::RangeInclusive<u32>) -> u64 {
        let mut points = 0u64;
        for n in counts {
            let counter = counter_at(n).expect("counter reaches every value");
            for launched in [false, true] {
                let l = launched as u32;
                if n + l > MAX_PRIORITY_WARPS {
                    continue;
                }
                for u in 0..=MAX_PRIORITY_WARPS - n - l {
                    let model = PriorityModel {
                        nonblocked: n,
                        blocked: u,
                    };
                    let top = n + l + u;
                    for b in 0..=top {
                        for f in 0..=top - b {
                            let ev = PriorityEvents {
                                launched,
                                blocked: b as u8,
                                unblocked: u as u8,
                                finished: f as u8,
                                misses: 0,
                            };
                            debug_assert!(model.legal(ev));
                            check(nonblocked_tracks_model(model, counter, ev));
                            points += 1;
                        }
                    }
                }
            }
        }
        points
    }

    #[test]
    fn exhaustive_nonblocked_legal_0_to_48() {
        assert_eq!(nonblocked_legal(0..=48), 34_539_855);
    }

    #[test]
    fn exhaustive_nonblocked_legal_49_to_127() {
        assert_eq!(nonblocked_legal(49..=MAX_PRIORITY_WARPS), 33_971_185);
    }

    /// The model's legal events, through the property body, for every
    /// state with at most 16 priority warps and every event with counts up
    /// to 17.
    #[test]
    fn exhaustive_nonblocked_tracks_model_small() {
        for nb in 0..=16 {
            for bl in 0..=16 - nb {
                let model = PriorityModel {
                    nonblocked: nb,
                    blocked: bl,
                };
                for launched in [false, true] {
                    for b in 0..=17u8 {
                        for u in 0..=17u8 {
                            for f in 0..=17u8 {
                                let ev = PriorityEvents {
                                    launched,
                                    blocked: b,
                                    unblocked: u,
                                    finished: f,
                                    misses: 0,
                                };
                                let counter = counter_at(nb).unwrap();
                                check(nonblocked_tracks_model(model, counter, ev));
                            }
                        }
                    }
                }
            }
        }
    }

    /// Every count (0..=127) x launched x blocked, unblocked, finished each
    /// in `edge_counts(8)` (35 values: 0..=8, 60..=68, 123..=133,
    /// 250..=255): 10,976,000 points of the full specification, legal and
    /// illegal alike.
    #[test]
    fn edge_domain_nonblocked() {
        let mut points = 0u64;
        for c in 0..=127 {
            let counter = counter_at(c).expect("counter reaches every value");
            for launched in [false, true] {
                for blocked in edge_counts(8) {
                    for unblocked in edge_counts(8) {
                        for finished in edge_counts(8) {
                            check(nonblocked_next_exact(
                                counter,
                                PriorityEvents {
                                    launched,
                                    blocked,
                                    unblocked,
                                    finished,
                                    misses: 0,
                                },
                            ));
                            points += 1;
                        }
                    }
                }
            }
        }
        assert_eq!(points, 128 * 2 * 35 * 35 * 35);
    }

    /// Seven-bit limit: 127 non-blocked priority warps are countable, a
    /// 128th is a fault; the model refuses to launch it.
    #[test]
    fn counter_limit_is_127_priority_warps() {
        let full = PriorityModel {
            nonblocked: 127,
            blocked: 0,
        };
        let launch = PriorityEvents {
            launched: true,
            ..Default::default()
        };
        assert!(!full.legal(launch));
        let e = counter_at(127).unwrap().next(launch).unwrap_err();
        assert_eq!((e.attempted, e.limit), (128, 127));
        assert!(free_mshr_at(31, 0).is_some());
        assert!(free_mshr_at(32, 0).is_none());
        assert!(counter_at(128).is_none());
    }
}
