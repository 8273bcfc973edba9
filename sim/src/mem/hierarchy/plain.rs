//! [`MemorySystem::tick`] written plainly, for the tests to run beside the
//! fast one: every core is visited in every step (no skipping of quiet
//! cores), every L1 hit travels to its L0 through the delivery queue (no
//! direct fill), the L2's candidates are listed from core `now % cores` in
//! a simple scan, and the final step always runs. The lockstep test below
//! drives two systems, one ticked each way, with the same accesses and
//! compares everything an owner can observe, every cycle.

use super::*;

impl MemorySystem {
    /// The plain twin of [`MemorySystem::tick`].
    pub(crate) fn tick_plain(&mut self, now: u64) {
        self.now = now;
        self.ticks += 1;
        self.ticked_until = now + 1;
        let track = self.track;
        let n = self.cores.len();
        let l1_reply = now + u64::from(self.cfg.l1.hit_latency) - 1;

        // 1. Every core: MSHR occupancy current, L0 misses presented to
        //    the L1 in order until the L1 refuses one, then the prefetch
        //    queue's head on the ports they left.
        let reserve = self.cfg.prefetch.l1_reserve;
        for (c, pf) in self.cores.iter_mut().zip(&mut self.pf) {
            c.active = !c.is_quiet();
            c.l1.release(now);
            let Some(l0) = c.l0.as_mut() else {
                prefetch_step(now, c, pf, track, reserve);
                continue;
            };
            l0.release(now);
            while let Some(&r) = c.to_l1.front() {
                if r.ready > now {
                    break;
                }
                match c.l1.access_entry(now, r.block, r.entry) {
                    (Lookup::Hit, _) => c.to_l0.push_back(Delivery {
                        at: l1_reply,
                        entry: r.entry,
                    }),
                    (Lookup::Miss, entry) => {
                        c.to_l2.push_back(Request {
                            ready: now + 1,
                            block: r.block,
                            entry,
                        });
                        match track {
                            Track::Nothing => {}
                            Track::L1 => mark_l0(l0, &mut c.l0_long, &mut c.long, r.entry),
                            Track::L2 => c.l1_long[entry as usize] = false,
                        }
                    }
                    (Lookup::Secondary, entry) => {
                        if track == Track::L1 || (track == Track::L2 && c.l1_long[entry as usize]) {
                            mark_l0(l0, &mut c.l0_long, &mut c.long, r.entry);
                        }
                    }
                    (Lookup::Stall | Lookup::MergeFull | Lookup::PortBusy, _) => break,
                }
                c.to_l1.drop_front();
            }
            prefetch_step(now, c, pf, track, reserve);
        }

        // 2. L1 misses to the L2: rounds over the cores from core `now %
        //    cores`, one ready head per core per round; a core leaves when
        //    the L2 refuses its head or its next head is not ready; all stop
        //    when the L2's ports are used.
        let l2_reply = now + u64::from(self.l2.config().hit_latency) - 1;
        let first = (now % n as u64) as usize;
        let mut order: Vec<usize> = (first..n)
            .chain(0..first)
            .filter(|&k| self.cores[k].to_l2.front().is_some_and(|r| r.ready <= now))
            .collect();
        'rounds: while !order.is_empty() {
            let mut next_round = Vec::new();
            for &k in &order {
                let c = &mut self.cores[k];
                let r = *c.to_l2.front().expect("a candidate has a request");
                match self.l2.access_entry_unmarked(now, r.block, k as u32) {
                    (Lookup::Hit, _) => self.to_l1.push_back(L2Reply {
                        at: l2_reply,
                        core: k as u32,
                        block: r.block,
                    }),
                    (Lookup::Miss, entry) => {
                        self.dram.request(now, r.block, entry);
                        if track == Track::L2 {
                            mark_l1(c, r.entry);
                        }
                    }
                    (Lookup::Secondary, _) => {
                        if track == Track::L2 {
                            mark_l1(c, r.entry);
                        }
                    }
                    (Lookup::PortBusy, _) => break 'rounds,
                    (Lookup::Stall | Lookup::MergeFull, _) => continue,
                }
                c.to_l2.drop_front();
                if c.to_l2.front().is_some_and(|r| r.ready <= now) {
                    next_round.push(k);
                }
            }
            order = next_round;
        }

        // 3. Main memory accepts, and its replies due now fill the L2.
        self.dram.accept(now);
        while let Some(entry) = self.dram.pop_reply(now) {
            let block = self.l2.pending_block(entry);
            for &core in self.l2.fill_entry_unmarked(now, entry) {
                self.to_l1.push_back(L2Reply {
                    at: l2_reply,
                    core,
                    block,
                });
            }
        }
        self.l2.release(now);

        // 4. L2 replies due now fill the L1s; their targets go on to the
        //    L0 (or complete, without L0).
        while let Some(r) = self.to_l1.pop_front_if(|r| r.at <= now) {
            let c = &mut self.cores[r.core as usize];
            let at = now + u64::from(c.l1.config().hit_latency) - 1;
            let targets = c.l1.fill(now, r.block);
            if c.l0.is_some() {
                for &entry in targets {
                    c.to_l0.push_back(Delivery { at, entry });
                }
            } else {
                complete_all(&mut c.completing, &mut c.ready, now, at, targets);
            }
        }

        // 5. Every core: L1 replies due now fill the L0; tags due now
        //    complete.
        for c in &mut self.cores {
            if let Some(l0) = c.l0.as_mut() {
                while let Some(d) = c.to_l0.pop_front_if(|d| d.at <= now) {
                    fill_l0(l0, &mut c.completing, &mut c.ready, now, d.entry);
                }
            }
            while let Some((_, tag)) = c.completing.pop_front_if(|&(at, _)| at <= now) {
                c.ready.push(tag);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::arb_config;
    use super::*;
    use proptest::prelude::*;

    /// Two systems, one ticked fast and one plainly, given the same
    /// accesses (`ops`: idle cycle when 0, else accesses per core and a
    /// base block) until drained; everything observable must agree every
    /// cycle: access results, MSHR views, long-latency reports,
    /// completions, and the statistics at the end.
    fn lockstep(cfg: &MemConfig, ops: &[(u8, u8, u64)]) -> Result<u64, TestCaseError> {
        let mut fast = MemorySystem::new(cfg).unwrap();
        let mut plain = fast.clone();
        let n = cfg.cores as usize;
        let (mut a, mut b) = (Vec::new(), Vec::new());
        let mut tag = 0u32;
        let mut ops = ops.iter();
        let mut draining = false;
        let mut now = 0u64;
        loop {
            if !draining {
                match ops.next() {
                    Some(&(0, _, _)) => {}
                    Some(&(_, count, block)) => {
                        for k in 0..n {
                            // A prefetch too, when the machine has a
                            // prefetcher: queued on both, served by each
                            // tick on the ports demand leaves.
                            if cfg.prefetch.enabled() {
                                let blk = block + 3 + k as u64 * 5;
                                fast.prefetch_queue(k).offer(blk);
                                plain.prefetch_queue(k).offer(blk);
                            }
                            for j in 0..u64::from(count) {
                                let blk = block + j * 7 + k as u64;
                                let (x, y) = (
                                    fast.access(now, k, blk, tag),
                                    plain.access(now, k, blk, tag),
                                );
                                prop_assert_eq!(x, y, "access of tag {} at cycle {}", tag, now);
                                tag += 1;
                            }
                        }
                    }
                    None => draining = true,
                }
            }
            fast.tick(now);
            plain.tick_plain(now);
            for k in 0..n {
                prop_assert_eq!(
                    fast.mshr_events(k),
                    plain.mshr_events(k),
                    "core {} cycle {}",
                    k,
                    now
                );
                a.clear();
                b.clear();
                fast.take_long_latency(k, &mut a);
                plain.take_long_latency(k, &mut b);
                prop_assert_eq!(&a, &b, "long latency, core {} cycle {}", k, now);
                a.clear();
                b.clear();
                fast.take_completions(k, &mut a);
                plain.take_completions(k, &mut b);
                prop_assert_eq!(&a, &b, "completions, core {} cycle {}", k, now);
            }
            now += 1;
            if draining && fast.is_idle() {
                prop_assert!(plain.is_idle());
                break;
            }
            prop_assert!(now < 100_000, "no drain");
        }
        prop_assert_eq!(fast.stats(), plain.stats());
        if cfg.prefetch.enabled() {
            prop_assert_eq!(fast.prefetch_stats(), plain.prefetch_stats());
        }
        Ok(now)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]

        #[test]
        fn the_plain_tick_is_the_fast_one(
            cfg in arb_config(),
            ops in proptest::collection::vec((0u8..4, 0u8..3, 0u64..40), 1..300),
        ) {
            lockstep(&cfg, &ops)?;
        }
    }

    #[test]
    fn the_plain_tick_is_the_fast_one_on_the_papers_machines() {
        // A texture-like load: bursts of accesses to a sliding window of
        // blocks, on the shipped hierarchy with and without L0.
        let ops: Vec<(u8, u8, u64)> = (0..3000u64)
            .map(|i| {
                (
                    (i % 5 != 0) as u8,
                    (1 + i % 2) as u8,
                    (i / 16) * 3 + (i * 7919) % 11,
                )
            })
            .collect();
        for width4 in [false, true] {
            let mut cfg = MemConfig::paper(width4);
            let cycles = lockstep(&cfg, &ops).unwrap();
            assert!(cycles > 3000, "{cycles}");
            cfg.prefetch.kind = crate::mem::PrefetchKind::Raster;
            let cycles = lockstep(&cfg, &ops).unwrap();
            assert!(cycles > 3000, "{cycles}");
        }
    }
}
