//! What bar and line charts share: pixel drawing with errors as strings,
//! text measurement, the y axis, the title, the legend, the paper lines'
//! margin labels and the placement of labels where they hide nothing.

use super::{mark_colour, PaperMark};
use crate::fonts::font;
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Colour of the grid lines.
pub(super) const GRID: RGBColor = RGBColor(225, 225, 225);
/// Colour of the reference line and the zero line.
pub(super) const REFERENCE: RGBColor = RGBColor(70, 70, 70);
/// Size of tick labels, category names and the legend.
pub(super) const LABEL_SIZE: u32 = 16;
/// Size of value labels and paper labels in the plot.
pub(super) const SMALL_SIZE: u32 = 13;
/// Height of one legend row.
const LEGEND_ROW: f64 = 26.0;
/// Width of a legend swatch.
const SWATCH_W: f64 = 30.0;

/// The pixel size of `text` in the chart font of `size`.
pub(super) fn text_size(text: &str, size: u32, bold: bool) -> (f64, f64) {
    match font(size, bold).box_size(text) {
        Ok((w, h)) => (f64::from(w), f64::from(h)),
        // Cannot happen with the embedded font; a generous guess.
        Err(_) => (
            text.chars().count() as f64 * f64::from(size) * 0.6,
            f64::from(size),
        ),
    }
}

/// A text style of the chart font.
pub(super) fn style(
    size: u32,
    bold: bool,
    colour: RGBColor,
    h: HPos,
    v: VPos,
) -> TextStyle<'static> {
    font(size, bold).color(&colour).pos(Pos::new(h, v))
}

/// A pixel point.
fn px((x, y): (f64, f64)) -> (i32, i32) {
    (x.round() as i32, y.round() as i32)
}

/// The root drawing area with the chart's error prefix.
pub(super) struct Canvas<'a, DB: DrawingBackend> {
    /// Where to draw.
    pub area: &'a DrawingArea<DB, Shift>,
    /// The error prefix (`drawing <title>`).
    pub who: &'a str,
}

impl<DB: DrawingBackend> Canvas<'_, DB>
where
    DB::ErrorType: 'static,
{
    /// A drawing error as the caller reports it.
    fn err<E: std::fmt::Display>(&self, e: E) -> String {
        format!("{}: {e}", self.who)
    }

    /// A rectangle from corner `a` to corner `b`.
    pub fn rect(&self, a: (f64, f64), b: (f64, f64), style: ShapeStyle) -> Result<(), String> {
        self.area
            .draw(&Rectangle::new([px(a), px(b)], style))
            .map_err(|e| self.err(e))
    }

    /// A polyline through `points`.
    pub fn path(&self, points: &[(f64, f64)], style: ShapeStyle) -> Result<(), String> {
        let points: Vec<(i32, i32)> = points.iter().copied().map(px).collect();
        self.area
            .draw(&PathElement::new(points, style))
            .map_err(|e| self.err(e))
    }

    /// A dashed polyline: `dash` pixels drawn, `gap` pixels left out.
    pub fn dashed(
        &self,
        points: &[(f64, f64)],
        dash: i32,
        gap: i32,
        style: ShapeStyle,
    ) -> Result<(), String> {
        let points: Vec<(i32, i32)> = points.iter().copied().map(px).collect();
        self.area
            .draw(&DashedPathElement::new(points, dash, gap, style))
            .map_err(|e| self.err(e))
    }

    /// A closed polygon.
    pub fn polygon(&self, points: &[(f64, f64)], style: ShapeStyle) -> Result<(), String> {
        let points: Vec<(i32, i32)> = points.iter().copied().map(px).collect();
        self.area
            .draw(&Polygon::new(points, style))
            .map_err(|e| self.err(e))
    }

    /// `text` at `at` in `style`.
    pub fn text(&self, text: &str, style: &TextStyle, at: (f64, f64)) -> Result<(), String> {
        self.area
            .draw_text(text, style, px(at))
            .map_err(|e| self.err(e))
    }

    /// A data point or paper marker of `shape` centred on `at`, `r` pixels
    /// from centre to edge: filled in `colour`, or `hollow` (white inside,
    /// a 2-pixel outline in `colour`).
    pub fn marker(
        &self,
        shape: Shape,
        at: (f64, f64),
        r: f64,
        colour: RGBColor,
        hollow: bool,
    ) -> Result<(), String> {
        let (x, y) = at;
        let outline = shape.outline(at, r);
        if hollow {
            match shape {
                Shape::Circle => {
                    self.area
                        .draw(&Circle::new(px(at), r.round() as i32, WHITE.filled()))
                        .map_err(|e| self.err(e))?;
                    self.area
                        .draw(&Circle::new(
                            px(at),
                            r.round() as i32,
                            colour.stroke_width(2),
                        ))
                        .map_err(|e| self.err(e))
                }
                _ => {
                    self.polygon(&outline, WHITE.filled())?;
                    let mut closed = outline.clone();
                    closed.push(outline[0]);
                    self.path(&closed, colour.stroke_width(2))
                }
            }
        } else if shape == Shape::Circle {
            self.area
                .draw(&Circle::new(px((x, y)), r.round() as i32, colour.filled()))
                .map_err(|e| self.err(e))
        } else {
            self.polygon(&outline, colour.filled())
        }
    }
}

/// The shapes marking the points of line-chart series (one per series, in
/// this order) and the paper's values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Shape {
    Circle,
    Square,
    Triangle,
    Diamond,
    TriangleDown,
}

impl Shape {
    /// The shape of series `s`.
    pub fn of(s: usize) -> Shape {
        [
            Shape::Circle,
            Shape::Square,
            Shape::Triangle,
            Shape::Diamond,
            Shape::TriangleDown,
        ][s % 5]
    }

    /// The corners of the shape (a 16-gon for the circle).
    fn outline(self, (x, y): (f64, f64), r: f64) -> Vec<(f64, f64)> {
        match self {
            Shape::Circle => (0..16)
                .map(|k| {
                    let a = f64::from(k) * std::f64::consts::PI / 8.0;
                    (x + r * a.cos(), y + r * a.sin())
                })
                .collect(),
            Shape::Square => {
                let r = r * 0.85;
                vec![
                    (x - r, y - r),
                    (x + r, y - r),
                    (x + r, y + r),
                    (x - r, y + r),
                ]
            }
            Shape::Triangle => vec![(x, y - r * 1.1), (x + r, y + r * 0.8), (x - r, y + r * 0.8)],
            Shape::TriangleDown => {
                vec![(x, y + r * 1.1), (x + r, y - r * 0.8), (x - r, y - r * 0.8)]
            }
            Shape::Diamond => vec![(x, y - r * 1.2), (x + r, y), (x, y + r * 1.2), (x - r, y)],
        }
    }
}

/// The y axis: its range and ticks.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct YAxis {
    /// The value at the bottom of the plot.
    pub lo: f64,
    /// The value at the top of the plot.
    pub hi: f64,
    /// The distance between ticks.
    step: f64,
    /// Decimals of the tick labels (of the percentage when `percent`).
    decimals: usize,
    /// Tick labels as percentages.
    percent: bool,
}

/// The distance between ticks: 1, 2 or 5 times a power of ten, at most
/// `max_ticks` ticks over `span`.
fn nice_step(span: f64, max_ticks: usize) -> f64 {
    let raw = span / max_ticks.max(1) as f64;
    let mag = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw * (1.0 - 1e-9))
        .unwrap_or(10.0 * mag)
}

/// Decimals that show a multiple of `step` exactly.
fn decimals(step: f64) -> usize {
    let d = (-step.log10() - 1e-9).ceil();
    if d > 0.0 {
        d.min(9.0) as usize
    } else {
        0
    }
}

impl YAxis {
    /// The axis over `values` and `include` (always in range), with 8%
    /// headroom above and, when anything is negative, below; at most
    /// `max_ticks` ticks.
    pub fn new(
        values: impl IntoIterator<Item = f64>,
        include: &[f64],
        percent: bool,
        max_ticks: usize,
    ) -> Self {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for v in values.into_iter().chain(include.iter().copied()) {
            lo = lo.min(v);
            hi = hi.max(v);
        }
        if !lo.is_finite() || !hi.is_finite() {
            (lo, hi) = (0.0, 1.0);
        }
        if hi - lo < 1e-12 * hi.abs().max(lo.abs()).max(1e-300) {
            // A single value: a range around it.
            let pad = if hi == 0.0 { 1.0 } else { hi.abs() * 0.5 };
            if lo >= 0.0 {
                hi += pad;
            } else {
                lo -= pad;
            }
        }
        let span = hi - lo;
        hi += 0.08 * span;
        if lo < 0.0 {
            lo -= 0.08 * span;
        }
        let step = nice_step(hi - lo, max_ticks);
        let shown = if percent { step * 100.0 } else { step };
        YAxis {
            lo,
            hi,
            step,
            decimals: decimals(shown),
            percent,
        }
    }

    /// The tick values, bottom to top.
    pub fn ticks(&self) -> Vec<f64> {
        let first = (self.lo / self.step - 1e-9).ceil() as i64;
        let last = (self.hi / self.step + 1e-9).floor() as i64;
        (first..=last).map(|k| k as f64 * self.step).collect()
    }

    /// The label of tick `v`.
    pub fn label(&self, v: f64) -> String {
        let v = if v.abs() < self.step * 1e-6 { 0.0 } else { v };
        if self.percent {
            format!("{:.*}%", self.decimals, v * 100.0)
        } else {
            format!("{:.*}", self.decimals, v)
        }
    }
}

/// A value as printed over its bar: two or three significant digits.
pub(super) fn value_label(v: f64, percent: bool) -> String {
    let shown = if percent { v * 100.0 } else { v };
    let a = shown.abs();
    // By the magnitude after rounding: 0.99996 is "1.0", not "1.00".
    let d = if a == 0.0 || a >= 99.5 {
        0
    } else if a >= 0.995 {
        1
    } else if a >= 0.0995 {
        2
    } else {
        3
    };
    let text = format!("{shown:.d$}");
    if percent {
        format!("{text}%")
    } else {
        text
    }
}

/// Where the plot is and how values map to its pixels.
#[derive(Clone, Debug)]
pub(super) struct Frame {
    /// Left edge of the plot.
    pub left: f64,
    /// Top edge of the plot.
    pub top: f64,
    /// Right edge of the plot.
    pub right: f64,
    /// Bottom edge of the plot.
    pub bottom: f64,
    /// The y axis.
    pub y: YAxis,
}

impl Frame {
    /// The pixel row of value `v`.
    pub fn py(&self, v: f64) -> f64 {
        self.bottom - (v - self.y.lo) / (self.y.hi - self.y.lo) * (self.bottom - self.top)
    }
}

/// The width of the y axis left of the plot: the axis label, the widest
/// tick label, gaps.
pub(super) fn y_axis_width(y: &YAxis) -> f64 {
    let widest = y
        .ticks()
        .iter()
        .map(|&v| text_size(&y.label(v), LABEL_SIZE, false).0)
        .fold(0.0, f64::max);
    14.0 + 22.0 + 10.0 + widest + 8.0
}

/// Draws the grid lines, tick labels and label of the y axis, and the left
/// edge of the plot.
pub(super) fn draw_y_axis<DB: DrawingBackend>(
    c: &Canvas<'_, DB>,
    f: &Frame,
    label: &str,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let tick_style = style(LABEL_SIZE, false, BLACK, HPos::Right, VPos::Center);
    for v in f.y.ticks() {
        let y = f.py(v);
        c.path(&[(f.left, y), (f.right, y)], GRID.stroke_width(1))?;
        c.path(&[(f.left - 5.0, y), (f.left, y)], BLACK.stroke_width(1))?;
        c.text(&f.y.label(v), &tick_style, (f.left - 8.0, y))?;
    }
    let desc = style(LABEL_SIZE + 1, false, BLACK, HPos::Center, VPos::Top)
        .transform(FontTransform::Rotate270);
    c.text(label, &desc, (14.0, (f.top + f.bottom) / 2.0))?;
    c.path(
        &[(f.left, f.top), (f.left, f.bottom)],
        BLACK.stroke_width(1),
    )
}

/// The title font sizes that fit `width`: title, subtitle.
fn title_sizes(title: &str, subtitle: &str, width: f64) -> (u32, u32) {
    let fit = |text: &str, mut size: u32, bold: bool, min: u32| {
        while size > min && text_size(text, size, bold).0 > width - 32.0 {
            size -= 1;
        }
        size
    };
    (fit(title, 27, true, 14), fit(subtitle, 19, false, 12))
}

/// The height of the title strip.
pub(super) fn title_height(subtitle: &str) -> f64 {
    if subtitle.is_empty() {
        52.0
    } else {
        78.0
    }
}

/// Draws the title and subtitle at the top of a picture `width` wide.
pub(super) fn draw_title<DB: DrawingBackend>(
    c: &Canvas<'_, DB>,
    title: &str,
    subtitle: &str,
    width: f64,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let (t, s) = title_sizes(title, subtitle, width);
    c.text(
        title,
        &style(t, true, BLACK, HPos::Left, VPos::Top),
        (16.0, 12.0),
    )?;
    if !subtitle.is_empty() {
        let grey = RGBColor(70, 70, 70);
        c.text(
            subtitle,
            &style(s, false, grey, HPos::Left, VPos::Top),
            (16.0, 44.0),
        )?;
    }
    Ok(())
}

/// How a legend entry shows what it names.
#[derive(Clone, Debug)]
pub(super) enum Swatch {
    /// A filled block (a bar series).
    Block(RGBColor),
    /// A line through a filled marker (a line series).
    Line(RGBColor, Shape),
    /// The paper's values: a dashed line and/or a hollow marker.
    Paper { line: bool, marker: Option<Shape> },
}

/// A legend entry.
#[derive(Clone, Debug)]
pub(super) struct Entry {
    /// The text.
    pub label: String,
    /// The swatch left of the text.
    pub swatch: Swatch,
}

/// The legend entry for the chart's paper marks, if it has any, shown with
/// `shape` for marks of one category.
pub(super) fn paper_entry(paper: &[PaperMark], shape: Shape) -> Option<Entry> {
    let line = paper.iter().any(|m| m.category.is_none());
    let marker = paper.iter().any(|m| m.category.is_some());
    let coloured = paper.iter().any(|m| m.series.is_some());
    let what = match (line, marker) {
        (false, false) => return None,
        (true, false) => "paper value: dashed line",
        (false, true) => "paper value: hollow mark",
        (true, true) => "paper values: dashed lines, hollow marks",
    };
    Some(Entry {
        label: if coloured {
            format!("{what} (series colour)")
        } else {
            what.to_string()
        },
        swatch: Swatch::Paper {
            line,
            marker: marker.then_some(shape),
        },
    })
}

/// The legend's entries placed in rows from `left` no wider than `width`:
/// (row, x of the swatch) per entry.
fn legend_places(entries: &[Entry], left: f64, width: f64) -> Vec<(usize, f64)> {
    let mut places = Vec::with_capacity(entries.len());
    let (mut row, mut x) = (0, left);
    for e in entries {
        let w = SWATCH_W + 8.0 + text_size(&e.label, LABEL_SIZE, false).0;
        if x > left && x + w > left + width {
            row += 1;
            x = left;
        }
        places.push((row, x));
        x += w + 26.0;
    }
    places
}

/// The height of the legend from `left`, `width` wide.
pub(super) fn legend_height(entries: &[Entry], left: f64, width: f64) -> f64 {
    let rows = legend_places(entries, left, width)
        .last()
        .map_or(0, |&(row, _)| row + 1);
    rows as f64 * LEGEND_ROW + 6.0
}

/// Draws the legend with its top at `top`, from `left`, `width` wide.
pub(super) fn draw_legend<DB: DrawingBackend>(
    c: &Canvas<'_, DB>,
    entries: &[Entry],
    left: f64,
    top: f64,
    width: f64,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let text_style = style(LABEL_SIZE, false, BLACK, HPos::Left, VPos::Center);
    for (e, (row, x)) in entries.iter().zip(legend_places(entries, left, width)) {
        let mid = top + (row as f64 + 0.5) * LEGEND_ROW;
        let (x0, x1) = (x, x + SWATCH_W);
        match &e.swatch {
            Swatch::Block(colour) => c.rect(
                (x0 + 4.0, mid - 8.0),
                (x1 - 4.0, mid + 8.0),
                colour.filled(),
            )?,
            Swatch::Line(colour, shape) => {
                c.path(&[(x0, mid), (x1, mid)], colour.stroke_width(2))?;
                c.marker(*shape, ((x0 + x1) / 2.0, mid), 5.0, *colour, false)?;
            }
            Swatch::Paper { line, marker } => {
                if *line {
                    c.dashed(&[(x0, mid), (x1, mid)], 5, 3, BLACK.stroke_width(2))?;
                }
                if let Some(shape) = marker {
                    c.marker(*shape, ((x0 + x1) / 2.0, mid), 6.0, BLACK, true)?;
                }
            }
        }
        c.text(&e.label, &text_style, (x1 + 8.0, mid))?;
    }
    Ok(())
}

/// A rectangle in pixels: left, top, right, bottom.
pub(super) type Rect = (f64, f64, f64, f64);

/// Labels placed where they hide nothing already placed.
#[derive(Default)]
pub(super) struct Placer {
    /// What labels must not cover.
    taken: Vec<Rect>,
}

impl Placer {
    /// Keeps labels off `r`.
    pub fn take(&mut self, r: Rect) {
        self.taken.push(r);
    }

    /// The first of `candidates` (rectangles) inside `bounds` that hides
    /// nothing taken, now taken itself; None if every one would.
    pub fn place(
        &mut self,
        candidates: impl IntoIterator<Item = Rect>,
        bounds: Rect,
    ) -> Option<Rect> {
        let inside =
            |r: &Rect| r.0 >= bounds.0 && r.1 >= bounds.1 && r.2 <= bounds.2 && r.3 <= bounds.3;
        let free = |r: &Rect| {
            self.taken
                .iter()
                .all(|t| r.2 <= t.0 || r.0 >= t.2 || r.3 <= t.1 || r.1 >= t.3)
        };
        let found = candidates.into_iter().find(|r| inside(r) && free(r))?;
        self.taken.push(found);
        Some(found)
    }
}

/// Rectangles `w` x `h` centred on `x` from `y0` away from the plot's zero
/// in steps of 3 pixels, upwards (`up`) or downwards: where to try a label
/// over (or under) a bar or marker.
pub(super) fn column(x: f64, y0: f64, w: f64, h: f64, up: bool, limit: f64) -> Vec<Rect> {
    let mut out = Vec::new();
    let mut k = 0.0;
    loop {
        let r = if up {
            (x - w / 2.0, y0 - h - k, x + w / 2.0, y0 - k)
        } else {
            (x - w / 2.0, y0 + k, x + w / 2.0, y0 + h + k)
        };
        if (up && r.1 < limit) || (!up && r.3 > limit) || out.len() > 400 {
            break;
        }
        out.push(r);
        k += 3.0;
    }
    out
}

/// The width of the margin right of the plot that holds the labels of the
/// paper's lines across the plot.
pub(super) fn paper_margin(paper: &[PaperMark]) -> f64 {
    paper
        .iter()
        .filter(|m| m.category.is_none())
        .map(|m| text_size(&m.label, SMALL_SIZE + 1, true).0 + 16.0)
        .fold(30.0, f64::max)
}

/// Draws the paper's lines across the plot (marks of no category): a white
/// halo under a dashed line in the mark's colour, and the label in the
/// right margin at the line's height, moved up or down as little as needed
/// to keep labels apart. The lines are kept free of labels in the plot.
pub(super) fn draw_paper_lines<DB: DrawingBackend>(
    c: &Canvas<'_, DB>,
    f: &Frame,
    paper: &[PaperMark],
    placer: &mut Placer,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let mut lines: Vec<&PaperMark> = paper.iter().filter(|m| m.category.is_none()).collect();
    for m in &lines {
        let y = f.py(m.value);
        let ends = [(f.left, y), (f.right, y)];
        c.path(&ends, WHITE.mix(0.8).stroke_width(4))?;
        c.dashed(&ends, 9, 5, mark_colour(m.series).stroke_width(2))?;
        placer.take((f.left, y - 2.0, f.right, y + 2.0));
    }
    // Labels: top to bottom, each at least a line below the previous one.
    lines.sort_by(|a, b| b.value.total_cmp(&a.value));
    let h = text_size("Ag", SMALL_SIZE + 1, true).1 + 2.0;
    let mut ys: Vec<f64> = lines.iter().map(|m| f.py(m.value)).collect();
    for i in 1..ys.len() {
        ys[i] = ys[i].max(ys[i - 1] + h);
    }
    // Pushed below the plot's bottom: shift the whole stack up.
    if let Some(&last) = ys.last() {
        let over = last - (f.bottom + h / 2.0);
        if over > 0.0 {
            ys.iter_mut().for_each(|y| *y -= over);
        }
    }
    for (m, y) in lines.iter().zip(ys) {
        let s = style(
            SMALL_SIZE + 1,
            true,
            mark_colour(m.series),
            HPos::Left,
            VPos::Center,
        );
        c.text(&m.label, &s, (f.right + 8.0, y))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_round_and_labelled_as_percentages() {
        let y = YAxis::new([0.039, 0.02, -0.02], &[0.0], true, 8);
        assert!(y.lo < -0.02 && y.hi > 0.039, "{y:?}");
        let ticks = y.ticks();
        assert!(ticks.len() >= 4 && ticks.len() <= 9, "{ticks:?}");
        let labels: Vec<String> = ticks.iter().map(|&v| y.label(v)).collect();
        assert!(labels.contains(&"0%".to_string()), "{labels:?}");
        assert!(labels.contains(&"-2%".to_string()), "{labels:?}");
        assert!(labels.iter().all(|l| l.ends_with('%')), "{labels:?}");
        let y = YAxis::new([0.5, 1.2], &[0.0, 1.0], false, 8);
        let labels: Vec<String> = y.ticks().iter().map(|&v| y.label(v)).collect();
        assert_eq!(labels, ["0.0", "0.2", "0.4", "0.6", "0.8", "1.0", "1.2"]);
    }

    #[test]
    fn a_flat_range_still_has_height() {
        let y = YAxis::new([0.0, 0.0], &[0.0], false, 8);
        assert!(y.hi > 0.9 && y.lo == 0.0, "{y:?}");
        let y = YAxis::new([-3.0], &[], false, 8);
        assert!(y.lo < -3.0 && y.hi > -3.0, "{y:?}");
    }

    #[test]
    fn value_labels_keep_two_or_three_digits() {
        assert_eq!(value_label(0.039, true), "3.9%");
        assert_eq!(value_label(-0.0213, true), "-2.1%");
        assert_eq!(value_label(0.00123, true), "0.12%");
        assert_eq!(value_label(1.234, false), "1.2");
        assert_eq!(value_label(0.0, false), "0");
        assert_eq!(value_label(0.009999999999999998, true), "1.0%");
        assert_eq!(value_label(0.0999, false), "0.10");
        assert_eq!(value_label(1234.4, false), "1234");
    }

    #[test]
    fn labels_avoid_what_is_taken() {
        let mut p = Placer::default();
        p.take((0.0, 50.0, 10.0, 100.0));
        let bounds = (0.0, 0.0, 100.0, 100.0);
        let r = p
            .place(column(5.0, 60.0, 10.0, 10.0, true, 0.0), bounds)
            .expect("room above");
        assert!(r.3 <= 50.0, "{r:?}");
        // Nowhere to go: the column is full.
        p.take((0.0, 0.0, 10.0, 50.0));
        assert_eq!(
            p.place(column(5.0, 60.0, 10.0, 10.0, true, 0.0), bounds),
            None
        );
    }
}
