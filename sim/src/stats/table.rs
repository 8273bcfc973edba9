//! The statistics as a readable table.

use super::{is_default, LevelStats, RunStats};
use std::fmt::Write as _;

impl RunStats {
    /// A readable table.
    pub fn to_table(&self) -> String {
        let mut s = String::new();
        self.machine_lines(&mut s);
        self.cache_lines(&mut s);
        self.warp_lines(&mut s);
        self.pipeline_lines(&mut s);
        self.workload_lines(&mut s);
        self.frame_lines(&mut s);
        s
    }

    /// The machine, the run's totals and the filter unit.
    fn machine_lines(&self, s: &mut String) {
        let _ = writeln!(s, "machine {}  |  workload {}", self.machine, self.workload);
        let _ = writeln!(
            s,
            "warps per core {}  input queue {} entries",
            self.occupancy.max_warps, self.input_queue
        );
        let _ = write!(
            s,
            "policy {}  launch rule {}  subset {}  ideal memory {}",
            self.policy, self.launch_rule, self.subset.subset, self.ideal_memory
        );
        if !is_default(&self.issue) {
            let _ = write!(s, "  issue {}", self.issue);
        }
        if !is_default(&self.texture_cache) {
            let _ = write!(s, "  texture cache {}", self.texture_cache);
        }
        s.push('\n');
        let _ = writeln!(
            s,
            "dispatch {}  core map {}  colour flush {}  dram {}",
            self.dispatch, self.core_map, self.color_flush, self.dram_model
        );
        let _ = writeln!(
            s,
            "cycles {}  ipc {:.3}  warps {}  instructions {} ({} texture)  tiles {}",
            self.cycles, self.ipc, self.warps, self.instructions, self.tex_instructions, self.tiles
        );
        let f = &self.filter;
        let _ = writeln!(
            s,
            "filter {}/{} cycles ({})  trilinear {} ({:.1}%)  busy {:.2}%  wait {:.2} cycles/instr",
            f.cycles_bilinear,
            f.cycles_trilinear,
            f.timing,
            f.trilinear_instructions,
            100.0 * f.trilinear_share,
            100.0 * f.busy_fraction,
            f.avg_wait
        );
    }

    /// Each cache level, the DRAM and the memory latency per warp.
    fn cache_lines(&self, s: &mut String) {
        let _ = writeln!(
            s,
            "{:<6}{:>12}{:>12}{:>10}{:>12}{:>10}{:>9}{:>13}",
            "level", "accesses", "hits", "misses", "secondary", "stalls", "stall%", "outstanding"
        );
        let mut level = |name: &str, l: &LevelStats| {
            let _ = writeln!(
                s,
                "{:<6}{:>12}{:>12}{:>10}{:>12}{:>10}{:>8.2}%{:>13.2}",
                name,
                l.accesses,
                l.hits,
                l.misses,
                l.secondary_misses,
                l.stall_cycles,
                100.0 * l.stall_fraction,
                l.avg_outstanding_misses
            );
        };
        if let Some(l0) = &self.l0 {
            level("l0", l0);
        }
        level("l1", &self.l1);
        level("l2", &self.l2);
        let _ = writeln!(
            s,
            "dram requests {} (row hits {}, row misses {}), avg latency {:.1} cycles",
            self.dram.requests, self.dram.row_hits, self.dram.row_misses, self.dram.avg_latency
        );
        let _ = writeln!(
            s,
            "memory latency per warp: all {:.1}, priority {:.1}, regular {:.1} cycles",
            self.memory_latency.all, self.memory_latency.priority, self.memory_latency.regular
        );
    }

    /// Occupancy, hold idle cycles, the gate and the blocked episodes.
    fn warp_lines(&self, s: &mut String) {
        let _ = writeln!(
            s,
            "warps per core {:.1} of {} (below 25%: {:.1}% of core-cycles, below 50%: {:.1}%); priority warps {}",
            self.avg_warps_per_core,
            self.occupancy.max_warps,
            100.0 * self.occupancy.below_quarter,
            100.0 * self.occupancy.below_half,
            self.subset.priority_warps,
        );
        let per_core: Vec<String> = self
            .held_cycles_per_core
            .iter()
            .map(u64::to_string)
            .collect();
        let _ = writeln!(
            s,
            "hold idle core-cycles {} (per core {}): a free slot, a priority warp waiting, nothing launched",
            self.held_cycles,
            per_core.join(" ")
        );
        let _ = writeln!(
            s,
            "gate: {} launches with both FIFOs waiting, {} of them regular ({:.1}%: the priority warp waited)",
            self.gate.both_waiting,
            self.gate.regular_first,
            100.0 * self.gate.closed_share
        );
        let b = &self.blocked;
        let _ = writeln!(
            s,
            "blocked on {}: {} episodes ({:.1}% of texture instructions; {} of priority warps), mean {:.1} cycles (priority {:.1})",
            self.blocked_on,
            b.episodes,
            100.0 * b.episode_share,
            b.priority_episodes,
            b.mean_cycles,
            b.priority_mean_cycles
        );
    }

    /// The raster pipeline, the tiles and the lead of priority warps.
    fn pipeline_lines(&self, s: &mut String) {
        let r = &self.raster;
        let _ = writeln!(
            s,
            "raster: {} quads ({} rejected by Early-Z), back-pressure {} cycles, barrier wait {} cycles, {} colour lines flushed",
            r.quads_rasterized, r.quads_rejected, r.backpressure_cycles, r.barrier_cycles, r.flush_lines
        );
        if let Some(p) = &self.prefetch {
            p.table_lines(s);
        }
        let t = &self.tile_timing;
        let _ = writeln!(
            s,
            "tiles: {:.0} cycles each on average, fill {:.0} ({:.1}%), drain {:.0} ({:.1}%), {:.0} primary misses",
            t.mean_cycles,
            t.mean_fill,
            100.0 * t.fill_share,
            t.mean_drain,
            100.0 * t.drain_share,
            t.mean_primary_misses
        );
        let l = &self.priority_lead;
        if l.priority_warps > 0 {
            let _ = writeln!(
                s,
                "priority lead: mean {:+.1} positions, {:.1}% ahead, {:.1}% after a regular warp of their subtile",
                l.mean,
                100.0 * l.ahead_share,
                100.0 * l.after_subtile_regular_share
            );
        }
    }

    /// The subset, the workload and the energy.
    fn workload_lines(&self, s: &mut String) {
        let _ = writeln!(
            s,
            "subset size ratio {:.4}, texture footprint ratio {:.3}",
            self.subset.subset_size_ratio, self.subset.texture_footprint_ratio
        );
        let _ = writeln!(
            s,
            "workload: mem-instr ratio {:.3}, block reuse {:.1}, CF {:.2}, Min_Estimate1 {:.3}, Min_Estimate2 {:.3}",
            self.mem_instr_ratio, self.block_reuse, self.cf, self.min_estimate1, self.min_estimate2
        );
        let e = &self.energy;
        let _ = writeln!(
            s,
            "energy {:.1} uJ (alu {:.1}, texture {:.1}, l0 {:.1}, l1 {:.1}, l2 {:.1}, dram {:.1}, static {:.1})",
            e.total_nj / 1000.0,
            e.alu_nj / 1000.0,
            e.texture_nj / 1000.0,
            e.l0_nj / 1000.0,
            e.l1_nj / 1000.0,
            e.l2_nj / 1000.0,
            e.dram_nj / 1000.0,
            e.static_nj / 1000.0
        );
    }
}
