//! What every picture shares, and what plotters lacks: the strip above the
//! plot (title, subtitle, legend), the paper's marks, the [`Placer`] that
//! puts labels where they hide nothing; and the plot's `ChartBuilder`,
//! mesh style, range and axes ticked with their labels ([`Ticked`]).

use super::legend::{legend, line_height, marker, rows, Legend, Shape, Swatch};
use crate::fonts::{font, register_fonts};
use crate::palette::{shade, GRID, INK};
use crate::picture::{is_svg, save};
pub(crate) use crate::picture::{Area, Drawn, Picture};
use plotters::coord::ranged1d::{KeyPointHint, NoDefaultFormatting, ValueFormatter};
use plotters::coord::types::RangedCoordf64;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos as H, Pos, VPos as V};
use std::ops::Range;
use std::path::Path;

/// Size of tick labels, category names and the legend.
pub(super) const LABEL: u32 = 16;
/// Size of value labels and paper labels in the plot.
pub(super) const SMALL: u32 = 13;
/// A rectangle in pixels: left, top, right, bottom.
pub(super) type Rect = (f64, f64, f64, f64);
/// The label areas left of and under a plot, its margins over and right.
pub(crate) type Pad = (f64, f64, f64, f64);
/// Writes the chart that `layout` gives to `path` (PNG or SVG by the
/// extension), registering the fonts first: the layout measures text.
pub(super) fn write<C: Picture>(
    who: &str,
    path: &Path,
    layout: impl FnOnce() -> C,
) -> Result<(), String> {
    let svg = is_svg(path, "a chart")?;
    register_fonts().map_err(|e| format!("{who}: {e}"))?;
    save(&layout(), who, path, svg)
}

/// The pixel size of `text` in the chart font of `size`.
pub(super) fn text_size(text: &str, size: u32, bold: bool) -> (f64, f64) {
    let guess = (text.chars().count() as u32 * size * 3 / 5, size);
    let (w, h) = font(size, bold).box_size(text).unwrap_or(guess);
    (f64::from(w), f64::from(h))
}

/// A text style of the chart font.
pub(super) fn style(size: u32, bold: bool, c: RGBColor, h: H, v: V) -> TextStyle<'static> {
    font(size, bold).color(&c).pos(Pos::new(h, v))
}

/// A pixel point.
pub(super) fn px(x: f64, y: f64) -> (i32, i32) {
    (x.round() as i32, y.round() as i32)
}

/// The rectangle `r.0` either side of `(x, y)` and `r.1` over and under.
pub(super) fn around((x, y): (f64, f64), r: (f64, f64)) -> Rect {
    (x - r.0, y - r.1, x + r.0, y + r.1)
}

/// The strip above the plot: title, subtitle, the legend from `left`;
/// `width` is the picture's.
pub(crate) struct Frame<'a> {
    pub title: (&'a str, &'a str),
    pub legend: Legend,
    pub left: f64,
    pub width: f64,
}

impl<'a> Frame<'a> {
    /// The strip of `title` (and subtitle), `legend` from `left`.
    pub fn new(title: (&'a str, &'a str), legend: Legend, left: f64, width: f64) -> Self {
        Frame {
            title,
            legend,
            left,
            width,
        }
    }

    /// The height of the title and subtitle.
    fn title_h(&self) -> f64 {
        52.0 + 26.0 * f64::from(u8::from(!self.title.1.is_empty()))
    }

    /// The lines of each column of the legend.
    fn rows(&self) -> usize {
        rows(&self.legend, LABEL, self.width - self.left - 16.0)
    }

    /// The height of the strip: title, legend, a gap.
    pub fn height(&self) -> u32 {
        (self.title_h() + self.rows() as f64 * line_height(LABEL) + 10.0) as u32
    }

    /// Fills `root` white, draws the strip and returns the area under it.
    pub fn draw<DB: DrawingBackend>(&self, root: &Area<DB>) -> Drawn<DB, Area<DB>> {
        root.fill(&WHITE)?;
        let ((title, sub), room) = (self.title, self.width - 32.0);
        let fit = |t: &str, s: u32, b| (12..s).rev().find(|&s| text_size(t, s, b).0 <= room);
        let size = fit(title, 28, true).unwrap_or(12);
        root.draw_text(title, &style(size, true, BLACK, H::Left, V::Top), (16, 12))?;
        let size = fit(sub, 20, false).unwrap_or(12);
        root.draw_text(sub, &style(size, false, INK, H::Left, V::Top), (16, 44))?;
        let (rows, top, w) = (self.rows(), self.title_h() as u32, self.width - self.left);
        let (at, size) = ((self.left as u32, top), (w as u32, self.height() - top));
        let strip = root.clone().shrink(at, size);
        legend(&strip, &self.legend, (rows, LABEL))?;
        Ok(root.split_vertically(self.height()).1)
    }
}

/// The legend entry of the paper's marks, if any, showing `shape` for
/// marks of one category.
pub(super) fn paper_entry(paper: &[super::PaperMark], shape: Shape) -> Option<(String, Swatch)> {
    let line = paper.iter().any(|m| m.category.is_none());
    let marker = paper.iter().any(|m| m.category.is_some());
    let what = match (line, marker) {
        (false, false) => return None,
        (true, false) => "paper value: dashed line",
        (false, true) => "paper value: hollow mark",
        (true, true) => "paper values: dashed lines, hollow marks",
    };
    let coloured = paper.iter().any(|m| m.series.is_some());
    let label = format!("{what}{}", if coloured { " (series colour)" } else { "" });
    let swatch = Swatch::Dashed(INK.stroke_width(2), marker.then_some(shape));
    Some((label, swatch))
}

/// The colour of the paper's marks of `series` (dark grey for none) in a
/// chart of series `colours`.
pub(super) fn mark_colour(colours: &[RGBColor], series: Option<usize>) -> RGBColor {
    series.map_or(INK, |s| shade(colours[s], 0.62))
}

/// The width of the margin right of the plot for the labels of the paper's
/// lines across it.
pub(super) fn paper_margin(paper: &[super::PaperMark]) -> f64 {
    let width = |m: &super::PaperMark| text_size(&m.label, SMALL + 1, true).0 + 16.0;
    let lines = paper.iter().filter(|m| m.category.is_none());
    lines.map(width).fold(30.0, f64::max)
}

/// Draws the paper's lines across the plot `p` (marks of no category) at
/// the pixel rows `row(value)`: a dashed line in the mark's colour over a
/// white halo, labelled right of the plot at its height (moved as little as
/// keeps labels apart). The lines, halo and a gap are kept free of labels.
pub(super) fn paper_lines<DB: DrawingBackend>(
    root: &Area<DB>,
    (p, placer): (Rect, &mut Placer),
    paper: &[super::PaperMark],
    row: impl Fn(f64) -> f64,
    colour: impl Fn(Option<usize>) -> RGBColor,
) -> Drawn<DB> {
    let mut lines: Vec<_> = paper.iter().filter(|m| m.category.is_none()).collect();
    for m in &lines {
        let (y, style) = (row(m.value), colour(m.series).stroke_width(2));
        let ends = vec![px(p.0, y), px(p.2, y)];
        let halo = WHITE.mix(0.8).stroke_width(4);
        root.draw(&PathElement::new(ends.clone(), halo))?;
        root.draw(&DashedPathElement::new(ends, 9, 5, style))?;
        placer.take((p.0, y - 5.0, p.2, y + 5.0));
    }
    // Labels top to bottom, each a line below the one before; the stack
    // moved up if it would pass the plot's bottom.
    lines.sort_by(|a, b| b.value.total_cmp(&a.value));
    let h = text_size("Ag", SMALL + 1, true).1 + 2.0;
    let mut ys: Vec<f64> = lines.iter().map(|m| row(m.value)).collect();
    for i in 1..ys.len() {
        ys[i] = ys[i].max(ys[i - 1] + h);
    }
    let over = ys.last().map_or(0.0, |y| y - p.3 - h / 2.0).max(0.0);
    for (m, y) in lines.iter().zip(ys) {
        let s = style(SMALL + 1, true, colour(m.series), H::Left, V::Center);
        root.draw_text(&m.label, &s, px(p.2 + 8.0, y - over))?;
    }
    Ok(())
}

/// Draws a paper mark of one category at pixel `at`: a dashed line `half`
/// pixels either side over a white halo, and a hollow `shape` of radius
/// `r`; what it covers is kept free of labels.
pub(super) fn paper_point<DB: DrawingBackend>(
    (root, placer): (&Area<DB>, &mut Placer),
    (at, half, r): ((f64, f64), f64, f64),
    shape: Shape,
    colour: RGBColor,
) -> Drawn<DB> {
    let ends = vec![px(at.0 - half, at.1), px(at.0 + half, at.1)];
    root.draw(&PathElement::new(ends.clone(), WHITE.stroke_width(5)))?;
    root.draw(&DashedPathElement::new(ends, 4, 2, colour.stroke_width(2)))?;
    root.draw(&marker(px(at.0, at.1), (shape, r as i32), colour, true))?;
    placer.take(around(at, (r + 2.0, r + 3.0)));
    Ok(())
}

/// The range over `values` and `include`, with 8% of headroom above and,
/// unless it starts at 0 (the bars' base), below; a single value gets a
/// range around it.
pub(super) fn range(values: impl IntoIterator<Item = f64>, include: &[f64]) -> Range<f64> {
    let all = values.into_iter().chain(include.iter().copied());
    let (lo, hi) = all.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
        (l.min(v), h.max(v))
    });
    let (lo, hi) = if lo <= hi { (lo, hi) } else { (0.0, 1.0) };
    let pad = if hi == 0.0 { 1.0 } else { hi.abs() * 0.5 };
    let flat = hi - lo < 1e-12 * hi.abs().max(lo.abs()).max(1e-300);
    let (lo, hi) = match (flat, lo >= 0.0) {
        (false, _) => (lo, hi),
        (true, true) => (lo, hi + pad),
        (true, false) => (lo - pad, hi),
    };
    let below = if lo != 0.0 { 0.08 * (hi - lo) } else { 0.0 };
    lo - below..hi + 0.08 * (hi - lo)
}

/// A linear axis ticked at given values, each tick with its label.
/// (Plotters' `WithKeyPoints` keeps no labels, and an axis of f64 has no
/// formatter for the mesh to give them.)
#[derive(Clone)]
pub(crate) struct Ticked(pub RangedCoordf64, pub Vec<(f64, String)>);

impl Ticked {
    /// The axis over `r` with at most `n` of plotters' ticks, labelled as
    /// percentages when `percent`, with the decimals of the tick step.
    pub fn numeric(r: &Range<f64>, n: usize, percent: bool) -> Ticked {
        let ticks = RangedCoordf64::from(r.clone()).key_points(n);
        let step = ticks.windows(2).map(|w| w[1] - w[0]).next().unwrap_or(1.0);
        let scale = if percent { 100.0 } else { 1.0 };
        let d = (-(step * scale).log10() - 1e-9).ceil().clamp(0.0, 9.0) as usize;
        let label = |v: f64| {
            let v = [v * scale, 0.0][usize::from(v.abs() < step * 1e-6)];
            format!("{v:.d$}{}", if percent { "%" } else { "" })
        };
        let labelled = ticks.into_iter().map(|v| (v, label(v))).collect();
        Ticked(r.clone().into(), labelled)
    }

    /// The axis over categories `0..n` of `names`, each a unit wide,
    /// ticked at its centre with its name.
    pub fn categories(names: &[String]) -> Ticked {
        let centre = |(i, name): (usize, &String)| (i as f64 + 0.5, name.clone());
        let ticks = names.iter().enumerate().map(centre).collect();
        Ticked((0.0..names.len() as f64).into(), ticks)
    }
}

impl Ranged for Ticked {
    type FormatOption = NoDefaultFormatting;
    type ValueType = f64;

    fn map(&self, v: &f64, limit: (i32, i32)) -> i32 {
        self.0.map(v, limit)
    }

    fn key_points<H: KeyPointHint>(&self, hint: H) -> Vec<f64> {
        let light = hint.weight().allow_light_points();
        self.1.iter().map(|t| t.0).filter(|_| !light).collect()
    }

    fn range(&self) -> Range<f64> {
        self.0.range()
    }
}

impl ValueFormatter<f64> for Ticked {
    fn format_ext(&self, v: &f64) -> String {
        let near = self.1.iter().find(|t| (t.0 - v).abs() < 1e-9);
        near.map(|t| t.1.clone()).unwrap_or_default()
    }
}

/// A value as printed by its bar, point or cell: two or three significant
/// digits (by the magnitude after rounding: 0.99996 is "1.0").
pub(super) fn value_label(v: f64, percent: bool) -> String {
    let shown = if percent { v * 100.0 } else { v };
    let d = [99.5, 0.995, 0.0995]
        .iter()
        .take_while(|&&t| shown.abs() < t)
        .count();
    let d = if shown == 0.0 { 0 } else { d };
    format!("{shown:.d$}{}", if percent { "%" } else { "" })
}

/// The mesh as every chart has it: the chart font, light grid lines at the
/// ticks only.
pub(crate) fn style_mesh<X: Ranged, Y: Ranged, DB: DrawingBackend>(
    m: &mut plotters::chart::MeshStyle<'_, '_, X, Y, DB>,
) {
    m.label_style(font(LABEL, false).color(&BLACK));
    m.axis_desc_style(font(LABEL + 1, false).color(&BLACK));
    m.bold_line_style(GRID.stroke_width(1));
    m.light_line_style(TRANSPARENT);
}

/// Every chart's `ChartBuilder`: label areas `left` wide and `bottom` high,
/// margins `top` and `right` (for the paper's labels).
pub(crate) fn builder<DB: DrawingBackend>(area: &Area<DB>, pad: Pad) -> ChartBuilder<'_, '_, DB> {
    let (left, bottom, top, right) = pad;
    let mut b = ChartBuilder::on(area);
    b.margin_top(top as u32).margin_left(6).margin_bottom(8);
    b.margin_right(right as u32).y_label_area_size(left as u32);
    b.x_label_area_size(bottom as u32);
    b
}

/// The width of a y label area over `r`: the axis label and the widest of
/// the tick labels of [`Ticked::numeric`].
pub(super) fn y_area(r: &Range<f64>, percent: bool) -> f64 {
    let ticks = Ticked::numeric(r, 8, percent).1;
    let width = |t: &(f64, String)| text_size(&t.1, LABEL, false).0;
    ticks.iter().map(width).fold(0.0, f64::max) + 44.0
}

/// The plot's rectangle in pixels.
pub(super) fn plot_rect<DB: DrawingBackend, X: Ranged, Y: Ranged>(
    chart: &ChartContext<'_, DB, Cartesian2d<X, Y>>,
) -> Rect {
    let ((x, y), f) = (chart.plotting_area().get_pixel_range(), f64::from);
    (f(x.start), f(y.start), f(x.end), f(y.end))
}

/// Values to pixels.
pub(super) type At<'a> = dyn Fn(f64, f64) -> (f64, f64) + 'a;

/// The pixel of each value in `chart`, through a copy of its mapping, so
/// that the chart stays free to draw on.
pub(super) fn pixel_of<DB: DrawingBackend, X, Y>(
    chart: &ChartContext<'_, DB, Cartesian2d<X, Y>>,
) -> impl Fn(f64, f64) -> (f64, f64)
where
    X: Ranged<ValueType = f64> + Clone,
    Y: Ranged<ValueType = f64> + Clone,
{
    let map = chart.as_coord_spec().clone();
    move |x, y| {
        let (x, y) = map.translate(&(x, y));
        (f64::from(x), f64::from(y))
    }
}

/// The rectangle in pixels between the values `a` and `b`, which `pixel`
/// maps to pixels ([`pixel_of`]).
pub(super) fn rect_of(
    pixel: impl Fn(f64, f64) -> (f64, f64),
    a: (f64, f64),
    b: (f64, f64),
) -> Rect {
    let (p, q) = (pixel(a.0, a.1), pixel(b.0, b.1));
    (p.0.min(q.0), p.1.min(q.1), p.0.max(q.0), p.1.max(q.1))
}

/// Labels placed where they hide nothing already placed or taken.
#[derive(Default)]
pub(super) struct Placer(Vec<Rect>);

impl Placer {
    /// Keeps labels off `r`.
    pub fn take(&mut self, r: Rect) {
        self.0.push(r);
    }

    /// Keeps labels `pad` pixels off the polyline through `points`.
    pub fn take_path(&mut self, points: &[(f64, f64)], pad: f64) {
        for w in points.windows(2) {
            let ((x0, y0), (x1, y1)) = (w[0], w[1]);
            let n = ((x1 - x0).hypot(y1 - y0) / 4.0).ceil().max(1.0);
            for t in (0..=n as u32).map(|k| f64::from(k) / n) {
                self.take(around((x0 + t * (x1 - x0), y0 + t * (y1 - y0)), (pad, pad)));
            }
        }
    }

    /// The first of `candidates` inside `b` that covers nothing taken, now
    /// taken itself; None if every one would.
    pub fn place(&mut self, candidates: impl IntoIterator<Item = Rect>, b: Rect) -> Option<Rect> {
        let inside = |r: &Rect| r.0 >= b.0 && r.1 >= b.1 && r.2 <= b.2 && r.3 <= b.3;
        let apart = |r: &Rect, t: &Rect| r.2 <= t.0 || r.0 >= t.2 || r.3 <= t.1 || r.1 >= t.3;
        let free = |r: &Rect| inside(r) && self.0.iter().all(|t| apart(r, t));
        let found = candidates.into_iter().find(free)?;
        self.0.push(found);
        Some(found)
    }

    /// Draws each label in `SMALL` at the first of its candidates that is
    /// free (reading upwards in a rectangle taller than wide that the text
    /// does not fit across); a label with none free is left out.
    pub fn draw_all<DB: DrawingBackend>(
        &mut self,
        root: &Area<DB>,
        labels: Vec<(Vec<Rect>, &str, RGBColor)>,
        bounds: Rect,
    ) -> Drawn<DB> {
        for (candidates, text, colour) in labels {
            let Some(r) = self.place(candidates, bounds) else {
                continue;
            };
            let up = r.3 - r.1 > r.2 - r.0 && text_size(text, SMALL, false).0 > r.2 - r.0 + 1.0;
            let s = style(SMALL, false, colour, H::Center, V::Center);
            let turn = [FontTransform::None, FontTransform::Rotate270];
            let s = s.transform(turn[usize::from(up)].clone());
            root.draw_text(text, &s, px((r.0 + r.2) / 2.0, (r.1 + r.3) / 2.0))?;
        }
        Ok(())
    }
}

/// Rectangles for `text` (reading upwards if `upright`) centred on `x`,
/// the first touching row `y0`, then moving up (`up`) or down in steps of
/// 3 pixels, up to `n` of them, not past row `limit`.
pub(super) fn column(
    x: f64,
    (y0, up, limit): (f64, bool, f64),
    text: (&str, bool),
    n: u32,
) -> Vec<Rect> {
    let (w, h) = text_size(text.0, SMALL, false);
    let (w, h) = if text.1 { (h, w) } else { (w, h) };
    let sign = if up { -1.0 } else { 1.0 };
    let centre = |k: u32| (x, y0 + sign * (h / 2.0 + 3.0 * f64::from(k)));
    let inside = |r: &Rect| if up { r.1 >= limit } else { r.3 <= limit };
    let rects = (0..n).map(|k| around(centre(k), (w / 2.0, h / 2.0)));
    rects.take_while(inside).collect()
}

/// Rectangles for `text` beside `at` at `d` pixels (right, then left),
/// then under and over it (`n` places each way), inside `b`.
pub(super) fn beside(at: (f64, f64), d: f64, text: &str, n: u32, b: Rect) -> Vec<Rect> {
    let (w, h) = text_size(text, SMALL, false);
    let side = |s: f64| around((at.0 + s * (d + w / 2.0), at.1), (w / 2.0, h / 2.0));
    let under = column(at.0, (at.1 + d, false, b.3), (text, false), n);
    let over = column(at.0, (at.1 - d, true, b.1), (text, false), n);
    let sides = [side(1.0), side(-1.0)];
    sides.into_iter().chain(under).chain(over).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_avoid_what_is_taken() {
        let (mut p, bounds) = (Placer::default(), (0.0, 0.0, 100.0, 100.0));
        p.take((0.0, 50.0, 30.0, 100.0));
        let up =
            |p: &mut Placer| p.place(column(15.0, (60.0, true, 0.0), ("x", false), 400), bounds);
        assert!(up(&mut p).expect("room above").3 <= 50.0);
        p.take((0.0, 0.0, 30.0, 50.0));
        assert_eq!(up(&mut p), None);
    }

    #[test]
    fn ranges_hold_everything_with_headroom() {
        let r = range([0.039, 0.02, -0.02], &[0.0]);
        assert!(r.start < -0.02 && r.end > 0.039, "{r:?}");
        assert_eq!(range([0.0, 0.0], &[0.0]), 0.0..1.08);
        let r = range([-3.0], &[]);
        assert!(r.start < -3.0 && r.end > -3.0, "{r:?}");
    }

    #[test]
    fn numbers_have_the_digits_they_need() {
        let labels = |r: Range<f64>, percent, at: [f64; 3]| {
            let axis = Ticked::numeric(&r, 8, percent);
            at.map(|v| axis.format_ext(&v))
        };
        let want = ["0%", "-2%", "4%"];
        assert_eq!(labels(-0.03..0.05, true, [0.0, -0.02, 0.04]), want);
        let want = ["0.0", "0.2", "1.2"];
        assert_eq!(labels(0.0..1.3, false, [0.0, 0.2, 1.2]), want);
        let percent = |v| value_label(v, true);
        let shown = [0.039, -0.0213, 0.00123, 0.009999999999999998].map(percent);
        assert_eq!(shown, ["3.9%", "-2.1%", "0.12%", "1.0%"]);
        let shown = [0.0999, 0.0, 1234.4].map(|v| value_label(v, false));
        assert_eq!(shown, ["0.10", "0", "1234"]);
    }
}
