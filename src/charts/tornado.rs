//! Tornado charts ([`draw_tornado`]): one row per parameter, a bar per
//! series (e.g. the 3D and the 2D scenes) from the lowest to the highest
//! value a quantity takes over the parameter's range, each end labelled
//! with the parameter value that gave it; a vertical line at each series'
//! value on the shipped machine; the widest row on top. The bars are
//! rectangles in plotters' coordinates, a row a unit of y.

use super::frame::{
    around, builder, pixel_of, plot_rect, range, rect_of, style_mesh, text_size, value_label,
    write, Drawn, Frame, Picture, Placer, Rect, Ticked, LABEL, SMALL,
};
use super::legend::Swatch;
use super::{ensure, finite, who, Key};
use crate::palette::{series_colours, shade};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// A series of a tornado chart.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TornadoSeries {
    /// What the series shows: it chooses the colour ([`crate::palette`]).
    pub key: Key,
    /// The name in the legend (e.g. "3D").
    pub name: String,
    /// The series' value on the shipped machine: a vertical line.
    pub reference: Option<f64>,
}

/// The range of the quantity over one parameter's range, for one series:
/// the lowest and the highest value, each with the parameter value that
/// gave it (e.g. "32 warps").
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Span {
    /// The lowest value and its parameter value.
    pub low: (f64, String),
    /// The highest value and its parameter value.
    pub high: (f64, String),
}

/// One parameter: a span per series (None: not measured).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TornadoRow {
    /// The parameter's name, left of the row.
    pub parameter: String,
    /// One span per series.
    pub spans: Vec<Option<Span>>,
}

/// A tornado chart.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TornadoChart {
    /// The title.
    pub title: String,
    /// The line under the title (none when empty).
    pub subtitle: String,
    /// The x axis label (e.g. "WaSP's speedup over the baseline").
    pub x_label: String,
    /// The series (the bars of each row, top to bottom).
    pub series: Vec<TornadoSeries>,
    /// The rows, in any order: drawn widest (largest span) on top.
    pub rows: Vec<TornadoRow>,
    /// What the references are, in the legend (e.g. "shipped machine").
    pub reference_label: String,
    /// The values are fractions, labelled as percentages.
    pub percent: bool,
}

/// Draws `chart` into `path`, a PNG or an SVG by the file's extension.
///
/// Errors (starting with `drawing <title>:` or naming the file): another
/// extension; no series or no rows; a row whose span count is not the
/// series count; a non-finite value or reference; a span whose low is
/// above its high; a file that cannot be written.
pub fn draw_tornado(chart: &TornadoChart, path: &Path) -> Result<(), String> {
    let (who, n) = (who(&chart.title), chart.series.len());
    let nothing = "no series or no rows: nothing to draw";
    ensure(n > 0 && !chart.rows.is_empty(), || {
        format!("{who}: {nothing}")
    })?;
    for s in &chart.series {
        let what = format_args!("the reference of `{}`", s.name);
        finite(&who, what, s.reference.unwrap_or(0.0))?;
    }
    for r in &chart.rows {
        let (p, spans) = (&r.parameter, r.spans.len());
        ensure(spans == n, || {
            format!("{who}: row `{p}` has {spans} spans for {n} series")
        })?;
        for s in r.spans.iter().flatten() {
            let ((lo, _), (hi, _)) = (&s.low, &s.high);
            finite(&who, format_args!("row `{p}`"), lo + hi)?;
            ensure(lo <= hi, || {
                format!("{who}: row `{p}` has a low {lo} above its high {hi}")
            })?;
        }
    }
    write(&who, path, || Tornado::new(chart))
}

/// A tornado chart laid out: the rows widest first, the x range, the
/// width of the parameter names left of the plot.
struct Tornado<'a> {
    c: &'a TornadoChart,
    frame: Frame<'a>,
    colours: Vec<RGBColor>,
    order: Vec<usize>,
    x: std::ops::Range<f64>,
    left: f64,
}

impl<'a> Tornado<'a> {
    fn new(c: &'a TornadoChart) -> Self {
        let spans = |r: &'a TornadoRow| r.spans.iter().flatten();
        let width = |r| spans(r).map(|s| s.high.0 - s.low.0).fold(0.0, f64::max);
        let mut order: Vec<usize> = (0..c.rows.len()).collect();
        order.sort_by(|&a, &b| width(&c.rows[b]).total_cmp(&width(&c.rows[a])));
        let ends = |s: &Span| [s.low.0, s.high.0];
        let ends = c.rows.iter().flat_map(spans).flat_map(ends);
        let refs: Vec<f64> = c.series.iter().filter_map(|s| s.reference).collect();
        let x = range(ends, &refs);
        // Room for the end labels either side.
        let pad = 0.14 * (x.end - x.start);
        let name = |r: &TornadoRow| text_size(&r.parameter, LABEL, false).0;
        let left = c.rows.iter().map(name).fold(0.0, f64::max) + 24.0;
        let colours = series_colours(&c.series.iter().map(|s| s.key).collect::<Vec<_>>());
        let series = || c.series.iter().zip(&colours);
        let block = |(s, &k): (&TornadoSeries, _)| (s.name.clone(), Swatch::Block(k));
        let mut legend: Vec<_> = series().map(block).collect();
        for (s, &k) in series() {
            let Some(v) = s.reference else { continue };
            let (label, value) = (&c.reference_label, value_label(v, c.percent));
            let text = format!("{label}, {}: {value}", s.name);
            legend.push((text, Swatch::Line(shade(k, 0.62).stroke_width(2), None)));
        }
        let frame = Frame::new((&c.title, &c.subtitle), legend, left, 1200.0);
        let x = x.start - pad..x.end + pad;
        Tornado {
            c,
            frame,
            colours,
            order,
            x,
            left,
        }
    }
}

impl Picture for Tornado<'_> {
    fn size(&self) -> (u32, u32) {
        let rows = self.c.rows.len() as f64 * (22.0 * self.c.series.len() as f64 + 18.0);
        let height = f64::from(self.frame.height()) + rows + 90.0;
        (1200, height.max(500.0) as u32)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Drawn<DB> {
        let (c, s) = (self.c, self.c.series.len() as f64);
        let area = self.frame.draw(root)?;
        // Row i spans y from i to i + 1: the widest row on top.
        let rows = self
            .order
            .iter()
            .rev()
            .map(|&r| c.rows[r].parameter.clone());
        let y = Ticked::categories(&rows.collect::<Vec<_>>());
        let x = Ticked::numeric(&self.x, 10, c.percent);
        let pad = (self.left, 64.0, 10.0, 40.0);
        let mut chart = builder(&area, pad).build_cartesian_2d(x, y)?;
        let mut mesh = chart.configure_mesh();
        style_mesh(&mut mesh);
        mesh.disable_y_mesh().x_desc(&c.x_label).draw()?;
        let (p, pixel) = (plot_rect(&chart), pixel_of(&chart));
        // The bars of a row over 70% of it, none thicker than 28 pixels:
        // `bar` is a bar's thickness in rows.
        let bar = (0.7 / s).min(28.0 / (pixel(0.0, 0.0).1 - pixel(0.0, 1.0).1));
        let (mut placer, mut labels) = (Placer::default(), Vec::new());
        for (i, &r) in self.order.iter().rev().enumerate() {
            for (j, (span, &colour)) in c.rows[r].spans.iter().zip(&self.colours).enumerate() {
                let Some(span) = span else { continue };
                let top = i as f64 + (1.0 + s * bar) / 2.0 - j as f64 * bar;
                let corners = [(span.low.0, top - bar), (span.high.0, top)];
                chart.draw_series(std::iter::once(Rectangle::new(corners, colour.filled())))?;
                let (x0, y0, x1, y1) = rect_of(&pixel, corners[0], corners[1]);
                placer.take((x0, y0, x1.max(x0 + 1.0), y1));
                let (low, high, mid) = (&span.low.1, &span.high.1, (y0 + y1) / 2.0);
                labels.push((outward((x0, mid), low, -1.0), low.as_str(), BLACK));
                labels.push((outward((x1, mid), high, 1.0), high.as_str(), BLACK));
            }
        }
        // The references over the bars.
        for (s, &colour) in c.series.iter().zip(&self.colours) {
            let Some(v) = s.reference else { continue };
            let line = vec![(v, 0.0), (v, c.rows.len() as f64)];
            let style = shade(colour, 0.62).stroke_width(2);
            chart.draw_series(std::iter::once(PathElement::new(line, style)))?;
            let x = pixel(v, 0.0).0;
            placer.take((x - 3.0, p.1, x + 3.0, p.3));
        }
        placer.draw_all(root, labels, p)
    }
}

/// Places for `text` beside a bar's end at `(x, mid)`, right (`dir` 1) or
/// left (-1) of it, moving outwards past what it would cover.
fn outward((x, mid): (f64, f64), text: &str, dir: f64) -> Vec<Rect> {
    let (w, h) = text_size(text, SMALL, false);
    let at = |d: u32| (x + dir * (4.0 + 6.0 * f64::from(d) + w / 2.0), mid);
    (0..12).map(|d| around(at(d), (w / 2.0, h / 2.0))).collect()
}

#[cfg(test)]
mod tests {
    use super::super::tests::{out, pixels, refused, same_twice, texts, Case};
    use super::*;
    use crate::palette::Key;

    /// The span from `lo` (at the parameter value `l`) to `hi` (at `h`).
    fn span(lo: f64, l: &str, hi: f64, h: &str) -> Option<Span> {
        let (low, high) = ((lo, l.into()), (hi, h.into()));
        Some(Span { low, high })
    }

    /// WaSP's speedup range over three parameters, for 3D and 2D scenes.
    fn gains() -> TornadoChart {
        let row = |parameter: &str, spans| TornadoRow {
            parameter: parameter.into(),
            spans,
        };
        let series = |key, name: &str, r| TornadoSeries {
            key,
            name: name.into(),
            reference: Some(r),
        };
        let mshrs = vec![
            span(-0.032, "8 MSHRs", 0.005, "31 MSHRs"),
            span(-0.01, "8 MSHRs", 0.03, "31 MSHRs"),
        ];
        let warps = vec![
            span(-0.013, "128 warps", 0.03, "32 warps"),
            span(0.0, "128 warps", 0.045, "32 warps"),
        ];
        let issue = vec![span(0.0, "lrr", 0.004, "gto"), None];
        TornadoChart {
            title: "What decides WaSP's gain".into(),
            subtitle: "speedup range over each parameter's range".into(),
            x_label: "WaSP's speedup over the baseline".into(),
            series: vec![
                series(Key::ThreeD, "3D", 0.001),
                series(Key::TwoD, "2D", 0.02),
            ],
            rows: vec![
                row("l0.mshrs", mshrs),
                row("core.max_warps", warps),
                row("core.issue", issue),
            ],
            reference_label: "shipped machine".into(),
            percent: true,
        }
    }

    #[test]
    fn rows_are_sorted_by_width_and_ends_labelled() {
        let path = out("tornado", "gains.svg");
        draw_tornado(&gains(), &path).expect("draw svg");
        let want = "What decides WaSP's gain|3D|2D|32 warps|128 warps|8 MSHRs|31 MSHRs|gto";
        let placed = texts(&path, &format!("{want}|shipped machine, 2D: 2.0%"));
        let y = |t: &str| placed.iter().find(|p| p.0 == t).map_or(0.0, |p| p.2);
        assert!(y("core.max_warps") < y("l0.mshrs") && y("l0.mshrs") < y("core.issue"));
        let path = out("tornado", "gains.png");
        draw_tornado(&gains(), &path).expect("draw png");
        let d3 = pixels(&path, Key::ThreeD.colour().unwrap());
        let d2 = pixels(&path, Key::TwoD.colour().unwrap());
        assert!(d3 > 1000 && d2 > 1000, "{d3} 3D and {d2} 2D pixels");
        same_twice("tornado-same", &|p| draw_tornado(&gains(), p));
        let cases: &[Case<TornadoChart>] = &[
            (
                |c| drop(c.rows[0].spans.pop()),
                "row `l0.mshrs` has 1 spans for 2",
            ),
            (
                |c| c.rows[1].spans[0].as_mut().unwrap().low.0 = 0.5,
                "a low 0.5 above",
            ),
            (
                |c| c.series[1].reference = Some(f64::NAN),
                "the reference of `2D`",
            ),
            (|c| c.rows.clear(), "no series or no rows"),
        ];
        refused(("tornado-bad", &gains(), ""), draw_tornado, cases);
    }
}
