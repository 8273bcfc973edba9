//! Heat maps ([`draw_heatmap`]): a grid over two parameters in plotters'
//! coordinates, a unit square per cell, each cell coloured on a diverging scale centred
//! on 0 (red below, white at 0, blue above: [`crate::palette::diverging`])
//! with its value printed in it, and a colour bar, a chart of its own,
//! right of the grid.

use super::frame::{
    builder, style, style_mesh, text_size, value_label, write, Drawn, Frame, Picture, Ticked,
    LABEL, SMALL,
};
use super::{ensure, finite, who};
use crate::palette::diverging;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};
use std::path::Path;

/// Width of the colour bar's strip.
const BAR_W: u32 = 190;

/// A heat map: `values[row][column]` over `x` (columns, left to right) and
/// `y` (rows, bottom to top).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct HeatMap {
    /// The title.
    pub title: String,
    /// The line under the title (none when empty).
    pub subtitle: String,
    /// The x axis label (the first parameter).
    pub x_label: String,
    /// The y axis label (the second parameter).
    pub y_label: String,
    /// The columns' labels (e.g. "8", "16", "31").
    pub x: Vec<String>,
    /// The rows' labels, bottom to top.
    pub y: Vec<String>,
    /// A row of values per `y`, a value per `x` (None: not measured, grey).
    pub values: Vec<Vec<Option<f64>>>,
    /// The values are fractions, labelled as percentages.
    pub percent: bool,
    /// What the colours mean, along the colour bar (e.g. "WaSP's speedup").
    pub scale_label: String,
}

/// Draws `map` into `path`, a PNG or an SVG by the file's extension.
///
/// Errors (starting with `drawing <title>:` or naming the file): another
/// extension; no columns or no rows; a row count other than the `y` count
/// or a row whose length is not the `x` count; a non-finite value; a file
/// that cannot be written.
pub fn draw_heatmap(map: &HeatMap, path: &Path) -> Result<(), String> {
    let (who, nx, ny) = (who(&map.title), map.x.len(), map.y.len());
    let rows = map.values.len();
    let what = format!("{rows} rows of values for {nx} columns and {ny} rows");
    ensure(nx > 0 && ny > 0 && rows == ny, || format!("{who}: {what}"))?;
    for (row, name) in map.values.iter().zip(&map.y) {
        let len = row.len();
        ensure(len == nx, || {
            format!("{who}: row `{name}` has {len} values for {nx} columns")
        })?;
        for (v, col) in row.iter().zip(&map.x) {
            let cell = format_args!("the cell ({col}, {name})");
            finite(&who, cell, v.unwrap_or(0.0))?;
        }
    }
    write(&who, path, || Heat::new(map))
}

/// A heat map laid out.
struct Heat<'a> {
    m: &'a HeatMap,
    frame: Frame<'a>,
    /// The largest magnitude: the ends of the scale.
    scale: f64,
    left: f64,
}

impl<'a> Heat<'a> {
    fn new(m: &'a HeatMap) -> Self {
        let values = m.values.iter().flatten().flatten();
        let scale = values.fold(0.0f64, |s, v| s.max(v.abs()));
        let scale = if scale > 0.0 { scale } else { 1.0 };
        let names = m.y.iter().map(|y| text_size(y, LABEL, false).0);
        let left = names.fold(0.0, f64::max) + 44.0;
        let width = left + 110.0 * m.x.len() as f64 + f64::from(BAR_W) + 20.0;
        let width = width.clamp(800.0, 1600.0).round();
        let frame = Frame::new((&m.title, &m.subtitle), Vec::new(), left, width);
        Heat {
            m,
            frame,
            scale,
            left,
        }
    }
}

impl Picture for Heat<'_> {
    fn size(&self) -> (u32, u32) {
        let height = f64::from(self.frame.height()) + 72.0 * self.m.y.len() as f64 + 90.0;
        (self.frame.width as u32, height.clamp(560.0, 1200.0) as u32)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Drawn<DB> {
        let (m, s) = (self.m, self.scale);
        let area = self.frame.draw(root)?;
        let (grid, bar) = area.split_horizontally(self.size().0 - BAR_W);
        // Column i spans x from i to i + 1, row j y from j to j + 1.
        let (x, y) = (Ticked::categories(&m.x), Ticked::categories(&m.y));
        let pad = (self.left, 64.0, 10.0, 10.0);
        let mut chart = builder(&grid, pad).build_cartesian_2d(x, y)?;
        let mut mesh = chart.configure_mesh();
        style_mesh(&mut mesh);
        mesh.disable_mesh()
            .x_desc(&m.x_label)
            .y_desc(&m.y_label)
            .draw()?;
        for (j, row) in m.values.iter().enumerate() {
            for (i, v) in row.iter().enumerate() {
                let t = v.map_or(0.0, |v| v / s);
                let fill = v.map_or(RGBColor(200, 200, 200), |_| diverging(t));
                let (x, y) = (i as f64, j as f64);
                let mut cell = Rectangle::new([(x, y), (x + 1.0, y + 1.0)], fill.filled());
                cell.set_margin(1, 1, 1, 1);
                chart.draw_series(std::iter::once(cell))?;
                let ink = if t.abs() > 0.6 { WHITE } else { BLACK };
                let text = v.map_or("-".to_string(), |v| value_label(v, m.percent));
                let s = style(SMALL + 1, false, ink, HPos::Center, VPos::Center);
                chart.draw_series(std::iter::once(Text::new(text, (x + 0.5, y + 0.5), s)))?;
            }
        }

        // The colour bar: thin bands from -scale to +scale, ticks right.
        let mut key = ChartBuilder::on(&bar);
        key.margin(20).margin_bottom(74).margin_right(30);
        key.right_y_label_area_size(90);
        let ticks = Ticked::numeric(&(-s..s), 6, m.percent);
        let mut key = key.build_cartesian_2d(0.0..1.0, ticks)?;
        let band = |k: u32| {
            let (a, b) = (f64::from(k) / 50.0 - 1.0, f64::from(k + 1) / 50.0 - 1.0);
            let colour = diverging((a + b) / 2.0);
            Rectangle::new([(0.0, a * s), (1.0, b * s)], colour.filled())
        };
        key.draw_series((0..100).map(band))?;
        let mut mesh = key.configure_mesh();
        style_mesh(&mut mesh);
        mesh.disable_mesh().disable_x_axis();
        mesh.y_desc(&m.scale_label).draw()
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::{out, pixels, refused, same_twice, texts, Case};
    use super::*;

    /// WaSP's speedup over L0 MSHRs and warps per core.
    fn mshrs_by_warps() -> HeatMap {
        let top = vec![Some(-0.05), Some(-0.013), None, Some(-0.004)];
        let rows = [[-0.01, 0.02, 0.03, 0.035], [-0.032, 0.001, 0.004, 0.005]];
        HeatMap {
            title: "WaSP's speedup over L0 MSHRs and warps per core".into(),
            subtitle: "3D scenes, mean".into(),
            x_label: "l0.mshrs".into(),
            y_label: "core.max_warps".into(),
            x: ["8", "16", "24", "31"].map(String::from).to_vec(),
            y: ["32", "64", "128"].map(String::from).to_vec(),
            values: vec![rows[0].map(Some).to_vec(), rows[1].map(Some).to_vec(), top],
            percent: true,
            scale_label: "WaSP's speedup over the baseline".into(),
        }
    }

    #[test]
    fn cells_show_values_on_a_diverging_scale() {
        let path = out("heat", "map.svg");
        draw_heatmap(&mshrs_by_warps(), &path).expect("draw svg");
        let axes = "l0.mshrs|core.max_warps|8|31|32|128|WaSP's speedup over the baseline|4%";
        texts(&path, &format!("-3.2%|3.5%|-5.0%|-|0.10%|{axes}"));
        let path = out("heat", "map.png");
        draw_heatmap(&mshrs_by_warps(), &path).expect("draw png");
        // The most negative cell has the scale's red end.
        let red = pixels(&path, diverging(-1.0));
        assert!(red > 2000, "{red} pixels of the red end");
        same_twice("heat-same", &|p| draw_heatmap(&mshrs_by_warps(), p));
        let cases: &[Case<HeatMap>] = &[
            (|c| c.values[1].truncate(3), "row `64` has 3 values for 4"),
            (|c| drop(c.values.pop()), "2 rows of values for 4 columns"),
            (|c| c.values[0][0] = Some(f64::NAN), "the cell (8, 32) has"),
            (|c| c.x.clear(), "for 0 columns and 3 rows"),
        ];
        refused(("heat-bad", &mshrs_by_warps(), ""), draw_heatmap, cases);
    }
}
