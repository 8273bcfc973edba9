//! Co-simulation of the Verilog twin (`props/verilog/wasp_sched.v`) against
//! the Rust register-transfer model (`wasp_rtl::scheduler::LaunchScheduler`).
//!
//! For each configuration, seeded random stimulus drives the Rust scheduler
//! cycle by cycle in the block-level order `enqueue -> launch -> clock`,
//! and every cycle's inputs and the model's outputs are
//! recorded. The stimulus goes to a file; `iverilog -g2005` compiles
//! `tb_cosim.v` with the configuration as parameters, `vvp` runs it, and
//! every output of every cycle is compared with the model: the registers
//! (free MSHRs, non-blocked count, both queue occupancies), the comparator,
//! push acceptance, the datapath (product, real_free, the comparison), the
//! policy's selection under the launch rule (`hold` or `launch`), the
//! launch, the fault flag, and wasp-m's CF meter (its launch count,
//! accumulator and the CF the datapath uses).
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
use wasp_rtl::policy::LaunchRule;

#[path = "cosim/stimulus.rs"]
mod stimulus;
#[path = "cosim/verilog.rs"]
mod verilog;

use stimulus::*;
use verilog::*;

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
    let meter = if cfg.policy == 4 {
        format!(
            "; meter: {} windows, {} cycles saturated, {} misses clamped, {} CF values",
            c.meter_windows,
            c.meter_saturated,
            c.misses_clamped,
            c.cf_values.count_ones()
        )
    } else {
        String::new()
    };
    eprintln!(
        "cosim {}: {seeds} seeds x {cycles} cycles = {} cycles match; pushes {} accepted / {} refused, launches {} priority / {} regular, priority held back {}, free==0 {}, real_free<0 {} (min {}), faults {}, max nonblocked {}{meter}",
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

const fn wasp_m(name: &'static str, mshrs: u32, queue_cap: usize, threshold: u32) -> Config {
    Config {
        policy: 4,
        ..wasp(name, mshrs, queue_cap, 10, threshold)
    }
}

/// wasp-m (POLICY 4): the CF the datapath multiplies by comes from the CF
/// meter, compared register by register with `wasp_rtl::cf_meter::CfMeter`
/// every cycle: windows of 16 priority launches load the CF register, the
/// accumulator saturates, counts above the 2-bit misses input clamp, and a
/// fault holds the meter too.
#[test]
#[cfg_attr(
    wasp_no_iverilog,
    ignore = "iverilog/vvp not installed (apt-get install iverilog, then touch props/build.rs)"
)]
fn cosim_wasp_measured() {
    let configs = [
        Config {
            seeds: 8,
            ..wasp_m("waspm_paper_m16_q64_t4", 16, 64, 4)
        },
        wasp_m("waspm_worked_m3_q16_t1", 3, 16, 1),
        wasp_m("waspm_m31_q8_t0", 31, 8, 0),
        Config {
            launch_rule: LaunchRule::Launch,
            ..wasp_m("launch_waspm_m16_q64_t4", 16, 64, 4)
        },
        Config {
            illegal_per_mille: 30,
            ..wasp_m("illegal_waspm_m16_q64_t4", 16, 64, 4)
        },
    ];
    let mut total = Coverage::default();
    for cfg in &configs {
        let Some(c) = cosim(cfg) else { return };
        assert!(
            c.priority_launches > 0 && c.regular_launches > 0 && c.meter_windows > 0,
            "{}: vacuous stimulus: {c:?}",
            cfg.name
        );
        if cfg.illegal_per_mille > 0 {
            assert!(c.faults > 10, "{}: too few faults: {c:?}", cfg.name);
        }
        total.add(&c);
    }
    assert!(
        total.meter_saturated > 0 && total.misses_clamped > 0 && total.priority_held_back > 0,
        "{total:?}"
    );
    assert!(
        total.cf_values.count_ones() >= 8,
        "the meter held few CF values: {:#b}",
        total.cf_values
    );
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
