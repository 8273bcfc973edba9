//! The bullets on the workloads, which no machine changes: the priority
//! subsets' footprint ratios and the scenes' CF, each against the paper's.

use super::Notes;
use crate::reproduce::figures::Figure;
use crate::reproduce::headline::group_values;
use crate::reproduce::paper;
use std::fmt::Write as _;

/// A priority subset's footprint ratio: ours (games mean) and the paper's.
struct Subset {
    name: String,
    ours: Option<f64>,
    paper: Option<f64>,
}

/// The subsets' footprint ratios, and whether they order the subsets as
/// the paper's do.
pub(super) fn footprint_note(md: &mut String, n: &Notes) {
    let Some(footprints) = workload_figure(n, "footprint") else {
        return;
    };
    // Each subset: its name, our games mean and the paper's value.
    let ours: Vec<Subset> = footprints
        .series
        .iter()
        .enumerate()
        .map(|(i, s)| Subset {
            name: s.name.clone(),
            ours: group_values(&footprints, i)[0],
            paper: paper::footprint(&s.name),
        })
        .collect();
    let text: Vec<String> = ours
        .iter()
        .map(|o| {
            format!(
                "{} {}",
                o.name,
                o.ours.map_or("-".into(), |x| format!("{x:.2}"))
            )
        })
        .collect();
    let papers: Vec<String> = ours
        .iter()
        .filter_map(|o| Some(format!("{} {}", o.name, o.paper?)))
        .collect();
    // The orders of the subsets both sides measure, smallest ratio first.
    let both: Vec<&Subset> = ours
        .iter()
        .filter(|o| o.ours.is_some() && o.paper.is_some())
        .collect();
    let order = |key: fn(&Subset) -> Option<f64>| {
        let mut v: Vec<(&str, f64)> = both
            .iter()
            .filter_map(|o| Some((o.name.as_str(), key(o)?)))
            .collect();
        v.sort_by(|a, b| a.1.total_cmp(&b.1));
        v.into_iter().map(|(name, _)| name).collect::<Vec<_>>()
    };
    let (mine, theirs) = (order(|o| o.ours), order(|o| o.paper));
    let reading = if mine.is_empty() {
        "no measurement".to_string()
    } else if mine == theirs {
        format!(
            "they order the subsets as the paper's do ({})",
            mine.join(" < ")
        )
    } else {
        format!(
            "they order the subsets {}, unlike the paper's {}",
            mine.join(" < "),
            theirs.join(" < ")
        )
    };
    let _ = writeln!(
        md,
        "- **Footprint ratios** (games: {}; paper: {}): a property of the workloads, not of the \
         machine; {reading}.",
        text.join(", "),
        papers.join(", ")
    );
}

/// The workload figure `id` (`footprint`, `cf`) of the run.
fn workload_figure(n: &Notes, id: &str) -> Option<Figure> {
    crate::reproduce::figures::scene_figures(n.plan, n.out)
        .into_iter()
        .find(|f| f.id == id)
}

/// CF: ours against the paper's 2.5, and 3D against 2D scenes.
pub(super) fn cf_note(md: &mut String, n: &Notes) {
    let Some(cf) = workload_figure(n, "cf") else {
        return;
    };
    let cf = group_values(&cf, 0);
    let f2 = |v: Option<f64>| v.map_or("-".into(), |x| format!("{x:.2}"));
    let groups = match (cf[1], cf[2]) {
        (Some(a), Some(b)) if a > b => format!(
            "3D scenes ({}) above 2D ones ({}): they sample several mip levels and textures \
             per fragment, 2D sprites fewer",
            f2(Some(a)),
            f2(Some(b))
        ),
        (Some(a), Some(b)) => format!(
            "3D scenes ({}) not above 2D ones ({})",
            f2(Some(a)),
            f2(Some(b))
        ),
        _ => "one scene group only".into(),
    };
    let _ = writeln!(
        md,
        "- **CF** ({} on games; paper {}): {groups}; the shipped CF was chosen once for the \
         suite (docs/calibration.md).",
        f2(cf[0]),
        paper::CF.value
    );
}
