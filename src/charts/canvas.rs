//! Drawing in pixels for bar and line charts: the root area with errors as
//! strings, text measurement and styles, marker shapes, and the placement
//! of labels where they hide nothing.

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

/// Rectangles `w` x `h` centred on `x`, the first touching row `y0`, then
/// moving upwards (`up`) or downwards in steps of 3 pixels up to row
/// `limit`: where to try a label over (or under) a bar or marker.
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

#[cfg(test)]
mod tests {
    use super::*;

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
