//! Textures with their mip chains and the materials that map screen pixels
//! to their texels.

use crate::trace::morton;

/// A texture: base block and mip chain.
pub(super) struct Texture {
    pub(super) base: u64,
    /// Per level: (first block offset, edge in texels, edge in blocks).
    pub(super) levels: Vec<(u64, u32, u32)>,
}

impl Texture {
    pub(super) fn new(base: u64, size: u32) -> Texture {
        let mut levels = Vec::new();
        let (mut offset, mut edge) = (0u64, size);
        loop {
            let blocks_edge = edge.div_ceil(4);
            levels.push((offset, edge, blocks_edge));
            offset += u64::from(blocks_edge) * u64::from(blocks_edge);
            if edge == 1 {
                break;
            }
            edge /= 2;
        }
        Texture { base, levels }
    }

    pub(super) fn total_blocks(&self) -> u64 {
        let &(offset, _, be) = self.levels.last().expect("at least one level");
        offset + u64::from(be) * u64::from(be)
    }

    /// The block holding texel (i, j) of `level`, wrapping.
    pub(super) fn block(&self, level: usize, i: i64, j: i64) -> u64 {
        let (offset, edge, _) = self.levels[level];
        let i = i.rem_euclid(i64::from(edge)) as u32;
        let j = j.rem_euclid(i64::from(edge)) as u32;
        self.base + offset + morton(i / 4, j / 4)
    }
}

/// A material: a surface's texture map, textures and shader program.
pub(super) struct Material {
    pub(super) cx: f64,
    pub(super) cy: f64,
    /// Rotation-and-scale matrix of the base texture, texels per pixel.
    pub(super) m: [f64; 4],
    /// Perspective gradient: w = 1 + g . (pixel - site).
    pub(super) g: [f64; 2],
    /// Texel offset of the map.
    pub(super) u0: f64,
    pub(super) v0: f64,
    /// Direction of repeated taps.
    pub(super) tap: [f64; 2],
    pub(super) textures: Vec<Texture>,
    /// Scale of each texture relative to the base.
    pub(super) tex_scale: Vec<f64>,
    /// Program: `None` = texture instruction, `Some(n)` = n ALU.
    pub(super) program: Vec<Option<u32>>,
}

impl Material {
    /// Texel coordinates (level 0 of the base) of pixel centre (x, y).
    pub(super) fn uv(&self, x: f64, y: f64) -> (f64, f64) {
        let (dx, dy) = (x - self.cx, y - self.cy);
        let w = 1.0 + self.g[0] * dx + self.g[1] * dy;
        let u = (self.m[0] * dx + self.m[1] * dy) / w;
        let v = (self.m[2] * dx + self.m[3] * dy) / w;
        (self.u0 + u, self.v0 + v)
    }

    /// The blocks texture instruction `j` of the quad at pixel (px, py)
    /// touches, in first-touch order.
    pub(super) fn tex_blocks(&self, j: usize, px: f64, py: f64, mipmaps: bool, out: &mut Vec<u64>) {
        out.clear();
        let t = j % self.textures.len();
        let round = (j / self.textures.len()) as f64;
        let tex = &self.textures[t];
        let k = self.tex_scale[t];
        let centres = [(0.5, 0.5), (1.5, 0.5), (0.5, 1.5), (1.5, 1.5)];
        let uv = centres.map(|(ox, oy)| {
            let (u, v) = self.uv(px + ox, py + oy);
            (u * k, v * k)
        });
        let level = if mipmaps {
            // Squared texel footprint per pixel along x and y, across the
            // quad; the level is round(log2(footprint)), found by exact
            // comparisons of the square with powers of two.
            let sq = |a: (f64, f64), b: (f64, f64)| {
                let (du, dv) = (b.0 - a.0, b.1 - a.1);
                du * du + dv * dv
            };
            let f2 = sq(uv[0], uv[1]).max(sq(uv[0], uv[2]));
            let mut level = 0;
            while level + 1 < tex.levels.len() && f2 >= f64::from(1u32 << (2 * level + 1)) {
                level += 1;
            }
            level
        } else {
            0
        };
        let inv = 1.0 / f64::from(1u32 << level);
        for &(u, v) in &uv {
            let u = u * inv + round * 1.5 * self.tap[0];
            let v = v * inv + round * 1.5 * self.tap[1];
            let (i0, j0) = ((u - 0.5).floor() as i64, (v - 0.5).floor() as i64);
            for (di, dj) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                let b = tex.block(level, i0 + di, j0 + dj);
                if !out.contains(&b) {
                    out.push(b);
                }
            }
        }
    }
}
