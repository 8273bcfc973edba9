//! Point records as tables: CSV with the point's description and every
//! statistic flattened (`wasp run --csv`'s field names).

use super::cache::PointRecord;
use std::collections::HashMap;
use wasp_sim::stats::csv_text;

/// A CSV field, quoted only where it must be (for a line put together by
/// hand; whole tables go through [`csv_text`]).
pub use wasp_sim::stats::csv_field as csv;

/// Every point as CSV: scene, base configuration, overrides, then the
/// flattened statistics (the columns of the first record).
pub fn points_csv(records: &[&PointRecord]) -> String {
    let Some(first) = records.iter().find(|r| !r.stats.is_null()) else {
        return "scene,config,sets,key\n".into();
    };
    let mut cols = Vec::new();
    wasp_sim::stats::flatten("", &first.stats, &mut cols);
    let names: Vec<String> = cols.into_iter().map(|(k, _)| k).collect();
    let header = ["scene", "config", "sets", "key"]
        .into_iter()
        .map(String::from)
        .chain(names.iter().cloned());
    let rows = records.iter().map(|r| {
        let mut row = Vec::new();
        wasp_sim::stats::flatten("", &r.stats, &mut row);
        let row: HashMap<String, String> = row.into_iter().collect();
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
    use crate::study::point::Point;
    use wasp_sim::config::Override;

    #[test]
    fn points_become_rows_with_their_overrides_and_statistics() {
        let sets = Override::parse_sets(&["l0.mshrs=8", "scheduler.policy=\"wasp\""]).unwrap();
        let r = |scene: &str, c: u64| PointRecord {
            key: format!("k{c}"),
            point: Point::new(scene, "paper", &sets),
            binary: String::new(),
            stats: serde_json::json!({"cycles": c, "l0": {"misses": 3}, "policy": "a,b"}),
        };
        let (a, b) = (r("s1", 10), r("s2", 20));
        let t = points_csv(&[&a, &b]);
        let lines: Vec<&str> = t.lines().collect();
        assert_eq!(lines[0], "scene,config,sets,key,cycles,l0.misses,policy");
        assert_eq!(
            lines[1],
            "s1,paper,\"l0.mshrs=8 scheduler.policy=\"\"wasp\"\"\",k10,10,3,\"a,b\""
        );
        assert!(lines[2].starts_with("s2,paper,"), "{}", lines[2]);
        assert_eq!(points_csv(&[]), "scene,config,sets,key\n");
        assert_eq!(csv("x"), "x");
    }
}
