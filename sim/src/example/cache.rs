//! The example's single-level cache: unbounded capacity, a few MSHRs,
//! fixed memory latency.

use super::Outcome;

/// An MSHR entry of the example cache.
#[derive(Clone, Debug)]
pub(super) struct ExampleMshr {
    pub(super) block: usize,
    pub(super) reply: u64,
    pub(super) waiters: Vec<u32>,
}

/// The single-level cache of the example: unbounded capacity, `mshrs`
/// entries, fixed memory latency.
#[derive(Clone, Debug)]
pub(super) struct ExampleCache {
    pub(super) mshrs: usize,
    pub(super) latency: u64,
    pub(super) entries: Vec<ExampleMshr>,
    pub(super) filled_at: [Option<u64>; 3],
}

impl ExampleCache {
    pub(super) fn new(mshrs: u32, latency: u32) -> Self {
        Self {
            mshrs: mshrs as usize,
            latency: latency as u64,
            entries: Vec::with_capacity(mshrs as usize),
            filled_at: [None; 3],
        }
    }

    /// Start of cycle `t`: entries replied at r are held through r + 1.
    pub(super) fn begin_cycle(&mut self, t: u64) {
        self.entries.retain(|e| e.reply + 1 >= t);
    }

    pub(super) fn full(&self) -> bool {
        self.entries.len() >= self.mshrs
    }

    /// One access of `warp` to `block` in cycle `t`; `None` if refused.
    pub(super) fn access(&mut self, t: u64, block: usize, warp: u32) -> Option<Outcome> {
        if self.full() {
            return None;
        }
        if matches!(self.filled_at[block], Some(r) if r < t) {
            return Some(Outcome::Hit);
        }
        if let Some(e) = self.entries.iter_mut().find(|e| e.block == block) {
            e.waiters.push(warp);
            return Some(Outcome::Secondary);
        }
        self.entries.push(ExampleMshr {
            block,
            reply: t + self.latency,
            waiters: vec![warp],
        });
        Some(Outcome::Miss)
    }

    /// Replies arriving in cycle `t`: fill the lines, return (block, waiters).
    pub(super) fn replies(&mut self, t: u64) -> Vec<(usize, Vec<u32>)> {
        let mut out = Vec::new();
        for e in self.entries.iter_mut().filter(|e| e.reply == t) {
            self.filled_at[e.block] = Some(t);
            out.push((e.block, std::mem::take(&mut e.waiters)));
        }
        out
    }
}
