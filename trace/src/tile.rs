//! A tile record ([`Tile`]): its quads in launch order with their programs
//! and block accesses in flat pools, and the Early-Z-rejected quads among
//! them; [`QuadRef`] views one quad, [`Quads`] and [`Instrs`] walk them.

use crate::instr::{Instr, Op, OpKind};
use crate::memo::Memo;

/// Where a quad's program and block accesses lie in its tile's pools
/// (see [`Tile::op_kind`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct QuadSpan {
    /// Index of its first instruction entry.
    pub op_start: u32,
    /// Its instruction entries.
    pub op_len: u32,
    /// Index of its first block access in [`Tile::block_accesses`].
    pub block_start: u32,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct QuadRec {
    pub(crate) x: u16,
    pub(crate) y: u16,
    pub(crate) op_start: u32,
    pub(crate) op_len: u32,
    pub(crate) block_start: u32,
    pub(crate) block_len: u32,
}

/// One tile record: its position, its quads in launch (file) order and the
/// Early-Z-rejected quads rasterized among them. It may hold no quad (every
/// quad rejected), never neither quad nor rejected quad.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Tile {
    pub(crate) tx: u32,
    pub(crate) ty: u32,
    pub(crate) quads: Vec<QuadRec>,
    /// Early-Z-rejected quads rasterized just before each quad (empty when
    /// the tile has none before any quad; else one entry per quad).
    pub(crate) rej_before: Vec<u32>,
    /// Rejected quads after the last quad (while the tile is built: since
    /// the last quad).
    pub(crate) rej_tail: u32,
    /// All rejected quads of the tile.
    pub(crate) rej_total: u64,
    pub(crate) ops: Vec<Op>,
    pub(crate) blocks: Vec<u64>,
    /// Its number of distinct blocks, counted on first use: every run's
    /// texture footprint ratio divides by it.
    pub(crate) unique: Memo<usize>,
}

impl Tile {
    /// Tile column in the frame.
    pub fn tx(&self) -> u32 {
        self.tx
    }

    /// Tile row in the frame.
    pub fn ty(&self) -> u32 {
        self.ty
    }

    /// Number of quads (warps) in the tile. With overdraw several warps
    /// share a quad position. A tile whose every quad Early-Z rejected
    /// (format 3 or 4) has none.
    pub fn quad_count(&self) -> usize {
        self.quads.len()
    }

    /// Early-Z-rejected quads rasterized after quad `i - 1` and before quad
    /// `i` (0 for an `i` past the last quad).
    #[inline]
    pub fn rejected_before(&self, i: usize) -> u32 {
        self.rej_before.get(i).copied().unwrap_or(0)
    }

    /// Early-Z-rejected quads rasterized after the last quad (all of them in
    /// a tile without quads).
    #[inline]
    pub fn rejected_after_last(&self) -> u32 {
        self.rej_tail
    }

    /// Early-Z-rejected quads of the tile.
    pub fn rejected_count(&self) -> u64 {
        self.rej_total
    }

    /// Quads the rasterizer produces for the tile: its warps and the quads
    /// Early-Z rejected.
    pub fn raster_count(&self) -> u64 {
        self.quads.len() as u64 + self.rej_total
    }

    /// Number of distinct quad positions the tile's warps occupy (at most
    /// `quad_count`, equal to it in a version-1 trace).
    pub fn position_count(&self) -> usize {
        let mut seen = vec![0u64; 1024];
        let mut n = 0;
        for q in &self.quads {
            // x, y < 256: a 65536-bit set.
            let i = (usize::from(q.y) << 8) | usize::from(q.x);
            let (word, bit) = (i / 64, 1u64 << (i % 64));
            if seen[word] & bit == 0 {
                seen[word] |= bit;
                n += 1;
            }
        }
        n
    }

    /// Where quad `i`'s program and block accesses lie in the tile's pools.
    #[inline]
    pub fn quad_span(&self, i: usize) -> Option<QuadSpan> {
        self.quads.get(i).map(|r| QuadSpan {
            op_start: r.op_start,
            op_len: r.op_len,
            block_start: r.block_start,
        })
    }

    /// Entry `i` of the tile's instruction pool (a quad's entries are
    /// `op_start..op_start + op_len` of its [`QuadSpan`]).
    #[inline]
    pub fn op_kind(&self, i: usize) -> Option<OpKind> {
        self.ops.get(i).map(|&op| match op {
            Op::Alu(n) => OpKind::Alu(n),
            Op::Tex { len, tri, .. } => OpKind::Tex { len, tri },
        })
    }

    /// The `i`-th quad in launch order.
    pub fn quad(&self, i: usize) -> Option<QuadRef<'_>> {
        self.quads.get(i).map(|rec| QuadRef {
            tile: self,
            rec: *rec,
            index: i,
        })
    }

    /// The first quad (in launch order) at in-tile position (x, y), if
    /// shaded.
    pub fn quad_at(&self, x: u32, y: u32) -> Option<QuadRef<'_>> {
        self.quads_at(x, y).next()
    }

    /// Every quad at in-tile position (x, y), in launch order (one per
    /// fragment shaded there).
    pub fn quads_at(&self, x: u32, y: u32) -> impl Iterator<Item = QuadRef<'_>> + '_ {
        self.quads().filter(move |q| q.x() == x && q.y() == y)
    }

    /// The quads in launch order.
    pub fn quads(&self) -> Quads<'_> {
        Quads {
            tile: self,
            range: 0..self.quads.len(),
        }
    }

    /// Every block access of the tile: the blocks of every texture
    /// instruction of every quad, in order, repeats included.
    pub fn block_accesses(&self) -> &[u64] {
        &self.blocks
    }

    /// The distinct blocks the tile touches, sorted.
    pub fn unique_blocks(&self) -> Vec<u64> {
        sorted_unique(&self.blocks)
    }

    /// Number of distinct blocks the tile touches (its texture footprint).
    pub fn unique_block_count(&self) -> usize {
        *self.unique.0.get_or_init(|| self.unique_blocks().len())
    }

    /// [`Tile::unique_blocks`], remembering their count for
    /// [`Tile::unique_block_count`] on the way.
    pub(crate) fn unique_blocks_counted(&self) -> Vec<u64> {
        let v = self.unique_blocks();
        self.unique.0.get_or_init(|| v.len());
        v
    }

    /// Instructions of all quads (ALU runs counted by length).
    pub fn instr_count(&self) -> u64 {
        self.quads().map(|q| q.instr_count()).sum()
    }

    /// Texture instructions of all quads.
    pub fn tex_count(&self) -> u64 {
        self.ops
            .iter()
            .filter(|op| matches!(op, Op::Tex { .. }))
            .count() as u64
    }

    /// Trilinear texture instructions of all quads.
    pub fn trilinear_count(&self) -> u64 {
        self.ops
            .iter()
            .filter(|op| matches!(op, Op::Tex { tri: true, .. }))
            .count() as u64
    }
}

fn sorted_unique(blocks: &[u64]) -> Vec<u64> {
    let mut v = blocks.to_vec();
    v.sort_unstable();
    v.dedup();
    v
}

/// Iterator over a tile's quads in launch order.
#[derive(Clone, Debug)]
pub struct Quads<'a> {
    tile: &'a Tile,
    range: std::ops::Range<usize>,
}

impl<'a> Iterator for Quads<'a> {
    type Item = QuadRef<'a>;
    fn next(&mut self) -> Option<QuadRef<'a>> {
        let i = self.range.next()?;
        self.tile.quad(i)
    }
    fn size_hint(&self) -> (usize, Option<usize>) {
        self.range.size_hint()
    }
}

impl DoubleEndedIterator for Quads<'_> {
    fn next_back(&mut self) -> Option<Self::Item> {
        let i = self.range.next_back()?;
        self.tile.quad(i)
    }
}

impl ExactSizeIterator for Quads<'_> {}

/// A view of one quad (one warp) of a tile.
#[derive(Clone, Copy, Debug)]
pub struct QuadRef<'a> {
    tile: &'a Tile,
    rec: QuadRec,
    index: usize,
}

impl<'a> QuadRef<'a> {
    /// In-tile quad column, 0 to tile/2 - 1.
    pub fn x(&self) -> u32 {
        u32::from(self.rec.x)
    }

    /// In-tile quad row, 0 to tile/2 - 1.
    pub fn y(&self) -> u32 {
        u32::from(self.rec.y)
    }

    /// Position of the quad in its tile's launch order.
    pub fn index(&self) -> usize {
        self.index
    }

    /// The tile this quad belongs to.
    pub fn tile(&self) -> &'a Tile {
        self.tile
    }

    fn ops(&self) -> &'a [Op] {
        let start = self.rec.op_start as usize;
        &self.tile.ops[start..start + self.rec.op_len as usize]
    }

    fn decode(&self, op: Op) -> Instr<'a> {
        match op {
            Op::Alu(n) => Instr::Alu(n),
            Op::Tex { start, len, tri } => {
                let s = start as usize;
                let blocks = &self.tile.blocks[s..s + len as usize];
                if tri {
                    Instr::TriTex(blocks)
                } else {
                    Instr::Tex(blocks)
                }
            }
        }
    }

    /// Number of instruction entries (ALU runs and texture instructions).
    pub fn entry_count(&self) -> usize {
        self.rec.op_len as usize
    }

    /// The `i`-th instruction entry, in O(1).
    pub fn entry(&self, i: usize) -> Option<Instr<'a>> {
        self.ops().get(i).map(|&op| self.decode(op))
    }

    /// The instruction entries in program order.
    pub fn instrs(&self) -> Instrs<'a> {
        Instrs {
            quad: *self,
            range: 0..self.entry_count(),
        }
    }

    /// Number of instructions, ALU runs counted by their length.
    pub fn instr_count(&self) -> u64 {
        self.ops()
            .iter()
            .map(|op| match op {
                Op::Alu(n) => u64::from(*n),
                Op::Tex { .. } => 1,
            })
            .sum()
    }

    /// Number of texture instructions.
    pub fn tex_count(&self) -> usize {
        self.ops()
            .iter()
            .filter(|op| matches!(op, Op::Tex { .. }))
            .count()
    }

    /// Number of trilinear texture instructions.
    pub fn trilinear_count(&self) -> usize {
        self.ops()
            .iter()
            .filter(|op| matches!(op, Op::Tex { tri: true, .. }))
            .count()
    }

    /// Every block access of the quad in program order, repeats across
    /// texture instructions included.
    pub fn block_accesses(&self) -> &'a [u64] {
        let s = self.rec.block_start as usize;
        &self.tile.blocks[s..s + self.rec.block_len as usize]
    }

    /// The distinct blocks the quad touches, sorted.
    pub fn unique_blocks(&self) -> Vec<u64> {
        sorted_unique(self.block_accesses())
    }
}

/// Iterator over a quad's instruction entries.
#[derive(Clone, Debug)]
pub struct Instrs<'a> {
    quad: QuadRef<'a>,
    range: std::ops::Range<usize>,
}

impl<'a> Iterator for Instrs<'a> {
    type Item = Instr<'a>;
    fn next(&mut self) -> Option<Instr<'a>> {
        let i = self.range.next()?;
        self.quad.entry(i)
    }
    fn size_hint(&self) -> (usize, Option<usize>) {
        self.range.size_hint()
    }
}

impl ExactSizeIterator for Instrs<'_> {}

#[cfg(test)]
mod tests {
    use crate::{Instr, Trace, TraceHeader};

    #[test]
    fn a_hand_built_tile_answers_where_its_rejected_quads_are() {
        let build = |split: bool, tail: u32| {
            let mut b = Trace::builder(TraceHeader::new("w", 64, 64, 64)).unwrap();
            b.begin_tile(0, 0).unwrap();
            b.rejected(3).unwrap();
            b.quad(0, 0, &[Instr::Alu(1)]).unwrap();
            b.quad(1, 0, &[Instr::Tex(&[9])]).unwrap();
            if split {
                b.rejected(2).unwrap();
                b.rejected(3).unwrap();
            } else {
                b.rejected(5).unwrap();
            }
            b.quad(1, 0, &[Instr::Alu(2)]).unwrap();
            b.quad(0, 1, &[Instr::Alu(3)]).unwrap();
            if tail > 0 {
                b.rejected(tail).unwrap();
            }
            b.end_tile().unwrap();
            b.finish().unwrap()
        };
        let t = build(false, 4);
        let tile = &t.tiles()[0];
        assert_eq!(tile.quad_count(), 4);
        let before: Vec<u32> = (0..4).map(|i| tile.rejected_before(i)).collect();
        assert_eq!(before, vec![3, 0, 5, 0]);
        assert_eq!(tile.rejected_after_last(), 4);
        assert_eq!((tile.rejected_count(), tile.raster_count()), (12, 16));
        assert_eq!(t.rejected_count(), 12);
        assert_eq!(tile.stats().rejected_quads, 12);
        assert_eq!(t.stats().rejected_quads, 12);
        // Split calls add up to the same tile; other rejections make another.
        assert_eq!(build(true, 4), t);
        assert_ne!(build(false, 5), t);
        assert_ne!(build(false, 0), t);
        assert_eq!(
            t.to_text().split_once("tile 0 0\n").unwrap().1,
            "z 3\nq 0 0 a1\nq 1 0 t9\nz 5\nq 1 0 a2\nq 0 1 a3\nz 4\nend\n"
        );
        assert_eq!(Trace::parse(&t.to_text(), "rt").unwrap(), t);
    }
}
