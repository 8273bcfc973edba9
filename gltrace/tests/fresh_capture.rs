//! Builds tests/gl/quads.c, records it afresh with apitrace under xvfb
//! (tests/gl/capture.sh), and checks that this reader and `apitrace dump`
//! read the same calls from it, and that they are the calls of the
//! committed capture (tests/gl/quads.trace). Without the tools (gcc,
//! libGL and libX11 headers, xvfb, apitrace) it passes with a note, unless
//! `WASP_REQUIRE_TOOLS=1` (CI).

use std::path::PathBuf;
use std::process::Command;
use wasp_gltrace::{Call, Capture};

fn tool(name: &str) -> bool {
    Command::new("sh")
        .args(["-c", &format!("command -v {name}")])
        .output()
        .is_ok_and(|o| o.status.success())
}

fn names(capture: Capture) -> Vec<(u64, String)> {
    capture
        .map(|r| r.unwrap())
        .map(|c: Call| (c.no, c.name.to_string()))
        .collect()
}

#[test]
fn a_fresh_capture_of_quads_reads_as_apitrace_dump_reads_it() {
    let missing: Vec<&str> = ["cc", "xvfb-run", "xauth", "apitrace"]
        .into_iter()
        .filter(|t| !tool(t))
        .collect();
    if !missing.is_empty() {
        assert_ne!(
            std::env::var("WASP_REQUIRE_TOOLS").as_deref(),
            Ok("1"),
            "required tools are missing: {missing:?}"
        );
        eprintln!("skipped: {missing:?} not installed");
        return;
    }
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..");
    let dir = std::env::temp_dir().join(format!("wasp-gltrace-fresh-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("quads.trace");
    let run = Command::new("bash")
        .arg(root.join("tests/gl/capture.sh"))
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "capture.sh failed: {}",
        String::from_utf8_lossy(&run.stderr)
    );

    let ours = names(Capture::open(&out).unwrap());
    let dump = Command::new("apitrace")
        .args(["dump", "--verbose", "--multiline=no", "--color=never"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(dump.status.success());
    // `apitrace dump` prints each call as "NUMBER NAME(ARGS...)".
    let theirs: Vec<(u64, String)> = String::from_utf8_lossy(&dump.stdout)
        .lines()
        .filter_map(|l| {
            let (no, rest) = l.split_once(' ')?;
            Some((no.parse().ok()?, rest.split_once('(')?.0.to_string()))
        })
        .collect();
    assert_eq!(ours, theirs);
    let committed = names(Capture::open(root.join("tests/gl/quads.trace")).unwrap());
    assert_eq!(
        ours, committed,
        "tests/gl/quads.trace is out of date: rerun tests/gl/capture.sh"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
