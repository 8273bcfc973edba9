//! The text of `wasp run --json`, byte for byte: runs that set every
//! descriptive field of the statistics one way or another (policy, launch
//! rule, dispatch, core map, colour flush, DRAM model, blocked-on rule,
//! issue order, prefetcher, subset) are compared with
//! `tests/golden/text/`, and each reads back as [`RunStats`] that writes
//! the same text again. An intended change is accepted with
//!
//! ```sh
//! WASP_ACCEPT_GOLDEN=1 cargo test --test stats_json_cli
//! ```

use wasp_sim::stats::RunStats;

mod common;
use common::{ok, wasp};

/// Each case: its file name, trace and the options of its run.
const CASES: [(&str, &str, &[&str]); 3] = [
    ("tiny-shipped", "tiny", &[]),
    (
        "tiny-wasp-m-gto-raster",
        "tiny",
        &[
            "--policy",
            "wasp-m:0",
            "--set",
            "core.issue=\"gto\"",
            "--set",
            "prefetch.kind=\"raster\"",
            "--set",
            "scheduler.launch_rule=\"launch\"",
            "--set",
            "scheduler.blocked_on=\"dram\"",
            "--set",
            "dram.model=\"fixed\"",
        ],
    ),
    (
        "overdraw-baseline-per-core",
        "overdraw",
        &[
            "--policy",
            "baseline",
            "--set",
            "raster.dispatch=\"per-core-tile\"",
            "--set",
            "raster.color_flush=\"blocking\"",
            "--set",
            "raster.core_map=\"rowmajor:1\"",
            "--set",
            "prefetch.kind=\"oracle-tile\"",
        ],
    ),
];

fn root() -> &'static str {
    env!("CARGO_MANIFEST_DIR")
}

/// The text of `wasp run --json` of `trace` with `opts`, the tile size set
/// to the trace's own.
fn run(trace: &str, opts: &[&str]) -> String {
    let path = format!("{}/tests/traces/{trace}.trace", root());
    let text = std::fs::read_to_string(&path).unwrap();
    let frame = text.lines().find(|l| l.starts_with("frame ")).unwrap();
    let tile = format!("gpu.tile_size={}", frame.rsplit(' ').next().unwrap());
    let mut args = vec!["run", "-q", "--trace", &path, "--set", &tile];
    args.extend_from_slice(opts);
    args.extend_from_slice(&["--json", "-"]);
    ok(&wasp(&args))
}

#[test]
fn run_json_is_unchanged_and_reads_back() {
    let accept = std::env::var_os("WASP_ACCEPT_GOLDEN").is_some();
    let dir = format!("{}/tests/golden/text", root());
    for (name, trace, opts) in CASES {
        let got = run(trace, opts);
        let path = format!("{dir}/{name}.json");
        if accept {
            std::fs::create_dir_all(&dir).unwrap();
            std::fs::write(&path, &got).unwrap();
        } else {
            let want = std::fs::read_to_string(&path)
                .unwrap_or_else(|e| panic!("{path}: {e} (accept with WASP_ACCEPT_GOLDEN=1)"));
            assert!(got == want, "{name}: the JSON differs from {path}");
        }
        let back: RunStats = serde_json::from_str(&got).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(back.to_json(), got, "{name}: read back and written again");
    }
}
