//! Level sets: the text format (one line per bubble row, blank lines
//! between levels) parsed into the bubbles of each level.

use super::*;

/// What a cell holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Bubble {
    /// Column (0..8 on even rows, 0..7 on odd rows).
    pub col: u8,
    /// Row from the top.
    pub row: u8,
    /// Colour 0..8.
    pub colour: u8,
}

/// One level: its bubbles in file order.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Level {
    /// Bubbles.
    pub bubbles: Vec<Bubble>,
    /// Byte offset of the level's first line in the file.
    pub offset: usize,
}

/// Parse a level set (see the module documentation); `path` names it in
/// errors, which carry the byte offset of the offending cell.
pub fn parse_levels(path: &Path, text: &[u8]) -> Result<Vec<Level>, SceneError> {
    let mut levels = Vec::new();
    let mut current: Option<Level> = None;
    let mut row = 0usize;
    let mut pos = 0usize;
    for line in text.split_inclusive(|&b| b == b'\n') {
        let start = pos;
        pos += line.len();
        let body = line.strip_suffix(b"\n").unwrap_or(line);
        let body = body.strip_suffix(b"\r").unwrap_or(body);
        if body.iter().all(|b| b.is_ascii_whitespace()) {
            if let Some(l) = current.take() {
                levels.push(l);
                row = 0;
            }
            continue;
        }
        let level = current.get_or_insert_with(|| Level {
            bubbles: Vec::new(),
            offset: start,
        });
        if row >= ROWS {
            return Err(SceneError::at(
                path,
                start as u64,
                format!(
                    "level {}: row {} (the playfield has {ROWS} rows)",
                    levels.len() + 1,
                    row + 1
                ),
            ));
        }
        parse_row(path, body, start, row, levels.len() + 1, &mut level.bubbles)?;
        row += 1;
    }
    if let Some(l) = current.take() {
        levels.push(l);
    }
    Ok(levels)
}

/// Parse one row of a level (`body`, the line at byte offset `start`
/// without its end of line): a cell per token, `-` empty or a colour
/// 0..7; the bubbles go to `bubbles`. `number` is the level's (from 1).
fn parse_row(
    path: &Path,
    body: &[u8],
    start: usize,
    row: usize,
    number: usize,
    bubbles: &mut Vec<Bubble>,
) -> Result<(), SceneError> {
    let mut col = 0usize;
    let mut i = 0usize;
    while i < body.len() {
        if body[i].is_ascii_whitespace() {
            i += 1;
            continue;
        }
        let tok_start = i;
        while i < body.len() && !body[i].is_ascii_whitespace() {
            i += 1;
        }
        let tok = &body[tok_start..i];
        let at = (start + tok_start) as u64;
        let cols = 8 - row % 2;
        if !tok.contains(&b'-') {
            let colour = match tok {
                [d @ b'0'..=b'7'] => d - b'0',
                _ => {
                    return Err(SceneError::at(
                        path,
                        at,
                        format!(
                            "level {number}: cell {:?}: expected `-` or a colour 0..7",
                            String::from_utf8_lossy(tok)
                        ),
                    ))
                }
            };
            if col >= cols {
                return Err(SceneError::at(
                    path,
                    at,
                    format!(
                        "level {number}: bubble in column {} of row {} (that row has {cols} columns)",
                        col + 1,
                        row + 1
                    ),
                ));
            }
            bubbles.push(Bubble {
                col: col as u8,
                row: row as u8,
                colour,
            });
        }
        col += 1;
    }
    Ok(())
}

#[cfg(test)]
/// A level set of three levels (tests).
pub(super) const TINY: &str = "\
6   6   4   -   -   -   -   -
  -   7   -   -   -   -   -

-   -   -   -   -   -   -   0


1   2   3   4   5   6   7   0
  1   2   3   4   5   6   7
";

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn parses_levels() {
        let l = parse_levels(Path::new("levels"), TINY.as_bytes()).unwrap();
        assert_eq!(l.len(), 3);
        assert_eq!(
            l[0].bubbles,
            vec![
                Bubble {
                    col: 0,
                    row: 0,
                    colour: 6
                },
                Bubble {
                    col: 1,
                    row: 0,
                    colour: 6
                },
                Bubble {
                    col: 2,
                    row: 0,
                    colour: 4
                },
                Bubble {
                    col: 1,
                    row: 1,
                    colour: 7
                },
            ]
        );
        assert_eq!(
            l[1].bubbles,
            vec![Bubble {
                col: 7,
                row: 0,
                colour: 0
            }]
        );
        assert_eq!(l[2].bubbles.len(), 15);
        assert_eq!(l[2].offset, TINY.find("1   2").unwrap());
        assert_eq!(bubble_position(1, 1), (190.0 + 32.0 + 16.0, 44.0 + 28.0));
    }

    #[test]
    fn level_errors_name_the_cell() {
        let text = b"-  -  9\n";
        let e = parse_levels(Path::new("levels"), text).unwrap_err();
        assert_eq!(e.offset, Some(6));
        assert!(e.message.contains("\"9\""), "{e}");
        // Odd rows have 7 columns.
        let text = b"0 0 0 0 0 0 0 0\n0 0 0 0 0 0 0 0\n";
        let e = parse_levels(Path::new("levels"), text).unwrap_err();
        assert_eq!(e.offset, Some(16 + 14));
        let thirteen = "-\n".repeat(13);
        let e = parse_levels(Path::new("levels"), thirteen.as_bytes()).unwrap_err();
        assert_eq!(e.offset, Some(24));
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]

        #[test]
        fn random_level_text_never_panics(text in "[-0-9 \\n\\r\\tx]{0,300}") {
            match parse_levels(Path::new("levels"), text.as_bytes()) {
                Ok(levels) => {
                    for l in levels {
                        for b in l.bubbles {
                            prop_assert!(b.colour < COLOURS && (b.row as usize) < ROWS);
                            prop_assert!(b.col < 8 - b.row % 2);
                        }
                    }
                }
                Err(e) => prop_assert!(e.offset.unwrap() as usize <= text.len()),
            }
        }

        #[test]
        fn random_level_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..300)) {
            let _ = parse_levels(Path::new("levels"), &bytes);
        }
    }
}
