//! How wasp's pictures (the timeline of `wasp run --timeline`, the
//! reproduction's charts) are written: a picture lays itself out and draws
//! on any plotters backend; [`save`] renders it to an SVG or a PNG file,
//! chosen by the file's extension ([`is_svg`]). Their colours come from
//! [`crate::palette`].

use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// A picture laid out and ready to draw on any backend.
pub(crate) trait Picture {
    /// The picture's size in pixels.
    fn size(&self) -> (u32, u32);
    /// Draws the picture on `root` (of [`Picture::size`]).
    fn draw<DB: DrawingBackend>(&self, root: &Area<DB>) -> Drawn<DB>;
}

/// A drawing area in pixels.
pub(crate) type Area<DB> = DrawingArea<DB, Shift>;
/// What drawing returns.
pub(crate) type Drawn<DB, T = ()> =
    Result<T, DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

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
    if svg {
        let mut text = String::new();
        {
            let root = SVGBackend::with_string(&mut text, (w, h)).into_drawing_area();
            let drawn = picture.draw(&root).and_then(|()| root.present());
            drawn.map_err(|e| format!("{who}: {e}"))?;
        }
        crate::output::write_atomic(path, text.as_bytes())
            .map_err(|e| format!("writing {}: {e}", path.display()))
    } else {
        let mut pixels = vec![0u8; w as usize * h as usize * 3];
        {
            let root = BitMapBackend::with_buffer(&mut pixels, (w, h)).into_drawing_area();
            let drawn = picture.draw(&root).and_then(|()| root.present());
            drawn.map_err(|e| format!("{who}: {e}"))?;
        }
        let img = image::RgbImage::from_raw(w, h, pixels)
            .ok_or_else(|| format!("{who}: the pixel buffer has the wrong size"))?;
        let mut png = std::io::Cursor::new(Vec::new());
        img.write_to(&mut png, image::ImageFormat::Png)
            .map_err(|e| format!("{who}: encoding the PNG: {e}"))?;
        crate::output::write_atomic(path, png.get_ref())
            .map_err(|e| format!("writing {}: {e}", path.display()))
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
}
