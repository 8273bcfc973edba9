//! Helpers the sink's tests share: a small design traced over six cycles,
//! a design of any shape, and readers of what a sink wrote.

use std::io;

use vcd::{Command, ScopeItem, Value};

use super::VcdSink;
use crate::{Traceable, Tracer};

/// A small design: a 5-bit counter, a valid bit, and a nested scheduler
/// with a 3-bit warp id and a 64-bit word.
#[derive(Clone, Copy)]
pub(crate) struct Toy {
    pub(crate) free_mshrs: u64,
    pub(crate) valid: bool,
    pub(crate) warp: u64,
    pub(crate) word: u64,
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

pub(crate) const START: Toy = Toy {
    free_mshrs: 0b00110,
    valid: false,
    warp: 0,
    word: u64::MAX,
};

/// Cycles 0..=5: a change in 1, 2, 4 and 5, nothing in 3.
pub(crate) fn toy_cycles() -> Vec<(u64, Toy)> {
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

pub(crate) fn write_toy() -> Vec<u8> {
    let mut sink = VcdSink::new(Vec::new(), "top");
    for (cycle, toy) in toy_cycles() {
        sink.trace_cycle(cycle, &toy).unwrap();
    }
    sink.finish(6).unwrap()
}

pub(crate) fn write_toy_with(setup: impl FnOnce(VcdSink<Vec<u8>>) -> VcdSink<Vec<u8>>) -> Vec<u8> {
    let mut sink = setup(VcdSink::new(Vec::new(), "top"));
    for (cycle, toy) in toy_cycles() {
        sink.trace_cycle(cycle, &toy).unwrap();
    }
    sink.finish(6).unwrap()
}

/// Body commands after `$enddefinitions`, without dumpvars markers.
pub(crate) fn body(bytes: &[u8]) -> Vec<Command> {
    let mut parser = vcd::Parser::new(bytes);
    parser.parse_header().unwrap();
    parser
        .map(Result::unwrap)
        .filter(|c| !matches!(c, Command::Begin(_) | Command::End(_)))
        .collect()
}

pub(crate) fn timestamps(bytes: &[u8]) -> Vec<u64> {
    body(bytes)
        .into_iter()
        .filter_map(|c| match c {
            Command::Timestamp(t) => Some(t),
            _ => None,
        })
        .collect()
}

pub(crate) fn header_comments(bytes: &[u8]) -> Vec<String> {
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

pub(crate) fn bits(s: &str) -> vcd::Vector {
    s.bytes()
        .map(|b| if b == b'1' { Value::V1 } else { Value::V0 })
        .collect()
}

pub(crate) fn expect_error(result: io::Result<()>, kind: io::ErrorKind, needle: &str) {
    let err = result.expect_err("expected an error");
    assert_eq!(err.kind(), kind, "{err}");
    let message = err.to_string();
    assert!(message.contains(needle), "`{message}` lacks `{needle}`");
}

/// A design whose shape is chosen per cycle.
pub(crate) struct Shaped(pub(crate) fn(&mut dyn Tracer));

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
