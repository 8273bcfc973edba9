//! `wasp render`: a scene's frame as a PNG (with overlays, a heat map run
//! on the cycle model) and its trace.

use super::defs::{find_def, painter_note, scene_err};
use super::timings::{print_timings, PhaseTimes, Stopwatch};
use crate::cli_error::CliError;
use crate::output::{self, Output};
use crate::run_cmd::MachineFlags;
use crate::scenes_dir::ScenesDir;
use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::path::PathBuf;
use wasp_frontend::def::SceneDef;
use wasp_frontend::load;
use wasp_frontend::raster::{DrawOrder, Frame};
use wasp_frontend::render::{self, HeatStat, Overlay, RenderRequest, WarpValue};
use wasp_frontend::texture::FormatChoice;
use wasp_rtl::policy::PolicyName;
use wasp_rtl::subset::SubsetSpec;
use wasp_sim::config::{MachineConfig, TextureCache};
use wasp_sim::run::{simulate_recording, RunOptions, WarpRecord};
use wasp_sim::stats::RunStats;

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
    /// `texture_format`, etc2 for every shipped scene; see
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

/// Largest frame side in pixels, as the scene definitions' width and height.
const MAX_SIDE: u64 = 16384;

/// The frame size `s` (WxH), each side in 1..=[`MAX_SIDE`].
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
    let base = match &args.config {
        Some(p) => crate::run_cmd::read_config(p)?,
        None => MachineConfig::paper(),
    };
    let config = crate::run_cmd::configure(&base, &[], &machine_flags(args))?;
    Ok(RenderJob {
        def,
        width,
        height,
        crop,
        config,
    })
}

/// The flags of `wasp render` that change the machine, typed: the heat
/// map's run holds in its texture caches what the trace lists, under its
/// policy and subset.
fn machine_flags(args: &RenderArgs) -> MachineFlags {
    MachineFlags::default()
        .with("memory.texture_cache", args.texture_cache)
        .with("scheduler.subset", args.subset.as_ref())
        .with("scheduler.policy", args.policy.map(|p| p.to_string()))
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
pub fn write_trace(
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
