//! What the front end is asked (options) and gives back: the frame with
//! its trace, picture, counts and timings.

use super::*;

/// Options of the front end.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RasterOptions {
    /// Tile edge in pixels (even; the paper's 64).
    pub tile: u32,
    /// Cull back faces (clockwise in normalized device coordinates).
    pub cull_back_faces: bool,
    /// Compute the picture (off: the trace only, faster; the image is the
    /// clear colour). Alpha-tested surfaces need their alpha for their
    /// depth writes, so it is always sampled.
    pub colour: bool,
    /// Hidden-surface removal by a per-tile depth pre-pass over the opaque
    /// triangles (as tile-based deferred renderers do): only the nearest
    /// opaque fragment of a pixel survives early-Z. Off by default: plain
    /// early-Z in submission order.
    pub depth_prepass: bool,
    /// Worker threads for the tiles (0: one per available core). The
    /// result does not depend on it.
    pub threads: usize,
    /// The order of the opaque geometry ([`DrawOrder`]; the default, as
    /// loaded, is the order every trace had before the option existed).
    pub draw_order: DrawOrder,
    /// How the textures are stored ([`FormatChoice`]: RGBA8, the default
    /// and the layout of every trace before compressed formats, or a
    /// compressed format or rule); it moves the blocks a texture
    /// instruction touches, not the picture.
    pub texture_format: FormatChoice,
    /// List the *decoded* lines of compressed textures (laid out as RGBA8)
    /// and map them to the stored lines (`texture-lines decoded`), for a
    /// machine whose L0/L1 hold decompressed texels
    /// (`memory.texture_cache = "decompressed"`). Off: the trace lists the
    /// stored lines. Changes nothing with RGBA8, whose lines are both.
    pub decoded_lines: bool,
}

impl Default for RasterOptions {
    fn default() -> Self {
        Self {
            tile: 64,
            cull_back_faces: false,
            colour: true,
            depth_prepass: false,
            threads: 0,
            draw_order: DrawOrder::AsLoaded,
            texture_format: FormatChoice::Rgba8,
            decoded_lines: false,
        }
    }
}

/// Counts of one material.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct MaterialStats {
    /// Material name.
    pub name: String,
    /// Blend mode.
    pub blend: String,
    /// Input triangles.
    pub triangles: u64,
    /// Surviving (triangle, quad) fragments it shaded: its warps.
    pub warps: u64,
    /// Quads of its triangles rejected by early-Z.
    pub quads_rejected_early_z: u64,
    /// Pixels it shaded (surviving, inside the triangle).
    pub pixels: u64,
}

/// What the front end did.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct RasterStats {
    /// Input triangles.
    pub primitives: u64,
    /// Triangles entirely outside the view frustum.
    pub culled_outside: u64,
    /// Back faces culled (only with `cull_back_faces`).
    pub culled_back_faces: u64,
    /// Triangles with zero area on screen.
    pub degenerate: u64,
    /// Triangles crossing the near or far plane or the guard band, clipped.
    pub clipped: u64,
    /// Screen triangles after clipping (set up and binned).
    pub setup_triangles: u64,
    /// (tile, triangle) entries of the polygon lists.
    pub bin_entries: u64,
    /// Tile records of the trace: tiles that rasterized at least one quad,
    /// shaded or rejected by early-Z (a tile whose every quad was rejected
    /// is a record without warps).
    pub tiles: u64,
    /// (triangle, quad) pairs with at least one covered pixel.
    pub quads_covered: u64,
    /// Of those, quads whose every covered pixel failed the depth test.
    pub quads_rejected_early_z: u64,
    /// Of those, quads the hierarchical (coarse) depth test rejected
    /// without testing their pixels (the rest were tested pixel by pixel).
    pub quads_rejected_hiz: u64,
    /// Surviving (triangle, quad) fragments: the warps (quad records of the
    /// trace), one per fragment as in a hardware TBR.
    pub warps: u64,
    /// Quad positions with at least one surviving fragment (warps /
    /// positions is the overdraw the shader cores see).
    pub positions: u64,
    /// Pixels shaded (surviving, inside their triangle).
    pub pixels_shaded: u64,
    /// Per material, in scene order.
    pub materials: Vec<MaterialStats>,
    /// The draw order that took effect ([`DrawOrder::effective`]: a 2D
    /// scene is always drawn as loaded).
    pub draw_order: DrawOrder,
}

/// Where the front end's time went: wall-clock seconds of each phase of
/// [`rasterize`] (not part of the results, which never depend on time).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct RasterTimings {
    /// Mip chains and the texture heap layout ([`TextureSet::new`]).
    pub textures: f64,
    /// Geometry (transform, clip, set-up) and binning into tiles.
    pub geometry: f64,
    /// Raster, early-Z, texturing, shading of the tiles and building the
    /// trace.
    pub tiles: f64,
}

impl RasterTimings {
    /// All phases.
    pub fn total(&self) -> f64 {
        self.textures + self.geometry + self.tiles
    }
}

/// A rasterized frame: the trace, the picture and the counts.
#[derive(Clone, Debug)]
pub struct Frame {
    /// The warps of the frame.
    pub trace: Trace,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// RGBA8, row-major, top row first.
    pub image: Vec<u8>,
    /// What the front end did.
    pub stats: RasterStats,
    /// How long each phase took.
    pub timings: RasterTimings,
}
