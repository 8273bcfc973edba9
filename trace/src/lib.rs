//! The wasp trace: the shaded quads of one frame, tile by tile, the quads
//! Early-Z rejected between them, and the instructions each shaded quad's
//! shader executes — the input of the cycle model.
//!
//! # Format `wasp-trace 4` (and `wasp-trace 3`, `2`, `1`)
//!
//! (The same text is in `tests/traces/FORMAT.md`; a test checks that the two
//! agree.)
//!
//! ## Example
//!
//! ```text
//! wasp-trace 4
//! # free comment lines
//! workload synthetic:texmap scale=1 mem=0.15 seed=7
//! frame 1960 768 tile 64
//! tile 0 0
//! q 0 0 a3 t1a40,1a41 a2 T1a40,1b20
//! q 1 0 a5
//! z 12
//! q 0 0 a2 t2b00
//! z 3
//! end
//! tile 1 0
//! q 0 0 t1a48 a4
//! end
//! tile 0 1
//! z 40
//! end
//! ```
//!
//! The first warp, at quad (0, 0) of tile (0, 0), runs 3 ALU instructions, a
//! texture instruction touching blocks 0x1a40 and 0x1a41, 2 ALU instructions,
//! and a trilinear texture instruction touching blocks 0x1a40 and 0x1b20 (two
//! mip levels). After the second warp the
//! rasterizer produced 12 quads that Early-Z rejected, then the third warp, a
//! second fragment at position (0, 0) of a primitive drawn later (overdraw):
//! its own warp with its own program. 3 more rejected quads end the tile.
//! Tile (0, 1) is hidden: its 40 quads were all rejected.
//!
//! ## Rules
//!
//! A trace is UTF-8 text in lines ending in LF (a CR just before the LF is
//! ignored). Tokens are separated by one or more spaces or tabs; blanks at the
//! start and end of a line are ignored. No line may hold any other control
//! character.
//!
//! * **Line 1** is exactly `wasp-trace 4` (or, below, `wasp-trace 3`,
//!   `wasp-trace 2` or `wasp-trace 1`): the magic word and the format
//!   version. A reader rejects any other version.
//! * **Comments**: a line whose first non-blank character is `#` is a comment;
//!   blank lines are ignored. Both may appear anywhere after line 1. Comments
//!   before the `frame` line are the header *notes*: a reader keeps their text
//!   (everything after the `#`, verbatim) and a writer writes them back right
//!   after line 1. Other comments are dropped. There are no comments at the end
//!   of a line.
//! * **Header**, before the first tile and in this order, each exactly once:
//!   * `workload NAME` — provenance: NAME is the rest of the line, not empty.
//!     A synthetic workload's name starts with `synthetic:` and names its
//!     generator parameters.
//!   * `frame W H tile T` — frame width and height in pixels (1 to 65536) and
//!     the tile edge in pixels (even, 2 to 512). The frame is cut into
//!     ceil(W/T) x ceil(H/T) tiles; a tile holds (T/2) x (T/2) quads of 2x2
//!     pixels (32 x 32 for the paper's 64-pixel tiles).
//! * **Tile record**: `tile TX TY` (tile column and row, inside the frame),
//!   then the tile's `q` lines (one per warp) and `z` lines (rejected quads)
//!   in rasterization order, then `end` alone on its line. A tile appears at
//!   most once and holds at least one line, a `q` or a `z`: a tile of `z`
//!   lines only is a tile whose every quad Early-Z rejected (it costs the
//!   rasterizer time and launches no warp). Tiles appear in traversal order
//!   (the front end emits Z-order; a reader does not check the order).
//! * **Quad**: `q X Y INSTR...` — one warp: one shaded (primitive, quad)
//!   fragment. X, Y are the in-tile quad column and row (0 to T/2-1); the
//!   quad's top-left pixel (TX*T + 2X, TY*T + 2Y) lies inside the frame. The
//!   quads of a tile appear in rasterization order, the order the cycle model
//!   launches them: primitives in draw order, each primitive's quads in
//!   scanline order. A position repeats once per fragment shaded there
//!   (overdraw). A reader checks no order: a record does not name its
//!   primitive, and any sequence of positions is the rasterization order of
//!   some sequence of primitives.
//! * **Rejected quads** (versions 3 and 4): `z N` — N quads (decimal, 1 to 4194304 = 2^22)
//!   that the rasterizer produced at this point of the tile's rasterization
//!   order (after the `q` line before it, before the `q` line after it) and
//!   Early-Z rejected: they launch no warp but cost the rasterizer a slot
//!   each. Quads a hierarchical (coarse) depth test rejects are among them:
//!   the same rejections, found faster. Two `z` lines are never adjacent, not
//!   even with blank or comment lines between: write one line with their sum.
//!   (A builder merges them; a reader rejects adjacent ones, so that writing
//!   a trace it read gives back the same text.)
//! * **Instructions**, at least one per quad and at most 65536 (ALU runs
//!   counted by their length, a texture instruction as one), in program order:
//!   * `aN` — a run of N ALU instructions (decimal, 1 to 4096). Two runs are
//!     never adjacent: write `a5`, not `a3 a2`.
//!   * `tB,B,...` — one texture instruction and the 64-byte memory blocks it
//!     touches, as block numbers (byte address / 64) in hex (1 to 16 digits,
//!     either case, no `0x`; writers use lowercase without leading zeros),
//!     comma-separated without blanks: 1 to 1024 blocks, distinct within the
//!     instruction, in the order the texture unit requests them. Its sample
//!     is filtered bilinear or nearest: one filter pass.
//!   * `TB,B,...` (version 4) — the same for a texture instruction whose
//!     sample is trilinear: it filters two mip levels, two filter passes. The
//!     front end writes `T` exactly when the sample read two levels (a
//!     trilinear sample that magnifies, or minifies to the last level, reads
//!     one level and is written `t`).
//! * Decimal numbers are ASCII digits without sign and must fit their range.
//!   The bounds on ALU runs, instructions per quad, blocks per texture
//!   instruction and rejected quads per `z` line lie far above any real
//!   shader or scene; they keep a corrupt number from running the model for
//!   minutes.
//!
//! **Version 3** (`wasp-trace 3`) is version 4 without `T` instructions: it
//! does not say which samples are trilinear, and a reader takes every
//! texture instruction of a version-3 (or older) file as bilinear. A reader
//! rejects a `T` instruction in a version-3, -2 or -1 file, naming the
//! version and the token. Every version-3 trace is a version-4 trace, and a
//! writer always writes version 4: reading an older file and writing it back
//! changes line 1 only (for a file in the writer's canonical form).
//!
//! **Version 2** (`wasp-trace 2`) is version 3 without `z` lines: a reader
//! rejects a `z` line in a version-2 (or version-1) file, naming the version.
//! An older trace records no rejected quad, so its rasterizer cost counts
//! surviving quads only. Every version-2 trace is a version-3 trace.
//!
//! **Version 1** (`wasp-trace 1`) is version 2 except that the quads of a
//! tile appear in scanline order, strictly increasing in (Y, X), so each
//! position at most once: fragments at one position had to be merged into one
//! warp running their programs one after the other. A reader accepts version
//! 1 with this rule enforced (errors `quad X Y appears twice in the tile` and
//! `quad X Y after quad X' Y'`). Every version-1 trace is a version-2 trace.
//!
//! A reader rejects any other input with an error `file:line: what was wrong
//! (expected what)`, for example
//!
//! ```text
//! scene.trace:7: quad 40 3 outside the tile (expected x and y from 0 to 31)
//! ```
//!
//! and never panics. Writing a trace and reading it back gives the same trace.
//!
//! # In memory
//!
//! [`Trace`] holds a [`TraceHeader`] and the [`Tile`]s in file order. A tile
//! keeps its quads, instructions and block numbers in three flat vectors (no
//! allocation per quad or instruction; a texture instruction's trilinear
//! flag shares its 12-byte entry), so a tile is self-contained and a
//! full 1960x768 frame (about 376k quad positions, a few million fragments
//! with overdraw) stays small. Its Early-Z-rejected quads take one `u32` per
//! quad, and only in a tile with rejections before some quad, plus one for
//! those after its last quad ([`Tile::rejected_before`],
//! [`Tile::rejected_after_last`]); they are part of the tile's equality. A
//! tile may hold no quad at all (every quad rejected): whatever divides by a
//! tile's quads must allow for that ([`TileStats`] and [`TraceStats`] leave
//! such tiles out of per-tile means). [`QuadRef`] views one quad; [`Instr`]
//! is one run-length instruction entry. Build traces with [`TraceBuilder`],
//! which enforces every rule of the format, so whatever it builds the writer
//! writes and the reader reads back identically.

mod read;
pub mod rng;
mod stats;
#[cfg(test)]
mod tests;
mod write;
mod zorder;

pub use stats::{footprint_ratio, mean_footprint_ratio, TileStats, TraceStats};
pub use zorder::{morton, z_order};

use std::collections::HashSet;
use std::fmt;

/// The magic word on line 1.
pub const MAGIC: &str = "wasp-trace";
/// The format version this module writes (and reads).
pub const FORMAT_VERSION: u32 = 4;
/// The previous version, which this module also reads: no trilinear
/// marker (`T`), every texture instruction taken as bilinear.
pub const FORMAT_VERSION_3: u32 = 3;
/// The version before, which this module also reads: no `z` records.
pub const FORMAT_VERSION_2: u32 = 2;
/// The older version this module also reads: one quad per position, in
/// scanline order.
pub const FORMAT_VERSION_1: u32 = 1;
/// Largest frame width or height, in pixels.
pub const MAX_FRAME_DIM: u32 = 65_536;
/// Largest tile edge, in pixels.
pub const MAX_TILE_SIZE: u32 = 512;
/// Longest ALU run of one `aN` entry (wasp): 4096, far above the
/// straight-line ALU stretch of any fragment shader of the paper's
/// workloads (a handful to a few dozen), so a typo or a corrupt number is
/// refused instead of keeping the model busy for minutes.
pub const MAX_ALU_RUN: u32 = 4096;
/// Most instructions of one quad's program (wasp), ALU runs counted by
/// their length and a texture instruction as one: 65536, 16 runs of
/// [`MAX_ALU_RUN`] with texture instructions between them. It bounds the
/// cycles one warp can occupy a core.
pub const MAX_QUAD_INSTRS: u32 = 65_536;
/// Most Early-Z-rejected quads one `z N` record may count (wasp): 2^22 =
/// 4194304, the quads of the largest tile (256 x 256 for 512 pixels) times
/// an overdraw of 64, or 4096 times the quads of the paper's 64-pixel tile.
pub const MAX_REJECTED_RUN: u32 = 1 << 22;
/// Most blocks one texture instruction may touch.
pub const MAX_TEX_BLOCKS: usize = 1024;

/// The header: provenance, frame and tile size, and the header notes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TraceHeader {
    /// Where the trace comes from; `synthetic:...` for generated ones.
    pub workload: String,
    /// Frame width in pixels.
    pub frame_w: u32,
    /// Frame height in pixels.
    pub frame_h: u32,
    /// Tile edge in pixels (even).
    pub tile: u32,
    /// Header comment lines, the text after `#` verbatim.
    pub notes: Vec<String>,
}

impl TraceHeader {
    /// A header without notes (validated when a [`TraceBuilder`] takes it).
    pub fn new(workload: impl Into<String>, frame_w: u32, frame_h: u32, tile: u32) -> TraceHeader {
        TraceHeader {
            workload: workload.into(),
            frame_w,
            frame_h,
            tile,
            notes: Vec::new(),
        }
    }

    /// Checks the header against the format's rules.
    pub fn validate(&self) -> Result<(), Problem> {
        check_text(&self.workload, TextField::Workload)?;
        if self.workload.is_empty() {
            return Err(Problem::EmptyWorkload);
        }
        if self.workload.trim_matches(BLANKS) != self.workload {
            return Err(Problem::BadText {
                field: TextField::Workload,
                why: "starts or ends with a blank",
            });
        }
        for note in &self.notes {
            check_text(note, TextField::Note)?;
        }
        for (dim, v) in [("width", self.frame_w), ("height", self.frame_h)] {
            if v == 0 || v > MAX_FRAME_DIM {
                return Err(Problem::BadFrame { dim, value: v });
            }
        }
        if self.tile < 2 || self.tile > MAX_TILE_SIZE || !self.tile.is_multiple_of(2) {
            return Err(Problem::BadTileSize(self.tile));
        }
        Ok(())
    }

    /// Tile columns in the frame, ceil(frame_w / tile).
    pub fn tiles_x(&self) -> u32 {
        self.frame_w.div_ceil(self.tile.max(1))
    }

    /// Tile rows in the frame, ceil(frame_h / tile).
    pub fn tiles_y(&self) -> u32 {
        self.frame_h.div_ceil(self.tile.max(1))
    }

    /// Quads per tile edge, tile / 2.
    pub fn quads_per_side(&self) -> u32 {
        self.tile / 2
    }

    /// Quads whose top-left pixel lies in the frame: the most a frame can
    /// shade, ceil(w/2) x ceil(h/2).
    pub fn frame_quads(&self) -> u64 {
        u64::from(self.frame_w.div_ceil(2)) * u64::from(self.frame_h.div_ceil(2))
    }

    /// Whether quad (x, y) of tile (tx, ty) has its top-left pixel in the frame.
    pub fn quad_in_frame(&self, tx: u32, ty: u32, x: u32, y: u32) -> bool {
        let px = u64::from(tx) * u64::from(self.tile) + 2 * u64::from(x);
        let py = u64::from(ty) * u64::from(self.tile) + 2 * u64::from(y);
        px < u64::from(self.frame_w) && py < u64::from(self.frame_h)
    }
}

const BLANKS: &[char] = &[' ', '\t'];

fn check_text(s: &str, field: TextField) -> Result<(), Problem> {
    if s.chars().any(|c| c.is_control() && c != '\t') {
        return Err(Problem::BadText {
            field,
            why: "contains a control character",
        });
    }
    Ok(())
}

/// One instruction entry of a quad's program.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Instr<'a> {
    /// A run of this many ALU instructions (at least 1).
    Alu(u32),
    /// One texture instruction whose sample is bilinear (or nearest), and
    /// the distinct 64-byte block numbers it touches (at least 1), in
    /// request order: `t` in the text.
    Tex(&'a [u64]),
    /// One texture instruction whose sample is trilinear (it filters two
    /// mip levels), and its blocks as for [`Instr::Tex`]: `T` in the text
    /// (format 4).
    TriTex(&'a [u64]),
}

impl<'a> Instr<'a> {
    /// The blocks of a texture instruction (`None` for an ALU run).
    pub fn blocks(&self) -> Option<&'a [u64]> {
        match *self {
            Instr::Alu(_) => None,
            Instr::Tex(b) | Instr::TriTex(b) => Some(b),
        }
    }

    /// Whether this is a trilinear texture instruction.
    pub fn is_trilinear(&self) -> bool {
        matches!(self, Instr::TriTex(_))
    }
}

/// One entry of a tile's instruction pool: 12 bytes whichever the kind
/// (the trilinear flag lies in the padding beside the tag).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Op {
    Alu(u32),
    /// Blocks `start..start + len` of the tile's block pool; `tri`: the
    /// sample is trilinear.
    Tex {
        start: u32,
        len: u32,
        tri: bool,
    },
}

/// An instruction entry as the shader core's hot path reads it: the
/// entry's kind and length, without borrowing its block list (the core
/// walks a quad's blocks in order, so it knows where they start).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OpKind {
    /// A run of this many ALU instructions.
    Alu(u32),
    /// A texture instruction touching `len` blocks; `tri`: its sample is
    /// trilinear.
    Tex {
        /// Blocks it touches.
        len: u32,
        /// Whether it is trilinear.
        tri: bool,
    },
}

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
struct QuadRec {
    x: u16,
    y: u16,
    op_start: u32,
    op_len: u32,
    block_start: u32,
    block_len: u32,
}

/// One tile record: its position, its quads in launch (file) order and the
/// Early-Z-rejected quads rasterized among them. It may hold no quad (every
/// quad rejected), never neither quad nor rejected quad.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Tile {
    tx: u32,
    ty: u32,
    quads: Vec<QuadRec>,
    /// Early-Z-rejected quads rasterized just before each quad (empty when
    /// the tile has none before any quad; else one entry per quad).
    rej_before: Vec<u32>,
    /// Rejected quads after the last quad (while the tile is built: since
    /// the last quad).
    rej_tail: u32,
    /// All rejected quads of the tile.
    rej_total: u64,
    ops: Vec<Op>,
    blocks: Vec<u64>,
    /// Its number of distinct blocks, counted on first use: every run's
    /// texture footprint ratio divides by it.
    unique: Memo<usize>,
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

    /// This tile's statistics.
    pub fn stats(&self) -> TileStats {
        TileStats::of(self)
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

/// A whole trace: header and tiles in traversal (file) order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Trace {
    header: TraceHeader,
    tiles: Vec<Tile>,
    /// Its statistics, computed on first use: every run's report reads
    /// them, and `wasp compare` runs several policies on one trace.
    stats: Memo<TraceStats>,
}

/// A value derived from the rest of its owner, computed on first use.
/// It is not part of what the owner is: any two compare equal.
#[derive(Clone)]
struct Memo<T>(std::sync::OnceLock<T>);

impl<T> Default for Memo<T> {
    fn default() -> Self {
        Memo(std::sync::OnceLock::new())
    }
}

impl<T> PartialEq for Memo<T> {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl<T> Eq for Memo<T> {}

impl<T> std::fmt::Debug for Memo<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(if self.0.get().is_some() {
            "Memo(computed)"
        } else {
            "Memo(not computed)"
        })
    }
}

impl Trace {
    /// A builder for a trace with this header (checked here).
    pub fn builder(header: TraceHeader) -> Result<TraceBuilder, Problem> {
        TraceBuilder::new(header)
    }

    /// The header.
    pub fn header(&self) -> &TraceHeader {
        &self.header
    }

    /// The tiles in traversal order.
    pub fn tiles(&self) -> &[Tile] {
        &self.tiles
    }

    /// Quads (warps) in the whole trace.
    pub fn quad_count(&self) -> usize {
        self.tiles.iter().map(Tile::quad_count).sum()
    }

    /// Early-Z-rejected quads in the whole trace.
    pub fn rejected_count(&self) -> u64 {
        self.tiles.iter().map(Tile::rejected_count).sum()
    }

    /// Instructions in the whole trace, ALU runs counted by length.
    pub fn instr_count(&self) -> u64 {
        self.tiles.iter().map(Tile::instr_count).sum()
    }

    /// Texture instructions in the whole trace.
    pub fn tex_count(&self) -> u64 {
        self.tiles.iter().map(Tile::tex_count).sum()
    }

    /// Trilinear texture instructions in the whole trace.
    pub fn trilinear_count(&self) -> u64 {
        self.tiles.iter().map(Tile::trilinear_count).sum()
    }

    /// Adds a header note (e.g. provenance or measured figures).
    pub fn push_note(&mut self, text: impl Into<String>) -> Result<(), Problem> {
        let text = text.into();
        check_text(&text, TextField::Note)?;
        self.header.notes.push(text);
        Ok(())
    }

    /// Per-tile statistics in traversal order.
    pub fn tile_stats(&self) -> Vec<TileStats> {
        self.tiles.iter().map(Tile::stats).collect()
    }

    /// Whole-trace statistics (see [`TraceStats`] for the definitions).
    pub fn stats(&self) -> TraceStats {
        self.stats.0.get_or_init(|| TraceStats::of(self)).clone()
    }
}

/// Builds a [`Trace`] step by step, enforcing every rule of the format
/// (version 4: quad positions may repeat, in any order, with rejected
/// quads among them, and texture instructions bilinear or trilinear).
///
/// A call that returns an error changes nothing, so a caller may report it
/// and stop. `begin_quad` closes the previous quad, `end_tile` the tile.
#[derive(Debug)]
pub struct TraceBuilder {
    header: TraceHeader,
    tiles: Vec<Tile>,
    seen: HashSet<(u32, u32)>,
    open: Option<Tile>,
    /// Version 1's rule: quads in strictly increasing scanline order.
    scanline_order: bool,
    /// Instructions of the open quad so far (ALU runs by length), held to
    /// [`MAX_QUAD_INSTRS`].
    quad_instrs: u32,
}

impl TraceBuilder {
    /// Starts a trace with this header; fails if the header breaks a rule.
    pub fn new(header: TraceHeader) -> Result<TraceBuilder, Problem> {
        header.validate()?;
        Ok(TraceBuilder {
            header,
            tiles: Vec::new(),
            seen: HashSet::new(),
            open: None,
            scanline_order: false,
            quad_instrs: 0,
        })
    }

    /// Enforces version 1's rule from now on: the quads of a tile in
    /// strictly increasing scanline order, each position at most once (the
    /// reader of `wasp-trace 1` files uses it).
    pub fn require_scanline_order(&mut self) {
        self.scanline_order = true;
    }

    /// The header being built.
    pub fn header(&self) -> &TraceHeader {
        &self.header
    }

    /// Number of closed tiles so far.
    pub fn tile_count(&self) -> usize {
        self.tiles.len()
    }

    /// Adds a header note (a comment line written after line 1).
    pub fn note(&mut self, text: impl Into<String>) -> Result<(), Problem> {
        let text = text.into();
        check_text(&text, TextField::Note)?;
        self.header.notes.push(text);
        Ok(())
    }

    /// Position of the open tile, if any.
    pub fn open_tile(&self) -> Option<(u32, u32)> {
        self.open.as_ref().map(|t| (t.tx, t.ty))
    }

    /// Opens tile (tx, ty).
    pub fn begin_tile(&mut self, tx: u32, ty: u32) -> Result<(), Problem> {
        if let Some(t) = &self.open {
            return Err(Problem::TileNotClosed { tx: t.tx, ty: t.ty });
        }
        let (nx, ny) = (self.header.tiles_x(), self.header.tiles_y());
        if tx >= nx || ty >= ny {
            return Err(Problem::TileOutsideFrame {
                tx,
                ty,
                tiles_x: nx,
                tiles_y: ny,
            });
        }
        if self.seen.contains(&(tx, ty)) {
            return Err(Problem::DuplicateTile { tx, ty });
        }
        self.open = Some(Tile {
            tx,
            ty,
            quads: Vec::new(),
            rej_before: Vec::new(),
            rej_tail: 0,
            rej_total: 0,
            ops: Vec::new(),
            blocks: Vec::new(),
            unique: Memo::default(),
        });
        Ok(())
    }

    /// Reserves room in the open tile for this many more quads, instruction
    /// entries and block numbers (a hint: saves reallocating while it
    /// grows; no effect without an open tile).
    pub fn reserve(&mut self, quads: usize, entries: usize, blocks: usize) {
        if let Some(t) = &mut self.open {
            t.quads.reserve_exact(quads);
            t.ops.reserve_exact(entries);
            t.blocks.reserve_exact(blocks);
        }
    }

    /// Opens quad (x, y) of the open tile, closing the previous quad.
    pub fn begin_quad(&mut self, x: u32, y: u32) -> Result<(), Problem> {
        let header = &self.header;
        let tile = self.open.as_mut().ok_or(Problem::QuadWithoutTile)?;
        if let Some(prev) = tile.quads.last() {
            if prev.op_len == 0 {
                return Err(Problem::EmptyQuad {
                    x: u32::from(prev.x),
                    y: u32::from(prev.y),
                });
            }
        }
        let side = header.quads_per_side();
        if x >= side || y >= side {
            return Err(Problem::QuadOutsideTile { x, y, side });
        }
        if !header.quad_in_frame(tile.tx, tile.ty, x, y) {
            return Err(Problem::QuadOutsideFrame {
                x,
                y,
                px: u64::from(tile.tx) * u64::from(header.tile) + 2 * u64::from(x),
                py: u64::from(tile.ty) * u64::from(header.tile) + 2 * u64::from(y),
            });
        }
        if let Some(prev) = tile.quads.last().filter(|_| self.scanline_order) {
            let (px, py) = (u32::from(prev.x), u32::from(prev.y));
            if (y, x) == (py, px) {
                return Err(Problem::DuplicateQuad { x, y });
            }
            if (y, x) < (py, px) {
                return Err(Problem::QuadOutOfOrder {
                    x,
                    y,
                    prev_x: px,
                    prev_y: py,
                });
            }
        }
        // The rejected quads since the previous quad come before this one.
        if tile.rej_tail > 0 || !tile.rej_before.is_empty() {
            tile.rej_before.resize(tile.quads.len(), 0);
            tile.rej_before.push(std::mem::take(&mut tile.rej_tail));
        }
        // x, y < side <= 256 and the pools are below u32::MAX (checked when
        // they grow), so these conversions are exact.
        tile.quads.push(QuadRec {
            x: x as u16,
            y: y as u16,
            op_start: tile.ops.len() as u32,
            op_len: 0,
            block_start: tile.blocks.len() as u32,
            block_len: 0,
        });
        self.quad_instrs = 0;
        Ok(())
    }

    /// Checks that `n` more instructions fit the open quad's program.
    fn quad_room(&self, n: u32) -> Result<u32, Problem> {
        let sum = u64::from(self.quad_instrs) + u64::from(n);
        if sum > u64::from(MAX_QUAD_INSTRS) {
            return Err(Problem::QuadTooLong(sum));
        }
        Ok(sum as u32)
    }

    fn open_quad(&mut self) -> Result<&mut Tile, Problem> {
        match &mut self.open {
            Some(t) if !t.quads.is_empty() => Ok(t),
            _ => Err(Problem::InstrWithoutQuad),
        }
    }

    /// Records `n` quads rasterized at this point of the open tile and
    /// rejected by Early-Z (no warp): before the next quad
    /// ([`begin_quad`]), or at the tile's end. Consecutive calls add up
    /// (the format's `z` lines are never adjacent).
    ///
    /// Fails, changing nothing, if `n` is 0 ([`Problem::ZeroRejected`]), no
    /// tile is open ([`Problem::RejectedWithoutTile`]), the open quad has
    /// no instruction yet ([`Problem::EmptyQuad`]), or the rejected quads
    /// at this point would exceed [`MAX_REJECTED_RUN`] (2^22, what one
    /// `z` line holds; [`Problem::RejectedRunTooLong`]).
    ///
    /// [`begin_quad`]: TraceBuilder::begin_quad
    pub fn rejected(&mut self, n: u32) -> Result<(), Problem> {
        if n == 0 {
            return Err(Problem::ZeroRejected);
        }
        let tile = self.open.as_mut().ok_or(Problem::RejectedWithoutTile)?;
        if let Some(q) = tile.quads.last() {
            if q.op_len == 0 {
                return Err(Problem::EmptyQuad {
                    x: u32::from(q.x),
                    y: u32::from(q.y),
                });
            }
        }
        let sum = u64::from(tile.rej_tail) + u64::from(n);
        if sum > u64::from(MAX_REJECTED_RUN) {
            return Err(Problem::RejectedRunTooLong(sum));
        }
        tile.rej_tail = sum as u32;
        tile.rej_total += u64::from(n);
        Ok(())
    }

    /// Appends a run of `n` ALU instructions to the open quad (merged into a
    /// run that ends the quad's program so far).
    pub fn alu(&mut self, n: u32) -> Result<(), Problem> {
        if n == 0 {
            return Err(Problem::ZeroAlu);
        }
        if n > MAX_ALU_RUN {
            return Err(Problem::AluRunTooLong(u64::from(n)));
        }
        self.open_quad()?;
        let count = self.quad_room(n)?;
        let tile = self.open_quad()?;
        let q = *tile.quads.last().expect("open quad");
        if q.op_len > 0 {
            if let Some(Op::Alu(m)) = tile.ops.last_mut() {
                let sum = u64::from(*m) + u64::from(n);
                if sum > u64::from(MAX_ALU_RUN) {
                    return Err(Problem::AluRunTooLong(sum));
                }
                *m = sum as u32;
                self.quad_instrs = count;
                return Ok(());
            }
        }
        if tile.ops.len() >= u32::MAX as usize {
            return Err(Problem::TileTooLarge);
        }
        tile.ops.push(Op::Alu(n));
        tile.quads.last_mut().expect("open quad").op_len += 1;
        self.quad_instrs = count;
        Ok(())
    }

    /// Appends a bilinear (or nearest) texture instruction touching
    /// `blocks` to the open quad.
    pub fn tex(&mut self, blocks: &[u64]) -> Result<(), Problem> {
        self.tex_filtered(blocks, false)
    }

    /// Appends a trilinear texture instruction touching `blocks` to the
    /// open quad.
    pub fn tex_trilinear(&mut self, blocks: &[u64]) -> Result<(), Problem> {
        self.tex_filtered(blocks, true)
    }

    /// Appends a texture instruction touching `blocks` to the open quad,
    /// trilinear if `trilinear`.
    pub fn tex_filtered(&mut self, blocks: &[u64], trilinear: bool) -> Result<(), Problem> {
        if blocks.is_empty() {
            return Err(Problem::TexNoBlock);
        }
        if blocks.len() > MAX_TEX_BLOCKS {
            return Err(Problem::TooManyBlocks(blocks.len()));
        }
        if let Some(b) = first_duplicate(blocks) {
            return Err(Problem::DuplicateBlock(b));
        }
        self.open_quad()?;
        let count = self.quad_room(1)?;
        let tile = self.open_quad()?;
        if tile.ops.len() >= u32::MAX as usize
            || tile.blocks.len() + blocks.len() >= u32::MAX as usize
        {
            return Err(Problem::TileTooLarge);
        }
        let start = tile.blocks.len() as u32;
        tile.blocks.extend_from_slice(blocks);
        tile.ops.push(Op::Tex {
            start,
            len: blocks.len() as u32,
            tri: trilinear,
        });
        let q = tile.quads.last_mut().expect("open quad");
        q.op_len += 1;
        q.block_len += blocks.len() as u32;
        self.quad_instrs = count;
        Ok(())
    }

    /// Appends one instruction entry to the open quad.
    pub fn instr(&mut self, instr: Instr<'_>) -> Result<(), Problem> {
        match instr {
            Instr::Alu(n) => self.alu(n),
            Instr::Tex(b) => self.tex(b),
            Instr::TriTex(b) => self.tex_trilinear(b),
        }
    }

    /// Adds a whole quad: `begin_quad(x, y)` then each entry. On error the
    /// quad may be partly added; stop building.
    pub fn quad(&mut self, x: u32, y: u32, instrs: &[Instr<'_>]) -> Result<(), Problem> {
        if instrs.is_empty() {
            return Err(Problem::EmptyQuad { x, y });
        }
        self.begin_quad(x, y)?;
        instrs.iter().try_for_each(|&i| self.instr(i))
    }

    /// Closes the open tile.
    pub fn end_tile(&mut self) -> Result<(), Problem> {
        let tile = self.open.as_ref().ok_or(Problem::EndWithoutTile)?;
        match tile.quads.last() {
            None if tile.rej_total > 0 => {}
            None => {
                return Err(Problem::EmptyTile {
                    tx: tile.tx,
                    ty: tile.ty,
                })
            }
            Some(q) if q.op_len == 0 => {
                return Err(Problem::EmptyQuad {
                    x: u32::from(q.x),
                    y: u32::from(q.y),
                })
            }
            Some(_) => {}
        }
        let mut tile = self.open.take().expect("open tile");
        // Free a grown vector's slack (a copy), not a few spare entries.
        for (len, cap) in [
            (tile.quads.len(), tile.quads.capacity()),
            (tile.rej_before.len(), tile.rej_before.capacity()),
            (tile.ops.len(), tile.ops.capacity()),
            (tile.blocks.len(), tile.blocks.capacity()),
        ] {
            if cap > len + len / 8 + 16 {
                tile.quads.shrink_to_fit();
                tile.rej_before.shrink_to_fit();
                tile.ops.shrink_to_fit();
                tile.blocks.shrink_to_fit();
                break;
            }
        }
        self.seen.insert((tile.tx, tile.ty));
        self.tiles.push(tile);
        Ok(())
    }

    /// Moves the tiles of `part`, a trace of the same frame and tile size
    /// (built, say, on another thread), to the end of this one. Fails,
    /// changing nothing, if a tile is open, the frame or tile size differ,
    /// a tile of `part` is already here (or twice in `part`), or this
    /// builder requires scanline order and a tile of `part` breaks it.
    pub fn append(&mut self, part: Trace) -> Result<(), Problem> {
        if let Some(t) = &self.open {
            return Err(Problem::TileNotClosed { tx: t.tx, ty: t.ty });
        }
        let (h, p) = (&self.header, &part.header);
        if (h.frame_w, h.frame_h, h.tile) != (p.frame_w, p.frame_h, p.tile) {
            return Err(Problem::FrameMismatch {
                found: (p.frame_w, p.frame_h, p.tile),
                expected: (h.frame_w, h.frame_h, h.tile),
            });
        }
        let mut new = HashSet::new();
        for tile in &part.tiles {
            if self.seen.contains(&(tile.tx, tile.ty)) || !new.insert((tile.tx, tile.ty)) {
                return Err(Problem::DuplicateTile {
                    tx: tile.tx,
                    ty: tile.ty,
                });
            }
            if self.scanline_order {
                for w in tile.quads.windows(2) {
                    let (a, b) = ((w[0].y, w[0].x), (w[1].y, w[1].x));
                    if a >= b {
                        let (x, y) = (u32::from(b.1), u32::from(b.0));
                        return Err(if a == b {
                            Problem::DuplicateQuad { x, y }
                        } else {
                            Problem::QuadOutOfOrder {
                                x,
                                y,
                                prev_x: u32::from(a.1),
                                prev_y: u32::from(a.0),
                            }
                        });
                    }
                }
            }
        }
        self.seen.extend(new);
        self.tiles.extend(part.tiles);
        Ok(())
    }

    /// The finished trace; fails if a tile is still open.
    pub fn finish(self) -> Result<Trace, Problem> {
        if let Some(t) = &self.open {
            return Err(Problem::TileNotClosed { tx: t.tx, ty: t.ty });
        }
        Ok(Trace {
            header: self.header,
            tiles: self.tiles,
            stats: Memo::default(),
        })
    }
}

fn first_duplicate(blocks: &[u64]) -> Option<u64> {
    if blocks.len() <= 32 {
        for (i, b) in blocks.iter().enumerate() {
            if blocks[..i].contains(b) {
                return Some(*b);
            }
        }
        None
    } else {
        let mut v = blocks.to_vec();
        v.sort_unstable();
        v.windows(2).find(|w| w[0] == w[1]).map(|w| w[0])
    }
}

/// Which free-text header field a [`Problem::BadText`] is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TextField {
    /// The `workload` name.
    Workload,
    /// A header note (comment).
    Note,
}

/// What is wrong with a trace: one broken rule of the format. Its Display
/// reads `what was wrong (expected what)`.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Problem {
    /// The input has no line at all.
    EmptyInput,
    /// `z 0`.
    ZeroRejected,
    /// Rejected quads outside any tile.
    RejectedWithoutTile,
    /// More rejected quads in one place than a record holds.
    RejectedRunTooLong(u64),
    /// Two `z` lines in a row.
    AdjacentRejected,
    /// A `z` line in a trace of a version without them.
    RejectedInOldVersion(u32),
    /// A trilinear texture instruction (`T...`) in a trace of a version
    /// without them (before 4).
    TrilinearInOldVersion {
        /// The file's format version.
        version: u32,
        /// The token.
        token: String,
    },
    /// The input is not UTF-8.
    InvalidUtf8,
    /// A line holds a control character other than tab.
    ControlCharacter,
    /// Line 1 is not `wasp-trace 4`, `3`, `2` or `1`.
    BadMagic(String),
    /// Line 1 names another format version.
    UnsupportedVersion(String),
    /// A header line is missing before this line.
    MissingHeader {
        /// The header line that is missing.
        missing: &'static str,
        /// What was found instead.
        found: String,
    },
    /// A header line appears twice or after the first tile.
    MisplacedHeader(&'static str),
    /// A line starts with an unknown word.
    UnknownDirective {
        /// The word found.
        found: String,
        /// What may appear here.
        expected: &'static str,
    },
    /// A directive line has the wrong number of fields.
    WrongFieldCount {
        /// The directive.
        directive: &'static str,
        /// Fields found (the directive included).
        found: usize,
        /// The line's syntax.
        usage: &'static str,
    },
    /// A decimal field is not a decimal number.
    BadNumber {
        /// The field.
        what: &'static str,
        /// The token.
        found: String,
    },
    /// A number does not fit its range.
    NumberTooLarge {
        /// The field.
        what: &'static str,
        /// The token.
        found: String,
        /// The largest value allowed.
        max: u64,
    },
    /// A block number is not 1 to 16 hex digits.
    BadHex {
        /// The token.
        found: String,
    },
    /// The workload name is empty.
    EmptyWorkload,
    /// A workload name or note holds characters a line cannot.
    BadText {
        /// Which field.
        field: TextField,
        /// Why.
        why: &'static str,
    },
    /// Frame width or height out of range.
    BadFrame {
        /// `width` or `height`.
        dim: &'static str,
        /// The value.
        value: u32,
    },
    /// Tile size not even or out of range.
    BadTileSize(u32),
    /// A tile outside the frame's tile grid.
    TileOutsideFrame {
        /// Tile column.
        tx: u32,
        /// Tile row.
        ty: u32,
        /// Tile columns in the frame.
        tiles_x: u32,
        /// Tile rows in the frame.
        tiles_y: u32,
    },
    /// A tile appears twice.
    DuplicateTile {
        /// Tile column.
        tx: u32,
        /// Tile row.
        ty: u32,
    },
    /// A tile record has no `end` before the next tile or end of input.
    TileNotClosed {
        /// Tile column.
        tx: u32,
        /// Tile row.
        ty: u32,
    },
    /// A tile record has neither a quad nor a rejected quad.
    EmptyTile {
        /// Tile column.
        tx: u32,
        /// Tile row.
        ty: u32,
    },
    /// `end` with no open tile.
    EndWithoutTile,
    /// A quad with no open tile.
    QuadWithoutTile,
    /// An instruction with no open quad (builder only).
    InstrWithoutQuad,
    /// A quad position beyond the tile's edge.
    QuadOutsideTile {
        /// Quad column.
        x: u32,
        /// Quad row.
        y: u32,
        /// Quads per tile edge.
        side: u32,
    },
    /// A quad whose top-left pixel is outside the frame.
    QuadOutsideFrame {
        /// Quad column.
        x: u32,
        /// Quad row.
        y: u32,
        /// Its top-left pixel column.
        px: u64,
        /// Its top-left pixel row.
        py: u64,
    },
    /// A quad appears twice in a tile (version 1 only).
    DuplicateQuad {
        /// Quad column.
        x: u32,
        /// Quad row.
        y: u32,
    },
    /// A quad before its predecessor in scanline order (version 1 only).
    QuadOutOfOrder {
        /// Quad column.
        x: u32,
        /// Quad row.
        y: u32,
        /// Previous quad's column.
        prev_x: u32,
        /// Previous quad's row.
        prev_y: u32,
    },
    /// A quad with no instruction.
    EmptyQuad {
        /// Quad column.
        x: u32,
        /// Quad row.
        y: u32,
    },
    /// An ALU run of length 0.
    ZeroAlu,
    /// An ALU run longer than [`MAX_ALU_RUN`].
    AluRunTooLong(u64),
    /// A quad program of more than [`MAX_QUAD_INSTRS`] instructions.
    QuadTooLong(u64),
    /// Two ALU runs next to each other in the text.
    AdjacentAlu {
        /// The first run.
        first: u32,
        /// The second run.
        second: u32,
    },
    /// An instruction token that is neither `aN` nor `tB,...`.
    BadInstr(String),
    /// A texture instruction without blocks.
    TexNoBlock,
    /// An empty entry in a block list, e.g. `t1,,2`.
    EmptyBlockEntry(String),
    /// A block listed twice in one texture instruction.
    DuplicateBlock(u64),
    /// More than [`MAX_TEX_BLOCKS`] blocks in one texture instruction.
    TooManyBlocks(usize),
    /// A tile whose pools would exceed 2^32 - 1 entries.
    TileTooLarge,
    /// Tiles of another frame or tile size (builder only).
    FrameMismatch {
        /// Their frame width, height and tile size.
        found: (u32, u32, u32),
        /// This trace's.
        expected: (u32, u32, u32),
    },
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use Problem::*;
        match self {
            EmptyInput => write!(
                f,
                "empty input (expected `{MAGIC} {FORMAT_VERSION}`, `{MAGIC} \
                 {FORMAT_VERSION_3}`, `{MAGIC} {FORMAT_VERSION_2}` or `{MAGIC} \
                 {FORMAT_VERSION_1}` on line 1)"
            ),
            InvalidUtf8 => write!(f, "invalid UTF-8 (expected UTF-8 text)"),
            ZeroRejected => write!(f, "0 rejected quads (expected `z N` with N at least 1)"),
            RejectedWithoutTile => write!(
                f,
                "rejected quads outside any tile (expected `tile TX TY` first)"
            ),
            RejectedRunTooLong(n) => write!(
                f,
                "{n} rejected quads in one place (expected 1 to {MAX_REJECTED_RUN})"
            ),
            AdjacentRejected => write!(
                f,
                "two `z` lines in a row (expected one `z N` with their sum)"
            ),
            RejectedInOldVersion(v) => write!(
                f,
                "`z` line in a format-{v} trace (expected `z` lines only from format \
                 {FORMAT_VERSION_3} on: write `{MAGIC} {FORMAT_VERSION}` on line 1)"
            ),
            TrilinearInOldVersion { version, token } => write!(
                f,
                "trilinear texture instruction `{}` in a format-{version} trace \
                 (expected `T` only from format {FORMAT_VERSION} on: write `t`, or \
                 `{MAGIC} {FORMAT_VERSION}` on line 1)",
                clip(token)
            ),
            ControlCharacter => write!(
                f,
                "control character in line (expected printable text, blanks and tabs)"
            ),
            BadMagic(s) => write!(
                f,
                "bad magic line `{}` (expected `{MAGIC} {FORMAT_VERSION}`, `{MAGIC} \
                 {FORMAT_VERSION_3}`, `{MAGIC} {FORMAT_VERSION_2}` or `{MAGIC} \
                 {FORMAT_VERSION_1}` on line 1)",
                clip(s)
            ),
            UnsupportedVersion(v) => write!(
                f,
                "unsupported format version `{}` (expected {FORMAT_VERSION}, \
                 {FORMAT_VERSION_3}, {FORMAT_VERSION_2} or {FORMAT_VERSION_1})",
                clip(v)
            ),
            MissingHeader { missing, found } => write!(
                f,
                "`{}` before the header line `{missing}` (expected `workload NAME` then \
                 `frame W H tile T` before the first tile)",
                clip(found)
            ),
            MisplacedHeader(h) => write!(
                f,
                "header line `{h}` repeated or after the first tile (expected it once, \
                 before the first tile)"
            ),
            UnknownDirective { found, expected } => {
                write!(
                    f,
                    "unknown directive `{}` (expected {expected})",
                    clip(found)
                )
            }
            WrongFieldCount {
                directive,
                found,
                usage,
            } => write!(
                f,
                "`{directive}` line with {found} fields (expected `{usage}`)"
            ),
            BadNumber { what, found } => write!(
                f,
                "bad {what} `{}` (expected a decimal number)",
                clip(found)
            ),
            NumberTooLarge { what, found, max } => write!(
                f,
                "{what} `{}` out of range (expected at most {max})",
                clip(found)
            ),
            BadHex { found } => write!(
                f,
                "bad block number `{}` (expected 1 to 16 hex digits, no `0x`)",
                clip(found)
            ),
            EmptyWorkload => write!(f, "empty workload name (expected `workload NAME`)"),
            BadText { field, why } => {
                let name = match field {
                    TextField::Workload => "workload name",
                    TextField::Note => "header note",
                };
                write!(f, "{name} {why} (expected printable text)")
            }
            BadFrame { dim, value } => write!(
                f,
                "frame {dim} {value} (expected 1 to {MAX_FRAME_DIM} pixels)"
            ),
            BadTileSize(t) => write!(
                f,
                "tile size {t} (expected an even number of pixels from 2 to {MAX_TILE_SIZE})"
            ),
            TileOutsideFrame {
                tx,
                ty,
                tiles_x,
                tiles_y,
            } => write!(
                f,
                "tile {tx} {ty} outside the frame (expected x below {tiles_x} and y below \
                 {tiles_y})"
            ),
            DuplicateTile { tx, ty } => write!(
                f,
                "tile {tx} {ty} appears twice (expected each tile at most once)"
            ),
            TileNotClosed { tx, ty } => write!(
                f,
                "tile {tx} {ty} is not closed (expected `end` before the next tile or the \
                 end of input)"
            ),
            EmptyTile { tx, ty } => write!(
                f,
                "tile {tx} {ty} is empty (expected at least one `q` or `z` line before `end`)"
            ),
            EndWithoutTile => write!(f, "`end` outside any tile (expected `tile TX TY` first)"),
            QuadWithoutTile => write!(f, "quad outside any tile (expected `tile TX TY` first)"),
            InstrWithoutQuad => {
                write!(f, "instruction outside any quad (expected a quad first)")
            }
            QuadOutsideTile { x, y, side } => write!(
                f,
                "quad {x} {y} outside the tile (expected x and y from 0 to {})",
                side.saturating_sub(1)
            ),
            QuadOutsideFrame { x, y, px, py } => write!(
                f,
                "quad {x} {y} at pixel ({px}, {py}) outside the frame (expected its top-left \
                 pixel inside the frame)"
            ),
            DuplicateQuad { x, y } => write!(
                f,
                "quad {x} {y} appears twice in the tile (expected each quad at most once in \
                 format {FORMAT_VERSION_1}; formats {FORMAT_VERSION_2} to {FORMAT_VERSION} \
                 allow repeats)"
            ),
            QuadOutOfOrder {
                x,
                y,
                prev_x,
                prev_y,
            } => write!(
                f,
                "quad {x} {y} after quad {prev_x} {prev_y} (expected scanline order in \
                 format {FORMAT_VERSION_1}: y, then x increasing)"
            ),
            EmptyQuad { x, y } => write!(
                f,
                "quad {x} {y} has no instruction (expected at least one `aN`, `tB,...` or \
                 `TB,...`)"
            ),
            ZeroAlu => write!(f, "ALU run of 0 (expected a run of at least 1)"),
            AluRunTooLong(n) => {
                write!(f, "ALU run of {n} (expected 1 to {MAX_ALU_RUN})")
            }
            QuadTooLong(n) => write!(
                f,
                "quad program of {n} instructions (expected 1 to {MAX_QUAD_INSTRS}, ALU runs \
                 counted by length)"
            ),
            AdjacentAlu { first, second } => write!(
                f,
                "adjacent ALU runs `a{first} a{second}` (expected one run `a{}`)",
                u64::from(*first) + u64::from(*second)
            ),
            BadInstr(s) => write!(
                f,
                "bad instruction `{}` (expected `aN`, `tB,B,...` or `TB,B,...`)",
                clip(s)
            ),
            TexNoBlock => write!(
                f,
                "texture instruction without blocks (expected `t` or `T` and hex block \
                 numbers)"
            ),
            EmptyBlockEntry(s) => write!(
                f,
                "empty block number in `{}` (expected hex digits between commas)",
                clip(s)
            ),
            DuplicateBlock(b) => write!(
                f,
                "block {b:x} listed twice in one texture instruction (expected distinct \
                 blocks)"
            ),
            TooManyBlocks(n) => write!(
                f,
                "texture instruction with {n} blocks (expected at most {MAX_TEX_BLOCKS})"
            ),
            TileTooLarge => write!(
                f,
                "tile too large (expected fewer than 2^32 instruction entries and blocks)"
            ),
            FrameMismatch { found, expected } => write!(
                f,
                "tiles of a {}x{} frame with {}-pixel tiles (expected {}x{} with {}-pixel \
                 tiles)",
                found.0, found.1, found.2, expected.0, expected.1, expected.2
            ),
        }
    }
}

impl std::error::Error for Problem {}

/// Shortens a quoted token in a message so one bad line cannot make a huge
/// error.
fn clip(s: &str) -> String {
    const MAX: usize = 40;
    if s.chars().count() <= MAX {
        s.to_string()
    } else {
        let head: String = s.chars().take(MAX).collect();
        format!("{head}...")
    }
}

/// An error reading a trace.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum TraceError {
    /// The file could not be read.
    Io {
        /// The path.
        path: String,
        /// The operating system's message.
        message: String,
    },
    /// The input breaks the format at a line.
    Malformed {
        /// File name (or the source name given to [`Trace::parse`]).
        source: String,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        problem: Problem,
    },
}

impl TraceError {
    /// The broken rule, if the input was read.
    pub fn problem(&self) -> Option<&Problem> {
        match self {
            TraceError::Io { .. } => None,
            TraceError::Malformed { problem, .. } => Some(problem),
        }
    }

    /// The 1-based line of the problem, if the input was read.
    pub fn line(&self) -> Option<usize> {
        match self {
            TraceError::Io { .. } => None,
            TraceError::Malformed { line, .. } => Some(*line),
        }
    }
}

impl fmt::Display for TraceError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            TraceError::Io { path, message } => write!(f, "{path}: cannot read: {message}"),
            TraceError::Malformed {
                source,
                line,
                problem,
            } => write!(f, "{source}:{line}: {problem}"),
        }
    }
}

impl std::error::Error for TraceError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            TraceError::Io { .. } => None,
            TraceError::Malformed { problem, .. } => Some(problem),
        }
    }
}
