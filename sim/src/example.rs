//! The paper's worked example (Section III-A), run on the RTL scheduler.
//!
//! A tile of 15 warps, one texture access each: W0-W4 read block A, W5-W9
//! block B, W10-W14 block C. A single-level cache with 3 MSHRs sits in front
//! of a main memory of fixed latency 7; the core makes one access per cycle.
//! Blocks stay in the cache once fetched (the tile's working set fits).
//!
//! Three launch orders are compared, each produced by a launch policy
//! running on [`wasp_rtl::scheduler::LaunchScheduler`]:
//! - `scanline`: the baseline policy (one FIFO, rasterization order);
//! - `all_priority_first`: Fullpriority with W0, W5, W10 as priority warps;
//! - `wasp`: the WaSP rule `Real_freeMSHRs > threshold` with CF = 1 (each
//!   warp makes exactly one access) and threshold 1 by default.
//!
//! ## The timing reading (documented, as the paper leaves it implicit)
//!
//! - A warp is launched when the LDST unit's access register is empty, and
//!   presents its access to the cache in the cycle it is launched.
//! - A cache whose MSHRs are all occupied refuses every access, hits
//!   included; the access waits in the LDST register and retries next cycle.
//!   Each refused cycle is a stall cycle.
//! - A primary miss in cycle m allocates an MSHR entry; its reply arrives
//!   in cycle r = m + latency, fills the line and completes every warp
//!   waiting on it in cycle r. An access in cycle r itself merges (secondary
//!   miss, completing at r); from r + 1 on, the block hits.
//! - The cache keeps the entry held through cycle r + 1 (it is writing the
//!   line) and can allocate it again from r + 2.
//! - The free-MSHR register counts the entry free from its reply: the reply
//!   in cycle r is an event of cycle r, loaded at the clock edge, so a
//!   launch decision in cycle r + 1 already sees the entry as free (while
//!   the cache still holds it for that one cycle).
//! - A warp finishes when its access completes; the tile ends with the
//!   last warp.
//!
//! With this reading: scanline 18 cycles, 0 stall cycles; all priority
//! first 21 cycles, 6 stall cycles; WaSP (threshold 1, CF = 1) 16 cycles.

use serde::Serialize;
use wasp_rtl::datapath::{Cf, Threshold, WaspDatapath};
use wasp_rtl::free_mshr::{FreeMshrReg, MshrEvents, FREE_MSHR_BITS};
use wasp_rtl::nonblocked::PriorityEvents;
use wasp_rtl::policy::{LaunchPolicy, LaunchRule, PolicySpec, Wasp};
use wasp_rtl::queue::QueueClass;
use wasp_rtl::scheduler::{EdgeEvents, LaunchScheduler};
use wasp_rtl::subset::Explicit;
use wasp_waves::{CycleSink, Traceable, Tracer};

mod cache;
mod chronograph;

use cache::ExampleCache;
pub use chronograph::{
    render_chronograph, render_report, Chronograph, CycleRow, ExampleReport, Outcome,
};

/// Number of warps in the example tile.
pub const WARPS: u32 = 15;
/// Warps per block (W0-W4 read A, ...).
pub const WARPS_PER_BLOCK: u32 = 5;
/// Block names.
pub const BLOCKS: [char; 3] = ['A', 'B', 'C'];

/// The machine of the example.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub struct ExampleConfig {
    /// Main-memory latency in cycles (paper: 7).
    pub latency: u32,
    /// MSHR entries of the cache (paper: 3); the 5-bit free-MSHR register
    /// holds at most 31.
    pub mshrs: u32,
    /// WaSP threshold (default 1).
    pub threshold: u32,
    /// What a closed gate does with a lone waiting priority warp (default
    /// `hold`, the paper's rule: "W10 is delayed until there is more space
    /// in the MSHR").
    pub launch_rule: LaunchRule,
}

impl Default for ExampleConfig {
    fn default() -> Self {
        Self {
            latency: 7,
            mshrs: 3,
            threshold: 1,
            launch_rule: LaunchRule::Hold,
        }
    }
}

impl ExampleConfig {
    /// Check the machine against what its registers can hold.
    pub fn validate(&self) -> Result<(), String> {
        if self.latency == 0 {
            return Err("--latency must be at least 1 cycle (a reply cannot arrive in the cycle of its miss)".into());
        }
        if self.latency > 1_000_000 {
            return Err(format!(
                "--latency {} is implausible (at most 1000000 cycles)",
                self.latency
            ));
        }
        if self.mshrs == 0 {
            return Err("--mshrs must be at least 1: a cache without MSHRs can never miss".into());
        }
        if FreeMshrReg::with_capacity(self.mshrs).is_none() {
            return Err(format!(
                "--mshrs {}: the {}-bit free-MSHR register holds at most {}",
                self.mshrs,
                FREE_MSHR_BITS,
                (1u32 << FREE_MSHR_BITS) - 1
            ));
        }
        self.wasp_policy().map(|_| ())
    }

    fn wasp_policy(&self) -> Result<Box<dyn LaunchPolicy>, String> {
        // Build through PolicySpec for its checks, then with CF = 1 exactly.
        PolicySpec::Wasp {
            threshold: self.threshold,
            cf: 1.0,
        }
        .build(self.mshrs)
        .map_err(|e| format!("--threshold: {e}"))?;
        Ok(Box::new(Wasp::new(WaspDatapath {
            cf: Cf::ONE,
            threshold: Threshold::masked(self.threshold),
        })))
    }
}

fn block_of(warp: u32) -> usize {
    (warp / WARPS_PER_BLOCK) as usize
}

/// Signals of the example machine visible in the waveform.
#[derive(Clone, Copy, Debug, Default)]
struct CacheSignals {
    access_valid: bool,
    access_block: u64,
    access_warp: u64,
    access_outcome: u64,
    stall: bool,
    reply_valid: bool,
    reply_block: u64,
    mshr_occupancy: u64,
    launch_warp: u64,
}

/// One example machine: scheduler, LDST access register, cache.
struct Machine {
    key: &'static str,
    sched: LaunchScheduler<u32>,
    cache: ExampleCache,
    ldst: Option<u32>,
    priority: [bool; WARPS as usize],
    finished: u32,
    done_at: Option<u64>,
    signals: CacheSignals,
    chrono: Chronograph,
}

impl Machine {
    fn new(
        key: &'static str,
        title: &'static str,
        cfg: &ExampleConfig,
        policy: Box<dyn LaunchPolicy>,
    ) -> Self {
        let name = policy.name();
        let free = FreeMshrReg::with_capacity(cfg.mshrs).expect("validated");
        // The paper designates W0, W5 and W10 (the first warp of each block)
        // as the priority subset. Warp i is the quad at (i, 0).
        let subset = Explicit::new((0..WARPS).step_by(WARPS_PER_BLOCK as usize).map(|w| (w, 0)));
        let mut sched = LaunchScheduler::new(
            WARPS as usize,
            Box::new(subset),
            free,
            policy.as_ref(),
            cfg.launch_rule,
        );
        let mut priority = [false; WARPS as usize];
        for w in 0..WARPS {
            let class = sched.enqueue(w, w, 0).expect("queue holds the tile");
            priority[w as usize] = class == QueueClass::Priority;
        }
        Self {
            key,
            sched,
            cache: ExampleCache::new(cfg.mshrs, cfg.latency),
            ldst: None,
            priority,
            finished: 0,
            done_at: None,
            signals: CacheSignals::default(),
            chrono: Chronograph {
                title: title.into(),
                policy: name,
                machine: *cfg,
                cf: 1.0,
                cycles: 0,
                stall_cycles: 0,
                held_cycles: 0,
                hits: 0,
                misses: 0,
                secondary_misses: 0,
                launch_order: Vec::new(),
                timeline: Vec::new(),
            },
        }
    }

    fn done(&self) -> bool {
        self.done_at.is_some()
    }

    /// Phase 1 (combinational, from current state) of cycle `t`, then the
    /// events of the cycle: the launch stage, the LDST stage, the cache's
    /// replies. Returns the events for the clock edge.
    fn evaluate(&mut self, t: u64) -> EdgeEvents {
        self.cache.begin_cycle(t);
        let mut c = Cycle {
            row: CycleRow {
                cycle: t,
                block: None,
                warp: None,
                outcome: None,
                blocked: false,
                replies: Vec::new(),
                mshrs_held: 0,
                free_mshrs: self.sched.free_mshrs().free().get(),
                nonblocked_priority: self.sched.nonblocked().count().get(),
                real_free_mshrs: None,
                launched: None,
            },
            sig: CacheSignals::default(),
            mshr: MshrEvents::default(),
            prio: PriorityEvents::default(),
        };
        self.launch_stage(&mut c);
        self.ldst_stage(t, &mut c);
        self.reply_stage(t, &mut c);
        c.row.mshrs_held = self.cache.entries.len() as u32;
        c.sig.mshr_occupancy = c.row.mshrs_held as u64;
        self.signals = c.sig;
        self.chrono.timeline.push(c.row);
        if self.finished == WARPS {
            self.done_at = Some(t);
            self.chrono.cycles = t;
        }
        EdgeEvents {
            mshr: c.mshr,
            prio: c.prio,
        }
    }

    /// Launch stage: a warp enters the LDST register when it is empty.
    fn launch_stage(&mut self, c: &mut Cycle) {
        let launch = self.sched.launch(self.ldst.is_none());
        let decision = launch.decision;
        c.row.real_free_mshrs = decision.datapath.map(|d| d.real_free.get());
        if decision.held && self.ldst.is_none() {
            self.chrono.held_cycles += 1;
        }
        if let Some((w, class)) = launch.warp {
            self.ldst = Some(w);
            self.chrono.launch_order.push(w);
            c.row.launched = Some((
                w,
                match class {
                    QueueClass::Priority => "priority".into(),
                    QueueClass::Regular => "regular".into(),
                },
            ));
            c.sig.launch_warp = w as u64;
        }
    }

    /// LDST stage: present the pending access.
    fn ldst_stage(&mut self, t: u64, c: &mut Cycle) {
        let Some(w) = self.ldst else {
            return;
        };
        let block = block_of(w);
        let Some(o) = self.cache.access(t, block, w) else {
            c.row.blocked = true;
            c.sig.stall = true;
            self.chrono.stall_cycles += 1;
            return;
        };
        self.ldst = None;
        c.row.block = Some(BLOCKS[block]);
        c.row.warp = Some(w);
        c.row.outcome = Some(o);
        c.sig.access_valid = true;
        c.sig.access_block = block as u64 + 1;
        c.sig.access_warp = w as u64;
        c.sig.access_outcome = o.code();
        let is_prio = self.priority[w as usize];
        match o {
            Outcome::Hit => {
                self.chrono.hits += 1;
                self.finished += 1;
                c.prio.finished += is_prio as u8;
            }
            Outcome::Miss => {
                self.chrono.misses += 1;
                c.mshr.allocs += 1;
                c.prio.blocked += is_prio as u8;
            }
            Outcome::Secondary => {
                self.chrono.secondary_misses += 1;
                c.prio.blocked += is_prio as u8;
            }
        }
    }

    /// Replies of this cycle complete their waiting warps.
    fn reply_stage(&mut self, t: u64, c: &mut Cycle) {
        for (block, waiters) in self.cache.replies(t) {
            c.mshr.replies += 1;
            c.row.replies.push(BLOCKS[block]);
            c.sig.reply_valid = true;
            c.sig.reply_block = block as u64 + 1;
            for w in waiters {
                self.finished += 1;
                if self.priority[w as usize] {
                    c.prio.unblocked += 1;
                    c.prio.finished += 1;
                }
            }
        }
    }
}

/// What one cycle of the worked example records and signals, and its
/// events for the clock edge.
struct Cycle {
    row: CycleRow,
    sig: CacheSignals,
    mshr: MshrEvents,
    prio: PriorityEvents,
}

impl Traceable for Machine {
    fn trace<T: Tracer + ?Sized>(&self, t: &mut T) {
        t.push_scope(self.key);
        t.push_scope("scheduler");
        self.sched.trace(t);
        t.signal("launch_warp", 4, self.signals.launch_warp);
        t.pop_scope();
        t.push_scope("cache");
        let s = &self.signals;
        t.signal("mshr_occupancy", FREE_MSHR_BITS, s.mshr_occupancy);
        t.bit("cache_stall", s.stall);
        t.bit("access_valid", s.access_valid);
        t.signal("access_block", 2, s.access_block);
        t.signal("access_warp", 4, s.access_warp);
        t.signal("access_outcome", 2, s.access_outcome);
        t.bit("reply_valid", s.reply_valid);
        t.signal("reply_block", 2, s.reply_block);
        t.pop_scope();
        t.bit("done", self.done());
        t.pop_scope();
    }
}

/// Errors of the example run.
#[derive(Debug)]
pub enum ExampleError {
    /// The machine's parameters are out of range.
    Config(String),
    /// A register left its range (a model bug; reported, never wrapped).
    Register(wasp_rtl::RegisterFault),
    /// Writing the waveform failed.
    Io(std::io::Error),
    /// A run did not finish (a model bug).
    NoProgress(u64),
}

impl std::fmt::Display for ExampleError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ExampleError::Config(e) => write!(f, "{e}"),
            ExampleError::Register(e) => write!(f, "{e}"),
            ExampleError::Io(e) => write!(f, "writing the waveform: {e}"),
            ExampleError::NoProgress(c) => write!(f, "the example made no progress by cycle {c}"),
        }
    }
}

impl std::error::Error for ExampleError {}

/// Run the three launch orders without tracing.
pub fn run(cfg: &ExampleConfig) -> Result<ExampleReport, ExampleError> {
    run_inner::<wasp_waves::NullTracer>(cfg, None)
}

/// Run the three launch orders, sampling every signal into `sink` each
/// cycle (cycle 0 is the reset state). Returns the report and the last
/// cycle sampled.
pub fn run_traced<S: CycleSink>(
    cfg: &ExampleConfig,
    sink: &mut S,
) -> Result<(ExampleReport, u64), ExampleError> {
    let r = run_inner(cfg, Some(sink))?;
    let last = r
        .scanline
        .cycles
        .max(r.all_priority_first.cycles)
        .max(r.wasp.cycles);
    Ok((r, last))
}

fn run_inner<S: CycleSink>(
    cfg: &ExampleConfig,
    mut sink: Option<&mut S>,
) -> Result<ExampleReport, ExampleError> {
    cfg.validate().map_err(ExampleError::Config)?;
    let mut machines = [
        Machine::new(
            "scanline",
            "Scanline order (baseline)",
            cfg,
            PolicySpec::Baseline
                .build(cfg.mshrs)
                .map_err(ExampleError::Config)?,
        ),
        Machine::new(
            "all_priority_first",
            "All priority warps first (Fullpriority)",
            cfg,
            PolicySpec::FullPriority
                .build(cfg.mshrs)
                .map_err(ExampleError::Config)?,
        ),
        Machine::new(
            "wasp",
            "WaSP (Real_freeMSHRs > threshold)",
            cfg,
            cfg.wasp_policy().map_err(ExampleError::Config)?,
        ),
    ];
    if let Some(s) = sink.as_deref_mut() {
        s.begin_cycle(0);
        for m in &machines {
            m.trace(s);
        }
        s.end_cycle().map_err(ExampleError::Io)?;
    }
    // Every warp needs at most one full round of misses per MSHR-sized
    // batch; this bound is far above any legal run.
    let limit = (WARPS as u64 + 2) * (cfg.latency as u64 + 2) + 16;
    let mut t = 0u64;
    while machines.iter().any(|m| !m.done()) {
        t += 1;
        if t > limit {
            return Err(ExampleError::NoProgress(limit));
        }
        let mut events = Vec::with_capacity(3);
        for m in machines.iter_mut() {
            if !m.done() {
                events.push(Some(m.evaluate(t)));
            } else {
                m.signals = CacheSignals::default();
                events.push(None);
            }
        }
        if let Some(s) = sink.as_deref_mut() {
            s.begin_cycle(t);
            for m in &machines {
                m.trace(s);
            }
            s.end_cycle().map_err(ExampleError::Io)?;
        }
        for (m, ev) in machines.iter_mut().zip(events) {
            if let Some(ev) = ev {
                m.sched.clock(ev).map_err(ExampleError::Register)?;
            }
        }
    }
    let [a, b, c] = machines;
    Ok(ExampleReport {
        scanline: a.chrono,
        all_priority_first: b.chrono,
        wasp: c.chrono,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_papers_three_chronographs() {
        let r = run(&ExampleConfig::default()).unwrap();
        assert_eq!((r.scanline.cycles, r.scanline.stall_cycles), (18, 0));
        assert_eq!(
            (
                r.all_priority_first.cycles,
                r.all_priority_first.stall_cycles
            ),
            (21, 6)
        );
        assert_eq!((r.wasp.cycles, r.wasp.stall_cycles), (16, 0));
        // 18 / 16 = 1.125: the paper's "11% speedup" (12.5% by this ratio,
        // 11.1% as a reduction of cycles).
        assert!((r.wasp_speedup() - 0.125).abs() < 1e-12);
    }

    #[test]
    fn scanline_follows_the_papers_narrative() {
        let r = run(&ExampleConfig::default()).unwrap();
        let c = &r.scanline;
        assert_eq!(c.launch_order, (0..15).collect::<Vec<_>>());
        // W0 misses A in cycle 1, W1-W4 merge, W5 misses B in cycle 6,
        // A's reply in cycle 8, W14 requests C in 15, C replies in 18.
        assert_eq!(c.timeline[0].outcome, Some(Outcome::Miss));
        for i in 1..5 {
            assert_eq!(c.timeline[i].outcome, Some(Outcome::Secondary));
        }
        assert_eq!(c.timeline[5].warp, Some(5));
        assert_eq!(c.timeline[5].outcome, Some(Outcome::Miss));
        assert_eq!(c.timeline[7].replies, vec!['A']);
        assert_eq!(c.timeline[14].warp, Some(14));
        assert_eq!(c.timeline[17].replies, vec!['C']);
        assert_eq!((c.misses, c.secondary_misses, c.hits), (3, 12, 0));
    }

    #[test]
    fn all_priority_first_stalls_from_cycle_4_to_9() {
        let r = run(&ExampleConfig::default()).unwrap();
        let c = &r.all_priority_first;
        assert_eq!(&c.launch_order[..3], &[0, 5, 10]);
        let blocked: Vec<u64> = c
            .timeline
            .iter()
            .filter(|r| r.blocked)
            .map(|r| r.cycle)
            .collect();
        assert_eq!(blocked, vec![4, 5, 6, 7, 8, 9]);
        assert_eq!((c.misses, c.secondary_misses, c.hits), (3, 0, 12));
    }

    #[test]
    fn wasp_spaces_the_third_priority_warp() {
        let r = run(&ExampleConfig::default()).unwrap();
        let c = &r.wasp;
        // W5 follows W0 at once; W10 waits until the free-MSHR register has
        // counted A's reply (cycle 8) and Real_freeMSHRs = 2 > 1 in cycle 9.
        assert_eq!(
            c.launch_order,
            vec![0, 5, 1, 2, 3, 4, 6, 7, 10, 8, 9, 11, 12, 13, 14]
        );
        assert_eq!(c.timeline[8].warp, Some(10));
        assert_eq!(c.timeline[8].outcome, Some(Outcome::Miss));
        assert_eq!(c.timeline[8].real_free_mshrs, Some(2));
        assert_eq!(c.timeline[7].real_free_mshrs, Some(1));
    }

    #[test]
    fn wasp_order_depends_on_the_threshold() {
        // Threshold 0 lets the third priority warp in at once: it then
        // behaves like Fullpriority.
        let r = run(&ExampleConfig {
            threshold: 0,
            ..Default::default()
        })
        .unwrap();
        assert_eq!(r.wasp.launch_order, r.all_priority_first.launch_order);
        assert_eq!(r.wasp.cycles, 21);
    }

    #[test]
    fn plentiful_mshrs_never_stall() {
        let r = run(&ExampleConfig {
            mshrs: 31,
            threshold: 1,
            latency: 7,
            ..Default::default()
        })
        .unwrap();
        for c in [&r.scanline, &r.all_priority_first, &r.wasp] {
            assert_eq!(c.stall_cycles, 0, "{}", c.title);
        }
        // Clustering the misses then pays off: 3 misses overlap.
        assert!(r.all_priority_first.cycles < r.scanline.cycles);
    }

    #[test]
    fn rejects_what_the_registers_cannot_hold() {
        let e = ExampleConfig {
            mshrs: 32,
            ..Default::default()
        }
        .validate()
        .unwrap_err();
        assert!(e.contains("5-bit"), "{e}");
        assert!(ExampleConfig {
            mshrs: 0,
            ..Default::default()
        }
        .validate()
        .is_err());
        assert!(ExampleConfig {
            latency: 0,
            ..Default::default()
        }
        .validate()
        .is_err());
        let e = ExampleConfig {
            threshold: 3,
            ..Default::default()
        }
        .validate()
        .unwrap_err();
        assert!(e.contains("below"), "{e}");
    }

    #[test]
    fn every_warp_finishes_for_many_machines() {
        for mshrs in 1..=6 {
            for latency in 1..=12 {
                for threshold in 0..mshrs {
                    for launch_rule in LaunchRule::ALL {
                        let r = run(&ExampleConfig {
                            mshrs,
                            latency,
                            threshold,
                            launch_rule,
                        })
                        .unwrap();
                        for c in [&r.scanline, &r.all_priority_first, &r.wasp] {
                            let mut order = c.launch_order.clone();
                            order.sort_unstable();
                            assert_eq!(order, (0..15).collect::<Vec<_>>());
                            assert_eq!(c.hits + c.misses + c.secondary_misses, 15);
                            assert_eq!(c.misses, 3);
                            assert!(c.timeline.iter().all(|r| r.mshrs_held <= mshrs));
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn renders_the_papers_rows() {
        let r = run(&ExampleConfig::default()).unwrap();
        let text = render_report(&r);
        assert!(text.contains("18 cycles, 0 stall cycles"));
        assert!(text.contains("21 cycles, 6 stall cycles"));
        assert!(text.contains("16 cycles, 0 stall cycles"));
        let fp = render_chronograph(&r.all_priority_first);
        let cache_row = fp
            .lines()
            .find(|l| l.trim_start().starts_with("cache"))
            .unwrap();
        assert_eq!(cache_row.matches("##").count(), 6);
        assert!(cache_row.contains("   X   X   X  ##"));
    }

    #[test]
    fn the_launch_rule_leaves_the_papers_example_alone() {
        // At threshold 1, W10 launches (cycle 9) while regular warps still
        // wait: the gate is never closed with only priority warps queued,
        // so `launch` changes nothing.
        let hold = run(&ExampleConfig::default()).unwrap();
        let launch = run(&ExampleConfig {
            launch_rule: LaunchRule::Launch,
            ..Default::default()
        })
        .unwrap();
        assert_eq!(hold.wasp.held_cycles, 0);
        assert_eq!(launch.wasp.timeline, hold.wasp.timeline);
        assert_eq!(
            (
                launch.scanline.cycles,
                launch.all_priority_first.cycles,
                launch.wasp.cycles
            ),
            (18, 21, 16)
        );
    }

    #[test]
    fn at_threshold_2_hold_idles_and_launch_does_not() {
        // Threshold 2 of 3 MSHRs: a priority warp needs all 3 free. W0
        // launches first (3 > 2); every later decision sees at most 2 free
        // until C's reply, so the regular warps go first, in scanline order,
        // and W14 (cycle 13) empties the regular FIFO with W5 and W10 still
        // waiting.
        let cfg = ExampleConfig {
            threshold: 2,
            ..Default::default()
        };
        let hold = run(&cfg).unwrap();
        let launch = run(&ExampleConfig {
            launch_rule: LaunchRule::Launch,
            ..cfg
        })
        .unwrap();
        let order = vec![0, 1, 2, 3, 4, 6, 7, 8, 9, 11, 12, 13, 14, 5, 10];
        assert_eq!(hold.wasp.launch_order, order);
        assert_eq!(launch.wasp.launch_order, order);
        // hold: cycles 14-17 launch nothing (free_mshrs 2, not > 2); C
        // replies in 17, the register counts it in 18: W5 hits B in 18,
        // W10 hits C in 19. 19 cycles, 4 hold cycles.
        assert_eq!((hold.wasp.cycles, hold.wasp.held_cycles), (19, 4));
        let idle: Vec<u64> = hold.wasp.timeline[13..17]
            .iter()
            .filter(|r| r.launched.is_none() && r.warp.is_none())
            .map(|r| r.cycle)
            .collect();
        assert_eq!(idle, vec![14, 15, 16, 17]);
        assert_eq!(hold.wasp.timeline[17].warp, Some(5));
        assert_eq!(hold.wasp.timeline[18].warp, Some(10));
        // launch: W5 in 14 (hits B, replied in 13), W10 in 15 merges into
        // C's entry and completes with C's reply in 17: 17 cycles, 2 fewer.
        assert_eq!((launch.wasp.cycles, launch.wasp.held_cycles), (17, 0));
        assert_eq!(launch.wasp.timeline[13].warp, Some(5));
        assert_eq!(launch.wasp.timeline[13].outcome, Some(Outcome::Hit));
        assert_eq!(launch.wasp.timeline[14].warp, Some(10));
        assert_eq!(launch.wasp.timeline[14].outcome, Some(Outcome::Secondary));
        // The baseline and Fullpriority never close a gate on a waiting
        // priority warp: the rule does not change them.
        assert_eq!(launch.scanline.timeline, hold.scanline.timeline);
        assert_eq!(
            launch.all_priority_first.timeline,
            hold.all_priority_first.timeline
        );
    }
}
