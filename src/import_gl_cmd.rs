//! `wasp import-gl`: one frame of an apitrace capture of a fixed-function
//! OpenGL 1.x program, drawn by wasp's own raster front end into a trace
//! (and a picture), with the import's summary (docs/import-gl.md).

use crate::cli_error::CliError;
use crate::output::{self, Input, Output};
use clap::Args;
use std::path::PathBuf;
use wasp_frontend::gl::{self, ImportOptions, Summary};
use wasp_frontend::raster::{rasterize, Frame, RasterOptions};
use wasp_frontend::render;
use wasp_frontend::texture::FormatChoice;
use wasp_sim::trace::Trace;

/// Tile edge of the imported frame (the paper's 64).
const TILE: u32 = 64;

/// Arguments of `wasp import-gl`.
#[derive(Args, Debug)]
pub struct ImportGlArgs {
    /// The apitrace capture (`apitrace trace --api gl -o FILE PROGRAM`).
    #[arg(value_name = "CAPTURE")]
    pub capture: PathBuf,
    /// The frame to import, from 0 (each ends at a buffer swap); default:
    /// the last complete frame.
    #[arg(long, value_name = "N", conflicts_with = "frames")]
    pub frame: Option<u64>,
    /// Import frames A to B (both included, from 0) into one trace of
    /// several frames, run in order by `wasp run` with caches and DRAM
    /// carrying over (`--warm K` there measures the last after K earlier).
    /// The summary, picture and Mesa check are the last frame's.
    #[arg(long, value_name = "A..B", value_parser = parse_frames)]
    pub frames: Option<FrameRange>,
    /// Save the frame's trace to FILE (`-` for standard output), for
    /// `wasp run --trace FILE`.
    #[arg(long, value_name = "FILE")]
    pub trace_out: PathBuf,
    /// Write wasp's picture of the frame as PNG to FILE (`-` for standard
    /// output).
    #[arg(long, value_name = "FILE")]
    pub png: Option<PathBuf>,
    /// Write the summary as JSON to FILE (`-` for standard output).
    #[arg(long, value_name = "FILE")]
    pub json: Option<PathBuf>,
    /// Count the draws that need what is not modelled (a shader program,
    /// display lists, texture coordinate generation, a primitive other
    /// than triangles and quads) instead of stopping at the first.
    #[arg(long)]
    pub skip_unsupported: bool,
    /// Check the frame against Mesa: glretrace replays of rewritten
    /// captures give, per pixel, the fragments written and the texture of
    /// the last one; the agreement with wasp's is printed and written to
    /// DIR (agreement.json and disagreement maps, docs/scenes.md).
    #[arg(long, value_name = "DIR")]
    pub check_mesa: Option<PathBuf>,
    /// How the textures are stored (docs/textures.md): `rgba8` (the
    /// default: the texels as the program uploaded them), `etc2` (the rule
    /// a mobile port follows: opaque textures ETC2 RGB, those whose alpha a
    /// draw reads ETC2 RGBA), or one format for every texture. An engine
    /// scene's frame takes its scene's `texture_format`.
    #[arg(long, value_name = "FORMAT", default_value_t = FormatChoice::Rgba8)]
    pub texture_format: FormatChoice,
    /// No progress output on stderr; results, warnings and errors still
    /// print.
    #[arg(long, short)]
    pub quiet: bool,
}

/// A range of frames, `A..B` (both included).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameRange {
    /// The first frame.
    pub first: u64,
    /// The last frame (at least `first`).
    pub last: u64,
}

/// Parse `--frames A..B`.
fn parse_frames(s: &str) -> Result<FrameRange, String> {
    let bad = || format!("`{s}`: expected A..B, frames A to B from 0 with A <= B (e.g. 10..14)");
    let (a, b) = s.split_once("..").ok_or_else(bad)?;
    let (first, last) = (
        a.trim().parse::<u64>().map_err(|_| bad())?,
        b.trim().parse::<u64>().map_err(|_| bad())?,
    );
    if first > last {
        return Err(bad());
    }
    Ok(FrameRange { first, last })
}

/// Rasterize an imported frame (with its picture when `colour`), its
/// textures stored in `format`.
fn rasterize_frame(
    imported: &gl::Imported,
    colour: bool,
    format: FormatChoice,
) -> Result<Frame, CliError> {
    let raster = RasterOptions {
        tile: TILE,
        colour,
        texture_format: format,
        ..RasterOptions::default()
    };
    rasterize(&imported.scene, imported.width, imported.height, &raster)
        .map_err(|e| CliError::failed(e.to_string()))
}

/// Import frames `first` to `last` (`None`: the last complete frame
/// alone) in one pass over the capture, each rasterized as it comes (the
/// last with its picture when `colour`): the earlier frames' traces, and
/// the last frame imported and rasterized.
fn import_frames(
    args: &ImportGlArgs,
    range: Option<(u64, u64)>,
    colour: bool,
) -> Result<(Vec<Trace>, gl::Imported, Frame), CliError> {
    let failed = |e: &dyn std::fmt::Display| CliError::failed(e.to_string());
    let capture = wasp_gltrace::Capture::open(&args.capture).map_err(|e| failed(&e))?;
    capture.require_gl().map_err(|e| failed(&e))?;
    let Some((first, last)) = range else {
        let opts = ImportOptions {
            frame: None,
            skip_unsupported: args.skip_unsupported,
        };
        let imported = gl::import(capture, &args.capture, opts).map_err(|e| failed(&e))?;
        let frame = rasterize_frame(&imported, colour, args.texture_format)?;
        return Ok((Vec::new(), imported, frame));
    };
    let mut reader = gl::Reader::new(capture, &args.capture, args.skip_unsupported);
    let mut traces = Vec::new();
    for f in first..last {
        let imported = reader.frame(f).map_err(|e| failed(&e))?;
        let frame = rasterize_frame(&imported, false, args.texture_format)?;
        if !args.quiet {
            eprintln!(
                "wasp: imported frame {} ({} draw calls, {} quads shaded)",
                imported.frame,
                imported.draw_calls,
                frame.trace.quad_count()
            );
        }
        traces.push(frame.trace);
    }
    let imported = reader.frame(last).map_err(|e| failed(&e))?;
    let frame = rasterize_frame(&imported, colour, args.texture_format)?;
    Ok((traces, imported, frame))
}

/// Run `wasp import-gl`.
pub fn run(args: &ImportGlArgs) -> Result<(), CliError> {
    output::check(
        &[
            Output::new("--trace-out", Some(&args.trace_out)),
            Output::new("--png", args.png.as_deref()),
            Output::new("--json", args.json.as_deref()),
        ],
        &[Input::file("CAPTURE", Some(&args.capture))],
    )?;
    if args.check_mesa.is_some() {
        crate::check_mesa::require_tools()?;
    }
    let failed = |e: &dyn std::fmt::Display| CliError::failed(e.to_string());
    let clock = std::time::Instant::now();
    let range = match (args.frames, args.frame) {
        (Some(r), _) => Some((r.first, r.last)),
        (None, Some(n)) => Some((n, n)),
        (None, None) => None,
    };
    // One pass over the capture: the frames of a range in order, the GL
    // state carried from one to the next.
    let (traces, imported, frame) = import_frames(args, range, args.png.is_some())?;
    let read = clock.elapsed().as_secs_f64() - frame.timings.total();
    if !args.quiet {
        eprintln!(
            "wasp: imported frame {} of {} ({} draw calls) in {read:.2} s, rasterized in {:.2} s",
            imported.frame,
            args.capture.display(),
            imported.draw_calls,
            frame.timings.total()
        );
    }
    let summary = Summary::new(&args.capture.display().to_string(), &imported, &frame);
    if traces.is_empty() {
        crate::scene_cmd::write_trace(&args.trace_out, &frame.trace, args.quiet)?;
    } else {
        let mut frames = traces.into_iter();
        let first = frames.next().expect("a range has an earlier frame");
        let rest = frames.chain(std::iter::once(frame.trace));
        let joined = Trace::concat(first, rest).map_err(|e| failed(&e))?;
        crate::scene_cmd::write_trace(&args.trace_out, &joined, args.quiet)?;
    }
    if let Some(p) = &args.png {
        let bytes =
            render::encode_png(&frame.image, frame.width, frame.height).map_err(|e| failed(&e))?;
        output::write_bytes(p, &bytes)?;
        if !args.quiet {
            eprintln!("wasp: wrote {}", output::name(p));
        }
    }
    if let Some(p) = &args.json {
        let text = serde_json::to_string_pretty(&summary).map_err(|e| failed(&e))? + "\n";
        output::emit(p, &text)?;
    }
    // The summary goes to standard output unless an output took it.
    let stdout_taken = [Some(&args.trace_out), args.png.as_ref(), args.json.as_ref()]
        .into_iter()
        .flatten()
        .any(|p| output::is_stdout(p));
    if stdout_taken {
        eprint!("{}", summary.text());
    } else {
        print!("{}", summary.text());
    }
    if let Some(dir) = &args.check_mesa {
        crate::check_mesa::run(&args.capture, &imported, dir, args.quiet)?;
    }
    Ok(())
}
