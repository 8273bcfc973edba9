//! The map's knobs whose best WaSP value lies at the edge of the values
//! swept ([`crate::reproduce::edges::best_at_edge`]), for the map's
//! section of REPORT.md.

use super::table::MapTable;
use crate::reproduce::edges::best_at_edge;
use crate::reproduce::plan::Group;
use crate::reproduce::prose::pct;

/// The map's numeric knobs whose best WaSP value (group mean) lies at an
/// edge of the values swept, per group; empty when none does.
pub fn map_note(t: &MapTable, groups: &[Group]) -> String {
    let mut notes = Vec::new();
    for &g in groups {
        let at: Vec<String> = t
            .knobs
            .iter()
            // A range has edges only when its values are numbers.
            .filter(|k| k.rows.iter().all(|r| r.value.parse::<f64>().is_ok()))
            .filter_map(|k| {
                let labels: Vec<String> = k.rows.iter().map(|r| r.value.clone()).collect();
                let values: Vec<Option<f64>> = k.rows.iter().map(|r| r.of(g).wasp).collect();
                let (best, v, range) = best_at_edge(&labels, &values)?;
                Some(format!(
                    "{} {best} ({}; swept {range})",
                    k.label,
                    pct(Some(v))
                ))
            })
            .collect();
        if !at.is_empty() {
            notes.push(format!("{} scenes: {}", g.label(), at.join(", ")));
        }
    }
    if notes.is_empty() {
        return String::new();
    }
    format!(
        "**At the edge of the range**: WaSP's best value of these knobs is the first or last \
         value swept, so its best may lie beyond the range: {}.\n\n",
        notes.join("; ")
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reproduce::map::data::Metrics;
    use crate::reproduce::map::table::{KnobResult, Row};

    fn row(value: &str, wasp: f64) -> Row {
        let m = Metrics {
            wasp: Some(wasp),
            ..Metrics::default()
        };
        Row {
            knob: "warps".into(),
            value: value.into(),
            label: format!("{value} warps"),
            shipped: value == "64",
            repeats: false,
            groups: [m, m, m],
        }
    }

    #[test]
    fn numeric_knobs_at_an_edge_are_named() {
        let rows = vec![row("32", 0.03), row("64", 0.01), row("128", 0.0)];
        let mut t = MapTable {
            shipped: rows[1].clone(),
            knobs: vec![KnobResult {
                index: 0,
                id: "warps".into(),
                label: "warps per core".into(),
                rows,
                wasp_range: [None, None, None],
            }],
            grid: None,
            deep_queue: Vec::new(),
        };
        let note = map_note(&t, &[Group::ThreeD]);
        assert!(
            note.contains("3D scenes: warps per core 32 (+3.0%; swept 32..128)"),
            "{note}"
        );
        // A best value inside the range says nothing.
        t.knobs[0].rows[1].groups[0].wasp = Some(0.05);
        assert_eq!(map_note(&t, &[Group::ThreeD]), "");
    }
}
