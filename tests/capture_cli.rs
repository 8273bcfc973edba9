//! Whole-program tests of `wasp scenes capture` and of the engine route:
//! the errors need no game; the captures themselves need the Debian
//! packages (openarena; teeworlds and teeworlds-server; xvfb; apitrace)
//! and are `#[ignore]`d (`cargo test --test capture_cli -- --ignored`).

mod common;
use common::{ok, scratch, stderr, wasp};
use std::process::{Command, Output};

/// `wasp ARGS` with the scene cache in `cache` and `PATH` set to `path`.
fn wasp_env(args: &[&str], cache: &std::path::Path, path: &str) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wasp"))
        .args(args)
        .env("WASP_SCENES", cache)
        .env("PATH", path)
        .output()
        .unwrap()
}

#[test]
fn missing_tools_stop_the_capture_with_the_apt_get_line() {
    let d = scratch("capture", "missing-tools");
    let empty = d.join("empty-bin");
    std::fs::create_dir_all(&empty).unwrap();
    // No xvfb-run and no apitrace on this PATH.
    let o = wasp_env(
        &["scenes", "capture", "oa-dm1-spawn0-engine"],
        &d.join("cache"),
        empty.to_str().unwrap(),
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(e.contains("wasp installs nothing itself"), "{e}");
    let line = e
        .lines()
        .find(|l| l.trim_start().starts_with("apt-get install "))
        .unwrap_or_else(|| panic!("no apt-get line: {e}"));
    assert!(line.contains("xvfb") && line.contains("apitrace"), "{line}");
    assert!(
        !d.join("cache/captures").exists(),
        "nothing written before the check"
    );
}

#[test]
fn only_engine_scenes_are_captured() {
    let o = wasp(&["scenes", "capture", "oa-dm1-spawn0"]);
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert!(
        e.contains("route = \"loader\"") && e.contains("oa-dm1-spawn0-engine"),
        "{e}"
    );
    let o = wasp(&["scenes", "capture", "no-such-scene"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("no scene named `no-such-scene`"),
        "{}",
        stderr(&o)
    );
    let o = wasp(&["scenes", "capture", "oa-dm1-spawn0-engine", "--frames", "0"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--frames 0"), "{}", stderr(&o));
}

#[test]
fn an_engine_scene_is_rendered_from_its_capture_only() {
    let d = scratch("capture", "render-engine");
    let png = d.join("x.png");
    // Without --trace-out: nothing is captured or written.
    let o = wasp(&[
        "render",
        "oa-dm1-spawn0-engine",
        "--png",
        png.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert!(
        e.contains("engine route") && e.contains("--trace-out"),
        "{e}"
    );
    assert!(!png.exists());
    // The loader's options are refused by name.
    let t = d.join("x.trace");
    let o = wasp(&[
        "render",
        "oa-dm1-spawn0-engine",
        "--trace-out",
        t.to_str().unwrap(),
        "--overlay",
        "grid",
        "--depth-prepass",
    ]);
    assert_eq!(o.status.code(), Some(2));
    let e = stderr(&o);
    assert!(
        e.contains("--overlay, --depth-prepass apply to loader scenes only"),
        "{e}"
    );
    assert!(!t.exists());
}

#[test]
fn characterize_captures_an_engine_scene_or_says_why_not() {
    let d = scratch("capture", "characterize-engine");
    let empty = d.join("empty-bin");
    std::fs::create_dir_all(&empty).unwrap();
    // No capture in this cache and no tools on this PATH: the capture
    // stops with the apt-get line and nothing is characterised.
    let o = wasp_env(
        &["characterize", "oa-dm1-spawn0-engine"],
        &d.join("cache"),
        empty.to_str().unwrap(),
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(e.contains("apt-get install"), "{e}");
    assert!(e.contains("no scene could be characterised"), "{e}");
    // The loader's depth pre-pass is refused by name for an engine scene.
    let o = wasp_env(
        &["characterize", "oa-dm1-spawn0-engine", "--depth-prepass"],
        &d.join("cache"),
        empty.to_str().unwrap(),
    );
    let e = stderr(&o);
    assert!(
        e.contains("--depth-prepass applies to loader scenes"),
        "{e}"
    );
}

#[test]
fn the_list_names_the_engine_twins_and_how_to_capture_them() {
    let d = scratch("capture", "list");
    let o = wasp_env(&["scenes", "list"], &d, &std::env::var("PATH").unwrap());
    let list = ok(&o);
    let line = list
        .lines()
        .find(|l| l.starts_with("oa-dm5-spawn1-engine "))
        .unwrap_or_else(|| panic!("{list}"));
    assert!(
        line.contains("engine: not captured (wasp scenes capture oa-dm5-spawn1-engine)"),
        "{line}"
    );
}

/// Capture `scene` into a fresh scene cache; its sidecar.
fn capture(scene: &str) -> (serde_json::Value, std::path::PathBuf) {
    let d = scratch("capture", scene);
    let o = wasp_env(
        &["scenes", "capture", scene],
        &d,
        &std::env::var("PATH").unwrap(),
    );
    let out = ok(&o);
    let trace = d.join("captures").join(format!("{scene}.trace"));
    assert_eq!(out.trim(), trace.to_str().unwrap());
    let side = std::fs::read_to_string(d.join("captures").join(format!("{scene}.json"))).unwrap();
    let v: serde_json::Value = serde_json::from_str(&side).unwrap();
    assert!(v["seconds"].as_f64().unwrap() < 60.0, "{v}");
    assert_eq!(
        v["bytes"].as_u64(),
        Some(std::fs::metadata(&trace).unwrap().len())
    );
    // A second run finds it in the cache.
    let again = wasp_env(
        &["scenes", "capture", scene],
        &d,
        &std::env::var("PATH").unwrap(),
    );
    assert!(
        stderr(&again).contains("is in the scene cache"),
        "{}",
        stderr(&again)
    );
    (v, trace)
}

#[test]
#[ignore = "needs the openarena, xvfb and apitrace packages"]
fn openarena_is_captured_at_the_spawn_point() {
    let (v, _) = capture("oa-dm1-spawn0-engine");
    assert!(v["frames"].as_u64().unwrap() > 5, "{v}");
    // The spawn point's eye is (280 1416 -94); viewpos prints whole
    // units, truncated toward zero.
    let at = |i: usize| v["camera"]["engine_viewpos"][i].as_i64().unwrap();
    assert!((at(0) - 280).abs() <= 1 && at(1) == 1416, "{v}");
    assert!(
        (at(2) + 94).abs() <= 1 && at(3).rem_euclid(360) == 180,
        "{v}"
    );
}

#[test]
#[ignore = "needs the teeworlds, teeworlds-server, xvfb and apitrace packages"]
fn teeworlds_is_captured_from_a_local_server() {
    let (v, _) = capture("tw-dm1-spawn0-engine");
    assert!(v["frames"].as_u64().unwrap() > 1, "{v}");
    assert!(v["camera"]["server"]
        .as_str()
        .unwrap()
        .contains("bindaddr 127.0.0.1"));
}
