//! One run from configuration and trace to report: the GPU ([`crate::gpu`])
//! clocked to the end by the one run loop ([`run`]), its counters made
//! into [`RunStats`] ([`RunStats::collect`]). The GPU itself knows nothing
//! of the report, so the dependencies point one way: run -> stats -> gpu.
//!
//! A trace of several frames runs them in order on one GPU, caches and
//! DRAM carrying over (see [`crate::gpu`]); the report is that of the
//! last frame run, with a record of every frame run
//! ([`RunStats::frames`]). [`RunOptions::warm`] runs only the last frame
//! and the K frames before it.

use crate::config::MachineConfig;
use crate::gpu::{CoreModel, Gpu, ShaderCore};
pub use crate::gpu::{SimError, WarpRecord};
use crate::stats::{FrameRecord, RunStats};
use crate::timeline::Timeline;
use crate::trace::Trace;
use wasp_waves::{CycleSink, NullTracer};

/// What one run records beyond its statistics, and which frames of the
/// trace it runs. (The machine is the configuration's alone: overrides
/// are applied where it is loaded, [`crate::config::Override`].)
#[derive(Clone, Debug, Default)]
pub struct RunOptions {
    /// Sample the waveform only in `from..=to`.
    pub vcd_window: Option<(u64, u64)>,
    /// Record every warp (see [`WarpRecord`]).
    pub record_warps: bool,
    /// Record a [`Timeline`] of the cycles `from..=to`.
    pub timeline: Option<(u64, u64)>,
    /// Of a trace of several frames, run the last frame after this many
    /// earlier ones (`wasp run --warm K`: frames n-1-K to n-1); `None`:
    /// every frame. The report is the last frame's either way.
    pub warm: Option<usize>,
}

impl RunOptions {
    /// The frames of `trace` a run covers: the last one and
    /// [`warm`](Self::warm) before it (all of them without), or an error
    /// when the trace has fewer.
    pub fn frames(&self, trace: &Trace) -> Result<std::ops::Range<usize>, SimError> {
        let n = trace.frame_count();
        match self.warm {
            None => Ok(0..n),
            Some(k) if k < n => Ok(n - 1 - k..n),
            Some(k) => Err(SimError::Config(format!(
                "warm-up of {k} frames: the trace has {n} frame{}, so at most {} can run \
                 before the last",
                if n == 1 { "" } else { "s" },
                n - 1
            ))),
        }
    }
}

/// What one run produced.
#[derive(Debug)]
pub struct Run {
    /// The statistics.
    pub stats: RunStats,
    /// The timeline of [`RunOptions::timeline`]'s window, if asked for.
    pub timeline: Option<Timeline>,
    /// One record per warp, ordered by tile and quad, if
    /// [`RunOptions::record_warps`] asked for them.
    pub warps: Vec<WarpRecord>,
}

/// The run loop: run `trace` on `cfg` with the recordings of `opts` to the
/// end, sampling the waveform into `sink` (in
/// `opts.vcd_window`, or every cycle). `progress` is called every 4096
/// cycles and at the end with (tiles done, tiles total).
pub fn run<S: CycleSink>(
    cfg: &MachineConfig,
    trace: &Trace,
    opts: &RunOptions,
    sink: Option<&mut S>,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Run, SimError> {
    run_on::<ShaderCore, S>(cfg, trace, opts, sink, progress)
}

/// [`run`] on a GPU of cores `C` (the lockstep tests run the plain twin).
pub(crate) fn run_on<C: CoreModel, S: CycleSink>(
    cfg: &MachineConfig,
    trace: &Trace,
    opts: &RunOptions,
    mut sink: Option<&mut S>,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<Run, SimError> {
    cfg.validate().map_err(SimError::Config)?;
    let frames = opts.frames(trace)?;
    let mut gpu = Gpu::<C>::build(cfg, trace)?;
    if opts.record_warps {
        gpu.record_warps();
    }
    let window_end = opts.timeline.map(|(from, to)| {
        gpu.record_timeline(from, to);
        to
    });
    let mut timeline = None;
    let run_tiles = trace.frame_range(frames.start).start..trace.tiles().len();
    let total = run_tiles.len();
    let mut records = Vec::new();
    let mut last = None;
    for f in frames.clone() {
        // (A one-frame run needs no call: a new GPU runs every tile.)
        if frames.len() > 1 || run_tiles.start > 0 {
            gpu.start_frame(trace.frame_range(f));
        }
        while !gpu.done() {
            let next = gpu.cycle() + 1;
            let sampled = opts
                .vcd_window
                .is_none_or(|(from, to)| (from..=to).contains(&next));
            match sink.as_deref_mut() {
                Some(s) if sampled => gpu.step_traced(Some(s))?,
                _ => gpu.step()?,
            }
            if gpu.cycle().is_multiple_of(4096) {
                progress(gpu.tiles_done(), total);
            }
            if timeline.is_none() && window_end.is_some_and(|to| gpu.cycle() > to) {
                // The window is recorded; the rest of the run needs no samples.
                timeline = gpu.take_timeline();
            }
        }
        let stats = RunStats::collect_frame(cfg, trace, f, gpu.end_frame()?);
        if trace.frame_count() > 1 {
            records.push(FrameRecord::of(f, gpu.cycle() - stats.cycles, &stats));
        }
        last = Some(stats);
    }
    progress(gpu.tiles_done(), total);
    if timeline.is_none() {
        timeline = gpu.take_timeline();
    }
    let warps = gpu.take_records();
    let mut stats = last.expect("a run covers at least one frame");
    stats.frames = records;
    Ok(Run {
        stats,
        timeline,
        warps,
    })
}

/// Run `trace` on `cfg` with `opts`, no waveform.
pub fn simulate(
    cfg: &MachineConfig,
    trace: &Trace,
    opts: &RunOptions,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<RunStats, SimError> {
    Ok(run(cfg, trace, opts, None::<&mut NullTracer>, progress)?.stats)
}

/// Run `trace` on `cfg` with `opts` and return the statistics with the
/// [`Timeline`] of the window `opts.timeline` (the whole run without one).
pub fn simulate_timeline(
    cfg: &MachineConfig,
    trace: &Trace,
    opts: &RunOptions,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<(RunStats, Timeline), SimError> {
    let opts = RunOptions {
        timeline: Some(opts.timeline.unwrap_or((0, u64::MAX))),
        ..opts.clone()
    };
    let r = run(cfg, trace, &opts, None::<&mut NullTracer>, progress)?;
    Ok((r.stats, r.timeline.expect("recorded")))
}

/// Run `trace` on `cfg` with `opts` and return the statistics with one
/// record per warp (for heat maps).
pub fn simulate_recording(
    cfg: &MachineConfig,
    trace: &Trace,
    opts: &RunOptions,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<(RunStats, Vec<WarpRecord>), SimError> {
    let opts = RunOptions {
        record_warps: true,
        ..opts.clone()
    };
    let r = run(cfg, trace, &opts, None::<&mut NullTracer>, progress)?;
    Ok((r.stats, r.warps))
}

/// Run `trace` on `cfg` with `opts`, sampling the waveform into `sink`.
pub fn simulate_traced<S: CycleSink>(
    cfg: &MachineConfig,
    trace: &Trace,
    opts: &RunOptions,
    sink: &mut S,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<RunStats, SimError> {
    Ok(run(cfg, trace, opts, Some(sink), progress)?.stats)
}

#[cfg(test)]
mod frame_tests;
#[cfg(test)]
mod tests;
