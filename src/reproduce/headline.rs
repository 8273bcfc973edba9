//! REPORT.md's side-by-side table: each of the paper's headline numbers
//! beside ours, per machine and scene group, also written as
//! `data/headline.csv`.

use super::figures::{Figure, Figures};
use super::paper;
use super::plan::{Group, Plan, Width};
use super::prose::pct;
use super::rgba8;
use crate::study::runner::Outcome;
use std::fmt::Write as _;
use wasp_rtl::policy::PolicySpec;
use wasp_sim::config::Dispatch;
use wasp_sim::stats::csv_text;

/// One row of the side-by-side table.
pub struct Row {
    /// What is compared.
    pub claim: String,
    /// The paper's value as text.
    pub paper: String,
    /// Ours per machine: (games, 3D, 2D, procedural).
    pub ours: Vec<[String; 4]>,
}

pub use super::figures::group_values;

/// The group means of a figure's series as text: changes with their sign,
/// shares without, other numbers with two decimals.
pub fn group_means(f: &Figure, series: usize) -> [String; 4] {
    group_values(f, series).map(|v| {
        if f.percent && f.signed {
            pct(v)
        } else if f.percent {
            super::prose::share(v)
        } else {
            v.map_or("-".into(), |x| format!("{x:.2}"))
        }
    })
}

/// The index of the series `name` (the first if there is none).
pub fn series_index(f: &Figure, name: &str) -> usize {
    f.series.iter().position(|s| s.name == name).unwrap_or(0)
}

/// The rows of the table.
pub fn headline(plan: &Plan, out: &Outcome, machines: &[(Dispatch, Figures)]) -> Vec<Row> {
    let textures = Textures::of(plan, out);
    let mut rows = Vec::new();
    policy_rows(&mut rows, plan, machines, &textures);
    for w in &plan.widths {
        sensitivity_rows(&mut rows, plan, machines, w);
    }
    workload_rows(&mut rows, plan, out, machines, &textures);
    rows
}

/// The run with every texture in RGBA8 ([`rgba8::view`]) and the labels
/// that tell its rows from those of the scenes' own textures (none when
/// the run has no RGBA8 measurements: the rows keep their plain names).
struct Textures {
    view: Outcome,
    own: String,
    rgba8: String,
}

impl Textures {
    fn of(plan: &Plan, out: &Outcome) -> Textures {
        let view = rgba8::view(plan, out);
        let compared = !view.scenes.is_empty() || !view.points.is_empty();
        let (own, rgba8) = if compared {
            let own = rgba8::own_format(plan, out);
            (rgba8::suffix(own.as_deref()), rgba8::rgba8_suffix())
        } else {
            (String::new(), String::new())
        };
        Textures { view, own, rgba8 }
    }
}

type PerMachine<'a> = &'a dyn Fn(Dispatch, &Figures) -> [String; 4];

fn row(claim: &str, paper: String, machines: &[(Dispatch, Figures)], f: PerMachine) -> Row {
    Row {
        claim: claim.into(),
        paper,
        ours: machines.iter().map(|(d, x)| f(*d, x)).collect(),
    }
}

/// The policies' speedups and what WaSP changes (latency, energy, misses),
/// and ideal memory (with the scenes' textures and with RGBA8's).
fn policy_rows(
    rows: &mut Vec<Row>,
    plan: &Plan,
    machines: &[(Dispatch, Figures)],
    textures: &Textures,
) {
    let p = |c: paper::Claim| pct(Some(c.value));
    heuristic_rows(rows, plan, machines);
    rows.push(row(
        "Memory latency change (WaSP)",
        p(paper::LATENCY_CHANGE),
        machines,
        &|d, x| group_means(&x.latency_change(d), 0),
    ));
    rows.push(row(
        "Priority warps' latency above regular warps'",
        "yes".into(),
        machines,
        &priority_latency_counts,
    ));
    rows.push(row(
        "Energy change (WaSP)",
        p(paper::ENERGY_CHANGE),
        machines,
        &|d, x| group_means(&x.energy(d), 0),
    ));
    for (claim, series) in [
        ("L1 misses change (WaSP)", 0),
        ("L2 misses change (WaSP)", 1),
    ] {
        rows.push(row(claim, "unchanged".into(), machines, &|d, x| {
            group_means(&x.misses(d), series)
        }));
    }
    let ideal_paper = "Figure 1 (no number)";
    rows.push(row(
        &format!("Ideal-memory speedup{}", textures.own),
        ideal_paper.into(),
        machines,
        &|d, x| group_means(&x.motivation(d), 0),
    ));
    if !textures.view.points.is_empty() {
        rows.push(row(
            &format!("Ideal-memory speedup{}", textures.rgba8),
            ideal_paper.into(),
            machines,
            &|d, _| {
                rgba8::ideal(plan, &textures.view, d).map_or_else(
                    || ["-".into(), "-".into(), "-".into(), "-".into()],
                    |f| group_means(&f, 0),
                )
            },
        ));
    }
}

/// The three heuristics' speedups, printed with as many decimals as keep
/// their order in each column ([`super::digits`]): +0.84% and +0.76% never
/// both print +0.8%.
fn heuristic_rows(rows: &mut Vec<Row>, plan: &Plan, machines: &[(Dispatch, Figures)]) {
    let p = |c: paper::Claim| pct(Some(c.value));
    let wasp = plan.wasp.to_string();
    let policies = [
        ("WaSP speedup", p(paper::WASP_SPEEDUP), wasp.as_str()),
        (
            "Fullpriority speedup",
            p(paper::FULLPRIORITY_SPEEDUP),
            "fullpriority",
        ),
        (
            "Freemshr10 speedup",
            "like Fullpriority".into(),
            "freemshr:10",
        ),
    ];
    // Per machine, per policy, the four columns.
    let texts: Vec<Vec<[String; 4]>> = machines
        .iter()
        .map(|(d, x)| {
            let f = x.heuristics(*d);
            let vals: Vec<[Option<f64>; 4]> = policies
                .iter()
                .map(|(_, _, name)| group_values(&f, series_index(&f, name)))
                .collect();
            let mut out = vec![<[String; 4]>::default(); policies.len()];
            for col in 0..4 {
                let column: Vec<Option<f64>> = vals.iter().map(|v| v[col]).collect();
                for (i, t) in super::digits::distinct_pcts(&column)
                    .into_iter()
                    .enumerate()
                {
                    out[i][col] = t;
                }
            }
            out
        })
        .collect();
    for (i, (claim, paper, _)) in policies.into_iter().enumerate() {
        rows.push(Row {
            claim: claim.into(),
            paper,
            ours: texts.iter().map(|m| m[i].clone()).collect(),
        });
    }
}

/// On how many scenes of each group the priority warps' mean latency is
/// above the regular warps'.
fn priority_latency_counts(d: Dispatch, x: &Figures) -> [String; 4] {
    let f = x.latency(d);
    let (pr, rg) = (&f.series[2].values, &f.series[3].values);
    let n = x.axis.scenes.len();
    let count = |idx: &dyn Fn(Group) -> bool| {
        let v: Vec<bool> = (0..n)
            .filter(|&i| idx(x.axis.groups[i]))
            .filter_map(|i| Some(pr[i]? > rg[i]?))
            .collect();
        if v.is_empty() {
            "-".to_string()
        } else {
            format!("{} of {}", v.iter().filter(|&&b| b).count(), v.len())
        }
    };
    [
        count(&|g| g != Group::Procedural),
        count(&|g| g == Group::ThreeD),
        count(&|g| g == Group::TwoD),
        count(&|g| g == Group::Procedural),
    ]
}

/// The paper's claim of WaSP with fewer warps against the baseline at the
/// paper's optimum, at a width: (WaSP's warps, the paper's value as text).
pub fn fewer_warps_claim(w: &Width) -> (u32, paper::Claim) {
    if w.width == 2 {
        (32, paper::WIDTH2_WASP32_OVER_BEST)
    } else {
        (48, paper::WIDTH4_WASP48_OVER_BEST)
    }
}

/// The sensitivity rows of one width: where the baseline is fastest, the
/// baseline past the optimum, WaSP with fewer warps and WaSP at the
/// optimum, each against the baseline at the paper's optimum.
fn sensitivity_rows(rows: &mut Vec<Row>, plan: &Plan, machines: &[(Dispatch, Figures)], w: &Width) {
    rows.push(row(
        &format!("Best baseline warp count, width {}", w.width),
        w.paper_best_warps.to_string(),
        machines,
        &|d, x| {
            let b = x.best_warps(d, w).map_or("-".into(), |b| b.short());
            [b, "-".into(), "-".into(), "-".into()]
        },
    ));
    let opt = w.paper_best_warps;
    if !plan.warps.contains(&opt) {
        return;
    }
    let sens = |k: u32, pol: PolicySpec| {
        move |d: Dispatch, x: &Figures| -> [String; 4] {
            let v = x.sensitivity_speedup(d, w, k, pol, opt);
            [pct(v), "-".into(), "-".into(), "-".into()]
        }
    };
    if let Some(&most) = plan.warps.iter().max().filter(|&&m| m > opt) {
        rows.push(row(
            &format!("Baseline@{most} over the baseline@{opt}, width {}", w.width),
            "< 0 (\"slow down after\" the optimum)".into(),
            machines,
            &sens(most, PolicySpec::Baseline),
        ));
    }
    let (k, claim) = fewer_warps_claim(w);
    let paper_text = if w.width == 2 {
        ">= 0 (matches)".to_string()
    } else {
        pct(Some(claim.value))
    };
    if plan.warps.contains(&k) {
        rows.push(row(
            &format!("WaSP@{k} over the baseline@{opt}, width {}", w.width),
            paper_text,
            machines,
            &sens(k, plan.wasp),
        ));
    }
    let gain = if w.width == 2 {
        paper::WIDTH2_WASP_GAIN
    } else {
        paper::WIDTH4_WASP_GAIN
    };
    rows.push(row(
        &format!("WaSP@{opt} over the baseline@{opt}, width {}", w.width),
        pct(Some(gain.value)),
        machines,
        &sens(opt, plan.wasp),
    ));
}

/// The workload figures: the same on every machine. The footprint ratios
/// and CF are given with the scenes' textures and, where the run measured
/// them, with RGBA8's, each right after the other.
fn workload_rows(
    rows: &mut Vec<Row>,
    plan: &Plan,
    out: &Outcome,
    machines: &[(Dispatch, Figures)],
    textures: &Textures,
) {
    let sf = super::figures::scene_figures(plan, out);
    let sf8 = (!textures.view.scenes.is_empty())
        .then(|| super::figures::scene_figures(plan, &textures.view));
    // The row of series `i` of figure `fig` of `sf`, and its RGBA8 twin.
    let both = |rows: &mut Vec<Row>, claim: &str, paper: String, fig: usize, i: usize| {
        let same = |suffix: &str, figs: &[Figure]| Row {
            claim: format!("{claim}{suffix}"),
            paper: paper.clone(),
            ours: machines
                .iter()
                .map(|_| group_means(&figs[fig], i))
                .collect(),
        };
        rows.push(same(&textures.own, &sf));
        if let Some(sf8) = &sf8 {
            rows.push(same(&textures.rgba8, sf8));
        }
    };
    for (i, s) in sf[2].series.iter().enumerate() {
        let pv = paper::footprint(&s.name).map_or("-".into(), |v| format!("{v}"));
        both(rows, &format!("Footprint ratio, {}", s.name), pv, 2, i);
    }
    if let Some(i) = sf[3]
        .series
        .iter()
        .position(|s| s.name.starts_with("Mesh2 "))
    {
        both(
            rows,
            "Footprint ratio, Mesh2 (size ratio 0.25)",
            format!("{}", paper::MESH2_FOOTPRINT.value),
            3,
            i,
        );
    }
    rows.push(Row {
        claim: "Min_Estimate1".into(),
        paper: format!("{}", paper::MIN_ESTIMATE1.value),
        ours: machines.iter().map(|_| group_means(&sf[0], 0)).collect(),
    });
    both(rows, "CF", format!("{}", paper::CF.value), 1, 0);
}

/// The table in REPORT.md.
pub fn headline_md(md: &mut String, rows: &[Row], plan: &Plan) {
    let _ = writeln!(md, "\n## The paper's headline numbers beside ours\n");
    let mut head = "| | paper |".to_string();
    let mut rule = "|---|---|".to_string();
    for d in &plan.dispatches {
        let _ = write!(head, " {d}: games | 3D | 2D | procedural |");
        rule.push_str("---|---|---|---|");
    }
    let _ = writeln!(md, "{head}\n{rule}");
    for r in rows {
        let _ = write!(md, "| {} | {} |", r.claim, r.paper);
        for o in &r.ours {
            let _ = write!(md, " {} | {} | {} | {} |", o[0], o[1], o[2], o[3]);
        }
        let _ = writeln!(md);
    }
    let _ = writeln!(
        md,
        "\nSpeedups and changes are per-scene `baseline / WaSP - 1` (cycles) or `WaSP / \
         baseline - 1`, averaged arithmetically; sensitivity rows are means over games. \
         `data/headline.csv` holds this table."
    );
    let rgba8 = rgba8::rgba8_suffix();
    if rows.iter().any(|r| r.claim.ends_with(&rgba8)) {
        let _ = writeln!(
            md,
            "\nRows ending `{}` store every texture of every scene as RGBA8, the layout before \
             compressed formats; the rows above each of them store the scenes' textures as \
             their definitions say (shipped scenes: the `etc2` rule of docs/textures.md). The \
             RGBA8 ideal-memory row is measured on the {} machine only.",
            rgba8.trim_start_matches(", "),
            rgba8::machine(plan).map_or("first".into(), |d| d.to_string())
        );
    }
}

/// The table as CSV.
pub fn headline_csv(rows: &[Row], plan: &Plan) -> String {
    let header = ["claim".to_string(), "paper".to_string()]
        .into_iter()
        .chain(
            plan.dispatches
                .iter()
                .flat_map(|d| ["games", "3D", "2D", "procedural"].map(|g| format!("{d} {g}"))),
        );
    let records = rows.iter().map(|r| {
        [r.claim.clone(), r.paper.clone()]
            .into_iter()
            .chain(r.ours.iter().flatten().cloned())
            .collect::<Vec<String>>()
    });
    csv_text(std::iter::once(header.collect::<Vec<String>>()).chain(records))
}
