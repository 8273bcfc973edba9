//! The texture path: mip chains, the block-linear layout of the texture
//! heap, level-of-detail selection, the texels a texture instruction of a
//! quad touches, and filtered colours for the picture.
//!
//! # Layout
//!
//! * A 64-byte memory block (one cache line) holds a 4x4 block of RGBA8
//!   texels (16 texels x 4 bytes), or, for a texture in a compressed
//!   format, the texel region its compressed blocks fill (for example
//!   16x8 texels of ETC2 RGB, 16x16 of ASTC 8x8): the module [`mod@format`]
//!   gives every format's region and where a texel's bytes lie in it.
//!   Below, "block" is the 64-byte memory block and "cell" its region.
//! * Each texture gets a full mip chain, box-filtered (2x2 average) from
//!   level 0 down to 1x1 (an odd edge drops its last row or column, a
//!   1-texel edge stays 1).
//! * Textures live in a texture heap starting at [`HEAP_BASE`] (256 MiB
//!   into a 1 GiB memory, the paper's Table II size), each texture starting
//!   on a 64 KiB boundary ([`TEXTURE_ALIGN`]), in scene order, so two
//!   textures never share a block. Its levels follow one another, level 0
//!   first; each level starts on a block boundary.
//! * Inside a level, the grid of cells (4x4 texels in RGBA8) is padded to
//!   powers of two (`pw` x `ph` blocks) and stored in Morton (Z) order: the level is
//!   cut into squares of `2^k` x `2^k` blocks (`2^k = min(pw, ph)`), blocks
//!   inside a square in Morton order (x in the even bits, y in the odd
//!   bits), squares in row-major order. This is how GPUs swizzle textures
//!   so that a 2D neighbourhood of texels maps to consecutive lines and
//!   spreads over the cache sets (a row-major block order would map
//!   vertically adjacent blocks of a 1024-texel-wide texture to the same set
//!   of a 256-set cache).
//!
//! # Level of detail and filtering
//!
//! Per quad (2x2 pixels, pixel 0 top-left, 1 top-right, 2 bottom-left,
//! 3 bottom-right) the derivatives are the differences of the pixels' UVs
//! in texels of level 0 (one pair per quad, as hardware does; helper pixels
//! outside the primitive take part with their extrapolated UVs):
//! `lambda = log2(max(|d(uv)/dx|, |d(uv)/dy|))`, the standard rule of the
//! OpenGL specification (isotropic, no anisotropic filtering).
//!
//! * **Nearest** (`NEAREST_MIPMAP_NEAREST`): level `round(lambda)` clamped
//!   to the chain, the one texel containing the sample point.
//! * **Bilinear** (`LINEAR_MIPMAP_NEAREST`): level `round(lambda)`, the 2x2
//!   texels around the sample point (texel centres at half-integers).
//! * **Trilinear** (`LINEAR_MIPMAP_LINEAR`): 2x2 texels at level
//!   `floor(lambda)` and 2x2 at `floor(lambda) + 1`, 8 texels per pixel;
//!   when magnifying (`lambda <= 0`) or at the last level, one level only
//!   (the magnification filter is bilinear on level 0). The trace marks a
//!   quad's texture instruction trilinear (`T`) exactly when its sample
//!   reads two levels ([`TextureSet::reads_two_levels`]): the texture unit
//!   then filters twice; a one-level trilinear sample is one bilinear
//!   pass, written `t`.
//!
//! Wrap mode per texture: repeat (texel index modulo the level's size) or
//! clamp to edge. A texture instruction of a quad touches the union of the
//! blocks of its 4 pixels' texels: [`TextureSet::quad_blocks`] gives them
//! sorted and deduplicated, as block numbers (byte address / 64), which is
//! what the trace lists.

use super::{Filter, TexSample, Texture};
use crate::trace::{MapLevel, TextureMap};
use std::borrow::Cow;

mod filter;
#[cfg(test)]
mod fixtures;
mod footprint;
pub mod format;
mod heap;
mod mip;

pub use footprint::*;
use format::morton2;
pub use format::{alpha_needed, FormatChoice, TextureFormat};
pub use heap::*;
pub use mip::halve;
use mip::*;

/// Bytes of one memory block (cache line).
pub const BLOCK_BYTES: u64 = 64;
/// Texels along one edge of the texel block a memory block holds in RGBA8
/// ([`TextureFormat::line_texels`] for every format).
pub const BLOCK_TEXELS: u32 = 4;
/// Byte address of the texture heap.
pub const HEAP_BASE: u64 = 0x1000_0000;
/// Every texture starts on a multiple of this many bytes.
pub const TEXTURE_ALIGN: u64 = 64 * 1024;
