//! `wasp run --timeline FILE.png|FILE.svg`: draws a [`Timeline`] so that a
//! reader sees each tile's fill and drain.
//!
//! The picture is [`WIDTH`] x [`HEIGHT`] pixels: a title (dispatch mode and
//! window) over three stacked panels that share the cycle axis:
//!
//! 1. the warps resident in each core (one colour per core; y from 0 to a
//!    little above the warp slots, whose count is a dashed line, leaving
//!    room for the tile labels),
//! 2. the misses outstanding per cache level (L0 only on a machine with L0,
//!    L1, L2),
//! 3. the priority warps launched per cycle, stacked by core in the core
//!    colours of panel 1.
//!
//! Tile boundaries are vertical lines in every panel, each with a pointer
//! at the panel's top: a tile start points right (the tile runs on to the
//! right), a tile end points left. Shared-tile dispatch: a solid dark line
//! where a tile starts (labelled `tile N` in panel 1) and a dashed red one
//! at the end of the cycle its last warp retires, so an end in the column
//! of the next start still shows as its red pointer. Per-core-tile
//! dispatch: the same two styles and pointers, thin and in the colour of
//! the core that takes or finishes the tile (labelled with the tile number
//! in that colour, one row of labels per core). The title strip and the
//! legends (plotters' series labels, right of each panel) are the charts'
//! ([`crate::charts`]), the colours [`crate::palette`]'s.
//!
//! # Long windows
//!
//! When the window has more cycles than the plot has pixel columns, the
//! samples are split into one run of consecutive cycles per pixel column
//! and each column shows, per series, the mean over its cycles as the line
//! and the minimum to maximum as a light band around it; panel 3 shows the
//! mean launches per cycle over the column (so its area still counts the
//! launches). Tile marks falling into the same column are merged: one mark
//! per column, core and kind (a start and an end in one column are both
//! kept). When more than one column in ten still has a mark, lines
//! across the panels would hide the data: starts become short ticks down
//! from each panel's top edge and ends ticks up from its bottom edge (same
//! colours), without tile labels or pointers. The files stay small (an
//! SVG of a 200,000-cycle window with 800 tiles is under a megabyte) and
//! drawing is fast whatever the window.
//!
//! # Fonts
//!
//! Text is rendered by plotters' `ab_glyph` support from the DejaVu Sans
//! that the `dejavu` crate embeds in the binary, so the picture has its
//! labels and legends on a machine with no fonts installed. (An SVG names
//! the `sans-serif` family; its viewer supplies the glyphs.)

mod downsample;
mod layout;
mod marks;
mod panel;

use crate::fonts::register_fonts;
use crate::picture::{is_svg, save};
use std::path::Path;
use wasp_sim::timeline::Timeline;

/// Width of the picture in pixels.
pub const WIDTH: u32 = 1600;
/// Height of the picture in pixels.
pub const HEIGHT: u32 = 1000;

/// Draw `t` into `path`, a PNG or an SVG by the file's extension (`.png`,
/// `.svg`, in any case).
///
/// Errors: another extension, a timeline without samples or with samples
/// that do not match its core count or are out of cycle order, and a file
/// that cannot be written.
pub fn draw(t: &Timeline, path: &Path) -> Result<(), String> {
    let svg = is_svg(path, "a timeline")?;
    check(t)?;
    let who = "drawing the timeline";
    register_fonts().map_err(|e| format!("{who}: {e}"))?;
    save(&layout::TimelineChart(t), who, path, svg)
}

/// The checks that keep [`render`] from drawing nonsense.
fn check(t: &Timeline) -> Result<(), String> {
    if t.samples.is_empty() {
        return Err(format!(
            "the timeline of cycles {}..={} has no samples (did the run end before the window?): nothing to draw",
            t.from, t.to
        ));
    }
    let mut last = None;
    for s in &t.samples {
        if s.resident.len() != t.cores || s.priority_launches.len() != t.cores {
            return Err(format!(
                "timeline sample of cycle {}: {} resident counts and {} launch counts for {} cores",
                s.cycle,
                s.resident.len(),
                s.priority_launches.len(),
                t.cores
            ));
        }
        if last.is_some_and(|c| s.cycle <= c) {
            return Err(format!(
                "timeline sample of cycle {} follows cycle {}: samples must be in cycle order",
                s.cycle,
                last.unwrap_or_default()
            ));
        }
        last = Some(s.cycle);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::palette::{TILE_END, TILE_START};
    use plotters::style::RGBColor;
    use wasp_sim::timeline::{TileMark, TimelineSample};

    /// A unique scratch directory for one test.
    fn scratch(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!(
            "wasp-timeline-plot-{name}-{}-{}",
            std::process::id(),
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map(|d| d.as_nanos())
                .unwrap_or(0)
        ));
        std::fs::create_dir_all(&dir).expect("scratch dir");
        dir
    }

    /// The texts of an SVG's `<text>` elements, trimmed.
    fn svg_texts(svg: &str) -> Vec<String> {
        svg.split("<text")
            .skip(1)
            .filter_map(|part| {
                let body = part.split_once('>')?.1;
                Some(body.split_once("</text>")?.0.trim().to_string())
            })
            .collect()
    }

    /// Four cores, two shared tiles of `len` cycles each starting at
    /// `from`: each fills (resident warps ramp up, misses rise, priority
    /// warps launch early) and drains (warps retire, misses fall).
    fn synthetic(from: u64, len: u64) -> Timeline {
        let cores = 4;
        let max_warps = 48;
        let mut t = Timeline::new(
            from,
            from + 2 * len - 1,
            cores,
            max_warps,
            true,
            "shared-tile",
        );
        for tile in 0..2u64 {
            let start = from + tile * len;
            t.marks.push(TileMark {
                cycle: start,
                tile: tile as u32,
                core: None,
                start: true,
            });
            for k in 0..len {
                let cycle = start + k;
                // Fill over the first 30%, hold, drain over the last 30%.
                let phase = k as f64 / len as f64;
                let level = if phase < 0.3 {
                    phase / 0.3
                } else if phase < 0.7 {
                    1.0
                } else {
                    (1.0 - phase) / 0.3
                };
                let resident = (0..cores)
                    .map(|c| {
                        let wobble = ((cycle / 9 + c as u64 * 5) % 6) as f64;
                        ((f64::from(max_warps) - 4.0 * c as f64 - wobble) * level).max(0.0) as u32
                    })
                    .collect();
                let outstanding = [
                    (12.0 * level) as u32 + (cycle / 11 % 3) as u32,
                    (30.0 * level) as u32 + (cycle / 7 % 4) as u32,
                    (20.0 * level * level) as u32,
                ];
                let priority_launches = (0..cores)
                    .map(|c| {
                        u32::from(phase < 0.5 && (cycle + c as u64).is_multiple_of(3 + c as u64))
                    })
                    .collect();
                t.samples.push(TimelineSample {
                    cycle,
                    resident,
                    outstanding,
                    priority_launches,
                });
            }
            t.marks.push(TileMark {
                cycle: start + len - 1,
                tile: tile as u32,
                core: None,
                start: false,
            });
        }
        t
    }

    /// The same shape under per-core-tile dispatch: each core takes its own
    /// tiles, staggered.
    fn per_core(from: u64, len: u64) -> Timeline {
        let mut t = synthetic(from, len);
        t.dispatch = "per-core-tile".into();
        t.marks.clear();
        for core in 0..t.cores as u32 {
            let shift = u64::from(core) * len / 5;
            for tile in 0..2u64 {
                let start = from + tile * len + shift;
                t.marks.push(TileMark {
                    cycle: start,
                    tile: tile as u32 * 4 + core,
                    core: Some(core),
                    start: true,
                });
                t.marks.push(TileMark {
                    cycle: start + len * 9 / 10,
                    tile: tile as u32 * 4 + core,
                    core: Some(core),
                    start: false,
                });
            }
        }
        let (from, to) = (t.from, t.to);
        t.marks.retain(|m| (from..=to).contains(&m.cycle));
        t.marks.sort_by_key(|m| m.cycle);
        t
    }

    /// 200,000 cycles of per-core-tile dispatch, each core taking a tile
    /// every 1,000 cycles.
    fn dense_per_core() -> Timeline {
        let mut t = per_core(5, 100_000);
        t.marks.clear();
        for k in 0..200u32 {
            for core in 0..4u32 {
                let cycle = 5 + u64::from(k) * 1000 + u64::from(core) * 97;
                t.marks.push(TileMark {
                    cycle,
                    tile: k * 4 + core,
                    core: Some(core),
                    start: true,
                });
                t.marks.push(TileMark {
                    cycle: cycle + 900,
                    tile: k * 4 + core,
                    core: Some(core),
                    start: false,
                });
            }
        }
        let (from, to) = (t.from, t.to);
        t.marks.retain(|m| (from..=to).contains(&m.cycle));
        t.marks.sort_by_key(|m| m.cycle);
        t
    }

    #[test]
    fn png_has_the_picture_size() {
        let dir = scratch("png");
        let path = dir.join("timeline.png");
        let t = synthetic(1000, 600);
        draw(&t, &path).expect("draw png");
        let img = image::open(&path).expect("png decodes").to_rgb8();
        assert_eq!((img.width(), img.height()), (WIDTH, HEIGHT));
        // Not a blank page: some pixels carry the core colours.
        let c = crate::palette::other(0);
        let core0 = img.pixels().filter(|p| p.0 == [c.0, c.1, c.2]).count();
        assert!(core0 > 100, "{core0} pixels of core 0's colour");
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn svg_has_the_legend_texts() {
        let dir = scratch("svg");
        let path = dir.join("timeline.svg");
        draw(&synthetic(1000, 600), &path).expect("draw svg");
        let svg = std::fs::read_to_string(&path).expect("svg");
        let texts = svg_texts(&svg);
        for text in [
            "Cores",
            "core 0",
            "core 3",
            "tile start",
            "tile end",
            "Cache levels",
            "L0",
            "L1",
            "L2",
            "Launching core",
            "tile 0",
            "tile 1",
            "48 warp slots",
            "Resident warps per core",
            "warps",
            "misses",
            "launches / cycle",
            "cycle",
            "1000",
            "2200",
        ] {
            assert!(
                texts.iter().any(|t| t == text),
                "the SVG lacks `{text}`: {texts:?}"
            );
        }
        let title = &texts
            .iter()
            .find(|t| t.starts_with("wasp timeline"))
            .expect("title");
        assert!(title.contains("shared-tile dispatch"), "{title}");
        assert!(title.contains("cycles 1000..=2199"), "{title}");
        assert!(texts.iter().any(|t| t.starts_with("Outstanding misses")));
        assert!(texts
            .iter()
            .any(|t| t.starts_with("Priority-warp launches")));
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn tile_ends_are_drawn_apart_from_the_next_start() {
        // Under shared-tile dispatch tile 0 ends in the column where tile 1
        // starts: both marks are drawn, each with its own colour and
        // pointer, and each has its legend entry.
        let dir = scratch("ends");
        let path = dir.join("timeline.png");
        draw(&synthetic(1000, 600), &path).expect("draw png");
        let img = image::open(&path).expect("png decodes").to_rgb8();
        let count = |c: RGBColor| img.pixels().filter(|p| p.0 == [c.0, c.1, c.2]).count();
        let (ends, starts) = (count(TILE_END), count(TILE_START));
        // A pointer is about 45 pixels; two ends and two starts in each of
        // three panels.
        assert!(
            ends > 200 && starts > 200,
            "{ends} end and {starts} start pixels"
        );
        let path = dir.join("timeline.svg");
        draw(&synthetic(1000, 600), &path).expect("draw svg");
        let texts = svg_texts(&std::fs::read_to_string(&path).expect("svg"));
        assert!(texts.iter().any(|t| t == "tile start") && texts.iter().any(|t| t == "tile end"));
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn l0_is_left_out_without_l0() {
        let dir = scratch("nol0");
        let path = dir.join("timeline.svg");
        let mut t = synthetic(0, 300);
        t.has_l0 = false;
        draw(&t, &path).expect("draw svg");
        let texts = svg_texts(&std::fs::read_to_string(&path).expect("svg"));
        assert!(texts.iter().any(|t| t == "L1") && texts.iter().any(|t| t == "L2"));
        assert!(!texts.iter().any(|t| t == "L0"), "{texts:?}");
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn long_window_is_downsampled_and_small() {
        let dir = scratch("long");
        let svg_path = dir.join("timeline.svg");
        let png_path = dir.join("timeline.png");
        let many = dense_per_core();
        draw(&many, &svg_path).expect("draw svg");
        draw(&many, &png_path).expect("draw png");
        let size = std::fs::metadata(&svg_path).expect("svg").len();
        assert!(size < 3_000_000, "SVG of {size} bytes");
        let texts = svg_texts(&std::fs::read_to_string(&svg_path).expect("svg"));
        assert!(texts.iter().any(|t| t.contains("per-core-tile dispatch")));
        assert!(texts.iter().any(|t| t.contains("cycles per pixel column")));
        assert!(texts.iter().any(|t| t == "min..max in column"));
        // 800 tiles' marks are too dense for lines: ticks.
        assert!(
            texts.iter().any(|t| t == "tile start (top ticks)"),
            "{texts:?}"
        );
        assert!(
            texts.iter().any(|t| t == "tile end (bottom ticks)"),
            "{texts:?}"
        );
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn per_core_tiles_draw() {
        let dir = scratch("percore");
        let path = dir.join("timeline.png");
        draw(&per_core(0, 800), &path).expect("draw png");
        let img = image::open(&path).expect("png decodes");
        assert_eq!((img.width(), img.height()), (WIDTH, HEIGHT));
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn tiny_timelines_draw() {
        let dir = scratch("tiny");
        // One cycle, one core, a tile starting and ending in it.
        let mut t = Timeline::new(7, 7, 1, 0, false, "shared-tile");
        t.samples.push(TimelineSample {
            cycle: 7,
            resident: vec![0],
            outstanding: [0, 0, 0],
            priority_launches: vec![0],
        });
        for start in [true, false] {
            t.marks.push(TileMark {
                cycle: 7,
                tile: 0,
                core: None,
                start,
            });
        }
        // A mark outside the window is left out, not drawn off the plot.
        t.marks.push(TileMark {
            cycle: u64::MAX,
            tile: 1,
            core: None,
            start: false,
        });
        draw(&t, &dir.join("one.png")).expect("one cycle");
        draw(&t, &dir.join("one.svg")).expect("one cycle");
        // No cores at all.
        let mut t = Timeline::new(0, 3, 0, 16, true, "shared-tile");
        for cycle in 0..4 {
            t.samples.push(TimelineSample {
                cycle,
                resident: vec![],
                outstanding: [1, 2, 3],
                priority_launches: vec![],
            });
        }
        draw(&t, &dir.join("none.png")).expect("no cores");
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn wrong_extension_is_an_error() {
        let dir = scratch("ext");
        for name in ["timeline.jpg", "timeline", "timeline.png.txt"] {
            let path = dir.join(name);
            let e = draw(&synthetic(0, 100), &path).expect_err("not a picture format");
            assert!(e.contains(name), "{e}");
            assert!(e.contains(".png") && e.contains(".svg"), "{e}");
            assert!(!path.exists());
        }
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn empty_timeline_is_an_error() {
        let dir = scratch("empty");
        let path = dir.join("timeline.png");
        let t = Timeline::new(500, 900, 4, 64, false, "shared-tile");
        let e = draw(&t, &path).expect_err("no samples");
        assert!(e.contains("no samples"), "{e}");
        assert!(e.contains("500..=900"), "{e}");
        assert!(!path.exists());
        std::fs::remove_dir_all(dir).ok();
    }

    #[test]
    fn inconsistent_samples_are_errors() {
        let dir = scratch("bad");
        let path = dir.join("timeline.svg");
        let mut t = synthetic(0, 50);
        t.samples[7].resident.pop();
        let e = draw(&t, &path).expect_err("3 counts for 4 cores");
        assert!(e.contains("cycle 7"), "{e}");
        let mut t = synthetic(0, 50);
        t.samples.swap(3, 4);
        let e = draw(&t, &path).expect_err("out of order");
        assert!(e.contains("cycle order"), "{e}");
        std::fs::remove_dir_all(dir).ok();
    }
}
