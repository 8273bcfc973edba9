//! Pictures of where Mesa and wasp disagree (RGBA8, top row first, the
//! frame's size), and false-colour pictures of each side's texture ids.

use super::compare::View;

/// Coverage: grey where both cover, red where only Mesa does, blue where
/// only wasp does, black where neither.
pub fn coverage_map(mesa: &View, wasp: &View) -> Vec<u8> {
    per_pixel(mesa, wasp, |m, w| match (m.count > 0, w.count > 0) {
        (true, true) => [110, 110, 110],
        (true, false) => [255, 40, 40],
        (false, true) => [40, 90, 255],
        (false, false) => [0, 0, 0],
    })
}

/// Depth complexity: grey where the counts agree, blue (wasp more) or red
/// (Mesa more) by how many, brighter for larger differences; black where
/// neither side covers.
pub fn depth_map(mesa: &View, wasp: &View) -> Vec<u8> {
    per_pixel(mesa, wasp, |m, w| {
        let d = i64::from(w.count) - i64::from(m.count);
        let level = (100 + 50 * d.unsigned_abs().min(3)) as u8;
        match d {
            _ if m.count == 0 && w.count == 0 => [0, 0, 0],
            0 => [90, 90, 90],
            d if d > 0 => [0, level / 2, level],
            _ => [level, level / 4, 0],
        }
    })
}

/// Texture: grey where both name the same texture, yellow where they
/// differ, dim where one side alone covers, black where neither.
pub fn texture_map(mesa: &View, wasp: &View) -> Vec<u8> {
    per_pixel(mesa, wasp, |m, w| match (m.count > 0, w.count > 0) {
        (true, true) if m.texture == w.texture => [90, 90, 90],
        (true, true) => [255, 220, 0],
        (false, false) => [0, 0, 0],
        _ => [40, 40, 40],
    })
}

/// One side's texture ids in false colour (a colour per texture name,
/// white for untextured, black for the clear).
pub fn ids_picture(v: &View) -> Vec<u8> {
    let mut out = Vec::with_capacity(v.pixels.len() * 4);
    for p in &v.pixels {
        let c = match p.texture {
            None => [0, 0, 0],
            Some(None) => [255, 255, 255],
            Some(Some(n)) => {
                // A hash of the name, kept away from black and white.
                let h = n.wrapping_mul(0x9E37_79B9).rotate_left(13);
                [
                    64 + (h as u8 >> 1),
                    64 + ((h >> 8) as u8 >> 1),
                    64 + ((h >> 16) as u8 >> 1),
                ]
            }
        };
        out.extend_from_slice(&[c[0], c[1], c[2], 255]);
    }
    out
}

fn per_pixel(
    mesa: &View,
    wasp: &View,
    f: impl Fn(&super::compare::PixelView, &super::compare::PixelView) -> [u8; 3],
) -> Vec<u8> {
    let mut out = Vec::with_capacity(mesa.pixels.len() * 4);
    for (m, w) in mesa.pixels.iter().zip(&wasp.pixels) {
        let c = f(m, w);
        out.extend_from_slice(&[c[0], c[1], c[2], 255]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::compare::PixelView;
    use super::*;

    #[test]
    fn each_class_of_pixel_has_its_colour() {
        let px = |count, texture| PixelView { count, texture };
        let view = |p: Vec<PixelView>| View {
            width: 4,
            height: 1,
            pixels: p,
        };
        let mesa = view(vec![
            px(1, Some(Some(1))),
            px(1, Some(Some(1))),
            px(0, None),
            px(2, Some(None)),
        ]);
        let wasp = view(vec![
            px(1, Some(Some(1))),
            px(0, None),
            px(1, Some(Some(2))),
            px(1, Some(Some(2))),
        ]);
        let cov = coverage_map(&mesa, &wasp);
        assert_eq!(&cov[..4], &[110, 110, 110, 255]);
        assert_eq!(&cov[4..8], &[255, 40, 40, 255]);
        assert_eq!(&cov[8..12], &[40, 90, 255, 255]);
        let depth = depth_map(&mesa, &wasp);
        assert_eq!(&depth[..3], &[90, 90, 90]);
        assert_eq!(&depth[12..15], &[150, 37, 0]);
        let tex = texture_map(&mesa, &wasp);
        assert_eq!(&tex[12..15], &[255, 220, 0]);
        let ids = ids_picture(&mesa);
        assert_eq!(&ids[8..15], &[0, 0, 0, 255, 255, 255, 255]);
    }
}
