//! The values of `wasp render --overlay heat:STAT`: a cycle-model run's
//! warp records turned into one value per warp for the front end's heat
//! map (which knows nothing of the machine and averages the warps of each
//! quad position).

use wasp_frontend::render::{HeatStat, WarpValue};
use wasp_sim::run::WarpRecord;

/// Each warp's value of `stat`, in record order; warps without one (no
/// texture instruction, for the latency) are left out.
///
/// - `Latency`: the mean memory latency of the warp's texture instructions;
/// - `Cycles`: cycles from launch to finish;
/// - `Launch`: the launch cycle after the first launch of its tile.
pub fn warp_values(records: &[WarpRecord], stat: HeatStat) -> Vec<WarpValue> {
    let tiles = records
        .iter()
        .map(|r| r.tile as usize + 1)
        .max()
        .unwrap_or(0);
    let mut first_launch = vec![u64::MAX; tiles];
    for r in records {
        let f = &mut first_launch[r.tile as usize];
        *f = (*f).min(r.launched);
    }
    records
        .iter()
        .filter_map(|r| {
            let v = match stat {
                HeatStat::Latency => r.mem_latency?,
                HeatStat::Cycles => r.finished.saturating_sub(r.launched) as f64,
                HeatStat::Launch => r.launched.saturating_sub(first_launch[r.tile as usize]) as f64,
            };
            v.is_finite().then_some(WarpValue {
                tile: r.tile,
                quad: r.quad,
                value: v,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use wasp_frontend::raster::Frame;
    use wasp_frontend::render::heat_values;
    use wasp_sim::config::MachineConfig;
    use wasp_sim::run::{simulate_recording, RunOptions};
    use wasp_sim::trace::Trace;

    fn overdraw_frame() -> Frame {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/traces/overdraw.trace");
        Frame {
            trace: Trace::read(path).unwrap(),
            width: 16,
            height: 8,
            image: vec![0; 16 * 8 * 4],
            stats: Default::default(),
            timings: Default::default(),
        }
    }

    fn rec(tile: u32, quad: u32, lat: Option<f64>, launched: u64) -> WarpRecord {
        WarpRecord {
            tile,
            quad,
            core: 0,
            priority: false,
            mem_latency: lat,
            launched,
            finished: launched + 100,
        }
    }

    #[test]
    fn each_statistic_takes_its_field_and_launches_count_from_the_tile() {
        let recs = [
            rec(0, 6, Some(30.0), 9),
            rec(0, 0, Some(7.0), 1),
            rec(1, 1, Some(10.0), 50),
            rec(0, 2, None, 2),
        ];
        let lat: Vec<f64> = warp_values(&recs, HeatStat::Latency)
            .iter()
            .map(|w| w.value)
            .collect();
        assert_eq!(lat, [30.0, 7.0, 10.0], "a warp without latency is left out");
        let launch: Vec<(u32, f64)> = warp_values(&recs, HeatStat::Launch)
            .iter()
            .map(|w| (w.quad, w.value))
            .collect();
        assert_eq!(launch, [(6, 8.0), (0, 0.0), (1, 0.0), (2, 1.0)]);
        assert!(warp_values(&recs, HeatStat::Cycles)
            .iter()
            .all(|w| w.value == 100.0));
        assert!(warp_values(&[], HeatStat::Launch).is_empty());
    }

    #[test]
    fn a_positions_heat_is_the_mean_of_its_warps() {
        let frame = overdraw_frame();
        // Quads 5 and 6 share position (1, 1); 2 and 4 share (0, 1).
        let recs = [
            rec(0, 6, Some(30.0), 9),
            rec(0, 0, Some(7.0), 1),
            rec(0, 5, Some(10.0), 5),
            rec(0, 2, None, 2),
            rec(0, 4, Some(4.0), 3),
        ];
        let v = heat_values(&frame, &warp_values(&recs, HeatStat::Latency));
        assert_eq!(v, vec![(0, 0, 7.0), (0, 2, 4.0), (2, 2, 20.0)]);
        let l = heat_values(&frame, &warp_values(&recs, HeatStat::Launch));
        assert_eq!(l, vec![(0, 0, 0.0), (0, 2, 1.5), (2, 2, 6.0)]);
    }

    #[test]
    fn a_recorded_run_gives_a_value_to_every_textured_warp() {
        let frame = overdraw_frame();
        let mut cfg = MachineConfig::paper();
        cfg.gpu.tile_size = frame.trace.header().tile;
        let run = RunOptions {
            record_warps: true,
            ..RunOptions::default()
        };
        let (stats, recs) = simulate_recording(&cfg, &frame.trace, &run, &mut |_, _| {}).unwrap();
        assert_eq!(recs.len() as u64, stats.warps);
        let cycles = warp_values(&recs, HeatStat::Cycles);
        assert_eq!(cycles.len(), recs.len(), "every warp has a duration");
        assert!(cycles.iter().all(|w| w.value > 0.0));
        let map = heat_values(&frame, &cycles);
        assert!(!map.is_empty());
    }
}
