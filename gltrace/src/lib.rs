//! Reads apitrace captures: the file container (Snappy chunks with
//! apitrace's own framing), the header (format version, API, properties)
//! and the calls with their signatures, into [`Call`]s of typed
//! [`Value`]s.
//!
//! The format is apitrace's `docs/FORMAT.markdown`. This crate knows no GL
//! state: it only decodes what was recorded. Frame boundaries are decided
//! by the call's name ([`is_frame_end`]), as apitrace itself does.
//!
//! It stands at the bottom of the workspace with `wasp-trace`: it depends
//! on no crate of the workspace.

mod call;
mod error;
mod value;

pub use call::{is_frame_end, Call};
pub use error::CaptureError;
pub use value::Value;
