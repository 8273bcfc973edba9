//! wasp-sim: the clock, the paper's worked example, GPU assembly, memory
//! system, workloads and statistics.

pub mod example;
pub mod mem;
pub mod rng;
pub mod synth;
pub mod trace;
