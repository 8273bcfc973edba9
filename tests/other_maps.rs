//! Maps and tracks of the four games that are not among the shipped scenes,
//! run end to end through the command line as a user would: a scene
//! definition written on the spot, `wasp render --trace-out`, then
//! `wasp run --trace` on the paper's machine with the baseline and WaSP.
//!
//! The games' data is GPL / CC-BY-SA and is never committed, so these tests
//! need it fetched first (`wasp scenes fetch supertuxkart openarena
//! teeworlds frozen-bubble`) and are ignored by default:
//!
//! ```sh
//! cargo test --release --test other_maps -- --ignored
//! ```

use std::path::Path;

mod common;
use common::{scratch, stderr, wasp};

fn json_u64(v: &serde_json::Value, key: &str) -> u64 {
    v[key]
        .as_u64()
        .unwrap_or_else(|| panic!("`{key}` missing in {v}"))
}

/// Write a scene definition for (`game`, `map`, `camera`), render it to a
/// trace and a PNG, run the trace with two policies, and check what the
/// runs report.
fn end_to_end(game: &str, map: &str, camera: &str) {
    let dir = scratch("other-maps", &format!("{game}-{map}"));
    let scene = dir.join("scene.toml");
    std::fs::write(
        &scene,
        format!(
            "name = \"other-{game}-{map}\"\ngame = \"{game}\"\nmap = \"{map}\"\ncamera = \"{camera}\"\nwidth = 1960\nheight = 768\ndescription = \"not shipped: end-to-end test\"\n"
        ),
    )
    .unwrap();
    let trace = dir.join("frame.trace");
    let png = dir.join("frame.png");
    let (scene, trace, png) = (path(&scene), path(&trace), path(&png));
    let out = wasp(&["render", "-q", scene, "--trace-out", trace, "--png", png]);
    assert!(
        out.status.success(),
        "render {game} {map}: {}",
        stderr(&out)
    );
    assert_png(Path::new(png));
    let mut cycles = Vec::new();
    for policy in ["baseline", "wasp:4"] {
        let out = wasp(&[
            "run", "-q", "--policy", policy, "--json", "-", "--trace", trace,
        ]);
        assert!(
            out.status.success(),
            "run {game} {map} {policy}: {}",
            stderr(&out)
        );
        let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let warps = json_u64(&v, "warps");
        assert!(warps > 1000, "{game} {map}: only {warps} warps");
        assert!(json_u64(&v, "instructions") > warps);
        assert!(v["l1"]["accesses"].as_u64().unwrap() > 0, "{v}");
        assert!(v["dram"]["requests"].as_u64().unwrap() > 0, "{v}");
        cycles.push(json_u64(&v, "cycles"));
        eprintln!(
            "{game} {map} {policy}: {warps} warps, {} cycles",
            json_u64(&v, "cycles")
        );
    }
    assert!(cycles.iter().all(|&c| c > 1000));
    std::fs::remove_dir_all(&dir).ok();
}

fn path(p: &Path) -> &str {
    p.to_str().expect("a UTF-8 temporary path")
}

fn assert_png(p: &Path) {
    let bytes = std::fs::read(p).unwrap();
    assert_eq!(
        &bytes[..8],
        b"\x89PNG\r\n\x1a\n",
        "{} is not a PNG",
        p.display()
    );
}

#[test]
#[ignore = "needs fetched game data: wasp scenes fetch supertuxkart"]
fn supertuxkart_tracks_not_shipped() {
    end_to_end("supertuxkart", "hacienda", "start:0");
    end_to_end("supertuxkart", "snowmountain", "driveline:0.3");
}

#[test]
#[ignore = "needs fetched game data: wasp scenes fetch openarena"]
fn openarena_maps_not_shipped() {
    end_to_end("openarena", "oa_dm2", "spawn:0");
    end_to_end("openarena", "aggressor", "spawn:1");
}

#[test]
#[ignore = "needs fetched game data: wasp scenes fetch teeworlds"]
fn teeworlds_maps_not_shipped() {
    end_to_end("teeworlds", "ctf2", "spawn:0");
    end_to_end("teeworlds", "dm2", "center");
}

#[test]
#[ignore = "needs fetched game data: wasp scenes fetch frozen-bubble"]
fn frozen_bubble_levels_not_shipped() {
    end_to_end("frozen-bubble", "levels", "level:7");
    end_to_end("frozen-bubble", "levels", "level:77");
}
