//! `tests/traces/FORMAT.md` and the crate documentation: the same rules
//! and the same example, which parses.

use crate::Trace;

#[test]
fn the_example_of_format_md_parses_with_a_repeated_position() {
    let md = include_str!("../../../tests/traces/FORMAT.md");
    let start = md.find("```text\n").unwrap() + "```text\n".len();
    let text = &md[start..start + md[start..].find("```").unwrap()];
    let t = Trace::parse(text, "FORMAT.md").unwrap();
    let tile = &t.tiles()[0];
    assert_eq!((tile.quad_count(), tile.position_count()), (3, 2));
    assert_eq!(tile.quads_at(0, 0).count(), 2);
    // 12 rejected quads before the third warp, 3 after the last one, and a
    // tile without warps.
    let before: Vec<u32> = (0..3).map(|i| tile.rejected_before(i)).collect();
    assert_eq!(before, vec![0, 0, 12]);
    assert_eq!((tile.rejected_after_last(), tile.raster_count()), (3, 18));
    let hidden = &t.tiles()[2];
    assert_eq!((hidden.tx(), hidden.ty(), hidden.quad_count()), (0, 1, 0));
    assert_eq!(hidden.rejected_after_last(), 40);
    assert_eq!((t.quad_count(), t.rejected_count()), (4, 55));
    assert_eq!(t.to_text(), text, "the example is in the writer's form");
    // The module documentation repeats the same example.
    let doc = include_str!("../lib.rs");
    for line in text.lines() {
        assert!(doc.contains(&format!("//! {line}\n")), "{line}");
    }
}

/// The words of `text` from the line that starts with `from` to the line
/// that starts with `to`, without the `//!` of documentation comments.
fn words_between(text: &str, from: &str, to: &str) -> Vec<String> {
    let lines: Vec<&str> = text
        .lines()
        .map(|l| l.strip_prefix("//!").unwrap_or(l).trim())
        .collect();
    let a = lines.iter().position(|l| l.starts_with(from)).unwrap();
    let b = a + lines[a..].iter().position(|l| l.starts_with(to)).unwrap();
    lines[a..b]
        .iter()
        .flat_map(|l| l.split_whitespace())
        .map(str::to_string)
        .collect()
}

#[test]
fn format_md_and_the_module_documentation_state_the_same_rules() {
    let md = include_str!("../../../tests/traces/FORMAT.md");
    let doc = include_str!("../lib.rs");
    let rules = |text: &str, end: &str| words_between(text, "A trace is UTF-8 text", end);
    let (a, b) = (rules(md, "## Statistics"), rules(doc, "# In memory"));
    assert!(a.len() > 500, "{}", a.len());
    assert_eq!(a, b, "tests/traces/FORMAT.md and trace/src/lib.rs differ");
    let example = |text: &str| words_between(text, "The first warp, at quad", "## Rules");
    assert_eq!(example(md), example(doc));
    for phrase in [
        "An older trace records no rejected quad, so its rasterizer cost counts surviving quads only.",
        "`z N`",
    ] {
        let words: Vec<&str> = phrase.split_whitespace().collect();
        assert!(a.windows(words.len()).any(|w| w == words.as_slice()), "{phrase}");
    }
}
