//! The font of the pictures wasp draws (`wasp run --timeline`, the
//! reproduction's charts).
//!
//! Text is rendered by plotters' `ab_glyph` support from the DejaVu Sans
//! that the `dejavu` crate embeds in the binary, so pictures have their
//! labels on a machine with no fonts installed. (An SVG names the
//! [`FONT`] family; its viewer supplies the glyphs.)

use plotters::style::{register_font, FontDesc, FontFamily, FontStyle};
use std::sync::OnceLock;

/// The font family every text uses (registered by [`register_fonts`]).
pub const FONT: &str = "sans-serif";

/// The font of every text: DejaVu Sans of `size` (plotters' size unit:
/// the glyphs are about `size / 1.24` pixels high), bold or not.
pub fn font(size: u32, bold: bool) -> FontDesc<'static> {
    let style = if bold {
        FontStyle::Bold
    } else {
        FontStyle::Normal
    };
    FontDesc::new(FontFamily::Name(FONT), f64::from(size), style)
}

/// Registers the embedded DejaVu Sans (regular and bold) as the [`FONT`]
/// family, once per process; later calls return the first call's result.
///
/// Errors: the embedded font does not load (the message names the font
/// only; callers say what they were drawing).
pub fn register_fonts() -> Result<(), String> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
    DONE.get_or_init(|| {
        let faces = [
            (FontStyle::Normal, dejavu::sans::regular()),
            (FontStyle::Bold, dejavu::sans::bold()),
        ];
        for (style, bytes) in faces {
            register_font(FONT, style, bytes)
                .map_err(|_| "the embedded DejaVu Sans font does not load")?;
        }
        Ok(())
    })
    .clone()
}
