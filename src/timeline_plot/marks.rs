//! The tile marks of the timeline: where tiles start and end, merged per
//! pixel column, how each mark looks (lines with a pointer, or ticks when
//! dense) and its legend entry, and the tile numbers beside the starts.

use super::panel::Panel;
use crate::charts::frame::{Area, Drawn};
use crate::charts::legend::{tile, Swatch};
use crate::fonts::font;
use crate::palette::{other, TILE_END, TILE_START};
use plotters::prelude::*;
use std::collections::BTreeMap;
use wasp_sim::timeline::Timeline;

/// Length of a tick mark in pixels.
const TICK: i32 = 10;

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
pub(super) fn merge_marks<DB: DrawingBackend>(t: &Timeline, chart: &Panel<'_, DB>) -> Vec<Mark> {
    let (area, range) = (chart.plotting_area(), chart.x_range());
    let mut seen: BTreeMap<(i32, Option<u32>, bool), Mark> = BTreeMap::new();
    for m in &t.marks {
        let x = m.cycle.saturating_add(u64::from(!m.start)) as f64;
        if x < range.start || x > range.end {
            continue;
        }
        let px = area.map_coordinate(&(x, 0.0)).0;
        let (tile, core, start) = (m.tile, m.core, m.start);
        let mark = Mark {
            x,
            tile,
            core,
            start,
        };
        seen.entry((px, m.core, m.start)).or_insert(mark);
    }
    let mut marks: Vec<Mark> = seen.into_values().collect();
    marks.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.start.cmp(&b.start)));
    marks
}

/// The colour and width of a mark of `core` (None: shared-tile dispatch):
/// starts dark and ends red, or both thin in the core's colour.
fn mark_colour(core: Option<u32>, start: bool) -> (RGBColor, u32) {
    match (core, start) {
        (None, true) => (TILE_START, 2),
        (None, false) => (TILE_END, 2),
        (Some(c), _) => (other(c as usize), 1),
    }
}

/// The style of a mark of `core`: a full line or, `dense`, a tick.
pub(super) fn mark_style(core: Option<u32>, start: bool, dense: bool) -> ShapeStyle {
    let (colour, width) = mark_colour(core, start);
    match dense {
        false => colour.mix(0.85).stroke_width(width),
        true => colour.stroke_width(1),
    }
}

/// The legend entries of the tile marks as drawn: shared marks in their
/// own colours, per-core ones in grey for the core's colour.
pub(super) fn mark_entries(marks: &[Mark], dense: bool) -> Vec<(String, Swatch)> {
    let shared = marks.iter().all(|m| m.core.is_none());
    let suffix = if shared { "" } else { " (core colour)" };
    let entry = |start: bool| {
        let style = match shared {
            true => mark_style(None, start, dense),
            false => RGBColor(90, 90, 90).stroke_width(1),
        };
        let (kind, edge) = [("end", "bottom"), ("start", "top")][usize::from(start)];
        match dense {
            false => (format!("tile {kind}{suffix}"), Swatch::Tile(style, start)),
            true => (
                format!("tile {kind} ({edge} ticks)"),
                Swatch::Ticks(style, start),
            ),
        }
    };
    vec![entry(true), entry(false)]
}

/// The tile marks across `chart`: a start a solid line, an end a dashed
/// one, each with its pointer at the top ([`tile()`]); when `dense`,
/// full-height lines would hide the data, so starts are ticks down from
/// the panel's top and ends ticks up from its bottom.
pub(super) fn draw_marks<DB: DrawingBackend>(
    chart: &mut Panel<'_, DB>,
    marks: &[Mark],
    dense: bool,
) -> Drawn<DB> {
    let (y0, y1) = (chart.y_range().start, chart.y_range().end);
    let plot_h = chart.plotting_area().dim_in_pixel().1 as i32;
    for m in marks {
        let style = mark_style(m.core, m.start, dense);
        if dense {
            let (y, d) = if m.start { (y1, TICK) } else { (y0, -TICK) };
            let tick = PathElement::new(vec![(0, 0), (0, d)], style);
            chart.draw_series(std::iter::once(EmptyElement::at((m.x, y)) + tick))?;
        } else {
            chart.draw_series(std::iter::once(tile((m.x, y1), style, m.start, plot_h)))?;
        }
    }
    Ok(())
}

/// Tile numbers at the top of panel 1 beside their start lines: `tile N`
/// (shared-tile) or `N` in the core's colour, one row per core
/// (per-core-tile, rows repeating past four cores); a label that would
/// overlap the previous one in its row is left out.
pub(super) fn label_tiles<DB: DrawingBackend>(
    root: &Area<DB>,
    chart: &Panel<'_, DB>,
    marks: &[Mark],
) -> Drawn<DB> {
    let area = chart.plotting_area();
    let top = chart.y_range().end;
    let right = area.map_coordinate(&(chart.x_range().end, top)).0;
    let mut next_free: BTreeMap<Option<u32>, i32> = BTreeMap::new();
    for m in marks.iter().filter(|m| m.start) {
        let (px, py) = area.map_coordinate(&(m.x, top));
        let (text, colour, row) = match m.core {
            None => (format!("tile {}", m.tile), TILE_START, 0),
            Some(c) => (m.tile.to_string(), other(c as usize), (c % 4) as i32),
        };
        let style = font(16, false).color(&colour);
        let width = root.estimate_text_size(&text, &style)?.0 as i32;
        let x = px + 11;
        if next_free.get(&m.core).is_some_and(|&f| x < f) || x + width > right {
            continue;
        }
        next_free.insert(m.core, x + width + 6);
        let y = py + 3 + 16 * row;
        let back = [(x - 1, y), (x + width + 1, y + 14)];
        root.draw(&Rectangle::new(back, WHITE.mix(0.75).filled()))?;
        root.draw_text(&text, &style, (x, y))?;
    }
    Ok(())
}
