//! REPORT.md, the data files and the plots of a reproduction.
//!
//! Under the output folder:
//!
//! - `REPORT.md`: the side-by-side table of the paper's headline numbers
//!   and ours (both machines), a sentence per difference saying what causes
//!   it, every figure embedded with its numbers;
//! - `figures/ID.png` and `figures/ID.svg`: each figure, plus the
//!   timelines (`timeline.SCENE.MACHINE.POLICY.png`);
//! - `data/ID.csv`: each figure's numbers (category, one column a series);
//!   `data/points.csv` and `data/points.json`: every point's statistics;
//!   `data/headline.csv`: the side-by-side table.
//!
//! The report holds results only (no wall times), so the same binary and
//! scenes give the same bytes.

use super::figures::{mean, pct_opt, scene_figures, Figure, Figures, Kind};
use super::paper;
use super::plan::{Group, Plan, Width};
use crate::study::cache::{write_atomic, PointRecord};
use crate::study::runner::Outcome;
use crate::study::table::{csv, points_csv};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use wasp_rtl::policy::PolicySpec;
use wasp_sim::config::Dispatch;

/// Write everything; returns the report's path.
pub fn write(
    plan: &Plan,
    out: &Outcome,
    cells: &[super::map::plan::Cell],
    dir: &Path,
    subset: bool,
) -> Result<PathBuf, String> {
    let data = dir.join("data");
    let figs = dir.join("figures");
    for d in [&data, &figs] {
        std::fs::create_dir_all(d).map_err(|e| format!("cannot create {}: {e}", d.display()))?;
    }
    let mut records: Vec<&PointRecord> = out.points.values().collect();
    records.sort_by(|a, b| (&a.point, &a.key).cmp(&(&b.point, &b.key)));
    write_atomic(&data.join("points.csv"), &points_csv(&records))?;
    let json = serde_json::to_string_pretty(&records).expect("records serialize") + "\n";
    write_atomic(&data.join("points.json"), &json)?;

    let mut md = String::new();
    header(&mut md, plan, subset);
    let machines: Vec<(Dispatch, Figures)> = plan
        .dispatches
        .iter()
        .map(|&d| (d, Figures::new(plan, out)))
        .collect();
    let rows = headline(plan, out, &machines);
    write_atomic(&data.join("headline.csv"), &headline_csv(&rows, plan))?;
    headline_md(&mut md, &rows, plan);
    why(&mut md, plan, out, &machines);

    let _ = writeln!(md, "\n## The workloads (Section III)\n");
    for f in scene_figures(plan, out) {
        figure(&mut md, &f, &data, &figs)?;
    }
    for (d, figs_of) in &machines {
        let _ = writeln!(
            md,
            "\n## {} machine (Section V)\n",
            if *d == Dispatch::SharedTile {
                "The paper's shared-tile"
            } else {
                "The per-core-tile"
            }
        );
        let _ = writeln!(md, "{}\n", machine_note(*d));
        let mut list = vec![figs_of.motivation(*d), figs_of.heuristics(*d)];
        for w in &plan.widths {
            if let Some(f) = figs_of.sensitivity(*d, w) {
                list.push(f);
            }
        }
        list.extend([
            figs_of.thresholds(*d),
            figs_of.l0_stall(*d),
            figs_of.misses(*d),
            figs_of.latency(*d),
            figs_of.latency_change(*d),
            figs_of.energy(*d),
            figs_of.mesh_speedup(*d),
            figs_of.early_z(*d),
            figs_of.lead(*d),
            figs_of.occupancy(*d),
        ]);
        for f in &list {
            figure(&mut md, f, &data, &figs)?;
        }
        timelines(&mut md, plan, *d);
    }
    if let (Some(map), Some(table)) = (&plan.map, super::map::table(plan, out, cells)) {
        let groups: Vec<Group> = [Group::ThreeD, Group::TwoD, Group::Procedural]
            .into_iter()
            .filter(|&g| plan.scenes.iter().any(|s| s.group == g))
            .collect();
        let section = super::map::report::Section {
            plan,
            map,
            out,
            table: &table,
            groups: &groups,
            data: &data,
            figs: &figs,
        };
        super::map::report::write(&mut md, &section)?;
    }
    footer(&mut md, plan);
    let path = dir.join("REPORT.md");
    write_atomic(&path, &md)?;
    Ok(path)
}

fn machine_note(d: Dispatch) -> &'static str {
    match d {
        Dispatch::SharedTile => {
            "One tile at a time for the whole GPU, one rasterizer with Early-Z feeding every \
             core, a barrier between tiles (the paper: \"tiles rendered one at a time\"). This \
             is the machine the paper simulates."
        }
        Dispatch::PerCoreTile => {
            "Each core renders a tile of its own with its own rasterizer; tiles run out of \
             phase, so the cores stay full. Not the paper's machine: it shows how much of the \
             result depends on the tile dispatch."
        }
    }
}

fn header(md: &mut String, plan: &Plan, subset: bool) {
    let _ = writeln!(md, "# WaSP reproduced\n");
    let _ = writeln!(
        md,
        "Generated by `wasp reproduce{}` (wasp {}) from the shipped configuration \
         (configs/paper.toml; configs/paper-width2.toml for width 2). Nothing is tuned per \
         scene: every scene runs the same machine.\n",
        if plan.quick { " --quick" } else { "" },
        env!("CARGO_PKG_VERSION")
    );
    if plan.quick {
        let _ = writeln!(
            md,
            "**Quick look**: one scene per game, fewer thresholds and warp counts, the \
             shared-tile machine only. Run `wasp reproduce` for the whole study.\n"
        );
    }
    if subset {
        let _ = writeln!(
            md,
            "**A subset of the scenes** (`--scenes`): the means are over these scenes only.\n"
        );
    }
    let mut by: Vec<(Group, Vec<&str>)> = Vec::new();
    for s in &plan.scenes {
        match by.iter_mut().find(|x| x.0 == s.group) {
            Some(x) => x.1.push(&s.name),
            None => by.push((s.group, vec![&s.name])),
        }
    }
    by.sort();
    let _ = writeln!(md, "Scenes ({}):\n", plan.scenes.len());
    for (g, names) in by {
        let _ = writeln!(
            md,
            "- {} ({}): {}",
            g.label(),
            names.len(),
            names.join(", ")
        );
    }
    let _ = writeln!(
        md,
        "\nThe paper measures twelve Android games on its TEAPOT simulator; ours are scenes of \
         open-source games rendered by wasp's front end (docs/scenes.md). \"games\" means below \
         are over the 3D and 2D scenes; procedural scenes are reported apart."
    );
}

/// One row of the side-by-side table.
pub struct Row {
    /// What is compared.
    pub claim: String,
    /// The paper's value as text.
    pub paper: String,
    /// Ours per machine: (games, 3D, 2D, procedural).
    pub ours: Vec<[String; 4]>,
}

fn group_means(f: &Figure, series: usize) -> [String; 4] {
    let at = |label: &str| {
        f.categories
            .iter()
            .position(|c| c == label)
            .and_then(|i| f.series.get(series).and_then(|s| s.values[i]))
    };
    let fmt = |v: Option<f64>| {
        if f.percent {
            pct_opt(v)
        } else {
            v.map_or("-".into(), |x| format!("{x:.2}"))
        }
    };
    [
        fmt(at("mean games")),
        fmt(at("mean 3D")),
        fmt(at("mean 2D")),
        fmt(at("mean procedural")),
    ]
}

fn series_index(f: &Figure, name: &str) -> usize {
    f.series.iter().position(|s| s.name == name).unwrap_or(0)
}

fn headline(plan: &Plan, out: &Outcome, machines: &[(Dispatch, Figures)]) -> Vec<Row> {
    let mut rows = Vec::new();
    let mut add = |claim: &str, paper: String, f: &dyn Fn(Dispatch, &Figures) -> [String; 4]| {
        rows.push(Row {
            claim: claim.into(),
            paper,
            ours: machines.iter().map(|(d, x)| f(*d, x)).collect(),
        });
    };
    let p = |c: paper::Claim| pct_opt(Some(c.value));
    let wasp = plan.wasp.to_string();
    add("WaSP speedup", p(paper::WASP_SPEEDUP), &|d, x| {
        let f = x.heuristics(d);
        group_means(&f, series_index(&f, &wasp))
    });
    add(
        "Fullpriority speedup",
        p(paper::FULLPRIORITY_SPEEDUP),
        &|d, x| {
            let f = x.heuristics(d);
            group_means(&f, series_index(&f, "fullpriority"))
        },
    );
    add("Freemshr10 speedup", "like Fullpriority".into(), &|d, x| {
        let f = x.heuristics(d);
        group_means(&f, series_index(&f, "freemshr:10"))
    });
    add(
        "Memory latency change (WaSP)",
        p(paper::LATENCY_CHANGE),
        &|d, x| group_means(&x.latency_change(d), 0),
    );
    add(
        "Priority warps' latency above regular warps'",
        "yes".into(),
        &|d, x| {
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
        },
    );
    add("Energy change (WaSP)", p(paper::ENERGY_CHANGE), &|d, x| {
        group_means(&x.energy(d), 0)
    });
    add("L1 misses change (WaSP)", "unchanged".into(), &|d, x| {
        group_means(&x.misses(d), 0)
    });
    add("L2 misses change (WaSP)", "unchanged".into(), &|d, x| {
        group_means(&x.misses(d), 1)
    });
    add(
        "Ideal-memory speedup",
        "Figure 1 (no number)".into(),
        &|d, x| group_means(&x.motivation(d), 0),
    );
    for w in &plan.widths {
        let w2 = w.clone();
        add(
            &format!("Best baseline warp count, width {}", w.width),
            w.paper_best_warps.to_string(),
            &move |d, x| {
                let b = x.best_warps(d, &w2).map_or("-".into(), |b| b.short());
                [b, "-".into(), "-".into(), "-".into()]
            },
        );
        let opt = w.paper_best_warps;
        let wasp_pol = plan.wasp;
        let sens = move |w: super::plan::Width, k: u32, pol: PolicySpec| {
            move |d: Dispatch, x: &Figures| -> [String; 4] {
                let v = x.sensitivity_speedup(d, &w, k, pol, opt);
                [pct_opt(v), "-".into(), "-".into(), "-".into()]
            }
        };
        if plan.warps.contains(&opt) {
            if let Some(&most) = plan.warps.iter().max().filter(|&&m| m > opt) {
                add(
                    &format!("Baseline@{most} over the baseline@{opt}, width {}", w.width),
                    "< 0 (\"slow down after\" the optimum)".into(),
                    &sens(w.clone(), most, PolicySpec::Baseline),
                );
            }
            let (k, paper_text) = if w.width == 2 {
                (32, ">= 0 (matches)".to_string())
            } else {
                (48, p(paper::WIDTH4_WASP48_OVER_BEST))
            };
            if plan.warps.contains(&k) {
                add(
                    &format!("WaSP@{k} over the baseline@{opt}, width {}", w.width),
                    paper_text,
                    &sens(w.clone(), k, wasp_pol),
                );
            }
            let gain = if w.width == 2 {
                paper::WIDTH2_WASP_GAIN
            } else {
                paper::WIDTH4_WASP_GAIN
            };
            add(
                &format!("WaSP@{opt} over the baseline@{opt}, width {}", w.width),
                p(gain),
                &sens(w.clone(), opt, wasp_pol),
            );
        }
    }
    // Workload figures: the same on both machines.
    let sf = scene_figures(plan, out);
    let fp = &sf[2];
    for (i, s) in fp.series.iter().enumerate() {
        let v = group_means(fp, i);
        let pv = paper::footprint(&s.name).map_or("-".into(), |v| format!("{v}"));
        rows.push(Row {
            claim: format!("Footprint ratio, {}", s.name),
            paper: pv,
            ours: machines.iter().map(|_| v.clone()).collect(),
        });
    }
    let mesh = &sf[3];
    if let Some(i) = mesh
        .series
        .iter()
        .position(|s| s.name.starts_with("Mesh2 "))
    {
        let v = group_means(mesh, i);
        rows.push(Row {
            claim: "Footprint ratio, Mesh2 (size ratio 0.25)".into(),
            paper: format!("{}", paper::MESH2_FOOTPRINT.value),
            ours: machines.iter().map(|_| v.clone()).collect(),
        });
    }
    for (fig, series, claim, c) in [
        (&sf[0], 0, "Min_Estimate1", paper::MIN_ESTIMATE1),
        (&sf[1], 0, "CF", paper::CF),
    ] {
        let v = group_means(fig, series);
        rows.push(Row {
            claim: claim.into(),
            paper: format!("{}", c.value),
            ours: machines.iter().map(|_| v.clone()).collect(),
        });
    }
    rows
}

fn headline_md(md: &mut String, rows: &[Row], plan: &Plan) {
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
}

fn headline_csv(rows: &[Row], plan: &Plan) -> String {
    let mut s = "claim,paper".to_string();
    for d in &plan.dispatches {
        for g in ["games", "3D", "2D", "procedural"] {
            let _ = write!(s, ",{d} {g}");
        }
    }
    s.push('\n');
    for r in rows {
        let _ = write!(s, "{},{}", csv(&r.claim), csv(&r.paper));
        for o in &r.ours {
            for v in o {
                let _ = write!(s, ",{}", csv(v));
            }
        }
        s.push('\n');
    }
    s
}

/// Mean of a statistic over the scenes of a group for one point kind.
fn group_stat(
    x: &Figures,
    group: Group,
    point: &dyn Fn(&str) -> crate::study::point::Point,
    f: &dyn Fn(&PointRecord) -> Option<f64>,
) -> Option<f64> {
    mean(
        x.axis
            .scenes
            .iter()
            .zip(&x.axis.groups)
            .filter(|(_, g)| **g == group)
            .filter_map(|(s, _)| x.out.get(&point(s)).and_then(f)),
    )
}

/// The rasterizer's share of cycles busy: the quads it produced (Early-Z
/// rejected ones included) over quads_per_cycle x cycles.
fn raster_busy(r: &PointRecord) -> Option<f64> {
    let q = r.get("raster.quads_rasterized")?;
    let qpc = f64::from(
        wasp_sim::config::MachineConfig::paper()
            .raster
            .quads_per_cycle,
    );
    Some(q / (qpc * r.cycles()))
}

fn why(md: &mut String, plan: &Plan, out: &Outcome, machines: &[(Dispatch, Figures)]) {
    let _ = writeln!(md, "\n## Why the numbers differ\n");
    let Some((d, x)) = machines.first() else {
        return;
    };
    let d = *d;
    let base = |s: &str| plan.policy_point(s, d, PolicySpec::Baseline);
    let wasp = |s: &str| plan.policy_point(s, d, plan.wasp);
    let f1 = |v: Option<f64>| v.map_or("-".into(), |x| format!("{x:.1}"));
    let pc = |v: Option<f64>| v.map_or("-".into(), |x| format!("{:.0}%", 100.0 * x));
    let heur = x.heuristics(d);
    let wi = series_index(&heur, &plan.wasp.to_string());
    let fi = series_index(&heur, "fullpriority");
    let m = group_means(&heur, wi);
    let fm = group_means(&heur, fi);
    let ideal = group_means(&x.motivation(d), 0);
    let ratio = |a: &'static str, b: &'static str| {
        move |r: &PointRecord| {
            let (x, y) = (r.get(a)?, r.get(b)?);
            (y > 0.0).then(|| x / y)
        }
    };
    let per_cycle = |a: &'static str| move |r: &PointRecord| Some(r.get(a)? / r.cycles());
    let _ = writeln!(
        md,
        "Measured on the first machine of the table ({d}); the instruments are means over the \
         group's scenes.\n"
    );
    let _ = writeln!(
        md,
        "- **WaSP speedup** ({} on games: {} 3D, {} 2D; paper +3.9%). The gain is bounded by \
         the headroom memory leaves: ideal memory gains {} on 3D and {} on 2D scenes.",
        m[0], m[1], m[2], ideal[1], ideal[2]
    );
    for g in [Group::ThreeD, Group::TwoD] {
        let stat =
            |p: &dyn Fn(&str) -> crate::study::point::Point,
             f: &dyn Fn(&PointRecord) -> Option<f64>| group_stat(x, g, p, f);
        let _ =
            writeln!(
            md,
            "  On {} scenes the baseline holds {} of 64 warps per core; the single rasterizer is \
             busy {} of the cycles, {} of its quads are rejected by Early-Z (they cost a raster \
             slot and launch no warp), and a full core queue holds it back in {} of the cycles; \
             WaSP's priority warps launch {} positions ahead of their raster order, its gate \
             keeps the waiting priority warp back in {} of the launches where both FIFOs wait; \
             the L0 is stalled {} of the time under the baseline and {} under WaSP.",
            g.label(),
            f1(stat(&base, &|r| r.get("occupancy.mean"))),
            pc(stat(&base, &raster_busy)),
            pc(stat(&base, &ratio("raster.quads_rejected", "raster.quads_rasterized"))),
            pc(stat(&base, &per_cycle("raster.backpressure_cycles"))),
            f1(stat(&wasp, &|r| r.get("priority_lead.mean"))),
            pc(stat(&wasp, &|r| r.get("gate.closed_share"))),
            pc(stat(&base, &|r| r.get("l0.stall_fraction"))),
            pc(stat(&wasp, &|r| r.get("l0.stall_fraction")))
        );
    }
    if let Some(&k) = plan.early_z.last() {
        let ez = x.early_z(d);
        let wk = group_means(&ez, ez.series.len() - 1);
        let fast = |s: &str| plan.early_z_point(s, d, k, PolicySpec::Baseline);
        let fast_wasp = |s: &str| plan.early_z_point(s, d, k, plan.wasp);
        let _ = writeln!(
            md,
            "  The rasterizer is tested rather than assumed to be the cause: with a coarse \
             Early-Z disposing of {k} rejected quads a slot, the 3D baseline runs {} faster and \
             holds {} warps per core, yet WaSP gains {} on 3D scenes ({} on 2D), and its \
             priority warps launch {} positions ahead of their raster order. The rate at which \
             Early-Z rejects quads is a wasp choice (`raster.rejected_per_slot`, \
             docs/machine.md); it moves the 3D scenes' speed, not WaSP's share of it.",
            pct_opt(x.early_z_gain(d, k, Group::ThreeD)),
            f1(group_stat(x, Group::ThreeD, &fast, &|r| r.get("occupancy.mean"))),
            wk[1],
            wk[2],
            f1(group_stat(x, Group::ThreeD, &fast_wasp, &|r| r
                .get("priority_lead.mean")))
        );
    }
    let _ = writeln!(
        md,
        "  The paper reports neither its rasterizer's rate nor its cores' occupancy, nor how \
         far its priority warps run ahead; its memory system's parameters (MSHR counts, \
         DRAMSim2 configuration) are not published in full either: ours are calibrated once \
         for the suite (docs/calibration.md)."
    );
    if let Some((od, ox)) = machines.get(1) {
        let h = ox.heuristics(*od);
        let om = group_means(&h, series_index(&h, &plan.wasp.to_string()));
        let _ = writeln!(
            md,
            "  On the {od} machine, whose cores stay fuller, WaSP gains {} on games ({} 3D, {} \
             2D): occupancy does not explain the 3D result either.",
            om[0], om[1], om[2]
        );
    }
    let games = |pol: PolicySpec| {
        let p = move |s: &str| plan.policy_point(s, d, pol);
        let v: Vec<f64> = [Group::ThreeD, Group::TwoD]
            .iter()
            .filter_map(|&g| group_stat(x, g, &p, &|r| r.get("l0.stall_fraction")))
            .collect();
        mean(v.into_iter())
    };
    let wins = {
        let f = &heur.series;
        (0..x.axis.scenes.len())
            .filter(|&i| x.axis.groups[i] != Group::Procedural)
            .filter_map(|i| Some(f[wi].values[i]? >= f[fi].values[i]?))
            .fold((0, 0), |(w, n), b| (w + usize::from(b), n + 1))
    };
    let _ = writeln!(
        md,
        "- **Fullpriority** ({} on games; paper +1.3%): the L0 is stalled {} of the time under \
         Fullpriority, {} under the baseline and {} under WaSP (mean of the 3D and 2D means); \
         the paper sees Fullpriority's stalls rise and WaSP avoid them. WaSP is at least as fast \
         as Fullpriority on {} of {} game scenes here.",
        fm[0],
        pc(games(PolicySpec::FullPriority)),
        pc(games(PolicySpec::Baseline)),
        pc(games(plan.wasp)),
        wins.0,
        wins.1
    );
    let lat = group_means(&x.latency_change(d), 0);
    let _ = writeln!(
        md,
        "- **Memory latency** ({} on games; paper -9%): the prefetching effect is there; how \
         much of it becomes speed depends on how much latency the warps could not already hide.",
        lat[0]
    );
    let en = group_means(&x.energy(d), 0);
    let part = |path: &'static str| {
        let v: Vec<f64> = x
            .axis
            .scenes
            .iter()
            .zip(&x.axis.groups)
            .filter(|(_, g)| **g != Group::Procedural)
            .filter_map(|(s, _)| {
                let (b, w) = (x.out.get(&base(s))?, x.out.get(&wasp(s))?);
                let get = |r: &PointRecord| match path {
                    "dynamic" => Some(r.get("energy.total_nj")? - r.get("energy.static_nj")?),
                    p => r.get(p),
                };
                Some(get(w)? / get(b)? - 1.0)
            })
            .collect();
        pct_opt(mean(v.into_iter()))
    };
    let _ = writeln!(
        md,
        "- **Energy** ({} on games; paper -0.5%): static energy follows the run time ({} on \
         games) and dynamic energy the accesses ({}); the paper's drop comes with its larger \
         speedup.",
        en[0],
        part("energy.static_nj"),
        part("dynamic")
    );
    let mi = x.misses(d);
    let (l1, l2) = (group_means(&mi, 0), group_means(&mi, 1));
    let _ = writeln!(
        md,
        "- **L1/L2 misses** ({} and {} on games; paper unchanged): as the paper argues, the \
         tile's working set fits the L1 and L2, so the order of warps changes when blocks \
         arrive, not how many.",
        l1[0], l2[0]
    );
    let sf = scene_figures(plan, out);
    let fp = &sf[2];
    let fpm: Vec<String> = (0..fp.series.len())
        .map(|i| format!("{} {}", fp.series[i].name, group_means(fp, i)[0]))
        .collect();
    let _ = writeln!(
        md,
        "- **Footprint ratios** (games: {}; paper 0.17/0.3/0.4/0.59/0.56): a property of the \
         workloads, not of the machine; they order the subsets as the paper does when our \
         scenes' texture reuse in a tile is in the paper's range (Table I in `wasp \
         characterize`).",
        fpm.join(", ")
    );
    let cf = group_means(&sf[1], 0);
    let _ = writeln!(
        md,
        "- **CF** ({} on games; paper 2.5): 3D scenes sample several mip levels and textures per \
         fragment, 2D sprites fewer; the shipped CF is the suite mean, once (docs/calibration.md).",
        cf[0]
    );
    for w in &plan.widths {
        sensitivity_note(md, plan, x, d, w);
    }
}

/// The sensitivity bullet of one width: where the baseline is fastest
/// (never an optimum at the edge of the range measured), WaSP at the
/// paper's optimum, and what the extra warp slots change in the
/// instruments (occupancy, raster back-pressure), from the baseline's
/// sensitivity points at the smallest and largest counts.
fn sensitivity_note(md: &mut String, plan: &Plan, x: &Figures, d: Dispatch, w: &Width) {
    let Some(best) = x.best_warps(d, w) else {
        return;
    };
    let opt = w.paper_best_warps;
    let paper_gain = if w.width == 2 { "about +2%" } else { "+4%" };
    let mut text = format!(
        "- **Sensitivity, width {}** (paper: optimum at {opt} warps): the baseline is {}",
        w.width,
        best.describe()
    );
    if plan.warps.contains(&opt) && best.warps != opt {
        let at_best = x.sensitivity_speedup(d, w, best.warps, PolicySpec::Baseline, opt);
        let _ = write!(
            text,
            "; at {} warps it is {} against {opt} warps",
            best.warps,
            pct_opt(at_best)
        );
    }
    text.push('.');
    let games = |k: u32, f: &dyn Fn(&PointRecord) -> Option<f64>| {
        let point = |s: &str| plan.sensitivity_point(s, d, w, k, PolicySpec::Baseline);
        let v: Vec<f64> = [Group::ThreeD, Group::TwoD]
            .iter()
            .filter_map(|&g| group_stat(x, g, &point, f))
            .collect();
        mean(v.into_iter())
    };
    let occupancy = |r: &PointRecord| r.get("occupancy.mean");
    let pressure = |r: &PointRecord| Some(r.get("raster.backpressure_cycles")? / r.cycles());
    let pc = |v: Option<f64>| v.map_or("-".into(), |x| format!("{:.0}%", 100.0 * x));
    let f1 = |v: Option<f64>| v.map_or("-".into(), |x| format!("{x:.1}"));
    if best.lowest < best.highest {
        let (lo, hi) = (best.lowest, best.highest);
        let (p_lo, p_hi) = (games(lo, &pressure), games(hi, &pressure));
        let reading = match (p_lo, p_hi) {
            (Some(a), Some(b)) if a - b >= 0.02 => {
                ": part of what the extra slots buy is room for quads that the in-order \
                 rasterizer could not otherwise hand out, not only latency hidden"
            }
            (Some(_), Some(_)) => {
                ": the rasterizer is held back about as often at both counts, so the extra \
                 slots act by hiding latency"
            }
            _ => "",
        };
        let _ = write!(
            text,
            " From {lo} to {hi} warps (input queue as deep as the warp slots) the baseline's \
             cores hold {} and {} warps on average, and a full core queue holds the single \
             rasterizer back in {} and {} of the cycles (mean of the 3D and 2D means){reading}.",
            f1(games(lo, &occupancy)),
            f1(games(hi, &occupancy)),
            pc(p_lo),
            pc(p_hi)
        );
    }
    if plan.warps.contains(&opt) {
        let wasp_opt = x.sensitivity_speedup(d, w, opt, plan.wasp, opt);
        let _ = write!(
            text,
            " WaSP at {opt} warps: {} (paper {paper_gain}).",
            pct_opt(wasp_opt)
        );
    }
    let _ = writeln!(md, "{text}");
}

fn figure(md: &mut String, f: &Figure, data: &Path, figs: &Path) -> Result<(), String> {
    write_atomic(&data.join(format!("{}.csv", f.id)), &figure_csv(f))?;
    super::draw::figure(f, figs)?;
    let _ = writeln!(md, "### {}\n", f.title);
    let _ = writeln!(md, "![{}](figures/{}.png)\n", f.title, f.id);
    let _ = writeln!(
        md,
        "{} ({}; data: `data/{}.csv`)\n",
        f.caption, f.subtitle, f.id
    );
    // The means (bars) or every point (lines) as a table.
    let cols: Vec<usize> = match f.kind {
        Kind::Bars => f.highlight.clone(),
        Kind::Lines { .. } => (0..f.categories.len()).collect(),
    };
    if cols.is_empty() {
        return Ok(());
    }
    let mut head = "| |".to_string();
    let mut rule = "|---|".to_string();
    for &c in &cols {
        let _ = write!(head, " {} |", f.categories[c]);
        rule.push_str("---|");
    }
    let _ = writeln!(md, "{head}\n{rule}");
    for s in &f.series {
        let _ = write!(md, "| {} |", s.name);
        for &c in &cols {
            let v = s.values.get(c).copied().flatten();
            let t = if f.percent {
                pct_opt(v)
            } else {
                v.map_or("-".into(), |x| format!("{x:.3}"))
            };
            let _ = write!(md, " {t} |");
        }
        let _ = writeln!(md);
    }
    if !f.paper.is_empty() {
        let marks: Vec<String> = f.paper.iter().map(|p| p.label.clone()).collect();
        let _ = writeln!(md, "\nThe paper: {}.", marks.join("; "));
    }
    let _ = writeln!(md);
    Ok(())
}

/// A figure's numbers: category, then one column a series.
pub fn figure_csv(f: &Figure) -> String {
    let mut s = "category".to_string();
    for x in &f.series {
        let _ = write!(s, ",{}", csv(&x.name));
    }
    s.push('\n');
    for (i, c) in f.categories.iter().enumerate() {
        s.push_str(&csv(c));
        for x in &f.series {
            match x.values.get(i).copied().flatten() {
                Some(v) => {
                    let _ = write!(s, ",{v}");
                }
                None => s.push(','),
            }
        }
        s.push('\n');
    }
    s
}

fn timelines(md: &mut String, plan: &Plan, d: Dispatch) {
    if plan.timeline_scenes.is_empty() {
        return;
    }
    let _ = writeln!(
        md,
        "### Timelines: occupancy over a tile and the priority warps' launches\n\n\
         Cycles {} to {} of one scene per game, per policy: warps resident per core (fill and \
         drain of each tile), misses outstanding per cache level, priority warps launched. \
         What the paper could not show.\n",
        plan.timeline_window.0, plan.timeline_window.1
    );
    for s in &plan.timeline_scenes {
        for &p in &plan.timeline_policies {
            let file = Plan::timeline_file(s, d, p);
            let _ = writeln!(md, "**{s}, {p}**\n\n![{s} {p}](figures/{file})\n");
        }
    }
}

fn footer(md: &mut String, plan: &Plan) {
    let _ = writeln!(
        md,
        "\n## How to read and redo this\n\n\
         - Every number comes from the points in `points/` (one JSON per simulation, keyed by \
         scene, effective configuration and wasp binary); `data/points.csv` flattens them.\n\
         - A single point can be checked by hand: `wasp render SCENE --trace-out t.trace`, then \
         `wasp run --trace t.trace --set raster.dispatch=\"...\" --set \
         scheduler.policy=\"...\"` with the overrides the point lists.\n\
         - WaSP's shipped parameters ({}) were chosen once for the whole suite \
         (docs/calibration.md); the threshold figure shows the sweep.",
        plan.wasp
    );
}
