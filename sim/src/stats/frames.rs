//! [`FrameRecord`]: what one frame of a run of several frames measured —
//! the counters that matter for the paper's comparisons (cycles, IPC, the
//! caches' accesses and misses, DRAM requests, memory latency, energy),
//! one record per frame in [`RunStats::frames`](super::RunStats::frames).

use super::{LatencyStats, LevelStats, RunStats};
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;

/// One cache level's counters in one frame, summed over its instances.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FrameLevel {
    /// Accesses accepted.
    pub accesses: u64,
    /// Primary misses.
    pub misses: u64,
    /// Secondary misses (merged into an MSHR entry).
    pub secondary_misses: u64,
    /// Stall cycles / (cycles x instances).
    pub stall_fraction: f64,
}

impl FrameLevel {
    fn of(l: &LevelStats) -> Self {
        FrameLevel {
            accesses: l.accesses,
            misses: l.misses,
            secondary_misses: l.secondary_misses,
            stall_fraction: l.stall_fraction,
        }
    }
}

/// What one frame measured. A frame runs from the cycle after the previous
/// frame ended (every tile flushed, memory idle) to its own end; its
/// counters are its own, the caches' and DRAM's contents those the frames
/// before left.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct FrameRecord {
    /// The frame's index in the trace (from 0).
    pub frame: usize,
    /// The run's cycle before the frame's first (0 for the first frame run).
    pub start_cycle: u64,
    /// GPU cycles of the frame.
    pub cycles: u64,
    /// Warp instructions per cycle.
    pub ipc: f64,
    /// Tiles rendered.
    pub tiles: u64,
    /// Warps (quads) run.
    pub warps: u64,
    /// Warp instructions.
    pub instructions: u64,
    /// Texture instructions.
    pub tex_instructions: u64,
    /// The L0s (absent without L0).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub l0: Option<FrameLevel>,
    /// The L1s.
    pub l1: FrameLevel,
    /// The L2.
    pub l2: FrameLevel,
    /// Main-memory read requests.
    pub dram_requests: u64,
    /// Their average latency in cycles.
    pub dram_avg_latency: f64,
    /// Colour-buffer lines written.
    pub dram_writes: u64,
    /// Average memory latency per warp.
    pub memory_latency: LatencyStats,
    /// Energy of the frame, in nanojoules.
    pub energy_nj: f64,
}

impl FrameRecord {
    /// The record of frame `frame`, started after cycle `start_cycle`, from
    /// its statistics.
    pub fn of(frame: usize, start_cycle: u64, s: &RunStats) -> Self {
        FrameRecord {
            frame,
            start_cycle,
            cycles: s.cycles,
            ipc: s.ipc,
            tiles: s.tiles,
            warps: s.warps,
            instructions: s.instructions,
            tex_instructions: s.tex_instructions,
            l0: s.l0.as_ref().map(FrameLevel::of),
            l1: FrameLevel::of(&s.l1),
            l2: FrameLevel::of(&s.l2),
            dram_requests: s.dram.requests,
            dram_avg_latency: s.dram.avg_latency,
            dram_writes: s.dram.writes,
            memory_latency: s.memory_latency.clone(),
            energy_nj: s.energy.total_nj,
        }
    }
}

impl RunStats {
    /// The run's last cycle: [`cycles`](RunStats::cycles) for a one-frame
    /// trace, the end of the last frame for several (the cycles the
    /// waveform and the timeline count).
    pub fn last_cycle(&self) -> u64 {
        self.frames
            .last()
            .map_or(self.cycles, |f| f.start_cycle + f.cycles)
    }

    /// The per-frame table of a trace of several frames (nothing for one
    /// frame): a line per frame run, the last one the report's.
    pub(super) fn frame_lines(&self, s: &mut String) {
        let Some(last) = self.frames.last() else {
            return;
        };
        let _ = writeln!(
            s,
            "frames: {} run, the report above is frame {}'s (after {} earlier, caches and DRAM \
             carried over)",
            self.frames.len(),
            last.frame,
            self.frames.len() - 1
        );
        let _ = writeln!(
            s,
            "{:>7}{:>12}{:>8}{:>9}{:>11}{:>10}{:>10}{:>10}{:>10}{:>10}{:>9}",
            "frame",
            "cycles",
            "ipc",
            "warps",
            "l0 miss",
            "l1 acc",
            "l1 miss",
            "l2 miss",
            "dram req",
            "latency",
            "energy"
        );
        for f in &self.frames {
            let l0 =
                f.l0.as_ref()
                    .map_or("-".to_string(), |l| l.misses.to_string());
            let _ = writeln!(
                s,
                "{:>7}{:>12}{:>8.3}{:>9}{:>11}{:>10}{:>10}{:>10}{:>10}{:>10.1}{:>7.1}uJ",
                f.frame,
                f.cycles,
                f.ipc,
                f.warps,
                l0,
                f.l1.accesses,
                f.l1.misses,
                f.l2.misses,
                f.dram_requests,
                f.memory_latency.all,
                f.energy_nj / 1000.0
            );
        }
    }
}
