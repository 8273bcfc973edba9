//! The arithmetic and the text of the figures' numbers: speedups and
//! changes between two points, percent text, and the Mesh size ratios.

use crate::study::cache::PointRecord;
use wasp_sim::stats::RunStats;

/// `base cycles / x cycles - 1`.
pub fn speedup(base: &PointRecord, x: &PointRecord) -> f64 {
    base.cycles() / x.cycles() - 1.0
}

/// `x / base - 1` of the statistic `stat`.
pub fn change(base: &PointRecord, x: &PointRecord, stat: fn(&RunStats) -> f64) -> Option<f64> {
    let (b, v) = (stat(&base.stats), stat(&x.stats));
    (b != 0.0).then(|| v / b - 1.0)
}

pub(super) fn fmt_claim(v: f64) -> String {
    crate::reproduce::prose::pct(Some(v))
}

/// Subset size ratio of MeshN: one quad in N x N.
pub fn size_ratio(n: u32) -> String {
    format!("1/{}", n * n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::cache::tests::stats_of;
    use crate::study::point::Point;

    #[test]
    fn speedups_and_changes() {
        let r = |c: u64, l: f64| PointRecord {
            key: String::new(),
            point: Point::new("s", "paper", &[]),
            binary: String::new(),
            stats: {
                let mut s = stats_of(c);
                s.memory_latency.all = l;
                s
            },
        };
        let (b, x) = (r(110, 100.0), r(100, 91.0));
        let all = |s: &RunStats| s.memory_latency.all;
        assert!((speedup(&b, &x) - 0.1).abs() < 1e-12);
        assert!((change(&b, &x, all).unwrap() + 0.09).abs() < 1e-12);
        assert_eq!(change(&r(1, 0.0), &x, all), None);
    }
}
