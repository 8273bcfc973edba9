//! Point records as tables: CSV with the point's description and every
//! statistic flattened (`wasp run --csv`'s field names).

use super::cache::PointRecord;
use std::collections::HashMap;
use wasp_sim::stats::csv_text;

/// Every point as CSV: scene, base configuration, overrides, then the
/// flattened statistics (the columns of the first record).
pub fn points_csv(records: &[&PointRecord]) -> String {
    let Some(first) = records.first() else {
        return "scene,config,sets,key\n".into();
    };
    let names: Vec<String> = first.flat_stats().into_iter().map(|(k, _)| k).collect();
    let header = ["scene", "config", "sets", "key"]
        .into_iter()
        .map(String::from)
        .chain(names.iter().cloned());
    let rows = records.iter().map(|r| {
        let row: HashMap<String, String> = r.flat_stats().into_iter().collect();
        [
            r.point.scene.clone(),
            r.point.config.clone(),
            r.point.sets_text(),
            r.key.clone(),
        ]
        .into_iter()
        .chain(
            names
                .iter()
                .map(|n| row.get(n).cloned().unwrap_or_default()),
        )
        .collect::<Vec<String>>()
    });
    csv_text(std::iter::once(header.collect::<Vec<String>>()).chain(rows))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::cache::tests::stats_of;
    use crate::study::point::Point;
    use wasp_sim::config::Override;

    #[test]
    fn points_become_rows_with_their_overrides_and_statistics() {
        let sets = Override::parse_sets(&["l0.mshrs=8", "scheduler.policy=\"wasp\""]).unwrap();
        let r = |scene: &str, c: u64| PointRecord {
            key: format!("k{c}"),
            point: Point::new(scene, "paper", &sets),
            binary: String::new(),
            stats: wasp_sim::stats::RunStats {
                workload: "a,b".into(),
                ..stats_of(c)
            },
        };
        let (a, b) = (r("s1", 10), r("s2", 20));
        let t = points_csv(&[&a, &b]);
        let lines: Vec<&str> = t.lines().collect();
        assert!(
            lines[0].starts_with("scene,config,sets,key,avg_warps_per_core,block_reuse,"),
            "{}",
            lines[0]
        );
        assert!(lines[0].ends_with(",tiles,warps,workload"), "{}", lines[0]);
        assert!(lines[0].contains(",cycles,") && lines[0].contains(",l0.misses,"));
        assert!(
            lines[1].starts_with("s1,paper,\"l0.mshrs=8 scheduler.policy=\"\"wasp\"\"\",k10,"),
            "{}",
            lines[1]
        );
        assert!(lines[1].ends_with(",\"a,b\""), "{}", lines[1]);
        assert!(lines[2].starts_with("s2,paper,"), "{}", lines[2]);
        assert_eq!(points_csv(&[]), "scene,config,sets,key\n");
    }
}
