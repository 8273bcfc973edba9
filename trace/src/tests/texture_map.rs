//! The `texture-lines decoded` header line and its `texture-level` lines:
//! read, written back, checked against the blocks of the texture
//! instructions, and every misuse reported with its line.

use crate::{MapLevel, Problem, TextureMap, Trace, TraceHeader};

/// One 16x16-texel level: 4x4 RGBA8 lines at 0x10, stored as ETC2 RGB in
/// 1x2 lines (16x8 texels each) at 0x900.
const WITH: &str = "wasp-trace 4\n# n\nworkload w\ntexture-format etc2\ntexture-lines decoded\n\
                    texture-level 10 4 4 900 1 2 4 2\nframe 8 8 tile 8\n\
                    tile 0 0\nq 0 0 t10,1f\nend\n";

#[test]
fn the_map_is_read_written_back_and_maps_blocks() {
    let t = Trace::parse(WITH, "x").unwrap();
    let map = t.header().texture_map.as_ref().unwrap();
    assert_eq!(
        map.levels(),
        &[MapLevel {
            first: 0x10,
            grid: (4, 4),
            stored_first: 0x900,
            stored_grid: (1, 2),
            per_line: (4, 2),
        }]
    );
    // Line (0, 0) is in the top stored line, line (3, 3) in the bottom one.
    assert_eq!(map.stored(0x10), Some(0x900));
    assert_eq!(map.stored(0x1f), Some(0x901));
    assert_eq!(t.to_text(), WITH);
    // A trace without the line has no map, and none is written.
    let plain = WITH
        .replace("texture-lines decoded\n", "")
        .replace("texture-level 10 4 4 900 1 2 4 2\n", "");
    let p = Trace::parse(&plain, "x").unwrap();
    assert_eq!(p.header().texture_map, None);
    assert_eq!(p.to_text(), plain);
    // A builder's header carries it; an empty map still says `decoded`.
    let mut h = TraceHeader::new("w", 8, 8, 8);
    h.texture_map = Some(TextureMap::new());
    let t = Trace::builder(h).unwrap().finish().unwrap();
    assert!(t
        .to_text()
        .contains("\nworkload w\ntexture-lines decoded\nframe"));
}

#[test]
fn misuse_of_the_map_is_reported_with_its_line() {
    let level = "texture-level 10 4 4 900 1 2 4 2\n";
    let cases: [(String, usize, &str); 8] = [
        (
            WITH.replace("texture-lines decoded\n", ""),
            5,
            "not after `texture-lines decoded`",
        ),
        (
            WITH.replace("texture-lines decoded", "texture-lines stored"),
            5,
            "`texture-lines stored` (expected `texture-lines decoded`",
        ),
        (
            WITH.replace(
                "texture-lines decoded\n",
                "texture-lines decoded\ntexture-lines decoded\n",
            ),
            6,
            "at most once",
        ),
        (
            WITH.replace(level, "texture-level 10 4 4 900 1 2 4\n"),
            6,
            "texture-level R0 RW RH S0 SW SH RX RY",
        ),
        (
            WITH.replace(level, "texture-level 10 3 4 900 1 2 4 2\n"),
            6,
            "powers of two",
        ),
        (
            WITH.replace(level, &format!("{level}texture-level 12 4 4 a00 1 2 4 2\n")),
            7,
            "inside the previous level",
        ),
        (
            WITH.replace("t10,1f", "t10,20"),
            9,
            "block 20 lies in no `texture-level`",
        ),
        (
            WITH.replace("frame 8 8 tile 8\n", "").replace(
                "tile 0 0\n",
                "frame 8 8 tile 8\ntexture-level 40 4 4 a00 1 2 4 2\ntile 0 0\n",
            ),
            8,
            "before `frame",
        ),
    ];
    crate::testkit::reported_at(&cases);
    assert!(matches!(
        Trace::parse(&WITH.replace("t10,1f", "t10,20"), "x")
            .unwrap_err()
            .problem(),
        Some(Problem::BlockOutsideTextureMap(0x20))
    ));
}
