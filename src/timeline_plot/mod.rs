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
//! ([`crate::charts`]), the colours [`crate::palette`]'s, the font
//! [`crate::fonts`]' embedded DejaVu Sans.
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

mod downsample;
mod layout;
mod marks;
mod panel;

use crate::charts::ensure;
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

/// The checks that keep the drawing from drawing nonsense.
fn check(t: &Timeline) -> Result<(), String> {
    let (from, to, cores) = (t.from, t.to, t.cores);
    let why = "(did the run end before the window?): nothing to draw";
    let none = || format!("the timeline of cycles {from}..={to} has no samples {why}");
    ensure(!t.samples.is_empty(), none)?;
    for (i, s) in t.samples.iter().enumerate() {
        let (c, r, l) = (s.cycle, s.resident.len(), s.priority_launches.len());
        let counts = format_args!("{r} resident counts and {l} launch counts for {cores} cores");
        ensure(r == cores && l == cores, || {
            format!("timeline sample of cycle {c}: {counts}")
        })?;
        let last = t.samples[i.max(1) - 1].cycle;
        let order = format_args!("follows cycle {last}: samples must be in cycle order");
        let after = || format!("timeline sample of cycle {c} {order}");
        ensure(i == 0 || c > last, after)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::charts::tests::{error, out, pixels, refused, texts, Case};
    use crate::palette::{other, TILE_END, TILE_START};
    use wasp_sim::timeline::{TileMark, TimelineSample};

    /// A tile mark.
    fn mark(cycle: u64, tile: u32, core: Option<u32>, start: bool) -> TileMark {
        TileMark {
            cycle,
            tile,
            core,
            start,
        }
    }

    /// A sample of cycle `cycle` on `cores` cores at `level` of a tile's
    /// fill (0 to 1) and in its first half or not (priority launches).
    fn sample(cycle: u64, cores: usize, level: f64, early: bool) -> TimelineSample {
        let wobble = |c: u64| ((cycle / 9 + c * 5) % 6) as f64;
        let warps = |c: u64| ((48.0 - 4.0 * c as f64 - wobble(c)) * level).max(0.0) as u32;
        let launch = |c: u64| u32::from(early && (cycle + c).is_multiple_of(3 + c));
        let l0 = (12.0 * level) as u32 + (cycle / 11 % 3) as u32;
        let l1 = (30.0 * level) as u32 + (cycle / 7 % 4) as u32;
        TimelineSample {
            cycle,
            resident: (0..cores as u64).map(warps).collect(),
            outstanding: [l0, l1, (20.0 * level * level) as u32],
            priority_launches: (0..cores as u64).map(launch).collect(),
        }
    }

    /// Four cores, two shared tiles of `len` cycles each starting at
    /// `from`: each fills over its first 30% (resident warps ramp up,
    /// misses rise, priority warps launch early), holds and drains over
    /// its last 30%.
    fn synthetic(from: u64, len: u64) -> Timeline {
        let mut t = Timeline::new(from, from + 2 * len - 1, 4, 48, true, "shared-tile");
        for (tile, start) in [(0, from), (1, from + len)] {
            t.marks.push(mark(start, tile, None, true));
            for k in 0..len {
                let phase = k as f64 / len as f64;
                let level = (phase / 0.3).min(1.0).min((1.0 - phase) / 0.3);
                t.samples.push(sample(start + k, 4, level, phase < 0.5));
            }
            t.marks.push(mark(start + len - 1, tile, None, false));
        }
        t
    }

    /// The same shape under per-core-tile dispatch, each core taking a
    /// tile every `every` cycles, staggered by `shift` cycles a core, and
    /// finishing it after `busy` cycles.
    fn per_core(len: u64, (every, shift, busy): (u64, u64, u64)) -> Timeline {
        let mut t = synthetic(0, len);
        (t.dispatch, t.marks) = ("per-core-tile".into(), Vec::new());
        for (k, core) in (0..2 * len / every).flat_map(|k| (0..4).map(move |c| (k, c))) {
            let (cycle, tile) = (k * every + u64::from(core) * shift, k as u32 * 4 + core);
            t.marks.push(mark(cycle, tile, Some(core), true));
            t.marks.push(mark(cycle + busy, tile, Some(core), false));
        }
        t.marks.retain(|m| m.cycle < 2 * len);
        t.marks.sort_by_key(|m| m.cycle);
        t
    }

    #[test]
    fn the_picture_has_its_size_colours_and_legends() {
        let path = out("timeline", "t.png");
        draw(&synthetic(1000, 600), &path).expect("draw png");
        assert_eq!(image::image_dimensions(&path).ok(), Some((WIDTH, HEIGHT)));
        let core0 = pixels(&path, other(0));
        assert!(core0 > 100, "{core0} pixels of core 0's colour");
        // Tile 0 ends in the column where tile 1 starts: both marks are
        // drawn, each with its own colour and pointer (about 45 pixels; two
        // ends and two starts in each of three panels).
        let (ends, starts) = (pixels(&path, TILE_END), pixels(&path, TILE_START));
        assert!(ends.min(starts) > 200, "{ends} end, {starts} start pixels");
        let path = out("timeline", "t.svg");
        draw(&synthetic(1000, 600), &path).expect("draw svg");
        let legends =
            "Cores|core 0|core 3|tile start|tile end|Cache levels|L0|L1|L2|Launching core";
        let axes =
            "tile 0|tile 1|48 warp slots|Resident warps per core|warps|misses|cycle|1000|2200";
        let texts = texts(&path, &format!("{legends}|{axes}|launches / cycle"));
        let starting = |p: &str| texts.iter().filter(|t| t.0.starts_with(p)).count();
        let captions = starting("Outstanding misses") + starting("Priority-warp launches");
        assert_eq!(captions, 2);
        let title = "wasp timeline: shared-tile dispatch, cycles 1000..=2199";
        assert_eq!(starting(title), 1, "{texts:?}");
    }

    #[test]
    fn l0_is_left_out_without_l0() {
        let (path, mut t) = (out("timeline-nol0", "t.svg"), synthetic(0, 300));
        t.has_l0 = false;
        draw(&t, &path).expect("draw svg");
        assert!(!texts(&path, "L1|L2").iter().any(|t| t.0 == "L0"));
    }

    #[test]
    fn long_windows_are_downsampled_small_and_ticked() {
        // 200,000 cycles, each core taking a tile every 1,000 cycles: 800
        // tiles' marks are too dense for lines.
        let many = per_core(100_000, (1000, 97, 900));
        let (svg, png) = (out("timeline-long", "t.svg"), out("timeline-long", "t.png"));
        draw(&many, &svg).and(draw(&many, &png)).expect("drawn");
        let size = std::fs::metadata(&svg).expect("svg").len();
        assert!(size < 3_000_000, "SVG of {size} bytes");
        let want = "min..max in column|tile start (top ticks)|tile end (bottom ticks)";
        let texts = texts(&svg, want);
        let has = |part: &str| texts.iter().any(|t| t.0.contains(part));
        assert!(has("per-core-tile dispatch") && has("cycles per pixel column"));
    }

    #[test]
    fn per_core_tiles_and_tiny_timelines_draw() {
        let path = out("timeline-percore", "t.png");
        draw(&per_core(800, (800, 160, 720)), &path).expect("draw png");
        assert_eq!(image::image_dimensions(&path).ok(), Some((WIDTH, HEIGHT)));
        // One cycle, one core, a tile starting and ending in it; a mark
        // outside the window is left out, not drawn off the plot.
        let mut t = Timeline::new(7, 7, 1, 0, false, "shared-tile");
        t.samples.push(sample(7, 1, 0.0, false));
        t.marks = vec![mark(7, 0, None, true), mark(7, 0, None, false)];
        t.marks.push(mark(u64::MAX, 1, None, false));
        draw(&t, &out("timeline-tiny", "one.png")).expect("one cycle");
        draw(&t, &out("timeline-tiny", "one.svg")).expect("one cycle");
        // No cores at all.
        let mut t = Timeline::new(0, 3, 0, 16, true, "shared-tile");
        t.samples = (0..4).map(|c| sample(c, 0, 0.5, false)).collect();
        draw(&t, &out("timeline-tiny", "none.png")).expect("no cores");
    }

    #[test]
    fn bad_files_and_timelines_are_errors() {
        for name in ["timeline.jpg", "timeline", "timeline.png.txt"] {
            let e = error("timeline-ext", name, &|p| draw(&synthetic(0, 100), p));
            let named = e.contains(name) && e.contains(".png") && e.contains(".svg");
            assert!(named, "{e}");
        }
        let cases: &[Case<Timeline>] = &[
            (
                |t| t.samples.clear(),
                "no samples (did the run end before the window?): nothing to draw",
            ),
            (
                |t| t.samples[7].resident.truncate(3),
                "cycle 7: 3 resident counts and 4 launch counts for 4 cores",
            ),
            (
                |t| t.samples.swap(3, 4),
                "sample of cycle 3 follows cycle 4: samples must be in cycle order",
            ),
        ];
        refused(("timeline-bad", &synthetic(0, 50), ""), draw, cases);
    }
}
