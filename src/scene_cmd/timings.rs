//! The phase timings of `wasp render --timings`: wall-clock and CPU
//! seconds of loading, rasterizing and writing, and their report.

/// Wall-clock and CPU seconds (CPU: of the whole process, all threads).
#[derive(Clone, Copy, Debug, Default)]
pub struct Times {
    pub wall: f64,
    pub cpu: Option<f64>,
}

impl Times {
    /// The better of two measurements: the one with less wall time.
    pub fn min(self, o: Times) -> Times {
        if o.wall < self.wall {
            o
        } else {
            self
        }
    }
}

/// A clock started at a point: wall-clock time and the process's CPU
/// seconds then.
pub struct Stopwatch {
    start: std::time::Instant,
    cpu: Option<f64>,
}

impl Stopwatch {
    /// A stopwatch started now.
    pub fn start() -> Stopwatch {
        Stopwatch {
            start: std::time::Instant::now(),
            cpu: process_cpu_seconds(),
        }
    }

    /// Time since the start.
    pub fn lap(&self) -> Times {
        let cpu_now = process_cpu_seconds();
        Times {
            wall: self.start.elapsed().as_secs_f64(),
            cpu: self.cpu.zip(cpu_now).map(|(a, b)| (b - a).max(0.0)),
        }
    }
}

/// User + system CPU seconds of this process (all threads), from
/// /proc/self/stat (Linux; None elsewhere). Clock ticks of 1/100 s, the
/// Linux USER_HZ.
fn process_cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // Fields after the command name (which may hold blanks) in parentheses:
    // state is the 1st, utime the 12th, stime the 13th.
    let after = stat.rsplit_once(')')?.1;
    let f: Vec<&str> = after.split_whitespace().collect();
    let tick = |i: usize| f.get(i)?.parse::<f64>().ok();
    Some((tick(11)? + tick(12)?) / 100.0)
}

/// The best times of `wasp render --timings`.
#[derive(Clone, Copy, Debug, Default)]
pub struct PhaseTimes {
    pub load: Times,
    pub render: Times,
    pub raster: wasp_frontend::raster::RasterTimings,
    pub png: Times,
    pub trace: Times,
}

/// Print the front-end timings of `scene` at `w` x `h`, best of `repeat`
/// runs.
pub fn print_timings(scene: &str, w: u32, h: u32, repeat: u32, t: &PhaseTimes) {
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let cpu = |x: Times| x.cpu.map_or(String::new(), |c| format!("  (CPU {c:.3} s)"));
    let of = if repeat > 1 {
        format!("best of {repeat}")
    } else {
        "one run".to_string()
    };
    let line = |what: &str, secs: f64, extra: String| {
        println!("  {what:<48} {secs:>7.3} s{extra}");
    };
    println!("front-end timings of {scene} at {w}x{h} ({of}; {threads} hardware threads):");
    line(
        "load: parse meshes, decode textures",
        t.load.wall,
        cpu(t.load),
    );
    line("raster + texture", t.raster.total(), String::new());
    line(
        "  mip chains and texture heap",
        t.raster.textures,
        String::new(),
    );
    line(
        "  geometry, clipping, binning",
        t.raster.geometry,
        String::new(),
    );
    line(
        "  tiles: raster, early-Z, texture, shade, trace",
        t.raster.tiles,
        String::new(),
    );
    line(
        "render call (raster + texture and overlays)",
        t.render.wall,
        cpu(t.render),
    );
    if t.png.wall > 0.0 {
        line("PNG encode and write", t.png.wall, String::new());
    }
    if t.trace.wall > 0.0 {
        line("trace write", t.trace.wall, String::new());
    }
    println!("  (wall-clock seconds; CPU: the whole process, all threads)");
}
