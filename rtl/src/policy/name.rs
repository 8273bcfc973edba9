//! A launch policy as the user names it on the command line or in a
//! `--set scheduler.policy=...`: a bare family name (`wasp`, `wasp-m`,
//! `freemshr`) takes its constants from the machine's configured policy,
//! so that a bare `wasp` means the WaSP the machine ships with, never a
//! hidden default.

use super::PolicySpec;
use std::fmt;
use std::str::FromStr;

/// A policy family named without its constants.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PolicyFamily {
    /// `wasp`: threshold and CF from the machine.
    Wasp,
    /// `wasp-m`: threshold from the machine.
    WaspMeasured,
    /// `freemshr`: N from the machine.
    FreeMshr,
}

/// A policy as named: complete, or a bare family to resolve against a
/// machine.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PolicyName {
    /// Every constant given (`wasp:0:3`, `baseline`, ...).
    Given(PolicySpec),
    /// A bare family name.
    Bare(PolicyFamily),
}

impl PolicyName {
    /// The policy this name means on a machine whose configured policy is
    /// `configured`:
    /// - `wasp`: the configured `wasp:T:CF`; for `wasp-m:T`, `wasp:T` with
    ///   the shipped CF; otherwise the shipped `wasp:0:3`;
    /// - `wasp-m`: `wasp-m:T` at the configured WaSP's threshold T, else
    ///   the shipped threshold;
    /// - `freemshr`: the configured `freemshr:N`, else the paper's
    ///   `freemshr:10`.
    pub fn resolve(self, configured: PolicySpec) -> PolicySpec {
        let shipped_cf = match PolicySpec::SHIPPED_WASP {
            PolicySpec::Wasp { cf, .. } => cf,
            _ => unreachable!("the shipped policy is WaSP"),
        };
        match (self, configured) {
            (PolicyName::Given(p), _) => p,
            (PolicyName::Bare(PolicyFamily::Wasp), c @ PolicySpec::Wasp { .. }) => c,
            (PolicyName::Bare(PolicyFamily::Wasp), PolicySpec::WaspMeasured { threshold }) => {
                PolicySpec::Wasp {
                    threshold,
                    cf: shipped_cf,
                }
            }
            (PolicyName::Bare(PolicyFamily::Wasp), _) => PolicySpec::SHIPPED_WASP,
            (PolicyName::Bare(PolicyFamily::WaspMeasured), c) => c.measured(),
            (PolicyName::Bare(PolicyFamily::FreeMshr), c @ PolicySpec::FreeMshr(_)) => c,
            (PolicyName::Bare(PolicyFamily::FreeMshr), _) => {
                PolicySpec::FreeMshr(PolicySpec::FREEMSHR_DEFAULT)
            }
        }
    }
}

impl fmt::Display for PolicyName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PolicyName::Given(p) => p.fmt(f),
            PolicyName::Bare(PolicyFamily::Wasp) => f.write_str("wasp"),
            PolicyName::Bare(PolicyFamily::WaspMeasured) => f.write_str("wasp-m"),
            PolicyName::Bare(PolicyFamily::FreeMshr) => f.write_str("freemshr"),
        }
    }
}

impl FromStr for PolicyName {
    type Err = String;
    /// A bare family name, else a complete policy ([`PolicySpec`]'s
    /// grammar, case-sensitive).
    fn from_str(s: &str) -> Result<Self, String> {
        match s.trim() {
            "wasp" => Ok(PolicyName::Bare(PolicyFamily::Wasp)),
            "wasp-m" => Ok(PolicyName::Bare(PolicyFamily::WaspMeasured)),
            "freemshr" => Ok(PolicyName::Bare(PolicyFamily::FreeMshr)),
            _ => s.parse().map(PolicyName::Given),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn r(name: &str, configured: &str) -> String {
        let n: PolicyName = name.parse().unwrap();
        n.resolve(configured.parse().unwrap()).to_string()
    }

    #[test]
    fn bare_names_take_the_machines_constants() {
        assert_eq!(r("wasp", "wasp:0:3"), "wasp:0:3");
        assert_eq!(r("wasp", "wasp:5:2"), "wasp:5:2");
        assert_eq!(r("wasp", "wasp-m:2"), "wasp:2:3");
        assert_eq!(r("wasp", "baseline"), "wasp:0:3");
        assert_eq!(r("wasp-m", "wasp:6:1.5"), "wasp-m:6");
        assert_eq!(r("wasp-m", "fullpriority"), "wasp-m:0");
        assert_eq!(r("freemshr", "freemshr:7"), "freemshr:7");
        assert_eq!(r("freemshr", "wasp:0:3"), "freemshr:10");
    }

    #[test]
    fn given_names_are_kept_and_case_matters() {
        assert_eq!(r("wasp:4", "wasp:0:3"), "wasp:4");
        assert_eq!(r("baseline", "wasp:0:3"), "baseline");
        assert!("Wasp".parse::<PolicyName>().is_err());
        assert_eq!("wasp".parse::<PolicyName>().unwrap().to_string(), "wasp");
    }
}
