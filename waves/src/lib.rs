//! Signal tracing for wasp.
//!
//! Hardware blocks expose their registers and wires through one visitor,
//! [`Traceable::trace`], which names each signal by its hardware name and
//! width inside nested scopes. A [`Tracer`] receives those calls. The clock
//! owner (the simulator) calls `trace` once per cycle, after every block has
//! been clocked, and only when tracing is on: with tracing off no tracing
//! code runs at all.
//!
//! Sinks provided here: [`vcd_sink::VcdSink`] writes a Value Change Dump
//! (change-only values, vectors MSB first, one time unit per cycle or
//! real time in picoseconds, stated in a `$comment`) and
//! [`gtkw`] writes a GTKWave save file that preselects signals.
//! [`readback`] parses a VCD back into per-cycle values, for tests.

pub mod gtkw;
pub mod vcd_sink;

pub use gtkw::{Format, GtkwSave};
pub use vcd_sink::{readback, SignalInfo, TimeAxis, VcdSink};

/// Receives the signals of a design, one cycle at a time.
///
/// Scopes nest: `push_scope("core0")`, signals, `pop_scope()`. A design must
/// visit the same scopes and signals, in the same order and with the same
/// widths, on every cycle; sinks rely on that to identify signals by
/// position without hashing names on the hot path.
pub trait Tracer {
    /// Enter a named scope (a module instance in hardware terms).
    fn push_scope(&mut self, name: &str);
    /// Leave the innermost scope.
    fn pop_scope(&mut self);
    /// One signal: its hardware name, width in bits (1..=64) and its value in
    /// this cycle. Bits of `value` above `width` must be zero.
    fn signal(&mut self, name: &str, width: u32, value: u64);

    /// Convenience for a one-bit signal.
    fn bit(&mut self, name: &str, value: bool) {
        self.signal(name, 1, value as u64);
    }
}

/// A block whose signals can be traced.
pub trait Traceable {
    /// Visit every signal worth seeing in a waveform.
    fn trace<T: Tracer + ?Sized>(&self, t: &mut T);
}

/// A [`Tracer`] that is sampled once per clock cycle: the clock owner calls
/// [`CycleSink::begin_cycle`], lets the design visit its signals, then
/// [`CycleSink::end_cycle`].
pub trait CycleSink: Tracer {
    /// Start the sample of `cycle` (cycles only increase).
    fn begin_cycle(&mut self, cycle: u64);
    /// Finish the sample of the current cycle.
    fn end_cycle(&mut self) -> std::io::Result<()>;
}

/// A tracer that records nothing; useful to measure the cost of the visitor
/// itself, and as the type parameter when tracing is off.
#[derive(Debug, Default, Clone, Copy)]
pub struct NullTracer;

impl Tracer for NullTracer {
    #[inline]
    fn push_scope(&mut self, _name: &str) {}
    #[inline]
    fn pop_scope(&mut self) {}
    #[inline]
    fn signal(&mut self, _name: &str, _width: u32, _value: u64) {}
}

impl CycleSink for NullTracer {
    #[inline]
    fn begin_cycle(&mut self, _cycle: u64) {}
    #[inline]
    fn end_cycle(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}
