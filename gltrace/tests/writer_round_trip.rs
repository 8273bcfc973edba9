//! Writes every call of the committed capture tests/gl/quads.trace back
//! with [`CaptureWriter`] and reads the result: the same header
//! properties and the same calls, value for value.

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
