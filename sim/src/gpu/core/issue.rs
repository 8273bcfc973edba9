//! The issue stage: the warps' wake-ups, and each cycle up to
//! `pipeline_width` instructions from ready warps, one per warp.
//!
//! A warp comes to the stage when it launches or when its ALU result or
//! texture data is ready ([`accept`](Issue::accept)): at that cycle it is
//! ready again in the middle of an ALU run, or it starts its next
//! instruction entry (an ALU run, or a texture instruction for the LDST
//! unit), or, past its last, it is done ([`wake`](Issue::wake)).
//!
//! Which ready warps issue: loose round-robin over the warp slots:
//! starting at the slot `rr` (the one after the previous cycle's last
//! pick), the slots are visited in ascending order, wrapping; each
//! candidate issues until `width` instructions have issued. A candidate is
//! a warp ready for an ALU instruction, or one waiting on a texture
//! instruction while the LDST unit has room; one texture instruction
//! enters the LDST unit per cycle, so after the first texture pick only
//! ALU-ready warps are taken.
//!
//! [`pick`] is the fast form on slot masks (one rotation, then a bit scan
//! per pick); [`pick_plain`] visits the slots one by one, as the text
//! reads. The tests run both on random masks. The stage keeps its ready
//! warps as slot masks and its wake-ups on a timing wheel ([`WakeWheel`]).

use super::ldst::{Ldst, LdstEntry};
use super::mask::SlotMask;
use super::warp::{Warps, MAX_SLOTS};
use super::wheel::WakeWheel;
use super::Notes;
use crate::config::CoreConfig;
use crate::trace::{OpKind, Tile};

/// The issue stage.
#[derive(Clone, Debug)]
pub(super) struct Issue {
    /// Instructions issued per cycle.
    width: u32,
    /// Cycles from an ALU issue to the warp's next issue.
    alu_latency: u64,
    /// Warp slots of the core.
    slots: u32,
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
    /// The slot the round-robin visits first.
    rr: u32,
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
            slots: core.max_warps,
            narrow: core.max_warps <= 64,
            ready: 0,
            ready_tex: 0,
            alu_left: Box::new([0; MAX_SLOTS]),
            rr: 0,
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
    /// issued (the stage's progress).
    #[inline(always)]
    pub(super) fn run(
        &mut self,
        now: u64,
        tile: &Tile,
        warps: &mut Warps,
        ldst: &mut Ldst,
        notes: &mut Notes,
    ) -> bool {
        if self.narrow {
            self.issue_with::<u64>(now, tile, warps, ldst, notes)
        } else {
            self.issue_with::<u128>(now, tile, warps, ldst, notes)
        }
    }

    /// Issue on masks of width `M` (every slot fits).
    ///
    /// The picks are found first ([`pick`], checked against its plain
    /// reference; each ALU pick counts its run down), then the ALU picks
    /// are put on the wake-up wheels as whole masks: those with more of
    /// their run to go on the ready wheel, those that ended it on the wheel
    /// that looks at them.
    #[inline(always)]
    fn issue_with<M: SlotMask>(
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
        let Picks {
            alu,
            run_end,
            tex,
            issued,
            last,
        } = pick(ready, tex_cand, self.rr, self.width, |s| {
            let left = &mut alu_left[s % MAX_SLOTS];
            *left -= 1;
            *left == 0
        });
        notes.signals.issued = issued;
        notes.signals.tex_issued = tex.is_some();
        if issued == 0 {
            return false;
        }
        self.rr = if last + 1 >= self.slots { 0 } else { last + 1 };
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

/// The picks from `ready` (ALU-ready slots) and `tex` (slots whose texture
/// instruction may enter the LDST unit; disjoint from `ready`), starting
/// at slot `rr`, at most `width` of them. `on_alu(slot)` is called for
/// each ALU pick in pick order and says whether the warp's ALU run ends
/// with this instruction.
#[inline(always)]
pub(crate) fn pick<M: SlotMask>(
    ready: M,
    tex: M,
    rr: u32,
    width: u32,
    mut on_alu: impl FnMut(usize) -> bool,
) -> Picks<M> {
    let mut rot = (ready | tex).rotate_right(rr);
    let mut p = Picks {
        alu: M::ZERO,
        run_end: M::ZERO,
        tex: None,
        issued: 0,
        last: 0,
    };
    while p.issued < width && rot != M::ZERO {
        let s = (rot.lowest() + rr as usize) & (M::BITS as usize - 1);
        rot = rot.without_lowest();
        let bit = M::bit(s);
        if ready & bit != M::ZERO {
            p.alu |= bit;
            p.run_end |= M::bit_if(s, on_alu(s));
        } else {
            p.tex = Some(s);
            rot &= ready.rotate_right(rr);
        }
        p.issued += 1;
        p.last = s as u32;
    }
    p
}

/// [`pick`] by visiting slots `rr, rr + 1, ...` (wrapping at 128) one by
/// one: the plain reference.
#[cfg(test)]
pub(crate) fn pick_plain(
    ready: u128,
    tex: u128,
    rr: u32,
    width: u32,
    mut on_alu: impl FnMut(usize) -> bool,
) -> Picks<u128> {
    let mut p = Picks {
        alu: 0,
        run_end: 0,
        tex: None,
        issued: 0,
        last: 0,
    };
    for k in 0..128 {
        if p.issued == width {
            break;
        }
        let s = ((rr as usize) + k) % 128;
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

#[cfg(test)]
mod tests {
    use super::super::testkit::{cycles, one_core, trace};
    use super::*;
    use crate::trace::Instr;
    use proptest::prelude::*;

    #[test]
    fn a_texture_pick_closes_the_door_to_others() {
        // Slots 1 and 3 wait on texture, 2 and 5 are ALU-ready; from slot 1.
        let p = pick::<u64>(0b100100, 0b1010, 1, 4, |s| s == 5);
        assert_eq!(p.tex, Some(1));
        assert_eq!((p.alu, p.run_end), (0b100100, 0b100000));
        assert_eq!((p.issued, p.last), (3, 5));
        // Width 1 from slot 4: slot 5 only.
        let p = pick::<u64>(0b100100, 0b1010, 4, 1, |_| false);
        assert_eq!((p.alu, p.tex, p.issued, p.last), (0b100000, None, 1, 5));
        // Wrapping: from slot 6 the next is slot 1 (texture), then 2.
        let p = pick::<u64>(0b100, 0b10, 6, 2, |_| false);
        assert_eq!((p.alu, p.tex, p.last), (0b100, Some(1), 2));
        assert_eq!(pick::<u64>(0, 0, 3, 4, |_| true).issued, 0);
    }

    proptest! {
        #[test]
        fn the_fast_pick_is_the_plain_one(
            n in 1usize..=128,
            ready in any::<u128>(),
            tex in any::<u128>(),
            rr in any::<u32>(),
            width in 1u32..=8,
        ) {
            let live = if n == 128 { u128::MAX } else { (1u128 << n) - 1 };
            let ready = ready & live;
            let tex = tex & live & !ready;
            let rr = rr % n as u32;
            // The callback sees the ALU picks in order; every third slot
            // ends its run.
            let mut order_plain = Vec::new();
            let want = pick_plain(ready, tex, rr, width, |s| {
                order_plain.push(s);
                s % 3 == 0
            });
            let mut order = Vec::new();
            let wide = pick::<u128>(ready, tex, rr, width, |s| {
                order.push(s);
                s % 3 == 0
            });
            prop_assert_eq!(wide, want);
            prop_assert_eq!(&order, &order_plain);
            if n <= 64 {
                let mut order = Vec::new();
                let narrow = pick::<u64>(ready as u64, tex as u64, rr, width, |s| {
                    order.push(s);
                    s % 3 == 0
                });
                prop_assert_eq!(
                    (u128::from(narrow.alu), u128::from(narrow.run_end), narrow.tex),
                    (want.alu, want.run_end, want.tex)
                );
                prop_assert_eq!((narrow.issued, narrow.last), (want.issued, want.last));
                prop_assert_eq!(&order, &order_plain);
            }
        }
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
