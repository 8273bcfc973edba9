//! The colours of the timeline, from [`crate::palette`]: one per core (the
//! palette's other colours, in order), one per cache level, and those of
//! tile starts and ends.

use crate::palette;
use plotters::style::RGBColor;

pub(super) use palette::{LEVELS as LEVEL_COLOURS, TILE_END, TILE_START};

/// The colour of core `c`.
pub(super) fn core_colour(c: usize) -> RGBColor {
    palette::other(c)
}
