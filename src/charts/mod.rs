//! Charts of the reproduction (`wasp reproduce`), drawn with plotters'
//! chart API (`ChartBuilder`, its mesh, series and coordinates)
//! and written as PNG or SVG by the file's extension:
//!
//! - grouped bars ([`draw_bars`]) and lines ([`draw_lines`]) beside the
//!   values the paper gives ([`PaperMark`]);
//! - points over a numeric x with labels and ringed pairs ([`draw_xy`]);
//! - tornado charts of a quantity's range per parameter ([`draw_tornado`]);
//! - heat maps over two parameters on a diverging scale ([`draw_heatmap`]).
//!
//! Every chart is, top to bottom: the title and subtitle; the legend,
//! plotters' series labels in columns above the plot so it hides no data;
//! the plot. Markers are plotters' marker elements (`legend`). What
//! plotters lacks is drawn by hand in `frame`: the paper's marks (a dashed line across
//! the plot, labelled right of it, for a value of every category; a short
//! dashed line with a hollow marker for one category) and the placing of
//! labels where they hide nothing. The timeline
//! ([`crate::timeline_plot`]) shares the frame and the legend. Colours come
//! from [`crate::palette`] by each series' [`Key`], so a policy has one
//! colour in every figure. Drawing is deterministic.

mod bars;
pub(crate) mod frame;
mod heatmap;
pub(crate) mod legend;
mod lines;
mod tornado;
mod xy;

pub use crate::palette::Key;
pub use bars::draw_bars;
pub use heatmap::{draw_heatmap, HeatMap};
pub use lines::draw_lines;
pub use tornado::{draw_tornado, Span, TornadoChart, TornadoRow, TornadoSeries};
pub use xy::{draw_xy, Highlight, XyChart, XySeries};

/// One series: a value per category or x position (None: no bar, or a gap
/// in the line).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Series {
    /// What the series shows: it chooses the colour ([`crate::palette`]).
    pub key: Key,
    /// The name in the legend.
    pub name: String,
    /// One value per category or x position.
    pub values: Vec<Option<f64>>,
}

/// A value the paper gives, drawn beside ours.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PaperMark {
    /// The series it belongs to (a dark shade of its colour); None: the
    /// whole chart (dark grey).
    pub series: Option<usize>,
    /// None: every category (a dashed line across the plot); Some(i):
    /// category or x position i only (a hollow marker there).
    pub category: Option<usize>,
    /// The paper's value, in the units of the y axis.
    pub value: f64,
    /// The text beside the mark, e.g. "paper 3.9%".
    pub label: String,
}

/// A run of categories named over the plot (e.g. "3D games").
#[derive(Clone, Debug, PartialEq)]
pub struct CategoryGroup {
    /// The name over the run.
    pub label: String,
    /// The run of category indices.
    pub categories: std::ops::Range<usize>,
}

/// A grouped bar chart: a group of bars per category, one per series.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BarChart {
    /// The title.
    pub title: String,
    /// The line under the title (none when empty).
    pub subtitle: String,
    /// The y axis label.
    pub y_label: String,
    /// The x axis: scene names, then group means such as "mean 3D".
    pub categories: Vec<String>,
    /// One colour and one bar per category each.
    pub series: Vec<Series>,
    /// The paper's values.
    pub paper: Vec<PaperMark>,
    /// The values are fractions, labelled as percentages.
    pub percent: bool,
    /// A solid horizontal line at this value (e.g. 0.0 for speedups).
    pub reference: Option<f64>,
    /// A dotted line before each of these category indices (may be the
    /// category count: after the last).
    pub separators: Vec<usize>,
    /// Categories with a light grey band behind them, e.g. the means.
    pub highlight: Vec<usize>,
    /// Runs of categories named above the plot.
    pub groups: Vec<CategoryGroup>,
}

/// A line chart: the series' values at shared x positions, each series a
/// line through markers of its own shape.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LineChart {
    /// The title.
    pub title: String,
    /// The line under the title (none when empty).
    pub subtitle: String,
    /// The x axis label.
    pub x_label: String,
    /// The y axis label.
    pub y_label: String,
    /// The x positions, shared by every series, strictly increasing.
    pub x: Vec<f64>,
    /// A label at each x position (thinned where they would overlap);
    /// None: a numeric axis.
    pub x_ticks: Option<Vec<String>>,
    /// Values aligned with `x`.
    pub series: Vec<Series>,
    /// The paper's values; a mark's category is an index into `x`.
    pub paper: Vec<PaperMark>,
    /// The values are fractions, labelled as percentages.
    pub percent: bool,
    /// A solid horizontal line at this value.
    pub reference: Option<f64>,
}

/// The start of every error message about drawing the chart `title`.
fn who(title: &str) -> String {
    match title {
        "" => "drawing the untitled chart".to_string(),
        t => format!("drawing {t}"),
    }
}

/// Ok when `ok`, else the error `msg()`.
pub(crate) fn ensure(ok: bool, msg: impl FnOnce() -> String) -> Result<(), String> {
    ok.then_some(()).ok_or_else(msg)
}

/// An error unless `v` is finite; `what` names it.
fn finite(who: &str, what: impl std::fmt::Display, v: f64) -> Result<(), String> {
    match v.is_finite() {
        true => Ok(()),
        false => Err(format!("{who}: {what} has the non-finite value {v}")),
    }
}

/// Checks the series against `n` categories (or x positions: `what`), the
/// paper's marks and the reference line.
fn check(
    who: &str,
    (series, paper, reference): (&[Series], &[PaperMark], Option<f64>),
    (n, what): (usize, &str),
    name_of: impl Fn(usize) -> String,
) -> Result<(), String> {
    let (k, nothing) = (series.len(), "nothing to draw");
    ensure(n > 0 && k > 0, || {
        format!("{who}: {n} {what} and {k} series: {nothing}")
    })?;
    for s in series {
        let (name, len) = (&s.name, s.values.len());
        ensure(len == n, || {
            format!("{who}: series `{name}` has {len} values for {n} {what}")
        })?;
        for (i, v) in s.values.iter().enumerate() {
            let at = format_args!("series `{name}` at {}", name_of(i));
            finite(who, at, v.unwrap_or(0.0))?;
        }
    }
    for m in paper {
        let (l, past) = (&m.label, m.series >= Some(k) || m.category >= Some(n));
        ensure(!past, || {
            format!("{who}: paper mark `{l}` is past the {k} series or {n} {what}")
        })?;
        finite(who, format_args!("paper mark `{l}`"), m.value)?;
    }
    finite(who, "the reference line", reference.unwrap_or(0.0))
}

#[cfg(test)]
pub(crate) mod tests {
    use std::path::{Path, PathBuf};

    /// A fresh path `file` in a scratch directory of the test `name`.
    pub(crate) fn out(name: &str, file: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("wasp-charts-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("scratch dir");
        let path = dir.join(file);
        std::fs::remove_file(&path).ok();
        path
    }

    /// The texts of the SVG at `path`, each with its anchor (x, y) and
    /// whether it reads upwards, after asserting that `want` (texts
    /// separated by `|`) are among them.
    pub(crate) fn texts(path: &Path, want: &str) -> Vec<(String, f64, f64, bool)> {
        let svg = std::fs::read_to_string(path).expect("svg");
        let attr = |part: &str, a: &str| {
            let v = part.split(&format!(" {a}=\"")).nth(1)?.split('"').next()?;
            v.parse::<f64>().ok()
        };
        let texts: Vec<(String, f64, f64, bool)> = (svg.split("<text").skip(1))
            .filter_map(|part| {
                let text = part.split_once('>')?.1.split_once("</text>")?.0.trim();
                let text = text.replace("&apos;", "'").replace("&amp;", "&");
                let up = part.split_once('>')?.0.contains("rotate(");
                Some((text, attr(part, "x")?, attr(part, "y")?, up))
            })
            .collect();
        for w in want.split('|').filter(|w| !w.is_empty()) {
            assert!(texts.iter().any(|t| t.0 == w), "no `{w}` in {texts:?}");
        }
        texts
    }

    /// A series of `key` named `name` with a value for every category.
    pub(crate) fn full(key: super::Key, name: &str, values: &[f64]) -> super::Series {
        let values = values.iter().map(|&v| Some(v)).collect();
        let name = name.into();
        super::Series { key, name, values }
    }

    /// A paper mark.
    pub(crate) fn mark(
        series: Option<usize>,
        category: Option<usize>,
        value: f64,
        label: &str,
    ) -> super::PaperMark {
        let label = label.into();
        super::PaperMark {
            series,
            category,
            value,
            label,
        }
    }

    /// The number of pixels of `colour` in the PNG at `path`.
    pub(crate) fn pixels(path: &Path, colour: plotters::style::RGBColor) -> usize {
        let img = image::open(path).expect("png decodes").to_rgb8();
        let want = [colour.0, colour.1, colour.2];
        img.pixels().filter(|p| p.0 == want).count()
    }

    /// Something that draws a chart into a file.
    type Draw<'a> = &'a dyn Fn(&Path) -> Result<(), String>;

    /// Draws with `draw` twice as PNG and as SVG: the same bytes each time.
    pub(crate) fn same_twice(name: &str, draw: Draw) {
        for ext in ["png", "svg"] {
            let [a, b] = ["a", "b"].map(|file| out(name, &format!("{file}.{ext}")));
            draw(&a).and(draw(&b)).expect("drawn");
            let same = std::fs::read(&a).ok() == std::fs::read(&b).ok();
            assert!(same, "{ext}s differ");
        }
    }

    /// The error of drawing with `draw` into `file`; no file is written.
    pub(crate) fn error(name: &str, file: &str, draw: Draw) -> String {
        let path = out(name, file);
        let e = draw(&path).expect_err(name);
        assert!(!path.exists(), "{name}: a file was written");
        e
    }

    /// A bad change to a chart `C` and a text its error holds.
    pub(crate) type Case<C> = (fn(&mut C), &'static str);

    /// Asserts of each case that drawing `chart` with `draw` after the
    /// case's change fails with an error that starts with `prefix` and
    /// holds the case's text.
    pub(crate) fn refused<C: Clone>(
        (name, chart, prefix): (&str, &C, &str),
        draw: fn(&C, &Path) -> Result<(), String>,
        cases: &[Case<C>],
    ) {
        for (change, want) in cases {
            let mut c = chart.clone();
            change(&mut c);
            let e = error(name, "c.svg", &|p| draw(&c, p));
            assert!(e.starts_with(prefix) && e.contains(want), "{e}");
        }
    }

    #[test]
    fn errors_say_what_failed() {
        assert_eq!(super::who(""), "drawing the untitled chart");
        let e = super::finite("drawing x", "y", f64::NAN).unwrap_err();
        assert_eq!(e, "drawing x: y has the non-finite value NaN");
    }
}
