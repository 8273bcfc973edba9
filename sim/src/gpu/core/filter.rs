//! The core's one texture filter unit. It serves texture instructions in
//! the order their last block arrives: an instruction whose data arrives
//! at cycle `a` starts filtering at `s = max(a, filter free)` and holds the
//! filter for its `f` filter cycles (`core.filter_cycles_bilinear` or
//! `_trilinear`), so the filter is free again at `s + f`. With
//! `L = max(core.texture_latency, 1)` the warp continues at
//! `max(s + f, a + L)` (`core.filter_timing = "overlap"`) or `s + f + L`
//! (`"serial"`); with no filter cycles, at `a + L`.
//!
//! The unit has no cycle of its own to run: each instruction's pass is
//! placed in time when its data arrives ([`accept`](Filter::accept)).

use super::CoreStats;
use crate::config::{CoreConfig, FilterTiming};

/// The filter unit.
#[derive(Clone, Copy, Debug)]
pub(super) struct Filter {
    /// Filter cycles of a quad-sample, [bilinear, trilinear].
    cycles: [u64; 2],
    /// The texture unit's latency after the data, at least 1.
    latency: u64,
    /// The filter pass is part of the latency (else precedes it).
    overlap: bool,
    /// First cycle the filter is free.
    free: u64,
}

impl Filter {
    /// The unit of a core of `core`, free.
    pub(super) fn new(core: &CoreConfig) -> Self {
        Filter {
            cycles: [
                u64::from(core.filter_cycles_bilinear),
                u64::from(core.filter_cycles_trilinear),
            ],
            latency: u64::from(core.texture_latency.max(1)),
            overlap: core.filter_timing == FilterTiming::Overlap,
            free: 0,
        }
    }

    /// The data of a texture instruction (`trilinear` or not) arrived at
    /// `now`: its pass is placed after the passes before it. Returns the
    /// cycle its warp continues; counts the filter's busy and wait cycles.
    #[inline(always)]
    pub(super) fn accept(&mut self, now: u64, trilinear: bool, stats: &mut CoreStats) -> u64 {
        let f = self.cycles[trilinear as usize];
        let start = now.max(self.free);
        self.free = start + f;
        stats.filter_busy_cycles += f;
        stats.filter_wait_cycles += start - now;
        if self.overlap {
            (start + f).max(now + self.latency)
        } else {
            start + f + self.latency
        }
    }

    /// No pass runs in cycle `now`.
    pub(super) fn is_idle(&self, now: u64) -> bool {
        self.free <= now
    }
}

#[cfg(test)]
mod tests {
    //! The texture filter unit: its rate, its order and how it adds to
    //! the texture latency, alone and in a core.
    use super::Filter;
    use crate::config::FilterTiming;
    use crate::config::MachineConfig;
    use crate::gpu::core::testkit::{cfg, trace, OVERLAP, SERIAL};
    use crate::gpu::core::CoreStats;
    use crate::gpu::Gpu;
    use crate::run::simulate;
    use crate::run::RunOptions;
    use crate::stats::RunStats;
    use crate::trace::{Instr, Trace};

    /// (launch, finish) of each warp, by quad index, and the statistics.
    fn run(c: &MachineConfig, t: &Trace) -> (Vec<(u64, u64)>, RunStats) {
        let mut gpu = Gpu::new(c, t).unwrap();
        gpu.record_warps();
        while !gpu.done() {
            gpu.step().unwrap();
        }
        let mut r = gpu.take_records();
        r.sort_by_key(|w| w.quad);
        let times = r.iter().map(|w| (w.launched, w.finished)).collect();
        let s = simulate(c, t, &RunOptions::default(), &mut |_, _| {}).unwrap();
        (times, s)
    }

    /// The unit alone: a pass hides in the latency under `overlap` and
    /// follows it under `serial`; passes queue in order of arrival.
    #[test]
    fn passes_queue_in_arrival_order_and_add_to_the_latency() {
        let mut core = MachineConfig::paper().core;
        core.texture_latency = 4;
        core.filter_cycles_bilinear = 2;
        core.filter_cycles_trilinear = 6;
        let mut s = CoreStats::default();
        let mut f = Filter::new(&core);
        assert!(f.is_idle(0));
        assert_eq!(f.accept(10, false, &mut s), 14, "max(10 + 2, 10 + 4)");
        assert!(!f.is_idle(11) && f.is_idle(12));
        assert_eq!(f.accept(10, true, &mut s), 18, "from 12, 6 cycles");
        assert_eq!(f.accept(11, false, &mut s), 20, "from 18, 2 cycles");
        assert_eq!((s.filter_busy_cycles, s.filter_wait_cycles), (10, 2 + 7));
        core.filter_timing = FilterTiming::Serial;
        let mut f = Filter::new(&core);
        assert_eq!(f.accept(10, false, &mut s), 16, "10 + 2 + 4");
    }

    /// A lone warp: under `overlap` a pass no longer than the texture
    /// latency (4) costs nothing, a longer one its excess; under `serial`
    /// every filter cycle adds.
    #[test]
    fn a_lone_warp_pays_the_filter_pass_beyond_the_latency() {
        let bil = trace(&[(0, 0)], &[Instr::Alu(1), Instr::Tex(&[9]), Instr::Alu(1)]);
        let tri = trace(
            &[(0, 0)],
            &[Instr::Alu(1), Instr::TriTex(&[9]), Instr::Alu(1)],
        );
        let span = |c: &MachineConfig, t: &Trace| {
            let (w, _) = run(c, t);
            w[0].1 - w[0].0
        };
        let base = span(&cfg(0, 0, OVERLAP), &bil);
        assert_eq!(span(&cfg(0, 0, OVERLAP), &tri), base);
        assert_eq!(span(&cfg(0, 0, SERIAL), &tri), base);
        assert_eq!(span(&cfg(1, 2, OVERLAP), &bil), base);
        assert_eq!(span(&cfg(1, 2, OVERLAP), &tri), base);
        assert_eq!(span(&cfg(1, 4, OVERLAP), &tri), base, "f = latency");
        assert_eq!(span(&cfg(1, 7, OVERLAP), &tri), base + 3);
        assert_eq!(span(&cfg(7, 1, OVERLAP), &bil), base + 3);
        assert_eq!(span(&cfg(7, 1, OVERLAP), &tri), base);
        assert_eq!(span(&cfg(1, 2, SERIAL), &bil), base + 1);
        assert_eq!(span(&cfg(1, 2, SERIAL), &tri), base + 2);
        let (_, s) = run(&cfg(1, 7, OVERLAP), &tri);
        assert_eq!(s.filter.busy_cycles, 7);
        assert_eq!(s.filter.wait_cycles, 0);
        assert_eq!(s.filter.trilinear_instructions, 1);
        assert_eq!(
            (s.filter.cycles_bilinear, s.filter.cycles_trilinear),
            (1, 7)
        );
        assert_eq!(s.filter.timing, FilterTiming::Overlap);
    }

    /// Quads of one core whose one block arrives in the same cycle (the
    /// first misses, the others merge into its MSHR) queue at the filter:
    /// the k-th waits k filter passes, and finishes a pass after the one
    /// before it once the queue outgrows the latency.
    #[test]
    fn data_arriving_together_queues_at_the_one_filter() {
        // Shared-tile dispatch sends an 8x8-quad block to one core: the 16
        // quads of the 8x8-pixel tile all run on it.
        let quads: Vec<(u32, u32)> = (0..4).flat_map(|y| (0..4).map(move |x| (x, y))).collect();
        let tri = trace(&quads, &[Instr::TriTex(&[9]), Instr::Alu(1)]);
        let (free, s0) = run(&cfg(0, 0, OVERLAP), &tri);
        assert_eq!(s0.filter.wait_cycles, 0);
        assert_eq!(s0.filter.busy_cycles, 0);
        let (w, s) = run(&cfg(1, 8, SERIAL), &tri);
        assert_eq!(s.tex_instructions, 16);
        assert_eq!(s.filter.trilinear_instructions, 16);
        assert!((s.filter.trilinear_share - 1.0).abs() < 1e-12);
        assert_eq!(s.filter.busy_cycles, 16 * 8);
        // Each warp's data arrives when it would have without a filter:
        // it waits for the passes of those before it.
        let mut ends: Vec<u64> = w.iter().map(|x| x.1).collect();
        ends.sort_unstable();
        for pair in ends.windows(2) {
            assert!(pair[1] - pair[0] >= 8, "{ends:?}");
        }
        assert!(
            s.filter.wait_cycles >= 8 * (15 * 16 / 2) / 2,
            "{:?}",
            s.filter
        );
        assert!(
            s.cycles > s0.cycles + 15 * 8,
            "{} vs {}",
            s.cycles,
            s0.cycles
        );
        assert!(s.filter.avg_wait > 0.0 && s.filter.busy_fraction > 0.0);
        // No filter cycles: every warp as without a filter.
        let (w0, _) = run(&cfg(0, 0, SERIAL), &tri);
        assert_eq!(w0, free);
    }

    /// With both filter cycles 0 a trilinear trace runs exactly as the
    /// same trace bilinear, either timing: the marker changes nothing but
    /// the count.
    #[test]
    fn no_filter_cycles_make_trilinear_cost_nothing() {
        let quads: Vec<(u32, u32)> = (0..4).flat_map(|y| (0..4).map(move |x| (x, y))).collect();
        let prog_b = [
            Instr::Alu(2),
            Instr::Tex(&[1, 2]),
            Instr::Alu(1),
            Instr::Tex(&[3]),
        ];
        let prog_t = [
            Instr::Alu(2),
            Instr::TriTex(&[1, 2]),
            Instr::Alu(1),
            Instr::Tex(&[3]),
        ];
        let (b, t) = (trace(&quads, &prog_b), trace(&quads, &prog_t));
        for timing in [OVERLAP, SERIAL] {
            let c = cfg(0, 0, timing);
            let (wb, mut sb) = run(&c, &b);
            let (wt, mut st) = run(&c, &t);
            assert_eq!(wb, wt);
            assert_eq!(
                (
                    sb.filter.trilinear_instructions,
                    st.filter.trilinear_instructions
                ),
                (0, 16)
            );
            sb.filter.trilinear_instructions = 0;
            st.filter.trilinear_instructions = 0;
            sb.filter.trilinear_share = 0.0;
            st.filter.trilinear_share = 0.0;
            assert_eq!(sb.to_json(), st.to_json());
        }
        // With a rate, trilinear costs more than bilinear.
        let c = cfg(1, 8, SERIAL);
        assert!(run(&c, &t).1.cycles > run(&c, &b).1.cycles);
    }
}
