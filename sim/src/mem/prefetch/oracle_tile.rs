//! `oracle-tile`: the bound of "launch early to prefetch". When a tile
//! opens, every distinct texture block the tile will touch is requested
//! for the cores that will touch it, in the order of first use in
//! rasterization order (the tile's quads in trace order, each quad's
//! blocks in program order).
//!
//! - Shared-tile dispatch: when the tile fetcher opens the tile, each core
//!   gets the blocks of the quads the core map sends it.
//! - Per-core-tile dispatch: the core that takes the tile gets all of its
//!   blocks.
//!
//! The requests go through the core's prefetch queue into its L1, the L2
//! and DRAM, under the rules every prefetch obeys (`mem/prefetch`): the
//! ports demand leaves, the L1 MSHRs above the demand reserve, the L2's
//! MSHRs, the DRAM's banks and buses. It is not free memory (ideal memory
//! is that bound). A list still queued when the core's next tile opens is
//! cancelled: its tile has ended.
//!
//! The lists are made once, when the GPU is built, not in the cycle loop.
//! Hardware would need the whole list of a tile, the trace's knowledge,
//! before the tile's first quad is shaded: no rasterizer has it, so this
//! is a bound, not a design (`prefetch/cost.rs` prices its storage).

use super::{PrefetchKind, PrefetchQueues, Prefetcher};
use crate::trace::{Tile, Trace};
use std::collections::HashSet;

/// The per-tile, per-core block lists.
#[derive(Debug)]
pub struct OracleTile {
    /// Lists per tile: one per core under shared-tile dispatch, one per
    /// tile under per-core-tile dispatch.
    per_tile: usize,
    /// `(start, len)` in `blocks` of list `tile * per_tile + core`.
    lists: Vec<(u32, u32)>,
    /// Every list, one after the other.
    blocks: Vec<u64>,
    /// The longest list.
    longest: usize,
}

impl OracleTile {
    /// The lists of `trace` for `cores` cores; `core_of(x, y)` names the
    /// core of in-tile quad (x, y) under shared-tile dispatch, `None`
    /// under per-core-tile dispatch.
    pub fn new(trace: &Trace, cores: usize, core_of: Option<&dyn Fn(u32, u32) -> usize>) -> Self {
        let per_tile = if core_of.is_some() { cores } else { 1 };
        let mut lists = Vec::with_capacity(trace.tiles().len() * per_tile);
        let mut blocks = Vec::new();
        let mut seen: Vec<HashSet<u64>> = vec![HashSet::new(); per_tile];
        let mut per_core: Vec<Vec<u64>> = vec![Vec::new(); per_tile];
        let mut longest = 0;
        for tile in trace.tiles() {
            first_uses(tile, core_of, &mut seen, &mut per_core);
            for list in &mut per_core {
                lists.push((blocks.len() as u32, list.len() as u32));
                longest = longest.max(list.len());
                blocks.append(list);
            }
        }
        OracleTile {
            per_tile,
            lists,
            blocks,
            longest,
        }
    }

    /// The list of tile `tile` for core `core` (under per-core-tile
    /// dispatch, the tile's one list whatever `core`).
    pub fn list(&self, tile: usize, core: usize) -> &[u64] {
        let k = if self.per_tile == 1 { 0 } else { core };
        let (start, len) = self.lists[tile * self.per_tile + k];
        &self.blocks[start as usize..(start + len) as usize]
    }

    /// The most requests one list holds: the storage a core's list needs
    /// on this trace.
    pub fn longest(&self) -> usize {
        self.longest
    }
}

/// The distinct blocks of `tile` in order of first use, per core
/// (`core_of`) or in one list, into `out` (emptied lists in, `seen` the
/// per-list sets, cleared here).
fn first_uses(
    tile: &Tile,
    core_of: Option<&dyn Fn(u32, u32) -> usize>,
    seen: &mut [HashSet<u64>],
    out: &mut [Vec<u64>],
) {
    for s in seen.iter_mut() {
        s.clear();
    }
    for q in tile.quads() {
        let k = core_of.map_or(0, |f| f(q.x(), q.y()));
        for &b in q.block_accesses() {
            if seen[k].insert(b) {
                out[k].push(b);
            }
        }
    }
}

impl Prefetcher for OracleTile {
    fn kind(&self) -> PrefetchKind {
        PrefetchKind::OracleTile
    }

    fn tile_opened(&mut self, tile: usize, core: Option<usize>, queues: &mut dyn PrefetchQueues) {
        match core {
            Some(c) => {
                let q = queues.prefetch_queue(c);
                q.reserve(self.longest);
                q.replace(self.list(tile, c));
            }
            None => {
                for c in 0..self.per_tile {
                    let q = queues.prefetch_queue(c);
                    q.reserve(self.longest);
                    q.replace(self.list(tile, c));
                }
            }
        }
    }

    fn watches_quads(&self) -> bool {
        false
    }

    fn quad_entered(&mut self, _: &Tile, _: usize, _: usize, _: &mut dyn PrefetchQueues) {}
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mem::prefetch::PrefetchQueue;
    use crate::trace::{Instr, TraceHeader};

    /// Two 4x4-pixel tiles (2x2 quads); quads at x = 0 go to core 0,
    /// x = 1 to core 1.
    fn trace() -> Trace {
        let mut b = Trace::builder(TraceHeader::new("o", 8, 4, 4)).unwrap();
        b.begin_tile(0, 0).unwrap();
        b.quad(
            1,
            0,
            &[Instr::Tex(&[30, 10]), Instr::Alu(2), Instr::Tex(&[40])],
        )
        .unwrap();
        b.quad(0, 0, &[Instr::Tex(&[10, 20])]).unwrap();
        b.rejected(2).unwrap();
        b.quad(0, 1, &[Instr::Tex(&[20]), Instr::TriTex(&[5, 10])])
            .unwrap();
        b.quad(1, 1, &[Instr::Tex(&[40, 30])]).unwrap();
        b.end_tile().unwrap();
        b.begin_tile(1, 0).unwrap();
        b.quad(0, 0, &[Instr::Alu(3)]).unwrap();
        b.end_tile().unwrap();
        b.finish().unwrap()
    }

    struct Queues(Vec<PrefetchQueue>);
    impl PrefetchQueues for Queues {
        fn prefetch_queue(&mut self, core: usize) -> &mut PrefetchQueue {
            &mut self.0[core]
        }
    }

    #[test]
    fn lists_hold_each_block_once_in_order_of_first_use_per_core() {
        let t = trace();
        let by_x = |x: u32, _y: u32| x as usize;
        let o = OracleTile::new(&t, 2, Some(&by_x));
        assert_eq!(o.list(0, 0), &[10, 20, 5]);
        assert_eq!(o.list(0, 1), &[30, 10, 40]);
        assert_eq!(o.list(1, 0), &[] as &[u64]);
        assert_eq!(o.longest(), 3);
        // One list per tile under per-core-tile dispatch.
        let o = OracleTile::new(&t, 2, None);
        assert_eq!(o.list(0, 1), &[30, 10, 40, 20, 5]);
        assert_eq!(o.list(0, 0), o.list(0, 1));
        assert_eq!(o.longest(), 5);
    }

    #[test]
    fn a_tile_opening_replaces_each_cores_list() {
        let t = trace();
        let by_x = |x: u32, _y: u32| x as usize;
        let mut o = OracleTile::new(&t, 2, Some(&by_x));
        let mut q = Queues(vec![
            PrefetchQueue::new(1, true),
            PrefetchQueue::new(1, true),
        ]);
        o.tile_opened(0, None, &mut q);
        assert_eq!((q.0[0].len(), q.0[1].len()), (3, 3), "no queue bound");
        o.tile_opened(1, None, &mut q);
        assert!(q.0[0].is_empty() && q.0[1].is_empty());
        assert_eq!(q.0[0].counts().cancelled, 3);
        assert_eq!(q.0[1].counts().generated, 3);
        // Per-core-tile: only the core that took the tile.
        let mut o = OracleTile::new(&t, 2, None);
        o.tile_opened(0, Some(1), &mut q);
        assert_eq!((q.0[0].len(), q.0[1].len()), (0, 5));
    }
}
