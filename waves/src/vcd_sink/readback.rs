//! Reading a VCD back, for tests: what was signal X at cycle N?
//!
//! [`values_by_cycle`] parses a whole VCD (any writer's, within the limits
//! below) into a [`ReadBack`], keyed by dotted full signal name as given by
//! [`SignalInfo::full_name`](super::SignalInfo::full_name), e.g.
//! `top.core0.free_mshrs` (no `[msb:lsb]` suffix).
//!
//! ```
//! use wasp_waves::{readback, Tracer, VcdSink};
//!
//! let mut sink = VcdSink::new(Vec::new(), "top");
//! for cycle in 0..4 {
//!     sink.begin_cycle(cycle);
//!     sink.signal("count", 4, cycle * 3);
//!     sink.end_cycle()?;
//! }
//! let vcd = sink.finish(4)?;
//!
//! let waves = readback::values_by_cycle(&vcd)?;
//! assert_eq!(waves.value_at("top.count", 2), Some(6));
//! assert_eq!(waves.end_time(), Some(4));
//! # Ok::<(), std::io::Error>(())
//! ```
//!
//! Limits: values must be two-state (`0`/`1`; `x` and `z` are errors),
//! vectors at most 64 bits, no real or string variables. Timestamps are
//! returned as written: cycle numbers on the cycle axis, picoseconds on the
//! real-time one (see the [time unit](super#time); divide by
//! [`period_ps`](super::period_ps) to get cycles).

use std::collections::{BTreeMap, HashMap};
use std::io;

use vcd::{Command, IdCode, ScopeItem, Value};

/// The value history of one signal.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SignalTrace {
    width: u32,
    changes: Vec<(u64, u64)>,
}

impl SignalTrace {
    /// Declared width in bits.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// `(time, value)` for every value written, in file order (the initial
    /// dump included).
    pub fn changes(&self) -> &[(u64, u64)] {
        &self.changes
    }

    /// The value in effect at `cycle`: the last one written at or before it.
    /// `None` before the first value.
    pub fn value_at(&self, cycle: u64) -> Option<u64> {
        let after = self.changes.partition_point(|&(t, _)| t <= cycle);
        after.checked_sub(1).map(|i| self.changes[i].1)
    }
}

/// Every signal of a VCD with its value history.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ReadBack {
    signals: BTreeMap<String, SignalTrace>,
    end_time: Option<u64>,
}

impl ReadBack {
    /// The history of the signal with this dotted full name.
    pub fn signal(&self, full_name: &str) -> Option<&SignalTrace> {
        self.signals.get(full_name)
    }

    /// The value of `full_name` at `cycle`; `None` if there is no such
    /// signal or it had no value yet.
    pub fn value_at(&self, full_name: &str, cycle: u64) -> Option<u64> {
        self.signal(full_name)?.value_at(cycle)
    }

    /// Every signal's value at `cycle`, by full name (signals without a value
    /// yet are left out).
    pub fn values_at(&self, cycle: u64) -> BTreeMap<&str, u64> {
        self.signals
            .iter()
            .filter_map(|(name, trace)| Some((name.as_str(), trace.value_at(cycle)?)))
            .collect()
    }

    /// Full names of all signals, sorted.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.signals.keys().map(String::as_str)
    }

    /// The last timestamp in the file (for a [`VcdSink`](super::VcdSink)
    /// file, the `final_cycle` given to `finish`).
    pub fn end_time(&self) -> Option<u64> {
        self.end_time
    }
}

fn invalid(message: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidData, message)
}

/// Collects `(full name, width, id)` of every variable under `items`.
fn collect_vars(items: &[ScopeItem], prefix: &str, out: &mut Vec<(String, u32, IdCode)>) {
    for item in items {
        match item {
            ScopeItem::Var(var) => {
                out.push((format!("{prefix}{}", var.reference), var.size, var.code));
            }
            ScopeItem::Scope(scope) => {
                let prefix = format!("{prefix}{}.", scope.identifier);
                collect_vars(&scope.items, &prefix, out);
            }
            ScopeItem::Comment(_) => {}
            // `ScopeItem` is non-exhaustive.
            _ => {}
        }
    }
}

/// Two-state value of a bit, if it is one.
fn bit(value: Value) -> Option<u64> {
    match value {
        Value::V0 => Some(0),
        Value::V1 => Some(1),
        _ => None,
    }
}

/// Parses a whole VCD into per-signal value histories.
///
/// # Errors
///
/// [`io::ErrorKind::InvalidData`] for a malformed file, a value change for
/// an undeclared identifier, an `x`/`z` value, a vector wider than 64 bits, a
/// real or string value, or two variables with the same full name.
pub fn values_by_cycle(vcd: &[u8]) -> io::Result<ReadBack> {
    let mut parser = vcd::Parser::new(vcd);
    let header = parser.parse_header()?;

    let mut vars = Vec::new();
    collect_vars(&header.items, "", &mut vars);

    let mut signals = BTreeMap::new();
    // An id may be shared by several variables that always have the same
    // value.
    let mut by_id: HashMap<IdCode, Vec<String>> = HashMap::new();
    for (name, width, id) in vars {
        if width == 0 || width > 64 {
            return Err(invalid(format!(
                "signal `{name}` has width {width}; readback supports 1..=64"
            )));
        }
        let trace = SignalTrace {
            width,
            changes: Vec::new(),
        };
        if signals.insert(name.clone(), trace).is_some() {
            return Err(invalid(format!("signal `{name}` is declared twice")));
        }
        by_id.entry(id).or_default().push(name);
    }

    let mut time = 0;
    let mut end_time = None;
    for command in parser {
        let (id, value) = match command? {
            Command::Timestamp(t) => {
                time = t;
                end_time = Some(t);
                continue;
            }
            Command::ChangeScalar(id, v) => {
                let value = bit(v)
                    .ok_or_else(|| invalid(format!("value {v} at time {time} is not 0 or 1")))?;
                (id, value)
            }
            Command::ChangeVector(id, v) => {
                if v.len() > 64 {
                    return Err(invalid(format!(
                        "vector of {} bits at time {time}; readback supports 64",
                        v.len()
                    )));
                }
                // Fewer bits than the width means leading zeros (0/1 only).
                let mut value = 0u64;
                for b in v.iter() {
                    let b = bit(b).ok_or_else(|| {
                        invalid(format!("vector {v} at time {time} is not all 0 or 1"))
                    })?;
                    value = (value << 1) | b;
                }
                (id, value)
            }
            Command::ChangeReal(..) | Command::ChangeString(..) => {
                return Err(invalid(format!(
                    "real or string value at time {time}; readback supports bits"
                )));
            }
            _ => continue,
        };
        let names = by_id.get(&id).ok_or_else(|| {
            invalid(format!(
                "value change at time {time} for undeclared id `{id}`"
            ))
        })?;
        for name in names {
            if let Some(trace) = signals.get_mut(name) {
                trace.changes.push((time, value));
            }
        }
    }

    Ok(ReadBack { signals, end_time })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Traceable, Tracer, VcdSink};

    struct Core {
        free_mshrs: u64,
        stall: bool,
    }

    impl Traceable for Core {
        fn trace<T: Tracer + ?Sized>(&self, t: &mut T) {
            t.push_scope("core0");
            t.signal("free_mshrs", 5, self.free_mshrs);
            t.bit("stall", self.stall);
            t.pop_scope();
        }
    }

    fn record() -> Vec<u8> {
        let mut sink = VcdSink::new(Vec::new(), "top");
        for cycle in 0..12 {
            let core = Core {
                free_mshrs: 16 - (cycle / 3),
                stall: cycle % 4 == 3,
            };
            sink.trace_cycle(cycle, &core).unwrap();
        }
        sink.finish(12).unwrap()
    }

    #[test]
    fn values_match_cycle_by_cycle() {
        let waves = values_by_cycle(&record()).unwrap();
        assert_eq!(
            waves.names().collect::<Vec<_>>(),
            ["top.core0.free_mshrs", "top.core0.stall"]
        );
        for cycle in 0..12 {
            assert_eq!(
                waves.value_at("top.core0.free_mshrs", cycle),
                Some(16 - cycle / 3),
                "cycle {cycle}"
            );
            assert_eq!(
                waves.value_at("top.core0.stall", cycle),
                Some(u64::from(cycle % 4 == 3)),
                "cycle {cycle}"
            );
        }
        // After the last change the last value holds.
        assert_eq!(waves.value_at("top.core0.free_mshrs", 100), Some(13));
        assert_eq!(waves.value_at("top.nothing", 0), None);
        assert_eq!(waves.end_time(), Some(12));
        assert_eq!(waves.signal("top.core0.free_mshrs").unwrap().width(), 5);
        let at9 = waves.values_at(9);
        assert_eq!(at9["top.core0.free_mshrs"], 13);
        assert_eq!(at9["top.core0.stall"], 0);
        // Only changes are stored.
        assert_eq!(
            waves.signal("top.core0.free_mshrs").unwrap().changes(),
            [(0, 16), (3, 15), (6, 14), (9, 13)]
        );
    }

    #[test]
    fn foreign_vcd_with_trimmed_vectors_and_shared_ids() {
        let text = "$timescale 1 ns $end\n\
                    $scope module a $end\n\
                    $var wire 8 % v [7:0] $end\n\
                    $scope module b $end\n\
                    $var wire 8 % w [7:0] $end\n\
                    $upscope $end\n\
                    $upscope $end\n\
                    $enddefinitions $end\n\
                    #3\nb101 %\n#7\n";
        let waves = values_by_cycle(text.as_bytes()).unwrap();
        assert_eq!(waves.value_at("a.v", 2), None);
        assert_eq!(waves.value_at("a.v", 3), Some(5));
        assert_eq!(waves.value_at("a.b.w", 5), Some(5));
        assert_eq!(waves.end_time(), Some(7));
    }

    #[test]
    fn unsupported_values_are_errors() {
        let header = "$scope module a $end\n$var wire 2 ! v [1:0] $end\n\
                      $upscope $end\n$enddefinitions $end\n";
        for body in ["#0\nbx1 !\n", "#0\nb01 ?\n", "#0\nr1.5 !\n"] {
            let text = format!("{header}{body}");
            let err = values_by_cycle(text.as_bytes()).unwrap_err();
            assert_eq!(err.kind(), io::ErrorKind::InvalidData, "{body}: {err}");
        }
    }
}
