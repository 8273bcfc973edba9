//! `--set SECTION.KEY=VALUE`: change single fields of a machine
//! configuration on the command line, for sweeps without a file per point.
//!
//! An override names an existing field by its dotted TOML path
//! (`l0.mshrs`, `scheduler.policy`, `dram.model`, `name`). The value is a
//! TOML value (`24`, `2.5`, `true`, `"banked"`); a value that is not valid
//! TOML is taken as a string, so `dram.model=banked` works unquoted. The
//! overridden configuration is validated like a file, and every error names
//! the override and what was expected. Overrides apply in order, so a later
//! one on the same field wins.

use crate::config::{ConfigError, MachineConfig};
use serde::Deserialize;
use wasp_rtl::policy::{PolicyName, PolicySpec};

/// A bare policy family (`wasp`, `wasp-m`, `freemshr`) set as
/// `scheduler.policy` takes its constants from the policy it replaces
/// ([`PolicyName::resolve`]); anything else is kept as written.
fn resolve_bare_policy(slot: &toml::Value, value: toml::Value) -> toml::Value {
    let (Some(old), Some(new)) = (slot.as_str(), value.as_str()) else {
        return value;
    };
    match (old.parse::<PolicySpec>(), new.parse::<PolicyName>()) {
        (Ok(old), Ok(name @ PolicyName::Bare(_))) => {
            toml::Value::String(name.resolve(old).to_string())
        }
        _ => value,
    }
}

/// `cfg` with every override in `sets` (each `PATH=VALUE`) applied, then
/// validated.
pub fn apply(cfg: &MachineConfig, sets: &[String]) -> Result<MachineConfig, ConfigError> {
    if sets.is_empty() {
        return Ok(cfg.clone());
    }
    let fail = |set: &str, message: String| ConfigError {
        source: format!("--set {set}"),
        message,
    };
    let mut root = toml::Value::try_from(cfg).map_err(|e| fail("", e.to_string()))?;
    for set in sets {
        let (path, text) = set.split_once('=').ok_or_else(|| {
            fail(
                set,
                "expected PATH=VALUE, e.g. l0.mshrs=24 or dram.model=fixed".into(),
            )
        })?;
        let path = path.trim();
        let mut value = parse_value(text.trim());
        let slot = field(&mut root, path).map_err(|m| fail(set, m))?;
        if path == "scheduler.policy" {
            value = resolve_bare_policy(slot, value);
        }
        if !same_kind(slot, &value) {
            return Err(fail(
                set,
                format!(
                    "{path} holds {}, not {} (expected e.g. {path}={})",
                    kind(slot),
                    kind(&value),
                    slot
                ),
            ));
        }
        *slot = value;
    }
    let out = MachineConfig::deserialize(root.clone()).map_err(|e| {
        let message = e.to_string().trim_end().to_string();
        // A number its field's type cannot hold (`l0.mshrs=-1`): name the
        // set and the field's allowed range.
        let bad = sets.iter().rev().find_map(|set| {
            let (path, text) = set.split_once('=')?;
            let path = path.trim();
            let in_field = message.contains(&format!("`{path}`"));
            let int = matches!(parse_value(text.trim()), toml::Value::Integer(_));
            (in_field && int).then(|| (set, path, text.trim()))
        });
        match bad {
            Some((set, path, text)) => fail(
                set,
                format!(
                    "{path} = {text}: must be in {}",
                    allowed_range(&root, path).unwrap_or_else(|| "0..=4294967295".into())
                ),
            ),
            None => ConfigError {
                source: "--set".into(),
                message,
            },
        }
    })?;
    out.validate().map_err(|message| ConfigError {
        source: format!("--set {}", sets.join(" --set ")),
        message,
    })?;
    Ok(out)
}

/// The range `validate` allows for the integer field `path` (`1..=4096`),
/// found by probing the field with its type's extremes.
fn allowed_range(root: &toml::Value, path: &str) -> Option<String> {
    for probe in [0, i64::from(u32::MAX)] {
        let mut r = root.clone();
        *field(&mut r, path).ok()? = toml::Value::Integer(probe);
        let Ok(c) = MachineConfig::deserialize(r) else {
            continue;
        };
        if let Err(m) = c.validate() {
            if let Some(i) = m.find(": must be in ").filter(|_| m.contains(path)) {
                let rest = &m[i + ": must be in ".len()..];
                return Some(rest.split([' ', ';', ',']).next()?.to_string());
            }
        }
    }
    None
}

/// The TOML value `text` stands for, or the string `text` itself.
fn parse_value(text: &str) -> toml::Value {
    #[derive(Deserialize)]
    struct One {
        v: toml::Value,
    }
    match toml::from_str::<One>(&format!("v = {text}")) {
        Ok(one) => one.v,
        Err(_) => toml::Value::String(text.to_string()),
    }
}

/// The existing field at dotted `path` in `root`.
fn field<'a>(root: &'a mut toml::Value, path: &str) -> Result<&'a mut toml::Value, String> {
    let mut at = root;
    let mut walked = String::new();
    for part in path.split('.') {
        let table = match at {
            toml::Value::Table(t) => t,
            _ => return Err(format!("{walked} is a value, not a section")),
        };
        if !table.contains_key(part) {
            let mut keys: Vec<&str> = table.keys().map(String::as_str).collect();
            keys.sort_unstable();
            let place = if walked.is_empty() {
                "the configuration".to_string()
            } else {
                format!("[{walked}]")
            };
            return Err(format!(
                "{place} has no field `{part}` (expected one of: {})",
                keys.join(", ")
            ));
        }
        if !walked.is_empty() {
            walked.push('.');
        }
        walked.push_str(part);
        at = table.get_mut(part).expect("checked above");
    }
    if at.is_table() {
        return Err(format!(
            "{path} is a section (expected a field inside it, e.g. {path}.KEY=VALUE)"
        ));
    }
    Ok(at)
}

/// Whether `new` may replace `old` (an integer may replace a float).
fn same_kind(old: &toml::Value, new: &toml::Value) -> bool {
    use toml::Value::*;
    matches!(
        (old, new),
        (String(_), String(_))
            | (Integer(_), Integer(_))
            | (Float(_), Float(_) | Integer(_))
            | (Boolean(_), Boolean(_))
            | (Array(_), Array(_))
    )
}

fn kind(v: &toml::Value) -> &'static str {
    match v {
        toml::Value::String(_) => "a string",
        toml::Value::Integer(_) => "an integer",
        toml::Value::Float(_) => "a number",
        toml::Value::Boolean(_) => "true or false",
        toml::Value::Datetime(_) => "a date",
        toml::Value::Array(_) => "a list",
        toml::Value::Table(_) => "a section",
    }
}

/// The name of a machine as run: `base` (its configured name) followed by
/// every override but `name=...` as written, spaces around `=` removed:
/// `paper-width4-64warps + core.max_warps=32 + l0.mshrs=16`. With no
/// override it is `base` alone.
pub fn describe(base: &str, sets: &[String]) -> String {
    let mut s = base.to_string();
    for set in sets {
        let (path, value) = set.split_once('=').unwrap_or((set, ""));
        if path.trim() == "name" {
            continue;
        }
        s.push_str(&format!(" + {}={}", path.trim(), value.trim()));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mem::DramModel;

    fn sets(s: &[&str]) -> Vec<String> {
        s.iter().map(|x| x.to_string()).collect()
    }

    #[test]
    fn a_number_its_type_cannot_hold_names_the_range() {
        let base = MachineConfig::paper();
        let e = apply(&base, &sets(&["l0.mshrs=-1"]))
            .unwrap_err()
            .to_string();
        assert_eq!(e, "--set l0.mshrs=-1: l0.mshrs = -1: must be in 1..=4096");
        let e = apply(&base, &sets(&["prefetch.l1_reserve=-3"]))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("prefetch.l1_reserve = -3: must be in 0..="),
            "{e}"
        );
    }

    #[test]
    fn a_machine_is_named_with_its_overrides() {
        assert_eq!(describe("m", &[]), "m");
        assert_eq!(
            describe("m", &sets(&["core.max_warps = 32", "name=x", "l0.mshrs=8"])),
            "m + core.max_warps=32 + l0.mshrs=8"
        );
    }

    #[test]
    fn a_bare_policy_takes_the_machines_constants() {
        let base = MachineConfig::paper();
        let p = |sets_: &[&str]| apply(&base, &sets(sets_)).unwrap().scheduler.policy;
        assert_eq!(p(&["scheduler.policy=wasp"]), base.scheduler.policy);
        assert_eq!(
            p(&["scheduler.policy=wasp:5:2", "scheduler.policy=wasp-m"]),
            PolicySpec::WaspMeasured { threshold: 5 }
        );
        assert_eq!(
            p(&["scheduler.policy=freemshr"]),
            PolicySpec::FreeMshr(PolicySpec::FREEMSHR_DEFAULT)
        );
        // The shipped file's policy is the shipped constant.
        assert_eq!(base.scheduler.policy, PolicySpec::SHIPPED_WASP);
    }

    #[test]
    fn overrides_change_exactly_the_named_fields() {
        let base = MachineConfig::paper();
        let c = apply(
            &base,
            &sets(&[
                "l0.mshrs=24",
                "dram.model=fixed",
                "scheduler.policy = \"wasp:6\"",
                "name=sweep",
                "l0.mshrs=20",
            ]),
        )
        .unwrap();
        assert_eq!(c.l0.as_ref().unwrap().mshrs, 20, "the later override wins");
        assert_eq!(c.dram.model, DramModel::Fixed);
        assert_eq!(c.scheduler.policy, PolicySpec::wasp(6));
        assert_eq!(c.name, "sweep");
        let mut expect = base.clone();
        expect.l0.as_mut().unwrap().mshrs = 20;
        expect.dram.model = DramModel::Fixed;
        expect.scheduler.policy = PolicySpec::wasp(6);
        expect.name = "sweep".into();
        assert_eq!(c, expect);
        assert_eq!(apply(&base, &[]).unwrap(), base);
        // The filter fields, like every field.
        let c = apply(
            &base,
            &sets(&[
                "core.filter_cycles_bilinear=0",
                "core.filter_cycles_trilinear=3",
                "core.filter_timing=\"serial\"",
            ]),
        )
        .unwrap();
        assert_eq!(
            (
                c.core.filter_cycles_bilinear,
                c.core.filter_cycles_trilinear,
                c.core.filter_timing
            ),
            (0, 3, crate::config::FilterTiming::Serial)
        );
    }

    #[test]
    fn issue_order_can_be_set() {
        let base = MachineConfig::paper();
        let c = apply(&base, &sets(&["core.issue=gto"])).unwrap();
        assert_eq!(c.core.issue, crate::config::IssueOrder::Gto);
        let c = apply(&c, &sets(&["core.issue=\"lrr\""])).unwrap();
        assert_eq!(c, base);
    }

    #[test]
    fn blocked_on_can_be_set() {
        let base = MachineConfig::paper();
        let c = apply(&base, &sets(&["scheduler.blocked_on=\"dram\""])).unwrap();
        assert_eq!(c.scheduler.blocked_on, crate::config::BlockedOn::Dram);
    }

    #[test]
    fn bad_overrides_say_what_was_expected() {
        let base = MachineConfig::paper();
        let cases = [
            ("l0.mshrs", "expected PATH=VALUE"),
            ("l0.nope=1", "[l0] has no field `nope` (expected one of:"),
            ("nope.x=1", "the configuration has no field `nope`"),
            ("l0=1", "l0 is a section"),
            ("l0.mshrs.x=1", "l0.mshrs is a value, not a section"),
            ("l0.mshrs=many", "l0.mshrs holds an integer, not a string"),
            ("dram.model=3", "dram.model holds a string, not an integer"),
            ("dram.model=slow", "dram.model"),
            ("scheduler.blocked_on=\"l2\"", "scheduler.blocked_on"),
            // Validation runs on the result: the register holds 31 at most.
            ("l0.mshrs=40", "31"),
            (
                "core.filter_cycles_trilinear=2000",
                "core.filter_cycles_trilinear",
            ),
            ("core.filter_timing=\"later\"", "core.filter_timing"),
            ("core.issue=fifo", "expected `lrr` or `gto`"),
            ("core.issue=2", "core.issue holds a string, not an integer"),
            (
                "core.filter_cycles_bilinear=\"one\"",
                "holds an integer, not a string",
            ),
        ];
        for (set, needle) in cases {
            let e = apply(&base, &sets(&[set])).unwrap_err().to_string();
            assert!(e.contains(needle), "{set}: {e}");
            assert!(e.starts_with("--set"), "{set}: {e}");
        }
    }
}
