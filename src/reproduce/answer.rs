//! REPORT.md's opening section, "The answer": a few sentences generated
//! from the run's own numbers. Does WaSP gain, and where; how it stands
//! against Fullpriority, the raster prefetcher, the oracle tile prefetcher
//! and ideal memory; what the paper's claims come to. Every count names
//! what ran, two numbers never print the same unless they are
//! ([`super::digits`]), and a group mean that one game dominates carries
//! its median and per-game values ([`dominated`]).

use super::digits::distinct_pcts;
use super::figures::{Figure, Figures};
use super::headline::{group_values, series_index};
use super::map::table::MapTable;
use super::paper;
use super::plan::{Group, Plan};
use super::prose::pct;
use std::fmt::Write as _;
use wasp_sim::config::Dispatch;

/// The groups, in the order the figures' means hold them (after `games`).
const GROUPS: [Group; 3] = [Group::ThreeD, Group::TwoD, Group::Procedural];

/// One group's values of a series: per scene (name, value) and the mean.
struct GroupValues {
    group: Group,
    scenes: Vec<(String, f64)>,
    mean: Option<f64>,
}

/// The values of series `s` of figure `f`, per group that has scenes.
fn by_group(x: &Figures, f: &Figure, s: usize) -> Vec<GroupValues> {
    let means = group_values(f, s);
    GROUPS
        .iter()
        .enumerate()
        .filter_map(|(gi, &g)| {
            let scenes: Vec<(String, f64)> = x
                .axis
                .scenes
                .iter()
                .enumerate()
                .filter(|(i, _)| x.axis.groups[*i] == g)
                .filter_map(|(i, name)| Some((name.clone(), f.series.get(s)?.values[i]?)))
                .collect();
            (!scenes.is_empty()).then_some(GroupValues {
                group: g,
                scenes,
                mean: means[gi + 1],
            })
        })
        .collect()
}

/// The game of a scene, from its definition (its name when unknown).
fn game_of(scene: &str) -> String {
    wasp_frontend::def::all()
        .ok()
        .and_then(|all| all.into_iter().find(|d| d.name == scene))
        .map_or_else(|| scene.to_string(), |d| d.game.to_string())
}

/// The median of `v` (not empty).
fn median(v: &[f64]) -> f64 {
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    let n = s.len();
    if n % 2 == 1 {
        s[n / 2]
    } else {
        (s[n / 2 - 1] + s[n / 2]) / 2.0
    }
}

/// When one game dominates a group's mean, the median and per-game means
/// as text: a game holds at least three quarters of the scenes' summed
/// absolute values while holding at most half of the scenes, and the group
/// has at least two games.
pub fn dominated(scenes: &[(String, f64)]) -> Option<String> {
    let mut games: Vec<(String, Vec<f64>)> = Vec::new();
    for (name, v) in scenes {
        let g = game_of(name);
        match games.iter_mut().find(|x| x.0 == g) {
            Some(x) => x.1.push(*v),
            None => games.push((g, vec![*v])),
        }
    }
    if games.len() < 2 {
        return None;
    }
    let total: f64 = scenes.iter().map(|(_, v)| v.abs()).sum();
    let n = scenes.len() as f64;
    let top = games.iter().find(|(_, vs)| {
        let part: f64 = vs.iter().map(|v| v.abs()).sum();
        total > 0.0 && part / total >= 0.75 && vs.len() as f64 / n <= 0.5
    })?;
    let values: Vec<f64> = scenes.iter().map(|(_, v)| *v).collect();
    let per_game: Vec<String> = games
        .iter()
        .map(|(g, vs)| {
            let m = vs.iter().sum::<f64>() / vs.len() as f64;
            let n = vs.len();
            let scenes = if n == 1 { "scene" } else { "scenes" };
            format!("{g} {} ({n} {scenes})", pct(Some(m)))
        })
        .collect();
    Some(format!(
        "mostly {}: median {}, per game {}",
        top.0,
        pct(Some(median(&values))),
        per_game.join(", ")
    ))
}

/// When one game dominates group `g`'s mean of series `s` of `f`, " (mostly
/// GAME: median ..., per game ...)", else nothing.
pub fn dominance_note(x: &Figures, f: &Figure, s: usize, g: Group) -> String {
    by_group(x, f, s)
        .iter()
        .find(|v| v.group == g)
        .and_then(|v| dominated(&v.scenes))
        .map_or_else(String::new, |d| format!(" ({d})"))
}

/// A group's mean as text, with its median and per-game values when one
/// game dominates it.
fn mean_text(g: &GroupValues, text: &str) -> String {
    match dominated(&g.scenes) {
        Some(d) => format!("{text} ({d})"),
        None => text.to_string(),
    }
}

/// "The answer", appended to `md`.
pub fn answer(
    md: &mut String,
    plan: &Plan,
    machines: &[(Dispatch, Figures)],
    map: Option<&MapTable>,
) {
    let _ = writeln!(md, "\n## The answer\n");
    let mut s: Vec<String> = Vec::new();
    s.push(what_ran(plan));
    for (d, x) in machines {
        s.push(wasp_sentence(plan, *d, x));
    }
    if let Some((d, x)) = machines.first() {
        s.push(fullpriority_sentence(plan, *d, x));
        s.extend(ideal_sentence(*d, x));
    }
    if let Some(t) = map {
        s.extend(bounds_sentence(plan, t));
    }
    if let Some((d, x)) = machines.first() {
        s.push(claims_sentence(plan, *d, x));
    }
    let _ = writeln!(md, "{}\n", s.join(" "));
}

fn what_ran(plan: &Plan) -> String {
    let count = |g: Group| plan.scenes.iter().filter(|s| s.group == g).count();
    let groups: Vec<String> = GROUPS
        .iter()
        .filter(|&&g| count(g) > 0)
        .map(|&g| format!("{} {}", count(g), g.label()))
        .collect();
    let machines: Vec<String> = plan.dispatches.iter().map(|d| d.to_string()).collect();
    format!(
        "This run measured {} scenes ({}; {}) on the {} machine{}{}; every number below is \
         a group's mean over its scenes in this run.",
        plan.scenes.len(),
        groups.join(", "),
        super::routes_report::route_counts(plan),
        machines.join(" and the "),
        if machines.len() > 1 { "s" } else { "" },
        if plan.quick { " (a quick look)" } else { "" }
    )
}

fn wasp_sentence(plan: &Plan, d: Dispatch, x: &Figures) -> String {
    let f = x.heuristics(d);
    let groups = by_group(x, &f, series_index(&f, &plan.wasp.to_string()));
    let parts: Vec<String> = groups
        .iter()
        .map(|g| format!("{} on the {} scenes", mean_text(g, &pct(g.mean)), g.label()))
        .collect();
    let all: Vec<f64> = groups
        .iter()
        .flat_map(|g| g.scenes.iter().map(|s| s.1))
        .collect();
    let gains = all.iter().filter(|&&v| v > 0.0).count();
    format!(
        "On the {d} machine WaSP ({}) changes speed by {}, gaining on {gains} of the {} \
         scenes where it ran.",
        plan.wasp,
        parts.join(", "),
        all.len()
    )
}

impl GroupValues {
    fn label(&self) -> &'static str {
        self.group.label()
    }
}

fn fullpriority_sentence(plan: &Plan, d: Dispatch, x: &Figures) -> String {
    let f = x.heuristics(d);
    let w = by_group(x, &f, series_index(&f, &plan.wasp.to_string()));
    let fp = by_group(x, &f, series_index(&f, "fullpriority"));
    let parts: Vec<String> = w
        .iter()
        .zip(&fp)
        .map(|(a, b)| {
            let t = distinct_pcts(&[a.mean, b.mean]);
            let rel = match (a.mean, b.mean) {
                (Some(p), Some(q)) if p > q => "ahead",
                (Some(p), Some(q)) if p < q => "behind",
                (Some(_), Some(_)) => "tied",
                _ => "not compared",
            };
            format!(
                "{rel} on the {} scenes (WaSP {}, Fullpriority {})",
                a.label(),
                t[0],
                t[1]
            )
        })
        .collect();
    format!(
        "Against Fullpriority on the {d} machine, WaSP is {}.",
        parts.join("; ")
    )
}

fn ideal_sentence(d: Dispatch, x: &Figures) -> Option<String> {
    let f = x.motivation(d);
    let groups = by_group(x, &f, 0);
    let parts: Vec<String> = groups
        .iter()
        .map(|g| format!("{} on the {} scenes", mean_text(g, &pct(g.mean)), g.label()))
        .collect();
    (!parts.is_empty()).then(|| {
        format!(
            "The headroom: ideal (zero-latency) main memory makes the baseline faster by {}.",
            parts.join(", ")
        )
    })
}

/// The map's shipped machine: the prefetchers and the bounds beside WaSP.
fn bounds_sentence(plan: &Plan, t: &MapTable) -> Option<String> {
    let parts: Vec<String> = GROUPS
        .iter()
        .filter_map(|&g| {
            let m = t.shipped.of(g);
            let w = m.wasp?;
            let v = distinct_pcts(&[Some(w), m.raster, m.oracle]);
            Some(format!(
                "on the {} scenes WaSP {}, the raster prefetcher {}, the oracle {}",
                g.label(),
                v[0],
                v[1],
                v[2]
            ))
        })
        .collect();
    let _ = plan;
    (!parts.is_empty()).then(|| {
        format!(
            "Against the prefetchers on the shipped shared-tile machine (the map's runs, \
             over its scenes): {}.",
            parts.join("; ")
        )
    })
}

fn claims_sentence(plan: &Plan, d: Dispatch, x: &Figures) -> String {
    let f = x.heuristics(d);
    let w = group_values(&f, series_index(&f, &plan.wasp.to_string()));
    let fp = group_values(&f, series_index(&f, "fullpriority"));
    let lat = group_values(&x.latency_change(d), 0);
    let names = ["3D", "2D", "procedural"];
    let reach: Vec<&str> = (0..3)
        .filter(|&i| w[i + 1].is_some_and(|v| v >= paper::WASP_SPEEDUP.value))
        .map(|i| names[i])
        .collect();
    let above: Vec<&str> = (0..3)
        .filter(|&i| matches!((w[i + 1], fp[i + 1]), (Some(a), Some(b)) if a >= b))
        .map(|i| names[i])
        .collect();
    let list = |v: &[&str]| {
        if v.is_empty() {
            "no group".to_string()
        } else {
            format!("the {} scenes", v.join(" and "))
        }
    };
    let latency = match lat[0] {
        Some(v) if v < 0.0 => format!("falls {}", pct(Some(v)).trim_start_matches('-')),
        Some(v) if v > 0.0 => format!("rises {}", pct(Some(v)).trim_start_matches('+')),
        Some(_) => "does not change".to_string(),
        None => "was not measured".to_string(),
    };
    format!(
        "The paper's claims on the {d} machine: WaSP's +3.9% is reached on {}; WaSP at least \
         as fast as Fullpriority (the paper: +3.9% against +1.3%) holds on {}; WaSP's mean \
         memory latency {latency} on the games (the paper: falls {}).",
        list(&reach),
        list(&above),
        pct(Some(paper::LATENCY_CHANGE.value)).trim_start_matches('-')
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn s(v: &[(&str, f64)]) -> Vec<(String, f64)> {
        v.iter().map(|(n, x)| (n.to_string(), *x)).collect()
    }

    #[test]
    fn one_game_dominating_a_mean_is_shown_with_the_median() {
        // Two Frozen Bubble scenes far above three Teeworlds scenes.
        let v = s(&[
            ("fb-level1", 0.74),
            ("fb-level100-wide", 0.76),
            ("tw-dm1-spawn0", 0.05),
            ("tw-dm6-center", 0.04),
            ("tw-dm8-center", 0.06),
        ]);
        let d = dominated(&v).unwrap();
        assert!(d.starts_with("mostly frozen-bubble: median +6.0%"), "{d}");
        assert!(d.contains("frozen-bubble +75.0% (2 scenes)"), "{d}");
        // Values of one size: no game dominates.
        let even = s(&[("fb-level1", 0.05), ("tw-dm1-spawn0", 0.04)]);
        assert!(dominated(&even).is_none());
        // One game only: nothing to set beside.
        assert!(dominated(&s(&[("fb-level1", 0.7), ("fb-level100-wide", 0.1)])).is_none());
    }

    #[test]
    fn the_median_of_even_and_odd_counts() {
        assert_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&[4.0, 1.0, 2.0, 3.0]), 2.5);
    }
}
