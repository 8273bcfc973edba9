//! Charts of points over a numeric x ([`draw_xy`]), e.g. cycles against
//! register-file bits across warp counts: each series a line through its
//! points, each point labelled (e.g. "48"), chosen points ringed and
//! joined with a caption over them (e.g. WaSP@48 against the baseline@64).
//! [`super::lines`] draws them.

use super::lines::{Plot, Point};
use super::{ensure, finite, frame::write, who};
use std::path::Path;

/// One series of an [`XyChart`]: points joined in their order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct XySeries {
    /// What the series shows: it chooses the colour ([`crate::palette`]).
    pub key: super::Key,
    /// The name in the legend.
    pub name: String,
    /// The points (x, y).
    pub points: Vec<(f64, f64)>,
    /// A label beside each point (e.g. "48"), or none at all (empty).
    pub labels: Vec<String>,
}

/// Points of an [`XyChart`] ringed and joined, with a caption over them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Highlight {
    /// (series index, point index) of each ringed point.
    pub points: Vec<(usize, usize)>,
    /// The text over the rings.
    pub caption: String,
}

/// A chart of points over a numeric x.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct XyChart {
    /// The title.
    pub title: String,
    /// The line under the title (none when empty).
    pub subtitle: String,
    /// The x axis label.
    pub x_label: String,
    /// The y axis label.
    pub y_label: String,
    /// The series.
    pub series: Vec<XySeries>,
    /// Ringed groups of points with their captions.
    pub highlights: Vec<Highlight>,
    /// The y values are fractions, labelled as percentages.
    pub percent: bool,
    /// A solid horizontal line at this value.
    pub reference: Option<f64>,
}

/// Draws `chart` into `path`, a PNG or an SVG by the file's extension.
///
/// Errors (starting with `drawing <title>:` or naming the file): another
/// extension; no series or a series without points; a non-finite
/// coordinate; a label count other than none or the point count; a
/// highlight of a point that does not exist; a non-finite reference; a
/// file that cannot be written.
pub fn draw_xy(chart: &XyChart, path: &Path) -> Result<(), String> {
    let (who, c) = (who(&chart.title), chart);
    let nothing = "no series: nothing to draw";
    ensure(!c.series.is_empty(), || format!("{who}: {nothing}"))?;
    for s in &c.series {
        let (n, l, name) = (s.points.len(), s.labels.len(), &s.name);
        let ok = n > 0 && (l == 0 || l == n);
        ensure(ok, || {
            format!("{who}: series `{name}` has {n} points and {l} labels")
        })?;
        for (i, (x, y)) in s.points.iter().enumerate() {
            finite(&who, format_args!("series `{name}` at point {i}"), x + y)?;
        }
    }
    finite(&who, "the reference line", c.reference.unwrap_or(0.0))?;
    let missing = |&&(s, i): &&(usize, usize)| c.series.get(s).is_none_or(|s| i >= s.points.len());
    for h in &c.highlights {
        let (caption, found) = (&h.caption, h.points.iter().find(missing));
        let no =
            |(s, i)| format!("{who}: `{caption}` rings point {i} of series {s}: no such point");
        found.map_or(Ok(()), |&p| Err(no(p)))?;
    }
    let points = |s: &XySeries| -> Vec<Option<Point>> {
        let label = |i: usize| s.labels.get(i).cloned().unwrap_or_default();
        let point = |(i, &(x, y)): (usize, &(f64, f64))| Some((x, y, label(i)));
        s.points.iter().enumerate().map(point).collect()
    };
    let lines = c.series.iter().map(|s| (s.name.as_str(), s.key, points(s)));
    let plot = Plot {
        texts: [&c.title, &c.subtitle, &c.x_label, &c.y_label].map(String::as_str),
        lines: lines.collect(),
        rings: &c.highlights,
        percent: c.percent,
        reference: c.reference,
        ..Plot::default()
    };
    write(&who, path, || plot.lay_out())
}

#[cfg(test)]
mod tests {
    use super::super::tests::{out, pixels, refused, same_twice, texts, Case};
    use super::*;
    use crate::palette::Key;

    /// Cycles against register-file bits for two policies over warp
    /// counts, WaSP@48 ringed with the baseline@64.
    fn area() -> XyChart {
        let warps = [32, 48, 64, 96];
        let series = |key, name: &str, extra: f64, cycles: [f64; 4]| {
            let at = |(&w, c): (&i32, f64)| (f64::from(w) * 4096.0 + extra, c);
            let points = warps.iter().zip(cycles).map(at).collect();
            let labels = warps.iter().map(|w| w.to_string()).collect();
            XySeries {
                key,
                name: name.into(),
                points,
                labels,
            }
        };
        let caption = "paper: WaSP@48 against the baseline@64".into();
        XyChart {
            title: "Cycles against register-file bits".into(),
            subtitle: "width 4, mean over games".into(),
            x_label: "register-file bits per core".into(),
            y_label: "cycles".into(),
            series: vec![
                series(
                    Key::Baseline,
                    "baseline",
                    0.0,
                    [1.30e6, 1.12e6, 1.05e6, 1.01e6],
                ),
                series(Key::Wasp, "WaSP", 36.0, [1.22e6, 1.07e6, 1.04e6, 1.02e6]),
            ],
            highlights: vec![Highlight {
                points: vec![(1, 1), (0, 2)],
                caption,
            }],
            ..XyChart::default()
        }
    }

    #[test]
    fn points_are_labelled_and_pairs_ringed() {
        let path = out("xy", "area.svg");
        draw_xy(&area(), &path).expect("draw svg");
        let want = "Cycles against register-file bits|register-file bits per core|WaSP|48|64";
        let caption = "paper: WaSP@48 against the baseline@64";
        texts(&path, &format!("{want}|{caption}"));
        let svg = std::fs::read_to_string(&path).expect("svg");
        assert_eq!(svg.matches("r=\"11\"").count(), 2, "two rings");
        let path = out("xy", "area.png");
        draw_xy(&area(), &path).expect("draw png");
        assert!(pixels(&path, Key::Wasp.colour().unwrap()) > 100);
        same_twice("xy-same", &|p| draw_xy(&area(), p));
        let cases: &[Case<XyChart>] = &[
            (
                |c| c.series[0].labels.truncate(3),
                "has 4 points and 3 labels",
            ),
            (|c| c.series[1].points[0].0 = f64::NAN, "`WaSP` at point 0"),
            (
                |c| c.highlights[0].points.push((2, 0)),
                "of series 2: no such",
            ),
            (|c| c.series.clear(), "bits: no series: nothing to draw"),
        ];
        refused(("xy-bad", &area(), ""), draw_xy, cases);
    }
}
