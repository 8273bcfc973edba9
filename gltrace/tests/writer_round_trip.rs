//! Writes every call of the committed capture tests/gl/quads.trace back
//! with [`CaptureWriter`] and reads the result: the same header
//! properties and the same calls, value for value; and `apitrace dump`
//! reads the written capture as it reads the original.

use std::path::PathBuf;
use wasp_gltrace::{Call, Capture, CaptureWriter};

#[test]
fn every_call_of_quads_trace_reads_back_identically() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../tests/gl/quads.trace");
    let capture = Capture::open(&path).unwrap();
    let (semantic, props) = (capture.semantic_version, capture.properties.clone());
    let calls: Vec<Call> = capture.map(Result::unwrap).collect();
    assert_eq!(calls.len(), 232);
    let mut w = CaptureWriter::new(Vec::new(), semantic, &props).unwrap();
    for (i, c) in calls.iter().enumerate() {
        assert_eq!(w.write_call(c).unwrap(), i as u64);
    }
    let bytes = w.finish().unwrap();
    let back = Capture::from_bytes("written.trace", bytes).unwrap();
    assert_eq!((back.version, back.semantic_version), (6, semantic));
    assert_eq!(back.properties, props);
    assert_eq!(back.api, wasp_gltrace::Api::Gl);
    let again: Vec<Call> = back.map(Result::unwrap).collect();
    assert_eq!(again.len(), calls.len());
    for (a, c) in again.iter().zip(&calls) {
        assert_eq!(a, c, "call {}", c.no);
    }
}

fn tool(name: &str) -> bool {
    std::process::Command::new("sh")
        .args(["-c", &format!("command -v {name}")])
        .output()
        .is_ok_and(|o| o.status.success())
}

/// `apitrace dump`'s "NUMBER NAME" of every call of `path`.
fn dump_names(path: &std::path::Path) -> Vec<(u64, String)> {
    let dump = std::process::Command::new("apitrace")
        .args(["dump", "--verbose", "--multiline=no", "--color=never"])
        .arg(path)
        .output()
        .unwrap();
    assert!(
        dump.status.success(),
        "{}",
        String::from_utf8_lossy(&dump.stderr)
    );
    String::from_utf8_lossy(&dump.stdout)
        .lines()
        .filter_map(|l| {
            let (no, rest) = l.split_once(' ')?;
            Some((no.parse().ok()?, rest.split_once('(')?.0.to_string()))
        })
        .collect()
}

/// apitrace itself reads the written capture: the same calls by number
/// and name as the original. Without apitrace it passes with a note,
/// unless `WASP_REQUIRE_TOOLS=1` (CI).
#[test]
fn apitrace_dump_reads_the_written_capture_as_the_original() {
    if !tool("apitrace") {
        assert_ne!(
            std::env::var("WASP_REQUIRE_TOOLS").as_deref(),
            Ok("1"),
            "apitrace is missing"
        );
        eprintln!("skipped: apitrace not installed");
        return;
    }
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../tests/gl/quads.trace");
    let capture = Capture::open(&path).unwrap();
    let written = std::env::temp_dir().join(format!("wasp-writer-{}.trace", std::process::id()));
    let mut w =
        CaptureWriter::create(&written, capture.semantic_version, &capture.properties).unwrap();
    for c in capture {
        w.write_call(&c.unwrap()).unwrap();
    }
    w.finish().unwrap();
    let ours = dump_names(&written);
    assert_eq!(ours.len(), 232);
    assert_eq!(ours, dump_names(&path));
    std::fs::remove_file(&written).unwrap();
}
