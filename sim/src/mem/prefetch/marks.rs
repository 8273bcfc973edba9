//! What an L1 remembers of its prefetches, to tell whether each was
//! useful, late or useless: a "prefetched, not yet used" bit per line and
//! a state per MSHR entry.
//!
//! - A prefetch miss allocates an entry: *in flight*.
//! - A demand miss that merges into an in-flight prefetch makes it
//!   *useful* and *late* (the demand waits for the rest of its latency);
//!   its fill then marks nothing.
//! - The fill of a prefetch no demand merged into marks its line.
//! - The first demand hit on a marked line makes the prefetch *useful*
//!   and clears the mark; the eviction of a marked line makes it
//!   *useless*. Marks still set at the end are *unused*.
//!
//! Each prefetch is counted useful at most once. The cache calls the hooks
//! only while something is marked or in flight ([`PrefetchMarks::live`]),
//! so a cache without prefetches pays one test per hit, merge and fill.

use serde::{Deserialize, Serialize};

/// Entry state: not a prefetch.
const NONE: u8 = 0;
/// Entry state: a prefetch in flight, no demand merged yet.
const IN_FLIGHT: u8 = 1;
/// Entry state: a prefetch in flight that a demand miss merged into.
const MERGED: u8 = 2;

/// Outcomes of the prefetches an L1 filled or was filling.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct MarkCounts {
    /// Prefetches a demand access used: hit their line, or merged into
    /// their MSHR entry.
    pub useful: u64,
    /// Of the useful ones, those a demand miss merged into while in
    /// flight.
    pub late: u64,
    /// Prefetched lines evicted before any demand access used them.
    pub useless: u64,
}

impl MarkCounts {
    /// Add `o` into `self`.
    pub fn add(&mut self, o: &MarkCounts) {
        self.useful += o.useful;
        self.late += o.late;
        self.useless += o.useless;
    }

    /// The counts since `before`, an earlier reading.
    pub fn since(&self, before: &MarkCounts) -> MarkCounts {
        MarkCounts {
            useful: self.useful - before.useful,
            late: self.late - before.late,
            useless: self.useless - before.useless,
        }
    }
}

/// The marks of one cache (empty, and never touched, for a cache that
/// takes no prefetch).
#[derive(Clone, Debug, Default)]
pub(crate) struct PrefetchMarks {
    /// Per line (`set * ways + way`): filled by a prefetch, no demand hit
    /// since.
    line: Box<[bool]>,
    /// Per MSHR entry: [`NONE`], [`IN_FLIGHT`] or [`MERGED`].
    entry: Box<[u8]>,
    /// Lines marked plus entries in flight.
    live: u32,
    counts: MarkCounts,
    /// Lines marked now.
    marked: u64,
}

impl PrefetchMarks {
    /// Marks for a cache of `lines` lines and `mshrs` MSHR entries.
    pub(crate) fn new(lines: usize, mshrs: usize) -> Self {
        PrefetchMarks {
            line: vec![false; lines].into(),
            entry: vec![NONE; mshrs].into(),
            ..Self::default()
        }
    }

    /// Something is marked or in flight: the other hooks have work.
    #[inline(always)]
    pub(crate) fn live(&self) -> bool {
        self.live != 0
    }

    /// A prefetch miss allocated entry `e`.
    pub(crate) fn allocated(&mut self, e: u32) {
        debug_assert_eq!(self.entry[e as usize], NONE);
        self.entry[e as usize] = IN_FLIGHT;
        self.live += 1;
    }

    /// A demand access hit line `line`.
    #[inline]
    pub(crate) fn hit(&mut self, line: usize) {
        if self.line[line] {
            self.line[line] = false;
            self.live -= 1;
            self.marked -= 1;
            self.counts.useful += 1;
        }
    }

    /// A demand miss merged into entry `e`.
    #[inline]
    pub(crate) fn merged(&mut self, e: u32) {
        let s = &mut self.entry[e as usize];
        if *s == IN_FLIGHT {
            *s = MERGED;
            self.counts.useful += 1;
            self.counts.late += 1;
        }
    }

    /// Line `line` is about to be replaced (its block evicted).
    #[inline]
    pub(crate) fn evicted(&mut self, line: usize) {
        if self.line[line] {
            self.line[line] = false;
            self.live -= 1;
            self.marked -= 1;
            self.counts.useless += 1;
        }
    }

    /// Entry `e`'s fill wrote line `line` (after [`evicted`](Self::evicted)
    /// cleared the line's old mark).
    #[inline]
    pub(crate) fn filled(&mut self, e: u32, line: usize) {
        match std::mem::replace(&mut self.entry[e as usize], NONE) {
            IN_FLIGHT => {
                // The entry's liveness passes to the line.
                self.line[line] = true;
                self.marked += 1;
            }
            MERGED => self.live -= 1,
            _ => {}
        }
    }

    /// The counts so far.
    pub(crate) fn counts(&self) -> MarkCounts {
        self.counts
    }

    /// Lines marked now (prefetched, not yet used, not evicted).
    pub(crate) fn unused(&self) -> u64 {
        self.marked
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_prefetched_line_is_useful_once_and_then_forgotten() {
        let mut m = PrefetchMarks::new(8, 2);
        assert!(!m.live());
        m.allocated(1);
        assert!(m.live());
        m.evicted(3);
        m.filled(1, 3);
        assert_eq!(m.unused(), 1);
        m.hit(3);
        m.hit(3);
        m.evicted(3);
        assert_eq!(
            m.counts(),
            MarkCounts {
                useful: 1,
                late: 0,
                useless: 0
            }
        );
        assert!(!m.live() && m.unused() == 0);
    }

    #[test]
    fn a_late_prefetch_marks_no_line_and_an_unused_one_is_useless_when_evicted() {
        let mut m = PrefetchMarks::new(8, 2);
        m.allocated(0);
        m.allocated(1);
        m.merged(0);
        m.merged(0);
        m.filled(0, 2);
        m.filled(1, 5);
        // A demand fill of entry 0 later, into a line of its own: no mark.
        m.filled(0, 6);
        m.hit(2);
        m.hit(6);
        assert_eq!(m.counts().useful, 1);
        assert_eq!(m.counts().late, 1);
        assert_eq!(m.unused(), 1);
        m.evicted(5);
        assert_eq!(m.counts().useless, 1);
        assert!(!m.live());
    }
}
