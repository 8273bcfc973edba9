//! (d) The split queue never loses, duplicates or reorders warps within a
//! class, and never holds more than the baseline queue's capacity.
//!
//! The reference [`RefQueue`] is two unbounded `VecDeque`s and an explicit
//! capacity check: a push is accepted iff fewer than `capacity` warps wait
//! in both FIFOs together. Each pushed warp is a fresh ticket (0, 1, 2, ...),
//! so equality of every popped ticket with the reference's shows that no
//! warp is lost, duplicated or overtaken within its class.

use crate::cex::{ensure, Cex};
use std::collections::VecDeque;
use wasp_rtl::queue::{QueueClass, SplitQueue};

/// Property name used in counterexamples.
pub const PROP: &str = "(d) split queue";

/// One operation on the split queue.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum QueueOp {
    /// Push a fresh ticket into the class's FIFO.
    Push(QueueClass),
    /// Pop the oldest ticket of the class.
    Pop(QueueClass),
}

/// Every operation.
pub const OPS: [QueueOp; 4] = [
    QueueOp::Push(QueueClass::Priority),
    QueueOp::Push(QueueClass::Regular),
    QueueOp::Pop(QueueClass::Priority),
    QueueOp::Pop(QueueClass::Regular),
];

/// Operation from a code (`code % 4` indexes [`OPS`]).
pub fn op_from_code(code: u8) -> QueueOp {
    OPS[(code % 4) as usize]
}

/// The reference: two unbounded FIFOs and a capacity.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RefQueue {
    /// Priority FIFO, oldest first.
    pub priority: VecDeque<u32>,
    /// Regular FIFO, oldest first.
    pub regular: VecDeque<u32>,
    /// Shared slots.
    pub capacity: usize,
    /// The next fresh ticket.
    pub next_ticket: u32,
    /// Pushes accepted so far.
    pub accepted: u64,
    /// Pops that returned a ticket so far.
    pub popped: u64,
}

impl RefQueue {
    /// Empty, with `capacity` shared slots.
    pub fn new(capacity: usize) -> Self {
        Self {
            priority: VecDeque::new(),
            regular: VecDeque::new(),
            capacity,
            next_ticket: 0,
            accepted: 0,
            popped: 0,
        }
    }

    /// Warps waiting in both FIFOs.
    pub fn len(&self) -> usize {
        self.priority.len() + self.regular.len()
    }

    /// Whether both FIFOs are empty.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// One class's FIFO.
    pub fn fifo(&self, c: QueueClass) -> &VecDeque<u32> {
        match c {
            QueueClass::Priority => &self.priority,
            QueueClass::Regular => &self.regular,
        }
    }

    /// One class's FIFO, mutably.
    pub fn fifo_mut(&mut self, c: QueueClass) -> &mut VecDeque<u32> {
        match c {
            QueueClass::Priority => &mut self.priority,
            QueueClass::Regular => &mut self.regular,
        }
    }
}

fn class_code(c: QueueClass) -> i64 {
    match c {
        QueueClass::Priority => 2,
        QueueClass::Regular => 1,
    }
}

fn op_code(op: QueueOp) -> i64 {
    match op {
        QueueOp::Push(c) => class_code(c),
        QueueOp::Pop(c) => -class_code(c),
    }
}

/// (d), one step: apply `op` to the queue and the reference, compare the
/// result, then compare every observable of the queue (length, per-class
/// occupancy, full, empty, has, heads, capacity) with the reference and
/// check conservation (`accepted - popped == len <= capacity`). `step` is
/// the index of the operation, for the counterexample.
pub fn queue_step(
    q: &mut SplitQueue<u32>,
    r: &mut RefQueue,
    op: QueueOp,
    step: usize,
) -> Result<(), Cex> {
    let capacity = r.capacity;
    let cex = |what| {
        Cex::new(PROP, what)
            .with("capacity", capacity as i64)
            .with("step", step as i64)
            .with("op(+push/-pop, 2 prio, 1 reg)", op_code(op))
    };
    match op {
        QueueOp::Push(c) => {
            let ticket = r.next_ticket;
            let len = r.len();
            let accept = len < capacity;
            let got = q.push(c, ticket);
            ensure(got == accept, || {
                cex(if accept {
                    "push refused below capacity"
                } else {
                    "push accepted beyond capacity"
                })
                .with("len", len as i64)
            })?;
            r.next_ticket += 1;
            if accept {
                r.fifo_mut(c).push_back(ticket);
                r.accepted += 1;
            }
        }
        QueueOp::Pop(c) => {
            let want = r.fifo_mut(c).pop_front();
            let got = q.pop(c);
            ensure(got == want, || {
                cex("pop returned the wrong warp (lost, duplicated or reordered)")
                    .with("expected", want.map_or(-1, |t| t as i64))
                    .with("got", got.map_or(-1, |t| t as i64))
            })?;
            r.popped += want.is_some() as u64;
        }
    }
    observables_match(q, r).map_err(cex)
}

fn observables_match(q: &SplitQueue<u32>, r: &RefQueue) -> Result<(), &'static str> {
    let check = |ok: bool, what: &'static str| if ok { Ok(()) } else { Err(what) };
    check(q.capacity() == r.capacity, "capacity changed")?;
    check(q.len() == r.len(), "length differs from the reference")?;
    check(q.len() <= r.capacity, "more warps than the capacity")?;
    check(
        r.accepted - r.popped == r.len() as u64,
        "conservation: accepted - popped != waiting",
    )?;
    check(q.is_empty() == r.is_empty(), "is_empty differs")?;
    check(q.is_full() == (r.len() >= r.capacity), "is_full differs")?;
    for c in [QueueClass::Priority, QueueClass::Regular] {
        check(
            q.occupancy(c) == r.fifo(c).len(),
            "class occupancy differs from the reference",
        )?;
        check(q.has(c) != r.fifo(c).is_empty(), "has differs")?;
        check(q.peek(c) == r.fifo(c).front(), "head of a FIFO differs")?;
    }
    Ok(())
}

/// (d) over a whole operation sequence from an empty queue of `capacity`.
pub fn queue_sequence(capacity: usize, ops: &[QueueOp]) -> Result<(), Cex> {
    let mut q = SplitQueue::new(capacity);
    let mut r = RefQueue::new(capacity);
    observables_match(&q, &r).map_err(|what| Cex::new(PROP, what))?;
    for (i, &op) in ops.iter().enumerate() {
        queue_step(&mut q, &mut r, op, i)?;
    }
    Ok(())
}

#[cfg(any(kani, feature = "kani-shim"))]
mod proofs {
    use super::*;

    /// Depth of the Kani harness.
    const KANI_DEPTH: usize = 6;

    /// Twin: `tests::exhaustive_queue_sequences` (capacities 1..=4).
    #[kani::proof]
    #[kani::unwind(8)]
    fn proof_queue_sequence() {
        let cap: u8 = kani::any_where(|c: &u8| (1..=4).contains(c));
        let mut ops = [QueueOp::Push(QueueClass::Regular); KANI_DEPTH];
        for op in ops.iter_mut() {
            *op = op_from_code(kani::any_where(|c: &u8| usize::from(*c) < OPS.len()));
        }
        assert!(queue_sequence(cap as usize, &ops).is_ok());
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Depth of the exhaustive twin: every sequence of up to this many
    /// operations.
    pub const DEPTH: usize = 8;

    fn explore(
        q: &SplitQueue<u32>,
        r: &RefQueue,
        depth: usize,
        path: &mut Vec<QueueOp>,
        count: &mut u64,
    ) {
        if depth == DEPTH {
            return;
        }
        for op in OPS {
            let mut q2 = q.clone();
            let mut r2 = r.clone();
            path.push(op);
            if let Err(c) = queue_step(&mut q2, &mut r2, op, depth) {
                panic!("{c}\nsequence: {path:?}");
            }
            *count += 1;
            explore(&q2, &r2, depth + 1, path, count);
            path.pop();
        }
    }

    /// Every sequence of push/pop priority/regular of length up to 8
    /// (4 + 16 + ... + 4^8 = 87,380 steps per capacity), from an empty
    /// queue of each capacity 0..=4, sharing prefixes.
    #[test]
    fn exhaustive_queue_sequences() {
        for cap in 0..=4 {
            let q = SplitQueue::new(cap);
            let r = RefQueue::new(cap);
            let mut count = 0;
            explore(&q, &r, 0, &mut Vec::new(), &mut count);
            assert_eq!(count, (1..=DEPTH as u32).map(|d| 4u64.pow(d)).sum::<u64>());
        }
    }

    #[test]
    fn sequence_body_agrees_and_reports() {
        use QueueClass::*;
        let ops = [
            QueueOp::Push(Regular),
            QueueOp::Push(Priority),
            QueueOp::Push(Regular),
            QueueOp::Pop(Regular),
            QueueOp::Push(Priority),
            QueueOp::Pop(Priority),
            QueueOp::Pop(Priority),
            QueueOp::Pop(Regular),
        ];
        for cap in 0..=4 {
            assert!(queue_sequence(cap, &ops).is_ok());
        }
        // A wrong reference is reported: a queue that already holds a warp
        // the reference does not know of.
        let mut q = SplitQueue::new(2);
        assert!(q.push(Regular, 99));
        let mut r = RefQueue::new(2);
        let e = queue_step(&mut q, &mut r, QueueOp::Pop(Regular), 0).unwrap_err();
        assert_eq!(e.get("got"), Some(99));
    }
}
