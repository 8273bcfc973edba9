//! [`Problem`]: one broken rule of the format, and how its message reads.

use crate::limits::{
    FORMAT_VERSION, FORMAT_VERSION_1, FORMAT_VERSION_2, FORMAT_VERSION_3, FORMAT_VERSION_FRAMES,
    FRAME_MARKER, MAGIC, MAX_ALU_RUN, MAX_FRAME_DIM, MAX_QUAD_INSTRS, MAX_REJECTED_RUN,
    MAX_TEX_BLOCKS, MAX_TILE_SIZE,
};

/// Which free-text header field a [`Problem::BadText`] is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TextField {
    /// The `workload` name.
    Workload,
    /// A header note (comment).
    Note,
}

/// What is wrong with a trace: one broken rule of the format. Its Display
/// reads `what was wrong (expected what)`; each variant's message stands
/// beside it.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum Problem {
    /// The input has no line at all.
    #[error(
        "empty input (expected `{MAGIC} {FORMAT_VERSION_FRAMES}`, `{MAGIC} {FORMAT_VERSION}`, \
         `{MAGIC} {FORMAT_VERSION_3}`, `{MAGIC} {FORMAT_VERSION_2}` or `{MAGIC} \
         {FORMAT_VERSION_1}` on line 1)"
    )]
    EmptyInput,
    /// `z 0`.
    #[error("0 rejected quads (expected `z N` with N at least 1)")]
    ZeroRejected,
    /// Rejected quads outside any tile.
    #[error("rejected quads outside any tile (expected `tile TX TY` first)")]
    RejectedWithoutTile,
    /// More rejected quads in one place than a record holds.
    #[error("{0} rejected quads in one place (expected 1 to {MAX_REJECTED_RUN})")]
    RejectedRunTooLong(u64),
    /// Two `z` lines in a row.
    #[error("two `z` lines in a row (expected one `z N` with their sum)")]
    AdjacentRejected,
    /// A `z` line in a trace of a version without them.
    #[error(
        "`z` line in a format-{0} trace (expected `z` lines only from format \
         {FORMAT_VERSION_3} on: write `{MAGIC} {FORMAT_VERSION}` on line 1)"
    )]
    RejectedInOldVersion(u32),
    /// A frame boundary (`next-frame`) in a trace of a version without
    /// them (before 5).
    #[error(
        "`{FRAME_MARKER}` line in a format-{0} trace (expected frame boundaries only in format \
         {FORMAT_VERSION_FRAMES}: write `{MAGIC} {FORMAT_VERSION_FRAMES}` on line 1)"
    )]
    FrameMarkerInOldVersion(u32),
    /// A trilinear texture instruction (`T...`) in a trace of a version
    /// without them (before 4).
    #[error(
        "trilinear texture instruction `{}` in a format-{version} trace (expected `T` only \
         from format {FORMAT_VERSION} on: write `t`, or `{MAGIC} {FORMAT_VERSION}` on line 1)",
        clip(.token)
    )]
    TrilinearInOldVersion {
        /// The file's format version.
        version: u32,
        /// The token.
        token: String,
    },
    /// The input is not UTF-8.
    #[error("invalid UTF-8 (expected UTF-8 text)")]
    InvalidUtf8,
    /// A line holds a control character other than tab.
    #[error("control character in line (expected printable text, blanks and tabs)")]
    ControlCharacter,
    /// Line 1 is not `wasp-trace 5`, `4`, `3`, `2` or `1`.
    #[error(
        "bad magic line `{}` (expected `{MAGIC} {FORMAT_VERSION_FRAMES}`, `{MAGIC} \
         {FORMAT_VERSION}`, `{MAGIC} {FORMAT_VERSION_3}`, `{MAGIC} {FORMAT_VERSION_2}` or \
         `{MAGIC} {FORMAT_VERSION_1}` on line 1)",
        clip(.0)
    )]
    BadMagic(String),
    /// Line 1 names another format version.
    #[error(
        "unsupported format version `{}` (expected {FORMAT_VERSION_FRAMES}, {FORMAT_VERSION}, \
         {FORMAT_VERSION_3}, {FORMAT_VERSION_2} or {FORMAT_VERSION_1})",
        clip(.0)
    )]
    UnsupportedVersion(String),
    /// A header line is missing before this line.
    #[error(
        "`{}` before the header line `{missing}` (expected `workload NAME` then \
         `frame W H tile T` before the first tile)",
        clip(.found)
    )]
    MissingHeader {
        /// The header line that is missing.
        missing: &'static str,
        /// What was found instead.
        found: String,
    },
    /// A header line appears twice or after the first tile.
    #[error("{}", misplaced_header(.0))]
    MisplacedHeader(&'static str),
    /// A line starts with an unknown word.
    #[error("unknown directive `{}` (expected {expected})", clip(.found))]
    UnknownDirective {
        /// The word found.
        found: String,
        /// What may appear here.
        expected: &'static str,
    },
    /// A directive line has the wrong number of fields.
    #[error("`{directive}` line with {found} fields (expected `{usage}`)")]
    WrongFieldCount {
        /// The directive.
        directive: &'static str,
        /// Fields found (the directive included).
        found: usize,
        /// The line's syntax.
        usage: &'static str,
    },
    /// A decimal field is not a decimal number.
    #[error("bad {what} `{}` (expected a decimal number)", clip(.found))]
    BadNumber {
        /// The field.
        what: &'static str,
        /// The token.
        found: String,
    },
    /// A number does not fit its range.
    #[error("{what} `{}` out of range (expected at most {max})", clip(.found))]
    NumberTooLarge {
        /// The field.
        what: &'static str,
        /// The token.
        found: String,
        /// The largest value allowed.
        max: u64,
    },
    /// A block number is not 1 to 16 hex digits.
    #[error(
        "bad block number `{}` (expected 1 to 16 hex digits, no `0x`)",
        clip(.found)
    )]
    BadHex {
        /// The token.
        found: String,
    },
    /// The workload name is empty.
    #[error("empty workload name (expected `workload NAME`)")]
    EmptyWorkload,
    /// A `texture-format` name that is not 1 to 32 lowercase letters,
    /// digits and `-`.
    #[error(
        "texture format `{}` (expected 1 to 32 lowercase letters, digits and `-`, \
         e.g. `texture-format etc2`)",
        clip(.0)
    )]
    BadTextureFormat(String),
    /// A `texture-lines` line other than `texture-lines decoded`, or one
    /// repeated or misplaced (its word, as found).
    #[error(
        "`texture-lines {}` (expected `texture-lines decoded`, at most once, after \
         `workload NAME` and before the `texture-level` lines and `frame W H tile T`)",
        clip(.0)
    )]
    BadTextureLines(String),
    /// A `texture-level` line that is malformed, misplaced or does not fit
    /// the levels before it (why).
    #[error(
        "bad `texture-level` line: {0} (expected `texture-level R0 RW RH S0 SW SH RX RY` \
         after `texture-lines decoded`, before `frame W H tile T`)"
    )]
    BadTextureLevel(String),
    /// A texture instruction's block that lies in no `texture-level` of a
    /// decoded-lines trace, or outside its level's stored grid.
    #[error(
        "block {0:x} lies in no `texture-level` of this decoded-lines trace, or outside \
         its level's stored grid (expected every texture block inside a level)"
    )]
    BlockOutsideTextureMap(u64),
    /// A workload name or note holds characters a line cannot.
    #[error("{} {why} (expected printable text)", .field.name())]
    BadText {
        /// Which field.
        field: TextField,
        /// Why.
        why: &'static str,
    },
    /// Frame width or height out of range.
    #[error("frame {dim} {value} (expected 1 to {MAX_FRAME_DIM} pixels)")]
    BadFrame {
        /// `width` or `height`.
        dim: &'static str,
        /// The value.
        value: u32,
    },
    /// Tile size not even or out of range.
    #[error("tile size {0} (expected an even number of pixels from 2 to {MAX_TILE_SIZE})")]
    BadTileSize(u32),
    /// A tile outside the frame's tile grid.
    #[error("tile {tx} {ty} outside the frame (expected x below {tiles_x} and y below {tiles_y})")]
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
    #[error("tile {tx} {ty} appears twice (expected each tile at most once per frame)")]
    DuplicateTile {
        /// Tile column.
        tx: u32,
        /// Tile row.
        ty: u32,
    },
    /// A tile record has no `end` before the next tile or end of input.
    #[error(
        "tile {tx} {ty} is not closed (expected `end` before the next tile or the end of input)"
    )]
    TileNotClosed {
        /// Tile column.
        tx: u32,
        /// Tile row.
        ty: u32,
    },
    /// A tile record has neither a quad nor a rejected quad.
    #[error("tile {tx} {ty} is empty (expected at least one `q` or `z` line before `end`)")]
    EmptyTile {
        /// Tile column.
        tx: u32,
        /// Tile row.
        ty: u32,
    },
    /// `end` with no open tile.
    #[error("`end` outside any tile (expected `tile TX TY` first)")]
    EndWithoutTile,
    /// A quad with no open tile.
    #[error("quad outside any tile (expected `tile TX TY` first)")]
    QuadWithoutTile,
    /// An instruction with no open quad (builder only).
    #[error("instruction outside any quad (expected a quad first)")]
    InstrWithoutQuad,
    /// A quad position beyond the tile's edge.
    #[error(
        "quad {x} {y} outside the tile (expected x and y from 0 to {})",
        .side.saturating_sub(1)
    )]
    QuadOutsideTile {
        /// Quad column.
        x: u32,
        /// Quad row.
        y: u32,
        /// Quads per tile edge.
        side: u32,
    },
    /// A quad whose top-left pixel is outside the frame.
    #[error(
        "quad {x} {y} at pixel ({px}, {py}) outside the frame (expected its top-left pixel \
         inside the frame)"
    )]
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
    #[error(
        "quad {x} {y} appears twice in the tile (expected each quad at most once in format \
         {FORMAT_VERSION_1}; formats {FORMAT_VERSION_2} to {FORMAT_VERSION} allow repeats)"
    )]
    DuplicateQuad {
        /// Quad column.
        x: u32,
        /// Quad row.
        y: u32,
    },
    /// A quad before its predecessor in scanline order (version 1 only).
    #[error(
        "quad {x} {y} after quad {prev_x} {prev_y} (expected scanline order in format \
         {FORMAT_VERSION_1}: y, then x increasing)"
    )]
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
    #[error("quad {x} {y} has no instruction (expected at least one `aN`, `tB,...` or `TB,...`)")]
    EmptyQuad {
        /// Quad column.
        x: u32,
        /// Quad row.
        y: u32,
    },
    /// An ALU run of length 0.
    #[error("ALU run of 0 (expected a run of at least 1)")]
    ZeroAlu,
    /// An ALU run longer than [`MAX_ALU_RUN`].
    #[error("ALU run of {0} (expected 1 to {MAX_ALU_RUN})")]
    AluRunTooLong(u64),
    /// A quad program of more than [`MAX_QUAD_INSTRS`] instructions.
    #[error(
        "quad program of {0} instructions (expected 1 to {MAX_QUAD_INSTRS}, ALU runs counted \
         by length)"
    )]
    QuadTooLong(u64),
    /// Two ALU runs next to each other in the text.
    #[error(
        "adjacent ALU runs `a{first} a{second}` (expected one run `a{}`)",
        u64::from(*.first) + u64::from(*.second)
    )]
    AdjacentAlu {
        /// The first run.
        first: u32,
        /// The second run.
        second: u32,
    },
    /// An instruction token that is neither `aN` nor `tB,...`.
    #[error(
        "bad instruction `{}` (expected `aN`, `tB,B,...` or `TB,B,...`)",
        clip(.0)
    )]
    BadInstr(String),
    /// A texture instruction without blocks.
    #[error("texture instruction without blocks (expected `t` or `T` and hex block numbers)")]
    TexNoBlock,
    /// An empty entry in a block list, e.g. `t1,,2`.
    #[error(
        "empty block number in `{}` (expected hex digits between commas)",
        clip(.0)
    )]
    EmptyBlockEntry(String),
    /// A block listed twice in one texture instruction.
    #[error("block {0:x} listed twice in one texture instruction (expected distinct blocks)")]
    DuplicateBlock(u64),
    /// More than [`MAX_TEX_BLOCKS`] blocks in one texture instruction.
    #[error("texture instruction with {0} blocks (expected at most {MAX_TEX_BLOCKS})")]
    TooManyBlocks(usize),
    /// A tile whose pools would exceed 2^32 - 1 entries.
    #[error("tile too large (expected fewer than 2^32 instruction entries and blocks)")]
    TileTooLarge,
    /// Tiles of another frame or tile size (builder only).
    #[error(
        "tiles of a {}x{} frame with {}-pixel tiles (expected {}x{} with {}-pixel tiles)",
        .found.0, .found.1, .found.2, .expected.0, .expected.1, .expected.2
    )]
    FrameMismatch {
        /// Their frame width, height and tile size.
        found: (u32, u32, u32),
        /// This trace's.
        expected: (u32, u32, u32),
    },
}

impl TextField {
    /// How a message names the field.
    fn name(self) -> &'static str {
        match self {
            TextField::Workload => "workload name",
            TextField::Note => "header note",
        }
    }
}

/// The message of [`Problem::MisplacedHeader`]: `texture-format` has its
/// own place in the header, the other header lines precede the first tile.
fn misplaced_header(header: &str) -> String {
    if header == "texture-format" {
        "header line `texture-format` repeated or after the `frame` line (expected it at most \
         once, between `workload NAME` and `frame W H tile T`)"
            .to_string()
    } else {
        format!(
            "header line `{header}` repeated or after the first tile (expected it once, before \
             the first tile)"
        )
    }
}

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

#[cfg(test)]
mod tests {
    use crate::testkit::*;

    #[test]
    fn error_messages_read_well() {
        let (_, _, msg) = fail(&body("tile 0 0\nq 40 3 a1\n"));
        assert_eq!(
            msg,
            "x.trace:5: quad 40 3 outside the tile (expected x and y from 0 to 31)"
        );
        let (_, _, msg) = fail("wasp-trace 6\n");
        assert_eq!(
            msg,
            "x.trace:1: unsupported format version `6` (expected 5, 4, 3, 2 or 1)"
        );
        let (_, _, msg) = fail(&body("tile 0 0\nq 0 0 a1\nend\nnext-frame\n"));
        assert_eq!(
            msg,
            "x.trace:7: `next-frame` line in a format-2 trace (expected frame boundaries only \
             in format 5: write `wasp-trace 5` on line 1)"
        );
        let (_, _, msg) = fail(&body1("tile 0 0\nq 1 0 a1\nq 1 0 a2\n"));
        assert_eq!(
            msg,
            "x.trace:6: quad 1 0 appears twice in the tile (expected each quad at most once in \
             format 1; formats 2 to 4 allow repeats)"
        );
        let (_, _, msg) = fail(&body1("tile 0 0\nq 1 1 a1\nq 2 0 a1\n"));
        assert_eq!(
            msg,
            "x.trace:6: quad 2 0 after quad 1 1 (expected scanline order in format 1: y, then x \
             increasing)"
        );
        let (_, _, msg) = fail(&body("tile 0 0\nq 0 0 t1,1\n"));
        assert_eq!(
            msg,
            "x.trace:5: block 1 listed twice in one texture instruction (expected distinct blocks)"
        );
        let (_, _, msg) = fail(&body(&format!("tile 0 0\nq 0 0 a{}\n", "9".repeat(200))));
        assert!(msg.len() < 200, "{msg}");
    }
}
