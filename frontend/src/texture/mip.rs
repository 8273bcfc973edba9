//! Mip chains: each level box-filtered (2x2 average) from the one above,
//! down to 1x1.

use super::*;

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

/// One level down a mip chain, as the texture path builds it: half the size per
/// side (at least 1), each texel the mean of its 2x2 source texels. A
/// loader uses it to upload a texture from a smaller level, as an engine
/// does at `r_picmip` above 0.
pub fn halve(w: u32, h: u32, rgba: &[u8]) -> (u32, u32, Vec<u8>) {
    downsample(w, h, rgba)
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

/// Mip levels as (width, height, texels).
pub(super) type Chain<'a> = Vec<(u32, u32, Cow<'a, [u8]>)>;

/// The mip chain of one texture, level 0 borrowed: (width, height, texels)
/// per level, down to 1x1; without `texels`, the levels beyond 0 are sizes
/// only (empty texels). A texture with a zero edge or a texel array of the
/// wrong size becomes a 1x1 magenta texture.
pub(super) fn mip_chain(t: &Texture, texels: bool) -> Chain<'_> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::texture::fixtures::*;

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
}
