//! Point records as tables: CSV with the point's description and every
//! statistic flattened (`wasp run --csv`'s field names).

use super::cache::PointRecord;
use std::collections::HashMap;
use std::fmt::Write as _;

/// A CSV field, quoted when it holds a comma, quote or newline.
pub fn csv(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// Every point as CSV: scene, base configuration, overrides, then the
/// flattened statistics (the columns of the first record).
pub fn points_csv(records: &[&PointRecord]) -> String {
    let mut s = String::new();
    let Some(first) = records.iter().find(|r| !r.stats.is_null()) else {
        return "scene,config,sets,key\n".into();
    };
    let mut cols = Vec::new();
    wasp_sim::stats::flatten("", &first.stats, &mut cols);
    let names: Vec<String> = cols.into_iter().map(|(k, _)| k).collect();
    let _ = write!(s, "scene,config,sets,key");
    for n in &names {
        let _ = write!(s, ",{}", csv(n));
    }
    s.push('\n');
    for r in records {
        let _ = write!(
            s,
            "{},{},{},{}",
            csv(&r.point.scene),
            csv(&r.point.config),
            csv(&r.point.sets.join(" ")),
            r.key
        );
        let mut row = Vec::new();
        wasp_sim::stats::flatten("", &r.stats, &mut row);
        let row: HashMap<String, String> = row.into_iter().collect();
        for n in &names {
            let _ = write!(s, ",{}", row.get(n).map_or("", |v| v.as_str()));
        }
        s.push('\n');
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::point::Point;

    #[test]
    fn points_become_rows_with_their_overrides_and_statistics() {
        let r = |scene: &str, c: u64| PointRecord {
            key: format!("k{c}"),
            point: Point::new(scene, "paper", &["l0.mshrs=8", "scheduler.policy=\"wasp\""]),
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
