//! `wasp run --timeline FILE.png|FILE.svg`: draws a [`Timeline`] so that a
//! reader sees each tile's fill and drain.
//!
//! The picture is [`WIDTH`] x [`HEIGHT`] pixels: a title (dispatch mode and
//! window) over three stacked panels that share the cycle axis:
//!
//! 1. the warps resident in each core (one colour per core; y from 0 to a
//!    little above the warp slots, whose count is a dashed line, leaving
//!    room for the tile labels),
//! 2. the misses outstanding per cache level (L0 only on a machine with L0,
//!    L1, L2),
//! 3. the priority warps launched per cycle, stacked by core in the core
//!    colours of panel 1.
//!
//! Tile boundaries are vertical lines in every panel. Shared-tile dispatch:
//! a solid dark line where a tile starts (labelled `tile N` in panel 1) and
//! a dashed one at the end of the cycle its last warp retires. Per-core-tile
//! dispatch: the same two styles, thin and in the colour of the core that
//! takes or finishes the tile (labelled with the tile number in that
//! colour, one row of labels per core).
//!
//! # Long windows
//!
//! When the window has more cycles than the plot has pixel columns, the
//! samples are split into one run of consecutive cycles per pixel column
//! and each column shows, per series, the mean over its cycles as the line
//! and the minimum to maximum as a light band around it; panel 3 shows the
//! mean launches per cycle over the column (so its area still counts the
//! launches). Tile marks falling into the same column are merged: one mark
//! per column, core and kind, and a start hides an end of the same core in
//! that column. When more than one column in ten still has a mark, lines
//! across the panels would hide the data: starts become short ticks down
//! from each panel's top edge and ends ticks up from its bottom edge (same
//! colours), without tile labels. A tile end in the same column as the next
//! tile's start (the usual case under shared-tile dispatch, where the next
//! tile opens the cycle after the last one ends) is hidden by that start.
//! The files stay small (an SVG of a 200,000-cycle window with 800 tiles
//! is under a megabyte) and drawing is fast whatever the window.
//!
//! # Fonts
//!
//! Text is rendered by plotters' `ab_glyph` support from the DejaVu Sans
//! that the `dejavu` crate embeds in the binary, so the picture has its
//! labels and legends on a machine with no fonts installed. (An SVG names
//! the `sans-serif` family; its viewer supplies the glyphs.)

use crate::picture::{is_svg, palette_colour, save, Picture};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::collections::BTreeMap;
use std::path::Path;
use wasp_sim::timeline::Timeline;

use crate::fonts::{font, register_fonts};

/// Width of the picture in pixels.
pub const WIDTH: u32 = 1600;
/// Height of the picture in pixels.
pub const HEIGHT: u32 = 1000;

/// Width of the legend strip to the right of each panel.
mod downsample;

use downsample::{downsample, Agg, Column};

const LEGEND_W: u32 = 230;
/// Height of the title strip.
const TITLE_H: u32 = 58;

/// Colours of the cache levels L0, L1, L2.
const LEVEL_COLOURS: [RGBColor; 3] = [
    RGBColor(106, 61, 154),
    RGBColor(0, 139, 139),
    RGBColor(217, 95, 2),
];

/// Colour of the shared-tile marks.
const MARK_COLOUR: RGBColor = RGBColor(40, 40, 40);

/// Draw `t` into `path`, a PNG or an SVG by the file's extension (`.png`,
/// `.svg`, in any case).
///
/// Errors: another extension, a timeline without samples or with samples
/// that do not match its core count or are out of cycle order, and a file
/// that cannot be written.
pub fn draw(t: &Timeline, path: &Path) -> Result<(), String> {
    let svg = is_svg(path, "a timeline")?;
    check(t)?;
    register_fonts().map_err(drawing)?;
    save(&TimelinePicture(t), "drawing the timeline", path, svg)
}

/// A timeline as a [`Picture`] of [`WIDTH`] x [`HEIGHT`] pixels.
struct TimelinePicture<'a>(&'a Timeline);

impl Picture for TimelinePicture<'_> {
    fn size(&self) -> (u32, u32) {
        (WIDTH, HEIGHT)
    }

    fn render<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String>
    where
        DB::ErrorType: 'static,
    {
        render(self.0, root)
    }
}

/// A drawing error as the CLI reports it.
fn drawing<E: std::fmt::Display>(e: E) -> String {
    format!("drawing the timeline: {e}")
}

/// The checks that keep [`render`] from drawing nonsense.
fn check(t: &Timeline) -> Result<(), String> {
    if t.samples.is_empty() {
        return Err(format!(
            "the timeline of cycles {}..={} has no samples (did the run end before the window?): nothing to draw",
            t.from, t.to
        ));
    }
    let mut last = None;
    for s in &t.samples {
        if s.resident.len() != t.cores || s.priority_launches.len() != t.cores {
            return Err(format!(
                "timeline sample of cycle {}: {} resident counts and {} launch counts for {} cores",
                s.cycle,
                s.resident.len(),
                s.priority_launches.len(),
                t.cores
            ));
        }
        if last.is_some_and(|c| s.cycle <= c) {
            return Err(format!(
                "timeline sample of cycle {} follows cycle {}: samples must be in cycle order",
                s.cycle,
                last.unwrap_or_default()
            ));
        }
        last = Some(s.cycle);
    }
    Ok(())
}

/// The colour of core `c`.
fn core_colour(c: usize) -> RGBColor {
    palette_colour(c)
}

/// How a legend entry shows its series.
enum Swatch {
    Line(ShapeStyle),
    Mark(ShapeStyle, Look),
    Band(RGBColor),
    Block(RGBColor),
}

/// A tile mark as drawn: at `x`, of `core` (per-core-tile) or all.
#[derive(Clone, Copy, Debug)]
struct Mark {
    x: f64,
    tile: u32,
    core: Option<u32>,
    start: bool,
}

type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Draw the whole picture on `root`.
fn render<DB: DrawingBackend>(t: &Timeline, root: &DrawingArea<DB, Shift>) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(drawing)?;
    let (w, h) = root.dim_in_pixel();
    let first = t.samples.first().map_or(t.from, |s| s.cycle);
    let last = t.samples.last().map_or(t.to, |s| s.cycle);
    let x_lo = t.from.min(first) as f64;
    let x_hi = t.to.max(last).saturating_add(1) as f64;
    let n = t.samples.len();

    let (title, body) = root.split_vertically(TITLE_H);
    let body_h = h.saturating_sub(TITLE_H);
    let h1 = body_h * 37 / 100;
    let h2 = body_h * 32 / 100;
    let (p1, rest) = body.split_vertically(h1);
    let (p2, p3) = rest.split_vertically(h2);
    let chart_w = w.saturating_sub(LEGEND_W);
    let (c1, l1) = p1.split_horizontally(chart_w);
    let (c2, l2) = p2.split_horizontally(chart_w);
    let (c3, l3) = p3.split_horizontally(chart_w);

    // Panel 1 first: its plot width sets the number of columns. Above the
    // warp slots it keeps room for the rows of tile labels (one, or one per
    // core up to four under per-core-tile dispatch).
    let top1 = f64::from(t.max_warps.max(1));
    let label_rows = if t.marks.iter().any(|m| m.core.is_some()) {
        t.cores.clamp(1, 4) as u32
    } else {
        1
    };
    // The plot's height: the panel less margins, caption and tick labels.
    let plot_h1 = f64::from(h1.saturating_sub(63).max(100));
    let room = f64::from(10 + 16 * label_rows).min(plot_h1 / 2.0);
    let mut chart1 = panel(
        &c1,
        "Resident warps per core",
        "warps",
        false,
        x_lo..x_hi,
        0.0..top1 * plot_h1 / (plot_h1 - room),
    )?;
    let plot_w = chart1.plotting_area().dim_in_pixel().0.max(1) as usize;
    let cols = downsample(t, plot_w);
    let per_column = n as f64 / cols.len().max(1) as f64;
    let banded = per_column > 1.0;

    let levels: Vec<usize> = if t.has_l0 { vec![0, 1, 2] } else { vec![1, 2] };
    let top2 = cols
        .iter()
        .flat_map(|c| levels.iter().map(move |&l| c.outstanding[l].max))
        .fold(0.0, f64::max)
        .max(1.0);
    let mut chart2 = panel(
        &c2,
        "Outstanding misses per cache level (MSHR entries, summed over the level)",
        "misses",
        false,
        x_lo..x_hi,
        0.0..top2 * 1.08,
    )?;
    let top3 = cols
        .iter()
        .map(|c| c.launches.iter().sum::<f64>())
        .fold(0.0, f64::max);
    let top3 = if top3 > 0.0 { top3 * 1.1 } else { 1.0 };
    let launch_title = if banded {
        "Priority-warp launches per cycle (mean over each pixel column, stacked by core)"
    } else {
        "Priority-warp launches per cycle (stacked by core)"
    };
    let mut chart3 = panel(
        &c3,
        launch_title,
        "launches / cycle",
        true,
        x_lo..x_hi,
        0.0..top3,
    )?;

    // Tile marks, merged per pixel column, behind the data.
    let marks = merge_marks(t, &chart1);
    // Lines for dense marks would hide the data: ticks instead.
    let dense = marks.len() > plot_w / 10;
    for chart in [&mut chart1, &mut chart2, &mut chart3] {
        draw_marks(chart, &marks, dense)?;
    }

    // Panel 1: resident warps, under a dashed line at the warp slots.
    let slots_style = BLACK.mix(0.5).stroke_width(1);
    chart1
        .draw_series(std::iter::once(DashedPathElement::new(
            vec![(x_lo, top1), (x_hi, top1)],
            6,
            4,
            slots_style,
        )))
        .map_err(drawing)?;
    for c in 0..t.cores {
        let colour = core_colour(c);
        series(&mut chart1, &cols, colour, banded, 2, |col| col.resident[c])?;
    }
    if !dense {
        label_tiles(root, &chart1, &marks)?;
    }

    // Panel 2: outstanding misses.
    for &l in &levels {
        series(&mut chart2, &cols, LEVEL_COLOURS[l], banded, 2, |col| {
            col.outstanding[l]
        })?;
    }

    // Panel 3: priority launches, stacked by core; one polygon per run of
    // columns in which the core launched.
    let mut below = vec![0.0; cols.len()];
    for c in 0..t.cores {
        let above: Vec<f64> = cols
            .iter()
            .zip(&below)
            .map(|(col, b)| b + col.launches[c])
            .collect();
        let mut i = 0;
        while i < cols.len() {
            if cols[i].launches[c] == 0.0 {
                i += 1;
                continue;
            }
            let run = i..(i..cols.len())
                .find(|&j| cols[j].launches[c] == 0.0)
                .unwrap_or(cols.len());
            i = run.end;
            let part = &cols[run.clone()];
            let mut outline = steps(part, |k| above[run.start + k]);
            let mut bottom = steps(part, |k| below[run.start + k]);
            bottom.reverse();
            outline.extend(bottom);
            chart3
                .draw_series(std::iter::once(Polygon::new(
                    outline,
                    core_colour(c).filled(),
                )))
                .map_err(drawing)?;
        }
        below = above;
    }

    // Legends.
    let mut entries: Vec<(String, Swatch)> = (0..t.cores)
        .map(|c| {
            (
                format!("core {c}"),
                Swatch::Line(core_colour(c).stroke_width(3)),
            )
        })
        .collect();
    let shared = marks.iter().all(|m| m.core.is_none());
    let (mark_colour, mark_width, suffix) = if shared {
        (MARK_COLOUR, 2, "")
    } else {
        (RGBColor(90, 90, 90), 1, " (core colour)")
    };
    for start in [true, false] {
        let (style, look) = mark_look(mark_colour, mark_width, start, dense);
        let name = match look {
            Look::Line => format!("tile start{suffix}"),
            Look::Dashed => format!("tile end{suffix}"),
            Look::TopTick => "tile start (top ticks)".to_string(),
            Look::BottomTick => "tile end (bottom ticks)".to_string(),
        };
        entries.push((name, Swatch::Mark(style, look)));
    }
    entries.push((
        format!("{} warp slots", t.max_warps),
        Swatch::Mark(slots_style, Look::Dashed),
    ));
    if banded {
        entries.push(("min..max in column".into(), Swatch::Band(core_colour(0))));
    }
    legend(&l1, "Cores", &entries)?;
    let mut entries: Vec<(String, Swatch)> = levels
        .iter()
        .map(|&l| {
            (
                format!("L{l}"),
                Swatch::Line(LEVEL_COLOURS[l].stroke_width(3)),
            )
        })
        .collect();
    if banded {
        entries.push((
            "min..max in column".into(),
            Swatch::Band(LEVEL_COLOURS[levels[0]]),
        ));
    }
    legend(&l2, "Cache levels", &entries)?;
    let entries: Vec<(String, Swatch)> = (0..t.cores)
        .map(|c| (format!("core {c}"), Swatch::Block(core_colour(c))))
        .collect();
    legend(&l3, "Launching core", &entries)?;

    // The title, last: it reports how the window was drawn.
    let head = format!(
        "wasp timeline: {} dispatch, cycles {}..={} ({} cycles, {} cores)",
        t.dispatch,
        t.from,
        t.to,
        t.to.saturating_sub(t.from) + 1,
        t.cores
    );
    title
        .draw_text(&head, &font(27, true).color(&BLACK), (16, 8))
        .map_err(drawing)?;
    let sub = if banded {
        format!(
            "{per_column:.1} cycles per pixel column: lines are column means, light bands the column min..max"
        )
    } else {
        "one sample per cycle".to_string()
    };
    title
        .draw_text(&sub, &font(18, false).color(&BLACK.mix(0.75)), (16, 36))
        .map_err(drawing)?;
    Ok(())
}

/// One panel's chart: caption, axes, grid; the cycle axis labelled only
/// when `bottom`.
fn panel<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    caption: &str,
    y_desc: &str,
    bottom: bool,
    x: std::ops::Range<f64>,
    y: std::ops::Range<f64>,
) -> Result<Chart<'a, DB>, String>
where
    DB::ErrorType: 'static,
{
    let mut chart = ChartBuilder::on(area)
        .caption(caption, font(21, true))
        .margin_left(10)
        .margin_right(14)
        .margin_top(6)
        .margin_bottom(if bottom { 8 } else { 2 })
        .x_label_area_size(if bottom { 52 } else { 28 })
        .y_label_area_size(76)
        .build_cartesian_2d(x, y)
        .map_err(drawing)?;
    let cycle = |v: &f64| {
        if (v - v.round()).abs() < 1e-6 {
            format!("{}", v.round() as i64)
        } else {
            format!("{v:.1}")
        }
    };
    let count = |v: &f64| {
        if (v - v.round()).abs() < 1e-6 {
            format!("{}", v.round() as i64)
        } else {
            let text = format!("{v:.3}");
            text.trim_end_matches('0').to_string()
        }
    };
    let mut mesh = chart.configure_mesh();
    mesh.x_labels(12)
        .y_labels(6)
        .x_label_formatter(&cycle)
        .y_label_formatter(&count)
        .label_style(font(17, false).color(&BLACK))
        .axis_desc_style(font(18, false).color(&BLACK))
        .y_desc(y_desc)
        .bold_line_style(RGBColor(215, 215, 215).stroke_width(1))
        .light_line_style(RGBColor(242, 242, 242).stroke_width(1))
        .max_light_lines(2);
    if bottom {
        mesh.x_desc("cycle");
    }
    mesh.draw().map_err(drawing)?;
    Ok(chart)
}

/// The step outline of `value(i)` over the columns: two points per column.
fn steps(cols: &[Column], value: impl Fn(usize) -> f64) -> Vec<(f64, f64)> {
    cols.iter()
        .enumerate()
        .flat_map(|(i, c)| [(c.x0, value(i)), (c.x1, value(i))])
        .collect()
}

/// One series: the band from the column minima to maxima (when `banded`)
/// and the step line through the column means.
fn series<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    cols: &[Column],
    colour: RGBColor,
    banded: bool,
    width: u32,
    agg: impl Fn(&Column) -> Agg,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    if banded && cols.iter().any(|c| agg(c).max > agg(c).min) {
        let mut outline = steps(cols, |i| agg(&cols[i]).max);
        let mut low = steps(cols, |i| agg(&cols[i]).min);
        low.reverse();
        outline.extend(low);
        chart
            .draw_series(std::iter::once(Polygon::new(
                outline,
                colour.mix(0.18).filled(),
            )))
            .map_err(drawing)?;
    }
    chart
        .draw_series(std::iter::once(PathElement::new(
            steps(cols, |i| agg(&cols[i]).mean),
            colour.stroke_width(width),
        )))
        .map_err(drawing)?;
    Ok(())
}

/// The timeline's tile marks within the cycle axis, at most one per pixel
/// column, core and kind; a start hides an end of the same core in its
/// column. Ends are drawn at the end of their cycle.
fn merge_marks<DB: DrawingBackend>(t: &Timeline, chart: &Chart<'_, DB>) -> Vec<Mark> {
    let area = chart.plotting_area();
    let range = chart.x_range();
    let mut seen: BTreeMap<(i32, Option<u32>), Mark> = BTreeMap::new();
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
        seen.entry((px, m.core))
            .and_modify(|old| {
                if mark.start && !old.start {
                    *old = mark;
                }
            })
            .or_insert(mark);
    }
    let mut marks: Vec<Mark> = seen.into_values().collect();
    marks.sort_by(|a, b| a.x.total_cmp(&b.x));
    marks
}

/// How a tile mark looks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Look {
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
const TICK: u32 = 10;

/// How a tile mark in `colour` and `width` is drawn. Starts are solid
/// lines, ends dashed ones; when the marks are `dense`, full-height lines
/// would hide the data, so starts are ticks at the top of each panel and
/// ends ticks at the bottom.
fn mark_look(colour: RGBColor, width: u32, start: bool, dense: bool) -> (ShapeStyle, Look) {
    match (dense, start) {
        (false, true) => (colour.mix(0.85).stroke_width(width), Look::Line),
        (false, false) => (colour.mix(0.85).stroke_width(width), Look::Dashed),
        (true, true) => (colour.stroke_width(1), Look::TopTick),
        (true, false) => (colour.stroke_width(1), Look::BottomTick),
    }
}

/// The tile marks across `chart` (see [`mark_look`]): shared-tile marks
/// dark, per-core-tile marks thin in the core's colour.
fn draw_marks<DB: DrawingBackend>(
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
        let (colour, width) = match m.core {
            None => (MARK_COLOUR, 2),
            Some(c) => (core_colour(c as usize), 1),
        };
        let (style, look) = mark_look(colour, width, m.start, dense);
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
fn label_tiles<DB: DrawingBackend>(
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
            None => (format!("tile {}", m.tile), MARK_COLOUR, 0),
            Some(c) => (
                format!("{}", m.tile),
                core_colour(c as usize),
                (c % 4) as i32,
            ),
        };
        let style = font(16, false).color(&colour);
        let width = root.estimate_text_size(&text, &style).map_err(drawing)?.0 as i32;
        let x = px + 3;
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

/// A legend: `heading` over one row per entry, in as many columns as the
/// strip's height needs.
fn legend<DB: DrawingBackend>(
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
        match swatch {
            Swatch::Line(style) => area
                .draw(&PathElement::new(vec![(x0, mid), (x1, mid)], *style))
                .map_err(drawing)?,
            Swatch::Mark(style, Look::Line) => area
                .draw(&PathElement::new(vec![(x0, mid), (x1, mid)], *style))
                .map_err(drawing)?,
            Swatch::Mark(style, Look::Dashed) => area
                .draw(&DashedPathElement::new(
                    vec![(x0, mid), (x1, mid)],
                    5,
                    3,
                    *style,
                ))
                .map_err(drawing)?,
            Swatch::Mark(style, look) => {
                // A stretch of panel edge with three ticks on it.
                let tick = TICK as i32 - 2;
                let (edge, end) = if *look == Look::TopTick {
                    (mid - tick / 2, mid + tick / 2)
                } else {
                    (mid + tick / 2, mid - tick / 2)
                };
                area.draw(&PathElement::new(vec![(x0, edge), (x1, edge)], BLACK))
                    .map_err(drawing)?;
                for k in 0..3 {
                    let x = x0 + 4 + k * (swatch_w - 8) / 2;
                    area.draw(&PathElement::new(vec![(x, edge), (x, end)], *style))
                        .map_err(drawing)?;
                }
            }
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
                .map_err(drawing)?;
            }
            Swatch::Block(c) => area
                .draw(&Rectangle::new([(x0, mid - 6), (x1, mid + 6)], c.filled()))
                .map_err(drawing)?,
        }
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

#[cfg(test)]
mod tests {
    use super::*;
    use wasp_sim::timeline::{TileMark, TimelineSample};

    /// A unique scratch directory for one test.
    fn scratch(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!(
            "wasp-timeline-plot-{name}-{}-{}",
            std::process::id(),
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map(|d| d.as_nanos())
                .unwrap_or(0)
        ));
        std::fs::create_dir_all(&dir).expect("scratch dir");
        dir
    }

    /// The texts of an SVG's `<text>` elements, trimmed.
    fn svg_texts(svg: &str) -> Vec<String> {
        svg.split("<text")
            .skip(1)
            .filter_map(|part| {
                let body = part.split_once('>')?.1;
                Some(body.split_once("</text>")?.0.trim().to_string())
            })
            .collect()
    }

    /// Four cores, two shared tiles of `len` cycles each starting at
    /// `from`: each fills (resident warps ramp up, misses rise, priority
    /// warps launch early) and drains (warps retire, misses fall).
    fn synthetic(from: u64, len: u64) -> Timeline {
        let cores = 4;
        let max_warps = 48;
        let mut t = Timeline::new(
            from,
            from + 2 * len - 1,
            cores,
            max_warps,
            true,
            "shared-tile",
        );
        for tile in 0..2u64 {
            let start = from + tile * len;
            t.marks.push(TileMark {
                cycle: start,
                tile: tile as u32,
                core: None,
                start: true,
            });
            for k in 0..len {
                let cycle = start + k;
                // Fill over the first 30%, hold, drain over the last 30%.
                let phase = k as f64 / len as f64;
                let level = if phase < 0.3 {
                    phase / 0.3
                } else if phase < 0.7 {
                    1.0
                } else {
                    (1.0 - phase) / 0.3
                };
                let resident = (0..cores)
                    .map(|c| {
                        let wobble = ((cycle / 9 + c as u64 * 5) % 6) as f64;
                        ((f64::from(max_warps) - 4.0 * c as f64 - wobble) * level).max(0.0) as u32
                    })
                    .collect();
                let outstanding = [
                    (12.0 * level) as u32 + (cycle / 11 % 3) as u32,
                    (30.0 * level) as u32 + (cycle / 7 % 4) as u32,
                    (20.0 * level * level) as u32,
                ];
                let priority_launches = (0..cores)
                    .map(|c| {
                        u32::from(phase < 0.5 && (cycle + c as u64).is_multiple_of(3 + c as u64))
                    })
                    .collect();
                t.samples.push(TimelineSample {
                    cycle,
                    resident,
                    outstanding,
                    priority_launches,
                });
            }
            t.marks.push(TileMark {
                cycle: start + len - 1,
                tile: tile as u32,
                core: None,
                start: false,
            });
        }
        t
    }

    /// The same shape under per-core-tile dispatch: each core takes its own
    /// tiles, staggered.
    fn per_core(from: u64, len: u64) -> Timeline {
        let mut t = synthetic(from, len);
        t.dispatch = "per-core-tile".into();
        t.marks.clear();
        for core in 0..t.cores as u32 {
            let shift = u64::from(core) * len / 5;
            for tile in 0..2u64 {
                let start = from + tile * len + shift;
                t.marks.push(TileMark {
                    cycle: start,
                    tile: tile as u32 * 4 + core,
                    core: Some(core),
                    start: true,
                });
                t.marks.push(TileMark {
                    cycle: start + len * 9 / 10,
                    tile: tile as u32 * 4 + core,
                    core: Some(core),
                    start: false,
                });
            }
        }
        let (from, to) = (t.from, t.to);
        t.marks.retain(|m| (from..=to).contains(&m.cycle));
        t.marks.sort_by_key(|m| m.cycle);
        t
    }

    /// 200,000 cycles of per-core-tile dispatch, each core taking a tile
    /// every 1,000 cycles.
    fn dense_per_core() -> Timeline {
        let mut t = per_core(5, 100_000);
        t.marks.clear();
        for k in 0..200u32 {
            for core in 0..4u32 {
                let cycle = 5 + u64::from(k) * 1000 + u64::from(core) * 97;
                t.marks.push(TileMark {
                    cycle,
                    tile: k * 4 + core,
                    core: Some(core),
                    start: true,
                });
                t.marks.push(TileMark {
                    cycle: cycle + 900,
                    tile: k * 4 + core,
                    core: Some(core),
                    start: false,
                });
            }
        }
        let (from, to) = (t.from, t.to);
        t.marks.retain(|m| (from..=to).contains(&m.cycle));
        t.marks.sort_by_key(|m| m.cycle);
        t
    }

    #[test]
    fn png_has_the_picture_size() {
        let dir = scratch("png");
        let path = dir.join("timeline.png");
        let t = synthetic(1000, 600);
        draw(&t, &path).expect("draw png");
        let img = image::open(&path).expect("png decodes").to_rgb8();
        assert_eq!((img.width(), img.height()), (WIDTH, HEIGHT));
        // Not a blank page: some pixels carry the core colours.
        let blue = img.pixels().filter(|p| p.0 == [31, 119, 180]).count();
        assert!(blue > 100, "{blue} pixels of core 0's colour");
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn svg_has_the_legend_texts() {
        let dir = scratch("svg");
        let path = dir.join("timeline.svg");
        draw(&synthetic(1000, 600), &path).expect("draw svg");
        let svg = std::fs::read_to_string(&path).expect("svg");
        let texts = svg_texts(&svg);
        for text in [
            "Cores",
            "core 0",
            "core 3",
            "tile start",
            "tile end",
            "Cache levels",
            "L0",
            "L1",
            "L2",
            "Launching core",
            "tile 0",
            "tile 1",
            "48 warp slots",
            "Resident warps per core",
            "warps",
            "misses",
            "launches / cycle",
            "cycle",
            "1000",
            "2200",
        ] {
            assert!(
                texts.iter().any(|t| t == text),
                "the SVG lacks `{text}`: {texts:?}"
            );
        }
        let title = &texts
            .iter()
            .find(|t| t.starts_with("wasp timeline"))
            .expect("title");
        assert!(title.contains("shared-tile dispatch"), "{title}");
        assert!(title.contains("cycles 1000..=2199"), "{title}");
        assert!(texts.iter().any(|t| t.starts_with("Outstanding misses")));
        assert!(texts
            .iter()
            .any(|t| t.starts_with("Priority-warp launches")));
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn l0_is_left_out_without_l0() {
        let dir = scratch("nol0");
        let path = dir.join("timeline.svg");
        let mut t = synthetic(0, 300);
        t.has_l0 = false;
        draw(&t, &path).expect("draw svg");
        let texts = svg_texts(&std::fs::read_to_string(&path).expect("svg"));
        assert!(texts.iter().any(|t| t == "L1") && texts.iter().any(|t| t == "L2"));
        assert!(!texts.iter().any(|t| t == "L0"), "{texts:?}");
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn long_window_is_downsampled_and_small() {
        let dir = scratch("long");
        let svg_path = dir.join("timeline.svg");
        let png_path = dir.join("timeline.png");
        let many = dense_per_core();
        draw(&many, &svg_path).expect("draw svg");
        draw(&many, &png_path).expect("draw png");
        let size = std::fs::metadata(&svg_path).expect("svg").len();
        assert!(size < 3_000_000, "SVG of {size} bytes");
        let texts = svg_texts(&std::fs::read_to_string(&svg_path).expect("svg"));
        assert!(texts.iter().any(|t| t.contains("per-core-tile dispatch")));
        assert!(texts.iter().any(|t| t.contains("cycles per pixel column")));
        assert!(texts.iter().any(|t| t == "min..max in column"));
        // 800 tiles' marks are too dense for lines: ticks.
        assert!(
            texts.iter().any(|t| t == "tile start (top ticks)"),
            "{texts:?}"
        );
        assert!(
            texts.iter().any(|t| t == "tile end (bottom ticks)"),
            "{texts:?}"
        );
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn per_core_tiles_draw() {
        let dir = scratch("percore");
        let path = dir.join("timeline.png");
        draw(&per_core(0, 800), &path).expect("draw png");
        let img = image::open(&path).expect("png decodes");
        assert_eq!((img.width(), img.height()), (WIDTH, HEIGHT));
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn tiny_timelines_draw() {
        let dir = scratch("tiny");
        // One cycle, one core, a tile starting and ending in it.
        let mut t = Timeline::new(7, 7, 1, 0, false, "shared-tile");
        t.samples.push(TimelineSample {
            cycle: 7,
            resident: vec![0],
            outstanding: [0, 0, 0],
            priority_launches: vec![0],
        });
        for start in [true, false] {
            t.marks.push(TileMark {
                cycle: 7,
                tile: 0,
                core: None,
                start,
            });
        }
        // A mark outside the window is left out, not drawn off the plot.
        t.marks.push(TileMark {
            cycle: u64::MAX,
            tile: 1,
            core: None,
            start: false,
        });
        draw(&t, &dir.join("one.png")).expect("one cycle");
        draw(&t, &dir.join("one.svg")).expect("one cycle");
        // No cores at all.
        let mut t = Timeline::new(0, 3, 0, 16, true, "shared-tile");
        for cycle in 0..4 {
            t.samples.push(TimelineSample {
                cycle,
                resident: vec![],
                outstanding: [1, 2, 3],
                priority_launches: vec![],
            });
        }
        draw(&t, &dir.join("none.png")).expect("no cores");
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn wrong_extension_is_an_error() {
        let dir = scratch("ext");
        for name in ["timeline.jpg", "timeline", "timeline.png.txt"] {
            let path = dir.join(name);
            let e = draw(&synthetic(0, 100), &path).expect_err("not a picture format");
            assert!(e.contains(name), "{e}");
            assert!(e.contains(".png") && e.contains(".svg"), "{e}");
            assert!(!path.exists());
        }
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn empty_timeline_is_an_error() {
        let dir = scratch("empty");
        let path = dir.join("timeline.png");
        let t = Timeline::new(500, 900, 4, 64, false, "shared-tile");
        let e = draw(&t, &path).expect_err("no samples");
        assert!(e.contains("no samples"), "{e}");
        assert!(e.contains("500..=900"), "{e}");
        assert!(!path.exists());
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn inconsistent_samples_are_errors() {
        let dir = scratch("bad");
        let path = dir.join("timeline.svg");
        let mut t = synthetic(0, 50);
        t.samples[7].resident.pop();
        let e = draw(&t, &path).expect_err("3 counts for 4 cores");
        assert!(e.contains("cycle 7"), "{e}");
        let mut t = synthetic(0, 50);
        t.samples.swap(3, 4);
        let e = draw(&t, &path).expect_err("out of order");
        assert!(e.contains("cycle order"), "{e}");
        std::fs::remove_dir_all(dir).ok();
    }
}
