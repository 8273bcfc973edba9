//! The figures of the scenes themselves, the same on every machine:
//! Min_Estimate1, CF and Min_Estimate2 (Figure 4) and the footprint ratios
//! of the priority subsets (Figures 11 and 15).

use super::axis::Axis;
use super::figure::{Figure, Kind, PaperValue, SeriesData};
use super::numbers::size_ratio;
use crate::palette::Key;
use crate::reproduce::paper;
use crate::reproduce::plan::Plan;
use crate::study::runner::Outcome;

type Char = wasp_frontend::characterize::Characterization;

/// The scene characterisation figures (no machine): Min_Estimate1, CF and
/// Min_Estimate2 (Figure 4), and the footprint ratios (Figures 11 and 15).
pub fn scene_figures(plan: &Plan, out: &Outcome) -> Vec<Figure> {
    let s = Scenes {
        axis: Axis::new(plan),
        out,
    };
    let base = s.base();
    vec![
        s.estimates(&base),
        s.cf(&base),
        s.footprint(&base),
        s.meshes(&base, &plan.meshes),
    ]
}

/// A subset's footprint ratio in a characterisation.
fn footprint_of(name: &str, c: &Char) -> Option<f64> {
    c.footprints
        .iter()
        .find(|f| f.subset == name || f.subset.starts_with(&format!("{name}:")))
        .map(|f| f.footprint_ratio)
}

/// The scenes on the x axis and their characterisations.
struct Scenes<'a> {
    axis: Axis,
    out: &'a Outcome,
}

impl Scenes<'_> {
    /// `f` of every scene, with the group means.
    fn per(&self, f: &dyn Fn(&Char) -> Option<f64>) -> Vec<Option<f64>> {
        let v = self
            .axis
            .scenes
            .iter()
            .map(|s| self.out.scenes.get(s).and_then(f))
            .collect();
        self.axis.with_means(v)
    }

    /// What every scene figure shares: the categories and their marks.
    fn base(&self) -> Figure {
        let (separators, highlight, groups) = self.axis.marks();
        Figure {
            id: String::new(),
            title: String::new(),
            subtitle: "per scene, 64x64-pixel tiles".into(),
            y_label: String::new(),
            kind: Kind::Bars,
            categories: self.axis.categories(),
            series: Vec::new(),
            paper: Vec::new(),
            percent: false,
            signed: false,
            reference: None,
            separators,
            highlight,
            groups,
            caption: String::new(),
        }
    }

    /// Figure 4: Min_Estimate1 and Min_Estimate2.
    fn estimates(&self, base: &Figure) -> Figure {
        Figure {
            id: "subset-size".into(),
            title: "Priority subset size: Min_Estimate1 and Min_Estimate2".into(),
            y_label: "fraction of a tile's warps".into(),
            series: vec![
                SeriesData {
                    key: Key::Other,
                    name: "Min_Estimate1 (unique blocks / warps)".into(),
                    values: self.per(&|c| Some(c.min_estimate1)),
                },
                SeriesData {
                    key: Key::Other,
                    name: "Min_Estimate2 (/ CF)".into(),
                    values: self.per(&|c| Some(c.min_estimate2)),
                },
            ],
            paper: vec![
                PaperValue {
                    series: Some(0),
                    category: None,
                    value: paper::MIN_ESTIMATE1.value,
                    label: format!("Min_Estimate1 mean {}", paper::MIN_ESTIMATE1.value),
                },
                PaperValue {
                    series: Some(1),
                    category: None,
                    value: paper::MIN_ESTIMATE2.value,
                    label: "its pick for Min_Estimate2, 1/16".into(),
                },
            ],
            caption: "The paper's Figure 4: the smallest subset that could hold a tile's \
                      footprint, from which it picks 1/16 (Mesh4)."
                .into(),
            ..base.clone()
        }
    }

    /// Section III-B's CF.
    fn cf(&self, base: &Figure) -> Figure {
        Figure {
            id: "cf".into(),
            title: "CF: distinct texture blocks per warp".into(),
            y_label: "blocks per warp".into(),
            series: vec![SeriesData {
                key: Key::Other,
                name: "CF".into(),
                values: self.per(&|c| Some(c.cf)),
            }],
            paper: vec![PaperValue {
                series: Some(0),
                category: None,
                value: paper::CF.value,
                label: format!("CF mean {}", paper::CF.value),
            }],
            caption: "Section III-B's CF, the x CF of WaSP's datapath.".into(),
            ..base.clone()
        }
    }

    /// A series per subset, `(subset, series name, paper label)`, with the
    /// paper's value where it gives one.
    fn subsets(&self, fig: &mut Figure, subsets: &[(&str, String, String)]) {
        for (i, (subset, name, label)) in subsets.iter().enumerate() {
            fig.series.push(SeriesData {
                key: Key::Other,
                name: name.clone(),
                values: self.per(&|c| footprint_of(subset, c)),
            });
            if let Some(v) = paper::footprint(subset) {
                fig.paper.push(PaperValue {
                    series: Some(i),
                    category: None,
                    value: v,
                    label: format!("{label} {v}"),
                });
            }
        }
    }

    /// Figure 11: the footprint ratio of each priority subset.
    fn footprint(&self, base: &Figure) -> Figure {
        let mut fig = Figure {
            id: "footprint".into(),
            title: "Texture footprint ratio of each priority subset".into(),
            y_label: "subset's unique blocks / tile's".into(),
            caption: "Figure 11: the share of a tile's texture blocks the subset's warps \
                      touch; dashed lines are the paper's means."
                .into(),
            ..base.clone()
        };
        let subsets: Vec<_> = ["top16", "hlines", "vlines", "mesh4", "random"]
            .iter()
            .map(|s| (*s, s.to_string(), s.to_string()))
            .collect();
        self.subsets(&mut fig, &subsets);
        fig
    }

    /// Figure 15: the footprint ratio per Mesh size.
    fn meshes(&self, base: &Figure, meshes: &[u32]) -> Figure {
        let mut fig = Figure {
            id: "footprint-mesh".into(),
            title: "Texture footprint ratio per Mesh size".into(),
            y_label: "subset's unique blocks / tile's".into(),
            caption: "Figure 15: larger meshes select fewer warps (size ratio 1/N^2) and \
                      cover less of the footprint."
                .into(),
            ..base.clone()
        };
        let subsets: Vec<_> = meshes
            .iter()
            .map(|n| {
                let name = match n {
                    2 => "mesh2",
                    4 => "mesh4",
                    8 => "mesh8",
                    _ => "mesh16",
                };
                (
                    name,
                    format!("Mesh{n} (size ratio {})", size_ratio(*n)),
                    format!("Mesh{n}"),
                )
            })
            .collect();
        self.subsets(&mut fig, &subsets);
        fig
    }
}
