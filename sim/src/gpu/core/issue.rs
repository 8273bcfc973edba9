//! The issue stage: the warps' wake-ups, and each cycle up to
//! `pipeline_width` instructions from ready warps, one per warp.
//!
//! A warp comes to the stage when it launches or when its ALU result or
//! texture data is ready ([`accept`](Issue::accept)): at that cycle it is
//! ready again in the middle of an ALU run, or it starts its next
//! instruction entry (an ALU run, or a texture instruction for the LDST
//! unit), or, past its last, it is done ([`wake`](Issue::wake)).
//!
//! Which ready warps issue, in the order `core.issue` names. Every order
//! keeps the stage's rules: at most `pipeline_width` instructions a cycle,
//! one per warp; a candidate is a warp ready for an ALU instruction, or
//! one waiting on a texture instruction while the LDST unit has room; one
//! texture instruction enters the LDST unit per cycle, so after the first
//! texture pick only ALU-ready warps are taken. The candidates are visited
//! in the order's sequence and each issues until the width is used. The
//! orders differ only in that sequence:
//! - [`lrr`]: loose round-robin over the slots from a pointer
//!   ([`IssueOrder::Lrr`]);
//! - [`gto`]: greedy-then-oldest ([`IssueOrder::Gto`]).
//!
//! Each order is one file with a fast form on slot masks, which the stage
//! runs, and a plain form that visits the slots one by one as its text
//! reads; the tests in each file compare the two on random masks. The
//! plain twin of the whole core (`core/plain.rs`) visits its slots in the
//! same terms again. The stage keeps its ready warps as slot masks and
//! its wake-ups on a timing wheel ([`WakeWheel`]).

pub(crate) mod gto;
pub(crate) mod lrr;

use super::ldst::{Ldst, LdstEntry};
use super::mask::SlotMask;
use super::warp::{Warps, MAX_SLOTS};
use super::wheel::WakeWheel;
use super::Notes;
use crate::config::{CoreConfig, IssueOrder};
use crate::trace::{OpKind, Tile};
use gto::Gto;
use lrr::Lrr;

/// The issue stage.
#[derive(Clone, Debug)]
pub(super) struct Issue {
    /// Instructions issued per cycle.
    width: u32,
    /// Cycles from an ALU issue to the warp's next issue.
    alu_latency: u64,
    /// Every slot fits in a `u64` mask (the hot loops then use `u64`).
    narrow: bool,
    /// Warps ready to issue an ALU instruction.
    ready: u128,
    /// Warps ready to issue a texture instruction (to the LDST unit).
    ready_tex: u128,
    /// Per slot, the ALU instructions left in the warp's current ALU run
    /// (0: not started), apart from the rest of the warp: the stage counts
    /// a run down without touching the warp.
    alu_left: Box<[u32; MAX_SLOTS]>,
    /// The issue order and its state.
    issuer: Issuer,
    /// Wake-ups: due ones (the stage looks at the warp's next instruction
    /// entry) and ready ones (warps in the middle of an ALU run join the
    /// ready set as a whole mask, with no per-warp look).
    wakes: WakeWheel,
}

impl Issue {
    /// The stage of a core of `core`, with no warp.
    pub(super) fn new(core: &CoreConfig) -> Self {
        Issue {
            width: core.pipeline_width,
            alu_latency: u64::from(core.alu_latency),
            narrow: core.max_warps <= 64,
            ready: 0,
            ready_tex: 0,
            alu_left: Box::new([0; MAX_SLOTS]),
            issuer: Issuer::new(core.issue, core.max_warps as usize),
            wakes: WakeWheel::new(),
        }
    }

    /// The warp in `slot` comes to the stage at cycle `at` (> `now`, the
    /// current cycle).
    #[inline]
    pub(super) fn accept(&mut self, now: u64, at: u64, slot: usize) {
        self.wakes.schedule(now, at, slot);
    }

    /// A warp launched into `slot` in cycle `now`: it can issue from the
    /// next cycle.
    #[inline]
    pub(super) fn launched(&mut self, now: u64, slot: usize) {
        self.alu_left[slot % MAX_SLOTS] = 0;
        self.accept(now, now + 1, slot);
    }

    /// Nothing to do in cycle `now`: no warp is ready (or only ones
    /// waiting for an LDST unit that is full) and none comes to the stage.
    pub(super) fn is_idle(&self, now: u64, ldst: &Ldst) -> bool {
        let tex = if ldst.can_accept() { self.ready_tex } else { 0 };
        self.ready | tex == 0 && !self.wakes.has_any(now)
    }

    /// Warps ready to issue (ALU or texture).
    pub(super) fn ready_count(&self) -> u32 {
        (self.ready | self.ready_tex).count_ones()
    }

    /// Whether the warp in `slot` is ready for an ALU and for a texture
    /// instruction, and the ALU instructions left in its run.
    pub(super) fn view(&self, slot: usize) -> (bool, bool, u32) {
        (
            self.ready >> slot & 1 == 1,
            self.ready_tex >> slot & 1 == 1,
            self.alu_left[slot % MAX_SLOTS],
        )
    }

    /// The wake-ups of cycle `now`: warps in the middle of an ALU run are
    /// ready again; the others start their next instruction entry of
    /// `tile`, read from `warps`. Returns the slots whose warps are past
    /// their last instruction: they are done.
    #[inline(always)]
    pub(super) fn wake(&mut self, now: u64, tile: &Tile, warps: &mut Warps) -> u128 {
        if self.narrow {
            self.wake_due::<u64>(now, tile, warps)
        } else {
            self.wake_due::<u128>(now, tile, warps)
        }
    }

    /// The wake-ups due at `now`, on masks of width `M` (every slot fits).
    #[inline(always)]
    fn wake_due<M: SlotMask>(&mut self, now: u64, tile: &Tile, warps: &mut Warps) -> u128 {
        let (ready_now, due_now) = self.wakes.take(now);
        self.ready |= ready_now;
        let mut due = M::from_wide(due_now);
        let mut ready = M::ZERO;
        let mut ready_tex = M::ZERO;
        let mut done = M::ZERO;
        while due != M::ZERO {
            let s = due.lowest();
            due = due.without_lowest();
            let w = warps.get_mut(s);
            if self.alu_left[s % MAX_SLOTS] > 0 {
                // In an ALU run (a latency beyond the wheels' reach).
                ready |= M::bit(s);
            } else if w.op >= w.n_ops {
                done |= M::bit(s);
            } else {
                // Starting a new instruction entry: decode it once.
                match tile.op_kind(w.op as usize).expect("op in program") {
                    OpKind::Alu(n) => {
                        self.alu_left[s % MAX_SLOTS] = n;
                        ready |= M::bit(s);
                    }
                    OpKind::Tex { len, tri } => {
                        w.tex_len = len;
                        w.tex_tri = tri;
                        ready_tex |= M::bit(s);
                    }
                }
                w.op += 1;
            }
        }
        self.ready |= ready.to_wide();
        self.ready_tex |= ready_tex.to_wide();
        done.to_wide()
    }

    /// Cycle `now`: issue from the ready warps of `warps`; a texture
    /// instruction picked enters `ldst`. Returns whether any instruction
    /// issued (the stage's progress). One copy of the stage per order and
    /// mask width: loose round-robin's copies are inlined into the cycle;
    /// greedy-then-oldest's stay out of it, so that they do not change how
    /// the compiler lays out the default's path.
    #[inline(always)]
    pub(super) fn run(
        &mut self,
        now: u64,
        tile: &Tile,
        warps: &mut Warps,
        ldst: &mut Ldst,
        notes: &mut Notes,
    ) -> bool {
        match self.issuer.order {
            IssueOrder::Lrr => self.run_in::<Lrr>(now, tile, warps, ldst, notes),
            IssueOrder::Gto => self.run_gto(now, tile, warps, ldst, notes),
        }
    }

    #[inline(never)]
    fn run_gto(
        &mut self,
        now: u64,
        tile: &Tile,
        warps: &mut Warps,
        ldst: &mut Ldst,
        notes: &mut Notes,
    ) -> bool {
        self.run_in::<Gto>(now, tile, warps, ldst, notes)
    }

    #[inline(always)]
    fn run_in<O: Order>(
        &mut self,
        now: u64,
        tile: &Tile,
        warps: &mut Warps,
        ldst: &mut Ldst,
        notes: &mut Notes,
    ) -> bool {
        if self.narrow {
            self.issue_with::<u64, O>(now, tile, warps, ldst, notes)
        } else {
            self.issue_with::<u128, O>(now, tile, warps, ldst, notes)
        }
    }

    /// Issue on masks of width `M` (every slot fits), in the order `O`.
    ///
    /// The picks are found first (by the order, whose fast pick is checked
    /// against its plain reference; each ALU pick counts its run down),
    /// then the ALU picks are put on the wake-up wheels as whole masks:
    /// those with more of their run to go on the ready wheel, those that
    /// ended it on the wheel that looks at them.
    #[inline(always)]
    fn issue_with<M: SlotMask, O: Order>(
        &mut self,
        now: u64,
        tile: &Tile,
        warps: &mut Warps,
        ldst: &mut Ldst,
        notes: &mut Notes,
    ) -> bool {
        let ready = M::from_wide(self.ready);
        let tex_cand = if ldst.can_accept() {
            M::from_wide(self.ready_tex)
        } else {
            M::ZERO
        };
        // Each ALU pick counts its run down; those that end it wait on the
        // wheel that looks at their next instruction.
        let alu_left = &mut self.alu_left;
        let on_alu = |s: usize| {
            let left = &mut alu_left[s % MAX_SLOTS];
            *left -= 1;
            *left == 0
        };
        let Picks {
            alu,
            run_end,
            tex,
            issued,
            ..
        } = {
            let age = |s: usize| warps.get(s).launched_at;
            O::state(&mut self.issuer).pick(ready, tex_cand, self.width, age, on_alu)
        };
        notes.signals.issued = issued;
        notes.signals.tex_issued = tex.is_some();
        if issued == 0 {
            return false;
        }
        notes.stats.instructions += u64::from(issued);
        self.ready = (ready & !alu).to_wide();
        let at = now + self.alu_latency;
        if WakeWheel::reaches(now, at) {
            // Mid-run warps are ready again at `at`, nothing to decide.
            self.wakes
                .schedule_masks(at, (alu & !run_end).to_wide(), run_end.to_wide());
        } else {
            let mut m = alu;
            while m != M::ZERO {
                let s = m.lowest();
                m = m.without_lowest();
                self.wakes.schedule(now, at, s);
            }
        }
        if let Some(s) = tex {
            let w = warps.get_mut(s);
            let end = w.blk + w.tex_len;
            debug_assert_eq!(
                tile.op_kind(w.op as usize - 1),
                Some(OpKind::Tex {
                    len: w.tex_len,
                    tri: w.tex_tri
                }),
                "ready_tex warps wait on a texture instruction"
            );
            w.pending = w.tex_len;
            w.tex_start = now;
            ldst.accept(LdstEntry {
                slot: s as u8,
                next: w.blk,
                end,
            });
            w.blk = end;
            self.ready_tex &= !(1u128 << s);
            notes.stats.tex_instructions += 1;
            notes.stats.tri_tex_instructions += u64::from(w.tex_tri);
        }
        true
    }
}

/// What the issue stage picked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Picks<M> {
    /// Slots issuing an ALU instruction.
    pub alu: M,
    /// Those of `alu` for which the pick callback said their ALU run ends.
    pub run_end: M,
    /// The slot issuing a texture instruction, if any.
    pub tex: Option<usize>,
    /// Instructions issued.
    pub issued: u32,
    /// The last slot picked (meaningful when `issued > 0`).
    pub last: u32,
}

impl<M: SlotMask> Picks<M> {
    /// Nothing picked yet.
    pub(crate) const NONE: Self = Picks {
        alu: M::ZERO,
        run_end: M::ZERO,
        tex: None,
        issued: 0,
        last: 0,
    };

    /// Every slot picked, ALU and texture.
    #[inline(always)]
    pub(crate) fn slots(&self) -> M {
        match self.tex {
            Some(s) => self.alu | M::bit(s),
            None => self.alu,
        }
    }

    /// Take slot `s`: its ALU instruction when `s` is in `ready`
    /// (`on_alu(s)` saying whether its run ends), else its texture
    /// instruction. Returns whether it took the texture instruction.
    #[inline(always)]
    pub(crate) fn take(
        &mut self,
        s: usize,
        ready: M,
        on_alu: &mut impl FnMut(usize) -> bool,
    ) -> bool {
        let bit = M::bit(s);
        let tex = ready & bit == M::ZERO;
        if tex {
            self.tex = Some(s);
        } else {
            self.alu |= bit;
            self.run_end |= M::bit_if(s, on_alu(s));
        }
        self.issued += 1;
        self.last = s as u32;
        tex
    }
}

/// One issue order: its pick and the state it keeps between cycles.
pub(crate) trait Order: Sized {
    /// The order's state in a core's [`Issuer`].
    fn state(issuer: &mut Issuer) -> &mut Self;

    /// This cycle's picks from `ready` (ALU-ready slots) and `tex` (slots
    /// whose texture instruction may enter the LDST unit; disjoint from
    /// `ready`), at most `width`; `age(s)` is the launch cycle of the warp
    /// in slot `s`. `on_alu(slot)` is called for each ALU pick in visiting
    /// order and says whether the warp's ALU run ends with this
    /// instruction. The order updates its state for the next cycle.
    fn pick<M: SlotMask>(
        &mut self,
        ready: M,
        tex: M,
        width: u32,
        age: impl Fn(usize) -> u64,
        on_alu: impl FnMut(usize) -> bool,
    ) -> Picks<M>;
}

/// A core's issue order and the state of every order (a pointer and a
/// slot set, a few bytes), so that the core runs one copy of its issue
/// stage per order with the state in place ([`Order::state`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Issuer {
    /// The order the core runs.
    pub(crate) order: IssueOrder,
    lrr: lrr::Lrr,
    gto: gto::Gto,
}

impl Issuer {
    /// `order` in its reset state on a core of `slots` warp slots.
    pub(crate) fn new(order: IssueOrder, slots: usize) -> Self {
        Issuer {
            order,
            lrr: lrr::Lrr::new(slots),
            gto: gto::Gto::default(),
        }
    }
}

/// The plain references' visit: slots in `order`, one by one; an
/// ALU-ready slot issues, else the first texture-ready one takes the
/// texture port, until `width` have issued.
#[cfg(test)]
pub(crate) fn visit_plain(
    order: impl IntoIterator<Item = usize>,
    ready: u128,
    tex: u128,
    width: u32,
    mut on_alu: impl FnMut(usize) -> bool,
) -> Picks<u128> {
    let mut p = Picks::NONE;
    for s in order {
        if p.issued == width {
            break;
        }
        let alu_ready = ready >> s & 1 == 1;
        let tex_ready = tex >> s & 1 == 1 && p.tex.is_none();
        if alu_ready {
            p.alu |= 1u128 << s;
            if on_alu(s) {
                p.run_end |= 1u128 << s;
            }
        } else if tex_ready {
            p.tex = Some(s);
        } else {
            continue;
        }
        p.issued += 1;
        p.last = s as u32;
    }
    p
}

impl Order for lrr::Lrr {
    #[inline(always)]
    fn state(issuer: &mut Issuer) -> &mut Self {
        &mut issuer.lrr
    }

    #[inline(always)]
    fn pick<M: SlotMask>(
        &mut self,
        ready: M,
        tex: M,
        width: u32,
        _age: impl Fn(usize) -> u64,
        on_alu: impl FnMut(usize) -> bool,
    ) -> Picks<M> {
        self.pick(ready, tex, width, on_alu)
    }
}

impl Order for gto::Gto {
    #[inline(always)]
    fn state(issuer: &mut Issuer) -> &mut Self {
        &mut issuer.gto
    }

    #[inline(always)]
    fn pick<M: SlotMask>(
        &mut self,
        ready: M,
        tex: M,
        width: u32,
        age: impl Fn(usize) -> u64,
        on_alu: impl FnMut(usize) -> bool,
    ) -> Picks<M> {
        self.pick(ready, tex, width, age, on_alu)
    }
}

#[cfg(test)]
mod tests {
    use super::super::testkit::{cycles, one_core, trace};
    use super::*;
    use crate::trace::Instr;

    #[test]
    fn orders_read_back_from_their_names() {
        for o in IssueOrder::ALL {
            assert_eq!(o.to_string().parse::<IssueOrder>(), Ok(o));
        }
        let e = "fifo".parse::<IssueOrder>().unwrap_err();
        assert!(e.contains("expected lrr or gto"), "{e}");
        assert_eq!(IssueOrder::default(), IssueOrder::Lrr);
    }

    #[test]
    fn picks_name_their_slots() {
        let p = Picks::<u64> {
            alu: 0b101,
            run_end: 0,
            tex: Some(4),
            issued: 3,
            last: 4,
        };
        assert_eq!(p.slots(), 0b10101);
        assert_eq!(Picks::<u64>::NONE.slots(), 0);
    }

    /// Cycle in which each of two warps finished, on one core of width 1
    /// with an ALU latency of 1; both run eight ALU instructions, the first
    /// launched a cycle before the second.
    fn finish_cycles(order: IssueOrder) -> [u64; 2] {
        use crate::config::MachineConfig;
        use crate::gpu::Gpu;
        use crate::trace::{Instr, Trace, TraceHeader};
        let mut b = Trace::builder(TraceHeader::new("issue", 8, 8, 8)).unwrap();
        b.begin_tile(0, 0).unwrap();
        for x in 0..2 {
            b.quad(x, 0, &[Instr::Alu(8)]).unwrap();
        }
        b.end_tile().unwrap();
        let t = b.finish().unwrap();
        let mut c = MachineConfig::paper();
        c.gpu.tile_size = 8;
        c.gpu.cores = 1;
        c.raster.quads_per_cycle = 1;
        c.core.pipeline_width = 1;
        c.core.alu_latency = 1;
        c.core.issue = order;
        c.validate().unwrap();
        let mut gpu = Gpu::new(&c, &t).unwrap();
        gpu.record_warps();
        while !gpu.done() {
            gpu.step().unwrap();
        }
        let mut r = gpu.take_records();
        r.sort_by_key(|w| w.quad);
        [r[0].finished, r[1].finished]
    }

    /// Greedy-then-oldest runs the older warp's ALU run back to back;
    /// loose round-robin alternates the two.
    #[test]
    fn the_order_decides_who_runs_first() {
        let [a, b] = finish_cycles(IssueOrder::Gto);
        assert!(b >= a + 7, "gto: the older warp finishes first ({a}, {b})");
        let [a, b] = finish_cycles(IssueOrder::Lrr);
        assert!(a.abs_diff(b) <= 2, "lrr: the two interleave ({a}, {b})");
    }

    /// The stage in a one-core machine, cycle by cycle.
    /// Issue takes at most `pipeline_width` instructions a cycle, and a warp
    /// in an ALU run issues once every `alu_latency` cycles.
    #[test]
    fn issue_keeps_the_width_and_the_alu_latency() {
        let quads: Vec<(u32, u32)> = (0..4).flat_map(|y| (0..4).map(move |x| (x, y))).collect();
        for (width, alu) in [(1, 1), (2, 3), (4, 5)] {
            let run = cycles(&one_core(width, 16, alu), &trace(&quads, &[Instr::Alu(6)]));
            let per_cycle: Vec<u64> = run.windows(2).map(|w| w[1].0[0] - w[0].0[0]).collect();
            assert!(per_cycle.iter().all(|&n| n <= u64::from(width)));
            assert_eq!(run.last().unwrap().0[0], 16 * 6);
            // A lone warp: its six instructions `alu` cycles apart.
            let lone = cycles(
                &one_core(width, 16, alu),
                &trace(&[(0, 0)], &[Instr::Alu(6)]),
            );
            let at: Vec<usize> = lone
                .windows(2)
                .enumerate()
                .filter(|(_, w)| w[1].0[0] > w[0].0[0])
                .map(|(i, _)| i)
                .collect();
            assert_eq!(at.len(), 6 - usize::from(lone[0].0[0] > 0));
            assert!(at.windows(2).all(|d| d[1] - d[0] == alu as usize));
        }
    }
}
