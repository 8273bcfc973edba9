//! Lines: every 16th row (horizontal) or column (vertical) of quads.
//!
//! A line subset is clustered along one axis and spread along the other.
//! For a 32 x 32 quad tile, rows 0 and 16 (or columns 0 and 16) are 1/16 of
//! the tile.

use super::PrioritySubset;

/// Every 16th row: rows with `qy % 16 == 0`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct HorizontalLines {
    period: u32,
}

/// Every 16th column: columns with `qx % 16 == 0`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct VerticalLines {
    period: u32,
}

impl HorizontalLines {
    /// Lines for tiles of `side` quads; the period is 16 (1/16 of the rows).
    pub fn new(side: u32) -> Self {
        let _ = side;
        Self { period: 16 }
    }
}

impl VerticalLines {
    /// Lines for tiles of `side` quads; the period is 16.
    pub fn new(side: u32) -> Self {
        let _ = side;
        Self { period: 16 }
    }
}

impl PrioritySubset for HorizontalLines {
    fn name(&self) -> String {
        "hlines".into()
    }
    fn is_priority(&self, _qx: u32, qy: u32) -> bool {
        qy.is_multiple_of(self.period)
    }
}

impl PrioritySubset for VerticalLines {
    fn name(&self) -> String {
        "vlines".into()
    }
    fn is_priority(&self, qx: u32, _qy: u32) -> bool {
        qx.is_multiple_of(self.period)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_and_columns() {
        let h = HorizontalLines::new(32);
        let v = VerticalLines::new(32);
        assert!(h.is_priority(7, 0) && h.is_priority(31, 16) && !h.is_priority(0, 1));
        assert!(v.is_priority(0, 7) && v.is_priority(16, 31) && !v.is_priority(1, 0));
    }
}
