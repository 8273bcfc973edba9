//! Golden outputs of the shipped machine: `wasp run --json` of the three
//! traces in `tests/traces/` under the scanline baseline, the shipped WaSP
//! (`wasp:0:3`) and the measured-CF variant (`wasp-m:0`), compared by
//! content (parsed JSON) with `tests/golden/current/`. An intended change of
//! the model's results is accepted with
//!
//! ```sh
//! WASP_ACCEPT_GOLDEN=1 cargo test --test golden_cli
//! ```
//!
//! which rewrites the files; the diff then shows what changed.

use serde_json::Value;

mod common;
use common::{ok, wasp};

const TRACES: [&str; 3] = ["tiny", "overdraw", "synthetic-small"];
const POLICIES: [(&str, &str); 3] = [
    ("baseline", "baseline"),
    ("wasp:0:3", "wasp"),
    ("wasp-m:0", "wasp-m"),
];

fn root() -> &'static str {
    env!("CARGO_MANIFEST_DIR")
}

/// `wasp run --json` of `trace` under `policy`, the tile size set to the
/// trace's own.
fn run(trace: &str, policy: &str) -> Value {
    let path = format!("{}/tests/traces/{trace}.trace", root());
    let text = std::fs::read_to_string(&path).unwrap();
    let frame = text.lines().find(|l| l.starts_with("frame ")).unwrap();
    let tile = format!("gpu.tile_size={}", frame.rsplit(' ').next().unwrap());
    let out = ok(&wasp(&[
        "run", "-q", "--trace", &path, "--policy", policy, "--set", &tile, "--json", "-",
    ]));
    serde_json::from_str(&out).unwrap()
}

#[test]
fn runs_match_their_golden_outputs() {
    let accept = std::env::var_os("WASP_ACCEPT_GOLDEN").is_some();
    let dir = format!("{}/tests/golden/current", root());
    let mut differ = Vec::new();
    for trace in TRACES {
        for (policy, file) in POLICIES {
            let got = run(trace, policy);
            let path = format!("{dir}/{trace}-{file}.json");
            if accept {
                std::fs::create_dir_all(&dir).unwrap();
                let text = serde_json::to_string_pretty(&got).unwrap() + "\n";
                std::fs::write(&path, text).unwrap();
                continue;
            }
            let want: Value = serde_json::from_str(
                &std::fs::read_to_string(&path)
                    .unwrap_or_else(|e| panic!("{path}: {e} (accept with WASP_ACCEPT_GOLDEN=1)")),
            )
            .unwrap();
            // A file names its policy and machine: a misplaced one cannot
            // pass for another.
            assert_eq!(want["policy"], policy, "{path}");
            // The machine is named with the run's one override, the tile size.
            let machine = want["machine"].as_str().unwrap_or("");
            assert!(
                machine.starts_with("paper-width4-64warps + gpu.tile_size="),
                "{path}: {machine}"
            );
            if got != want {
                let keys: Vec<&String> = got
                    .as_object()
                    .unwrap()
                    .iter()
                    .filter(|(k, v)| want.get(k.as_str()) != Some(v))
                    .map(|(k, _)| k)
                    .collect();
                differ.push(format!("{trace} {policy}: fields {keys:?}"));
            }
        }
    }
    assert!(
        differ.is_empty(),
        "runs differ from tests/golden/current (an intended change is accepted with WASP_ACCEPT_GOLDEN=1):\n{}",
        differ.join("\n")
    );
}
