//! docs/waveforms.md against the waveforms: the signals it says `wasp
//! example --vcd` and `wasp run --vcd` preselect are those their GTKWave
//! save files list, no more and no fewer; and the datapath's outputs hold
//! what it says they hold in each cycle.

use std::collections::BTreeSet;
use wasp_waves::readback;

mod common;
use common::run::{dir, run_tiny, tiny_config};
use common::{ok, wasp};

/// The backticked words of docs/waveforms.md between `from` and `to`,
/// without the command names.
fn documented(from: &str, to: &str) -> BTreeSet<String> {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/docs/waveforms.md"))
        .unwrap()
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    let a = text.find(from).unwrap_or_else(|| panic!("`{from}`")) + from.len();
    let b = a + text[a..].find(to).unwrap_or_else(|| panic!("`{to}`"));
    text[a..b]
        .split('`')
        .skip(1)
        .step_by(2)
        .filter(|w| !w.starts_with("wasp"))
        .map(str::to_string)
        .collect()
}

/// The signal names (last path component, without the bit range) a save
/// file traces.
fn saved(gtkw: &std::path::Path) -> BTreeSet<String> {
    std::fs::read_to_string(gtkw)
        .unwrap()
        .lines()
        .filter(|l| !l.is_empty() && !"[@-*".contains(&l[..1]))
        .map(|l| {
            let name = l.rsplit('.').next().unwrap();
            name.split('[').next().unwrap().to_string()
        })
        .collect()
}

#[test]
fn the_documented_preselections_are_the_save_files() {
    let d = dir("waves-doc");
    let vcd = d.join("example.vcd");
    ok(&wasp(&["example", "-q", "--vcd", vcd.to_str().unwrap()]));
    let example = saved(&d.join("example.vcd.gtkw"));
    assert_eq!(
        documented("for `wasp example --vcd`", "For `wasp run --vcd`"),
        example
    );
    let cfg = tiny_config(&d);
    let mut run = BTreeSet::new();
    for policy in ["wasp", "wasp-m"] {
        let vcd = d.join(format!("{policy}.vcd"));
        ok(&run_tiny(
            &cfg,
            &["--policy", policy, "--vcd", vcd.to_str().unwrap()],
        ));
        run.extend(saved(&d.join(format!("{policy}.vcd.gtkw"))));
    }
    assert_eq!(
        documented("For `wasp run --vcd`", "The caches, the other cores"),
        run
    );
}

/// `real_free_mshrs` at each cycle with a launch, against `free_mshrs -
/// CF x nonblocked_priority` at the cycle `lag` before: every launch
/// cycle, the share that matches.
fn datapath_matches(vcd: &std::path::Path, scope: &str, cf_q: u64, lag: u64) -> (usize, usize) {
    let rb = readback::values_by_cycle(&std::fs::read(vcd).unwrap()).unwrap();
    let sig = |n: &str| format!("{scope}.scheduler.{n}");
    let launch = rb.signal(&sig("launch")).unwrap();
    let (mut launches, mut matching) = (0, 0);
    for &(t, v) in launch.changes() {
        if v == 0 || t < lag {
            continue;
        }
        let at = |n: &str, c: u64| rb.value_at(&sig(n), c).map(|v| v as i64);
        // The first sampled cycle has no cycle before it.
        let (Some(real), Some(free), Some(nb)) = (
            at("real_free_mshrs", t),
            at("free_mshrs", t - lag),
            at("nonblocked_priority", t - lag),
        ) else {
            continue;
        };
        let real = if real >= 1024 { real - 2048 } else { real };
        let want = free - (nb * cf_q as i64) / 4;
        launches += 1;
        matching += usize::from(real == want);
    }
    (launches, matching)
}

#[test]
fn the_datapath_holds_the_last_decision_as_documented() {
    let d = dir("waves-datapath");
    // `wasp example`: sampled before the edge, the same cycle's registers
    // (the example's WaSP: CF 1, four quarters).
    let vcd = d.join("e.vcd");
    ok(&wasp(&["example", "-q", "--vcd", vcd.to_str().unwrap()]));
    let (n, same) = datapath_matches(&vcd, "wasp_example.wasp", 4, 0);
    assert!(n > 0);
    assert_eq!(same, n, "example: same-cycle registers");
    // `wasp run`: sampled after the edge, the registers shown a cycle
    // before (the shipped CF 3, twelve quarters).
    let cfg = tiny_config(&d);
    let vcd = d.join("r.vcd");
    ok(&run_tiny(
        &cfg,
        &["--policy", "wasp", "--vcd", vcd.to_str().unwrap()],
    ));
    let (n, before) = datapath_matches(&vcd, "wasp.core0", 12, 1);
    assert!(n > 0);
    assert_eq!(before, n, "run: the previous cycle's registers");
}
