//! How a parameter of the machine is declared: once, typed, with its
//! description and its bound beside it. (gem5's `Param` declarations are
//! the model: `cores = Param.Unsigned(4, "shader cores")` names the type,
//! the description and, with a checked type, the bound; the model receives
//! a typed struct.)
//!
//! A section of the configuration file is one struct declared with
//! `section!`: each field's doc comment is its
//! description, `#[range(lo..=hi)]` its bound, and its type is what the
//! model receives. A value written as text in the file (a policy such as
//! `wasp:0:3`, a subset, a core map) has a type that deserializes from that
//! text and names the allowed forms when it cannot (`TryFrom<String>`), so
//! no part of the model parses a string. Checks that involve several
//! fields (a power-of-two tile, the scheduler's registers) stay in
//! [`MachineConfig::validate`](crate::config::MachineConfig::validate).
//!
//! The declarations are also facts ([`Param`]: path, type, value, range,
//! description) that [`crate::config::params`] lists for the whole machine:
//! the bounds tests, the check of `configs/paper.toml` ([`PAPER_TOML`],
//! the source of every default) and docs/machine.md's parameter table are
//! generated from them.

use std::fmt::Display;

/// The paper's machine, `configs/paper.toml`: every parameter with its
/// default value and the value's source.
pub const PAPER_TOML: &str = include_str!("../../configs/paper.toml");

/// `field = v: must be in lo..=hi` (with `why` appended) when `v` is out of
/// range: the style of every bound check of the machine configuration.
pub fn check_range(field: &str, v: u64, lo: u64, hi: u64, why: &str) -> Result<(), String> {
    if (lo..=hi).contains(&v) {
        Ok(())
    } else {
        Err(format!("{field} = {v}: must be in {lo}..={hi}{why}"))
    }
}

/// A numeric parameter whose declared range can be checked.
pub trait Bounded: Copy + Display {
    /// `Err` naming `section.key`, the value and the range (and `why`)
    /// unless `lo <= self <= hi` (and, for a float, finite).
    fn check_in(
        self,
        section: &str,
        key: &str,
        lo: Self,
        hi: Self,
        why: &str,
    ) -> Result<(), String>;
}

impl Bounded for u32 {
    fn check_in(self, section: &str, key: &str, lo: u32, hi: u32, why: &str) -> Result<(), String> {
        check_range(
            &format!("{section}.{key}"),
            self.into(),
            lo.into(),
            hi.into(),
            why,
        )
    }
}

impl Bounded for u64 {
    fn check_in(self, section: &str, key: &str, lo: u64, hi: u64, why: &str) -> Result<(), String> {
        check_range(&format!("{section}.{key}"), self, lo, hi, why)
    }
}

impl Bounded for f64 {
    fn check_in(self, section: &str, key: &str, lo: f64, hi: f64, why: &str) -> Result<(), String> {
        if self.is_finite() && (lo..=hi).contains(&self) {
            Ok(())
        } else {
            Err(format!(
                "{section}.{key} = {self}: must be a finite number in {lo}..={hi}{why}"
            ))
        }
    }
}

/// The upper end of a declared range: a number, or one that depends on the
/// section the struct serves (the caches' capacities: `[l0]`, `[l1]` and
/// `[l2]` are one struct).
pub trait Limit<T> {
    /// The bound in section `section`.
    fn at(&self, section: &str) -> T;
    /// Text the range's error appends after the declared note.
    fn note(&self, _section: &str) -> String {
        String::new()
    }
}

impl<T: Bounded> Limit<T> for T {
    fn at(&self, _section: &str) -> T {
        *self
    }
}

/// One field of a section as `section!` declares it, in a given section
/// and with a given value: the facts the bounds tests, the check of
/// `configs/paper.toml` and docs/machine.md's parameter table are made of.
#[derive(Clone, Debug, PartialEq)]
pub struct Param {
    /// `section.key`.
    pub path: String,
    /// The Rust type the model receives, as written (`u32`, `PolicySpec`).
    pub ty: &'static str,
    /// The value (the paper's machine's: the default).
    pub value: toml::Value,
    /// The declared range, if the field is a bounded number.
    pub range: Option<Range>,
    /// The description: the field's doc comment, one line per line.
    pub doc: &'static str,
}

/// A declared range, its ends as the configuration file writes them.
#[derive(Clone, Debug, PartialEq)]
pub struct Range {
    /// Lowest accepted value.
    pub lo: String,
    /// Highest accepted value.
    pub hi: String,
    /// What the error appends (`#[range]`), or the further rule that its
    /// own check applies (`#[bound]`).
    pub note: String,
    /// Checked by `check_bounds` (`#[range]`) rather than by a rule of
    /// its own that also names this range (`#[bound]`).
    pub generic: bool,
}

impl Range {
    /// A range from its ends.
    pub fn new<T: Display>(lo: T, hi: T, note: String, generic: bool) -> Self {
        Range {
            lo: lo.to_string(),
            hi: hi.to_string(),
            note,
            generic,
        }
    }
}

/// Declare a section of the configuration: a struct whose fields are the
/// section's keys, each with its description (the doc comment), its bound
/// and its type; `serde` attributes pass through. Unknown keys are errors.
/// A bound is `#[range(lo..=hi)]` or `#[range(lo..=hi, " why")]` (`hi` a
/// number or a [`Limit`]), which `check_bounds(section)` checks, naming
/// the field (`core.max_warps = 0: must be in 1..=128`); or
/// `#[bound(lo..=hi, "rule")]`, a range within which a check of its own
/// applies a further rule (a power of two, a limit set by another field)
/// and whose error names the range itself. The struct also gets
/// `params(section)`, each field's [`Param`].
///
/// ```ignore
/// section! {
///     /// Global GPU parameters.
///     #[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
///     pub struct GpuConfig {
///         /// Shader cores.
///         #[range(1..=MAX_CORES)]
///         pub cores: u32,
///     }
/// }
/// ```
macro_rules! section {
    (
        $(#[$meta:meta])*
        pub struct $name:ident {
            $(
                $(#[doc = $doc:expr])*
                $(#[range($lo:tt ..= $hi:expr $(, $why:literal)?)])?
                $(#[bound($blo:tt ..= $bhi:expr, $rule:literal)])?
                $(#[serde($($serde:tt)*)])*
                pub $field:ident : $ty:ty,
            )*
        }
    ) => {
        $(#[$meta])*
        #[serde(deny_unknown_fields)]
        pub struct $name {
            $(
                $(#[doc = $doc])*
                $(#[serde($($serde)*)])*
                pub $field: $ty,
            )*
        }

        impl $name {
            /// Check the declared range of every numeric field; `section`
            /// names the section in the error.
            pub fn check_bounds(&self, section: &str) -> Result<(), String> {
                $($(
                    let hi = &$hi;
                    $crate::param::Bounded::check_in(
                        self.$field,
                        section,
                        stringify!($field),
                        $lo,
                        $crate::param::Limit::<$ty>::at(hi, section),
                        &format!(
                            "{}{}",
                            concat!("" $(, $why)?),
                            $crate::param::Limit::<$ty>::note(hi, section)
                        ),
                    )?;
                )?)*
                let _ = section;
                Ok(())
            }

            /// Every field's [`Param`]($crate::param::Param) in section
            /// `section`, with this struct's values, in declaration order.
            pub fn params(&self, section: &str) -> Vec<$crate::param::Param> {
                vec![$(
                    $crate::param::Param {
                        path: format!("{section}.{}", stringify!($field)),
                        ty: stringify!($ty),
                        value: toml::Value::try_from(&self.$field)
                            .expect("a parameter serializes"),
                        range: None
                            $(.or({
                                let hi = &$hi;
                                Some($crate::param::Range::new::<$ty>(
                                    $lo,
                                    $crate::param::Limit::<$ty>::at(hi, section),
                                    format!(
                                        "{}{}",
                                        concat!("" $(, $why)?),
                                        $crate::param::Limit::<$ty>::note(hi, section)
                                    ),
                                    true,
                                ))
                            }))?
                            $(.or(Some($crate::param::Range::new::<$ty>(
                                $blo,
                                $bhi,
                                $rule.to_string(),
                                false,
                            ))))?,
                        doc: concat!($($doc, "\n",)* ""),
                    },
                )*]
            }
        }
    };
}
pub(crate) use section;

#[cfg(test)]
mod tests {
    use super::Range;
    use serde::{Deserialize, Serialize};

    section! {
        /// A test section.
        #[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
        pub struct Demo {
            /// Bounded, no note.
            #[range(1..=8)]
            pub a: u32,
            /// Bounded with a note.
            #[range(0..=100, " cycles")]
            pub b: u64,
            /// A float.
            #[range(0.0..=2.5)]
            pub c: f64,
            /// Not bounded, with a default.
            #[serde(default)]
            pub d: bool,
            /// Bounded by a rule of its own.
            #[bound(2..=6, "even")]
            #[serde(default)]
            pub e: u32,
        }
    }

    #[test]
    fn declared_ranges_are_checked_and_named() {
        let ok = Demo {
            a: 8,
            b: 0,
            c: 2.5,
            d: false,
            e: 0,
        };
        assert_eq!(ok.check_bounds("demo"), Ok(()));
        let e = Demo { a: 9, ..ok.clone() }.check_bounds("demo");
        assert_eq!(e.unwrap_err(), "demo.a = 9: must be in 1..=8");
        let e = Demo {
            b: 101,
            ..ok.clone()
        }
        .check_bounds("x");
        assert_eq!(e.unwrap_err(), "x.b = 101: must be in 0..=100 cycles");
        for c in [f64::NAN, -0.5, 3.0] {
            let e = Demo { c, ..ok.clone() }.check_bounds("demo").unwrap_err();
            assert!(e.contains("must be a finite number in 0..=2.5"), "{e}");
        }
    }

    #[test]
    fn params_are_the_declared_facts() {
        let d = Demo {
            a: 8,
            b: 0,
            c: 2.5,
            d: true,
            e: 9,
        };
        assert_eq!(d.check_bounds("demo"), Ok(()), "e's rule is its own");
        let p = d.params("demo");
        let paths: Vec<&str> = p.iter().map(|p| p.path.as_str()).collect();
        assert_eq!(paths, ["demo.a", "demo.b", "demo.c", "demo.d", "demo.e"]);
        assert_eq!(p[1].range, Some(Range::new(0, 100, " cycles".into(), true)));
        assert_eq!(p[2].range, Some(Range::new(0.0, 2.5, String::new(), true)));
        assert_eq!(p[2].range.as_ref().map(|r| &r.lo[..]), Some("0"));
        assert_eq!((p[3].ty, p[3].range.clone()), ("bool", None));
        assert_eq!(p[4].range, Some(Range::new(2, 6, "even".into(), false)));
        assert_eq!(p[0].value, toml::Value::Integer(8));
        assert_eq!(p[3].value, toml::Value::Boolean(true));
        assert_eq!(p[0].doc, " Bounded, no note.\n");
    }

    #[test]
    fn sections_refuse_unknown_keys_and_keep_serde_attributes() {
        let d: Demo = toml::from_str("a = 1\nb = 2\nc = 0.5\n").unwrap();
        assert!(!d.d, "the default");
        let e = toml::from_str::<Demo>("a = 1\nb = 2\nc = 0.5\nz = 1\n").unwrap_err();
        assert!(e.to_string().contains("unknown field `z`"), "{e}");
    }
}
