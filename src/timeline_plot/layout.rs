//! The whole timeline picture: the title strip over the three panels that
//! share the cycle axis, each with its legend strip, and what each panel
//! draws.

use super::colours::{core_colour, LEVEL_COLOURS};
use super::downsample::{downsample, Column};
use super::error::drawing;
use super::legend::{legend, Swatch};
use super::marks::{draw_marks, label_tiles, mark_colour, mark_look, merge_marks, Look, Mark};
use super::panel::{panel, series, steps, Chart};
use crate::fonts::font;
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use wasp_sim::timeline::Timeline;

/// Width of the legend strip to the right of each panel.
const LEGEND_W: u32 = 230;
/// Height of the title strip.
const TITLE_H: u32 = 58;

/// The picture's areas: the title strip, then per panel its chart area
/// and its legend strip.
struct Areas<DB: DrawingBackend> {
    title: DrawingArea<DB, Shift>,
    charts: [DrawingArea<DB, Shift>; 3],
    legends: [DrawingArea<DB, Shift>; 3],
    /// Height of the first panel.
    h1: u32,
}

/// Split `root` (`w` x `h`) into the title strip and three panels of 37%,
/// 32% and the rest of the body, each with its legend strip.
fn split<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, w: u32, h: u32) -> Areas<DB> {
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
    Areas {
        title,
        charts: [c1, c2, c3],
        legends: [l1, l2, l3],
        h1,
    }
}

/// The style of the dashed line at the warp slots.
fn slots_style() -> ShapeStyle {
    BLACK.mix(0.5).stroke_width(1)
}

/// Panel 1's chart, resident warps: above the warp slots (`top1`) it
/// keeps room for the rows of tile labels (one, or one per core up to
/// four under per-core-tile dispatch).
fn resident_chart<'a, DB: DrawingBackend>(
    t: &Timeline,
    area: &'a DrawingArea<DB, Shift>,
    h1: u32,
    x: std::ops::Range<f64>,
    top1: f64,
) -> Result<Chart<'a, DB>, String>
where
    DB::ErrorType: 'static,
{
    let label_rows = if t.marks.iter().any(|m| m.core.is_some()) {
        t.cores.clamp(1, 4) as u32
    } else {
        1
    };
    // The plot's height: the panel less margins, caption and tick labels.
    let plot_h1 = f64::from(h1.saturating_sub(63).max(100));
    let room = f64::from(10 + 16 * label_rows).min(plot_h1 / 2.0);
    panel(
        area,
        "Resident warps per core",
        "warps",
        false,
        x,
        0.0..top1 * plot_h1 / (plot_h1 - room),
    )
}

/// Panel 2's chart, outstanding misses of the cache `levels`.
fn miss_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    cols: &[Column],
    levels: &[usize],
    x: std::ops::Range<f64>,
) -> Result<Chart<'a, DB>, String>
where
    DB::ErrorType: 'static,
{
    let top2 = cols
        .iter()
        .flat_map(|c| levels.iter().map(move |&l| c.outstanding[l].max))
        .fold(0.0, f64::max)
        .max(1.0);
    panel(
        area,
        "Outstanding misses per cache level (MSHR entries, summed over the level)",
        "misses",
        false,
        x,
        0.0..top2 * 1.08,
    )
}

/// Panel 3's chart, priority launches stacked by core (their column means
/// when `banded`).
fn launch_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    cols: &[Column],
    banded: bool,
    x: std::ops::Range<f64>,
) -> Result<Chart<'a, DB>, String>
where
    DB::ErrorType: 'static,
{
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
    panel(area, launch_title, "launches / cycle", true, x, 0.0..top3)
}

/// Panel 3's data: priority launches, stacked by core; one polygon per run
/// of columns in which the core launched.
fn draw_launches<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    cores: usize,
    cols: &[Column],
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let mut below = vec![0.0; cols.len()];
    for c in 0..cores {
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
            chart
                .draw_series(std::iter::once(Polygon::new(
                    outline,
                    core_colour(c).filled(),
                )))
                .map_err(drawing)?;
        }
        below = above;
    }
    Ok(())
}

/// Panel 1's legend: the cores, the tile marks as drawn (shared marks in
/// their own colours, per-core ones in the core's; ticks when `dense`),
/// the warp slots and, when `banded`, the band.
fn core_legend(t: &Timeline, marks: &[Mark], dense: bool, banded: bool) -> Vec<(String, Swatch)> {
    let mut entries: Vec<(String, Swatch)> = (0..t.cores)
        .map(|c| {
            (
                format!("core {c}"),
                Swatch::Line(core_colour(c).stroke_width(3)),
            )
        })
        .collect();
    let shared = marks.iter().all(|m| m.core.is_none());
    let suffix = if shared { "" } else { " (core colour)" };
    for start in [true, false] {
        let (colour, width) = match shared {
            true => mark_colour(None, start),
            false => (RGBColor(90, 90, 90), 1),
        };
        let (style, look) = mark_look(colour, width, start, dense);
        let (name, swatch) = match look {
            Look::Line => (format!("tile start{suffix}"), Swatch::Tile(style, true)),
            Look::Dashed => (format!("tile end{suffix}"), Swatch::Tile(style, false)),
            Look::TopTick => ("tile start (top ticks)".into(), Swatch::Mark(style, look)),
            Look::BottomTick => ("tile end (bottom ticks)".into(), Swatch::Mark(style, look)),
        };
        entries.push((name, swatch));
    }
    entries.push((
        format!("{} warp slots", t.max_warps),
        Swatch::Mark(slots_style(), Look::Dashed),
    ));
    if banded {
        entries.push(("min..max in column".into(), Swatch::Band(core_colour(0))));
    }
    entries
}

/// Panel 2's legend: the cache levels drawn and, when `banded`, the band.
fn level_legend(levels: &[usize], banded: bool) -> Vec<(String, Swatch)> {
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
    entries
}

/// The title strip: the run and window, and how the window was drawn
/// (`per_column` cycles per pixel column when `banded`).
fn draw_title<DB: DrawingBackend>(
    title: &DrawingArea<DB, Shift>,
    t: &Timeline,
    banded: bool,
    per_column: f64,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
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

/// Draw the whole picture on `root`: the three panels' axes, the tile
/// marks behind the data, each panel's data, the legends, then the title.
pub(super) fn render<DB: DrawingBackend>(
    t: &Timeline,
    root: &DrawingArea<DB, Shift>,
) -> Result<(), String>
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
    let areas = split(root, w, h);
    let [c1, c2, c3] = &areas.charts;

    // Panel 1 first: its plot width sets the number of columns.
    let top1 = f64::from(t.max_warps.max(1));
    let mut chart1 = resident_chart(t, c1, areas.h1, x_lo..x_hi, top1)?;
    let plot_w = chart1.plotting_area().dim_in_pixel().0.max(1) as usize;
    let cols = downsample(t, plot_w);
    let per_column = n as f64 / cols.len().max(1) as f64;
    let banded = per_column > 1.0;

    let levels: Vec<usize> = if t.has_l0 { vec![0, 1, 2] } else { vec![1, 2] };
    let mut chart2 = miss_chart(c2, &cols, &levels, x_lo..x_hi)?;
    let mut chart3 = launch_chart(c3, &cols, banded, x_lo..x_hi)?;

    // Tile marks, merged per pixel column, behind the data.
    let marks = merge_marks(t, &chart1);
    // Lines for dense marks would hide the data: ticks instead.
    let dense = marks.len() > plot_w / 10;
    for chart in [&mut chart1, &mut chart2, &mut chart3] {
        draw_marks(chart, &marks, dense)?;
    }

    // Panel 1: resident warps, under a dashed line at the warp slots.
    chart1
        .draw_series(std::iter::once(DashedPathElement::new(
            vec![(x_lo, top1), (x_hi, top1)],
            6,
            4,
            slots_style(),
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
    draw_launches(&mut chart3, t.cores, &cols)?;

    let [l1, l2, l3] = &areas.legends;
    legend(l1, "Cores", &core_legend(t, &marks, dense, banded))?;
    legend(l2, "Cache levels", &level_legend(&levels, banded))?;
    let entries: Vec<(String, Swatch)> = (0..t.cores)
        .map(|c| (format!("core {c}"), Swatch::Block(core_colour(c))))
        .collect();
    legend(l3, "Launching core", &entries)?;
    // The title, last: it reports how the window was drawn.
    draw_title(&areas.title, t, banded, per_column)
}
