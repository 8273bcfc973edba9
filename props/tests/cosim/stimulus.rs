//! The Rust side of the co-simulation: configurations, seeded random
//! stimulus kept legal by a model of the MSHR file and the priority warps
//! (or made illegal on purpose), and the Rust scheduler driven by it, every
//! cycle's inputs and outputs recorded.

use std::fmt::Write as _;
use std::hash::Hasher;
use wasp_rtl::cf_meter::CfMeter;
use wasp_rtl::datapath::{Cf, Threshold, WaspDatapath};
use wasp_rtl::free_mshr::{FreeMshrReg, MshrEvents};
use wasp_rtl::nonblocked::PriorityEvents;
use wasp_rtl::policy::{LaunchRule, PolicySpec};
use wasp_rtl::queue::QueueClass;
use wasp_rtl::scheduler::{launch_code, EdgeEvents, LaunchDecision, LaunchScheduler};
use wasp_rtl::subset::Mesh;
use wasp_splitmix::SplitMix64;

/// The most priority warps a core may hold (the 7-bit counter's maximum).
pub(crate) const MAX_WARPS: i64 = 127;

/// SplitMix64 (`wasp-splitmix`) on a seed mixed with a constant.
pub(crate) struct Rng(SplitMix64);

impl Rng {
    pub(crate) fn new(seed: u64) -> Self {
        Rng(SplitMix64::new(seed ^ 0x5851_f42d_4c95_7f2d))
    }
    pub(crate) fn next(&mut self) -> u64 {
        self.0.next_u64()
    }
    /// Uniform in `0..=max`.
    pub(crate) fn upto(&mut self, max: i64) -> i64 {
        if max <= 0 {
            0
        } else {
            (self.next() % (max as u64 + 1)) as i64
        }
    }
    /// True with probability `p` / 1000.
    pub(crate) fn per_mille(&mut self, p: u32) -> bool {
        self.next() % 1000 < p as u64
    }
}

/// One configuration of the block, for both models.
#[derive(Clone, Debug)]
pub(crate) struct Config {
    pub(crate) name: &'static str,
    /// Verilog POLICY: 0 baseline, 1 fullpriority, 2 freemshr-N, 3 wasp,
    /// 4 wasp-m (the CF from the meter).
    pub(crate) policy: u32,
    pub(crate) mshrs: u32,
    pub(crate) queue_cap: usize,
    /// CF in quarters (the Verilog CF_Q); the datapath is compared for
    /// every policy, with these constants (wasp-m: with the meter's CF).
    pub(crate) cf_q: u32,
    pub(crate) threshold: u32,
    pub(crate) freemshr_n: u32,
    /// Mesh-k.
    pub(crate) mesh_k: u32,
    /// The launch rule for a closed gate (the Verilog LAUNCH_RULE: 0 hold,
    /// 1 launch).
    pub(crate) launch_rule: LaunchRule,
    pub(crate) seeds: u64,
    pub(crate) cycles: usize,
    /// Cycles (per 1000) that carry one arbitrary, possibly illegal, count.
    pub(crate) illegal_per_mille: u32,
}

impl Config {
    pub(crate) fn spec(&self) -> PolicySpec {
        match self.policy {
            0 => PolicySpec::Baseline,
            1 => PolicySpec::FullPriority,
            2 => PolicySpec::FreeMshr(self.freemshr_n),
            4 => PolicySpec::WaspMeasured {
                threshold: self.threshold,
            },
            _ => PolicySpec::Wasp {
                threshold: self.threshold,
                cf: self.cf_q as f64 / 4.0,
            },
        }
    }

    pub(crate) fn datapath(&self) -> WaspDatapath {
        WaspDatapath {
            cf: Cf::from_quarters(self.cf_q).expect("CF_Q fits 5 bits"),
            threshold: Threshold::new(self.threshold).expect("threshold fits 5 bits"),
        }
    }

    pub(crate) fn scheduler(&self) -> LaunchScheduler<u32> {
        LaunchScheduler::new(
            self.queue_cap,
            Box::new(Mesh::new(self.mesh_k).expect("mesh k")),
            FreeMshrReg::with_capacity(self.mshrs).expect("capacity fits 5 bits"),
            self.spec()
                .build(self.mshrs)
                .expect("valid policy")
                .as_ref(),
            self.launch_rule,
        )
    }

    pub(crate) fn iverilog_params(&self) -> Vec<String> {
        let p = [
            ("POLICY", self.policy as usize),
            ("CAPACITY", self.mshrs as usize),
            ("QUEUE_CAP", self.queue_cap),
            ("CF_Q", self.cf_q as usize),
            ("THRESHOLD", self.threshold as usize),
            ("FREEMSHR_N", self.freemshr_n as usize),
            ("MESH_BITS", self.mesh_k.trailing_zeros() as usize),
            (
                "LAUNCH_RULE",
                match self.launch_rule {
                    LaunchRule::Hold => 0,
                    LaunchRule::Launch => 1,
                },
            ),
        ];
        p.iter()
            .map(|(k, v)| format!("-Ptb_cosim.{k}={v}"))
            .collect()
    }
}

/// One cycle's inputs (a stimulus line).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Inputs {
    pub(crate) push_valid: bool,
    pub(crate) qx: u32,
    pub(crate) qy: u32,
    pub(crate) launch_enable: bool,
    pub(crate) allocs: u8,
    pub(crate) replies: u8,
    pub(crate) blocked: u8,
    pub(crate) unblocked: u8,
    pub(crate) finished: u8,
    /// Primary misses of priority warps (wasp-m's meter clamps them to 3).
    pub(crate) misses: u8,
}

/// One cycle's outputs, in the testbench's column order.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Outputs {
    pub(crate) free_mshrs: i64,
    pub(crate) nonblocked: i64,
    pub(crate) prio_occ: i64,
    pub(crate) reg_occ: i64,
    pub(crate) is_priority: i64,
    pub(crate) push_accepted: i64,
    pub(crate) product: i64,
    pub(crate) real_free: i64,
    pub(crate) priority_over_regular: i64,
    pub(crate) select: i64,
    pub(crate) launch: i64,
    pub(crate) fault: i64,
    pub(crate) meter_launches: i64,
    pub(crate) meter_acc: i64,
    pub(crate) cf_q: i64,
}

impl Outputs {
    pub(crate) const NAMES: [&'static str; 15] = [
        "free_mshrs",
        "nonblocked",
        "prio_occ",
        "reg_occ",
        "is_priority",
        "push_accepted",
        "product",
        "real_free",
        "priority_over_regular",
        "select",
        "launch",
        "fault",
        "meter_launches",
        "meter_acc",
        "cf_q",
    ];

    pub(crate) fn to_array(self) -> [i64; 15] {
        [
            self.free_mshrs,
            self.nonblocked,
            self.prio_occ,
            self.reg_occ,
            self.is_priority,
            self.push_accepted,
            self.product,
            self.real_free,
            self.priority_over_regular,
            self.select,
            self.launch,
            self.fault,
            self.meter_launches,
            self.meter_acc,
            self.cf_q,
        ]
    }

    pub(crate) fn from_line(line: &str) -> Option<Outputs> {
        let v: Vec<i64> = line
            .split_whitespace()
            .map(|t| t.parse().ok())
            .collect::<Option<_>>()?;
        if v.len() != Self::NAMES.len() {
            return None;
        }
        Some(Outputs {
            free_mshrs: v[0],
            nonblocked: v[1],
            prio_occ: v[2],
            reg_occ: v[3],
            is_priority: v[4],
            push_accepted: v[5],
            product: v[6],
            real_free: v[7],
            priority_over_regular: v[8],
            select: v[9],
            launch: v[10],
            fault: v[11],
            meter_launches: v[12],
            meter_acc: v[13],
            cf_q: v[14],
        })
    }
}

/// What the stimulus exercised (a pass must not be vacuous).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Coverage {
    pub(crate) cycles: u64,
    pub(crate) pushes_accepted: u64,
    pub(crate) pushes_refused: u64,
    pub(crate) priority_launches: u64,
    pub(crate) regular_launches: u64,
    /// A priority warp waited but the policy chose regular or nothing.
    pub(crate) priority_held_back: u64,
    /// The launch rule `hold` idled: a lone priority warp, the gate closed.
    pub(crate) held: u64,
    /// A WaSP priority launch with the datapath saying regular (only the
    /// launch rule `launch` does that).
    pub(crate) launched_gate_closed: u64,
    pub(crate) free_zero: u64,
    pub(crate) real_free_negative: u64,
    pub(crate) faults: u64,
    pub(crate) max_nonblocked: i64,
    pub(crate) min_real_free: i64,
    /// wasp-m: windows of 16 priority launches that loaded the CF register.
    pub(crate) meter_windows: u64,
    /// wasp-m: cycles with the meter's accumulator saturated (127).
    pub(crate) meter_saturated: u64,
    /// wasp-m: cycles with a misses input above the meter's 2-bit range.
    pub(crate) misses_clamped: u64,
    /// wasp-m: the distinct CF values the meter held (bit q: q quarters).
    pub(crate) cf_values: u32,
}

impl Coverage {
    pub(crate) fn add(&mut self, o: &Coverage) {
        self.cycles += o.cycles;
        self.pushes_accepted += o.pushes_accepted;
        self.pushes_refused += o.pushes_refused;
        self.priority_launches += o.priority_launches;
        self.regular_launches += o.regular_launches;
        self.priority_held_back += o.priority_held_back;
        self.held += o.held;
        self.launched_gate_closed += o.launched_gate_closed;
        self.free_zero += o.free_zero;
        self.real_free_negative += o.real_free_negative;
        self.faults += o.faults;
        self.max_nonblocked = self.max_nonblocked.max(o.max_nonblocked);
        self.min_real_free = self.min_real_free.min(o.min_real_free);
        self.meter_windows += o.meter_windows;
        self.meter_saturated += o.meter_saturated;
        self.misses_clamped += o.misses_clamped;
        self.cf_values |= o.cf_values;
    }
}

/// One seed's stimulus knobs, drawn from the seed so that runs differ in
/// pressure: some keep the MSHRs full, some keep the queue full.
pub(crate) struct Knobs {
    pub(crate) push: u32,
    pub(crate) enable: u32,
    pub(crate) alloc: u32,
    pub(crate) reply: u32,
    pub(crate) block: u32,
    pub(crate) unblock: u32,
    pub(crate) finish: u32,
    pub(crate) regular_finish: u32,
    pub(crate) priority_bias: u32,
    pub(crate) max_warps: i64,
    /// An unblock event unblocks every blocked priority warp.
    pub(crate) bulk_unblock: bool,
}

impl Knobs {
    pub(crate) fn draw(rng: &mut Rng) -> Knobs {
        // One seed in four hoards priority warps: they rarely block or
        // finish, so the counter climbs to its maximum of 127. One in four
        // blocks them at once and unblocks them in bulk, so that the
        // counter jumps even when WaSP holds priority launches back.
        let mode = rng.next() % 4;
        let mut pick = |lo: u64, hi: u64| (lo + rng.next() % (hi - lo + 1)) as u32;
        if mode == 1 {
            return Knobs {
                push: pick(600, 1000),
                enable: pick(600, 1000),
                alloc: pick(50, 400),
                reply: pick(50, 600),
                block: pick(900, 1000),
                unblock: pick(5, 40),
                finish: pick(0, 4),
                regular_finish: pick(200, 900),
                priority_bias: pick(500, 1000),
                max_warps: MAX_WARPS,
                bulk_unblock: true,
            };
        }
        if mode == 0 {
            return Knobs {
                push: pick(600, 1000),
                enable: pick(600, 1000),
                alloc: pick(100, 800),
                reply: pick(50, 600),
                block: pick(0, 8),
                unblock: pick(0, 8),
                finish: pick(0, 4),
                regular_finish: pick(200, 900),
                priority_bias: pick(500, 1000),
                max_warps: MAX_WARPS,
                bulk_unblock: false,
            };
        }
        Knobs {
            push: pick(200, 950),
            enable: pick(200, 950),
            alloc: pick(100, 800),
            reply: pick(50, 600),
            block: pick(50, 600),
            unblock: pick(50, 600),
            finish: pick(10, 300),
            regular_finish: pick(20, 500),
            priority_bias: pick(0, 600),
            max_warps: pick(1, 127) as i64,
            bulk_unblock: false,
        }
    }
}

/// A count in `0..=max`, zero unless an event of probability `p` happens;
/// then mostly 1 or 2, sometimes anything up to `max`.
pub(crate) fn count(rng: &mut Rng, p: u32, max: i64) -> i64 {
    if max <= 0 || !rng.per_mille(p) {
        return 0;
    }
    if rng.per_mille(800) {
        (1 + rng.upto(1)).min(max)
    } else {
        rng.upto(max.min(255))
    }
}

/// The cycles of one configuration: stimulus text (with one reset line per
/// seed) and the model's outputs for every non-reset line.
pub(crate) struct Run {
    pub(crate) stimulus: String,
    pub(crate) inputs: Vec<(u64, u64, Inputs)>,
    pub(crate) expected: Vec<Outputs>,
    pub(crate) coverage: Coverage,
}

/// Drive the Rust scheduler of `cfg` with `seeds` seeds of `cycles` cycles
/// each, every seed from reset.
pub(crate) fn drive_rust(cfg: &Config, seeds: u64, cycles: usize) -> Run {
    let mut run = Run {
        stimulus: String::new(),
        inputs: Vec::new(),
        expected: Vec::new(),
        coverage: Coverage::default(),
    };
    for seed in 0..seeds {
        let mut g = Generator::new(cfg, seed);
        let mut s = cfg.scheduler();
        run.stimulus.push_str("1 0 0 0 0 0 0 0 0 0 0\n");
        for cyc in 0..cycles {
            let c = g.cycle(cfg, &mut s);
            c.count(&mut run.coverage);
            write_inputs(&mut run.stimulus, &c.inp);
            run.inputs.push((seed, cyc as u64, c.inp));
            run.expected.push(c.out);
        }
    }
    run
}

/// One cycle as driven: its inputs and the model's outputs, and what the
/// coverage counts of it.
struct Cycle {
    inp: Inputs,
    out: Outputs,
    decision: LaunchDecision,
    /// A priority warp waited when the cycle decided.
    prio_waiting: bool,
    /// A priority warp launched (0 or 1).
    lp: i64,
    /// A regular warp launched (0 or 1).
    lr: i64,
    /// wasp-m's meter at the start of the cycle.
    meter: Option<CfMeter>,
}

impl Cycle {
    /// Add the cycle to the coverage `c`.
    fn count(&self, c: &mut Coverage) {
        let (inp, out) = (&self.inp, &self.out);
        let (lp, lr) = (self.lp, self.lr);
        let pushed = inp.push_valid as u64;
        c.pushes_accepted += pushed * out.push_accepted as u64;
        c.pushes_refused += pushed * (out.push_accepted == 0) as u64;
        c.cycles += 1;
        c.priority_launches += lp as u64;
        c.regular_launches += lr as u64;
        c.priority_held_back +=
            (self.prio_waiting && self.decision.select != Some(QueueClass::Priority)) as u64;
        c.held += self.decision.held as u64;
        c.launched_gate_closed += (lp == 1 && out.priority_over_regular == 0) as u64;
        c.free_zero += (out.free_mshrs == 0) as u64;
        c.real_free_negative += (out.real_free < 0) as u64;
        c.faults += out.fault as u64;
        c.max_nonblocked = c.max_nonblocked.max(out.nonblocked);
        c.min_real_free = c.min_real_free.min(out.real_free);
        if let Some(m) = self.meter {
            c.meter_windows += (lp == 1 && out.fault == 0 && m.launches().get() == 15) as u64;
            c.meter_saturated += (m.acc().get() == 127) as u64;
            c.misses_clamped += (inp.misses > 3) as u64;
            c.cf_values |= 1 << m.cf().quarters();
        }
    }
}

/// A cycle's inputs as a stimulus line (not a reset).
fn write_inputs(stimulus: &mut String, inp: &Inputs) {
    writeln!(
        stimulus,
        "0 {} {} {} {} {} {} {} {} {} {}",
        inp.push_valid as u8,
        inp.qx,
        inp.qy,
        inp.launch_enable as u8,
        inp.allocs,
        inp.replies,
        inp.blocked,
        inp.unblocked,
        inp.finished,
        inp.misses
    )
    .unwrap();
}

/// The stimulus of one seed: its random streams and knobs, and the state
/// it models beyond the registers (blocked priority warps and regular
/// warps in the core).
struct Generator {
    rng: Rng,
    /// The misses of priority warps (read by wasp-m's meter) come from a
    /// stream of their own, so that the other inputs are those of the
    /// configurations before the meter.
    miss_rng: Rng,
    /// Per mille of cycles with misses: 100..=900.
    miss_rate: u32,
    knobs: Knobs,
    blocked: i64,
    regular_in_core: i64,
    ticket: u32,
}

impl Generator {
    fn new(cfg: &Config, seed: u64) -> Generator {
        let name_hash = {
            let mut h = fnv::FnvHasher::default();
            h.write(cfg.name.as_bytes());
            h.finish()
        };
        let mut rng = Rng::new(name_hash ^ seed.wrapping_mul(0x9e37_79b9_7f4a_7c15));
        let mut miss_rng = Rng::new(name_hash ^ seed.wrapping_mul(0xd1b5_4a32_d192_ed03) ^ 0x4d45);
        let miss_rate = 100 + miss_rng.upto(800) as u32;
        let knobs = Knobs::draw(&mut rng);
        Generator {
            rng,
            miss_rng,
            miss_rate,
            knobs,
            blocked: 0,
            regular_in_core: 0,
            ticket: 0,
        }
    }

    /// One cycle of the scheduler `s`: 1. enqueue, 2. decide and 3. launch
    /// (the pop at the FIFO's read port), 4. the cycle's events at the
    /// clock edge.
    fn cycle(&mut self, cfg: &Config, s: &mut LaunchScheduler<u32>) -> Cycle {
        let meter = s.cf_meter();
        let (mut out, dp) = start_of_cycle(cfg, s, meter);
        let mut inp = self.inputs(cfg.mesh_k, out.nonblocked);

        // 1. enqueue
        out.is_priority = (s.classify(inp.qx, inp.qy) == QueueClass::Priority) as i64;
        if inp.push_valid {
            let ok = s.enqueue(self.ticket, inp.qx, inp.qy).is_ok();
            self.ticket = self.ticket.wrapping_add(1);
            out.push_accepted = ok as i64;
        }
        // 2. decide, and 3. launch
        let prio_waiting = s.queue().has(QueueClass::Priority);
        let (decision, launched) = launch(cfg, s, &inp, &dp, &mut out);
        let lp = (launched == Some(QueueClass::Priority)) as i64;
        let lr = (launched == Some(QueueClass::Regular)) as i64;
        // 4. the cycle's events
        self.events(cfg, &mut inp, &out, lp);
        out.fault = self.clock(s, &inp, lr) as i64;
        Cycle {
            inp,
            out,
            decision,
            prio_waiting,
            lp,
            lr,
            meter,
        }
    }

    /// The inputs of the first half of a cycle: a push and its tile, and
    /// the launch enable (only with room in the core; `nb` non-blocked
    /// priority warps hold some of it).
    fn inputs(&mut self, k: u32, nb: i64) -> Inputs {
        let (rng, knobs) = (&mut self.rng, &self.knobs);
        let mut inp = Inputs {
            push_valid: rng.per_mille(knobs.push),
            ..Inputs::default()
        };
        if rng.per_mille(knobs.priority_bias) {
            inp.qx = (rng.upto(31) as u32) & !(k - 1);
            inp.qy = (rng.upto(31) as u32) & !(k - 1);
        } else {
            inp.qx = rng.upto(31) as u32;
            inp.qy = rng.upto(31) as u32;
        }
        let room = nb + self.blocked + self.regular_in_core < knobs.max_warps;
        inp.launch_enable = rng.per_mille(knobs.enable) && room;
        inp
    }

    /// The cycle's events into `inp`, legal for the model of the MSHR file
    /// and of the priority warps in the core (`out`: the registers at the
    /// start of the cycle; `lp`: a priority warp launched), except for the
    /// few cycles of an illegal configuration.
    fn events(&mut self, cfg: &Config, inp: &mut Inputs, out: &Outputs, lp: i64) {
        let (rng, knobs) = (&mut self.rng, &self.knobs);
        let (free, nb) = (out.free_mshrs, out.nonblocked);
        let in_flight = cfg.mshrs as i64 - free;
        let replies = count(rng, knobs.reply, in_flight);
        let allocs = count(rng, knobs.alloc, free + replies);
        let unblocked = if knobs.bulk_unblock {
            self.blocked * rng.per_mille(knobs.unblock) as i64
        } else {
            count(rng, knobs.unblock, self.blocked)
        };
        let avail = nb + lp + unblocked;
        let blocks = count(rng, knobs.block, avail);
        let finished = count(rng, knobs.finish, avail - blocks);
        let mut ev = [allocs, replies, blocks, unblocked, finished].map(|v| v as u8);
        if cfg.illegal_per_mille > 0 && rng.per_mille(cfg.illegal_per_mille) {
            let which = rng.upto(4) as usize;
            ev[which] = rng.upto(255) as u8;
        }
        [
            inp.allocs,
            inp.replies,
            inp.blocked,
            inp.unblocked,
            inp.finished,
        ] = ev;
        // Misses of priority warps: mostly 0..=3, one cycle in forty any
        // u8 (the meter's input clamps it to 3).
        inp.misses = if self.miss_rng.per_mille(25) {
            self.miss_rng.upto(255) as u8
        } else {
            count(&mut self.miss_rng, self.miss_rate, 3) as u8
        };
    }

    /// Clock `s` with the events of `inp`, and follow it in the
    /// generator's model (`lr`: a regular warp launched). Whether the
    /// registers refused the events (a fault).
    fn clock(&mut self, s: &mut LaunchScheduler<u32>, inp: &Inputs, lr: i64) -> bool {
        let r = s.clock(EdgeEvents {
            mshr: MshrEvents {
                allocs: inp.allocs,
                replies: inp.replies,
            },
            prio: PriorityEvents {
                launched: false,
                blocked: inp.blocked,
                unblocked: inp.unblocked,
                finished: inp.finished,
                misses: inp.misses,
            },
        });
        if r.is_ok() {
            self.blocked += inp.blocked as i64 - inp.unblocked as i64;
            // After an arbitrary (accepted) count, keep the generator's
            // model consistent with the registers.
            let nb_new = s.nonblocked().count().get() as i64;
            self.blocked = self.blocked.clamp(0, MAX_WARPS - nb_new);
        }
        self.regular_in_core += lr;
        self.regular_in_core -= count(
            &mut self.rng,
            self.knobs.regular_finish,
            self.regular_in_core,
        );
        r.is_err()
    }
}

/// The registers of `s` at the start of a cycle, as the outputs that show
/// them, and the cycle's datapath: wasp-m's with the CF of its `meter`,
/// the other policies' with the wired CF.
fn start_of_cycle(
    cfg: &Config,
    s: &LaunchScheduler<u32>,
    meter: Option<CfMeter>,
) -> (Outputs, WaspDatapath) {
    let dp = match meter {
        Some(m) => WaspDatapath {
            cf: m.cf(),
            ..cfg.datapath()
        },
        None => cfg.datapath(),
    };
    let out = Outputs {
        free_mshrs: s.free_mshrs().free().get() as i64,
        nonblocked: s.nonblocked().count().get() as i64,
        prio_occ: s.queue().occupancy(QueueClass::Priority) as i64,
        reg_occ: s.queue().occupancy(QueueClass::Regular) as i64,
        meter_launches: meter.map_or(0, |m| m.launches().get() as i64),
        meter_acc: meter.map_or(0, |m| m.acc().get() as i64),
        cf_q: dp.cf.quarters() as i64,
        ..Outputs::default()
    };
    (out, dp)
}

/// The decision of the cycle and the launch under `inp`'s enable, into
/// `out` (checked against the datapath `dp` of the policy's constants):
/// the decision and the class launched.
fn launch(
    cfg: &Config,
    s: &mut LaunchScheduler<u32>,
    inp: &Inputs,
    dp: &WaspDatapath,
    out: &mut Outputs,
) -> (LaunchDecision, Option<QueueClass>) {
    let l = s.launch(inp.launch_enable);
    let d = l.decision;
    let dpo = dp.eval(s.free_mshrs().free(), s.nonblocked().count());
    if let Some(got) = d.datapath {
        assert_eq!(
            got, dpo,
            "{}: the policy's datapath differs from its constants",
            cfg.name
        );
    }
    out.product = dpo.product.get() as i64;
    out.real_free = dpo.real_free.get() as i64;
    out.priority_over_regular = dpo.priority_over_regular as i64;
    out.select = launch_code(d.select) as i64;
    let launched = l.warp.map(|(_, c)| c);
    out.launch = launch_code(launched) as i64;
    (d, launched)
}
