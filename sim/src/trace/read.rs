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
        let mut lines = text.split('\n').enumerate().map(|(i, l)| {
            let l = l.strip_suffix('\r').unwrap_or(l);
            (i + 1, l)
        });
        // `split` yields one empty piece after a final newline: not a line.
        let ends_with_newline = text.ends_with('\n');
        let line_count = text.split('\n').count() - usize::from(ends_with_newline);
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
            notes: Vec::new(),
            workload: None,
            builder: None,
            scanline_order: version == FORMAT_VERSION_1,
        };
        let mut last_line = 1;
        for (n, line) in lines {
            if n > line_count {
                break;
            }
            last_line = n;
            parser.line(line).map_err(|p| err(n, p))?;
        }
        parser.finish().map_err(|p| err(last_line, p))
    }
}

fn check_line(line: &str) -> Result<(), Problem> {
    if line.chars().any(|c| c.is_control() && c != '\t') {
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

fn tokens(line: &str) -> impl Iterator<Item = &str> {
    line.split([' ', '\t']).filter(|t| !t.is_empty())
}

struct Parser {
    notes: Vec<String>,
    workload: Option<String>,
    /// Present once the `frame` line has been read.
    builder: Option<TraceBuilder>,
    /// A version-1 file: quads in strictly increasing scanline order.
    scanline_order: bool,
}

const FRAME_USAGE: &str = "frame W H tile T";
const TILE_USAGE: &str = "tile TX TY";

impl Parser {
    fn line(&mut self, line: &str) -> Result<(), Problem> {
        check_line(line)?;
        let trimmed = line.trim_start_matches([' ', '\t']);
        if let Some(comment) = trimmed.strip_prefix('#') {
            // Comments before the `frame` line are header notes.
            if self.builder.is_none() {
                self.notes.push(comment.to_string());
            }
            return Ok(());
        }
        let fields: Vec<&str> = tokens(line).collect();
        let Some(&directive) = fields.first() else {
            return Ok(()); // blank line
        };
        match directive {
            "workload" => self.workload_line(trimmed),
            "frame" => self.frame_line(&fields),
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
                let b = self.body(directive)?;
                quad_line(b, &fields)
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

fn quad_line(b: &mut TraceBuilder, fields: &[&str]) -> Result<(), Problem> {
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
    let mut instrs = Vec::with_capacity(fields.len() - 3);
    let mut prev_alu: Option<u32> = None;
    for tok in &fields[3..] {
        let instr = instr_token(tok)?;
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
    for instr in &instrs {
        match instr {
            Tok::Alu(n) => b.alu(*n)?,
            Tok::Tex(blocks) => b.tex(blocks)?,
        }
    }
    Ok(())
}

enum Tok {
    Alu(u32),
    Tex(Vec<u64>),
}

fn instr_token(tok: &str) -> Result<Tok, Problem> {
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
        let mut blocks = Vec::new();
        for item in list.split(',') {
            if item.is_empty() {
                return Err(Problem::EmptyBlockEntry(tok.to_string()));
            }
            if blocks.len() == MAX_TEX_BLOCKS {
                return Err(Problem::TooManyBlocks(list.split(',').count()));
            }
            blocks.push(hex(item)?);
        }
        return Ok(Tok::Tex(blocks));
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
    u64::from_str_radix(tok, 16).map_err(|_| Problem::BadHex {
        found: tok.to_string(),
    })
}
