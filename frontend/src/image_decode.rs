//! GIF and TGA images decoded by the `image` crate into the RGBA8 level 0
//! a [`crate::Texture`] holds; its errors become [`SceneError`]s naming the
//! file.

use crate::SceneError;
use image::{ImageDecoder, ImageFormat};
use std::io::Cursor;
use std::path::Path;

/// Largest image accepted (pixels): a bound on what a corrupt header can
/// make the decoder allocate.
const MAX_PIXELS: u64 = 4096 * 4096;

/// Decode `bytes` (a whole file in `format`) into (width, height, RGBA8,
/// top row first).
pub(crate) fn decode_rgba(
    path: &Path,
    bytes: &[u8],
    format: ImageFormat,
) -> Result<(u32, u32, Vec<u8>), SceneError> {
    let name = format!("{format:?}").to_uppercase();
    let fail =
        |e: image::ImageError| SceneError::in_file(path, format!("not a readable {name}: {e}"));
    let mut reader = image::ImageReader::with_format(Cursor::new(bytes), format);
    let mut limits = image::Limits::default();
    limits.max_alloc = Some(MAX_PIXELS * 4 * 2);
    reader.limits(limits);
    let decoder = reader.into_decoder().map_err(fail)?;
    let (w, h) = decoder.dimensions();
    if w == 0 || h == 0 || u64::from(w) * u64::from(h) > MAX_PIXELS {
        return Err(SceneError::in_file(
            path,
            format!("{name} size {w}x{h}: expected 1..{MAX_PIXELS} pixels"),
        ));
    }
    let img = image::DynamicImage::from_decoder(decoder).map_err(fail)?;
    let mut rgba = img.into_rgba8().into_raw();
    if format == ImageFormat::Gif {
        // A GIF's transparent colour is transparent black (the decoder
        // keeps the palette colour under alpha 0): filtering then mixes in
        // no colour of the transparent index.
        for px in rgba.chunks_exact_mut(4).filter(|p| p[3] == 0) {
            px.copy_from_slice(&[0, 0, 0, 0]);
        }
    }
    Ok((w, h, rgba))
}
