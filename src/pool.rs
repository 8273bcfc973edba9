//! The CLI's one worker pool: scoped threads that take the indices of a
//! list of jobs in order and hand back every job's result in index order
//! (`compare`'s runs, the study runner's tasks). A job's result does not
//! depend on the thread that ran it, so the output is the same for any
//! thread count.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// Run `work(i)` for every `i` in `0..n` on at most `threads` threads (at
/// least one), the indices taken in increasing order; the results in index
/// order.
pub fn run_indexed<R: Send>(n: usize, threads: usize, work: impl Fn(usize) -> R + Sync) -> Vec<R> {
    let next = AtomicUsize::new(0);
    let slots: Mutex<Vec<Option<R>>> = Mutex::new((0..n).map(|_| None).collect());
    std::thread::scope(|s| {
        for _ in 0..threads.clamp(1, n.max(1)) {
            s.spawn(|| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                if i >= n {
                    break;
                }
                let r = work(i);
                slots.lock().expect("lock")[i] = Some(r);
            });
        }
    });
    slots
        .into_inner()
        .expect("lock")
        .into_iter()
        .map(|r| r.expect("every index ran"))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_index_runs_once_and_results_come_back_in_order() {
        for threads in [0, 1, 2, 7] {
            let calls = AtomicUsize::new(0);
            let out = run_indexed(25, threads, |i| {
                calls.fetch_add(1, Ordering::Relaxed);
                i * i
            });
            assert_eq!(out, (0..25).map(|i| i * i).collect::<Vec<_>>());
            assert_eq!(calls.load(Ordering::Relaxed), 25);
        }
        assert!(run_indexed(0, 2, |i| i).is_empty());
    }
}
