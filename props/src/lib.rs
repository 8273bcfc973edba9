//! wasp-props: safety properties of the WaSP scheduler blocks of `wasp-rtl`
//! and of the `wasp-sim` caches and GPU around them.
//!
//! Each property is a plain function over a block's inputs and state that
//! returns `Result<(), Cex>` (a [`Cex`] names the property and carries the
//! counterexample's values). Each is called twice:
//!
//! * by a `#[kani::proof]` harness on `kani::any()` inputs, bounded by
//!   `kani::any_where` and `kani::assume`, in a `proofs` module compiled
//!   under `cfg(kani)` (Kani proves it: `cargo kani -p wasp-props` where
//!   Kani is installed) or under the feature `kani-shim` (the shim crate
//!   `wasp-kani-shim` runs it as a test on every case of its domain, or on
//!   seeded random cases where the domain is too large:
//!   `scripts/harnesses.sh`; see `README.md`);
//! * by a `#[test]` twin that checks every value of the finite domain, or,
//!   for sequential properties, every input sequence up to a stated depth
//!   (run with `cargo test -p wasp-props`).
//!
//! "Exact" below means unbounded `i64` arithmetic on the register values;
//! CF is `q / 4` with a 5-bit `q`, so the real-number WaSP condition
//! `free - CF x nonblocked > T` is the integer `4 free - q nonblocked > 4 T`.
//!
//! # (a) No priority launch when `Real_freeMSHRs <= Threshold`
//!
//! Under the launch rule `hold` (the paper's); under `launch` a priority
//! warp goes below the threshold only when no regular warp waits, and the
//! scheduler never idles while a warp waits. Every body below checks both
//! rules.
//!
//! | body | harness | test twin | domain |
//! |---|---|---|---|
//! | [`policy::wasp_priority_only_above_threshold`] | `policy::proofs::proof_wasp_priority_only_above_threshold` | `policy::tests::exhaustive_wasp_select_q0_to_15`, `..._q16_to_31` | free 0..=31 x nonblocked 0..=127 x q 0..=31 x T 0..=31 x both FIFO flags: 16,777,216 decisions, each under both launch rules; `select` gives `Priority` only if the exact condition holds (under `launch`: or no regular warp waits), never idles under `launch` with a warp waiting, and equals the exact WaSP rule |
//! | [`policy::wasp_without_datapath_never_priority`] | `proof_wasp_without_datapath_never_priority` | `exhaustive_wasp_without_datapath` | q x T x free x flags (131,072) |
//! | [`policy::policy_matches_reference`] | `proof_other_policies_match_reference` | `exhaustive_other_policies` | Baseline, Fullpriority, FreeMSHR-N for N 0..=31, x free x nonblocked x flags (557,056) |
//! | [`scheduler::SchedulerCheck`] (`front`/`back`, via [`scheduler::explore_wasp`]) | `scheduler::proofs::proof_wasp_scheduler_cycles` (3 cycles, any CF, T < 4, 4 MSHRs, queue 2) | `scheduler::tests::exhaustive_wasp_scheduler_depth6_a`, `..._b` (hold), `..._launch` (launch: (T, q) in {(1,0), (1,4), (0,10)}) | `LaunchScheduler` with WaSP, 2 MSHRs, queue 2, (T, q) in {(0,4), (0,10), (1,0), (1,4)}: every input sequence of up to 6 cycles over a 192-letter alphabet (offer nothing / a priority quad / a regular quad, enable or not, each event count 0 or 1, reduced to legal), as a state graph (about 330 states, 44,000 transitions per configuration); plus `extreme_register_values_through_the_scheduler` (127 priority warps, CF 7.75) |
//!
//! At the scheduler level every cycle checks: the decision equals the exact
//! rule on that cycle's register values, a priority launch happens only
//! when the exact condition held (under `launch`: or no regular warp
//! waited), `launch` selects a FIFO whenever a warp waits, `held` is set
//! exactly when `hold` idles with a lone priority warp, the datapath outputs are exact, the
//! launched warp is the reference FIFO head, the registers equal the
//! model's unbounded counters after the clock, no `RegisterFault` under
//! legal events, and queue conservation.
//!
//! # (b) The shift-add comparison is the exact rational comparison
//!
//! | body | harness | test twin | domain |
//! |---|---|---|---|
//! | [`datapath::datapath_exact`] | `datapath::proofs::proof_datapath_exact` | `datapath::tests::exhaustive_datapath_exact_q0_to_15`, `..._q16_to_31` | free x nonblocked x q x T: 4,194,304 points; `q n` fits the 12-bit accumulator, `product == floor(q n / 4)`, the exact `free - product` fits 11 bits and equals `real_free`, `priority_over_regular == (4 free - q n > 4 T)` |
//! | [`datapath::shift_add_exact`] | `proof_shift_add_exact` | `exhaustive_shift_add` | nonblocked x q (4,096) |
//! | [`datapath::paper_cf_is_shift_add`] | `proof_paper_cf_is_shift_add` | `exhaustive_paper_cf` | nonblocked (128): for q = 10, the product is `(n << 1) + (n >> 1)` |
//! | [`datapath::subtractor_exact`] | `proof_subtractor_exact` | `exhaustive_subtractor` | the subtractor's whole input domain, free x 10-bit product (32,768) |
//! | [`datapath::comparator_exact`] | `proof_comparator_exact` | `exhaustive_comparator` | the comparator's whole input domain, 11-bit signed x T (65,536) |
//!
//! # (c) The 5-bit register and the 7-bit counter never wrap
//!
//! | body | harness | test twin | domain |
//! |---|---|---|---|
//! | [`counters::free_mshr_next_exact`] | `counters::proofs::proof_free_mshr_next_exact` | `counters::tests::exhaustive_free_mshr_cap0_to_21`, `..._cap22_to_31` | every capacity 0..=31, free 0..=capacity, allocs and replies each 0..=255, legal or not: 34,603,008 points; `Ok(exact)` iff in range, else a fault with the exact attempted value; `FreeMshrReg::legal` equals the [`counters::MshrModel`] |
//! | [`counters::nonblocked_tracks_model`] | `proof_nonblocked_tracks_model` | `exhaustive_nonblocked_legal_0_to_48`, `..._49_to_127`; `exhaustive_nonblocked_tracks_model_small` | every legal (counter, event) of the [`counters::PriorityModel`] (at most 127 priority warps in the core): 68,511,040 points; the small twin runs the body on every model state of up to 16 warps x every event with counts 0..=17 |
//! | [`counters::nonblocked_next_exact`] | `proof_nonblocked_next_exact` (every `u8` count) | `edge_domain_nonblocked` | count 0..=127 x launched x blocked, unblocked, finished each in 0..=8, 60..=68, 123..=133, 250..=255 (10,976,000 points; the full `u8` domain, 4.3e9, is left to Kani) |
//!
//! # (d) The split queue loses, duplicates and reorders nothing
//!
//! | body | harness | test twin | domain |
//! |---|---|---|---|
//! | [`queue::queue_step`], [`queue::queue_sequence`] | `queue::proofs::proof_queue_sequence` (6 operations, capacity 1..=4) | `queue::tests::exhaustive_queue_sequences` | capacity 0..=4, every sequence of push/pop priority/regular of length up to 8 (87,380 steps per capacity), against two unbounded `VecDeque`s and an explicit capacity check |
//!
//! # (e) Subset sizes
//!
//! | body | harness | test twin | domain |
//! |---|---|---|---|
//! | [`subset::mesh_quad_exact`], [`subset::mesh_selects_one_over_k_squared`] | `subset::proofs::proof_mesh_quad_exact` (per quad; the count follows) | `subset::tests::exhaustive_mesh` | k in {2, 4, 8, 16} x every quad of a 32 x 32 tile: selected iff the low log2(k) bits of x and y are zero, 1024 / k^2 in all |
//! | [`subset::selects_one_sixteenth`] | (none: enumeration over a tile) | `subset::tests::exhaustive_sixteenths` | hlines, vlines, top16, mesh4, random with 7 seeds, built directly and from `SubsetSpec`: 64 of 1024 quads each |
//!
//! # (f) A cache's MSHR file (`wasp-sim`)
//!
//! | body | harness | test twin | domain |
//! |---|---|---|---|
//! | [`mshr_file::cache_step`], [`mshr_file::cache_sequence`] | `mshr_file::proofs::proof_cache_sequence` (5 operations, 1..=3 MSHRs, 0..=1 merges, 1..=2 ports) | `mshr_file::tests::exhaustive_cache_sequences` | a one-set four-way cache with 1..=3 MSHRs x 0..=1 merged targets x 1..=2 ports, every sequence of up to 7 operations (access block 0/1/2, fill a pending block, next cycle): 798,282 steps against [`mshr_file::CacheModel`]; occupancy never above capacity, a full file refuses every access (hits included) and a refused access changes nothing, every lookup and fill as the model says |
//!
//! # (l) The CF meter of `wasp-m` (beyond the paper)
//!
//! | property | Kani harness | exhaustive twin | domain |
//! |---|---|---|---|
//! | [`cf_meter::cf_meter_next_exact`] | `cf_meter::proofs::proof_cf_meter_next_exact` | `cf_meter::tests::exhaustive_cf_meter` | every launch count (4 bits), accumulator (7 bits) and CF register (5 bits) x launch or not x 0..=3 misses: 524,288 points; the next state equals the specification and the CF register stays in the datapath's 5-bit range |
//!
//! # (g)-(k) The assembled GPU (`wasp-sim`)
//!
//! | body | harness | test twin | domain |
//! |---|---|---|---|
//! | [`machine::machine_cycle`], [`machine::machine_end`] (via [`machine::run_checked`]) | `machine::proofs::proof_machine_two_quads` (one tile, two quads of any program, one core, one L0 MSHR, WaSP threshold 0) | `machine::tests::exhaustive_one_tile_up_to_three_quads`, `..._two_tiles_up_to_two_quads_each` | small GPUs ([`machine::SmallMachine`]: 8x8-pixel tiles, 1-2 cores, 1-3 warp slots, width 1-2, 1-2 scheduler-level MSHRs, every policy, Mesh2/Mesh4, L0 or not, ideal memory or not) on every trace of up to 3 quads in one tile (5 programs each: 155 traces x 7 machines) and of up to 2 quads in each of two tiles (900 traces x 3 machines), every cycle: (g) MSHR occupancy <= capacity at every cache, (h) free-MSHR register == capacity - outstanding, (i) non-blocked counter == unblocked priority warps in the slots, (j) fill and drain, (k) every warp finishes within `200 + 300 I` cycles (`I`: the trace's instructions) and every quad finishes exactly once |
//!
//! Planted bugs in `wasp-sim` that these catch (tried by hand): a core that
//! releases its tile with warps still running ((j)), a dropped decrement of
//! the non-blocked counter when a priority warp finishes ((i)), a cache that
//! lets hits through with every MSHR occupied ((f)).
//!
//! # Random long runs
//!
//! `tests/scheduler_random.rs` drives [`scheduler::SchedulerCheck`] with
//! proptest: 1000-cycle random event sequences for WaSP (any CF and
//! threshold, and the paper's CF), Baseline, Fullpriority and FreeMSHR-N,
//! random MSHRs (1..=31), queue (1..=64), warp slots (1..=127) and subset;
//! an illegal event after a random prefix must fault and leave both
//! registers unchanged; and a fixed 5000-cycle run per policy checks that
//! the runs are not vacuous (launches, full queue, no free MSHR, priority
//! warps held back).
//!
//! `tests/sim_models.rs` does the same around the scheduler: a
//! `proptest-state-machine` test drives a `wasp-sim` cache with up to 400
//! random operations against [`mshr_file::CacheModel`] (property (f)), and
//! a proptest runs random small GPUs (1-2 cores, 1-4 warp slots, every
//! policy, L0 or not) on random traces of up to two tiles of eight quads
//! (positions may repeat), checking (g)-(k) every cycle.
//!
//! # Limits of the models
//!
//! The priority-warp model allows at most [`counters::MAX_PRIORITY_WARPS`]
//! = 127 priority warps in a core at once. A core with 128 warp slots and
//! a subset with 128 or more priority quads per tile (Mesh2 selects 256)
//! could count 128 non-blocked priority warps, which the 7-bit counter
//! reports as a `RegisterFault`; `wasp-sim`'s configuration check rejects
//! such a configuration (at most min(warp slots, one tile's priority quads)
//! priority warps can be in a core, since a core drains a tile before the
//! next).
//!
//! The registers see only the net effect of a cycle's events. An event the
//! models call illegal but whose net result stays in range (for example an
//! allocation and a reply in the same cycle with every MSHR free: the reply
//! has no entry to free) is returned as the exact in-range value, not a
//! fault; `FreeMshrReg::legal` reports it. That is not a wrap, and the
//! properties say exactly this.

// The shim stands in for Kani's `kani` crate; under `cargo kani` both would
// be linked under one name.
#[cfg(all(kani, feature = "kani-shim"))]
compile_error!("the `kani-shim` feature is for `cargo test` (scripts/harnesses.sh); run `cargo kani -p wasp-props` without it");

pub mod cex;
pub mod cf_meter;
pub mod counters;
pub mod datapath;
pub mod machine;
pub mod mshr_file;
pub mod policy;
pub mod queue;
pub mod scheduler;
pub mod subset;

pub use cex::Cex;
