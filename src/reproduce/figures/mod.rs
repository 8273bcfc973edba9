//! The numbers of each figure of the reproduction, from a run's results:
//! per scene (3D games, then 2D games, then procedural scenes) and the
//! group means, with the paper's value where it states one.
//!
//! A figure here is data only; [`super::report`] draws it and writes it as
//! CSV. Speedups are `baseline cycles / cycles - 1`; changes are
//! `x / base - 1`; means are arithmetic means over the group's scenes,
//! "games" being the 3D and 2D scenes together (the paper's suite is games
//! only).
//!
//! - [`figure`]: what a figure holds;
//! - [`axis`]: the scenes in figure order and the group means;
//! - [`numbers`]: speedups, changes and their text;
//! - [`speedups`], [`effects`], [`warps`] and [`sensitivity`]: the figures
//!   of one machine, by family, as methods of [`Figures`];
//! - [`scenes`]: the figures of the scenes themselves (no machine).

mod axis;
mod effects;
mod figure;
mod numbers;
mod scenes;
mod sensitivity;
mod speedups;
mod warps;

pub use axis::{group_key, mean, Axis};
pub use figure::{group_values, Figure, Kind, PaperValue};
pub use scenes::scene_figures;

use super::paper::Claim;
use super::plan::Plan;
use crate::study::cache::PointRecord;
use crate::study::point::Point;
use crate::study::runner::Outcome;
use numbers::fmt_claim;

/// Builds the figures of one machine from the results.
pub struct Figures<'a> {
    /// The plan.
    pub plan: &'a Plan,
    /// The results.
    pub out: &'a Outcome,
    /// The axis.
    pub axis: Axis,
}

impl<'a> Figures<'a> {
    /// Figures of `plan` from `out`.
    pub fn new(plan: &'a Plan, out: &'a Outcome) -> Self {
        Figures {
            plan,
            out,
            axis: Axis::new(plan),
        }
    }

    fn get(&self, p: &Point) -> Option<&PointRecord> {
        self.out.get(p)
    }

    /// Per scene: f(record of a(scene), record of b(scene)).
    fn pair(
        &self,
        a: impl Fn(&str) -> Point,
        b: impl Fn(&str) -> Point,
        f: impl Fn(&PointRecord, &PointRecord) -> Option<f64>,
    ) -> Vec<Option<f64>> {
        let v = self
            .axis
            .scenes
            .iter()
            .map(|s| match (self.get(&a(s)), self.get(&b(s))) {
                (Some(x), Some(y)) => f(x, y),
                _ => None,
            })
            .collect();
        self.axis.with_means(v)
    }

    /// Per scene: f(record of a(scene)).
    fn single(
        &self,
        a: impl Fn(&str) -> Point,
        f: impl Fn(&PointRecord) -> Option<f64>,
    ) -> Vec<Option<f64>> {
        let v = self
            .axis
            .scenes
            .iter()
            .map(|s| self.get(&a(s)).and_then(&f))
            .collect();
        self.axis.with_means(v)
    }

    fn bars(&self, id: String, title: &str, subtitle: String, y_label: &str) -> Figure {
        let (separators, highlight, groups) = self.axis.marks();
        Figure {
            id,
            title: title.to_string(),
            subtitle,
            y_label: y_label.to_string(),
            kind: Kind::Bars,
            categories: self.axis.categories(),
            series: Vec::new(),
            paper: Vec::new(),
            percent: true,
            signed: true,
            reference: Some(0.0),
            separators,
            highlight,
            groups,
            caption: String::new(),
        }
    }

    fn paper_line(&self, series: Option<usize>, c: Claim, what: &str) -> PaperValue {
        PaperValue {
            series,
            category: None,
            value: c.value,
            label: format!("{what} {} ({})", fmt_claim(c.value), c.source),
        }
    }
}
