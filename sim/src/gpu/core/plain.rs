//! The plain twin of the shader core: the machine of [`ShaderCore`]
//! (wake-ups, launch, issue, the LDST unit, completions through the filter
//! unit, blocking and the scheduler's edge) written to be read rather than
//! to be fast.
//!
//! Where the fast core keeps slot masks, a timing wheel, per-slot arrays
//! apart from the warps and one LDST entry out of its queue, the twin keeps
//! one `Option<PlainWarp>` a slot, each warp in one [`State`], and visits
//! every slot every cycle:
//! - a warp asleep until cycle `t` wakes at `t`: in the middle of an ALU run
//!   it is ready again; otherwise it starts its next instruction entry
//!   (an ALU run, or a texture instruction that waits for the LDST unit)
//!   or, past its last, finishes;
//! - issue visits the slots in the order `core.issue` names and takes
//!   ready warps until the pipeline width is used; at most one texture
//!   instruction a cycle, and only while the LDST queue has room. Loose
//!   round-robin visits the slots from the round-robin pointer, wrapping;
//!   greedy-then-oldest visits the slots that issued in the last issuing
//!   cycle, then the others, each oldest first by launch cycle;
//! - the LDST unit presents the oldest instruction's blocks in order until
//!   the cache refuses one.
//!
//! Progress is whatever moved work on (a count of launches, instructions,
//! retired warps, presented or returned blocks and rasterized quads went
//! up), and the core is idle when no warp is ready, wakes, waits for data
//! or waits in a queue with a free slot to go to, and the filter is free.
//!
//! The lockstep tests (`gpu/lockstep.rs`) run a GPU of these beside a GPU
//! of fast cores and compare every core's observable state every cycle.
//! Only the input queue and registers ([`LaunchScheduler`]) and a core's
//! own rasterizer ([`OwnRaster`]) are shared with the fast core: they have
//! their own references and tests.
//!
//! [`ShaderCore`]: super::ShaderCore

use super::observe::CoreView;
use super::raster::OwnRaster;
use super::{CoreParams, CoreSignals, CoreSnapshot, CoreStats, WarpRecord, WarpView};
use crate::config::FilterTiming;
use crate::config::{BlockedOn, IssueOrder};
use crate::gpu::core_model::CoreModel;
use crate::gpu::SimError;
use crate::mem::{Access, MemorySystem, MissEvent};
use crate::trace::{OpKind, Tile, Trace};
use std::collections::BTreeMap;
use std::collections::VecDeque;
use wasp_rtl::free_mshr::{FreeMshrReg, MshrEvents};
use wasp_rtl::nonblocked::PriorityEvents;
use wasp_rtl::policy::{LaunchPolicy, LaunchRule};
use wasp_rtl::queue::QueueClass;
use wasp_rtl::scheduler::{EdgeEvents, LaunchScheduler};
use wasp_rtl::subset::PrioritySubset;
use wasp_waves::{Traceable, Tracer};

/// Where a warp is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum State {
    /// Waiting until the cycle given: its launch, an ALU result, or its
    /// texture data through the filter unit and the texture latency.
    Asleep(u64),
    /// Ready to issue the next ALU instruction of its run.
    ReadyAlu,
    /// Ready to hand its texture instruction to the LDST unit.
    ReadyTex,
    /// Its texture instruction is in the LDST unit or waits for blocks.
    Texture,
}

/// A warp in a slot.
#[derive(Clone, Copy, Debug)]
struct PlainWarp {
    quad: u32,
    priority: bool,
    state: State,
    /// Its next instruction entry in the tile's pool, and one past its last.
    next_op: u32,
    end_op: u32,
    /// ALU instructions left in its current run.
    alu_left: u32,
    /// The current texture instruction: its blocks, whether trilinear, the
    /// index of its first block in the tile's block accesses, the blocks
    /// not yet returned, and the cycle it entered the LDST unit.
    tex_len: u32,
    tex_tri: bool,
    blk: u32,
    pending: u32,
    tex_start: u64,
    /// Waiting on a long-latency miss since `blocked_at`.
    blocked: bool,
    blocked_at: u64,
    /// Sum of its texture instructions' latencies, and their number.
    lat_sum: u64,
    tex_done: u32,
    launched_at: u64,
}

/// A texture instruction in the LDST unit: the warp in `slot` presents
/// blocks `next..end` of the tile's block accesses.
#[derive(Clone, Copy, Debug)]
struct LdstInstr {
    slot: usize,
    next: u32,
    end: u32,
}

/// The rule of which miss blocks a warp, written plainly: the first-level
/// MSHR entry each waiting access went to, and whether a miss at the
/// rule's level holds the entry.
#[derive(Debug, Default)]
struct PlainBlocking {
    /// First-level entry -> (slots whose accesses allocated or merged into
    /// it, whether a miss at the rule's level holds it).
    first: BTreeMap<u32, (Vec<usize>, bool)>,
    /// L1 entry -> (L0 entries whose requests allocated or merged into it,
    /// whether its request missed in the L2), with an L0 under `dram`.
    l1: BTreeMap<u32, (Vec<u32>, bool)>,
}

impl PlainBlocking {
    /// The slots blocked by first-level entry `e` being held now (none if
    /// it was already).
    fn hold(&mut self, e: u32) -> Vec<usize> {
        let (slots, held) = self.first.get_mut(&e).expect("a pending entry");
        if *held {
            return vec![];
        }
        *held = true;
        slots.clone()
    }
}

/// The plain shader core.
#[derive(Debug)]
pub(crate) struct PlainCore {
    id: usize,
    p: CoreParams,
    sched: LaunchScheduler<u32>,
    track_mshrs: bool,
    measures_cf: bool,
    warps: Vec<Option<PlainWarp>>,
    ldst: VecDeque<LdstInstr>,
    /// First cycle the filter unit is free.
    filter_free: u64,
    tile: Option<usize>,
    /// Its own rasterizer (per-core-tile dispatch).
    raster: OwnRaster,
    tile_misses: u64,
    /// The slot issue visits first (loose round-robin).
    rr: usize,
    /// The slots that issued in the last cycle in which any issued
    /// (greedy-then-oldest).
    last_issued: Vec<usize>,
    /// The cycle's priority-warp events, for the scheduler's edge.
    prio: PriorityEvents,
    signals: CoreSignals,
    stats: CoreStats,
    /// Blocks presented to the cache, and blocks returned, so far.
    presented: u64,
    returned: u64,
    records: Option<Vec<WarpRecord>>,
    blocking: PlainBlocking,
}

impl PlainCore {
    fn active_count(&self) -> u32 {
        self.warps.iter().flatten().count() as u32
    }

    /// Every count of work moved on, for progress.
    fn work(&self) -> [u64; 6] {
        let s = &self.stats;
        [
            s.warps_launched,
            s.instructions,
            s.warps_finished,
            s.quads_rasterized,
            self.presented,
            self.returned,
        ]
    }

    fn warp(&mut self, slot: usize) -> &mut PlainWarp {
        self.warps[slot].as_mut().expect("a warp in the slot")
    }

    /// Block the warp in `slot` at `now`, unless it is blocked already.
    fn block(&mut self, slot: usize, now: u64) {
        let w = self.warps[slot].as_mut().expect("a warp in the slot");
        if w.blocked {
            return;
        }
        w.blocked = true;
        w.blocked_at = now;
        self.stats.blocked_episodes[usize::from(w.priority)] += 1;
        if w.priority {
            self.prio.blocked += 1;
        }
    }

    fn wake(&mut self, now: u64, tile: &Tile) {
        for s in 0..self.warps.len() {
            let Some(w) = self.warps[s].as_mut() else {
                continue;
            };
            if w.state != State::Asleep(now) {
                continue;
            }
            if w.alu_left > 0 {
                w.state = State::ReadyAlu;
            } else if w.next_op >= w.end_op {
                self.finish(s, now);
            } else {
                match tile.op_kind(w.next_op as usize).expect("op in program") {
                    OpKind::Alu(n) => {
                        w.alu_left = n;
                        w.state = State::ReadyAlu;
                    }
                    OpKind::Tex { len, tri } => {
                        w.tex_len = len;
                        w.tex_tri = tri;
                        w.state = State::ReadyTex;
                    }
                }
                w.next_op += 1;
            }
        }
    }

    /// The warp in `slot` leaves the core at `now`: its record, and the
    /// counts of its class.
    fn finish(&mut self, slot: usize, now: u64) {
        let w = self.warps[slot].take().expect("a warp in the slot");
        let class = usize::from(w.priority);
        let mean = (w.tex_done > 0).then(|| w.lat_sum as f64 / f64::from(w.tex_done));
        let record = WarpRecord {
            tile: self.tile.expect("a tile") as u32,
            quad: w.quad,
            core: self.id as u32,
            priority: w.priority,
            mem_latency: mean,
            launched: w.launched_at,
            finished: now,
        };
        let st = &mut self.stats;
        st.warps_finished += 1;
        st.warps_with_tex[class] += u64::from(mean.is_some());
        st.warp_latency_sum[class] += mean.unwrap_or(0.0);
        self.signals.finished += 1;
        self.prio.finished += u8::from(w.priority && !w.blocked);
        if let Some(r) = self.records.as_mut() {
            r.push(record);
        }
    }

    fn launch(&mut self, now: u64, tile: &Tile) {
        let Some(slot) = self.warps.iter().position(Option::is_none) else {
            return;
        };
        let queue = self.sched.queue();
        if queue.is_empty() {
            return;
        }
        let both = queue.has(QueueClass::Priority) && queue.has(QueueClass::Regular);
        let launch = self.sched.launch(true);
        let Some((quad, class)) = launch.warp else {
            self.stats.held_cycles += u64::from(launch.decision.held);
            return;
        };
        if both {
            self.stats.both_waiting += 1;
            self.stats.regular_first += u64::from(class == QueueClass::Regular);
        }
        let priority = class == QueueClass::Priority;
        let span = tile.quad_span(quad as usize).expect("quad in tile");
        self.warps[slot] = Some(PlainWarp {
            quad,
            priority,
            // It can issue from the next cycle.
            state: State::Asleep(now + 1),
            next_op: span.op_start,
            end_op: span.op_start + span.op_len,
            alu_left: 0,
            tex_len: 0,
            tex_tri: false,
            blk: span.block_start,
            pending: 0,
            tex_start: 0,
            blocked: false,
            blocked_at: 0,
            lat_sum: 0,
            tex_done: 0,
            launched_at: now,
        });
        self.stats.warps_launched += 1;
        self.stats.priority_launches += u64::from(priority);
        self.signals.launched = Some((quad, priority));
    }

    /// The slots in the order issue visits them this cycle.
    fn visiting_order(&self) -> Vec<usize> {
        let n = self.warps.len();
        match self.p.core.issue {
            IssueOrder::Lrr => (0..n).map(|k| (self.rr + k) % n).collect(),
            IssueOrder::Gto => {
                let mut order: Vec<usize> = (0..n).filter(|&s| self.warps[s].is_some()).collect();
                order.sort_by_key(|&s| {
                    let launched = self.warps[s].map(|w| w.launched_at);
                    (!self.last_issued.contains(&s), launched)
                });
                order
            }
        }
    }

    fn issue(&mut self, now: u64) {
        let n = self.warps.len();
        let mut tex_room = self.ldst.len() < self.p.core.ldst_queue as usize;
        let mut issued = 0;
        let mut picked = Vec::new();
        for s in self.visiting_order() {
            if issued == self.p.core.pipeline_width {
                break;
            }
            let Some(w) = self.warps[s].as_mut() else {
                continue;
            };
            match w.state {
                State::ReadyAlu => {
                    w.alu_left -= 1;
                    w.state = State::Asleep(now + u64::from(self.p.core.alu_latency));
                }
                State::ReadyTex if tex_room => {
                    tex_room = false;
                    w.pending = w.tex_len;
                    w.tex_start = now;
                    w.state = State::Texture;
                    self.ldst.push_back(LdstInstr {
                        slot: s,
                        next: w.blk,
                        end: w.blk + w.tex_len,
                    });
                    w.blk += w.tex_len;
                    self.stats.tex_instructions += 1;
                    self.stats.tri_tex_instructions += u64::from(w.tex_tri);
                    self.signals.tex_issued = true;
                }
                _ => continue,
            }
            issued += 1;
            picked.push(s);
        }
        self.signals.issued = issued;
        if let Some(&s) = picked.last() {
            self.rr = (s + 1) % n;
            self.last_issued = picked;
            self.stats.instructions += u64::from(issued);
        }
    }

    fn present(&mut self, now: u64, tile: &Tile, mem: &mut MemorySystem) {
        let blocks = tile.block_accesses();
        // The first level's own misses block under first-level, and under
        // l1-miss without an L0 (the first level is the L1).
        let at_access = self.p.blocked_on == BlockedOn::FirstLevel
            || (self.p.blocked_on == BlockedOn::L1Miss && self.p.l0_mshrs.is_none());
        while let Some(mut e) = self.ldst.front().copied() {
            while e.next < e.end {
                let (r, entry) =
                    mem.access_entry(now, self.id, blocks[e.next as usize], e.slot as u32);
                if !r.accepted() {
                    self.ldst[0] = e;
                    self.signals.ldst_refused = true;
                    return;
                }
                e.next += 1;
                self.presented += 1;
                self.signals.ldst_presented += 1;
                if self.measures_cf && r == Access::Miss && self.warp(e.slot).priority {
                    self.prio.misses = self.prio.misses.saturating_add(1);
                }
                let waits = &mut self.blocking.first;
                let held = match r {
                    Access::Miss => {
                        waits.insert(entry, (vec![e.slot], false));
                        false
                    }
                    Access::SecondaryMiss => {
                        // (An entry a prefetch allocated has no record
                        // yet.)
                        let (slots, held) = waits.entry(entry).or_default();
                        slots.push(e.slot);
                        *held
                    }
                    _ => false,
                };
                let missed = matches!(r, Access::Miss | Access::SecondaryMiss);
                if held || (at_access && missed) {
                    self.block(e.slot, now);
                }
            }
            self.ldst.pop_front();
        }
    }

    /// The slots that miss event `ev` blocks under the core's rule.
    fn miss_blocks(&mut self, ev: MissEvent) -> Vec<usize> {
        let has_l0 = self.p.l0_mshrs.is_some();
        match (self.p.blocked_on, ev) {
            (BlockedOn::L1Miss, MissEvent::L1 { l0, .. }) => self.blocking.hold(l0),
            (BlockedOn::Dram, MissEvent::L1 { l0, l1, merged }) => {
                let (l0s, held) = self.blocking.l1.entry(l1).or_default();
                if !merged {
                    l0s.clear();
                    *held = false;
                }
                l0s.push(l0);
                if *held {
                    self.blocking.hold(l0)
                } else {
                    vec![]
                }
            }
            // A prefetch allocated an L1 entry: no warp waits on it yet.
            (BlockedOn::Dram, MissEvent::Prefetch { l1 }) if has_l0 => {
                self.blocking.l1.insert(l1, (vec![], false));
                vec![]
            }
            (BlockedOn::Dram, MissEvent::Prefetch { l1 }) => {
                self.blocking.first.insert(l1, (vec![], false));
                vec![]
            }
            (BlockedOn::Dram, MissEvent::L2 { l1 }) if !has_l0 => self.blocking.hold(l1),
            (BlockedOn::Dram, MissEvent::L2 { l1 }) => {
                let (l0s, held) = self.blocking.l1.get_mut(&l1).expect("a pending entry");
                if *held {
                    return vec![];
                }
                *held = true;
                let l0s = l0s.clone();
                l0s.into_iter()
                    .flat_map(|e| self.blocking.hold(e))
                    .collect()
            }
            _ => vec![],
        }
    }

    /// The warp in slot `tag` waits for a block, or the model is wrong.
    fn waiting_warp(&self, tag: u32, what: &str, now: u64) -> Result<usize, SimError> {
        let s = tag as usize;
        match self.warps.get(s).copied().flatten() {
            Some(w) if w.pending > 0 => Ok(s),
            _ => Err(SimError::Internal(format!(
                "core {}: {what} for slot {s}, which waits for no block, at cycle {now}",
                self.id
            ))),
        }
    }

    /// The data of the warp in `slot` arrived at `now`: through the filter
    /// unit, in order of arrival, then the texture latency.
    fn data_arrived(&mut self, slot: usize, now: u64) {
        let (overlap, latency) = (
            self.p.core.filter_timing == FilterTiming::Overlap,
            u64::from(self.p.core.texture_latency.max(1)),
        );
        let f = u64::from(if self.warp(slot).tex_tri {
            self.p.core.filter_cycles_trilinear
        } else {
            self.p.core.filter_cycles_bilinear
        });
        let start = now.max(self.filter_free);
        self.filter_free = start + f;
        self.stats.filter_busy_cycles += f;
        self.stats.filter_wait_cycles += start - now;
        let w = self.warp(slot);
        w.lat_sum += now - w.tex_start;
        w.tex_done += 1;
        let unblocked = w.blocked.then_some((w.priority, w.blocked_at));
        w.blocked = false;
        w.state = State::Asleep(if overlap {
            (start + f).max(now + latency)
        } else {
            start + f + latency
        });
        if let Some((priority, at)) = unblocked {
            self.stats.blocked_cycles[usize::from(priority)] += now - at;
            if priority {
                self.prio.unblocked += 1;
            }
        }
    }

    fn view(&self) -> CoreView<'_> {
        CoreView {
            id: self.id,
            sched: &self.sched,
            slots: self.warps.len(),
            active: self.active_count(),
            ready: self
                .warps
                .iter()
                .flatten()
                .filter(|w| matches!(w.state, State::ReadyAlu | State::ReadyTex))
                .count() as u32,
            ldst_cap: self.p.core.ldst_queue as usize,
            ldst_len: self.ldst.len(),
            signals: &self.signals,
            tile: self.tile,
            external_raster: self.p.external_raster,
            rasterized: self.raster.delivered(),
        }
    }
}

impl CoreModel for PlainCore {
    fn build(
        id: usize,
        p: &CoreParams,
        policy: &dyn LaunchPolicy,
        rule: LaunchRule,
        subset: Box<dyn PrioritySubset>,
    ) -> Self {
        let free = FreeMshrReg::with_capacity(p.watched_mshrs).expect("fits the register");
        let slots = p.core.max_warps as usize;
        let queue = p.core.input_queue as usize;
        Self {
            id,
            p: *p,
            sched: LaunchScheduler::new(queue, subset, free, policy, rule),
            track_mshrs: policy.reads_free_mshrs(),
            measures_cf: policy.measures_cf(),
            warps: vec![None; slots],
            ldst: VecDeque::new(),
            filter_free: 0,
            tile: None,
            raster: OwnRaster::new(p.raster_rate, p.rejected_per_slot),
            tile_misses: 0,
            rr: 0,
            last_issued: Vec::new(),
            prio: PriorityEvents::default(),
            signals: CoreSignals::default(),
            stats: CoreStats {
                occupancy_hist: vec![0; slots + 1],
                ..CoreStats::default()
            },
            presented: 0,
            returned: 0,
            records: None,
            blocking: PlainBlocking::default(),
        }
    }

    fn tile(&self) -> Option<usize> {
        self.tile
    }

    fn idle(&self) -> bool {
        self.tile.is_none()
    }

    fn assign_tile(&mut self, index: usize, tile: &Tile) {
        self.tile = Some(index);
        self.raster.start(tile);
        self.tile_misses = 0;
    }

    fn begin_shared_tile(&mut self, tile: usize) {
        self.tile = Some(tile);
        self.tile_misses = 0;
    }

    fn push_quad(&mut self, quad: u32, x: u32, y: u32) -> bool {
        self.sched.enqueue(quad, x, y).is_ok()
    }

    fn input_full(&self) -> bool {
        self.sched.queue().is_full()
    }

    fn quads_entered(&self) -> u32 {
        self.raster.delivered()
    }

    fn drained(&self) -> bool {
        self.active_count() == 0 && self.ldst.is_empty() && self.sched.queue().is_empty()
    }

    fn end_shared_tile(&mut self) {
        self.tile = None;
    }

    fn tile_misses(&self) -> u64 {
        self.tile_misses
    }

    fn launched_now(&self) -> Option<(u32, bool)> {
        self.signals.launched
    }

    fn stats(&self) -> &CoreStats {
        &self.stats
    }
    fn reset_stats(&mut self) {
        self.stats = self.stats.cleared();
    }

    fn is_idle(&self, now: u64) -> bool {
        let Some(_) = self.tile else {
            return true;
        };
        let ldst_room = self.ldst.len() < self.p.core.ldst_queue as usize;
        let busy_warp = self.warps.iter().flatten().any(|w| {
            w.pending > 0
                || w.state == State::ReadyAlu
                || (w.state == State::ReadyTex && ldst_room)
                || w.state == State::Asleep(now)
        });
        let can_launch = !self.sched.queue().is_empty() && self.warps.iter().any(Option::is_none);
        let rasterizing = !self.p.external_raster && !self.raster.is_idle();
        !busy_warp && !can_launch && !rasterizing && self.ldst.is_empty() && self.filter_free <= now
    }

    fn evaluate(&mut self, now: u64, trace: &Trace, mem: &mut MemorySystem) -> bool {
        self.signals = CoreSignals::default();
        self.prio = PriorityEvents::default();
        let Some(t) = self.tile else {
            self.stats.idle_cycles += 1;
            self.stats.occupancy_hist[0] += 1;
            return false;
        };
        let before = self.work();
        let tile = &trace.tiles()[t];
        self.wake(now, tile);
        if !self.p.external_raster {
            let sched = &mut self.sched;
            self.raster.run(tile, &mut self.stats, |i, x, y| {
                sched.enqueue(i, x, y).is_ok()
            });
        }
        self.launch(now, tile);
        self.issue(now);
        self.present(now, tile, mem);
        let active = self.active_count();
        self.stats.occupancy_sum += u64::from(active);
        self.stats.occupancy_hist[active as usize] += 1;
        self.work() != before
    }

    fn complete(&mut self, now: u64, mem: &mut MemorySystem) -> Result<bool, SimError> {
        let mut events = Vec::new();
        mem.take_miss_events(self.id, &mut events);
        for ev in events {
            for s in self.miss_blocks(ev) {
                let s = self.waiting_warp(s as u32, "long-latency report", now)?;
                self.block(s, now);
            }
        }
        let before = self.returned;
        let mut arrived = Vec::new();
        mem.take_completions(self.id, &mut arrived);
        for tag in arrived {
            let s = self.waiting_warp(tag, "completion", now)?;
            self.returned += 1;
            let w = self.warp(s);
            w.pending -= 1;
            if w.pending == 0 {
                self.data_arrived(s, now);
            }
        }
        // The edge: the watched cache's allocations and replies (for a
        // policy that reads them) and the cycle's priority-warp events.
        let ev = mem.mshr_events(self.id);
        self.tile_misses += u64::from(ev.allocated);
        let seen = u8::from(self.track_mshrs);
        let edge = EdgeEvents {
            mshr: MshrEvents {
                allocs: ev.allocated as u8 * seen,
                replies: ev.replied as u8 * seen,
            },
            prio: self.prio,
        };
        let id = self.id;
        let fault = |fault| SimError::Register {
            core: id,
            cycle: now,
            fault,
        };
        self.sched.clock(edge).map_err(fault)?;
        let cf = self.sched.cf_meter().map(|m| u64::from(m.cf().quarters()));
        self.stats.cf_quarters_sum += cf.unwrap_or(0);
        self.stats.cf_samples += u64::from(cf.is_some());
        Ok(self.returned != before)
    }

    fn end_cycle(&mut self) -> bool {
        if self.tile.is_none() || self.p.external_raster {
            return false;
        }
        let done = self.raster.is_idle() && self.sched.queue().is_empty() && self.drained();
        if done {
            self.tile = None;
            self.stats.tiles += 1;
        }
        done
    }

    fn describe(&self, trace: &Trace) -> String {
        let blocked = self.warps.iter().flatten().filter(|w| w.blocked).count();
        self.view().describe(trace, blocked)
    }

    fn record_warps(&mut self) {
        self.records = Some(Vec::new());
    }

    fn take_records(&mut self) -> Vec<WarpRecord> {
        self.records.take().unwrap_or_default()
    }

    fn active(&self) -> u32 {
        self.active_count()
    }

    fn snapshot(&self) -> CoreSnapshot {
        let q = self.sched.queue();
        CoreSnapshot {
            tile: self.tile,
            rasterized: self.raster.delivered(),
            queued: [
                q.occupancy(QueueClass::Priority),
                q.occupancy(QueueClass::Regular),
            ],
            free_mshrs: self.sched.free_mshrs().free().get(),
            tracks_free_mshrs: self.track_mshrs,
            nonblocked: self.sched.nonblocked().count().get(),
            active: self.active_count(),
            slots: self.warps.len(),
            warps: self
                .warps
                .iter()
                .enumerate()
                .filter_map(|(slot, w)| {
                    let w = w.as_ref()?;
                    Some(WarpView {
                        slot,
                        quad: w.quad,
                        priority: w.priority,
                        blocked: w.blocked,
                        launched: w.launched_at,
                        ready_alu: w.state == State::ReadyAlu,
                        ready_tex: w.state == State::ReadyTex,
                        alu_left: w.alu_left,
                        next_op: w.next_op,
                        pending: w.pending,
                    })
                })
                .collect(),
            ldst: self.ldst.len(),
        }
    }
}

impl Traceable for PlainCore {
    fn trace<T: Tracer + ?Sized>(&self, t: &mut T) {
        self.view().trace(t);
    }
}
