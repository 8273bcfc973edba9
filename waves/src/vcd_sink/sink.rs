//! [`VcdSink`]: its options, the cycle protocol, finishing the file, and
//! the sticky error that poisons it.

use std::io::{self, Write};

use super::hierarchy::{name_problem, Event, SignalInfo};
use super::time::{period_ps, TimeAxis};
use super::value::Slot;
use crate::{CycleSink, Traceable};

/// The first error met, kept to be reported again (errors are sticky).
#[derive(Debug, Clone)]
struct Poison {
    kind: io::ErrorKind,
    message: String,
}

impl Poison {
    fn to_error(&self) -> io::Error {
        io::Error::new(self.kind, self.message.clone())
    }
}

/// Writes the signals of a design as a VCD file, one cycle at a time.
///
/// See the [module documentation](super) for the protocol, the time unit and
/// error handling.
#[derive(Debug)]
pub struct VcdSink<W: Write> {
    pub(super) out: W,
    pub(super) top: String,
    pub(super) date: Option<String>,
    /// Clock frequency named in the time comment, MHz.
    pub(super) clock_mhz: Option<u32>,
    /// Time axis; [`TimeAxis::RealTime`] only with a clock.
    pub(super) axis: TimeAxis,
    /// VCD time units per cycle (1, or the period in ps).
    scale: u64,
    /// Whether the header and the first cycle's dump were written.
    pub(super) defined: bool,
    /// Between `begin_cycle` and `end_cycle`.
    in_cycle: bool,
    /// Cycle being traced (or last traced).
    pub(super) cycle: u64,
    /// Last cycle begun, to keep timestamps increasing.
    last_cycle: Option<u64>,
    /// Last timestamp written to the file.
    pub(super) last_time: Option<u64>,
    /// Visit order of the first cycle.
    pub(super) events: Vec<Event>,
    pub(super) signals: Vec<SignalInfo>,
    pub(super) slots: Vec<Slot>,
    /// Position in `events` during a cycle.
    pub(super) event_pos: usize,
    /// Position in `signals` during a cycle.
    pub(super) signal_pos: usize,
    /// Scope nesting depth during a cycle (below `top`).
    pub(super) depth: usize,
    /// Current scope path during the first cycle (starts with `top`).
    pub(super) path: Vec<String>,
    poison: Option<Poison>,
}

impl<W: Write> VcdSink<W> {
    /// A sink writing to `writer`, with every traced scope and signal inside
    /// a top-level scope named `top`.
    ///
    /// Nothing is written until the first [`end_cycle`](Self::end_cycle) (or
    /// [`finish`](Self::finish)). An invalid `top` name (empty, containing
    /// whitespace or `.`) is reported by that first call.
    pub fn new(writer: W, top: &str) -> Self {
        let mut sink = VcdSink {
            out: writer,
            top: top.to_owned(),
            date: None,
            clock_mhz: None,
            axis: TimeAxis::Cycles,
            scale: 1,
            defined: false,
            in_cycle: false,
            cycle: 0,
            last_cycle: None,
            last_time: None,
            events: Vec::new(),
            signals: Vec::new(),
            slots: Vec::new(),
            event_pos: 0,
            signal_pos: 0,
            depth: 0,
            path: vec![top.to_owned()],
            poison: None,
        };
        if let Some(problem) = name_problem(top) {
            sink.fail(
                io::ErrorKind::InvalidInput,
                format!("top scope name {top:?} {problem}"),
            );
        }
        sink
    }

    /// Adds a `$date` header with the given text.
    ///
    /// No date is written by default, so that identical runs produce
    /// byte-identical files; pass one explicitly if you want it.
    pub fn with_date(mut self, date: impl Into<String>) -> Self {
        self.date = Some(date.into());
        self
    }

    /// Names the clock in the time `$comment`: "one time unit = one GPU cycle
    /// at 600 MHz (1.667 ns)". The time axis stays one unit per cycle unless
    /// [`with_time_axis`](Self::with_time_axis) asks for real time.
    /// A frequency of 0 is reported by the first
    /// [`end_cycle`](Self::end_cycle) (or [`finish`](Self::finish)).
    pub fn with_clock_mhz(mut self, mhz: u32) -> Self {
        if mhz == 0 {
            self.fail(
                io::ErrorKind::InvalidInput,
                "clock frequency 0 MHz".to_owned(),
            );
        }
        self.clock_mhz = Some(mhz);
        self.update_scale();
        self
    }

    /// Chooses the time axis. [`TimeAxis::RealTime`] needs the clock
    /// ([`with_clock_mhz`](Self::with_clock_mhz), in either order); without
    /// one the first [`end_cycle`](Self::end_cycle) (or
    /// [`finish`](Self::finish)) reports an error.
    pub fn with_time_axis(mut self, axis: TimeAxis) -> Self {
        self.axis = axis;
        self.update_scale();
        self
    }

    /// The time axis in use.
    pub fn time_axis(&self) -> TimeAxis {
        self.axis
    }

    /// VCD time units per cycle: 1 on the cycle axis, the clock period in
    /// picoseconds on the real-time axis.
    pub fn units_per_cycle(&self) -> u64 {
        self.scale
    }

    fn update_scale(&mut self) {
        self.scale = match (self.axis, self.clock_mhz) {
            (TimeAxis::RealTime, Some(mhz)) => period_ps(mhz),
            _ => 1,
        };
    }

    /// The VCD time of `cycle`.
    pub(super) fn time_of(&self, cycle: u64) -> u64 {
        cycle.saturating_mul(self.scale)
    }

    /// The signals defined by the first cycle, in visit order (empty before
    /// the first [`end_cycle`](Self::end_cycle) succeeded).
    pub fn signals(&self) -> &[SignalInfo] {
        if self.defined {
            &self.signals
        } else {
            &[]
        }
    }

    /// Starts cycle `cycle`; the design's trace calls follow.
    ///
    /// Cycle numbers must strictly increase from one call to the next; they
    /// need not be contiguous. Misuse is reported by
    /// [`end_cycle`](Self::end_cycle).
    pub fn begin_cycle(&mut self, cycle: u64) {
        if self.poison.is_some() {
            return;
        }
        if self.in_cycle {
            self.fail(
                io::ErrorKind::InvalidInput,
                format!(
                    "begin_cycle({cycle}) called while cycle {} is still open",
                    self.cycle
                ),
            );
            return;
        }
        if let Some(last) = self.last_cycle {
            if cycle <= last {
                self.fail(
                    io::ErrorKind::InvalidInput,
                    format!("cycle numbers must increase: cycle {cycle} after cycle {last}"),
                );
                return;
            }
        }
        self.in_cycle = true;
        self.cycle = cycle;
        self.last_cycle = Some(cycle);
        self.event_pos = 0;
        self.signal_pos = 0;
        self.depth = 0;
    }

    /// Ends the current cycle and writes it: the header and a full dump on
    /// the first cycle, the changed values afterwards.
    ///
    /// # Errors
    ///
    /// [`io::ErrorKind::InvalidData`] if the design's shape differs from the
    /// first cycle's, or a signal has a width outside 1..=64, or a name cannot
    /// be written; [`io::ErrorKind::InvalidInput`] for protocol misuse; any
    /// error of the underlying writer. All are sticky.
    pub fn end_cycle(&mut self) -> io::Result<()> {
        self.check()?;
        if !self.in_cycle {
            return Err(self.fail(
                io::ErrorKind::InvalidInput,
                "end_cycle called without begin_cycle".to_owned(),
            ));
        }
        self.in_cycle = false;
        if self.depth != 0 {
            let open = if self.defined {
                self.open_scope_name()
            } else {
                self.path.last().cloned().unwrap_or_default()
            };
            return Err(self.fail(
                io::ErrorKind::InvalidData,
                format!(
                    "cycle {} ended with scope `{open}` still open (missing pop_scope)",
                    self.cycle
                ),
            ));
        }
        let result = if self.defined {
            if self.event_pos != self.events.len() {
                let expected = self.describe_event(self.event_pos);
                return Err(self.fail(
                    io::ErrorKind::InvalidData,
                    format!(
                        "design changed shape at cycle {}: expected {expected}, \
                         but the cycle ended",
                        self.cycle
                    ),
                ));
            }
            self.write_changes()
        } else {
            self.check_unique_names()?;
            self.write_header().and_then(|()| self.write_dumpvars())
        };
        result.map_err(|e| self.fail(e.kind(), e.to_string()))
    }

    /// Traces one whole cycle: [`begin_cycle`](Self::begin_cycle),
    /// `design.trace`, [`end_cycle`](Self::end_cycle).
    pub fn trace_cycle<D: Traceable + ?Sized>(&mut self, cycle: u64, design: &D) -> io::Result<()> {
        self.begin_cycle(cycle);
        design.trace(self);
        self.end_cycle()
    }

    /// Writes a final timestamp `#final_cycle`, flushes and returns the
    /// writer.
    ///
    /// Pass the cycle after the last traced one, so that viewers draw the
    /// last cycle's values with a width. No timestamp is added when
    /// `final_cycle` equals the last timestamp written. If no cycle was
    /// traced, the file has the header with an empty top scope.
    ///
    /// # Errors
    ///
    /// A sticky error from an earlier call; [`io::ErrorKind::InvalidInput`]
    /// if a cycle is still open or `final_cycle` is before the last traced
    /// cycle; any error of the underlying writer.
    pub fn finish(mut self, final_cycle: u64) -> io::Result<W> {
        self.check()?;
        if self.in_cycle {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                format!("finish called while cycle {} is still open", self.cycle),
            ));
        }
        if let Some(last) = self.last_cycle {
            if final_cycle < last {
                return Err(io::Error::new(
                    io::ErrorKind::InvalidInput,
                    format!("final cycle {final_cycle} is before the last traced cycle {last}"),
                ));
            }
        }
        if !self.defined {
            self.write_header()?;
        }
        let end = self.time_of(final_cycle);
        if self.last_time != Some(end) {
            vcd::Writer::new(&mut self.out).timestamp(end)?;
        }
        self.out.flush()?;
        Ok(self.out)
    }

    /// Records `message` as the sticky error unless one is already recorded,
    /// and returns the recorded error.
    pub(super) fn fail(&mut self, kind: io::ErrorKind, message: String) -> io::Error {
        self.poison
            .get_or_insert(Poison { kind, message })
            .to_error()
    }

    fn check(&self) -> io::Result<()> {
        match &self.poison {
            Some(p) => Err(p.to_error()),
            None => Ok(()),
        }
    }

    /// Whether a trace call should be processed; records misuse.
    pub(super) fn accepting(&mut self, what: &str) -> bool {
        if self.poison.is_some() {
            return false;
        }
        if !self.in_cycle {
            self.fail(
                io::ErrorKind::InvalidInput,
                format!("{what} called outside begin_cycle/end_cycle"),
            );
            return false;
        }
        true
    }
}

impl<W: Write> CycleSink for VcdSink<W> {
    fn begin_cycle(&mut self, cycle: u64) {
        VcdSink::begin_cycle(self, cycle);
    }

    fn end_cycle(&mut self) -> io::Result<()> {
        VcdSink::end_cycle(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vcd_sink::testkit::*;
    use crate::Tracer;
    use vcd::Command;

    #[test]
    fn usable_as_cycle_sink() {
        fn run<S: CycleSink>(sink: &mut S) -> io::Result<()> {
            for (cycle, toy) in toy_cycles() {
                sink.begin_cycle(cycle);
                toy.trace(sink);
                sink.end_cycle()?;
            }
            Ok(())
        }
        let mut sink = VcdSink::new(Vec::new(), "top");
        run(&mut sink).unwrap();
        assert_eq!(sink.finish(6).unwrap(), write_toy());
    }

    #[test]
    fn final_timestamp_not_duplicated() {
        let mut sink = VcdSink::new(Vec::new(), "top");
        sink.trace_cycle(0, &START).unwrap();
        let text = String::from_utf8(sink.finish(0).unwrap()).unwrap();
        assert_eq!(text.matches("#0\n").count(), 1, "{text}");
    }

    #[test]
    fn finish_without_cycles_writes_header() {
        let sink = VcdSink::new(Vec::new(), "top");
        let bytes = sink.finish(0).unwrap();
        let mut parser = vcd::Parser::new(&bytes[..]);
        let header = parser.parse_header().unwrap();
        assert!(header.find_scope(&["top"]).is_some());
        assert_eq!(parser.next().unwrap().unwrap(), Command::Timestamp(0));
    }

    #[test]
    fn protocol_misuse_is_an_error() {
        let mut sink = VcdSink::new(Vec::new(), "top");
        sink.trace_cycle(5, &START).unwrap();
        expect_error(
            sink.trace_cycle(5, &START),
            io::ErrorKind::InvalidInput,
            "cycle numbers must increase: cycle 5 after cycle 5",
        );

        let mut sink = VcdSink::new(Vec::new(), "top");
        expect_error(
            sink.end_cycle(),
            io::ErrorKind::InvalidInput,
            "end_cycle called without begin_cycle",
        );

        let mut sink = VcdSink::new(Vec::new(), "top");
        sink.bit("stray", true);
        expect_error(
            sink.trace_cycle(0, &START),
            io::ErrorKind::InvalidInput,
            "signal called outside begin_cycle/end_cycle",
        );

        let mut sink = VcdSink::new(Vec::new(), "top");
        sink.trace_cycle(3, &START).unwrap();
        let err = sink.finish(2).unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::InvalidInput);

        let mut sink = VcdSink::new(Vec::new(), "top");
        sink.begin_cycle(0);
        let err = sink.finish(1).unwrap_err();
        assert!(err.to_string().contains("still open"), "{err}");
    }

    /// A writer that fails after a number of bytes.
    struct Failing(usize);

    impl Write for Failing {
        fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
            if self.0 < buf.len() {
                return Err(io::Error::new(io::ErrorKind::BrokenPipe, "pipe closed"));
            }
            self.0 -= buf.len();
            Ok(buf.len())
        }
        fn flush(&mut self) -> io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn writer_errors_are_sticky() {
        let mut sink = VcdSink::new(Failing(20), "top");
        let err = sink.trace_cycle(0, &START).unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::BrokenPipe);
        let err = sink.trace_cycle(1, &START).unwrap_err();
        assert_eq!(err.kind(), io::ErrorKind::BrokenPipe);
    }
}
