//! Overrides: single fields of a machine configuration changed by name,
//! for sweeps without a file per point (`--set SECTION.KEY=VALUE`, the
//! flags of `wasp run`, the study's points and the map's knobs).
//!
//! An [`Override`] is a typed value: the parameter it sets, by its dotted
//! TOML path (`l0.mshrs`, `scheduler.policy`, `dram.model`, `name`; the
//! paths of [`MachineConfig::params`]), and the TOML value it takes (`24`,
//! `2.5`, `true`, `"banked"`). Code builds one from a Rust value
//! ([`Override::new`]); a user writes one as `PATH=VALUE`
//! ([`Override::from_str`](std::str::FromStr)), where a value that is not
//! valid TOML is taken as a string, so `dram.model=banked` works unquoted.
//! Its text ([`Display`](fmt::Display)) is `PATH=VALUE` as written, spaces
//! around `=` removed: the form in machine names, study records and
//! reports.
//!
//! [`MachineConfig::with_overrides`] applies overrides in order (a later
//! one on the same field wins) and validates the result like a file;
//! every error names the override and what was expected, a number out of
//! its type the field's declared range.

use crate::config::{ConfigError, MachineConfig};
use serde::{Deserialize, Serialize};
use std::cmp::Ordering;
use std::fmt;
use std::hash::{Hash, Hasher};
use std::str::FromStr;
use wasp_rtl::policy::{PolicyName, PolicySpec};

/// One field of the machine set to a value.
#[derive(Clone, Debug)]
pub struct Override {
    /// The field's dotted path (`core.max_warps`).
    path: String,
    /// The value it takes.
    value: toml::Value,
    /// The value as written (`32`, `"wasp:0:3"`, `fixed`).
    written: String,
}

impl Override {
    /// Field `path` set to `value`, written as TOML writes it: a string
    /// quoted (`scheduler.policy="wasp:0:3"`), a number or a boolean bare
    /// (`core.max_warps=32`, `memory.ideal=true`).
    pub fn new<T: Serialize + ?Sized>(path: &str, value: &T) -> Override {
        let value = toml::Value::try_from(value).unwrap_or_else(|e| {
            // Every parameter's type serializes as one TOML value; anything
            // else is kept as its message, which applying refuses.
            toml::Value::String(format!("<{e}>"))
        });
        let written = value.to_string();
        Override {
            path: path.to_string(),
            value,
            written,
        }
    }

    /// Field `path` set to the text of `value`, written bare
    /// (`scheduler.blocked_on=dram`), as `--set` takes an unquoted string.
    pub fn bare<T: fmt::Display + ?Sized>(path: &str, value: &T) -> Override {
        let written = value.to_string();
        Override {
            path: path.to_string(),
            value: parse_value(&written),
            written,
        }
    }

    /// The field's dotted path.
    pub fn path(&self) -> &str {
        &self.path
    }

    /// The value the field takes.
    pub fn value(&self) -> &toml::Value {
        &self.value
    }

    /// The overrides of `--set` texts (`PATH=VALUE` each), in order; a
    /// text without `=` is an error naming it.
    pub fn parse_sets<S: AsRef<str>>(texts: &[S]) -> Result<Vec<Override>, ConfigError> {
        texts
            .iter()
            .map(|t| t.as_ref().parse().map_err(|m| fail(t.as_ref(), m)))
            .collect()
    }
}

impl FromStr for Override {
    type Err = String;

    /// `PATH=VALUE`, spaces around `=` ignored.
    fn from_str(s: &str) -> Result<Override, String> {
        let (path, text) = s
            .split_once('=')
            .ok_or("expected PATH=VALUE, e.g. l0.mshrs=24 or dram.model=fixed")?;
        Ok(Override::bare(path.trim(), text.trim()))
    }
}

/// Serialized as its text.
impl Serialize for Override {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

impl<'de> Deserialize<'de> for Override {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Override, D::Error> {
        String::deserialize(d)?
            .parse()
            .map_err(serde::de::Error::custom)
    }
}

impl fmt::Display for Override {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}={}", self.path, self.written)
    }
}

// Two overrides are the same when written the same: their text is what
// names a machine and a study point.
impl PartialEq for Override {
    fn eq(&self, other: &Override) -> bool {
        (&self.path, &self.written) == (&other.path, &other.written)
    }
}

impl Eq for Override {}

impl Hash for Override {
    fn hash<H: Hasher>(&self, h: &mut H) {
        (&self.path, &self.written).hash(h);
    }
}

impl PartialOrd for Override {
    fn partial_cmp(&self, other: &Override) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Override {
    fn cmp(&self, other: &Override) -> Ordering {
        self.to_string().cmp(&other.to_string())
    }
}

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

/// An error about override `o` (all of them when `None`).
fn fail(o: impl fmt::Display, message: String) -> ConfigError {
    ConfigError {
        source: format!("--set {o}"),
        message,
    }
}

impl MachineConfig {
    /// This machine with every override applied in order, then validated.
    pub fn with_overrides(&self, overrides: &[Override]) -> Result<MachineConfig, ConfigError> {
        if overrides.is_empty() {
            return Ok(self.clone());
        }
        let mut root = toml::Value::try_from(self).map_err(|e| fail("", e.to_string()))?;
        for o in overrides {
            let slot = field(&mut root, &o.path).map_err(|m| fail(o, m))?;
            let mut value = o.value.clone();
            if o.path == "scheduler.policy" {
                value = resolve_bare_policy(slot, value);
            }
            if !same_kind(slot, &value) {
                return Err(fail(
                    o,
                    format!(
                        "{} holds {}, not {} (expected e.g. {}={})",
                        o.path,
                        kind(slot),
                        kind(&value),
                        o.path,
                        slot
                    ),
                ));
            }
            *slot = value;
        }
        let out = MachineConfig::deserialize(root).map_err(|e| self.refused(overrides, &e))?;
        out.validate().map_err(|message| ConfigError {
            source: format!("--set {}", join(overrides, " --set ")),
            message,
        })?;
        Ok(out)
    }

    /// The error of overrides the configuration's types refuse: a number
    /// its field's type cannot hold (`l0.mshrs=-1`) names the override and
    /// the field's declared range.
    fn refused(&self, overrides: &[Override], e: &toml::de::Error) -> ConfigError {
        let message = e.to_string().trim_end().to_string();
        let bad = overrides
            .iter()
            .rev()
            .find(|o| message.contains(&format!("`{}`", o.path)) && o.value.is_integer());
        match bad {
            Some(o) => fail(
                o,
                format!(
                    "{} = {}: must be in {}",
                    o.path,
                    o.written,
                    self.declared_range(&o.path)
                ),
            ),
            None => ConfigError {
                source: "--set".into(),
                message,
            },
        }
    }

    /// The declared range of the integer field `path` ([`Self::params`]),
    /// else its type's.
    fn declared_range(&self, path: &str) -> String {
        let p = self.params().into_iter().find(|p| p.path == path);
        match p {
            Some(crate::param::Param { range: Some(r), .. }) => format!("{}..={}", r.lo, r.hi),
            Some(p) if p.ty == "u64" => format!("0..={}", u64::MAX),
            _ => format!("0..={}", u32::MAX),
        }
    }

    /// The name of this machine as run with `overrides`: its name followed
    /// by every override but `name=...`
    /// (`paper-width4-64warps + core.max_warps=32 + l0.mshrs=16`); with no
    /// override its name alone.
    pub fn named_with(&self, overrides: &[Override]) -> String {
        let mut s = self.name.clone();
        for o in overrides.iter().filter(|o| o.path != "name") {
            s.push_str(&format!(" + {o}"));
        }
        s
    }
}

/// The overrides' texts joined by `sep`.
fn join(overrides: &[Override], sep: &str) -> String {
    let texts: Vec<String> = overrides.iter().map(Override::to_string).collect();
    texts.join(sep)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mem::DramModel;

    fn sets(s: &[&str]) -> Vec<Override> {
        Override::parse_sets(s).unwrap()
    }

    /// `base` with the `--set` texts `s` applied.
    fn apply(base: &MachineConfig, s: &[&str]) -> Result<MachineConfig, ConfigError> {
        base.with_overrides(&Override::parse_sets(s)?)
    }

    #[test]
    fn a_number_its_type_cannot_hold_names_the_range() {
        let base = MachineConfig::paper();
        let e = apply(&base, &["l0.mshrs=-1"]).unwrap_err().to_string();
        assert_eq!(e, "--set l0.mshrs=-1: l0.mshrs = -1: must be in 1..=4096");
        let e = apply(&base, &["prefetch.l1_reserve=-3"])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("prefetch.l1_reserve = -3: must be in 0..="),
            "{e}"
        );
        // The range is the field's declared one, whatever its type.
        let e = apply(&base, &["gpu.tile_size=-4"]).unwrap_err().to_string();
        assert!(e.ends_with("gpu.tile_size = -4: must be in 4..=64"), "{e}");
        let e = apply(&base, &["sim.seed=-1"]).unwrap_err().to_string();
        assert!(e.ends_with(&format!("must be in 0..={}", u64::MAX)), "{e}");
    }

    #[test]
    fn a_machine_is_named_with_its_overrides() {
        let mut m = MachineConfig::paper();
        m.name = "m".into();
        assert_eq!(m.named_with(&[]), "m");
        let os = sets(&["core.max_warps = 32", "name=x", "l0.mshrs=8"]);
        assert_eq!(m.named_with(&os), "m + core.max_warps=32 + l0.mshrs=8");
        assert_eq!(os[0].to_string(), "core.max_warps=32");
    }

    #[test]
    fn a_bare_policy_takes_the_machines_constants() {
        let base = MachineConfig::paper();
        let p = |sets_: &[&str]| apply(&base, sets_).unwrap().scheduler.policy;
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
            &[
                "l0.mshrs=24",
                "dram.model=fixed",
                "scheduler.policy = \"wasp:6\"",
                "name=sweep",
                "l0.mshrs=20",
            ],
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
        assert_eq!(apply(&base, &[] as &[&str]).unwrap(), base);
        // The filter fields, like every field.
        let c = apply(
            &base,
            &[
                "core.filter_cycles_bilinear=0",
                "core.filter_cycles_trilinear=3",
                "core.filter_timing=\"serial\"",
            ],
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
        let c = apply(&base, &["core.issue=gto"]).unwrap();
        assert_eq!(c.core.issue, crate::config::IssueOrder::Gto);
        let c = apply(&c, &["core.issue=\"lrr\""]).unwrap();
        assert_eq!(c, base);
    }

    #[test]
    fn blocked_on_can_be_set() {
        let base = MachineConfig::paper();
        let c = apply(&base, &["scheduler.blocked_on=\"dram\""]).unwrap();
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
            let e = apply(&base, &[set]).unwrap_err().to_string();
            assert!(e.contains(needle), "{set}: {e}");
            assert!(e.starts_with("--set"), "{set}: {e}");
        }
    }

    #[test]
    fn typed_overrides_are_written_as_toml() {
        let o = Override::new("core.max_warps", &32u32);
        assert_eq!(o.to_string(), "core.max_warps=32");
        assert_eq!(o.value(), &toml::Value::Integer(32));
        let p = Override::new("scheduler.policy", &PolicySpec::wasp(6));
        assert_eq!(
            p.to_string(),
            format!("scheduler.policy=\"{}\"", PolicySpec::wasp(6))
        );
        assert_eq!(p, "scheduler.policy=\"wasp:6\"".parse().unwrap());
        assert_eq!(
            Override::new("memory.ideal", &true).to_string(),
            "memory.ideal=true"
        );
        let b = Override::bare("scheduler.blocked_on", &crate::config::BlockedOn::Dram);
        assert_eq!(b.to_string(), "scheduler.blocked_on=dram");
        assert_eq!(b.value(), &toml::Value::String("dram".into()));
        // The text is the serialized form, both ways.
        let json = serde_json::to_string(&[&o, &p]).unwrap();
        assert_eq!(
            json,
            r#"["core.max_warps=32","scheduler.policy=\"wasp:6\""]"#
        );
        let back: Vec<Override> = serde_json::from_str(&json).unwrap();
        assert_eq!(back, [o, p]);
    }
}
