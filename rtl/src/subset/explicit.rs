//! Explicit: a listed set of quads (used by the paper's worked example,
//! where W0, W5 and W10 are designated priority warps).

use super::PrioritySubset;

/// A fixed list of priority quads.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Explicit {
    quads: Vec<(u32, u32)>,
}

impl Explicit {
    /// The quads at these in-tile coordinates are priority warps.
    pub fn new(quads: impl IntoIterator<Item = (u32, u32)>) -> Self {
        let mut quads: Vec<_> = quads.into_iter().collect();
        quads.sort_unstable();
        quads.dedup();
        Self { quads }
    }
}

impl PrioritySubset for Explicit {
    fn name(&self) -> String {
        "explicit".into()
    }
    fn is_priority(&self, qx: u32, qy: u32) -> bool {
        self.quads.binary_search(&(qx, qy)).is_ok()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn membership() {
        let e = Explicit::new([(10, 0), (0, 0), (5, 0), (5, 0)]);
        assert!(e.is_priority(5, 0));
        assert!(!e.is_priority(1, 0));
        assert_eq!(e.size_ratio(16), 3.0 / 256.0);
    }
}
