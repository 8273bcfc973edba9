//! `wasp import-gl ... --check-mesa DIR`: the imported frame checked
//! against Mesa. The capture is rewritten twice (a texture id per pixel,
//! a fragment count per pixel: `wasp_frontend::glcheck::rewrite`),
//! `glretrace` replays both under `xvfb-run` with Mesa and writes the
//! frame's picture, wasp rasterizes the frame with its per-pixel maps, and
//! the two views are compared: the figures printed and written to
//! DIR/agreement.json, the disagreement maps to DIR/*.png
//! (docs/scenes.md, "Checked against Mesa").

use crate::capture::tools::find_program;
use crate::cli_error::CliError;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::process::Command;
use wasp_frontend::gl::Imported;
use wasp_frontend::glcheck::{self, images, Agreement, Mode, Rewritten, View};
use wasp_frontend::raster::{rasterize_with_maps, RasterOptions};
use wasp_frontend::{render, ShaderOp};

/// The packages the check needs, for the error that names them.
const APT: &str = "sudo apt-get install apitrace xvfb xauth";

/// What DIR/agreement.json holds.
#[derive(Serialize)]
struct Report<'a> {
    capture: String,
    frame: u64,
    /// The frame's calls in the original capture (first, swap).
    calls: (u64, u64),
    id_replay: &'a Rewritten,
    count_replay: &'a Rewritten,
    /// Pixels of Mesa's count picture whose red, green and blue differ.
    mesa_count_channel_mismatch: u64,
    /// wasp's fragments that passed the depth test (shaded) and of them
    /// the ones the alpha test discarded, summed over the frame.
    wasp_fragments_shaded: u64,
    wasp_fragments_alpha_discarded: u64,
    agreement: &'a Agreement,
}

/// Runs the check of `imported` (read from `capture`) into `dir`.
pub fn run(
    capture: &Path,
    imported: &Imported,
    dir: &Path,
    quiet: bool,
) -> Result<Agreement, CliError> {
    require_tools()?;
    let failed = |e: &dyn std::fmt::Display| CliError::failed(e.to_string());
    std::fs::create_dir_all(dir)
        .map_err(|e| CliError::failed(format!("{}: {e}", dir.display())))?;
    let (w, h) = (imported.width, imported.height);
    let mut replays = Vec::new();
    for (mode, name) in [(Mode::Id, "id"), (Mode::Count, "count")] {
        let src = wasp_gltrace::Capture::open(capture).map_err(|e| failed(&e))?;
        let out = dir.join(format!("{name}.trace"));
        let rewritten =
            glcheck::rewrite(src, mode, imported.calls, (w, h), &out).map_err(|e| failed(&e))?;
        let png = replay(
            &out,
            rewritten.swap_call,
            &dir.join(format!("mesa-{name}")),
            (w, h),
        )?;
        if !quiet {
            eprintln!(
                "wasp: Mesa replayed {} (call {})",
                out.display(),
                rewritten.swap_call
            );
        }
        replays.push((rewritten, png));
    }
    let opts = RasterOptions {
        colour: false,
        ..RasterOptions::default()
    };
    let (_, maps) = rasterize_with_maps(&imported.scene, w, h, &opts).map_err(|e| failed(&e))?;
    let textures = material_textures(imported);
    let (mesa, odd) = View::from_mesa(w, h, &replays[1].1, &replays[0].1);
    let wasp = View::from_wasp(&maps, &textures);
    let agreement = glcheck::compare(&mesa, &wasp);
    let shaded: u64 = maps.shaded.iter().map(|&c| u64::from(c)).sum();
    let written: u64 = maps.written.iter().map(|&c| u64::from(c)).sum();
    let report = Report {
        capture: capture.display().to_string(),
        frame: imported.frame,
        calls: imported.calls,
        id_replay: &replays[0].0,
        count_replay: &replays[1].0,
        mesa_count_channel_mismatch: odd,
        wasp_fragments_shaded: shaded,
        wasp_fragments_alpha_discarded: shaded - written,
        agreement: &agreement,
    };
    let json = serde_json::to_string_pretty(&report).map_err(|e| failed(&e))? + "\n";
    write(&dir.join("agreement.json"), json.as_bytes())?;
    let pictures = [
        ("coverage.png", images::coverage_map(&mesa, &wasp)),
        ("depth.png", images::depth_map(&mesa, &wasp)),
        ("texture.png", images::texture_map(&mesa, &wasp)),
        ("mesa-ids.png", images::ids_picture(&mesa)),
        ("wasp-ids.png", images::ids_picture(&wasp)),
    ];
    for (name, rgba) in pictures {
        let bytes = render::encode_png(&rgba, w, h).map_err(|e| failed(&e))?;
        write(&dir.join(name), &bytes)?;
    }
    print_results(dir, &report);
    Ok(agreement)
}

/// The figures on standard output, with the notes of the rewriting.
fn print_results(dir: &Path, r: &Report) {
    println!("checked against Mesa ({}):", dir.display());
    print!("{}", r.agreement.text());
    println!(
        "wasp fragments: {} shaded (passed the depth test), {} of them discarded by the \
         alpha test",
        r.wasp_fragments_shaded, r.wasp_fragments_alpha_discarded
    );
    if r.mesa_count_channel_mismatch > 0 {
        println!(
            "warning: {} pixels of Mesa's count picture have unequal channels",
            r.mesa_count_channel_mismatch
        );
    }
    for (replay, what) in [(r.id_replay, "id"), (r.count_replay, "count")] {
        for (note, n) in &replay.notes {
            println!("note ({what} replay): {note}: {n}");
        }
    }
}

/// Per material, the GL name of its first sampled texture (`None`:
/// untextured).
fn material_textures(imported: &Imported) -> Vec<Option<u32>> {
    imported
        .scene
        .materials
        .iter()
        .map(|m| {
            m.shader.iter().find_map(|op| match op {
                ShaderOp::Tex(t) => imported.texture_ids.get(t.texture).copied(),
                _ => None,
            })
        })
        .collect()
}

fn write(path: &Path, bytes: &[u8]) -> Result<(), CliError> {
    std::fs::write(path, bytes).map_err(|e| CliError::failed(format!("{}: {e}", path.display())))
}

/// An error naming the packages unless glretrace, xvfb-run and xauth are
/// installed (checked before anything is imported or written).
pub fn require_tools() -> Result<(), CliError> {
    let missing: Vec<&str> = ["glretrace", "xvfb-run", "xauth"]
        .into_iter()
        .filter(|t| find_program(t).is_none())
        .collect();
    if missing.is_empty() {
        return Ok(());
    }
    Err(CliError::failed(format!(
        "--check-mesa replays the frame with glretrace under xvfb-run; not installed: {}. \
         Install them with: {APT}",
        missing.join(", ")
    )))
}

/// Replays `trace` with glretrace under a virtual X server and returns
/// its picture of call `call` as RGBA8 (`size`, top row first).
fn replay(trace: &Path, call: u64, out: &Path, size: (u32, u32)) -> Result<Vec<u8>, CliError> {
    let _ = std::fs::remove_dir_all(out);
    std::fs::create_dir_all(out)
        .map_err(|e| CliError::failed(format!("{}: {e}", out.display())))?;
    let screen = format!("-screen 0 {}x{}x24", size.0.max(2048), size.1.max(1024));
    let mut prefix = out.as_os_str().to_owned();
    prefix.push("/");
    let run = Command::new("xvfb-run")
        .args([
            "-a",
            "-s",
            &screen,
            "glretrace",
            "-S",
            &call.to_string(),
            "-s",
        ])
        .arg(&prefix)
        .arg(trace)
        .output()
        .map_err(|e| CliError::failed(format!("cannot run xvfb-run: {e}")))?;
    let png: PathBuf = out.join(format!("{call:010}.png"));
    if !run.status.success() || !png.is_file() {
        return Err(CliError::failed(format!(
            "glretrace did not write {} ({}): {}",
            png.display(),
            run.status,
            String::from_utf8_lossy(&run.stderr).trim()
        )));
    }
    let img = image::open(&png)
        .map_err(|e| CliError::failed(format!("{}: {e}", png.display())))?
        .to_rgba8();
    if img.dimensions() != size {
        return Err(CliError::failed(format!(
            "{}: glretrace's picture is {}x{}, the imported frame {}x{}",
            png.display(),
            img.width(),
            img.height(),
            size.0,
            size.1
        )));
    }
    Ok(img.into_raw())
}
