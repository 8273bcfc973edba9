//! The design's hierarchy as the first cycle defines it: the signals
//! ([`SignalInfo`]), the visit order of scopes and signals, and the rule
//! on the names a VCD can hold.

/// A signal as defined by the first traced cycle.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct SignalInfo {
    /// Enclosing scopes, outermost first, starting with the sink's top scope.
    pub path: Vec<String>,
    /// The signal's own name.
    pub name: String,
    /// Width in bits, 1..=[`MAX_WIDTH`](super::MAX_WIDTH).
    pub width: u32,
}

impl SignalInfo {
    /// Dotted hierarchical name, e.g. `top.core0.free_mshrs`.
    ///
    /// This is the key used by [`readback::ReadBack`](super::readback::ReadBack).
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
pub(super) enum Event {
    Push(String),
    Pop,
    Signal,
}

/// Why a name cannot appear in a VCD file, if it cannot.
pub(super) fn name_problem(name: &str) -> Option<&'static str> {
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

#[cfg(test)]
mod tests {
    use super::SignalInfo;
    use crate::vcd_sink::testkit::*;
    use crate::vcd_sink::VcdSink;

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
}
