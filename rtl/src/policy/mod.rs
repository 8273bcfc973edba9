//! Launch policies: which input FIFO the core launches its next warp from.
//!
//! Every policy decides from the same inputs the hardware has in the cycle
//! of the launch: whether each FIFO holds a warp, the free-MSHR register, and
//! the decision datapath's outputs. One file per policy.
//!
//! All four share one launch rule and differ only in its gate
//! ([`PriorityGate`]): a priority warp if one waits and the gate is open,
//! else a regular warp if one waits, else -- when only a priority warp
//! waits and the gate is closed -- what the [`LaunchRule`] says: nothing
//! ([`LaunchRule::Hold`], the paper's rule and the default) or that priority
//! warp ([`LaunchRule::Launch`], work-conserving). A policy names its gate;
//! [`PriorityGate::select`] is the rule around it. The scheduler reads the
//! gate once when it is built, is built with the launch rule, and evaluates
//! the rule itself each cycle.

mod baseline;
mod freemshr;
mod fullpriority;
mod name;
mod wasp;
mod wasp_measured;

pub use baseline::Baseline;
pub use freemshr::FreeMshrN;
pub use fullpriority::FullPriority;
pub use name::{PolicyFamily, PolicyName};
pub use wasp::Wasp;
pub use wasp_measured::WaspMeasured;

use crate::datapath::{Cf, DatapathOut, Threshold, WaspDatapath};
use crate::free_mshr::FreeMshrs;
use crate::queue::QueueClass;
use std::fmt;
use std::str::FromStr;

/// What a policy sees in the cycle it decides.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LaunchView {
    /// A warp waits in the priority FIFO.
    pub priority_waiting: bool,
    /// A warp waits in the regular FIFO.
    pub regular_waiting: bool,
    /// The free-MSHR register.
    pub free_mshrs: FreeMshrs,
    /// The decision datapath's outputs, for policies that have the datapath.
    pub datapath: Option<DatapathOut>,
}

/// What the core launches when a priority warp waits, the gate is closed
/// and no regular warp waits.
///
/// The paper (Section IV-C): "If the boolean evaluates to true, a priority
/// warp (if available) is launched; otherwise, a regular warp is launched",
/// and "this estimation prevents launching a new priority warp"; its worked
/// example: "W10 is delayed until there is more space in the MSHR". A
/// closed gate therefore holds the priority warp even when no regular warp
/// is there to launch instead: [`LaunchRule::Hold`]. [`LaunchRule::Launch`]
/// is the work-conserving alternative (wasp): the core never idles while a
/// warp waits and it has a free slot.
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, serde::Serialize, serde::Deserialize,
)]
#[serde(try_from = "String", into = "String")]
pub enum LaunchRule {
    /// Launch nothing (the paper's rule).
    #[default]
    Hold,
    /// Launch the waiting priority warp anyway (work-conserving).
    Launch,
}

impl LaunchRule {
    /// Both rules, default first.
    pub const ALL: [LaunchRule; 2] = [LaunchRule::Hold, LaunchRule::Launch];

    /// The name used on the command line and in config files.
    pub fn name(self) -> &'static str {
        match self {
            LaunchRule::Hold => "hold",
            LaunchRule::Launch => "launch",
        }
    }
}

impl fmt::Display for LaunchRule {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for LaunchRule {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.trim().to_ascii_lowercase().as_str() {
            "hold" => Ok(LaunchRule::Hold),
            "launch" => Ok(LaunchRule::Launch),
            _ => Err(format!(
                "unknown launch rule `{s}` (expected hold or launch)"
            )),
        }
    }
}

/// Read from its name in a config file: the error names the allowed forms.
impl TryFrom<String> for LaunchRule {
    type Error = String;
    fn try_from(s: String) -> Result<Self, String> {
        s.parse()
    }
}

impl From<LaunchRule> for String {
    fn from(r: LaunchRule) -> String {
        r.to_string()
    }
}

/// When a waiting priority warp may launch (ahead of any regular warp).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PriorityGate {
    /// Never: the policy has no priority warps (the baseline).
    Closed,
    /// Always (Fullpriority).
    Open,
    /// While the free-MSHR register holds at least N (FreeMSHR-N).
    FreeMshrsAtLeast(FreeMshrs),
    /// While the decision datapath says `Real_freeMSHRs > threshold`
    /// (WaSP); closed when the view has no datapath output.
    Datapath,
}

impl PriorityGate {
    /// Whether the gate is open in the cycle `v` describes.
    #[inline]
    pub fn is_open(self, v: &LaunchView) -> bool {
        match self {
            PriorityGate::Closed => false,
            PriorityGate::Open => true,
            PriorityGate::FreeMshrsAtLeast(n) => v.free_mshrs >= n,
            PriorityGate::Datapath => v.datapath.is_some_and(|d| d.priority_over_regular),
        }
    }

    /// The launch rule: the priority FIFO if a warp waits there and the gate
    /// is open, else the regular FIFO if a warp waits there, else the
    /// priority FIFO if a warp waits there and `rule` is
    /// [`LaunchRule::Launch`], else nothing.
    #[inline]
    pub fn select(self, rule: LaunchRule, v: &LaunchView) -> Option<QueueClass> {
        if v.priority_waiting && self.is_open(v) {
            Some(QueueClass::Priority)
        } else if v.regular_waiting {
            Some(QueueClass::Regular)
        } else if v.priority_waiting && rule == LaunchRule::Launch {
            Some(QueueClass::Priority)
        } else {
            None
        }
    }

    /// Whether `rule` decides this cycle: a priority warp waits, the gate
    /// is closed and no regular warp waits. Only then do the two rules
    /// differ (a hold under [`LaunchRule::Hold`]).
    #[inline]
    pub fn rule_decides(self, v: &LaunchView) -> bool {
        v.priority_waiting && !v.regular_waiting && !self.is_open(v)
    }
}

/// A warp launch policy.
pub trait LaunchPolicy: fmt::Debug + Send + Sync {
    /// Name as used on the command line (`baseline`, `wasp:4`, ...).
    fn name(&self) -> String;
    /// Whether the policy uses the priority FIFO at all. The baseline does
    /// not: it sends every warp to the regular FIFO, which then behaves as
    /// the baseline's single scanline-ordered queue.
    fn uses_priority_queue(&self) -> bool {
        true
    }
    /// Whether the policy reads the free-MSHR register (WaSP and
    /// FreeMSHR-N do; the baseline and Fullpriority do not, so their
    /// scheduler-level cache may have more MSHRs than 5 bits can count).
    fn reads_free_mshrs(&self) -> bool {
        self.datapath().is_some()
    }
    /// The datapath constants, for policies that use the WaSP datapath.
    fn datapath(&self) -> Option<WaspDatapath> {
        None
    }
    /// Whether the datapath's CF comes from the core's CF meter
    /// ([`crate::cf_meter`]) rather than a wired constant (`wasp-m`).
    fn measures_cf(&self) -> bool {
        false
    }
    /// When a waiting priority warp may launch. A policy is fixed wiring:
    /// the gate never changes.
    fn gate(&self) -> PriorityGate;
}

impl dyn LaunchPolicy + '_ {
    /// Which FIFO to launch from this cycle, or `None` to launch nothing:
    /// the shared launch rule ([`PriorityGate::select`]) under `rule` around
    /// this policy's gate. Not a trait method, so no policy can decide
    /// otherwise than the gate it names (the scheduler evaluates the rule on
    /// the gate directly).
    pub fn select(&self, rule: LaunchRule, v: &LaunchView) -> Option<QueueClass> {
        self.gate().select(rule, v)
    }
}

/// A policy named on the command line or in a config file (where it is
/// written as its name, `wasp:0:3`).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "String", into = "String")]
pub enum PolicySpec {
    /// Scanline order: one FIFO, no priority warps.
    Baseline,
    /// All priority warps before any regular warp.
    FullPriority,
    /// Priority warps only while at least N MSHRs are free.
    FreeMshr(u32),
    /// WaSP with a threshold and CF.
    Wasp {
        /// `Real_freeMSHRs > threshold` launches a priority warp.
        threshold: u32,
        /// Expected misses per non-blocked priority warp.
        cf: f64,
    },
    /// WaSP whose CF a per-core meter measures (beyond the paper).
    WaspMeasured {
        /// `Real_freeMSHRs > threshold` launches a priority warp.
        threshold: u32,
    },
}

impl PolicySpec {
    /// The shipped machine's policy (configs/paper.toml): WaSP with
    /// threshold 0 and CF 3. A bare `wasp` in a configuration file means
    /// it; on the command line a bare name takes the machine's own
    /// ([`PolicyName::resolve`]).
    pub const SHIPPED_WASP: PolicySpec = PolicySpec::Wasp {
        threshold: 0,
        cf: 3.0,
    };

    /// The N of a bare `freemshr` when the machine's policy is not a
    /// FreeMSHR-N: the paper's rival Freemshr10.
    pub const FREEMSHR_DEFAULT: u32 = 10;

    /// The paper's WaSP with threshold `t` and CF = 2.5.
    pub fn wasp(threshold: u32) -> Self {
        PolicySpec::Wasp { threshold, cf: 2.5 }
    }

    /// The measured-CF variant at this policy's threshold (`wasp-m:T` for
    /// `wasp:T:CF` or `wasp-m:T`); the shipped threshold otherwise.
    pub fn measured(self) -> Self {
        match self {
            PolicySpec::Wasp { threshold, .. } | PolicySpec::WaspMeasured { threshold } => {
                PolicySpec::WaspMeasured { threshold }
            }
            _ => PolicySpec::SHIPPED_WASP.measured(),
        }
    }

    /// Whether the policy reads the free-MSHR register.
    pub fn reads_free_mshrs(&self) -> bool {
        matches!(
            self,
            PolicySpec::FreeMshr(_) | PolicySpec::Wasp { .. } | PolicySpec::WaspMeasured { .. }
        )
    }

    /// Build the policy for a scheduler-level cache with `mshrs` entries,
    /// checking that the registers can hold the constants and that priority
    /// warps can always launch eventually.
    pub fn build(&self, mshrs: u32) -> Result<Box<dyn LaunchPolicy>, String> {
        match *self {
            PolicySpec::Baseline => Ok(Box::new(Baseline)),
            PolicySpec::FullPriority => Ok(Box::new(FullPriority)),
            PolicySpec::FreeMshr(n) => {
                let n = FreeMshrs::new(n).ok_or_else(|| {
                    format!("freemshr:{n}: N must fit the 5-bit free-MSHR register (0..=31)")
                })?;
                if n.get() > mshrs {
                    return Err(format!(
                        "freemshr:{n}: N exceeds the {mshrs} MSHRs, so priority warps could never launch"
                    ));
                }
                Ok(Box::new(FreeMshrN::new(n)))
            }
            PolicySpec::Wasp { threshold, cf } => {
                let t = gate_threshold("wasp", threshold, mshrs)?;
                let cf = Cf::from_f64(cf).ok_or_else(|| {
                    format!("wasp CF {cf}: must be a multiple of 0.25 between 0 and 7.75 (a 5-bit constant in quarters)")
                })?;
                Ok(Box::new(Wasp::new(WaspDatapath { cf, threshold: t })))
            }
            PolicySpec::WaspMeasured { threshold } => {
                let t = gate_threshold("wasp-m", threshold, mshrs)?;
                Ok(Box::new(WaspMeasured::new(t)))
            }
        }
    }
}

/// The threshold register of a WaSP policy named `name`, checked: it must
/// fit 5 bits and lie below the `mshrs` MSHRs, or `Real_freeMSHRs >
/// threshold` never holds and priority warps never launch.
fn gate_threshold(name: &str, threshold: u32, mshrs: u32) -> Result<Threshold, String> {
    let t = Threshold::new(threshold).ok_or_else(|| {
        format!("{name}:{threshold}: the threshold must fit its 5-bit register (0..=31)")
    })?;
    if threshold >= mshrs {
        return Err(format!(
            "{name}:{threshold}: the threshold must be below the {mshrs} MSHRs, or Real_freeMSHRs > threshold never holds and priority warps never launch"
        ));
    }
    Ok(t)
}

impl fmt::Display for PolicySpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            PolicySpec::Baseline => f.write_str("baseline"),
            PolicySpec::FullPriority => f.write_str("fullpriority"),
            PolicySpec::FreeMshr(n) => write!(f, "freemshr:{n}"),
            PolicySpec::Wasp { threshold, cf: 2.5 } => write!(f, "wasp:{threshold}"),
            PolicySpec::Wasp { threshold, cf } => write!(f, "wasp:{threshold}:{cf}"),
            PolicySpec::WaspMeasured { threshold } => write!(f, "wasp-m:{threshold}"),
        }
    }
}

impl FromStr for PolicySpec {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let trimmed = s.trim();
        // Names are case-sensitive: `WASP` is not silently `wasp`.
        if trimmed != trimmed.to_ascii_lowercase() && trimmed != "Freemshr10" {
            return Err(format!(
                "unknown policy `{s}`: policy names are lower case (`{}`)",
                trimmed.to_ascii_lowercase()
            ));
        }
        let parts: Vec<&str> = trimmed.split(':').collect();
        let int = |p: &str, what: &str| {
            p.parse::<u32>()
                .map_err(|_| format!("policy `{s}`: {what} `{p}` is not a non-negative integer"))
        };
        match parts.as_slice() {
            ["baseline"] | ["scanline"] => Ok(PolicySpec::Baseline),
            ["fullpriority"] | ["full-priority"] => Ok(PolicySpec::FullPriority),
            ["freemshr", n] => Ok(PolicySpec::FreeMshr(int(n, "N")?)),
            ["freemshr10"] | ["Freemshr10"] => Ok(PolicySpec::FreeMshr(10)),
            ["freemshr"] => Ok(PolicySpec::FreeMshr(PolicySpec::FREEMSHR_DEFAULT)),
            ["wasp"] => Ok(PolicySpec::SHIPPED_WASP),
            ["wasp", t] => Ok(PolicySpec::wasp(int(t, "threshold")?)),
            ["wasp", t, cf] => Ok(PolicySpec::Wasp {
                threshold: int(t, "threshold")?,
                cf: cf
                    .parse::<f64>()
                    .map_err(|_| format!("policy `{s}`: CF `{cf}` is not a number"))?,
            }),
            ["wasp-m"] => Ok(PolicySpec::SHIPPED_WASP.measured()),
            ["wasp-m", t] => Ok(PolicySpec::WaspMeasured {
                threshold: int(t, "threshold")?,
            }),
            _ => Err(format!(
                "unknown policy `{s}` (expected baseline, fullpriority, freemshr[:N], wasp[:threshold[:cf]], wasp-m[:threshold])"
            )),
        }
    }
}

/// Read from its name in a config file: the error names the allowed forms.
impl TryFrom<String> for PolicySpec {
    type Error = String;
    fn try_from(s: String) -> Result<Self, String> {
        s.parse()
    }
}

impl From<PolicySpec> for String {
    fn from(p: PolicySpec) -> String {
        p.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parse_and_display() {
        for s in [
            "baseline",
            "fullpriority",
            "freemshr:10",
            "wasp:4",
            "wasp:3:1",
            "wasp-m:6",
        ] {
            assert_eq!(s.parse::<PolicySpec>().unwrap().to_string(), s);
        }
        assert_eq!(
            "scanline".parse::<PolicySpec>().unwrap(),
            PolicySpec::Baseline
        );
        assert_eq!(
            "wasp".parse::<PolicySpec>().unwrap(),
            PolicySpec::SHIPPED_WASP
        );
        assert_eq!(
            "wasp-m".parse::<PolicySpec>().unwrap(),
            PolicySpec::WaspMeasured { threshold: 0 }
        );
        assert_eq!(
            "freemshr".parse::<PolicySpec>().unwrap(),
            PolicySpec::FreeMshr(10)
        );
        assert!("WASP"
            .parse::<PolicySpec>()
            .unwrap_err()
            .contains("lower case (`wasp`)"));
        assert!("wasp:x"
            .parse::<PolicySpec>()
            .unwrap_err()
            .contains("threshold"));
        assert!("lifo"
            .parse::<PolicySpec>()
            .unwrap_err()
            .contains("expected"));
    }

    #[test]
    fn build_checks_register_limits() {
        assert!(PolicySpec::wasp(4).build(16).is_ok());
        assert!(PolicySpec::wasp(32)
            .build(16)
            .unwrap_err()
            .contains("5-bit"));
        assert!(PolicySpec::wasp(16)
            .build(16)
            .unwrap_err()
            .contains("below"));
        let m = |t| PolicySpec::WaspMeasured { threshold: t }.build(16);
        assert!(m(15).is_ok());
        assert!(m(16)
            .unwrap_err()
            .starts_with("wasp-m:16: the threshold must be below"));
        assert!(m(32).unwrap_err().contains("5-bit"));
        assert!(PolicySpec::FreeMshr(40)
            .build(16)
            .unwrap_err()
            .contains("5-bit"));
        assert!(PolicySpec::FreeMshr(17)
            .build(16)
            .unwrap_err()
            .contains("never"));
        let bad_cf = PolicySpec::Wasp {
            threshold: 1,
            cf: 2.3,
        };
        assert!(bad_cf.build(16).unwrap_err().contains("0.25"));
    }

    #[test]
    fn built_policies_name_themselves_as_parsed() {
        for s in [
            "baseline",
            "fullpriority",
            "freemshr:3",
            "wasp:2",
            "wasp:2:1.5",
            "wasp-m:2",
        ] {
            let spec: PolicySpec = s.parse().unwrap();
            assert_eq!(spec.build(8).unwrap().name(), s);
        }
    }

    /// Each policy's `select` as it was written out per policy before the
    /// rule was shared (the `hold` rule).
    fn select_as_written(spec: &PolicySpec, v: &LaunchView) -> Option<QueueClass> {
        let regular = || v.regular_waiting.then_some(QueueClass::Regular);
        match *spec {
            PolicySpec::Baseline => v.regular_waiting.then_some(QueueClass::Regular),
            PolicySpec::FullPriority => {
                if v.priority_waiting {
                    Some(QueueClass::Priority)
                } else {
                    regular()
                }
            }
            PolicySpec::FreeMshr(n) => {
                if v.priority_waiting && v.free_mshrs.get() >= n {
                    Some(QueueClass::Priority)
                } else {
                    regular()
                }
            }
            PolicySpec::Wasp { .. } | PolicySpec::WaspMeasured { .. } => {
                if v.priority_waiting && v.datapath.is_some_and(|d| d.priority_over_regular) {
                    Some(QueueClass::Priority)
                } else {
                    regular()
                }
            }
        }
    }

    #[test]
    fn gated_rule_is_each_policys_select_on_every_view() {
        let mut specs = vec![PolicySpec::Baseline, PolicySpec::FullPriority];
        specs.extend((0..=31).map(PolicySpec::FreeMshr));
        for threshold in [0, 1, 4, 30] {
            for cf in [0.0, 1.0, 2.5, 7.75] {
                specs.push(PolicySpec::Wasp { threshold, cf });
            }
        }
        for spec in &specs {
            let policy = spec.build(31).unwrap();
            for free in 0..=FreeMshrs::MAX.get() {
                let free_mshrs = FreeMshrs::new(free).unwrap();
                for nb in 0..=crate::nonblocked::NonblockedCount::MAX.get() {
                    let nb = crate::nonblocked::NonblockedCount::new(nb).unwrap();
                    let dp = policy.datapath().map(|d| d.eval(free_mshrs, nb));
                    for datapath in [dp, None] {
                        for (priority_waiting, regular_waiting) in
                            [(false, false), (false, true), (true, false), (true, true)]
                        {
                            let v = LaunchView {
                                priority_waiting,
                                regular_waiting,
                                free_mshrs,
                                datapath,
                            };
                            let hold = policy.select(LaunchRule::Hold, &v);
                            assert_eq!(hold, select_as_written(spec, &v), "{spec} {v:?}");
                            assert_eq!(policy.gate().select(LaunchRule::Hold, &v), hold);
                            // `launch` differs from `hold` only where the
                            // rule decides, and there launches the priority
                            // warp.
                            let launch = policy.select(LaunchRule::Launch, &v);
                            if policy.gate().rule_decides(&v) {
                                assert_eq!(hold, None, "{spec} {v:?}");
                                assert_eq!(launch, Some(QueueClass::Priority), "{spec} {v:?}");
                            } else {
                                assert_eq!(launch, hold, "{spec} {v:?}");
                            }
                            // Work-conserving: `launch` picks a FIFO
                            // whenever a warp waits.
                            assert_eq!(launch.is_some(), v.priority_waiting || v.regular_waiting);
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn launch_rule_parses_and_names_itself() {
        for rule in LaunchRule::ALL {
            assert_eq!(rule.to_string().parse::<LaunchRule>(), Ok(rule));
        }
        assert_eq!(LaunchRule::default(), LaunchRule::Hold);
        assert_eq!(" Launch ".parse::<LaunchRule>(), Ok(LaunchRule::Launch));
        assert!("idle"
            .parse::<LaunchRule>()
            .unwrap_err()
            .contains("hold or launch"));
    }

    #[test]
    fn a_closed_gate_holds_or_launches_the_lone_priority_warp() {
        let v = LaunchView {
            priority_waiting: true,
            regular_waiting: false,
            free_mshrs: FreeMshrs::new(0).unwrap(),
            datapath: None,
        };
        for gate in [
            PriorityGate::Closed,
            PriorityGate::Datapath,
            PriorityGate::FreeMshrsAtLeast(FreeMshrs::new(1).unwrap()),
        ] {
            assert!(gate.rule_decides(&v), "{gate:?}");
            assert_eq!(gate.select(LaunchRule::Hold, &v), None, "{gate:?}");
            assert_eq!(
                gate.select(LaunchRule::Launch, &v),
                Some(QueueClass::Priority),
                "{gate:?}"
            );
            // A waiting regular warp goes first under both rules.
            let both = LaunchView {
                regular_waiting: true,
                ..v
            };
            assert!(!gate.rule_decides(&both));
            for rule in LaunchRule::ALL {
                assert_eq!(gate.select(rule, &both), Some(QueueClass::Regular));
            }
        }
        // An open gate launches the priority warp under both rules.
        assert!(!PriorityGate::Open.rule_decides(&v));
        for rule in LaunchRule::ALL {
            assert_eq!(
                PriorityGate::Open.select(rule, &v),
                Some(QueueClass::Priority)
            );
        }
    }

    #[test]
    fn freemshr_n_may_equal_the_mshrs() {
        // N = every MSHR: priority warps launch when all are free.
        assert!(PolicySpec::FreeMshr(16).build(16).is_ok());
        assert!(PolicySpec::FreeMshr(0).build(1).is_ok());
    }

    #[test]
    fn the_paper_name_freemshr10_is_an_alias() {
        assert_eq!(
            "Freemshr10".parse::<PolicySpec>().unwrap(),
            PolicySpec::FreeMshr(10)
        );
    }

    #[test]
    fn which_policies_read_the_free_mshr_register() {
        for (s, reads) in [
            ("baseline", false),
            ("fullpriority", false),
            ("freemshr:3", true),
            ("wasp:2", true),
        ] {
            let spec: PolicySpec = s.parse().unwrap();
            assert_eq!(spec.reads_free_mshrs(), reads, "{s}");
            assert_eq!(spec.build(8).unwrap().reads_free_mshrs(), reads, "{s}");
        }
    }
}
