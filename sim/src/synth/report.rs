//! What a generated trace was asked for beside what it measures.

use super::GenParams;
use crate::trace::{Trace, TraceStats};
use serde::Serialize;
use std::fmt;

/// What was asked beside what a generated trace measures.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct GenReport {
    /// The workload name.
    pub workload: String,
    /// Requested memory-instruction ratio.
    pub requested_mem_ratio: f64,
    /// Requested coverage.
    pub requested_coverage: f64,
    /// Requested base texel scale (texels per pixel).
    pub texel_scale: f64,
    /// The measured statistics of the trace.
    pub measured: TraceStats,
}

impl GenReport {
    /// The report of `trace`, generated from `params`.
    pub fn new(params: &GenParams, trace: &Trace) -> GenReport {
        GenReport {
            workload: trace.header().workload.clone(),
            requested_mem_ratio: params.mem_ratio,
            requested_coverage: params.coverage,
            texel_scale: params.texel_scale,
            measured: trace.stats(),
        }
    }
}

impl fmt::Display for GenReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let m = &self.measured;
        write!(
            f,
            "{}: {} tiles, {} warps; mem-instr ratio {:.3} (requested {}), coverage {:.3} \
             (requested {}); measured at texel scale {}: block reuse in tile {:.2}, CF {:.2}, \
             Min_Estimate1 {:.3}, Min_Estimate2 {:.3}",
            self.workload,
            m.tiles,
            m.warps,
            m.mem_instr_ratio,
            self.requested_mem_ratio,
            m.coverage,
            self.requested_coverage,
            self.texel_scale,
            m.reuse,
            m.cf,
            m.min_estimate1,
            m.min_estimate2
        )
    }
}
