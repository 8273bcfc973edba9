//! Workload characterisation: the statistics of the paper's Table I and
//! Section III-B, per tile and per trace.
//!
//! Definitions (a warp is a quad record of the trace: one shaded
//! (primitive, quad) fragment, so with overdraw several warps share a quad
//! position; a block is a 64-byte memory block; all block counts are per
//! tile, a block touched in two tiles counts in both):
//!
//! * **positions** of a tile = distinct quad positions its warps occupy;
//!   **warps per position** = warps / positions (the overdraw the cores
//!   see; 1 for a version-1 trace).
//! * **memory-instruction ratio** = texture instructions / all instructions
//!   (ALU runs counted by length). Table I's "Memory-Instr ratio".
//! * **warp blocks** of a tile = sum over its warps of the number of distinct
//!   blocks the warp touches = the number of distinct (warp, block) pairs.
//! * **unique blocks** of a tile = distinct blocks any of its warps touch
//!   (the tile's texture footprint).
//! * **memory-block reuse in tile** = warp blocks / unique blocks: how many
//!   warps touch each unique block of the tile, on average. Table I's
//!   "Memory Block reuse in tile".
//! * **CF** = warp blocks / warps: distinct blocks per warp, on average.
//! * **Min_Estimate1** = unique blocks / warps (Section III-B).
//! * **Min_Estimate2** = Min_Estimate1 / CF (Section III-B). Per tile this
//!   equals 1 / reuse.
//! * **texture footprint ratio** of a subset of a tile's warps = distinct
//!   blocks the subset touches / unique blocks of the tile (Section III-B).
//!   A priority subset selects quad *positions*, so it selects every warp
//!   (fragment) at a selected position.
//!
//! * **trilinear texture instructions** = texture instructions written `T`
//!   (format 4): their sample filters two mip levels. A trace of an older
//!   version has none (every texture instruction taken as bilinear).
//!   **trilinear share** = trilinear / all texture instructions.
//!
//! * **rejected quads** = quads Early-Z rejected (the trace's `z` lines);
//!   warps + rejected quads are the quads the rasterizer produced.
//!
//! A ratio whose denominator is zero is 0, except the footprint ratio of a
//! tile without blocks, which is 1 (the empty footprint is fully covered).
//! So a tile without warps (format 3 or 4: every quad it rasterized Early-Z
//! rejected) has every ratio 0 and footprint ratio 1, never NaN.
//!
//! Over a trace: the memory-instruction ratio pools all instructions (sum of
//! texture instructions / sum of instructions). CF and Min_Estimate1 are the
//! means over tiles weighted by warps, which equal the pooled ratios (sum of
//! warp blocks / sum of warps, sum of unique blocks / sum of warps). Reuse is
//! the mean over tiles weighted by warps, over tiles that touch at least one
//! block. Min_Estimate2 is the trace's Min_Estimate1 / the trace's CF, as in
//! the paper, which divides by one CF for all tiles.
//!
//! Tiles without warps are left out of every per-tile mean: warps per tile
//! divides by the tiles with at least one warp, and the warp-weighted means
//! (CF, Min_Estimate1, reuse, [`mean_footprint_ratio`]) give them weight 0
//! (they touch no block either).

use super::{Tile, Trace, TraceHeader};
use serde::Serialize;

/// Statistics of one tile. Counts are exact; the ratios are methods.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct TileStats {
    /// Tile column.
    pub tx: u32,
    /// Tile row.
    pub ty: u32,
    /// Quads (warps); 0 for a tile whose every quad Early-Z rejected.
    pub warps: u64,
    /// Quads Early-Z rejected.
    pub rejected_quads: u64,
    /// Distinct quad positions of the warps.
    pub positions: u64,
    /// Instructions, ALU runs counted by length.
    pub instrs: u64,
    /// Texture instructions.
    pub tex_instrs: u64,
    /// Of those, trilinear ones (`T`).
    pub tri_tex_instrs: u64,
    /// Block accesses: blocks listed over all texture instructions.
    pub block_accesses: u64,
    /// Distinct (warp, block) pairs.
    pub warp_blocks: u64,
    /// Distinct blocks of the tile.
    pub unique_blocks: u64,
}

fn ratio(num: f64, den: f64) -> f64 {
    if den == 0.0 {
        0.0
    } else {
        num / den
    }
}

impl TileStats {
    pub(super) fn of(tile: &Tile) -> TileStats {
        Self::with_unique(tile, &tile.unique_blocks_counted())
    }

    /// The statistics of `tile`, whose distinct blocks are `unique`.
    fn with_unique(tile: &Tile, unique: &[u64]) -> TileStats {
        let mut buf = Vec::new();
        let mut warp_blocks = 0u64;
        let mut instrs = 0u64;
        let mut tex = 0u64;
        let mut tri = 0u64;
        for q in tile.quads() {
            buf.clear();
            buf.extend_from_slice(q.block_accesses());
            buf.sort_unstable();
            buf.dedup();
            warp_blocks += buf.len() as u64;
            instrs += q.instr_count();
            tex += q.tex_count() as u64;
            tri += q.trilinear_count() as u64;
        }
        TileStats {
            tx: tile.tx(),
            ty: tile.ty(),
            warps: tile.quad_count() as u64,
            rejected_quads: tile.rejected_count(),
            positions: tile.position_count() as u64,
            instrs,
            tex_instrs: tex,
            tri_tex_instrs: tri,
            block_accesses: tile.block_accesses().len() as u64,
            warp_blocks,
            unique_blocks: unique.len() as u64,
        }
    }

    /// Texture instructions / instructions.
    pub fn mem_instr_ratio(&self) -> f64 {
        ratio(self.tex_instrs as f64, self.instrs as f64)
    }

    /// Memory-block reuse in tile: warp blocks / unique blocks.
    pub fn reuse(&self) -> f64 {
        ratio(self.warp_blocks as f64, self.unique_blocks as f64)
    }

    /// CF: distinct blocks per warp, warp blocks / warps.
    pub fn cf(&self) -> f64 {
        ratio(self.warp_blocks as f64, self.warps as f64)
    }

    /// Min_Estimate1: unique blocks / warps.
    pub fn min_estimate1(&self) -> f64 {
        ratio(self.unique_blocks as f64, self.warps as f64)
    }

    /// Min_Estimate2: Min_Estimate1 / CF.
    pub fn min_estimate2(&self) -> f64 {
        ratio(self.min_estimate1(), self.cf())
    }
}

/// Statistics of a whole trace (definitions in the module documentation).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TraceStats {
    /// The workload name, so a report always says what it ran on.
    pub workload: String,
    /// Tile records.
    pub tiles: u64,
    /// Tile records with at least one warp (the others hold only quads
    /// Early-Z rejected).
    pub warp_tiles: u64,
    /// Quads (warps).
    pub warps: u64,
    /// Quads Early-Z rejected (0 for a version-1 or version-2 trace).
    pub rejected_quads: u64,
    /// Sum over tiles of the distinct quad positions of their warps.
    pub positions: u64,
    /// warps / positions: fragments shaded per covered quad position.
    pub warps_per_position: f64,
    /// Quads the frame could shade (top-left pixel inside the frame).
    pub frame_quads: u64,
    /// positions / frame_quads: the fraction of the frame's quad
    /// positions shaded at least once.
    pub coverage: f64,
    /// warps / warp_tiles: the mean over tiles with at least one warp.
    pub warps_per_tile: f64,
    /// Instructions, ALU runs counted by length.
    pub instrs: u64,
    /// Texture instructions.
    pub tex_instrs: u64,
    /// Of those, trilinear ones (`T`; 0 before format 4).
    pub tri_tex_instrs: u64,
    /// tri_tex_instrs / tex_instrs: the trilinear share.
    pub trilinear_share: f64,
    /// instrs / warps.
    pub instrs_per_warp: f64,
    /// Block accesses over all texture instructions.
    pub block_accesses: u64,
    /// Sum over tiles of distinct (warp, block) pairs.
    pub warp_blocks: u64,
    /// Sum over tiles of unique blocks per tile.
    pub tile_unique_blocks: u64,
    /// Distinct blocks of the whole frame.
    pub frame_unique_blocks: u64,
    /// Texture instructions / instructions.
    pub mem_instr_ratio: f64,
    /// Memory-block reuse in tile, mean over tiles weighted by warps.
    pub reuse: f64,
    /// Distinct blocks per warp.
    pub cf: f64,
    /// Unique blocks per tile / warps per tile, warp-weighted.
    pub min_estimate1: f64,
    /// min_estimate1 / cf.
    pub min_estimate2: f64,
}

impl TraceStats {
    /// The statistics of `tiles`, `frames` frames of the trace with header
    /// `header` (every frame's quad positions count in `frame_quads`).
    fn of(header: &TraceHeader, tiles: &[Tile], frames: usize) -> TraceStats {
        // Each tile's distinct blocks serve its own statistics and, merged,
        // the frame's distinct blocks (far fewer than its block accesses).
        let mut all: Vec<u64> = Vec::new();
        let tiles: Vec<TileStats> = tiles
            .iter()
            .map(|t| {
                let unique = t.unique_blocks_counted();
                all.extend_from_slice(&unique);
                TileStats::with_unique(t, &unique)
            })
            .collect();
        let sum = |f: fn(&TileStats) -> u64| tiles.iter().map(f).sum::<u64>();
        let warps = sum(|t| t.warps);
        let warp_tiles = tiles.iter().filter(|t| t.warps > 0).count() as u64;
        let positions = sum(|t| t.positions);
        let instrs = sum(|t| t.instrs);
        let tex = sum(|t| t.tex_instrs);
        let tri = sum(|t| t.tri_tex_instrs);
        let warp_blocks = sum(|t| t.warp_blocks);
        let unique = sum(|t| t.unique_blocks);
        let (mut reuse_num, mut reuse_den) = (0.0, 0.0);
        // (A tile without warps touches no block.)
        for t in tiles.iter().filter(|t| t.unique_blocks > 0) {
            reuse_num += t.warps as f64 * t.reuse();
            reuse_den += t.warps as f64;
        }
        all.sort_unstable();
        all.dedup();
        let frame_quads = header.frame_quads() * frames as u64;
        let cf = ratio(warp_blocks as f64, warps as f64);
        let min_estimate1 = ratio(unique as f64, warps as f64);
        TraceStats {
            workload: header.workload.clone(),
            tiles: tiles.len() as u64,
            warp_tiles,
            warps,
            rejected_quads: sum(|t| t.rejected_quads),
            positions,
            warps_per_position: ratio(warps as f64, positions as f64),
            frame_quads,
            coverage: ratio(positions as f64, frame_quads as f64),
            warps_per_tile: ratio(warps as f64, warp_tiles as f64),
            instrs,
            tex_instrs: tex,
            tri_tex_instrs: tri,
            trilinear_share: ratio(tri as f64, tex as f64),
            instrs_per_warp: ratio(instrs as f64, warps as f64),
            block_accesses: sum(|t| t.block_accesses),
            warp_blocks,
            tile_unique_blocks: unique,
            frame_unique_blocks: all.len() as u64,
            mem_instr_ratio: ratio(tex as f64, instrs as f64),
            reuse: ratio(reuse_num, reuse_den),
            cf,
            min_estimate1,
            min_estimate2: ratio(min_estimate1, cf),
        }
    }
}

impl Tile {
    /// This tile's statistics.
    pub fn stats(&self) -> TileStats {
        TileStats::of(self)
    }
}

impl Trace {
    /// Per-tile statistics in traversal order.
    pub fn tile_stats(&self) -> Vec<TileStats> {
        self.tiles.iter().map(Tile::stats).collect()
    }

    /// Whole-trace statistics (see [`TraceStats`] for the definitions).
    /// Over several frames they pool every frame's tiles, and
    /// `frame_quads` counts the quads of every frame.
    pub fn stats(&self) -> TraceStats {
        self.stats
            .0
            .get_or_init(|| TraceStats::of(&self.header, &self.tiles, self.frame_count()))
            .clone()
    }

    /// The statistics of frame `frame` alone (those of the whole trace
    /// for a one-frame trace).
    ///
    /// # Panics
    ///
    /// If `frame >= frame_count()`.
    pub fn frame_stats(&self, frame: usize) -> TraceStats {
        if self.frame_count() == 1 {
            return self.stats();
        }
        TraceStats::of(&self.header, self.frame_tiles(frame), 1)
    }
}

/// Texture footprint ratio of the warps of `tile` whose in-tile quad
/// position (x, y) satisfies `is_priority`: distinct blocks they touch /
/// distinct blocks the whole tile touches. 1 for a tile without blocks.
pub fn footprint_ratio(tile: &Tile, is_priority: impl Fn(u32, u32) -> bool) -> f64 {
    let (selected, total) = footprint(tile, &is_priority);
    if total == 0 {
        1.0
    } else {
        selected as f64 / total as f64
    }
}

fn footprint(tile: &Tile, is_priority: &impl Fn(u32, u32) -> bool) -> (usize, usize) {
    let mut chosen: Vec<u64> = tile
        .quads()
        .filter(|q| is_priority(q.x(), q.y()))
        .flat_map(|q| q.block_accesses().iter().copied())
        .collect();
    chosen.sort_unstable();
    chosen.dedup();
    (chosen.len(), tile.unique_block_count())
}

/// Mean texture footprint ratio over the tiles of `trace` that touch at
/// least one block, weighted by their warps (0 if no tile touches a block).
/// A tile without warps touches no block, so it is left out.
pub fn mean_footprint_ratio(trace: &Trace, is_priority: impl Fn(u32, u32) -> bool) -> f64 {
    mean_footprint_ratio_of(trace.tiles(), is_priority)
}

/// [`mean_footprint_ratio`] over `tiles` (one frame's, say).
pub fn mean_footprint_ratio_of(tiles: &[Tile], is_priority: impl Fn(u32, u32) -> bool) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for tile in tiles {
        let (selected, total) = footprint(tile, &is_priority);
        if total > 0 {
            let w = tile.quad_count() as f64;
            num += w * selected as f64 / total as f64;
            den += w;
        }
    }
    ratio(num, den)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit::*;
    use proptest::prelude::*;

    #[test]
    fn tiny_trace_statistics_match_hand_computation() {
        let t = Trace::read(TINY).unwrap();
        let s0 = t.tiles()[0].stats();
        assert_eq!(
            s0,
            TileStats {
                tx: 0,
                ty: 0,
                warps: 16,
                rejected_quads: 0,
                positions: 16,
                instrs: 16 * 9,
                tex_instrs: 32,
                tri_tex_instrs: 0,
                block_accesses: 36 + 16,
                warp_blocks: 52,
                unique_blocks: 10,
            }
        );
        assert!(close(s0.reuse(), 5.2));
        assert!(close(s0.cf(), 3.25));
        assert!(close(s0.min_estimate1(), 10.0 / 16.0));
        assert!(close(s0.min_estimate2(), 10.0 / 52.0));
        assert!(close(s0.mem_instr_ratio(), 2.0 / 9.0));
        let s1 = t.tiles()[1].stats();
        assert_eq!((s1.warps, s1.warp_blocks, s1.unique_blocks), (10, 23, 8));

        let s = t.stats();
        assert_eq!(s.workload, "hand:tiny");
        assert_eq!((s.tiles, s.warp_tiles, s.warps), (2, 2, 26));
        assert_eq!((s.rejected_quads, s.frame_quads), (0, 32));
        assert_eq!((s.instrs, s.tex_instrs), (224, 42));
        assert_eq!(
            (s.warp_blocks, s.tile_unique_blocks, s.frame_unique_blocks),
            (75, 18, 18)
        );
        assert!(close(s.coverage, 26.0 / 32.0));
        assert_eq!(s.positions, 26);
        assert!(close(s.warps_per_position, 1.0));
        assert!(close(s.mem_instr_ratio, 42.0 / 224.0));
        assert!(close(s.cf, 75.0 / 26.0));
        assert!(close(s.min_estimate1, 18.0 / 26.0));
        assert!(close(s.min_estimate2, 18.0 / 75.0));
        assert!(close(s.reuse, (16.0 * 5.2 + 10.0 * 2.875) / 26.0));
        assert!(close(s.warps_per_tile, 13.0));

        // Footprint of one quad in four (x, y even) and of Mesh4's (0, 0).
        let tile0 = &t.tiles()[0];
        assert!(close(
            footprint_ratio(tile0, |x, y| x % 2 == 0 && y % 2 == 0),
            0.5
        ));
        assert!(close(
            footprint_ratio(tile0, |x, y| x % 4 == 0 && y % 4 == 0),
            0.2
        ));
        assert!(close(footprint_ratio(tile0, |_, _| true), 1.0));
        assert!(close(footprint_ratio(tile0, |_, _| false), 0.0));
        // Tile 1 0: (0, 0) touches 1 of 8 blocks; (0,2),(2,2) add 3412 and 3413.
        let mesh2 = mean_footprint_ratio(&t, |x, y| x % 2 == 0 && y % 2 == 0);
        assert!(close(mesh2, (16.0 * 0.5 + 10.0 * 3.0 / 8.0) / 26.0));
    }

    #[test]
    fn statistics_are_remembered_and_not_part_of_equality() {
        let t = Trace::read(TINY).unwrap();
        let fresh = t.clone();
        let first = t.stats();
        // The remembered statistics are the computed ones, and a trace that
        // has them equals one that has not computed them yet.
        assert_eq!(first, TraceStats::of(t.header(), t.tiles(), 1));
        assert_eq!(t.stats(), first);
        assert_eq!(t, fresh);
        assert!(format!("{t:?}").contains("Memo(computed)"));
        assert!(format!("{fresh:?}").contains("Memo(not computed)"));
        assert_eq!(fresh.stats(), first);
        // A tile's distinct-block count likewise.
        let tile = &t.tiles()[0];
        let plain = tile.unique_blocks().len();
        assert!(plain > 0);
        assert_eq!(tile.unique_block_count(), plain);
        assert_eq!(tile.unique_block_count(), plain);
        assert_eq!(tile, &fresh.tiles()[0]);
    }

    #[test]
    fn a_tile_without_warps_stays_out_of_per_tile_means() {
        let text =
            format!("{HEAD3}tile 0 0\nq 0 0 a1 t1,2\nq 1 0 a1 t2\nz 4\nend\ntile 1 0\nz 9\nend\n");
        let t = Trace::parse(&text, "z").unwrap();
        let hidden = &t.tiles()[1];
        let hs = hidden.stats();
        assert_eq!((hs.warps, hs.positions, hs.unique_blocks), (0, 0, 0));
        assert_eq!(hs.rejected_quads, 9);
        for x in [
            hs.cf(),
            hs.reuse(),
            hs.min_estimate1(),
            hs.min_estimate2(),
            hs.mem_instr_ratio(),
        ] {
            assert_eq!(x, 0.0);
        }
        assert_eq!(footprint_ratio(hidden, |_, _| true), 1.0);
        assert_eq!(hidden.position_count(), 0);
        assert!(hidden.quad(0).is_none() && hidden.quads().next().is_none());
        let s = t.stats();
        assert_eq!(
            (s.tiles, s.warp_tiles, s.warps, s.rejected_quads),
            (2, 1, 2, 13)
        );
        // Means over the tile with warps only: as if the hidden tile were not there.
        assert!(close(s.warps_per_tile, 2.0));
        assert!(close(s.cf, 1.5));
        assert!(close(s.min_estimate1, 1.0));
        assert!(close(s.reuse, 1.5));
        assert!(close(mean_footprint_ratio(&t, |x, _| x == 0), 1.0));
        assert!(close(mean_footprint_ratio(&t, |x, _| x == 1), 0.5));
        // A trace of hidden tiles only.
        let text = format!("{HEAD3}tile 1 0\nz 9\nend\n");
        let s = Trace::parse(&text, "z").unwrap().stats();
        assert_eq!(
            (s.tiles, s.warp_tiles, s.warps, s.rejected_quads),
            (1, 0, 0, 9)
        );
        assert_eq!(
            (s.warps_per_tile, s.cf, s.reuse, s.coverage),
            (0.0, 0.0, 0.0, 0.0)
        );
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

        #[test]
        fn statistics_are_consistent(t in arb_trace()) {
            let s = t.stats();
            prop_assert_eq!(s.warps as usize, t.quad_count());
            prop_assert_eq!(s.rejected_quads, t.rejected_count());
            prop_assert!(s.positions <= s.warps && s.positions >= s.warp_tiles);
            prop_assert!(s.warp_tiles <= s.tiles);
            let least = if s.warps > 0 { 1.0 } else { 0.0 };
            prop_assert!(s.warps_per_tile >= least);
            for x in [s.warps_per_position, s.coverage, s.warps_per_tile, s.instrs_per_warp,
                      s.mem_instr_ratio, s.reuse, s.cf, s.min_estimate1, s.min_estimate2] {
                prop_assert!(x.is_finite(), "{:?}", s);
            }
            prop_assert!(s.coverage <= 1.0);
            prop_assert_eq!(s.instrs, t.instr_count());
            prop_assert!(s.warp_blocks >= s.tile_unique_blocks);
            prop_assert!(s.block_accesses >= s.warp_blocks);
            prop_assert!(s.tile_unique_blocks >= s.frame_unique_blocks);
            // The frame's distinct blocks, the plain way: every access of every
            // tile, sorted and deduplicated.
            let mut all: Vec<u64> = t
                .tiles()
                .iter()
                .flat_map(|tile| tile.block_accesses().iter().copied())
                .collect();
            all.sort_unstable();
            all.dedup();
            prop_assert_eq!(s.frame_unique_blocks, all.len() as u64);
            let tile_unique: usize = t.tiles().iter().map(|tile| tile.unique_block_count()).sum();
            prop_assert_eq!(s.tile_unique_blocks, tile_unique as u64);
            let warp_blocks: u64 = t.tile_stats().iter().map(|ts| ts.warp_blocks).sum();
            prop_assert_eq!(s.warp_blocks, warp_blocks);
            for tile in t.tiles() {
                let ts = tile.stats();
                prop_assert!(tile.quad_count() > 0 || tile.rejected_count() > 0);
                prop_assert_eq!(ts.rejected_quads, tile.rejected_count());
                prop_assert_eq!(
                    tile.raster_count(),
                    tile.quad_count() as u64 + tile.rejected_count()
                );
                let by_gap: u64 = (0..tile.quad_count())
                    .map(|i| u64::from(tile.rejected_before(i)))
                    .sum::<u64>()
                    + u64::from(tile.rejected_after_last());
                prop_assert_eq!(by_gap, tile.rejected_count());
                for x in [ts.cf(), ts.reuse(), ts.min_estimate1(), ts.min_estimate2(), ts.mem_instr_ratio()] {
                    prop_assert!(x.is_finite());
                }
                prop_assert!(ts.unique_blocks == 0 || ts.reuse() >= 1.0);
                prop_assert!(close(footprint_ratio(tile, |_, _| true), 1.0));
                let f = footprint_ratio(tile, |x, _| x % 2 == 0);
                prop_assert!((0.0..=1.0).contains(&f));
            }
        }
    }
}
