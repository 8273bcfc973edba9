//! Reads apitrace captures: the file container (Snappy chunks with
//! apitrace's own framing, or gzip), the header (format version, API,
//! properties) and the calls with their signatures, into [`Call`]s of typed
//! [`Value`]s, streamed one decompressed chunk at a time.
//!
//! The format is apitrace's `docs/FORMAT.markdown`. This crate knows no GL
//! state: it only decodes what was recorded. Frame boundaries are decided
//! by the call's name ([`is_frame_end`]), as apitrace itself does.
//!
//! ```no_run
//! let mut capture = wasp_gltrace::Capture::open("quads.trace")?;
//! capture.require_gl()?;
//! for call in capture {
//!     let call = call?;
//!     println!("{} {}", call.no, call.name);
//! }
//! # Ok::<(), wasp_gltrace::CaptureError>(())
//! ```
//!
//! [`CaptureWriter`] writes calls back into a capture that `glretrace`
//! replays (the inverse of the reader, for rewritten captures).
//!
//! It stands at the bottom of the workspace with `wasp-trace`: it depends
//! on no crate of the workspace.

mod api;
mod call;
mod capture;
mod container;
mod decoder;
mod error;
mod events;
mod frames;
mod stream;
mod value;
mod writer;

pub use api::Api;
pub use call::{is_frame_end, Call};
pub use capture::{Capture, MAX_VERSION};
pub use container::Compression;
pub use error::CaptureError;
pub use frames::{count_frames, frames, Frame, Frames};
pub use value::Value;
pub use writer::{CaptureWriter, WRITE_VERSION};
