//! What one figure of the reproduction holds: its series over categories
//! (bars) or over x (lines), the paper's values drawn beside ours, and the
//! texts and marks around them.

use crate::palette::Key;

/// A series: a value per category.
#[derive(Clone, Debug, PartialEq)]
pub struct SeriesData {
    /// What it shows: it chooses the colour.
    pub key: Key,
    /// Legend name.
    pub name: String,
    /// Values (None: missing).
    pub values: Vec<Option<f64>>,
}

/// A paper value drawn beside ours.
#[derive(Clone, Debug, PartialEq)]
pub struct PaperValue {
    /// The series it belongs to (None: the whole figure).
    pub series: Option<usize>,
    /// The category (or x index) it applies to (None: all).
    pub category: Option<usize>,
    /// The value.
    pub value: f64,
    /// Label.
    pub label: String,
}

/// Bars over categories, or lines over x.
#[derive(Clone, Debug, PartialEq)]
pub enum Kind {
    /// Grouped bars, one group per category.
    Bars,
    /// Lines over numeric x (the categories are the tick labels).
    Lines {
        /// x of each category.
        x: Vec<f64>,
        /// x axis label.
        x_label: String,
    },
}

/// One figure's data.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    /// File stem (`speedup.shared-tile`).
    pub id: String,
    /// Title.
    pub title: String,
    /// One line under the title.
    pub subtitle: String,
    /// y axis label.
    pub y_label: String,
    /// Bars or lines.
    pub kind: Kind,
    /// Categories (scenes then means) or x tick labels.
    pub categories: Vec<String>,
    /// Series.
    pub series: Vec<SeriesData>,
    /// The paper's values.
    pub paper: Vec<PaperValue>,
    /// Values are fractions shown as percent.
    pub percent: bool,
    /// Values are changes or speedups (`x / base - 1`), printed with their
    /// sign (`+3.9%`); otherwise shares or amounts, printed without.
    pub signed: bool,
    /// A reference line.
    pub reference: Option<f64>,
    /// Category indices before which a separator is drawn.
    pub separators: Vec<usize>,
    /// Categories drawn emphasised (the means).
    pub highlight: Vec<usize>,
    /// Runs of categories named over the plot (e.g. "3D games").
    pub groups: Vec<(String, std::ops::Range<usize>)>,
    /// What the figure shows, for the report.
    pub caption: String,
}

/// The group means of a figure's series: games, 3D, 2D, procedural.
pub fn group_values(f: &Figure, series: usize) -> [Option<f64>; 4] {
    let at = |label: &str| {
        f.categories
            .iter()
            .position(|c| c == label)
            .and_then(|i| f.series.get(series).and_then(|s| s.values[i]))
    };
    [
        at("mean games"),
        at("mean 3D"),
        at("mean 2D"),
        at("mean procedural"),
    ]
}
