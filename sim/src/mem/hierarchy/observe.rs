//! The memory system's observation port: every cache's MSHR file as a
//! property checker sees it (capacity, entries occupied, entries awaiting
//! their reply). Read-only, off the hot path.

use super::MemorySystem;
use crate::mem::Cache;

/// One cache's MSHR file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MshrFileView {
    /// `"l0"`, `"l1"` or `"l2"`.
    pub level: &'static str,
    /// The core of a private cache; `None` for the shared L2.
    pub core: Option<usize>,
    /// Entries.
    pub capacity: u32,
    /// Entries occupied (awaiting their reply, or in the cycle after it).
    pub occupied: u32,
    /// Entries awaiting their reply.
    pub outstanding: u32,
}

fn view(level: &'static str, core: Option<usize>, c: &Cache) -> MshrFileView {
    MshrFileView {
        level,
        core,
        capacity: c.mshr_capacity(),
        occupied: c.mshr_occupied(),
        outstanding: c.mshr_outstanding(),
    }
}

impl MemorySystem {
    /// Every MSHR file: per core its L0 (if present) and L1, then the L2.
    pub fn mshr_files(&self) -> Vec<MshrFileView> {
        let mut v = Vec::with_capacity(2 * self.cores.len() + 1);
        for (i, c) in self.cores.iter().enumerate() {
            if let Some(l0) = &c.l0 {
                v.push(view("l0", Some(i), l0));
            }
            v.push(view("l1", Some(i), &c.l1));
        }
        v.push(view("l2", None, &self.l2));
        v
    }
}
