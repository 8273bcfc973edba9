//! Checking an imported GL frame against Mesa (`wasp import-gl
//! --check-mesa`, docs/scenes.md): the capture rewritten into replays
//! whose pictures measure the frame ([`mod@rewrite`]: a texture id per pixel,
//! a count of fragments per pixel), Mesa's and wasp's views of every pixel
//! compared ([`mod@compare`]: coverage, depth complexity, texture) and drawn
//! as disagreement maps ([`images`]).

pub mod compare;
pub mod images;
pub mod rewrite;
mod texels;
mod vertex_alpha;

pub use compare::{compare, Agreement, View};
pub use rewrite::{rewrite, Mode, RewriteError, Rewritten};
