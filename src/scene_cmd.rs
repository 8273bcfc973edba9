//! `wasp scenes`, `wasp render` and `wasp characterize`: real-game and
//! procedural scenes through the TBR front end.

use crate::cli_error::CliError;
use crate::output::{self, emit, Output};
use crate::scenes_dir::ScenesDir;
use clap::{Args, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::path::PathBuf;
use wasp_frontend::characterize::{self, Characterization};
use wasp_frontend::def::{self, Game, Route, SceneDef};
use wasp_frontend::raster::{DrawOrder, Frame};
use wasp_frontend::render::{self, HeatStat, Overlay, RenderRequest, WarpValue};
use wasp_frontend::texture::FormatChoice;
use wasp_frontend::{fetch, load};
use wasp_rtl::policy::PolicyName;
use wasp_rtl::subset::SubsetSpec;
use wasp_sim::config::{MachineConfig, TextureCache};
use wasp_sim::run::{simulate_recording, RunOptions, WarpRecord};
use wasp_sim::stats::RunStats;

/// Options of `wasp scenes`.
#[derive(Args, Debug, Clone)]
pub struct ScenesArgs {
    #[command(subcommand)]
    pub command: ScenesCommand,
    /// No progress output on stderr (as `-q` after `list` or `fetch`).
    #[arg(long, short)]
    pub quiet: bool,
}

impl ScenesArgs {
    /// The `-q` of `list` or `fetch`, set also by a `-q` before them.
    pub fn quiet_mut(&mut self) -> &mut bool {
        let before = self.quiet;
        let q = match &mut self.command {
            ScenesCommand::List(a) => &mut a.quiet,
            ScenesCommand::Fetch(a) => &mut a.quiet,
            ScenesCommand::Capture(a) => &mut a.quiet,
        };
        *q |= before;
        q
    }

    /// The `--scenes-dir` of `scenes list` and `scenes capture` (fetching
    /// reads no definition).
    pub fn scenes_dir(&self) -> Option<&ScenesDir> {
        match &self.command {
            ScenesCommand::List(a) => Some(&a.scene_defs),
            ScenesCommand::Capture(a) => Some(&a.scene_defs),
            ScenesCommand::Fetch(_) => None,
        }
    }
}

/// `wasp scenes list|fetch`.
#[derive(Subcommand, Debug, Clone)]
pub enum ScenesCommand {
    /// List the scene definitions (built in, plus --scenes-dir) and whether their game
    /// data is in the cache.
    List(ListArgs),
    /// Download a game's Debian packages (apt-get download) and unpack
    /// them (dpkg-deb) into the scene cache: $WASP_SCENES, else
    /// $XDG_CACHE_HOME/wasp/scenes, else ~/.cache/wasp/scenes. Needs a
    /// Debian-family host (apt-get, dpkg-deb); all four games are about
    /// 835 MB to download and 0.9 GB unpacked.
    Fetch(FetchArgs),
    /// Run a game's own engine headless (xvfb-run) at an engine-route
    /// scene's camera and resolution under apitrace, and store the capture
    /// in the scene cache (captures/SCENE.trace, with SCENE.json beside
    /// it). Needs the game's Debian package (openarena, or teeworlds and
    /// teeworlds-server), xvfb and apitrace; installs nothing.
    Capture(crate::capture::CaptureArgs),
}

/// Options of `wasp scenes list`.
#[derive(Args, Debug, Clone)]
pub struct ListArgs {
    #[command(flatten)]
    pub scene_defs: ScenesDir,
    /// No progress output on stderr; results, warnings and errors still
    /// print. (The list shows none.)
    #[arg(long, short)]
    pub quiet: bool,
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
    /// Fetch a game again even when its data is already in the cache (by
    /// default a fetched game is skipped, saying so).
    #[arg(long)]
    pub force: bool,
    /// No progress output on stderr (what is downloaded and unpacked);
    /// errors still print.
    #[arg(long, short)]
    pub quiet: bool,
}

/// Options of `wasp render`.
#[derive(Args, Debug, Clone)]
pub struct RenderArgs {
    /// Scene name (see `wasp scenes list`) or a scene definition file.
    /// A game's data is fetched into the scene cache if it is not there.
    #[arg(value_name = "SCENE")]
    pub scene: String,
    #[command(flatten)]
    pub scene_defs: ScenesDir,
    /// Write the picture as PNG to FILE (`-` for standard output).
    #[arg(long, value_name = "FILE")]
    pub png: Option<PathBuf>,
    /// Overlay, repeatable: grid, subset or subset:SUBSET (default mesh4),
    /// heat[:latency|cycles|launch] (runs the cycle model on the frame).
    #[arg(long, value_name = "OVERLAY")]
    pub overlay: Vec<Overlay>,
    /// Save the frame's trace to FILE (`-` for standard output), for
    /// `wasp run --trace FILE`.
    #[arg(long, value_name = "FILE")]
    pub trace_out: Option<PathBuf>,
    /// Machine configuration (TOML) for the tile size and heat-map runs;
    /// default: the embedded configs/paper.toml.
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// Launch policy of the heat-map run (overrides scheduler.policy; a
    /// bare `wasp`, `wasp-m` or `freemshr` takes its constants from the
    /// machine's, as in `wasp run --policy`).
    #[arg(long, value_name = "POLICY")]
    pub policy: Option<PolicyName>,
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
    /// How the textures are stored: rgba8, etc2 (per texture: ETC2 RGB,
    /// or ETC2 RGBA where its alpha is used), etc2-rgb, etc2-rgba,
    /// astc-4x4, astc-6x6 or astc-8x8 (default: the scene definition's
    /// `texture_format`, rgba8 for every shipped scene; see
    /// docs/textures.md). It moves the blocks the trace lists, not the
    /// picture.
    #[arg(long, value_name = "FORMAT")]
    pub texture_format: Option<FormatChoice>,
    /// What the machine's texture caches hold: compressed (the trace lists
    /// the stored lines of the textures) or decompressed (it lists their
    /// decoded RGBA8 lines and maps each to the stored line holding it,
    /// for `memory.texture_cache = "decompressed"`; see docs/textures.md).
    /// Default: the --config's `memory.texture_cache`, compressed in the
    /// shipped machines. Changes nothing with rgba8 textures.
    #[arg(long, value_name = "CACHE")]
    pub texture_cache: Option<TextureCache>,
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
    #[command(flatten)]
    pub scene_defs: ScenesDir,
    /// Write the characterisation as JSON to FILE (`-` for standard
    /// output).
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// Write it as CSV to FILE (`-` for standard output).
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
    /// How the textures are stored (see `wasp render`); repeat it to
    /// characterise every scene in each format given (default: each
    /// scene's own `texture_format`).
    #[arg(long, value_name = "FORMAT")]
    pub texture_format: Vec<FormatChoice>,
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
    let d = def::lookup(name).map_err(|e| CliError::usage(e.to_string()))?;
    if d.route == Route::Engine {
        return Err(CliError::usage(format!(
            "scene {} takes the engine route (route = \"engine\"): its frame comes from the \
             game's engine, not a loader; run `wasp scenes capture {}`, then import the capture \
             with `wasp import-gl`",
            d.name, d.name
        )));
    }
    Ok(d)
}

/// Run `wasp scenes`.
pub fn scenes(args: &ScenesArgs) -> Result<(), CliError> {
    match &args.command {
        ScenesCommand::List(_) => {
            let defs = def::every().map_err(scene_err)?;
            println!(
                "{:<28} {:<14} {:<18} {:<16} {:>10}  data",
                "scene", "game", "map", "camera", "frame"
            );
            for d in &defs {
                let data = if d.route == Route::Engine {
                    let (trace, _) = crate::capture::capture_paths(&d.name);
                    if trace.is_file() {
                        "engine: captured".to_string()
                    } else {
                        format!("engine: not captured (wasp scenes capture {})", d.name)
                    }
                } else if d.game == Game::Procedural {
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
            let quiet = f.quiet;
            for g in games {
                if g != Game::Procedural && fetch::is_fetched(g) && !f.force {
                    if !quiet {
                        eprintln!(
                            "wasp: {g}: already fetched in {}; skipped (--force fetches it again)",
                            fetch::cache_dir().display()
                        );
                    }
                    continue;
                }
                let root = fetch::fetch(g, &mut |m| {
                    if !quiet {
                        eprintln!("wasp: {g}: {m}")
                    }
                })
                .map_err(scene_err)?;
                if g != Game::Procedural && !quiet {
                    eprintln!("wasp: {g}: data in {}", root.display());
                }
            }
            Ok(())
        }
        ScenesCommand::Capture(a) => crate::capture::capture(a),
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

/// What `wasp render` draws, checked before any work.
struct RenderJob {
    def: SceneDef,
    width: u32,
    height: u32,
    crop: Option<Rect>,
    config: MachineConfig,
}

/// Check the options of `wasp render` before rendering: the outputs, the
/// scene, its size and crop, the configuration.
fn render_job(args: &RenderArgs) -> Result<RenderJob, CliError> {
    if args.png.is_none() && args.trace_out.is_none() && !args.timings {
        return Err(CliError::usage(
            "nothing to write: give --png FILE and/or --trace-out FILE (or --timings)",
        ));
    }
    output::check(
        &[
            Output::new("--png", args.png.as_deref()),
            Output::new("--trace-out", args.trace_out.as_deref()),
        ],
        &[
            output::Input::file("--config", args.config.as_deref()),
            output::Input::folder(
                "--scenes-dir",
                args.scene_defs.scenes_dir.as_deref(),
                "toml",
            ),
            // A scene named by its definition file.
            output::Input::file(
                "the scene file",
                Some(std::path::Path::new(&args.scene)).filter(|p| p.is_file()),
            ),
        ],
    )?;
    if args.repeat == 0 {
        return Err(CliError::usage("--repeat 0: expected at least 1"));
    }
    let mut def = find_def(&args.scene)?;
    def.draw_order = args.draw_order.unwrap_or(def.draw_order);
    def.texture_format = args.texture_format.unwrap_or(def.texture_format);
    let (width, height) = match &args.size {
        Some(s) => parse_size(s)?,
        None => (def.width, def.height),
    };
    // Check the crop against the frame before spending time on rendering.
    let crop = match &args.crop {
        Some(c) => Some(parse_crop(c, width, height)?),
        None => None,
    };
    let mut config = match &args.config {
        Some(p) => crate::run_cmd::read_config(p)?,
        None => MachineConfig::paper(),
    };
    // The heat map's run holds in its texture caches what the trace lists.
    if let Some(c) = args.texture_cache {
        config.memory.texture_cache = c;
    }
    Ok(RenderJob {
        def,
        width,
        height,
        crop,
        config,
    })
}

/// Run `wasp render`.
pub fn render(args: &RenderArgs) -> Result<(), CliError> {
    let job = render_job(args)?;
    // A game's data is fetched when first needed, as `reproduce` does.
    crate::game_data::fetch_missing(&[job.def.game], args.quiet).map_err(CliError::failed)?;
    let req = RenderRequest {
        overlays: args.overlay.clone(),
        tile: job.config.gpu.tile_size,
        depth_prepass: args.depth_prepass,
        threads: args.threads,
        draw_order: job.def.draw_order,
        texture_format: job.def.texture_format,
        decoded_lines: job.config.memory.texture_cache == TextureCache::Decompressed,
    };
    let run = RunOptions {
        policy: args.policy.map(|p| p.resolve(job.config.scheduler.policy)),
        subset: args.subset.clone(),
        record_warps: true,
        ..RunOptions::default()
    };
    let pb = heat_progress(args.quiet);
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
                simulate_recording(&job.config, &frame.trace, &run, &mut progress)
                    .map_err(|e| e.to_string())?,
            );
        }
        let (_, records) = heat_run.as_ref().expect("run");
        Ok(crate::heat::warp_values(records, stat))
    };
    let (scene_name, out, mut best) = render_best(args, &job, &req, &mut heat)?;
    pb.finish_and_clear();
    note_frame(
        &scene_name,
        &job,
        &out,
        heat_run.as_ref().map(|(r, _)| r),
        args.quiet,
    );
    let clock = Stopwatch::start();
    if let Some(p) = &args.png {
        let (img, cw, ch) = match job.crop {
            Some(r) => crop(&out.image, job.width, r),
            None => (out.image.clone(), job.width, job.height),
        };
        let bytes = render::encode_png(&img, cw, ch).map_err(scene_err)?;
        output::write_bytes(p, &bytes)?;
        if !args.quiet {
            eprintln!("wasp: wrote {}", output::name(p));
        }
    }
    best.png = clock.lap();
    if let Some(p) = &args.trace_out {
        write_trace(p, &out.frame.trace, args.quiet)?;
    }
    best.trace = clock.lap();
    if args.timings {
        if args.png.is_none() {
            best.png.wall = 0.0;
        }
        if args.trace_out.is_none() {
            best.trace.wall = 0.0;
        }
        print_timings(&scene_name, job.width, job.height, args.repeat, &best);
    }
    Ok(())
}

/// The progress bar of a heat-map run (hidden when quiet or not on a
/// terminal).
fn heat_progress(quiet: bool) -> ProgressBar {
    if quiet || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let pb = ProgressBar::with_draw_target(Some(1), ProgressDrawTarget::stderr());
    pb.set_style(
        ProgressStyle::with_template("{prefix:>14} [{bar:40}] {pos}/{len} tiles {elapsed}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    pb.set_prefix("heat-map run");
    pb
}

/// Load and render the scene `args.repeat` times: its name, the last
/// rendering (results are deterministic) and the best time of each phase.
fn render_best(
    args: &RenderArgs,
    job: &RenderJob,
    req: &RenderRequest,
    heat: &mut render::HeatSource<'_>,
) -> Result<(String, render::Rendered, PhaseTimes), CliError> {
    let mut best = PhaseTimes::default();
    let mut out: Option<render::Rendered> = None;
    let mut name = String::new();
    for i in 0..args.repeat {
        let clock = Stopwatch::start();
        let scene = load::load_scene(&job.def).map_err(scene_err)?;
        let load = clock.lap();
        let clock = Stopwatch::start();
        let r = render::render(&scene, job.width, job.height, req, heat).map_err(scene_err)?;
        let whole = clock.lap();
        let t = &r.frame.timings;
        if i == 0 {
            (best.load, best.render, best.raster) = (load, whole, *t);
        } else {
            best.load = best.load.min(load);
            best.render = best.render.min(whole);
            best.raster.textures = best.raster.textures.min(t.textures);
            best.raster.geometry = best.raster.geometry.min(t.geometry);
            best.raster.tiles = best.raster.tiles.min(t.tiles);
        }
        name = scene.name.clone();
        out = Some(r);
    }
    Ok((name, out.expect("at least one repeat"), best))
}

/// The notes on stderr of a rendered frame: its draw order (and, where
/// the painter's order changed what it shows, a note), its counts, the
/// heat-map run and the heat range (under `quiet`, the painter's note alone).
fn note_frame(
    name: &str,
    job: &RenderJob,
    out: &render::Rendered,
    heat: Option<&RunStats>,
    quiet: bool,
) {
    let s = &out.frame.stats;
    // A draw order that changes nothing is a warning: it prints under -q.
    if let Some(n) = painter_note(&job.def.name, job.def.draw_order, s.draw_order) {
        eprintln!("{n}");
    }
    if quiet {
        return;
    }
    eprintln!(
        "wasp: {} {}x{} ({}): {} triangles ({} clipped), {} warps (one per fragment) at {} quad \
         positions ({:.2} per position) over {} tiles, {} quads rejected by early-Z; front end \
         {:.3} s",
        name,
        job.width,
        job.height,
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
    if let Some(run) = heat {
        eprintln!("wasp: heat-map run ({}): {} cycles", run.policy, run.cycles);
    }
    if let Some((lo, hi)) = out.heat_range {
        eprintln!("wasp: heat map range {lo:.1} to {hi:.1}");
    }
}

/// Write a frame's trace to FILE (or standard output); say so unless
/// `quiet`.
pub(crate) fn write_trace(
    p: &std::path::Path,
    trace: &wasp_sim::trace::Trace,
    quiet: bool,
) -> Result<(), CliError> {
    let mut w = output::create(p)?;
    trace
        .write(&mut w)
        .and_then(|_| w.finish())
        .map_err(|e| CliError::failed(format!("writing {}: {e}", output::name(p))))?;
    if quiet {
        return Ok(());
    }
    if output::is_stdout(p) {
        eprintln!("wasp: wrote the trace to standard output");
    } else {
        eprintln!(
            "wasp: wrote {} (run it with `wasp run --trace {}`)",
            p.display(),
            p.display()
        );
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

/// The scenes `wasp characterize` takes, each in every draw order asked
/// for: the named ones (their games' data fetched if missing), else every
/// scene whose data is in the cache.
fn characterize_defs(args: &CharacterizeArgs) -> Result<Vec<SceneDef>, CliError> {
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
        let named: Vec<SceneDef> = args
            .scenes
            .iter()
            .map(|s| find_def(s))
            .collect::<Result<_, _>>()?;
        let games: Vec<Game> = named.iter().map(|d| d.game).collect();
        crate::game_data::fetch_missing(&games, args.quiet).map_err(CliError::failed)?;
        named
    };
    // Each scene in each order and format asked for (none: its own),
    // scene by scene.
    Ok(defs
        .into_iter()
        .flat_map(|d| {
            let orders = match args.draw_order.is_empty() {
                true => vec![d.draw_order],
                false => args.draw_order.clone(),
            };
            let formats = match args.texture_format.is_empty() {
                true => vec![d.texture_format],
                false => args.texture_format.clone(),
            };
            orders.into_iter().flat_map(move |o| {
                let d = d.clone();
                formats.clone().into_iter().map(move |f| SceneDef {
                    draw_order: o,
                    texture_format: f,
                    ..d.clone()
                })
            })
        })
        .collect())
}

/// Run `wasp characterize`.
pub fn characterize(args: &CharacterizeArgs) -> Result<(), CliError> {
    output::check(
        &[
            Output::new("--json", args.json.as_deref()),
            Output::new("--csv", args.csv.as_deref()),
        ],
        &[output::Input::folder(
            "--scenes-dir",
            args.scene_defs.scenes_dir.as_deref(),
            "toml",
        )],
    )?;
    let defs = characterize_defs(args)?;
    let mut rows: Vec<Characterization> = Vec::new();
    let mut failed = Vec::new();
    for (i, d) in defs.iter().enumerate() {
        if !args.quiet {
            let mut order = match args.draw_order.is_empty() {
                true => String::new(),
                false => format!(" in draw order {}", d.draw_order),
            };
            if !args.texture_format.is_empty() {
                order.push_str(&format!(" with textures as {}", d.texture_format));
            }
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
                eprintln!(
                    "wasp: {} ({}, {}): {e}",
                    d.name, d.draw_order, d.texture_format
                );
                failed.push(format!(
                    "{} ({}, {})",
                    d.name, d.draw_order, d.texture_format
                ));
            }
        }
    }
    if rows.is_empty() {
        return Err(CliError::failed("no scene could be characterised"));
    }
    if !output::to_stdout(&args.json) && !output::to_stdout(&args.csv) {
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
