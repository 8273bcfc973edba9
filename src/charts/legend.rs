//! Legends and markers of every picture (charts and the timeline): how an
//! entry shows what it names ([`Swatch`]), the legend drawn through
//! plotters' series labels beside the plot, so that it hides no data
//! ([`legend`]), and the markers of points and of the paper's values,
//! built from plotters' marker elements ([`marker`]).

use crate::fonts::font;
use crate::palette::INK;
use plotters::coord::Shift;
use plotters::element::{DashedPathElement, Drawable, DynElement, PointCollection};
use plotters::prelude::*;
use plotters_backend::{BackendCoord, DrawingErrorKind};

/// Width of a legend's swatches.
const SWATCH: i32 = 30;

/// Elements drawn at pixel offsets from one point `.0` (in any
/// coordinates). Plotters' `EmptyElement` composition does the same but
/// holds dynamic elements only for backends that live forever.
pub(crate) struct Parts<'a, DB: DrawingBackend, C>(C, Vec<DynElement<'a, DB, BackendCoord>>);

impl<'b, DB: DrawingBackend, C> PointCollection<'b, C> for &'b Parts<'_, DB, C> {
    type Point = &'b C;
    type IntoIter = std::iter::Once<&'b C>;

    fn point_iter(self) -> Self::IntoIter {
        std::iter::once(&self.0)
    }
}

impl<DB: DrawingBackend, C> Drawable<DB> for Parts<'_, DB, C> {
    fn draw<I: Iterator<Item = BackendCoord>>(
        &self,
        mut at: I,
        backend: &mut DB,
        size: (u32, u32),
    ) -> Result<(), DrawingErrorKind<DB::ErrorType>> {
        let Some((x, y)) = at.next() else {
            return Ok(());
        };
        for part in &self.1 {
            let points = part.point_iter().iter().map(|p| (p.0 + x, p.1 + y));
            part.draw(points, backend, size)?;
        }
        Ok(())
    }
}

/// The marker shapes of line series (series k has shape k mod 4): plotters'
/// marker elements.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Shape {
    Circle,
    Square,
    Triangle,
    Cross,
}

impl Shape {
    /// The shape of series `s`.
    pub fn of(s: usize) -> Shape {
        [Shape::Circle, Shape::Square, Shape::Triangle, Shape::Cross][s % 4]
    }

    /// The element of this shape at (0, 0), `r` pixels from centre to edge.
    fn element<'a, DB: DrawingBackend + 'a>(
        self,
        r: i32,
        s: ShapeStyle,
    ) -> DynElement<'a, DB, BackendCoord> {
        match self {
            Shape::Circle => Circle::new((0, 0), r, s).into_dyn(),
            Shape::Square => Rectangle::new([(1 - r, 1 - r), (r - 1, r - 1)], s).into_dyn(),
            Shape::Triangle => TriangleMarker::new((0, 0), r + 1, s).into_dyn(),
            Shape::Cross => Cross::new((0, 0), r - 1, s.stroke_width(2)).into_dyn(),
        }
    }
}

/// A marker of `shape` at `at` (in any coordinates), `r` pixels from
/// centre to edge: filled in `colour`, or hollow (white inside).
pub(crate) fn marker<'a, DB: DrawingBackend + 'a, C>(
    at: C,
    (shape, r): (Shape, i32),
    colour: impl Color,
    hollow: bool,
) -> Parts<'a, DB, C> {
    let mut parts = vec![shape.element(r, colour.filled())];
    if hollow && shape != Shape::Cross {
        let inside = r - 2 - i32::from(shape == Shape::Triangle);
        parts.push(shape.element(inside, WHITE.filled()));
    }
    Parts(at, parts)
}

/// How a legend entry shows what it names.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Swatch {
    /// A filled block (bars, stacked areas).
    Block(RGBColor),
    /// A line, through a filled marker if any (a line series).
    Line(ShapeStyle, Option<Shape>),
    /// A dashed line, through a hollow marker if any (the paper's values,
    /// the warp slots).
    Dashed(ShapeStyle, Option<Shape>),
    /// A line in a light band (a series' minimum to maximum).
    Band(RGBColor),
    /// An upright line with a pointer on top: a tile's start (solid,
    /// pointing right) or end (dashed, pointing left).
    Tile(ShapeStyle, bool),
    /// Three ticks down from a top edge (true) or up from a bottom edge.
    Ticks(ShapeStyle, bool),
}

impl Swatch {
    /// The swatch as an element of the legend row whose left middle is
    /// `at`.
    pub fn element<'a, DB: DrawingBackend + 'a>(
        self,
        at: BackendCoord,
    ) -> Parts<'a, DB, BackendCoord> {
        let (line, mid) = (vec![(0, 0), (SWATCH, 0)], (SWATCH / 2, 0));
        let parts = match self {
            Swatch::Block(c) => {
                vec![Rectangle::new([(4, -7), (SWATCH - 4, 7)], c.filled()).into_dyn()]
            }
            Swatch::Line(s, shape) => {
                let mark = shape.map(|m| marker(mid, (m, 6), s.color, false).into_dyn());
                let solid = PathElement::new(line, s).into_dyn();
                [solid].into_iter().chain(mark).collect()
            }
            Swatch::Dashed(s, shape) => {
                let mark = shape.map(|m| marker(mid, (m, 6), s.color, true).into_dyn());
                let dashes = DashedPathElement::new(line, 5, 3, s).into_dyn();
                [dashes].into_iter().chain(mark).collect()
            }
            Swatch::Band(c) => vec![
                Rectangle::new([(0, -6), (SWATCH, 6)], c.mix(0.18).filled()).into_dyn(),
                PathElement::new(line, c.stroke_width(2)).into_dyn(),
            ],
            Swatch::Tile(s, start) => return tile((at.0 + mid.0, at.1 - 9), s, start, 18),
            Swatch::Ticks(s, top) => {
                let (edge, d) = if top { (-4, 8) } else { (4, -8) };
                let tick = |t| PathElement::new(vec![(t, edge), (t, edge + d)], s).into_dyn();
                let rule = PathElement::new(vec![(0, edge), (SWATCH, edge)], INK).into_dyn();
                vec![rule, tick(4), tick(SWATCH / 2), tick(SWATCH - 4)]
            }
        };
        Parts(at, parts)
    }
}

/// A tile's start (solid) or end (dashed) line from `top` (in any
/// coordinates) `len` pixels down, with an opaque pointer on top: a start
/// points right (the tile runs on to the right), an end points left, so a
/// tile ending where the next starts shows both.
pub(crate) fn tile<'a, DB: DrawingBackend + 'a, C>(
    top: C,
    s: ShapeStyle,
    start: bool,
    len: i32,
) -> Parts<'a, DB, C> {
    let ((r, g, b), d) = (s.color.rgb(), if start { 1 } else { -1 });
    let tip = Polygon::new(
        vec![(0, 0), (9 * d, 5), (0, 10)],
        RGBColor(r, g, b).filled(),
    );
    let line = vec![(0, 0), (0, len)];
    let line = match start {
        true => PathElement::new(line, s).into_dyn(),
        false => DashedPathElement::new(line, 7, 5, s).into_dyn(),
    };
    Parts(top, vec![line, tip.into_dyn()])
}

/// The entries of a legend: the text and how it looks.
pub(crate) type Legend = Vec<(String, Swatch)>;

/// The height in pixels of a line of a legend in the font of `size`.
pub(crate) fn line_height(size: u32) -> f64 {
    f64::from(size) * 1.25
}

/// The width in pixels of a legend column of `entries` in the font of
/// `size`: swatch, gap, widest text, gap.
fn column_width(entries: &[(String, Swatch)], size: u32) -> f64 {
    let text =
        |e: &(String, Swatch)| f64::from(font(size, false).box_size(&e.0).map_or(0, |b| b.0));
    f64::from(SWATCH + 8) + entries.iter().map(text).fold(0.0, f64::max) + 24.0
}

/// The fewest lines a column of `legend` (font of `size`) needs so that
/// its columns fit in `width` pixels.
pub(crate) fn rows(legend: &[(String, Swatch)], size: u32, width: f64) -> usize {
    let fits = |&r: &usize| {
        let columns = legend.chunks(r).map(|c| column_width(c, size));
        columns.sum::<f64>() <= width
    };
    (1..legend.len().max(1)).find(fits).unwrap_or(legend.len())
}

/// Draws `legend` on `area` through plotters' series labels, in columns of
/// `rows` lines in the font of `size`: each column a chart whose series
/// are the entries (their labels and swatches), labelled from its top
/// left corner.
pub(crate) fn legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    legend: &[(String, Swatch)],
    (rows, size): (usize, u32),
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (mut x, h) = (0.0, area.dim_in_pixel().1);
    for column in legend.chunks(rows.max(1)) {
        let width = column_width(column, size);
        let part = area.clone().shrink((x as u32, 0), (width as u32, h));
        let mut chart = ChartBuilder::on(&part).build_cartesian_2d(0.0..1.0, 0.0..1.0)?;
        for (label, swatch) in column {
            let (none, swatch) = (std::iter::empty::<Circle<(f64, f64), u32>>(), *swatch);
            let series = chart.draw_series(none)?.label(label);
            series.legend(move |p| swatch.element(p));
        }
        let mut labels = chart.configure_series_labels();
        labels.position(SeriesLabelPosition::Coordinate(0, 0));
        labels.margin(0);
        labels.label_font(font(size, false).color(&BLACK));
        labels.legend_area_size(SWATCH + 8).draw()?;
        x += width;
    }
    Ok(())
}
