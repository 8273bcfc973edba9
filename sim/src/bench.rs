//! `wasp bench`: simulation speed in simulated core-cycles per second.
//!
//! Measured, never asserted: the numbers go to the README. Each point runs
//! the same simulation several times and keeps the fastest (least
//! disturbed) run. Modes:
//! - `off`: the hook-free clock path (`Gpu::step`), what `wasp run` uses
//!   without `--vcd`;
//! - `hooks`: the traced clock path with no sink (the hook compiled in,
//!   tracing off), to price the hook itself;
//! - `visitor`: every signal visited each cycle into a tracer that drops
//!   them (the cost of the visitor);
//! - `vcd`: every signal written to a VCD (into a byte sink).

use crate::config::MachineConfig;
use crate::gpu::{Gpu, RunOptions, SimError};
use crate::synth::{generate, GenParams};
use crate::trace::Trace;
use serde::Serialize;
use std::time::Instant;
use wasp_waves::{NullTracer, VcdSink};

/// How the clock is driven.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Mode {
    /// No tracing code at all.
    Off,
    /// Tracing hook compiled in, no sink.
    Hooks,
    /// Visitor into a tracer that drops everything.
    Visitor,
    /// Full VCD output into a byte sink.
    Vcd,
}

/// One measurement.
#[derive(Clone, Debug, Serialize)]
pub struct Point {
    /// What varied.
    pub label: String,
    /// Mode.
    pub mode: Mode,
    /// Tiles in the workload.
    pub tiles: usize,
    /// Warp slots per core.
    pub max_warps: u32,
    /// Simulated GPU cycles.
    pub cycles: u64,
    /// Simulated core-cycles (cycles x cores).
    pub core_cycles: u64,
    /// Best wall time in seconds.
    pub seconds: f64,
    /// Core-cycles per second.
    pub core_cycles_per_second: f64,
}

fn time_run(
    cfg: &MachineConfig,
    trace: &Trace,
    mode: Mode,
    repeats: usize,
) -> Result<(u64, f64), SimError> {
    let mut best = f64::INFINITY;
    let mut cycles = 0;
    for _ in 0..repeats.max(1) {
        let mut gpu = Gpu::new(cfg, trace)?;
        let start = Instant::now();
        match mode {
            Mode::Off => {
                while !gpu.done() {
                    gpu.step()?;
                }
            }
            Mode::Hooks => {
                while !gpu.done() {
                    gpu.step_traced::<NullTracer>(None)?;
                }
            }
            Mode::Visitor => {
                let mut t = NullTracer;
                while !gpu.done() {
                    gpu.step_traced(Some(&mut t))?;
                }
            }
            Mode::Vcd => {
                let mut sink = VcdSink::new(std::io::sink(), "wasp");
                while !gpu.done() {
                    gpu.step_traced(Some(&mut sink))?;
                }
                sink.end_cycle().ok();
            }
        }
        let dt = start.elapsed().as_secs_f64();
        best = best.min(dt);
        cycles = gpu.cycle();
    }
    Ok((cycles, best))
}

/// A synthetic workload of `tiles_x` x `tiles_y` full tiles.
pub fn workload(cfg: &MachineConfig, tiles_x: u32, tiles_y: u32) -> Result<Trace, SimError> {
    generate(&GenParams {
        frame_w: tiles_x * cfg.gpu.tile_size,
        frame_h: tiles_y * cfg.gpu.tile_size,
        tile: cfg.gpu.tile_size,
        seed: cfg.sim.seed,
        ..GenParams::default()
    })
    .map_err(|e| SimError::Config(e.to_string()))
}

/// The whole benchmark: tracing modes on one workload, then growth with
/// tile count and warp count (tracing off). `scale` multiplies the
/// workload sizes (1 = the default sizes).
pub fn run(
    cfg: &MachineConfig,
    scale: u32,
    repeats: usize,
    trace: Option<&Trace>,
    report: &mut dyn FnMut(&Point),
) -> Result<Vec<Point>, SimError> {
    let cfg = RunOptions::default().apply(cfg)?;
    let cores = cfg.gpu.cores as u64;
    let mut points = Vec::new();
    let mut push = |p: Point, points: &mut Vec<Point>| {
        report(&p);
        points.push(p);
    };
    let s = scale.max(1);
    let generated;
    let base = match trace {
        Some(t) => t,
        None => {
            generated = workload(&cfg, 8 * s, 4)?;
            &generated
        }
    };
    for mode in [Mode::Off, Mode::Hooks, Mode::Visitor, Mode::Vcd] {
        let (cycles, secs) = time_run(&cfg, base, mode, repeats)?;
        push(
            Point {
                label: "tracing".into(),
                mode,
                tiles: base.tiles().len(),
                max_warps: cfg.core.max_warps,
                cycles,
                core_cycles: cycles * cores,
                seconds: secs,
                core_cycles_per_second: (cycles * cores) as f64 / secs,
            },
            &mut points,
        );
    }
    for (tx, ty) in [(2 * s, 2), (4 * s, 4), (8 * s, 8)] {
        let t = workload(&cfg, tx, ty)?;
        let (cycles, secs) = time_run(&cfg, &t, Mode::Off, repeats)?;
        push(
            Point {
                label: "tiles".into(),
                mode: Mode::Off,
                tiles: t.tiles().len(),
                max_warps: cfg.core.max_warps,
                cycles,
                core_cycles: cycles * cores,
                seconds: secs,
                core_cycles_per_second: (cycles * cores) as f64 / secs,
            },
            &mut points,
        );
    }
    for warps in [32u32, 64, 128] {
        let mut c = cfg.clone();
        c.core.max_warps = warps;
        c.validate().map_err(SimError::Config)?;
        let (cycles, secs) = time_run(&c, base, Mode::Off, repeats)?;
        push(
            Point {
                label: "warps".into(),
                mode: Mode::Off,
                tiles: base.tiles().len(),
                max_warps: warps,
                cycles,
                core_cycles: cycles * cores,
                seconds: secs,
                core_cycles_per_second: (cycles * cores) as f64 / secs,
            },
            &mut points,
        );
    }
    Ok(points)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_mode_simulates_the_same_cycles() {
        let cfg = MachineConfig::paper();
        let t = workload(&cfg, 2, 1).unwrap();
        let mut cycles = Vec::new();
        for mode in [Mode::Off, Mode::Hooks, Mode::Visitor, Mode::Vcd] {
            cycles.push(time_run(&cfg, &t, mode, 1).unwrap().0);
        }
        assert!(
            cycles.iter().all(|&c| c == cycles[0] && c > 0),
            "{cycles:?}"
        );
    }
}
