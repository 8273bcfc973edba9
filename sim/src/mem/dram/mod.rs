//! Main memory: two timing models behind one interface, chosen by
//! `dram.model` ([`DramModel`]).
//!
//! - [`FixedDram`] (`"fixed"`, the default): an open-row DRAM with a fixed
//!   row-hit / row-miss latency and `requests_per_cycle` acceptances a cycle;
//!   no bank busy time and no data-bus limit.
//! - [`BankedDram`] (`"banked"`): `channels` independent channels, each with
//!   banks with row buffers (open-page policy), ACTIVATE / PRECHARGE / READ /
//!   WRITE timing (tRCD, tRP, tRAS, CL), one data bus (`t_burst` cycles a
//!   line) and one command a cycle chosen FR-FCFS-lite, plus a fixed
//!   controller latency.
//!
//! Both map a block to bank `block % banks` and row
//! `block / banks / (row_bytes / 64)` (the banked model after taking the
//! channel `block % channels` and dividing it out), take an L2 miss in cycle `m` into
//! their FIFO from cycle `m + 1`, absorb colour-buffer writes
//! ([`Dram::write`]) in the same FIFO, banks (and bus) without a reply, and
//! answer every request in the cycle of the miss with ideal memory (ideal
//! memory always runs the fixed model's zero-latency path, whatever `model`
//! says).

mod banked;
mod channel;
mod fixed;
#[cfg(test)]
mod plain;

pub use banked::BankedDram;
pub use fixed::FixedDram;

use super::config::{DramConfig, DramModel};
use super::stats::DramStats;
use wasp_waves::Tracer;

#[derive(Debug, Clone)]
enum Model {
    Fixed(FixedDram),
    Banked(BankedDram),
}

/// Main memory: the model `cfg.model` selects.
#[derive(Debug, Clone)]
pub struct Dram {
    model: Model,
}

/// Calls the same method on whichever model runs.
macro_rules! each {
    ($self:expr, $d:ident => $e:expr) => {
        match &$self.model {
            Model::Fixed($d) => $e,
            Model::Banked($d) => $e,
        }
    };
    (mut $self:expr, $d:ident => $e:expr) => {
        match &mut $self.model {
            Model::Fixed($d) => $e,
            Model::Banked($d) => $e,
        }
    };
}

impl Dram {
    /// A memory with every bank closed. `max_outstanding` bounds the requests
    /// in flight (the L2's MSHR count) and sizes the queues. `cfg` must have
    /// passed [`DramConfig::check`]. With `ideal` the fixed model's
    /// zero-latency path runs whatever `cfg.model` is.
    pub fn new(cfg: &DramConfig, ideal: bool, max_outstanding: u32) -> Self {
        let model = match cfg.model {
            DramModel::Banked if !ideal => Model::Banked(BankedDram::new(cfg, max_outstanding)),
            _ => Model::Fixed(FixedDram::new(cfg, ideal, max_outstanding)),
        };
        Dram { model }
    }

    /// Bank and row of `block`.
    #[inline]
    pub fn bank_row(&self, block: u64) -> (usize, u64) {
        each!(self, d => d.bank_row(block))
    }

    /// An L2 primary miss on `block` in cycle `now`, for the L2's MSHR
    /// entry `entry` (returned with the reply).
    #[inline]
    pub fn request(&mut self, now: u64, block: u64, entry: u32) {
        each!(mut self, d => d.request(now, block, entry))
    }

    /// A 64-byte line write to `block` in cycle `now` (the colour-buffer
    /// flush): it waits in the FIFO with the reads, uses its bank (and, in
    /// the banked model, the data bus) and is answered by no reply. With
    /// ideal memory it is absorbed at once.
    pub fn write(&mut self, now: u64, block: u64) {
        each!(mut self, d => d.write(now, block))
    }

    /// Advance the memory in cycle `now` (once per cycle): the fixed model
    /// accepts requests from its FIFO, the banked model issues at most one
    /// DRAM command.
    #[inline]
    pub fn accept(&mut self, now: u64) {
        each!(mut self, d => d.accept(now))
    }

    /// The next reply due by cycle `now`, if any: the `entry` of its request.
    #[inline]
    pub fn pop_reply(&mut self, now: u64) -> Option<u32> {
        each!(mut self, d => d.pop_reply(now))
    }

    /// Nothing queued or in flight.
    #[inline]
    pub fn is_idle(&self) -> bool {
        each!(self, d => d.is_idle())
    }

    /// Requests (reads and writes) waiting in the FIFO.
    pub fn queued(&self) -> usize {
        each!(self, d => d.queued())
    }

    /// Reads whose data is on its way and not yet answered.
    pub fn in_flight(&self) -> usize {
        each!(self, d => d.in_flight())
    }

    /// Restart the `max_queue` counter at the requests queued now (a
    /// frame begins: its largest FIFO depth is its own).
    pub fn restart_max_queue(&mut self) {
        each!(mut self, d => d.restart_max_queue())
    }

    /// Counters so far.
    pub fn stats(&self) -> &DramStats {
        each!(self, d => d.stats())
    }

    /// Signals: FIFO depth, requests in flight, requests accepted (fixed) or
    /// column commands issued (banked) this cycle.
    pub fn trace<T: Tracer + ?Sized>(&self, now: u64, t: &mut T) {
        each!(self, d => d.trace(now, t))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_model_field_selects_the_model_and_ideal_answers_at_once() {
        for model in [DramModel::Fixed, DramModel::Banked] {
            let cfg = DramConfig {
                model,
                ..DramConfig::default()
            };
            let d = Dram::new(&cfg, false, 8);
            assert_eq!(
                matches!(d.model, Model::Banked(_)),
                model == DramModel::Banked
            );
            // Ideal memory: the reply is due in the cycle of the miss.
            let mut d = Dram::new(&cfg, true, 8);
            d.request(10, 3, 7);
            d.write(10, 4);
            d.accept(10);
            assert_eq!(d.pop_reply(10), Some(7));
            assert!(d.is_idle());
            assert_eq!(d.stats().latency_sum, 0);
        }
    }
}
