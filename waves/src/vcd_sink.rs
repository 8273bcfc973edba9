//! A [`Tracer`] that writes a Value Change Dump (IEEE 1364 VCD).
//!
//! # Time
//!
//! The VCD format only allows a timescale of 1, 10 or 100 of a physical unit
//! (s, ms, us, ns, ps, fs), so a clock period such as 1.667 ns cannot be the
//! unit. A sink offers two time axes ([`TimeAxis`]):
//!
//! - [`TimeAxis::Cycles`] (the default): **one VCD time unit is one clock
//!   cycle**. Timestamps are the cycle numbers given to
//!   [`VcdSink::begin_cycle`], so the cycle numbers of the simulator's
//!   statistics, `--vcd-from`/`--vcd-to` and the waveform agree. The file
//!   declares `$timescale 1 ns $end` because a timescale must name a
//!   physical unit, and says in a `$comment` that a unit is a cycle (and,
//!   when the clock is given with [`VcdSink::with_clock_mhz`], which clock:
//!   "one time unit = one GPU cycle at 600 MHz (1.667 ns)"). A waveform
//!   viewer's "ns" axis therefore reads as cycles.
//! - [`TimeAxis::RealTime`]: `$timescale 1 ps $end` and timestamps of
//!   cycle × the clock period rounded to whole picoseconds (1667 ps at
//!   600 MHz), so a viewer shows real time; the `$comment` states the
//!   period. Cycle N is at time N × period.
//!
//! # Protocol
//!
//! ```text
//! let mut sink = VcdSink::new(file, "top");
//! for each cycle c (strictly increasing):
//!     sink.begin_cycle(c);
//!     design.trace(&mut sink);      // or sink.trace_cycle(c, &design)
//!     sink.end_cycle()?;
//! let file = sink.finish(last_cycle + 1)?;
//! ```
//!
//! The first cycle defines the hierarchy: every scope becomes a
//! `$scope module`, every signal a `$var wire`, all inside the `top` scope
//! given to [`VcdSink::new`]. Its values are dumped in full under
//! `$dumpvars`. Later cycles write a `#cycle` timestamp followed by the
//! signals whose value changed, and nothing at all when none changed.
//!
//! Signals are identified by their position in the visit order, so the
//! design must visit the same scopes and signals, with the same names and
//! widths, in the same order every cycle (the [`Tracer`] contract). This is
//! checked on every call at the cost of one string comparison; a violation is
//! reported by [`VcdSink::end_cycle`] as an [`io::ErrorKind::InvalidData`]
//! error naming the offending item, never by a panic.
//!
//! # Errors are sticky
//!
//! After any error (a shape change, a misuse of the protocol, an I/O error
//! from the writer) the sink is poisoned: nothing more is written, and every
//! later [`VcdSink::end_cycle`] and [`VcdSink::finish`] returns the same
//! error. A half-written cycle is never emitted: a cycle's changes are written
//! only once the whole cycle was visited without error.
//!
//! # Values
//!
//! Widths are 1 to 64 bits ([`MAX_WIDTH`]). Bits of a value above its width
//! are masked off (the [`Tracer`] contract says they must be zero; a sink
//! does not panic on a design's mistake). Vectors are written in binary, most
//! significant bit first, at full width (`b00110 !` for 6 in 5 bits); one-bit
//! signals as scalars (`1"`).
//!
//! # Cost
//!
//! After the first cycle, tracing allocates nothing: values are compared in
//! place and each change is formatted into a small stack buffer. Wrap the
//! writer in a [`std::io::BufWriter`] when writing to a file.

use std::collections::HashSet;
use std::io::{self, Write};

use vcd::{IdCode, ReferenceIndex, SimulationCommand, TimescaleUnit, VarType};

use crate::{CycleSink, Traceable, Tracer};

pub mod readback;

/// The widest signal a [`VcdSink`] accepts, in bits.
pub const MAX_WIDTH: u32 = 64;

/// Text of the `$version` header.
pub const VERSION: &str = concat!("wasp ", env!("CARGO_PKG_VERSION"));

/// Text of the `$comment` header that states the time unit when the clock
/// frequency is not given.
pub const TIME_UNIT_COMMENT: &str = "one time unit = one clock cycle";

/// How VCD time relates to clock cycles (see the [time unit](self#time)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum TimeAxis {
    /// One time unit per cycle (`$timescale 1 ns`, read as cycles).
    #[default]
    Cycles,
    /// Picoseconds (`$timescale 1 ps`): cycle × the clock period.
    RealTime,
}

/// The clock period in whole picoseconds (rounded), at least 1.
pub fn period_ps(clock_mhz: u32) -> u64 {
    let mhz = u64::from(clock_mhz.max(1));
    ((1_000_000 + mhz / 2) / mhz).max(1)
}

/// The sentence that states what a VCD time unit is: the `$comment` of a
/// [`VcdSink`] and a comment line of its GTKWave save file.
///
/// ```
/// use wasp_waves::vcd_sink::{time_unit_note, TimeAxis};
///
/// assert_eq!(
///     time_unit_note(Some(600), TimeAxis::Cycles),
///     "one time unit = one GPU cycle at 600 MHz (1.667 ns)"
/// );
/// assert_eq!(
///     time_unit_note(Some(600), TimeAxis::RealTime),
///     "time unit = 1 ps; one GPU cycle at 600 MHz = 1667 ps: cycle N is at time N x 1667"
/// );
/// ```
pub fn time_unit_note(clock_mhz: Option<u32>, axis: TimeAxis) -> String {
    match (clock_mhz, axis) {
        (None, _) => TIME_UNIT_COMMENT.to_owned(),
        (Some(mhz), TimeAxis::Cycles) => format!(
            "one time unit = one GPU cycle at {mhz} MHz ({:.3} ns)",
            1000.0 / f64::from(mhz.max(1))
        ),
        (Some(mhz), TimeAxis::RealTime) => {
            let ps = period_ps(mhz);
            format!(
                "time unit = 1 ps; one GPU cycle at {mhz} MHz = {ps} ps: \
                 cycle N is at time N x {ps}"
            )
        }
    }
}

/// Longest VCD identifier code a `u64` index can produce (94 printable
/// characters per digit: 94^10 > 2^64).
const MAX_ID_LEN: usize = 10;

/// A signal as defined by the first traced cycle.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct SignalInfo {
    /// Enclosing scopes, outermost first, starting with the sink's top scope.
    pub path: Vec<String>,
    /// The signal's own name.
    pub name: String,
    /// Width in bits, 1..=[`MAX_WIDTH`].
    pub width: u32,
}

impl SignalInfo {
    /// Dotted hierarchical name, e.g. `top.core0.free_mshrs`.
    ///
    /// This is the key used by [`readback::ReadBack`].
    pub fn full_name(&self) -> String {
        let mut s = String::new();
        for scope in &self.path {
            s.push_str(scope);
            s.push('.');
        }
        s.push_str(&self.name);
        s
    }

    /// Whether the signal is written as a vector (width above one bit).
    pub fn is_vector(&self) -> bool {
        self.width > 1
    }

    /// The name GTKWave shows and expects in save files: the full name, plus
    /// `[msb:0]` for vectors, e.g. `top.core0.free_mshrs[4:0]`.
    pub fn gtkwave_name(&self) -> String {
        let mut s = self.full_name();
        if self.is_vector() {
            s.push_str(&format!("[{}:0]", self.width - 1));
        }
        s
    }
}

/// One step of the visit order recorded on the first cycle.
#[derive(Debug)]
enum Event {
    Push(String),
    Pop,
    Signal,
}

/// Per-signal state, indexed like [`VcdSink::signals`].
#[derive(Debug)]
struct Slot {
    /// VCD identifier code, ASCII.
    id: [u8; MAX_ID_LEN],
    id_len: u8,
    width: u32,
    mask: u64,
    /// Value seen this cycle.
    value: u64,
    /// Value last written to the file.
    written: u64,
}

impl Slot {
    fn new(index: usize, width: u32, value: u64) -> Slot {
        let code = IdCode::from(index as u64).to_string();
        debug_assert!(code.len() <= MAX_ID_LEN);
        let mut id = [0u8; MAX_ID_LEN];
        id[..code.len()].copy_from_slice(code.as_bytes());
        let mask = width_mask(width);
        Slot {
            id,
            id_len: code.len() as u8,
            width,
            mask,
            value: value & mask,
            written: value & mask,
        }
    }

    fn id(&self) -> &[u8] {
        &self.id[..self.id_len as usize]
    }

    /// Writes the current value as one VCD value-change line.
    fn write_value<W: Write>(&self, out: &mut W) -> io::Result<()> {
        // 'b' + 64 bits + ' ' + id + '\n'
        let mut buf = [0u8; 1 + MAX_WIDTH as usize + 1 + MAX_ID_LEN + 1];
        let mut n;
        if self.width == 1 {
            buf[0] = b'0' + (self.value & 1) as u8;
            n = 1;
        } else {
            buf[0] = b'b';
            n = 1;
            for bit in (0..self.width).rev() {
                buf[n] = b'0' + ((self.value >> bit) & 1) as u8;
                n += 1;
            }
            buf[n] = b' ';
            n += 1;
        }
        let id = self.id();
        buf[n..n + id.len()].copy_from_slice(id);
        n += id.len();
        buf[n] = b'\n';
        n += 1;
        out.write_all(&buf[..n])
    }
}

fn width_mask(width: u32) -> u64 {
    if width >= 64 {
        u64::MAX
    } else {
        (1u64 << width) - 1
    }
}

/// Why a name cannot appear in a VCD file, if it cannot.
fn name_problem(name: &str) -> Option<&'static str> {
    if name.is_empty() {
        Some("is empty")
    } else if name.chars().any(|c| c.is_whitespace() || c.is_control()) {
        Some("contains whitespace or a control character")
    } else if name.contains('.') {
        Some("contains '.', the hierarchy separator")
    } else {
        None
    }
}

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
/// See the [module documentation](self) for the protocol, the time unit and
/// error handling.
#[derive(Debug)]
pub struct VcdSink<W: Write> {
    out: W,
    top: String,
    date: Option<String>,
    /// Clock frequency named in the time comment, MHz.
    clock_mhz: Option<u32>,
    /// Time axis; [`TimeAxis::RealTime`] only with a clock.
    axis: TimeAxis,
    /// VCD time units per cycle (1, or the period in ps).
    scale: u64,
    /// Whether the header and the first cycle's dump were written.
    defined: bool,
    /// Between `begin_cycle` and `end_cycle`.
    in_cycle: bool,
    /// Cycle being traced (or last traced).
    cycle: u64,
    /// Last cycle begun, to keep timestamps increasing.
    last_cycle: Option<u64>,
    /// Last timestamp written to the file.
    last_time: Option<u64>,
    /// Visit order of the first cycle.
    events: Vec<Event>,
    signals: Vec<SignalInfo>,
    slots: Vec<Slot>,
    /// Position in `events` during a cycle.
    event_pos: usize,
    /// Position in `signals` during a cycle.
    signal_pos: usize,
    /// Scope nesting depth during a cycle (below `top`).
    depth: usize,
    /// Current scope path during the first cycle (starts with `top`).
    path: Vec<String>,
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
    fn time_of(&self, cycle: u64) -> u64 {
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
    fn fail(&mut self, kind: io::ErrorKind, message: String) -> io::Error {
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
    fn accepting(&mut self, what: &str) -> bool {
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

    /// Human description of the first cycle's event at `pos`.
    fn describe_event(&self, pos: usize) -> String {
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
    fn open_scope_name(&self) -> String {
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

    fn check_unique_names(&mut self) -> io::Result<()> {
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

    /// Header and hierarchy, up to `$enddefinitions`.
    fn write_header(&mut self) -> io::Result<()> {
        if self.axis == TimeAxis::RealTime && self.clock_mhz.is_none() {
            return Err(self.fail(
                io::ErrorKind::InvalidInput,
                "a real-time axis needs the clock frequency (with_clock_mhz)".to_owned(),
            ));
        }
        let note = time_unit_note(self.clock_mhz, self.axis);
        let unit = match self.axis {
            TimeAxis::Cycles => TimescaleUnit::NS,
            TimeAxis::RealTime => TimescaleUnit::PS,
        };
        let mut w = vcd::Writer::new(&mut self.out);
        if let Some(date) = &self.date {
            w.date(date)?;
        }
        w.version(VERSION)?;
        w.comment(&note)?;
        w.timescale(1, unit)?;
        w.add_module(&self.top)?;
        let mut index = 0;
        for event in &self.events {
            match event {
                Event::Push(name) => w.add_module(name)?,
                Event::Pop => w.upscope()?,
                Event::Signal => {
                    let info = &self.signals[index];
                    let range = info
                        .is_vector()
                        .then(|| ReferenceIndex::Range(info.width as i32 - 1, 0));
                    w.var_def(
                        VarType::Wire,
                        info.width,
                        IdCode::from(index as u64),
                        &info.name,
                        range,
                    )?;
                    index += 1;
                }
            }
        }
        w.upscope()?;
        w.enddefinitions()?;
        self.defined = true;
        Ok(())
    }

    /// The first cycle: every value under `$dumpvars`.
    fn write_dumpvars(&mut self) -> io::Result<()> {
        let time = self.time_of(self.cycle);
        let mut w = vcd::Writer::new(&mut self.out);
        w.timestamp(time)?;
        w.begin(SimulationCommand::Dumpvars)?;
        for slot in &mut self.slots {
            slot.write_value(w.writer())?;
            slot.written = slot.value;
        }
        w.end()?;
        self.last_time = Some(time);
        Ok(())
    }

    /// A later cycle: the changed values, under a timestamp if any.
    fn write_changes(&mut self) -> io::Result<()> {
        let mut stamped = false;
        let time = self.time_of(self.cycle);
        for slot in &mut self.slots {
            if slot.value != slot.written {
                if !stamped {
                    vcd::Writer::new(&mut self.out).timestamp(time)?;
                    stamped = true;
                }
                slot.write_value(&mut self.out)?;
                slot.written = slot.value;
            }
        }
        if stamped {
            self.last_time = Some(time);
        }
        Ok(())
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
    use vcd::{Command, ScopeItem, Value};

    /// A small design: a 5-bit counter, a valid bit, and a nested scheduler
    /// with a 3-bit warp id and a 64-bit word.
    #[derive(Clone, Copy)]
    struct Toy {
        free_mshrs: u64,
        valid: bool,
        warp: u64,
        word: u64,
    }

    impl Traceable for Toy {
        fn trace<T: Tracer + ?Sized>(&self, t: &mut T) {
            t.push_scope("core0");
            t.signal("free_mshrs", 5, self.free_mshrs);
            t.bit("valid", self.valid);
            t.push_scope("sched");
            t.signal("warp", 3, self.warp);
            t.signal("word", 64, self.word);
            t.pop_scope();
            t.pop_scope();
        }
    }

    const START: Toy = Toy {
        free_mshrs: 0b00110,
        valid: false,
        warp: 0,
        word: u64::MAX,
    };

    /// Cycles 0..=5: a change in 1, 2, 4 and 5, nothing in 3.
    fn toy_cycles() -> Vec<(u64, Toy)> {
        let mut t = START;
        let mut v = vec![(0, t)];
        t.valid = true;
        v.push((1, t));
        t.free_mshrs = 5;
        t.warp = 7;
        v.push((2, t));
        v.push((3, t));
        t.valid = false;
        v.push((4, t));
        t.word = 1 << 63;
        v.push((5, t));
        v
    }

    fn write_toy() -> Vec<u8> {
        let mut sink = VcdSink::new(Vec::new(), "top");
        for (cycle, toy) in toy_cycles() {
            sink.trace_cycle(cycle, &toy).unwrap();
        }
        sink.finish(6).unwrap()
    }

    /// Body commands after `$enddefinitions`, without dumpvars markers.
    fn body(bytes: &[u8]) -> Vec<Command> {
        let mut parser = vcd::Parser::new(bytes);
        parser.parse_header().unwrap();
        parser
            .map(Result::unwrap)
            .filter(|c| !matches!(c, Command::Begin(_) | Command::End(_)))
            .collect()
    }

    fn bits(s: &str) -> vcd::Vector {
        s.bytes()
            .map(|b| if b == b'1' { Value::V1 } else { Value::V0 })
            .collect()
    }

    #[test]
    fn header_defines_hierarchy_timescale_and_vars() {
        let bytes = write_toy();
        let mut parser = vcd::Parser::new(&bytes[..]);
        let header = parser.parse_header().unwrap();
        assert_eq!(header.timescale, Some((1, TimescaleUnit::NS)));
        assert_eq!(header.version.as_deref(), Some(VERSION));
        assert_eq!(header.date, None);
        assert!(header
            .items
            .iter()
            .any(|i| matches!(i, ScopeItem::Comment(c) if c == TIME_UNIT_COMMENT)));

        let mshrs = header.find_var(&["top", "core0", "free_mshrs"]).unwrap();
        assert_eq!(mshrs.size, 5);
        assert_eq!(mshrs.index, Some(ReferenceIndex::Range(4, 0)));
        let valid = header.find_var(&["top", "core0", "valid"]).unwrap();
        assert_eq!(valid.size, 1);
        assert_eq!(valid.index, None);
        let word = header.find_var(&["top", "core0", "sched", "word"]).unwrap();
        assert_eq!(word.size, 64);
        assert_eq!(word.index, Some(ReferenceIndex::Range(63, 0)));
        assert!(header.find_scope(&["top", "core0", "sched"]).is_some());

        let text = String::from_utf8(bytes).unwrap();
        assert!(
            text.contains("$var wire 5 ! free_mshrs [4:0] $end\n"),
            "{text}"
        );
        assert!(text.contains("$var wire 1 \" valid $end\n"), "{text}");
        assert!(text.contains("$scope module top $end\n$scope module core0 $end\n"));
    }

    #[test]
    fn exact_output() {
        let text = String::from_utf8(write_toy()).unwrap();
        let expected = format!(
            "$version\n    {VERSION}\n$end\n\
             $comment\n    one time unit = one clock cycle\n$end\n\
             $timescale 1 ns $end\n\
             $scope module top $end\n\
             $scope module core0 $end\n\
             $var wire 5 ! free_mshrs [4:0] $end\n\
             $var wire 1 \" valid $end\n\
             $scope module sched $end\n\
             $var wire 3 # warp [2:0] $end\n\
             $var wire 64 $ word [63:0] $end\n\
             $upscope $end\n\
             $upscope $end\n\
             $upscope $end\n\
             $enddefinitions $end\n\
             #0\n$dumpvars\nb00110 !\n0\"\nb000 #\nb{ones} $\n$end\n\
             #1\n1\"\n\
             #2\nb00101 !\nb111 #\n\
             #4\n0\"\n\
             #5\nb1{zeros} $\n\
             #6\n",
            ones = "1".repeat(64),
            zeros = "0".repeat(63),
        );
        assert_eq!(text, expected);
    }

    #[test]
    fn only_changes_after_first_cycle_msb_first() {
        let cmds = body(&write_toy());
        let mshrs: IdCode = "!".parse().unwrap();
        let valid: IdCode = "\"".parse().unwrap();
        let warp: IdCode = "#".parse().unwrap();
        let word: IdCode = "$".parse().unwrap();
        let expected = vec![
            Command::Timestamp(0),
            // 0b00110 in 5 bits, MSB first: 0,0,1,1,0
            Command::ChangeVector(mshrs, bits("00110")),
            Command::ChangeScalar(valid, Value::V0),
            Command::ChangeVector(warp, bits("000")),
            Command::ChangeVector(word, bits(&"1".repeat(64))),
            Command::Timestamp(1),
            Command::ChangeScalar(valid, Value::V1),
            Command::Timestamp(2),
            Command::ChangeVector(mshrs, bits("00101")),
            Command::ChangeVector(warp, bits("111")),
            // cycle 3: nothing changed, no timestamp
            Command::Timestamp(4),
            Command::ChangeScalar(valid, Value::V0),
            Command::Timestamp(5),
            Command::ChangeVector(word, bits(&format!("1{}", "0".repeat(63)))),
            Command::Timestamp(6),
        ];
        assert_eq!(cmds, expected);
    }

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
    fn deterministic() {
        assert_eq!(write_toy(), write_toy());
    }

    #[test]
    fn signals_lists_first_cycle_in_order() {
        let mut sink = VcdSink::new(Vec::new(), "top");
        assert!(sink.signals().is_empty());
        sink.trace_cycle(0, &START).unwrap();
        let names: Vec<_> = sink.signals().iter().map(SignalInfo::full_name).collect();
        assert_eq!(
            names,
            [
                "top.core0.free_mshrs",
                "top.core0.valid",
                "top.core0.sched.warp",
                "top.core0.sched.word"
            ]
        );
        assert_eq!(
            sink.signals()[0].gtkwave_name(),
            "top.core0.free_mshrs[4:0]"
        );
        assert_eq!(sink.signals()[1].gtkwave_name(), "top.core0.valid");
        assert_eq!(sink.signals()[2].path, ["top", "core0", "sched"]);
    }

    #[test]
    fn values_wider_than_width_are_masked() {
        let mut sink = VcdSink::new(Vec::new(), "top");
        let design = Toy {
            free_mshrs: 0xFF, // 8 bits into a 5-bit signal
            warp: 0b1010,     // 4 bits into 3
            ..START
        };
        sink.trace_cycle(0, &design).unwrap();
        // Same low bits, different high bits: no change.
        let same = Toy {
            free_mshrs: 0x3F,
            warp: 0b0010,
            ..START
        };
        sink.trace_cycle(1, &same).unwrap();
        let text = String::from_utf8(sink.finish(2).unwrap()).unwrap();
        assert!(text.contains("b11111 !\n"), "{text}");
        assert!(text.contains("b010 #\n"), "{text}");
        assert!(!text.contains("#1\n"), "{text}");
    }

    #[test]
    fn no_change_cycles_write_no_timestamp_and_final_is_written() {
        let mut sink = VcdSink::new(Vec::new(), "top");
        for cycle in 0..10 {
            sink.trace_cycle(cycle, &START).unwrap();
        }
        let cmds = body(&sink.finish(10).unwrap());
        let stamps: Vec<_> = cmds
            .iter()
            .filter_map(|c| match c {
                Command::Timestamp(t) => Some(*t),
                _ => None,
            })
            .collect();
        assert_eq!(stamps, [0, 10]);
    }

    #[test]
    fn final_timestamp_not_duplicated() {
        let mut sink = VcdSink::new(Vec::new(), "top");
        sink.trace_cycle(0, &START).unwrap();
        let text = String::from_utf8(sink.finish(0).unwrap()).unwrap();
        assert_eq!(text.matches("#0\n").count(), 1, "{text}");
    }

    #[test]
    fn date_is_opt_in() {
        let mut sink = VcdSink::new(Vec::new(), "top").with_date("today");
        sink.trace_cycle(0, &START).unwrap();
        let bytes = sink.finish(1).unwrap();
        let header = vcd::Parser::new(&bytes[..]).parse_header().unwrap();
        assert_eq!(header.date.as_deref(), Some("today"));
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

    fn expect_error(result: io::Result<()>, kind: io::ErrorKind, needle: &str) {
        let err = result.expect_err("expected an error");
        assert_eq!(err.kind(), kind, "{err}");
        let message = err.to_string();
        assert!(message.contains(needle), "`{message}` lacks `{needle}`");
    }

    /// A design whose shape is chosen per cycle.
    struct Shaped(fn(&mut dyn Tracer));

    impl Traceable for Shaped {
        fn trace<T: Tracer + ?Sized>(&self, t: &mut T) {
            // Route through a trait object so each test can pass a closure.
            let mut adapter = Adapter(t);
            (self.0)(&mut adapter);
        }
    }

    struct Adapter<'a, T: Tracer + ?Sized>(&'a mut T);

    impl<T: Tracer + ?Sized> Tracer for Adapter<'_, T> {
        fn push_scope(&mut self, name: &str) {
            self.0.push_scope(name)
        }
        fn pop_scope(&mut self) {
            self.0.pop_scope()
        }
        fn signal(&mut self, name: &str, width: u32, value: u64) {
            self.0.signal(name, width, value)
        }
    }

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

    fn write_toy_with(setup: impl FnOnce(VcdSink<Vec<u8>>) -> VcdSink<Vec<u8>>) -> Vec<u8> {
        let mut sink = setup(VcdSink::new(Vec::new(), "top"));
        for (cycle, toy) in toy_cycles() {
            sink.trace_cycle(cycle, &toy).unwrap();
        }
        sink.finish(6).unwrap()
    }

    fn timestamps(bytes: &[u8]) -> Vec<u64> {
        body(bytes)
            .into_iter()
            .filter_map(|c| match c {
                Command::Timestamp(t) => Some(t),
                _ => None,
            })
            .collect()
    }

    fn header_comments(bytes: &[u8]) -> Vec<String> {
        let header = vcd::Parser::new(bytes).parse_header().unwrap();
        header
            .items
            .iter()
            .filter_map(|i| match i {
                ScopeItem::Comment(c) => Some(c.clone()),
                _ => None,
            })
            .collect()
    }

    #[test]
    fn period_is_rounded_to_whole_picoseconds() {
        assert_eq!(period_ps(600), 1667);
        assert_eq!(period_ps(1000), 1000);
        assert_eq!(period_ps(1), 1_000_000);
        assert_eq!(period_ps(10_000), 100);
        assert_eq!(period_ps(0), 1_000_000);
    }

    #[test]
    fn clock_names_the_cycle_in_the_comment_and_keeps_cycle_times() {
        let plain = write_toy();
        let bytes = write_toy_with(|s| s.with_clock_mhz(600));
        assert_eq!(
            header_comments(&bytes),
            ["one time unit = one GPU cycle at 600 MHz (1.667 ns)"]
        );
        let header = vcd::Parser::new(&bytes[..]).parse_header().unwrap();
        assert_eq!(header.timescale, Some((1, TimescaleUnit::NS)));
        assert_eq!(timestamps(&bytes), timestamps(&plain));
        assert_eq!(timestamps(&bytes), [0, 1, 2, 4, 5, 6]);
        assert_eq!(body(&bytes), body(&plain));
    }

    #[test]
    fn real_time_axis_writes_picoseconds() {
        let plain = write_toy();
        let bytes = write_toy_with(|s| s.with_time_axis(TimeAxis::RealTime).with_clock_mhz(600));
        let header = vcd::Parser::new(&bytes[..]).parse_header().unwrap();
        assert_eq!(header.timescale, Some((1, TimescaleUnit::PS)));
        assert_eq!(
            header_comments(&bytes),
            ["time unit = 1 ps; one GPU cycle at 600 MHz = 1667 ps: cycle N is at time N x 1667"]
        );
        let want: Vec<u64> = [0, 1, 2, 4, 5, 6].iter().map(|c| c * 1667).collect();
        assert_eq!(timestamps(&bytes), want);
        // The same changes, only the timestamps differ.
        let strip = |b: &[u8]| -> Vec<Command> {
            body(b)
                .into_iter()
                .filter(|c| !matches!(c, Command::Timestamp(_)))
                .collect()
        };
        assert_eq!(strip(&bytes), strip(&plain));
        let waves = readback::values_by_cycle(&bytes).unwrap();
        assert_eq!(waves.value_at("top.core0.sched.warp", 2 * 1667), Some(7));
        assert_eq!(
            waves.value_at("top.core0.sched.warp", 2 * 1667 - 1),
            Some(0)
        );
        assert_eq!(waves.end_time(), Some(6 * 1667));
    }

    #[test]
    fn real_time_needs_a_clock_and_a_clock_must_tick() {
        let mut sink = VcdSink::new(Vec::new(), "top").with_time_axis(TimeAxis::RealTime);
        expect_error(
            sink.trace_cycle(0, &START),
            io::ErrorKind::InvalidInput,
            "clock frequency",
        );
        let mut sink = VcdSink::new(Vec::new(), "top").with_clock_mhz(0);
        expect_error(
            sink.trace_cycle(0, &START),
            io::ErrorKind::InvalidInput,
            "0 MHz",
        );
    }
}
