//! Best points at the edge of a sweep: for every swept figure (a line
//! over thresholds or warp counts) and (through [`best_at_edge`], in
//! `map::edges`) every numeric knob of the map, the report says when the
//! best value lies at the first or last value swept, since the best may
//! then lie beyond the range.

use super::figures::{Figure, Kind};

/// Where the best (largest) of `values` lies among `labels`, if at an
/// edge: (its label, its value, the range as text). `None` when the best
/// is inside, fewer than three values ran or every value is the same.
pub fn best_at_edge(labels: &[String], values: &[Option<f64>]) -> Option<(String, f64, String)> {
    let known: Vec<(usize, f64)> = values
        .iter()
        .enumerate()
        .filter_map(|(i, v)| v.map(|v| (i, v)))
        .collect();
    if known.len() < 3 {
        return None;
    }
    let (best, v) = known.iter().copied().max_by(|a, b| a.1.total_cmp(&b.1))?;
    if known.iter().all(|&(_, x)| x == v) {
        return None;
    }
    let (first, last) = (known[0].0, known[known.len() - 1].0);
    (best == first || best == last).then(|| {
        (
            labels[best].clone(),
            v,
            format!("{}..{}", labels[first], labels[last]),
        )
    })
}

/// The sentences flagging a swept figure's series whose best point is at
/// an edge of its range; empty for bar charts.
pub fn figure_note(f: &Figure) -> String {
    let Kind::Lines { x_label, .. } = &f.kind else {
        return String::new();
    };
    let what = x_label.split(" (").next().unwrap_or(x_label);
    let mut notes = Vec::new();
    for s in &f.series {
        if let Some((at, v, range)) = best_at_edge(&f.categories, &s.values) {
            notes.push(format!(
                "{}: best at {what} {at} ({}), the edge of the range swept ({range})",
                s.name,
                super::prose::pct(Some(v))
            ));
        }
    }
    if notes.is_empty() {
        return String::new();
    }
    format!(
        "**At the edge of the range**: {}; the best may lie beyond it.\n",
        notes.join("; ")
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn l(v: &[&str]) -> Vec<String> {
        v.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn edges_are_flagged_and_inner_bests_are_not() {
        let x = l(&["0", "2", "4", "8"]);
        let at0 = best_at_edge(&x, &[Some(0.01), Some(0.0), Some(-0.01), None]).unwrap();
        assert_eq!(at0, ("0".into(), 0.01, "0..4".into()));
        assert!(best_at_edge(&x, &[Some(0.0), Some(0.02), Some(0.01), Some(0.0)]).is_none());
        let top = best_at_edge(&x, &[Some(0.0), Some(0.01), Some(0.01), Some(0.03)]).unwrap();
        assert_eq!(top.0, "8");
        // Too few points or a flat line say nothing.
        assert!(best_at_edge(&x, &[Some(0.1), Some(0.0), None, None]).is_none());
        assert!(best_at_edge(&x, &[Some(0.0); 4]).is_none());
    }
}
