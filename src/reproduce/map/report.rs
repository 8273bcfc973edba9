//! The "What decides WaSP's gain" section of REPORT.md and its data files
//! (`data/map.csv`, `data/map.json`): the knobs and their ranges, WaSP's
//! range per knob, the per-group tables, the 2-D grid, the warp-slot
//! question and the conclusion. Every sentence is built from the numbers
//! of the run.

use super::conclusion;
use super::data::{Metrics, GROUPS};
use super::figures;
use super::knobs::Variant;
use super::plan::{MapPlan, DEEP_QUEUE};
use super::table::{movement, MapTable, Row};
use crate::reproduce::plan::{Group, Plan};
use crate::study::cache::write_atomic;
use crate::study::runner::Outcome;
use std::fmt::Write as _;
use std::path::Path;
use wasp_sim::stats::csv_text;

/// Percent with one decimal, or `-`.
pub(super) fn pct(v: Option<f64>) -> String {
    crate::reproduce::prose::pct(v)
}

/// A share as a whole percent without sign, or `-`.
pub(super) fn share(v: Option<f64>) -> String {
    crate::reproduce::prose::whole_share(v)
}

fn num(v: Option<f64>) -> String {
    v.map_or("-".into(), |x| format!("{x:.0}"))
}

/// The columns of a group table: heading and the value of a row.
type Column = (&'static str, fn(&Metrics) -> String);

const COLUMNS: [Column; 9] = [
    ("baseline cycles vs shipped", |m| pct(m.baseline_cycles)),
    ("WaSP", |m| pct(m.wasp)),
    ("Fullpriority", |m| pct(m.fullpriority)),
    ("raster prefetch", |m| pct(m.raster)),
    ("oracle bound", |m| pct(m.oracle)),
    ("ideal memory", |m| pct(m.ideal)),
    ("gate closed", |m| share(m.gate_closed)),
    ("lead", |m| num(m.lead)),
    ("drain", |m| share(m.drain)),
];

/// Where the section's inputs and outputs are.
pub struct Section<'a> {
    /// The reproduction's plan (its sensitivity points feed the area
    /// figure).
    pub plan: &'a Plan,
    /// The map's plan.
    pub map: &'a MapPlan,
    /// The run's results.
    pub out: &'a Outcome,
    /// The map's numbers.
    pub table: &'a MapTable,
    /// The groups with scenes.
    pub groups: &'a [Group],
    /// `data/`.
    pub data: &'a Path,
    /// `figures/`.
    pub figs: &'a Path,
}

fn embed(md: &mut String, d: Option<figures::Drawn>) {
    if let Some(d) = d {
        let _ = writeln!(md, "![{}](figures/{}.png)\n", d.title, d.id);
    }
}

/// The section, appended to `md`, with its figures and data files.
pub fn write(md: &mut String, x: &Section) -> Result<(), String> {
    let (map, t, groups) = (x.map, x.table, x.groups);
    write_atomic(&x.data.join("map.csv"), &to_csv(t))?;
    let json = serde_json::to_string_pretty(t).map_err(|e| e.to_string())? + "\n";
    write_atomic(&x.data.join("map.json"), &json)?;
    let _ = writeln!(md, "\n## What decides WaSP's gain\n");
    intro(md, map, t);
    scenes_note(md, x.plan, map);
    knobs_table(md, map);
    ranking(md, t, groups);
    md.push_str(&super::edges::map_note(t, groups));
    embed(md, figures::tornado(t, x.figs, x.data)?);
    for &g in groups {
        group_table(md, t, g);
    }
    let _ = writeln!(md, "### WaSP and the oracle bound against warps per core\n");
    embed(md, figures::warps(t, x.figs, x.data)?);
    grid(md, map, t, groups);
    for d in figures::grid(map, t, groups, x.figs)? {
        embed(md, Some(d));
    }
    conclusion::warp_slots(md, t, groups);
    let _ = writeln!(
        md,
        "### Area and performance\n\nCycles against the register file of one core (warps x \
         4 threads x `core.registers_per_thread` 32-bit registers, as `wasp cost` sizes it) \
         for the baseline and WaSP at every warp count of the sensitivity study (input queue \
         as deep as the warp slots); the paper's highlighted pairs are ringed. Data: \
         `data/map-area.csv`.\n"
    );
    embed(md, figures::area(x.plan, x.out, x.figs, x.data)?);
    conclusion::claims(md, t, groups);
    super::textures::compressed(md, t, groups);
    Ok(())
}

fn intro(md: &mut String, map: &MapPlan, t: &MapTable) {
    let values: usize = t.knobs.iter().map(|k| k.rows.len().saturating_sub(1)).sum();
    let varied = t.knobs.iter().filter(|k| k.rows.len() > 1).count();
    let _ = writeln!(
        md,
        "The paper leaves many of its machine's choices unstated. This section varies {} of \
         them one at a time, each over a range a mobile GPU could have (docs/machine.md gives \
         each range and its source): {} values in all besides the shipped machine's, on the \
         paper's shared-tile machine. At every value it runs the scanline baseline, WaSP ({}), \
         Fullpriority, the baseline with a raster texture prefetcher, the baseline with the \
         oracle tile prefetcher (every block of a tile requested when the tile opens: the \
         bound of any \"launch early to prefetch\" scheme) and the baseline with ideal memory \
         (zero-latency main memory; the L1 and L2 keep their latencies).{}\n",
        varied,
        values,
        map.wasp,
        if map.quick {
            format!(
                " **Quick look**: the {varied} knobs below of the {} the full study varies, \
                 fewer values, one scene per game.",
                t.knobs.len()
            )
        } else {
            String::new()
        }
    );
    let _ = writeln!(
        md,
        "Speedups are over the baseline of the same machine; \"baseline cycles vs shipped\" \
         is that baseline against the shipped machine's (positive is slower). \"Gate closed\" \
         is the share of WaSP's launches with both FIFOs waiting in which it kept the \
         priority warp back; \"lead\" how many positions WaSP's priority warps launch ahead \
         of their raster order; \"drain\" the baseline's share of a tile spent draining. \
         `data/map.csv` and `data/map.json` hold every number.\n"
    );
}

fn knobs_table(md: &mut String, map: &MapPlan) {
    let _ = writeln!(md, "| knob | field | values | shipped |\n|---|---|---|---|");
    // Only the knobs this run varies (a quick look holds some at their
    // shipped value).
    let varied = map
        .knobs
        .iter()
        .filter(|k| k.values_for(map.quick).iter().any(|v| *v != k.shipped));
    for k in varied {
        let _ = writeln!(
            md,
            "| {} | `{}` | {} | {} |",
            k.label,
            k.field,
            k.values_for(map.quick).join(", "),
            k.shipped
        );
    }
    let _ = writeln!(md);
}

fn ranking(md: &mut String, t: &MapTable, groups: &[Group]) {
    let mut order: Vec<_> = t.knobs.iter().filter(|k| k.rows.len() > 1).collect();
    order.sort_by(|a, b| {
        movement(b)
            .total_cmp(&movement(a))
            .then(a.index.cmp(&b.index))
    });
    let _ = writeln!(
        md,
        "### WaSP's speedup range per knob\n\nEach knob's lowest and highest group-mean \
         speedup of WaSP over its values, the knobs ordered by how far they move it on the \
         games (the 3D range plus the 2D range).\n"
    );
    let mut head = "| knob |".to_string();
    let mut rule = "|---|".to_string();
    for g in groups {
        let _ = write!(head, " {} low | {} high |", g.label(), g.label());
        rule.push_str("---|---|");
    }
    let _ = writeln!(md, "{head}\n{rule}");
    for k in order {
        let _ = write!(md, "| {} |", k.label);
        for g in groups {
            let i = GROUPS.iter().position(|x| x == g).unwrap_or(0);
            match &k.wasp_range[i] {
                Some(r) => {
                    let _ = write!(
                        md,
                        " {} ({}) | {} ({}) |",
                        pct(Some(r.low.1)),
                        r.low.0,
                        pct(Some(r.high.1)),
                        r.high.0
                    );
                }
                None => md.push_str(" - | - |"),
            }
        }
        let _ = writeln!(md);
    }
    let _ = writeln!(md);
}

fn group_table(md: &mut String, t: &MapTable, g: Group) {
    let any = t.machines().iter().any(|r| r.of(g).wasp.is_some());
    if !any {
        return;
    }
    let _ = writeln!(md, "### {} scenes\n", g.label());
    let mut head = "| machine |".to_string();
    let mut rule = "|---|".to_string();
    for (h, _) in COLUMNS {
        let _ = write!(head, " {h} |");
        rule.push_str("---|");
    }
    let _ = writeln!(md, "{head}\n{rule}");
    let line = |md: &mut String, label: &str, r: &Row| {
        let _ = write!(md, "| {label} |");
        for (_, f) in COLUMNS {
            let _ = write!(md, " {} |", f(r.of(g)));
        }
        let _ = writeln!(md);
    };
    line(md, "**shipped**", &t.shipped);
    for k in &t.knobs {
        for r in k.rows.iter().filter(|r| !r.shipped) {
            line(md, &r.label, r);
        }
    }
    for r in &t.deep_queue {
        line(md, &r.label, r);
    }
    let _ = writeln!(md);
}

fn grid(md: &mut String, map: &MapPlan, t: &MapTable, groups: &[Group]) {
    let Some((a, b, cells)) = &t.grid else {
        return;
    };
    let (ka, kb) = (&map.knobs[*a], &map.knobs[*b]);
    let _ = writeln!(
        md,
        "### The two knobs that move WaSP most: {} and {}\n\nEvery pair of their values \
         (the baseline and WaSP at each); WaSP's speedup per group.\n",
        ka.label, kb.label
    );
    for &g in groups {
        if !cells.iter().any(|r| r.of(g).wasp.is_some()) {
            continue;
        }
        let _ = writeln!(md, "{} scenes:\n", g.label());
        let ys = kb.values_for(map.quick);
        let _ = write!(md, "| {} \\ {} |", ka.label, kb.label);
        for y in ys {
            let _ = write!(md, " {y} |");
        }
        let _ = writeln!(md, "\n|---|{}", "---|".repeat(ys.len()));
        for x in ka.values_for(map.quick) {
            let _ = write!(md, "| {x} |");
            for y in ys {
                let v = cells
                    .iter()
                    .find(|r| r.value == format!("{x}, {y}"))
                    .and_then(|r| r.of(g).wasp);
                let _ = write!(md, " {} |", pct(v));
            }
            let _ = writeln!(md);
        }
        let _ = writeln!(md);
    }
}

/// Every row of the map as CSV: machine, group, then the numbers.
pub fn to_csv(t: &MapTable) -> String {
    let header = "knob,value,label,group,baseline_cycles_vs_shipped,wasp,fullpriority,raster,\
                  oracle,ideal,gate_closed,lead,drain,cf,blocks_per_tile";
    let mut rows: Vec<&Row> = vec![&t.shipped];
    for k in &t.knobs {
        rows.extend(&k.rows);
    }
    if let Some((_, _, cells)) = &t.grid {
        rows.extend(cells);
    }
    rows.extend(&t.deep_queue);
    let f = |v: Option<f64>| v.map_or(String::new(), |x| format!("{x}"));
    let records = rows.into_iter().flat_map(|r| {
        GROUPS.into_iter().map(move |g| {
            let m = r.of(g);
            let numbers = [
                m.baseline_cycles,
                m.wasp,
                m.fullpriority,
                m.raster,
                m.oracle,
                m.ideal,
                m.gate_closed,
                m.lead,
                m.drain,
                m.cf,
                m.blocks_per_tile,
            ];
            [
                r.knob.clone(),
                r.value.clone(),
                r.label.clone(),
                g.label().to_string(),
            ]
            .into_iter()
            .chain(numbers.into_iter().map(f))
            .collect::<Vec<String>>()
        })
    });
    let header: Vec<String> = header.split(',').map(String::from).collect();
    csv_text(std::iter::once(header).chain(records))
}

/// Which of the reproduction's scenes the map runs on, when not all.
fn scenes_note(md: &mut String, plan: &Plan, map: &MapPlan) {
    let kept = super::scene_names(plan, map);
    let eligible = super::eligible(plan);
    let left: Vec<&str> = eligible
        .iter()
        .map(|s| s.name.as_str())
        .filter(|n| !map.keeps(n))
        .collect();
    let engine: Vec<String> = plan
        .every
        .iter()
        .filter(|s| !eligible.iter().any(|e| e.name == s.name))
        .map(|s| format!("`{}`", s.name))
        .collect();
    if !engine.is_empty() {
        let _ = writeln!(
            md,
            "The map runs on the loader route: it leaves out the engine scenes ({}), so that \
             its scenes are the same whichever route the means count (`--routes`).\n",
            engine.join(", ")
        );
    }
    if left.is_empty() {
        return;
    }
    let _ = writeln!(
        md,
        "The map runs on {} of the reproduction's {} {}scenes. It leaves out {}, the 3D scenes \
         with the most cycles, which would double its time (`--map-scenes all` runs it on \
         every scene); every game keeps at least two scenes, and the paper's experiments \
         above run on all {}.\n",
        kept.len(),
        eligible.len(),
        if engine.is_empty() { "" } else { "loader " },
        left.iter()
            .map(|n| format!("`{n}`"))
            .collect::<Vec<_>>()
            .join(", "),
        plan.scenes.len()
    );
}

/// The plan in words, printed before the run: knobs, values, scenes and
/// simulations.
pub fn plan_text(map: &MapPlan, names: &[String], all: usize) -> String {
    let scenes = names.len();
    let values: usize = map
        .knobs
        .iter()
        .map(|k| k.values_for(map.quick).len() - 1)
        .sum();
    let varied = map
        .knobs
        .iter()
        .filter(|k| k.values_for(map.quick).len() > 1)
        .count();
    let deep = map.deep_queue_warps.len() * map.deep_queue_variants().len();
    let runs = scenes * ((values + 1) * Variant::ALL.len() + deep);
    format!(
        "the map \"What decides WaSP's gain\": {} knobs, {values} values besides the shipped \
         machine, {} warp counts with a {DEEP_QUEUE}-entry input queue, on {scenes} scenes{}: \
         up to {runs} simulations, then a 2-D grid over the two knobs that move WaSP most",
        varied,
        map.deep_queue_warps.len(),
        if scenes < all {
            format!(" of {all} (--map-scenes all for every scene)")
        } else {
            String::new()
        }
    )
}
