//! The category axis of the per-scene figures: the scenes in figure order
//! (3D games, then 2D games, then procedural scenes) and the group means
//! after them.

use crate::palette::Key;
use crate::reproduce::plan::{Group, Plan};
use std::ops::Range;

/// The colour key of a scene group's series.
pub fn group_key(g: Group) -> Key {
    match g {
        Group::ThreeD => Key::ThreeD,
        Group::TwoD => Key::TwoD,
        Group::Procedural => Key::Procedural,
    }
}

/// The scenes in figure order and the mean columns after them.
pub struct Axis {
    /// Scene names in order (3D, 2D, procedural; by name within).
    pub scenes: Vec<String>,
    /// Each scene's group.
    pub groups: Vec<Group>,
    /// The mean columns: label and the scene indices it averages.
    pub means: Vec<(String, Vec<usize>)>,
    /// The colour key of each mean column's group.
    pub mean_keys: Vec<Key>,
}

impl Axis {
    /// The axis of a plan.
    pub fn new(plan: &Plan) -> Axis {
        let mut s: Vec<(Group, String)> = plan
            .scenes
            .iter()
            .map(|x| (x.group, x.name.clone()))
            .collect();
        s.sort();
        let groups: Vec<Group> = s.iter().map(|x| x.0).collect();
        let idx = |f: &dyn Fn(Group) -> bool| -> Vec<usize> {
            (0..groups.len()).filter(|&i| f(groups[i])).collect()
        };
        let (mut means, mut mean_keys) = (Vec::new(), Vec::new());
        let games = idx(&|g| g != Group::Procedural);
        for (label, key, v) in [
            ("mean 3D", Key::ThreeD, idx(&|g| g == Group::ThreeD)),
            ("mean 2D", Key::TwoD, idx(&|g| g == Group::TwoD)),
            ("mean games", Key::Games, games),
            (
                "mean procedural",
                Key::Procedural,
                idx(&|g| g == Group::Procedural),
            ),
        ] {
            if !v.is_empty() {
                means.push((label.to_string(), v));
                mean_keys.push(key);
            }
        }
        Axis {
            scenes: s.into_iter().map(|x| x.1).collect(),
            groups,
            means,
            mean_keys,
        }
    }

    /// Scene names, then mean labels.
    pub fn categories(&self) -> Vec<String> {
        let mut c = self.scenes.clone();
        c.extend(self.means.iter().map(|m| m.0.clone()));
        c
    }

    /// Per-scene values extended with the means (a mean skips missing
    /// scenes; None if all are missing).
    pub fn with_means(&self, v: Vec<Option<f64>>) -> Vec<Option<f64>> {
        let mut out = v.clone();
        for (_, idx) in &self.means {
            out.push(mean(idx.iter().filter_map(|&i| v[i])));
        }
        out
    }

    /// The separators between the groups and before the means, the mean
    /// columns (highlighted), and the named runs of columns: each group's
    /// scenes ("3D games", "2D games", "procedural scenes") and the means.
    pub(super) fn marks(&self) -> (Vec<usize>, Vec<usize>, Vec<Run>) {
        let n = self.scenes.len();
        let mut sep: Vec<usize> = Vec::new();
        let mut runs = Vec::new();
        for i in 1..=n {
            if i == n || self.groups[i] != self.groups[i - 1] {
                let start = sep.last().copied().unwrap_or(0);
                let name = match self.groups[i - 1] {
                    Group::Procedural => "procedural scenes".to_string(),
                    g => format!("{} games", g.label()),
                };
                runs.push((name, start..i));
                sep.push(i);
            }
        }
        if !self.means.is_empty() {
            runs.push(("means".to_string(), n..n + self.means.len()));
        }
        (sep, (n..n + self.means.len()).collect(), runs)
    }
}

/// A named run of columns: its name and indices.
pub type Run = (String, Range<usize>);

/// Arithmetic mean (None for no values).
pub fn mean(v: impl Iterator<Item = f64>) -> Option<f64> {
    let (s, n) = v.fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
    (n > 0).then(|| s / n as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn means_skip_missing_scenes() {
        assert_eq!(mean([1.0, 2.0, 6.0].into_iter()), Some(3.0));
        assert_eq!(mean(std::iter::empty()), None);
        let axis = Axis {
            scenes: vec!["a".into(), "b".into(), "c".into()],
            groups: vec![Group::ThreeD, Group::ThreeD, Group::TwoD],
            means: vec![
                ("mean 3D".into(), vec![0, 1]),
                ("mean games".into(), vec![0, 1, 2]),
            ],
            mean_keys: vec![Key::ThreeD, Key::Games],
        };
        assert_eq!(
            axis.with_means(vec![Some(1.0), None, Some(3.0)]),
            [Some(1.0), None, Some(3.0), Some(1.0), Some(2.0)]
        );
        let (sep, hi, runs) = axis.marks();
        assert_eq!(sep, [2, 3]);
        assert_eq!(hi, [3, 4]);
        let names: Vec<&str> = runs.iter().map(|r| r.0.as_str()).collect();
        assert_eq!(names, ["3D games", "2D games", "means"]);
        assert_eq!(runs[0].1, 0..2);
        assert_eq!(runs[2].1, 3..5);
    }
}
