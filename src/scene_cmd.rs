//! `wasp scenes`, `wasp render` and `wasp characterize`: real-game and
//! procedural scenes through the TBR front end.

use crate::run_cmd::emit;
use crate::CliError;
use clap::{Args, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::path::PathBuf;
use wasp_frontend::characterize::{self, Characterization};
use wasp_frontend::def::{self, Game, SceneDef};
use wasp_frontend::raster::{DrawOrder, Frame};
use wasp_frontend::render::{self, HeatStat, Overlay, RenderRequest, WarpValue};
use wasp_frontend::{fetch, load};
use wasp_rtl::policy::PolicySpec;
use wasp_rtl::subset::SubsetSpec;
use wasp_sim::config::MachineConfig;
use wasp_sim::run::{simulate_recording, RunOptions, WarpRecord};
use wasp_sim::stats::RunStats;

/// Options of `wasp scenes`.
#[derive(Args, Debug, Clone)]
pub struct ScenesArgs {
    #[command(subcommand)]
    pub command: ScenesCommand,
}

/// `wasp scenes list|fetch`.
#[derive(Subcommand, Debug, Clone)]
pub enum ScenesCommand {
    /// List the scene definitions (built in, plus --scenes-dir) and whether their game
    /// data is in the cache.
    List,
    /// Download a game's Debian packages (apt-get download) and unpack
    /// them (dpkg-deb) into the scene cache: $WASP_SCENES, else
    /// $XDG_CACHE_HOME/wasp/scenes, else ~/.cache/wasp/scenes.
    Fetch(FetchArgs),
}

/// Options of `wasp scenes fetch`.
#[derive(Args, Debug, Clone)]
pub struct FetchArgs {
    /// Games: supertuxkart, openarena, teeworlds, frozen-bubble.
    #[arg(value_name = "GAME", required_unless_present = "all")]
    pub games: Vec<String>,
    /// Every game.
    #[arg(long, conflicts_with = "games")]
    pub all: bool,
}

/// Options of `wasp render`.
#[derive(Args, Debug, Clone)]
pub struct RenderArgs {
    /// Scene name (see `wasp scenes list`) or a scene definition file.
    #[arg(value_name = "SCENE")]
    pub scene: String,
    /// Write the picture as PNG to FILE.
    #[arg(long, value_name = "FILE")]
    pub png: Option<PathBuf>,
    /// Overlay, repeatable: grid, subset or subset:SUBSET (default mesh4),
    /// heat[:latency|cycles|launch] (runs the cycle model on the frame).
    #[arg(long, value_name = "OVERLAY")]
    pub overlay: Vec<Overlay>,
    /// Save the frame's trace (for `wasp run --trace FILE`).
    #[arg(long, value_name = "FILE")]
    pub trace_out: Option<PathBuf>,
    /// Machine configuration (TOML) for the tile size and heat-map runs;
    /// default: the embedded configs/paper.toml.
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// Launch policy of the heat-map run (overrides scheduler.policy).
    #[arg(long, value_name = "POLICY")]
    pub policy: Option<PolicySpec>,
    /// Priority subset of the heat-map run (overrides scheduler.subset).
    #[arg(long, value_name = "SUBSET")]
    pub subset: Option<SubsetSpec>,
    /// Frame size WxH instead of the scene's.
    #[arg(long, value_name = "WxH")]
    pub size: Option<String>,
    /// Write only this rectangle of the picture to the PNG: X,Y,W,H in
    /// pixels (to look closely at a few tiles).
    #[arg(long, value_name = "X,Y,W,H")]
    pub crop: Option<String>,
    /// Hidden-surface removal: a per-tile depth pre-pass over the opaque
    /// triangles, so only visible opaque fragments are shaded (a tile-based
    /// deferred renderer). Default: plain early-Z in submission order.
    #[arg(long)]
    pub depth_prepass: bool,
    /// Order of the opaque geometry: as-loaded, front-to-back-object or
    /// front-to-back-draw (default: the scene definition's `draw_order`,
    /// as-loaded for every shipped scene). A 2D scene is drawn in
    /// painter's order whatever this says.
    #[arg(long, value_name = "ORDER")]
    pub draw_order: Option<DrawOrder>,
    /// Print where the time went: loading the scene (parsing meshes,
    /// decoding textures) and the front end (mip chains, geometry and
    /// binning, raster + early-Z + texturing + shading + trace), wall-clock
    /// and CPU seconds. Needs no --png or --trace-out.
    #[arg(long)]
    pub timings: bool,
    /// Worker threads of the front end (0: one per hardware thread). The
    /// picture and the trace do not depend on it.
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub threads: usize,
    /// With --timings: load and rasterize N times and report the best
    /// (fastest) time of each phase (the frame is the same every time).
    #[arg(long, value_name = "N", default_value_t = 1, requires = "timings")]
    pub repeat: u32,
    /// No progress output on stderr (progress bars, notes of what is being
    /// done); results, warnings and errors still print.
    #[arg(long, short)]
    pub quiet: bool,
}

/// Options of `wasp characterize`.
#[derive(Args, Debug, Clone)]
pub struct CharacterizeArgs {
    /// Scenes (names or definition files); default: every scene whose data
    /// is in the cache, the procedural ones included.
    #[arg(value_name = "SCENE")]
    pub scenes: Vec<String>,
    /// Write the characterisation as JSON to FILE (`-`: standard output).
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// Write it as CSV to FILE (`-`: standard output).
    #[arg(long, value_name = "FILE")]
    pub csv: Option<PathBuf>,
    /// Hidden-surface removal by a depth pre-pass (see `wasp render`).
    #[arg(long)]
    pub depth_prepass: bool,
    /// Order of the opaque geometry (see `wasp render`); repeat it to
    /// characterise every scene in each order given (default: each
    /// scene's own `draw_order`).
    #[arg(long, value_name = "ORDER")]
    pub draw_order: Vec<DrawOrder>,
    /// No progress output on stderr (progress bars, notes of what is being
    /// done); results, warnings and errors still print.
    #[arg(long, short)]
    pub quiet: bool,
}

/// The note for a draw order that changes nothing on a 2D scene, if
/// `asked` is not what takes effect.
fn painter_note(scene: &str, asked: DrawOrder, took: DrawOrder) -> Option<String> {
    (asked != took).then(|| {
        format!(
            "wasp: note: {scene} is a 2D scene drawn in painter's order without a depth test \
             (its order is its picture): draw order {asked} changes nothing, it is drawn {took}"
        )
    })
}

fn parse_game(s: &str) -> Result<Game, CliError> {
    Game::ALL
        .into_iter()
        .find(|g| g.name() == s.to_ascii_lowercase())
        .ok_or_else(|| {
            let names: Vec<&str> = Game::ALL.iter().map(|g| g.name()).collect();
            CliError::usage(format!(
                "unknown game `{s}` (expected one of {})",
                names.join(", ")
            ))
        })
}

fn scene_err(e: impl std::fmt::Display) -> CliError {
    CliError::failed(e.to_string())
}

fn find_def(name: &str) -> Result<SceneDef, CliError> {
    // A name that is a path on disk but no definition file: say what it is,
    // rather than that no scene has that name.
    let p = std::path::Path::new(name);
    if p.is_dir() {
        return Err(CliError::usage(format!(
            "{name} is a directory, not a scene name or scene file (see `wasp scenes list`)"
        )));
    }
    let is_toml = p.extension().is_some_and(|x| x == "toml");
    if p.exists() && !is_toml {
        return Err(CliError::usage(format!(
            "{name} is not a scene definition: a scene file is TOML and ends in .toml \
             (see scenes/*.toml)"
        )));
    }
    if is_toml && !p.exists() {
        return Err(CliError::usage(format!("{name}: no such scene file")));
    }
    def::lookup(name).map_err(|e| CliError::usage(e.to_string()))
}

/// Run `wasp scenes`.
pub fn scenes(args: &ScenesArgs) -> Result<(), CliError> {
    match &args.command {
        ScenesCommand::List => {
            let defs = def::all().map_err(scene_err)?;
            println!(
                "{:<28} {:<14} {:<18} {:<16} {:>10}  data",
                "scene", "game", "map", "camera", "frame"
            );
            for d in &defs {
                let data = if d.game == Game::Procedural {
                    "built in".to_string()
                } else if fetch::is_fetched(d.game) {
                    "fetched".to_string()
                } else {
                    format!("not fetched (wasp scenes fetch {})", d.game)
                };
                println!(
                    "{:<28} {:<14} {:<18} {:<16} {:>10}  {data}",
                    d.name,
                    d.game.name(),
                    d.map,
                    d.camera,
                    format!("{}x{}", d.width, d.height)
                );
            }
            match def::scenes_dir() {
                Some(d) => println!(
                    "scene definitions: built in, and {} (--scenes-dir / WASP_SCENES_DIR)",
                    d.display()
                ),
                None => println!("scene definitions: built in"),
            }
            println!("scene cache: {}", fetch::cache_dir().display());
            Ok(())
        }
        ScenesCommand::Fetch(f) => {
            let games: Vec<Game> = if f.all {
                Game::ALL
                    .into_iter()
                    .filter(|g| *g != Game::Procedural)
                    .collect()
            } else {
                f.games
                    .iter()
                    .map(|g| parse_game(g))
                    .collect::<Result<_, _>>()?
            };
            for g in games {
                let root =
                    fetch::fetch(g, &mut |m| eprintln!("wasp: {g}: {m}")).map_err(scene_err)?;
                if g != Game::Procedural {
                    eprintln!("wasp: {g}: data in {}", root.display());
                }
            }
            Ok(())
        }
    }
}

/// Largest frame side in pixels, as the scene definitions' width and height.
const MAX_SIDE: u64 = 16384;

fn parse_size(s: &str) -> Result<(u32, u32), CliError> {
    let bad = || CliError::usage(format!("--size `{s}`: expected WxH, e.g. 1960x768"));
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let (w, h) = (
        w.trim().parse::<u64>().map_err(|_| bad())?,
        h.trim().parse::<u64>().map_err(|_| bad())?,
    );
    for (side, v) in [("width", w), ("height", h)] {
        if v == 0 || v > MAX_SIDE {
            return Err(CliError::usage(format!(
                "--size `{s}`: the {side} is {v} pixels; each side must be in 1..={MAX_SIDE}"
            )));
        }
    }
    Ok((w as u32, h as u32))
}

/// Run `wasp render`.
pub fn render(args: &RenderArgs) -> Result<(), CliError> {
    if args.png.is_none() && args.trace_out.is_none() && !args.timings {
        return Err(CliError::usage(
            "nothing to write: give --png FILE and/or --trace-out FILE (or --timings)",
        ));
    }
    if args.repeat == 0 {
        return Err(CliError::usage("--repeat 0: expected at least 1"));
    }
    let mut d = find_def(&args.scene)?;
    d.draw_order = args.draw_order.unwrap_or(d.draw_order);
    let (w, h) = match &args.size {
        Some(s) => parse_size(s)?,
        None => (d.width, d.height),
    };
    // Check the crop against the frame before spending time on rendering.
    let crop_rect = match &args.crop {
        Some(c) => Some(parse_crop(c, w, h)?),
        None => None,
    };
    let config = match &args.config {
        Some(p) => crate::run_cmd::read_config(p)?,
        None => MachineConfig::paper(),
    };
    let mut best = PhaseTimes::default();
    let clock = Stopwatch::start();
    let mut scene = load::load_scene(&d).map_err(scene_err)?;
    best.load = clock.lap();
    let req = RenderRequest {
        overlays: args.overlay.clone(),
        tile: config.gpu.tile_size,
        depth_prepass: args.depth_prepass,
        threads: args.threads,
        draw_order: d.draw_order,
    };
    let run = RunOptions {
        policy: args.policy,
        subset: args.subset.clone(),
        record_warps: true,
        ..RunOptions::default()
    };
    let pb = if args.quiet || !std::io::stderr().is_terminal() {
        ProgressBar::hidden()
    } else {
        let pb = ProgressBar::with_draw_target(Some(1), ProgressDrawTarget::stderr());
        pb.set_style(
            ProgressStyle::with_template("{prefix:>14} [{bar:40}] {pos}/{len} tiles {elapsed}")
                .expect("valid template")
                .progress_chars("=> "),
        );
        pb.set_prefix("heat-map run");
        pb
    };
    // A heat overlay runs the cycle model once on the frame's trace; its
    // warp records give every heat statistic.
    let mut heat_run: Option<(RunStats, Vec<WarpRecord>)> = None;
    let mut heat = |frame: &Frame, stat: HeatStat| -> Result<Vec<WarpValue>, String> {
        if heat_run.is_none() {
            let mut progress = |done: usize, total: usize| {
                pb.set_length(total as u64);
                pb.set_position(done as u64);
            };
            heat_run = Some(
                simulate_recording(&config, &frame.trace, &run, &mut progress)
                    .map_err(|e| e.to_string())?,
            );
        }
        let (_, records) = heat_run.as_ref().expect("run");
        Ok(crate::heat::warp_values(records, stat))
    };
    let clock = Stopwatch::start();
    let mut out = render::render(&scene, w, h, &req, &mut heat).map_err(scene_err)?;
    best.render = clock.lap();
    best.raster = out.frame.timings;
    for _ in 1..args.repeat {
        // The same work again; results are deterministic, times are not.
        let clock = Stopwatch::start();
        scene = load::load_scene(&d).map_err(scene_err)?;
        best.load = best.load.min(clock.lap());
        let clock = Stopwatch::start();
        out = render::render(&scene, w, h, &req, &mut heat).map_err(scene_err)?;
        best.render = best.render.min(clock.lap());
        let t = &out.frame.timings;
        best.raster.textures = best.raster.textures.min(t.textures);
        best.raster.geometry = best.raster.geometry.min(t.geometry);
        best.raster.tiles = best.raster.tiles.min(t.tiles);
    }
    pb.finish_and_clear();
    let s = &out.frame.stats;
    if let Some(n) = painter_note(&d.name, d.draw_order, s.draw_order) {
        eprintln!("{n}");
    }
    eprintln!(
        "wasp: {} {}x{} ({}): {} triangles ({} clipped), {} warps (one per fragment) at {} quad \
         positions ({:.2} per position) over {} tiles, {} quads rejected by early-Z; front end \
         {:.3} s",
        scene.name,
        w,
        h,
        s.draw_order,
        s.primitives,
        s.clipped,
        s.warps,
        s.positions,
        s.warps as f64 / s.positions.max(1) as f64,
        s.tiles,
        s.quads_rejected_early_z,
        out.raster_seconds
    );
    if let Some((run, _)) = &heat_run {
        eprintln!("wasp: heat-map run ({}): {} cycles", run.policy, run.cycles);
    }
    if let Some((lo, hi)) = out.heat_range {
        eprintln!("wasp: heat map range {lo:.1} to {hi:.1}");
    }
    let clock = Stopwatch::start();
    if let Some(p) = &args.png {
        let (img, cw, ch) = match crop_rect {
            Some(r) => crop(&out.image, w, r),
            None => (out.image.clone(), w, h),
        };
        render::write_png(p, &img, cw, ch).map_err(scene_err)?;
        eprintln!("wasp: wrote {}", p.display());
    }
    best.png = clock.lap();
    if let Some(p) = &args.trace_out {
        let file = std::fs::File::create(p)
            .map_err(|e| CliError::failed(format!("cannot create {}: {e}", p.display())))?;
        out.frame
            .trace
            .write(std::io::BufWriter::new(file))
            .map_err(|e| CliError::failed(format!("writing {}: {e}", p.display())))?;
        eprintln!(
            "wasp: wrote {} (run it with `wasp run --trace {}`)",
            p.display(),
            p.display()
        );
    }
    best.trace = clock.lap();
    if args.timings {
        if args.png.is_none() {
            best.png.wall = 0.0;
        }
        if args.trace_out.is_none() {
            best.trace.wall = 0.0;
        }
        print_timings(&scene.name, w, h, args.repeat, &best);
    }
    Ok(())
}

/// Wall-clock and CPU seconds (CPU: of the whole process, all threads).
#[derive(Clone, Copy, Debug, Default)]
struct Times {
    wall: f64,
    cpu: Option<f64>,
}

impl Times {
    /// The better of two measurements: the one with less wall time.
    fn min(self, o: Times) -> Times {
        if o.wall < self.wall {
            o
        } else {
            self
        }
    }
}

struct Stopwatch {
    start: std::time::Instant,
    cpu: Option<f64>,
}

impl Stopwatch {
    fn start() -> Stopwatch {
        Stopwatch {
            start: std::time::Instant::now(),
            cpu: process_cpu_seconds(),
        }
    }

    /// Time since the start.
    fn lap(&self) -> Times {
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
struct PhaseTimes {
    load: Times,
    render: Times,
    raster: wasp_frontend::raster::RasterTimings,
    png: Times,
    trace: Times,
}

fn print_timings(scene: &str, w: u32, h: u32, repeat: u32, t: &PhaseTimes) {
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

/// A rectangle of the picture: left, top, width, height in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Rect {
    x: u32,
    y: u32,
    w: u32,
    h: u32,
}

/// The rectangle `spec` (X,Y,W,H) of a `w` x `h` frame, checked to lie
/// inside it.
fn parse_crop(spec: &str, w: u32, h: u32) -> Result<Rect, CliError> {
    let bad = |why: String| CliError::usage(format!("--crop `{spec}`: {why}"));
    let v: Vec<u32> = spec
        .split(',')
        .map(|t| t.trim().parse::<u32>())
        .collect::<Result<_, _>>()
        .map_err(|_| bad("expected X,Y,W,H: four whole numbers of pixels".into()))?;
    let [x, y, cw, ch] = v[..] else {
        return Err(bad(format!(
            "expected X,Y,W,H: four numbers, not {}",
            v.len()
        )));
    };
    if cw == 0 || ch == 0 {
        return Err(bad("the width and height must be at least 1".into()));
    }
    if x.checked_add(cw).is_none_or(|e| e > w) || y.checked_add(ch).is_none_or(|e| e > h) {
        return Err(bad(format!(
            "pixels {x}..{} x {y}..{} reach outside the {w}x{h} frame",
            x as u64 + cw as u64,
            y as u64 + ch as u64
        )));
    }
    Ok(Rect { x, y, w: cw, h: ch })
}

/// The rectangle `r` of an RGBA picture `w` pixels wide.
fn crop(img: &[u8], w: u32, r: Rect) -> (Vec<u8>, u32, u32) {
    let mut out = Vec::with_capacity(r.w as usize * r.h as usize * 4);
    for row in r.y..r.y + r.h {
        let s = (row as usize * w as usize + r.x as usize) * 4;
        out.extend_from_slice(&img[s..s + r.w as usize * 4]);
    }
    (out, r.w, r.h)
}

/// Run `wasp characterize`.
pub fn characterize(args: &CharacterizeArgs) -> Result<(), CliError> {
    let defs: Vec<SceneDef> = if args.scenes.is_empty() {
        let all = def::all().map_err(scene_err)?;
        let (have, missing): (Vec<_>, Vec<_>) =
            all.into_iter().partition(|d| fetch::is_fetched(d.game));
        if !missing.is_empty() {
            let names: Vec<&str> = missing.iter().map(|d| d.name.as_str()).collect();
            eprintln!(
                "wasp: skipping scenes without fetched data ({}); see `wasp scenes list`",
                names.join(", ")
            );
        }
        have
    } else {
        args.scenes
            .iter()
            .map(|s| find_def(s))
            .collect::<Result<_, _>>()?
    };
    // Each scene in each order asked for (none: its own), scene by scene.
    let defs: Vec<SceneDef> = defs
        .into_iter()
        .flat_map(|d| {
            let orders = match args.draw_order.is_empty() {
                true => vec![d.draw_order],
                false => args.draw_order.clone(),
            };
            orders.into_iter().map(move |o| SceneDef {
                draw_order: o,
                ..d.clone()
            })
        })
        .collect();
    let mut rows: Vec<Characterization> = Vec::new();
    let mut failed = Vec::new();
    for (i, d) in defs.iter().enumerate() {
        if !args.quiet {
            let order = match args.draw_order.is_empty() {
                true => String::new(),
                false => format!(" in draw order {}", d.draw_order),
            };
            eprintln!(
                "wasp: characterising {}{order} ({} of {})",
                d.name,
                i + 1,
                defs.len()
            );
        }
        match characterize::characterize_def(d, args.depth_prepass) {
            Ok(c) => {
                if let Some(n) = painter_note(&d.name, d.draw_order, c.draw_order) {
                    if !args.quiet {
                        eprintln!("{n}");
                    }
                }
                rows.push(c)
            }
            Err(e) => {
                eprintln!("wasp: {} ({}): {e}", d.name, d.draw_order);
                failed.push(format!("{} ({})", d.name, d.draw_order));
            }
        }
    }
    if rows.is_empty() {
        return Err(CliError::failed("no scene could be characterised"));
    }
    let to_stdout = |p: &Option<PathBuf>| p.as_ref().is_some_and(|p| p.as_os_str() == "-");
    if !to_stdout(&args.json) && !to_stdout(&args.csv) {
        println!(
            "Workload characterisation (ours: the scenes named in each column; paper: ten \
             Android games on TEAPOT)"
        );
        print!("{}", characterize::table(&rows));
    }
    if let Some(p) = &args.json {
        let text = serde_json::to_string_pretty(&rows)
            .map_err(|e| CliError::failed(format!("encoding JSON: {e}")))?
            + "\n";
        emit(p, &text)?;
    }
    if let Some(p) = &args.csv {
        emit(p, &characterize::csv(&rows))?;
    }
    if !failed.is_empty() {
        return Err(CliError::failed(format!(
            "could not characterise: {}",
            failed.join(", ")
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crops_are_checked_against_the_frame() {
        assert_eq!(
            parse_crop("1, 2,3,4", 4, 6).unwrap(),
            Rect {
                x: 1,
                y: 2,
                w: 3,
                h: 4
            }
        );
        for bad in ["1,2,4,4", "0,0,0,1", "1,2,3", "x,0,1,1", "0,4294967295,1,1"] {
            let e = parse_crop(bad, 4, 6).unwrap_err().to_string();
            assert!(e.starts_with(&format!("--crop `{bad}`: ")), "{e}");
        }
        // A 2x2 RGBA picture: its right column.
        let img: Vec<u8> = (0..16).collect();
        let r = Rect {
            x: 1,
            y: 0,
            w: 1,
            h: 2,
        };
        assert_eq!(crop(&img, 2, r), (vec![4, 5, 6, 7, 12, 13, 14, 15], 1, 2));
    }

    #[test]
    fn sizes_name_the_side_out_of_range() {
        assert_eq!(parse_size("16384x1").unwrap(), (16384, 1));
        let e = parse_size("1x65536").unwrap_err().to_string();
        assert!(
            e.contains("the height is 65536 pixels") && e.contains("1..=16384"),
            "{e}"
        );
        let e = parse_size("99999999999x1").unwrap_err().to_string();
        assert!(e.contains("the width is 99999999999"), "{e}");
    }
}
