//! Studies: many simulations over scenes and machines, run in parallel,
//! cached point by point, and read back for reports and merges.
//!
//! - [`point`]: what a point is (scene, base configuration, overrides) and
//!   the key its result is stored under;
//! - [`cache`]: the study folder of finished points and scenes;
//! - [`runner`]: runs tasks with shared traces, progress and timing;
//! - [`count`]: what a run would do, counted without running;
//! - [`table`]: point records as CSV;
//! - [`sweep`]: a user's grid of scenes, machines, dispatches and policies;
//! - [`jobs`]: a sweep's points as cluster jobs;
//! - [`merge`]: records of several folders combined into a sweep's results.
//!
//! `wasp reproduce` (the paper's experiments) and `wasp sweep` (a user's
//! own grid) are both built on it; `wasp merge` reads its folders.

pub mod cache;
pub mod count;
pub mod jobs;
pub mod merge;
pub mod point;
pub mod runner;
pub mod sweep;
pub mod table;
