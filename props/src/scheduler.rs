//! The launch scheduler against a reference model, cycle by cycle; (a) at
//! the scheduler level.
//!
//! [`SchedulerCheck`] drives a [`LaunchScheduler`] and a [`Model`] with the
//! same inputs and compares them every cycle. The model keeps unbounded
//! counters (`i64`): the MSHR entries in flight, the priority warps in the
//! core, non-blocked and blocked, the regular warps in the core, and an
//! ideal pair of FIFOs with a capacity check. The launch rule is the exact
//! [`RefPolicy`] under the configured [`LaunchRule`]. A cycle is:
//!
//! 1. the rasterizer may offer one warp (in-tile quad coordinates): its
//!    class must be the reference classification, and it must be accepted
//!    iff fewer than `queue_capacity` warps wait;
//! 2. `decide` must pick the reference FIFO from the current register
//!    values; for WaSP the datapath outputs must equal the exact product,
//!    difference and comparison, and **(a)**: under `hold` a priority
//!    selection, and a priority launch, happen only when
//!    `4 free - q nonblocked > 4 T` on that cycle's register values (under
//!    `launch` also when no regular warp waits); under `launch` a FIFO is
//!    selected whenever a warp waits; `held` is set exactly when `hold`
//!    idles with a priority warp waiting;
//! 3. `launch` (enabled when the core has a free warp slot and the
//!    environment wants a launch) must pop the reference FIFO's head;
//! 4. the cycle's memory and warp events, legal in the model, are clocked
//!    in: `clock` must not fault, and the registers must then equal the
//!    model (`free_mshrs == capacity - in_flight`, `nonblocked_priority ==`
//!    the model's non-blocked priority warps);
//! 5. conservation: warps accepted = warps launched + warps waiting.
//!
//! Events are drawn by [`CycleChoice`]: raw numbers reduced modulo the
//! largest legal value, so that every choice is a legal event and every
//! legal event (up to the raw range) is some choice.

use crate::cex::{ensure, Cex};
use crate::counters::MAX_PRIORITY_WARPS;
use crate::datapath::{exact_priority, exact_product};
use crate::policy::{class_code, RefPolicy};
use std::collections::VecDeque;
use wasp_rtl::free_mshr::{FreeMshrReg, MshrEvents};
use wasp_rtl::nonblocked::PriorityEvents;
use wasp_rtl::policy::{LaunchRule, PolicySpec};
use wasp_rtl::queue::QueueClass;
use wasp_rtl::scheduler::{EdgeEvents, LaunchDecision, LaunchScheduler};
use wasp_rtl::subset::SubsetSpec;
use wasp_rtl::RegisterFault;

mod explore;
mod model;

pub use explore::{explore_wasp, small_alphabet, Explored};
pub use model::Model;

/// Property name used in counterexamples.
pub const PROP: &str = "(a) scheduler vs model";

/// A scheduler configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct SchedConfig {
    /// The launch policy.
    pub policy: PolicySpec,
    /// The launch rule for a closed gate.
    pub launch_rule: LaunchRule,
    /// The priority subset.
    pub subset: SubsetSpec,
    /// MSHR entries of the scheduler-level cache (0..=31).
    pub mshrs: u32,
    /// Shared slots of the split input queue.
    pub queue_capacity: usize,
    /// Warp slots of the core (1..=127, see [`MAX_PRIORITY_WARPS`]).
    pub max_warps: u32,
}

/// One cycle's inputs as raw choices; [`SchedulerCheck::cycle`] turns them
/// into legal events.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct CycleChoice {
    /// A warp offered by the rasterizer at these in-tile quad coordinates.
    pub enqueue: Option<(u32, u32)>,
    /// The core wants to launch this cycle (granted only if it has a free
    /// warp slot).
    pub enable: bool,
    /// MSHR allocations, reduced modulo (free + replies + 1).
    pub allocs: u8,
    /// MSHR replies, reduced modulo (in flight + 1).
    pub replies: u8,
    /// Priority warps that block, reduced modulo (available + 1).
    pub blocked: u8,
    /// Blocked priority warps that unblock, reduced modulo (blocked + 1).
    pub unblocked: u8,
    /// Non-blocked priority warps that finish, reduced modulo (available + 1).
    pub finished: u8,
    /// Regular warps that finish, reduced modulo (regular in core + 1).
    pub regular_finished: u8,
}

/// The events of one cycle, as given to the scheduler's clock.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CycleEvents {
    /// MSHR allocations and replies.
    pub mshr: MshrEvents,
    /// Priority-warp events, without this cycle's launch (the scheduler
    /// counts its own launch).
    pub prio: PriorityEvents,
    /// Regular warps that finished.
    pub regular_finished: u32,
}

/// What happened in phase 1 of a cycle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Launched {
    /// The warp launched, if any, and its FIFO.
    pub warp: Option<(u32, QueueClass)>,
}

/// What a run exercised (to tell a vacuous pass from a real one).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Coverage {
    /// Priority warps launched.
    pub priority_launches: u64,
    /// Regular warps launched.
    pub regular_launches: u64,
    /// Decisions where a priority warp waited but the rule held it back.
    pub priority_held_back: u64,
    /// Warps refused by a full queue.
    pub queue_full_refusals: u64,
    /// Decisions taken with no free MSHR.
    pub no_free_mshr: u64,
    /// Largest non-blocked priority count seen.
    pub max_nonblocked: i64,
}

/// A scheduler and its reference model, driven in lockstep.
#[derive(Debug)]
pub struct SchedulerCheck {
    /// The scheduler under test.
    pub sched: LaunchScheduler<u32>,
    /// The reference.
    pub model: Model,
    /// Cycles run.
    pub cycle: u64,
    /// What the run exercised so far.
    pub coverage: Coverage,
    prio_launched: bool,
    regular_launched: bool,
}

/// The inputs of a cycle's decision as the model sees them: the register
/// values (free MSHRs, non-blocked priority warps) and which FIFOs hold a
/// warp.
#[derive(Clone, Copy, Debug)]
struct DecisionInputs {
    free: i64,
    nb: i64,
    pw: bool,
    rw: bool,
}

/// Reduce a raw choice to `0..=max`.
#[inline]
fn fit(raw: u8, max: i64) -> i64 {
    raw as i64 % (max + 1)
}

impl SchedulerCheck {
    /// A scheduler and a model in their reset states; `Err` if the
    /// configuration is refused (by `PolicySpec::build` or the register
    /// widths, or `max_warps` outside 1..=127).
    pub fn new(cfg: &SchedConfig) -> Result<Self, String> {
        if cfg.max_warps == 0 || cfg.max_warps > MAX_PRIORITY_WARPS {
            return Err(format!(
                "max_warps {} outside 1..={MAX_PRIORITY_WARPS}",
                cfg.max_warps
            ));
        }
        let policy = cfg.policy.build(cfg.mshrs)?;
        let reference = RefPolicy::from_spec(&cfg.policy)
            .ok_or_else(|| format!("no reference for {}", cfg.policy))?;
        let reg = FreeMshrReg::with_capacity(cfg.mshrs)
            .ok_or_else(|| format!("{} MSHRs do not fit 5 bits", cfg.mshrs))?;
        let sched = LaunchScheduler::new(
            cfg.queue_capacity,
            cfg.subset.build(32),
            reg,
            policy.as_ref(),
            cfg.launch_rule,
        );
        let model = Model {
            policy: reference,
            rule: cfg.launch_rule,
            subset_spec: cfg.subset.clone(),
            subset: cfg.subset.build(32),
            priority: VecDeque::new(),
            regular: VecDeque::new(),
            queue_capacity: cfg.queue_capacity,
            mshrs: cfg.mshrs as i64,
            in_flight: 0,
            nonblocked: 0,
            blocked: 0,
            regular_in_core: 0,
            max_warps: cfg.max_warps as i64,
            next_ticket: 0,
            accepted: 0,
            launched: 0,
        };
        Ok(Self {
            sched,
            model,
            cycle: 0,
            coverage: Coverage::default(),
            prio_launched: false,
            regular_launched: false,
        })
    }

    fn cex(&self, what: &'static str) -> Cex {
        let m = &self.model;
        Cex::new(PROP, what)
            .with("cycle", self.cycle as i64)
            .with("free", m.free())
            .with("nonblocked", m.nonblocked)
            .with("blocked", m.blocked)
            .with("prio_waiting", m.priority.len() as i64)
            .with("regular_waiting", m.regular.len() as i64)
    }

    /// Registers equal the model, and queue conservation holds.
    pub fn registers_match(&self) -> Result<(), Cex> {
        let free = self.sched.free_mshrs().free().get() as i64;
        let nb = self.sched.nonblocked().count().get() as i64;
        ensure(free == self.model.free(), || {
            self.cex("free_mshrs register differs from the model")
                .with("register", free)
        })?;
        ensure(nb == self.model.nonblocked, || {
            self.cex("nonblocked_priority register differs from the model")
                .with("register", nb)
        })?;
        let q = self.sched.queue();
        ensure(
            q.occupancy(QueueClass::Priority) == self.model.priority.len()
                && q.occupancy(QueueClass::Regular) == self.model.regular.len(),
            || self.cex("queue occupancy differs from the model"),
        )?;
        ensure(
            self.model.accepted == self.model.launched + self.model.waiting() as u64
                && q.len() <= self.model.queue_capacity,
            || self.cex("queue conservation violated"),
        )
    }

    /// Phase 1 of a cycle: offer `enqueue`, decide, launch if `enable` and
    /// the core has a free slot. Checks steps 1 to 3 of the module doc.
    pub fn front(&mut self, enqueue: Option<(u32, u32)>, enable: bool) -> Result<Launched, Cex> {
        self.prio_launched = false;
        self.regular_launched = false;
        // 1. Enqueue.
        if let Some((qx, qy)) = enqueue {
            self.enqueue(qx, qy)?;
        }
        // 2. Decide on the current register values.
        self.registers_match()?;
        let inputs = DecisionInputs {
            free: self.model.free(),
            nb: self.model.nonblocked,
            pw: !self.model.priority.is_empty(),
            rw: !self.model.regular.is_empty(),
        };
        let room = self.model.in_core() < self.model.max_warps;
        let enable = enable && room;
        let launch = self.sched.launch(enable);
        let want = self.check_decision(&launch.decision, inputs)?;
        // 3. Launch.
        let got = launch.warp;
        self.check_launch(got, want, enable, inputs)?;
        self.count_launch(got, inputs);
        Ok(Launched { warp: got })
    }

    /// Step 1: the rasterizer offers a warp at (`qx`, `qy`): its class is
    /// the reference's, and it is accepted iff the queue has room.
    fn enqueue(&mut self, qx: u32, qy: u32) -> Result<(), Cex> {
        let want = self.model.classify(qx, qy);
        let got = self.sched.classify(qx, qy);
        ensure(got == want, || {
            self.cex("classification differs from the reference subset")
                .with("qx", qx as i64)
                .with("qy", qy as i64)
        })?;
        let ticket = self.model.next_ticket;
        self.model.next_ticket += 1;
        let accept = self.model.waiting() < self.model.queue_capacity;
        match self.sched.enqueue(ticket, qx, qy) {
            Ok(c) => {
                ensure(accept && c == want, || {
                    self.cex("warp accepted into a full queue or the wrong FIFO")
                })?;
                self.model.fifo_mut(c).push_back(ticket);
                self.model.accepted += 1;
            }
            Err(t) => {
                ensure(!accept && t == ticket, || {
                    self.cex("warp refused below capacity, or another ticket returned")
                })?;
                self.coverage.queue_full_refusals += 1;
            }
        }
        Ok(())
    }

    /// Whether the launch rule lets a priority warp below the threshold
    /// launch: never under `hold`; under `launch` only with no regular warp
    /// waiting.
    fn below_ok(&self, inputs: DecisionInputs) -> bool {
        self.model.rule == LaunchRule::Launch && !inputs.rw
    }

    /// Step 2: the decision `d` against the reference policy (returned):
    /// WaSP's datapath outputs, (a) for a priority selection, the
    /// selection itself, the launch rule and `held`.
    fn check_decision(
        &self,
        d: &LaunchDecision,
        inputs: DecisionInputs,
    ) -> Result<Option<QueueClass>, Cex> {
        let DecisionInputs { free, nb, pw, rw } = inputs;
        let rule = self.model.rule;
        let want = self.model.policy.select(rule, pw, rw, free, nb);
        self.check_datapath(d, free, nb)?;
        let below_ok = self.below_ok(inputs);
        if let RefPolicy::Wasp { q, t } = self.model.policy {
            ensure(
                d.select != Some(QueueClass::Priority)
                    || exact_priority(free, nb, q, t)
                    || below_ok,
                || {
                    self.cex("(a) priority selected with Real_freeMSHRs <= Threshold")
                        .with("scaled_real_minus_threshold", 4 * free - q * nb - 4 * t)
                },
            )?;
        }
        ensure(d.select == want, || {
            self.cex("decision differs from the reference policy")
                .with("expected_select", class_code(want))
                .with("got_select", class_code(d.select))
        })?;
        ensure(
            rule == LaunchRule::Hold || d.select.is_some() == (pw || rw),
            || self.cex("launch rule `launch` idles while a warp waits"),
        )?;
        let held =
            rule == LaunchRule::Hold && pw && !rw && !self.model.policy.priority_allowed(free, nb);
        ensure(d.held == held, || {
            self.cex("`held` differs from: hold, a lone priority warp, gate closed")
        })?;
        Ok(want)
    }

    /// WaSP's datapath outputs equal the exact product, difference and
    /// comparison; other policies have no datapath.
    fn check_datapath(&self, d: &LaunchDecision, free: i64, nb: i64) -> Result<(), Cex> {
        match (self.model.policy, d.datapath) {
            (RefPolicy::Wasp { q, t }, Some(out)) => {
                let product = exact_product(nb, q);
                ensure(
                    out.product.get() as i64 == product
                        && out.real_free.get() as i64 == free - product
                        && out.priority_over_regular == exact_priority(free, nb, q, t),
                    || {
                        self.cex("datapath outputs differ from the exact arithmetic")
                            .with("real_free", out.real_free.get() as i64)
                    },
                )
            }
            (RefPolicy::Wasp { .. }, None) => Err(self.cex("WaSP decided without its datapath")),
            (_, Some(_)) => Err(self.cex("a non-WaSP policy has a datapath")),
            (_, None) => Ok(()),
        }
    }

    /// Step 3: the warp launched (`got`) is the head of the reference FIFO
    /// `want` when launching is enabled (popped from the model), and a
    /// priority launch keeps (a) on this cycle's register values.
    fn check_launch(
        &mut self,
        got: Option<(u32, QueueClass)>,
        want: Option<QueueClass>,
        enable: bool,
        inputs: DecisionInputs,
    ) -> Result<(), Cex> {
        let expect = match want {
            Some(c) if enable => self.model.fifo_mut(c).pop_front().map(|t| (t, c)),
            _ => None,
        };
        ensure(got == expect, || {
            self.cex("launched warp differs from the reference FIFO head")
                .with("expected", expect.map_or(-1, |(t, _)| t as i64))
                .with("got", got.map_or(-1, |(t, _)| t as i64))
        })?;
        if let (Some((_, QueueClass::Priority)), RefPolicy::Wasp { q, t }) =
            (got, self.model.policy)
        {
            // (a) at the scheduler level, on this cycle's register values.
            let (free, nb) = (inputs.free, inputs.nb);
            ensure(
                exact_priority(free, nb, q, t) || self.below_ok(inputs),
                || self.cex("(a) priority warp launched with Real_freeMSHRs <= Threshold"),
            )?;
        }
        Ok(())
    }

    /// Count the launch `got` in the coverage and the model.
    fn count_launch(&mut self, got: Option<(u32, QueueClass)>, inputs: DecisionInputs) {
        let DecisionInputs { free, nb, pw, .. } = inputs;
        let cov = &mut self.coverage;
        match got {
            Some((_, QueueClass::Priority)) => {
                self.prio_launched = true;
                cov.priority_launches += 1;
            }
            Some((_, QueueClass::Regular)) => {
                self.regular_launched = true;
                cov.regular_launches += 1;
            }
            None => {}
        }
        cov.priority_held_back += (pw && !self.model.policy.priority_allowed(free, nb)) as u64;
        cov.no_free_mshr += (free == 0) as u64;
        cov.max_nonblocked = cov.max_nonblocked.max(nb);
        self.model.launched += got.is_some() as u64;
    }

    /// Legal events for this cycle from raw choices (after [`Self::front`]).
    pub fn legalize(&self, c: &CycleChoice) -> CycleEvents {
        let m = &self.model;
        let l = self.prio_launched as i64;
        let replies = fit(c.replies, m.in_flight);
        let allocs = fit(c.allocs, m.free() + replies);
        let unblocked = fit(c.unblocked, m.blocked);
        let avail = m.nonblocked + l + unblocked;
        let blocked = fit(c.blocked, avail);
        let finished = fit(c.finished, avail - blocked);
        let regular_finished = fit(
            c.regular_finished,
            m.regular_in_core + self.regular_launched as i64,
        );
        CycleEvents {
            mshr: MshrEvents {
                allocs: allocs as u8,
                replies: replies as u8,
            },
            prio: PriorityEvents {
                launched: false,
                blocked: blocked as u8,
                unblocked: unblocked as u8,
                finished: finished as u8,
                misses: 0,
            },
            regular_finished: regular_finished as u32,
        }
    }

    /// Whether `ev` is legal in the model this cycle.
    pub fn legal(&self, ev: &CycleEvents) -> bool {
        let prio = PriorityEvents {
            launched: self.prio_launched,
            ..ev.prio
        };
        self.model.mshr_model().legal(ev.mshr)
            && self.model.priority_model().legal(prio)
            && (ev.regular_finished as i64)
                <= self.model.regular_in_core + self.regular_launched as i64
    }

    /// Phase 2: clock `ev` in and end the cycle. A legal event must not
    /// fault and must leave the registers equal to the model
    /// (`Ok(None)`). An event the model calls illegal must fault exactly
    /// when a register's exact next value leaves its range, and a fault
    /// must leave both registers unchanged (`Ok(Some(fault))`); the model
    /// is then not advanced.
    pub fn back(&mut self, ev: CycleEvents) -> Result<Option<RegisterFault>, Cex> {
        let legal = self.legal(&ev);
        let before = (self.sched.free_mshrs(), self.sched.nonblocked());
        let r = self.sched.clock(EdgeEvents {
            mshr: ev.mshr,
            prio: ev.prio,
        });
        self.cycle += 1;
        let l = self.prio_launched as i64;
        let free_next = self.model.free() - ev.mshr.allocs as i64 + ev.mshr.replies as i64;
        let nb_next = self.model.nonblocked + l + ev.prio.unblocked as i64
            - ev.prio.blocked as i64
            - ev.prio.finished as i64;
        let cex = |s: &Self, what| {
            s.cex(what)
                .with("allocs", ev.mshr.allocs as i64)
                .with("replies", ev.mshr.replies as i64)
                .with("ev_blocked", ev.prio.blocked as i64)
                .with("ev_unblocked", ev.prio.unblocked as i64)
        };
        if legal {
            if r.is_err() {
                return Err(cex(self, "RegisterFault under a legal event"));
            }
            let m = &mut self.model;
            m.in_flight += ev.mshr.allocs as i64 - ev.mshr.replies as i64;
            m.blocked += ev.prio.blocked as i64 - ev.prio.unblocked as i64;
            m.nonblocked = nb_next;
            m.regular_in_core += self.regular_launched as i64 - ev.regular_finished as i64;
            self.registers_match()?;
            return Ok(None);
        }
        let out_of_range = !(0..=self.model.mshrs).contains(&free_next)
            || !(0..=MAX_PRIORITY_WARPS as i64).contains(&nb_next);
        match r {
            Err(f) => {
                ensure(out_of_range, || {
                    cex(self, "fault with both values in range")
                })?;
                ensure(
                    (self.sched.free_mshrs(), self.sched.nonblocked()) == before,
                    || cex(self, "a faulting clock changed a register"),
                )?;
                Ok(Some(f))
            }
            Ok(()) => {
                ensure(!out_of_range, || {
                    cex(self, "out-of-range event accepted (wrapped)")
                        .with("free_next", free_next)
                        .with("nonblocked_next", nb_next)
                })?;
                ensure(
                    self.sched.free_mshrs().free().get() as i64 == free_next
                        && self.sched.nonblocked().count().get() as i64 == nb_next,
                    || cex(self, "model-illegal event in range: register not exact"),
                )?;
                Ok(None)
            }
        }
    }

    /// One whole cycle from raw choices (all events legal).
    pub fn cycle(&mut self, c: &CycleChoice) -> Result<Launched, Cex> {
        let launched = self.front(c.enqueue, c.enable)?;
        let ev = self.legalize(c);
        debug_assert!(self.legal(&ev));
        match self.back(ev)? {
            None => Ok(launched),
            Some(_) => Err(self.cex("legalized event faulted")),
        }
    }
}

/// Run `choices` from reset on `cfg`, checking every cycle.
pub fn run(cfg: &SchedConfig, choices: &[CycleChoice]) -> Result<(), Cex> {
    let mut s = match SchedulerCheck::new(cfg) {
        Ok(s) => s,
        Err(_) => return Err(Cex::new(PROP, "configuration refused")),
    };
    for c in choices {
        s.cycle(c)?;
    }
    Ok(())
}

#[cfg(any(kani, feature = "kani-shim"))]
mod proofs {
    use super::*;

    /// Cycles of the Kani harness.
    const KANI_CYCLES: usize = 3;

    /// Twin: `tests::exhaustive_wasp_scheduler_depth6_a`, `_b` and
    /// `_launch`. WaSP with any CF, any threshold below 4 MSHRs, either
    /// launch rule, a queue of 2, symbolic inputs for 3 cycles.
    #[kani::proof]
    #[kani::unwind(8)]
    fn proof_wasp_scheduler_cycles() {
        let q: u8 = kani::any_where(|q: &u8| *q <= 31);
        let t: u8 = kani::any_where(|t: &u8| *t < 4);
        let launch: bool = kani::any();
        let cfg = SchedConfig {
            policy: PolicySpec::Wasp {
                threshold: t as u32,
                cf: q as f64 / 4.0,
            },
            launch_rule: if launch {
                LaunchRule::Launch
            } else {
                LaunchRule::Hold
            },
            subset: SubsetSpec::Mesh(4),
            mshrs: 4,
            queue_capacity: 2,
            max_warps: 127,
        };
        let mut s = SchedulerCheck::new(&cfg).unwrap();
        for _ in 0..KANI_CYCLES {
            let enq: u8 = kani::any();
            let c = CycleChoice {
                enqueue: match enq % 3 {
                    0 => None,
                    1 => Some((0, 0)),
                    _ => Some((1, 0)),
                },
                enable: kani::any(),
                allocs: kani::any(),
                replies: kani::any(),
                blocked: kani::any(),
                unblocked: kani::any(),
                finished: kani::any(),
                regular_finished: kani::any(),
            };
            assert!(s.cycle(&c).is_ok());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every WaSP configuration below, every input sequence of length up to
    /// 6 over [`small_alphabet`] (192 choices per cycle).
    pub const DEPTH: usize = 6;

    fn wasp_cfg(threshold: u32, q: u32, mshrs: u32, queue: usize) -> SchedConfig {
        SchedConfig {
            policy: PolicySpec::Wasp {
                threshold,
                cf: q as f64 / 4.0,
            },
            launch_rule: LaunchRule::Hold,
            subset: SubsetSpec::Mesh(4),
            mshrs,
            queue_capacity: queue,
            max_warps: 127,
        }
    }

    fn explore(configs: &[(u32, u32)], launch_rule: LaunchRule) {
        let alphabet = small_alphabet();
        for &(t, q) in configs {
            let cfg = SchedConfig {
                launch_rule,
                ..wasp_cfg(t, q, 2, 2)
            };
            let st =
                explore_wasp(&cfg, &alphabet, DEPTH).unwrap_or_else(|e| panic!("{cfg:?}: {e}"));
            assert!(st.states > 1 && st.transitions > 0, "{st:?}");
            assert!(st.priority_launches > 0, "{cfg:?}: {st:?}");
        }
    }

    /// MSHRs 2, queue 2: threshold 0 with CF 1 and 2.5; threshold 1 with
    /// CF 0 and 1 (WaSP holds priority warps back in each).
    #[test]
    fn exhaustive_wasp_scheduler_depth6_a() {
        explore(&[(0, 4), (0, 10)], LaunchRule::Hold);
    }

    #[test]
    fn exhaustive_wasp_scheduler_depth6_b() {
        explore(&[(1, 0), (1, 4)], LaunchRule::Hold);
    }

    /// The work-conserving rule on the configurations of `_a` and `_b`
    /// where WaSP closes its gate most (threshold 1).
    #[test]
    fn exhaustive_wasp_scheduler_depth6_launch() {
        explore(&[(1, 0), (1, 4), (0, 10)], LaunchRule::Launch);
    }

    /// Under `hold` a closed gate with only a priority warp waiting idles
    /// and says so (`held`); under `launch` the warp launches.
    #[test]
    fn a_lone_priority_warp_with_the_gate_closed() {
        for rule in LaunchRule::ALL {
            let cfg = SchedConfig {
                launch_rule: rule,
                // Threshold 1 of 2 MSHRs: one miss closes the gate.
                ..wasp_cfg(1, 4, 2, 4)
            };
            let mut s = SchedulerCheck::new(&cfg).unwrap();
            let l = s
                .cycle(&CycleChoice {
                    enqueue: Some((0, 0)),
                    enable: true,
                    allocs: 1,
                    blocked: 1,
                    ..Default::default()
                })
                .unwrap();
            assert!(matches!(l.warp, Some((_, QueueClass::Priority))));
            let l = s
                .cycle(&CycleChoice {
                    enqueue: Some((4, 0)),
                    enable: true,
                    ..Default::default()
                })
                .unwrap();
            match rule {
                LaunchRule::Hold => assert_eq!(l.warp, None),
                LaunchRule::Launch => {
                    assert!(matches!(l.warp, Some((_, QueueClass::Priority))))
                }
            }
        }
    }

    /// The register extremes through the scheduler: 127 priority warps
    /// launched (each blocking at once, so WaSP with CF 7.75 and threshold
    /// 0 keeps launching), then all unblocked in one cycle: the counter
    /// holds 127 and the datapath sees 31 - floor(7.75 x 127) = -953.
    #[test]
    fn extreme_register_values_through_the_scheduler() {
        let mut cfg = wasp_cfg(0, 31, 31, 4);
        cfg.max_warps = 127;
        let mut s = SchedulerCheck::new(&cfg).unwrap();
        for _ in 0..127 {
            let l = s
                .cycle(&CycleChoice {
                    enqueue: Some((0, 0)),
                    enable: true,
                    blocked: 1,
                    ..Default::default()
                })
                .unwrap();
            assert!(matches!(l.warp, Some((_, QueueClass::Priority))));
        }
        assert_eq!((s.model.nonblocked, s.model.blocked), (0, 127));
        // The core is full: no launch although a priority warp waits.
        let l = s
            .cycle(&CycleChoice {
                enqueue: Some((0, 0)),
                enable: true,
                unblocked: 127,
                ..Default::default()
            })
            .unwrap();
        assert_eq!(l.warp, None);
        assert_eq!(s.sched.nonblocked().count().get(), 127);
        let d = s.sched.launch(false).decision;
        let out = d.datapath.unwrap();
        assert_eq!(out.real_free.get(), 31 - 984);
        assert_eq!(d.select, None);
        // And back down: all 127 finish in one cycle.
        s.cycle(&CycleChoice {
            finished: 127,
            ..Default::default()
        })
        .unwrap();
        assert_eq!(s.sched.nonblocked().count().get(), 0);
    }

    #[test]
    fn illegal_events_fault_without_changing_registers() {
        let cfg = wasp_cfg(1, 10, 2, 2);
        let mut s = SchedulerCheck::new(&cfg).unwrap();
        s.front(Some((0, 0)), true).unwrap();
        // A reply with nothing in flight: free would be 3 > 2.
        let ev = CycleEvents {
            mshr: MshrEvents {
                allocs: 0,
                replies: 1,
            },
            ..Default::default()
        };
        assert!(!s.legal(&ev));
        let f = s.back(ev).unwrap().expect("fault");
        assert_eq!(f.register, "free_mshrs");
        // The launch was not counted either: the clock is all or nothing.
        assert_eq!(s.sched.nonblocked().count().get(), 0);
    }
}
