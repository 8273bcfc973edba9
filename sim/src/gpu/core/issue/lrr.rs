//! Loose round-robin (`core.issue = "lrr"`): starting at the slot `rr`
//! (the one after the previous issuing cycle's last pick), the slots are
//! visited in ascending order, wrapping; each candidate issues until
//! `width` instructions have issued (the stage's rules are in
//! [`super`]).
//!
//! [`pick`] is the fast form on slot masks (one rotation, then a bit scan
//! per pick); [`pick_plain`] visits the slots one by one, as the text
//! reads. The tests run both on random masks.

use super::super::mask::SlotMask;
use super::Picks;

/// Loose round-robin's state in a core: the pointer.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Lrr {
    /// The slot visited first.
    rr: u32,
    /// The core's warp slots (the pointer wraps there).
    slots: u32,
}

impl Lrr {
    /// The pointer at slot 0 of a core of `slots` warp slots.
    pub(crate) fn new(slots: usize) -> Self {
        Lrr {
            rr: 0,
            slots: slots as u32,
        }
    }

    /// This cycle's picks ([`pick`]); the pointer moves to the slot after
    /// the last one, if any issued.
    #[inline(always)]
    pub(crate) fn pick<M: SlotMask>(
        &mut self,
        ready: M,
        tex: M,
        width: u32,
        on_alu: impl FnMut(usize) -> bool,
    ) -> Picks<M> {
        let p = pick(ready, tex, self.rr, width, on_alu);
        if p.issued > 0 {
            self.rr = if p.last + 1 >= self.slots {
                0
            } else {
                p.last + 1
            };
        }
        p
    }
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
    let mut p = Picks::NONE;
    while p.issued < width && rot != M::ZERO {
        let s = (rot.lowest() + rr as usize) & (M::BITS as usize - 1);
        rot = rot.without_lowest();
        if p.take(s, ready, &mut on_alu) {
            // The texture port is taken: only ALU-ready slots remain.
            rot &= ready.rotate_right(rr);
        }
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
    on_alu: impl FnMut(usize) -> bool,
) -> Picks<u128> {
    let order = (0..128).map(|k| ((rr as usize) + k) % 128);
    super::visit_plain(order, ready, tex, width, on_alu)
}

#[cfg(test)]
mod tests {
    use super::*;
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
}
