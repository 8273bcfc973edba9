//! A whole trace ([`Trace`]): the header, the tiles in traversal order
//! and the frames they form, with whole-trace counts.

use std::ops::Range;

use crate::header::{check_text, TraceHeader};
use crate::memo::Memo;
use crate::problem::{Problem, TextField};
use crate::stats::TraceStats;
use crate::tile::Tile;
use crate::TraceBuilder;

/// A whole trace: header and tiles in traversal (file) order, cut into
/// one or more frames (consecutive runs of tiles, see [`Trace::frames`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Trace {
    pub(crate) header: TraceHeader,
    pub(crate) tiles: Vec<Tile>,
    /// The index in `tiles` of each frame's first tile: `[0]` for a
    /// one-frame trace, increasing (equal for an empty frame).
    pub(crate) frame_starts: Vec<usize>,
    /// Its statistics, computed on first use: every run's report reads
    /// them, and `wasp compare` runs several policies on one trace.
    pub(crate) stats: Memo<TraceStats>,
}

impl Trace {
    /// The header.
    pub fn header(&self) -> &TraceHeader {
        &self.header
    }

    /// The tiles in traversal order.
    pub fn tiles(&self) -> &[Tile] {
        &self.tiles
    }

    /// Frames in the trace (at least 1).
    pub fn frame_count(&self) -> usize {
        self.frame_starts.len()
    }

    /// The frames in order, each as the range of its tiles in
    /// [`tiles`](Self::tiles): consecutive, together covering every tile.
    /// A frame may be empty (nothing was drawn). A one-frame trace has the
    /// one range `0..tiles().len()`.
    pub fn frames(&self) -> impl ExactSizeIterator<Item = Range<usize>> + '_ {
        (0..self.frame_starts.len()).map(|i| self.frame_range(i))
    }

    /// The tiles of frame `frame` as a range of [`tiles`](Self::tiles).
    ///
    /// # Panics
    ///
    /// If `frame >= frame_count()`.
    pub fn frame_range(&self, frame: usize) -> Range<usize> {
        let start = self.frame_starts[frame];
        let end = self
            .frame_starts
            .get(frame + 1)
            .copied()
            .unwrap_or(self.tiles.len());
        start..end
    }

    /// The tiles of frame `frame` (see [`frame_range`](Self::frame_range)).
    pub fn frame_tiles(&self, frame: usize) -> &[Tile] {
        &self.tiles[self.frame_range(frame)]
    }

    /// The frame that tile `tile` (an index in [`tiles`](Self::tiles))
    /// belongs to.
    pub fn frame_of_tile(&self, tile: usize) -> usize {
        self.frame_starts.partition_point(|&s| s <= tile) - 1
    }

    /// The frames of `first`, then those of each trace of `rest`, in one
    /// trace with `first`'s header (its workload and notes): what `wasp
    /// trace-cat` writes. Fails if a trace of `rest` has another frame or
    /// tile size ([`Problem::FrameMismatch`]).
    pub fn concat(first: Trace, rest: impl IntoIterator<Item = Trace>) -> Result<Trace, Problem> {
        let mut b = TraceBuilder::new(first.header.clone())?;
        b.append(first)?;
        for t in rest {
            b.next_frame()?;
            b.append(t)?;
        }
        b.finish()
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
}
