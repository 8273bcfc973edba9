//! Top 16th: the first rows of the tile, clustered together.

use super::PrioritySubset;

/// The top `1/fraction` of the tile's rows of quads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Top {
    rows: u32,
}

impl Top {
    /// The top `side / fraction` rows (at least one).
    pub fn new(side: u32, fraction: u32) -> Self {
        Self {
            rows: (side / fraction.max(1)).max(1),
        }
    }
}

impl PrioritySubset for Top {
    fn name(&self) -> String {
        "top16".into()
    }
    fn is_priority(&self, _qx: u32, qy: u32) -> bool {
        qy < self.rows
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_rows_of_a_32_quad_tile() {
        let t = Top::new(32, 16);
        assert!(t.is_priority(31, 1));
        assert!(!t.is_priority(0, 2));
    }
}
