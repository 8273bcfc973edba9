//! The banked model's rules ([`super::BankedDram`]'s module docs) in their
//! plainest form, for tests only: every channel looks at its whole queue
//! in every cycle, with no counts, no wake-ups, no window structure and no
//! sleeping, and a column command removes its request from one `Vec`. The
//! tests at the bottom run it in lockstep with [`super::BankedDram`] on
//! random traffic and compare everything observable every cycle.

use super::channel::WRITE;
use crate::mem::config::{DramConfig, BLOCK_BYTES};
use crate::mem::stats::DramStats;

/// The open row of a precharged bank.
const CLOSED: u64 = u64::MAX;

#[derive(Debug, Clone, Copy)]
struct Request {
    /// First cycle the scheduler sees it.
    ready: u64,
    missed: u64,
    bank: usize,
    row: u64,
    entry: u32,
    /// Cycle of its first command, if any.
    first_command: Option<u64>,
    opened: bool,
    closed: bool,
}

#[derive(Debug, Clone, Copy)]
struct Bank {
    open_row: u64,
    ready: u64,
    activated: u64,
}

#[derive(Debug, Clone)]
struct PlainChannel {
    banks: Vec<Bank>,
    /// Every request not yet issued its column command, oldest first.
    queue: Vec<Request>,
    bus_free: u64,
    /// (reply cycle, entry), in issue order.
    replies: Vec<(u64, u32)>,
}

/// The plain banked memory.
#[derive(Debug, Clone)]
pub(super) struct PlainDram {
    cfg: DramConfig,
    channels: Vec<PlainChannel>,
    stats: DramStats,
    /// Column commands issued in the last `accept`.
    pub(super) issued: usize,
}

impl PlainDram {
    pub(super) fn new(cfg: &DramConfig) -> Self {
        let bank = Bank {
            open_row: CLOSED,
            ready: 0,
            activated: 0,
        };
        let channel = PlainChannel {
            banks: vec![bank; cfg.banks as usize],
            queue: Vec::new(),
            bus_free: 0,
            replies: Vec::new(),
        };
        PlainDram {
            cfg: *cfg,
            channels: vec![channel; cfg.channels as usize],
            stats: DramStats::default(),
            issued: 0,
        }
    }

    pub(super) fn request(&mut self, now: u64, block: u64, entry: u32) {
        self.stats.requests += 1;
        self.enqueue(now, block, entry);
    }

    pub(super) fn write(&mut self, now: u64, block: u64) {
        self.stats.writes += 1;
        self.enqueue(now, block, WRITE);
    }

    fn enqueue(&mut self, now: u64, block: u64, entry: u32) {
        let channels = u64::from(self.cfg.channels);
        let banks = u64::from(self.cfg.banks);
        let in_channel = block / channels;
        let row = in_channel / banks / u64::from(self.cfg.row_bytes / BLOCK_BYTES);
        self.channels[(block % channels) as usize]
            .queue
            .push(Request {
                ready: now + 1,
                missed: now,
                bank: (in_channel % banks) as usize,
                row,
                entry,
                first_command: None,
                opened: false,
                closed: false,
            });
        self.stats.max_queue = self.stats.max_queue.max(self.queued() as u64);
    }

    pub(super) fn queued(&self) -> usize {
        self.channels.iter().map(|c| c.queue.len()).sum()
    }

    pub(super) fn in_flight(&self) -> usize {
        self.channels.iter().map(|c| c.replies.len()).sum()
    }

    pub(super) fn stats(&self) -> &DramStats {
        &self.stats
    }

    /// Every channel issues at most one command in cycle `now`.
    pub(super) fn accept(&mut self, now: u64) {
        self.issued = 0;
        for ch in 0..self.channels.len() {
            self.step(ch, now);
        }
    }

    fn step(&mut self, ch: usize, now: u64) {
        let cfg = self.cfg;
        let c = &self.channels[ch];
        let window: Vec<usize> = (0..c.queue.len().min(cfg.scheduler_window as usize))
            .filter(|&i| c.queue[i].ready <= now)
            .collect();
        if window.is_empty() {
            return;
        }
        let hits = |i: usize| c.banks[c.queue[i].bank].open_row == c.queue[i].row;
        let bus_ok = c.bus_free <= now + u64::from(cfg.t_cl);
        let bank_free = |i: usize| c.banks[c.queue[i].bank].ready <= now;
        // Whether request `i` may take its row command, with the open-row
        // protection unless `head`.
        let row_ok = |i: usize, head: bool| {
            let b = c.banks[c.queue[i].bank];
            if b.ready > now || b.open_row == c.queue[i].row {
                return false;
            }
            if b.open_row == CLOSED {
                return true;
            }
            let protected = window
                .iter()
                .any(|&j| c.queue[j].bank == c.queue[i].bank && hits(j));
            now >= b.activated + u64::from(cfg.t_ras) && (head || !protected)
        };
        // 1. The head.
        if hits(0) {
            if bank_free(0) && bus_ok {
                return self.column(ch, 0, now);
            }
        } else if row_ok(0, true) {
            return self.row_command(ch, 0, now);
        }
        // 2. The oldest row hit.
        if bus_ok {
            if let Some(&i) = window.iter().find(|&&i| hits(i) && bank_free(i)) {
                return self.column(ch, i, now);
            }
        }
        // 3. The oldest row command.
        if let Some(&i) = window[1..].iter().find(|&&i| row_ok(i, false)) {
            self.row_command(ch, i, now);
        }
    }

    fn column(&mut self, ch: usize, i: usize, now: u64) {
        let (cfg, s) = (&self.cfg, &mut self.stats);
        let c = &mut self.channels[ch];
        let r = c.queue.remove(i);
        let burst = u64::from(cfg.t_burst);
        c.banks[r.bank].ready = now + burst;
        c.bus_free = now + u64::from(cfg.t_cl) + burst;
        s.bus_busy_cycles += burst;
        self.issued += 1;
        if r.entry == WRITE {
            s.write_row_misses += u64::from(r.opened);
            s.write_row_conflicts += u64::from(r.closed);
            return;
        }
        let at = c.bus_free - 1 + u64::from(cfg.controller_latency);
        c.replies.push((at, r.entry));
        s.row_hits += u64::from(!r.opened);
        s.row_misses += u64::from(r.opened);
        s.row_conflicts += u64::from(r.closed);
        s.queue_wait_sum += r.first_command.unwrap_or(now) - r.ready;
        s.latency_sum += at - r.missed;
    }

    fn row_command(&mut self, ch: usize, i: usize, now: u64) {
        let cfg = self.cfg;
        let c = &mut self.channels[ch];
        let r = &mut c.queue[i];
        let b = &mut c.banks[r.bank];
        if b.open_row == CLOSED {
            *b = Bank {
                open_row: r.row,
                ready: now + u64::from(cfg.t_rcd),
                activated: now,
            };
            self.stats.activates += 1;
        } else {
            b.open_row = CLOSED;
            b.ready = now + u64::from(cfg.t_rp);
            self.stats.precharges += 1;
            r.closed = true;
        }
        r.opened = true;
        r.first_command.get_or_insert(now);
    }

    /// The next reply due by `now`: the earliest (ties: the lowest channel).
    pub(super) fn pop_reply(&mut self, now: u64) -> Option<u32> {
        let (_, ch) = (0..self.channels.len())
            .filter_map(|ch| self.channels[ch].replies.first().map(|r| (r.0, ch)))
            .filter(|&(at, _)| at <= now)
            .min()?;
        Some(self.channels[ch].replies.remove(0).1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mem::config::DramModel;
    use crate::mem::dram::banked::tests::{send_random, signals, Driven};
    use crate::mem::dram::BankedDram;
    use crate::rng::Rng;

    impl Driven for PlainDram {
        fn request(&mut self, now: u64, block: u64, entry: u32) {
            PlainDram::request(self, now, block, entry);
        }
        fn write(&mut self, now: u64, block: u64) {
            PlainDram::write(self, now, block);
        }
    }

    /// Column commands `d` issued in cycle `now` (its `accepted` signal).
    fn accepted(d: &BankedDram, now: u64) -> u64 {
        signals(d, now)
            .into_iter()
            .find_map(|(name, v)| (name == "accepted").then_some(v))
            .expect("the memory traces `accepted`")
    }

    /// `d` and the plain model under the same random traffic in the first
    /// `cycles` cycles, then until both drain: requests now and then in
    /// bursts (so that the queues grow past the window) to `blocks`
    /// blocks, a fifth of them writes.
    fn lockstep(c: &DramConfig, seed: u64, rate: f64, blocks: u64, cycles: u64) {
        let mut fast = BankedDram::new(c, 64);
        let mut plain = PlainDram::new(c);
        let mut rng = Rng::new(seed);
        let mut n = 0u32;
        for now in 0.. {
            if now >= cycles && fast.is_idle() && plain.queued() + plain.in_flight() == 0 {
                break;
            }
            let burst = if rng.chance(0.01) { 20 } else { 1 };
            for _ in 0..burst {
                if now < cycles && rng.chance(rate) {
                    send_random(&mut rng, now, blocks, &mut n, &mut fast, &mut plain);
                }
            }
            fast.accept(now);
            plain.accept(now);
            let ctx = format!("{c:?} seed {seed}, cycle {now}");
            assert_eq!(accepted(&fast, now), plain.issued as u64, "{ctx}");
            loop {
                let (a, b) = (fast.pop_reply(now), plain.pop_reply(now));
                assert_eq!(a, b, "{ctx}");
                if a.is_none() {
                    break;
                }
            }
            assert_eq!(fast.queued(), plain.queued(), "{ctx}");
            assert_eq!(fast.in_flight(), plain.in_flight(), "{ctx}");
        }
        assert_eq!(
            format!("{:?}", fast.stats()),
            format!("{:?}", plain.stats()),
            "{c:?} seed {seed}"
        );
    }

    #[test]
    fn the_banked_memory_follows_the_plain_rules() {
        // Windows from 1 to the largest, 1 to 64 banks, 1 to 4 channels,
        // tRAS from none to long, few rows (hits, protection) and many
        // (conflicts), light and saturating traffic.
        let cases: [(u32, u32, u32, u32, f64, u64); 12] = [
            (1, 1, 4, 26, 0.1, 4 * 16 * 3),
            (2, 2, 4, 26, 0.3, 4 * 16 * 6),
            (3, 1, 1, 0, 0.2, 16 * 4),
            (16, 4, 8, 26, 0.5, 1 << 16),
            (16, 1, 4, 26, 0.15, 4 * 16 * 6),
            (16, 1, 4, 60, 0.4, 4 * 16 * 6),
            (16, 2, 64, 26, 0.6, 64 * 16 * 4),
            (63, 1, 8, 26, 0.3, 8 * 16 * 8),
            (64, 3, 8, 40, 0.7, 1 << 12),
            (65, 1, 4, 26, 0.3, 4 * 16 * 8),
            (200, 1, 2, 26, 0.5, 2 * 16 * 5),
            (256, 2, 8, 26, 0.9, 1 << 14),
        ];
        for (k, (window, channels, banks, t_ras, rate, blocks)) in cases.into_iter().enumerate() {
            let c = DramConfig {
                model: DramModel::Banked,
                channels,
                banks,
                row_bytes: 1024,
                scheduler_window: window,
                t_ras,
                ..DramConfig::default()
            };
            for seed in 0..3 {
                lockstep(&c, k as u64 * 10 + seed, rate, blocks, 10_000);
            }
        }
    }
}
