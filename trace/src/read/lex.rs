//! The text's lines, fields and tokens: the line checks, the magic line
//! and the decoding of numbers, block numbers and instruction tokens.

use crate::{
    Problem, FORMAT_VERSION, FORMAT_VERSION_1, FORMAT_VERSION_2, FORMAT_VERSION_3,
    FORMAT_VERSION_FRAMES, MAGIC, MAX_ALU_RUN, MAX_TEX_BLOCKS,
};

/// Every version the reader accepts, newest first.
const VERSIONS: [u32; 5] = [
    FORMAT_VERSION_FRAMES,
    FORMAT_VERSION,
    FORMAT_VERSION_3,
    FORMAT_VERSION_2,
    FORMAT_VERSION_1,
];

/// The lines of `text`: they end at '\n' (the last one may not), and a
/// '\r' before the end of a line is part of the line ending.
#[inline]
pub(super) fn lines(text: &str) -> impl Iterator<Item = &str> {
    text.split_inclusive('\n').map(|l| {
        let l = l.strip_suffix('\n').unwrap_or(l);
        l.strip_suffix('\r').unwrap_or(l)
    })
}

pub(super) fn check_line(line: &str) -> Result<(), Problem> {
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
pub(super) fn check_magic(line: &str) -> Result<u32, Problem> {
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
#[inline]
pub(super) fn tokens(line: &str) -> impl Iterator<Item = &str> {
    debug_assert!(check_line(line).is_ok());
    line.split_ascii_whitespace()
}

/// One checked instruction token.
pub(super) enum Tok {
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
#[inline]
pub(super) fn instr_token(tok: &str, blocks: &mut Vec<u64>) -> Result<Tok, Problem> {
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

#[inline]
pub(super) fn dec_u32(tok: &str, what: &'static str, max: u64) -> Result<u32, Problem> {
    let max = max.min(u64::from(u32::MAX));
    dec(tok, what, max).map(|v| v as u32)
}

/// A block number: 1 to 16 hex digits.
#[inline]
pub(super) fn hex(tok: &str) -> Result<u64, Problem> {
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

    /// The reader's own [`lines`], collected.
    fn lines_fast(text: &str) -> Vec<&str> {
        lines(text).collect()
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
