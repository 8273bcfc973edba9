//! One channel of the banked DRAM ([`super::BankedDram`], whose module
//! docs state the rules): its banks, its request queue, its command bus
//! (one command a cycle) and its data bus, and the scheduler that picks
//! the cycle's command.
//!
//! The scheduler works on events, not on cycles times requests:
//! - the queue is kept in two parts, in arrival order: `oldest`, the first
//!   `scheduler_window` requests (all of them when there are fewer), whose
//!   visible prefix is the scheduler's window; and `backlog`, the requests
//!   behind them, which move up as requests leave. A request leaving
//!   `oldest` leaves a tombstone, so that nothing moves; tombstones go when
//!   the first live request passes them or `oldest` fills up;
//! - per bank, the window's requests that hit its open row and those that
//!   do not are counted as the window and the banks change (a request
//!   becomes visible or leaves, an ACTIVATE, a PRECHARGE), so a step
//!   looks for a request only in the banks that can take a command, and
//!   stops at the first;
//! - after every step the channel computes the first cycle in which a
//!   command might issue ([`Channel::next_chance`]); the memory skips the
//!   cycles before it.
//!
//! In test builds every step checks the counts against a count of the
//! window from scratch.

use crate::mem::config::DramConfig;
use crate::mem::ring::Ring;
use crate::mem::stats::DramStats;

/// The open row of a precharged bank.
const CLOSED: u64 = u64::MAX;
/// The `entry` of a queued write: it gets no reply.
pub(super) const WRITE: u32 = u32::MAX;
/// `first_command` of a request that has issued none.
const NOT_YET: u64 = u64::MAX;
/// A cycle that never comes: no wake-up, no reply, no column command.
pub(super) const NEVER: u64 = u64::MAX;
/// Banks a channel can have (a bank mask fits a `u64`).
const MAX_BANKS: usize = 64;

/// A request in a channel's queue, waiting for the scheduler.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct QueuedRequest {
    /// First cycle the scheduler sees it.
    ready: u64,
    /// Cycle of the L2 miss (or of the write).
    missed: u64,
    row: u64,
    /// Cycle of its first command ([`NOT_YET`] before).
    first_command: u64,
    /// The L2's MSHR entry, or [`WRITE`].
    entry: u32,
    /// Its bank (below [`MAX_BANKS`]; a byte keeps the request at 40
    /// bytes, which a column command moves).
    bank: u8,
    /// It issued an ACTIVATE or a PRECHARGE.
    opened: bool,
    /// It issued a PRECHARGE.
    closed: bool,
    /// It has left the window (its column command issued): a tombstone
    /// in `Channel::oldest`.
    dead: bool,
}

impl QueuedRequest {
    /// A request for `bank` and `row` (or a write, `entry` [`WRITE`])
    /// missed in cycle `now`: the scheduler sees it from `now + 1`.
    pub(super) fn new(now: u64, bank: usize, row: u64, entry: u32) -> Self {
        debug_assert!(bank < MAX_BANKS);
        QueuedRequest {
            ready: now + 1,
            missed: now,
            bank: bank as u8,
            row,
            entry,
            first_command: NOT_YET,
            opened: false,
            closed: false,
            dead: false,
        }
    }
}

#[derive(Debug, Clone, Copy)]
struct Bank {
    /// Open row, or [`CLOSED`].
    open_row: u64,
    /// First cycle the bank takes its next command.
    ready: u64,
    /// Cycle of the last ACTIVATE (for tRAS).
    activated: u64,
    /// First cycle the bank takes a row command: `ready`, and with a row
    /// open, `activated + t_ras` (the open-row protection aside).
    row_free: u64,
}

impl Bank {
    /// `row_free` by its definition, for a memory of `t_ras`.
    #[inline]
    fn row_free_now(&self, t_ras: u32) -> u64 {
        // A closed bank's ACTIVATE is past `activated` already.
        let t_ras = if self.open_row == CLOSED { 0 } else { t_ras };
        self.ready.max(self.activated + u64::from(t_ras))
    }
}

/// The set bits of a bank mask, lowest first.
struct Bits(u64);

impl Iterator for Bits {
    type Item = usize;
    #[inline(always)]
    fn next(&mut self) -> Option<usize> {
        if self.0 == 0 {
            return None;
        }
        let k = self.0.trailing_zeros() as usize;
        self.0 &= self.0 - 1;
        Some(k)
    }
}

/// A read's reply on its way to the L2.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct Reply {
    /// Cycle the reply reaches the L2.
    pub(super) at: u64,
    pub(super) entry: u32,
}

/// Per bank, the window's requests by whether they hit the bank's open
/// row, and the banks with any of each.
#[derive(Debug, Clone)]
struct BankCounts {
    /// Requests hitting the bank's open row.
    hits: [u16; MAX_BANKS],
    /// Requests for a closed bank or another row than the open one.
    others: [u16; MAX_BANKS],
    /// Banks with a hit.
    hit_banks: u64,
    /// Banks with another request.
    other_banks: u64,
}

impl BankCounts {
    const EMPTY: BankCounts = BankCounts {
        hits: [0; MAX_BANKS],
        others: [0; MAX_BANKS],
        hit_banks: 0,
        other_banks: 0,
    };

    #[inline]
    fn add(&mut self, k: usize, hit: bool) {
        if hit {
            self.hits[k] += 1;
            self.hit_banks |= 1 << k;
        } else {
            self.others[k] += 1;
            self.other_banks |= 1 << k;
        }
    }

    #[inline]
    fn remove_hit(&mut self, k: usize) {
        self.hits[k] -= 1;
        if self.hits[k] == 0 {
            self.hit_banks &= !(1 << k);
        }
    }

    /// Bank `k` now holds `hits` of its requests as hits, the rest as
    /// others.
    #[inline]
    fn set_bank(&mut self, k: usize, hits: u16) {
        let all = self.hits[k] + self.others[k];
        self.hits[k] = hits;
        self.others[k] = all - hits;
        let bit = 1 << k;
        self.hit_banks = if hits > 0 {
            self.hit_banks | bit
        } else {
            self.hit_banks & !bit
        };
        self.other_banks = if all > hits {
            self.other_banks | bit
        } else {
            self.other_banks & !bit
        };
    }
}

/// One channel (see the module docs).
#[derive(Debug, Clone)]
pub(super) struct Channel {
    /// The banks; the first `banks` of the configuration are used.
    banks: Box<[Bank; MAX_BANKS]>,
    /// The oldest `scheduler_window` requests in arrival order, with the
    /// tombstones of those that have left (a column command marks its
    /// request `dead` rather than moving the ones behind it up); the
    /// tombstones are dropped when the first live request moves past them
    /// and when the vector is full.
    oldest: Vec<QueuedRequest>,
    /// Index in `oldest` of the first live request (its length with none).
    head: usize,
    /// Live requests in `oldest`.
    live: usize,
    /// `oldest` holds at most this many entries, live or dead.
    room: usize,
    /// Entries of `oldest` the scheduler has seen: the live ones of them
    /// are its window (requests enter in cycle order, so the visible ones
    /// are a prefix, and a tombstone was visible).
    visible: usize,
    /// The window's requests per bank.
    counts: Box<BankCounts>,
    /// The requests behind `oldest` (empty unless `oldest` is full).
    backlog: Ring<QueuedRequest>,
    /// Reads issued, in issue (= reply) order.
    pub(super) replies: Ring<Reply>,
    /// First cycle the data bus is free.
    bus_free: u64,
    /// Cycle of the last column command ([`NEVER`] before the first).
    pub(super) column_at: u64,
    /// First cycle in which the scheduler could issue a command: a lower
    /// bound computed after every step ([`Channel::next_chance`]), lowered
    /// by a request entering `oldest`.
    pub(super) wake: u64,
}

impl Channel {
    /// A channel with every bank closed, for a memory of `cfg` that holds
    /// at most `max_outstanding` reads.
    pub(super) fn new(cfg: &DramConfig, max_outstanding: usize) -> Self {
        Channel {
            banks: Box::new(
                [Bank {
                    open_row: CLOSED,
                    ready: 0,
                    activated: 0,
                    row_free: 0,
                }; MAX_BANKS],
            ),
            oldest: Vec::with_capacity(4 * cfg.scheduler_window as usize),
            head: 0,
            live: 0,
            room: 4 * cfg.scheduler_window as usize,
            visible: 0,
            counts: Box::new(BankCounts::EMPTY),
            backlog: Ring::with_capacity(max_outstanding + 64),
            replies: Ring::with_capacity(max_outstanding),
            bus_free: 0,
            column_at: NEVER,
            wake: NEVER,
        }
    }

    /// Whether no request waits.
    #[inline]
    pub(super) fn is_empty(&self) -> bool {
        self.live == 0
    }

    /// Queue `r` in the cycle before its `ready`, behind the others.
    #[inline]
    pub(super) fn enqueue(&mut self, cfg: &DramConfig, r: QueuedRequest) {
        if self.live < cfg.scheduler_window as usize {
            // It enters the window when it becomes visible: the scheduler
            // looks again when it could take a command.
            self.wake = self.wake.min(self.first_chance(cfg, &r));
            self.push_oldest(r);
        } else {
            // Behind the window: it moves up when a request leaves, in a
            // cycle in which the channel steps anyway.
            self.backlog.push_back(r);
        }
    }

    /// Append `r` to `oldest`, first dropping the tombstones if it is
    /// full.
    #[inline]
    fn push_oldest(&mut self, r: QueuedRequest) {
        if self.oldest.len() == self.room {
            self.compact();
        }
        self.oldest.push(r);
        self.live += 1;
    }

    /// Drop the tombstones of `oldest`.
    #[cold]
    fn compact(&mut self) {
        let dead_seen = self.oldest[..self.visible]
            .iter()
            .filter(|r| r.dead)
            .count();
        self.oldest.retain(|r| !r.dead);
        self.visible -= dead_seen;
        self.head = 0;
    }

    /// The first live request if the scheduler sees it.
    #[inline(always)]
    fn visible_head(&self) -> Option<&QueuedRequest> {
        self.oldest[..self.visible].get(self.head)
    }

    #[inline(always)]
    fn bank(&self, k: usize) -> &Bank {
        &self.banks[k % MAX_BANKS]
    }

    /// Whether request `r` hits its bank's open row.
    #[inline(always)]
    fn hits(&self, r: &QueuedRequest) -> bool {
        self.bank(usize::from(r.bank)).open_row == r.row
    }

    /// Count the requests that have become visible by cycle `now` into
    /// the window.
    #[inline]
    fn see(&mut self, now: u64) {
        while let Some(r) = self.oldest.get(self.visible) {
            if r.ready > now {
                break;
            }
            let hit = self.hits(r);
            self.counts.add(usize::from(r.bank) % MAX_BANKS, hit);
            self.visible += 1;
        }
    }

    /// Issue at most one command in cycle `now`; whether a request left the
    /// queue (its column command issued). Then set `wake`.
    #[inline(always)]
    pub(super) fn step(&mut self, cfg: &DramConfig, stats: &mut DramStats, now: u64) -> bool {
        self.see(now);
        let left = self.command(cfg, stats, now);
        self.see(now);
        #[cfg(debug_assertions)]
        self.check_counts(cfg);
        self.wake = self.next_chance(cfg, now);
        left
    }

    /// The command of cycle `now`, by the rules' order; whether a request
    /// left the queue.
    #[inline]
    fn command(&mut self, cfg: &DramConfig, stats: &mut DramStats, now: u64) -> bool {
        let Some(head) = self.visible_head() else {
            return false;
        };
        let h = self.head;
        let bus_ok = self.bus_free <= now + u64::from(cfg.t_cl);
        // 1. The head, if it can issue anything.
        let b = self.bank(usize::from(head.bank));
        if b.open_row == head.row {
            if b.ready <= now && bus_ok {
                self.issue_column(cfg, stats, h, now);
                return true;
            }
        } else if self.try_row_command(cfg, stats, h, now, true) {
            return false;
        }
        // 2. The oldest row hit that can issue its column command: one in
        // a bank with a hit, free.
        if bus_ok {
            let mut free = 0u64;
            for k in Bits(self.counts.hit_banks) {
                free |= u64::from(self.bank(k).ready <= now) << k;
            }
            if free != 0 {
                let i = self.oldest[h..self.visible]
                    .iter()
                    .position(|r| {
                        free >> (usize::from(r.bank) % MAX_BANKS) & 1 == 1
                            && self.hits(r)
                            && !r.dead
                    })
                    .expect("a free bank with a hit has a request hitting it");
                self.issue_column(cfg, stats, h + i, now);
                return true;
            }
        }
        // 3. The oldest request that can issue a row command: one in a
        // free bank, closed, or open for tRAS and not protected.
        // (A closed bank has no row hit, so it is never protected.)
        let mut free = 0u64;
        for k in Bits(self.counts.other_banks & !self.counts.hit_banks) {
            free |= u64::from(self.bank(k).row_free <= now) << k;
        }
        if free != 0 {
            let found = self.oldest[h + 1..self.visible].iter().position(|r| {
                free >> (usize::from(r.bank) % MAX_BANKS) & 1 == 1 && !self.hits(r) && !r.dead
            });
            if let Some(i) = found {
                let issued = self.try_row_command(cfg, stats, h + 1 + i, now, false);
                debug_assert!(issued, "a request of a free bank takes its row command");
            }
        }
        false
    }

    /// After cycle `now`'s step: the first cycle in which something might
    /// issue. Until a command issues or a request enters the window
    /// (which lowers `wake` to its first chance), banks, bus and queue
    /// change only with time, and each condition of the rules, once true,
    /// stays true (the window only grows, which can only add to the
    /// open-row protection); so the earliest cycle any of them can turn
    /// true bounds the next command from below. Each depends on the
    /// request's bank only:
    /// - a row hit: its bank free and its data slot free,
    ///   `max(bank ready, bus free - t_cl)`;
    /// - an ACTIVATE or a PRECHARGE: its bank's `row_free`; never,
    ///   without a command or an arrival first, while the open-row
    ///   protection holds it (not the head's; a closed bank has no row
    ///   hit, so it is never protected);
    /// - a request still to become visible: its
    ///   [`first_chance`](Self::first_chance).
    #[inline]
    fn next_chance(&self, cfg: &DramConfig, now: u64) -> u64 {
        let mut wake = NEVER;
        for r in &self.oldest[self.visible..] {
            wake = wake.min(self.first_chance(cfg, r));
        }
        let hit_banks = self.counts.hit_banks;
        // The earliest of `max(ready, data)` is `max(earliest ready, data)`.
        let mut hit_ready = NEVER;
        for k in Bits(hit_banks) {
            hit_ready = hit_ready.min(self.bank(k).ready);
        }
        let data = self.bus_free.saturating_sub(u64::from(cfg.t_cl));
        wake = wake.min(hit_ready.max(data));
        for k in Bits(self.counts.other_banks & !hit_banks) {
            wake = wake.min(self.bank(k).row_free);
        }
        // The head is not held by the protection.
        if let Some(r) = self.visible_head() {
            let b = self.bank(usize::from(r.bank));
            if b.open_row != r.row {
                wake = wake.min(b.row_free);
            }
        }
        wake.max(now + 1)
    }

    /// The first cycle in which `r`, still to become visible, could take
    /// a command if banks and bus do not change before: once visible, its
    /// row hit or row command as for the window's requests (the open-row
    /// protection, which it may add to, only holds commands back).
    #[inline]
    fn first_chance(&self, cfg: &DramConfig, r: &QueuedRequest) -> u64 {
        let b = self.bank(usize::from(r.bank));
        let t = if b.open_row == r.row {
            b.ready
                .max(self.bus_free.saturating_sub(u64::from(cfg.t_cl)))
        } else {
            b.row_free
        };
        t.max(r.ready)
    }

    /// Issue the READ / WRITE of request `i` (an index in `oldest`) in
    /// cycle `now`: it leaves the queue, and the first request of the
    /// backlog moves up.
    fn issue_column(&mut self, c: &DramConfig, stats: &mut DramStats, i: usize, now: u64) {
        let r = self.oldest[i];
        self.oldest[i].dead = true;
        self.live -= 1;
        if i == self.head {
            self.head += 1;
            while self.oldest.get(self.head).is_some_and(|r| r.dead) {
                self.head += 1;
            }
            if self.head == self.oldest.len() {
                // Nothing left but tombstones, all of them seen.
                self.oldest.clear();
                self.head = 0;
                self.visible = 0;
            }
        }
        let k = usize::from(r.bank) % MAX_BANKS;
        self.counts.remove_hit(k);
        if let Some(next) = self.backlog.pop_front() {
            self.push_oldest(next);
        }
        let burst = u64::from(c.t_burst);
        let b = &mut self.banks[k];
        b.ready = now + burst;
        b.row_free = b.row_free_now(c.t_ras);
        let data = now + u64::from(c.t_cl);
        self.bus_free = data + burst;
        stats.bus_busy_cycles += burst;
        self.column_at = now;
        if r.entry == WRITE {
            stats.write_row_misses += u64::from(r.opened);
            stats.write_row_conflicts += u64::from(r.closed);
            return;
        }
        let at = data + burst - 1 + u64::from(c.controller_latency);
        self.replies.push_back(Reply { at, entry: r.entry });
        if r.opened {
            stats.row_misses += 1;
            stats.row_conflicts += u64::from(r.closed);
        } else {
            stats.row_hits += 1;
        }
        let first = r.first_command.min(now);
        stats.queue_wait_sum += first - r.ready;
        stats.latency_sum += at - r.missed;
    }

    /// Issue request `i`'s ACTIVATE or PRECHARGE in cycle `now` if the rules
    /// allow; `head` lifts the open-row protection (a PRECHARGE of a bank
    /// whose open row a request of the window would hit).
    fn try_row_command(
        &mut self,
        cfg: &DramConfig,
        stats: &mut DramStats,
        i: usize,
        now: u64,
        head: bool,
    ) -> bool {
        let r = &self.oldest[i];
        let k = usize::from(r.bank) % MAX_BANKS;
        let b = self.banks[k];
        if b.ready > now || b.open_row == r.row {
            return false;
        }
        if b.open_row == CLOSED {
            let bank = &mut self.banks[k];
            *bank = Bank {
                open_row: r.row,
                ready: now + u64::from(cfg.t_rcd),
                activated: now,
                row_free: 0,
            };
            bank.row_free = bank.row_free_now(cfg.t_ras);
            stats.activates += 1;
            let row = r.row;
            // Every request of a closed bank is an other; a lone one is
            // this one.
            let hits = if self.counts.others[k] == 1 {
                1
            } else {
                self.oldest[self.head..self.visible]
                    .iter()
                    .filter(|o| usize::from(o.bank) % MAX_BANKS == k && o.row == row && !o.dead)
                    .count()
            };
            self.counts.set_bank(k, hits as u16);
        } else {
            let protected = !head && self.counts.hit_banks >> k & 1 == 1;
            if now < b.activated + u64::from(cfg.t_ras) || protected {
                return false;
            }
            let bank = &mut self.banks[k];
            bank.open_row = CLOSED;
            bank.ready = now + u64::from(cfg.t_rp);
            bank.row_free = bank.row_free_now(cfg.t_ras);
            stats.precharges += 1;
            self.oldest[i].closed = true;
            self.counts.set_bank(k, 0);
        }
        let q = &mut self.oldest[i];
        q.opened = true;
        q.first_command = q.first_command.min(now);
        true
    }

    /// The counts against a count of the window from scratch, and each
    /// bank's `row_free` against its definition.
    #[cfg(debug_assertions)]
    fn check_counts(&self, cfg: &DramConfig) {
        for b in self.banks.iter() {
            assert_eq!(b.row_free, b.row_free_now(cfg.t_ras), "{b:?}");
        }
        let mut fresh = BankCounts::EMPTY;
        for r in self.oldest[self.head..self.visible]
            .iter()
            .filter(|r| !r.dead)
        {
            fresh.add(usize::from(r.bank) % MAX_BANKS, self.hits(r));
        }
        assert!(self.oldest[..self.head].iter().all(|r| r.dead));
        assert!(self.oldest[self.visible..].iter().all(|r| !r.dead));
        let live = self.oldest.iter().filter(|r| !r.dead).count();
        assert_eq!(live, self.live, "live requests");
        assert!(self.oldest.get(self.head).is_none_or(|r| !r.dead));
        assert_eq!(fresh.hits, self.counts.hits, "row hits per bank");
        assert_eq!(fresh.others, self.counts.others, "other requests per bank");
        assert_eq!(
            (fresh.hit_banks, fresh.other_banks),
            (self.counts.hit_banks, self.counts.other_banks)
        );
    }
}
