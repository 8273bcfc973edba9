//! The texture heap: each texture's mip levels laid out block-linear
//! (64-byte lines, each holding the texel region its format packs into a
//! line, in Morton order; levels one after another, textures aligned to
//! [`TEXTURE_ALIGN`] from [`HEAP_BASE`]), the chains built on worker
//! threads.

use super::*;

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
    /// The texel region one block (64-byte line) holds: its width and
    /// height as log2 when a power of two, else the width and height.
    cell: Cell,
    /// log2 of the padded block grid's width.
    pw_log2: u32,
    /// log2 of the Morton square edge in blocks.
    k: u32,
    /// The alpha channel alone (empty unless asked for): a 4x denser copy
    /// for the alpha test, which reads alpha only.
    pub(super) alpha: Vec<u8>,
}

impl MipLevel<'_> {
    /// The cell (column, row of the level's grid of 64-byte blocks) of
    /// texel (`x`, `y`).
    #[inline]
    pub fn cell_of(&self, x: u32, y: u32) -> (u32, u32) {
        match self.cell {
            Cell::Shift(sx, sy) => (x >> sx, y >> sy),
            Cell::Div(w, h) => (x / w, y / h),
        }
    }

    /// Block number of the block holding texel (`x`, `y`) (inside the level).
    #[inline]
    pub fn block_of(&self, x: u32, y: u32) -> u64 {
        let (bx, by) = self.cell_of(x, y);
        self.block_of_cell(bx, by)
    }

    /// Block number of the block of cell (`bx`, `by`) ([`MipLevel::cell_of`]).
    #[inline]
    pub fn block_of_cell(&self, bx: u32, by: u32) -> u64 {
        let mask = (1u32 << self.k) - 1;
        let inner = morton2(bx & mask, by & mask);
        let squares_per_row = 1u64 << (self.pw_log2 - self.k);
        let square = u64::from(by >> self.k) * squares_per_row + u64::from(bx >> self.k);
        self.first_block + (square << (2 * self.k)) + inner
    }
}

/// The texel region of a 64-byte block: edges as shifts (powers of two,
/// the common case) or divisors.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Cell {
    Shift(u32, u32),
    Div(u32, u32),
}

impl Cell {
    fn of(format: TextureFormat) -> Cell {
        let (w, h) = format.line_texels();
        if w.is_power_of_two() && h.is_power_of_two() {
            Cell::Shift(w.trailing_zeros(), h.trailing_zeros())
        } else {
            Cell::Div(w, h)
        }
    }
}

/// One texture in the heap: its mip chain and address range.
#[derive(Clone, Debug)]
pub struct HeapTexture<'a> {
    /// Name (from the scene).
    pub name: String,
    /// How it is stored.
    pub format: TextureFormat,
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
    pub(super) textures: Vec<HeapTexture<'a>>,
    end: u64,
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
    /// How it is stored ([`TextureFormat`]: where its texels' blocks lie).
    pub format: TextureFormat,
}

impl Default for TextureUse {
    fn default() -> Self {
        TextureUse {
            sampled: true,
            alpha_tested: false,
            format: TextureFormat::Rgba8,
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
        let chains = mip_chains(textures, threads, &use_of);
        let mut out = Vec::with_capacity(textures.len());
        let mut addr = HEAP_BASE;
        for (i, (t, chain)) in textures.iter().zip(chains).enumerate() {
            let with_alpha = use_of(i).alpha_tested && use_of(i).sampled;
            let placed = place(t, chain, addr, with_alpha, use_of(i).format);
            addr = (placed.base + placed.bytes).div_ceil(TEXTURE_ALIGN) * TEXTURE_ALIGN;
            out.push(placed);
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

    /// The map from this set's lines, which must be laid out as RGBA8
    /// (the decoded texels), to the lines of the same textures stored as
    /// `formats` (one per texture, in scene order; RGBA8 beyond its end),
    /// placed as [`TextureSet::with_threads`] places them: one
    /// `texture-level` per level ([`TextureMap`]).
    pub fn decoded_map(&self, formats: &[TextureFormat]) -> TextureMap {
        let mut map = TextureMap::new();
        let mut addr = HEAP_BASE;
        for (i, t) in self.textures.iter().enumerate() {
            debug_assert_eq!(t.format, TextureFormat::Rgba8, "decoded lines are RGBA8");
            let format = formats.get(i).copied().unwrap_or_default();
            let (lx, ly) = format.line_texels();
            let mut block = addr / BLOCK_BYTES;
            for l in &t.levels {
                let (sw, sh) = line_grid(l.width, l.height, format);
                let rw = 1u32 << l.pw_log2;
                map.push(MapLevel {
                    first: l.first_block,
                    grid: (rw, (l.block_count >> l.pw_log2) as u32),
                    stored_first: block,
                    stored_grid: (sw, sh),
                    per_line: (lx / 4, ly / 4),
                })
                .expect("levels are laid out in increasing block order");
                block += u64::from(sw) * u64::from(sh);
            }
            addr = (block * BLOCK_BYTES).div_ceil(TEXTURE_ALIGN) * TEXTURE_ALIGN;
        }
        map
    }
}

/// The grid of 64-byte lines of a `w` x `h` level stored as `format`:
/// whole format blocks, then whole lines (a line's region is a whole
/// number of blocks, so ceil(w / region) is both), padded to powers of
/// two.
fn line_grid(w: u32, h: u32, format: TextureFormat) -> (u32, u32) {
    let (cw, ch) = format.line_texels();
    (
        w.div_ceil(cw).next_power_of_two(),
        h.div_ceil(ch).next_power_of_two(),
    )
}

/// Every texture's mip chain (texels beyond level 0 only for sampled
/// ones), on up to `threads` threads: largest textures first, dealt
/// round-robin, so threads get similar work; each chain lands in its
/// texture's slot.
fn mip_chains<'a>(
    textures: &'a [Texture],
    threads: usize,
    use_of: &(impl Fn(usize) -> TextureUse + Sync),
) -> Vec<Chain<'a>> {
    let mut order: Vec<usize> = (0..textures.len()).collect();
    order.sort_by_key(|&i| std::cmp::Reverse(textures[i].rgba.len()));
    let threads = threads.clamp(1, textures.len().max(1));
    let mut chains: Vec<Chain<'a>> = vec![Vec::new(); textures.len()];
    if threads == 1 {
        for (i, t) in textures.iter().enumerate() {
            chains[i] = mip_chain(t, use_of(i).sampled);
        }
        return chains;
    }
    let built: Vec<Vec<(usize, Chain<'a>)>> = std::thread::scope(|sc| {
        let handles: Vec<_> = (0..threads)
            .map(|k| {
                let mine: Vec<usize> = order.iter().copied().skip(k).step_by(threads).collect();
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
    chains
}

/// Place texture `t`'s levels (`chain`) in the heap from `addr`, stored
/// as `format`: each level's 64-byte blocks (the texel region `format`
/// packs into one) in Morton order over a power-of-two grid of blocks,
/// the levels one after the other; `with_alpha` adds each level's
/// alpha-only copy.
fn place<'a>(
    t: &Texture,
    chain: Chain<'a>,
    addr: u64,
    with_alpha: bool,
    format: TextureFormat,
) -> HeapTexture<'a> {
    let base = addr;
    let mut levels = Vec::with_capacity(chain.len());
    let mut block = base / BLOCK_BYTES;
    for (w, h, rgba) in chain {
        let (bw, bh) = line_grid(w, h, format);
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
            cell: Cell::of(format),
            pw_log2,
            k: pw_log2.min(ph_log2),
            alpha,
        });
        block += block_count;
    }
    HeapTexture {
        name: t.name.clone(),
        format,
        repeat: t.repeat,
        base,
        bytes: block * BLOCK_BYTES - base,
        levels,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::texture::fixtures::*;

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
    fn every_format_packs_its_line_region_into_one_block() {
        let texs = [tex("a", 64, 64, true), tex("b", 100, 20, false)];
        for format in TextureFormat::ALL {
            let uses = [TextureUse {
                format,
                ..TextureUse::default()
            }; 2];
            let set = TextureSet::with_threads(&texs, 1, &uses);
            let (cw, ch) = format.line_texels();
            let mut all = Vec::new();
            for ht in set.textures() {
                assert_eq!(ht.format, format);
                let (lo, hi) = (ht.base / 64, (ht.base + ht.bytes) / 64);
                for l in &ht.levels {
                    let mut mine = Vec::new();
                    for y in 0..l.height {
                        for x in 0..l.width {
                            let blk = l.block_of(x, y);
                            // The texel's line is its region's first texel's.
                            assert_eq!(blk, l.block_of(x / cw * cw, y / ch * ch), "{format}");
                            assert!(blk >= lo && blk < hi, "{format}");
                            mine.push(blk);
                        }
                    }
                    mine.sort_unstable();
                    mine.dedup();
                    let expect = l.width.div_ceil(cw) as usize * l.height.div_ceil(ch) as usize;
                    assert_eq!(mine.len(), expect, "{format} {}x{}", l.width, l.height);
                    all.extend(mine);
                }
            }
            let n = all.len();
            all.sort_unstable();
            all.dedup();
            assert_eq!(all.len(), n, "{format}: no block shared");
        }
        // ETC2 RGB: level 0 of a 64x64 texture is 4x8 lines of 16x8 texels;
        // the first two lines side by side, then the one below.
        let uses = [TextureUse {
            format: TextureFormat::Etc2Rgb,
            ..TextureUse::default()
        }];
        let set = TextureSet::with_threads(&texs[..1], 1, &uses);
        let l0 = &set.textures()[0].levels[0];
        assert_eq!(l0.block_count, 32);
        assert_eq!(l0.block_of(16, 0), l0.first_block + 1);
        assert_eq!(l0.block_of(0, 8), l0.first_block + 2);
        assert_eq!(l0.block_of(15, 7), l0.first_block);
        // RGBA8: 256 lines for the same level.
        assert_eq!(
            TextureSet::new(&texs[..1]).textures()[0].levels[0].block_count,
            256
        );
    }

    #[test]
    fn the_decoded_map_finds_every_texels_stored_line() {
        let texs = [
            tex("a", 64, 64, true),
            tex("b", 100, 20, false),
            tex("c", 12, 36, true),
        ];
        let decoded = TextureSet::new(&texs);
        for format in TextureFormat::ALL {
            // Mixed formats too: the etc2 rule gives RGB and RGBA in one set.
            let formats = [format, TextureFormat::Etc2Rgba, format];
            let uses: Vec<TextureUse> = formats
                .iter()
                .map(|&format| TextureUse {
                    format,
                    ..TextureUse::default()
                })
                .collect();
            let stored = TextureSet::with_threads(&texs, 1, &uses);
            let map = decoded.decoded_map(&formats);
            let levels: usize = decoded.textures().iter().map(|t| t.levels.len()).sum();
            assert_eq!(map.levels().len(), levels);
            for (d, s) in decoded.textures().iter().zip(stored.textures()) {
                for (dl, sl) in d.levels.iter().zip(&s.levels) {
                    for y in 0..dl.height {
                        for x in 0..dl.width {
                            assert_eq!(
                                map.stored(dl.block_of(x, y)),
                                Some(sl.block_of(x, y)),
                                "{format} {} {}x{} ({x},{y})",
                                d.name,
                                dl.width,
                                dl.height
                            );
                        }
                    }
                }
            }
        }
    }
}
