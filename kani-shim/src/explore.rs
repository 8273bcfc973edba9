//! The explorer: where each `kani::any()` of a harness body takes its value
//! from. A harness body is run many times (cases); the draws of one case,
//! in the order the body makes them, form a path in a tree whose node at
//! each draw has one branch per value the draw can take (every value of the
//! type for `any`, the values the predicate accepts for `any_where`).
//!
//! * `Probe`: a uniformly random path; the product of the branching
//!   factors along it is Knuth's unbiased estimate of the tree's leaves.
//! * `Exhaustive`: depth-first over every path, as an odometer: the stack
//!   holds each draw position's branch index and branch count (and the
//!   accepted codes of an `any_where`), and after a case the deepest
//!   position that made a draw in it advances. A case cut short by
//!   `kani::assume` advances at its last draw, so every continuation of a
//!   refused prefix is skipped at once.
//! * `Sample`: every draw uniformly random (an `any_where` by rejection,
//!   then by enumeration).

use crate::arbitrary::{show, Arbitrary};
use crate::rng::Rng;
use std::cell::RefCell;
use std::panic::resume_unwind;

/// Domains up to this size can be enumerated for `any_where`.
pub(crate) const ENUMERABLE: u128 = 1 << 16;

/// Rejection tries of a sampled `any_where` before it enumerates.
const REJECTION_TRIES: u32 = 256;

/// The unwinding payload of a case that `kani::assume` refused.
pub(crate) struct Discarded;

/// The unwinding payload of a draw the exhaustive mode cannot enumerate.
pub(crate) struct Unenumerable;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Mode {
    Probe,
    Exhaustive,
    Sample,
}

/// How a draw's code is shown (its type's `Debug`).
type Show = fn(u64) -> String;

/// One draw position of the exhaustive odometer.
struct Node {
    index: u64,
    count: u128,
    /// For `any_where`: the accepted codes, found at the first visit.
    codes: Option<Vec<u64>>,
}

pub(crate) struct Explorer {
    pub(crate) mode: Mode,
    rng: Rng,
    stack: Vec<Node>,
    /// Draws made by the current case.
    depth: usize,
    /// Probe: the product of the branching factors of the current case.
    pub(crate) branching: f64,
    /// Probe: a draw's domain was too large to count its branches.
    pub(crate) unenumerable: bool,
    /// The current case's draws, for a failure report.
    trail: Vec<(u64, Show)>,
}

thread_local! {
    static EXPLORER: RefCell<Option<Explorer>> = const { RefCell::new(None) };
}

impl Explorer {
    pub(crate) fn new(mode: Mode, seed: u64) -> Self {
        Self {
            mode,
            rng: Rng::new(seed),
            stack: Vec::new(),
            depth: 0,
            branching: 1.0,
            unenumerable: false,
            trail: Vec::new(),
        }
    }

    /// Install `self` as this thread's explorer, run `f`, take it back.
    pub(crate) fn with_installed<R>(self, f: impl FnOnce() -> R) -> (Self, R) {
        EXPLORER.with(|e| *e.borrow_mut() = Some(self));
        let r = f();
        let me = EXPLORER
            .with(|e| e.borrow_mut().take())
            .expect("explorer installed");
        (me, r)
    }

    /// Reset the per-case state before a case.
    pub(crate) fn begin_case(&mut self) {
        self.depth = 0;
        self.branching = 1.0;
        self.trail.clear();
    }

    /// Exhaustive: after a case, advance the odometer at the case's last
    /// draw. `false` when every path has been run.
    pub(crate) fn advance(&mut self) -> bool {
        self.stack.truncate(self.depth);
        while let Some(top) = self.stack.last_mut() {
            top.index += 1;
            if u128::from(top.index) < top.count {
                return true;
            }
            self.stack.pop();
        }
        false
    }

    /// The current case's draws, one per line.
    pub(crate) fn trail(&self) -> String {
        let lines: Vec<String> = self
            .trail
            .iter()
            .enumerate()
            .map(|(i, (code, show))| format!("  draw {i}: {}", show(*code)))
            .collect();
        if lines.is_empty() {
            "  (no draws)".into()
        } else {
            lines.join("\n")
        }
    }

    fn record<T: Arbitrary>(&mut self, code: u64) -> T {
        self.depth += 1;
        self.trail.push((code, show::<T>));
        T::from_code(code)
    }

    /// The code of an unconstrained draw of a `domain`-valued type.
    fn pick(&mut self, domain: u128) -> u64 {
        match self.mode {
            Mode::Probe | Mode::Sample => {
                self.branching *= domain as f64;
                self.rng.below(domain)
            }
            Mode::Exhaustive => {
                if let Some(node) = self.stack.get(self.depth) {
                    if node.count != domain || node.codes.is_some() {
                        nondeterministic(self.depth);
                    }
                    node.index
                } else {
                    self.stack.push(Node {
                        index: 0,
                        count: domain,
                        codes: None,
                    });
                    0
                }
            }
        }
    }
}

fn nondeterministic(depth: usize) -> ! {
    panic!(
        "kani shim: draw {depth} differs between two runs of the same prefix: \
         the harness body is not deterministic"
    )
}

fn with<R>(f: impl FnOnce(&mut Explorer) -> R) -> R {
    EXPLORER.with(|e| {
        let mut e = e.borrow_mut();
        let e = e
            .as_mut()
            .expect("kani::any/assume called outside a #[kani::proof] harness");
        f(e)
    })
}

/// `kani::any()`.
pub(crate) fn any<T: Arbitrary>() -> T {
    with(|e| {
        let code = e.pick(T::DOMAIN);
        e.record(code)
    })
}

/// The codes of `T` that `pred` accepts (the domain must be enumerable).
fn accepted<T: Arbitrary>(pred: &impl Fn(&T) -> bool) -> Vec<u64> {
    (0..T::DOMAIN as u64)
        .filter(|&c| pred(&T::from_code(c)))
        .collect()
}

/// `kani::any_where(pred)`. The predicate runs with no borrow of the
/// explorer held (it may be any code of the harness).
pub(crate) fn any_where<T: Arbitrary>(pred: impl Fn(&T) -> bool) -> T {
    let mode = with(|e| e.mode);
    let code = match mode {
        Mode::Exhaustive => {
            let cached = with(|e| e.stack.get(e.depth).map(|n| (n.index, n.codes.clone())));
            match cached {
                Some((i, Some(codes))) => {
                    let c = codes[i as usize];
                    if !pred(&T::from_code(c)) {
                        nondeterministic(with(|e| e.depth));
                    }
                    c
                }
                Some((_, None)) => nondeterministic(with(|e| e.depth)),
                None => {
                    if T::DOMAIN > ENUMERABLE {
                        resume_unwind(Box::new(Unenumerable));
                    }
                    let codes = accepted(&pred);
                    let Some(&first) = codes.first() else {
                        resume_unwind(Box::new(Discarded));
                    };
                    with(|e| {
                        e.stack.push(Node {
                            index: 0,
                            count: codes.len() as u128,
                            codes: Some(codes),
                        })
                    });
                    first
                }
            }
        }
        Mode::Probe if T::DOMAIN <= ENUMERABLE => {
            let codes = accepted(&pred);
            if codes.is_empty() {
                resume_unwind(Box::new(Discarded));
            }
            with(|e| {
                e.branching *= codes.len() as f64;
                codes[e.rng.below(codes.len() as u128) as usize]
            })
        }
        Mode::Probe | Mode::Sample => {
            if mode == Mode::Probe {
                with(|e| e.unenumerable = true);
            }
            sample_where(&pred)
        }
    };
    with(|e| e.record(code))
}

/// A uniformly random accepted code: by rejection, then by enumerating
/// (an enumerable domain), else the case is discarded.
fn sample_where<T: Arbitrary>(pred: &impl Fn(&T) -> bool) -> u64 {
    for _ in 0..REJECTION_TRIES {
        let c = with(|e| e.rng.below(T::DOMAIN));
        if pred(&T::from_code(c)) {
            return c;
        }
    }
    if T::DOMAIN > ENUMERABLE {
        resume_unwind(Box::new(Discarded));
    }
    let codes = accepted(pred);
    if codes.is_empty() {
        resume_unwind(Box::new(Discarded));
    }
    with(|e| codes[e.rng.below(codes.len() as u128) as usize])
}

/// `kani::assume(cond)`: a false condition discards the case.
pub(crate) fn assume(cond: bool) {
    if !cond {
        // No panic hook, no message: a discarded case is not a failure.
        resume_unwind(Box::new(Discarded));
    }
}
