//! wasp-sim: the clock, the paper's worked example, GPU assembly, memory
//! system, workloads and statistics.

pub mod bench;
pub mod config;
pub mod cost;
pub mod example;
pub mod gpu;
pub mod mem;
pub mod param;
/// The deterministic generator (in `wasp-trace`), under its old path.
pub use wasp_trace::rng;
pub mod run;
pub mod stats;
pub mod synth;
pub mod timeline;
/// The trace format (the `wasp-trace` crate), re-exported under its old
/// path.
pub use wasp_trace as trace;
