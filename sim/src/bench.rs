//! `wasp bench`: simulation speed in simulated core-cycles per second.
//!
//! Measured, never asserted: the numbers go to docs/speed.md. A *sample* of a
//! point simulates its workload from reset as many whole times as it takes
//! to fill at least [`MIN_SAMPLE_SECONDS`] (every run is simulated in full;
//! nothing is reused between runs), and its rate is the core-cycles of
//! those runs over their time. Each point keeps its best of `repeats`
//! samples (the least disturbed one), by wall time and, separately, by the
//! thread's on-CPU time (Linux: `/proc/thread-self/schedstat`), which does
//! not count the time the thread waited for a CPU on a loaded machine. The
//! four tracing modes are sampled in turns (off, hooks, visitor, vcd, off,
//! ...) so that a slow spell of the machine hits them alike. Modes:
//! - `off`: the hook-free clock path (`Gpu::step`), what `wasp run` uses
//!   without `--vcd`;
//! - `hooks`: the traced clock path with no sink (the hook compiled in,
//!   tracing off), to price the hook itself;
//! - `visitor`: every signal visited each cycle into a tracer that drops
//!   them (the cost of the visitor);
//! - `vcd`: every signal written to a VCD (into a byte sink).

use crate::config::{Dispatch, MachineConfig};
use crate::gpu::{Gpu, SimError};
use crate::synth::{generate, GenParams};
use crate::trace::Trace;
use serde::Serialize;
use std::time::{Duration, Instant};
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

/// Least time one sample of a point spends simulating.
pub const MIN_SAMPLE_SECONDS: f64 = 0.5;

/// Nanoseconds this thread has spent on a CPU, where the OS tells (Linux).
fn thread_cpu_ns() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    s.split_whitespace().next()?.parse().ok()
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
    /// Wall time of one run in the best sample, in seconds.
    pub seconds: f64,
    /// Core-cycles per second of wall time, best sample.
    pub core_cycles_per_second: f64,
    /// Whole runs in each sample.
    pub runs_per_sample: u64,
    /// Samples taken (the best is kept).
    pub samples: usize,
    /// On-CPU time of one run in the best sample by that measure, in
    /// seconds (when the OS reports it).
    pub cpu_seconds: Option<f64>,
    /// Core-cycles per second of on-CPU time, best sample.
    pub core_cycles_per_cpu_second: Option<f64>,
    /// Core-cycles per second of on-CPU time (wall time where the OS does
    /// not report it), the median sample.
    pub median_core_cycles_per_second: f64,
    /// How far the samples of the point scatter: the slowest sample's time
    /// per run over the fastest's, minus 1 (by on-CPU time where the OS
    /// reports it, else wall time). On a quiet machine a few percent; a
    /// difference between two points smaller than their spread is not
    /// measured.
    pub spread: f64,
}

/// Best times of a point so far.
#[derive(Clone, Debug)]
struct Best {
    cycles: u64,
    runs: u64,
    /// Seconds per run, best sample.
    wall: f64,
    cpu: Option<f64>,
    /// Seconds per run of every sample, on-CPU where known, else wall.
    each: Vec<f64>,
    /// Wall seconds per run of every sample (what `each` becomes when a
    /// sample has no on-CPU time: the measures are never mixed).
    each_wall: Vec<f64>,
}

impl Best {
    fn point(&self, label: &str, mode: Mode, tiles: usize, max_warps: u32, cores: u64) -> Point {
        let cc = self.cycles * cores;
        let mut each = self.each.clone();
        each.sort_by(f64::total_cmp);
        let (fast, slow) = (each[0], each[each.len() - 1]);
        // The median sample's time (the mean of the middle two for an even
        // count).
        let n = each.len();
        let mid = (each[(n - 1) / 2] + each[n / 2]) / 2.0;
        Point {
            label: label.into(),
            mode,
            tiles,
            max_warps,
            cycles: self.cycles,
            core_cycles: cc,
            seconds: self.wall,
            core_cycles_per_second: cc as f64 / self.wall,
            runs_per_sample: self.runs,
            samples: self.each.len(),
            cpu_seconds: self.cpu,
            core_cycles_per_cpu_second: self.cpu.map(|c| cc as f64 / c),
            median_core_cycles_per_second: cc as f64 / mid,
            spread: slow / fast - 1.0,
        }
    }
}

/// One sample: whole runs of `trace` in `mode` until `min` has passed
/// (at least one run; `runs` fixes the count instead when given). Returns
/// the cycles of one run, the runs, and the wall and on-CPU seconds per run.
fn sample(
    cfg: &MachineConfig,
    trace: &Trace,
    mode: Mode,
    min: Duration,
    runs: Option<u64>,
) -> Result<(u64, u64, f64, Option<f64>), SimError> {
    let cpu0 = thread_cpu_ns();
    let start = Instant::now();
    let mut n = 0u64;
    let mut cycles;
    loop {
        let (c, _) = time_run(cfg, trace, mode, 1)?;
        cycles = c;
        n += 1;
        match runs {
            Some(r) if n >= r => break,
            Some(_) => {}
            None if start.elapsed() >= min => break,
            None => {}
        }
    }
    let wall = start.elapsed().as_secs_f64() / n as f64;
    let cpu = match (cpu0, thread_cpu_ns()) {
        (Some(a), Some(b)) if b > a => Some((b - a) as f64 * 1e-9 / n as f64),
        _ => None,
    };
    Ok((cycles, n, wall, cpu))
}

/// Best of `repeats` samples of each of `jobs`, sampled in turns.
fn measure(
    jobs: &[(&MachineConfig, &Trace, Mode)],
    repeats: usize,
    min: Duration,
) -> Result<Vec<Best>, SimError> {
    let mut best: Vec<Option<Best>> = vec![None; jobs.len()];
    for _ in 0..repeats.max(1) {
        for (i, &(cfg, trace, mode)) in jobs.iter().enumerate() {
            // The first sample sets the run count; later ones repeat it.
            let runs = best[i].as_ref().map(|b| b.runs);
            let (cycles, runs, wall, cpu) = sample(cfg, trace, mode, min, runs)?;
            let b = best[i].get_or_insert(Best {
                cycles,
                runs,
                wall,
                cpu,
                each: Vec::new(),
                each_wall: Vec::new(),
            });
            b.each_wall.push(wall);
            b.wall = b.wall.min(wall);
            b.cpu = match (b.cpu, cpu) {
                (Some(x), Some(y)) if b.each.len() == b.each_wall.len() - 1 => {
                    b.each.push(y);
                    Some(x.min(y))
                }
                _ => {
                    // A sample without on-CPU time: every figure of the
                    // point is by wall time.
                    b.each.clone_from(&b.each_wall);
                    None
                }
            };
        }
    }
    Ok(best.into_iter().map(|b| b.expect("sampled")).collect())
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

/// `cfg` with `raster.dispatch = d` (the raster rate must suit the mode).
fn with_dispatch(cfg: &MachineConfig, d: Dispatch) -> Result<MachineConfig, SimError> {
    let mut c = cfg.clone();
    c.raster.dispatch = d;
    c.validate().map_err(SimError::Config)?;
    Ok(c)
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

/// Both dispatch modes on the same workload, tracing off, sampled in
/// turns (the configured mode is the "tracing off" point too).
fn dispatch_points(
    cfg: &MachineConfig,
    base: &Trace,
    repeats: usize,
    min: Duration,
) -> Result<Vec<Point>, SimError> {
    let shared = with_dispatch(cfg, Dispatch::SharedTile)?;
    let per_core = with_dispatch(cfg, Dispatch::PerCoreTile)?;
    let jobs = [(&shared, base, Mode::Off), (&per_core, base, Mode::Off)];
    let cores = cfg.gpu.cores as u64;
    let b = measure(&jobs, repeats, min)?;
    Ok(b.iter()
        .zip([&shared, &per_core])
        .map(|(b, c)| {
            let label = format!("dispatch {}", c.raster.dispatch);
            b.point(
                &label,
                Mode::Off,
                base.tiles().len(),
                c.core.max_warps,
                cores,
            )
        })
        .collect())
}

/// The whole benchmark: tracing modes on one workload, then growth with
/// tile count and warp count (tracing off). `scale` multiplies the
/// workload sizes (1 = the default sizes); `min_seconds` is the least time
/// of one sample (see [`MIN_SAMPLE_SECONDS`]).
pub fn run(
    cfg: &MachineConfig,
    scale: u32,
    repeats: usize,
    min_seconds: f64,
    trace: Option<&Trace>,
    report: &mut dyn FnMut(&Point),
) -> Result<Vec<Point>, SimError> {
    let min = Duration::from_secs_f64(min_seconds.max(0.0));
    cfg.validate().map_err(SimError::Config)?;
    let cfg = cfg.clone();
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
    let modes = [Mode::Off, Mode::Hooks, Mode::Visitor, Mode::Vcd];
    let jobs: Vec<_> = modes.iter().map(|&m| (&cfg, base, m)).collect();
    for (b, &mode) in measure(&jobs, repeats, min)?.iter().zip(&modes) {
        let p = b.point(
            "tracing",
            mode,
            base.tiles().len(),
            cfg.core.max_warps,
            cores,
        );
        push(p, &mut points);
    }
    for p in dispatch_points(&cfg, base, repeats, min)? {
        push(p, &mut points);
    }
    for (tx, ty) in [(2 * s, 2), (4 * s, 4), (8 * s, 8)] {
        let t = workload(&cfg, tx, ty)?;
        let b = measure(&[(&cfg, &t, Mode::Off)], repeats, min)?.remove(0);
        let p = b.point(
            "tiles",
            Mode::Off,
            t.tiles().len(),
            cfg.core.max_warps,
            cores,
        );
        push(p, &mut points);
    }
    for warps in [32u32, 64, 128] {
        let mut c = cfg.clone();
        c.core.max_warps = warps;
        c.validate().map_err(SimError::Config)?;
        let b = measure(&[(&c, base, Mode::Off)], repeats, min)?.remove(0);
        push(
            b.point("warps", Mode::Off, base.tiles().len(), warps, cores),
            &mut points,
        );
    }
    Ok(points)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spread_and_median_come_from_every_sample() {
        // Three samples of 1, 2 and 4 seconds per run (by CPU time) of a
        // 100-cycle run on 4 cores: the median is 2 s, the slowest is 4x
        // the fastest; the best figures stay the fastest sample's.
        let b = Best {
            cycles: 100,
            runs: 1,
            wall: 1.5,
            cpu: Some(1.0),
            each: vec![4.0, 1.0, 2.0],
            each_wall: vec![4.0, 1.0, 2.0],
        };
        let p = b.point("tracing", Mode::Off, 1, 64, 4);
        assert_eq!(p.median_core_cycles_per_second, 400.0 / 2.0);
        assert_eq!(p.spread, 3.0);
        assert_eq!(p.core_cycles_per_cpu_second, Some(400.0));
        // An even count takes the mean of the middle two.
        let b = Best {
            each: vec![1.0, 3.0],
            each_wall: vec![1.0, 3.0],
            ..b
        };
        let p = b.point("tracing", Mode::Off, 1, 64, 4);
        assert_eq!(p.median_core_cycles_per_second, 200.0);
        assert_eq!(p.spread, 2.0);
    }

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

    #[test]
    fn samples_repeat_whole_runs_and_keep_the_best() {
        let cfg = MachineConfig::paper();
        let t = workload(&cfg, 1, 1).unwrap();
        let one = time_run(&cfg, &t, Mode::Off, 1).unwrap().0;
        // A fixed run count is honoured; a time floor takes at least one run.
        let (c, n, wall, _) = sample(&cfg, &t, Mode::Off, Duration::ZERO, Some(3)).unwrap();
        assert_eq!((c, n), (one, 3));
        assert!(wall > 0.0);
        let (_, n, _, _) = sample(&cfg, &t, Mode::Off, Duration::ZERO, None).unwrap();
        assert_eq!(n, 1);
        let b = measure(
            &[(&cfg, &t, Mode::Off), (&cfg, &t, Mode::Hooks)],
            2,
            Duration::from_millis(5),
        )
        .unwrap();
        for x in &b {
            assert_eq!((x.cycles, x.each.len()), (one, 2));
            assert!(x.runs >= 1 && x.wall > 0.0);
        }
        let p = b[0].point("tracing", Mode::Off, 1, 64, 4);
        assert_eq!(p.core_cycles, one * 4);
        assert_eq!(b[0].each.len(), 2);
        assert!(p.spread >= 0.0 && p.median_core_cycles_per_second > 0.0);
        assert!((p.core_cycles_per_second - (one * 4) as f64 / p.seconds).abs() < 1e-6);
    }
}
