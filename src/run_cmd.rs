//! `wasp run` and `wasp compare`: the GPU model on a trace.

use crate::CliError;
use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::{BufWriter, IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use wasp_rtl::policy::{LaunchRule, PolicySpec};
use wasp_rtl::subset::SubsetSpec;
use wasp_sim::config::BlockedOn;
use wasp_sim::config::{Dispatch, MachineConfig};
use wasp_sim::run::{simulate, simulate_timeline, simulate_traced, RunOptions, SimError};
use wasp_sim::stats::{csv_table, RunStats};
use wasp_sim::synth::{generate, GenParams};
use wasp_sim::trace::Trace;
use wasp_waves::vcd_sink::time_unit_note;
use wasp_waves::{Format, GtkwSave, TimeAxis, VcdSink};

/// The time axis of `wasp run --vcd` (see [`TimeAxis`]).
///
/// (wasp) Cycles by default: every number the simulator prints or accepts
/// (`cycles`, `--vcd-from`, `--vcd-to`, `--timeline-from`) is a cycle, and
/// one time unit per cycle lets a user read them off the waveform directly;
/// real time is the option for comparing with wall-clock figures.
#[derive(clap::ValueEnum, Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum VcdTime {
    /// One time unit per GPU cycle.
    #[default]
    Cycles,
    /// Picoseconds: cycle x the clock period.
    Real,
}

impl From<VcdTime> for TimeAxis {
    fn from(t: VcdTime) -> TimeAxis {
        match t {
            VcdTime::Cycles => TimeAxis::Cycles,
            VcdTime::Real => TimeAxis::RealTime,
        }
    }
}

/// Where the machine and the workload come from.
#[derive(Args, Debug, Clone)]
pub struct Inputs {
    /// Machine configuration (TOML). Default: the embedded
    /// configs/paper.toml (Table II, width 4, 64 warps, L0).
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,

    /// Workload trace (wasp-trace format, see tests/traces/FORMAT.md).
    /// Default: the synthetic workload of `wasp synth` with its defaults
    /// (a 1960x768 frame), generated with the config's seed.
    #[arg(long, value_name = "FILE")]
    pub trace: Option<PathBuf>,

    /// Priority subset: mesh2, mesh4, mesh8, mesh16, hlines, vlines, top16,
    /// random or random:SEED. Overrides scheduler.subset.
    #[arg(long, value_name = "SUBSET")]
    pub subset: Option<SubsetSpec>,

    /// What a core launches when a priority warp waits, the policy's gate
    /// is closed and no regular warp waits: hold (nothing; the paper's rule)
    /// or launch (that priority warp; work-conserving). Overrides
    /// scheduler.launch_rule.
    #[arg(long, value_name = "RULE")]
    pub launch_rule: Option<LaunchRule>,

    /// Zero-latency main memory (overrides memory.ideal).
    #[arg(long)]
    pub ideal_memory: bool,

    /// Which miss blocks a warp: first-level (any miss in the L0, or the L1
    /// without L0), l1-miss (a request misses in the L1) or dram (in the
    /// L2). Overrides scheduler.blocked_on.
    #[arg(long, value_name = "RULE")]
    pub blocked_on: Option<BlockedOn>,

    /// Tile dispatch: shared-tile (the paper's machine: one tile at a time
    /// for the whole GPU, one rasterizer) or per-core-tile (each core renders
    /// a tile of its own). Overrides raster.dispatch.
    #[arg(long, value_name = "MODE")]
    pub dispatch: Option<Dispatch>,

    /// Change one configuration field, e.g. `--set l0.mshrs=24` or
    /// `--set dram.model=fixed` (dotted TOML path = TOML value; repeatable,
    /// applied in order after --config, before the other options).
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub set: Vec<String>,

    /// No progress output on stderr (progress bars, notes of what is being
    /// done); results, warnings and errors still print.
    #[arg(long, short)]
    pub quiet: bool,
}

/// Options of `wasp run`.
#[derive(Args, Debug, Clone)]
pub struct RunArgs {
    #[command(flatten)]
    pub inputs: Inputs,

    /// Launch policy: baseline, fullpriority, freemshr:N, wasp, wasp:THRESHOLD or wasp:THRESHOLD:CF.
    /// Overrides scheduler.policy.
    #[arg(long, value_name = "POLICY")]
    pub policy: Option<PolicySpec>,

    /// Write the statistics as JSON to FILE (`-` for standard output).
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,

    /// Write the statistics as CSV to FILE (`-` for standard output).
    #[arg(long, value_name = "FILE")]
    pub csv: Option<PathBuf>,

    /// Write the waveform (VCD) to FILE, and a GTKWave save file FILE.gtkw
    /// preselecting core 0's scheduler signals.
    #[arg(long, value_name = "FILE")]
    pub vcd: Option<PathBuf>,

    /// First cycle written to the VCD.
    #[arg(long, value_name = "CYCLE", requires = "vcd")]
    pub vcd_from: Option<u64>,

    /// Last cycle written to the VCD.
    #[arg(long, value_name = "CYCLE", requires = "vcd")]
    pub vcd_to: Option<u64>,

    /// Time axis of the VCD. cycles: one time unit is one GPU cycle (the
    /// VCD format needs a physical unit, so the file declares 1 ns and says
    /// in a comment that a unit is a cycle at gpu.frequency_mhz; GTKWave's
    /// "ns" reads as cycles). real: picoseconds, cycle x the clock period
    /// rounded to whole ps (1667 ps at 600 MHz), so GTKWave shows real time.
    /// Default: cycles.
    #[arg(long, value_name = "AXIS", value_enum, requires = "vcd")]
    pub vcd_time: Option<VcdTime>,

    /// Draw the timeline (resident warps per core, outstanding misses per
    /// cache level, priority-warp launches, tile starts and ends) to FILE,
    /// a .png or .svg.
    #[arg(long, value_name = "FILE", conflicts_with = "vcd")]
    pub timeline: Option<PathBuf>,

    /// First cycle of the timeline.
    #[arg(long, value_name = "CYCLE", requires = "timeline", default_value_t = 1)]
    pub timeline_from: u64,

    /// Last cycle of the timeline (default: 20000 cycles after the first).
    #[arg(long, value_name = "CYCLE", requires = "timeline")]
    pub timeline_to: Option<u64>,
}

/// Options of `wasp compare`.
#[derive(Args, Debug, Clone)]
pub struct CompareArgs {
    #[command(flatten)]
    pub inputs: Inputs,

    /// Policies to compare, comma separated; the first is the reference for
    /// speedups. Default: baseline, fullpriority, freemshr:10, the
    /// configuration's `scheduler.policy` and, when that is WaSP, the
    /// measured-CF variant `wasp-m` at its threshold.
    #[arg(long, value_delimiter = ',')]
    pub policies: Option<Vec<PolicySpec>>,

    /// Also run the reference policy with ideal (zero-latency) main memory.
    #[arg(long)]
    pub with_ideal: bool,

    /// Write every run's statistics as a JSON array to FILE (`-`: stdout).
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,

    /// Write every run's statistics as CSV to FILE (`-`: stdout).
    #[arg(long, value_name = "FILE")]
    pub csv: Option<PathBuf>,

    /// Simulations run at once (default: the machine's cores).
    #[arg(long, value_name = "N")]
    pub jobs: Option<usize>,
}

/// Read and validate the machine configuration FILE
/// ([`MachineConfig::load`]: a file that is not UTF-8 is named with the line
/// and byte column of its first invalid byte).
pub fn read_config(path: &Path) -> Result<MachineConfig, CliError> {
    MachineConfig::load(path).map_err(|e| CliError::usage(e.to_string()))
}

/// Load the configuration named by the inputs.
pub fn load_config(inputs: &Inputs) -> Result<MachineConfig, CliError> {
    let cfg = match &inputs.config {
        Some(p) => read_config(p)?,
        None => MachineConfig::paper(),
    };
    let mut cfg = wasp_sim::overrides::apply(&cfg, &inputs.set)
        .map_err(|e| CliError::usage(e.to_string()))?;
    if let Some(b) = inputs.blocked_on {
        cfg.scheduler.blocked_on = b;
    }
    Ok(cfg)
}

/// Load (or generate) the trace named by the inputs.
pub fn load_trace(inputs: &Inputs, cfg: &MachineConfig) -> Result<Trace, CliError> {
    match &inputs.trace {
        Some(p) => Trace::read(p).map_err(|e| CliError::usage(e.to_string())),
        None => {
            let params = GenParams {
                tile: cfg.gpu.tile_size,
                seed: cfg.sim.seed,
                ..GenParams::default()
            };
            if !inputs.quiet {
                eprintln!(
                    "wasp: no --trace given: generating the synthetic workload {}",
                    params.workload_name()
                );
            }
            generate(&params).map_err(|e| CliError::failed(format!("generating the trace: {e}")))
        }
    }
}

fn progress_bar(quiet: bool, total: usize, label: &str) -> ProgressBar {
    if quiet || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let pb = ProgressBar::with_draw_target(Some(total as u64), ProgressDrawTarget::stderr());
    pb.set_style(
        ProgressStyle::with_template(
            "{prefix:>14} [{bar:40}] {pos}/{len} tiles {elapsed_precise} eta {eta}",
        )
        .expect("valid template")
        .progress_chars("=> "),
    );
    pb.set_prefix(label.to_string());
    // Redraw (elapsed time) even while one long tile keeps the count still.
    pb.enable_steady_tick(std::time::Duration::from_millis(250));
    pb
}

fn sim_err(e: SimError) -> CliError {
    match e {
        SimError::Config(m) => CliError::usage(m),
        other => CliError::failed(other.to_string()),
    }
}

/// Write `text` to FILE, or to standard output for `-`.
pub fn emit(path: &Path, text: &str) -> Result<(), CliError> {
    if path.as_os_str() == "-" {
        let mut out = std::io::stdout().lock();
        out.write_all(text.as_bytes())
            .map_err(|e| CliError::failed(format!("writing to standard output: {e}")))
    } else {
        std::fs::write(path, text)
            .map_err(|e| CliError::failed(format!("cannot write {}: {e}", path.display())))
    }
}

/// `FILE.gtkw` beside `FILE`.
pub fn gtkw_path(vcd: &Path) -> PathBuf {
    let mut s = vcd.as_os_str().to_owned();
    s.push(".gtkw");
    PathBuf::from(s)
}

/// Run the command.
pub fn run(args: &RunArgs) -> Result<(), CliError> {
    // The flags are checked before the (possibly long) trace is read.
    let window = match (args.vcd_from, args.vcd_to) {
        (None, None) => None,
        (f, t) => {
            let (f, t) = (f.unwrap_or(0), t.unwrap_or(u64::MAX));
            if f > t {
                return Err(CliError::usage(format!(
                    "--vcd-from {f} is after --vcd-to {t}"
                )));
            }
            Some((f, t))
        }
    };
    let timeline_window = match &args.timeline {
        None => None,
        Some(path) => {
            let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
            if !matches!(ext, "png" | "svg") {
                return Err(CliError::usage(format!(
                    "--timeline {}: the file must end in .png or .svg",
                    path.display()
                )));
            }
            let from = args.timeline_from;
            let to = args.timeline_to.unwrap_or(from.saturating_add(19_999));
            if from > to {
                return Err(CliError::usage(format!(
                    "--timeline-from {from} is after --timeline-to {to}"
                )));
            }
            if to - from > 2_000_000 {
                return Err(CliError::usage(format!(
                    "--timeline-from {from} --timeline-to {to}: at most 2000000 cycles can be drawn"
                )));
            }
            Some((from, to))
        }
    };
    let cfg = load_config(&args.inputs)?;
    let trace = load_trace(&args.inputs, &cfg)?;
    let opts = RunOptions {
        policy: args.policy,
        launch_rule: args.inputs.launch_rule,
        subset: args.inputs.subset.clone(),
        ideal_memory: args.inputs.ideal_memory.then_some(true),
        dispatch: args.inputs.dispatch,
        vcd_window: window,
        timeline: timeline_window,
        record_warps: false,
    };
    let pb = progress_bar(args.inputs.quiet, trace.tiles().len(), "simulating");
    let mut progress = |done: usize, _total: usize| pb.set_position(done as u64);
    let stats = match &args.vcd {
        None if args.timeline.is_some() => {
            let path = args.timeline.as_ref().expect("checked");
            let (stats, timeline) =
                simulate_timeline(&cfg, &trace, &opts, &mut progress).map_err(sim_err)?;
            if timeline.samples.is_empty() {
                return Err(CliError::usage(format!(
                    "--timeline-from {}: the run ended at cycle {}, before the window",
                    timeline.from, stats.cycles
                )));
            }
            crate::timeline_plot::draw(&timeline, path).map_err(CliError::failed)?;
            stats
        }
        None => simulate(&cfg, &trace, &opts, &mut progress).map_err(sim_err)?,
        Some(path) => {
            let file = std::fs::File::create(path)
                .map_err(|e| CliError::failed(format!("cannot create {}: {e}", path.display())))?;
            let axis = TimeAxis::from(args.vcd_time.unwrap_or_default());
            let mut sink = VcdSink::new(BufWriter::new(file), "wasp")
                .with_clock_mhz(cfg.gpu.frequency_mhz)
                .with_time_axis(axis);
            let scale = sink.units_per_cycle();
            let stats =
                simulate_traced(&cfg, &trace, &opts, &mut sink, &mut progress).map_err(sim_err)?;
            if let Some((from, to)) = window.filter(|w| w.0 > stats.cycles) {
                // The window is known to be empty only once the run has ended.
                let to = if to == u64::MAX {
                    String::new()
                } else {
                    format!("={to}")
                };
                eprintln!(
                    "wasp: warning: the run ended at cycle {}, before --vcd-from {from}: {} holds \
                     no cycle of the window {from}..{to}",
                    stats.cycles,
                    path.display()
                );
            }
            let signals = sink.signals().to_vec();
            let end = match window {
                Some((_, to)) => to.min(stats.cycles) + 1,
                None => stats.cycles + 1,
            };
            sink.finish(end)
                .and_then(|mut w| w.flush())
                .map_err(|e| CliError::failed(format!("writing {}: {e}", path.display())))?;
            let mut save = GtkwSave::new(path.display().to_string())
                .note(time_unit_note(Some(cfg.gpu.frequency_mhz), axis))
                .timestart(window.map(|w| w.0).unwrap_or(0).saturating_mul(scale))
                .window_size(1400, 700)
                .signals_width(320)
                .zoom_to_fit(end.saturating_mul(scale));
            save = save.begin_group("core0 scheduler", false);
            for s in signals
                .iter()
                .filter(|s| s.path.len() >= 3 && s.path[1] == "core0" && s.path[2] == "scheduler")
            {
                let f = if s.name == "real_free_mshrs" {
                    Format::SignedDecimal
                } else {
                    Format::Decimal
                };
                save = save.traced(s, f);
            }
            save = save.end_group().begin_group("raster", false);
            for s in signals
                .iter()
                .filter(|s| s.path.len() == 2 && s.path[1] == "raster")
            {
                save = save.traced(s, Format::Decimal);
            }
            save = save.end_group().begin_group("core0", false);
            for s in signals
                .iter()
                .filter(|s| s.path.len() == 2 && s.path[1] == "core0")
            {
                save = save.traced(s, Format::Decimal);
            }
            save = save.end_group();
            let g = gtkw_path(path);
            let mut out = Vec::new();
            save.write_to(&mut out)
                .map_err(|e| CliError::failed(format!("writing {}: {e}", g.display())))?;
            emit(&g, &String::from_utf8_lossy(&out))?;
            stats
        }
    };
    pb.finish_and_clear();
    let to_stdout = |p: &Option<PathBuf>| p.as_ref().is_some_and(|p| p.as_os_str() == "-");
    if let Some(p) = &args.json {
        emit(p, &stats.to_json())?;
    }
    if let Some(p) = &args.csv {
        emit(p, &stats.to_csv())?;
    }
    if !to_stdout(&args.json) && !to_stdout(&args.csv) {
        emit(Path::new("-"), &stats.to_table())?;
    }
    Ok(())
}

/// One run of a comparison.
struct Job {
    label: String,
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
    let cfg = load_config(&args.inputs)?;
    let trace = load_trace(&args.inputs, &cfg)?;
    let policies = match &args.policies {
        Some(p) => p.clone(),
        None => default_policies(&cfg),
    };
    if policies.is_empty() {
        return Err(CliError::usage("--policies: name at least one policy"));
    }
    let mut jobs: Vec<Job> = policies
        .iter()
        .map(|p| Job {
            label: p.to_string(),
            opts: RunOptions {
                policy: Some(*p),
                launch_rule: args.inputs.launch_rule,
                subset: args.inputs.subset.clone(),
                ideal_memory: args.inputs.ideal_memory.then_some(true),
                dispatch: args.inputs.dispatch,
                ..RunOptions::default()
            },
        })
        .collect();
    if args.with_ideal {
        jobs.push(Job {
            label: format!("{} +ideal memory", policies[0]),
            opts: RunOptions {
                policy: Some(policies[0]),
                launch_rule: args.inputs.launch_rule,
                subset: args.inputs.subset.clone(),
                ideal_memory: Some(true),
                dispatch: args.inputs.dispatch,
                ..RunOptions::default()
            },
        });
    }
    // Check every configuration before spending time on any run.
    for j in &jobs {
        j.opts.apply(&cfg).map_err(sim_err)?;
    }
    let threads = args
        .jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
        .clamp(1, jobs.len());
    let pb = progress_bar(
        args.inputs.quiet,
        trace.tiles().len() * jobs.len(),
        "comparing",
    );
    let done_tiles = Mutex::new(vec![0usize; jobs.len()]);
    let next = Mutex::new(0usize);
    let results: Mutex<Vec<Option<Result<RunStats, SimError>>>> =
        Mutex::new((0..jobs.len()).map(|_| None).collect());
    std::thread::scope(|s| {
        for _ in 0..threads {
            s.spawn(|| loop {
                let i = {
                    let mut n = next.lock().expect("lock");
                    let i = *n;
                    *n += 1;
                    i
                };
                if i >= jobs.len() {
                    break;
                }
                let mut progress = |d: usize, _t: usize| {
                    let mut v = done_tiles.lock().expect("lock");
                    v[i] = d;
                    pb.set_position(v.iter().sum::<usize>() as u64);
                };
                let r = simulate(&cfg, &trace, &jobs[i].opts, &mut progress);
                results.lock().expect("lock")[i] = Some(r);
            });
        }
    });
    pb.finish_and_clear();
    let mut runs = Vec::with_capacity(jobs.len());
    for (j, r) in jobs.iter().zip(results.into_inner().expect("lock")) {
        let r = r.expect("every job ran");
        runs.push(r.map_err(|e| CliError::failed(format!("{}: {}", j.label, sim_err(e))))?);
    }
    let labels: Vec<String> = jobs.iter().map(|j| j.label.clone()).collect();
    let to_stdout = |p: &Option<PathBuf>| p.as_ref().is_some_and(|p| p.as_os_str() == "-");
    if let Some(p) = &args.json {
        let text = serde_json::to_string_pretty(&runs)
            .map_err(|e| CliError::failed(format!("encoding JSON: {e}")))?
            + "\n";
        emit(p, &text)?;
    }
    if let Some(p) = &args.csv {
        emit(p, &csv_table(&runs))?;
    }
    if !to_stdout(&args.json) && !to_stdout(&args.csv) {
        emit(Path::new("-"), &compare_table(&labels, &runs))?;
    }
    Ok(())
}

/// The comparison as a table: speedups against the first run.
pub fn compare_table(labels: &[String], runs: &[RunStats]) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    let Some(base) = runs.first() else {
        return s;
    };
    let _ = writeln!(
        s,
        "machine {}  |  dispatch {}  |  workload {}  |  subset {}  |  launch rule {}",
        base.machine, base.dispatch, base.workload, base.subset.subset, base.launch_rule
    );
    let _ = writeln!(
        s,
        "{:<26}{:>12}{:>8}{:>9}{:>9}{:>10}{:>10}{:>10}{:>11}{:>7}{:>8}{:>10}",
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
            "{:<26}{:>12}{:>8.3}{:>+8.2}%{:>8.2}%{:>10.1}{:>10}{:>10}{:>9.1}uJ{:>7.1}{:>8}{:>10}",
            l,
            r.cycles,
            r.ipc,
            100.0 * (base.cycles as f64 / r.cycles as f64 - 1.0),
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
        labels[0]
    );
    s
}
