//! The format's fixed words and numbers: the magic word of line 1, the
//! versions a reader accepts and the bounds on every number of a trace.

/// The magic word on line 1.
pub const MAGIC: &str = "wasp-trace";
/// The format version this crate writes a one-frame trace in (and reads).
pub const FORMAT_VERSION: u32 = 4;
/// The format version of a trace of two or more frames: version 4 with
/// [`FRAME_MARKER`] lines between frames. This crate writes a trace in it
/// exactly when the trace has two or more frames, so a one-frame trace is
/// written as before frames existed.
pub const FORMAT_VERSION_FRAMES: u32 = 5;
/// The line between two frames of a format-5 trace.
pub const FRAME_MARKER: &str = "next-frame";
/// The previous version, which this crate also reads: no trilinear
/// marker (`T`), every texture instruction taken as bilinear.
pub const FORMAT_VERSION_3: u32 = 3;
/// The version before, which this crate also reads: no `z` records.
pub const FORMAT_VERSION_2: u32 = 2;
/// The older version this crate also reads: one quad per position, in
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
