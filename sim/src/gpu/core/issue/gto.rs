//! Greedy-then-oldest (`core.issue = "gto"`), the default warp scheduler
//! of GPGPU-Sim and Accel-Sim, on this core's one issue stage of width W.
//!
//! **Definition.** The core keeps a *greedy set* G: the slots that issued
//! in the last cycle in which any instruction issued (empty at reset; at
//! most W slots). Each cycle the issue stage visits the candidates in this
//! order:
//! 1. the candidates in G, oldest first;
//! 2. then every other candidate, oldest first;
//!
//! where a warp is older than another if it launched earlier. A core
//! launches at most one warp a cycle, so the launch cycles order its
//! resident warps totally (ties, which the core never has, go to the lower
//! slot). The stage's rules are those of every order ([`super`]): each
//! candidate in turn issues one instruction until W have issued, and only
//! the first texture candidate reached may issue. After a cycle in which
//! any instruction issued, G becomes the set of slots that issued in it;
//! after a cycle in which none did, G stays as it was.
//!
//! **Greed at width W.** GPGPU-Sim's `gto_scheduler::order_warps` calls
//! `order_by_priority(..., ORDERING_GREEDY_THEN_PRIORITY_FUNC,
//! sort_warps_by_oldest_dynamic_id)`: the warp of
//! `m_last_supervised_issued` first, then every warp sorted by its dynamic
//! warp id (a per-core launch counter, so oldest first);
//! `scheduler_unit::cycle` moves `m_last_supervised_issued` only in a
//! cycle in which a warp issued. That scheduler issues from one warp a
//! cycle; a GPGPU-Sim core of width W has W such schedulers and gives warp
//! `i` to scheduler `i mod W` (Accel-Sim's Volta configuration:
//! `-gpgpu_num_sched_per_core 4`, `-gpgpu_scheduler gto`). Here one stage
//! issues up to W warps a cycle from all slots, as its loose round-robin
//! does, so that the two orders differ in their order only: "the warp that
//! issued last" becomes the up-to-W warps of the last issuing cycle, and
//! each keeps its place at the head while it is ready. Since G holds at
//! most W slots, every ALU-ready warp of G issues again; of two texture
//! candidates in G the older goes.
//!
//! **What greed changes in this core.** A warp's instructions depend on
//! each other: it issues again `core.alu_latency` cycles after an ALU
//! instruction and only after its data after a texture one. With an ALU
//! latency above 1 a warp of G is therefore never ready in the next
//! cycle; G decides only after cycles in which nothing issued, and the
//! order is in effect oldest-first. With an ALU latency of 1, G's warps
//! run their ALU runs back to back.
//!
//! [`pick`] is the fast form on slot masks (a scan of the candidates that
//! keeps the W oldest); [`pick_plain`] sorts every slot by the definition's
//! key and visits them one by one. The tests compare them on random masks.

use super::super::mask::SlotMask;
use super::Picks;
use crate::config::limits::MAX_WIDTH;

/// Greedy-then-oldest's state in a core: the greedy set.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Gto {
    /// The slots that issued in the last cycle in which any issued.
    greedy: u128,
}

impl Gto {
    /// This cycle's picks ([`pick`]), `age(s)` being the launch cycle of
    /// the warp in slot `s`; the greedy set becomes the picks, if any.
    #[inline(always)]
    pub(crate) fn pick<M: SlotMask>(
        &mut self,
        ready: M,
        tex: M,
        width: u32,
        age: impl Fn(usize) -> u64,
        on_alu: impl FnMut(usize) -> bool,
    ) -> Picks<M> {
        let p = pick(ready, tex, M::from_wide(self.greedy), width, age, on_alu);
        if p.issued > 0 {
            self.greedy = p.slots().to_wide();
        }
        p
    }
}

/// Up to `MAX_WIDTH` slots in visiting order: ascending (age, slot).
struct Oldest {
    slot: [u8; MAX_WIDTH as usize],
    age: [u64; MAX_WIDTH as usize],
    n: usize,
}

impl Oldest {
    /// The `k` (at most `MAX_WIDTH`) oldest slots of `m`, oldest first.
    #[inline(always)]
    fn of<M: SlotMask>(mut m: M, k: usize, age: &impl Fn(usize) -> u64) -> Self {
        let mut o = Oldest {
            slot: [0; MAX_WIDTH as usize],
            age: [0; MAX_WIDTH as usize],
            n: 0,
        };
        if k == 0 {
            return o;
        }
        while m != M::ZERO {
            let s = m.lowest();
            m = m.without_lowest();
            let a = age(s);
            if o.n == k {
                // Slots come in ascending order: an equal age loses.
                if a >= o.age[k - 1] {
                    continue;
                }
                o.n -= 1;
            }
            let mut i = o.n;
            while i > 0 && o.age[i - 1] > a {
                o.age[i] = o.age[i - 1];
                o.slot[i] = o.slot[i - 1];
                i -= 1;
            }
            o.age[i] = a;
            o.slot[i] = s as u8;
            o.n += 1;
        }
        o
    }
}

/// The oldest slot of the non-empty set `m` (the lower slot on a tie).
#[inline(always)]
fn oldest<M: SlotMask>(m: M, age: &impl Fn(usize) -> u64) -> usize {
    let o = Oldest::of(m, 1, age);
    o.slot[0] as usize
}

/// The picks from `ready` (ALU-ready slots) and `tex` (slots whose texture
/// instruction may enter the LDST unit; disjoint from `ready`), the
/// greedy set `greedy` first, at most `width` (<= `MAX_WIDTH`) of them;
/// `age(s)` orders the slots (smaller: older). `on_alu(slot)` is called
/// for each ALU pick in visiting order and says whether the warp's ALU run
/// ends with this instruction.
#[inline(always)]
pub(crate) fn pick<M: SlotMask>(
    ready: M,
    tex: M,
    greedy: M,
    width: u32,
    age: impl Fn(usize) -> u64,
    mut on_alu: impl FnMut(usize) -> bool,
) -> Picks<M> {
    debug_assert!(width <= MAX_WIDTH);
    // Only the first texture candidate in the visiting order can issue.
    let tex_greedy = tex & greedy;
    let cand = if tex_greedy != M::ZERO {
        ready | M::bit(oldest(tex_greedy, &age))
    } else if tex != M::ZERO {
        ready | M::bit(oldest(tex, &age))
    } else {
        ready
    };
    let mut p = Picks::NONE;
    for part in [cand & greedy, cand & !greedy] {
        let o = Oldest::of(part, (width - p.issued) as usize, &age);
        for &s in &o.slot[..o.n] {
            p.take(s as usize, ready, &mut on_alu);
        }
    }
    p
}

/// [`pick`] by sorting the 128 slots by (not greedy, age, slot) and
/// visiting them one by one: the plain reference.
#[cfg(test)]
pub(crate) fn pick_plain(
    ready: u128,
    tex: u128,
    greedy: u128,
    width: u32,
    age: impl Fn(usize) -> u64,
    on_alu: impl FnMut(usize) -> bool,
) -> Picks<u128> {
    let mut order: Vec<usize> = (0..128).collect();
    order.sort_by_key(|&s| (greedy >> s & 1 == 0, age(s), s));
    super::visit_plain(order, ready, tex, width, on_alu)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Slot s launched at cycle `launch[s]`.
    fn ages(launch: &[u64]) -> impl Fn(usize) -> u64 + '_ {
        move |s| launch.get(s).copied().unwrap_or(u64::MAX)
    }

    #[test]
    fn greedy_warps_first_then_the_oldest() {
        // Slots 0..6 launched at 50, 10, 40, 20, 30, 60.
        let launch = [50, 10, 40, 20, 30, 60];
        let age = ages(&launch);
        // All ALU-ready, none greedy: the oldest two, 1 then 3.
        let p = pick::<u64>(0b111111, 0, 0, 2, &age, |_| false);
        assert_eq!((p.alu, p.issued, p.last), (0b1010, 2, 3));
        // Slot 5 (the youngest) greedy: it first, then the oldest, 1.
        let p = pick::<u64>(0b111111, 0, 0b100000, 2, &age, |_| false);
        assert_eq!((p.alu, p.last), (0b100010, 1));
        // A greedy slot that is not ready takes no port.
        let p = pick::<u64>(0b011111, 0, 0b100000, 2, &age, |_| false);
        assert_eq!(p.alu, 0b1010);
        assert_eq!(pick::<u64>(0, 0, 0b1, 4, &age, |_| true).issued, 0);
    }

    #[test]
    fn one_texture_pick_the_first_in_order() {
        let launch = [50, 10, 40, 20, 30, 60];
        let age = ages(&launch);
        // 1 and 3 wait on texture, 0, 2 and 4 are ALU-ready: 1 goes (the
        // oldest), 3 is passed over, then 4, 2 and 0 by age.
        let p = pick::<u64>(0b10101, 0b1010, 0, 4, &age, |s| s == 4);
        assert_eq!(p.tex, Some(1));
        assert_eq!(
            (p.alu, p.run_end, p.issued, p.last),
            (0b10101, 0b10000, 4, 0)
        );
        // Greedy texture candidates go before older ones outside G, and
        // among themselves by age: 3 (launched 20) before 5 (60).
        let p = pick::<u64>(0, 0b101010, 0b101000, 4, &age, |_| false);
        assert_eq!((p.tex, p.issued), (Some(3), 1));
        // The ALU callback sees the picks in visiting order.
        let mut seen = vec![];
        pick::<u64>(0b111111, 0, 0b1, 6, &age, |s| {
            seen.push(s);
            false
        });
        assert_eq!(seen, [0, 1, 3, 4, 2, 5]);
    }

    #[test]
    fn the_greedy_set_follows_the_issuing_cycles() {
        let launch = [3, 1, 2];
        let age = ages(&launch);
        let mut g = Gto::default();
        let p = g.pick::<u64>(0b111, 0, 2, &age, |_| false);
        assert_eq!(p.alu, 0b110);
        assert_eq!(g.greedy, 0b110);
        // Nothing issues: the set stays.
        g.pick::<u64>(0, 0, 2, &age, |_| false);
        assert_eq!(g.greedy, 0b110);
        // Slot 0 alone issues (a texture instruction): it is the set.
        let p = g.pick::<u64>(0, 0b1, 2, &age, |_| false);
        assert_eq!(p.tex, Some(0));
        assert_eq!(g.greedy, 0b1);
    }

    proptest! {
        #[test]
        fn the_fast_pick_is_the_plain_one(
            n in 1usize..=128,
            ready in any::<u128>(),
            tex in any::<u128>(),
            greedy in any::<u128>(),
            sparse_greedy in any::<bool>(),
            launch in prop::collection::vec(0u64..200, 128),
            width in 1u32..=MAX_WIDTH,
        ) {
            let live = if n == 128 { u128::MAX } else { (1u128 << n) - 1 };
            let ready = ready & live;
            let tex = tex & live & !ready;
            // The core's greedy set holds at most W slots; any set is
            // defined, so both kinds are drawn.
            let greedy = if sparse_greedy {
                greedy & greedy.rotate_left(37) & greedy.rotate_left(71) & live
            } else {
                greedy
            };
            // Ages drawn from a small range, so that ties occur.
            let age = ages(&launch);
            let mut order_plain = Vec::new();
            let want = pick_plain(ready, tex, greedy, width, &age, |s| {
                order_plain.push(s);
                s % 3 == 0
            });
            let mut order = Vec::new();
            let wide = pick::<u128>(ready, tex, greedy, width, &age, |s| {
                order.push(s);
                s % 3 == 0
            });
            prop_assert_eq!(wide, want);
            prop_assert_eq!(&order, &order_plain);
            if n <= 64 {
                let mut order = Vec::new();
                let narrow = pick::<u64>(
                    ready as u64, tex as u64, greedy as u64, width, &age,
                    |s| {
                        order.push(s);
                        s % 3 == 0
                    },
                );
                prop_assert_eq!(
                    (u128::from(narrow.alu), u128::from(narrow.run_end), narrow.tex),
                    (want.alu, want.run_end, want.tex)
                );
                prop_assert_eq!((narrow.issued, narrow.last), (want.issued, want.last));
                prop_assert_eq!(&order, &order_plain);
            }
        }
    }
}
