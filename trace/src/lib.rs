//! The wasp trace: the shaded quads of one or more frames, tile by tile, the quads
//! Early-Z rejected between them, and the instructions each shaded quad's
//! shader executes — the input of the cycle model.
//!
//! # Format `wasp-trace 4` and `5` (and `wasp-trace 3`, `2`, `1`)
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
//! * **Line 1** is exactly `wasp-trace 4` (`wasp-trace 5` for a trace of
//!   several frames, or, below, `wasp-trace 3`, `wasp-trace 2` or
//!   `wasp-trace 1`): the magic word and the format version. A reader
//!   rejects any other version.
//! * **Comments**: a line whose first non-blank character is `#` is a comment;
//!   blank lines are ignored. Both may appear anywhere after line 1. Comments
//!   before the `frame` line are the header *notes*: a reader keeps their text
//!   (everything after the `#`, verbatim) and a writer writes them back right
//!   after line 1. Other comments are dropped. There are no comments at the end
//!   of a line.
//! * **Header**, before the first tile and in this order, each exactly once
//!   (`texture-format` and `texture-lines` at most once):
//!   * `workload NAME` — provenance: NAME is the rest of the line, not empty.
//!     A synthetic workload's name starts with `synthetic:` and names its
//!     generator parameters.
//!   * `texture-format NAME` (optional) — how the textures whose blocks the
//!     texture instructions list are stored: NAME is 1 to 32 lowercase
//!     letters, digits and `-`, the front end's format choice (`etc2`,
//!     `etc2-rgb`, `etc2-rgba`, `astc-4x4`, `astc-6x6`, `astc-8x8`: see
//!     `docs/textures.md`). Without the line a trace does not say; a trace of
//!     the front end then holds RGBA8 textures (a 64-byte block is 4x4
//!     texels), as every trace did before the line existed, and the front
//!     end writes no line for RGBA8, so such traces are unchanged. A reader
//!     accepts the line in every version and keeps its name; it changes
//!     nothing the cycle model does (a block is a block).
//!   * `texture-lines decoded` (optional, at most once) and its
//!     `texture-level R0 RW RH S0 SW SH RX RY` lines (any number, after it)
//!     — the texture instructions list the lines of the *decoded* texels
//!     (RGBA8, 4x4 texels a 64-byte line, laid out as an RGBA8 trace's),
//!     for a machine whose L0/L1 texture caches hold decompressed texels
//!     (`memory.texture_cache = "decompressed"`), while memory holds the
//!     textures as `texture-format` says. Each `texture-level` line maps one
//!     mip level: R0 (hex) is its first RGBA8 line and RW x RH its grid of
//!     RGBA8 lines, S0 (hex) its first stored (compressed) line and SW x SH
//!     that grid (all four powers of two, 1 to 65536), and RX x RY (1 to 16
//!     each) the RGBA8 lines one stored line holds. Both grids are laid out
//!     in Morton squares (docs/textures.md), and RGBA8 line (x, y) of a level
//!     lies in stored line (x / RX, y / RY). Levels appear in increasing R0
//!     order and do not overlap; every block of every texture instruction
//!     lies in a level and maps inside its stored grid. Without the line the
//!     texture instructions list the stored lines, as in every trace before
//!     the line existed.
//!   * `frame W H tile T` — frame width and height in pixels (1 to 65536) and
//!     the tile edge in pixels (even, 2 to 512). The frame is cut into
//!     ceil(W/T) x ceil(H/T) tiles; a tile holds (T/2) x (T/2) quads of 2x2
//!     pixels (32 x 32 for the paper's 64-pixel tiles).
//! * **Tile record**: `tile TX TY` (tile column and row, inside the frame),
//!   then the tile's `q` lines (one per warp) and `z` lines (rejected quads)
//!   in rasterization order, then `end` alone on its line. A tile appears at
//!   most once per frame and holds at least one line, a `q` or a `z`: a tile of `z`
//!   lines only is a tile whose every quad Early-Z rejected (it costs the
//!   rasterizer time and launches no warp). Tiles appear in traversal order
//!   (the front end emits Z-order; a reader does not check the order).
//! * **Frames** (version 5): `next-frame` alone on its line, outside any
//!   tile record, ends a frame and starts the next. A trace without such a
//!   line is one frame; with N of them it has N + 1 frames, in file order,
//!   each a sequence of tile records as above, all of the header's frame and
//!   tile size. A frame may hold no tile (a `next-frame` line right after
//!   the header, after another, or at the end of the file): a frame that
//!   drew nothing. The cycle model runs the frames in order, caches and
//!   main memory carrying over from one to the next (`docs/model.md`).
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
//! **Version 5** (`wasp-trace 5`) is version 4 with `next-frame` lines. A
//! writer writes version 5 exactly when the trace has two or more frames,
//! and version 4 otherwise, so a one-frame trace is written as it was
//! before frames existed; a version-5 file of one frame reads as that trace
//! and is written back in version 4 (line 1 changes). A reader rejects a
//! `next-frame` line in a version-4 (or older) file, naming the version.
//! Every version-4 trace is a version-5 trace of one frame.
//!
//! **Version 3** (`wasp-trace 3`) is version 4 without `T` instructions: it
//! does not say which samples are trilinear, and a reader takes every
//! texture instruction of a version-3 (or older) file as bilinear. A reader
//! rejects a `T` instruction in a version-3, -2 or -1 file, naming the
//! version and the token. Every version-3 trace is a version-4 trace, and a
//! writer writes version 4 (5 for several frames): reading an older file and
//! writing it back changes line 1 only (for a file in the writer's canonical
//! form).
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
//! **Texture coordinates.** A texture instruction's blocks are what its
//! sample read; the format does not say how its texture coordinates were
//! made. A prefetcher that requests the blocks before the shader runs (the
//! model's `prefetch.kind` `raster` and `oracle-tile`) needs coordinates known
//! at rasterization: interpolated vertex attributes. A *dependent* read,
//! whose coordinates the shader computes (from another texture's texels, or
//! by arithmetic on the attributes), could not be requested before the
//! shader reaches it. No version of the format marks dependent reads. The
//! front end samples every texture at interpolated UVs (each texture
//! instruction reads its material's UV set, `frontend/src/shader.rs`), so
//! every texture instruction of its traces is prefetchable, and the model
//! takes every texture instruction of every trace as prefetchable.
//!
//! # In memory
//!
//! [`Trace`] holds a [`TraceHeader`] and the [`Tile`]s in file order, with
//! the index of each frame's first tile ([`Trace::frames`] gives each
//! frame's tiles as a range; [`TraceBuilder::next_frame`] starts a frame). A tile
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

mod builder;
mod error;
mod header;
mod instr;
mod limits;
mod memo;
mod problem;
mod read;
pub mod rng;
mod stats;
#[cfg(test)]
mod testkit;
#[cfg(test)]
mod tests;
mod texmap;
mod tile;
mod trace;
mod write;
mod zorder;

pub use builder::TraceBuilder;
pub use error::TraceError;
pub use header::TraceHeader;
pub use instr::{Instr, OpKind};
pub use limits::{
    FORMAT_VERSION, FORMAT_VERSION_1, FORMAT_VERSION_2, FORMAT_VERSION_3, FORMAT_VERSION_FRAMES,
    FRAME_MARKER, MAGIC, MAX_ALU_RUN, MAX_FRAME_DIM, MAX_QUAD_INSTRS, MAX_REJECTED_RUN,
    MAX_TEX_BLOCKS, MAX_TILE_SIZE,
};
pub use problem::{Problem, TextField};
pub use stats::{
    footprint_ratio, mean_footprint_ratio, mean_footprint_ratio_of, TileStats, TraceStats,
};
pub use texmap::{MapLevel, TextureMap, MAX_GRID, MAX_LINES_PER_LINE};
pub use tile::{Instrs, QuadRef, QuadSpan, Quads, Tile};
pub use trace::Trace;
pub use zorder::{morton, z_order};
