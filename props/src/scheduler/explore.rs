//! Exhaustive exploration of the scheduler against its model: every
//! sequence of choices from a small alphabet up to a depth.

use super::{CycleChoice, SchedConfig, SchedulerCheck};
use wasp_rtl::queue::QueueClass;

/// Per-cycle input alphabet of [`explore_wasp`]: enqueue nothing, a
/// priority quad (0, 0) or a regular quad (1, 0) (under Mesh4); enable or
/// not; each event count 0 or 1 (reduced to legal values).
pub fn small_alphabet() -> Vec<CycleChoice> {
    let mut v = Vec::new();
    for enqueue in [None, Some((0, 0)), Some((1, 0))] {
        for enable in [false, true] {
            for bits in 0u8..32 {
                let b = |i: u8| (bits >> i) & 1;
                v.push(CycleChoice {
                    enqueue,
                    enable,
                    allocs: b(0),
                    replies: b(1),
                    blocked: b(2),
                    unblocked: b(3),
                    finished: b(4),
                    regular_finished: 0,
                });
            }
        }
    }
    v
}

/// Statistics of an exploration.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Explored {
    /// Distinct states reached (including reset).
    pub states: usize,
    /// Transitions checked.
    pub transitions: u64,
    /// Priority launches seen.
    pub priority_launches: u64,
    /// Cycles where a priority warp waited but WaSP chose otherwise.
    pub priority_held_back: u64,
}

/// Every input sequence of length up to `depth` over `alphabet`, from
/// reset, explored breadth-first as a state graph: two runs that reach the
/// same [`Model::key`](super::Model::key) are merged. This is sound because, with the model
/// equal to the scheduler (checked every cycle), the key fixes everything
/// that later cycles depend on: the FIFO lengths (tickets are opaque to the
/// scheduler), the free-MSHR register, the non-blocked counter, the
/// blocked warps; the per-cycle launch and decision signals are cleared by
/// `end_cycle`/`decide`. Regular warps in the core only gate `enable`, and
/// with `max_warps` above `depth` they never do (asserted). The scheduler is
/// not `Clone`, so each state is re-reached by replaying its shortest path.
pub fn explore_wasp(
    cfg: &SchedConfig,
    alphabet: &[CycleChoice],
    depth: usize,
) -> Result<Explored, String> {
    use std::collections::HashSet;
    if cfg.max_warps as usize <= depth {
        return Err("max_warps must exceed the depth".into());
    }
    let fresh = || SchedulerCheck::new(cfg);
    let start = fresh()?;
    let mut seen = HashSet::new();
    seen.insert(start.model.key());
    let mut frontier: Vec<Vec<usize>> = vec![Vec::new()];
    let mut stats = Explored::default();
    for _ in 0..depth {
        let mut next = Vec::new();
        for path in &frontier {
            for (i, choice) in alphabet.iter().enumerate() {
                let mut s = fresh()?;
                for &p in path {
                    s.cycle(&alphabet[p]).map_err(|c| c.to_string())?;
                }
                let pw = !s.model.priority.is_empty();
                let launched = s
                    .cycle(choice)
                    .map_err(|c| format!("{c}\npath: {:?}", trace(alphabet, path, i)))?;
                stats.transitions += 1;
                match launched.warp {
                    Some((_, QueueClass::Priority)) => stats.priority_launches += 1,
                    _ if pw && choice.enable => stats.priority_held_back += 1,
                    _ => {}
                }
                if s.model.in_core() >= s.model.max_warps {
                    return Err("core filled up: the key would be unsound".into());
                }
                if seen.insert(s.model.key()) {
                    let mut p = path.clone();
                    p.push(i);
                    next.push(p);
                }
            }
        }
        frontier = next;
    }
    stats.states = seen.len();
    Ok(stats)
}

fn trace(alphabet: &[CycleChoice], path: &[usize], last: usize) -> Vec<CycleChoice> {
    path.iter()
        .chain(std::iter::once(&last))
        .map(|&i| alphabet[i])
        .collect()
}
