//! The texture map of a trace that lists decoded lines (`texture-lines
//! decoded`): for each mip level, where its RGBA8 lines (the decoded
//! texels a texture cache holding decompressed texels keeps, the blocks
//! the texture instructions list) lie, and where the compressed lines that
//! hold the same texels lie in memory (what the L2 and DRAM hold), so that
//! the cycle model can find the compressed line of any listed block.
//!
//! Both layouts are the front end's block-linear one (`docs/textures.md`):
//! a level is a power-of-two grid of 64-byte lines stored in Morton squares
//! (squares of `2^k x 2^k` lines, `k` the log2 of the grid's shorter edge,
//! row after row of squares, the lines of a square in Morton order, x in
//! the even bits). An RGBA8 line holds 4x4 texels; a compressed line holds
//! `rx x ry` RGBA8 lines' worth of texels (ETC2 RGB: 4 x 2, ASTC 8x8: 4 x 4,
//! ASTC 6x6: 3 x 3), so RGBA8 line (x, y) of a level lies in compressed line
//! (x / rx, y / ry) of the same level.

use crate::zorder::morton;
use crate::Problem;

/// Largest edge of a level's grid of lines (a 16384-texel level has 4096
/// RGBA8 lines a row): 65536.
pub const MAX_GRID: u32 = 1 << 16;

/// Largest number of RGBA8 lines along one edge of a compressed line (an
/// ASTC 12x12 line of 2x2 blocks would need 6; room to spare).
pub const MAX_LINES_PER_LINE: u32 = 16;

/// One mip level of the map: a `texture-level` line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MapLevel {
    /// Block number of the level's first RGBA8 line.
    pub first: u64,
    /// The level's grid of RGBA8 lines (width, height): powers of two.
    pub grid: (u32, u32),
    /// Block number of the level's first compressed line.
    pub stored_first: u64,
    /// The level's grid of compressed lines (width, height): powers of two.
    pub stored_grid: (u32, u32),
    /// RGBA8 lines along x and y of one compressed line.
    pub per_line: (u32, u32),
}

impl MapLevel {
    /// Lines of the RGBA8 grid.
    pub fn lines(&self) -> u64 {
        u64::from(self.grid.0) * u64::from(self.grid.1)
    }

    /// The `texture-level` line's fields after the word.
    pub fn to_fields(&self) -> String {
        format!(
            "{:x} {} {} {:x} {} {} {} {}",
            self.first,
            self.grid.0,
            self.grid.1,
            self.stored_first,
            self.stored_grid.0,
            self.stored_grid.1,
            self.per_line.0,
            self.per_line.1
        )
    }

    /// Checks one level on its own: power-of-two grids up to [`MAX_GRID`],
    /// lines per line 1 to [`MAX_LINES_PER_LINE`], no address overflow.
    fn check(&self) -> Result<(), String> {
        for (what, (w, h)) in [("RGBA8 grid", self.grid), ("stored grid", self.stored_grid)] {
            for v in [w, h] {
                if !v.is_power_of_two() || v > MAX_GRID {
                    return Err(format!(
                        "{what} {w}x{h} (expected powers of two from 1 to {MAX_GRID})"
                    ));
                }
            }
        }
        let (rx, ry) = self.per_line;
        if !(1..=MAX_LINES_PER_LINE).contains(&rx) || !(1..=MAX_LINES_PER_LINE).contains(&ry) {
            return Err(format!(
                "{rx}x{ry} RGBA8 lines per stored line (expected 1 to {MAX_LINES_PER_LINE} each)"
            ));
        }
        let stored = u64::from(self.stored_grid.0) * u64::from(self.stored_grid.1);
        if self.first.checked_add(self.lines()).is_none()
            || self.stored_first.checked_add(stored).is_none()
        {
            return Err("its lines run past the last block number".into());
        }
        Ok(())
    }

    /// Column and row of RGBA8 line `block` of this level (`block` inside
    /// it).
    #[inline]
    fn cell_of(&self, block: u64) -> (u32, u32) {
        let inner = block - self.first;
        let k = self.grid.0.min(self.grid.1).trailing_zeros();
        let square = inner >> (2 * k);
        let (x, y) = unmorton(inner & ((1u64 << (2 * k)) - 1));
        let per_row = u64::from(self.grid.0 >> k);
        let (sx, sy) = ((square % per_row) as u32, (square / per_row) as u32);
        ((sx << k) | x, (sy << k) | y)
    }

    /// The compressed line holding RGBA8 line `block` of this level, or
    /// `None` when it lies outside the stored grid.
    #[inline]
    fn stored_of(&self, block: u64) -> Option<u64> {
        let (x, y) = self.cell_of(block);
        let (cx, cy) = (x / self.per_line.0, y / self.per_line.1);
        let (cw, ch) = self.stored_grid;
        if cx >= cw || cy >= ch {
            return None;
        }
        let k = cw.min(ch).trailing_zeros();
        let mask = (1u32 << k) - 1;
        let square = u64::from(cy >> k) * u64::from(cw >> k) + u64::from(cx >> k);
        Some(self.stored_first + (square << (2 * k)) + morton(cx & mask, cy & mask))
    }
}

/// The inverse of [`morton`] for a key of up to 64 bits.
#[inline]
fn unmorton(key: u64) -> (u32, u32) {
    fn squash(mut v: u64) -> u32 {
        v &= 0x5555_5555_5555_5555;
        v = (v | (v >> 1)) & 0x3333_3333_3333_3333;
        v = (v | (v >> 2)) & 0x0f0f_0f0f_0f0f_0f0f;
        v = (v | (v >> 4)) & 0x00ff_00ff_00ff_00ff;
        v = (v | (v >> 8)) & 0x0000_ffff_0000_ffff;
        v = (v | (v >> 16)) & 0x0000_0000_ffff_ffff;
        v as u32
    }
    (squash(key), squash(key >> 1))
}

/// Every level of a decoded-lines trace, in increasing RGBA8 block order,
/// their RGBA8 ranges disjoint.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct TextureMap {
    levels: Vec<MapLevel>,
}

impl TextureMap {
    /// An empty map (a scene without textures).
    pub fn new() -> TextureMap {
        TextureMap::default()
    }

    /// Adds the next level: it must be valid and start after the last
    /// level's RGBA8 lines.
    pub fn push(&mut self, level: MapLevel) -> Result<(), Problem> {
        let bad = |why: String| Problem::BadTextureLevel(why);
        level.check().map_err(bad)?;
        if let Some(last) = self.levels.last() {
            if level.first < last.first + last.lines() {
                return Err(bad(format!(
                    "its RGBA8 lines start at block {:x}, inside the previous level's \
                     (levels in increasing block order, not overlapping)",
                    level.first
                )));
            }
        }
        self.levels.push(level);
        Ok(())
    }

    /// The levels, in order.
    pub fn levels(&self) -> &[MapLevel] {
        &self.levels
    }

    /// The compressed line (block number) holding the texels of RGBA8 line
    /// `block`, or `None` when `block` lies in no level or outside its
    /// level's stored grid (the reader refuses such blocks in a trace).
    #[inline]
    pub fn stored(&self, block: u64) -> Option<u64> {
        let i = self.levels.partition_point(|l| l.first <= block);
        let level = self.levels.get(i.checked_sub(1)?)?;
        if block - level.first >= level.lines() {
            return None;
        }
        level.stored_of(block)
    }

    /// Checks a texture instruction's block against the map.
    pub(crate) fn check_block(&self, block: u64) -> Result<(), Problem> {
        match self.stored(block) {
            Some(_) => Ok(()),
            None => Err(Problem::BlockOutsideTextureMap(block)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A level of `w x h` texels at `first` / `stored`, in a format whose
    /// line holds `lx x ly` texels, laid out as the front end does.
    fn level(w: u32, h: u32, first: u64, stored: u64, lx: u32, ly: u32) -> MapLevel {
        let grid = |a: u32, b: u32| a.div_ceil(b).next_power_of_two();
        MapLevel {
            first,
            grid: (grid(w, 4), grid(h, 4)),
            stored_first: stored,
            stored_grid: (grid(w, lx), grid(h, ly)),
            per_line: (lx / 4, ly / 4),
        }
    }

    /// Block of texel (x, y) in a level laid out in lines of `lx x ly`
    /// texels: the front end's rule, written out independently.
    fn block_of(first: u64, gw: u32, gh: u32, x: u32, y: u32, lx: u32, ly: u32) -> u64 {
        let (bx, by) = (x / lx, y / ly);
        let k = gw.min(gh).trailing_zeros();
        let mask = (1 << k) - 1;
        let square = u64::from(by >> k) * u64::from(gw >> k) + u64::from(bx >> k);
        first + (square << (2 * k)) + morton(bx & mask, by & mask)
    }

    #[test]
    fn unmorton_inverts_morton() {
        for (x, y) in [(0, 0), (1, 0), (0, 1), (5, 9), (4095, 17), (65535, 65535)] {
            assert_eq!(unmorton(morton(x, y)), (x, y));
        }
    }

    #[test]
    fn every_texel_maps_to_the_stored_line_holding_it() {
        // ETC2 RGB (16x8-texel lines), ASTC 8x8 (16x16), ASTC 6x6 (12x12),
        // on square, wide and tall levels whose sizes are not multiples.
        for (lx, ly) in [(16, 8), (16, 16), (12, 12), (8, 8)] {
            for (w, h) in [(64, 64), (100, 20), (20, 100), (12, 12), (1, 1), (37, 5)] {
                let l = level(w, h, 0x1000, 0x9000, lx, ly);
                let mut map = TextureMap::new();
                map.push(l).unwrap();
                for y in 0..h {
                    for x in 0..w {
                        let rgba8 = block_of(l.first, l.grid.0, l.grid.1, x, y, 4, 4);
                        let (cw, ch) = l.stored_grid;
                        let want = block_of(l.stored_first, cw, ch, x, y, lx, ly);
                        assert_eq!(map.stored(rgba8), Some(want), "{lx}x{ly} {w}x{h} ({x},{y})");
                    }
                }
            }
        }
    }

    #[test]
    fn blocks_outside_every_level_have_no_stored_line() {
        let mut map = TextureMap::new();
        let a = level(64, 64, 0x1000, 0x9000, 16, 8);
        map.push(a).unwrap();
        map.push(level(32, 32, 0x1000 + 256, 0x9000 + 32, 16, 8))
            .unwrap();
        assert_eq!(map.stored(0xfff), None);
        assert!(map.stored(0x1000 + 255).is_some());
        assert!(map.stored(0x1000 + 256).is_some());
        assert_eq!(map.stored(0x1000 + 256 + 64), None);
        assert_eq!(
            map.check_block(0x5),
            Err(Problem::BlockOutsideTextureMap(0x5))
        );
        // A padded RGBA8 cell beyond the stored grid (ASTC 6x6, 12 texels:
        // 4 RGBA8 lines a row, the fourth past the one stored line).
        let mut m = TextureMap::new();
        m.push(level(12, 12, 0, 0x100, 12, 12)).unwrap();
        assert_eq!(m.stored(block_of(0, 4, 4, 12, 0, 4, 4)), None);
    }

    #[test]
    fn bad_levels_are_refused() {
        let mut map = TextureMap::new();
        let good = level(64, 64, 0x1000, 0x9000, 16, 8);
        map.push(good).unwrap();
        let overlap = MapLevel {
            first: 0x1000 + 100,
            ..good
        };
        let e = map.push(overlap).unwrap_err().to_string();
        assert!(e.contains("inside the previous level"), "{e}");
        for bad in [
            MapLevel {
                grid: (3, 4),
                ..good
            },
            MapLevel {
                stored_grid: (4, 0),
                ..good
            },
            MapLevel {
                per_line: (0, 2),
                ..good
            },
            MapLevel {
                per_line: (17, 2),
                ..good
            },
            MapLevel {
                first: u64::MAX - 3,
                ..good
            },
        ] {
            assert!(matches!(
                TextureMap::new().push(bad),
                Err(Problem::BadTextureLevel(_))
            ));
        }
    }
}
