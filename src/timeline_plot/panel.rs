//! One panel of the timeline: its chart (caption, axes, grid) over the
//! shared cycle axis, and a series drawn on it as a step line through the
//! column means inside the band of the column minima to maxima.

use super::downsample::{Agg, Column};
use super::error::drawing;
use crate::fonts::font;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;

pub(super) type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// One panel's chart: caption, axes, grid; the cycle axis labelled only
/// when `bottom`.
pub(super) fn panel<'a, DB: DrawingBackend>(
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
pub(super) fn steps(cols: &[Column], value: impl Fn(usize) -> f64) -> Vec<(f64, f64)> {
    cols.iter()
        .enumerate()
        .flat_map(|(i, c)| [(c.x0, value(i)), (c.x1, value(i))])
        .collect()
}

/// One series: the band from the column minima to maxima (when `banded`)
/// and the step line through the column means.
pub(super) fn series<DB: DrawingBackend>(
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
