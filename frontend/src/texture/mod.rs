//! The texture path: mip chains, the block-linear layout of the texture
//! heap, level-of-detail selection, the texels a texture instruction of a
//! quad touches, and filtered colours for the picture.
//!
//! # Layout
//!
//! * A 64-byte memory block (one cache line) holds a 4x4 block of RGBA8
//!   texels (16 texels x 4 bytes).
//! * Each texture gets a full mip chain, box-filtered (2x2 average) from
//!   level 0 down to 1x1 (an odd edge drops its last row or column, a
//!   1-texel edge stays 1).
//! * Textures live in a texture heap starting at [`HEAP_BASE`] (256 MiB
//!   into a 1 GiB memory, the paper's Table II size), each texture starting
//!   on a 64 KiB boundary ([`TEXTURE_ALIGN`]), in scene order, so two
//!   textures never share a block. Its levels follow one another, level 0
//!   first; each level starts on a block boundary.
//! * Inside a level, the grid of 4x4-texel blocks is padded to powers of
//!   two (`pw` x `ph` blocks) and stored in Morton (Z) order: the level is
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
use std::borrow::Cow;

/// Bytes of one memory block (cache line).
pub const BLOCK_BYTES: u64 = 64;
/// Texels along one edge of the texel block a memory block holds.
pub const BLOCK_TEXELS: u32 = 4;
/// Byte address of the texture heap.
pub const HEAP_BASE: u64 = 0x1000_0000;
/// Every texture starts on a multiple of this many bytes.
pub const TEXTURE_ALIGN: u64 = 64 * 1024;

/// One mip level: its texels and where its blocks are.
#[derive(Clone, Debug)]
pub struct MipLevel<'a> {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// Texels, RGBA8, row-major, top row first (level 0 borrowed from the
    /// scene's texture).
    pub rgba: Cow<'a, [u8]>,
    /// Block number (byte address / 64) of the level's first block.
    pub first_block: u64,
    /// Blocks the level occupies (its padded block grid).
    pub block_count: u64,
    /// log2 of the padded block grid's width.
    pw_log2: u32,
    /// log2 of the Morton square edge in blocks.
    k: u32,
    /// The alpha channel alone (empty unless asked for): a 4x denser copy
    /// for the alpha test, which reads alpha only.
    alpha: Vec<u8>,
}

impl MipLevel<'_> {
    /// Block number of the block holding texel (`x`, `y`) (inside the level).
    #[inline]
    pub fn block_of(&self, x: u32, y: u32) -> u64 {
        let (bx, by) = (x / BLOCK_TEXELS, y / BLOCK_TEXELS);
        let mask = (1u32 << self.k) - 1;
        let inner = morton2(bx & mask, by & mask);
        let squares_per_row = 1u64 << (self.pw_log2 - self.k);
        let square = u64::from(by >> self.k) * squares_per_row + u64::from(bx >> self.k);
        self.first_block + (square << (2 * self.k)) + inner
    }

    /// Alpha of texel (`x`, `y`) in 0..=1.
    #[inline]
    fn texel_alpha(&self, x: u32, y: u32) -> f32 {
        let i = (y as usize) * (self.width as usize) + x as usize;
        let a = if self.alpha.is_empty() {
            self.rgba.get(i * 4 + 3)
        } else {
            self.alpha.get(i)
        };
        f32::from(a.copied().unwrap_or(0)) / 255.0
    }

    /// Texel (`x`, `y`) as RGBA in 0..=1.
    #[inline]
    fn texel(&self, x: u32, y: u32) -> [f32; 4] {
        let i = ((y as usize) * (self.width as usize) + x as usize) * 4;
        let Some(p) = self.rgba.get(i..i + 4) else {
            return [0.0; 4]; // a texture without texels (never sampled)
        };
        [
            f32::from(p[0]) / 255.0,
            f32::from(p[1]) / 255.0,
            f32::from(p[2]) / 255.0,
            f32::from(p[3]) / 255.0,
        ]
    }
}

/// One texture in the heap: its mip chain and address range.
#[derive(Clone, Debug)]
pub struct HeapTexture<'a> {
    /// Name (from the scene).
    pub name: String,
    /// Repeat (true) or clamp to edge.
    pub repeat: bool,
    /// Byte address of level 0.
    pub base: u64,
    /// Bytes of the whole chain (a multiple of 64).
    pub bytes: u64,
    /// Levels, level 0 first, down to 1x1.
    pub levels: Vec<MipLevel<'a>>,
}

/// Every texture of a scene laid out in the texture heap.
#[derive(Clone, Debug)]
pub struct TextureSet<'a> {
    textures: Vec<HeapTexture<'a>>,
    end: u64,
}

/// Interleaves the low 16 bits of x (even bit positions) and y (odd).
#[inline]
fn morton2(x: u32, y: u32) -> u64 {
    fn spread(v: u32) -> u64 {
        let mut v = u64::from(v & 0xffff);
        v = (v | (v << 8)) & 0x00ff_00ff;
        v = (v | (v << 4)) & 0x0f0f_0f0f;
        v = (v | (v << 2)) & 0x3333_3333;
        v = (v | (v << 1)) & 0x5555_5555;
        v
    }
    spread(x) | (spread(y) << 1)
}

/// The next level of a chain: 2x2 box filter.
fn downsample(w: u32, h: u32, src: &[u8]) -> (u32, u32, Vec<u8>) {
    let (nw, nh) = ((w / 2).max(1), (h / 2).max(1));
    if w >= 2 && h >= 2 {
        // Every output texel has its 2x2 source texels (an odd last row or
        // column is dropped): rows at a time, no clamping.
        let (sw, ow) = (w as usize * 4, nw as usize * 4);
        let mut out = Vec::with_capacity(ow * nh as usize);
        for y in 0..nh as usize {
            let r0 = &src[2 * y * sw..2 * y * sw + sw];
            let r1 = &src[(2 * y + 1) * sw..(2 * y + 1) * sw + sw];
            for (a, b) in r0.chunks_exact(8).zip(r1.chunks_exact(8)).take(nw as usize) {
                for c in 0..4 {
                    let s = u32::from(a[c])
                        + u32::from(a[4 + c])
                        + u32::from(b[c])
                        + u32::from(b[4 + c]);
                    out.push(((s + 2) / 4) as u8);
                }
            }
        }
        return (nw, nh, out);
    }
    downsample_clamped(w, h, src)
}

/// [`downsample`] for any size: source coordinates clamped to the edge (a
/// 1-texel edge stays 1).
fn downsample_clamped(w: u32, h: u32, src: &[u8]) -> (u32, u32, Vec<u8>) {
    let (nw, nh) = ((w / 2).max(1), (h / 2).max(1));
    let mut out = vec![0u8; nw as usize * nh as usize * 4];
    for y in 0..nh {
        let y0 = (2 * y).min(h - 1) as usize;
        let y1 = (2 * y + 1).min(h - 1) as usize;
        for x in 0..nw {
            let x0 = (2 * x).min(w - 1) as usize;
            let x1 = (2 * x + 1).min(w - 1) as usize;
            let o = (y as usize * nw as usize + x as usize) * 4;
            for c in 0..4 {
                let s = u32::from(src[(y0 * w as usize + x0) * 4 + c])
                    + u32::from(src[(y0 * w as usize + x1) * 4 + c])
                    + u32::from(src[(y1 * w as usize + x0) * 4 + c])
                    + u32::from(src[(y1 * w as usize + x1) * 4 + c]);
                out[o + c] = ((s + 2) / 4) as u8;
            }
        }
    }
    (nw, nh, out)
}

/// Where a texel coordinate lands in a level of `size` texels.
#[inline]
fn wrap(i: i64, size: u32, repeat: bool) -> u32 {
    if repeat {
        if size.is_power_of_two() {
            // Two's complement: 2^64 is a multiple of size.
            (i as u64 & u64::from(size - 1)) as u32
        } else {
            i.rem_euclid(i64::from(size)) as u32
        }
    } else {
        i.clamp(0, i64::from(size) - 1) as u32
    }
}

/// floor() as an integer without a libm call (the baseline x86-64 target
/// has no rounding instruction); saturating far outside the i64 range,
/// NaN to 0.
#[inline]
fn floor_i64(v: f64) -> i64 {
    let i = v as i64;
    i.saturating_sub(i64::from((i as f64) > v))
}

/// How the front end uses a texture ([`TextureSet::with_threads`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TextureUse {
    /// Whether any visible triangle samples it (if not, its levels beyond
    /// 0 keep their size and place in the heap but get no texels).
    pub sampled: bool,
    /// Whether an alpha test reads its alpha (then its levels get an
    /// alpha-only copy).
    pub alpha_tested: bool,
}

impl Default for TextureUse {
    fn default() -> Self {
        TextureUse {
            sampled: true,
            alpha_tested: false,
        }
    }
}

/// Mip levels as (width, height, texels).
type Chain<'a> = Vec<(u32, u32, Cow<'a, [u8]>)>;

/// The mip chain of one texture, level 0 borrowed: (width, height, texels)
/// per level, down to 1x1; without `texels`, the levels beyond 0 are sizes
/// only (empty texels). A texture with a zero edge or a texel array of the
/// wrong size becomes a 1x1 magenta texture.
fn mip_chain(t: &Texture, texels: bool) -> Chain<'_> {
    let valid =
        t.width > 0 && t.height > 0 && t.rgba.len() == t.width as usize * t.height as usize * 4;
    let mut chain: Vec<(u32, u32, Cow<'_, [u8]>)> = vec![if valid {
        (t.width, t.height, Cow::Borrowed(&t.rgba[..]))
    } else {
        (1, 1, Cow::Owned(vec![255, 0, 255, 255]))
    }];
    loop {
        let (w, h, rgba) = chain.last().expect("level 0");
        if *w == 1 && *h == 1 {
            return chain;
        }
        if texels {
            let (nw, nh, next) = downsample(*w, *h, rgba);
            chain.push((nw, nh, Cow::Owned(next)));
        } else {
            let (nw, nh) = ((*w / 2).max(1), (*h / 2).max(1));
            chain.push((nw, nh, Cow::Owned(Vec::new())));
        }
    }
}

impl<'a> TextureSet<'a> {
    /// Builds every texture's mip chain and places it in the heap. A texture
    /// with a zero edge or a texel array of the wrong size is replaced by a
    /// 1x1 magenta texture (the raster front end checks scenes before).
    pub fn new(textures: &'a [Texture]) -> TextureSet<'a> {
        TextureSet::with_threads(textures, 1, &[])
    }

    /// [`TextureSet::new`], building the mip chains on up to `threads`
    /// threads (the result does not depend on it), as `uses` says (default
    /// for textures beyond its end): an alpha-only copy of every level of
    /// alpha-tested textures (it speeds up [`TextureSet::sample_alpha`],
    /// same results), and no texels beyond level 0 for textures never
    /// sampled (same layout, so the same block addresses; sampling one
    /// anyway gives transparent black).
    pub fn with_threads(
        textures: &'a [Texture],
        threads: usize,
        uses: &[TextureUse],
    ) -> TextureSet<'a> {
        let use_of = |i: usize| uses.get(i).copied().unwrap_or_default();
        // Largest textures first, dealt round-robin, so threads get similar
        // work; each chain lands in its texture's slot.
        let mut order: Vec<usize> = (0..textures.len()).collect();
        order.sort_by_key(|&i| std::cmp::Reverse(textures[i].rgba.len()));
        let threads = threads.clamp(1, textures.len().max(1));
        let mut chains: Vec<Chain<'a>> = vec![Vec::new(); textures.len()];
        if threads == 1 {
            for (i, t) in textures.iter().enumerate() {
                chains[i] = mip_chain(t, use_of(i).sampled);
            }
        } else {
            let built: Vec<Vec<(usize, Chain<'a>)>> = std::thread::scope(|sc| {
                let handles: Vec<_> = (0..threads)
                    .map(|k| {
                        let mine: Vec<usize> =
                            order.iter().copied().skip(k).step_by(threads).collect();
                        sc.spawn(move || {
                            mine.into_iter()
                                .map(|i| (i, mip_chain(&textures[i], use_of(i).sampled)))
                                .collect::<Vec<_>>()
                        })
                    })
                    .collect();
                handles
                    .into_iter()
                    .map(|h| h.join().expect("mip chain thread"))
                    .collect()
            });
            for (i, chain) in built.into_iter().flatten() {
                chains[i] = chain;
            }
        }
        let mut out = Vec::with_capacity(textures.len());
        let mut addr = HEAP_BASE;
        for (i, (t, chain)) in textures.iter().zip(chains).enumerate() {
            let with_alpha = use_of(i).alpha_tested && use_of(i).sampled;
            let base = addr;
            let mut levels = Vec::with_capacity(chain.len());
            let mut block = base / BLOCK_BYTES;
            for (w, h, rgba) in chain {
                let bw = w.div_ceil(BLOCK_TEXELS).next_power_of_two();
                let bh = h.div_ceil(BLOCK_TEXELS).next_power_of_two();
                let (pw_log2, ph_log2) = (bw.trailing_zeros(), bh.trailing_zeros());
                let block_count = u64::from(bw) * u64::from(bh);
                let alpha = if with_alpha {
                    rgba.chunks_exact(4).map(|p| p[3]).collect()
                } else {
                    Vec::new()
                };
                levels.push(MipLevel {
                    width: w,
                    height: h,
                    rgba,
                    first_block: block,
                    block_count,
                    pw_log2,
                    k: pw_log2.min(ph_log2),
                    alpha,
                });
                block += block_count;
            }
            let bytes = block * BLOCK_BYTES - base;
            addr = (block * BLOCK_BYTES).div_ceil(TEXTURE_ALIGN) * TEXTURE_ALIGN;
            out.push(HeapTexture {
                name: t.name.clone(),
                repeat: t.repeat,
                base,
                bytes,
                levels,
            });
        }
        TextureSet {
            textures: out,
            end: addr,
        }
    }

    /// The textures in scene order.
    pub fn textures(&self) -> &[HeapTexture<'a>] {
        &self.textures
    }

    /// Bytes of the heap in use (textures and their alignment padding).
    pub fn heap_bytes(&self) -> u64 {
        self.end - HEAP_BASE
    }

    /// The level of detail of a quad sampling `texture` at these UVs (pixel
    /// 0 top-left, 1 top-right, 2 bottom-left, 3 bottom-right): log2 of the
    /// larger texel footprint of a pixel step in x or y, in level-0 texels.
    /// Negative when magnifying; `-inf` when the UVs do not change.
    pub fn quad_lambda(&self, texture: usize, uvs: &[[f32; 2]; 4]) -> f32 {
        let l0 = &self.textures[texture].levels[0];
        let (w, h) = (l0.width as f32, l0.height as f32);
        let dudx = (uvs[1][0] - uvs[0][0]) * w;
        let dvdx = (uvs[1][1] - uvs[0][1]) * h;
        let dudy = (uvs[2][0] - uvs[0][0]) * w;
        let dvdy = (uvs[2][1] - uvs[0][1]) * h;
        let rho2 = (dudx * dudx + dvdx * dvdx).max(dudy * dudy + dvdy * dvdy);
        if rho2.is_nan() {
            return 0.0;
        }
        0.5 * rho2.log2()
    }

    /// The mip levels a sample with this filter and lambda reads, and the
    /// weight of the second level (0 when there is one level).
    pub fn levels_for(&self, texture: usize, filter: Filter, lambda: f32) -> (usize, usize, f32) {
        let last = self.textures[texture].levels.len() - 1;
        match filter {
            Filter::Nearest | Filter::Bilinear => {
                let l = if lambda.is_nan() || lambda <= 0.5 {
                    0
                } else {
                    ((lambda + 0.5).floor() as usize).min(last)
                };
                (l, l, 0.0)
            }
            Filter::Trilinear => {
                if lambda.is_nan() || lambda <= 0.0 {
                    (0, 0, 0.0)
                } else {
                    let f = lambda.floor();
                    let l = (f as usize).min(last);
                    if l == last {
                        (l, l, 0.0)
                    } else {
                        (l, l + 1, lambda - f)
                    }
                }
            }
        }
    }

    /// Whether `sample` at this level of detail filters two mip levels:
    /// a trilinear sample that minifies above the last level. Such a
    /// texture instruction is trilinear in the trace (`T`, format 4); every
    /// other one (nearest, bilinear, or trilinear reading one level) is
    /// one bilinear filter pass (`t`).
    pub fn reads_two_levels(&self, sample: &TexSample, lambda: f32) -> bool {
        let (a, b, _) = self.levels_for(sample.texture, sample.filter, lambda);
        a != b
    }

    /// The distinct blocks (block numbers = byte address / 64, sorted) that
    /// the texture instruction `sample` of a quad whose pixels have these
    /// UVs touches. `out` is cleared first.
    pub fn quad_blocks(&self, sample: &TexSample, uvs: [[f32; 2]; 4], out: &mut Vec<u64>) {
        self.quad_blocks_lambda(sample, uvs, out);
    }

    /// [`TextureSet::quad_blocks`], returning the quad's level of detail
    /// (for [`TextureSet::sample_rgba`]).
    pub fn quad_blocks_lambda(
        &self,
        sample: &TexSample,
        uvs: [[f32; 2]; 4],
        out: &mut Vec<u64>,
    ) -> f32 {
        self.quad_blocks_with(sample, uvs, out, None)
    }

    /// [`TextureSet::quad_blocks_lambda`], also keeping in `texels` where
    /// each pixel reads (for [`TextureSet::quad_alpha`], so an alpha test
    /// does not find the texels again).
    pub fn quad_blocks_texels(
        &self,
        sample: &TexSample,
        uvs: [[f32; 2]; 4],
        out: &mut Vec<u64>,
        texels: &mut QuadTexels,
    ) -> f32 {
        self.quad_blocks_with(sample, uvs, out, Some(texels))
    }

    fn quad_blocks_with(
        &self,
        sample: &TexSample,
        uvs: [[f32; 2]; 4],
        out: &mut Vec<u64>,
        mut texels: Option<&mut QuadTexels>,
    ) -> f32 {
        out.clear();
        let tex = &self.textures[sample.texture];
        let lambda = self.quad_lambda(sample.texture, &uvs);
        let levels = self.levels_for(sample.texture, sample.filter, lambda);
        let (la, lb, _) = levels;
        // A block holds the texels of one (x / 4, y / 4) cell of its level,
        // so the distinct cells the texels fall in (few: at most 16 per
        // level) give the distinct blocks; levels never share a block.
        let mut push_level = |level: &MipLevel, slot: usize| {
            let mut cells = [0u64; 16];
            let mut n = 0;
            // By cell: (cx, cy) as a key.
            let mut add = |cx: u32, cy: u32| {
                let key = u64::from(cx) | (u64::from(cy) << 32);
                if !cells[..n].contains(&key) {
                    cells[n] = key;
                    n += 1;
                }
            };
            for (i, uv) in uvs.iter().enumerate() {
                // The 2x2 texels span one cell in x unless they straddle a
                // cell edge (or wrap), and so in y: only the distinct cells
                // are looked up (nearest: one texel, x1 = x0, y1 = y0).
                let f = footprint(level, sample.filter, tex.repeat, *uv);
                let (cx0, cx1) = (f.x0 / BLOCK_TEXELS, f.x1 / BLOCK_TEXELS);
                let (cy0, cy1) = (f.y0 / BLOCK_TEXELS, f.y1 / BLOCK_TEXELS);
                add(cx0, cy0);
                if cx1 != cx0 {
                    add(cx1, cy0);
                }
                if cy1 != cy0 {
                    add(cx0, cy1);
                    if cx1 != cx0 {
                        add(cx1, cy1);
                    }
                }
                if let Some(q) = texels.as_deref_mut() {
                    q.px[slot][i] = f;
                }
            }
            out.extend(cells[..n].iter().map(|&k| {
                level.block_of((k as u32) * BLOCK_TEXELS, ((k >> 32) as u32) * BLOCK_TEXELS)
            }));
        };
        push_level(&tex.levels[la], 0);
        if lb != la {
            push_level(&tex.levels[lb], 1);
        }
        if let Some(q) = texels {
            q.texture = sample.texture;
            q.filter = sample.filter;
            q.levels = levels;
        }
        out.sort_unstable();
        lambda
    }

    /// The alpha of pixel `pixel` (0..4) of the quad whose texels
    /// [`TextureSet::quad_blocks_texels`] kept in `q`: the same value as
    /// `sample_alpha` of that pixel's UV with the quad's lambda.
    pub fn quad_alpha(&self, q: &QuadTexels, pixel: usize) -> f32 {
        let levels = &self.textures[q.texture].levels;
        let (la, lb, t) = q.levels;
        let a = footprint_alpha(&levels[la], q.filter, &q.px[0][pixel]);
        if lb == la || t <= 0.0 {
            return a;
        }
        let b = footprint_alpha(&levels[lb], q.filter, &q.px[1][pixel]);
        a + (b - a) * t
    }

    /// The filtered colour (RGBA in 0..=1) of `texture` at `uv` with this
    /// filter and the quad's `lambda` (from [`TextureSet::quad_lambda`]).
    pub fn sample_rgba(
        &self,
        texture: usize,
        filter: Filter,
        uv: [f32; 2],
        lambda: f32,
    ) -> [f32; 4] {
        let tex = &self.textures[texture];
        let (la, lb, t) = self.levels_for(texture, filter, lambda);
        let one = |level: &MipLevel| match filter {
            Filter::Nearest => {
                let (x, y) = nearest(level, tex.repeat, uv);
                level.texel(x, y)
            }
            Filter::Bilinear | Filter::Trilinear => {
                let (x0, x1, y0, y1, fx, fy) = bilinear(level, tex.repeat, uv);
                let (a, b) = (level.texel(x0, y0), level.texel(x1, y0));
                let (c, d) = (level.texel(x0, y1), level.texel(x1, y1));
                let mut o = [0.0f32; 4];
                for i in 0..4 {
                    let top = a[i] + (b[i] - a[i]) * fx;
                    let bot = c[i] + (d[i] - c[i]) * fx;
                    o[i] = top + (bot - top) * fy;
                }
                o
            }
        };
        let a = one(&tex.levels[la]);
        if lb == la || t <= 0.0 {
            return a;
        }
        let b = one(&tex.levels[lb]);
        let mut o = [0.0f32; 4];
        for i in 0..4 {
            o[i] = a[i] + (b[i] - a[i]) * t;
        }
        o
    }

    /// `sample_rgba(texture, filter, uv, lambda)[3]`, the same value, without
    /// the colour channels.
    pub fn sample_alpha(&self, texture: usize, filter: Filter, uv: [f32; 2], lambda: f32) -> f32 {
        let tex = &self.textures[texture];
        let (la, lb, t) = self.levels_for(texture, filter, lambda);
        let one = |level: &MipLevel| {
            footprint_alpha(level, filter, &footprint(level, filter, tex.repeat, uv))
        };
        let a = one(&tex.levels[la]);
        if lb == la || t <= 0.0 {
            return a;
        }
        let b = one(&tex.levels[lb]);
        a + (b - a) * t
    }
}

/// The texels one pixel's sample reads in one level: the 2x2 texels
/// x0..=x1, y0..=y1 (x1, y1 wrapped or clamped) and the blend fractions;
/// nearest: the one texel (x0, y0) = (x1, y1), fractions 0.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Footprint {
    x0: u32,
    x1: u32,
    y0: u32,
    y1: u32,
    fx: f32,
    fy: f32,
}

/// Where the 4 pixels of a quad read one texture instruction
/// ([`TextureSet::quad_blocks_texels`]), for [`TextureSet::quad_alpha`].
#[derive(Clone, Copy, Debug)]
pub struct QuadTexels {
    texture: usize,
    filter: Filter,
    /// The levels and the second one's weight ([`TextureSet::levels_for`]).
    levels: (usize, usize, f32),
    /// Per level read (first, second), per pixel.
    px: [[Footprint; 4]; 2],
}

impl Default for QuadTexels {
    fn default() -> Self {
        QuadTexels {
            texture: 0,
            filter: Filter::Nearest,
            levels: (0, 0, 0.0),
            px: [[Footprint::default(); 4]; 2],
        }
    }
}

/// The texels a sample with `filter` at `uv` reads in `level`.
#[inline(always)]
fn footprint(level: &MipLevel, filter: Filter, repeat: bool, uv: [f32; 2]) -> Footprint {
    match filter {
        Filter::Nearest => {
            let (x, y) = nearest(level, repeat, uv);
            Footprint {
                x0: x,
                x1: x,
                y0: y,
                y1: y,
                fx: 0.0,
                fy: 0.0,
            }
        }
        Filter::Bilinear | Filter::Trilinear => {
            let (x0, x1, y0, y1, fx, fy) = bilinear(level, repeat, uv);
            Footprint {
                x0,
                x1,
                y0,
                y1,
                fx,
                fy,
            }
        }
    }
}

/// The filtered alpha of a footprint in `level`.
#[inline(always)]
fn footprint_alpha(level: &MipLevel, filter: Filter, f: &Footprint) -> f32 {
    match filter {
        Filter::Nearest => level.texel_alpha(f.x0, f.y0),
        Filter::Bilinear | Filter::Trilinear => {
            let (a, b) = (level.texel_alpha(f.x0, f.y0), level.texel_alpha(f.x1, f.y0));
            let (c, d) = (level.texel_alpha(f.x0, f.y1), level.texel_alpha(f.x1, f.y1));
            let top = a + (b - a) * f.fx;
            let bot = c + (d - c) * f.fx;
            top + (bot - top) * f.fy
        }
    }
}

/// The texel containing the sample point.
#[inline(always)]
fn nearest(level: &MipLevel, repeat: bool, uv: [f32; 2]) -> (u32, u32) {
    let x = floor_i64(f64::from(uv[0]) * f64::from(level.width));
    let y = floor_i64(f64::from(uv[1]) * f64::from(level.height));
    (wrap(x, level.width, repeat), wrap(y, level.height, repeat))
}

/// The 2x2 texels around the sample point and the blend fractions.
#[inline(always)]
fn bilinear(level: &MipLevel, repeat: bool, uv: [f32; 2]) -> (u32, u32, u32, u32, f32, f32) {
    let x = f64::from(uv[0]) * f64::from(level.width) - 0.5;
    let y = f64::from(uv[1]) * f64::from(level.height) - 0.5;
    let (ix, iy) = (floor_i64(x), floor_i64(y));
    (
        wrap(ix, level.width, repeat),
        wrap(ix.saturating_add(1), level.width, repeat),
        wrap(iy, level.height, repeat),
        wrap(iy.saturating_add(1), level.height, repeat),
        (x - ix as f64) as f32,
        (y - iy as f64) as f32,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tex(name: &str, w: u32, h: u32, repeat: bool) -> Texture {
        let mut rgba = Vec::with_capacity((w * h * 4) as usize);
        for y in 0..h {
            for x in 0..w {
                rgba.extend_from_slice(&[(x * 7) as u8, (y * 5) as u8, ((x ^ y) * 3) as u8, 255]);
            }
        }
        Texture {
            name: name.into(),
            width: w,
            height: h,
            rgba,
            repeat,
        }
    }

    fn sample(filter: Filter) -> TexSample {
        TexSample {
            texture: 0,
            uv_set: 0,
            filter,
        }
    }

    /// UVs of a quad at `origin` whose pixels step `step` texels in u (x) and
    /// v (y) on a `size`-texel texture.
    fn quad_uvs(origin: [f32; 2], step: f32, size: f32) -> [[f32; 2]; 4] {
        let d = step / size;
        let (u, v) = (origin[0], origin[1]);
        [[u, v], [u + d, v], [u, v + d], [u + d, v + d]]
    }

    #[test]
    fn mip_chain_goes_down_to_one_texel_and_is_box_filtered() {
        let texs = [tex("a", 256, 64, true)];
        let set = TextureSet::new(&texs);
        let levels = &set.textures()[0].levels;
        let dims: Vec<(u32, u32)> = levels.iter().map(|l| (l.width, l.height)).collect();
        assert_eq!(dims.first(), Some(&(256, 64)));
        assert_eq!(dims.last(), Some(&(1, 1)));
        assert_eq!(dims.len(), 9);
        // Level 1 texel (0,0) averages level-0 texels (0..2, 0..2).
        let l0 = &levels[0].rgba;
        let w = 256usize;
        let avg = (u32::from(l0[0])
            + u32::from(l0[4])
            + u32::from(l0[w * 4])
            + u32::from(l0[w * 4 + 4])
            + 2)
            / 4;
        assert_eq!(u32::from(levels[1].rgba[0]), avg);
    }

    #[test]
    fn mip_selection_magnified_minified_and_at_distance() {
        let texs = [tex("a", 256, 256, true)];
        let set = TextureSet::new(&texs);
        // Magnified: a pixel step is half a texel.
        let mag = set.quad_lambda(0, &quad_uvs([0.3, 0.3], 0.5, 256.0));
        assert!((mag + 1.0).abs() < 1e-4, "{mag}");
        assert_eq!(set.levels_for(0, Filter::Bilinear, mag).0, 0);
        assert_eq!(set.levels_for(0, Filter::Trilinear, mag), (0, 0, 0.0));
        // 1:1.
        let one = set.quad_lambda(0, &quad_uvs([0.3, 0.3], 1.0, 256.0));
        assert!(one.abs() < 1e-3, "{one}");
        // Minified 4x: level 2.
        let min = set.quad_lambda(0, &quad_uvs([0.3, 0.3], 4.0, 256.0));
        assert!((min - 2.0).abs() < 1e-3, "{min}");
        assert_eq!(set.levels_for(0, Filter::Bilinear, min).0, 2);
        // At a distance on a tilted surface: the larger footprint (y) wins.
        let far = [
            [0.1, 0.1],
            [0.1 + 2.0 / 256.0, 0.1],
            [0.1, 0.1 + 24.0 / 256.0],
            [0.1 + 2.0 / 256.0, 0.1 + 24.0 / 256.0],
        ];
        let lf = set.quad_lambda(0, &far);
        assert!((lf - 24f32.log2()).abs() < 1e-3, "{lf}");
        let (a, b, t) = set.levels_for(0, Filter::Trilinear, lf);
        assert_eq!((a, b), (4, 5));
        assert!(t > 0.5 && t < 0.6);
        assert_eq!(set.levels_for(0, Filter::Bilinear, lf).0, 5);
        // Beyond the chain: clamped to the 1x1 level.
        assert_eq!(set.levels_for(0, Filter::Bilinear, 20.0).0, 8);
        assert_eq!(set.levels_for(0, Filter::Trilinear, 20.0), (8, 8, 0.0));
    }

    #[test]
    fn block_layout_one_block_per_4x4_texels_and_textures_never_share() {
        let texs = [tex("a", 64, 64, true), tex("b", 100, 20, false)];
        let set = TextureSet::new(&texs);
        let a = &set.textures()[0];
        let b = &set.textures()[1];
        assert_eq!(a.base, HEAP_BASE);
        assert_eq!(b.base % TEXTURE_ALIGN, 0);
        assert!(b.base >= a.base + a.bytes);
        let l0 = &a.levels[0];
        // All 16 texels of a 4x4 block are one line; neighbours are others.
        for y in 4..8 {
            for x in 8..12 {
                assert_eq!(l0.block_of(x, y), l0.block_of(8, 4));
            }
        }
        assert_ne!(l0.block_of(12, 4), l0.block_of(8, 4));
        assert_ne!(l0.block_of(8, 8), l0.block_of(8, 4));
        // Morton order: the 2x2 blocks of the top-left corner are consecutive.
        let base = l0.first_block;
        assert_eq!(l0.block_of(0, 0), base);
        assert_eq!(l0.block_of(4, 0), base + 1);
        assert_eq!(l0.block_of(0, 4), base + 2);
        assert_eq!(l0.block_of(4, 4), base + 3);
        // Every block of every level of every texture is distinct and inside
        // its texture's range.
        let mut all = Vec::new();
        for (t, ht) in set.textures().iter().enumerate() {
            let (lo, hi) = (ht.base / 64, (ht.base + ht.bytes) / 64);
            for l in &ht.levels {
                let mut mine = Vec::new();
                for y in 0..l.height {
                    for x in 0..l.width {
                        let blk = l.block_of(x, y);
                        assert!(blk >= lo && blk < hi, "texture {t}");
                        mine.push(blk);
                    }
                }
                mine.sort_unstable();
                mine.dedup();
                let expect = l.width.div_ceil(4) as usize * l.height.div_ceil(4) as usize;
                assert_eq!(mine.len(), expect);
                all.extend(mine);
            }
        }
        let n = all.len();
        all.sort_unstable();
        all.dedup();
        assert_eq!(all.len(), n, "no block shared between levels or textures");
    }

    #[test]
    fn bilinear_trilinear_and_nearest_block_counts() {
        let texs = [tex("a", 256, 256, true)];
        let set = TextureSet::new(&texs);
        let mut out = Vec::new();
        // A quad at 1.5 texels per pixel step, straddling block edges.
        let uvs = quad_uvs([30.0 / 256.0, 62.0 / 256.0], 1.5, 256.0);
        set.quad_blocks(&sample(Filter::Nearest), uvs, &mut out);
        let nearest = out.len();
        set.quad_blocks(&sample(Filter::Bilinear), uvs, &mut out);
        let bil = out.clone();
        set.quad_blocks(&sample(Filter::Trilinear), uvs, &mut out);
        let tri = out.clone();
        assert!(nearest >= 1 && nearest <= bil.len(), "{nearest} {bil:?}");
        assert!(tri.len() > bil.len(), "trilinear {tri:?} bilinear {bil:?}");
        // Sorted and distinct.
        assert!(tri.windows(2).all(|w| w[0] < w[1]));
        // One pixel inside a block, magnified: one block.
        let inside = quad_uvs([5.5 / 256.0, 5.5 / 256.0], 0.25, 256.0);
        set.quad_blocks(&sample(Filter::Bilinear), inside, &mut out);
        assert_eq!(out.len(), 1);
    }

    #[test]
    fn wrap_and_clamp_at_the_edge() {
        let texs = [tex("r", 64, 64, true), tex("c", 64, 64, false)];
        let set = TextureSet::new(&texs);
        let mut out = Vec::new();
        let uvs = [[0.999, 0.5], [1.001, 0.5], [0.999, 0.51], [1.001, 0.51]];
        let rep = TexSample {
            texture: 0,
            uv_set: 0,
            filter: Filter::Bilinear,
        };
        set.quad_blocks(&rep, uvs, &mut out);
        // Repeat reaches column 0's blocks.
        let l0 = &set.textures()[0].levels[0];
        assert!(out.contains(&l0.block_of(0, 32)));
        assert!(out.contains(&l0.block_of(63, 32)));
        let cl = TexSample { texture: 1, ..rep };
        set.quad_blocks(&cl, uvs, &mut out);
        let c0 = &set.textures()[1].levels[0];
        assert!(!out.contains(&c0.block_of(0, 32)));
        assert!(out.contains(&c0.block_of(63, 32)));
    }

    #[test]
    fn row_downsampling_equals_the_clamped_one() {
        for (w, h) in [(2, 2), (5, 3), (7, 9), (64, 33), (3, 2), (1, 6), (6, 1)] {
            let src: Vec<u8> = (0..w * h * 4).map(|i| (i * 73 % 256) as u8).collect();
            assert_eq!(
                downsample(w, h, &src),
                downsample_clamped(w, h, &src),
                "{w}x{h}"
            );
        }
    }

    #[test]
    fn threads_and_alpha_only_sampling_change_nothing() {
        let mut texs = [
            tex("a", 64, 32, true),
            tex("b", 100, 20, false),
            tex("c", 1, 1, true),
            tex("d", 256, 256, true),
        ];
        for t in &mut texs {
            for (i, px) in t.rgba.chunks_exact_mut(4).enumerate() {
                px[3] = (i * 37 % 251) as u8;
            }
        }
        let one = TextureSet::new(&texs);
        let u = |alpha_tested| TextureUse {
            sampled: true,
            alpha_tested,
        };
        let alpha = TextureSet::with_threads(&texs, 2, &[u(true), u(false), u(true), u(true)]);
        // Unsampled textures: the same layout, no texels beyond level 0.
        let bare = TextureSet::with_threads(
            &texs,
            2,
            &[TextureUse {
                sampled: false,
                alpha_tested: true,
            }],
        );
        for (a, b) in one.textures().iter().zip(bare.textures()) {
            assert_eq!(
                (a.base, a.bytes, a.levels.len()),
                (b.base, b.bytes, b.levels.len())
            );
        }
        assert!(bare.textures()[0].levels[1].rgba.is_empty());
        assert_eq!(
            bare.textures()[1].levels[1].rgba,
            one.textures()[1].levels[1].rgba
        );
        assert_eq!(
            bare.sample_rgba(0, Filter::Trilinear, [0.3, 0.3], 2.5),
            [0.0; 4]
        );
        for threads in [2, 3, 8] {
            let many = TextureSet::with_threads(&texs, threads, &[]);
            assert_eq!(many.heap_bytes(), one.heap_bytes());
            for (a, b) in one.textures().iter().zip(many.textures()) {
                assert_eq!(
                    (a.base, a.bytes, a.levels.len()),
                    (b.base, b.bytes, b.levels.len())
                );
                for (la, lb) in a.levels.iter().zip(&b.levels) {
                    assert_eq!(la.rgba, lb.rgba);
                    assert_eq!(la.first_block, lb.first_block);
                }
            }
        }
        for t in 0..texs.len() {
            for filter in [Filter::Nearest, Filter::Bilinear, Filter::Trilinear] {
                for (uv, lambda) in [([0.3, 0.7], -1.0), ([1.37, -0.2], 1.6), ([0.01, 0.99], 4.3)] {
                    let c = one.sample_rgba(t, filter, uv, lambda);
                    let a = one.sample_alpha(t, filter, uv, lambda);
                    assert_eq!(a.to_bits(), c[3].to_bits(), "{t} {filter:?} {uv:?}");
                    let b = alpha.sample_alpha(t, filter, uv, lambda);
                    assert_eq!(b.to_bits(), c[3].to_bits(), "{t} {filter:?} {uv:?}");
                }
            }
        }
    }

    #[test]
    fn colours_are_filtered_texels() {
        let texs = [tex("a", 16, 16, false)];
        let set = TextureSet::new(&texs);
        // At a texel centre, bilinear is the texel itself.
        let c = set.sample_rgba(0, Filter::Bilinear, [2.5 / 16.0, 3.5 / 16.0], 0.0);
        assert!((c[0] - 14.0 / 255.0).abs() < 1e-5 && (c[1] - 15.0 / 255.0).abs() < 1e-5);
        // Halfway between two texels in x: the mean.
        let c = set.sample_rgba(0, Filter::Bilinear, [3.0 / 16.0, 3.5 / 16.0], 0.0);
        assert!((c[0] - 17.5 / 255.0).abs() < 1e-5, "{c:?}");
        let n = set.sample_rgba(0, Filter::Nearest, [3.2 / 16.0, 3.5 / 16.0], 0.0);
        assert!((n[0] - 21.0 / 255.0).abs() < 1e-5);
    }

    #[test]
    fn quad_alpha_is_sample_alpha_at_the_quads_texels() {
        let mut texs = [tex("a", 64, 32, true), tex("b", 100, 20, false)];
        for t in &mut texs {
            for (i, px) in t.rgba.chunks_exact_mut(4).enumerate() {
                px[3] = (i * 37 % 251) as u8;
            }
        }
        let set = TextureSet::new(&texs);
        let (mut a, mut b) = (Vec::new(), Vec::new());
        let mut q = QuadTexels::default();
        for texture in 0..texs.len() {
            for filter in [Filter::Nearest, Filter::Bilinear, Filter::Trilinear] {
                let smp = TexSample {
                    texture,
                    uv_set: 0,
                    filter,
                };
                for (origin, step) in [([0.3, 0.7], 0.4), ([1.37, -0.2], 3.1), ([0.99, 0.01], 11.0)]
                {
                    let uvs = quad_uvs(origin, step, 64.0);
                    let lambda = set.quad_blocks_texels(&smp, uvs, &mut a, &mut q);
                    assert_eq!(lambda, set.quad_blocks_lambda(&smp, uvs, &mut b));
                    assert_eq!(a, b);
                    for (i, uv) in uvs.iter().enumerate() {
                        let want = set.sample_alpha(texture, filter, *uv, lambda);
                        assert_eq!(set.quad_alpha(&q, i).to_bits(), want.to_bits());
                    }
                }
            }
        }
    }
}
