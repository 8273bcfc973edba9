//! The tile marks of the timeline: where tiles start and end, merged per
//! pixel column, how each mark looks (lines with a pointer, or ticks when
//! dense), and the tile numbers beside the starts.

use super::colours::{core_colour, TILE_END, TILE_START};
use super::error::drawing;
use super::panel::Chart;
use crate::fonts::font;
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use std::collections::BTreeMap;
use wasp_sim::timeline::Timeline;

/// A tile mark as drawn: at `x`, of `core` (per-core-tile) or all.
#[derive(Clone, Copy, Debug)]
pub(super) struct Mark {
    pub(super) x: f64,
    pub(super) tile: u32,
    pub(super) core: Option<u32>,
    pub(super) start: bool,
}

/// The timeline's tile marks within the cycle axis, at most one per pixel
/// column, core and kind (a start and an end in one column are both kept).
/// Ends are drawn at the end of their cycle.
pub(super) fn merge_marks<DB: DrawingBackend>(t: &Timeline, chart: &Chart<'_, DB>) -> Vec<Mark> {
    let area = chart.plotting_area();
    let range = chart.x_range();
    let mut seen: BTreeMap<(i32, Option<u32>, bool), Mark> = BTreeMap::new();
    for m in &t.marks {
        let x = if m.start {
            m.cycle as f64
        } else {
            m.cycle.saturating_add(1) as f64
        };
        if x < range.start || x > range.end {
            continue;
        }
        let px = area.map_coordinate(&(x, 0.0)).0;
        let mark = Mark {
            x,
            tile: m.tile,
            core: m.core,
            start: m.start,
        };
        seen.entry((px, m.core, m.start)).or_insert(mark);
    }
    let mut marks: Vec<Mark> = seen.into_values().collect();
    marks.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.start.cmp(&b.start)));
    marks
}

/// How a tile mark looks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Look {
    /// A solid line across the panel (a tile start).
    Line,
    /// A dashed line across the panel (a tile end).
    Dashed,
    /// A short tick down from the panel's top edge (a start, dense marks).
    TopTick,
    /// A short tick up from the panel's bottom edge (an end, dense marks).
    BottomTick,
}

/// Length of a tick mark in pixels.
pub(super) const TICK: u32 = 10;

/// The colour and width of a mark of `core` (None: shared-tile dispatch):
/// starts dark and ends red, or both thin in the core's colour.
pub(super) fn mark_colour(core: Option<u32>, start: bool) -> (RGBColor, u32) {
    match (core, start) {
        (None, true) => (TILE_START, 2),
        (None, false) => (TILE_END, 2),
        (Some(c), _) => (core_colour(c as usize), 1),
    }
}

/// How a tile mark in `colour` and `width` is drawn. Starts are solid
/// lines, ends dashed ones; when the marks are `dense`, full-height lines
/// would hide the data, so starts are ticks at the top of each panel and
/// ends ticks at the bottom.
pub(super) fn mark_look(
    colour: RGBColor,
    width: u32,
    start: bool,
    dense: bool,
) -> (ShapeStyle, Look) {
    match (dense, start) {
        (false, true) => (colour.mix(0.85).stroke_width(width), Look::Line),
        (false, false) => (colour.mix(0.85).stroke_width(width), Look::Dashed),
        (true, true) => (colour.stroke_width(1), Look::TopTick),
        (true, false) => (colour.stroke_width(1), Look::BottomTick),
    }
}

/// The pointer at the top of a tile line, as pixel offsets from the top of
/// the line: a start points right (the tile runs on to the right), an end
/// points left, so a tile ending where the next starts shows both.
pub(super) fn pointer(start: bool) -> Vec<(i32, i32)> {
    let d = if start { 1 } else { -1 };
    vec![(0, 0), (9 * d, 5), (0, 10)]
}

/// The tile marks across `chart` (see [`mark_look`], [`mark_colour`] and
/// [`pointer()`]).
pub(super) fn draw_marks<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    marks: &[Mark],
    dense: bool,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let (y0, y1) = {
        let r = chart.y_range();
        (r.start, r.end)
    };
    let plot_h = f64::from(chart.plotting_area().dim_in_pixel().1.max(1));
    let tick = (y1 - y0) * f64::from(TICK) / plot_h;
    for m in marks {
        let (colour, width) = mark_colour(m.core, m.start);
        let (style, look) = mark_look(colour, width, m.start, dense);
        if !dense {
            let tip = Polygon::new(pointer(m.start), colour.filled());
            chart
                .draw_series(std::iter::once(EmptyElement::at((m.x, y1)) + tip))
                .map_err(drawing)?;
        }
        let line = match look {
            Look::Line | Look::Dashed => vec![(m.x, y0), (m.x, y1)],
            Look::TopTick => vec![(m.x, y1 - tick), (m.x, y1)],
            Look::BottomTick => vec![(m.x, y0), (m.x, y0 + tick)],
        };
        if look == Look::Dashed {
            chart
                .draw_series(std::iter::once(DashedPathElement::new(line, 7, 5, style)))
                .map_err(drawing)?;
        } else {
            chart
                .draw_series(std::iter::once(PathElement::new(line, style)))
                .map_err(drawing)?;
        }
    }
    Ok(())
}

/// Tile numbers at the top of panel 1 beside their start lines: `tile N`
/// (shared-tile) or `N` in the core's colour, one row per core
/// (per-core-tile, rows repeating past four cores); a label that would
/// overlap the previous one in its row is left out.
pub(super) fn label_tiles<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    chart: &Chart<'_, DB>,
    marks: &[Mark],
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let area = chart.plotting_area();
    let top = chart.y_range().end;
    let right = area.map_coordinate(&(chart.x_range().end, top)).0;
    let mut next_free: BTreeMap<Option<u32>, i32> = BTreeMap::new();
    for m in marks.iter().filter(|m| m.start) {
        let (px, py) = area.map_coordinate(&(m.x, top));
        let (text, colour, row) = match m.core {
            None => (format!("tile {}", m.tile), TILE_START, 0),
            Some(c) => (
                format!("{}", m.tile),
                core_colour(c as usize),
                (c % 4) as i32,
            ),
        };
        let style = font(16, false).color(&colour);
        let width = root.estimate_text_size(&text, &style).map_err(drawing)?.0 as i32;
        let x = px + 11;
        if next_free.get(&m.core).is_some_and(|&f| x < f) || x + width > right {
            continue;
        }
        next_free.insert(m.core, x + width + 6);
        let y = py + 3 + 16 * row;
        root.draw(&Rectangle::new(
            [(x - 1, y), (x + width + 1, y + 14)],
            WHITE.mix(0.75).filled(),
        ))
        .map_err(drawing)?;
        root.draw_text(&text, &style, (x, y)).map_err(drawing)?;
    }
    Ok(())
}
