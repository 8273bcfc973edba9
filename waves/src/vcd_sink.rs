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
//!
//! [`Tracer`]: crate::Tracer
//! [`io::ErrorKind::InvalidData`]: std::io::ErrorKind::InvalidData

mod hierarchy;
pub mod readback;
mod shape;
mod sink;
#[cfg(test)]
mod testkit;
mod time;
mod value;
mod write;

pub use hierarchy::SignalInfo;
pub use sink::VcdSink;
pub use time::{period_ps, time_unit_note, TimeAxis, TIME_UNIT_COMMENT};
pub use value::MAX_WIDTH;
pub use write::VERSION;
