//! One run from configuration and trace to report: the GPU ([`crate::gpu`])
//! clocked to the end, its counters made into [`RunStats`]
//! ([`RunStats::collect`]). The GPU itself knows nothing of the report, so
//! the dependencies point one way: run -> stats -> gpu.

use crate::config::MachineConfig;
use crate::gpu::Gpu;
pub use crate::gpu::{RunOptions, SimError, WarpRecord};
use crate::stats::RunStats;
use crate::timeline::Timeline;
use crate::trace::Trace;
use wasp_waves::{CycleSink, NullTracer};

/// Run `trace` on `cfg` with `opts`, no waveform.
pub fn simulate(
    cfg: &MachineConfig,
    trace: &Trace,
    opts: &RunOptions,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<RunStats, SimError> {
    let cfg = opts.apply(cfg)?;
    let c = Gpu::new(&cfg, trace)?.run::<NullTracer>(None, None, progress)?;
    Ok(RunStats::collect(&cfg, trace, c))
}

/// Run `trace` on `cfg` with `opts` and return the statistics with the
/// [`Timeline`] of the window `opts.timeline` (the whole run without one).
pub fn simulate_timeline(
    cfg: &MachineConfig,
    trace: &Trace,
    opts: &RunOptions,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<(RunStats, Timeline), SimError> {
    let cfg = opts.apply(cfg)?;
    let mut gpu = Gpu::new(&cfg, trace)?;
    let (from, to) = opts.timeline.unwrap_or((0, u64::MAX));
    gpu.record_timeline(from, to);
    let total = trace.tiles().len();
    while !gpu.done() {
        gpu.step()?;
        if gpu.cycle() % 4096 == 0 {
            progress(gpu.tiles_done(), total);
        }
        if gpu.cycle() > to {
            // The window is recorded; the rest of the run needs no samples.
            break;
        }
    }
    let timeline = gpu.take_timeline().expect("recording");
    while !gpu.done() {
        gpu.step()?;
        if gpu.cycle() % 4096 == 0 {
            progress(gpu.tiles_done(), total);
        }
    }
    progress(gpu.tiles_done(), total);
    Ok((RunStats::collect(&cfg, trace, gpu.finish()?), timeline))
}

/// Run `trace` on `cfg` with `opts` and return the statistics with one
/// record per warp (for heat maps).
pub fn simulate_recording(
    cfg: &MachineConfig,
    trace: &Trace,
    opts: &RunOptions,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<(RunStats, Vec<WarpRecord>), SimError> {
    let cfg = opts.apply(cfg)?;
    let mut gpu = Gpu::new(&cfg, trace)?;
    gpu.record_warps();
    let total = trace.tiles().len();
    while !gpu.done() {
        gpu.step()?;
        if gpu.cycle() % 4096 == 0 {
            progress(gpu.tiles_done(), total);
        }
    }
    progress(gpu.tiles_done(), total);
    let records = gpu.take_records();
    Ok((RunStats::collect(&cfg, trace, gpu.finish()?), records))
}

/// Run `trace` on `cfg` with `opts`, sampling the waveform into `sink`.
/// Returns the statistics and the last cycle.
pub fn simulate_traced<S: CycleSink>(
    cfg: &MachineConfig,
    trace: &Trace,
    opts: &RunOptions,
    sink: &mut S,
    progress: &mut dyn FnMut(usize, usize),
) -> Result<RunStats, SimError> {
    let cfg = opts.apply(cfg)?;
    let c = Gpu::new(&cfg, trace)?.run(Some(sink), opts.vcd_window, progress)?;
    Ok(RunStats::collect(&cfg, trace, c))
}

#[cfg(test)]
mod tests;
