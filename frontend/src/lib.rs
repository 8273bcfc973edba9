//! Real workloads: scenes from real games, a TBR raster front end and the
//! texture path that turns a frame into the cycle model's trace.
//!
//! This crate stands on `wasp-trace` (its output) and `wasp-rtl` (the
//! priority subsets its overlays and footprint ratios use); it knows
//! nothing of the machine. The CLI runs the cycle model on its traces
//! (heat maps included).
//!
//! One [`Scene`] model serves every game: meshes with UVs, materials with
//! textures and a shader template, and a camera. Loaders (one file per
//! game) build a `Scene` from the game's own files; the raster front end
//! ([`raster`]) bins, rasterizes and textures it into 64x64 tiles of 2x2
//! quads and emits one warp per surviving quad, each with the block
//! addresses its texture instructions touch.
//!
//! Game data is GPL / CC-BY-SA: it is never committed. `wasp scenes fetch`
//! downloads the Debian packages into a cache outside the repository
//! ([`fetch::cache_dir`]: `$WASP_SCENES`, default under the user's cache
//! directory), and scene definitions (`scenes/*.toml`) name what to load.

pub mod builtin;
pub mod bytes;
pub mod characterize;
pub mod def;
pub mod draw_state;
pub mod fetch;
pub mod frozen_bubble;
pub mod gl;
pub mod glcheck;
mod image_decode;
pub mod load;
pub mod openarena;
pub mod procedural;
pub mod raster;
pub mod render;
pub mod shader;
pub mod supertuxkart;
pub mod teeworlds;
pub mod texture;
mod vec3;

pub use draw_state::{BlendFactor, Compare, Cull, DrawState};

// The trace crate and its generator under the paths the modules use.
use wasp_trace as trace;
use wasp_trace::rng;

use std::fmt;
use std::path::{Path, PathBuf};

/// A 3-vector (x, y, z).
pub type Vec3 = [f32; 3];
/// A 2-vector (u, v) or (x, y).
pub type Vec2 = [f32; 2];

/// A texture: level 0 as RGBA8, row-major, top row first. The texture path
/// builds the mip chain and the block-linear layout.
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    /// Name (file name inside the game data, for reports).
    pub name: String,
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// `width * height * 4` bytes, RGBA.
    pub rgba: Vec<u8>,
    /// Wrap mode: repeat (true) or clamp to edge (false).
    pub repeat: bool,
}

/// How a material's fragments are blended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Blend {
    /// Opaque: depth-tested and depth-written (early-Z rejects hidden quads).
    Opaque,
    /// Alpha-tested cut-outs: depth-tested and written; treated as opaque
    /// for early-Z (the shader discards, the quad still runs).
    AlphaTest,
    /// Alpha-blended (sprites, UI, particles): drawn back to front after the
    /// opaque geometry, depth-tested but not written, never rejecting what
    /// is behind it.
    AlphaBlend,
}

/// Texture filtering of a texture instruction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Filter {
    /// Bilinear: 4 texels of one mip level.
    Bilinear,
    /// Trilinear: 4 texels of each of two adjacent mip levels.
    Trilinear,
    /// Nearest: 1 texel (pixel-art 2D games).
    Nearest,
}

/// One texture instruction of a shader: which texture, through which UV
/// set, with which filter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TexSample {
    /// Index into [`Scene::textures`].
    pub texture: usize,
    /// UV set: 0 = [`Mesh::uv`], 1 = [`Mesh::uv2`] (lightmap).
    pub uv_set: u8,
    /// Filtering.
    pub filter: Filter,
    /// Whether the level of detail picks the mip levels read (every
    /// loader), or level 0 alone is read (`false`: GL's `GL_NEAREST` and
    /// `GL_LINEAR` minification filters, from the GL importer).
    pub mipmapped: bool,
    /// A second texture the instruction filters with the first, at the
    /// same UVs and level 0 of both (the GL importer's 3D textures: the
    /// two slices a linear filter in r reads): one texture instruction of
    /// two filter passes, like a trilinear one.
    pub second: Option<SecondSlice>,
}

impl TexSample {
    /// A mipmapped sample of one texture (the loaders' kind).
    pub fn new(texture: usize, uv_set: u8, filter: Filter) -> Self {
        Self {
            texture,
            uv_set,
            filter,
            mipmapped: true,
            second: None,
        }
    }
}

/// The second texture of a [`TexSample`] and its weight.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SecondSlice {
    /// Index into [`Scene::textures`].
    pub texture: usize,
    /// Its weight in the filtered colour, in 1/65536 (the first texture
    /// has the rest).
    pub weight: u16,
}

/// The instruction mix of a material's fragment shader, in program order:
/// ALU runs and texture instructions.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ShaderOp {
    /// This many ALU instructions.
    Alu(u32),
    /// One texture instruction.
    Tex(TexSample),
}

/// A material: blend mode, its shader program and, where the engine's own
/// pipeline state is known, that state.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Name (for reports).
    pub name: String,
    /// Blend mode.
    pub blend: Blend,
    /// The shader program: its texture instructions name the textures.
    pub shader: Vec<ShaderOp>,
    /// The pipeline state of its draws. `None` (every loader): the state
    /// its blend mode means ([`DrawState::for_blend`]), alpha-blended
    /// triangles drawn back to front after the others. `Some` (the GL
    /// importer): this state, every triangle in submission order.
    pub state: Option<DrawState>,
}

/// A triangle mesh in world space (2D scenes: z is the layer depth, larger
/// is nearer; positions in pixels of the orthographic camera's view).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Texture coordinates (set 0).
    pub uv: Vec<Vec2>,
    /// Second UV set (lightmaps), if any.
    pub uv2: Option<Vec<Vec2>>,
    /// Triangles: three vertex indices each.
    pub indices: Vec<u32>,
    /// Index into [`Scene::materials`].
    pub material: usize,
    /// The game's draw calls merged into this mesh, in order: they split
    /// its triangles into consecutive runs (empty: the whole mesh is one
    /// draw call and one object of its own). Only
    /// [`raster::DrawOrder`]s other than as-loaded read them.
    pub draws: Vec<Draw>,
    /// Sky geometry: kept after the opaque and alpha-tested geometry when
    /// a draw order sorts it, as engines draw their sky after the opaque
    /// pass rather than sorting it by depth.
    pub sky: bool,
    /// Clip-space w of each vertex, for [`Camera::Clip`] (whose positions
    /// are clip-space x, y, z): `None` is w = 1 everywhere. Only a
    /// [`Camera::Clip`] scene may have it.
    pub clip_w: Option<Vec<f32>>,
}

/// One draw call of the game's renderer inside a [`Mesh`] (loaders merge
/// the draw calls of a material into one mesh): a run of the mesh's
/// triangles, and the object it belongs to. What a draw call and an object
/// are is each loader's choice, documented in `docs/scenes.md` (for
/// example SuperTuxKart: a mesh buffer with one material, of a placed
/// model).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Draw {
    /// Triangles of the run (the runs of a mesh follow one another from
    /// its first triangle and cover all of them).
    pub triangles: u32,
    /// The object: draws with the same id belong to one object (ids are
    /// the loader's, unique in the scene).
    pub object: u32,
}

/// The camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Camera {
    /// A perspective camera (3D games).
    Perspective {
        /// Eye position.
        eye: Vec3,
        /// Point looked at.
        target: Vec3,
        /// Up direction.
        up: Vec3,
        /// Vertical field of view in degrees.
        fov_y_deg: f32,
        /// Near plane distance (> 0).
        near: f32,
        /// Far plane distance (> near).
        far: f32,
    },
    /// An orthographic view of a rectangle of the x-y plane (2D games):
    /// x grows right, y grows down (screen convention).
    Ortho {
        /// Left edge (x).
        left: f32,
        /// Top edge (y).
        top: f32,
        /// Width of the view.
        width: f32,
        /// Height of the view.
        height: f32,
    },
    /// Positions are already in clip space (x, y, z, with w from
    /// [`Mesh::clip_w`]): the view-projection is the identity, and
    /// normalized device coordinates (-1, -1)..(1, 1) fill the frame, y
    /// up. Used by the GL importer, which transforms the engine's vertices
    /// by the engine's own matrices and viewport.
    Clip,
}

/// A scene ready to rasterize.
#[derive(Clone, Debug, PartialEq)]
pub struct Scene {
    /// Name, e.g. `supertuxkart:lighthouse:start0` (synthetic and
    /// procedural scenes say so in their names).
    pub name: String,
    /// Where the data came from and its licence.
    pub source: String,
    /// Meshes, drawn in order (2D: painter's order).
    pub meshes: Vec<Mesh>,
    /// Materials.
    pub materials: Vec<Material>,
    /// Textures.
    pub textures: Vec<Texture>,
    /// The camera.
    pub camera: Camera,
}

/// A load error: the file, the byte offset where known, and what was wrong.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneError {
    /// File (inside the cache or the repository).
    pub file: PathBuf,
    /// Byte offset of the problem, where known.
    pub offset: Option<u64>,
    /// What was wrong, and what was expected.
    pub message: String,
}

impl SceneError {
    /// An error in `file` at `offset`.
    pub fn at(file: impl AsRef<Path>, offset: u64, message: impl Into<String>) -> Self {
        Self {
            file: file.as_ref().to_path_buf(),
            offset: Some(offset),
            message: message.into(),
        }
    }

    /// An error in `file`, offset unknown.
    pub fn in_file(file: impl AsRef<Path>, message: impl Into<String>) -> Self {
        Self {
            file: file.as_ref().to_path_buf(),
            offset: None,
            message: message.into(),
        }
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.offset {
            Some(o) => write!(f, "{} at offset {o}: {}", self.file.display(), self.message),
            None => write!(f, "{}: {}", self.file.display(), self.message),
        }
    }
}

impl std::error::Error for SceneError {}
