//! Frozen Bubble (2D puzzle, the paper's "Candy Crush" case): the one-player
//! screen at the start of a level of `frozen-bubble-data`.
//!
//! # Data layout
//!
//! The data root passed to [`load`] is the game's data directory inside the
//! unpacked Debian package: `<unpacked frozen-bubble-data>/usr/share/games/frozen-bubble`
//! ([`DATA_SUBDIR`] under the directory `dpkg-deb -x` unpacked the package
//! into; with `wasp scenes fetch`, `$WASP_SCENES/frozen-bubble/` + [`DATA_SUBDIR`]).
//! Files read:
//!
//! - `data/<levelset>`: the level set; `def.map` names it (`levels`, the
//!   game's 100 levels).
//! - `gfx/back_one_player.png` (640x480 background), `gfx/balls/bubble-N.gif`
//!   (N = 1..8, 32x32, GIF89a with a transparent colour; decoded here, see
//!   [`decode_gif`]), `gfx/compressor_main.png`,
//!   `gfx/shooter.png`, `gfx/on_top_next.png`, `gfx/dot_red.png`,
//!   `gfx/dot_green.png`, `gfx/pinguins/anime-shooter_p1_0020.png`.
//!
//! Data licence: GPL-2 (`debian/copyright` of `frozen-bubble-data`).
//!
//! # Level set format
//!
//! Plain text. A level is a block of non-blank lines, one line per bubble
//! row from the top; blank lines separate levels (runs of blank lines
//! count once). A line is whitespace-separated cells, one per column: `-`
//! (any token containing `-`) is empty, a digit `0`..`7` a bubble of that
//! colour (drawn with `bubble-<digit+1>.gif`). Even rows (0, 2, ...) have 8
//! columns, odd rows 7, shifted right by half a bubble (the file indents
//! them by two spaces); the playfield has 12 rows, the shipped levels fill
//! the top 10.
//!
//! # Scene
//!
//! The game draws with SDL blits on a 640x480 screen; the scene is that
//! screen at the start of a one-player level, in the game's blit order
//! (painter's order), positions in screen pixels (y down), one sprite = one
//! textured quad (2 triangles), z = draw order:
//!
//! 1. the background (`Blend::Opaque`);
//! 2. the compressor at the top of the playfield (x centred on 318, bottom
//!    at the playfield top 44, so it starts 7 pixels above the screen);
//! 3. the level's bubbles: column `c`, row `r` at
//!    x = 190 + 32 c + 16 (r odd), y = 44 + 28 r (32-pixel bubbles, rows
//!    7/8 of a bubble apart);
//! 4. the new-row progress dots (9 dots, 7x7, from (447, 28), one red);
//! 5. the next bubble at (302, 440) with its frame `on_top_next` at
//!    (299, 437), the bubble to launch at (302, 390);
//! 6. the launcher (`shooter.png` pointing up, cropped to its opaque
//!    bounding box as the game crops its rotated copies, box at (268, 356));
//! 7. the penguin (first frame of its idle animation) at (404, 420).
//!
//! Everything but the background is `Blend::AlphaBlend`. The layout
//! constants are those of the game's `Games::FrozenBubble::Stuff` (%POS_1P,
//! $BUBBLE_SIZE, $ROW_SIZE); the colours of the bubble to launch and of the
//! next bubble are random in the game: here the level's most and second
//! most frequent colours. Not drawn: text (level number and time, rendered
//! with a system font), the "hurry" warning, animations.
//!
//! Camera selector: `level:N` (1-based, in level-set order). The ortho view
//! keeps the 4:3 aspect of the 640x480 screen: it is the screen, widened
//! (pillarbox) or heightened (letterbox) around its centre to the frame's
//! aspect, so the frame shows the whole screen undistorted. Materials use
//! the `sprite` template with [`Filter::Bilinear`] (a GPU port scales the
//! 640x480 screen to the frame).

use super::def::SceneDef;
use super::teeworlds::program;
use super::{Blend, Camera, Filter, Material, Mesh, Scene, SceneError, Texture};
use std::path::{Path, PathBuf};

mod gif;
mod levels;
mod screen;
mod sprites;

pub use gif::*;
pub use levels::*;
pub use screen::*;
use sprites::*;

/// The Debian package holding the data.
pub const PACKAGE: &str = "frozen-bubble-data";
/// The data root inside the unpacked package.
pub const DATA_SUBDIR: &str = "usr/share/games/frozen-bubble";

/// Parse `level:N` (1-based).
pub fn parse_camera(s: &str) -> Option<usize> {
    s.strip_prefix("level:")
        .and_then(|n| n.parse::<usize>().ok())
        .filter(|&n| n >= 1)
}

/// Path of a level set under the data root.
pub fn levels_path(data_root: &Path, name: &str) -> Result<PathBuf, SceneError> {
    if name.is_empty()
        || !name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-' || c == '.')
        || name.starts_with('.')
    {
        return Err(SceneError::in_file(
            data_root.join("data"),
            format!("level set {name:?}: expected a file name under data/, such as `levels`"),
        ));
    }
    Ok(data_root.join("data").join(name))
}

/// Load a Frozen Bubble scene: `def.map` names the level set under `data/`
/// (`levels`), `def.camera` is `level:N`. See the module documentation.
pub fn load(data_root: &Path, def: &SceneDef) -> Result<Scene, SceneError> {
    let lpath = levels_path(data_root, &def.map)?;
    let text = std::fs::read(&lpath)
        .map_err(|e| SceneError::in_file(&lpath, format!("cannot read: {e}")))?;
    let levels = parse_levels(&lpath, &text)?;
    let n = parse_camera(&def.camera).ok_or_else(|| {
        SceneError::in_file(
            &lpath,
            format!(
                "scene `{}`: camera {:?}: expected `level:N` (N from 1)",
                def.name, def.camera
            ),
        )
    })?;
    let level = levels.get(n - 1).ok_or_else(|| {
        SceneError::in_file(
            &lpath,
            format!(
                "scene `{}`: level {n}: the level set has {} levels",
                def.name,
                levels.len()
            ),
        )
    })?;
    build(data_root, &lpath, level, n, def)
}

#[cfg(test)]
mod tests;
