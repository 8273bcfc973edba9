//! Reads the committed capture of tests/gl/quads.c (tests/gl/quads.trace)
//! and checks it against what `apitrace dump` prints for the same file;
//! then checks that no cut or corruption of it makes the reader panic.

use proptest::prelude::*;
use std::path::PathBuf;
use wasp_gltrace::{count_frames, frames, Api, Call, Capture, CaptureError, Compression, Value};

fn quads_path() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../tests/gl/quads.trace")
}

fn quads_bytes() -> Vec<u8> {
    std::fs::read(quads_path()).expect("tests/gl/quads.trace (made by tests/gl/capture.sh)")
}

fn all_calls(capture: Capture) -> Vec<Call> {
    capture
        .map(|r| r.expect("the committed capture reads"))
        .collect()
}

// Facts from `apitrace dump tests/gl/quads.trace` (apitrace 11.1) and
// `apitrace info tests/gl/quads.trace`:
//   `apitrace info`: "ContainerVersion": 6, "FramesCount": 3,
//                    "ActualDataSize": 111304
//   the last line: "231 glXDestroyContext(dpy = 0x5590b6441bd0, ctx = 0x5590b6460f40)"
//   (so 232 calls, numbered 0 to 231; `grep -c '^[0-9]'` of the dump: 232)
const CALLS: usize = 232;
const FRAMES: u64 = 3;
const DECOMPRESSED_BYTES: u64 = 111_304;
//   "89 glXSwapBuffers(...)", "159 glXSwapBuffers(...)", "229 glXSwapBuffers(...)"
const SWAPS: [u64; 3] = [89, 159, 229];
//   "0 glXChooseVisual(dpy = 0x5590b6441bd0, screen = 0, attribList = {GLX_RGBA,
//    GLX_DOUBLEBUFFER, GLX_DEPTH_SIZE, 24, 0}) = &{visual = 0x5590b644f640,
//    visualid = 975, ...}"
const CHOOSE_VISUAL: u64 = 0;
//   "12 glTexImage2D(target = GL_TEXTURE_2D, level = 0, internalformat = GL_RGBA,
//    width = 8, height = 8, border = 0, format = GL_RGBA, type = GL_UNSIGNED_BYTE,
//    pixels = blob(256))"
//   "13 glTexImage2D(... level = 1, ... width = 4, height = 4, ... pixels = blob(64))"
const TEX_IMAGE: [(u64, i64, i64, usize); 2] = [(12, 0, 8, 256), (13, 1, 4, 64)];
//   `apitrace dump --blobs --calls=12`: blob_call12.bin opens (xxd)
//   "0000 80ff 2000 80ff 4000 80ff 6000 80ff"
const TEX_IMAGE_12_HEAD: [u8; 16] = [
    0, 0, 0x80, 0xff, 0x20, 0, 0x80, 0xff, 0x40, 0, 0x80, 0xff, 0x60, 0, 0x80, 0xff,
];
//   "46 glDrawElements(mode = GL_TRIANGLES, count = 6, type = GL_UNSIGNED_SHORT,
//    indices = blob(12))" and `apitrace dump --blobs --calls=46,51`:
//   blob_call46.bin "0000 0100 0200 0000 0200 0300",
//   blob_call51.bin "0400 0500 0600 0400 0600 0700"
const DRAW_ELEMENTS: [(u64, [u16; 6]); 2] = [(46, [0, 1, 2, 0, 2, 3]), (51, [4, 5, 6, 4, 6, 7])];
const GL_TRIANGLES: i64 = 0x0004;
const GL_UNSIGNED_SHORT: i64 = 0x1403;
//   "21 glClearColor(red = 0.1, green = 0.2, blue = 0.3, alpha = 1)"
//   "28 glFrustum(left = -1, right = 1, bottom = -0.5, top = 0.5, zNear = 1, zFar = 10)"
//   "60 glOrtho(left = 0, right = 256, bottom = 0, top = 128, zNear = -1, zFar = 1)"
//   "75 glColorPointer(size = 4, type = GL_UNSIGNED_BYTE, stride = 0, pointer = blob(16)) // fake"
//   "83 glAlphaFunc(func = GL_GREATER, ref = 0.5)"
//   "24 glClear(mask = GL_DEPTH_BUFFER_BIT | GL_COLOR_BUFFER_BIT)"
const NAMED: [(u64, &str); 8] = [
    (5, "glGenTextures"),
    (21, "glClearColor"),
    (24, "glClear"),
    (28, "glFrustum"),
    (43, "glScalef"),
    (60, "glOrtho"),
    (75, "glColorPointer"),
    (83, "glAlphaFunc"),
];

fn by_no(calls: &[Call], no: u64) -> &Call {
    let c = &calls[no as usize];
    assert_eq!(
        c.no, no,
        "calls come in number order in this single-threaded capture"
    );
    c
}

#[test]
fn the_header_counts_and_numbers_match_apitrace_dump() {
    let mut capture = Capture::open(quads_path()).unwrap();
    assert_eq!((capture.version, capture.semantic_version), (6, 6));
    assert_eq!(
        (capture.api, capture.compression),
        (Api::Gl, Compression::Snappy)
    );
    capture.require_gl().unwrap();
    assert!(capture
        .property("process.name")
        .is_some_and(|n| n.ends_with("/quads")));
    let calls: Vec<Call> = capture.by_ref().map(Result::unwrap).collect();
    assert_eq!(capture.offset(), DECOMPRESSED_BYTES);
    assert!(capture.incomplete_calls().is_empty());
    assert_eq!(calls.len(), CALLS);
    for (i, c) in calls.iter().enumerate() {
        assert_eq!(c.no, i as u64);
    }
    for (no, name) in NAMED {
        assert_eq!(&*by_no(&calls, no).name, name, "call {no}");
    }
    let swaps: Vec<u64> = calls
        .iter()
        .filter(|c| &*c.name == "glXSwapBuffers")
        .map(|c| c.no)
        .collect();
    assert_eq!(swaps, SWAPS);
    assert_eq!(
        count_frames(Capture::open(quads_path()).unwrap()).unwrap(),
        FRAMES
    );
    let f: Vec<_> = frames(Capture::open(quads_path()).unwrap())
        .map(Result::unwrap)
        .collect();
    let ends: Vec<(u64, u64, bool)> = f
        .iter()
        .map(|f| (f.index, f.calls.last().unwrap().no, f.complete))
        .collect();
    assert_eq!(
        ends,
        [
            (0, 89, true),
            (1, 159, true),
            (2, 229, true),
            (3, 231, false)
        ]
    );
}

#[test]
fn argument_values_match_apitrace_dump() {
    let calls = all_calls(Capture::open(quads_path()).unwrap());
    for (no, level, size, bytes) in TEX_IMAGE {
        let c = by_no(&calls, no);
        assert_eq!(&*c.name, "glTexImage2D");
        assert_eq!(c.arg_names[3], "width");
        assert_eq!(
            (c.arg(1).as_i64(), c.arg(3).as_i64(), c.arg(4).as_i64()),
            (Some(level), Some(size), Some(size))
        );
        assert_eq!(
            c.arg(8).as_bytes().map(<[u8]>::len),
            Some(bytes),
            "call {no} pixels"
        );
    }
    assert_eq!(
        &by_no(&calls, 12).arg(8).as_bytes().unwrap()[..16],
        TEX_IMAGE_12_HEAD
    );
    for (no, indices) in DRAW_ELEMENTS {
        let c = by_no(&calls, no);
        assert_eq!(&*c.name, "glDrawElements");
        assert_eq!(
            c.args[..3],
            [
                Value::Enum(GL_TRIANGLES),
                Value::UInt(6),
                Value::Enum(GL_UNSIGNED_SHORT)
            ]
        );
        let blob = c.arg(3).as_bytes().unwrap();
        let got: Vec<u16> = blob
            .chunks(2)
            .map(|p| u16::from_le_bytes([p[0], p[1]]))
            .collect();
        assert_eq!(got, indices, "call {no} indices");
    }
    let clear = by_no(&calls, 21);
    let rgba: Vec<f64> = clear.args.iter().map(|v| v.as_f64().unwrap()).collect();
    assert_eq!(rgba, [0.1f32 as f64, 0.2f32 as f64, 0.3f32 as f64, 1.0]);
    assert!(matches!(clear.arg(0), Value::Float(_)));
    let frustum: Vec<f64> = by_no(&calls, 28)
        .args
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(frustum, [-1.0, 1.0, -0.5, 0.5, 1.0, 10.0]);
    assert!(matches!(by_no(&calls, 28).arg(0), Value::Double(_)));
    let ortho: Vec<f64> = by_no(&calls, 60)
        .args
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(ortho, [0.0, 256.0, 0.0, 128.0, -1.0, 1.0]);
    assert_eq!(
        by_no(&calls, 75).arg(3).as_bytes().map(<[u8]>::len),
        Some(16)
    );
    assert_eq!(by_no(&calls, 83).arg(1).as_f64(), Some(0.5));
    // glClear's mask: GL_DEPTH_BUFFER_BIT | GL_COLOR_BUFFER_BIT.
    assert_eq!(by_no(&calls, 24).arg(0), &Value::Bitmask(0x0100 | 0x4000));
    // glGenTextures' output array, recorded at the call's leave: {1, 2}.
    let textures = by_no(&calls, 5).arg(1).as_array().unwrap();
    assert_eq!(
        textures.iter().map(Value::as_i64).collect::<Vec<_>>(),
        [Some(1), Some(2)]
    );
    // glXChooseVisual: attribList {GLX_RGBA, GLX_DOUBLEBUFFER, GLX_DEPTH_SIZE, 24, 0}
    // and a returned struct with visualid = 975.
    let choose = by_no(&calls, CHOOSE_VISUAL);
    assert_eq!(choose.arg(2).as_array().map(<[Value]>::len), Some(5));
    let ret = format!("{:?}", choose.ret);
    assert!(ret.contains("(\"visualid\", UInt(975))"), "{ret}");
}

/// The committed capture's decompressed stream.
fn stream() -> &'static [u8] {
    static STREAM: std::sync::OnceLock<Vec<u8>> = std::sync::OnceLock::new();
    STREAM.get_or_init(|| decompressed(&quads_bytes()))
}

fn decompressed(file: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    let mut at = 2;
    while at < file.len() {
        let len = u32::from_le_bytes(file[at..at + 4].try_into().unwrap()) as usize;
        out.extend(
            snap::raw::Decoder::new()
                .decompress_vec(&file[at + 4..at + 4 + len])
                .unwrap(),
        );
        at += 4 + len;
    }
    out
}

/// A capture file of `stream` cut in two Snappy chunks at `split`.
fn container(stream: &[u8], split: usize) -> Vec<u8> {
    let mut f = b"at".to_vec();
    for part in [&stream[..split], &stream[split..]] {
        if part.is_empty() {
            continue;
        }
        let c = snap::raw::Encoder::new().compress_vec(part).unwrap();
        f.extend_from_slice(&(c.len() as u32).to_le_bytes());
        f.extend_from_slice(&c);
    }
    f
}

fn read_all(name: &str, bytes: Vec<u8>) -> (Vec<Call>, Option<CaptureError>, Vec<u64>) {
    let mut capture = match Capture::from_bytes(name, bytes) {
        Ok(c) => c,
        Err(e) => return (Vec::new(), Some(e), Vec::new()),
    };
    let mut calls = Vec::new();
    for r in capture.by_ref() {
        match r {
            Ok(c) => calls.push(c),
            Err(e) => return (calls, Some(e), capture.incomplete_calls().to_vec()),
        }
    }
    let incomplete = capture.incomplete_calls().to_vec();
    (calls, None, incomplete)
}

#[test]
fn every_cut_of_the_file_is_an_error_naming_the_file() {
    let file = quads_bytes();
    for cut in 0..file.len() {
        let (_, err, _) = read_all("cut.trace", file[..cut].to_vec());
        let e = err.unwrap_or_else(|| panic!("a cut at byte {cut} read without error"));
        assert!(e.to_string().starts_with("cut.trace"), "{e}");
        assert!(
            e.message.contains("truncated capture")
                || e.message.contains("not an apitrace capture"),
            "cut {cut}: {e}"
        );
    }
}

#[test]
fn cuts_of_the_stream_end_cleanly_only_between_events() {
    let full = all_calls(Capture::open(quads_path()).unwrap());
    let stream = stream();
    assert_eq!(stream.len() as u64, DECOMPRESSED_BYTES);
    // Every cut in the header and the first calls (their signatures), then
    // every 401st byte (each cut is decoded from the start: about 10 ms in
    // a debug build for the whole stream).
    let cuts = (0..1500).chain((1500..stream.len()).step_by(401));
    for cut in cuts {
        let (calls, err, incomplete) = read_all("cut.trace", container(&stream[..cut], cut / 3));
        // What was read agrees with the whole capture; calls still open at
        // a clean end are the incomplete ones.
        for c in &calls {
            let whole = &full[c.no as usize];
            assert!(
                c == whole || incomplete.contains(&c.no),
                "cut {cut}: call {}",
                c.no
            );
        }
        match err {
            Some(e) => {
                assert!(e.message.contains("truncated capture"), "cut {cut}: {e}");
                assert_eq!(e.offset, Some(cut as u64), "cut {cut}: {e}");
            }
            // A clean end: every call entered before the cut comes out,
            // numbered 0 to n-1 with none missing.
            None => {
                let mut nos: Vec<u64> = calls.iter().map(|c| c.no).collect();
                nos.sort_unstable();
                assert!(
                    nos.iter().copied().eq(0..nos.len() as u64),
                    "cut {cut}: {nos:?}"
                );
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Arbitrary bytes, bare or in a valid Snappy container, give calls or
    /// an error, never a panic.
    #[test]
    fn arbitrary_bytes_never_panic(body in proptest::collection::vec(any::<u8>(), 0..512), wrap in any::<bool>()) {
        let bytes = if wrap { container(&body, body.len() / 2) } else { body };
        let (_, err, _) = read_all("any.trace", bytes);
        if let Some(e) = err {
            prop_assert!(e.to_string().starts_with("any.trace"));
        }
    }

}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The real stream with a few bytes overwritten gives calls or an
    /// error, never a panic.
    #[test]
    fn corrupted_streams_never_panic(edits in proptest::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 1..8)) {
        let mut stream = stream().to_vec();
        let len = stream.len();
        for (i, b) in edits {
            stream[i.index(len)] = b;
        }
        let (_, err, _) = read_all("bad.trace", container(&stream, len / 2));
        if let Some(e) = err {
            prop_assert!(e.offset.is_some() && e.to_string().starts_with("bad.trace"));
        }
    }
}
