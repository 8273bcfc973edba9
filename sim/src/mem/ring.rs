//! A FIFO of `Copy` items in a ring buffer of power-of-two capacity: the
//! queues between the levels of the hierarchy and in the DRAM.
//!
//! Like a `VecDeque` restricted to `push_back` / `front` / `pop_front`, with
//! cheaper index arithmetic (a mask instead of a wrap test). Created at the
//! queue's bound, it never allocates in steady state; a push beyond the
//! capacity doubles it (never expected, but never a failure).

/// A FIFO ring buffer.
#[derive(Debug, Clone)]
pub(crate) struct Ring<T> {
    /// Storage; its length is a power of two.
    buf: Box<[T]>,
    /// Index of the front item in `buf`.
    head: usize,
    len: usize,
}

impl<T: Copy + Default> Ring<T> {
    /// An empty ring holding at least `n` items before it grows.
    pub(crate) fn with_capacity(n: usize) -> Self {
        Ring {
            buf: vec![T::default(); n.max(1).next_power_of_two()].into(),
            head: 0,
            len: 0,
        }
    }

    /// Items queued.
    #[inline]
    pub(crate) fn len(&self) -> usize {
        self.len
    }

    /// Nothing queued.
    #[inline]
    pub(crate) fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The oldest item.
    #[inline]
    pub(crate) fn front(&self) -> Option<&T> {
        if self.len == 0 {
            None
        } else {
            Some(&self.buf[self.head])
        }
    }

    /// The newest item.
    #[inline]
    pub(crate) fn back(&self) -> Option<&T> {
        if self.len == 0 {
            None
        } else {
            Some(&self.buf[(self.head + self.len - 1) & (self.buf.len() - 1)])
        }
    }

    /// Append `x`.
    #[inline]
    pub(crate) fn push_back(&mut self, x: T) {
        if self.len == self.buf.len() {
            self.grow();
        }
        let i = (self.head + self.len) & (self.buf.len() - 1);
        self.buf[i] = x;
        self.len += 1;
    }

    /// Remove and return the oldest item.
    #[inline]
    pub(crate) fn pop_front(&mut self) -> Option<T> {
        if self.len == 0 {
            return None;
        }
        let x = self.buf[self.head];
        self.head = (self.head + 1) & (self.buf.len() - 1);
        self.len -= 1;
        Some(x)
    }

    /// Remove and return the oldest item if `due` holds for it.
    #[inline(always)]
    pub(crate) fn pop_front_if(&mut self, due: impl FnOnce(&T) -> bool) -> Option<T> {
        if self.len == 0 {
            return None;
        }
        let x = self.buf[self.head];
        if !due(&x) {
            return None;
        }
        self.drop_front();
        Some(x)
    }

    /// Remove the oldest item, which the caller has seen through
    /// [`Ring::front`] (the ring is not empty).
    #[inline(always)]
    pub(crate) fn drop_front(&mut self) {
        debug_assert!(self.len > 0, "drop_front of an empty ring");
        self.head = (self.head + 1) & (self.buf.len() - 1);
        self.len -= 1;
    }

    /// Double the capacity, keeping the order.
    #[cold]
    #[inline(never)]
    fn grow(&mut self) {
        let n = self.buf.len();
        let mut buf = vec![T::default(); 2 * n];
        for (k, slot) in buf.iter_mut().take(self.len).enumerate() {
            *slot = self.buf[(self.head + k) & (n - 1)];
        }
        self.buf = buf.into();
        self.head = 0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::VecDeque;

    #[test]
    fn behaves_like_a_vecdeque_through_wraps_and_growth() {
        let mut r: Ring<u32> = Ring::with_capacity(3);
        let mut d: VecDeque<u32> = VecDeque::new();
        let mut rng = crate::rng::Rng::new(12345);
        for i in 0..5000u32 {
            let x = rng.next_u64() as u32;
            // Mostly balanced, with bursts that force growth.
            let pushes = if i % 500 == 0 { 9 } else { x % 3 };
            for k in 0..pushes {
                r.push_back(i * 10 + k);
                d.push_back(i * 10 + k);
            }
            for j in 0..(x >> 8) % 3 {
                match (x >> 12).wrapping_add(j) % 3 {
                    0 => assert_eq!(r.pop_front(), d.pop_front()),
                    1 => {
                        // Pops only even items.
                        let want = d.front().filter(|&&v| v % 2 == 0).copied();
                        if want.is_some() {
                            d.pop_front();
                        }
                        assert_eq!(r.pop_front_if(|&v| v % 2 == 0), want);
                    }
                    _ => {
                        if d.pop_front().is_some() {
                            r.drop_front();
                        }
                    }
                }
            }
            assert_eq!(r.front(), d.front());
            assert_eq!(r.back(), d.back());
            assert_eq!((r.len(), r.is_empty()), (d.len(), d.is_empty()));
        }
        while let Some(v) = d.pop_front() {
            assert_eq!(r.pop_front(), Some(v));
        }
        assert_eq!(r.pop_front(), None);
        assert!(r.buf.len() > 4, "the bursts made it grow");
    }

    #[test]
    fn capacity_is_the_next_power_of_two() {
        assert_eq!(Ring::<u8>::with_capacity(0).buf.len(), 1);
        assert_eq!(Ring::<u8>::with_capacity(16).buf.len(), 16);
        assert_eq!(Ring::<u8>::with_capacity(17).buf.len(), 32);
    }
}
