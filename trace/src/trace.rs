//! A whole trace ([`Trace`]): the header and the tiles in traversal order,
//! with whole-trace counts.

use crate::header::{check_text, TraceHeader};
use crate::memo::Memo;
use crate::problem::{Problem, TextField};
use crate::stats::TraceStats;
use crate::tile::Tile;

/// A whole trace: header and tiles in traversal (file) order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Trace {
    pub(crate) header: TraceHeader,
    pub(crate) tiles: Vec<Tile>,
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
