//! Reading a large text in pieces, one thread each: where the text may be
//! cut (at `tile` lines) and how the pieces' traces are put together.

use super::parser::{header, Parser};
use crate::{Trace, TraceBuilder};

/// Index of the first line at or after byte `from` of `text` that starts
/// with the `tile` directive (at the line's first byte), if any.
fn tile_line_from(text: &str, from: usize) -> Option<usize> {
    let bytes = text.as_bytes();
    let mut at = from;
    if at > 0 && bytes.get(at - 1) != Some(&b'\n') {
        at += bytes.get(at..)?.iter().position(|&b| b == b'\n')? + 1;
    }
    loop {
        let line = bytes.get(at..)?;
        if line.starts_with(b"tile ") || line.starts_with(b"tile\t") {
            return Some(at);
        }
        at += line.iter().position(|&b| b == b'\n')? + 1;
    }
}

/// Reads `text` in up to `pieces` pieces: the header up to the first
/// `tile` line on this thread, then pieces that each start at a `tile`
/// line, one thread and one builder each, appended in order. `None` when
/// the text cannot be cut or any part of it fails: the caller then reads
/// it on one thread, which names the first problem.
pub(super) fn parse_in_pieces(text: &str, pieces: usize) -> Option<Trace> {
    let (mut parser, rest) = header(text).ok()?;
    let body = text.len() - rest.len();
    let first = tile_line_from(text, body)?;
    let mut cuts = vec![first];
    for k in 1..pieces {
        let want = first + (text.len() - first) * k / pieces;
        if let Some(c) = tile_line_from(text, want) {
            if c > *cuts.last().expect("not empty") {
                cuts.push(c);
            }
        }
    }
    if cuts.len() < 2 {
        return None;
    }
    cuts.push(text.len());
    // The header lines (comments, `workload`, `frame`) before the first tile.
    parser.lines(&text[body..first], 2).ok()?;
    let mut builder = parser.builder.take()?;
    let head = builder.header().clone();
    let scanline = parser.scanline_order;
    let version = parser.version;
    let parts: Vec<Option<Trace>> = std::thread::scope(|s| {
        let handles: Vec<_> = cuts
            .windows(2)
            .map(|w| {
                let piece = &text[w[0]..w[1]];
                let head = head.clone();
                s.spawn(move || {
                    let mut b = TraceBuilder::new(head).ok()?;
                    if scanline {
                        b.require_scanline_order();
                    }
                    let mut p = Parser::new(Some(b), version);
                    // The line numbers do not matter: a piece that fails is
                    // read again with the whole text.
                    p.lines(piece, 1).ok()?;
                    p.finish().ok()
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().ok().flatten())
            .collect()
    });
    for part in parts {
        builder.append(part?).ok()?;
    }
    builder.finish().ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Instr, TraceHeader};

    #[test]
    fn a_trace_is_read_in_pieces_alike() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../tests/traces/synthetic-small.trace"
        );
        let text = std::fs::read_to_string(path).unwrap();
        let one = Trace::parse_with(&text, "s", 1, usize::MAX).unwrap();
        assert_eq!(one.tiles().len(), 4);
        for pieces in 2..=6 {
            // The pieces path itself succeeds (no fall-back) and agrees.
            let t = parse_in_pieces(&text, pieces).expect("a well-formed trace reads in pieces");
            assert_eq!(t, one, "{pieces} pieces");
            assert_eq!(t.header(), one.header());
        }
        // Cuts fall on `tile` lines only.
        let first = tile_line_from(&text, 0).unwrap();
        assert!(
            text[first..].starts_with("tile 0 0\n"),
            "{}",
            &text[first..first + 12]
        );
        let second = tile_line_from(&text, first + 1).unwrap();
        assert!(second > first && text[second..].starts_with("tile "));
        assert_eq!(tile_line_from(&text, text.len()), None);
        // A piece that fails sends the whole text to the one-thread read,
        // whose error names the line.
        let broken = text.replacen("end\ntile", "tile", 1);
        let line = broken[..broken.find("\ntile 1 ").unwrap() + 1]
            .lines()
            .count()
            + 1;
        assert_eq!(parse_in_pieces(&broken, 3), None);
        let e = Trace::parse_with(&broken, "s", 3, 0).unwrap_err();
        assert_eq!(
            e,
            Trace::parse_with(&broken, "s", 1, usize::MAX).unwrap_err()
        );
        assert!(e.to_string().starts_with(&format!("s:{line}:")), "{e}");
    }

    #[test]
    fn a_trace_with_rejections_reads_alike_in_pieces() {
        // Enough tiles for several pieces, rejections in each.
        let mut b = Trace::builder(TraceHeader::new("w", 64 * 60, 64 * 60, 64)).unwrap();
        for ty in 0..60 {
            for tx in 0..60 {
                b.begin_tile(tx, ty).unwrap();
                b.rejected(1 + tx).unwrap();
                for i in 0..160 {
                    b.quad(
                        i % 32,
                        i / 32,
                        &[Instr::Alu(1 + i), Instr::Tex(&[u64::from(i)])],
                    )
                    .unwrap();
                    if i % 7 == 3 {
                        b.rejected(i).unwrap();
                    }
                }
                b.end_tile().unwrap();
            }
        }
        let t = b.finish().unwrap();
        let text = t.to_text();
        assert!(text.len() > 4 << 20, "large enough for the pieces path");
        assert_eq!(Trace::parse(&text, "big").unwrap(), t);
    }

    #[test]
    fn a_trilinear_error_in_a_piece_is_reported_as_on_one_thread() {
        // A version-3 text long enough to be read in pieces, with one `T`
        // near the end: the pieces fail, the one-thread read names its line.
        let mut text = String::from("wasp-trace 3\nworkload w\nframe 4096 64 tile 64\n");
        for tx in 0..64 {
            text.push_str(&format!("tile {tx} 0\nq 0 0 a1 t{tx:x}\nend\n"));
        }
        let good = Trace::parse_with(&text, "p", 4, 0).unwrap();
        assert_eq!(good.trilinear_count(), 0);
        let bad = text.replacen("q 0 0 a1 t3e\n", "q 0 0 a1 T3e\n", 1);
        let line = bad.lines().position(|l| l.ends_with("T3e")).unwrap() + 1;
        let e = Trace::parse_with(&bad, "p", 4, 0).unwrap_err();
        assert_eq!(e, Trace::parse_with(&bad, "p", 1, usize::MAX).unwrap_err());
        assert_eq!(e.line(), Some(line));
        assert!(e.to_string().contains("`T3e` in a format-3 trace"), "{e}");
        // As version 4 it reads, in pieces or not, the same.
        let v4 = bad.replacen("wasp-trace 3\n", "wasp-trace 4\n", 1);
        let a = Trace::parse_with(&v4, "p", 4, 0).unwrap();
        assert_eq!(a, Trace::parse_with(&v4, "p", 1, usize::MAX).unwrap());
        assert_eq!(a.trilinear_count(), 1);
    }
}
