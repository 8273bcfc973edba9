//! The reader of `wasp-trace 4`, `3`, `2` and `1` text (see the module
//! documentation).

use super::{
    Problem, Trace, TraceBuilder, TraceError, TraceHeader, FORMAT_VERSION, FORMAT_VERSION_1,
    FORMAT_VERSION_2, FORMAT_VERSION_3, MAGIC, MAX_ALU_RUN, MAX_QUAD_INSTRS, MAX_TEX_BLOCKS,
};

/// Every version the reader accepts, newest first.
const VERSIONS: [u32; 4] = [
    FORMAT_VERSION,
    FORMAT_VERSION_3,
    FORMAT_VERSION_2,
    FORMAT_VERSION_1,
];
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

/// The lines of `text`: they end at '\n' (the last one may not), and a
/// '\r' before the end of a line is part of the line ending.
fn lines(text: &str) -> impl Iterator<Item = &str> {
    text.split_inclusive('\n').map(|l| {
        let l = l.strip_suffix('\n').unwrap_or(l);
        l.strip_suffix('\r').unwrap_or(l)
    })
}

/// Checks line 1 (the magic line) and returns a parser for the rest of
/// `text`, which starts at line 2.
fn header(text: &str) -> Result<(Parser<'_>, &str), Problem> {
    let Some(first) = lines(text).next() else {
        return Err(Problem::EmptyInput);
    };
    check_line(first)?;
    let version = check_magic(first)?;
    let rest = text.find('\n').map_or("", |i| &text[i + 1..]);
    Ok((Parser::new(None, version), rest))
}

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
fn parse_in_pieces(text: &str, pieces: usize) -> Option<Trace> {
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

fn check_line(line: &str) -> Result<(), Problem> {
    // `char::is_control` is U+0000-U+001F and U+007F-U+009F. The ASCII ones
    // are single bytes; only a line with other characters needs the
    // character-wise look for the rest.
    let ascii_control = line.bytes().fold(false, |bad, b| {
        bad | ((b < 0x20) & (b != b'\t')) | (b == 0x7f)
    });
    if ascii_control || (!line.is_ascii() && line.chars().any(|c| c.is_control() && c != '\t')) {
        return Err(Problem::ControlCharacter);
    }
    Ok(())
}

/// The version line 1 names: one of [`VERSIONS`].
fn check_magic(line: &str) -> Result<u32, Problem> {
    for v in VERSIONS {
        if line == format!("{MAGIC} {v}") {
            return Ok(v);
        }
    }
    let fields: Vec<&str> = tokens(line).collect();
    if fields.len() == 2
        && fields[0] == MAGIC
        && !VERSIONS.iter().any(|v| fields[1] == v.to_string())
    {
        return Err(Problem::UnsupportedVersion(fields[1].to_string()));
    }
    Err(Problem::BadMagic(line.to_string()))
}

/// The blank-separated fields of a line. Only spaces and tabs separate:
/// every other ASCII whitespace character is a control character, which
/// [`check_line`] refuses before a line is split.
fn tokens(line: &str) -> impl Iterator<Item = &str> {
    debug_assert!(check_line(line).is_ok());
    line.split_ascii_whitespace()
}

struct Parser<'a> {
    /// The fields of the current line (kept to reuse its allocation).
    fields: Vec<&'a str>,
    /// The instructions of the current quad line, checked before any is
    /// given to the builder, and the block numbers of its texture
    /// instructions (kept to reuse their allocations).
    instrs: Vec<Tok>,
    blocks: Vec<u64>,
    notes: Vec<String>,
    workload: Option<String>,
    /// Present once the `frame` line has been read.
    builder: Option<TraceBuilder>,
    /// A version-1 file: quads in strictly increasing scanline order.
    scanline_order: bool,
    /// The file's format version.
    version: u32,
    /// The last line other than a comment or blank line was a `z` line
    /// (two `z` lines are never adjacent, whatever lies between them).
    after_z: bool,
}

const FRAME_USAGE: &str = "frame W H tile T";
const TILE_USAGE: &str = "tile TX TY";

impl<'a> Parser<'a> {
    /// A parser after line 1: before the header when `builder` is `None`,
    /// else in the body of a trace that `builder` is building.
    fn new(builder: Option<TraceBuilder>, version: u32) -> Self {
        Parser {
            fields: Vec::new(),
            instrs: Vec::new(),
            blocks: Vec::new(),
            notes: Vec::new(),
            workload: None,
            builder,
            scanline_order: version == FORMAT_VERSION_1,
            version,
            after_z: false,
        }
    }

    /// Every line of `text`, numbered from `first`. Returns the number of
    /// the last line (`first - 1` if none), or the first problem and its
    /// line's number.
    fn lines(&mut self, text: &'a str, first: usize) -> Result<usize, (usize, Problem)> {
        let mut n = first - 1;
        for line in lines(text) {
            n += 1;
            self.line(line).map_err(|p| (n, p))?;
        }
        Ok(n)
    }

    fn line(&mut self, line: &'a str) -> Result<(), Problem> {
        check_line(line)?;
        let trimmed = line.trim_start_matches([' ', '\t']);
        if let Some(comment) = trimmed.strip_prefix('#') {
            // Comments before the `frame` line are header notes.
            if self.builder.is_none() {
                self.notes.push(comment.to_string());
            }
            return Ok(());
        }
        let mut fields = std::mem::take(&mut self.fields);
        fields.clear();
        fields.extend(tokens(line));
        let r = self.directive(trimmed, &fields);
        self.fields = fields;
        r
    }

    /// A line that is not a comment, split into `fields`.
    fn directive(&mut self, trimmed: &str, fields: &[&str]) -> Result<(), Problem> {
        let Some(&directive) = fields.first() else {
            return Ok(()); // blank line
        };
        let after_z = std::mem::replace(&mut self.after_z, directive == "z");
        match directive {
            "z" => {
                if self.version < FORMAT_VERSION_3 {
                    return Err(Problem::RejectedInOldVersion(self.version));
                }
                let b = self.body(directive)?;
                if fields.len() != 2 {
                    return Err(Problem::WrongFieldCount {
                        directive: "z",
                        found: fields.len(),
                        usage: "z N",
                    });
                }
                if after_z {
                    return Err(Problem::AdjacentRejected);
                }
                let n = dec_u32(
                    fields[1],
                    "rejected quads",
                    u64::from(super::MAX_REJECTED_RUN),
                )?;
                b.rejected(n)
            }
            "workload" => self.workload_line(trimmed),
            "frame" => self.frame_line(fields),
            "tile" => {
                let b = self.body(directive)?;
                if fields.len() != 3 {
                    return Err(Problem::WrongFieldCount {
                        directive: "tile",
                        found: fields.len(),
                        usage: TILE_USAGE,
                    });
                }
                let tx = dec_u32(fields[1], "tile x", u64::from(u32::MAX))?;
                let ty = dec_u32(fields[2], "tile y", u64::from(u32::MAX))?;
                b.begin_tile(tx, ty)
            }
            "q" => {
                let version = self.version;
                let mut instrs = std::mem::take(&mut self.instrs);
                let mut blocks = std::mem::take(&mut self.blocks);
                let r = self
                    .body(directive)
                    .and_then(|b| quad_line(b, fields, version, &mut instrs, &mut blocks));
                self.instrs = instrs;
                self.blocks = blocks;
                r
            }
            "end" => {
                let b = self.body(directive)?;
                if fields.len() != 1 {
                    return Err(Problem::WrongFieldCount {
                        directive: "end",
                        found: fields.len(),
                        usage: "end",
                    });
                }
                b.end_tile()
            }
            other => Err(Problem::UnknownDirective {
                found: other.to_string(),
                expected: match &self.builder {
                    None if self.workload.is_none() => "`workload NAME`",
                    None => "`frame W H tile T`",
                    Some(b) if b.open_tile().is_some() => "`q X Y ...`, `z N` or `end`",
                    Some(_) => "`tile TX TY`",
                },
            }),
        }
    }

    fn workload_line(&mut self, trimmed: &str) -> Result<(), Problem> {
        if self.workload.is_some() || self.builder.is_some() {
            return Err(Problem::MisplacedHeader("workload"));
        }
        // The first token is `workload`, so what follows starts with a blank.
        let rest = trimmed["workload".len()..].trim_matches([' ', '\t']);
        if rest.is_empty() {
            return Err(Problem::EmptyWorkload);
        }
        self.workload = Some(rest.to_string());
        Ok(())
    }

    fn frame_line(&mut self, fields: &[&str]) -> Result<(), Problem> {
        if self.builder.is_some() {
            return Err(Problem::MisplacedHeader("frame"));
        }
        let Some(workload) = self.workload.clone() else {
            return Err(Problem::MissingHeader {
                missing: "workload NAME",
                found: "frame".to_string(),
            });
        };
        if fields.len() != 5 || fields[3] != "tile" {
            return Err(Problem::WrongFieldCount {
                directive: "frame",
                found: fields.len(),
                usage: FRAME_USAGE,
            });
        }
        let w = dec_u32(fields[1], "frame width", u64::from(super::MAX_FRAME_DIM))?;
        let h = dec_u32(fields[2], "frame height", u64::from(super::MAX_FRAME_DIM))?;
        let t = dec_u32(fields[4], "tile size", u64::from(super::MAX_TILE_SIZE))?;
        let mut header = TraceHeader::new(workload, w, h, t);
        header.notes = self.notes.clone();
        let mut builder = TraceBuilder::new(header)?;
        if self.scanline_order {
            builder.require_scanline_order();
        }
        self.builder = Some(builder);
        Ok(())
    }

    /// The builder, once the header is complete.
    fn body(&mut self, directive: &str) -> Result<&mut TraceBuilder, Problem> {
        match &mut self.builder {
            Some(b) => Ok(b),
            None => Err(Problem::MissingHeader {
                missing: if self.workload.is_none() {
                    "workload NAME"
                } else {
                    FRAME_USAGE
                },
                found: directive.to_string(),
            }),
        }
    }

    fn finish(self) -> Result<Trace, Problem> {
        match self.builder {
            Some(b) => b.finish(),
            None => Err(Problem::MissingHeader {
                missing: if self.workload.is_none() {
                    "workload NAME"
                } else {
                    FRAME_USAGE
                },
                found: "end of input".to_string(),
            }),
        }
    }
}

/// A `q X Y INSTR...` line of a format-`version` file. `instrs` and
/// `blocks` are scratch space (their contents on entry are ignored).
fn quad_line(
    b: &mut TraceBuilder,
    fields: &[&str],
    version: u32,
    instrs: &mut Vec<Tok>,
    blocks: &mut Vec<u64>,
) -> Result<(), Problem> {
    if b.open_tile().is_none() {
        return Err(Problem::QuadWithoutTile);
    }
    if fields.len() < 3 {
        return Err(Problem::WrongFieldCount {
            directive: "q",
            found: fields.len(),
            usage: "q X Y INSTR...",
        });
    }
    let x = dec_u32(fields[1], "quad x", u64::from(u32::MAX))?;
    let y = dec_u32(fields[2], "quad y", u64::from(u32::MAX))?;
    if fields.len() == 3 {
        return Err(Problem::EmptyQuad { x, y });
    }
    // Check every instruction token before touching the builder, so an
    // error leaves no half-built quad behind.
    instrs.clear();
    blocks.clear();
    let mut prev_alu: Option<u32> = None;
    let mut count: u64 = 0;
    for tok in &fields[3..] {
        let instr = instr_token(tok, blocks)?;
        count += match instr {
            Tok::Alu(n) => u64::from(n),
            Tok::Tex { .. } => 1,
        };
        if count > u64::from(MAX_QUAD_INSTRS) {
            return Err(Problem::QuadTooLong(count));
        }
        if matches!(instr, Tok::Tex { tri: true, .. }) && version < FORMAT_VERSION {
            return Err(Problem::TrilinearInOldVersion {
                version,
                token: tok.to_string(),
            });
        }
        match instr {
            Tok::Alu(n) => {
                if let Some(first) = prev_alu {
                    return Err(Problem::AdjacentAlu { first, second: n });
                }
                prev_alu = Some(n);
            }
            Tok::Tex { .. } => prev_alu = None,
        }
        instrs.push(instr);
    }
    b.begin_quad(x, y)?;
    let mut start = 0;
    for instr in instrs.iter() {
        match *instr {
            Tok::Alu(n) => b.alu(n)?,
            Tok::Tex { len, tri } => {
                b.tex_filtered(&blocks[start..start + len], tri)?;
                start += len;
            }
        }
    }
    Ok(())
}

/// One checked instruction token.
enum Tok {
    Alu(u32),
    /// A texture instruction: its block numbers are the next `len` of the
    /// line's block scratch; `tri`: written `T` (trilinear).
    Tex {
        len: usize,
        tri: bool,
    },
}

/// Checks one instruction token; a texture instruction's block numbers
/// are appended to `blocks`.
fn instr_token(tok: &str, blocks: &mut Vec<u64>) -> Result<Tok, Problem> {
    if let Some(n) = tok.strip_prefix('a') {
        if n.is_empty() || !n.bytes().all(|c| c.is_ascii_digit()) {
            return Err(Problem::BadInstr(tok.to_string()));
        }
        let n = dec(n, "ALU run", u64::from(MAX_ALU_RUN))?;
        if n == 0 {
            return Err(Problem::ZeroAlu);
        }
        return Ok(Tok::Alu(n as u32));
    }
    let tex = match tok.as_bytes().first() {
        Some(b't') => Some(false),
        Some(b'T') => Some(true),
        _ => None,
    };
    if let Some(tri) = tex {
        // `t` and `T` are one byte each.
        let list = &tok[1..];
        if list.is_empty() {
            return Err(Problem::TexNoBlock);
        }
        let start = blocks.len();
        // The comma-separated items of `list`, by byte position (a comma
        // is one byte in UTF-8).
        let bytes = list.as_bytes();
        let mut from = 0;
        loop {
            let to = bytes[from..]
                .iter()
                .position(|&c| c == b',')
                .map_or(bytes.len(), |k| from + k);
            let item = &list[from..to];
            if item.is_empty() {
                return Err(Problem::EmptyBlockEntry(tok.to_string()));
            }
            if blocks.len() - start == MAX_TEX_BLOCKS {
                return Err(Problem::TooManyBlocks(list.split(',').count()));
            }
            blocks.push(hex(item)?);
            if to == bytes.len() {
                break;
            }
            from = to + 1;
        }
        return Ok(Tok::Tex {
            len: blocks.len() - start,
            tri,
        });
    }
    Err(Problem::BadInstr(tok.to_string()))
}

/// A decimal number of at most `max`.
fn dec(tok: &str, what: &'static str, max: u64) -> Result<u64, Problem> {
    if tok.is_empty() || !tok.bytes().all(|c| c.is_ascii_digit()) {
        return Err(Problem::BadNumber {
            what,
            found: tok.to_string(),
        });
    }
    let too_large = || Problem::NumberTooLarge {
        what,
        found: tok.to_string(),
        max,
    };
    let mut v: u64 = 0;
    for c in tok.bytes() {
        v = v
            .checked_mul(10)
            .and_then(|v| v.checked_add(u64::from(c - b'0')))
            .ok_or_else(too_large)?;
    }
    if v > max {
        return Err(too_large());
    }
    Ok(v)
}

fn dec_u32(tok: &str, what: &'static str, max: u64) -> Result<u32, Problem> {
    let max = max.min(u64::from(u32::MAX));
    dec(tok, what, max).map(|v| v as u32)
}

/// A block number: 1 to 16 hex digits.
fn hex(tok: &str) -> Result<u64, Problem> {
    if tok.is_empty() || tok.len() > 16 || !tok.bytes().all(|c| c.is_ascii_hexdigit()) {
        return Err(Problem::BadHex {
            found: tok.to_string(),
        });
    }
    // At most 16 checked digits: no overflow.
    Ok(tok.bytes().fold(0, |v, c| {
        let d = match c {
            b'0'..=b'9' => c - b'0',
            b'a'..=b'f' => c - b'a' + 10,
            _ => c - b'A' + 10,
        };
        v << 4 | u64::from(d)
    }))
}

#[cfg(test)]
mod tests {
    //! The reader's fast forms against the plain ones they replace.
    use super::*;
    use proptest::prelude::*;

    /// The lines of `text` as the reader numbers them, the plain way: split
    /// at '\n', drop the empty piece after a final '\n', strip one '\r'.
    fn lines_reference(text: &str) -> Vec<&str> {
        let mut v: Vec<&str> = text.split('\n').collect();
        if text.ends_with('\n') {
            v.pop();
        }
        v.into_iter()
            .map(|l| l.strip_suffix('\r').unwrap_or(l))
            .collect()
    }

    fn lines_fast(text: &str) -> Vec<&str> {
        text.split_inclusive('\n')
            .map(|l| {
                let l = l.strip_suffix('\n').unwrap_or(l);
                l.strip_suffix('\r').unwrap_or(l)
            })
            .collect()
    }

    fn check_line_reference(line: &str) -> bool {
        !line.chars().any(|c| c.is_control() && c != '\t')
    }

    /// The old block-list reading: `split(',')` and `from_str_radix`.
    fn blocks_reference(list: &str) -> Result<Vec<u64>, Problem> {
        let tok = format!("t{list}");
        if list.is_empty() {
            return Err(Problem::TexNoBlock);
        }
        let mut blocks = Vec::new();
        for item in list.split(',') {
            if item.is_empty() {
                return Err(Problem::EmptyBlockEntry(tok));
            }
            if blocks.len() == MAX_TEX_BLOCKS {
                return Err(Problem::TooManyBlocks(list.split(',').count()));
            }
            if item.len() > 16 || !item.bytes().all(|c| c.is_ascii_hexdigit()) {
                return Err(Problem::BadHex {
                    found: item.to_string(),
                });
            }
            blocks.push(u64::from_str_radix(item, 16).unwrap());
        }
        Ok(blocks)
    }

    fn blocks_fast(list: &str) -> Result<Vec<u64>, Problem> {
        let mut blocks = vec![7]; // scratch left from an earlier token
        match instr_token(&format!("t{list}"), &mut blocks)? {
            Tok::Tex { len: n, tri: false } => {
                assert_eq!(blocks.len(), n + 1);
                Ok(blocks[1..].to_vec())
            }
            _ => unreachable!("a `t` token"),
        }
    }

    /// `T` lists read as `t` lists, marked trilinear.
    fn blocks_fast_tri(list: &str) -> Result<Vec<u64>, Problem> {
        let mut blocks = Vec::new();
        match instr_token(&format!("T{list}"), &mut blocks)? {
            Tok::Tex { len: n, tri: true } => {
                assert_eq!(blocks.len(), n);
                Ok(blocks)
            }
            _ => unreachable!("a `T` token"),
        }
    }

    #[test]
    fn line_ends_and_control_characters_at_the_edges() {
        // (The reader refuses an empty input before it looks for lines.)
        for text in [
            "a", "a\n", "a\n\n", "\n", "a\r", "a\r\n", "a\r\r\n", "\r\n\r", "a\nb",
        ] {
            assert_eq!(lines_fast(text), lines_reference(text), "{text:?}");
        }
        for (line, ok) in [
            ("q 1 2\ta3", true),
            ("x\u{7f}", false),
            ("x\u{80}", false),
            ("x\u{9f}", false),
            ("x\u{a0}", true),
            ("\u{0}", false),
            ("é\r", false),
            ("é", true),
            ("é\tq", true),
        ] {
            assert_eq!(check_line(line).is_ok(), ok, "{line:?}");
            assert_eq!(check_line_reference(line), ok, "{line:?}");
        }
        assert_eq!(
            blocks_fast("0,aB,ffffffffffffffff"),
            Ok(vec![0, 0xab, u64::MAX])
        );
        for bad in ["", ",", "1,", ",1", "1,,2", "g", "12345678901234567", "é"] {
            assert_eq!(blocks_fast(bad), blocks_reference(bad), "{bad:?}");
            assert!(blocks_fast(bad).is_err(), "{bad:?}");
        }
        let many = vec!["1"; MAX_TEX_BLOCKS + 2].join(",");
        assert_eq!(
            blocks_fast(&many),
            Err(Problem::TooManyBlocks(MAX_TEX_BLOCKS + 2))
        );
    }

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

    proptest! {
        #[test]
        fn lines_split_as_the_plain_way(text in "[a\r\n é\t\u{85}]{1,24}") {
            prop_assert_eq!(lines_fast(&text), lines_reference(&text));
        }

        #[test]
        fn control_check_as_the_plain_way(line in "\\PC{0,8}|[\u{0}-\u{a0}]{0,8}|[\tá\u{85}a]{0,8}") {
            prop_assert_eq!(check_line(&line).is_ok(), check_line_reference(&line));
        }

        #[test]
        fn fields_split_as_the_plain_way(line in "[a1 \t\u{a0}\u{3000}]{0,16}") {
            let plain: Vec<&str> = line.split([' ', '\t']).filter(|t| !t.is_empty()).collect();
            prop_assert_eq!(tokens(&line).collect::<Vec<_>>(), plain);
        }

        #[test]
        fn block_lists_read_as_the_plain_way(list in "[0-9a-fA-Fg,]{0,40}") {
            prop_assert_eq!(blocks_fast(&list), blocks_reference(&list));
            // A `T` list reads as the `t` list, errors naming the `T` token.
            let tri = blocks_fast_tri(&list);
            match blocks_fast(&list) {
                Err(Problem::EmptyBlockEntry(tok)) => prop_assert_eq!(
                    tri,
                    Err(Problem::EmptyBlockEntry(tok.replacen('t', "T", 1)))
                ),
                plain => prop_assert_eq!(tri, plain),
            }
        }
    }
}
