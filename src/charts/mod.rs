//! Charts of the reproduction (`wasp reproduce`): grouped bar charts
//! ([`draw_bars`]) and line charts ([`draw_lines`]), each beside the values
//! the paper gives ([`PaperMark`]), written as PNG or SVG.
//!
//! # Layout
//!
//! Every chart is one picture, from top to bottom:
//!
//! 1. the title (bold) and, when given, a subtitle line under it;
//! 2. the legend, a row of entries (wrapping onto more rows when needed)
//!    above the plot, so it never hides data: one entry per series and one
//!    for the paper's values when the chart has any;
//! 3. the plot: the y axis on the left with its label, tick labels (as
//!    percentages for a `percent` chart) and light horizontal grid lines;
//!    the data; the reference line (thin, solid, dark grey);
//! 4. the x axis under the plot: category names for bars (vertical, reading
//!    upwards, when the widest does not fit its group) or the x tick labels
//!    and the x axis label for lines.
//!
//! The paper's values are dashed. A mark for every category is a dashed
//! horizontal line across the plot with its label in a margin right of the
//! plot, in the colour of its series (black for the whole chart); a mark
//! for one category is a short dashed line with a hollow marker over that
//! category (over the series' bar in a bar chart) with its label beside it
//! where there is room.
//!
//! The y range holds 0 (bar charts: the bars' base; line charts: unless
//! there is a reference line, which the range holds instead), the reference
//! line, every value and every paper mark, with 8% of headroom above (and
//! below when something is negative).
//!
//! The picture is about 1400 x 700 pixels: a bar chart is wider with more
//! categories and series (900 to 1800 pixels) and taller when its category
//! names are vertical. Drawing is deterministic: the same chart gives the
//! same bytes. Text is DejaVu Sans from [`crate::fonts`].
//!
//! # Code
//!
//! This file holds the charts' types, their common checks, the palette and
//! the output as PNG or SVG; `bars` and `lines` lay out and draw each kind
//! of chart; `axis` (the y axis), `legend` (title, legend, the paper's
//! lines) and `canvas` (pixel drawing, markers, label placement) are what
//! they share. `examples` (tests only, ignored) writes example pictures.

mod axis;
mod bars;
mod canvas;
#[cfg(test)]
mod examples;
mod legend;
mod lines;

pub use bars::draw_bars;
pub use lines::draw_lines;

use crate::picture::palette_colour;
pub(crate) use crate::picture::{save, Picture};
use plotters::prelude::*;
use std::path::Path;

/// One series of a chart: a value per category (None: no bar / gap in the
/// line).
#[derive(Clone, Debug, PartialEq)]
pub struct Series {
    /// The name in the legend.
    pub name: String,
    /// One value per category (bar chart) or x position (line chart).
    pub values: Vec<Option<f64>>,
}

impl Series {
    /// A series with a value, or none, per category.
    pub fn new(name: impl Into<String>, values: Vec<Option<f64>>) -> Self {
        Series {
            name: name.into(),
            values,
        }
    }

    #[cfg(test)]
    /// A series with a value for every category.
    pub fn full(name: impl Into<String>, values: &[f64]) -> Self {
        Series::new(name, values.iter().copied().map(Some).collect())
    }
}

/// A value the paper gives, drawn beside ours.
#[derive(Clone, Debug, PartialEq)]
pub struct PaperMark {
    /// The series it belongs to (its colour); None: the whole chart
    /// (black).
    pub series: Option<usize>,
    /// Categories it applies to: None = all (a dashed horizontal line
    /// across the plot, labelled in the margin right of the plot); Some(i)
    /// = only category (bar chart) or x position (line chart) i (a short
    /// dashed line and a hollow marker there).
    pub category: Option<usize>,
    /// The paper's value, in the units of the y axis (a fraction for a
    /// `percent` chart).
    pub value: f64,
    /// The text beside the mark, e.g. "paper 3.9%".
    pub label: String,
}

impl PaperMark {
    /// A mark for every category: a dashed line across the plot.
    pub fn all(series: Option<usize>, value: f64, label: impl Into<String>) -> Self {
        PaperMark {
            series,
            category: None,
            value,
            label: label.into(),
        }
    }

    /// A mark for category (or x position) `category` only.
    pub fn at(
        series: Option<usize>,
        category: usize,
        value: f64,
        label: impl Into<String>,
    ) -> Self {
        PaperMark {
            series,
            category: Some(category),
            value,
            label: label.into(),
        }
    }
}

/// A grouped bar chart: one group of bars per category, one bar (and
/// colour) per series.
#[derive(Clone, Debug, PartialEq)]
pub struct BarChart {
    /// The title over the chart.
    pub title: String,
    /// One line under the title (e.g. "shared-tile machine, 16 scenes");
    /// nothing when empty.
    pub subtitle: String,
    /// The y axis label.
    pub y_label: String,
    /// The x axis: scene names, then group means such as "mean 3D".
    pub categories: Vec<String>,
    /// Grouped bars, one colour per series, in the legend.
    pub series: Vec<Series>,
    /// The paper's values.
    pub paper: Vec<PaperMark>,
    /// The y values are fractions, labelled as percentages (0.039 ->
    /// "3.9%").
    pub percent: bool,
    /// A thin solid horizontal line at this value (e.g. 0.0 for speedups,
    /// 1.0 for ratios).
    pub reference: Option<f64>,
    /// A vertical dotted separator is drawn before each of these category
    /// indices (e.g. before the means); an index may be the category count
    /// (a line after the last group).
    pub separators: Vec<usize>,
    /// Categories drawn emphasised (bold name, light grey band behind the
    /// group), e.g. the means.
    pub highlight: Vec<usize>,
}

impl BarChart {
    /// A chart of `categories` with no series, subtitle, paper marks,
    /// reference, separators or highlights yet.
    pub fn new(
        title: impl Into<String>,
        y_label: impl Into<String>,
        categories: Vec<String>,
    ) -> Self {
        BarChart {
            title: title.into(),
            subtitle: String::new(),
            y_label: y_label.into(),
            categories,
            series: Vec::new(),
            paper: Vec::new(),
            percent: false,
            reference: None,
            separators: Vec::new(),
            highlight: Vec::new(),
        }
    }
}

/// A line chart: the series' values at shared x positions, points marked
/// with a shape per series and joined by lines.
#[derive(Clone, Debug, PartialEq)]
pub struct LineChart {
    /// The title over the chart.
    pub title: String,
    /// One line under the title; nothing when empty.
    pub subtitle: String,
    /// The x axis label.
    pub x_label: String,
    /// The y axis label.
    pub y_label: String,
    /// The x positions, shared by every series, strictly increasing; the
    /// axis is linear in them (0, 1, 2, ... with `x_ticks` spaces labelled
    /// positions evenly).
    pub x: Vec<f64>,
    /// Labels at the x positions (e.g. "28", "32", ...), one per position;
    /// None: a numeric axis.
    pub x_ticks: Option<Vec<String>>,
    /// Values aligned with `x`; a None leaves a gap in the line.
    pub series: Vec<Series>,
    /// The paper's values; a mark's category is an index into `x`.
    pub paper: Vec<PaperMark>,
    /// The y values are fractions, labelled as percentages.
    pub percent: bool,
    /// A thin solid horizontal line at this value.
    pub reference: Option<f64>,
}

impl LineChart {
    /// A chart over `x` with no series, subtitle, tick labels, paper marks
    /// or reference yet.
    pub fn new(
        title: impl Into<String>,
        x_label: impl Into<String>,
        y_label: impl Into<String>,
        x: Vec<f64>,
    ) -> Self {
        LineChart {
            title: title.into(),
            subtitle: String::new(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            x,
            x_ticks: None,
            series: Vec::new(),
            paper: Vec::new(),
            percent: false,
            reference: None,
        }
    }
}

/// The colour of series `s` ([`crate::picture::palette_colour`]).
fn series_colour(s: usize) -> RGBColor {
    palette_colour(s)
}

/// A darker shade of `c` for marks and text drawn over or beside its bars.
fn dark(c: RGBColor) -> RGBColor {
    let d = |v: u8| (u16::from(v) * 62 / 100) as u8;
    RGBColor(d(c.0), d(c.1), d(c.2))
}

/// The colour of a paper mark of `series` (black for the whole chart).
fn mark_colour(series: Option<usize>) -> RGBColor {
    series.map_or(BLACK, |s| dark(series_colour(s)))
}

/// The start of every error message about drawing the chart `title`.
fn who(title: &str) -> String {
    if title.is_empty() {
        "drawing the untitled chart".to_string()
    } else {
        format!("drawing {title}")
    }
}

/// Whether `path` asks for an SVG or a PNG ([`crate::picture::is_svg`]).
fn is_svg(path: &Path) -> Result<bool, String> {
    crate::picture::is_svg(path, "a chart")
}

/// Checks the series against `n` categories (or x positions, by `what`):
/// each has `n` values, all finite.
fn check_series(
    who: &str,
    series: &[Series],
    n: usize,
    what: &str,
    name_of: impl Fn(usize) -> String,
) -> Result<(), String> {
    if n == 0 {
        return Err(format!("{who}: no {what}: nothing to draw"));
    }
    if series.is_empty() {
        return Err(format!("{who}: no series: nothing to draw"));
    }
    for s in series {
        if s.values.len() != n {
            return Err(format!(
                "{who}: series `{}` has {} values for {n} {what}",
                s.name,
                s.values.len()
            ));
        }
        if let Some((i, v)) = s
            .values
            .iter()
            .enumerate()
            .find_map(|(i, v)| v.filter(|v| !v.is_finite()).map(|v| (i, v)))
        {
            return Err(format!(
                "{who}: series `{}` has the non-finite value {v} at {}",
                s.name,
                name_of(i)
            ));
        }
    }
    Ok(())
}

/// Checks the paper marks (their series and category indices, values) and
/// the reference line.
fn check_marks(
    who: &str,
    paper: &[PaperMark],
    reference: Option<f64>,
    series: usize,
    n: usize,
    what: &str,
) -> Result<(), String> {
    for m in paper {
        if let Some(s) = m.series.filter(|&s| s >= series) {
            return Err(format!(
                "{who}: paper mark `{}` belongs to series {s}, but there are {series} series",
                m.label
            ));
        }
        if let Some(c) = m.category.filter(|&c| c >= n) {
            return Err(format!(
                "{who}: paper mark `{}` is at index {c}, but there are {n} {what}",
                m.label
            ));
        }
        if !m.value.is_finite() {
            return Err(format!(
                "{who}: paper mark `{}` has the non-finite value {}",
                m.label, m.value
            ));
        }
    }
    if let Some(r) = reference.filter(|r| !r.is_finite()) {
        return Err(format!(
            "{who}: the reference line is at the non-finite value {r}"
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unique scratch directory for one test.
    pub(super) fn scratch(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!(
            "wasp-charts-{name}-{}-{}",
            std::process::id(),
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map(|d| d.as_nanos())
                .unwrap_or(0)
        ));
        std::fs::create_dir_all(&dir).expect("scratch dir");
        dir
    }

    /// The texts of an SVG's `<text>` elements, trimmed and unescaped.
    pub(super) fn svg_texts(svg: &str) -> Vec<String> {
        svg.split("<text")
            .skip(1)
            .filter_map(|part| {
                let body = part.split_once('>')?.1;
                let text = body.split_once("</text>")?.0.trim();
                Some(
                    text.replace("&lt;", "<")
                        .replace("&gt;", ">")
                        .replace("&quot;", "\"")
                        .replace("&apos;", "'")
                        .replace("&amp;", "&"),
                )
            })
            .collect()
    }

    /// The number of distinct colours in a PNG and the count of pixels of
    /// `colour` in it.
    pub(super) fn colours(path: &Path, colour: RGBColor) -> (usize, usize) {
        let img = image::open(path).expect("png decodes").to_rgb8();
        let distinct: std::collections::BTreeSet<[u8; 3]> = img.pixels().map(|p| p.0).collect();
        let want = [colour.0, colour.1, colour.2];
        let count = img.pixels().filter(|p| p.0 == want).count();
        (distinct.len(), count)
    }

    #[test]
    fn extensions_choose_the_format() {
        assert_eq!(is_svg(Path::new("a/b.svg")), Ok(true));
        assert_eq!(is_svg(Path::new("b.SVG")), Ok(true));
        assert_eq!(is_svg(Path::new("b.Png")), Ok(false));
        for bad in ["b.jpg", "b", "b.png.txt"] {
            let e = is_svg(Path::new(bad)).expect_err(bad);
            assert!(e.starts_with(bad), "{e}");
            assert!(e.contains(".png or .svg"), "{e}");
        }
    }

    #[test]
    fn later_palette_rounds_are_darker() {
        assert_eq!(series_colour(0), RGBColor(31, 119, 180));
        assert_eq!(series_colour(10), RGBColor(18, 71, 108));
        assert_eq!(series_colour(20), series_colour(0));
        assert_eq!(mark_colour(None), BLACK);
        assert_eq!(mark_colour(Some(1)), dark(series_colour(1)));
    }

    #[test]
    fn untitled_charts_still_say_what_failed() {
        assert_eq!(who("IPC"), "drawing IPC");
        assert_eq!(who(""), "drawing the untitled chart");
    }
}
