//! Which core shades a quad: the warp scheduler's placement of surviving
//! quads by screen position.
//!
//! The paper: "After the Rasterizer, the warp scheduler allocates warps to
//! the input FIFO queues of each GPU Core" and "the baseline scheduler
//! already evaluates these coordinates to assign warps to a specific GPU
//! core" (Section IV-D). It does not say how; the map is this model's
//! choice, a configuration field (`raster.core_map`).
//!
//! The tile is cut into blocks of BxB quads (B a power of two), G blocks a
//! side; block (bx, by) goes to
//!
//! * `latin:B` (the default, B = 8): core `(bx + r(by)) mod cores`, where
//!   `r` reverses the bits of `by` within log2(G) bits. On the paper's four
//!   cores with 32x32-quad tiles (G = 4) the blocks form a Latin square
//!   whose rows are 0123 / 2301 / 1230 / 3012: every row and every column
//!   of blocks holds every core, and so do the four blocks at even (bx,
//!   by). So every priority subset the model has — Mesh2/4/8/16 (the
//!   quads with x and y multiples of 2, 4, 8, 16), horizontal and vertical
//!   lines every 16 quads, the top 1/16th (two rows) and a random 1/16 —
//!   puts priority quads on every core, while each core keeps 16x16-pixel
//!   regions whose texels neighbour each other (its L0 and L1 see texture
//!   locality).
//! * `rowmajor:B`: core `(bx + by * G) mod cores`, blocks numbered row by
//!   row. `rowmajor:16` gives the four cores the four quadrants;
//!   `rowmajor:1` interleaves single quads and puts every Mesh4 priority
//!   quad (x a multiple of 4) on core 0 — what a map must not do.
//!
//! The map is built once as a table of one byte per in-tile position.

use std::fmt;
use std::str::FromStr;

/// A quad-to-core map (see the module documentation), written as its name
/// in a config file (`latin:8`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "String", into = "String")]
pub enum CoreMap {
    /// `latin:B`: block column plus bit-reversed block row, modulo cores.
    Latin {
        /// Block side in quads.
        block: u32,
    },
    /// `rowmajor:B`: blocks numbered row by row, modulo cores.
    RowMajor {
        /// Block side in quads.
        block: u32,
    },
}

impl fmt::Display for CoreMap {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CoreMap::Latin { block } => write!(f, "latin:{block}"),
            CoreMap::RowMajor { block } => write!(f, "rowmajor:{block}"),
        }
    }
}

impl FromStr for CoreMap {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let expected = "expected latin:B or rowmajor:B, B a power of two from 1 to 32";
        let (kind, b) = s
            .split_once(':')
            .ok_or_else(|| format!("`{s}`: {expected}"))?;
        let block: u32 = b
            .parse()
            .map_err(|_| format!("`{s}`: block size `{b}` is not a number ({expected})"))?;
        if !(1..=32).contains(&block) || !block.is_power_of_two() {
            return Err(format!("`{s}`: block size {block} ({expected})"));
        }
        match kind {
            "latin" => Ok(CoreMap::Latin { block }),
            "rowmajor" => Ok(CoreMap::RowMajor { block }),
            _ => Err(format!("`{s}`: unknown map `{kind}` ({expected})")),
        }
    }
}

/// Read from its name in a config file: the error names the allowed forms.
impl TryFrom<String> for CoreMap {
    type Error = String;
    fn try_from(s: String) -> Result<Self, String> {
        s.parse()
    }
}

impl From<CoreMap> for String {
    fn from(m: CoreMap) -> String {
        m.to_string()
    }
}

impl CoreMap {
    /// The core of in-tile quad (x, y) for tiles of `side` quads a side
    /// (a power of two) on `cores` cores: the plain formula.
    pub fn core_of(self, x: u32, y: u32, side: u32, cores: u32) -> u32 {
        let block = match self {
            CoreMap::Latin { block } | CoreMap::RowMajor { block } => block,
        };
        let g = (side / block).max(1);
        let (bx, by) = (x / block, y / block);
        match self {
            CoreMap::Latin { .. } => {
                let bits = g.trailing_zeros();
                let r = if bits == 0 {
                    0
                } else {
                    by.reverse_bits() >> (32 - bits)
                };
                (bx + r) % cores
            }
            CoreMap::RowMajor { .. } => (bx + by * g) % cores,
        }
    }

    /// The map as a table indexed by `y * side + x`.
    pub fn table(self, side: u32, cores: u32) -> CoreMapTable {
        let mut t = Vec::with_capacity((side * side) as usize);
        for y in 0..side {
            for x in 0..side {
                t.push(self.core_of(x, y, side, cores) as u8);
            }
        }
        CoreMapTable {
            side,
            cores: t.into(),
        }
    }
}

/// A [`CoreMap`] tabulated for one tile size and core count.
#[derive(Clone, Debug)]
pub struct CoreMapTable {
    side: u32,
    cores: Box<[u8]>,
}

impl CoreMapTable {
    /// The core of in-tile quad (x, y).
    #[inline]
    pub fn core(&self, x: u32, y: u32) -> usize {
        self.cores[(y * self.side + x) as usize] as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use wasp_rtl::subset::SubsetSpec;

    const SIDE: u32 = 32;

    /// Priority quads per core under `map` for `subset` on 4 cores.
    fn spread(map: CoreMap, subset: &str) -> Vec<u32> {
        let s: SubsetSpec = subset.parse().unwrap();
        let s = s.build(SIDE);
        let t = map.table(SIDE, 4);
        let mut per = vec![0u32; 4];
        for y in 0..SIDE {
            for x in 0..SIDE {
                if s.is_priority(x, y) {
                    per[t.core(x, y)] += 1;
                }
            }
        }
        per
    }

    #[test]
    fn the_default_map_is_the_latin_square() {
        let m: CoreMap = "latin:8".parse().unwrap();
        let rows: Vec<Vec<u32>> = (0..4)
            .map(|by| {
                (0..4)
                    .map(|bx| m.core_of(bx * 8, by * 8, SIDE, 4))
                    .collect()
            })
            .collect();
        assert_eq!(
            rows,
            vec![
                vec![0, 1, 2, 3],
                vec![2, 3, 0, 1],
                vec![1, 2, 3, 0],
                vec![3, 0, 1, 2]
            ]
        );
    }

    #[test]
    fn every_subset_reaches_every_core_under_the_default_map() {
        let m: CoreMap = "latin:8".parse().unwrap();
        for subset in [
            "mesh2", "mesh4", "mesh8", "mesh16", "hlines", "vlines", "top16", "random:1",
            "random:7",
        ] {
            let per = spread(m, subset);
            assert!(per.iter().all(|&n| n > 0), "{subset}: {per:?}");
        }
        // The regular subsets spread exactly evenly.
        for subset in [
            "mesh2", "mesh4", "mesh8", "mesh16", "hlines", "vlines", "top16",
        ] {
            let per = spread(m, subset);
            assert!(per.iter().all(|&n| n == per[0]), "{subset}: {per:?}");
        }
    }

    #[test]
    fn a_single_quad_interleave_puts_mesh4_on_one_core() {
        let m: CoreMap = "rowmajor:1".parse().unwrap();
        assert_eq!(spread(m, "mesh4"), vec![64, 0, 0, 0]);
        // Quadrants: Top16th (the two top rows) reaches two cores only.
        let q: CoreMap = "rowmajor:16".parse().unwrap();
        assert_eq!(spread(q, "top16"), vec![32, 32, 0, 0]);
        assert_eq!(spread(q, "mesh4"), vec![16, 16, 16, 16]);
    }

    #[test]
    fn every_core_gets_an_equal_share_of_the_tile() {
        for map in ["latin:8", "latin:4", "latin:1", "rowmajor:16", "rowmajor:2"] {
            let m: CoreMap = map.parse().unwrap();
            let t = m.table(SIDE, 4);
            let mut per = [0u32; 4];
            for y in 0..SIDE {
                for x in 0..SIDE {
                    per[t.core(x, y)] += 1;
                }
            }
            assert_eq!(per, [256; 4], "{map}");
        }
    }

    #[test]
    fn the_table_agrees_with_the_formula_for_every_shape() {
        for map in [
            "latin:1",
            "latin:8",
            "latin:32",
            "rowmajor:4",
            "rowmajor:32",
        ] {
            let m: CoreMap = map.parse().unwrap();
            for side in [2u32, 4, 8, 16, 32] {
                for cores in 1..=6 {
                    let t = m.table(side, cores);
                    for y in 0..side {
                        for x in 0..side {
                            let c = m.core_of(x, y, side, cores);
                            assert!(c < cores);
                            assert_eq!(t.core(x, y), c as usize);
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn bad_maps_name_the_problem() {
        for (s, want) in [
            ("latin", "expected latin:B"),
            ("latin:3", "block size 3"),
            ("latin:64", "block size 64"),
            ("latin:x", "not a number"),
            ("diagonal:8", "unknown map `diagonal`"),
        ] {
            let e = s.parse::<CoreMap>().unwrap_err();
            assert!(e.contains(want), "{s}: {e}");
        }
        assert_eq!(
            "rowmajor:16".parse::<CoreMap>().unwrap().to_string(),
            "rowmajor:16"
        );
    }
}
