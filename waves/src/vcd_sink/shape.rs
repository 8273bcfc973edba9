//! The design's shape: the [`Tracer`] calls record the hierarchy on the
//! first cycle and check every later cycle against it, and a mismatch is
//! described in terms of both.

use std::collections::HashSet;
use std::io::{self, Write};

use super::hierarchy::{name_problem, Event, SignalInfo};
use super::sink::VcdSink;
use super::value::{Slot, MAX_WIDTH};
use crate::Tracer;

impl<W: Write> VcdSink<W> {
    /// Human description of the first cycle's event at `pos`.
    pub(super) fn describe_event(&self, pos: usize) -> String {
        match self.events.get(pos) {
            None => "the end of the cycle".to_owned(),
            Some(Event::Push(name)) => format!("scope `{name}`"),
            Some(Event::Pop) => "the end of a scope (pop_scope)".to_owned(),
            Some(Event::Signal) => {
                let index = self.events[..pos]
                    .iter()
                    .filter(|e| matches!(e, Event::Signal))
                    .count();
                let info = &self.signals[index];
                format!("signal `{}` of width {}", info.full_name(), info.width)
            }
        }
    }

    /// Name of the innermost scope open at `event_pos` (later cycles).
    pub(super) fn open_scope_name(&self) -> String {
        let mut stack = Vec::new();
        for event in &self.events[..self.event_pos] {
            match event {
                Event::Push(name) => stack.push(name.as_str()),
                Event::Pop => {
                    stack.pop();
                }
                Event::Signal => {}
            }
        }
        stack.last().copied().unwrap_or_default().to_owned()
    }

    /// Records a shape mismatch at the current position.
    fn mismatch(&mut self, got: String) {
        let expected = self.describe_event(self.event_pos);
        self.fail(
            io::ErrorKind::InvalidData,
            format!(
                "design changed shape at cycle {}: expected {expected}, got {got}",
                self.cycle
            ),
        );
    }

    pub(super) fn check_unique_names(&mut self) -> io::Result<()> {
        let mut seen = HashSet::with_capacity(self.signals.len());
        let duplicate = self
            .signals
            .iter()
            .map(SignalInfo::full_name)
            .find(|name| !seen.insert(name.clone()));
        match duplicate {
            Some(name) => Err(self.fail(
                io::ErrorKind::InvalidData,
                format!("signal `{name}` is traced twice"),
            )),
            None => Ok(()),
        }
    }
}

impl<W: Write> Tracer for VcdSink<W> {
    fn push_scope(&mut self, name: &str) {
        if !self.accepting("push_scope") {
            return;
        }
        if self.defined {
            match self.events.get(self.event_pos) {
                Some(Event::Push(expected)) if expected == name => {}
                _ => return self.mismatch(format!("scope `{name}`")),
            }
        } else {
            if let Some(problem) = name_problem(name) {
                let message = format!("scope name {name:?} in `{}` {problem}", self.path.join("."));
                self.fail(io::ErrorKind::InvalidData, message);
                return;
            }
            self.events.push(Event::Push(name.to_owned()));
            self.path.push(name.to_owned());
        }
        self.event_pos += 1;
        self.depth += 1;
    }

    fn pop_scope(&mut self) {
        if !self.accepting("pop_scope") {
            return;
        }
        if self.depth == 0 {
            let message = format!(
                "pop_scope without a matching push_scope at cycle {}",
                self.cycle
            );
            self.fail(io::ErrorKind::InvalidData, message);
            return;
        }
        if self.defined {
            if !matches!(self.events.get(self.event_pos), Some(Event::Pop)) {
                return self.mismatch("the end of a scope (pop_scope)".to_owned());
            }
        } else {
            self.events.push(Event::Pop);
            self.path.pop();
        }
        self.event_pos += 1;
        self.depth -= 1;
    }

    fn signal(&mut self, name: &str, width: u32, value: u64) {
        if !self.accepting("signal") {
            return;
        }
        let index = self.signal_pos;
        if self.defined {
            let matches = matches!(self.events.get(self.event_pos), Some(Event::Signal))
                && self.signals[index].name == name
                && self.signals[index].width == width;
            if !matches {
                let got = format!("signal `{name}` of width {width}");
                return self.mismatch(got);
            }
            let slot = &mut self.slots[index];
            slot.value = value & slot.mask;
        } else {
            let info = SignalInfo {
                path: self.path.clone(),
                name: name.to_owned(),
                width,
            };
            if width == 0 || width > MAX_WIDTH {
                let message = format!(
                    "signal `{}` has width {width}; widths must be 1..={MAX_WIDTH}",
                    info.full_name()
                );
                self.fail(io::ErrorKind::InvalidData, message);
                return;
            }
            if let Some(problem) = name_problem(name) {
                let message = format!(
                    "signal name {name:?} in `{}` {problem}",
                    self.path.join(".")
                );
                self.fail(io::ErrorKind::InvalidData, message);
                return;
            }
            self.signals.push(info);
            self.slots.push(Slot::new(index, width, value));
            self.events.push(Event::Signal);
        }
        self.event_pos += 1;
        self.signal_pos += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vcd_sink::testkit::*;
    use crate::Traceable;

    #[test]
    fn shape_change_is_an_error_and_sticky() {
        let mut sink = VcdSink::new(Vec::new(), "top");
        sink.trace_cycle(0, &START).unwrap();
        // Width of free_mshrs changes from 5 to 6.
        let changed = Shaped(|t| {
            t.push_scope("core0");
            t.signal("free_mshrs", 6, 1);
        });
        expect_error(
            sink.trace_cycle(1, &changed),
            io::ErrorKind::InvalidData,
            "expected signal `top.core0.free_mshrs` of width 5, got signal `free_mshrs` of width 6",
        );
        // Sticky: later well-formed cycles and finish still fail.
        expect_error(
            sink.trace_cycle(2, &START),
            io::ErrorKind::InvalidData,
            "design changed shape at cycle 1",
        );
        let err = sink.finish(3).unwrap_err();
        assert!(err.to_string().contains("design changed shape"), "{err}");
    }

    #[test]
    fn renamed_scope_missing_and_extra_signals_are_errors() {
        let renamed = Shaped(|t| {
            t.push_scope("core1");
            t.pop_scope();
        });
        let missing = Shaped(|t| {
            t.push_scope("core0");
            t.signal("free_mshrs", 5, 0);
            t.bit("valid", false);
            t.pop_scope();
        });
        let extra = Shaped(|t| {
            START.trace(t);
            t.bit("extra", true);
        });
        let cases: [(&Shaped, &str); 3] = [
            (&renamed, "expected scope `core0`, got scope `core1`"),
            (&missing, "expected scope `sched`, got the end of a scope"),
            (&extra, "expected the end of the cycle, got signal `extra`"),
        ];
        for (design, needle) in cases {
            let mut sink = VcdSink::new(Vec::new(), "top");
            sink.trace_cycle(0, &START).unwrap();
            expect_error(
                sink.trace_cycle(1, design),
                io::ErrorKind::InvalidData,
                needle,
            );
        }

        // A cycle that stops early.
        let truncated = Shaped(|t| {
            t.push_scope("core0");
            t.signal("free_mshrs", 5, 0);
            t.bit("valid", false);
            t.push_scope("sched");
            t.signal("warp", 3, 0);
            t.signal("word", 64, 0);
            t.pop_scope();
            t.pop_scope();
        });
        let short = Shaped(|t| {
            t.push_scope("core0");
            t.pop_scope();
        });
        let mut sink = VcdSink::new(Vec::new(), "top");
        sink.trace_cycle(0, &truncated).unwrap();
        expect_error(
            sink.trace_cycle(1, &short),
            io::ErrorKind::InvalidData,
            "expected signal `top.core0.free_mshrs` of width 5, got the end of a scope",
        );
    }

    #[test]
    fn a_failed_cycle_writes_nothing() {
        let mut sink = VcdSink::new(Vec::new(), "top");
        sink.trace_cycle(0, &START).unwrap();
        let bad = Shaped(|t| {
            t.push_scope("core0");
            t.signal("free_mshrs", 5, 31);
            t.bit("oops", true);
        });
        assert!(sink.trace_cycle(1, &bad).is_err());
        let text = String::from_utf8(sink.out.clone()).unwrap();
        assert!(!text.contains("#1"), "{text}");
    }

    #[test]
    fn bad_widths_are_errors() {
        let zero = Shaped(|t| t.signal("x", 0, 0));
        let wide = Shaped(|t| t.signal("x", 65, 0));
        for (width, design) in [(0, zero), (65, wide)] {
            let mut sink = VcdSink::new(Vec::new(), "top");
            expect_error(
                sink.trace_cycle(0, &design),
                io::ErrorKind::InvalidData,
                &format!("signal `top.x` has width {width}; widths must be 1..=64"),
            );
        }
    }

    #[test]
    fn bad_names_are_errors() {
        let spaced = Shaped(|t| t.bit("a b", true));
        let mut sink = VcdSink::new(Vec::new(), "top");
        expect_error(
            sink.trace_cycle(0, &spaced),
            io::ErrorKind::InvalidData,
            "contains whitespace",
        );

        let twice = Shaped(|t| {
            t.bit("a", true);
            t.bit("a", false);
        });
        let mut sink = VcdSink::new(Vec::new(), "top");
        expect_error(
            sink.trace_cycle(0, &twice),
            io::ErrorKind::InvalidData,
            "signal `top.a` is traced twice",
        );

        let mut sink = VcdSink::new(Vec::new(), "");
        expect_error(
            sink.trace_cycle(0, &START),
            io::ErrorKind::InvalidInput,
            "top scope name \"\" is empty",
        );
    }

    #[test]
    fn unbalanced_scopes_are_errors() {
        let unclosed = Shaped(|t| t.push_scope("core0"));
        let mut sink = VcdSink::new(Vec::new(), "top");
        expect_error(
            sink.trace_cycle(0, &unclosed),
            io::ErrorKind::InvalidData,
            "scope `core0` still open",
        );

        let overclosed = Shaped(|t| t.pop_scope());
        let mut sink = VcdSink::new(Vec::new(), "top");
        expect_error(
            sink.trace_cycle(0, &overclosed),
            io::ErrorKind::InvalidData,
            "pop_scope without a matching push_scope",
        );
    }
}
