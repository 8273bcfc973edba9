//! Where a sample reads: a quad's level of detail, the mip levels its
//! filter reads, the texels of each pixel's sample (wrapped or clamped),
//! and the distinct blocks a quad's texture instruction touches.

use super::*;

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

/// The texels one pixel's sample reads in one level: the 2x2 texels
/// x0..=x1, y0..=y1 (x1, y1 wrapped or clamped) and the blend fractions;
/// nearest: the one texel (x0, y0) = (x1, y1), fractions 0.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Footprint {
    pub(super) x0: u32,
    pub(super) x1: u32,
    pub(super) y0: u32,
    pub(super) y1: u32,
    pub(super) fx: f32,
    pub(super) fy: f32,
}

/// Where the 4 pixels of a quad read one texture instruction
/// ([`TextureSet::quad_blocks_texels`]), for [`TextureSet::quad_alpha`].
#[derive(Clone, Copy, Debug)]
pub struct QuadTexels {
    pub(super) filter: Filter,
    /// The (texture, level) pairs read and the second one's weight
    /// ([`TextureSet::reads`]).
    pub(super) reads: Reads,
    /// Per pass (first, second), per pixel.
    pub(super) px: [[Footprint; 4]; 2],
}

impl Default for QuadTexels {
    fn default() -> Self {
        QuadTexels {
            filter: Filter::Nearest,
            reads: Reads {
                first: (0, 0),
                second: None,
                weight: 0.0,
            },
            px: [[Footprint::default(); 4]; 2],
        }
    }
}

/// What a texture instruction reads: the (texture, level) of its first
/// filter pass, that of its second if it has one, and the second's weight
/// in the result.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reads {
    pub first: (usize, usize),
    pub second: Option<(usize, usize)>,
    pub weight: f32,
}

/// The texels a sample with `filter` at `uv` reads in `level`.
#[inline(always)]
pub(super) fn footprint(level: &MipLevel, filter: Filter, repeat: bool, uv: [f32; 2]) -> Footprint {
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

/// The texel containing the sample point.
#[inline(always)]
pub(super) fn nearest(level: &MipLevel, repeat: bool, uv: [f32; 2]) -> (u32, u32) {
    let x = floor_i64(f64::from(uv[0]) * f64::from(level.width));
    let y = floor_i64(f64::from(uv[1]) * f64::from(level.height));
    (wrap(x, level.width, repeat), wrap(y, level.height, repeat))
}

/// The 2x2 texels around the sample point and the blend fractions.
#[inline(always)]
pub(super) fn bilinear(
    level: &MipLevel,
    repeat: bool,
    uv: [f32; 2],
) -> (u32, u32, u32, u32, f32, f32) {
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

impl TextureSet<'_> {
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
        self.reads(sample, lambda).second.is_some()
    }

    /// The (texture, level) pairs `sample` reads at this level of detail:
    /// the levels [`TextureSet::levels_for`] gives for a mipmapped sample,
    /// level 0 alone for one that is not; a sample with a
    /// [`crate::SecondSlice`] reads level 0 of its texture and of the
    /// second, with the second's weight.
    #[inline]
    pub fn reads(&self, sample: &TexSample, lambda: f32) -> Reads {
        if let Some(s) = sample.second {
            return Reads {
                first: (sample.texture, 0),
                second: Some((s.texture, 0)),
                weight: f32::from(s.weight) / 65536.0,
            };
        }
        let (la, lb, weight) = if sample.mipmapped {
            self.levels_for(sample.texture, sample.filter, lambda)
        } else {
            (0, 0, 0.0)
        };
        Reads {
            first: (sample.texture, la),
            second: (lb != la).then_some((sample.texture, lb)),
            weight,
        }
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
        let lambda = self.quad_lambda(sample.texture, &uvs);
        let reads = self.reads(sample, lambda);
        // A block holds the texels of one cell of its level (4x4 texels in
        // RGBA8, the format's line region otherwise), so the distinct cells
        // the texels fall in (few: at most 16 per level) give the distinct
        // blocks; levels never share a block.
        let mut push_level = |(t, l): (usize, usize), slot: usize| {
            let tex = &self.textures[t];
            let level = &tex.levels[l];
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
                let (cx0, cy0) = level.cell_of(f.x0, f.y0);
                let (cx1, cy1) = level.cell_of(f.x1, f.y1);
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
            out.extend(
                cells[..n]
                    .iter()
                    .map(|&k| level.block_of_cell(k as u32, (k >> 32) as u32)),
            );
        };
        push_level(reads.first, 0);
        if let Some(second) = reads.second {
            push_level(second, 1);
        }
        if let Some(q) = texels {
            q.filter = sample.filter;
            q.reads = reads;
        }
        out.sort_unstable();
        lambda
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::texture::fixtures::*;

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
        let rep = TexSample::new(0, 0, Filter::Bilinear);
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
}
