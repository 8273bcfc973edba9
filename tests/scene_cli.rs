//! Whole-program tests of `wasp render` with the procedural scenes (no game
//! data needed) and of running a format-2 trace with repeated positions.

use serde_json::Value;
use std::path::PathBuf;
use wasp_sim::config::MachineConfig;
use wasp_sim::trace::Trace;

mod common;
use common::{ok, wasp};

fn dir(name: &str) -> PathBuf {
    common::scratch("scene", name)
}

#[test]
fn rendered_traces_are_format_4_with_one_warp_per_fragment_for_any_thread_count() {
    let d = dir("threads");
    let mut texts = Vec::new();
    for threads in ["1", "3", "0"] {
        let p = d.join(format!("sprites-{threads}.trace"));
        let o = wasp(&[
            "render",
            "procedural-sprites",
            "--size",
            "320x192",
            "--threads",
            threads,
            "--trace-out",
            p.to_str().unwrap(),
        ]);
        ok(&o);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains("warps (one per fragment)"), "{err}");
        texts.push(std::fs::read_to_string(&p).unwrap());
    }
    assert!(
        texts.iter().all(|t| t == &texts[0]),
        "thread count changed the trace"
    );
    assert!(texts[0].starts_with("wasp-trace 4\n"));
    let t = Trace::parse(&texts[0], "sprites").unwrap();
    let s = t.stats();
    // Sprites filter bilinear or nearest: no trilinear instruction.
    assert_eq!(s.tri_tex_instrs, 0);
    assert!(!texts[0].contains(" T"));
    // Sprites blended over a backdrop: positions repeat.
    assert!(
        s.warps > s.positions,
        "{} warps at {} positions",
        s.warps,
        s.positions
    );
    assert_eq!(s.positions, s.frame_quads);
    let _ = std::fs::remove_dir_all(&d);
}

/// The plane's ground, crates and bricks filter trilinear, its sky
/// bilinear: the trace marks the instructions whose sample read two mip
/// levels, and only those.
#[test]
fn rendered_trilinear_samples_are_marked() {
    let d = dir("trilinear");
    let p = d.join("plane.trace");
    ok(&wasp(&[
        "render",
        "procedural-plane",
        "--size",
        "320x192",
        "-q",
        "--trace-out",
        p.to_str().unwrap(),
    ]));
    let t = Trace::read(&p).unwrap();
    let s = t.stats();
    assert!(s.tri_tex_instrs > 0, "{s:?}");
    assert!(
        s.tri_tex_instrs < s.tex_instrs,
        "the sky is bilinear: {s:?}"
    );
    assert!(s.trilinear_share > 0.0 && s.trilinear_share < 1.0);
    // A trilinear instruction reads two mip levels, so never fewer blocks
    // than two.
    for tile in t.tiles() {
        for q in tile.quads() {
            for i in q.instrs() {
                if i.is_trilinear() {
                    assert!(i.blocks().unwrap().len() >= 2, "{i:?}");
                }
            }
        }
    }
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn render_timings_split_load_and_raster() {
    let out = ok(&wasp(&[
        "render",
        "procedural-plane",
        "--size",
        "192x128",
        "--timings",
        "--repeat",
        "2",
        "-q",
    ]));
    for want in [
        "best of 2",
        "load: parse meshes, decode textures",
        "raster + texture",
        "mip chains",
        "tiles: raster, early-Z",
    ] {
        assert!(out.contains(want), "{want}: {out}");
    }
    assert!(!out.contains("PNG"), "nothing written: {out}");
    let o = wasp(&["render", "procedural-plane", "--timings", "--repeat", "0"]);
    assert!(!o.status.success());
    let o = wasp(&["render", "procedural-plane"]);
    assert!(!o.status.success(), "nothing to write or time");
}

#[test]
fn the_cycle_model_runs_repeated_positions_as_separate_warps() {
    let d = dir("overdraw");
    let mut c = MachineConfig::paper();
    c.gpu.tile_size = 8;
    let cfg = d.join("tile8.toml");
    std::fs::write(&cfg, c.to_toml()).unwrap();
    let trace = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/traces/overdraw.trace");
    let out = ok(&wasp(&[
        "run",
        "-q",
        "--json",
        "-",
        "--trace",
        trace,
        "--config",
        cfg.to_str().unwrap(),
    ]));
    let v: Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["warps"], 9, "{v}");
    assert_eq!(v["workload"], "hand:overdraw");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_scenes_folder_adds_and_replaces_definitions() {
    let d = dir("scenes-dir");
    let defs = d.join("defs");
    std::fs::create_dir_all(&defs).unwrap();
    let def = |name: &str, w: u32, h: u32| {
        format!(
            "name = \"{name}\"\ngame = \"procedural\"\nmap = \"plane\"\ncamera = \"ground\"\n\
             width = {w}\nheight = {h}\n"
        )
    };
    std::fs::write(defs.join("extra-plane.toml"), def("extra-plane", 128, 64)).unwrap();
    std::fs::write(defs.join("plane.toml"), def("procedural-plane", 192, 96)).unwrap();
    let defs_s = defs.to_str().unwrap();
    let by_flag = ok(&wasp(&["scenes", "list", "--scenes-dir", defs_s]));
    let line = |list: &str, name: &str| {
        list.lines()
            .find(|l| l.split_whitespace().next() == Some(name))
            .unwrap_or_else(|| panic!("{name} not listed:\n{list}"))
            .to_string()
    };
    assert!(line(&by_flag, "extra-plane").contains("128x64"));
    assert!(
        line(&by_flag, "procedural-plane").contains("192x96"),
        "replaced"
    );
    assert!(
        line(&by_flag, "tw-dm1-spawn0").contains("1960x768"),
        "still shipped"
    );
    assert!(
        by_flag.contains(&format!("built in, and {defs_s}")),
        "{by_flag}"
    );
    // The environment variable does the same.
    let by_env = std::process::Command::new(env!("CARGO_BIN_EXE_wasp"))
        .args(["scenes", "list"])
        .env("WASP_SCENES_DIR", &defs)
        .output()
        .unwrap();
    assert_eq!(ok(&by_env), by_flag);
    // Without either, the built-in definitions alone.
    let plain = ok(&wasp(&["scenes", "list"]));
    assert!(line(&plain, "procedural-plane").contains("1960x768"));
    assert!(!plain.contains("extra-plane"));
    // An added scene renders by name.
    let t = d.join("extra.trace");
    ok(&wasp(&[
        "render",
        "--scenes-dir",
        defs_s,
        "extra-plane",
        "--trace-out",
        t.to_str().unwrap(),
        "-q",
    ]));
    assert!(Trace::read(&t).unwrap().quad_count() > 0);
    // A folder that is not there is named.
    let r = wasp(&["scenes", "list", "--scenes-dir", "/nonexistent/defs"]);
    assert_eq!(r.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&r.stderr).contains("/nonexistent/defs"));
    let _ = std::fs::remove_dir_all(&d);
}

/// A reader that stops early ends wasp quietly (as `head` does to other
/// tools), never with a panic message.
#[cfg(unix)]
#[test]
fn a_closed_pipe_ends_the_listing_quietly() {
    use std::io::{BufRead, BufReader};
    use std::os::unix::process::ExitStatusExt;
    use std::process::{Command, Stdio};
    // Enough lines that the pipe is closed before the listing ends.
    let d = dir("pipe");
    for i in 0..2000 {
        std::fs::write(
            d.join(format!("p{i}.toml")),
            format!(
                "name = \"pipe-plane-{i}\"\ngame = \"procedural\"\nmap = \"plane\"\n\
                 camera = \"ground\"\nwidth = 64\nheight = 64\n"
            ),
        )
        .unwrap();
    }
    let mut child = Command::new(env!("CARGO_BIN_EXE_wasp"))
        .args(["scenes", "list", "--scenes-dir", d.to_str().unwrap()])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut first)
        .unwrap();
    assert!(first.starts_with("scene "), "{first}");
    // The reader is gone; wasp finishes by the signal or by success.
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("panicked"), "{err}");
    assert!(
        out.status.success() || out.status.signal() == Some(13),
        "{:?}",
        out.status
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn fetch_skips_a_fetched_game_and_render_q_prints_nothing() {
    let cache = dir("fetched-cache");
    let root = cache.join("teeworlds");
    std::fs::create_dir_all(&root).unwrap();
    std::fs::write(root.join(".wasp-fetched"), "teeworlds-data 1\n").unwrap();
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_wasp"))
        .args(["scenes", "fetch", "teeworlds"])
        .env("WASP_SCENES", &cache)
        .output()
        .unwrap();
    let e = common::stderr(&o);
    assert!(o.status.success(), "{e}");
    assert!(
        e.contains("teeworlds: already fetched") && e.contains("--force"),
        "{e}"
    );
    // The marker is untouched: nothing was fetched again.
    assert_eq!(
        std::fs::read_to_string(root.join(".wasp-fetched")).unwrap(),
        "teeworlds-data 1\n"
    );
    let out = dir("quiet").join("q.trace");
    let o = wasp(&[
        "render",
        "procedural-sprites",
        "--size",
        "128x64",
        "-q",
        "--trace-out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success());
    assert_eq!(common::stdout(&o), "");
    assert_eq!(common::stderr(&o), "");
}
