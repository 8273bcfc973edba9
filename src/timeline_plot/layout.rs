//! The whole timeline picture: the charts' title strip over the three
//! panels that share the cycle axis, what each panel draws and its legend
//! right of it.

use super::downsample::{downsample, Column};
use super::marks::{draw_marks, label_tiles, mark_entries, merge_marks};
use super::panel::{panel, panel_legend, plot_width, series, split, steps, Panel};
use super::{HEIGHT, WIDTH};
use crate::charts::frame::{Area, Drawn, Frame, Picture};
use crate::charts::legend::{Legend, Swatch};
use crate::palette::{other, LEVELS};
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use std::ops::Range;
use wasp_sim::timeline::Timeline;

/// A timeline to draw.
pub(super) struct TimelineChart<'a>(pub &'a Timeline);

impl Picture for TimelineChart<'_> {
    fn size(&self) -> (u32, u32) {
        (WIDTH, HEIGHT)
    }

    /// Draws the whole picture on `root`: the title strip, the three
    /// panels (each its data, then the tile marks and the legend), the
    /// tile labels.
    fn draw<DB: DrawingBackend>(&self, root: &Area<DB>) -> Drawn<DB> {
        let t = self.0;
        let first = t.samples.first().map_or(t.from, |s| s.cycle);
        let last = t.samples.last().map_or(t.to, |s| s.cycle);
        let x = t.from.min(first) as f64..t.to.max(last).saturating_add(1) as f64;
        let (w, h) = root.dim_in_pixel();
        let plot_w = plot_width(w) as usize;
        let cols = downsample(t, plot_w);
        let per_column = t.samples.len() as f64 / cols.len().max(1) as f64;
        let banded = per_column > 1.0;
        let (head, sub) = frame(t, banded, per_column);
        let frame = Frame::new((&head, &sub), Vec::new(), 0.0, f64::from(w));
        let body = frame.draw(root)?;
        let body_h = h.saturating_sub(frame.height());
        let (p1, rest) = body.split_vertically(body_h * 37 / 100);
        let (p2, p3) = rest.split_vertically(body_h * 32 / 100);
        let [(a1, l1), (a2, l2), (a3, l3)] = [p1, p2, p3].map(|p| split(&p));
        let levels: &[usize] = if t.has_l0 { &[0, 1, 2] } else { &[1, 2] };
        let mut charts = [
            resident_panel(t, &a1, x.clone())?,
            miss_panel(&a2, levels, (x.clone(), &cols))?,
            launch_panel(&a3, (x, &cols, banded))?,
        ];
        // Tile marks behind the data; lines for dense marks would hide the
        // data: ticks instead.
        debug_assert_eq!(charts[0].plotting_area().dim_in_pixel().0 as usize, plot_w);
        let marks = merge_marks(t, &charts[0]);
        let dense = marks.len() > plot_w / 10;
        for chart in &mut charts {
            draw_marks(chart, &marks, dense)?;
        }
        let [c1, c2, c3] = &mut charts;
        resident(c1, t, (&cols, banded))?;
        for &l in levels {
            series(c2, (&cols, banded), LEVELS[l], |c| c.outstanding[l])?;
        }
        launches(c3, t.cores, &cols)?;
        let [e1, e2, e3] = legends(t, levels, mark_entries(&marks, dense), banded);
        panel_legend(&l1, "Cores", &e1)?;
        panel_legend(&l2, "Cache levels", &e2)?;
        panel_legend(&l3, "Launching core", &e3)?;
        if !dense {
            label_tiles(root, c1, &marks)?;
        }
        Ok(())
    }
}

/// The style of the dashed line at the warp slots.
fn slots_style() -> ShapeStyle {
    BLACK.mix(0.5).stroke_width(1)
}

/// The title strip: the run and window, and how the window was drawn
/// (`per_column` cycles per pixel column when `banded`).
fn frame(t: &Timeline, banded: bool, per_column: f64) -> (String, String) {
    let (from, to, n) = (t.from, t.to, t.to.saturating_sub(t.from) + 1);
    let window = format!("cycles {from}..={to} ({n} cycles, {} cores)", t.cores);
    let bands = "lines are column means, light bands the column min..max";
    let sub = match banded {
        true => format!("{per_column:.1} cycles per pixel column: {bands}"),
        false => "one sample per cycle".to_string(),
    };
    let head = format!("wasp timeline: {} dispatch, {window}", t.dispatch);
    (head, sub)
}

/// Panel 1's chart, the warps resident in each core: above the warp
/// slots it keeps room for the rows of tile labels (one, or one per core
/// up to four under per-core-tile dispatch).
fn resident_panel<'a, DB: DrawingBackend>(
    t: &Timeline,
    area: &'a Area<DB>,
    x: Range<f64>,
) -> Drawn<DB, Panel<'a, DB>> {
    let rows = match t.marks.iter().any(|m| m.core.is_some()) {
        true => t.cores.clamp(1, 4) as u32,
        false => 1,
    };
    // The plot's height: the panel less margins, caption and tick labels.
    let plot_h = f64::from(area.dim_in_pixel().1.saturating_sub(63).max(100));
    let room = f64::from(10 + 16 * rows).min(plot_h / 2.0);
    let top = f64::from(t.max_warps.max(1)) * plot_h / (plot_h - room);
    let caption = ("Resident warps per core", "warps");
    panel(area, caption, false, x, 0.0..top)
}

/// Panel 1's data: a line per core under a dashed line at the warp slots.
fn resident<DB: DrawingBackend>(
    chart: &mut Panel<'_, DB>,
    t: &Timeline,
    (cols, banded): (&[Column], bool),
) -> Drawn<DB> {
    for c in 0..t.cores {
        series(chart, (cols, banded), other(c), |col| col.resident[c])?;
    }
    let (x, top) = (chart.x_range(), f64::from(t.max_warps.max(1)));
    let slots = DashedPathElement::new(vec![(x.start, top), (x.end, top)], 6, 4, slots_style());
    chart.draw_series(std::iter::once(slots))?;
    Ok(())
}

/// The legends of the panels: the cores (with the tile marks as drawn,
/// the warp slots and, when `banded`, the band), the cache `levels` (and
/// the band), the launching cores.
fn legends(t: &Timeline, levels: &[usize], marks: Legend, banded: bool) -> [Legend; 3] {
    let line = |c: RGBColor| Swatch::Line(c.stroke_width(3), None);
    let cores = (0..t.cores).map(|c| (format!("core {c}"), line(other(c))));
    let mut first: Legend = cores.chain(marks).collect();
    let slots = format!("{} warp slots", t.max_warps);
    first.push((slots, Swatch::Dashed(slots_style(), None)));
    let level = |&l: &usize| (format!("L{l}"), line(LEVELS[l]));
    let mut second: Legend = levels.iter().map(level).collect();
    if banded {
        let band = |c| ("min..max in column".to_string(), Swatch::Band(c));
        first.push(band(other(0)));
        second.push(band(LEVELS[levels[0]]));
    }
    let blocks = (0..t.cores).map(|c| (format!("core {c}"), Swatch::Block(other(c))));
    [first, second, blocks.collect()]
}

/// Panel 2's chart, the misses outstanding in the cache `levels`.
fn miss_panel<'a, DB: DrawingBackend>(
    area: &'a Area<DB>,
    levels: &[usize],
    (x, cols): (Range<f64>, &[Column]),
) -> Drawn<DB, Panel<'a, DB>> {
    let most = |c: &Column| levels.iter().fold(0.0, |m, &l| c.outstanding[l].max.max(m));
    let top = cols.iter().map(most).fold(0.0, f64::max).max(1.0);
    let caption = "Outstanding misses per cache level (MSHR entries, summed over the level)";
    panel(area, (caption, "misses"), false, x, 0.0..top * 1.08)
}

/// Panel 3's chart, priority launches per cycle (their column means when
/// `banded`) stacked by core.
fn launch_panel<'a, DB: DrawingBackend>(
    area: &'a Area<DB>,
    (x, cols, banded): (Range<f64>, &[Column], bool),
) -> Drawn<DB, Panel<'a, DB>> {
    let sums = cols.iter().map(|c| c.launches.iter().sum::<f64>());
    let top = sums.fold(0.0, f64::max);
    let top = if top > 0.0 { top * 1.1 } else { 1.0 };
    let caption = match banded {
        true => "Priority-warp launches per cycle (mean over each pixel column, stacked by core)",
        false => "Priority-warp launches per cycle (stacked by core)",
    };
    panel(area, (caption, "launches / cycle"), true, x, 0.0..top)
}

/// Panel 3's data: the launches stacked by core, a polygon per run of
/// columns in which the core launched.
fn launches<DB: DrawingBackend>(
    chart: &mut Panel<'_, DB>,
    cores: usize,
    cols: &[Column],
) -> Drawn<DB> {
    let mut below = vec![0.0; cols.len()];
    for c in 0..cores {
        let above = cols.iter().zip(&below).map(|(col, b)| b + col.launches[c]);
        let above: Vec<f64> = above.collect();
        let (mut runs, mut i) = (Vec::new(), 0);
        while let Some(start) = (i..cols.len()).find(|&j| cols[j].launches[c] != 0.0) {
            let end = (start..cols.len()).find(|&j| cols[j].launches[c] == 0.0);
            i = end.unwrap_or(cols.len());
            let part = &cols[start..i];
            let mut outline = steps(part, |k| above[start + k]);
            outline.extend(steps(part, |k| below[start + k]).into_iter().rev());
            runs.push(Polygon::new(outline, other(c).filled()));
        }
        chart.draw_series(runs)?;
        below = above;
    }
    Ok(())
}
