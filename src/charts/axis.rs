//! The y axis of bar and line charts: its range and round ticks, the
//! frame mapping values to pixel rows, value labels, and its drawing.

use super::canvas::{style, text_size, Canvas, GRID, LABEL_SIZE};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

/// The y axis: its range and ticks.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct YAxis {
    /// The value at the bottom of the plot.
    pub lo: f64,
    /// The value at the top of the plot.
    pub hi: f64,
    /// The distance between ticks.
    step: f64,
    /// Decimals of the tick labels (of the percentage when `percent`).
    decimals: usize,
    /// Tick labels as percentages.
    percent: bool,
}

/// The distance between ticks: 1, 2 or 5 times a power of ten, at most
/// `max_ticks` ticks over `span`.
fn nice_step(span: f64, max_ticks: usize) -> f64 {
    let raw = span / max_ticks.max(1) as f64;
    let mag = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * mag)
        .find(|s| *s >= raw * (1.0 - 1e-9))
        .unwrap_or(10.0 * mag)
}

/// Decimals that show a multiple of `step` exactly.
fn decimals(step: f64) -> usize {
    let d = (-step.log10() - 1e-9).ceil();
    if d > 0.0 {
        d.min(9.0) as usize
    } else {
        0
    }
}

impl YAxis {
    /// The axis over `values` and `include` (always in range), with 8%
    /// headroom above and, when anything is negative, below; at most
    /// `max_ticks` ticks.
    pub fn new(
        values: impl IntoIterator<Item = f64>,
        include: &[f64],
        percent: bool,
        max_ticks: usize,
    ) -> Self {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for v in values.into_iter().chain(include.iter().copied()) {
            lo = lo.min(v);
            hi = hi.max(v);
        }
        if !lo.is_finite() || !hi.is_finite() {
            (lo, hi) = (0.0, 1.0);
        }
        if hi - lo < 1e-12 * hi.abs().max(lo.abs()).max(1e-300) {
            // A single value: a range around it.
            let pad = if hi == 0.0 { 1.0 } else { hi.abs() * 0.5 };
            if lo >= 0.0 {
                hi += pad;
            } else {
                lo -= pad;
            }
        }
        let span = hi - lo;
        hi += 0.08 * span;
        if lo < 0.0 {
            lo -= 0.08 * span;
        }
        let step = nice_step(hi - lo, max_ticks);
        let shown = if percent { step * 100.0 } else { step };
        YAxis {
            lo,
            hi,
            step,
            decimals: decimals(shown),
            percent,
        }
    }

    /// The tick values, bottom to top.
    pub fn ticks(&self) -> Vec<f64> {
        let first = (self.lo / self.step - 1e-9).ceil() as i64;
        let last = (self.hi / self.step + 1e-9).floor() as i64;
        (first..=last).map(|k| k as f64 * self.step).collect()
    }

    /// The label of tick `v`.
    pub fn label(&self, v: f64) -> String {
        let v = if v.abs() < self.step * 1e-6 { 0.0 } else { v };
        if self.percent {
            format!("{:.*}%", self.decimals, v * 100.0)
        } else {
            format!("{:.*}", self.decimals, v)
        }
    }
}

/// A value as printed over its bar: two or three significant digits.
pub(super) fn value_label(v: f64, percent: bool) -> String {
    let shown = if percent { v * 100.0 } else { v };
    let a = shown.abs();
    // By the magnitude after rounding: 0.99996 is "1.0", not "1.00".
    let d = if a == 0.0 || a >= 99.5 {
        0
    } else if a >= 0.995 {
        1
    } else if a >= 0.0995 {
        2
    } else {
        3
    };
    let text = format!("{shown:.d$}");
    if percent {
        format!("{text}%")
    } else {
        text
    }
}

/// Where the plot is and how values map to its pixels.
#[derive(Clone, Debug)]
pub(super) struct Frame {
    /// Left edge of the plot.
    pub left: f64,
    /// Top edge of the plot.
    pub top: f64,
    /// Right edge of the plot.
    pub right: f64,
    /// Bottom edge of the plot.
    pub bottom: f64,
    /// The y axis.
    pub y: YAxis,
}

impl Frame {
    /// The pixel row of value `v`.
    pub fn py(&self, v: f64) -> f64 {
        self.bottom - (v - self.y.lo) / (self.y.hi - self.y.lo) * (self.bottom - self.top)
    }
}

/// The width of the y axis left of the plot: the axis label, the widest
/// tick label, gaps.
pub(super) fn y_axis_width(y: &YAxis) -> f64 {
    let widest = y
        .ticks()
        .iter()
        .map(|&v| text_size(&y.label(v), LABEL_SIZE, false).0)
        .fold(0.0, f64::max);
    14.0 + 22.0 + 10.0 + widest + 8.0
}

/// Draws the grid lines, tick labels and label of the y axis, and the left
/// edge of the plot.
pub(super) fn draw_y_axis<DB: DrawingBackend>(
    c: &Canvas<'_, DB>,
    f: &Frame,
    label: &str,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let tick_style = style(LABEL_SIZE, false, BLACK, HPos::Right, VPos::Center);
    for v in f.y.ticks() {
        let y = f.py(v);
        c.path(&[(f.left, y), (f.right, y)], GRID.stroke_width(1))?;
        c.path(&[(f.left - 5.0, y), (f.left, y)], BLACK.stroke_width(1))?;
        c.text(&f.y.label(v), &tick_style, (f.left - 8.0, y))?;
    }
    let desc = style(LABEL_SIZE + 1, false, BLACK, HPos::Center, VPos::Top)
        .transform(FontTransform::Rotate270);
    c.text(label, &desc, (14.0, (f.top + f.bottom) / 2.0))?;
    c.path(
        &[(f.left, f.top), (f.left, f.bottom)],
        BLACK.stroke_width(1),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_are_round_and_labelled_as_percentages() {
        let y = YAxis::new([0.039, 0.02, -0.02], &[0.0], true, 8);
        assert!(y.lo < -0.02 && y.hi > 0.039, "{y:?}");
        let ticks = y.ticks();
        assert!(ticks.len() >= 4 && ticks.len() <= 9, "{ticks:?}");
        let labels: Vec<String> = ticks.iter().map(|&v| y.label(v)).collect();
        assert!(labels.contains(&"0%".to_string()), "{labels:?}");
        assert!(labels.contains(&"-2%".to_string()), "{labels:?}");
        assert!(labels.iter().all(|l| l.ends_with('%')), "{labels:?}");
        let y = YAxis::new([0.5, 1.2], &[0.0, 1.0], false, 8);
        let labels: Vec<String> = y.ticks().iter().map(|&v| y.label(v)).collect();
        assert_eq!(labels, ["0.0", "0.2", "0.4", "0.6", "0.8", "1.0", "1.2"]);
    }

    #[test]
    fn a_flat_range_still_has_height() {
        let y = YAxis::new([0.0, 0.0], &[0.0], false, 8);
        assert!(y.hi > 0.9 && y.lo == 0.0, "{y:?}");
        let y = YAxis::new([-3.0], &[], false, 8);
        assert!(y.lo < -3.0 && y.hi > -3.0, "{y:?}");
    }

    #[test]
    fn value_labels_keep_two_or_three_digits() {
        assert_eq!(value_label(0.039, true), "3.9%");
        assert_eq!(value_label(-0.0213, true), "-2.1%");
        assert_eq!(value_label(0.00123, true), "0.12%");
        assert_eq!(value_label(1.234, false), "1.2");
        assert_eq!(value_label(0.0, false), "0");
        assert_eq!(value_label(0.009999999999999998, true), "1.0%");
        assert_eq!(value_label(0.0999, false), "0.10");
        assert_eq!(value_label(1234.4, false), "1234");
    }
}
