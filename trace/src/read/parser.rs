//! The line-by-line parser: the header lines, then each directive, fed to
//! a [`TraceBuilder`] that enforces the format's rules.

use super::lex::{
    check_line, check_magic, dec_u32, hex as hex_u64, instr_token, lines, tokens, Tok,
};
use crate::{
    MapLevel, Problem, TextureMap, Trace, TraceBuilder, TraceHeader, FORMAT_VERSION,
    FORMAT_VERSION_1, FORMAT_VERSION_3, FORMAT_VERSION_FRAMES, FRAME_MARKER, MAX_QUAD_INSTRS,
};

/// Checks line 1 (the magic line) and returns a parser for the rest of
/// `text`, which starts at line 2.
pub(super) fn header(text: &str) -> Result<(Parser<'_>, &str), Problem> {
    let Some(first) = lines(text).next() else {
        return Err(Problem::EmptyInput);
    };
    check_line(first)?;
    let version = check_magic(first)?;
    let rest = text.find('\n').map_or("", |i| &text[i + 1..]);
    Ok((Parser::new(None, version), rest))
}

pub(super) struct Parser<'a> {
    /// The fields of the current line (kept to reuse its allocation).
    fields: Vec<&'a str>,
    /// The instructions of the current quad line, checked before any is
    /// given to the builder, and the block numbers of its texture
    /// instructions (kept to reuse their allocations).
    instrs: Vec<Tok>,
    blocks: Vec<u64>,
    notes: Vec<String>,
    workload: Option<String>,
    /// The `texture-format` line's name, if read.
    texture_format: Option<String>,
    /// The map of a `texture-lines decoded` trace, once that line is read.
    texture_map: Option<TextureMap>,
    /// Present once the `frame` line has been read.
    pub(super) builder: Option<TraceBuilder>,
    /// A version-1 file: quads in strictly increasing scanline order.
    pub(super) scanline_order: bool,
    /// The file's format version.
    pub(super) version: u32,
    /// The last line other than a comment or blank line was a `z` line
    /// (two `z` lines are never adjacent, whatever lies between them).
    after_z: bool,
}

const FRAME_USAGE: &str = "frame W H tile T";
const TILE_USAGE: &str = "tile TX TY";

impl<'a> Parser<'a> {
    /// A parser after line 1: before the header when `builder` is `None`,
    /// else in the body of a trace that `builder` is building.
    pub(super) fn new(builder: Option<TraceBuilder>, version: u32) -> Self {
        Parser {
            fields: Vec::new(),
            instrs: Vec::new(),
            blocks: Vec::new(),
            notes: Vec::new(),
            workload: None,
            texture_format: None,
            texture_map: None,
            builder,
            scanline_order: version == FORMAT_VERSION_1,
            version,
            after_z: false,
        }
    }

    /// Every line of `text`, numbered from `first`. Returns the number of
    /// the last line (`first - 1` if none), or the first problem and its
    /// line's number.
    pub(super) fn lines(&mut self, text: &'a str, first: usize) -> Result<usize, (usize, Problem)> {
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
            "z" => self.rejected_line(fields, after_z),
            FRAME_MARKER => self.frame_marker_line(fields),
            "workload" => self.workload_line(trimmed),
            "texture-format" => self.texture_format_line(fields),
            "texture-lines" => self.texture_lines_line(fields),
            "texture-level" => self.texture_level_line(fields),
            "frame" => self.frame_line(fields),
            "tile" => self.tile_line(fields),
            "q" => self.q_line(fields),
            "end" => self.end_line(fields),
            other => Err(self.unknown_directive(other)),
        }
    }

    /// `z N`: `N` rejected quads (`after_z`: the line before was one too).
    fn rejected_line(&mut self, fields: &[&str], after_z: bool) -> Result<(), Problem> {
        if self.version < FORMAT_VERSION_3 {
            return Err(Problem::RejectedInOldVersion(self.version));
        }
        let b = self.body("z")?;
        field_count(fields, 2, "z", "z N")?;
        if after_z {
            return Err(Problem::AdjacentRejected);
        }
        let n = dec_u32(
            fields[1],
            "rejected quads",
            u64::from(crate::MAX_REJECTED_RUN),
        )?;
        b.rejected(n)
    }

    /// The line between two frames.
    fn frame_marker_line(&mut self, fields: &[&str]) -> Result<(), Problem> {
        if self.version < FORMAT_VERSION_FRAMES {
            return Err(Problem::FrameMarkerInOldVersion(self.version));
        }
        let b = self.body(FRAME_MARKER)?;
        field_count(fields, 1, FRAME_MARKER, FRAME_MARKER)?;
        b.next_frame()
    }

    /// `tile TX TY`: a tile begins.
    fn tile_line(&mut self, fields: &[&str]) -> Result<(), Problem> {
        let b = self.body("tile")?;
        field_count(fields, 3, "tile", TILE_USAGE)?;
        let tx = dec_u32(fields[1], "tile x", u64::from(u32::MAX))?;
        let ty = dec_u32(fields[2], "tile y", u64::from(u32::MAX))?;
        b.begin_tile(tx, ty)
    }

    /// `q X Y ...`: a quad and its program, parsed into the reused buffers.
    fn q_line(&mut self, fields: &[&str]) -> Result<(), Problem> {
        let version = self.version;
        let mut instrs = std::mem::take(&mut self.instrs);
        let mut blocks = std::mem::take(&mut self.blocks);
        let r = self
            .body("q")
            .and_then(|b| quad_line(b, fields, version, &mut instrs, &mut blocks));
        self.instrs = instrs;
        self.blocks = blocks;
        r
    }

    /// `end`: the open tile ends.
    fn end_line(&mut self, fields: &[&str]) -> Result<(), Problem> {
        let b = self.body("end")?;
        field_count(fields, 1, "end", "end")?;
        b.end_tile()
    }

    /// The error for directive `other`, naming what may come here.
    fn unknown_directive(&self, other: &str) -> Problem {
        Problem::UnknownDirective {
            found: other.to_string(),
            expected: match &self.builder {
                None if self.workload.is_none() => "`workload NAME`",
                None => "`frame W H tile T`",
                Some(b) if b.open_tile().is_some() => "`q X Y ...`, `z N` or `end`",
                Some(_) if self.version >= FORMAT_VERSION_FRAMES => "`tile TX TY` or `next-frame`",
                Some(_) => "`tile TX TY`",
            },
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

    /// `texture-format NAME`: after `workload`, before `frame`, at most once.
    fn texture_format_line(&mut self, fields: &[&str]) -> Result<(), Problem> {
        if self.texture_format.is_some() || self.builder.is_some() {
            return Err(Problem::MisplacedHeader("texture-format"));
        }
        if self.workload.is_none() {
            return Err(Problem::MissingHeader {
                missing: "workload NAME",
                found: "texture-format".to_string(),
            });
        }
        field_count(fields, 2, "texture-format", "texture-format NAME")?;
        crate::header::check_format_name(fields[1])?;
        self.texture_format = Some(fields[1].to_string());
        Ok(())
    }

    /// `texture-lines decoded`: after `workload`, before `frame`, at most
    /// once.
    fn texture_lines_line(&mut self, fields: &[&str]) -> Result<(), Problem> {
        let word = fields.get(1..).unwrap_or_default().join(" ");
        if word != "decoded"
            || self.texture_map.is_some()
            || self.builder.is_some()
            || self.workload.is_none()
        {
            return Err(Problem::BadTextureLines(word));
        }
        self.texture_map = Some(TextureMap::new());
        Ok(())
    }

    /// `texture-level R0 RW RH S0 SW SH RX RY`: after `texture-lines
    /// decoded`, before `frame`.
    fn texture_level_line(&mut self, fields: &[&str]) -> Result<(), Problem> {
        let bad = |why: &str| Problem::BadTextureLevel(why.to_string());
        let Some(map) = self.texture_map.as_mut().filter(|_| self.builder.is_none()) else {
            return Err(bad("not after `texture-lines decoded` and before `frame`"));
        };
        field_count(
            fields,
            9,
            "texture-level",
            "texture-level R0 RW RH S0 SW SH RX RY",
        )?;
        let grid = u64::from(crate::MAX_GRID);
        let per = u64::from(crate::MAX_LINES_PER_LINE);
        let level = MapLevel {
            first: hex_u64(fields[1])?,
            grid: (
                dec_u32(fields[2], "RGBA8 grid width", grid)?,
                dec_u32(fields[3], "RGBA8 grid height", grid)?,
            ),
            stored_first: hex_u64(fields[4])?,
            stored_grid: (
                dec_u32(fields[5], "stored grid width", grid)?,
                dec_u32(fields[6], "stored grid height", grid)?,
            ),
            per_line: (
                dec_u32(fields[7], "RGBA8 lines per stored line along x", per)?,
                dec_u32(fields[8], "RGBA8 lines per stored line along y", per)?,
            ),
        };
        map.push(level)
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
        let w = dec_u32(fields[1], "frame width", u64::from(crate::MAX_FRAME_DIM))?;
        let h = dec_u32(fields[2], "frame height", u64::from(crate::MAX_FRAME_DIM))?;
        let t = dec_u32(fields[4], "tile size", u64::from(crate::MAX_TILE_SIZE))?;
        let mut header = TraceHeader::new(workload, w, h, t);
        header.notes = self.notes.clone();
        header.texture_format = self.texture_format.clone();
        header.texture_map = self.texture_map.clone();
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

    pub(super) fn finish(self) -> Result<Trace, Problem> {
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
/// Whether a `directive` line has its `n` fields, else the error that
/// shows its `usage`.
fn field_count(
    fields: &[&str],
    n: usize,
    directive: &'static str,
    usage: &'static str,
) -> Result<(), Problem> {
    if fields.len() == n {
        return Ok(());
    }
    Err(Problem::WrongFieldCount {
        directive,
        found: fields.len(),
        usage,
    })
}
