//! The fixed-latency model: an open-row DRAM with a request FIFO.
//!
//! Timing: an L2 primary miss in cycle `m` enters the FIFO and can be accepted
//! from cycle `m + 1`; at most `requests_per_cycle` requests are accepted per
//! cycle, oldest first. A request accepted in cycle `p` with latency `L` (row
//! hit or row miss, decided against the bank's open row at acceptance, which
//! then becomes the request's row) is answered in cycle `p + L - 1`; so
//! without FIFO wait the reply reaches the L2 exactly `L` cycles after the L2
//! miss. Banks have no busy time: the model is open-row latency plus an
//! acceptance-rate bound, not a command-level DRAM.
//!
//! With ideal memory every request is answered in the cycle of the L2 miss,
//! with no FIFO and no bandwidth limit.
//!
//! Replies of the two latency classes are kept in two FIFOs, each sorted by
//! reply cycle (fixed latency, acceptance in cycle order), and merged by
//! (reply cycle, acceptance order): no heap, no allocation in steady state.

use crate::mem::cache::bits_for;
use crate::mem::config::{DramConfig, BLOCK_BYTES};
use crate::mem::ring::Ring;
use crate::mem::stats::DramStats;
use wasp_waves::Tracer;

const NO_ROW: u64 = u64::MAX;
/// The `entry` of a queued write: it gets no reply.
const WRITE: u32 = u32::MAX;

#[derive(Debug, Clone, Copy, Default)]
struct Queued {
    /// First cycle the request may be accepted.
    ready: u64,
    /// Cycle of the L2 miss.
    missed: u64,
    block: u64,
    /// The L2's MSHR entry for the block, handed back with the reply.
    entry: u32,
}

#[derive(Debug, Clone, Copy, Default)]
struct InFlight {
    /// Cycle the reply reaches the L2.
    at: u64,
    /// Acceptance order, to break ties between the two FIFOs.
    seq: u64,
    entry: u32,
}

/// Main memory, fixed-latency model.
#[derive(Debug, Clone)]
pub struct FixedDram {
    cfg: DramConfig,
    ideal: bool,
    blocks_per_row: u64,
    /// Open row of each bank ([`NO_ROW`] before the first access).
    open_row: Vec<u64>,
    queue: Ring<Queued>,
    row_hits: Ring<InFlight>,
    row_misses: Ring<InFlight>,
    seq: u64,
    /// Bound on requests in the memory at once (the L2's MSHR count), for
    /// signal widths.
    max_outstanding: u32,
    cycle: u64,
    accepted_now: u32,
    stats: DramStats,
}

impl FixedDram {
    /// A memory with every bank closed. `max_outstanding` bounds the requests
    /// in flight (the L2's MSHR count) and sizes the queues. `cfg` must have
    /// passed [`DramConfig::check`].
    pub fn new(cfg: &DramConfig, ideal: bool, max_outstanding: u32) -> Self {
        let n = max_outstanding as usize;
        FixedDram {
            cfg: *cfg,
            ideal,
            blocks_per_row: u64::from(cfg.row_bytes / BLOCK_BYTES),
            open_row: vec![NO_ROW; cfg.banks as usize],
            // Reads are bounded by the L2's MSHRs; the flush adds at most
            // one write a cycle against one acceptance a cycle or more.
            queue: Ring::with_capacity(n + 64),
            row_hits: Ring::with_capacity(n),
            row_misses: Ring::with_capacity(n),
            seq: 0,
            max_outstanding,
            cycle: 0,
            accepted_now: 0,
            stats: DramStats::default(),
        }
    }

    /// Bank and row of `block`.
    #[inline]
    pub fn bank_row(&self, block: u64) -> (usize, u64) {
        let banks = u64::from(self.cfg.banks);
        (
            (block % banks) as usize,
            block / banks / self.blocks_per_row,
        )
    }

    /// An L2 primary miss on `block` in cycle `now`, for the L2's MSHR
    /// entry `entry` (returned with the reply).
    #[inline]
    pub fn request(&mut self, now: u64, block: u64, entry: u32) {
        self.stats.requests += 1;
        if self.ideal {
            let seq = self.next_seq();
            self.row_hits.push_back(InFlight {
                at: now,
                seq,
                entry,
            });
            return;
        }
        self.queue.push_back(Queued {
            ready: now + 1,
            missed: now,
            block,
            entry,
        });
        self.stats.max_queue = self.stats.max_queue.max(self.queue.len() as u64);
    }

    /// A 64-byte line write to `block` in cycle `now` (the colour-buffer
    /// flush): it waits in the FIFO with the reads, takes an acceptance slot
    /// and opens its row, and is answered by no reply. With ideal memory it
    /// is absorbed at once.
    pub fn write(&mut self, now: u64, block: u64) {
        self.stats.writes += 1;
        if self.ideal {
            return;
        }
        self.queue.push_back(Queued {
            ready: now + 1,
            missed: now,
            block,
            entry: WRITE,
        });
        self.stats.max_queue = self.stats.max_queue.max(self.queue.len() as u64);
    }

    /// Accept requests from the FIFO in cycle `now` (once per cycle).
    #[inline]
    pub fn accept(&mut self, now: u64) {
        if now != self.cycle {
            self.cycle = now;
            self.accepted_now = 0;
        }
        while self.accepted_now < self.cfg.requests_per_cycle {
            let Some(&q) = self.queue.front() else { break };
            if q.ready > now {
                break;
            }
            self.queue.drop_front();
            self.accepted_now += 1;
            let (bank, row) = self.bank_row(q.block);
            if q.entry == WRITE {
                if self.open_row[bank] != row {
                    self.stats.write_row_misses += 1;
                    self.open_row[bank] = row;
                }
                continue;
            }
            let row_hit = self.open_row[bank] == row;
            let latency = if row_hit {
                self.stats.row_hits += 1;
                self.cfg.row_hit_latency
            } else {
                self.stats.row_misses += 1;
                self.open_row[bank] = row;
                self.cfg.row_miss_latency
            };
            let at = now + u64::from(latency) - 1;
            self.stats.queue_wait_sum += now - q.ready;
            self.stats.latency_sum += at - q.missed;
            let seq = self.next_seq();
            let f = InFlight {
                at,
                seq,
                entry: q.entry,
            };
            if row_hit {
                self.row_hits.push_back(f);
            } else {
                self.row_misses.push_back(f);
            }
        }
    }

    /// The next reply due by cycle `now`, if any, in (reply cycle, acceptance)
    /// order: the `entry` of its request.
    #[inline]
    pub fn pop_reply(&mut self, now: u64) -> Option<u32> {
        let due = |q: &Ring<InFlight>| q.front().filter(|f| f.at <= now).map(|f| (f.at, f.seq));
        let from_hits = match (due(&self.row_hits), due(&self.row_misses)) {
            (None, None) => return None,
            (Some(_), None) => true,
            (None, Some(_)) => false,
            (Some(a), Some(b)) => a < b,
        };
        let q = if from_hits {
            &mut self.row_hits
        } else {
            &mut self.row_misses
        };
        q.pop_front().map(|f| f.entry)
    }

    /// Nothing queued or in flight.
    #[inline]
    pub fn is_idle(&self) -> bool {
        self.queue.is_empty() && self.row_hits.is_empty() && self.row_misses.is_empty()
    }

    /// Restart `max_queue` at the requests queued now (a frame begins).
    pub fn restart_max_queue(&mut self) {
        self.stats.max_queue = self.queued() as u64;
    }

    /// Requests waiting in the FIFO.
    pub fn queued(&self) -> usize {
        self.queue.len()
    }

    /// Requests accepted and not yet answered.
    pub fn in_flight(&self) -> usize {
        self.row_hits.len() + self.row_misses.len()
    }

    /// Counters so far.
    pub fn stats(&self) -> &DramStats {
        &self.stats
    }

    /// Signals: FIFO depth, requests in flight, requests accepted this cycle.
    pub fn trace<T: Tracer + ?Sized>(&self, now: u64, t: &mut T) {
        let w = bits_for(u64::from(self.max_outstanding));
        t.signal("queue", w, self.queue.len() as u64);
        t.signal("in_flight", w, self.in_flight() as u64);
        let acc = if self.cycle == now {
            self.accepted_now
        } else {
            0
        };
        t.signal(
            "accepted",
            bits_for(u64::from(self.cfg.requests_per_cycle)),
            u64::from(acc),
        );
    }

    fn next_seq(&mut self) -> u64 {
        self.seq += 1;
        self.seq
    }
}

#[cfg(test)]
mod tests {
    use super::FixedDram as Dram;
    use super::*;

    fn cfg(rpc: u32) -> DramConfig {
        DramConfig {
            banks: 4,
            row_bytes: 256, // 4 blocks per row per bank
            row_hit_latency: 50,
            row_miss_latency: 100,
            requests_per_cycle: rpc,
            ..DramConfig::default()
        }
    }

    /// Run requests `(miss cycle, block)` to completion; return
    /// `(reply cycle, block)` in reply order.
    fn run(d: &mut Dram, reqs: &[(u64, u64)]) -> Vec<(u64, u64)> {
        let mut out = Vec::new();
        let mut i = 0;
        for now in 0..1000 {
            while i < reqs.len() && reqs[i].0 == now {
                // The entry handed back is the request's index.
                d.request(now, reqs[i].1, i as u32);
                i += 1;
            }
            d.accept(now);
            while let Some(e) = d.pop_reply(now) {
                out.push((now, reqs[e as usize].1));
            }
        }
        assert!(d.is_idle());
        out
    }

    #[test]
    fn mapping_interleaves_banks_on_low_block_bits() {
        let d = Dram::new(&cfg(1), false, 8);
        assert_eq!(d.bank_row(0), (0, 0));
        assert_eq!(d.bank_row(1), (1, 0));
        assert_eq!(d.bank_row(4), (0, 0));
        assert_eq!(d.bank_row(12), (0, 0));
        assert_eq!(d.bank_row(16), (0, 1));
        assert_eq!(d.bank_row(17), (1, 1));
    }

    #[test]
    fn row_miss_then_row_hit_latency() {
        let mut d = Dram::new(&cfg(1), false, 8);
        // Block 0 opens row 0 of bank 0 (miss), block 4 is then a row hit,
        // block 16 (row 1) a miss, block 0 again a miss.
        let out = run(&mut d, &[(10, 0), (200, 4), (400, 16), (600, 0)]);
        assert_eq!(out, vec![(110, 0), (250, 4), (500, 16), (700, 0)]);
        let s = d.stats();
        assert_eq!((s.requests, s.row_hits, s.row_misses), (4, 1, 3));
        assert_eq!(s.latency_sum, 100 + 50 + 100 + 100);
        assert_eq!(s.queue_wait_sum, 0);
    }

    #[test]
    fn requests_per_cycle_bound_and_fifo_wait() {
        let mut d = Dram::new(&cfg(1), false, 8);
        // Three misses in cycle 10 to three banks: accepted at 11, 12, 13.
        let out = run(&mut d, &[(10, 0), (10, 1), (10, 2)]);
        assert_eq!(out, vec![(110, 0), (111, 1), (112, 2)]);
        assert_eq!(d.stats().queue_wait_sum, 1 + 2);
        assert_eq!(d.stats().max_queue, 3);
        let mut d = Dram::new(&cfg(2), false, 8);
        let out = run(&mut d, &[(10, 0), (10, 1), (10, 2)]);
        assert_eq!(out, vec![(110, 0), (110, 1), (111, 2)]);
    }

    #[test]
    fn a_write_takes_a_slot_and_the_row_but_gets_no_reply() {
        let mut d = Dram::new(&cfg(1), false, 8);
        // A write to block 16 (bank 0, row 1) queued in cycle 9 goes first:
        // the read of block 0 (bank 0, row 0) waits a cycle for its
        // acceptance slot and finds row 1 open (a row miss); the read of
        // block 20 (bank 0, row 1) would have hit the write's row but
        // block 0 closed it again.
        d.write(9, 16);
        let out = run(&mut d, &[(9, 0), (300, 20)]);
        assert_eq!(out, vec![(110, 0), (400, 20)]);
        let s = d.stats();
        assert_eq!((s.writes, s.write_row_misses), (1, 1));
        assert_eq!((s.requests, s.row_hits, s.row_misses), (2, 0, 2));
        assert_eq!(
            s.queue_wait_sum, 1,
            "the read waited one cycle behind the write"
        );
        // With ideal memory a write is absorbed at once.
        let mut d = Dram::new(&cfg(1), true, 8);
        d.write(3, 0);
        assert!(d.is_idle());
        assert_eq!(d.stats().writes, 1);
    }

    #[test]
    fn row_hit_can_overtake_row_miss() {
        let mut d = Dram::new(&cfg(1), false, 8);
        // Open row 0 of bank 1 first, then a miss on bank 0 and a hit on bank 1.
        let out = run(&mut d, &[(0, 1), (200, 0), (200, 5)]);
        assert_eq!(out, vec![(100, 1), (251, 5), (300, 0)]);
    }

    #[test]
    fn ideal_memory_answers_in_the_miss_cycle() {
        let mut d = Dram::new(&cfg(1), true, 8);
        let out = run(&mut d, &[(10, 0), (10, 1), (10, 2), (11, 0)]);
        assert_eq!(out, vec![(10, 0), (10, 1), (10, 2), (11, 0)]);
        let s = d.stats();
        assert_eq!(
            (s.requests, s.row_hits, s.row_misses, s.latency_sum),
            (4, 0, 0, 0)
        );
    }
}
