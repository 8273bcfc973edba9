//! `wasp import-gl --check-mesa` on tests/gl/quads.trace: every frame's
//! coverage, depth complexity and texture per pixel agree with Mesa's
//! (glretrace under xvfb-run), and the comparison does see a difference
//! where there is one. Without the tools it passes with a note, unless
//! `WASP_REQUIRE_TOOLS=1` (CI).

use std::path::{Path, PathBuf};
use std::process::Command;
use wasp_frontend::glcheck::{compare, View};

mod common;
use common::{ok, wasp};

fn tool(name: &str) -> bool {
    Command::new("sh")
        .args(["-c", &format!("command -v {name}")])
        .output()
        .is_ok_and(|o| o.status.success())
}

/// Tools missing, after failing if CI requires them.
fn missing_tools() -> bool {
    let missing: Vec<&str> = ["xvfb-run", "xauth", "glretrace"]
        .into_iter()
        .filter(|t| !tool(t))
        .collect();
    if missing.is_empty() {
        return false;
    }
    assert_ne!(
        std::env::var("WASP_REQUIRE_TOOLS").as_deref(),
        Ok("1"),
        "required tools are missing: {missing:?}"
    );
    eprintln!("skipped: {missing:?} not installed");
    true
}

/// `wasp import-gl quads.trace --frame N --check-mesa DIR`: DIR and its
/// agreement.json.
fn check(frame: u64) -> (PathBuf, serde_json::Value) {
    let dir = common::scratch("checkmesa", &format!("frame{frame}"));
    let cap = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/gl/quads.trace");
    let trace = dir.join("out.trace");
    let mesa = dir.join("mesa");
    let f = frame.to_string();
    let args = [
        "import-gl",
        cap.to_str().unwrap(),
        "--frame",
        &f,
        "--trace-out",
        trace.to_str().unwrap(),
        "--check-mesa",
        mesa.to_str().unwrap(),
        "-q",
    ];
    let out = ok(&wasp(&args));
    assert!(out.contains("coverage agreement: "), "{out}");
    let text = std::fs::read_to_string(mesa.join("agreement.json")).unwrap();
    (mesa, serde_json::from_str(&text).unwrap())
}

fn rgba(p: &Path) -> Vec<u8> {
    image::open(p).unwrap().to_rgba8().into_raw()
}

fn mesa_view(dir: &Path, j: &serde_json::Value) -> View {
    let png = |name: &str, key: &str| {
        let call = j[key]["swap_call"].as_u64().unwrap();
        dir.join(format!("mesa-{name}/{call:010}.png"))
    };
    let count = rgba(&png("count", "count_replay"));
    let id = rgba(&png("id", "id_replay"));
    View::from_mesa(256, 128, &count, &id).0
}

/// Pixels wasp covers in quads.trace's frames 0, 1 and 2 (the geometry
/// moves from frame to frame; wasp's side does not depend on Mesa).
const WASP_COVERED: [u64; 3] = [15_412, 14_952, 14_586];

#[test]
fn quads_frames_agree_with_mesa_and_a_wrong_frame_does_not() {
    if missing_tools() {
        return;
    }
    let mut views = Vec::new();
    for frame in 0..3u64 {
        let (dir, j) = check(frame);
        let a = &j["agreement"];
        let f = |path: &[&str]| {
            path.iter()
                .fold(a, |v, k| &v[*k])
                .as_f64()
                .unwrap_or_else(|| panic!("frame {frame}: {path:?} in {a}"))
        };
        // Measured with Mesa 22.3.6 (llvmpipe): 100% on every measure; the
        // bounds leave room for edge pixels of another Mesa's rasterizer.
        assert!(
            f(&["coverage", "agreement_percent"]) >= 99.9,
            "frame {frame}: {a}"
        );
        assert!(
            f(&["depth_complexity", "exact_percent"]) >= 99.5,
            "frame {frame}: {a}"
        );
        assert!(
            f(&["depth_complexity", "mean_abs_difference"]) <= 0.01,
            "frame {frame}: {a}"
        );
        assert!(
            f(&["texture", "agreement_percent"]) >= 99.5,
            "frame {frame}: {a}"
        );
        let wasp_covered = f(&["coverage", "both"]) + f(&["coverage", "wasp_only"]);
        assert_eq!(
            wasp_covered as u64, WASP_COVERED[frame as usize],
            "frame {frame}"
        );
        assert_eq!(j["mesa_count_channel_mismatch"], 0);
        // The alpha test of the checkerboard quad discards 3200 fragments
        // wasp shades (80x80 pixels, half of them transparent).
        assert_eq!(j["wasp_fragments_alpha_discarded"], 3200, "frame {frame}");
        for png in [
            "coverage.png",
            "depth.png",
            "texture.png",
            "mesa-ids.png",
            "wasp-ids.png",
        ] {
            assert!(dir.join(png).is_file(), "frame {frame}: {png}");
        }
        views.push(mesa_view(&dir, &j));
    }
    // Mesa's frame 0 against Mesa's frame 2 (the quads moved by 16
    // pixels): the measures see it.
    let wrong = compare(&views[0], &views[2]);
    assert!(wrong.coverage.agreement_percent < 99.0, "{}", wrong.text());
    assert!(
        wrong.depth_complexity.exact_percent < 95.0,
        "{}",
        wrong.text()
    );
}

#[test]
fn without_the_tools_it_names_the_packages_and_writes_nothing() {
    let dir = common::scratch("checkmesa", "notools");
    let empty = dir.join("empty-path");
    std::fs::create_dir_all(&empty).unwrap();
    let cap = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/gl/quads.trace");
    let trace = dir.join("out.trace");
    let out = Command::new(env!("CARGO_BIN_EXE_wasp"))
        .env("PATH", &empty)
        .args(["import-gl", cap.to_str().unwrap(), "--trace-out"])
        .arg(&trace)
        .arg("--check-mesa")
        .arg(dir.join("mesa"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("glretrace, xvfb-run, xauth")
            && err.contains("sudo apt-get install apitrace xvfb xauth"),
        "{err}"
    );
    assert!(!trace.exists() && !dir.join("mesa").exists());
}
