//! `wasp scenes`, `wasp render` and `wasp characterize`: real-game and
//! procedural scenes through the TBR front end, one file per command
//! (`scenes list`, `scenes fetch`, `render`, `characterize`; `scenes
//! capture` is [`crate::capture`]).

mod characterize;
mod defs;
mod fetch;
mod list;
mod render;
mod scenes;
mod timings;

pub use characterize::{characterize, CharacterizeArgs};
pub use render::{render, write_trace, RenderArgs};
pub use scenes::{scenes, ScenesArgs};
