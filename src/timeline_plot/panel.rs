//! One panel of the timeline: its chart (caption, axes, grid) over the
//! shared cycle axis, its legend right of it, and a series drawn on it as
//! a step line through the column means inside the band of the column
//! minima to maxima.

use super::downsample::{Agg, Column};
use crate::charts::frame::{builder, style_mesh, Area, Drawn, Ticked};
use crate::charts::legend::{legend, line_height, Legend};
use crate::fonts::font;
use plotters::prelude::*;
use std::ops::Range;

/// A panel's chart.
pub(super) type Panel<'a, DB> = ChartContext<'a, DB, Cartesian2d<Ticked, Ticked>>;

/// Width of the legend right of each plot.
const LEGEND_W: u32 = 230;
/// Width of the label area left of each plot.
const LEFT: u32 = 76;

/// The width in pixels of the plot of a panel `width` wide.
pub(super) fn plot_width(width: u32) -> u32 {
    width.saturating_sub(6 + LEFT + LEGEND_W + 14).max(1)
}

/// A panel's row split into the chart's area and the legend's.
pub(super) fn split<DB: DrawingBackend>(row: &Area<DB>) -> (Area<DB>, Area<DB>) {
    row.split_horizontally(row.dim_in_pixel().0.saturating_sub(LEGEND_W))
}

/// One panel's chart: caption, axes, grid; the cycle axis labelled only
/// when `bottom`.
pub(super) fn panel<'a, DB: DrawingBackend>(
    area: &'a Area<DB>,
    (caption, y_desc): (&str, &str),
    bottom: bool,
    x: Range<f64>,
    y: Range<f64>,
) -> Drawn<DB, Panel<'a, DB>> {
    let under = if bottom { 52.0 } else { 28.0 };
    let mut b = builder(area, (f64::from(LEFT), under, 6.0, 14.0));
    let (x, y) = (
        Ticked::numeric(&x, 12, false),
        Ticked::numeric(&y, 6, false),
    );
    let mut chart = b
        .caption(caption, font(21, true))
        .build_cartesian_2d(x, y)?;
    let mut mesh = chart.configure_mesh();
    style_mesh(&mut mesh);
    mesh.y_desc(y_desc);
    if bottom {
        mesh.x_desc("cycle");
    }
    mesh.draw()?;
    Ok(chart)
}

/// Draws `entries` on the legend's `area` under `heading`, in one column
/// if they fit the height, else in more and a smaller font.
pub(super) fn panel_legend<DB: DrawingBackend>(
    area: &Area<DB>,
    heading: &str,
    entries: &Legend,
) -> Drawn<DB> {
    area.draw_text(heading, &font(19, true).color(&BLACK), (8, 34))?;
    let (w, h) = area.dim_in_pixel();
    let room = f64::from(h.saturating_sub(64));
    let size = if entries.len() as f64 * line_height(17) <= room {
        17
    } else {
        13
    };
    let rows = (room / line_height(size)).max(1.0) as usize;
    legend(
        &area.clone().shrink((8, 58), (w - 8, h - 58)),
        entries,
        (rows, size),
    )
}

/// The step outline of `value(i)` over the columns: two points per column.
pub(super) fn steps(cols: &[Column], value: impl Fn(usize) -> f64) -> Vec<(f64, f64)> {
    let step = |(i, c): (usize, &Column)| [(c.x0, value(i)), (c.x1, value(i))];
    cols.iter().enumerate().flat_map(step).collect()
}

/// One series: the band from the column minima to maxima
/// (when `banded`) and the step line through the column means.
pub(super) fn series<DB: DrawingBackend>(
    chart: &mut Panel<'_, DB>,
    (cols, banded): (&[Column], bool),
    colour: RGBColor,
    agg: impl Fn(&Column) -> Agg,
) -> Drawn<DB> {
    if banded && cols.iter().any(|c| agg(c).max > agg(c).min) {
        let mut outline = steps(cols, |i| agg(&cols[i]).max);
        let mut low = steps(cols, |i| agg(&cols[i]).min);
        low.reverse();
        outline.extend(low);
        let band = Polygon::new(outline, colour.mix(0.18).filled());
        chart.draw_series(std::iter::once(band))?;
    }
    let line = steps(cols, |i| agg(&cols[i]).mean);
    chart.draw_series(std::iter::once(PathElement::new(
        line,
        colour.stroke_width(2),
    )))?;
    Ok(())
}
