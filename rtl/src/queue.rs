//! The core's warp input queue, split into a priority FIFO and a regular
//! FIFO.
//!
//! The baseline core has one input FIFO of `capacity` warps. WaSP splits it
//! in two without adding storage: both FIFOs draw on the same `capacity`
//! slots (in hardware, one RAM with two head/tail pointer pairs and a free
//! list), so `priority + regular <= capacity` always. A push into a full
//! queue is refused (back-pressure to the rasterizer); within a class the
//! order is first in, first out.
//!
//! The baseline policy sends every warp to the regular FIFO, so the split
//! queue then behaves exactly like the single baseline FIFO.

use std::collections::VecDeque;
use wasp_waves::{Traceable, Tracer};

/// Which of the two FIFOs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum QueueClass {
    /// The priority FIFO (warps the subset comparator selected).
    Priority,
    /// The regular FIFO.
    Regular,
}

/// A split input queue of `T` (a warp ticket).
#[derive(Clone, Debug)]
pub struct SplitQueue<T> {
    priority: VecDeque<T>,
    regular: VecDeque<T>,
    capacity: usize,
}

impl<T: Copy> SplitQueue<T> {
    /// An empty queue with `capacity` shared slots.
    pub fn new(capacity: usize) -> Self {
        Self {
            priority: VecDeque::with_capacity(capacity),
            regular: VecDeque::with_capacity(capacity),
            capacity,
        }
    }

    /// Total slots (the baseline queue's size).
    pub fn capacity(&self) -> usize {
        self.capacity
    }

    /// Warps waiting in both FIFOs.
    pub fn len(&self) -> usize {
        self.priority.len() + self.regular.len()
    }

    /// Whether both FIFOs are empty.
    pub fn is_empty(&self) -> bool {
        self.priority.is_empty() && self.regular.is_empty()
    }

    /// Whether every shared slot is taken.
    pub fn is_full(&self) -> bool {
        self.len() >= self.capacity
    }

    /// Warps waiting in one FIFO.
    pub fn occupancy(&self, class: QueueClass) -> usize {
        match class {
            QueueClass::Priority => self.priority.len(),
            QueueClass::Regular => self.regular.len(),
        }
    }

    /// Whether a warp of `class` waits.
    pub fn has(&self, class: QueueClass) -> bool {
        self.occupancy(class) > 0
    }

    /// Enqueue `item` in `class`'s FIFO; `false` (and no change) if full.
    pub fn push(&mut self, class: QueueClass, item: T) -> bool {
        if self.is_full() {
            return false;
        }
        match class {
            QueueClass::Priority => self.priority.push_back(item),
            QueueClass::Regular => self.regular.push_back(item),
        }
        true
    }

    /// Dequeue the oldest warp of `class`, if any.
    pub fn pop(&mut self, class: QueueClass) -> Option<T> {
        match class {
            QueueClass::Priority => self.priority.pop_front(),
            QueueClass::Regular => self.regular.pop_front(),
        }
    }

    /// The oldest warp of `class` without removing it.
    pub fn peek(&self, class: QueueClass) -> Option<&T> {
        match class {
            QueueClass::Priority => self.priority.front(),
            QueueClass::Regular => self.regular.front(),
        }
    }

    /// Bits needed to count `0..=capacity` (width of the occupancy signals).
    pub fn occupancy_bits(&self) -> u32 {
        (usize::BITS - self.capacity.leading_zeros()).max(1)
    }
}

impl<T: Copy> Traceable for SplitQueue<T> {
    fn trace<Tr: Tracer + ?Sized>(&self, t: &mut Tr) {
        let w = self.occupancy_bits();
        t.signal("prio_queue_occupancy", w, self.priority.len() as u64);
        t.signal("regular_queue_occupancy", w, self.regular.len() as u64);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fifo_per_class_with_shared_capacity() {
        let mut q = SplitQueue::new(3);
        assert!(q.push(QueueClass::Regular, 1));
        assert!(q.push(QueueClass::Priority, 2));
        assert!(q.push(QueueClass::Regular, 3));
        assert!(q.is_full());
        assert!(!q.push(QueueClass::Priority, 4));
        assert_eq!(q.len(), 3);
        assert_eq!(q.pop(QueueClass::Regular), Some(1));
        assert_eq!(q.pop(QueueClass::Priority), Some(2));
        assert_eq!(q.pop(QueueClass::Priority), None);
        assert!(q.push(QueueClass::Priority, 4));
        assert_eq!(q.peek(QueueClass::Regular), Some(&3));
        assert_eq!(q.pop(QueueClass::Regular), Some(3));
        assert_eq!(q.pop(QueueClass::Priority), Some(4));
        assert!(q.is_empty());
    }

    #[test]
    fn occupancy_width() {
        assert_eq!(SplitQueue::<u8>::new(64).occupancy_bits(), 7);
        assert_eq!(SplitQueue::<u8>::new(63).occupancy_bits(), 6);
        assert_eq!(SplitQueue::<u8>::new(1).occupancy_bits(), 1);
        assert_eq!(SplitQueue::<u8>::new(0).occupancy_bits(), 1);
    }
}
