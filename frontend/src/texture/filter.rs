//! Filtered colours for the picture: texels as colours, and nearest,
//! bilinear and trilinear samples (alpha alone for the alpha test).

use super::*;

impl MipLevel<'_> {
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

impl TextureSet<'_> {
    /// The alpha of pixel `pixel` (0..4) of the quad whose texels
    /// [`TextureSet::quad_blocks_texels`] kept in `q`: the same value as
    /// `sample_alpha` of that pixel's UV with the quad's lambda.
    pub fn quad_alpha(&self, q: &QuadTexels, pixel: usize) -> f32 {
        let level = |(t, l): (usize, usize)| &self.textures[t].levels[l];
        let r = &q.reads;
        let a = footprint_alpha(level(r.first), q.filter, &q.px[0][pixel]);
        match r.second {
            Some(second) if r.weight > 0.0 => {
                let b = footprint_alpha(level(second), q.filter, &q.px[1][pixel]);
                a + (b - a) * r.weight
            }
            _ => a,
        }
    }

    /// The filtered colour (RGBA in 0..=1) of a mipmapped sample of
    /// `texture` at `uv` with this filter and the quad's `lambda` (from
    /// [`TextureSet::quad_lambda`]).
    pub fn sample_rgba(
        &self,
        texture: usize,
        filter: Filter,
        uv: [f32; 2],
        lambda: f32,
    ) -> [f32; 4] {
        self.sample_rgba_of(&TexSample::new(texture, 0, filter), uv, lambda)
    }

    /// The filtered colour (RGBA in 0..=1) of `sample` at `uv` with the
    /// quad's `lambda`: what it reads ([`TextureSet::reads`]) filtered.
    pub fn sample_rgba_of(&self, sample: &TexSample, uv: [f32; 2], lambda: f32) -> [f32; 4] {
        let filter = sample.filter;
        let r = self.reads(sample, lambda);
        let one = |(t, l): (usize, usize)| {
            let tex = &self.textures[t];
            let level = &tex.levels[l];
            match filter {
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
            }
        };
        let a = one(r.first);
        let Some(second) = r.second.filter(|_| r.weight > 0.0) else {
            return a;
        };
        let b = one(second);
        let mut o = [0.0f32; 4];
        for i in 0..4 {
            o[i] = a[i] + (b[i] - a[i]) * r.weight;
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::texture::fixtures::*;

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
            ..TextureUse::default()
        };
        let alpha = TextureSet::with_threads(&texs, 2, &[u(true), u(false), u(true), u(true)]);
        // Unsampled textures: the same layout, no texels beyond level 0.
        let bare = TextureSet::with_threads(
            &texs,
            2,
            &[TextureUse {
                sampled: false,
                alpha_tested: true,
                ..TextureUse::default()
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
                let smp = TexSample::new(texture, 0, filter);
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
