//! `wasp example`: the paper's worked example.

use crate::cli_error::CliError;
use crate::output::{self, emit, Output};
use crate::run_cmd::gtkw_path;
use clap::Args;
use std::path::{Path, PathBuf};
use wasp_rtl::policy::LaunchRule;
use wasp_sim::example::{self, ExampleConfig, ExampleError, ExampleReport};
use wasp_waves::{Format, GtkwSave, SignalInfo, VcdSink};

/// Options of `wasp example`.
#[derive(Args, Debug, Clone)]
pub struct ExampleArgs {
    /// Write the result as JSON to FILE (`-` for standard output, in place
    /// of the chronographs): keys `scanline`, `all_priority_first`, `wasp`,
    /// each with `cycles`, `stall_cycles`, hits and misses, the launch order
    /// and the per-cycle timeline.
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,

    /// Write the waveform of all three runs to FILE (`-` for standard
    /// output; VCD, one time unit per cycle, cycle 0 = reset) and a GTKWave
    /// save file FILE.gtkw that preselects the scheduler and cache signals:
    /// `gtkwave FILE FILE.gtkw`.
    #[arg(long, value_name = "FILE")]
    pub vcd: Option<PathBuf>,

    /// Main-memory latency in cycles (at least 1).
    #[arg(long, default_value_t = 7, value_name = "CYCLES")]
    pub latency: u32,

    /// MSHR entries of the cache (1..=31: the free-MSHR register has 5 bits).
    #[arg(long, default_value_t = 3, value_name = "N")]
    pub mshrs: u32,

    /// WaSP threshold: a priority warp launches when Real_freeMSHRs > this
    /// (0..=31 and below --mshrs). CF is 1, as each warp makes one access.
    #[arg(long, default_value_t = 1, value_name = "N")]
    pub threshold: u32,

    /// What a closed gate does when only a priority warp waits: hold
    /// (launch nothing; the paper's rule) or launch (that priority warp).
    #[arg(long, default_value_t = LaunchRule::Hold, value_name = "RULE")]
    pub launch_rule: LaunchRule,

    /// No progress output on stderr (progress bars, notes of what is being
    /// done); results, warnings and errors still print.
    /// (The example is short and shows none.)
    #[arg(long, short)]
    pub quiet: bool,
}

impl Default for ExampleArgs {
    fn default() -> Self {
        let d = ExampleConfig::default();
        Self {
            json: None,
            vcd: None,
            latency: d.latency,
            mshrs: d.mshrs,
            threshold: d.threshold,
            launch_rule: d.launch_rule,
            quiet: false,
        }
    }
}

fn map_err(e: ExampleError) -> CliError {
    match e {
        ExampleError::Config(m) => CliError::usage(m),
        other => CliError::failed(other.to_string()),
    }
}

/// Run the command.
pub fn run(args: &ExampleArgs) -> Result<(), CliError> {
    let gtkw = crate::run_cmd::save_file_of(args.vcd.as_deref());
    output::check(
        &[
            Output::new("--json", args.json.as_deref()),
            Output::new("--vcd", args.vcd.as_deref()),
            Output::new("--vcd's save file", gtkw.as_deref()),
        ],
        &[],
    )?;
    let cfg = ExampleConfig {
        latency: args.latency,
        mshrs: args.mshrs,
        threshold: args.threshold,
        launch_rule: args.launch_rule,
    };
    cfg.validate().map_err(CliError::usage)?;
    let report = match &args.vcd {
        None => example::run(&cfg).map_err(map_err)?,
        Some(path) => write_waves(&cfg, path)?,
    };
    if let Some(p) = &args.json {
        let mut s = serde_json::to_string_pretty(&report)
            .map_err(|e| CliError::failed(format!("encoding JSON: {e}")))?;
        s.push('\n');
        emit(p, &s)?;
    }
    if output::to_stdout(&args.json) || output::to_stdout(&args.vcd) {
        return Ok(());
    }
    let mut text = example::render_report(&report);
    if let Some(path) = &args.vcd {
        text.push_str(&format!(
            "Waveform: {} (open with: gtkwave {} {})\n",
            path.display(),
            path.display(),
            gtkw_path(path).display()
        ));
    }
    emit(Path::new("-"), &text)
}

fn write_waves(cfg: &ExampleConfig, path: &Path) -> Result<ExampleReport, CliError> {
    let mut sink = VcdSink::new(output::create(path)?, "wasp_example");
    let (report, last) = example::run_traced(cfg, &mut sink).map_err(map_err)?;
    let signals: Vec<SignalInfo> = sink.signals().to_vec();
    sink.finish(last + 1)
        .and_then(|w| w.finish())
        .map_err(|e| CliError::failed(format!("writing {}: {e}", output::name(path))))?;
    if output::is_stdout(path) {
        // No file to name in a save file.
        return Ok(report);
    }
    let gtkw = gtkw_path(path);
    let save = gtkw_save(path, &signals, last + 1);
    let mut g = output::create(&gtkw)?;
    save.write_to(&mut g)
        .and_then(|_| g.finish())
        .map_err(|e| CliError::failed(format!("writing {}: {e}", gtkw.display())))?;
    Ok(report)
}

/// How each example signal is best shown.
fn format_of(name: &str) -> Format {
    match name {
        "real_free_mshrs" => Format::SignedDecimal,
        _ => Format::Decimal,
    }
}

/// A save file showing every run's scheduler and cache signals, grouped.
fn gtkw_save(vcd: &Path, signals: &[SignalInfo], end: u64) -> GtkwSave {
    let mut save = GtkwSave::new(vcd.display().to_string())
        .note(wasp_waves::vcd_sink::TIME_UNIT_COMMENT)
        .zoom_to_fit(end)
        .window_size(1400, 700)
        .signals_width(300);
    // The WaSP run first: it is the one to look at; then the paper's order.
    let rank = |s: &&SignalInfo| match s.path.get(1).map(String::as_str) {
        Some("wasp") => 0,
        Some("scanline") => 1,
        _ => 2,
    };
    let mut ordered: Vec<&SignalInfo> = signals.iter().collect();
    ordered.sort_by_key(rank);
    let mut current: Option<String> = None;
    for s in ordered {
        // path = [top, run, block]
        let run = s.path.get(1).cloned().unwrap_or_default();
        if current.as_deref() != Some(run.as_str()) {
            if current.is_some() {
                save = save.end_group();
            }
            save = save.begin_group(run.clone(), false);
            current = Some(run);
        }
        save = save.traced(s, format_of(&s.name));
    }
    if current.is_some() {
        save = save.end_group();
    }
    save
}
