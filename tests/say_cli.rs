//! Whole-program tests: the CLI refuses nonsense before it works, and says
//! what happened when a run gives less than was asked for.

mod common;

use common::{scratch, stderr, wasp};
use std::path::PathBuf;

fn dir(name: &str) -> PathBuf {
    scratch("say", name)
}

/// The exit code and standard error of `wasp args`.
fn refused(args: &[&str]) -> (i32, String) {
    let o = wasp(args);
    (o.status.code().expect("exit code"), stderr(&o))
}

#[test]
fn cost_refuses_arguments_that_price_nothing() {
    let (code, e) = refused(&["cost", "--no-yosys", "--registers-per-thread", "0"]);
    assert_eq!(code, 2, "{e}");
    assert!(
        e.contains("--registers-per-thread") && e.contains("1..=1024"),
        "{e}"
    );
    let (code, e) = refused(&["cost", "--no-yosys", "--baseline-warps", "129"]);
    assert_eq!(code, 2, "{e}");
    assert!(
        e.contains("--baseline-warps") && e.contains("2..=128"),
        "{e}"
    );
    let (code, e) = refused(&["cost", "--no-yosys", "--wasp-warps", "0"]);
    assert_eq!(code, 2, "{e}");
    assert!(e.contains("--wasp-warps") && e.contains("1..128"), "{e}");
    // The paper machine's baseline needs 64 warps: WaSP with as many saves
    // nothing.
    let (code, e) = refused(&["cost", "--no-yosys", "--wasp-warps", "64"]);
    assert_eq!(code, 2, "{e}");
    assert!(
        e.contains("--wasp-warps 64 with --baseline-warps 64: WaSP must need fewer warps"),
        "{e}"
    );
    let o = wasp(&["cost", "--no-yosys", "--registers-per-thread", "1"]);
    let out = common::ok(&o);
    assert!(out.contains("register file per warp: 128 bits"), "{out}");
}

#[test]
fn bench_bounds_scale_and_repeats() {
    for (flag, value, range) in [
        ("--scale", "0", "1..=64"),
        ("--scale", "65", "1..=64"),
        ("--scale", "4294967295", "1..=64"),
        ("--repeats", "0", "1..=100"),
        ("--repeats", "101", "1..=100"),
    ] {
        let (code, e) = refused(&["bench", flag, value]);
        assert_eq!(code, 2, "{flag} {value}: {e}");
        assert!(
            e.contains(&format!("invalid value '{value}' for '{flag}"))
                && e.contains(&format!("{value} is not in {range}")),
            "{flag} {value}: {e}"
        );
    }
}

#[test]
fn render_checks_size_crop_and_scene_before_rendering() {
    let d = dir("render");
    let png = d.join("frame.png");
    let png = png.to_str().unwrap();
    let (code, e) = refused(&[
        "render",
        "procedural-plane",
        "--png",
        png,
        "--size",
        "1x65536",
    ]);
    assert_eq!(code, 2, "{e}");
    assert!(
        e.contains("--size `1x65536`: the height is 65536 pixels; each side must be in 1..=16384"),
        "{e}"
    );
    // At the scene's own 1960x768, a crop outside the frame is refused
    // before the frame is rendered (which would print its summary).
    let (code, e) = refused(&[
        "render",
        "procedural-plane",
        "--png",
        png,
        "--crop",
        "1900,0,100,10",
    ]);
    assert_eq!(code, 2, "{e}");
    assert!(
        e.contains(
            "--crop `1900,0,100,10`: pixels 1900..2000 x 0..10 reach outside the 1960x768 frame"
        ),
        "{e}"
    );
    assert!(!e.contains("triangles"), "rendered before refusing: {e}");
    assert!(!std::path::Path::new(png).exists());
    let tmp = std::env::temp_dir();
    let (code, e) = refused(&["render", tmp.to_str().unwrap(), "--png", png]);
    assert_eq!(code, 2, "{e}");
    assert!(
        e.contains("is a directory, not a scene name or scene file"),
        "{e}"
    );
    let readme = concat!(env!("CARGO_MANIFEST_DIR"), "/README.md");
    let (code, e) = refused(&["render", readme, "--png", png]);
    assert_eq!(code, 2, "{e}");
    assert!(e.contains("is not a scene definition"), "{e}");
    let (code, e) = refused(&["render", "missing.toml", "--png", png]);
    assert_eq!(code, 2, "{e}");
    assert!(e.contains("missing.toml: no such scene file"), "{e}");
    let (code, e) = refused(&["render", "no-such-scene", "--png", png]);
    assert_eq!(code, 2, "{e}");
    assert!(e.contains("no scene named `no-such-scene`"), "{e}");
}

#[test]
fn a_config_that_is_not_utf8_is_named_with_its_line_and_column() {
    let d = dir("utf8");
    let cfg = d.join("latin1.toml");
    // "é" in Latin-1 (0xe9) on line 3, after five ASCII bytes; the UTF-8
    // "é" of line 1 is fine.
    std::fs::write(&cfg, b"# caf\xc3\xa9\n[core]\nx = \"\xe9t\xe9\"\n").unwrap();
    let c = cfg.to_str().unwrap();
    for cmd in [
        &["run", "--config", c][..],
        &["cost", "--no-yosys", "--config", c],
    ] {
        let (code, e) = refused(cmd);
        assert_eq!(code, 2, "{e}");
        assert!(
            e.contains(&format!(
                "{c}:3:6: byte 0xe9 is not UTF-8 (line 3, byte column 6)"
            )),
            "{e}"
        );
    }
}

#[test]
fn a_vcd_window_after_the_run_is_a_warning() {
    let d = dir("vcd");
    let vcd = d.join("late.vcd");
    let trace = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/traces/tiny.trace");
    let run = |window: &[&str]| {
        let mut a = vec![
            "run",
            "-q",
            "--set",
            "gpu.tile_size=8",
            "--trace",
            trace,
            "--json",
            "-",
            "--vcd",
            vcd.to_str().unwrap(),
        ];
        a.extend_from_slice(window);
        wasp(&a)
    };
    let o = run(&["--vcd-from", "100000", "--vcd-to", "200000"]);
    let v: serde_json::Value = serde_json::from_str(&common::ok(&o)).unwrap();
    let cycles = v["cycles"].as_u64().unwrap();
    assert!(cycles < 100_000);
    let e = stderr(&o);
    assert!(
        e.contains(&format!(
            "wasp: warning: the run ended at cycle {cycles}, before --vcd-from 100000: {} holds no cycle of the window 100000..=200000",
            vcd.display()
        )),
        "{e}"
    );
    let o = run(&["--vcd-from", "100000"]);
    assert!(o.status.success());
    assert!(
        stderr(&o).contains("no cycle of the window 100000.."),
        "{}",
        stderr(&o)
    );
    // A window inside the run, and an inverted one (refused before the run).
    let o = run(&["--vcd-from", "10", "--vcd-to", "20"]);
    assert!(o.status.success());
    assert!(!stderr(&o).contains("warning"), "{}", stderr(&o));
    // (A trace that does not exist: the flags are refused before reading it.)
    let (code, e) = refused(&[
        "run",
        "-q",
        "--trace",
        "missing.trace",
        "--vcd",
        vcd.to_str().unwrap(),
        "--vcd-from",
        "20",
        "--vcd-to",
        "10",
    ]);
    assert_eq!(code, 2, "{e}");
    assert!(e.contains("--vcd-from 20 is after --vcd-to 10"), "{e}");
}

#[test]
fn every_command_that_simulates_or_renders_takes_quiet() {
    for cmd in [
        "example",
        "run",
        "compare",
        "synth",
        "bench",
        "render",
        "characterize",
    ] {
        let help = common::ok(&wasp(&[cmd, "--help"]));
        assert!(
            help.contains("-q, --quiet") && help.contains("No progress output on stderr"),
            "{cmd}: {help}"
        );
    }
    // Same result, quiet or not.
    assert_eq!(
        common::ok(&wasp(&["example", "-q"])),
        common::ok(&wasp(&["example"]))
    );
    // characterize notes each scene as it goes, unless quiet.
    let args = ["characterize", "procedural-sprites", "--json", "-"];
    let loud = wasp(&args);
    let quiet = wasp(&[&args[..], &["--quiet"]].concat());
    // The same figures (but for the wall-clock raster_seconds).
    let figures = |o: &std::process::Output| {
        let mut v: serde_json::Value = serde_json::from_str(&common::ok(o)).unwrap();
        v[0].as_object_mut().unwrap().remove("raster_seconds");
        v
    };
    assert_eq!(figures(&loud), figures(&quiet));
    assert!(
        stderr(&loud).contains("wasp: characterising procedural-sprites (1 of 1)"),
        "{}",
        stderr(&loud)
    );
    assert!(
        !stderr(&quiet).contains("characterising"),
        "{}",
        stderr(&quiet)
    );
}
