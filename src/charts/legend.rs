//! The strips around the plot of bar and line charts: the title, the
//! legend, and the paper's lines across the plot with their labels in the
//! margin right of it.

use super::axis::Frame;
use super::canvas::{style, text_size, Canvas, Placer, Shape, LABEL_SIZE, SMALL_SIZE};
use super::{mark_colour, PaperMark};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

/// Height of one legend row.
const LEGEND_ROW: f64 = 26.0;
/// Width of a legend swatch.
const SWATCH_W: f64 = 30.0;

/// The title font sizes that fit `width`: title, subtitle.
fn title_sizes(title: &str, subtitle: &str, width: f64) -> (u32, u32) {
    let fit = |text: &str, mut size: u32, bold: bool, min: u32| {
        while size > min && text_size(text, size, bold).0 > width - 32.0 {
            size -= 1;
        }
        size
    };
    (fit(title, 27, true, 14), fit(subtitle, 19, false, 12))
}

/// The height of the title strip.
pub(super) fn title_height(subtitle: &str) -> f64 {
    if subtitle.is_empty() {
        52.0
    } else {
        78.0
    }
}

/// Draws the title and subtitle at the top of a picture `width` wide.
pub(super) fn draw_title<DB: DrawingBackend>(
    c: &Canvas<'_, DB>,
    title: &str,
    subtitle: &str,
    width: f64,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let (t, s) = title_sizes(title, subtitle, width);
    c.text(
        title,
        &style(t, true, BLACK, HPos::Left, VPos::Top),
        (16.0, 12.0),
    )?;
    if !subtitle.is_empty() {
        let grey = RGBColor(70, 70, 70);
        c.text(
            subtitle,
            &style(s, false, grey, HPos::Left, VPos::Top),
            (16.0, 44.0),
        )?;
    }
    Ok(())
}

/// How a legend entry shows what it names.
#[derive(Clone, Debug)]
pub(super) enum Swatch {
    /// A filled block (a bar series).
    Block(RGBColor),
    /// A line through a filled marker (a line series).
    Line(RGBColor, Shape),
    /// The paper's values: a dashed line and/or a hollow marker.
    Paper { line: bool, marker: Option<Shape> },
}

/// A legend entry.
#[derive(Clone, Debug)]
pub(super) struct Entry {
    /// The text.
    pub label: String,
    /// The swatch left of the text.
    pub swatch: Swatch,
}

/// The legend entry for the chart's paper marks, if it has any, shown with
/// `shape` for marks of one category.
pub(super) fn paper_entry(paper: &[PaperMark], shape: Shape) -> Option<Entry> {
    let line = paper.iter().any(|m| m.category.is_none());
    let marker = paper.iter().any(|m| m.category.is_some());
    let coloured = paper.iter().any(|m| m.series.is_some());
    let what = match (line, marker) {
        (false, false) => return None,
        (true, false) => "paper value: dashed line",
        (false, true) => "paper value: hollow mark",
        (true, true) => "paper values: dashed lines, hollow marks",
    };
    Some(Entry {
        label: if coloured {
            format!("{what} (series colour)")
        } else {
            what.to_string()
        },
        swatch: Swatch::Paper {
            line,
            marker: marker.then_some(shape),
        },
    })
}

/// The legend's entries placed in rows from `left` no wider than `width`:
/// (row, x of the swatch) per entry.
fn legend_places(entries: &[Entry], left: f64, width: f64) -> Vec<(usize, f64)> {
    let mut places = Vec::with_capacity(entries.len());
    let (mut row, mut x) = (0, left);
    for e in entries {
        let w = SWATCH_W + 8.0 + text_size(&e.label, LABEL_SIZE, false).0;
        if x > left && x + w > left + width {
            row += 1;
            x = left;
        }
        places.push((row, x));
        x += w + 26.0;
    }
    places
}

/// The height of the legend from `left`, `width` wide.
pub(super) fn legend_height(entries: &[Entry], left: f64, width: f64) -> f64 {
    let rows = legend_places(entries, left, width)
        .last()
        .map_or(0, |&(row, _)| row + 1);
    rows as f64 * LEGEND_ROW + 6.0
}

/// Draws the legend with its top at `top`, from `left`, `width` wide.
pub(super) fn draw_legend<DB: DrawingBackend>(
    c: &Canvas<'_, DB>,
    entries: &[Entry],
    left: f64,
    top: f64,
    width: f64,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let text_style = style(LABEL_SIZE, false, BLACK, HPos::Left, VPos::Center);
    for (e, (row, x)) in entries.iter().zip(legend_places(entries, left, width)) {
        let mid = top + (row as f64 + 0.5) * LEGEND_ROW;
        let (x0, x1) = (x, x + SWATCH_W);
        match &e.swatch {
            Swatch::Block(colour) => c.rect(
                (x0 + 4.0, mid - 8.0),
                (x1 - 4.0, mid + 8.0),
                colour.filled(),
            )?,
            Swatch::Line(colour, shape) => {
                c.path(&[(x0, mid), (x1, mid)], colour.stroke_width(2))?;
                c.marker(*shape, ((x0 + x1) / 2.0, mid), 5.0, *colour, false)?;
            }
            Swatch::Paper { line, marker } => {
                if *line {
                    c.dashed(&[(x0, mid), (x1, mid)], 5, 3, BLACK.stroke_width(2))?;
                }
                if let Some(shape) = marker {
                    c.marker(*shape, ((x0 + x1) / 2.0, mid), 6.0, BLACK, true)?;
                }
            }
        }
        c.text(&e.label, &text_style, (x1 + 8.0, mid))?;
    }
    Ok(())
}
/// The width of the margin right of the plot that holds the labels of the
/// paper's lines across the plot.
pub(super) fn paper_margin(paper: &[PaperMark]) -> f64 {
    paper
        .iter()
        .filter(|m| m.category.is_none())
        .map(|m| text_size(&m.label, SMALL_SIZE + 1, true).0 + 16.0)
        .fold(30.0, f64::max)
}

/// Draws the paper's lines across the plot (marks of no category): a white
/// halo under a dashed line in the mark's colour, and the label in the
/// right margin at the line's height, moved up or down as little as needed
/// to keep labels apart. The lines are kept free of labels in the plot.
pub(super) fn draw_paper_lines<DB: DrawingBackend>(
    c: &Canvas<'_, DB>,
    f: &Frame,
    paper: &[PaperMark],
    placer: &mut Placer,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let mut lines: Vec<&PaperMark> = paper.iter().filter(|m| m.category.is_none()).collect();
    for m in &lines {
        let y = f.py(m.value);
        let ends = [(f.left, y), (f.right, y)];
        c.path(&ends, WHITE.mix(0.8).stroke_width(4))?;
        c.dashed(&ends, 9, 5, mark_colour(m.series).stroke_width(2))?;
        placer.take((f.left, y - 2.0, f.right, y + 2.0));
    }
    // Labels: top to bottom, each at least a line below the previous one.
    lines.sort_by(|a, b| b.value.total_cmp(&a.value));
    let h = text_size("Ag", SMALL_SIZE + 1, true).1 + 2.0;
    let mut ys: Vec<f64> = lines.iter().map(|m| f.py(m.value)).collect();
    for i in 1..ys.len() {
        ys[i] = ys[i].max(ys[i - 1] + h);
    }
    // Pushed below the plot's bottom: shift the whole stack up.
    if let Some(&last) = ys.last() {
        let over = last - (f.bottom + h / 2.0);
        if over > 0.0 {
            ys.iter_mut().for_each(|y| *y -= over);
        }
    }
    for (m, y) in lines.iter().zip(ys) {
        let s = style(
            SMALL_SIZE + 1,
            true,
            mark_colour(m.series),
            HPos::Left,
            VPos::Center,
        );
        c.text(&m.label, &s, (f.right + 8.0, y))?;
    }
    Ok(())
}
