//! [`Problem`]: one broken rule of the format, and how its message reads.

use std::fmt;

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
    /// A frame boundary (`next-frame`) in a trace of a version without
    /// them (before 5).
    FrameMarkerInOldVersion(u32),
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
    /// Line 1 is not `wasp-trace 5`, `4`, `3`, `2` or `1`.
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
    /// A `texture-format` name that is not 1 to 32 lowercase letters,
    /// digits and `-`.
    BadTextureFormat(String),
    /// A `texture-lines` line other than `texture-lines decoded`, or one
    /// repeated or misplaced (its word, as found).
    BadTextureLines(String),
    /// A `texture-level` line that is malformed, misplaced or does not fit
    /// the levels before it (why).
    BadTextureLevel(String),
    /// A texture instruction's block that lies in no `texture-level` of a
    /// decoded-lines trace, or outside its level's stored grid.
    BlockOutsideTextureMap(u64),
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
    // Long on purpose: one arm per variant, each arm that variant's whole
    // message, so the match is the table of messages, read by variant.
    // Split into groups it would name every variant twice (once to route
    // it, once to word it) and need an unreachable arm per group.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use Problem::*;
        match self {
            EmptyInput => write!(
                f,
                "empty input (expected `{MAGIC} {FORMAT_VERSION_FRAMES}`, `{MAGIC} \
                 {FORMAT_VERSION}`, `{MAGIC} {FORMAT_VERSION_3}`, `{MAGIC} \
                 {FORMAT_VERSION_2}` or `{MAGIC} {FORMAT_VERSION_1}` on line 1)"
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
            FrameMarkerInOldVersion(v) => write!(
                f,
                "`{FRAME_MARKER}` line in a format-{v} trace (expected frame boundaries \
                 only in format {FORMAT_VERSION_FRAMES}: write `{MAGIC} \
                 {FORMAT_VERSION_FRAMES}` on line 1)"
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
                "bad magic line `{}` (expected `{MAGIC} {FORMAT_VERSION_FRAMES}`, `{MAGIC} \
                 {FORMAT_VERSION}`, `{MAGIC} {FORMAT_VERSION_3}`, `{MAGIC} \
                 {FORMAT_VERSION_2}` or `{MAGIC} {FORMAT_VERSION_1}` on line 1)",
                clip(s)
            ),
            UnsupportedVersion(v) => write!(
                f,
                "unsupported format version `{}` (expected {FORMAT_VERSION_FRAMES}, \
                 {FORMAT_VERSION}, {FORMAT_VERSION_3}, {FORMAT_VERSION_2} or \
                 {FORMAT_VERSION_1})",
                clip(v)
            ),
            MissingHeader { missing, found } => write!(
                f,
                "`{}` before the header line `{missing}` (expected `workload NAME` then \
                 `frame W H tile T` before the first tile)",
                clip(found)
            ),
            MisplacedHeader("texture-format") => write!(
                f,
                "header line `texture-format` repeated or after the `frame` line (expected \
                 it at most once, between `workload NAME` and `frame W H tile T`)"
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
            BadTextureFormat(s) => write!(
                f,
                "texture format `{}` (expected 1 to 32 lowercase letters, digits and `-`, \
                 e.g. `texture-format etc2`)",
                clip(s)
            ),
            BadTextureLines(s) => write!(
                f,
                "`texture-lines {}` (expected `texture-lines decoded`, at most once, after \
                 `workload NAME` and before the `texture-level` lines and `frame W H tile T`)",
                clip(s)
            ),
            BadTextureLevel(why) => write!(
                f,
                "bad `texture-level` line: {why} (expected `texture-level R0 RW RH S0 SW SH RX RY` \
                 after `texture-lines decoded`, before `frame W H tile T`)"
            ),
            BlockOutsideTextureMap(b) => write!(
                f,
                "block {b:x} lies in no `texture-level` of this decoded-lines trace, or outside \
                 its level's stored grid (expected every texture block inside a level)"
            ),
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
                "tile {tx} {ty} appears twice (expected each tile at most once per frame)"
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
