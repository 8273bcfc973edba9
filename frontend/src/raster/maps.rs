//! Per-pixel maps of a rasterized frame, for checking the front end
//! against another renderer (`wasp import-gl --check-mesa`): per pixel,
//! the fragments that passed the depth test (the Early-Z survivors the
//! shader cores shade), those of them the alpha test kept (written), and
//! the material of the last fragment written with colour writes on.

use super::*;

/// Per-pixel maps of a frame, row-major, top row first.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct PixelMaps {
    pub width: u32,
    pub height: u32,
    /// Fragments (pixels of surviving quads, inside their triangle) that
    /// passed the scissor and depth tests: what the shader cores shade.
    pub shaded: Vec<u16>,
    /// Of those, the ones the alpha test kept: the fragments that write
    /// the pixel (saturating at `u16::MAX`).
    pub written: Vec<u16>,
    /// 1 + the material of the last fragment written with colour writes
    /// on; 0 where none was.
    pub last_material: Vec<u32>,
}

impl PixelMaps {
    pub(super) fn new(width: u32, height: u32) -> PixelMaps {
        let n = width as usize * height as usize;
        PixelMaps {
            width,
            height,
            shaded: vec![0; n],
            written: vec![0; n],
            last_material: vec![0; n],
        }
    }

    /// Copies a tile's maps in: the tile's pixels (`ox`, `oy`) to
    /// (`ox + tw`, `oy + th`), its buffers `t` wide.
    pub(super) fn join(&mut self, m: &TileMaps, (ox, oy, tw, th, t): (u32, u32, u32, u32, u32)) {
        for ly in 0..th {
            let row = ((oy + ly) * self.width + ox) as usize;
            let src = (ly * t) as usize;
            let n = tw as usize;
            self.shaded[row..row + n].copy_from_slice(&m.shaded[src..src + n]);
            self.written[row..row + n].copy_from_slice(&m.written[src..src + n]);
            self.last_material[row..row + n].copy_from_slice(&m.last[src..src + n]);
        }
    }
}

/// One tile's maps (as [`PixelMaps`], the tile's buffers).
#[derive(Clone, Debug)]
pub(super) struct TileMaps {
    pub(super) shaded: Vec<u16>,
    pub(super) written: Vec<u16>,
    pub(super) last: Vec<u32>,
}

impl TileMaps {
    pub(super) fn new(tile: u32) -> TileMaps {
        let n = (tile * tile) as usize;
        TileMaps {
            shaded: vec![0; n],
            written: vec![0; n],
            last: vec![0; n],
        }
    }

    pub(super) fn clear(&mut self) {
        self.shaded.fill(0);
        self.written.fill(0);
        self.last.fill(0);
    }
}

/// [`rasterize`], with the frame's [`PixelMaps`] (the frame is the same
/// as without them).
pub fn rasterize_with_maps(
    scene: &Scene,
    width: u32,
    height: u32,
    opts: &RasterOptions,
) -> Result<(Frame, PixelMaps), SceneError> {
    let (frame, maps) = rasterize_frame(scene, width, height, opts, true, true)?;
    Ok((frame, maps.unwrap_or_else(|| PixelMaps::new(width, height))))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::fixtures::*;

    #[test]
    fn maps_count_every_shaded_pixel_and_leave_the_frame_unchanged() {
        for (seed, (w, h)) in [(1u64, (200u32, 150u32)), (2, (97, 61)), (3, (130, 70))] {
            let scene = random_scene(0x9e37_79b9_7f4a_7c15 ^ seed, 300);
            let opts = RasterOptions {
                threads: 2,
                ..Default::default()
            };
            let plain = rasterize(&scene, w, h, &opts).unwrap();
            let (frame, maps) = rasterize_with_maps(&scene, w, h, &opts).unwrap();
            assert_eq!(frame.image, plain.image, "seed {seed}");
            assert_eq!(frame.stats, plain.stats, "seed {seed}");
            let shaded: u64 = maps.shaded.iter().map(|&c| u64::from(c)).sum();
            assert_eq!(shaded, frame.stats.pixels_shaded, "seed {seed}");
            for i in 0..maps.shaded.len() {
                assert!(maps.written[i] <= maps.shaded[i]);
                assert_eq!(maps.last_material[i] != 0, maps.written[i] != 0);
            }
        }
    }
}
