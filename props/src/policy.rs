//! (a) Under the launch rule `hold`, WaSP never launches a priority warp
//! when `Real_freeMSHRs <= Threshold`; under `launch` it does so only when
//! no regular warp waits, and never idles while a warp waits. Every
//! policy's `select` equals an exact reference under both rules.
//!
//! [`RefPolicy`] restates each launch rule in unbounded `i64` arithmetic on
//! the register values (for WaSP, the real-number rule scaled by 4). The
//! scheduler-level check ([`crate::scheduler`]) uses it as its reference.
//!
//! Counterexamples give a selection as the `launch` signal's code
//! ([`class_code`]): 0 none, 1 regular, 2 priority.

use crate::cex::{ensure, Cex};
use crate::datapath::exact_priority;
use wasp_rtl::datapath::{Cf, Threshold, WaspDatapath};
use wasp_rtl::free_mshr::FreeMshrs;
use wasp_rtl::nonblocked::NonblockedCount;
use wasp_rtl::policy::{LaunchPolicy, LaunchRule, LaunchView, PolicySpec, Wasp};
use wasp_rtl::queue::QueueClass;

/// Property name used in counterexamples.
pub const PROP: &str = "(a) WaSP threshold";
/// Property name for the other policies' reference check.
pub const PROP_REF: &str = "(a') policy reference";

/// A launch rule in exact arithmetic.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RefPolicy {
    /// Scanline order: every warp is regular.
    Baseline,
    /// Priority whenever one waits.
    FullPriority,
    /// Priority while `free >= n`.
    FreeMshr {
        /// N.
        n: i64,
    },
    /// Priority while `free - (q/4) nonblocked > t`.
    Wasp {
        /// CF in quarters.
        q: i64,
        /// Threshold.
        t: i64,
    },
}

impl RefPolicy {
    /// The reference of a policy named by `spec` (as `PolicySpec::build`
    /// would build it); `None` for a WaSP CF that is not a multiple of 0.25,
    /// and for `wasp-m`, whose CF is the state of its meter (checked by the
    /// meter's own exhaustive twin in `wasp_rtl::cf_meter`).
    pub fn from_spec(spec: &PolicySpec) -> Option<Self> {
        Some(match *spec {
            PolicySpec::Baseline => RefPolicy::Baseline,
            PolicySpec::FullPriority => RefPolicy::FullPriority,
            PolicySpec::FreeMshr(n) => RefPolicy::FreeMshr { n: n as i64 },
            PolicySpec::Wasp { threshold, cf } => {
                let q = cf * 4.0;
                if !(q.is_finite() && q >= 0.0 && q.fract() == 0.0) {
                    return None;
                }
                RefPolicy::Wasp {
                    q: q as i64,
                    t: threshold as i64,
                }
            }
            PolicySpec::WaspMeasured { .. } => return None,
        })
    }

    /// Whether warps are ever sent to the priority FIFO.
    pub fn uses_priority_queue(&self) -> bool {
        !matches!(self, RefPolicy::Baseline)
    }

    /// Whether the rule lets a priority warp go at these register values.
    pub fn priority_allowed(&self, free: i64, nonblocked: i64) -> bool {
        match *self {
            RefPolicy::Baseline => false,
            RefPolicy::FullPriority => true,
            RefPolicy::FreeMshr { n } => free >= n,
            RefPolicy::Wasp { q, t } => exact_priority(free, nonblocked, q, t),
        }
    }

    /// The FIFO to launch from: priority if one waits and the policy allows
    /// it, else regular if one waits, else priority if one waits and the
    /// launch rule is `launch`, else none.
    pub fn select(
        &self,
        rule: LaunchRule,
        priority_waiting: bool,
        regular_waiting: bool,
        free: i64,
        nonblocked: i64,
    ) -> Option<QueueClass> {
        if priority_waiting && self.priority_allowed(free, nonblocked) {
            Some(QueueClass::Priority)
        } else if regular_waiting {
            Some(QueueClass::Regular)
        } else if priority_waiting && rule == LaunchRule::Launch {
            Some(QueueClass::Priority)
        } else {
            None
        }
    }
}

/// The view the scheduler presents to `policy` at these register values
/// (the datapath evaluated when the policy has one).
pub fn scheduler_view(
    policy: &dyn LaunchPolicy,
    free: FreeMshrs,
    nonblocked: NonblockedCount,
    priority_waiting: bool,
    regular_waiting: bool,
) -> LaunchView {
    LaunchView {
        priority_waiting,
        regular_waiting,
        free_mshrs: free,
        datapath: policy.datapath().map(|dp| dp.eval(free, nonblocked)),
    }
}

/// The four combinations of (`priority_waiting`, `regular_waiting`).
pub const FIFO_FLAGS: [(bool, bool); 4] =
    [(false, false), (false, true), (true, false), (true, true)];

/// (a), combinational: for the WaSP policy with CF `cf` and threshold `t`,
/// at register values `free`, `nonblocked`, for each of the four
/// combinations of `priority_waiting` and `regular_waiting` and under both
/// launch rules, `select` returns `Priority` only if a priority warp waits
/// and, under `hold`, only if the exact `free - CF x nonblocked > t` holds
/// (under `launch`: if it holds or no regular warp waits); under `launch`
/// it selects a FIFO whenever a warp waits (work-conserving); and it equals
/// the exact WaSP rule ([`RefPolicy::Wasp`]). The datapath is evaluated
/// once, as the scheduler does, and the view differs only in the two FIFO
/// flags.
pub fn wasp_priority_only_above_threshold(
    free: FreeMshrs,
    nonblocked: NonblockedCount,
    cf: Cf,
    threshold: Threshold,
) -> Result<(), Cex> {
    let dp = WaspDatapath { cf, threshold };
    let policy = Wasp::new(dp);
    let out = dp.eval(free, nonblocked);
    let (f, n, q, t) = (
        free.get() as i64,
        nonblocked.get() as i64,
        cf.quarters() as i64,
        threshold.get() as i64,
    );
    let exact = exact_priority(f, n, q, t);
    for rule in LaunchRule::ALL {
        for (priority_waiting, regular_waiting) in FIFO_FLAGS {
            let view = LaunchView {
                priority_waiting,
                regular_waiting,
                free_mshrs: free,
                datapath: Some(out),
            };
            let got = (&policy as &dyn LaunchPolicy).select(rule, &view);
            let cex = |what| {
                Cex::new(PROP, what)
                    .with("launch_rule", rule as i64)
                    .with("free", f)
                    .with("nonblocked", n)
                    .with("cf_quarters", q)
                    .with("threshold", t)
                    .with("priority_waiting", priority_waiting as i64)
                    .with("regular_waiting", regular_waiting as i64)
            };
            // hold: never below the threshold; launch: below it only when
            // no regular warp waits.
            let below_allowed = rule == LaunchRule::Launch && !regular_waiting;
            ensure(
                got != Some(QueueClass::Priority) || exact || below_allowed,
                || {
                    cex("priority warp selected with Real_freeMSHRs <= Threshold (exact)")
                        .with("scaled_real_minus_threshold", 4 * f - q * n - 4 * t)
                },
            )?;
            ensure(
                got != Some(QueueClass::Priority) || priority_waiting,
                || cex("priority FIFO selected while empty"),
            )?;
            ensure(
                rule == LaunchRule::Hold || got.is_some() == (priority_waiting || regular_waiting),
                || cex("launch rule `launch` idles while a warp waits"),
            )?;
            let want =
                RefPolicy::Wasp { q, t }.select(rule, priority_waiting, regular_waiting, f, n);
            ensure(got == want, || {
                cex("select differs from the exact WaSP rule")
                    .with("expected_select", class_code(want))
                    .with("got_select", class_code(got))
            })?;
        }
    }
    Ok(())
}

/// (a), without a datapath: WaSP given a view with no datapath output
/// treats the gate as closed: never the priority FIFO under `hold`, and
/// under `launch` only when no regular warp waits.
pub fn wasp_without_datapath_never_priority(
    cf: Cf,
    threshold: Threshold,
    free: FreeMshrs,
    priority_waiting: bool,
    regular_waiting: bool,
) -> Result<(), Cex> {
    let policy = Wasp::new(WaspDatapath { cf, threshold });
    for rule in LaunchRule::ALL {
        let got = (&policy as &dyn LaunchPolicy).select(
            rule,
            &LaunchView {
                priority_waiting,
                regular_waiting,
                free_mshrs: free,
                datapath: None,
            },
        );
        let closed = match rule {
            LaunchRule::Hold => None,
            LaunchRule::Launch => priority_waiting.then_some(QueueClass::Priority),
        };
        let want = if regular_waiting {
            Some(QueueClass::Regular)
        } else {
            closed
        };
        ensure(got == want, || {
            Cex::new(PROP, "no datapath output must act as a closed gate")
                .with("launch_rule", rule as i64)
                .with("free", free.get() as i64)
                .with("priority_waiting", priority_waiting as i64)
                .with("regular_waiting", regular_waiting as i64)
                .with("expected_select", class_code(want))
                .with("got_select", class_code(got))
        })?;
    }
    Ok(())
}

/// Any policy: at these register values and FIFO flags, under both launch
/// rules, `select` on the view the scheduler builds equals `reference`, and
/// never names an empty FIFO.
pub fn policy_matches_reference(
    policy: &dyn LaunchPolicy,
    reference: RefPolicy,
    free: FreeMshrs,
    nonblocked: NonblockedCount,
    priority_waiting: bool,
    regular_waiting: bool,
) -> Result<(), Cex> {
    let view = scheduler_view(policy, free, nonblocked, priority_waiting, regular_waiting);
    let (f, n) = (free.get() as i64, nonblocked.get() as i64);
    for rule in LaunchRule::ALL {
        let got = policy.select(rule, &view);
        let want = reference.select(rule, priority_waiting, regular_waiting, f, n);
        let cex = |what| {
            Cex::new(PROP_REF, what)
                .with("launch_rule", rule as i64)
                .with("free", f)
                .with("nonblocked", n)
                .with("priority_waiting", priority_waiting as i64)
                .with("regular_waiting", regular_waiting as i64)
                .with("expected_select", class_code(want))
                .with("got_select", class_code(got))
        };
        let waiting = match got {
            None => true,
            Some(QueueClass::Priority) => priority_waiting,
            Some(QueueClass::Regular) => regular_waiting,
        };
        ensure(waiting, || cex("selected an empty FIFO"))?;
        ensure(got == want, || {
            cex("select differs from the reference rule")
        })?;
    }
    Ok(())
}

/// The `launch` signal encoding (0 none, 1 regular, 2 priority) as `i64`.
pub fn class_code(c: Option<QueueClass>) -> i64 {
    wasp_rtl::scheduler::launch_code(c) as i64
}

#[cfg(any(kani, feature = "kani-shim"))]
mod proofs {
    use super::*;
    use wasp_rtl::policy::{Baseline, FreeMshrN, FullPriority};

    fn any_u5() -> u32 {
        let v: u8 = kani::any_where(|v: &u8| *v <= 31);
        v as u32
    }

    fn any_nonblocked() -> NonblockedCount {
        let v: u8 = kani::any_where(|v: &u8| *v <= 127);
        NonblockedCount::masked(v as u32)
    }

    /// Twin: `tests::exhaustive_wasp_select_q0_to_15` and `_q16_to_31`.
    #[kani::proof]
    #[kani::unwind(7)]
    fn proof_wasp_priority_only_above_threshold() {
        let r = wasp_priority_only_above_threshold(
            FreeMshrs::masked(any_u5()),
            any_nonblocked(),
            Cf::from_quarters(any_u5()).unwrap(),
            Threshold::masked(any_u5()),
        );
        assert!(r.is_ok());
    }

    /// Twin: `tests::exhaustive_wasp_without_datapath`.
    #[kani::proof]
    fn proof_wasp_without_datapath_never_priority() {
        let r = wasp_without_datapath_never_priority(
            Cf::from_quarters(any_u5()).unwrap(),
            Threshold::masked(any_u5()),
            FreeMshrs::masked(any_u5()),
            kani::any(),
            kani::any(),
        );
        assert!(r.is_ok());
    }

    /// Twin: `tests::exhaustive_other_policies`.
    #[kani::proof]
    fn proof_other_policies_match_reference() {
        let free = FreeMshrs::masked(any_u5());
        let nb = any_nonblocked();
        let (pw, rw): (bool, bool) = (kani::any(), kani::any());
        let n = any_u5();
        assert!(policy_matches_reference(&Baseline, RefPolicy::Baseline, free, nb, pw, rw).is_ok());
        assert!(
            policy_matches_reference(&FullPriority, RefPolicy::FullPriority, free, nb, pw, rw)
                .is_ok()
        );
        let fm = FreeMshrN::new(FreeMshrs::masked(n));
        let r = RefPolicy::FreeMshr { n: n as i64 };
        assert!(policy_matches_reference(&fm, r, free, nb, pw, rw).is_ok());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cex::check;
    use wasp_rtl::policy::{Baseline, FreeMshrN, FullPriority};

    const FLAGS: [(bool, bool); 4] = FIFO_FLAGS;

    /// Every free (0..=31) x nonblocked (0..=127) x q (0..=31) x T (0..=31)
    /// x priority_waiting x regular_waiting: 16,777,216 points. Split by CF
    /// into two tests so that the test harness runs them on both cores.
    fn wasp_select_for_quarters(qs: std::ops::RangeInclusive<u32>) -> u64 {
        let mut points = 0;
        for q in qs {
            let cf = Cf::from_quarters(q).unwrap();
            for t in 0..=31 {
                let th = Threshold::masked(t);
                for n in 0..=127 {
                    let nb = NonblockedCount::masked(n);
                    for f in 0..=31 {
                        let free = FreeMshrs::masked(f);
                        check(wasp_priority_only_above_threshold(free, nb, cf, th));
                        points += FLAGS.len() as u64;
                    }
                }
            }
        }
        points
    }

    #[test]
    fn exhaustive_wasp_select_q0_to_15() {
        assert_eq!(wasp_select_for_quarters(0..=15), 16 * 32 * 128 * 32 * 4);
    }

    #[test]
    fn exhaustive_wasp_select_q16_to_31() {
        assert_eq!(wasp_select_for_quarters(16..=31), 16 * 32 * 128 * 32 * 4);
    }

    /// WaSP with no datapath output: every q, T, free and flag pair.
    #[test]
    fn exhaustive_wasp_without_datapath() {
        for q in 0..=31 {
            for t in 0..=31 {
                for f in 0..=31 {
                    for (pw, rw) in FLAGS {
                        check(wasp_without_datapath_never_priority(
                            Cf::from_quarters(q).unwrap(),
                            Threshold::masked(t),
                            FreeMshrs::masked(f),
                            pw,
                            rw,
                        ));
                    }
                }
            }
        }
    }

    /// Baseline, Fullpriority and FreeMSHR-N for every N (0..=31), over
    /// every free x nonblocked x flag pair.
    #[test]
    fn exhaustive_other_policies() {
        let mut policies: Vec<(Box<dyn LaunchPolicy>, RefPolicy)> = vec![
            (Box::new(Baseline), RefPolicy::Baseline),
            (Box::new(FullPriority), RefPolicy::FullPriority),
        ];
        for n in 0..=31 {
            policies.push((
                Box::new(FreeMshrN::new(FreeMshrs::masked(n))),
                RefPolicy::FreeMshr { n: n as i64 },
            ));
        }
        for (p, r) in &policies {
            for f in 0..=31 {
                for n in 0..=127 {
                    for (pw, rw) in FLAGS {
                        check(policy_matches_reference(
                            p.as_ref(),
                            *r,
                            FreeMshrs::masked(f),
                            NonblockedCount::masked(n),
                            pw,
                            rw,
                        ));
                    }
                }
            }
        }
    }

    /// The reference agrees with the specs `PolicySpec::build` accepts.
    #[test]
    fn reference_from_spec() {
        assert_eq!(
            RefPolicy::from_spec(&PolicySpec::wasp(4)),
            Some(RefPolicy::Wasp { q: 10, t: 4 })
        );
        assert_eq!(
            RefPolicy::from_spec(&PolicySpec::Wasp {
                threshold: 1,
                cf: 2.3
            }),
            None
        );
        assert!(!RefPolicy::Baseline.uses_priority_queue());
        // The rules differ only with a lone priority warp and a closed gate.
        let w = RefPolicy::Wasp { q: 10, t: 4 };
        assert_eq!(w.select(LaunchRule::Hold, true, false, 4, 0), None);
        assert_eq!(
            w.select(LaunchRule::Launch, true, false, 4, 0),
            Some(QueueClass::Priority)
        );
        assert_eq!(
            w.select(LaunchRule::Launch, true, true, 4, 0),
            Some(QueueClass::Regular)
        );
        assert!(RefPolicy::FreeMshr { n: 3 }.uses_priority_queue());
    }
}
