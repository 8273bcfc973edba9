//! Co-simulation of the Verilog twin (`props/verilog/wasp_sched.v`) against
//! the Rust register-transfer model (`wasp_rtl::scheduler::LaunchScheduler`).
//!
//! For each configuration, seeded random stimulus drives the Rust scheduler
//! cycle by cycle in the block-level order `enqueue -> decide -> launch ->
//! clock -> end_cycle`, and every cycle's inputs and the model's outputs are
//! recorded. The stimulus goes to a file; `iverilog -g2005` compiles
//! `tb_cosim.v` with the configuration as parameters, `vvp` runs it, and
//! every output of every cycle is compared with the model: the registers
//! (free MSHRs, non-blocked count, both queue occupancies), the comparator,
//! push acceptance, the datapath (product, real_free, the comparison), the
//! policy's selection under the launch rule (`hold` or `launch`), the
//! launch, and the fault flag.
//!
//! Events are legal (a model of the MSHR file and of the priority warps in
//! the core keeps them so, like `FreeMshrReg::legal` and the warp slots of a
//! core), except in the configurations with `illegal_per_mille > 0`, where a
//! few cycles carry an arbitrary `u8` count: the Rust model then returns a
//! `RegisterFault` (or not) and the twin must raise `fault` (or not) and hold
//! both registers exactly as the model does.
//!
//! Tools: if `iverilog`/`vvp` cannot run when the package is built,
//! `build.rs` marks these tests ignored (the summary counts them), unless
//! `WASP_REQUIRE_TOOLS=1` (CI), when they run and fail. Tools removed after
//! the build: the tests print "skipped: iverilog not installed" and pass. Knobs:
//! `WASP_COSIM_SEEDS=n` (seeds per configuration, default per
//! configuration), `WASP_COSIM_CYCLES=n` (cycles per seed),
//! `WASP_COSIM_VERILOG_DIR=dir` (take `wasp_sched.v` from `dir` instead of
//! `props/verilog`, e.g. a planted-bug copy made by
//! `props/verilog/mutate.sh`).

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;
use wasp_rtl::datapath::{Cf, Threshold, WaspDatapath};
use wasp_rtl::free_mshr::{FreeMshrReg, MshrEvents};
use wasp_rtl::nonblocked::PriorityEvents;
use wasp_rtl::policy::{LaunchRule, PolicySpec};
use wasp_rtl::queue::QueueClass;
use wasp_rtl::scheduler::{launch_code, EdgeEvents, LaunchScheduler};
use wasp_rtl::subset::Mesh;

/// The most priority warps a core may hold (the 7-bit counter's maximum).
const MAX_WARPS: i64 = 127;

/// SplitMix64: a small, seedable generator (no dependency needed).
struct Rng(u64);

impl Rng {
    fn new(seed: u64) -> Self {
        Rng(seed ^ 0x5851_f42d_4c95_7f2d)
    }
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// Uniform in `0..=max`.
    fn upto(&mut self, max: i64) -> i64 {
        if max <= 0 {
            0
        } else {
            (self.next() % (max as u64 + 1)) as i64
        }
    }
    /// True with probability `p` / 1000.
    fn per_mille(&mut self, p: u32) -> bool {
        self.next() % 1000 < p as u64
    }
}

/// One configuration of the block, for both models.
#[derive(Clone, Debug)]
struct Config {
    name: &'static str,
    /// Verilog POLICY: 0 baseline, 1 fullpriority, 2 freemshr-N, 3 wasp.
    policy: u32,
    mshrs: u32,
    queue_cap: usize,
    /// CF in quarters (the Verilog CF_Q); the datapath is compared for
    /// every policy, with these constants.
    cf_q: u32,
    threshold: u32,
    freemshr_n: u32,
    /// Mesh-k.
    mesh_k: u32,
    /// The launch rule for a closed gate (the Verilog LAUNCH_RULE: 0 hold,
    /// 1 launch).
    launch_rule: LaunchRule,
    seeds: u64,
    cycles: usize,
    /// Cycles (per 1000) that carry one arbitrary, possibly illegal, count.
    illegal_per_mille: u32,
}

impl Config {
    fn spec(&self) -> PolicySpec {
        match self.policy {
            0 => PolicySpec::Baseline,
            1 => PolicySpec::FullPriority,
            2 => PolicySpec::FreeMshr(self.freemshr_n),
            _ => PolicySpec::Wasp {
                threshold: self.threshold,
                cf: self.cf_q as f64 / 4.0,
            },
        }
    }

    fn datapath(&self) -> WaspDatapath {
        WaspDatapath {
            cf: Cf::from_quarters(self.cf_q).expect("CF_Q fits 5 bits"),
            threshold: Threshold::new(self.threshold).expect("threshold fits 5 bits"),
        }
    }

    fn scheduler(&self) -> LaunchScheduler<u32> {
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

    fn iverilog_params(&self) -> Vec<String> {
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
struct Inputs {
    push_valid: bool,
    qx: u32,
    qy: u32,
    launch_enable: bool,
    allocs: u8,
    replies: u8,
    blocked: u8,
    unblocked: u8,
    finished: u8,
}

/// One cycle's outputs, in the testbench's column order.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Outputs {
    free_mshrs: i64,
    nonblocked: i64,
    prio_occ: i64,
    reg_occ: i64,
    is_priority: i64,
    push_accepted: i64,
    product: i64,
    real_free: i64,
    priority_over_regular: i64,
    select: i64,
    launch: i64,
    fault: i64,
}

impl Outputs {
    const NAMES: [&'static str; 12] = [
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
    ];

    fn to_array(self) -> [i64; 12] {
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
        ]
    }

    fn from_line(line: &str) -> Option<Outputs> {
        let v: Vec<i64> = line
            .split_whitespace()
            .map(|t| t.parse().ok())
            .collect::<Option<_>>()?;
        if v.len() != 12 {
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
        })
    }
}

/// What the stimulus exercised (a pass must not be vacuous).
#[derive(Clone, Copy, Debug, Default)]
struct Coverage {
    cycles: u64,
    pushes_accepted: u64,
    pushes_refused: u64,
    priority_launches: u64,
    regular_launches: u64,
    /// A priority warp waited but the policy chose regular or nothing.
    priority_held_back: u64,
    /// The launch rule `hold` idled: a lone priority warp, the gate closed.
    held: u64,
    /// A WaSP priority launch with the datapath saying regular (only the
    /// launch rule `launch` does that).
    launched_gate_closed: u64,
    free_zero: u64,
    real_free_negative: u64,
    faults: u64,
    max_nonblocked: i64,
    min_real_free: i64,
}

impl Coverage {
    fn add(&mut self, o: &Coverage) {
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
    }
}

/// One seed's stimulus knobs, drawn from the seed so that runs differ in
/// pressure: some keep the MSHRs full, some keep the queue full.
struct Knobs {
    push: u32,
    enable: u32,
    alloc: u32,
    reply: u32,
    block: u32,
    unblock: u32,
    finish: u32,
    regular_finish: u32,
    priority_bias: u32,
    max_warps: i64,
    /// An unblock event unblocks every blocked priority warp.
    bulk_unblock: bool,
}

impl Knobs {
    fn draw(rng: &mut Rng) -> Knobs {
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
fn count(rng: &mut Rng, p: u32, max: i64) -> i64 {
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
struct Run {
    stimulus: String,
    inputs: Vec<(u64, u64, Inputs)>,
    expected: Vec<Outputs>,
    coverage: Coverage,
}

fn drive_rust(cfg: &Config, seeds: u64, cycles: usize) -> Run {
    let mut run = Run {
        stimulus: String::new(),
        inputs: Vec::new(),
        expected: Vec::new(),
        coverage: Coverage::default(),
    };
    let dp = cfg.datapath();
    let k = cfg.mesh_k;
    for seed in 0..seeds {
        let name_hash = cfg.name.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
            (h ^ b as u64).wrapping_mul(0x1000_0000_01b3)
        });
        let mut rng = Rng::new(name_hash ^ seed.wrapping_mul(0x9e37_79b9_7f4a_7c15));
        let knobs = Knobs::draw(&mut rng);
        let mut s = cfg.scheduler();
        // Generator state beyond the registers: blocked priority warps and
        // regular warps in the core.
        let mut blocked: i64 = 0;
        let mut regular_in_core: i64 = 0;
        let mut ticket = 0u32;
        run.stimulus.push_str("1 0 0 0 0 0 0 0 0 0\n");
        for cyc in 0..cycles {
            let free = s.free_mshrs().free().get() as i64;
            let nb = s.nonblocked().count().get() as i64;
            let in_flight = cfg.mshrs as i64 - free;
            let mut out = Outputs {
                free_mshrs: free,
                nonblocked: nb,
                prio_occ: s.queue().occupancy(QueueClass::Priority) as i64,
                reg_occ: s.queue().occupancy(QueueClass::Regular) as i64,
                ..Outputs::default()
            };
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
            let room = nb + blocked + regular_in_core < knobs.max_warps;
            inp.launch_enable = rng.per_mille(knobs.enable) && room;

            // 1. enqueue
            out.is_priority = (s.classify(inp.qx, inp.qy) == QueueClass::Priority) as i64;
            if inp.push_valid {
                let ok = s.enqueue(ticket, inp.qx, inp.qy).is_ok();
                ticket = ticket.wrapping_add(1);
                out.push_accepted = ok as i64;
                run.coverage.pushes_accepted += ok as u64;
                run.coverage.pushes_refused += !ok as u64;
            }
            // 2. decide, and 3. launch (the pop at the FIFO's read port)
            let prio_waiting = s.queue().has(QueueClass::Priority);
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
            let lp = (launched == Some(QueueClass::Priority)) as i64;
            let lr = (launched == Some(QueueClass::Regular)) as i64;

            // 4. the cycle's events, legal for the model of the MSHR file
            // and of the priority warps in the core
            let replies = count(&mut rng, knobs.reply, in_flight);
            let allocs = count(&mut rng, knobs.alloc, free + replies);
            let unblocked = if knobs.bulk_unblock {
                blocked * rng.per_mille(knobs.unblock) as i64
            } else {
                count(&mut rng, knobs.unblock, blocked)
            };
            let avail = nb + lp + unblocked;
            let blocks = count(&mut rng, knobs.block, avail);
            let finished = count(&mut rng, knobs.finish, avail - blocks);
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
                    misses: 0,
                },
            });
            out.fault = r.is_err() as i64;
            if r.is_ok() {
                blocked += inp.blocked as i64 - inp.unblocked as i64;
                // After an arbitrary (accepted) count, keep the generator's
                // model consistent with the registers.
                let nb_new = s.nonblocked().count().get() as i64;
                blocked = blocked.clamp(0, MAX_WARPS - nb_new);
            }
            regular_in_core += lr;
            regular_in_core -= count(&mut rng, knobs.regular_finish, regular_in_core);

            let c = &mut run.coverage;
            c.cycles += 1;
            c.priority_launches += lp as u64;
            c.regular_launches += lr as u64;
            c.priority_held_back += (prio_waiting && d.select != Some(QueueClass::Priority)) as u64;
            c.held += d.held as u64;
            c.launched_gate_closed += (lp == 1 && out.priority_over_regular == 0) as u64;
            c.free_zero += (free == 0) as u64;
            c.real_free_negative += (out.real_free < 0) as u64;
            c.faults += out.fault as u64;
            c.max_nonblocked = c.max_nonblocked.max(nb);
            c.min_real_free = c.min_real_free.min(out.real_free);

            writeln!(
                run.stimulus,
                "0 {} {} {} {} {} {} {} {} {}",
                inp.push_valid as u8,
                inp.qx,
                inp.qy,
                inp.launch_enable as u8,
                inp.allocs,
                inp.replies,
                inp.blocked,
                inp.unblocked,
                inp.finished
            )
            .unwrap();
            run.inputs.push((seed, cyc as u64, inp));
            run.expected.push(out);
        }
    }
    run
}

fn env_u64(name: &str) -> Option<u64> {
    std::env::var(name).ok().and_then(|s| s.trim().parse().ok())
}

fn verilog_dir() -> PathBuf {
    match std::env::var_os("WASP_COSIM_VERILOG_DIR") {
        Some(d) => PathBuf::from(d),
        None => Path::new(env!("CARGO_MANIFEST_DIR")).join("verilog"),
    }
}

/// Whether iverilog and vvp can run; if not, skip (or fail under
/// `WASP_REQUIRE_TOOLS=1`).
fn tools_present() -> bool {
    let ok = |prog: &str, arg: &str| {
        Command::new(prog)
            .arg(arg)
            .output()
            .map(|o| o.status.success() || !o.stdout.is_empty() || !o.stderr.is_empty())
            .unwrap_or(false)
    };
    if ok("iverilog", "-V") && ok("vvp", "-V") {
        return true;
    }
    if std::env::var("WASP_REQUIRE_TOOLS").as_deref() == Ok("1") {
        panic!("iverilog/vvp not installed and WASP_REQUIRE_TOOLS=1 (apt-get install iverilog)");
    }
    // Straight to the process's stderr, once: the test harness captures
    // `eprintln!` of passing tests.
    static SKIP_NOTE: std::sync::Once = std::sync::Once::new();
    SKIP_NOTE.call_once(|| {
        let _ = writeln!(
            std::io::stderr(),
            "skipped: iverilog not installed (the Verilog co-simulation did not run; set WASP_REQUIRE_TOOLS=1 to make this a failure)"
        );
    });
    false
}

/// Compile the testbench for `cfg`, run the stimulus, return the lines.
fn run_verilog(cfg: &Config, stimulus: &str) -> Vec<String> {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("wasp-cosim")
        .join(format!("{}-{}", cfg.name, std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let stim = dir.join("stimulus.txt");
    let out = dir.join("outputs.txt");
    let vvp = dir.join("tb.vvp");
    std::fs::write(&stim, stimulus).unwrap();
    let tb = Path::new(env!("CARGO_MANIFEST_DIR")).join("verilog/tb_cosim.v");
    let src = verilog_dir().join("wasp_sched.v");
    let o = Command::new("iverilog")
        .args(["-g2005", "-Wall", "-s", "tb_cosim", "-o"])
        .arg(&vvp)
        .args(cfg.iverilog_params())
        .arg(&tb)
        .arg(&src)
        .output()
        .expect("run iverilog");
    assert!(
        o.status.success() && o.stderr.is_empty(),
        "{}: iverilog failed or warned:\n{}",
        cfg.name,
        String::from_utf8_lossy(&o.stderr)
    );
    let mut plus_stim = std::ffi::OsString::from("+stim=");
    plus_stim.push(&stim);
    let mut plus_out = std::ffi::OsString::from("+out=");
    plus_out.push(&out);
    let o = Command::new("vvp")
        .arg("-n")
        .arg(&vvp)
        .arg(plus_stim)
        .arg(plus_out)
        .output()
        .expect("run vvp");
    let log = String::from_utf8_lossy(&o.stdout).to_string() + &String::from_utf8_lossy(&o.stderr);
    assert!(
        o.status.success() && !log.contains("ERROR"),
        "{}: vvp failed:\n{log}",
        cfg.name
    );
    let text = std::fs::read_to_string(&out).expect("testbench output");
    let _ = std::fs::remove_dir_all(&dir);
    text.lines().map(str::to_owned).collect()
}

fn fmt_outputs(o: &Outputs) -> String {
    Outputs::NAMES
        .iter()
        .zip(o.to_array())
        .map(|(n, v)| format!("{n}={v}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// Run `cfg` in both models and compare every output of every cycle.
fn cosim(cfg: &Config) -> Option<Coverage> {
    if !tools_present() {
        return None;
    }
    let seeds = env_u64("WASP_COSIM_SEEDS").unwrap_or(cfg.seeds);
    let cycles = env_u64("WASP_COSIM_CYCLES").map_or(cfg.cycles, |c| c as usize);
    let run = drive_rust(cfg, seeds, cycles);
    let lines = run_verilog(cfg, &run.stimulus);
    let n = run.expected.len();
    assert_eq!(
        lines.last().map(String::as_str),
        Some(format!("END {n}").as_str()),
        "{}: the testbench did not run all {n} cycles",
        cfg.name
    );
    let mut report = String::new();
    let mut mismatches = 0usize;
    for (i, want) in run.expected.iter().enumerate() {
        let got = Outputs::from_line(&lines[i])
            .unwrap_or_else(|| panic!("{}: bad output line {i}: {:?}", cfg.name, lines[i]));
        if got != *want {
            mismatches += 1;
            if mismatches <= 5 {
                let (seed, cyc, inp) = run.inputs[i];
                let diff: Vec<_> = Outputs::NAMES
                    .iter()
                    .zip(want.to_array().iter().zip(got.to_array()))
                    .filter(|(_, (w, g))| **w != *g)
                    .map(|(n, (w, g))| format!("{n}: rust {w} verilog {g}"))
                    .collect();
                let _ = writeln!(
                    report,
                    "  seed {seed} cycle {cyc} (line {i}): inputs {inp:?}\n    rust    {}\n    verilog {}\n    differ: {}",
                    fmt_outputs(want),
                    fmt_outputs(&got),
                    diff.join(", ")
                );
            }
        }
    }
    assert!(
        mismatches == 0,
        "{}: {mismatches} of {n} cycles differ between the Rust model and the Verilog twin ({}):\n{report}",
        cfg.name,
        verilog_dir().display()
    );
    let c = run.coverage;
    eprintln!(
        "cosim {}: {seeds} seeds x {cycles} cycles = {} cycles match; pushes {} accepted / {} refused, launches {} priority / {} regular, priority held back {}, free==0 {}, real_free<0 {} (min {}), faults {}, max nonblocked {}",
        cfg.name,
        c.cycles,
        c.pushes_accepted,
        c.pushes_refused,
        c.priority_launches,
        c.regular_launches,
        c.priority_held_back,
        c.free_zero,
        c.real_free_negative,
        c.min_real_free,
        c.faults,
        c.max_nonblocked
    );
    Some(c)
}

const fn wasp(
    name: &'static str,
    mshrs: u32,
    queue_cap: usize,
    cf_q: u32,
    threshold: u32,
) -> Config {
    Config {
        name,
        policy: 3,
        mshrs,
        queue_cap,
        cf_q,
        threshold,
        freemshr_n: 0,
        mesh_k: 4,
        launch_rule: LaunchRule::Hold,
        seeds: 6,
        cycles: 4000,
        illegal_per_mille: 0,
    }
}

/// WaSP: the paper's machine, the worked example, the widest CF, the
/// extremes of the MSHR count and threshold, tiny and large queues.
#[test]
#[cfg_attr(
    wasp_no_iverilog,
    ignore = "iverilog/vvp not installed (apt-get install iverilog, then touch props/build.rs)"
)]
fn cosim_wasp_configurations() {
    let configs = [
        Config {
            seeds: 10,
            ..wasp("wasp_paper_m16_q64_cf2.5_t4", 16, 64, 10, 4)
        },
        wasp("wasp_worked_m3_q16_cf1_t1", 3, 16, 4, 1),
        wasp("wasp_m31_q64_cf7.75_t0", 31, 64, 31, 0),
        wasp("wasp_m31_q100_cf2.5_t30", 31, 100, 10, 30),
        wasp("wasp_m3_q2_cf7.75_t2", 3, 2, 31, 2),
        wasp("wasp_m16_q1_cf0_t15", 16, 1, 0, 15),
        wasp("wasp_m1_q5_cf1.25_t0", 1, 5, 5, 0),
        Config {
            mesh_k: 2,
            ..wasp("wasp_mesh2_m8_q33_cf2.5_t3", 8, 33, 10, 3)
        },
    ];
    let mut total = Coverage::default();
    for cfg in &configs {
        let Some(c) = cosim(cfg) else { return };
        assert!(
            c.priority_launches > 0 && c.regular_launches > 0 && c.priority_held_back > 0,
            "{}: vacuous stimulus: {c:?}",
            cfg.name
        );
        assert_eq!(c.launched_gate_closed, 0, "{}: hold launched", cfg.name);
        total.add(&c);
    }
    assert!(total.held > 0, "hold never idled: {total:?}");
    assert!(total.pushes_refused > 0 && total.free_zero > 0 && total.real_free_negative > 0);
    assert_eq!(total.max_nonblocked, MAX_WARPS, "{total:?}");
}

/// The other policies: baseline (no priority FIFO), Fullpriority,
/// FreeMSHR-N, with Mesh4, Mesh8 and Mesh16.
#[test]
#[cfg_attr(
    wasp_no_iverilog,
    ignore = "iverilog/vvp not installed (apt-get install iverilog, then touch props/build.rs)"
)]
fn cosim_other_policies() {
    let base = wasp("", 16, 64, 10, 4);
    let configs = [
        Config {
            name: "baseline_m16_q64",
            policy: 0,
            ..base.clone()
        },
        Config {
            name: "fullpriority_m16_q16_mesh8",
            policy: 1,
            queue_cap: 16,
            mesh_k: 8,
            ..base.clone()
        },
        Config {
            name: "freemshr10_m16_q64",
            policy: 2,
            freemshr_n: 10,
            ..base.clone()
        },
        Config {
            name: "freemshr3_m3_q4_mesh16",
            policy: 2,
            mshrs: 3,
            queue_cap: 4,
            freemshr_n: 3,
            mesh_k: 16,
            ..base.clone()
        },
        Config {
            name: "freemshr0_m31_q7",
            policy: 2,
            mshrs: 31,
            queue_cap: 7,
            freemshr_n: 0,
            cf_q: 31,
            threshold: 0,
            ..base.clone()
        },
    ];
    for cfg in &configs {
        let Some(c) = cosim(cfg) else { return };
        assert!(c.regular_launches > 0, "{}: {c:?}", cfg.name);
        if cfg.policy == 0 {
            assert_eq!(
                c.priority_launches, 0,
                "{}: baseline launched priority",
                cfg.name
            );
        } else {
            assert!(c.priority_launches > 0, "{}: {c:?}", cfg.name);
        }
    }
}

/// Arbitrary counts on a few cycles: the twin must fault exactly when the
/// model returns a `RegisterFault`, and hold both registers as it does.
#[test]
#[cfg_attr(
    wasp_no_iverilog,
    ignore = "iverilog/vvp not installed (apt-get install iverilog, then touch props/build.rs)"
)]
fn cosim_faults_on_illegal_events() {
    let configs = [
        Config {
            illegal_per_mille: 20,
            ..wasp("illegal_wasp_m16_q64_cf2.5_t4", 16, 64, 10, 4)
        },
        Config {
            illegal_per_mille: 50,
            ..wasp("illegal_wasp_m31_q8_cf7.75_t1", 31, 8, 31, 1)
        },
        Config {
            illegal_per_mille: 50,
            ..wasp("illegal_wasp_m3_q16_cf1_t1", 3, 16, 4, 1)
        },
    ];
    for cfg in &configs {
        let Some(c) = cosim(cfg) else { return };
        assert!(
            c.faults > 10,
            "{}: too few faults exercised: {c:?}",
            cfg.name
        );
    }
}

/// The launch rule `launch` (LAUNCH_RULE = 1): WaSP launches priority warps
/// with its gate closed when no regular warp waits, and never holds; the
/// other policies with the same rule.
#[test]
#[cfg_attr(
    wasp_no_iverilog,
    ignore = "iverilog/vvp not installed (apt-get install iverilog, then touch props/build.rs)"
)]
fn cosim_launch_rule_launch() {
    let launch = |c: Config| Config {
        launch_rule: LaunchRule::Launch,
        ..c
    };
    let wasp_configs = [
        launch(wasp("launch_wasp_paper_m16_q64_cf2.5_t4", 16, 64, 10, 4)),
        launch(wasp("launch_wasp_worked_m3_q16_cf1_t1", 3, 16, 4, 1)),
        launch(wasp("launch_wasp_m31_q100_cf2.5_t30", 31, 100, 10, 30)),
        launch(wasp("launch_wasp_m3_q2_cf7.75_t2", 3, 2, 31, 2)),
    ];
    let mut total = Coverage::default();
    for cfg in &wasp_configs {
        let Some(c) = cosim(cfg) else { return };
        assert_eq!(c.held, 0, "{}: launch held: {c:?}", cfg.name);
        total.add(&c);
    }
    assert!(total.launched_gate_closed > 0, "{total:?}");
    let base = wasp("", 16, 64, 10, 4);
    for (name, policy, n) in [
        ("launch_baseline_m16_q64", 0, 0),
        ("launch_fullpriority_m16_q64", 1, 0),
        ("launch_freemshr10_m16_q64", 2, 10),
    ] {
        let cfg = launch(Config {
            name,
            policy,
            freemshr_n: n,
            ..base.clone()
        });
        let Some(c) = cosim(&cfg) else { return };
        assert_eq!(c.held, 0, "{name}: {c:?}");
        assert!(c.regular_launches > 0, "{name}: {c:?}");
    }
}
