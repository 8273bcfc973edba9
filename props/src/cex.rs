//! Counterexamples.
//!
//! A property body returns `Result<(), Cex>`. A [`Cex`] names the property,
//! says what went wrong and carries up to [`MAX_FIELDS`] named integer
//! values (the inputs and the expected and observed outputs). It is one
//! pointer wide (the record is boxed, allocated only when a property
//! fails) and is built without formatting, so the failing branch costs a
//! model checker (Kani/CBMC) little; the text is produced only by its
//! [`Display`](std::fmt::Display) implementation, in tests.

use std::fmt;

/// How many named values a counterexample holds.
pub const MAX_FIELDS: usize = 10;

/// A counterexample to a property. `Debug` prints the same text as
/// `Display`, so that `unwrap()` failures read well.
#[derive(Clone, PartialEq, Eq)]
pub struct Cex(Box<Record>);

#[derive(Clone, Debug, PartialEq, Eq)]
struct Record {
    property: &'static str,
    what: &'static str,
    fields: [(&'static str, i64); MAX_FIELDS],
    len: usize,
}

impl Cex {
    /// A counterexample with no values yet.
    pub fn new(property: &'static str, what: &'static str) -> Self {
        Self(Box::new(Record {
            property,
            what,
            fields: [("", 0); MAX_FIELDS],
            len: 0,
        }))
    }

    /// Add a named value (values past [`MAX_FIELDS`] are dropped).
    #[must_use]
    pub fn with(mut self, name: &'static str, value: i64) -> Self {
        let r = &mut *self.0;
        if r.len < MAX_FIELDS {
            r.fields[r.len] = (name, value);
            r.len += 1;
        }
        self
    }

    /// The property, as listed in the crate documentation, e.g.
    /// `"(b) datapath"`.
    pub fn property(&self) -> &'static str {
        self.0.property
    }

    /// What failed.
    pub fn what(&self) -> &'static str {
        self.0.what
    }

    /// The named values, in the order they were added.
    pub fn fields(&self) -> &[(&'static str, i64)] {
        &self.0.fields[..self.0.len]
    }

    /// The value named `name`, if present.
    pub fn get(&self, name: &str) -> Option<i64> {
        self.fields()
            .iter()
            .find(|(n, _)| *n == name)
            .map(|&(_, v)| v)
    }
}

impl fmt::Display for Cex {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.property(), self.what())?;
        if !self.fields().is_empty() {
            f.write_str(" [")?;
            for (i, (n, v)) in self.fields().iter().enumerate() {
                if i > 0 {
                    f.write_str(", ")?;
                }
                write!(f, "{n}={v}")?;
            }
            f.write_str("]")?;
        }
        Ok(())
    }
}

impl fmt::Debug for Cex {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(self, f)
    }
}

impl std::error::Error for Cex {}

/// `Err(cex)` unless `ok`.
#[inline]
pub fn ensure(ok: bool, cex: impl FnOnce() -> Cex) -> Result<(), Cex> {
    if ok {
        Ok(())
    } else {
        Err(cex())
    }
}

/// Panic with the counterexample of a failed property check (the tests'
/// assertion: the panic message is the counterexample).
#[cfg(test)]
#[track_caller]
pub(crate) fn check(r: Result<(), Cex>) {
    if let Err(c) = r {
        panic!("{c}");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_lists_fields_in_order() {
        let c = Cex::new("(x) demo", "went wrong")
            .with("a", 1)
            .with("b", -2);
        assert_eq!(c.to_string(), "(x) demo: went wrong [a=1, b=-2]");
        assert_eq!(format!("{c:?}"), c.to_string());
        assert_eq!(c.get("b"), Some(-2));
        assert_eq!(c.get("c"), None);
        let mut d = Cex::new("p", "w");
        for _ in 0..MAX_FIELDS + 3 {
            d = d.with("v", 0);
        }
        assert_eq!(d.fields().len(), MAX_FIELDS);
        assert_eq!(Cex::new("p", "w").to_string(), "p: w");
    }
}
