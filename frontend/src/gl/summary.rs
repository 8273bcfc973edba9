//! The import's summary: what was read and what the front end made of
//! it, printed (one line reads exactly `draw calls: N`) and as JSON.

use super::import::Imported;
use super::scene::TextureInfo;
use crate::raster::Frame;
use serde::Serialize;
use std::collections::BTreeMap;
use std::fmt::Write;

/// The summary of one imported frame.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Summary {
    /// The capture file.
    pub capture: String,
    /// The frame (from 0), its first and last calls (the last is its
    /// swap), and the complete frames read.
    pub frame: u64,
    pub first_call: u64,
    pub last_call: u64,
    pub frames_read: u64,
    /// The frame's size (the extent of its viewports).
    pub width: u32,
    pub height: u32,
    /// Draw calls imported (skipped ones not included).
    pub draw_calls: u64,
    /// Triangles of those draws, after primitive assembly.
    pub triangles_submitted: u64,
    /// Screen triangles after clipping (a clipped triangle's fan counts
    /// its pieces), culling and the scissor.
    pub triangles_after_clipping_and_culling: u64,
    /// Quads shaded: the warps of the trace.
    pub quads_shaded: u64,
    /// Quads Early-Z rejected.
    pub quads_rejected_early_z: u64,
    /// Quad positions with a shaded quad, and tiles with a trace record.
    pub positions: u64,
    pub tiles: u64,
    /// Distinct texture blocks of the frame, and summed over its tiles.
    pub distinct_blocks: u64,
    pub distinct_blocks_per_tile_sum: u64,
    /// The textures the frame samples.
    pub textures: Vec<TextureInfo>,
    /// Of those, how many have placeholder texels.
    pub placeholder_textures: u64,
    /// Calls up to the frame's end the model does not use, by name.
    pub unmodelled_calls: BTreeMap<String, u64>,
    /// Draws skipped for needing what is not modelled, and by what.
    pub unsupported_draws_skipped: u64,
    pub unsupported: BTreeMap<String, u64>,
    /// Draws of the frames before it that need what is not modelled (not
    /// imported, so not errors), by feature.
    pub unsupported_in_earlier_frames: BTreeMap<String, u64>,
    /// Per draw call, in issue order (JSON only).
    pub draws: Vec<DrawSummary>,
}

/// One draw call's counts.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct DrawSummary {
    /// The call's number in the capture.
    pub call: u64,
    /// Its triangles after primitive assembly.
    pub triangles: u64,
    /// Its quads shaded (warps) and rejected by Early-Z.
    pub quads_shaded: u64,
    pub quads_rejected_early_z: u64,
    /// Pixels it shaded.
    pub pixels: u64,
}

/// Per draw, its materials' statistics summed (a draw has more than one
/// when it reads several choices of 3D slices).
fn draws(imp: &Imported, frame: &Frame) -> Vec<DrawSummary> {
    let mut out: Vec<DrawSummary> = imp
        .draw_call_numbers
        .iter()
        .map(|&call| DrawSummary {
            call,
            triangles: 0,
            quads_shaded: 0,
            quads_rejected_early_z: 0,
            pixels: 0,
        })
        .collect();
    for (st, &d) in frame.stats.materials.iter().zip(&imp.material_draws) {
        let o = &mut out[d];
        o.triangles += st.triangles;
        o.quads_shaded += st.warps;
        o.quads_rejected_early_z += st.quads_rejected_early_z;
        o.pixels += st.pixels;
    }
    out
}

impl Summary {
    /// The summary of `imp` rasterized into `frame`.
    pub fn new(capture: &str, imp: &Imported, frame: &Frame) -> Summary {
        let ts = frame.trace.stats();
        Summary {
            capture: capture.into(),
            frame: imp.frame,
            first_call: imp.calls.0,
            last_call: imp.calls.1,
            frames_read: imp.frames_read,
            width: imp.width,
            height: imp.height,
            draw_calls: imp.draw_calls,
            triangles_submitted: imp.triangles,
            triangles_after_clipping_and_culling: frame.stats.setup_triangles,
            quads_shaded: frame.stats.warps,
            quads_rejected_early_z: frame.stats.quads_rejected_early_z,
            positions: frame.stats.positions,
            tiles: frame.stats.tiles,
            distinct_blocks: ts.frame_unique_blocks,
            distinct_blocks_per_tile_sum: ts.tile_unique_blocks,
            placeholder_textures: imp
                .textures
                .iter()
                .filter(|t| t.placeholder.is_some())
                .count() as u64,
            textures: imp.textures.clone(),
            unmodelled_calls: imp.unmodelled.clone(),
            unsupported_draws_skipped: imp.unsupported.values().sum(),
            unsupported: imp.unsupported.clone(),
            unsupported_in_earlier_frames: imp.unsupported_in_earlier_frames.clone(),
            draws: draws(imp, frame),
        }
    }

    /// The printed summary.
    pub fn text(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "{}: frame {} (calls {} to {}) of {} complete frames read, {}x{}",
            self.capture,
            self.frame,
            self.first_call,
            self.last_call,
            self.frames_read,
            self.width,
            self.height
        );
        let _ = writeln!(s, "draw calls: {}", self.draw_calls);
        let _ = writeln!(s, "triangles submitted: {}", self.triangles_submitted);
        let _ = writeln!(
            s,
            "triangles after clipping and culling: {}",
            self.triangles_after_clipping_and_culling
        );
        let _ = writeln!(s, "quads shaded: {}", self.quads_shaded);
        let _ = writeln!(
            s,
            "quads rejected by Early-Z: {}",
            self.quads_rejected_early_z
        );
        let _ = writeln!(
            s,
            "quad positions shaded: {} in {} tiles",
            self.positions, self.tiles
        );
        let _ = writeln!(
            s,
            "distinct texture blocks: {} (summed over tiles: {})",
            self.distinct_blocks, self.distinct_blocks_per_tile_sum
        );
        let _ = writeln!(
            s,
            "textures sampled: {} ({} with placeholder texels)",
            self.textures.len(),
            self.placeholder_textures
        );
        for t in &self.textures {
            let levels: Vec<String> = t.levels.iter().map(u32::to_string).collect();
            let _ = writeln!(
                s,
                "  texture {}: {}x{} {}, levels uploaded {}{}",
                t.id,
                t.width,
                t.height,
                t.format,
                levels.join(","),
                t.placeholder
                    .as_ref()
                    .map_or(String::new(), |p| format!(", placeholder texels ({p})"))
            );
        }
        let total: u64 = self.unmodelled_calls.values().sum();
        let _ = writeln!(s, "calls not modelled: {total}");
        for (n, c) in &self.unmodelled_calls {
            let _ = writeln!(s, "  {n}: {c}");
        }
        let _ = writeln!(
            s,
            "unsupported draws skipped: {}",
            self.unsupported_draws_skipped
        );
        for (n, c) in &self.unsupported {
            let _ = writeln!(s, "  {n}: {c}");
        }
        let earlier: u64 = self.unsupported_in_earlier_frames.values().sum();
        let _ = writeln!(
            s,
            "unsupported draws in earlier frames (not imported): {earlier}"
        );
        for (n, c) in &self.unsupported_in_earlier_frames {
            let _ = writeln!(s, "  {n}: {c}");
        }
        s
    }
}
