//! The colours of the timeline, from [`crate::palette`]: one per core (the
//! palette's other colours, in order), one per cache level, and the dark
//! grey of shared-tile marks.

use crate::palette;
use plotters::style::RGBColor;

pub(super) use palette::LEVELS as LEVEL_COLOURS;

/// Colour of the shared-tile marks.
pub(super) const MARK_COLOUR: RGBColor = palette::TILE_START;

/// The colour of core `c`.
pub(super) fn core_colour(c: usize) -> RGBColor {
    palette::other(c)
}
