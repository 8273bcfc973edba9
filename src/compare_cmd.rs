//! `wasp compare`: several launch policies on the same trace, with
//! speedups against the first; with `--variant`, on machine variants too
//! ([`crate::compare_variants`]), against one reference row.

use crate::cli_error::CliError;
use crate::compare_variants::{self as variants, Row, Variant};
use crate::output::{self, emit, Output};
use crate::run_cmd::{
    configure, load_config, load_trace, progress_bar, run_tiles, sim_err, Inputs, MachineFlags,
};
use clap::Args;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use wasp_rtl::policy::{PolicyName, PolicySpec};
use wasp_sim::config::{IssueOrder, MachineConfig, TextureCache};
use wasp_sim::run::{simulate, RunOptions};
use wasp_sim::stats::{csv_table, RunStats};
use wasp_sim::trace::Trace;

/// Options of `wasp compare`.
#[derive(Args, Debug, Clone)]
pub struct CompareArgs {
    #[command(flatten)]
    pub inputs: Inputs,

    /// Policies to compare, comma separated; the first is the reference for
    /// speedups. Default: baseline, fullpriority, freemshr:10, the
    /// configuration's `scheduler.policy` and, when that is WaSP, the
    /// measured-CF variant `wasp-m` at its threshold. Names as in `wasp run
    /// --policy`: a bare `wasp` is the machine's own (the shipped
    /// `wasp:0:3`), and the table names every policy resolved.
    #[arg(long, value_delimiter = ',')]
    pub policies: Option<Vec<PolicyName>>,

    /// Also run the reference policy with ideal (zero-latency) main memory.
    #[arg(long)]
    pub with_ideal: bool,

    /// Write every run's statistics as a JSON array to FILE (`-` for
    /// standard output).
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,

    /// Write every run's statistics as CSV to FILE (`-` for standard
    /// output).
    #[arg(long, value_name = "FILE")]
    pub csv: Option<PathBuf>,

    /// Simulations run at once (default: the machine's cores).
    #[arg(long, value_name = "N")]
    pub jobs: Option<usize>,

    /// A machine variant, NAME:KEY=VALUE[,KEY=VALUE...] (repeatable): the
    /// policies run also on the machine with these overrides (after
    /// --config and --set), in rows named NAME/POLICY, e.g. `--variant
    /// raster:prefetch.kind=raster --variant oracle:prefetch.kind=oracle-tile`.
    /// The table, JSON and CSV then give every row's speedup against one
    /// reference (--reference).
    #[arg(long = "variant", value_name = "NAME:KEY=VALUE[,...]")]
    pub variants: Vec<Variant>,

    /// The row every speedup is against, by its name in the table
    /// (`baseline`, `raster/baseline`, `wasp:0:3 +ideal memory`...).
    /// Default: the first policy on the machine without a variant.
    #[arg(long, value_name = "ROW")]
    pub reference: Option<String>,
}

/// One run of a comparison.
struct Job {
    label: String,
    /// The variant's name, `None` on the machine as configured.
    variant: Option<String>,
    /// The machine (as configured, or the variant's); after
    /// [`compare`]'s check, with the job's policy and memory.
    cfg: MachineConfig,
    /// The job's policy (and ideal memory): its own flags.
    flags: MachineFlags,
    opts: RunOptions,
}

/// The policies `wasp compare` runs when `--policies` is not given: the
/// scanline baseline, Fullpriority, Freemshr10, the configuration's policy
/// and, when that is WaSP, `wasp-m` at the same threshold.
fn default_policies(cfg: &MachineConfig) -> Vec<PolicySpec> {
    let mut v = vec![
        PolicySpec::Baseline,
        PolicySpec::FullPriority,
        PolicySpec::FreeMshr(10),
    ];
    let own = cfg.scheduler.policy;
    if !v.contains(&own) {
        v.push(own);
    }
    if let PolicySpec::Wasp { threshold, .. } = own {
        v.push(PolicySpec::WaspMeasured { threshold });
    }
    v
}

/// Run the comparison.
pub fn compare(args: &CompareArgs) -> Result<(), CliError> {
    output::check(
        &[
            Output::new("--json", args.json.as_deref()),
            Output::new("--csv", args.csv.as_deref()),
        ],
        &args.inputs.files(),
    )?;
    let cfg = load_config(&args.inputs, None)?;
    let trace = load_trace(&args.inputs, &cfg)?;
    let policies = match &args.policies {
        Some(p) => p.iter().map(|p| p.resolve(cfg.scheduler.policy)).collect(),
        None => default_policies(&cfg),
    };
    if policies.is_empty() {
        return Err(CliError::usage("--policies: name at least one policy"));
    }
    let machines = variants::machines(&cfg, &args.variants)?;
    let mut jobs = comparison_jobs(args, &policies, &cfg, &machines);
    let reference = reference_index(args, &jobs)?;
    // Check every configuration before spending time on any run.
    for j in &mut jobs {
        j.cfg = configure(&j.cfg, &[], &j.flags)?;
    }
    let threads = args
        .jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
        .clamp(1, jobs.len());
    let runs = run_jobs(&trace, &jobs, threads, args.inputs.quiet)?;
    let labels: Vec<String> = jobs.iter().map(|j| j.label.clone()).collect();
    if !args.variants.is_empty() || args.reference.is_some() {
        return write_against(args, &jobs, &runs, reference, &machines);
    }
    if let Some(p) = &args.json {
        let text = serde_json::to_string_pretty(&runs)
            .map_err(|e| CliError::failed(format!("encoding JSON: {e}")))?
            + "\n";
        emit(p, &text)?;
    }
    if let Some(p) = &args.csv {
        emit(p, &csv_table(&runs))?;
    }
    if !output::to_stdout(&args.json) && !output::to_stdout(&args.csv) {
        emit(Path::new("-"), &compare_table(&labels, &runs))?;
    }
    Ok(())
}

/// The row `--reference` names (the first when not given).
fn reference_index(args: &CompareArgs, jobs: &[Job]) -> Result<usize, CliError> {
    let Some(r) = &args.reference else {
        return Ok(0);
    };
    jobs.iter().position(|j| &j.label == r).ok_or_else(|| {
        let names: Vec<&str> = jobs.iter().map(|j| j.label.as_str()).collect();
        CliError::usage(format!(
            "--reference {r}: no such row (the rows: {})",
            names.join(", ")
        ))
    })
}

/// The outputs of a comparison with variants or a chosen reference: every
/// row's speedup against the reference row, in the table, JSON and CSV.
fn write_against(
    args: &CompareArgs,
    jobs: &[Job],
    runs: &[RunStats],
    reference: usize,
    machines: &[(Variant, MachineConfig)],
) -> Result<(), CliError> {
    let rows: Vec<Row> = jobs
        .iter()
        .zip(runs)
        .map(|(j, r)| Row {
            row: &j.label,
            variant: j.variant.as_deref(),
            reference: &jobs[reference].label,
            speedup_percent: variants::speedup(&runs[reference], r),
            stats: r,
        })
        .collect();
    if let Some(p) = &args.json {
        emit(p, &variants::json(&rows)?)?;
    }
    if let Some(p) = &args.csv {
        emit(p, &variants::csv(&rows))?;
    }
    if !output::to_stdout(&args.json) && !output::to_stdout(&args.csv) {
        let labels: Vec<String> = jobs.iter().map(|j| j.label.clone()).collect();
        let table = compare_table_against(&labels, runs, reference);
        let (first, rest) = table.split_once('\n').unwrap_or((&table, ""));
        let text = format!("{first}\n{}{rest}", variants::header(machines));
        emit(Path::new("-"), &text)?;
    }
    Ok(())
}

/// The runs of a comparison: each policy, then (`--with-ideal`) the first
/// with ideal memory, on the machine as configured; then each policy on
/// each variant's machine.
fn comparison_jobs(
    args: &CompareArgs,
    policies: &[PolicySpec],
    cfg: &MachineConfig,
    machines: &[(Variant, MachineConfig)],
) -> Vec<Job> {
    let opts = RunOptions {
        warm: args.inputs.warm,
        ..RunOptions::default()
    };
    let flags = |policy: &PolicySpec, ideal: bool| {
        MachineFlags::default()
            .with("scheduler.policy", Some(policy))
            .with("memory.ideal", ideal.then_some(true))
    };
    let mut jobs: Vec<Job> = policies
        .iter()
        .map(|p| Job {
            label: p.to_string(),
            variant: None,
            cfg: cfg.clone(),
            flags: flags(p, false),
            opts: opts.clone(),
        })
        .collect();
    if args.with_ideal {
        jobs.push(Job {
            label: format!("{} +ideal memory", policies[0]),
            variant: None,
            cfg: cfg.clone(),
            flags: flags(&policies[0], true),
            opts: opts.clone(),
        });
    }
    for (v, vcfg) in machines {
        jobs.extend(policies.iter().map(|p| Job {
            label: format!("{}/{p}", v.name),
            variant: Some(v.name.clone()),
            cfg: vcfg.clone(),
            flags: flags(p, false),
            opts: opts.clone(),
        }));
    }
    jobs
}

/// Run `jobs` on `threads` threads, with one progress bar over them all;
/// their statistics in job order.
fn run_jobs(
    trace: &Trace,
    jobs: &[Job],
    threads: usize,
    quiet: bool,
) -> Result<Vec<RunStats>, CliError> {
    let tiles = jobs.first().map_or(0, |j| run_tiles(trace, &j.opts));
    let pb = progress_bar(quiet, tiles * jobs.len(), "comparing");
    let done_tiles = Mutex::new(vec![0usize; jobs.len()]);
    let results = crate::pool::run_indexed(jobs.len(), threads, |i| {
        let mut progress = |d: usize, _t: usize| {
            let mut v = done_tiles.lock().expect("lock");
            v[i] = d;
            pb.set_position(v.iter().sum::<usize>() as u64);
        };
        simulate(&jobs[i].cfg, trace, &jobs[i].opts, &mut progress)
    });
    pb.finish_and_clear();
    let mut runs = Vec::with_capacity(jobs.len());
    for (j, r) in jobs.iter().zip(results) {
        runs.push(r.map_err(|e| CliError::failed(format!("{}: {}", j.label, sim_err(e))))?);
    }
    Ok(runs)
}

/// The comparison as a table: speedups against the first run.
pub fn compare_table(labels: &[String], runs: &[RunStats]) -> String {
    compare_table_against(labels, runs, 0)
}

/// The comparison as a table: the header from the first run's machine,
/// speedups against the run `reference`.
pub fn compare_table_against(labels: &[String], runs: &[RunStats], reference: usize) -> String {
    use std::fmt::Write as _;
    let Some(base) = runs.first() else {
        return String::new();
    };
    let against = &runs[reference];
    // Wide enough for every label (26 columns, as always, when they fit).
    let w = labels
        .iter()
        .map(|l| l.len() + 1)
        .max()
        .unwrap_or(0)
        .max(26);
    let mut s = machine_header(base);
    let _ = writeln!(
        s,
        "{:<w$}{:>12}{:>8}{:>9}{:>9}{:>10}{:>10}{:>10}{:>11}{:>7}{:>8}{:>10}",
        "policy",
        "cycles",
        "ipc",
        "speedup",
        "stall%",
        "latency",
        "l1 miss",
        "l2 miss",
        "energy",
        "occ",
        "lead",
        "held"
    );
    for (l, r) in labels.iter().zip(runs) {
        let stall = r.l0.as_ref().unwrap_or(&r.l1).stall_fraction;
        let lead = if r.priority_lead.priority_warps > 0 {
            format!("{:+.0}", r.priority_lead.mean)
        } else {
            "-".to_string()
        };
        let _ = writeln!(
            s,
            "{:<w$}{:>12}{:>8.3}{:>+8.2}%{:>8.2}%{:>10.1}{:>10}{:>10}{:>9.1}uJ{:>7.1}{:>8}{:>10}",
            l,
            r.cycles,
            r.ipc,
            variants::speedup(against, r),
            100.0 * stall,
            r.memory_latency.all,
            r.l1.misses,
            r.l2.misses,
            r.energy.total_nj / 1000.0,
            r.avg_warps_per_core,
            lead,
            r.held_cycles
        );
    }
    let _ = writeln!(
        s,
        "speedup = {} cycles / policy cycles - 1; stall% = scheduler-level cache (L0, else L1) stalled; latency = mean memory latency per warp in cycles; occ = mean warps resident per core; lead = mean raster position minus launch rank of priority warps; held = hold idle core-cycles (a free slot, a priority warp waiting, nothing launched)",
        labels[reference]
    );
    s
}

/// The table's first two lines: run `base`'s machine, and the options
/// set on it.
fn machine_header(base: &RunStats) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    let _ = write!(
        s,
        "machine {}  |  dispatch {}  |  workload {}  |  subset {}  |  launch rule {}",
        base.machine, base.dispatch, base.workload, base.subset.subset, base.launch_rule
    );
    // Options off by default are named only when set, so the shipped
    // machine's header stays as it is.
    if base.issue != IssueOrder::default() {
        let _ = write!(s, "  |  issue {}", base.issue);
    }
    if let Some(p) = &base.prefetch {
        let _ = write!(s, "  |  prefetch {}", p.kind);
    }
    if let Some(last) = base.frames.last() {
        let _ = write!(
            s,
            "  |  frame {} after {} earlier",
            last.frame,
            base.frames.len() - 1
        );
    }
    if base.ideal_memory {
        let _ = write!(s, "  |  ideal memory");
    }
    if base.texture_cache != TextureCache::default() {
        let _ = write!(s, "  |  texture cache {}", base.texture_cache);
    }
    let _ = write!(
        s,
        "\nwarps per core {}  input queue {} entries",
        base.occupancy.max_warps, base.input_queue
    );
    s.push('\n');
    s
}
