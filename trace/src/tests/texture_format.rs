//! The optional `texture-format NAME` header line: read, written back,
//! absent from older traces, and every misuse reported with its line.

use crate::{Problem, Trace, TraceHeader};

const WITH: &str = "wasp-trace 4\n# n\nworkload w\ntexture-format etc2\nframe 8 8 tile 8\n\
                    tile 0 0\nq 0 0 t10\nend\n";

#[test]
fn the_texture_format_is_read_and_written_back() {
    let t = Trace::parse(WITH, "x").unwrap();
    assert_eq!(t.header().texture_format.as_deref(), Some("etc2"));
    assert_eq!(t.to_text(), WITH);
    // Older traces, and this one without the line, say nothing.
    let old = WITH.replace("texture-format etc2\n", "");
    let t = Trace::parse(&old, "x").unwrap();
    assert_eq!(t.header().texture_format, None);
    assert_eq!(t.to_text(), old, "no line is added");
    let v3 = old.replace("wasp-trace 4", "wasp-trace 3");
    assert_eq!(
        Trace::parse(&v3, "x").unwrap().header().texture_format,
        None
    );
    // A builder's header carries it too.
    let mut h = TraceHeader::new("w", 8, 8, 8);
    h.texture_format = Some("astc-8x8".into());
    let t = Trace::builder(h).unwrap().finish().unwrap();
    assert!(t
        .to_text()
        .contains("\nworkload w\ntexture-format astc-8x8\nframe"));
}

#[test]
fn a_misplaced_or_bad_texture_format_is_reported_with_its_line() {
    let cases: [(String, usize, &str); 6] = [
        (
            WITH.replace(
                "texture-format etc2\nframe 8 8 tile 8\n",
                "frame 8 8 tile 8\ntexture-format etc2\n",
            ),
            5,
            "between `workload NAME` and `frame W H tile T`",
        ),
        (
            WITH.replace(
                "texture-format etc2\n",
                "texture-format etc2\ntexture-format rgba8\n",
            ),
            5,
            "repeated",
        ),
        (
            WITH.replace(
                "workload w\ntexture-format etc2\n",
                "texture-format etc2\nworkload w\n",
            ),
            3,
            "before the header line `workload NAME`",
        ),
        (
            WITH.replace("texture-format etc2", "texture-format"),
            4,
            "texture-format NAME",
        ),
        (
            WITH.replace("texture-format etc2", "texture-format ETC2"),
            4,
            "texture format `ETC2` (expected 1 to 32 lowercase",
        ),
        (
            WITH.replace("texture-format etc2", "texture-format etc2 rgb"),
            4,
            "texture-format NAME",
        ),
    ];
    crate::testkit::reported_at(&cases);
    assert!(matches!(
        Trace::parse(&WITH.replace("etc2", "a b"), "x")
            .unwrap_err()
            .problem(),
        Some(Problem::WrongFieldCount { .. })
    ));
}
