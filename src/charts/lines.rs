//! Line charts over shared x positions ([`draw_lines`]), and the plot that
//! draws them and [`super::draw_xy`]'s points: each series a line in its
//! colour through filled markers of its own shape (a missing value breaks
//! the line); the x axis numeric (plotters' ticks) or labelled at the x
//! positions (every second, third, ... label where they would overlap). A
//! paper mark of one x position is the series' shape, hollow, on a short
//! dashed line; ringed points are joined by a dotted line with their
//! caption over them. Labels go where they hide nothing.

use super::frame::{
    around, beside, builder, column, mark_colour, paper_entry, paper_lines, paper_margin,
    paper_point, pixel_of, plot_rect, px, range, style_mesh, text_size, write, y_area, Area, At,
    Drawn, Frame, Picture, Placer, Rect, Ticked, LABEL,
};
use super::legend::{marker, Shape, Swatch};
use super::{check, ensure, finite, who, Highlight, Key, LineChart, PaperMark};
use crate::palette::{series_colours, shade, INK};
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use std::ops::Range;
use std::path::Path;

/// Width of the picture in pixels.
const WIDTH: f64 = 1400.0;

/// Draws `chart` into `path`, a PNG or an SVG by the file's extension.
///
/// Errors (starting with `drawing <title>:` or naming the file): another
/// extension; no x positions or no series; a non-finite x or one not
/// greater than the one before; tick labels whose count is not the x
/// count; a series with a value count other than the x count or with a
/// non-finite value; a paper mark of a series or x position that does not
/// exist or with a non-finite value; a non-finite reference; a file that
/// cannot be written.
pub fn draw_lines(chart: &LineChart, path: &Path) -> Result<(), String> {
    let (who, x, n, c) = (who(&chart.title), &chart.x, chart.x.len(), chart);
    for i in 0..n {
        finite(&who, format_args!("x[{i}]"), x[i])?;
        let (a, b) = (x[i.max(1) - 1], x[i]);
        let order = "x must be strictly increasing";
        ensure(i == 0 || b > a, || {
            format!("{who}: x[{i}] = {b} follows {a}: {order}")
        })?;
    }
    let (ticks, count) = (c.x_ticks.as_deref(), c.x_ticks.as_ref().map_or(n, Vec::len));
    ensure(count == n, || {
        format!("{who}: {count} x tick labels for {n} x positions")
    })?;
    let name_of = |i: usize| format!("x = {}", ticks.map_or(x[i].to_string(), |t| t[i].clone()));
    let marks = (&c.series[..], &c.paper[..], c.reference);
    check(&who, marks, (n, "x positions"), name_of)?;
    let point = |(&x, v): (&f64, &Option<f64>)| v.map(|y| (x, y, String::new()));
    let lines = c.series.iter().map(|s| {
        let points = x.iter().zip(&s.values).map(point).collect();
        (s.name.as_str(), s.key, points)
    });
    let plot = Plot {
        texts: [&c.title, &c.subtitle, &c.x_label, &c.y_label].map(String::as_str),
        lines: lines.collect(),
        x,
        ticks,
        paper: &c.paper,
        percent: c.percent,
        reference: c.reference,
        ..Plot::default()
    };
    write(&who, path, || plot.lay_out())
}

/// A point: x, y and its label (empty: none).
pub(super) type Point = (f64, f64, String);

/// What line and XY charts draw.
#[derive(Default)]
pub(super) struct Plot<'a> {
    /// Title, subtitle, x label, y label.
    pub texts: [&'a str; 4],
    /// Each series' name, key and points (None: a gap).
    pub lines: Vec<(&'a str, Key, Vec<Option<Point>>)>,
    /// The x positions of the paper's marks and of the tick labels (None:
    /// plotters' ticks).
    pub x: &'a [f64],
    pub ticks: Option<&'a [String]>,
    pub paper: &'a [PaperMark],
    pub rings: &'a [Highlight],
    pub percent: bool,
    pub reference: Option<f64>,
}

/// A [`Plot`] laid out: its strip, colours, x axis (an empty tick label is
/// left out), y range and the label area left of it and the margin right.
pub(super) struct Layout<'a> {
    p: Plot<'a>,
    frame: Frame<'a>,
    colours: Vec<RGBColor>,
    axes: (Ticked, Range<f64>),
    pad: (f64, f64),
}

impl<'a> Plot<'a> {
    pub fn lay_out(self) -> Layout<'a> {
        let points = || self.lines.iter().flat_map(|l| l.2.iter().flatten());
        let marks = self.paper.iter().map(|m| m.value);
        let ys = points().map(|p| p.1).chain(marks);
        // Line charts hold 0 (or the reference); points over x do not.
        let base = vec![0.0; usize::from(!self.x.is_empty())];
        let y = range(ys, &self.reference.map_or(base, |r| vec![r]));
        let xs = points().map(|p| p.0);
        let (lo, hi) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| {
            (l.min(x), h.max(x))
        });
        // A single x gets a range around it.
        let pad = [lo.abs().max(2.0) * 0.5, 0.04 * (hi - lo)][usize::from(hi > lo)];
        let x = lo - pad..hi + pad;
        let (left, right) = (y_area(&y, self.percent), paper_margin(self.paper));
        let plot_w = WIDTH - left - right;
        let mut x_axis = match self.ticks {
            Some(labels) => Ticked(
                x.clone().into(),
                self.x.iter().copied().zip(labels.iter().cloned()).collect(),
            ),
            None => Ticked::numeric(&x, 12, false),
        };
        // Where labels would overlap, every k-th.
        let ticks = &mut x_axis.1;
        let widest = ticks.iter().map(|t| text_size(&t.1, LABEL, false).0);
        let span = x.end - x.start;
        let gaps = ticks.windows(2).map(|w| (w[1].0 - w[0].0) / span * plot_w);
        let gap = gaps.fold(f64::INFINITY, f64::min).max(1.0);
        let every = ((widest.fold(0.0, f64::max) + 10.0) / gap).ceil().max(1.0) as usize;
        for (_, t) in ticks.iter_mut().enumerate().filter(|(i, _)| i % every != 0) {
            t.1.clear();
        }
        let colours = series_colours(&self.lines.iter().map(|l| l.1).collect::<Vec<_>>());
        let swatch = |k, c: RGBColor| Swatch::Line(c.stroke_width(2), Some(Shape::of(k)));
        let entry = |(k, (l, &c))| (String::from(l), swatch(k, c));
        let names = self.lines.iter().map(|l| l.0).zip(&colours).enumerate();
        let mut legend: Vec<_> = names.map(entry).collect();
        let first = self.paper.iter().find(|m| m.category.is_some());
        let shape = first.map_or(Shape::Circle, |m| paper_shape(m.series));
        legend.extend(paper_entry(self.paper, shape));
        let frame = Frame::new((self.texts[0], self.texts[1]), legend, left, WIDTH);
        Layout {
            p: self,
            frame,
            colours,
            axes: (x_axis, y),
            pad: (left, right),
        }
    }
}

/// The shape of a paper mark of `series` at one x position: the series'
/// shape, or a circle for the whole chart.
fn paper_shape(series: Option<usize>) -> Shape {
    series.map_or(Shape::Circle, Shape::of)
}

impl Picture for Layout<'_> {
    fn size(&self) -> (u32, u32) {
        let height = (f64::from(self.frame.height()) + 504.0).max(700.0);
        (WIDTH as u32, height as u32)
    }

    fn draw<DB: DrawingBackend>(&self, root: &Area<DB>) -> Drawn<DB> {
        let (pl, (x, y)) = (&self.p, &self.axes);
        let ((x0, x1), y0) = ((x.range().start, x.range().end), y.start);
        let area = self.frame.draw(root)?;
        let pad = (self.pad.0, 64.0, 10.0, self.pad.1);
        let y = Ticked::numeric(y, 8, pl.percent);
        let mut chart = builder(&area, pad).build_cartesian_2d(x.clone(), y)?;
        let mut mesh = chart.configure_mesh();
        style_mesh(&mut mesh);
        mesh.x_desc(pl.texts[2]).y_desc(pl.texts[3]).draw()?;
        let zero = (y0 < 0.0).then_some((0.0, 1));
        let rule = pl.reference.map(|r| (r, 2)).or(zero);
        let rule = rule.map(|(v, w)| PathElement::new(vec![(x0, v), (x1, v)], INK.stroke_width(w)));
        chart.draw_series(rule)?;

        // The lines through each run of present points, then the markers,
        // all kept free of labels.
        let (p, at) = (plot_rect(&chart), pixel_of(&chart));
        let mut placer = Placer::default();
        let colour = |s| mark_colour(&self.colours, s);
        paper_lines(root, (p, &mut placer), pl.paper, |v| at(x0, v).1, colour)?;
        let series = || pl.lines.iter().map(|l| &l.2).zip(&self.colours).enumerate();
        for (_, (pts, &k)) in series() {
            for run in pts.split(Option::is_none).filter(|r| r.len() > 1) {
                let run: Vec<(f64, f64)> = run.iter().flatten().map(|p| (p.0, p.1)).collect();
                placer.take_path(&run.iter().map(|p| at(p.0, p.1)).collect::<Vec<_>>(), 2.0);
                chart.draw_series(LineSeries::new(run, k.stroke_width(2)))?;
            }
        }
        for (s, (pts, &k)) in series() {
            let xys: Vec<(f64, f64)> = pts.iter().flatten().map(|p| (p.0, p.1)).collect();
            for p in &xys {
                placer.take(around(at(p.0, p.1), (6.0, 6.0)));
            }
            let shape = (Shape::of(s), 6);
            let marks = xys.into_iter().map(|xy| marker(xy, shape, k, false));
            chart.draw_series(marks)?;
        }

        self.labels(root, placer, (p, &at))
    }
}

impl Layout<'_> {
    /// The paper's marks of one x position, the rings, then the labels:
    /// the marks', the captions, the points' (which give way). `at` maps
    /// values to pixels in the plot `p`.
    fn labels<DB: DrawingBackend>(
        &self,
        root: &Area<DB>,
        mut placer: Placer,
        (p, at): (Rect, &At<'_>),
    ) -> Drawn<DB> {
        let (pl, mut labels, mut ringed) = (&self.p, Vec::new(), Vec::new());
        for m in pl.paper.iter().filter(|m| m.category.is_some()) {
            let i = m.category.unwrap_or(0);
            let (xy, colour) = (at(pl.x[i], m.value), mark_colour(&self.colours, m.series));
            let (mark, shape) = ((xy, 16.0, 8.0), paper_shape(m.series));
            paper_point((root, &mut placer), mark, shape, colour)?;
            labels.push((beside(xy, 20.0, &m.label, 400, p), m.label.as_str(), colour));
        }
        for h in pl.rings {
            let point = |&(s, i): &(usize, usize)| pl.lines[s].2[i].as_ref().map(|p| at(p.0, p.1));
            let pts: Vec<(f64, f64)> = h.points.iter().filter_map(point).collect();
            let path = pts.iter().map(|&(x, y)| px(x, y));
            root.draw(&DashedPathElement::new(path, 3, 3, INK.stroke_width(1)))?;
            placer.take_path(&pts, 2.0);
            for &xy in &pts {
                root.draw(&Circle::new(px(xy.0, xy.1), 11, INK.stroke_width(2)))?;
                placer.take(around(xy, (13.0, 13.0)));
            }
            // The caption over the highest ring, else under the lowest.
            let mid = pts.iter().map(|p| p.0).sum::<f64>() / pts.len().max(1) as f64;
            let top = pts.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
            let low = pts.iter().map(|p| p.1).fold(0.0, f64::max);
            let text = (h.caption.as_str(), false);
            let over = column(mid, (top - 14.0, true, p.1), text, 400);
            let under = column(mid, (low + 14.0, false, p.3), text, 400);
            labels.push(([over, under].concat(), text.0, INK));
            ringed.extend(pts);
        }
        for (pts, &k) in pl.lines.iter().map(|l| &l.2).zip(&self.colours) {
            for (x, y, l) in pts.iter().flatten().filter(|p| !p.2.is_empty()) {
                let xy = at(*x, *y);
                let d = if ringed.contains(&xy) { 15.0 } else { 8.0 };
                labels.push((beside(xy, d, l, 8, p), l.as_str(), shade(k, 0.62)));
            }
        }
        placer.draw_all(root, labels, p)
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::{full, mark, out, pixels, refused, same_twice, texts, Case};
    use super::*;
    use crate::palette::Key;

    /// IPC over the warp count for two policies, one with a gap, with the
    /// paper's value at one count and its baseline across the plot.
    fn warps() -> LineChart {
        let x = vec![28.0, 32.0, 40.0, 48.0, 64.0];
        let mut wasp = full(Key::Wasp, "WaSP", &[0.66, 0.68, 0.0, 0.70, 0.705]);
        wasp.values[2] = None;
        LineChart {
            title: "IPC by warp count".into(),
            subtitle: "4 cores, 16 scenes".into(),
            x_label: "warps per core".into(),
            y_label: "IPC".into(),
            x_ticks: Some(x.iter().map(|v| format!("{v}")).collect()),
            x,
            series: vec![
                full(Key::Baseline, "baseline", &[0.61, 0.64, 0.66, 0.67, 0.675]),
                wasp,
            ],
            paper: vec![
                mark(Some(1), Some(1), 0.69, "paper 0.69"),
                mark(None, None, 0.6, "paper 0.60"),
            ],
            percent: false,
            reference: None,
        }
    }

    #[test]
    fn lines_have_the_policies_colours_and_texts() {
        let path = out("lines", "warps.png");
        draw_lines(&warps(), &path).expect("draw png");
        assert_eq!(image::image_dimensions(&path).ok(), Some((1400, 700)));
        let base = pixels(&path, Key::Baseline.colour().unwrap());
        let wasp = pixels(&path, Key::Wasp.colour().unwrap());
        assert!(base > 300 && wasp > 200, "{base}, {wasp} pixels");
        let path = out("lines", "warps.svg");
        draw_lines(&warps(), &path).expect("draw svg");
        let want = "IPC by warp count|4 cores, 16 scenes|warps per core|IPC|WaSP|paper 0.69|paper 0.60|28|64";
        texts(&path, want);
        same_twice("lines-same", &|p| draw_lines(&warps(), p));
    }

    #[test]
    fn numeric_axes_crowded_ticks_and_one_point_draw() {
        let mut c = warps();
        c.x = vec![1.0, 2.0, 4.0, 8.0];
        c.series = vec![full(Key::Wasp, "WaSP", &[-0.02, 0.01, 0.03, 0.02])];
        (c.percent, c.reference, c.x_ticks, c.paper) = (true, Some(0.0), None, vec![]);
        let path = out("lines-numeric", "speedup.svg");
        draw_lines(&c, &path).expect("draw svg");
        texts(&path, "-2%|0%|3%|2|8");
        (c.x, c.series) = (vec![5.0], vec![full(Key::Wasp, "WaSP", &[-0.01])]);
        let path = out("lines-numeric", "one.png");
        draw_lines(&c, &path).expect("draw png");
        assert!(pixels(&path, Key::Wasp.colour().unwrap()) > 20);
        c.x = (0..40).map(f64::from).collect();
        c.series = vec![full(Key::Other, "v", &c.x)];
        c.x_ticks = Some((0..40).map(|i| format!("scene-{i:02}")).collect());
        let path = out("lines-numeric", "many.svg");
        draw_lines(&c, &path).expect("draw svg");
        let thinned = !texts(&path, "scene-00").iter().any(|t| t.0 == "scene-01");
        assert!(thinned, "crowded labels are thinned");
    }

    #[test]
    fn bad_charts_are_errors() {
        let cases: &[Case<LineChart>] = &[
            (
                |c| (c.x, c.x_ticks) = (vec![], None),
                "0 x positions and 2 series",
            ),
            (|c| c.x[2] = 32.0, "x[2] = 32 follows 32: x must be"),
            (|c| c.x[4] = f64::NAN, "x[4] has the non-finite value NaN"),
            (
                |c| c.x_ticks = Some(vec!["28".into()]),
                "1 x tick labels for 5",
            ),
            (
                |c| c.series[1].values[4] = Some(f64::NAN),
                "`WaSP` at x = 64",
            ),
            (|c| c.paper[0].category = Some(5), "`paper 0.69` is past"),
        ];
        let chart = ("lines-bad", &warps(), "drawing IPC by warp");
        refused(chart, draw_lines, cases);
    }
}
