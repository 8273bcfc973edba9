//! How wasp's pictures (the timeline of `wasp run --timeline`, the
//! reproduction's charts) are written: a picture lays itself out and draws
//! on any plotters backend; [`save`] renders it to an SVG or a PNG file,
//! chosen by the file's extension ([`is_svg`]); the series colours come
//! from one palette ([`palette_colour`]).

use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// A picture laid out and ready to draw on any backend.
pub(crate) trait Picture {
    /// The picture's size in pixels.
    fn size(&self) -> (u32, u32);
    /// Draws the picture on `root` (of [`Picture::size`]).
    fn render<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String>
    where
        DB::ErrorType: 'static;
}

/// Whether `path` asks for an SVG (`.svg`) or a PNG (`.png`), in any case;
/// `what` (e.g. "a chart") names the picture in the error.
pub(crate) fn is_svg(path: &Path, what: &str) -> Result<bool, String> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("png") => Ok(false),
        Some("svg") => Ok(true),
        _ => Err(format!(
            "{}: cannot draw {what} in this format; the file must end in .png or .svg",
            path.display()
        )),
    }
}

/// Draws `picture` into `path`: an SVG when `svg`, else a PNG. `who`
/// ("drawing ...") begins the drawing errors.
pub(crate) fn save(
    picture: &impl Picture,
    who: &str,
    path: &Path,
    svg: bool,
) -> Result<(), String> {
    let (w, h) = picture.size();
    let failed = |e: DrawingAreaErrorKind<_>| format!("{who}: {e}");
    if svg {
        let mut text = String::new();
        {
            let root = SVGBackend::with_string(&mut text, (w, h)).into_drawing_area();
            picture.render(&root)?;
            root.present().map_err(failed)?;
        }
        std::fs::write(path, text).map_err(|e| format!("writing {}: {e}", path.display()))
    } else {
        let mut pixels = vec![0u8; w as usize * h as usize * 3];
        {
            let root = BitMapBackend::with_buffer(&mut pixels, (w, h)).into_drawing_area();
            picture.render(&root)?;
            root.present().map_err(|e| format!("{who}: {e}"))?;
        }
        let img = image::RgbImage::from_raw(w, h, pixels)
            .ok_or_else(|| format!("{who}: the pixel buffer has the wrong size"))?;
        img.save_with_format(path, image::ImageFormat::Png)
            .map_err(|e| format!("writing {}: {e}", path.display()))
    }
}

/// Distinguishable colours (matplotlib's tab10).
const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// The colour of series (or core) `i`: the palette, repeated darker past
/// its ten colours.
pub(crate) fn palette_colour(i: usize) -> RGBColor {
    let RGBColor(r, g, b) = PALETTE[i % PALETTE.len()];
    if (i / PALETTE.len()).is_multiple_of(2) {
        RGBColor(r, g, b)
    } else {
        let dark = |v: u8| (u16::from(v) * 3 / 5) as u8;
        RGBColor(dark(r), dark(g), dark(b))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_come_from_the_extension_in_any_case() {
        assert_eq!(is_svg(Path::new("a/b.svg"), "x"), Ok(true));
        assert_eq!(is_svg(Path::new("b.PNG"), "x"), Ok(false));
        let e = is_svg(Path::new("b.jpg"), "a thing").unwrap_err();
        assert_eq!(
            e,
            "b.jpg: cannot draw a thing in this format; the file must end in .png or .svg"
        );
    }

    #[test]
    fn the_palette_repeats_darker() {
        assert_eq!(palette_colour(0), RGBColor(31, 119, 180));
        assert_eq!(palette_colour(10), RGBColor(18, 71, 108));
        assert_eq!(palette_colour(20), palette_colour(0));
    }
}
