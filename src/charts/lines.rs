//! Line charts ([`draw_lines`]).
//!
//! Each series is a line in its colour through its values, with a filled
//! marker of its own shape (circle, square, triangle, diamond, downward
//! triangle, repeating) on every point; a missing value breaks the line.
//! The x axis is numeric (round ticks) or, with `x_ticks`, labelled at the
//! x positions; labels that would overlap are turned vertical, and when
//! even vertical ones would, only every second (third, ...) one is shown.
//! A paper mark of one x position is the series' shape, hollow and larger,
//! on a short dashed line, labelled beside it where there is room.

use super::axis::{draw_y_axis, y_axis_width, Frame, YAxis};
use super::canvas::{
    column, style, text_size, Canvas, Placer, Shape, GRID, LABEL_SIZE, REFERENCE, SMALL_SIZE,
};
use super::legend::{
    draw_legend, draw_paper_lines, draw_title, legend_height, paper_entry, paper_margin,
    title_height, Entry, Swatch,
};
use super::{
    check_marks, check_series, is_svg, mark_colour, save, series_colour, who, LineChart, Picture,
};
use crate::fonts::register_fonts;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};
use std::path::Path;

/// Width of the picture in pixels.
const WIDTH: f64 = 1400.0;
/// Lowest picture in pixels.
const MIN_HEIGHT: f64 = 700.0;
/// Lowest plot in pixels.
const MIN_PLOT_H: f64 = 430.0;
/// Radius of a data point's marker.
const POINT_R: f64 = 5.0;
/// Radius of a paper mark's hollow marker.
const PAPER_R: f64 = 8.0;

/// Draws `chart` into `path`, a PNG or an SVG by the file's extension
/// (`.png`, `.svg`, in any case).
///
/// Errors (starting with `drawing <title>:` or naming the file): another
/// extension; no x positions or no series; a non-finite x or one not
/// greater than the one before; tick labels whose count is not the x
/// count; a series with a value count other than the x count or with a
/// non-finite value; a paper mark of a series or x position that does not
/// exist or with a non-finite value; a non-finite reference; a file that
/// cannot be written.
pub fn draw_lines(chart: &LineChart, path: &Path) -> Result<(), String> {
    let svg = is_svg(path)?;
    let who = who(&chart.title);
    check(chart, &who)?;
    register_fonts().map_err(|e| format!("{who}: {e}"))?;
    save(&Layout::new(chart, &who), &who, path, svg)
}

/// The checks that keep [`Layout`] from drawing nonsense.
fn check(chart: &LineChart, who: &str) -> Result<(), String> {
    let n = chart.x.len();
    if let Some((i, x)) = chart.x.iter().enumerate().find(|(_, x)| !x.is_finite()) {
        return Err(format!("{who}: x[{i}] is the non-finite value {x}"));
    }
    if let Some(i) = (1..n).find(|&i| chart.x[i] <= chart.x[i - 1]) {
        return Err(format!(
            "{who}: the x positions must be strictly increasing, but x[{i}] = {} follows x[{}] = {}",
            chart.x[i],
            i - 1,
            chart.x[i - 1]
        ));
    }
    if let Some(ticks) = chart.x_ticks.as_ref().filter(|t| t.len() != n) {
        return Err(format!(
            "{who}: {} x tick labels for {n} x positions",
            ticks.len()
        ));
    }
    let name_of = |i: usize| match &chart.x_ticks {
        Some(t) => format!("x = {}", t[i]),
        None => format!("x = {}", chart.x[i]),
    };
    check_series(who, &chart.series, n, "x positions", name_of)?;
    check_marks(
        who,
        &chart.paper,
        chart.reference,
        chart.series.len(),
        n,
        "x positions",
    )
}

/// The ticks of the x axis: (position, label).
fn x_ticks(chart: &LineChart, lo: f64, hi: f64, max: usize) -> Vec<(f64, String)> {
    if let Some(labels) = &chart.x_ticks {
        return chart
            .x
            .iter()
            .copied()
            .zip(labels.iter().cloned())
            .collect();
    }
    // Round ticks as on the y axis.
    let y = YAxis::new([lo, hi], &[], false, max);
    let step = {
        let t = y.ticks();
        if t.len() > 1 {
            t[1] - t[0]
        } else {
            1.0
        }
    };
    let first = (lo / step - 1e-9).ceil() as i64;
    let last = (hi / step + 1e-9).floor() as i64;
    (first..=last)
        .map(|k| {
            let v = k as f64 * step;
            (v, y.label(v))
        })
        .collect()
}

/// The shape of a paper mark of `series` at one x position: the series'
/// shape, or a diamond for the whole chart.
fn paper_shape(series: Option<usize>) -> Shape {
    series.map_or(Shape::Diamond, Shape::of)
}

/// A line chart laid out in pixels.
struct Layout<'a> {
    chart: &'a LineChart,
    who: &'a str,
    height: f64,
    frame: Frame,
    /// The x range of the plot.
    x_lo: f64,
    x_hi: f64,
    /// The x ticks (position, label).
    ticks: Vec<(f64, String)>,
    /// Tick labels are vertical.
    rotate: bool,
    /// Every how many tick labels one is shown.
    every: usize,
    legend: Vec<Entry>,
}

impl<'a> Layout<'a> {
    fn new(chart: &'a LineChart, who: &'a str) -> Self {
        let data = chart
            .series
            .iter()
            .flat_map(|s| s.values.iter().flatten().copied())
            .chain(chart.paper.iter().map(|m| m.value));
        let include = [chart.reference.unwrap_or(0.0)];
        let y = YAxis::new(data, &include, chart.percent, 8);
        let left = y_axis_width(&y);
        let right = paper_margin(&chart.paper);
        let plot_w = WIDTH - left - right;

        let (first, last) = (chart.x[0], chart.x[chart.x.len() - 1]);
        let pad = if last > first {
            0.04 * (last - first)
        } else if first != 0.0 {
            first.abs() * 0.5
        } else {
            1.0
        };
        let (x_lo, x_hi) = (first - pad, last + pad);
        let ticks = x_ticks(chart, x_lo, x_hi, (plot_w / 90.0) as usize);
        let to_px = |x: f64| (x - x_lo) / (x_hi - x_lo) * plot_w;
        let sizes: Vec<(f64, f64)> = ticks
            .iter()
            .map(|(_, l)| text_size(l, LABEL_SIZE, false))
            .collect();
        let gaps: Vec<f64> = ticks
            .windows(2)
            .map(|w| to_px(w[1].0) - to_px(w[0].0))
            .collect();
        let crowded = gaps
            .iter()
            .zip(sizes.windows(2))
            .any(|(gap, s)| *gap < (s[0].0 + s[1].0) / 2.0 + 10.0);
        let text_h = text_size("Ag", LABEL_SIZE, false).1;
        let narrowest = gaps.iter().copied().fold(f64::INFINITY, f64::min);
        let every = if crowded && narrowest < text_h + 4.0 {
            ((text_h + 4.0) / narrowest.max(1.0)).ceil() as usize
        } else {
            1
        };
        let widest = sizes.iter().map(|s| s.0).fold(0.0, f64::max);
        let tick_h = if crowded { widest } else { text_h } + 14.0;
        let x_label_h = if chart.x_label.is_empty() {
            0.0
        } else {
            text_h + 12.0
        };

        let mut legend: Vec<Entry> = chart
            .series
            .iter()
            .enumerate()
            .map(|(k, s)| Entry {
                label: s.name.clone(),
                swatch: Swatch::Line(series_colour(k), Shape::of(k)),
            })
            .collect();
        // The hollow mark as the first mark of one x position is drawn.
        let shape = chart
            .paper
            .iter()
            .find(|m| m.category.is_some())
            .map_or(Shape::Diamond, |m| paper_shape(m.series));
        legend.extend(paper_entry(&chart.paper, shape));
        let top = title_height(&chart.subtitle) + legend_height(&legend, left, plot_w) + 12.0;
        let bottom_h = tick_h + x_label_h + 12.0;
        let height = (top + MIN_PLOT_H + bottom_h).max(MIN_HEIGHT).round();
        Layout {
            chart,
            who,
            height,
            frame: Frame {
                left,
                top,
                right: WIDTH - right,
                bottom: height - bottom_h,
                y,
            },
            x_lo,
            x_hi,
            ticks,
            rotate: crowded,
            every,
            legend,
        }
    }

    /// The pixel column of `x`.
    fn px(&self, x: f64) -> f64 {
        let f = &self.frame;
        f.left + (x - self.x_lo) / (self.x_hi - self.x_lo) * (f.right - f.left)
    }
}

impl Picture for Layout<'_> {
    fn size(&self) -> (u32, u32) {
        (WIDTH as u32, self.height as u32)
    }

    fn render<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String>
    where
        DB::ErrorType: 'static,
    {
        let c = Canvas {
            area: root,
            who: self.who,
        };
        let f = &self.frame;
        let chart = self.chart;
        root.fill(&WHITE)
            .map_err(|e| format!("{}: {e}", self.who))?;

        draw_y_axis(&c, f, &chart.y_label)?;
        for (x, _) in &self.ticks {
            let x = self.px(*x);
            c.path(&[(x, f.top), (x, f.bottom)], GRID.stroke_width(1))?;
        }
        match chart.reference {
            Some(r) => {
                let y = f.py(r);
                c.path(&[(f.left, y), (f.right, y)], REFERENCE.stroke_width(2))?;
            }
            None if f.y.lo < 0.0 => {
                let y = f.py(0.0);
                c.path(&[(f.left, y), (f.right, y)], REFERENCE.stroke_width(1))?;
            }
            None => {}
        }

        // The series: lines through each run of present values, then the
        // points, kept free of labels.
        let mut placer = Placer::default();
        draw_paper_lines(&c, f, &chart.paper, &mut placer)?;
        for (k, s) in chart.series.iter().enumerate() {
            let colour = series_colour(k);
            let mut run: Vec<(f64, f64)> = Vec::new();
            for (x, v) in chart.x.iter().zip(&s.values) {
                match v {
                    Some(v) => run.push((self.px(*x), f.py(*v))),
                    None => {
                        if run.len() > 1 {
                            c.path(&run, colour.stroke_width(2))?;
                        }
                        run.clear();
                    }
                }
            }
            if run.len() > 1 {
                c.path(&run, colour.stroke_width(2))?;
            }
        }
        for (k, s) in chart.series.iter().enumerate() {
            for (x, v) in chart.x.iter().zip(&s.values) {
                let Some(v) = v else { continue };
                let (x, y) = (self.px(*x), f.py(*v));
                c.marker(Shape::of(k), (x, y), POINT_R, series_colour(k), false)?;
                placer.take((x - POINT_R, y - POINT_R, x + POINT_R, y + POINT_R));
            }
        }

        // The paper's values: lines across the plot, then marks at one x.
        let mut marks = Vec::new();
        for m in &chart.paper {
            let Some(i) = m.category else { continue };
            let (x, y) = (self.px(chart.x[i]), f.py(m.value));
            let colour = mark_colour(m.series);
            let ends = [(x - 2.0 * PAPER_R, y), (x + 2.0 * PAPER_R, y)];
            c.path(&ends, WHITE.stroke_width(5))?;
            c.dashed(&ends, 4, 2, colour.stroke_width(2))?;
            let shape = paper_shape(m.series);
            c.marker(shape, (x, y), PAPER_R, colour, true)?;
            placer.take((
                x - PAPER_R - 1.0,
                y - PAPER_R - 2.0,
                x + PAPER_R + 1.0,
                y + PAPER_R + 2.0,
            ));
            marks.push((x, y, m));
        }
        let bounds = (f.left, f.top, f.right, f.bottom);
        for (x, y, m) in marks {
            let (w, h) = text_size(&m.label, SMALL_SIZE, false);
            let d = 2.0 * PAPER_R + 4.0;
            let beside = [
                (x + d, y - h / 2.0, x + d + w, y + h / 2.0),
                (x - d - w, y - h / 2.0, x - d, y + h / 2.0),
            ];
            let candidates = beside
                .into_iter()
                .chain(column(x, y - d, w, h, true, f.top))
                .chain(column(x, y + d, w, h, false, f.bottom));
            if let Some(r) = placer.place(candidates, bounds) {
                let s = style(
                    SMALL_SIZE,
                    false,
                    mark_colour(m.series),
                    HPos::Center,
                    VPos::Center,
                );
                c.text(&m.label, &s, ((r.0 + r.2) / 2.0, (r.1 + r.3) / 2.0))?;
            }
        }

        // The x axis: ticks, their labels, the axis label.
        c.path(
            &[(f.left, f.bottom), (f.right, f.bottom)],
            BLACK.stroke_width(1),
        )?;
        for (k, (x, label)) in self.ticks.iter().enumerate() {
            let x = self.px(*x);
            c.path(&[(x, f.bottom), (x, f.bottom + 5.0)], BLACK.stroke_width(1))?;
            if k % self.every != 0 {
                continue;
            }
            if self.rotate {
                let s = style(LABEL_SIZE, false, BLACK, HPos::Right, VPos::Center)
                    .transform(FontTransform::Rotate270);
                c.text(label, &s, (x, f.bottom + 8.0))?;
            } else {
                let s = style(LABEL_SIZE, false, BLACK, HPos::Center, VPos::Top);
                c.text(label, &s, (x, f.bottom + 8.0))?;
            }
        }
        let text_h = text_size("Ag", LABEL_SIZE, false).1;
        let label_y = self.height - 12.0 - text_h;
        let s = style(LABEL_SIZE + 1, false, BLACK, HPos::Center, VPos::Top);
        c.text(&chart.x_label, &s, ((f.left + f.right) / 2.0, label_y))?;

        draw_legend(
            &c,
            &self.legend,
            f.left,
            title_height(&chart.subtitle),
            f.right - f.left,
        )?;
        draw_title(&c, &chart.title, &chart.subtitle, WIDTH)
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::{colours, scratch, svg_texts};
    use super::super::{PaperMark, Series};
    use super::*;

    /// IPC over the MSHR count for two policies, one with a gap, with the
    /// paper's value at one count and its baseline across the plot.
    fn mshrs() -> LineChart {
        let x = vec![28.0, 32.0, 40.0, 48.0, 64.0];
        LineChart {
            subtitle: "4 cores, 16 scenes".into(),
            x_ticks: Some(x.iter().map(|v| format!("{v}")).collect()),
            series: vec![
                Series::full("baseline", &[0.61, 0.64, 0.66, 0.67, 0.675]),
                Series::new(
                    "WaSP",
                    vec![Some(0.66), Some(0.68), None, Some(0.70), Some(0.705)],
                ),
            ],
            paper: vec![
                PaperMark::at(Some(1), 1, 0.69, "paper 0.69"),
                PaperMark::all(None, 0.6, "paper baseline 0.60"),
            ],
            ..LineChart::new("IPC by MSHR count", "MSHRs per core", "IPC", x)
        }
    }

    #[test]
    fn png_has_lines_in_the_series_colours() {
        let dir = scratch("lines-png");
        let path = dir.join("mshrs.png");
        draw_lines(&mshrs(), &path).expect("draw png");
        let img = image::open(&path).expect("png decodes");
        assert_eq!((img.width(), img.height()), (1400, 700));
        let (distinct, blue) = colours(&path, series_colour(0));
        assert!(distinct > 20, "{distinct} colours");
        assert!(blue > 300, "{blue} pixels of series 0's colour");
        let (_, orange) = colours(&path, series_colour(1));
        assert!(orange > 200, "{orange} pixels of series 1's colour");
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn svg_has_the_title_legend_and_paper_labels() {
        let dir = scratch("lines-svg");
        let path = dir.join("mshrs.svg");
        draw_lines(&mshrs(), &path).expect("draw svg");
        let texts = svg_texts(&std::fs::read_to_string(&path).expect("svg"));
        for text in [
            "IPC by MSHR count",
            "4 cores, 16 scenes",
            "MSHRs per core",
            "IPC",
            "baseline",
            "WaSP",
            "paper 0.69",
            "paper baseline 0.60",
            "28",
            "64",
        ] {
            assert!(texts.iter().any(|t| t == text), "no `{text}` in {texts:?}");
        }
        assert!(
            texts.iter().any(|t| t.starts_with("paper values")),
            "no paper legend entry in {texts:?}"
        );
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn numeric_axes_and_negative_percentages_draw() {
        let dir = scratch("lines-numeric");
        let mut chart = LineChart::new("Speedup", "window", "speedup", vec![1.0, 2.0, 4.0, 8.0]);
        chart.series = vec![Series::full("WaSP", &[-0.02, 0.01, 0.03, 0.02])];
        chart.percent = true;
        chart.reference = Some(0.0);
        let path = dir.join("speedup.svg");
        draw_lines(&chart, &path).expect("draw svg");
        let texts = svg_texts(&std::fs::read_to_string(&path).expect("svg"));
        for text in ["-2%", "0%", "3%", "2", "8"] {
            assert!(texts.iter().any(|t| t == text), "no `{text}` in {texts:?}");
        }
        // A single point.
        chart.x = vec![5.0];
        chart.series = vec![Series::full("WaSP", &[-0.01])];
        let path = dir.join("one.png");
        draw_lines(&chart, &path).expect("draw png");
        let (distinct, blue) = colours(&path, series_colour(0));
        assert!(distinct > 5 && blue > 20, "{distinct} colours, {blue} blue");
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn crowded_tick_labels_turn_vertical() {
        let x: Vec<f64> = (0..40).map(f64::from).collect();
        let mut chart = LineChart::new("Many", "scene", "value", x.clone());
        chart.x_ticks = Some(
            (0..40)
                .map(|i| format!("scene-{i:02}-with-a-name"))
                .collect(),
        );
        chart.series = vec![Series::full("v", &x)];
        let layout = Layout::new(&chart, "drawing Many");
        assert!(layout.rotate && layout.every == 1);
        assert!(layout.height > 700.0, "{}", layout.height);
        let dir = scratch("lines-crowded");
        draw_lines(&chart, &dir.join("many.png")).expect("draw png");
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn drawing_is_deterministic() {
        let dir = scratch("lines-same");
        for ext in ["png", "svg"] {
            let (a, b) = (dir.join(format!("a.{ext}")), dir.join(format!("b.{ext}")));
            draw_lines(&mshrs(), &a).expect("first");
            draw_lines(&mshrs(), &b).expect("second");
            assert_eq!(std::fs::read(&a).ok(), std::fs::read(&b).ok(), "{ext}");
        }
        std::fs::remove_dir_all(dir).ok();
    }

    /// The error of drawing `chart` into a fresh PNG; no file is written.
    fn error(chart: &LineChart, name: &str) -> String {
        let dir = scratch(name);
        let path = dir.join("chart.png");
        let e = draw_lines(chart, &path).expect_err(name);
        assert!(!path.exists(), "{name}: a file was written");
        std::fs::remove_dir_all(dir).ok();
        e
    }

    #[test]
    fn bad_charts_are_errors() {
        let good = mshrs();
        let mut c = good.clone();
        c.x.clear();
        c.x_ticks = None;
        c.series.clear();
        let e = error(&c, "lines-empty");
        assert!(e.starts_with("drawing IPC by MSHR count:"), "{e}");
        assert!(e.contains("no x positions"), "{e}");

        let mut c = good.clone();
        c.x[2] = 32.0;
        let e = error(&c, "lines-order");
        assert!(
            e.contains("strictly increasing") && e.contains("x[2] = 32"),
            "{e}"
        );

        let mut c = good.clone();
        c.x[4] = f64::NAN;
        assert!(error(&c, "lines-nan-x").contains("x[4] is the non-finite value NaN"));

        let mut c = good.clone();
        c.x_ticks = Some(vec!["28".into()]);
        assert!(error(&c, "lines-ticks").contains("1 x tick labels for 5 x positions"));

        let mut c = good.clone();
        c.series[0].values.push(Some(1.0));
        let e = error(&c, "lines-length");
        assert!(
            e.contains("`baseline` has 6 values for 5 x positions"),
            "{e}"
        );

        let mut c = good.clone();
        c.series[1].values[4] = Some(f64::NEG_INFINITY);
        let e = error(&c, "lines-inf");
        assert!(
            e.contains("`WaSP`") && e.contains("-inf") && e.contains("x = 64"),
            "{e}"
        );

        let mut c = good.clone();
        c.paper.push(PaperMark::at(Some(0), 5, 0.7, "past"));
        let e = error(&c, "lines-mark");
        assert!(
            e.contains("`past` is at index 5") && e.contains("5 x positions"),
            "{e}"
        );

        let mut c = good;
        c.paper.push(PaperMark::all(Some(7), 0.7, "nobody"));
        assert!(error(&c, "lines-mark-series").contains("`nobody` belongs to series 7"));
    }

    #[test]
    fn bad_files_are_errors() {
        let dir = scratch("lines-files");
        let e = draw_lines(&mshrs(), &dir.join("chart.pdf")).expect_err("pdf");
        assert!(e.contains("chart.pdf") && e.contains(".png or .svg"), "{e}");
        let e = draw_lines(&mshrs(), &dir.join("none").join("c.png")).expect_err("dir");
        assert!(e.starts_with("writing ") && e.contains("c.png"), "{e}");
        std::fs::remove_dir_all(dir).ok();
    }
}
