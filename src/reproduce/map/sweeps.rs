//! The map as sweep files (docs/sweep.md), so that its points can run as
//! one cluster job each (`wasp sweep FILE --jobs-file`) into the
//! reproduction's folder; `wasp reproduce` then finds them done (a point's
//! cache key is its scene, effective configuration and build, not its
//! spelling), runs the grid and writes the report.
//!
//! Three files, because the map is not one full grid of configurations x
//! policies: `map-policies.toml` (every knob value under the baseline,
//! Fullpriority and WaSP), `map-bounds.toml` (every knob value with the
//! raster prefetcher, the oracle and ideal memory, under the baseline) and
//! `map-deep-queue.toml` (the warp series with a deep input queue); the
//! scene knobs' values have files of their own (`map-draw-order*.toml`
//! with `draw_orders`, `map-texture-format*.toml` with `texture_formats`,
//! one pair per cache choice of the texture caches).

use super::knobs::{Knob, Variant};
use super::plan::{deep_queue, MapPlan, DEEP_QUEUE};
use std::fmt::Write as _;
use wasp_rtl::policy::PolicySpec;
use wasp_sim::config::Override;

/// A `[[configs]]` entry: name and overrides.
type Entry = (String, Vec<Override>);

fn toml_list<T: ToString>(v: &[T]) -> String {
    let q: Vec<String> = v
        .iter()
        .map(|s| {
            let s = s.to_string();
            format!("\"{}\"", s.replace('\\', "\\\\").replace('"', "\\\""))
        })
        .collect();
    format!("[{}]", q.join(", "))
}

/// A sweep file's text; `orders` are its `draw_orders` and `formats` its
/// `texture_formats` (none: the scenes' own).
fn file(
    comment: &str,
    scenes: &[String],
    policies: &[PolicySpec],
    configs: &[Entry],
    orders: &[&str],
    formats: &[&str],
) -> String {
    let mut s = String::new();
    for line in comment.lines() {
        let _ = writeln!(s, "# {line}");
    }
    let _ = writeln!(s, "scenes = {}", toml_list(scenes));
    let p: Vec<String> = policies.iter().map(|p| p.to_string()).collect();
    let _ = writeln!(s, "policies = {}", toml_list(&p));
    let _ = writeln!(s, "dispatches = [\"shared-tile\"]");
    if !orders.is_empty() {
        let o: Vec<String> = orders.iter().map(|o| o.to_string()).collect();
        let _ = writeln!(s, "draw_orders = {}", toml_list(&o));
    }
    if !formats.is_empty() {
        let f: Vec<String> = formats.iter().map(|f| f.to_string()).collect();
        let _ = writeln!(s, "texture_formats = {}", toml_list(&f));
    }
    for (name, set) in configs {
        let _ = writeln!(
            s,
            "\n[[configs]]\nname = \"{name}\"\nbase = \"paper\"\nset = {}",
            toml_list(set)
        );
    }
    s
}

/// The knob values as configuration entries (the shipped machine once).
fn knob_entries(map: &MapPlan) -> Vec<Entry> {
    let mut v: Vec<Entry> = vec![("shipped".into(), Vec::new())];
    for k in map.knobs.iter().filter(|k| !k.scene_knob()) {
        for value in k.values_for(map.quick) {
            if *value != k.shipped {
                v.push((entry_name(k, value), k.overrides(value)));
            }
        }
    }
    v
}

fn entry_name(k: &Knob, value: &str) -> String {
    format!("{}={}", k.id, value)
}

/// The overrides a bound adds to the baseline, and its suffix.
fn bound(v: Variant) -> (&'static str, Vec<Override>) {
    let sets = v.machine();
    let name = match v {
        Variant::Raster => "raster",
        Variant::Oracle => "oracle",
        _ => "ideal",
    };
    (name, sets)
}

/// Each entry once under each bound: the raster prefetcher, the oracle and
/// ideal memory.
fn with_bounds(configs: &[Entry]) -> Vec<Entry> {
    let mut v = Vec::new();
    for (name, set) in configs {
        for b in [Variant::Raster, Variant::Oracle, Variant::Ideal] {
            let (suffix, extra) = bound(b);
            let mut s = set.clone();
            s.extend(extra);
            v.push((format!("{name}+{suffix}"), s));
        }
    }
    v
}

/// The draw orders the map runs besides the shipped one.
fn other_orders(map: &MapPlan) -> Vec<&'static str> {
    map.knobs
        .iter()
        .filter(|k| k.draw_order)
        .flat_map(|k| k.values_for(map.quick).iter().filter(|v| **v != k.shipped))
        .copied()
        .collect()
}

/// The deep-queue warp series, each count alone and with the oracle.
fn deep_entries(map: &MapPlan) -> Vec<Entry> {
    let mut deep = Vec::new();
    for &w in &map.deep_queue_warps {
        let set = deep_queue(w).to_vec();
        let mut oracle = set.clone();
        oracle.extend(bound(Variant::Oracle).1);
        deep.push((format!("warps={w}+queue={DEEP_QUEUE}"), set));
        deep.push((format!("warps={w}+queue={DEEP_QUEUE}+oracle"), oracle));
    }
    deep
}

/// The opening of every file's comment.
const HEAD: &str = "The map \"What decides WaSP's gain\" of `wasp reproduce`, written by \
                    `wasp reproduce --sweep-files`.\nRun it into the reproduction's folder, \
                    then `wasp reproduce --out` that folder for the grid and the report.";

/// The policies a file's entries run under, in its order: the baseline,
/// Fullpriority and the map's WaSP.
fn policies(map: &MapPlan) -> [PolicySpec; 3] {
    [PolicySpec::Baseline, PolicySpec::FullPriority, map.wasp]
}

/// The map's sweep files on `scenes`: (file name, text).
pub fn files(map: &MapPlan, scenes: &[String]) -> Vec<(String, String)> {
    let mut out = knob_files(map, scenes);
    out.extend(draw_order_files(map, scenes));
    out.extend(texture_format_files(map, scenes));
    out
}

/// The machine knobs' files: every value under the baseline, Fullpriority
/// and WaSP, every value with the bounds, and the deep-queue warp series.
fn knob_files(map: &MapPlan, scenes: &[String]) -> Vec<(String, String)> {
    let knobs = knob_entries(map);
    let policies = policies(map);
    let bounds = with_bounds(&knobs);
    let deep = deep_entries(map);
    vec![
        (
            "map-policies.toml".into(),
            file(
                &format!("{HEAD}\nEvery knob value under the baseline, Fullpriority and WaSP."),
                scenes,
                &policies,
                &knobs,
                &[],
                &[],
            ),
        ),
        (
            "map-bounds.toml".into(),
            file(
                &format!(
                    "{HEAD}\nEvery knob value with the raster prefetcher, the oracle tile \
                     prefetcher and ideal memory, under the baseline."
                ),
                scenes,
                &[PolicySpec::Baseline],
                &bounds,
                &[],
                &[],
            ),
        ),
        (
            "map-deep-queue.toml".into(),
            file(
                &format!(
                    "{HEAD}\nThe warp counts with a {DEEP_QUEUE}-entry input queue (the \
                     oracle entries run under the baseline; their WaSP point is not part of \
                     the map)."
                ),
                scenes,
                &[PolicySpec::Baseline, map.wasp],
                &deep,
                &[],
                &[],
            ),
        ),
    ]
}

/// The draw-order knob's files (none if the map runs no other order): the
/// shipped machine with the other orders under the baseline, Fullpriority
/// and WaSP, and with the bounds.
fn draw_order_files(map: &MapPlan, scenes: &[String]) -> Vec<(String, String)> {
    let policies = policies(map);
    let shipped: Vec<Entry> = vec![("shipped".into(), Vec::new())];
    let orders = other_orders(map);
    let mut out = Vec::new();
    if !orders.is_empty() {
        out.push((
            "map-draw-order.toml".into(),
            file(
                &format!(
                    "{HEAD}\nThe shipped machine with the scenes drawn in other opaque \
                     orders, under the baseline, Fullpriority and WaSP."
                ),
                scenes,
                &policies,
                &shipped,
                &orders,
                &[],
            ),
        ));
        out.push((
            "map-draw-order-bounds.toml".into(),
            file(
                &format!(
                    "{HEAD}\nThe same orders with the raster prefetcher, the oracle and \
                     ideal memory, under the baseline."
                ),
                scenes,
                &[PolicySpec::Baseline],
                &with_bounds(&shipped),
                &orders,
                &[],
            ),
        ));
    }
    out
}

/// The texture-format knob's values besides the shipped one, grouped by
/// the machine they run on: (the entry's name suffix, its overrides, the
/// formats).
fn other_formats(map: &MapPlan) -> Vec<(String, Vec<Override>, Vec<String>)> {
    let mut groups: Vec<(String, Vec<Override>, Vec<String>)> = Vec::new();
    for k in map.knobs.iter().filter(|k| k.texture_format) {
        for v in k.values_for(map.quick).iter().filter(|v| **v != k.shipped) {
            let Some(f) = k.format(v) else { continue };
            let sets = k.overrides(v);
            let suffix = v.strip_prefix(f.name()).unwrap_or("").to_string();
            match groups.iter_mut().find(|g| g.1 == sets) {
                Some(g) => g.2.push(f.name().to_string()),
                None => groups.push((suffix, sets, vec![f.name().to_string()])),
            }
        }
    }
    groups
}

/// The texture-format knob's files: per machine its formats under the
/// baseline, Fullpriority and WaSP, and with the bounds.
fn texture_format_files(map: &MapPlan, scenes: &[String]) -> Vec<(String, String)> {
    let policies = policies(map);
    let mut out = Vec::new();
    for (suffix, sets, formats) in other_formats(map) {
        let tag = suffix.trim_start_matches('+');
        let (file_tag, what) = match tag {
            "" => (String::new(), String::new()),
            t => (format!("-{t}"), format!(" (texture caches: {t})")),
        };
        let entry = vec![(format!("shipped{suffix}"), sets)];
        let formats: Vec<&str> = formats.iter().map(String::as_str).collect();
        out.push((
            format!("map-texture-format{file_tag}.toml"),
            file(
                &format!(
                    "{HEAD}
The shipped machine{what} with the scenes' textures stored in \
                     other formats, under the baseline, Fullpriority and WaSP."
                ),
                scenes,
                &policies,
                &entry,
                &[],
                &formats,
            ),
        ));
        out.push((
            format!("map-texture-format{file_tag}-bounds.toml"),
            file(
                &format!(
                    "{HEAD}
The same formats{what} with the raster prefetcher, the oracle \
                     and ideal memory, under the baseline."
                ),
                scenes,
                &[PolicySpec::Baseline],
                &with_bounds(&entry),
                &[],
                &formats,
            ),
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::point::Resolver;
    use crate::study::sweep::Sweep;
    use std::collections::HashSet;

    #[test]
    fn the_sweep_files_describe_the_maps_machines() {
        let map = MapPlan::new(
            PolicySpec::Wasp {
                threshold: 0,
                cf: 3.0,
            },
            false,
        );
        let scenes = vec!["procedural-plane".to_string()];
        let dir = std::env::temp_dir().join(format!("wasp-map-sweeps-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let mut r = Resolver::default();
        let mut swept = HashSet::new();
        for (name, text) in files(&map, &scenes) {
            let path = dir.join(name);
            std::fs::write(&path, text).unwrap();
            let sweep = Sweep::load(&path).unwrap();
            for p in sweep.points().unwrap() {
                swept.insert((
                    toml::to_string(&*p.machine).unwrap(),
                    p.point.draw_order,
                    p.point.texture_format,
                ));
            }
        }
        std::fs::remove_dir_all(&dir).ok();
        // Every machine of the map's one-at-a-time points is in a file,
        // the scene knobs' (draw orders, texture formats under both cache
        // choices) included.
        let mut formats = 0;
        for t in map.tasks(&scenes) {
            let crate::study::runner::Task::Run(p) = t else {
                continue;
            };
            formats += usize::from(p.texture_format.is_some());
            let cfg = r.config(&p).unwrap();
            let key = (
                toml::to_string(&cfg).unwrap(),
                p.draw_order,
                p.texture_format,
            );
            assert!(swept.contains(&key), "{} is in no sweep file", p.describe());
        }
        // rgba8, etc2 with decompressed texels and astc-8x8 (etc2 is the
        // shipped point), six variants.
        assert_eq!(formats, 3 * 6, "the texture-format points are checked");
    }
}
