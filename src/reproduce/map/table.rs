//! The map's results gathered from a run: every knob value's numbers per
//! group, each knob's range of WaSP's speedup, the 2-D grid and the
//! deep-input-queue warp series. The report, the figures and the data
//! files all read this one table.

use super::data::{self, MapScenes, Metrics, GROUPS};
use super::knobs::Variant;
use super::plan::{Cell, MapPlan};
use crate::reproduce::plan::Group;
use crate::study::runner::Outcome;
use serde::Serialize;

/// One machine of the map and its numbers per group ([`GROUPS`] order).
#[derive(Clone, Debug, Serialize)]
pub struct Row {
    /// The knob's id (`warps`), or the grid's `a x b`, or `deep-queue`.
    pub knob: String,
    /// The value ("32"), or the grid cell's "32, 31".
    pub value: String,
    /// A label for prose ("32 warps").
    pub label: String,
    /// Whether this is the shipped machine.
    pub shipped: bool,
    /// A grid cell at one knob's shipped value: the same machine as a row
    /// of the other knob (kept in the grid, counted once in
    /// [`MapTable::machines`]).
    pub repeats: bool,
    /// Per group, in [`GROUPS`] order.
    pub groups: [Metrics; 3],
}

impl Row {
    /// The numbers of group `g`.
    pub fn of(&self, g: Group) -> &Metrics {
        &self.groups[GROUPS.iter().position(|&x| x == g).unwrap_or(0)]
    }
}

/// The lowest and highest of one variant's group-mean speedup over a
/// knob's values, and the values that gave them.
#[derive(Clone, Debug, Serialize)]
pub struct Range {
    /// The value at the low end and the speedup there.
    pub low: (String, f64),
    /// The value at the high end and the speedup there.
    pub high: (String, f64),
}

impl Range {
    /// `high - low`.
    pub fn width(&self) -> f64 {
        self.high.1 - self.low.1
    }
}

/// One knob's rows and WaSP's range per group.
#[derive(Clone, Debug, Serialize)]
pub struct KnobResult {
    /// Index in the plan's knobs.
    pub index: usize,
    /// The knob's id.
    pub id: String,
    /// What it is.
    pub label: String,
    /// One row per value, in value order.
    pub rows: Vec<Row>,
    /// WaSP's range per group ([`GROUPS`] order; None without data).
    pub wasp_range: [Option<Range>; 3],
}

/// Everything the map measured.
#[derive(Clone, Debug, Serialize)]
pub struct MapTable {
    /// The shipped machine's row.
    pub shipped: Row,
    /// The knobs, one at a time.
    pub knobs: Vec<KnobResult>,
    /// The grid: the two knobs' indices and one row per cell.
    pub grid: Option<(usize, usize, Vec<Row>)>,
    /// The deep-input-queue warp series: one row per warp count.
    pub deep_queue: Vec<Row>,
}

/// The range of `v`'s speedup over `rows` in group `g`.
pub fn range(rows: &[Row], g: Group, v: Variant) -> Option<Range> {
    let vals: Vec<(String, f64)> = rows
        .iter()
        .filter_map(|r| Some((r.label.clone(), r.of(g).speedup(v)?)))
        .collect();
    let low = vals.iter().min_by(|a, b| a.1.total_cmp(&b.1))?.clone();
    let high = vals.iter().max_by(|a, b| a.1.total_cmp(&b.1))?.clone();
    Some(Range { low, high })
}

/// How much a knob moves WaSP: the width of its range on 3D scenes plus
/// that on 2D scenes (the games; procedural scenes are reported apart).
pub fn movement(k: &KnobResult) -> f64 {
    [Group::ThreeD, Group::TwoD]
        .iter()
        .filter_map(|&g| k.wasp_range[GROUPS.iter().position(|&x| x == g)?].as_ref())
        .map(Range::width)
        .sum()
}

/// The two knobs that move WaSP most (by [`movement`], ties in plan order),
/// if there are two with more than one value.
pub fn top_two(knobs: &[KnobResult]) -> Option<(usize, usize)> {
    let mut ranked: Vec<&KnobResult> = knobs.iter().filter(|k| k.rows.len() > 1).collect();
    ranked.sort_by(|a, b| {
        movement(b)
            .total_cmp(&movement(a))
            .then(a.index.cmp(&b.index))
    });
    match ranked.as_slice() {
        [a, b, ..] => Some((a.index.min(b.index), a.index.max(b.index))),
        _ => None,
    }
}

fn row(
    out: &Outcome,
    scenes: &MapScenes,
    plan: &MapPlan,
    (knob, value, label, shipped): (String, String, String, bool),
    point: &dyn Fn(&str, Variant) -> crate::study::point::Point,
) -> Row {
    let ship = |s: &str| plan.shipped_point(s, Variant::Baseline);
    Row {
        knob,
        value,
        label,
        shipped,
        repeats: false,
        groups: GROUPS.map(|g| data::metrics(out, scenes, g, point, &ship)),
    }
}

impl MapTable {
    /// The one-at-a-time results and the warp series of `plan` in `out`.
    pub fn new(plan: &MapPlan, out: &Outcome, scenes: &MapScenes) -> MapTable {
        let shipped = row(
            out,
            scenes,
            plan,
            (
                "shipped".into(),
                "-".into(),
                "the shipped machine".into(),
                true,
            ),
            &|s, v| plan.shipped_point(s, v),
        );
        let knobs = plan
            .knobs
            .iter()
            .enumerate()
            .map(|(index, k)| {
                let rows: Vec<Row> = k
                    .values_for(plan.quick)
                    .iter()
                    .map(|&value| {
                        let id = (
                            k.id.to_string(),
                            value.to_string(),
                            (k.unit)(value),
                            value == k.shipped,
                        );
                        row(out, scenes, plan, id, &|s, v| {
                            plan.knob_point(s, k, value, v)
                        })
                    })
                    .collect();
                let wasp_range = GROUPS.map(|g| range(&rows, g, Variant::Wasp));
                KnobResult {
                    index,
                    id: k.id.to_string(),
                    label: k.label.to_string(),
                    rows,
                    wasp_range,
                }
            })
            .collect();
        let deep_queue = plan
            .deep_queue_warps
            .iter()
            .map(|&w| {
                let id = (
                    "deep-queue".to_string(),
                    w.to_string(),
                    format!("{w} warps, {}-entry queue", super::plan::DEEP_QUEUE),
                    false,
                );
                row(out, scenes, plan, id, &|s, v| {
                    plan.deep_queue_point(s, w, v)
                })
            })
            .collect();
        MapTable {
            shipped,
            knobs,
            grid: None,
            deep_queue,
        }
    }

    /// Add the grid's rows.
    pub fn with_grid(
        mut self,
        plan: &MapPlan,
        out: &Outcome,
        scenes: &MapScenes,
        cells: &[Cell],
    ) -> MapTable {
        let Some(first) = cells.first() else {
            return self;
        };
        let (a, b) = (first.a.0, first.b.0);
        let (ka, kb) = (&plan.knobs[a], &plan.knobs[b]);
        let rows = cells
            .iter()
            .map(|c| {
                let id = (
                    format!("{} x {}", ka.id, kb.id),
                    format!("{}, {}", c.a.1, c.b.1),
                    format!("{} and {}", (ka.unit)(c.a.1), (kb.unit)(c.b.1)),
                    c.a.1 == ka.shipped && c.b.1 == kb.shipped,
                );
                let mut r = row(out, scenes, plan, id, &|s, v| plan.cell_point(s, c, v));
                r.repeats = c.a.1 == ka.shipped || c.b.1 == kb.shipped;
                r
            })
            .collect();
        self.grid = Some((a, b, rows));
        self
    }

    /// Every machine of the map: the knob rows (the shipped one once) and
    /// the grid's cells.
    pub fn machines(&self) -> Vec<&Row> {
        let mut v: Vec<&Row> = vec![&self.shipped];
        for k in &self.knobs {
            v.extend(k.rows.iter().filter(|r| !r.shipped));
        }
        if let Some((_, _, cells)) = &self.grid {
            v.extend(cells.iter().filter(|r| !r.repeats));
        }
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn r(label: &str, wasp: f64) -> Row {
        let m = Metrics {
            wasp: Some(wasp),
            ..Metrics::default()
        };
        Row {
            knob: "k".into(),
            value: label.into(),
            label: label.into(),
            shipped: false,
            repeats: false,
            groups: [m, m, Metrics::default()],
        }
    }

    #[test]
    fn ranges_and_the_two_knobs_that_move_wasp_most() {
        let rows = vec![r("a", 0.01), r("b", -0.02), r("c", 0.03)];
        let rg = range(&rows, Group::ThreeD, Variant::Wasp).unwrap();
        assert_eq!(rg.low.0, "b");
        assert_eq!(rg.high.0, "c");
        assert!((rg.width() - 0.05).abs() < 1e-12);
        assert!(range(&rows, Group::Procedural, Variant::Wasp).is_none());
        let knob = |index: usize, rows: Vec<Row>| KnobResult {
            index,
            id: format!("k{index}"),
            label: String::new(),
            wasp_range: GROUPS.map(|g| range(&rows, g, Variant::Wasp)),
            rows,
        };
        let knobs = vec![
            knob(0, vec![r("x", 0.0), r("y", 0.01)]),
            knob(1, vec![r("x", 0.0), r("y", 0.05)]),
            knob(2, vec![r("x", 0.0)]),
            knob(3, vec![r("x", -0.03), r("y", 0.0)]),
        ];
        assert!((movement(&knobs[1]) - 0.1).abs() < 1e-12);
        assert_eq!(top_two(&knobs), Some((1, 3)));
        assert_eq!(top_two(&knobs[..1]), None);
    }
}
