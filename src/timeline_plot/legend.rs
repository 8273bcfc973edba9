//! The legend strip to the right of a panel: a heading over one swatch and
//! label per series, in as many columns as the strip's height needs.

use super::error::drawing;
use super::marks::{pointer, Look, TICK};
use crate::fonts::font;
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// How a legend entry shows its series.
pub(super) enum Swatch {
    Line(ShapeStyle),
    Mark(ShapeStyle, Look),
    /// A tile's start (true) or end line, upright, with its pointer.
    Tile(ShapeStyle, bool),
    Band(RGBColor),
    Block(RGBColor),
}

/// A legend: `heading` over one row per entry, in as many columns as the
/// strip's height needs.
pub(super) fn legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    heading: &str,
    entries: &[(String, Swatch)],
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let (w, h) = area.dim_in_pixel();
    let (w, h) = (w as i32, h as i32);
    area.draw_text(heading, &font(19, true).color(&BLACK), (8, 34))
        .map_err(drawing)?;
    let y_start = 58;
    let avail = (h - y_start - 6).max(16);
    let mut row_h = 22;
    let mut per_col = (avail / row_h).max(1) as usize;
    if entries.len() > per_col {
        row_h = 18;
        per_col = (avail / row_h).max(1) as usize;
    }
    let columns = entries.len().div_ceil(per_col).max(1) as i32;
    let col_w = (w - 8) / columns;
    let font_size = if columns > 1 { 15 } else { 17 };
    let swatch_w = if columns > 1 { 16 } else { 28 };
    for (i, (label, swatch)) in entries.iter().enumerate() {
        let x = 8 + (i / per_col) as i32 * col_w;
        let y = y_start + (i % per_col) as i32 * row_h;
        let mid = y + row_h / 2 - 2;
        let (x0, x1) = (x, x + swatch_w);
        draw_swatch(area, swatch, (x0, x1), mid)?;
        area.draw_text(
            label,
            &font(font_size, false)
                .color(&BLACK)
                .pos(Pos::new(HPos::Left, VPos::Center)),
            (x1 + 6, mid),
        )
        .map_err(drawing)?;
    }
    Ok(())
}

/// Draw `swatch` from `x0` to `x1`, centred on row `mid`.
fn draw_swatch<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    swatch: &Swatch,
    (x0, x1): (i32, i32),
    mid: i32,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    match swatch {
        Swatch::Line(style) | Swatch::Mark(style, Look::Line) => area
            .draw(&PathElement::new(vec![(x0, mid), (x1, mid)], *style))
            .map_err(drawing),
        Swatch::Mark(style, Look::Dashed) => area
            .draw(&DashedPathElement::new(
                vec![(x0, mid), (x1, mid)],
                5,
                3,
                *style,
            ))
            .map_err(drawing),
        Swatch::Mark(style, look) => draw_ticks(area, *style, *look, (x0, x1), mid),
        Swatch::Tile(style, start) => draw_tile_line(area, *style, *start, x0 + (x1 - x0) / 2, mid),
        Swatch::Band(c) => {
            area.draw(&Rectangle::new(
                [(x0, mid - 6), (x1, mid + 6)],
                c.mix(0.18).filled(),
            ))
            .map_err(drawing)?;
            area.draw(&PathElement::new(
                vec![(x0, mid), (x1, mid)],
                c.stroke_width(2),
            ))
            .map_err(drawing)
        }
        Swatch::Block(c) => area
            .draw(&Rectangle::new([(x0, mid - 6), (x1, mid + 6)], c.filled()))
            .map_err(drawing),
    }
}

/// A stretch of panel edge with three ticks on it (top or bottom ticks, as
/// `look` says).
fn draw_ticks<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    style: ShapeStyle,
    look: Look,
    (x0, x1): (i32, i32),
    mid: i32,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let swatch_w = x1 - x0;
    let tick = TICK as i32 - 2;
    let (edge, end) = if look == Look::TopTick {
        (mid - tick / 2, mid + tick / 2)
    } else {
        (mid + tick / 2, mid - tick / 2)
    };
    area.draw(&PathElement::new(vec![(x0, edge), (x1, edge)], BLACK))
        .map_err(drawing)?;
    for k in 0..3 {
        let x = x0 + 4 + k * (swatch_w - 8) / 2;
        area.draw(&PathElement::new(vec![(x, edge), (x, end)], style))
            .map_err(drawing)?;
    }
    Ok(())
}

/// A tile's start (solid) or end (dashed) line, upright at `x`, with its
/// pointer on top.
fn draw_tile_line<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    style: ShapeStyle,
    start: bool,
    x: i32,
    mid: i32,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let line = vec![(x, mid - 9), (x, mid + 9)];
    if start {
        area.draw(&PathElement::new(line, style))
    } else {
        area.draw(&DashedPathElement::new(line, 4, 3, style))
    }
    .map_err(drawing)?;
    let tip = pointer(start)
        .into_iter()
        .map(|(dx, dy)| (x + dx, mid - 9 + dy));
    let fill = ShapeStyle {
        filled: true,
        ..style
    };
    area.draw(&Polygon::new(tip.collect::<Vec<_>>(), fill))
        .map_err(drawing)
}
