//! The reader of `wasp-trace 2` and `wasp-trace 1` text (see the module
//! documentation).

use super::{
    Problem, Trace, TraceBuilder, TraceError, TraceHeader, FORMAT_VERSION, FORMAT_VERSION_1, MAGIC,
    MAX_ALU_RUN, MAX_TEX_BLOCKS,
};
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
    pub fn parse(text: &str, source: &str) -> Result<Trace, TraceError> {
        // Lines end at '\n' (the last one may not), and a '\r' before the
        // end of a line is part of the line ending.
        let mut lines = text.split_inclusive('\n').enumerate().map(|(i, l)| {
            let l = l.strip_suffix('\n').unwrap_or(l);
            let l = l.strip_suffix('\r').unwrap_or(l);
            (i + 1, l)
        });
        let err = |line: usize, problem: Problem| TraceError::Malformed {
            source: source.to_string(),
            line,
            problem,
        };

        // Line 1: the magic line.
        if text.is_empty() {
            return Err(err(1, Problem::EmptyInput));
        }
        let (_, first) = lines.next().expect("split yields at least one piece");
        check_line(first).map_err(|p| err(1, p))?;
        let version = check_magic(first).map_err(|p| err(1, p))?;

        let mut parser = Parser {
            fields: Vec::new(),
            instrs: Vec::new(),
            blocks: Vec::new(),
            notes: Vec::new(),
            workload: None,
            builder: None,
            scanline_order: version == FORMAT_VERSION_1,
        };
        let mut last_line = 1;
        for (n, line) in lines {
            last_line = n;
            parser.line(line).map_err(|p| err(n, p))?;
        }
        parser.finish().map_err(|p| err(last_line, p))
    }
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

/// The version line 1 names: [`FORMAT_VERSION`] or [`FORMAT_VERSION_1`].
fn check_magic(line: &str) -> Result<u32, Problem> {
    for v in [FORMAT_VERSION, FORMAT_VERSION_1] {
        if line == format!("{MAGIC} {v}") {
            return Ok(v);
        }
    }
    let fields: Vec<&str> = tokens(line).collect();
    if fields.len() == 2
        && fields[0] == MAGIC
        && ![FORMAT_VERSION, FORMAT_VERSION_1]
            .iter()
            .any(|v| fields[1] == v.to_string())
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
}

const FRAME_USAGE: &str = "frame W H tile T";
const TILE_USAGE: &str = "tile TX TY";

impl<'a> Parser<'a> {
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
        match directive {
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
                let mut instrs = std::mem::take(&mut self.instrs);
                let mut blocks = std::mem::take(&mut self.blocks);
                let r = self
                    .body(directive)
                    .and_then(|b| quad_line(b, fields, &mut instrs, &mut blocks));
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
                    Some(b) if b.open_tile().is_some() => "`q X Y ...` or `end`",
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

/// A `q X Y INSTR...` line. `instrs` and `blocks` are scratch space (their
/// contents on entry are ignored).
fn quad_line(
    b: &mut TraceBuilder,
    fields: &[&str],
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
    for tok in &fields[3..] {
        let instr = instr_token(tok, blocks)?;
        match instr {
            Tok::Alu(n) => {
                if let Some(first) = prev_alu {
                    return Err(Problem::AdjacentAlu { first, second: n });
                }
                prev_alu = Some(n);
            }
            Tok::Tex(_) => prev_alu = None,
        }
        instrs.push(instr);
    }
    b.begin_quad(x, y)?;
    let mut start = 0;
    for instr in instrs.iter() {
        match *instr {
            Tok::Alu(n) => b.alu(n)?,
            Tok::Tex(len) => {
                b.tex(&blocks[start..start + len])?;
                start += len;
            }
        }
    }
    Ok(())
}

/// One checked instruction token.
enum Tok {
    Alu(u32),
    /// A texture instruction: its block numbers are the next this many of
    /// the line's block scratch.
    Tex(usize),
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
    if let Some(list) = tok.strip_prefix('t') {
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
        return Ok(Tok::Tex(blocks.len() - start));
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
            Tok::Tex(n) => {
                assert_eq!(blocks.len(), n + 1);
                Ok(blocks[1..].to_vec())
            }
            Tok::Alu(_) => unreachable!("a `t` token"),
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
        }
    }
}
