//! `wasp render` of an engine-route scene: the game's own engine is
//! captured when the scene cache holds no capture (as a loader scene's game
//! data is fetched when missing), and the capture's last complete frame is
//! imported as `wasp import-gl` imports it (docs/import-gl.md).

use crate::capture::{engine_scene, ensure_capture};
use crate::cli_error::CliError;
use crate::import_gl_cmd::{self, ImportGlArgs};
use crate::scene_cmd::RenderArgs;
use wasp_frontend::def::{self, Route};

/// Whether `name` names an engine-route scene (a name or a definition file
/// that does not load is left to the loader route's errors).
pub fn is_engine_scene(name: &str) -> bool {
    def::lookup(name).is_ok_and(|d| d.route == Route::Engine)
}

/// The options of `render` that only a loader scene takes, when given.
fn loader_only_options(args: &RenderArgs) -> Vec<&'static str> {
    let given = [
        (!args.overlay.is_empty(), "--overlay"),
        (args.config.is_some(), "--config"),
        (args.policy.is_some(), "--policy"),
        (args.subset.is_some(), "--subset"),
        (args.size.is_some(), "--size"),
        (args.crop.is_some(), "--crop"),
        (args.depth_prepass, "--depth-prepass"),
        (args.draw_order.is_some(), "--draw-order"),
        (args.timings, "--timings"),
    ];
    given.iter().filter(|g| g.0).map(|g| g.1).collect()
}

/// Render engine-route scene `args.scene`: capture if needed, then import
/// the last complete frame into `--trace-out` and `--png`.
pub fn render(args: &RenderArgs) -> Result<(), CliError> {
    let def = engine_scene(&args.scene)?;
    let refused = loader_only_options(args);
    if !refused.is_empty() {
        return Err(CliError::usage(format!(
            "scene {} takes the engine route (its frame is the engine's own draw calls, \
             imported as `wasp import-gl` does): {} apply to loader scenes only",
            def.name,
            refused.join(", ")
        )));
    }
    let Some(trace_out) = args.trace_out.clone() else {
        return Err(CliError::usage(format!(
            "scene {} takes the engine route: give --trace-out FILE (and --png FILE for the \
             picture)",
            def.name
        )));
    };
    let capture = ensure_capture(&def, false, None, args.quiet)?;
    import_gl_cmd::run(&ImportGlArgs {
        capture,
        frame: None,
        frames: None,
        trace_out,
        png: args.png.clone(),
        json: None,
        skip_unsupported: false,
        check_mesa: None,
        texture_format: args.texture_format.unwrap_or(def.texture_format),
        quiet: args.quiet,
    })
}
