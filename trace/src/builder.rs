//! [`TraceBuilder`]: builds a [`Trace`] step by step and enforces every
//! rule of the format on the way.

use std::collections::HashSet;

use crate::header::{check_text, TraceHeader};
use crate::instr::{Instr, Op};
use crate::limits::{MAX_ALU_RUN, MAX_QUAD_INSTRS, MAX_REJECTED_RUN, MAX_TEX_BLOCKS};
use crate::memo::Memo;
use crate::problem::{Problem, TextField};
use crate::tile::{QuadRec, Tile};
use crate::trace::Trace;

impl Trace {
    /// A builder for a trace with this header (checked here).
    pub fn builder(header: TraceHeader) -> Result<TraceBuilder, Problem> {
        TraceBuilder::new(header)
    }
}

/// Builds a [`Trace`] step by step, enforcing every rule of the format
/// (version 4: quad positions may repeat, in any order, with rejected
/// quads among them, and texture instructions bilinear or trilinear).
///
/// A call that returns an error changes nothing, so a caller may report it
/// and stop. `begin_quad` closes the previous quad, `end_tile` the tile.
///
/// # Frames
///
/// A trace holds one or more frames, each a sequence of tiles (a tile
/// position appears at most once per frame). The builder starts in frame
/// 0; [`next_frame`](TraceBuilder::next_frame) closes the current frame
/// and starts the next. A builder that never calls it builds a one-frame
/// trace, written in format 4 exactly as before frames existed; a trace of
/// two or more frames is written in format 5. To emit frames `A..B` of a
/// capture into one trace:
///
/// ```
/// # use wasp_trace::{Trace, TraceHeader, Instr};
/// let mut b = Trace::builder(TraceHeader::new("capture", 64, 64, 64)).unwrap();
/// for frame in 3..6 {
///     if frame > 3 {
///         b.next_frame().unwrap(); // closes the previous frame
///     }
///     b.begin_tile(0, 0).unwrap(); // the same tile again: a new frame
///     b.quad(0, 0, &[Instr::Alu(frame)]).unwrap();
///     b.end_tile().unwrap();
/// }
/// let t = b.finish().unwrap();
/// assert_eq!(t.frame_count(), 3);
/// assert_eq!(t.frames().collect::<Vec<_>>(), vec![0..1, 1..2, 2..3]);
/// assert!(t.to_text().starts_with("wasp-trace 5\n"));
/// ```
#[derive(Debug)]
pub struct TraceBuilder {
    header: TraceHeader,
    tiles: Vec<Tile>,
    /// The index in `tiles` of each frame's first tile (`[0]` to begin).
    frame_starts: Vec<usize>,
    /// The tile positions of the current frame.
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
            frame_starts: vec![0],
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

    /// Number of closed tiles so far (of every frame).
    pub fn tile_count(&self) -> usize {
        self.tiles.len()
    }

    /// Number of frames so far, the current one included (1 to begin).
    pub fn frame_count(&self) -> usize {
        self.frame_starts.len()
    }

    /// Closes the current frame and starts the next: the tiles built from
    /// now on belong to it, and every tile position is free again. Fails,
    /// changing nothing, if a tile is open ([`Problem::TileNotClosed`]).
    /// A frame may be empty (two calls in a row): a frame that drew
    /// nothing.
    pub fn next_frame(&mut self) -> Result<(), Problem> {
        if let Some(t) = &self.open {
            return Err(Problem::TileNotClosed { tx: t.tx, ty: t.ty });
        }
        self.frame_starts.push(self.tiles.len());
        self.seen.clear();
        Ok(())
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
        if let Some(map) = &self.header.texture_map {
            blocks.iter().try_for_each(|&b| map.check_block(b))?;
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
    /// (built, say, on another thread), to the end of this one: the tiles
    /// of its first frame join the current frame, each later frame of
    /// `part` starts a new frame here. Fails, changing nothing, if a tile
    /// is open, the frame or tile size differ, a tile of `part` is already
    /// in its frame here (or twice in one frame of `part`), or this
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
        for (i, tile) in part.tiles.iter().enumerate() {
            // A new frame of `part` at this tile starts with no position
            // taken; its first frame continues this builder's.
            if part.frame_starts[1..].contains(&i) {
                new.clear();
            }
            let first_frame = i < part.frame_starts.get(1).copied().unwrap_or(usize::MAX);
            let here = first_frame && self.seen.contains(&(tile.tx, tile.ty));
            if here || !new.insert((tile.tx, tile.ty)) {
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
        let base = self.tiles.len();
        if part.frame_starts.len() > 1 {
            // The current frame is now `part`'s last (perhaps empty) one.
            self.seen.clear();
            let last = part.frame_range(part.frame_starts.len() - 1);
            self.seen
                .extend(part.tiles[last].iter().map(|t| (t.tx, t.ty)));
        } else {
            self.seen.extend(new);
        }
        self.frame_starts
            .extend(part.frame_starts[1..].iter().map(|&s| base + s));
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
            frame_starts: self.frame_starts,
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builder_merges_alu_runs_and_rejects_without_changing_state() {
        let mut b = Trace::builder(TraceHeader::new("w", 64, 64, 64)).unwrap();
        assert_eq!(b.alu(1), Err(Problem::InstrWithoutQuad));
        assert_eq!(b.begin_quad(0, 0), Err(Problem::QuadWithoutTile));
        b.begin_tile(0, 0).unwrap();
        assert_eq!(b.end_tile(), Err(Problem::EmptyTile { tx: 0, ty: 0 }));
        b.begin_quad(0, 1).unwrap();
        assert_eq!(b.begin_quad(0, 2), Err(Problem::EmptyQuad { x: 0, y: 1 }));
        b.alu(3).unwrap();
        b.alu(2).unwrap();
        assert_eq!(b.tex(&[5, 5]), Err(Problem::DuplicateBlock(5)));
        assert_eq!(b.tex(&[]), Err(Problem::TexNoBlock));
        b.tex(&[5, 6]).unwrap();
        b.alu(1).unwrap();
        assert_eq!(
            b.alu(MAX_ALU_RUN),
            Err(Problem::AluRunTooLong(1 + u64::from(MAX_ALU_RUN)))
        );
        b.quad(1, 1, &[Instr::Tex(&[7]), Instr::Alu(4)]).unwrap();
        assert_eq!(
            b.finish().unwrap_err(),
            Problem::TileNotClosed { tx: 0, ty: 0 }
        );

        let mut b = Trace::builder(TraceHeader::new("w", 64, 64, 64)).unwrap();
        b.begin_tile(0, 0).unwrap();
        b.quad(
            0,
            1,
            &[
                Instr::Alu(3),
                Instr::Alu(2),
                Instr::Tex(&[5, 6]),
                Instr::Alu(1),
            ],
        )
        .unwrap();
        b.quad(1, 1, &[Instr::Tex(&[7]), Instr::Alu(4)]).unwrap();
        b.end_tile().unwrap();
        assert_eq!(
            b.begin_tile(0, 0),
            Err(Problem::DuplicateTile { tx: 0, ty: 0 })
        );
        let t = b.finish().unwrap();
        let q = t.tiles()[0].quad(0).unwrap();
        assert_eq!(
            q.instrs().collect::<Vec<_>>(),
            vec![Instr::Alu(5), Instr::Tex(&[5, 6]), Instr::Alu(1)]
        );
        assert_eq!(t.tiles()[0].quad(1).unwrap().block_accesses(), &[7]);
        assert_eq!(t.instr_count(), 7 + 5);
        assert_eq!(t.tex_count(), 2);
    }

    #[test]
    fn builder_appends_tiles_built_elsewhere() {
        let part = |tx: u32, quads: &[(u32, u32)]| {
            let mut b = Trace::builder(TraceHeader::new("part", 128, 64, 64)).unwrap();
            b.begin_tile(tx, 0).unwrap();
            for &(x, y) in quads {
                b.quad(x, y, &[Instr::Alu(x + 1)]).unwrap();
            }
            b.end_tile().unwrap();
            b.finish().unwrap()
        };
        let mut b = Trace::builder(TraceHeader::new("w", 128, 64, 64)).unwrap();
        b.append(part(1, &[(3, 0), (1, 0), (3, 0)])).unwrap();
        b.append(part(0, &[(0, 0)])).unwrap();
        assert_eq!(
            b.append(part(1, &[(0, 0)])),
            Err(Problem::DuplicateTile { tx: 1, ty: 0 })
        );
        let other = Trace::builder(TraceHeader::new("w", 64, 64, 64))
            .unwrap()
            .finish()
            .unwrap();
        assert!(matches!(
            b.append(other),
            Err(Problem::FrameMismatch { .. })
        ));
        b.begin_tile(0, 0).unwrap_err(); // already appended
        let t = b.finish().unwrap();
        assert_eq!(t.header().workload, "w");
        let order: Vec<(u32, usize)> = t.tiles().iter().map(|t| (t.tx(), t.quad_count())).collect();
        assert_eq!(order, vec![(1, 3), (0, 1)]);
        // A version-1 builder checks the appended tiles' order.
        let mut b = Trace::builder(TraceHeader::new("w", 128, 64, 64)).unwrap();
        b.require_scanline_order();
        assert_eq!(
            b.append(part(1, &[(3, 0), (1, 0)])),
            Err(Problem::QuadOutOfOrder {
                x: 1,
                y: 0,
                prev_x: 3,
                prev_y: 0
            })
        );
        b.append(part(1, &[(1, 0), (3, 0)])).unwrap();
    }

    #[test]
    fn builder_allows_repeats_unless_scanline_order_is_required() {
        let mut b = Trace::builder(TraceHeader::new("w", 64, 64, 64)).unwrap();
        b.begin_tile(0, 0).unwrap();
        b.quad(0, 1, &[Instr::Alu(1)]).unwrap();
        b.quad(0, 1, &[Instr::Alu(2)]).unwrap();
        b.quad(0, 0, &[Instr::Alu(3)]).unwrap();
        b.end_tile().unwrap();
        let t = b.finish().unwrap();
        let counts: Vec<u64> = t.tiles()[0].quads().map(|q| q.instr_count()).collect();
        assert_eq!(counts, vec![1, 2, 3], "never merged, never reordered");

        let mut b = Trace::builder(TraceHeader::new("w", 64, 64, 64)).unwrap();
        b.require_scanline_order();
        b.begin_tile(0, 0).unwrap();
        b.quad(0, 1, &[Instr::Alu(1)]).unwrap();
        assert_eq!(
            b.begin_quad(0, 1),
            Err(Problem::DuplicateQuad { x: 0, y: 1 })
        );
        assert_eq!(
            b.begin_quad(0, 0),
            Err(Problem::QuadOutOfOrder {
                x: 0,
                y: 0,
                prev_x: 0,
                prev_y: 1
            })
        );
        b.quad(1, 1, &[Instr::Alu(1)]).unwrap();
        b.end_tile().unwrap();
        assert_eq!(b.finish().unwrap().quad_count(), 2);
    }

    #[test]
    fn the_builder_adds_up_rejections_and_keeps_them_canonical() {
        let mut b = Trace::builder(TraceHeader::new("w", 64, 64, 64)).unwrap();
        assert_eq!(b.rejected(1), Err(Problem::RejectedWithoutTile));
        b.begin_tile(0, 0).unwrap();
        assert_eq!(b.rejected(0), Err(Problem::ZeroRejected));
        b.rejected(2).unwrap();
        b.rejected(3).unwrap();
        b.quad(0, 0, &[Instr::Alu(1)]).unwrap();
        b.quad(1, 0, &[Instr::Alu(1)]).unwrap();
        b.rejected(MAX_REJECTED_RUN).unwrap();
        assert!(matches!(b.rejected(1), Err(Problem::RejectedRunTooLong(_))));
        b.end_tile().unwrap();
        let t = b.finish().unwrap();
        let tile = &t.tiles()[0];
        assert_eq!(tile.rejected_before(0), 5);
        assert_eq!(tile.rejected_before(1), 0);
        assert_eq!(tile.rejected_after_last(), MAX_REJECTED_RUN);
        assert!(t
            .to_text()
            .contains("tile 0 0\nz 5\nq 0 0 a1\nq 1 0 a1\nz 4194304\nend\n"));
        // A tile with rejections after its quads only keeps no per-quad list:
        // it equals the same tile read back.
        let mut b = Trace::builder(TraceHeader::new("w", 64, 64, 64)).unwrap();
        b.begin_tile(0, 0).unwrap();
        b.quad(0, 0, &[Instr::Alu(1)]).unwrap();
        b.rejected(4).unwrap();
        b.end_tile().unwrap();
        let t = b.finish().unwrap();
        assert_eq!(Trace::parse(&t.to_text(), "rt").unwrap(), t);
    }

    #[test]
    fn a_failed_rejection_changes_nothing() {
        let mut b = Trace::builder(TraceHeader::new("w", 64, 64, 64)).unwrap();
        b.begin_tile(0, 0).unwrap();
        b.begin_quad(0, 0).unwrap();
        // The open quad has no instruction yet.
        assert_eq!(b.rejected(2), Err(Problem::EmptyQuad { x: 0, y: 0 }));
        b.alu(1).unwrap();
        b.rejected(MAX_REJECTED_RUN - 1).unwrap();
        assert_eq!(
            b.rejected(2),
            Err(Problem::RejectedRunTooLong(u64::from(MAX_REJECTED_RUN) + 1))
        );
        b.rejected(1).unwrap();
        b.end_tile().unwrap();
        assert_eq!(b.rejected(1), Err(Problem::RejectedWithoutTile));
        let t = b.finish().unwrap();
        assert_eq!(t.tiles()[0].rejected_after_last(), MAX_REJECTED_RUN);
        assert_eq!(t.tiles()[0].rejected_before(0), 0);
        // A tile with no line at all is still refused.
        let mut b = Trace::builder(TraceHeader::new("w", 64, 64, 64)).unwrap();
        b.begin_tile(0, 0).unwrap();
        assert_eq!(b.rejected(0), Err(Problem::ZeroRejected));
        assert_eq!(b.end_tile(), Err(Problem::EmptyTile { tx: 0, ty: 0 }));
    }

    #[test]
    fn the_builder_holds_a_quad_program_to_its_bound() {
        let mut b = Trace::builder(TraceHeader::new("w", 64, 64, 64)).unwrap();
        b.begin_tile(0, 0).unwrap();
        b.begin_quad(0, 0).unwrap();
        let runs = MAX_QUAD_INSTRS / MAX_ALU_RUN - 1;
        for _ in 0..runs {
            b.alu(MAX_ALU_RUN).unwrap();
            b.tex(&[1]).unwrap();
        }
        b.alu(MAX_QUAD_INSTRS - runs * (MAX_ALU_RUN + 1)).unwrap();
        // The program is full: nothing more fits, and a refusal changes nothing.
        assert_eq!(
            b.alu(1),
            Err(Problem::QuadTooLong(u64::from(MAX_QUAD_INSTRS) + 1))
        );
        assert_eq!(
            b.tex(&[2]),
            Err(Problem::QuadTooLong(u64::from(MAX_QUAD_INSTRS) + 1))
        );
        // The next quad starts from zero.
        b.begin_quad(1, 0).unwrap();
        b.alu(MAX_ALU_RUN).unwrap();
        b.end_tile().unwrap();
        b.finish().unwrap();
    }
}
