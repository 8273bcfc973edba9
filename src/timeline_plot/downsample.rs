//! The timeline's samples cut into pixel columns: when a column covers
//! several cycles, each series keeps its minimum, maximum and mean there
//! (the picture draws the mean as the line and min..max as a band), and the
//! priority launches their mean per cycle.

use wasp_sim::timeline::{Timeline, TimelineSample};

/// Minimum, maximum and mean of one series over one pixel column.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Agg {
    pub(super) min: f64,
    pub(super) max: f64,
    pub(super) mean: f64,
}

impl Agg {
    /// The aggregate of `value` over the samples `run`.
    fn of(run: &[TimelineSample], value: impl Fn(&TimelineSample) -> u32) -> Agg {
        let v: Vec<f64> = run.iter().map(|s| f64::from(value(s))).collect();
        let bounds = |(lo, hi): (f64, f64), &x: &f64| (x.min(lo), x.max(hi));
        let (min, max) = v.iter().fold((f64::INFINITY, 0.0), bounds);
        let mean = v.iter().sum::<f64>() / v.len().max(1) as f64;
        let min = if v.is_empty() { 0.0 } else { min };
        Agg { min, max, mean }
    }
}

/// The samples of one pixel column: cycles `x0..x1`.
#[derive(Clone, Debug)]
pub(super) struct Column {
    pub(super) x0: f64,
    pub(super) x1: f64,
    pub(super) resident: Vec<Agg>,
    pub(super) outstanding: [Agg; 3],
    /// Mean priority launches per cycle, per core.
    pub(super) launches: Vec<f64>,
}

/// Split the samples into at most `columns` runs of consecutive samples of
/// (nearly) equal length and aggregate each.
pub(super) fn downsample(t: &Timeline, columns: usize) -> Vec<Column> {
    let n = t.samples.len();
    let columns = columns.clamp(1, n.max(1));
    let runs = (0..columns).map(|i| &t.samples[i * n / columns..(i + 1) * n / columns]);
    runs.filter(|r| !r.is_empty())
        .map(|run| column(t.cores, run))
        .collect()
}

/// The column of the samples `run` (not empty) of `cores` cores.
fn column(cores: usize, run: &[TimelineSample]) -> Column {
    let launches = |c: usize| Agg::of(run, |s| s.priority_launches[c]).mean;
    Column {
        x0: run[0].cycle as f64,
        x1: (run[run.len() - 1].cycle + 1) as f64,
        resident: (0..cores)
            .map(|c| Agg::of(run, |s| s.resident[c]))
            .collect(),
        outstanding: [0, 1, 2].map(|l| Agg::of(run, |s| s.outstanding[l])),
        launches: (0..cores).map(launches).collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn downsample_keeps_min_max_and_mean() {
        let mut t = Timeline::new(0, 9, 1, 8, false, "shared-tile");
        for cycle in 0..10u64 {
            t.samples.push(TimelineSample {
                cycle,
                resident: vec![cycle as u32],
                outstanding: [0, cycle as u32 * 2, 1],
                priority_launches: vec![u32::from(cycle % 2 == 0)],
            });
        }
        let cols = downsample(&t, 2);
        assert_eq!(cols.len(), 2);
        assert_eq!((cols[0].x0, cols[0].x1), (0.0, 5.0));
        assert_eq!((cols[1].x0, cols[1].x1), (5.0, 10.0));
        let r = cols[0].resident[0];
        assert_eq!((r.min, r.max, r.mean), (0.0, 4.0, 2.0));
        assert_eq!(cols[1].outstanding[1].max, 18.0);
        assert_eq!(cols[0].launches[0], 0.6);
        // More columns than samples: one per sample.
        assert_eq!(downsample(&t, 1000).len(), 10);
    }
}
