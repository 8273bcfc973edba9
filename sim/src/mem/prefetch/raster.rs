//! `raster`: a texture prefetcher of the literature's kind. When a quad
//! enters a core's input FIFO, the blocks of its texture instructions are
//! requested into the core's L1 through the core's bounded prefetch queue.
//!
//! Igehy, Eldridge and Proudfoot, "Prefetching in a Texture Cache
//! Architecture" (Eurographics/SIGGRAPH Workshop on Graphics Hardware,
//! 1998): texel addresses are known as soon as a fragment is rasterized,
//! so the texture cache's tags are looked up then and the misses fetched
//! while the fragment waits in a FIFO in front of the texture unit; their
//! design reaches at least 97% of a zero-latency memory. Here the FIFO the
//! fragment waits in is the core's input FIFO (up to `core.input_queue`
//! quads, the paper's queue in front of the warp launch), and the lookups
//! go through the core's L1 under the rules of every prefetch
//! (`mem/prefetch`): below demand, above the MSHR reserve, through a queue
//! of `prefetch.queue` entries that drops requests when full and, with
//! `prefetch.queue_filter`, skips blocks already queued (gem5's queued
//! prefetcher, `queue_filter`, "Don't queue redundant prefetches").
//! APOGEE (Sethia et al., PACT 2013) adapts how far ahead a GPU prefetcher
//! runs and throttles it by its measured usefulness; this prefetcher has
//! no such feedback: its distance is the input FIFO's depth, and its only
//! throttles are the queue's bound and the MSHR reserve (the run's
//! `prefetch` counters show how often each acts).
//!
//! What it needs of the trace: each texture instruction's blocks at
//! rasterization, i.e. texture coordinates that are interpolated
//! attributes. A dependent read (coordinates computed by the shader)
//! could not be requested here; traces mark none, and the model takes
//! every texture instruction as prefetchable (`tests/traces/FORMAT.md`).

use super::{PrefetchKind, PrefetchQueues, Prefetcher};
use crate::trace::Tile;

/// The raster prefetcher (its state is the per-core queues).
#[derive(Debug, Clone, Copy, Default)]
pub struct RasterPrefetcher;

impl Prefetcher for RasterPrefetcher {
    fn kind(&self) -> PrefetchKind {
        PrefetchKind::Raster
    }

    fn tile_opened(&mut self, _: usize, _: Option<usize>, _: &mut dyn PrefetchQueues) {}

    fn watches_quads(&self) -> bool {
        true
    }

    /// Every block access of the quad's texture instructions, in program
    /// order, offered to the core's queue.
    fn quad_entered(
        &mut self,
        tile: &Tile,
        quad: usize,
        core: usize,
        queues: &mut dyn PrefetchQueues,
    ) {
        let q = queues.prefetch_queue(core);
        for &b in tile.quad(quad).expect("quad in tile").block_accesses() {
            q.offer(b);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mem::prefetch::PrefetchQueue;
    use crate::trace::{Instr, Trace, TraceHeader};

    struct Queues(Vec<PrefetchQueue>);
    impl PrefetchQueues for Queues {
        fn prefetch_queue(&mut self, core: usize) -> &mut PrefetchQueue {
            &mut self.0[core]
        }
    }

    #[test]
    fn a_quad_offers_its_blocks_in_program_order_to_its_core() {
        let mut b = Trace::builder(TraceHeader::new("r", 4, 4, 4)).unwrap();
        b.begin_tile(0, 0).unwrap();
        b.quad(
            0,
            0,
            &[Instr::Tex(&[7, 3]), Instr::Alu(1), Instr::Tex(&[3, 9])],
        )
        .unwrap();
        b.quad(1, 0, &[Instr::Tex(&[1, 2, 4])]).unwrap();
        b.end_tile().unwrap();
        let t = b.finish().unwrap();
        let tile = &t.tiles()[0];
        let mut q = Queues(vec![
            PrefetchQueue::new(3, true),
            PrefetchQueue::new(3, true),
        ]);
        let mut p = RasterPrefetcher;
        p.tile_opened(0, None, &mut q);
        assert!(q.0[0].is_empty(), "nothing at tile open");
        p.quad_entered(tile, 0, 1, &mut q);
        p.quad_entered(tile, 1, 1, &mut q);
        let c = q.0[1].counts();
        // 7 3 9 queued, the second 3 skipped; 1 2 4 dropped (full).
        assert_eq!((c.generated, c.duplicates, c.dropped), (7, 1, 3));
        let mut seen = Vec::new();
        q.0[1].issue(
            |b| {
                seen.push(b);
                crate::mem::prefetch::PrefetchLookup::Hit
            },
            |_, _| {},
        );
        assert_eq!(seen, vec![7, 3, 9]);
        assert!(q.0[0].is_empty());
    }
}
