//! The core's observation port: a read-only snapshot of the state a
//! property checker compares against its own model (the scheduler's two
//! registers, the warp slots, the tile), like a scan chain read between
//! clock edges; the description the watchdog prints; the signals of the
//! waveform. Nothing here is on the simulation's hot path.

use super::{CoreSignals, ShaderCore};
use crate::trace::Trace;
use wasp_rtl::queue::QueueClass;
use wasp_rtl::scheduler::LaunchScheduler;
use wasp_waves::{Traceable, Tracer};

/// One occupied warp slot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WarpView {
    /// Slot number.
    pub slot: usize,
    /// Index of its quad in the core's tile.
    pub quad: u32,
    /// Launched from the priority FIFO.
    pub priority: bool,
    /// Waiting for a long-latency miss (the paper's blocked state).
    pub blocked: bool,
    /// Cycle of its launch.
    pub launched: u64,
    /// Ready to issue an ALU instruction.
    pub ready_alu: bool,
    /// Ready to hand a texture instruction to the LDST unit.
    pub ready_tex: bool,
    /// ALU instructions left in its current ALU run.
    pub alu_left: u32,
    /// Its next instruction entry, as an index in the tile's pool.
    pub next_op: u32,
    /// Blocks of its current texture instruction not yet returned.
    pub pending: u32,
}

/// The observable state of one core after a cycle.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CoreSnapshot {
    /// Index of the core's tile in the trace, if it has one.
    pub tile: Option<usize>,
    /// Quads of the tile rasterized into the input queue so far.
    pub rasterized: u32,
    /// Warps in the priority and regular input FIFOs.
    pub queued: [usize; 2],
    /// The 5-bit free-MSHR register.
    pub free_mshrs: u32,
    /// Whether the register follows the cache (policies that read it).
    pub tracks_free_mshrs: bool,
    /// The 7-bit non-blocked priority-warp counter.
    pub nonblocked: u32,
    /// The core's count of warps in flight.
    pub active: u32,
    /// Warp slots.
    pub slots: usize,
    /// Occupied slots, in slot order.
    pub warps: Vec<WarpView>,
    /// Texture instructions in the LDST queue.
    pub ldst: usize,
}

impl ShaderCore {
    /// Read the core's observable state (see [`CoreSnapshot`]).
    pub fn snapshot(&self) -> CoreSnapshot {
        let warps = (0..self.warps.slots())
            .filter(|&s| self.warps.holds(s))
            .map(|s| {
                let w = self.warps.get(s);
                let (ready_alu, ready_tex, alu_left) = self.issue.view(s);
                WarpView {
                    slot: s,
                    quad: w.quad,
                    priority: w.priority,
                    blocked: w.blocked,
                    launched: w.launched_at,
                    ready_alu,
                    ready_tex,
                    alu_left,
                    next_op: w.op,
                    pending: w.pending,
                }
            })
            .collect();
        let sched = self.launch.sched();
        let q = sched.queue();
        CoreSnapshot {
            tile: self.tile,
            rasterized: self.rasterized(),
            queued: [
                q.occupancy(QueueClass::Priority),
                q.occupancy(QueueClass::Regular),
            ],
            free_mshrs: sched.free_mshrs().free().get(),
            tracks_free_mshrs: self.launch.tracks_mshrs(),
            nonblocked: sched.nonblocked().count().get(),
            active: self.warps.active(),
            slots: self.warps.slots(),
            warps,
            ldst: self.ldst.len(),
        }
    }

    /// Surviving quads of the tile its own rasterizer delivered.
    fn rasterized(&self) -> u32 {
        self.raster.as_ref().map_or(0, |r| r.delivered())
    }

    /// The view the waveform and the watchdog read (cheap: the waveform
    /// reads it every cycle).
    fn view(&self) -> CoreView<'_> {
        CoreView {
            id: self.id,
            sched: self.launch.sched(),
            slots: self.warps.slots(),
            active: self.warps.active(),
            ready: self.issue.ready_count(),
            ldst_cap: self.ldst.cap(),
            ldst_len: self.ldst.len(),
            signals: &self.notes.signals,
            tile: self.tile,
            external_raster: self.raster.is_none(),
            rasterized: self.rasterized(),
        }
    }

    /// A description of the core's state (for the watchdog).
    pub fn describe(&self, trace: &Trace) -> String {
        self.view().describe(trace, self.warps.blocked())
    }
}

impl Traceable for ShaderCore {
    fn trace<T: Tracer + ?Sized>(&self, t: &mut T) {
        self.view().trace(t);
    }
}

/// What the waveform and the watchdog show of a core, whichever core
/// model keeps it.
pub(super) struct CoreView<'a> {
    pub(super) id: usize,
    pub(super) sched: &'a LaunchScheduler<u32>,
    pub(super) slots: usize,
    pub(super) active: u32,
    /// Warps ready to issue (ALU or texture).
    pub(super) ready: u32,
    pub(super) ldst_cap: usize,
    pub(super) ldst_len: usize,
    pub(super) signals: &'a CoreSignals,
    pub(super) tile: Option<usize>,
    pub(super) external_raster: bool,
    /// Surviving quads of the tile its own rasterizer delivered.
    pub(super) rasterized: u32,
}

impl CoreView<'_> {
    /// The core's state in words, with `blocked` warps blocked on a
    /// long-latency miss.
    pub(super) fn describe(&self, trace: &Trace, blocked: usize) -> String {
        let tile = self
            .tile
            .map(|t| {
                let tl = &trace.tiles()[t];
                if self.external_raster {
                    return format!(
                        "tile {} at ({}, {}), shared by every core",
                        t,
                        tl.tx(),
                        tl.ty()
                    );
                }
                format!(
                    "tile {} at ({}, {}), {} of {} quads rasterized",
                    t,
                    tl.tx(),
                    tl.ty(),
                    self.rasterized,
                    tl.quad_count()
                )
            })
            .unwrap_or_else(|| "no tile".into());
        format!(
            "core {}: {tile}; {} warps active ({} blocked, {} ready), queue {} priority + {} regular, LDST {} entries, free_mshrs {}, nonblocked_priority {}",
            self.id,
            self.active,
            blocked,
            self.ready,
            self.sched.queue().occupancy(QueueClass::Priority),
            self.sched.queue().occupancy(QueueClass::Regular),
            self.ldst_len,
            self.sched.free_mshrs().free(),
            self.sched.nonblocked().count(),
        )
    }
}

impl Traceable for CoreView<'_> {
    fn trace<T: Tracer + ?Sized>(&self, t: &mut T) {
        t.push_scope("scheduler");
        self.sched.trace(t);
        t.pop_scope();
        let sw = (usize::BITS - self.slots.leading_zeros()).max(1);
        t.signal("warps_active", sw, self.active as u64);
        t.signal("warps_ready", sw, self.ready as u64);
        t.signal("issued", 5, self.signals.issued.min(31) as u64);
        t.bit("tex_issued", self.signals.tex_issued);
        let lw = (usize::BITS - self.ldst_cap.leading_zeros()).max(1);
        t.signal("ldst_occupancy", lw, self.ldst_len as u64);
        t.signal(
            "ldst_presented",
            4,
            self.signals.ldst_presented.min(15) as u64,
        );
        t.bit("ldst_refused", self.signals.ldst_refused);
        t.signal("warps_finished", sw, self.signals.finished as u64);
        t.signal(
            "tile",
            32,
            self.tile.map(|t| t as u64 + 1).unwrap_or(0) & 0xffff_ffff,
        );
    }
}
