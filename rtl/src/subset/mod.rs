//! Priority-subset selectors: which quads of a tile are priority warps.
//!
//! A selector sees only what the hardware sees when a quad is enqueued: its
//! in-tile quad coordinates (0..side, side = tile pixels / 2). The paper's
//! candidates (Section III-B, Figure "Different Priority subsets") are
//! Mesh-k for k = 2, 4, 8, 16, horizontal and vertical lines, the top 16th
//! and a random 1/16th; one file each.

mod explicit;
mod lines;
mod mesh;
mod random;
mod top;

pub use explicit::Explicit;
pub use lines::{HorizontalLines, VerticalLines};
pub use mesh::Mesh;
pub use random::Random;
pub use top::Top;

use std::fmt;
use std::str::FromStr;

/// Decides whether a quad is a priority warp.
///
/// A selector is combinational: `is_priority` is a pure function of the
/// coordinates (the scheduler reads it once per coordinate into a
/// [`SubsetTable`]).
pub trait PrioritySubset: fmt::Debug + Send + Sync {
    /// Short name as used on the command line (`mesh4`, `hlines`, ...).
    fn name(&self) -> String;
    /// Whether the quad at in-tile quad coordinates (`qx`, `qy`) is a
    /// priority warp.
    fn is_priority(&self, qx: u32, qy: u32) -> bool;
    /// Fraction of a `side` x `side` tile that is selected (the paper's
    /// subset size ratio), counted by enumeration.
    fn size_ratio(&self, side: u32) -> f64 {
        let mut n = 0u64;
        for y in 0..side {
            for x in 0..side {
                n += self.is_priority(x, y) as u64;
            }
        }
        n as f64 / (side as f64 * side as f64)
    }
}

/// Side of the coordinate square a [`SubsetTable`] covers: every 5-bit
/// in-tile quad coordinate (a 64 x 64-pixel tile is 32 x 32 quads).
pub const TABLE_SIDE: u32 = 1 << mesh::QUAD_COORD_BITS;

/// A selector's truth table over the in-tile coordinates `0..32` on each
/// axis, read once from the selector. Row `y` holds the 32 answers for
/// `x = 0..32` as bits, bit `x` set when the quad is a priority warp, so a
/// look-up is one shift and one AND. Coordinates outside the square are not
/// in the table; [`SubsetTable::get`] says so with `None`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SubsetTable {
    rows: [u32; TABLE_SIDE as usize],
}

impl SubsetTable {
    /// The table of `subset`: `TABLE_SIDE`^2 calls of `is_priority`.
    pub fn of(subset: &dyn PrioritySubset) -> Self {
        let mut rows = [0u32; TABLE_SIDE as usize];
        for (y, row) in (0..TABLE_SIDE).zip(rows.iter_mut()) {
            for x in 0..TABLE_SIDE {
                *row |= (subset.is_priority(x, y) as u32) << x;
            }
        }
        Self { rows }
    }

    /// The table that selects nothing.
    pub const fn empty() -> Self {
        Self {
            rows: [0; TABLE_SIDE as usize],
        }
    }

    /// The selector's answer for (`qx`, `qy`), or `None` outside the
    /// table's square.
    #[inline]
    pub fn get(&self, qx: u32, qy: u32) -> Option<bool> {
        if (qx | qy) < TABLE_SIDE {
            Some((self.rows[qy as usize] >> qx) & 1 == 1)
        } else {
            None
        }
    }
}

/// A subset named on the command line or in a config file (where it is
/// written as its name, `mesh4`).
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(try_from = "String", into = "String")]
pub enum SubsetSpec {
    /// Mesh-k, k in {2, 4, 8, 16}.
    Mesh(u32),
    /// Every 16th row of quads.
    HorizontalLines,
    /// Every 16th column of quads.
    VerticalLines,
    /// The top 16th of the tile.
    Top16,
    /// A seeded random 1/16th of the tile.
    Random(u64),
}

impl SubsetSpec {
    /// Every subset the paper evaluates, for sweeps.
    pub fn all() -> Vec<SubsetSpec> {
        vec![
            SubsetSpec::Top16,
            SubsetSpec::HorizontalLines,
            SubsetSpec::VerticalLines,
            SubsetSpec::Mesh(2),
            SubsetSpec::Mesh(4),
            SubsetSpec::Mesh(8),
            SubsetSpec::Mesh(16),
            SubsetSpec::Random(1),
        ]
    }

    /// Build the selector for tiles of `side` x `side` quads.
    pub fn build(&self, side: u32) -> Box<dyn PrioritySubset> {
        match *self {
            SubsetSpec::Mesh(k) => Box::new(Mesh::new(k).expect("validated at parse")),
            SubsetSpec::HorizontalLines => Box::new(HorizontalLines::new(side)),
            SubsetSpec::VerticalLines => Box::new(VerticalLines::new(side)),
            SubsetSpec::Top16 => Box::new(Top::new(side, 16)),
            SubsetSpec::Random(seed) => Box::new(Random::new(side, 16, seed)),
        }
    }
}

impl fmt::Display for SubsetSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SubsetSpec::Mesh(k) => write!(f, "mesh{k}"),
            SubsetSpec::HorizontalLines => f.write_str("hlines"),
            SubsetSpec::VerticalLines => f.write_str("vlines"),
            SubsetSpec::Top16 => f.write_str("top16"),
            SubsetSpec::Random(seed) => write!(f, "random:{seed}"),
        }
    }
}

impl FromStr for SubsetSpec {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let lower = s.trim().to_ascii_lowercase();
        let (head, arg) = match lower.split_once(':') {
            Some((h, a)) => (h, Some(a)),
            None => (lower.as_str(), None),
        };
        let no_arg = |spec: SubsetSpec| match arg {
            None => Ok(spec),
            Some(_) => Err(format!("subset `{s}` takes no `:` argument")),
        };
        match head {
            "mesh2" => no_arg(SubsetSpec::Mesh(2)),
            "mesh4" => no_arg(SubsetSpec::Mesh(4)),
            "mesh8" => no_arg(SubsetSpec::Mesh(8)),
            "mesh16" => no_arg(SubsetSpec::Mesh(16)),
            "hlines" | "horizontal-lines" => no_arg(SubsetSpec::HorizontalLines),
            "vlines" | "vertical-lines" => no_arg(SubsetSpec::VerticalLines),
            "top16" | "top" => no_arg(SubsetSpec::Top16),
            "random" => match arg {
                None => Ok(SubsetSpec::Random(1)),
                Some(a) => a
                    .parse::<u64>()
                    .map(SubsetSpec::Random)
                    .map_err(|_| format!("subset `{s}`: expected random:<seed> with an integer seed")),
            },
            _ => Err(format!(
                "unknown priority subset `{s}` (expected one of mesh2, mesh4, mesh8, mesh16, hlines, vlines, top16, random[:seed])"
            )),
        }
    }
}

/// Read from its name in a config file: the error names the allowed forms.
impl TryFrom<String> for SubsetSpec {
    type Error = String;
    fn try_from(s: String) -> Result<Self, String> {
        s.parse()
    }
}

impl From<SubsetSpec> for String {
    fn from(s: SubsetSpec) -> String {
        s.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_papers_subset_is_listed_and_names_itself() {
        let all = SubsetSpec::all();
        let names: Vec<String> = all.iter().map(|s| s.to_string()).collect();
        assert_eq!(
            names,
            ["top16", "hlines", "vlines", "mesh2", "mesh4", "mesh8", "mesh16", "random:1"]
        );
        for spec in all {
            assert_eq!(spec.build(32).name(), spec.to_string());
        }
        assert_eq!(SubsetSpec::Random(77).build(32).name(), "random:77");
        assert_eq!(Explicit::new([(1, 2)]).name(), "explicit");
    }

    #[test]
    fn every_paper_subset_selects_one_sixteenth_except_mesh_sizes() {
        for spec in SubsetSpec::all() {
            let s = spec.build(32);
            let want = match spec {
                SubsetSpec::Mesh(k) => 1.0 / (k * k) as f64,
                _ => 1.0 / 16.0,
            };
            assert_eq!(s.size_ratio(32), want, "{spec}");
        }
    }

    #[test]
    fn table_answers_as_the_selector_inside_its_square_and_none_outside() {
        let mut subsets: Vec<Box<dyn PrioritySubset>> =
            SubsetSpec::all().iter().map(|s| s.build(32)).collect();
        subsets.push(SubsetSpec::Random(9).build(16));
        subsets.push(Box::new(Explicit::new([
            (0, 0),
            (31, 31),
            (3, 17),
            (40, 2),
        ])));
        for s in &subsets {
            let t = SubsetTable::of(s.as_ref());
            for y in 0..TABLE_SIDE + 8 {
                for x in 0..TABLE_SIDE + 8 {
                    let want = (x < TABLE_SIDE && y < TABLE_SIDE).then(|| s.is_priority(x, y));
                    assert_eq!(t.get(x, y), want, "{} ({x},{y})", s.name());
                }
            }
            for far in [64, 1 << 16, u32::MAX] {
                assert_eq!(t.get(far, 0), None);
                assert_eq!(t.get(0, far), None);
            }
        }
        let e = SubsetTable::empty();
        assert!((0..32).all(|i| e.get(i, 31 - i) == Some(false)));
    }

    #[test]
    fn parse_round_trip_and_errors() {
        for spec in SubsetSpec::all() {
            assert_eq!(spec.to_string().parse::<SubsetSpec>().unwrap(), spec);
        }
        assert_eq!("MESH4".parse::<SubsetSpec>().unwrap(), SubsetSpec::Mesh(4));
        assert!("mesh3".parse::<SubsetSpec>().unwrap_err().contains("mesh4"));
        assert!("random:x".parse::<SubsetSpec>().is_err());
        assert!("mesh4:2".parse::<SubsetSpec>().is_err());
    }
}
