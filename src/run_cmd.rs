//! `wasp run`: the GPU model on a trace; the inputs it shares with
//! `wasp compare` ([`Inputs`]).

use crate::cli_error::CliError;
use crate::output::{self, emit, Output};
use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use serde::Serialize;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use wasp_rtl::policy::{LaunchRule, PolicyName};
use wasp_rtl::subset::SubsetSpec;
use wasp_sim::config::{BlockedOn, Dispatch, MachineConfig, Override};
use wasp_sim::run::{simulate, simulate_timeline, simulate_traced, RunOptions, SimError};
use wasp_sim::stats::RunStats;
use wasp_sim::synth::{generate, GenParams};
use wasp_sim::trace::Trace;
use wasp_waves::vcd_sink::time_unit_note;
use wasp_waves::{Format, GtkwSave, SignalInfo, TimeAxis, VcdSink};

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

    /// Of a trace of several frames, measure the last frame after K earlier
    /// ones: run frames n-1-K to n-1 in order (caches and DRAM carrying
    /// over) and report the last. Default: every frame before the last.
    /// The report is always the last frame's, with a record per frame run.
    #[arg(long, value_name = "K")]
    pub warm: Option<usize>,

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

impl Inputs {
    /// The input files, which no output may overwrite.
    pub fn files(&self) -> [output::Input<'_>; 2] {
        [
            output::Input::file("--config", self.config.as_deref()),
            output::Input::file("--trace", self.trace.as_deref()),
        ]
    }
}

/// Options of `wasp run`.
#[derive(Args, Debug, Clone)]
pub struct RunArgs {
    #[command(flatten)]
    pub inputs: Inputs,

    /// Launch policy: baseline, fullpriority, `freemshr[:N]`,
    /// `wasp[:THRESHOLD[:CF]]` or `wasp-m[:THRESHOLD]` (WaSP with a CF measured
    /// per core). Names are lower case. A bare `wasp` takes its threshold
    /// and CF from the machine's scheduler.policy (the shipped `wasp:0:3`),
    /// `wasp-m` its threshold (`wasp-m:0`), `freemshr` its N when the
    /// machine's policy is freemshr:N, else 10 (the paper's Freemshr10);
    /// `wasp:T` alone uses the paper's CF 2.5. Outputs name the resolved
    /// policy. Overrides scheduler.policy.
    #[arg(long, value_name = "POLICY")]
    pub policy: Option<PolicyName>,

    /// Write the statistics as JSON to FILE (`-` for standard output).
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,

    /// Write the statistics as CSV to FILE (`-` for standard output).
    #[arg(long, value_name = "FILE")]
    pub csv: Option<PathBuf>,

    /// Write the waveform (VCD) to FILE (`-` for standard output), and a
    /// GTKWave save file FILE.gtkw preselecting core 0's scheduler signals.
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
    /// a .png or .svg (the name chooses the format).
    #[arg(long, value_name = "FILE", conflicts_with = "vcd")]
    pub timeline: Option<PathBuf>,

    /// First cycle of the timeline.
    #[arg(long, value_name = "CYCLE", requires = "timeline", default_value_t = 1)]
    pub timeline_from: u64,

    /// Last cycle of the timeline (default: 20000 cycles after the first).
    #[arg(long, value_name = "CYCLE", requires = "timeline")]
    pub timeline_to: Option<u64>,
}

/// Read and validate the machine configuration FILE
/// ([`MachineConfig::load`]: a file that is not UTF-8 is named with the line
/// and byte column of its first invalid byte).
pub fn read_config(path: &Path) -> Result<MachineConfig, CliError> {
    MachineConfig::load(path).map_err(|e| CliError::usage(e.to_string()))
}

/// The machine of `--config FILE`, else the embedded paper.toml: a file
/// that patches a base without naming itself is named as the base plus the
/// file, not as the base alone.
fn base_machine(config: Option<&Path>) -> Result<MachineConfig, CliError> {
    let Some(p) = config else {
        return Ok(MachineConfig::paper());
    };
    let mut c = read_config(p)?;
    // A file that patches a base without naming itself is named as the
    // base plus the file, not as the base alone.
    let named = std::fs::read_to_string(p)
        .ok()
        .and_then(|t| t.parse::<toml::Table>().ok())
        .is_some_and(|t| t.contains_key("name"));
    if !named {
        c.name = format!("{} + {}", c.name, p.display());
    }
    Ok(c)
}

/// The `--set` texts as overrides, in order.
pub fn parse_sets(sets: &[String]) -> Result<Vec<Override>, CliError> {
    Override::parse_sets(sets).map_err(|e| CliError::usage(e.to_string()))
}

/// The machine of `--config FILE` (else the embedded paper.toml) with the
/// `--set` overrides applied, named as run: its name followed by every
/// override ([`MachineConfig::named_with`]).
pub fn machine(config: Option<&Path>, sets: &[Override]) -> Result<MachineConfig, CliError> {
    configure(&base_machine(config)?, sets, &MachineFlags::default())
}

/// The flags that change the machine, typed; applied after `--set`.
#[derive(Clone, Debug, Default)]
pub struct MachineFlags {
    /// `--blocked-on`: named in the machine's name when it changes it.
    pub blocked_on: Option<BlockedOn>,
    /// The other flags (`--subset`, `--launch-rule`, `--ideal-memory`,
    /// `--dispatch`, `--policy`), in that order: the machine's name does
    /// not show them (the report names policy, subset, rule, memory and
    /// dispatch on lines of their own).
    pub unnamed: Vec<Override>,
}

impl MachineFlags {
    /// These flags and, when given, field `path` set to `value` (unnamed).
    pub fn with<T: Serialize>(mut self, path: &str, value: Option<T>) -> MachineFlags {
        if let Some(v) = value {
            self.unnamed.push(Override::new(path, &v));
        }
        self
    }
}

impl Inputs {
    /// The machine flags of the inputs, with `policy` (`wasp run
    /// --policy`; a bare family takes the machine's constants, as
    /// [`MachineConfig::with_overrides`] resolves it) as typed overrides.
    pub fn flags(&self, policy: Option<PolicyName>) -> MachineFlags {
        MachineFlags {
            blocked_on: self.blocked_on,
            unnamed: Vec::new(),
        }
        .with("scheduler.subset", self.subset.as_ref())
        .with("scheduler.launch_rule", self.launch_rule)
        .with("memory.ideal", self.ideal_memory.then_some(true))
        .with("raster.dispatch", self.dispatch)
        .with("scheduler.policy", policy.map(|p| p.to_string()))
    }
}

/// `base` with every override applied, once each, in order: `sets`
/// (named in the machine's name), then the flags; validated. An error
/// of a flag is the rule it breaks (a flag names no field as written).
pub fn configure(
    base: &MachineConfig,
    sets: &[Override],
    flags: &MachineFlags,
) -> Result<MachineConfig, CliError> {
    let mut cfg = base
        .with_overrides(sets)
        .map_err(|e| CliError::usage(e.to_string()))?;
    cfg.name = cfg.named_with(sets);
    let named: Vec<Override> = flags
        .blocked_on
        .filter(|b| *b != cfg.scheduler.blocked_on)
        .map(|b| Override::bare("scheduler.blocked_on", &b))
        .into_iter()
        .collect();
    let all = [&named[..], &flags.unnamed[..]].concat();
    let mut out = cfg
        .with_overrides(&all)
        .map_err(|e| CliError::usage(e.message))?;
    out.name = cfg.named_with(&named);
    Ok(out)
}

/// Load the configuration named by the inputs, with `policy` (`wasp run
/// --policy`): the one place where the inputs' overrides and flags
/// become the machine ([`configure`]).
pub fn load_config(inputs: &Inputs, policy: Option<PolicyName>) -> Result<MachineConfig, CliError> {
    let sets = parse_sets(&inputs.set)?;
    configure(
        &base_machine(inputs.config.as_deref())?,
        &sets,
        &inputs.flags(policy),
    )
}

/// Load (or generate) the trace named by the inputs, and check that it
/// has the frames `--warm` asks for.
pub fn load_trace(inputs: &Inputs, cfg: &MachineConfig) -> Result<Trace, CliError> {
    let trace = read_trace(inputs, cfg)?;
    let n = trace.frame_count();
    match inputs.warm {
        Some(k) if k >= n => Err(CliError::usage(format!(
            "--warm {k}: {} has {n} frame{}, so at most {} can run before the last",
            inputs
                .trace
                .as_ref()
                .map_or("the synthetic trace".to_string(), |p| p
                    .display()
                    .to_string()),
            if n == 1 { "" } else { "s" },
            n - 1
        ))),
        _ => Ok(trace),
    }
}

/// Read (or generate) the trace named by the inputs.
fn read_trace(inputs: &Inputs, cfg: &MachineConfig) -> Result<Trace, CliError> {
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

/// The tiles a run of `trace` with `opts` renders (its frames').
pub fn run_tiles(trace: &Trace, opts: &RunOptions) -> usize {
    opts.frames(trace).map_or(0, |f| {
        trace.tiles().len() - trace.frame_range(f.start).start
    })
}

/// A progress bar of `total` tiles on stderr (hidden when quiet or not on
/// a terminal).
pub fn progress_bar(quiet: bool, total: usize, label: &str) -> ProgressBar {
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

/// A simulation error as the CLI reports it (a bad configuration is bad
/// input).
pub fn sim_err(e: SimError) -> CliError {
    match e {
        SimError::Config(m) => CliError::usage(m),
        other => CliError::failed(other.to_string()),
    }
}

/// `FILE.gtkw` beside `FILE`.
pub fn gtkw_path(vcd: &Path) -> PathBuf {
    let mut s = vcd.as_os_str().to_owned();
    s.push(".gtkw");
    PathBuf::from(s)
}

/// The GTKWave save file written beside a `--vcd FILE` (none for
/// standard output): an output too, checked with the others.
pub fn save_file_of(vcd: Option<&Path>) -> Option<PathBuf> {
    vcd.filter(|p| !output::is_stdout(p)).map(gtkw_path)
}

/// The VCD window of `--vcd-from`/`--vcd-to`, checked.
fn vcd_window(args: &RunArgs) -> Result<Option<(u64, u64)>, CliError> {
    match (args.vcd_from, args.vcd_to) {
        (None, None) => Ok(None),
        (f, t) => {
            let (f, t) = (f.unwrap_or(0), t.unwrap_or(u64::MAX));
            if f > t {
                return Err(CliError::usage(format!(
                    "--vcd-from {f} is after --vcd-to {t}"
                )));
            }
            Ok(Some((f, t)))
        }
    }
}

/// Most cycles a timeline draws.
const TIMELINE_MAX_CYCLES: u64 = 2_000_000;

/// The timeline's window of cycles, checked with its file name.
fn timeline_window(args: &RunArgs) -> Result<Option<(u64, u64)>, CliError> {
    let Some(path) = &args.timeline else {
        return Ok(None);
    };
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
    if to - from > TIMELINE_MAX_CYCLES {
        return Err(CliError::usage(format!(
            "--timeline-from {from} --timeline-to {to}: at most {TIMELINE_MAX_CYCLES} cycles \
             can be drawn"
        )));
    }
    Ok(Some((from, to)))
}

/// Run the command.
pub fn run(args: &RunArgs) -> Result<(), CliError> {
    // The options are checked before the (possibly long) trace is read and
    // simulated.
    let gtkw = save_file_of(args.vcd.as_deref());
    output::check(
        &[
            Output::new("--json", args.json.as_deref()),
            Output::new("--csv", args.csv.as_deref()),
            Output::new("--vcd", args.vcd.as_deref()),
            Output::new("--vcd's save file", gtkw.as_deref()),
            Output::file_only("--timeline", args.timeline.as_deref()),
        ],
        &args.inputs.files(),
    )?;
    let window = vcd_window(args)?;
    let timeline = timeline_window(args)?;
    let cfg = load_config(&args.inputs, args.policy)?;
    let trace = load_trace(&args.inputs, &cfg)?;
    let opts = RunOptions {
        vcd_window: window,
        timeline,
        record_warps: false,
        warm: args.inputs.warm,
    };
    let pb = progress_bar(args.inputs.quiet, run_tiles(&trace, &opts), "simulating");
    let mut progress = |done: usize, _total: usize| pb.set_position(done as u64);
    let stats = match (&args.vcd, &args.timeline) {
        (Some(path), _) => {
            let vcd = VcdRequest {
                path,
                window,
                axis: TimeAxis::from(args.vcd_time.unwrap_or_default()),
                quiet: args.inputs.quiet,
            };
            run_with_vcd(&cfg, &trace, &opts, &vcd, &mut progress)?
        }
        (None, Some(path)) => run_with_timeline(&cfg, &trace, &opts, path, &mut progress)?,
        (None, None) => simulate(&cfg, &trace, &opts, &mut progress).map_err(sim_err)?,
    };
    pb.finish_and_clear();
    if let Some(p) = &args.json {
        emit(p, &stats.to_json())?;
    }
    if let Some(p) = &args.csv {
        emit(p, &stats.to_csv())?;
    }
    let vcd_on_stdout = output::to_stdout(&args.vcd);
    if !output::to_stdout(&args.json) && !output::to_stdout(&args.csv) && !vcd_on_stdout {
        emit(Path::new("-"), &stats.to_table())?;
    }
    Ok(())
}

/// Simulate and draw the timeline to `path`.
fn run_with_timeline(
    cfg: &MachineConfig,
    trace: &Trace,
    opts: &RunOptions,
    path: &Path,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<RunStats, CliError> {
    let (stats, timeline) = simulate_timeline(cfg, trace, opts, progress).map_err(sim_err)?;
    if timeline.samples.is_empty() {
        return Err(CliError::usage(format!(
            "--timeline-from {}: the run ended at cycle {}, before the window",
            timeline.from,
            stats.last_cycle()
        )));
    }
    crate::timeline_plot::draw(&timeline, path).map_err(CliError::failed)?;
    Ok(stats)
}

/// What `--vcd` asks for.
struct VcdRequest<'a> {
    path: &'a Path,
    window: Option<(u64, u64)>,
    axis: TimeAxis,
    quiet: bool,
}

/// Simulate with the waveform written to the VCD file (or standard
/// output) and, for a file, its GTKWave save file beside it.
fn run_with_vcd(
    cfg: &MachineConfig,
    trace: &Trace,
    opts: &RunOptions,
    vcd: &VcdRequest,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<RunStats, CliError> {
    let path = vcd.path;
    let mut sink = VcdSink::new(output::create(path)?, "wasp")
        .with_clock_mhz(cfg.gpu.frequency_mhz)
        .with_time_axis(vcd.axis);
    let scale = sink.units_per_cycle();
    let stats = simulate_traced(cfg, trace, opts, &mut sink, progress).map_err(sim_err)?;
    if let Some((from, to)) = vcd.window.filter(|w| w.0 > stats.last_cycle()) {
        // The window is known to be empty only once the run has ended.
        let to = if to == u64::MAX {
            String::new()
        } else {
            format!("={to}")
        };
        eprintln!(
            "wasp: warning: the run ended at cycle {}, before --vcd-from {from}: {} holds \
             no cycle of the window {from}..{to}",
            stats.last_cycle(),
            output::name(path)
        );
    }
    let signals = sink.signals().to_vec();
    let end = match vcd.window {
        Some((_, to)) => to.min(stats.last_cycle()) + 1,
        None => stats.last_cycle() + 1,
    };
    sink.finish(end)
        .and_then(|w| w.finish())
        .map_err(|e| CliError::failed(format!("writing {}: {e}", output::name(path))))?;
    if output::is_stdout(path) {
        if !vcd.quiet {
            eprintln!("wasp: the VCD went to standard output: no GTKWave save file is written");
        }
        return Ok(stats);
    }
    let start = vcd.window.map(|w| w.0).unwrap_or(0).saturating_mul(scale);
    let save = run_gtkw_save(
        path,
        &signals,
        cfg,
        vcd.axis,
        start,
        end.saturating_mul(scale),
    );
    let g = gtkw_path(path);
    let mut out = Vec::new();
    save.write_to(&mut out)
        .map_err(|e| CliError::failed(format!("writing {}: {e}", g.display())))?;
    emit(&g, &String::from_utf8_lossy(&out))?;
    Ok(stats)
}

/// The GTKWave save file of a run's VCD: core 0's scheduler signals, the
/// rasterizer's and core 0's, from `start` to `end` (in VCD time units).
fn run_gtkw_save(
    path: &Path,
    signals: &[SignalInfo],
    cfg: &MachineConfig,
    axis: TimeAxis,
    start: u64,
    end: u64,
) -> GtkwSave {
    let mut save = GtkwSave::new(path.display().to_string())
        .note(time_unit_note(Some(cfg.gpu.frequency_mhz), axis))
        .timestart(start)
        .window_size(1400, 700)
        .signals_width(320)
        .zoom_to_fit(end);
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
    for group in ["raster", "core0"] {
        save = save.end_group().begin_group(group, false);
        for s in signals
            .iter()
            .filter(|s| s.path.len() == 2 && s.path[1] == group)
        {
            save = save.traced(s, Format::Decimal);
        }
    }
    save.end_group()
}
