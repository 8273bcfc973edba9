//! The map's conclusions in words: why the baseline keeps gaining with
//! warp slots, and where on the map each of the paper's claims holds. Every
//! sentence is built from the run's numbers and states the comparison they
//! show, whichever way it goes.

use super::data::Metrics;
use super::table::{MapTable, Row};
use crate::reproduce::plan::Group;
use crate::reproduce::prose::{faster_or_slower, pct, whole_share as share};
use std::fmt::Write as _;

/// The paper's WaSP speedup over its best baseline (Section V-B).
const PAPER_WASP: f64 = 0.039;

/// A speedup from two cycle changes against one reference: how much faster
/// the machine at `to` is than the one at `from`, each given as
/// `cycles / reference - 1`.
fn faster(from: Option<f64>, to: Option<f64>) -> Option<f64> {
    Some((1.0 + from?) / (1.0 + to?) - 1.0)
}

fn row<'a>(t: &'a MapTable, knob: &str, value: &str) -> Option<&'a Row> {
    if let Some(r) = t
        .knobs
        .iter()
        .find(|k| k.id == knob)
        .and_then(|k| k.rows.iter().find(|r| r.value == value))
    {
        return Some(r);
    }
    None
}

fn deep<'a>(t: &'a MapTable, warps: &str) -> Option<&'a Row> {
    t.deep_queue.iter().find(|r| r.value == warps)
}

fn f1(v: Option<f64>) -> String {
    v.map_or("-".into(), |x| format!("{x:.1}"))
}

fn f2(v: Option<f64>) -> String {
    v.map_or("-".into(), |x| format!("{x:.2}"))
}

/// Whether contention grows with the warps, from the L0 primary misses per
/// warp and the DRAM row-conflict share at 64 warps and at the most
/// (each a pair: at 64, at the most).
fn contention(l0: (Option<f64>, Option<f64>), rows: (Option<f64>, Option<f64>)) -> &'static str {
    // A rise counts when it is more than 5% of the value at 64 warps.
    let rises = |(a, b): (Option<f64>, Option<f64>)| match (a, b) {
        (Some(a), Some(b)) => Some(b > a * 1.05 && b - a > 1e-9),
        _ => None,
    };
    match (rises(l0), rises(rows)) {
        (Some(true), Some(true)) => "Contention grows with the warps",
        (Some(true), _) => "Contention grows with the warps in the L0, not in DRAM",
        (_, Some(true)) => "Contention grows with the warps in DRAM, not in the L0",
        (Some(false), Some(false)) => "Contention does not grow with the warps",
        _ => "Contention is not measured",
    }
}

/// "Why the baseline keeps gaining past 64 warps": the warp knob beside the
/// deep-input-queue series, with the instruments that separate queue room
/// from latency hiding and the contention that grows with warps.
pub fn warp_slots(md: &mut String, t: &MapTable, groups: &[Group]) {
    let warps = t.knobs.iter().find(|k| k.id == "warps");
    let Some(warps) = warps else {
        return;
    };
    let Some(most) = warps.rows.last() else {
        return;
    };
    let Some(ship) = row(t, "warps", "64") else {
        return;
    };
    let (d64, dmost) = (deep(t, "64"), deep(t, &most.value));
    let _ = writeln!(
        md,
        "### Why the baseline keeps gaining with warp slots\n\nThe paper finds the \
         baseline's optimum at 64 warps at width 4 and a slowdown past it, from \"resource \
         contention if we fill the core more\". Here the input queue stays at 64 entries \
         while the warp slots vary; the same counts run again with a {}-entry queue, deep \
         enough that a full core queue never holds the single in-order rasterizer back.\n",
        super::plan::DEEP_QUEUE
    );
    for &g in groups {
        let m = |r: Option<&Row>| r.map(|r| *r.of(g));
        let (s, x, d0, dx) = (m(Some(ship)), m(Some(most)), m(d64), m(dmost));
        let get = |v: Option<Metrics>, f: fn(&Metrics) -> Option<f64>| v.and_then(|v| f(&v));
        let more = faster(get(s, |m| m.baseline_cycles), get(x, |m| m.baseline_cycles));
        let queue = faster(
            get(s, |m| m.baseline_cycles),
            get(d0, |m| m.baseline_cycles),
        );
        let deep_more = faster(
            get(d0, |m| m.baseline_cycles),
            get(dx, |m| m.baseline_cycles),
        );
        if more.is_none() {
            continue;
        }
        let reading = slot_reading(more, deep_more, &most.value);
        let l0 = (
            get(s, |m| m.l0_misses_per_warp),
            get(x, |m| m.l0_misses_per_warp),
        );
        let rows = (get(s, |m| m.row_conflicts), get(x, |m| m.row_conflicts));
        let _ = writeln!(
            md,
            "- **{}**: from 64 to {} warps the baseline runs {}; at 64 warps a {}-entry queue \
             alone makes it {}. A full core queue holds the rasterizer back in {} of the cycles \
             at 64 warps, {} at {} and {} with the deep queue at 64; the cores hold {} warps on \
             average at 64 and {} at {}. So {}. {}: L0 primary misses per warp {} at 64 and {} \
             at {}, DRAM row conflicts {} and {} of the requests.",
            g.label(),
            most.value,
            faster_or_slower(more),
            super::plan::DEEP_QUEUE,
            faster_or_slower(queue),
            share(get(s, |m| m.backpressure)),
            share(get(x, |m| m.backpressure)),
            most.value,
            share(get(d0, |m| m.backpressure)),
            f1(get(s, |m| m.occupancy)),
            f1(get(x, |m| m.occupancy)),
            most.value,
            reading,
            contention(l0, rows),
            f2(l0.0),
            f2(l0.1),
            most.value,
            share(rows.0),
            share(rows.1),
        );
    }
    lower_levels(md, ship, most, groups);
}

/// What the extra warp slots buy, from the baseline's speedup from 64
/// warps to the most (`more`) and the same with the deep queue
/// (`deep_more`).
fn slot_reading(more: Option<f64>, deep_more: Option<f64>, most: &str) -> String {
    match (more, deep_more) {
        (Some(a), Some(b)) if a > 0.005 && b < 0.5 * a => format!(
            "most of what the extra slots buy is room for quads behind the in-order \
             rasterizer: with the deep queue they add {} instead of {}",
            pct(Some(b)),
            pct(Some(a))
        ),
        (Some(a), Some(b)) if a > 0.005 => format!(
            "the extra slots mostly hide latency: they still add {} with the deep queue \
             ({} without it)",
            pct(Some(b)),
            pct(Some(a))
        ),
        (Some(a), _) if a <= 0.005 => format!(
            "the extra slots do not pay ({} from 64 to {most} warps)",
            pct(Some(a))
        ),
        _ => "the deep-queue runs are missing".to_string(),
    }
}

/// How the L1's and L2's misses per warp move from 64 warps to the most,
/// and what that says of the cache thrashing Rogers et al. describe.
fn lower_levels(md: &mut String, ship: &Row, most: &Row, groups: &[Group]) {
    // (group, level, at 64, at the most, relative change)
    let mut moves = Vec::new();
    for &g in groups {
        let (a, b) = (
            ship.of(g).lower_misses_per_warp,
            most.of(g).lower_misses_per_warp,
        );
        for (level, x, y) in [("L1", a.0, b.0), ("L2", a.1, b.1)] {
            if let (Some(x), Some(y)) = (x, y) {
                if x > 0.0 {
                    moves.push((g, level, x, y, y / x - 1.0));
                }
            }
        }
    }
    let Some(largest) = moves.iter().max_by(|p, q| p.4.total_cmp(&q.4)) else {
        return;
    };
    let listed: Vec<String> = moves
        .iter()
        .map(|(g, level, x, y, _)| format!("{} {level} {x:.2} and {y:.2}", g.label()))
        .collect();
    let rogers = "the cache thrashing that Rogers et al. (\"Cache-Conscious Wavefront \
                  Scheduling\", MICRO 2012) find in GPGPU L1 data caches";
    let reading = if largest.4 <= 0.05 {
        format!(
            "They rise by at most {} ({} {}), so {rogers} does not show in them here; it \
             shows in the L0, where the bullets above measure it",
            pct(Some(largest.4.max(0.0))),
            largest.0.label(),
            largest.1
        )
    } else {
        format!(
            "The largest rise is {} ({} {}): {rogers} acts on that level here too, and the \
             extra warps gain in spite of it",
            pct(Some(largest.4)),
            largest.0.label(),
            largest.1
        )
    };
    let _ = writeln!(
        md,
        "\nMisses per warp below the L0 at 64 and {} warps: {}. {}. wasp models no \
         register-file or operand-collector limit that grows with the warp count: no source \
         found says the paper's class of machine has one, so none is added.\n",
        most.value,
        listed.join("; "),
        reading
    );
}

/// Where on the map each of the paper's claims holds.
pub fn claims(md: &mut String, t: &MapTable, groups: &[Group]) {
    let _ = writeln!(md, "### Where the paper's claims hold\n");
    let machines = t.machines();
    let games: Vec<Group> = groups
        .iter()
        .copied()
        .filter(|&g| g != Group::Procedural)
        .collect();
    for &g in &games {
        wasp_claim(md, &machines, g);
    }
    for &g in &games {
        fullpriority_claim(md, &machines, g);
    }
    for &g in &games {
        fewer_warps_claim(md, t, g);
    }
    for &g in &games {
        bound_claim(md, t, &machines, g);
    }
    let _ = writeln!(md);
}

/// Up to three labels, then "and N more".
fn some(v: &[&str]) -> String {
    match v.len() {
        0 => "none".into(),
        1..=3 => v.join(", "),
        n => format!("{} and {} more", v[..3].join(", "), n - 3),
    }
}

fn wasp_claim(md: &mut String, machines: &[&Row], g: Group) {
    let vals: Vec<(&str, f64)> = machines
        .iter()
        .filter_map(|r| Some((r.label.as_str(), r.of(g).wasp?)))
        .collect();
    let Some(lo) = vals.iter().min_by(|a, b| a.1.total_cmp(&b.1)) else {
        return;
    };
    let hi = vals.iter().max_by(|a, b| a.1.total_cmp(&b.1)).unwrap_or(lo);
    let reach: Vec<&str> = vals
        .iter()
        .filter(|v| v.1 >= PAPER_WASP)
        .map(|v| v.0)
        .collect();
    let gains = vals.iter().filter(|v| v.1 > 0.0).count();
    let _ = writeln!(
        md,
        "- **WaSP +3.9%, {} scenes**: over the {} machines of the map where WaSP ran, its mean speedup \
         runs from {} ({}) to {} ({}); it gains at {} of them and reaches the paper's +3.9% \
         at {}: {}.",
        g.label(),
        vals.len(),
        pct(Some(lo.1)),
        lo.0,
        pct(Some(hi.1)),
        hi.0,
        gains,
        reach.len(),
        some(&reach)
    );
}

fn fullpriority_claim(md: &mut String, machines: &[&Row], g: Group) {
    let pairs: Vec<(&str, f64, f64)> = machines
        .iter()
        .filter_map(|r| Some((r.label.as_str(), r.of(g).wasp?, r.of(g).fullpriority?)))
        .collect();
    if pairs.is_empty() {
        return;
    }
    let fails: Vec<&str> = pairs.iter().filter(|p| p.1 < p.2).map(|p| p.0).collect();
    let _ = writeln!(
        md,
        "- **WaSP above Fullpriority, {} scenes**: WaSP is at least as fast as Fullpriority \
         at {} of the {} machines where both ran; below it at {}.",
        g.label(),
        pairs.len() - fails.len(),
        pairs.len(),
        some(&fails)
    );
}

fn fewer_warps_claim(md: &mut String, t: &MapTable, g: Group) {
    // WaSP@k against the baseline@k' on the warp knob: both rows' cycles
    // are against the shipped baseline, WaSP's through its speedup.
    let Some(warps) = t.knobs.iter().find(|k| k.id == "warps") else {
        return;
    };
    let wasp_cycles = |r: &Row| {
        let m = r.of(g);
        Some((1.0 + m.baseline_cycles?) / (1.0 + m.wasp?) - 1.0)
    };
    let mut text = Vec::new();
    for (k, k2) in [("48", "64"), ("32", "48"), ("32", "64")] {
        let (Some(a), Some(b)) = (
            warps.rows.iter().find(|r| r.value == k),
            warps.rows.iter().find(|r| r.value == k2),
        ) else {
            continue;
        };
        let v = faster(b.of(g).baseline_cycles, wasp_cycles(a));
        if let Some(v) = v {
            let verdict = if v >= 0.0 {
                "at least as fast"
            } else {
                "slower"
            };
            text.push(format!(
                "WaSP@{k} is {} against the baseline@{k2} ({verdict})",
                pct(Some(v))
            ));
        }
    }
    if text.is_empty() {
        return;
    }
    let _ = writeln!(
        md,
        "- **WaSP with fewer warps as fast as the baseline with more, {} scenes** (input \
         queue 64): {}.",
        g.label(),
        text.join("; ")
    );
}

fn bound_claim(md: &mut String, t: &MapTable, machines: &[&Row], g: Group) {
    let s = t.shipped.of(g);
    let (Some(w), Some(o)) = (s.wasp, s.oracle) else {
        return;
    };
    let of_oracle = if o <= 0.0 {
        "nothing: the oracle gains nothing either".into()
    } else if w <= 0.0 {
        "none of the oracle's gain".into()
    } else {
        format!("{:.0}% of the oracle's gain", 100.0 * w / o)
    };
    let below: Vec<&str> = machines
        .iter()
        .filter(|r| matches!((r.of(g).wasp, r.of(g).oracle), (Some(w), Some(o)) if o < w))
        .map(|r| r.label.as_str())
        .collect();
    let raster = match s.raster {
        Some(r) if r > w => format!("the raster prefetcher's is larger ({})", pct(Some(r))),
        Some(r) => format!("the raster prefetcher's is {} (not larger)", pct(Some(r))),
        None => "the raster prefetcher did not run".into(),
    };
    let why = below
        .iter()
        .filter_map(|l| machines.iter().find(|r| r.label == *l))
        .max_by(|a, b| {
            let gap = |r: &&&Row| r.of(g).wasp.unwrap_or(0.0) - r.of(g).oracle.unwrap_or(0.0);
            gap(a).total_cmp(&gap(b))
        })
        .map(|r| {
            let m = r.of(g);
            format!(
                " At {}, where the gap is widest, the oracle's queue waits for free L1 MSHRs in \
                 {} of the core-cycles, {} of its prefetches arrive late, {} are evicted unused, \
                 and a DRAM request waits {} cycles in the queue against {} under WaSP.",
                r.label,
                share(m.oracle_reserve_wait),
                share(m.oracle_late),
                share(m.oracle_useless),
                f1(m.dram_wait.0),
                f1(m.dram_wait.1)
            )
        })
        .unwrap_or_default();
    let ideal_note = oracle_above_ideal(machines, g);
    // Counted over the machines where both ran, and said so.
    let both = machines
        .iter()
        .filter(|r| r.of(g).wasp.is_some() && r.of(g).oracle.is_some())
        .count();
    let _ = writeln!(
        md,
        "- **WaSP against the bounds, {} scenes**: on the shipped machine WaSP's speedup is {}, \
         the oracle tile prefetcher's {} and ideal memory's {}: WaSP takes {}; {}. The oracle is \
         slower than WaSP at {} of the {} machines where both ran{}.{why}{ideal_note}",
        g.label(),
        pct(Some(w)),
        pct(Some(o)),
        pct(s.ideal),
        of_oracle,
        raster,
        below.len(),
        both,
        if below.is_empty() {
            String::new()
        } else {
            format!(": {}", some(&below))
        }
    );
}

/// Where the oracle beats ideal memory, and why it can.
fn oracle_above_ideal(machines: &[&Row], g: Group) -> String {
    let above: Vec<&str> = machines
        .iter()
        .filter(|r| matches!((r.of(g).oracle, r.of(g).ideal), (Some(o), Some(i)) if o > i))
        .map(|r| r.label.as_str())
        .collect();
    if above.is_empty() {
        return String::new();
    }
    let both = machines
        .iter()
        .filter(|r| r.of(g).oracle.is_some() && r.of(g).ideal.is_some())
        .count();
    format!(
        " The oracle is faster than ideal memory at {} of the {} machines where both ran ({}): \
         ideal memory removes the main memory's latency only, while the oracle's blocks wait \
         in the L1, which also hides the L2's.",
        above.len(),
        both,
        some(&above)
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reproduce::map::data::GROUPS;
    use crate::reproduce::map::table::KnobResult;

    fn row(knob: &str, value: &str, base: f64, wasp: f64, fp: f64, oracle: f64) -> Row {
        let m = Metrics {
            baseline_cycles: Some(base),
            wasp: Some(wasp),
            fullpriority: Some(fp),
            oracle: Some(oracle),
            raster: Some(0.0),
            ideal: Some(0.1),
            ..Metrics::default()
        };
        Row {
            knob: knob.into(),
            value: value.into(),
            label: format!("{value} {knob}"),
            shipped: value == "64",
            repeats: false,
            groups: [m, m, Metrics::default()],
        }
    }

    fn table(rows: Vec<Row>, deep: Vec<Row>) -> MapTable {
        MapTable {
            shipped: rows.iter().find(|r| r.shipped).cloned().unwrap(),
            knobs: vec![KnobResult {
                index: 0,
                id: "warps".into(),
                label: "warps per core".into(),
                wasp_range: GROUPS.map(|_| None),
                rows,
            }],
            grid: None,
            deep_queue: deep,
        }
    }

    /// More warps that slow the baseline down and add no contention: the
    /// sentences say so, with no "faster" and no growing contention.
    #[test]
    fn the_warp_slots_follow_the_data() {
        let mut few = row("warps", "64", 0.0, 0.0, 0.0, 0.0);
        let mut many = row("warps", "128", 0.10, 0.0, 0.0, 0.0);
        for (r, rows) in [(&mut few, 0.20), (&mut many, 0.10)] {
            for m in &mut r.groups[..2] {
                m.l0_misses_per_warp = Some(1.0);
                m.row_conflicts = Some(rows);
            }
        }
        let t = table(vec![few, many], Vec::new());
        let mut md = String::new();
        warp_slots(&mut md, &t, &[Group::ThreeD]);
        assert!(
            md.contains("from 64 to 128 warps the baseline runs 9.1% slower"),
            "{md}"
        );
        assert!(md.contains("the extra slots do not pay (-9.1%"), "{md}");
        assert!(
            md.contains("Contention does not grow with the warps: L0 primary misses per warp"),
            "{md}"
        );
        assert!(
            !md.contains("% faster") && !md.contains("Contention grows"),
            "{md}"
        );
    }

    #[test]
    fn the_prose_follows_data_that_contradict_the_paper() {
        // WaSP slower than the baseline everywhere, below Fullpriority, and
        // WaSP@48 slower than the baseline@64; the oracle below WaSP at 32.
        let t = table(
            vec![
                row("warps", "32", 0.10, 0.02, 0.03, 0.01),
                row("warps", "48", 0.05, -0.01, 0.0, 0.02),
                row("warps", "64", 0.0, -0.02, 0.01, 0.03),
            ],
            Vec::new(),
        );
        let mut md = String::new();
        claims(&mut md, &t, &[Group::ThreeD]);
        assert!(md.contains("reaches the paper's +3.9% at 0: none"), "{md}");
        assert!(md.contains("it gains at 1 of them"), "{md}");
        assert!(
            md.contains("at least as fast as Fullpriority at 0 of the 3 machines where both ran"),
            "{md}"
        );
        // 1.0 / (1.05 / 0.99) - 1 = -5.7%: slower.
        assert!(
            md.contains("WaSP@48 is -5.7% against the baseline@64 (slower)"),
            "{md}"
        );
        assert!(
            md.contains("slower than WaSP at 1 of the 3 machines where both ran: 32 warps"),
            "{md}"
        );
        assert!(!md.contains("faster than ideal memory"), "{md}");
        // And data that agree read the other way.
        let t = table(
            vec![
                row("warps", "48", 0.01, 0.05, 0.01, 0.08),
                row("warps", "64", 0.0, 0.04, 0.01, 0.08),
            ],
            Vec::new(),
        );
        let mut md = String::new();
        claims(&mut md, &t, &[Group::ThreeD]);
        assert!(md.contains("reaches the paper's +3.9% at 2"), "{md}");
        assert!(md.contains("WaSP@48 is +4.0% against the baseline@64 (at least as fast)"));
        assert!(md.contains("WaSP takes 50% of the oracle's gain"), "{md}");
        // An oracle above ideal memory (ideal +10% in `row`) is explained.
        let t = table(vec![row("warps", "64", 0.0, 0.04, 0.01, 0.12)], Vec::new());
        let mut md = String::new();
        claims(&mut md, &t, &[Group::ThreeD]);
        assert!(
            md.contains(
                "The oracle is faster than ideal memory at 1 of the 1 machines where both ran"
            ),
            "{md}"
        );
    }

    #[test]
    fn the_warp_slot_reading_follows_the_deep_queue_runs() {
        let base = |v: &str, c: f64, bp: f64| {
            let mut r = row("warps", v, c, 0.0, 0.0, 0.0);
            for m in r.groups.iter_mut() {
                m.backpressure = Some(bp);
            }
            r
        };
        let rows = vec![base("64", 0.0, 0.4), base("128", -0.06, 0.3)];
        // With the deep queue 128 warps add 0.5%: queue room.
        let deep = vec![
            row("deep-queue", "64", -0.10, 0.0, 0.0, 0.0),
            row("deep-queue", "128", -0.105, 0.0, 0.0, 0.0),
        ];
        let mut md = String::new();
        warp_slots(&mut md, &table(rows.clone(), deep), &[Group::ThreeD]);
        assert!(
            md.contains("most of what the extra slots buy is room"),
            "{md}"
        );
        // With the deep queue 128 warps still add 5%: latency hiding.
        let deep = vec![
            row("deep-queue", "64", -0.10, 0.0, 0.0, 0.0),
            row("deep-queue", "128", -0.145, 0.0, 0.0, 0.0),
        ];
        let mut md = String::new();
        warp_slots(&mut md, &table(rows, deep), &[Group::ThreeD]);
        assert!(md.contains("the extra slots mostly hide latency"), "{md}");
    }

    /// The L1/L2 sentence follows their misses: flat misses say the
    /// thrashing does not show there; a rise names the level and its size.
    #[test]
    fn the_lower_levels_follow_their_misses() {
        let with = |v: &str, l1: f64| {
            let mut r = row("warps", v, 0.0, 0.0, 0.0, 0.0);
            r.groups[0].lower_misses_per_warp = (Some(l1), Some(0.5));
            r
        };
        let groups = [Group::ThreeD];
        let mut md = String::new();
        lower_levels(&mut md, &with("64", 1.0), &with("128", 1.01), &groups);
        assert!(
            md.contains("3D L1 1.00 and 1.01; 3D L2 0.50 and 0.50"),
            "{md}"
        );
        assert!(md.contains("rise by at most +1.0% (3D L1)"), "{md}");
        assert!(md.contains("does not show in them"), "{md}");
        let mut md = String::new();
        lower_levels(&mut md, &with("64", 1.0), &with("128", 1.5), &groups);
        assert!(md.contains("The largest rise is +50.0% (3D L1)"), "{md}");
        assert!(md.contains("acts on that level here too"), "{md}");
    }
}
