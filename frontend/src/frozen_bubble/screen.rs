//! The game's one-player screen: its layout (the constants of the game's
//! `Games::FrozenBubble::Stuff`), where a bubble of a level sits, and the
//! view of the screen at a frame's aspect.

/// The game's screen (pixels).
pub const SCREEN: (f32, f32) = (640.0, 480.0);
/// Bubble size (pixels).
pub const BUBBLE_SIZE: f32 = 32.0;
/// Distance between bubble rows: 7/8 of a bubble.
pub const ROW_SIZE: f32 = BUBBLE_SIZE * 7.0 / 8.0;
/// Left edge of the one-player playfield.
pub const LEFT_LIMIT: f32 = 190.0;
/// Right edge of the one-player playfield.
pub const RIGHT_LIMIT: f32 = 446.0;
/// Top edge of the one-player playfield.
pub const TOP_LIMIT: f32 = 44.0;
/// y of the bubble to launch.
pub const INITIAL_BUBBLE_Y: f32 = 390.0;
/// Top-left of the launcher's 100x100 box.
pub const CANON: (f32, f32) = (268.0, 356.0);
/// Top-left of the penguin.
pub const PENGUIN: (f32, f32) = (LEFT_LIMIT + 214.0, 420.0);
/// Top-left of the next bubble.
pub const NEXT_BUBBLE: (f32, f32) = (LEFT_LIMIT + 112.0, 440.0);
/// Offset of the next bubble's frame from the next bubble.
pub const ON_TOP_NEXT_REL: (f32, f32) = (-3.0, -3.0);
/// Horizontal centre of the compressor.
pub const COMPRESSOR_X: f32 = 318.0;
/// Top-left of the first progress dot.
pub const PROGRESS: (f32, f32) = (447.0, 28.0);
/// Shots between new rows in one-player games; the game shows this + 1 dots.
pub const TIME_APPEARS_NEW_ROOT: usize = 8;
/// Rows of the playfield.
pub const ROWS: usize = 12;
/// Bubble colours.
pub const COLOURS: u8 = 8;

/// Top-left of the bubble at column `col`, row `row` (row parity as at the
/// start of a level).
pub fn bubble_position(col: u8, row: u8) -> (f32, f32) {
    (
        LEFT_LIMIT + col as f32 * BUBBLE_SIZE + (row % 2) as f32 * BUBBLE_SIZE / 2.0,
        TOP_LIMIT + row as f32 * ROW_SIZE,
    )
}

/// The ortho view of the 640x480 screen at a frame aspect (width/height),
/// keeping the screen's aspect: (left, top, width, height).
pub fn screen_view(aspect: f32) -> (f32, f32, f32, f32) {
    let (sw, sh) = SCREEN;
    if aspect >= sw / sh {
        let w = sh * aspect;
        ((sw - w) / 2.0, 0.0, w, sh)
    } else {
        let h = sw / aspect;
        (0.0, (sh - h) / 2.0, sw, h)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn views_keep_the_aspect() {
        let (l, t, w, h) = screen_view(1960.0 / 768.0);
        assert!((h - 480.0).abs() < 1e-3 && (w / h - 1960.0 / 768.0).abs() < 1e-4);
        assert!((l + w / 2.0 - 320.0).abs() < 1e-3 && t == 0.0);
        assert_eq!(screen_view(4.0 / 3.0), (0.0, 0.0, 640.0, 480.0));
        let (_, t, w, h) = screen_view(0.5);
        assert!((w - 640.0).abs() < 1e-3 && (t + h / 2.0 - 240.0).abs() < 1e-3);
    }
}
