//! Early-Z-rejected quads (`z` lines, format 3 on): where they sit, how
//! they round-trip, and the errors of bad ones.

use crate::testkit::*;
use crate::Trace;

#[test]
fn rejected_quads_round_trip_and_sit_where_they_were_rasterized() {
    let text = format!(
        "{HEAD3}tile 0 0\nz 5\nq 0 0 a1\nq 1 0 a2\nz 3\nq 2 0 a1\nz 7\nend\ntile 1 0\nz 9\nend\n"
    );
    let t = Trace::parse(&text, "z").unwrap();
    let a = &t.tiles()[0];
    assert_eq!(a.quad_count(), 3);
    assert_eq!(
        (0..3).map(|i| a.rejected_before(i)).collect::<Vec<_>>(),
        vec![5, 0, 3]
    );
    assert_eq!(a.rejected_before(3), 0, "past the last quad");
    assert_eq!(a.rejected_after_last(), 7);
    assert_eq!((a.rejected_count(), a.raster_count()), (15, 18));
    // A tile whose every quad Early-Z rejected: no warp, raster time only.
    let b = &t.tiles()[1];
    assert_eq!((b.quad_count(), b.rejected_after_last()), (0, 9));
    assert_eq!(t.rejected_count(), 24);
    assert_eq!(
        t.to_text(),
        text.replacen("wasp-trace 3\n", "wasp-trace 4\n", 1),
        "the writer writes what it read, as version 4"
    );
    // Statistics of a trace with a warp-less tile stay finite.
    let st = t.stats();
    assert!(st.cf.is_finite() && st.min_estimate1.is_finite());
}

#[test]
fn bad_rejection_records_are_errors_with_their_line() {
    let cases: &[(&str, usize, &str)] = &[
        ("tile 0 0\nz 0\nq 0 0 a1\nend\n", 5, "0 rejected quads"),
        ("tile 0 0\nz\nq 0 0 a1\nend\n", 5, "`z N`"),
        ("tile 0 0\nz 1 2\nq 0 0 a1\nend\n", 5, "`z N`"),
        ("tile 0 0\nz x\nq 0 0 a1\nend\n", 5, "rejected quads"),
        ("tile 0 0\nz 4294967296\nend\n", 5, "rejected quads"),
        ("z 3\ntile 0 0\nq 0 0 a1\nend\n", 4, "outside any tile"),
        (
            "tile 0 0\nz 2\nz 3\nq 0 0 a1\nend\n",
            6,
            "two `z` lines in a row",
        ),
        ("tile 0 0\nq 0 0 a1\nend\nz 3\n", 7, "outside any tile"),
    ];
    for (body, line, want) in cases {
        let text = format!("{HEAD3}{body}");
        let e = Trace::parse(&text, "bad.trace").unwrap_err();
        let msg = e.to_string();
        assert!(
            msg.starts_with(&format!("bad.trace:{line}: ")),
            "{body:?}: {msg}"
        );
        assert!(msg.contains(want), "{body:?}: {msg}");
    }
    // Formats 1 and 2 have no `z` line.
    for v in [1, 2] {
        let text = format!(
            "wasp-trace {v}\nworkload w\nframe 64 64 tile 64\ntile 0 0\nz 2\nq 0 0 a1\nend\n"
        );
        let msg = Trace::parse(&text, "old.trace").unwrap_err().to_string();
        assert!(msg.starts_with("old.trace:5: "), "{msg}");
        assert!(msg.contains(&format!("format-{v} trace")), "{msg}");
    }
    // A version-2 trace without `z` lines still loads, with no rejection.
    let text = "wasp-trace 2\nworkload w\nframe 64 64 tile 64\ntile 0 0\nq 0 0 a1\nend\n";
    let t = Trace::parse(text, "v2").unwrap();
    assert_eq!(t.rejected_count(), 0);
    assert!(t.to_text().starts_with("wasp-trace 4\n"));
}

#[test]
fn more_bad_rejection_records_name_their_line() {
    let cases: &[(&str, usize, &str)] = &[
        // Adjacent even with a comment or blank line between.
        (
            "tile 0 0\nq 0 0 a1\nz 2\n# c\n\nz 3\nend\n",
            9,
            "two `z` lines in a row",
        ),
        ("tile 0 0\nz 2\n  z 1\nend\n", 6, "two `z` lines in a row"),
        ("tile 0 0\nz 4194305\nend\n", 5, "at most 4194304"),
        ("tile 0 0\nz -1\nend\n", 5, "bad rejected quads `-1`"),
        ("tile 0 0\nz 1x\nend\n", 5, "expected a decimal number"),
        ("tile 0 0\nz\tz\nend\n", 5, "bad rejected quads `z`"),
        ("tile 0 0\nend\n", 5, "tile 0 0 is empty"),
        ("tile 0 0\nz 2\ntile 1 0\n", 6, "tile 0 0 is not closed"),
        ("tile 0 0\nz 2\n", 5, "tile 0 0 is not closed"),
        ("tile 0 0\nzz 2\nend\n", 5, "`q X Y ...`, `z N` or `end`"),
    ];
    for (body, line, want) in cases {
        let text = format!("{HEAD3}{body}");
        let msg = Trace::parse(&text, "bad.trace").unwrap_err().to_string();
        assert!(
            msg.starts_with(&format!("bad.trace:{line}: ")),
            "{body:?}: {msg}"
        );
        assert!(msg.contains(want), "{body:?}: {msg}");
        assert!(msg.contains("(expected "), "{body:?}: {msg}");
    }
    // `z` before the header.
    let msg = Trace::parse("wasp-trace 3\nz 1\n", "h.trace")
        .unwrap_err()
        .to_string();
    assert!(msg.starts_with("h.trace:2: `z` before the header"), "{msg}");
    // Not adjacent: a quad or another tile between.
    let ok = format!("{HEAD3}tile 0 0\nz 2\nq 0 0 a1\nz 3\nend\ntile 1 0\nz 1\nend\n");
    let t = Trace::parse(&ok, "ok").unwrap();
    assert_eq!(t.rejected_count(), 6);
}
