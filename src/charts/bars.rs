//! Grouped bar charts ([`draw_bars`]).
//!
//! Each category has a group of equal width holding one bar per series
//! (left to right in series order, in the series' colour), centred, from 0
//! to the value. Highlighted categories have a light grey band behind the
//! group and a bold name; separators are dotted vertical lines between
//! groups. With at most three series and twenty categories each bar has
//! its value printed over it (under it when negative; vertical when wider
//! than the bar), unless that would cover another bar, mark or label.

use super::axis::{draw_y_axis, value_label, y_axis_width, Frame, YAxis};
use super::canvas::{
    column, style, text_size, Canvas, Placer, Rect, Shape, LABEL_SIZE, REFERENCE, SMALL_SIZE,
};
use super::legend::{
    draw_legend, draw_paper_lines, draw_title, legend_height, paper_entry, paper_margin,
    title_height, Entry, Swatch,
};
use super::{
    check_marks, check_series, dark, is_svg, mark_colour, save, series_colour, who, BarChart,
    Picture,
};
use crate::fonts::register_fonts;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};
use std::path::Path;

/// Narrowest and widest picture in pixels.
const WIDTH: (f64, f64) = (900.0, 1800.0);
/// Lowest picture in pixels.
const MIN_HEIGHT: f64 = 700.0;
/// Lowest plot in pixels.
const MIN_PLOT_H: f64 = 430.0;
/// Widest bar in pixels.
const MAX_BAR: f64 = 64.0;
/// Background of highlighted categories.
const BAND: RGBColor = RGBColor(236, 236, 236);
/// Colour of the separators.
const SEPARATOR: RGBColor = RGBColor(90, 90, 90);

/// Draws `chart` into `path`, a PNG or an SVG by the file's extension
/// (`.png`, `.svg`, in any case).
///
/// Errors (starting with `drawing <title>:` or naming the file): another
/// extension; no categories or no series; a series with a value count
/// other than the category count or with a non-finite value; a paper mark
/// of a series or category that does not exist or with a non-finite value;
/// a non-finite reference; a separator past the category count or a
/// highlight past the last category; a file that cannot be written.
pub fn draw_bars(chart: &BarChart, path: &Path) -> Result<(), String> {
    let svg = is_svg(path)?;
    let who = who(&chart.title);
    check(chart, &who)?;
    register_fonts().map_err(|e| format!("{who}: {e}"))?;
    save(&Layout::new(chart, &who), &who, path, svg)
}

/// The checks that keep [`Layout`] from drawing nonsense.
fn check(chart: &BarChart, who: &str) -> Result<(), String> {
    let n = chart.categories.len();
    check_series(who, &chart.series, n, "categories", |i| {
        format!("category `{}`", chart.categories[i])
    })?;
    check_marks(
        who,
        &chart.paper,
        chart.reference,
        chart.series.len(),
        n,
        "categories",
    )?;
    if let Some(i) = chart.separators.iter().find(|&&i| i > n) {
        return Err(format!(
            "{who}: a separator before category {i}, but there are {n} categories"
        ));
    }
    if let Some(i) = chart.highlight.iter().find(|&&i| i >= n) {
        return Err(format!(
            "{who}: highlighted category {i}, but there are {n} categories"
        ));
    }
    Ok(())
}

/// A bar chart laid out in pixels.
struct Layout<'a> {
    chart: &'a BarChart,
    who: &'a str,
    width: f64,
    height: f64,
    frame: Frame,
    /// Width of a category's group.
    group: f64,
    /// Width of a bar.
    bar: f64,
    /// Category names are vertical.
    rotate: bool,
    /// Values are printed over the bars.
    values: bool,
    legend: Vec<Entry>,
}

impl<'a> Layout<'a> {
    fn new(chart: &'a BarChart, who: &'a str) -> Self {
        let n = chart.categories.len();
        let s = chart.series.len().max(1);
        let values = chart.series.len() <= 3 && n <= 20;

        let data: Vec<f64> = chart
            .series
            .iter()
            .flat_map(|s| s.values.iter().flatten().copied())
            .chain(chart.paper.iter().map(|m| m.value))
            .collect();
        let mut include = vec![0.0];
        include.extend(chart.reference);
        if values {
            // Room over the tallest bar for its value.
            let (lo, hi) = data
                .iter()
                .chain(&include)
                .fold((0.0f64, 0.0f64), |(lo, hi), &v| (lo.min(v), hi.max(v)));
            if hi > 0.0 {
                include.push(hi + 0.06 * (hi - lo));
            }
            if lo < 0.0 {
                include.push(lo - 0.06 * (hi - lo));
            }
        }
        let y = YAxis::new(data.iter().copied(), &include, chart.percent, 8);

        let left = y_axis_width(&y);
        let right = paper_margin(&chart.paper);
        let bar_want = if s <= 3 { 24.0 } else { 17.0 };
        let group_want = (s as f64 * bar_want + 18.0).clamp(44.0, 140.0);
        let width = (left + n as f64 * group_want + right)
            .clamp(WIDTH.0, WIDTH.1)
            .round();
        let group = (width - left - right) / n as f64;
        let bar = (group * 0.8 / s as f64).min(MAX_BAR);

        let highlighted = |i: usize| chart.highlight.contains(&i);
        let widest = chart
            .categories
            .iter()
            .enumerate()
            .map(|(i, c)| text_size(c, LABEL_SIZE, highlighted(i)).0)
            .fold(0.0, f64::max);
        let rotate = widest > group - 6.0;
        let label_h = if rotate {
            widest + 16.0
        } else {
            text_size("Ag", LABEL_SIZE, false).1 + 16.0
        };

        let mut legend: Vec<Entry> = chart
            .series
            .iter()
            .enumerate()
            .map(|(k, s)| Entry {
                label: s.name.clone(),
                swatch: Swatch::Block(series_colour(k)),
            })
            .collect();
        legend.extend(paper_entry(&chart.paper, Shape::Diamond));
        let title_h = title_height(&chart.subtitle);
        let top = title_h + legend_height(&legend, left, width - left - right) + 12.0;
        let height = (top + MIN_PLOT_H + label_h + 12.0).max(MIN_HEIGHT).round();
        let frame = Frame {
            left,
            top,
            right: width - right,
            bottom: height - label_h - 12.0,
            y,
        };
        Layout {
            chart,
            who,
            width,
            height,
            frame,
            group,
            bar,
            rotate,
            values,
            legend,
        }
    }

    /// The left edge of category `i`'s group.
    fn group_x(&self, i: usize) -> f64 {
        self.frame.left + i as f64 * self.group
    }

    /// The left edge of series `k`'s bar in category `i`'s group.
    fn bar_x(&self, i: usize, k: usize) -> f64 {
        let s = self.chart.series.len() as f64;
        self.group_x(i) + (self.group - s * self.bar) / 2.0 + k as f64 * self.bar
    }
}

impl Picture for Layout<'_> {
    fn size(&self) -> (u32, u32) {
        (self.width as u32, self.height as u32)
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

        for &i in &chart.highlight {
            c.rect(
                (self.group_x(i), f.top),
                (self.group_x(i + 1), f.bottom),
                BAND.filled(),
            )?;
        }
        draw_y_axis(&c, f, &chart.y_label)?;
        for &i in &chart.separators {
            let x = self.group_x(i);
            c.dashed(
                &[(x, f.top), (x, f.bottom)],
                3,
                4,
                SEPARATOR.stroke_width(2),
            )?;
        }

        // The bars, kept free of labels.
        let mut placer = Placer::default();
        let zero = f.py(0.0);
        let inset = if self.bar > 8.0 { 1.0 } else { 0.0 };
        for (k, s) in chart.series.iter().enumerate() {
            for (i, v) in s.values.iter().enumerate() {
                let Some(v) = *v else { continue };
                let x0 = self.bar_x(i, k) + inset;
                let x1 = self.bar_x(i, k + 1) - inset;
                let y = f.py(v);
                // At least a pixel, so a zero still shows.
                let (y0, y1) = if (y - zero).abs() < 1.0 {
                    (zero - 1.0, zero)
                } else {
                    (y.min(zero), y.max(zero))
                };
                c.rect((x0, y0), (x1, y1), series_colour(k).filled())?;
                placer.take((x0, y0, x1, y1));
            }
        }
        c.path(
            &[(f.left, zero), (f.right, zero)],
            REFERENCE.stroke_width(1),
        )?;
        if let Some(r) = chart.reference {
            let y = f.py(r);
            c.path(&[(f.left, y), (f.right, y)], REFERENCE.stroke_width(2))?;
        }

        // The paper's values: lines across the plot, then marks per
        // category (a short dashed line over the bar or group with a
        // hollow diamond on it).
        draw_paper_lines(&c, f, &chart.paper, &mut placer)?;
        let mut marks: Vec<(Rect, usize)> = Vec::new();
        for (m_i, m) in chart.paper.iter().enumerate() {
            let Some(i) = m.category else { continue };
            let (x0, x1) = match m.series {
                Some(k) => (self.bar_x(i, k) - 3.0, self.bar_x(i, k + 1) + 3.0),
                None => (self.group_x(i) + 3.0, self.group_x(i + 1) - 3.0),
            };
            let (x, y) = ((x0 + x1) / 2.0, f.py(m.value));
            let colour = mark_colour(m.series);
            c.path(&[(x0, y), (x1, y)], WHITE.stroke_width(5))?;
            c.dashed(&[(x0, y), (x1, y)], 4, 2, colour.stroke_width(2))?;
            c.marker(Shape::Diamond, (x, y), 5.0, colour, true)?;
            let r = (x - 7.0, y - 8.0, x + 7.0, y + 8.0);
            placer.take(r);
            marks.push((r, m_i));
        }

        // Values over the bars, then the paper marks' labels over the
        // marks, where they hide nothing.
        let bounds = (f.left, f.top, f.right, f.bottom);
        if self.values {
            for (k, s) in chart.series.iter().enumerate() {
                for (i, v) in s.values.iter().enumerate() {
                    let Some(v) = *v else { continue };
                    let text = value_label(v, chart.percent);
                    let (w, h) = text_size(&text, SMALL_SIZE, false);
                    let rotate = w > self.bar + 2.0;
                    let (rw, rh) = if rotate { (h, w) } else { (w, h) };
                    let x = self.bar_x(i, k) + self.bar / 2.0;
                    let up = v >= 0.0;
                    let y = if up { f.py(v) - 2.0 } else { f.py(v) + 2.0 };
                    let limit = if up { f.top } else { f.bottom };
                    let Some(r) = placer.place(column(x, y, rw, rh, up, limit), bounds) else {
                        continue;
                    };
                    let colour = dark(series_colour(k));
                    if rotate {
                        let s = style(SMALL_SIZE, false, colour, HPos::Left, VPos::Center)
                            .transform(FontTransform::Rotate270);
                        c.text(&text, &s, ((r.0 + r.2) / 2.0, r.3))?;
                    } else {
                        let s = style(SMALL_SIZE, false, colour, HPos::Center, VPos::Center);
                        c.text(&text, &s, ((r.0 + r.2) / 2.0, (r.1 + r.3) / 2.0))?;
                    }
                }
            }
        }
        for (r, m_i) in marks {
            let m = &chart.paper[m_i];
            let (w, h) = text_size(&m.label, SMALL_SIZE, false);
            let x = (r.0 + r.2) / 2.0;
            let above = column(x, r.1, w, h, true, f.top);
            let below = column(x, r.3, w, h, false, f.bottom);
            if let Some(p) = placer.place(above.into_iter().chain(below), bounds) {
                let s = style(
                    SMALL_SIZE,
                    false,
                    mark_colour(m.series),
                    HPos::Center,
                    VPos::Center,
                );
                c.text(&m.label, &s, ((p.0 + p.2) / 2.0, (p.1 + p.3) / 2.0))?;
            }
        }

        // The x axis and the category names.
        c.path(
            &[(f.left, f.bottom), (f.right, f.bottom)],
            BLACK.stroke_width(1),
        )?;
        for (i, name) in chart.categories.iter().enumerate() {
            let x = self.group_x(i) + self.group / 2.0;
            let bold = chart.highlight.contains(&i);
            c.path(&[(x, f.bottom), (x, f.bottom + 4.0)], BLACK.stroke_width(1))?;
            if self.rotate {
                let s = style(LABEL_SIZE, bold, BLACK, HPos::Right, VPos::Center)
                    .transform(FontTransform::Rotate270);
                c.text(name, &s, (x, f.bottom + 8.0))?;
            } else {
                let s = style(LABEL_SIZE, bold, BLACK, HPos::Center, VPos::Top);
                c.text(name, &s, (x, f.bottom + 8.0))?;
            }
        }

        draw_legend(
            &c,
            &self.legend,
            f.left,
            title_height(&chart.subtitle),
            f.right - f.left,
        )?;
        draw_title(&c, &chart.title, &chart.subtitle, self.width)
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::{colours, scratch, svg_texts};
    use super::super::{PaperMark, Series};
    use super::*;

    /// Sixteen scenes with long names and two means, two series of
    /// speedups (one negative), the paper's mean and per-scene values.
    fn speedups() -> BarChart {
        let mut categories: Vec<String> = (0..16)
            .map(|i| format!("scene-{i:02}-with-a-long-name"))
            .collect();
        categories.truncate(16);
        categories.push("mean 3D".into());
        categories.push("mean all".into());
        let wasp: Vec<f64> = (0..18).map(|i| 0.01 * f64::from(i % 7) - 0.02).collect();
        let full: Vec<Option<f64>> = (0..18)
            .map(|i| (i != 3).then_some(0.005 * f64::from(i % 5)))
            .collect();
        BarChart {
            subtitle: "shared-tile machine, 16 scenes".into(),
            series: vec![
                Series::full("WaSP", &wasp),
                Series::new("Fullpriority", full),
            ],
            paper: vec![
                PaperMark::all(Some(0), 0.039, "paper 3.9%"),
                PaperMark::all(None, 0.05, "paper best 5.0%"),
                PaperMark::at(Some(1), 16, 0.02, "paper 2.0%"),
                PaperMark::at(None, 17, -0.01, "paper -1.0%"),
            ],
            percent: true,
            reference: Some(0.0),
            separators: vec![16],
            highlight: vec![16, 17],
            ..BarChart::new("Speedup over the baseline", "speedup", categories)
        }
    }

    #[test]
    fn png_has_bars_in_the_series_colours() {
        let dir = scratch("bars-png");
        let path = dir.join("speedup.png");
        draw_bars(&speedups(), &path).expect("draw png");
        let img = image::open(&path).expect("png decodes");
        let (w, h) = (img.width(), img.height());
        assert!(
            (900..=1800).contains(&w) && (700..=1000).contains(&h),
            "{w}x{h}"
        );
        let (distinct, blue) = colours(&path, series_colour(0));
        assert!(distinct > 20, "{distinct} colours");
        assert!(blue > 500, "{blue} pixels of series 0's colour");
        let (_, orange) = colours(&path, series_colour(1));
        assert!(orange > 200, "{orange} pixels of series 1's colour");
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn svg_has_the_title_legend_and_paper_labels() {
        let dir = scratch("bars-svg");
        let path = dir.join("speedup.svg");
        draw_bars(&speedups(), &path).expect("draw svg");
        let texts = svg_texts(&std::fs::read_to_string(&path).expect("svg"));
        for text in [
            "Speedup over the baseline",
            "shared-tile machine, 16 scenes",
            "speedup",
            "WaSP",
            "Fullpriority",
            "paper 3.9%",
            "paper best 5.0%",
            "mean 3D",
            "scene-15-with-a-long-name",
            "0%",
            "-2%",
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
    fn values_are_printed_for_few_series() {
        let dir = scratch("bars-values");
        let path = dir.join("few.svg");
        let mut chart = BarChart::new("IPC", "IPC", vec!["a".into(), "b".into(), "c".into()]);
        chart.series = vec![Series::full("ours", &[1.25, 0.5, 2.0])];
        draw_bars(&chart, &path).expect("draw svg");
        let texts = svg_texts(&std::fs::read_to_string(&path).expect("svg"));
        for text in ["1.2", "0.50", "2.0"] {
            assert!(texts.iter().any(|t| t == text), "no `{text}` in {texts:?}");
        }
        // Four series: no values.
        chart.series = (0..4)
            .map(|k| Series::full(format!("s{k}"), &[1.25, 0.5, 2.0]))
            .collect();
        draw_bars(&chart, &path).expect("draw svg");
        let texts = svg_texts(&std::fs::read_to_string(&path).expect("svg"));
        assert!(!texts.iter().any(|t| t == "0.50"), "{texts:?}");
        assert!(texts.iter().any(|t| t == "s3"), "{texts:?}");
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn negative_values_and_one_category_draw() {
        let dir = scratch("bars-negative");
        let mut chart = BarChart::new("Slowdown", "speedup", vec!["only".into()]);
        chart.series = vec![Series::full("WaSP", &[-0.02])];
        chart.percent = true;
        let path = dir.join("one.png");
        draw_bars(&chart, &path).expect("draw png");
        let (distinct, blue) = colours(&path, series_colour(0));
        assert!(
            distinct > 5 && blue > 100,
            "{distinct} colours, {blue} blue"
        );
        let path = dir.join("one.svg");
        draw_bars(&chart, &path).expect("draw svg");
        let texts = svg_texts(&std::fs::read_to_string(&path).expect("svg"));
        assert!(texts.iter().any(|t| t == "-2.0%"), "{texts:?}");
        assert!(texts.iter().any(|t| t == "0.0%"), "{texts:?}");
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn drawing_is_deterministic() {
        let dir = scratch("bars-same");
        for ext in ["png", "svg"] {
            let (a, b) = (dir.join(format!("a.{ext}")), dir.join(format!("b.{ext}")));
            draw_bars(&speedups(), &a).expect("first");
            draw_bars(&speedups(), &b).expect("second");
            assert_eq!(std::fs::read(&a).ok(), std::fs::read(&b).ok(), "{ext}");
        }
        std::fs::remove_dir_all(dir).ok();
    }

    /// The error of drawing `chart` into a fresh SVG; no file is written.
    fn error(chart: &BarChart, name: &str) -> String {
        let dir = scratch(name);
        let path = dir.join("chart.svg");
        let e = draw_bars(chart, &path).expect_err(name);
        assert!(!path.exists(), "{name}: a file was written");
        std::fs::remove_dir_all(dir).ok();
        e
    }

    #[test]
    fn bad_charts_are_errors() {
        let good = speedups();
        let mut c = good.clone();
        c.categories.clear();
        c.series.clear();
        let e = error(&c, "no-categories");
        assert!(e.starts_with("drawing Speedup over the baseline:"), "{e}");
        assert!(e.contains("no categories"), "{e}");

        let mut c = good.clone();
        c.series.clear();
        assert!(error(&c, "no-series").contains("no series"));

        let mut c = good.clone();
        c.series[1].values.pop();
        let e = error(&c, "length");
        assert!(
            e.contains("`Fullpriority` has 17 values for 18 categories"),
            "{e}"
        );

        let mut c = good.clone();
        c.series[0].values[2] = Some(f64::NAN);
        let e = error(&c, "nan");
        assert!(e.contains("`WaSP`") && e.contains("NaN"), "{e}");
        assert!(e.contains("category `scene-02-with-a-long-name`"), "{e}");

        let mut c = good.clone();
        c.paper.push(PaperMark::all(Some(2), 0.01, "ghost"));
        let e = error(&c, "mark-series");
        assert!(
            e.contains("`ghost` belongs to series 2") && e.contains("2 series"),
            "{e}"
        );

        let mut c = good.clone();
        c.paper.push(PaperMark::at(None, 18, 0.01, "far"));
        let e = error(&c, "mark-category");
        assert!(
            e.contains("`far` is at index 18") && e.contains("18 categories"),
            "{e}"
        );

        let mut c = good.clone();
        c.paper.push(PaperMark::all(None, f64::INFINITY, "huge"));
        assert!(error(&c, "mark-value").contains("`huge` has the non-finite value inf"));

        let mut c = good.clone();
        c.reference = Some(f64::NAN);
        assert!(error(&c, "reference").contains("reference line"));

        let mut c = good.clone();
        c.separators.push(19);
        assert!(error(&c, "separator").contains("separator before category 19"));

        let mut c = good;
        c.highlight.push(18);
        assert!(error(&c, "highlight").contains("highlighted category 18"));
    }

    #[test]
    fn bad_files_are_errors() {
        let dir = scratch("bars-files");
        let e = draw_bars(&speedups(), &dir.join("chart.jpg")).expect_err("jpg");
        assert!(e.contains("chart.jpg") && e.contains(".png or .svg"), "{e}");
        let missing = dir.join("no-such-dir").join("chart.png");
        let e = draw_bars(&speedups(), &missing).expect_err("unwritable");
        assert!(
            e.starts_with("writing ") && e.contains("no-such-dir"),
            "{e}"
        );
        let e = draw_bars(&speedups(), &dir.join("no-such-dir").join("c.svg")).expect_err("svg");
        assert!(e.starts_with("writing ") && e.contains("c.svg"), "{e}");
        std::fs::remove_dir_all(dir).ok();
    }
}
