//! `wasp synth`: write a synthetic workload trace.

use crate::cli_error::CliError;
use crate::output::{self, Output};
use clap::Args;
use std::path::PathBuf;
use wasp_sim::synth::{generate, GenParams, GenReport};

/// Options of `wasp synth`.
#[derive(Args, Debug, Clone)]
pub struct SynthArgs {
    /// Write the trace to FILE (`-` for standard output; the figures it
    /// measures then go to standard error).
    #[arg(long, short, value_name = "FILE")]
    pub out: PathBuf,
    /// Frame size in pixels, WIDTHxHEIGHT.
    #[arg(long, default_value = "1960x768", value_parser = parse_frame)]
    pub frame: (u32, u32),
    /// Tile side in pixels.
    #[arg(long, default_value_t = 64)]
    pub tile: u32,
    /// Seed.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Texture instructions / all instructions (the paper's Table I: 0.07-0.26).
    #[arg(long, default_value_t = GenParams::default().mem_ratio)]
    pub mem_ratio: f64,
    /// Mean shader length in instructions.
    #[arg(long, default_value_t = GenParams::default().instrs_per_quad)]
    pub instrs: u32,
    /// Fraction of the frame's quads shaded.
    #[arg(long, default_value_t = GenParams::default().coverage)]
    pub coverage: f64,
    /// Textures per material (base texture first).
    #[arg(long, default_value_t = GenParams::default().textures_per_material)]
    pub textures: u32,
    /// Texels per pixel of the base texture (smaller: more block reuse).
    #[arg(long, conflicts_with = "reuse")]
    pub texel_scale: Option<f64>,
    /// Aim at this memory-block reuse in tile (Table I: 3.3-22.9) by
    /// searching the texel scale; the achieved value is reported.
    #[arg(long)]
    pub reuse: Option<f64>,
    /// No progress output on stderr (progress bars, notes of what is being
    /// done); results, warnings and errors still print. (Synth shows none.)
    #[arg(long, short)]
    pub quiet: bool,
}

fn parse_frame(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("`{s}`: expected WIDTHxHEIGHT, e.g. 1960x768"))?;
    let n = |v: &str| {
        v.trim()
            .parse::<u32>()
            .map_err(|_| format!("`{s}`: `{v}` is not a positive integer"))
    };
    Ok((n(w)?, n(h)?))
}

/// Run the command.
pub fn run(args: &SynthArgs) -> Result<(), CliError> {
    output::check(&[Output::new("--out", Some(&args.out))], &[])?;
    let mut p = GenParams {
        frame_w: args.frame.0,
        frame_h: args.frame.1,
        tile: args.tile,
        seed: args.seed,
        mem_ratio: args.mem_ratio,
        instrs_per_quad: args.instrs,
        coverage: args.coverage,
        textures_per_material: args.textures,
        ..GenParams::default()
    };
    if let Some(s) = args.texel_scale {
        p.texel_scale = s;
    }
    p.validate().map_err(|e| CliError::usage(e.to_string()))?;
    if let Some(target) = args.reuse {
        let (q, probe) = p
            .with_target_reuse(target)
            .map_err(|e| CliError::usage(e.to_string()))?;
        eprintln!(
            "wasp synth: texel scale {:.4} gives block reuse {:.2} on a probe frame (target {target})",
            q.texel_scale, probe
        );
        p = q;
    }
    let trace = generate(&p).map_err(|e| CliError::failed(e.to_string()))?;
    let mut w = output::create(&args.out)?;
    trace
        .write(&mut w)
        .and_then(|_| w.finish())
        .map_err(|e| CliError::failed(format!("writing {}: {e}", output::name(&args.out))))?;
    if output::is_stdout(&args.out) {
        eprintln!("{}", GenReport::new(&p, &trace));
    } else {
        println!("{}", GenReport::new(&p, &trace));
        println!("wrote {}", args.out.display());
    }
    Ok(())
}
