//! The colours of the timeline: one per core (the palette of wasp's
//! pictures), one per cache level, and the dark grey of shared-tile marks.

use crate::picture::palette_colour;
use plotters::style::RGBColor;

/// Colours of the cache levels L0, L1, L2.
pub(super) const LEVEL_COLOURS: [RGBColor; 3] = [
    RGBColor(106, 61, 154),
    RGBColor(0, 139, 139),
    RGBColor(217, 95, 2),
];

/// Colour of the shared-tile marks.
pub(super) const MARK_COLOUR: RGBColor = RGBColor(40, 40, 40);

/// The colour of core `c`.
pub(super) fn core_colour(c: usize) -> RGBColor {
    palette_colour(c)
}
