//! The GL importer: one frame of an apitrace capture of a fixed-function
//! OpenGL 1.x program turned into a [`crate::Scene`] that wasp's own
//! rasterizer, Early-Z and texture path draw into a trace
//! (`wasp import-gl`, `docs/import-gl.md`).
//!
//! The capture is read by `wasp-gltrace`; the importer tracks the GL state
//! every call sets from the capture's start ([`tracker`]: matrices,
//! arrays and buffers, textures, the fixed-function state), records the
//! selected frame's draws in clip space ([`draw`]) and places them in the
//! frame with one material per draw carrying the engine's pipeline state
//! ([`scene`]; 3D textures as stacks of slices, [`volume`]); frames are
//! read in one pass ([`mod@import`]), and [`summary`] reports what it saw.

pub mod args;
pub mod arrays;
pub mod draw;
pub mod enums;
pub mod immediate;
pub mod import;
pub mod matrices;
pub mod scene;
pub mod state;
pub mod summary;
pub mod textures;
pub mod tracker;
pub mod volume;

pub use import::{import, ImportError, ImportOptions, Imported, Reader};
pub use scene::TextureInfo;
pub use summary::{DrawSummary, Summary};
