//! The reader of `wasp-trace 4`, `3`, `2` and `1` text (see the module
//! documentation): [`Trace::read`] and the `parse` functions, which read
//! a large text in pieces on several threads.

mod lex;
mod parser;
mod pieces;

use super::{Problem, Trace, TraceError};
use parser::header;
use pieces::parse_in_pieces;
use std::path::Path;

impl Trace {
    /// Reads and parses the trace file at `path`; errors name the path.
    pub fn read(path: impl AsRef<Path>) -> Result<Trace, TraceError> {
        let path = path.as_ref();
        let name = path.display().to_string();
        let bytes = std::fs::read(path).map_err(|e| TraceError::Io {
            path: name.clone(),
            message: e.to_string(),
        })?;
        Trace::parse_bytes(&bytes, &name)
    }

    /// Parses trace bytes; `source` names the input in errors. Never panics.
    pub fn parse_bytes(bytes: &[u8], source: &str) -> Result<Trace, TraceError> {
        match std::str::from_utf8(bytes) {
            Ok(text) => Trace::parse(text, source),
            Err(e) => {
                let line = 1 + bytes[..e.valid_up_to()]
                    .iter()
                    .filter(|&&b| b == b'\n')
                    .count();
                Err(TraceError::Malformed {
                    source: source.to_string(),
                    line,
                    problem: Problem::InvalidUtf8,
                })
            }
        }
    }

    /// Parses trace text; `source` names the input in errors. Never panics.
    ///
    /// A large trace is read in pieces on the machine's threads, each
    /// piece from a `tile` line on; the result is the same. If any piece
    /// fails, the whole text is read again on one thread, so a problem is
    /// reported exactly as a one-thread read finds it first.
    pub fn parse(text: &str, source: &str) -> Result<Trace, TraceError> {
        let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
        Trace::parse_with(text, source, threads.min(MAX_PIECES), PIECES_MIN_BYTES)
    }

    /// [`Trace::parse`] with `pieces` worker threads whatever the text's
    /// size (1: the plain one-thread reader). The result does not depend
    /// on `pieces`; the fuzz suite checks that on mutated traces.
    pub fn parse_pieces(text: &str, source: &str, pieces: usize) -> Result<Trace, TraceError> {
        Trace::parse_with(text, source, pieces.clamp(1, MAX_PIECES), 0)
    }

    /// [`Trace::parse`] in up to `pieces` pieces when the text has at
    /// least `min_bytes`.
    pub(super) fn parse_with(
        text: &str,
        source: &str,
        pieces: usize,
        min_bytes: usize,
    ) -> Result<Trace, TraceError> {
        if pieces >= 2 && text.len() >= min_bytes {
            if let Some(t) = parse_in_pieces(text, pieces) {
                return Ok(t);
            }
        }
        let err = |line: usize, problem: Problem| TraceError::Malformed {
            source: source.to_string(),
            line,
            problem,
        };
        let (mut parser, body) = header(text).map_err(|p| err(1, p))?;
        let last = parser.lines(body, 2).map_err(|(n, p)| err(n, p))?;
        parser.finish().map_err(|p| err(last, p))
    }
}

/// Texts shorter than this are read on one thread.
const PIECES_MIN_BYTES: usize = 4 << 20;

/// Most pieces a text is read in.
const MAX_PIECES: usize = 8;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit::*;

    #[test]
    fn read_reports_missing_file() {
        let e = Trace::read("/nonexistent/dir/x.trace").unwrap_err();
        assert!(matches!(e, TraceError::Io { .. }));
        assert!(e
            .to_string()
            .starts_with("/nonexistent/dir/x.trace: cannot read: "));
    }

    #[test]
    fn invalid_utf8_reports_its_line() {
        let mut bytes = body("tile 0 0\n").into_bytes();
        bytes.extend_from_slice(b"q 0 0 t\xff\n");
        let e = Trace::parse_bytes(&bytes, "b.trace").unwrap_err();
        assert_eq!(e.line(), Some(5));
        assert_eq!(e.problem(), Some(&Problem::InvalidUtf8));
    }
}
