//! Grouped bar charts ([`draw_bars`]) in plotters' coordinates: each
//! category a unit of x with one bar per series, from 0 to the value.
//! Highlighted categories have a grey band behind them, separators are
//! dotted lines, named runs of categories (3D games, ...) have their name
//! over the plot. With at most three series and twenty categories each bar
//! has its value printed over it (under it when negative; reading upwards
//! when wider than the bar) unless that would cover a bar, mark, line or
//! label.

use super::frame::{
    builder, column, mark_colour, paper_entry, paper_lines, paper_margin, paper_point, pixel_of,
    plot_rect, px, range, rect_of, style, style_mesh, text_size, value_label, write, y_area, Area,
    At, Drawn, Frame, Picture, Placer, Rect, Ticked, LABEL, SMALL,
};
use super::legend::{Shape, Swatch};
use super::{check, ensure, frame, who, BarChart, CategoryGroup};
use crate::palette::{series_colours, shade, INK};
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos as H, VPos as V};
use std::path::Path;
use FontTransform::Rotate270;

/// Background of highlighted categories.
const GREY: RGBColor = RGBColor(236, 236, 236);

/// Draws `chart` into `path`, a PNG or an SVG by the file's extension
/// (`.png`, `.svg`, in any case).
///
/// Errors (starting with `drawing <title>:` or naming the file): another
/// extension; no categories or no series; a series with a value count
/// other than the category count or with a non-finite value; a paper mark
/// of a series or category that does not exist or with a non-finite value;
/// a non-finite reference; a separator, highlight or group past the
/// categories; a file that cannot be written.
pub fn draw_bars(chart: &BarChart, path: &Path) -> Result<(), String> {
    let (who, n, c) = (who(&chart.title), chart.categories.len(), chart);
    let marks = (&c.series[..], &c.paper[..], c.reference);
    let name_of = |i: usize| format!("category `{}`", c.categories[i]);
    check(&who, marks, (n, "categories"), name_of)?;
    let bad_group = |g: &CategoryGroup| g.categories.end > n || g.categories.is_empty();
    let bad_sep = c.separators.iter().any(|&i| i > n) || c.highlight.iter().any(|&i| i >= n);
    let what = "a separator, highlight or group";
    let bad = bad_sep || c.groups.iter().any(bad_group);
    ensure(!bad, || format!("{who}: {what} is past the {n} categories"))?;
    write(&who, path, || Bars::new(chart))
}

/// A bar chart laid out.
struct Bars<'a> {
    c: &'a BarChart,
    frame: Frame<'a>,
    colours: Vec<RGBColor>,
    y: std::ops::Range<f64>,
    pad: frame::Pad,
    /// The row of each group's name over the plot (0: the lower).
    rows: Vec<f64>,
    /// Category names read upwards.
    rotate: bool,
}

impl<'a> Bars<'a> {
    fn new(c: &'a BarChart) -> Self {
        let (n, s) = (c.categories.len(), c.series.len());
        let bars = present(&c.series).into_iter().map(|b| b.2);
        let data: Vec<f64> = bars.chain(c.paper.iter().map(|m| m.value)).collect();
        let lo = data.iter().copied().fold(0.0, f64::min);
        let hi = data.iter().copied().fold(0.0, f64::max);
        // Room over the tallest (under the lowest) bar for its value.
        let room = 0.06 * (hi - lo) * f64::from(u8::from(s <= 3 && n <= 20));
        let mut include = vec![0.0, hi + room * hi.signum(), lo + room * lo.signum()];
        include.extend(c.reference);
        let y = range(data, &include);
        let (left, right) = (y_area(&y, c.percent), paper_margin(&c.paper));
        let want = (s as f64 * [24.0, 17.0][usize::from(s > 3)] + 18.0).clamp(44.0, 140.0);
        let width = (left + n as f64 * want + right).clamp(900.0, 1800.0);
        let group = (width - left - right - 6.0) / n as f64;
        let names = c.categories.iter().map(|t| text_size(t, LABEL, true).0);
        let widest = names.fold(0.0, f64::max);
        let rotate = widest > group - 6.0;
        let bottom = 16.0 + [text_size("Ag", LABEL, false).1, widest][usize::from(rotate)];
        // A group's name goes a row higher where it would touch the one
        // before.
        let mut end = f64::NEG_INFINITY;
        let mut row = |g: &CategoryGroup| {
            let half = text_size(&g.label, LABEL, true).0 / 2.0;
            let mid = (g.categories.start + g.categories.end) as f64 / 2.0 * group;
            let up = mid - half < end + 30.0;
            end = if up { end } else { mid + half };
            f64::from(u8::from(up))
        };
        let rows: Vec<f64> = c.groups.iter().map(&mut row).collect();
        let two = usize::from(rows.iter().any(|&r| r > 0.0));
        let top = [10.0, 34.0, 56.0][c.groups.len().min(1) + two];
        let colours = series_colours(&c.series.iter().map(|s| s.key).collect::<Vec<_>>());
        let swatch = |(s, &k): (&super::Series, _)| (s.name.clone(), Swatch::Block(k));
        let mut legend: Vec<_> = c.series.iter().zip(&colours).map(swatch).collect();
        legend.extend(paper_entry(&c.paper, Shape::Circle));
        let frame = Frame::new((&c.title, &c.subtitle), legend, left, width.round());
        let pad = (left, bottom, top, right);
        Bars {
            c,
            frame,
            colours,
            y,
            pad,
            rows,
            rotate,
        }
    }
}

impl Picture for Bars<'_> {
    fn size(&self) -> (u32, u32) {
        let height = f64::from(self.frame.height()) + self.pad.2 + 438.0 + self.pad.1;
        (self.frame.width as u32, height.max(700.0) as u32)
    }

    fn draw<DB: DrawingBackend>(&self, root: &Area<DB>) -> Drawn<DB> {
        let (c, n, (lo, hi)) = (self.c, self.c.categories.len(), (self.y.start, self.y.end));
        let area = self.frame.draw(root)?;
        // Category i spans x from i to i + 1; its name is drawn apart.
        let x = Ticked::categories(&vec![String::new(); n]);
        let y = Ticked::numeric(&self.y, 8, c.percent);
        let mut chart = builder(&area, self.pad).build_cartesian_2d(x, y)?;
        let band = |&i: &usize| {
            let x = i as f64;
            Rectangle::new([(x, hi), (x + 1.0, lo)], GREY.filled())
        };
        chart.draw_series(c.highlight.iter().map(band))?;
        let mut mesh = chart.configure_mesh();
        style_mesh(&mut mesh);
        mesh.disable_x_mesh().y_desc(&c.y_label).draw()?;
        let dots = RGBColor(90, 90, 90).stroke_width(2);
        let sep = |&i: &usize| {
            let x = i as f64;
            DashedPathElement::new([(x, lo), (x, hi)], 3, 4, dots)
        };
        chart.draw_series(c.separators.iter().map(sep))?;

        // The bars, kept free of labels, then the zero and reference lines.
        let (p, pixel) = (plot_rect(&chart), pixel_of(&chart));
        let slots = Slots::new(c.series.len(), (p.2 - p.0) / n as f64);
        let inset = u32::from(slots.px > 8.0);
        let mut placer = Placer::default();
        let mut rects = Vec::new();
        for (k, i, v) in present(&c.series) {
            let corners = [(slots.left(i, k), v), (slots.left(i, k + 1), 0.0)];
            placer.take(rect_of(&pixel, corners[0], corners[1]));
            let mut rect = Rectangle::new(corners, self.colours[k].filled());
            rect.set_margin(0, 0, inset, inset);
            rects.push(rect);
        }
        chart.draw_series(rects)?;
        for (v, w) in [(Some(0.0), 1), (c.reference, 2)] {
            let rule = v.map(|v| vec![(0.0, v), (n as f64, v)]);
            chart.draw_series(rule.map(|r| PathElement::new(r, INK.stroke_width(w))))?;
        }
        self.labels(root, &mut placer, (p, &pixel, &slots))?;
        self.names(root, (p, &pixel))
    }
}

impl Bars<'_> {
    /// The paper's values (lines across the plot, then marks of one
    /// category over the bar or group), then the values over the bars and
    /// the marks' labels where they hide nothing.
    fn labels<DB: DrawingBackend>(
        &self,
        root: &Area<DB>,
        placer: &mut Placer,
        (p, pixel, slots): (Rect, &At, &Slots),
    ) -> Drawn<DB> {
        let c = self.c;
        let colour = |s| mark_colour(&self.colours, s);
        let row = |v| pixel(0.0, v).1;
        paper_lines(root, (p, &mut *placer), &c.paper, row, colour)?;
        let bars = present(&c.series);
        let texts: Vec<String> = bars.iter().map(|b| value_label(b.2, c.percent)).collect();
        let mut labels = Vec::new();
        let few = c.series.len() <= 3 && c.categories.len() <= 20;
        for (&(k, i, v), text) in bars.iter().zip(&texts).filter(|_| few) {
            let upright = text_size(text, SMALL, false).0 > slots.px + 2.0;
            let (x, y) = pixel((slots.left(i, k) + slots.left(i, k + 1)) / 2.0, v);
            let (y, limit, up) =
                [(y + 2.0, p.3, false), (y - 2.0, p.1, true)][usize::from(v >= 0.0)];
            let candidates = column(x, (y, up, limit), (text, upright), 400);
            labels.push((candidates, text.as_str(), shade(self.colours[k], 0.62)));
        }
        for m in c.paper.iter().filter(|m| m.category.is_some()) {
            let i = m.category.unwrap_or(0);
            // Over the series' bar and 3 pixels wider, or over the
            // category and 3 pixels narrower.
            let ((x0, x1), d) = match m.series {
                Some(k) => ((slots.left(i, k), slots.left(i, k + 1)), 3.0),
                None => ((i as f64, i as f64 + 1.0), -3.0),
            };
            let ((x0, y), x1) = (pixel(x0, m.value), pixel(x1, 0.0).0);
            let (at, colour) = (((x0 + x1) / 2.0, y), colour(m.series));
            let mark = (at, (x1 - x0) / 2.0 + d, 5.0);
            paper_point((root, &mut *placer), mark, Shape::Circle, colour)?;
            let text = (m.label.as_str(), false);
            let over = column(at.0, (at.1 - 8.0, true, p.1), text, 400);
            let under = column(at.0, (at.1 + 8.0, false, p.3), text, 400);
            labels.push(([over, under].concat(), text.0, colour));
        }
        placer.draw_all(root, labels, p)
    }

    /// The category names under the axis, the group names over the plot.
    fn names<DB: DrawingBackend>(&self, root: &Area<DB>, (p, pixel): (Rect, &At)) -> Drawn<DB> {
        let (c, x) = (self.c, |i: usize| pixel(i as f64, 0.0).0);
        for (i, name) in c.categories.iter().enumerate() {
            let bold = c.highlight.contains(&i);
            let s = match self.rotate {
                true => style(LABEL, bold, BLACK, H::Right, V::Center).transform(Rotate270),
                false => style(LABEL, bold, BLACK, H::Center, V::Top),
            };
            root.draw_text(name, &s, px((x(i) + x(i + 1)) / 2.0, p.3 + 10.0))?;
        }
        for (grp, row) in c.groups.iter().zip(&self.rows) {
            let run = &grp.categories;
            let (x0, x1) = (x(run.start) + 6.0, x(run.end) - 6.0);
            let y = p.1 - 8.0 - 22.0 * row;
            let bracket = vec![px(x0, y + 4.0), px(x0, y), px(x1, y), px(x1, y + 4.0)];
            root.draw(&PathElement::new(bracket, INK))?;
            let s = style(LABEL, true, INK, H::Center, V::Bottom);
            root.draw_text(&grp.label, &s, px((x0 + x1) / 2.0, y - 3.0))?;
        }
        Ok(())
    }
}

/// Where the bars of a category go, in units of x (a category is one
/// unit): side by side over 80% of the category, none wider than 64
/// pixels.
struct Slots {
    /// The number of series.
    s: f64,
    /// A bar's width in units of x, and in pixels.
    width: f64,
    px: f64,
}

impl Slots {
    /// The slots of `s` series in categories `unit` pixels wide.
    fn new(s: usize, unit: f64) -> Slots {
        let s = s as f64;
        let width = (0.8 / s).min(64.0 / unit.max(1.0));
        let px = width * unit;
        Slots { s, width, px }
    }

    /// The left edge of series `k`'s bar in category `i` (the right edge
    /// of the bar of series `k` - 1).
    fn left(&self, i: usize, k: usize) -> f64 {
        i as f64 + (1.0 - self.s * self.width) / 2.0 + k as f64 * self.width
    }
}

/// The present values: (series, category, value) each.
fn present(series: &[super::Series]) -> Vec<(usize, usize, f64)> {
    let mut out = Vec::new();
    for (k, s) in series.iter().enumerate() {
        let values = s.values.iter().enumerate();
        out.extend(values.filter_map(|(i, v)| Some((k, i, (*v)?))));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::tests::{error, full, mark, out, pixels, refused, same_twice, texts, Case};
    use super::*;
    use crate::palette::Key;

    /// Sixteen scenes with long names in two groups and two means, two
    /// series of speedups (one negative), the paper's values.
    fn speedups() -> BarChart {
        let names = (0..16).map(|i| format!("scene-{i:02}-with-a-long-name"));
        let categories = names.chain(["mean 3D".into(), "mean all".into()]).collect();
        let wasp: Vec<f64> = (0..18).map(|i| 0.01 * f64::from(i % 7) - 0.02).collect();
        let half: Vec<f64> = wasp.iter().map(|v| v / 2.0).collect();
        let mut fp = full(Key::FullPriority, "Fullpriority", &half);
        fp.values[3] = None;
        let group = |label: &str, categories| CategoryGroup {
            label: label.into(),
            categories,
        };
        BarChart {
            title: "Speedup over the baseline".into(),
            subtitle: "shared-tile machine, 16 scenes".into(),
            y_label: "speedup".into(),
            categories,
            series: vec![full(Key::Wasp, "WaSP", &wasp), fp],
            paper: vec![
                mark(Some(0), None, 0.039, "paper 3.9%"),
                mark(None, None, 0.05, "paper best 5.0%"),
                mark(Some(1), Some(16), 0.02, "paper 2.0%"),
                mark(None, Some(17), -0.01, "paper -1.0%"),
            ],
            percent: true,
            reference: Some(0.0),
            separators: vec![10, 16],
            highlight: vec![16, 17],
            groups: vec![
                group("3D games", 0..10),
                group("2D", 10..16),
                group("means", 16..18),
            ],
        }
    }

    #[test]
    fn bars_have_the_policies_colours_names_and_groups() {
        let path = out("bars", "speedup.png");
        draw_bars(&speedups(), &path).expect("draw png");
        let (w, h) = image::image_dimensions(&path).expect("png");
        assert!((900..=1800).contains(&w) && (700..=1000).contains(&h));
        let wasp = pixels(&path, Key::Wasp.colour().unwrap());
        let full = pixels(&path, Key::FullPriority.colour().unwrap());
        assert!(wasp > 500 && full > 200, "{wasp}, {full} pixels");
        let path = out("bars", "speedup.svg");
        draw_bars(&speedups(), &path).expect("draw svg");
        texts(
            &path,
            "Speedup over the baseline|shared-tile machine, 16 scenes|speedup|WaSP|\
             paper 3.9%|paper best 5.0%|paper 2.0%|paper -1.0%|mean 3D|0%|-2%|\
             scene-15-with-a-long-name|3D games|means|\
             paper values: dashed lines, hollow marks (series colour)",
        );
        same_twice("bars-same", &|p| draw_bars(&speedups(), p));
    }

    #[test]
    fn values_show_for_few_series_and_keep_off_the_paper_lines() {
        // Min_Estimate-like values whose labels would cross the lines.
        let mut c = speedups();
        c.categories = ["a", "b", "c", "d"].map(String::from).to_vec();
        let one = full(Key::Other, "one", &[0.23, 0.099, 0.11, 0.068]);
        c.series = vec![one, full(Key::Other, "two", &[0.045, 0.053, 0.071, 0.062])];
        let p2 = mark(Some(1), None, 0.0625, "p2");
        c.paper = vec![mark(Some(0), None, 0.12, "p1"), p2];
        (c.separators, c.highlight, c.groups, c.percent) = (vec![], vec![], vec![], false);
        let path = out("bars-values", "subset.svg");
        draw_bars(&c, &path).expect("draw svg");
        let values = "0.23|0.099|0.11|0.068|0.045|0.053|0.071|0.062";
        let placed = texts(&path, values);
        let line = |label: &str| placed.iter().find(|t| t.0 == label).map_or(0.0, |t| t.2);
        for (text, _, y, up) in placed.iter().filter(|t| values.contains(t.0.as_str())) {
            let (w, h) = text_size(text, SMALL, false);
            let half = if *up { w / 2.0 } else { h / 2.0 };
            for l in [line("p1"), line("p2")] {
                assert!((y - l).abs() >= half + 3.0, "`{text}` at {y} on {l}");
            }
        }
        let four = |k| full(Key::Other, &format!("s{k}"), &[1.2, 0.5, 2.0, 1.0]);
        c.series = (0..4).map(four).collect();
        draw_bars(&c, &path).expect("draw svg");
        let values = texts(&path, "s3").into_iter().any(|t| t.0 == "0.50");
        assert!(!values, "four series: no values");
        (c.categories, c.series) = (vec!["only".into()], vec![full(Key::Wasp, "WaSP", &[-0.02])]);
        (c.paper, c.percent) = (vec![], true);
        draw_bars(&c, &path).expect("draw svg");
        texts(&path, "-2.0%|0.0%|only");
    }

    #[test]
    fn bad_charts_and_files_are_errors() {
        let cases: &[Case<BarChart>] = &[
            (|c| c.categories.clear(), "0 categories and 2 series"),
            (|c| c.series[1].values.truncate(17), "has 17 values for 18"),
            (|c| c.series[0].values[2] = Some(f64::NAN), "`scene-02"),
            (|c| c.paper[0].series = Some(2), "`paper 3.9%` is past"),
            (|c| c.paper[1].value = f64::INFINITY, "value inf"),
            (|c| c.reference = Some(f64::NAN), "the reference line"),
            (|c| c.separators.push(19), "past the 18 categories"),
            (|c| c.groups[0].categories = 0..19, "past the 18 categories"),
        ];
        let chart = ("bars-bad", &speedups(), "drawing Speedup");
        refused(chart, draw_bars, cases);
        let e = error("bars-jpg", "chart.jpg", &|p| draw_bars(&speedups(), p));
        assert!(e.contains("chart.jpg") && e.contains(".png or .svg"), "{e}");
        let e = draw_bars(&speedups(), &out("bars-dir", "no").join("c.png")).unwrap_err();
        assert!(e.starts_with("writing ") && e.contains("c.png"), "{e}");
    }
}
