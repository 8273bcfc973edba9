//! A tiny software rasterizer for eyeballing the 2D loaders (tests
//! only): the meshes in submission order (painter's order), nearest
//! texel, untextured materials light blue, alpha blending for blended
//! materials.

use super::*;

#[cfg(test)]
pub(crate) fn render_preview(scene: &Scene, w: u32, h: u32) -> image::RgbaImage {
    let Camera::Ortho {
        left,
        top,
        width,
        height,
    } = scene.camera
    else {
        panic!("preview needs an ortho camera")
    };
    let mut img = image::RgbaImage::from_pixel(w, h, image::Rgba([40, 40, 40, 255]));
    let (sx, sy) = (w as f32 / width, h as f32 / height);
    for m in &scene.meshes {
        let mat = &scene.materials[m.material];
        let tex = mat.shader.iter().find_map(|op| match op {
            ShaderOp::Tex(t) => Some(&scene.textures[t.texture]),
            _ => None,
        });
        for t in m.indices.chunks_exact(3) {
            let v = [t[0], t[1], t[2]].map(|i| {
                let p = m.positions[i as usize];
                ([(p[0] - left) * sx, (p[1] - top) * sy], m.uv[i as usize])
            });
            let area = (v[1].0[0] - v[0].0[0]) * (v[2].0[1] - v[0].0[1])
                - (v[2].0[0] - v[0].0[0]) * (v[1].0[1] - v[0].0[1]);
            if area.abs() < 1e-9 {
                continue;
            }
            let minx = v.iter().map(|q| q.0[0]).fold(f32::MAX, f32::min).max(0.0) as u32;
            let maxx = v
                .iter()
                .map(|q| q.0[0])
                .fold(f32::MIN, f32::max)
                .min(w as f32 - 1.0);
            let miny = v.iter().map(|q| q.0[1]).fold(f32::MAX, f32::min).max(0.0) as u32;
            let maxy = v
                .iter()
                .map(|q| q.0[1])
                .fold(f32::MIN, f32::max)
                .min(h as f32 - 1.0);
            if maxx < 0.0 || maxy < 0.0 {
                continue;
            }
            for py in miny..=maxy as u32 {
                for px in minx..=maxx as u32 {
                    let (fx, fy) = (px as f32 + 0.5, py as f32 + 0.5);
                    let e = |a: [f32; 2], b: [f32; 2]| {
                        ((b[0] - a[0]) * (fy - a[1]) - (fx - a[0]) * (b[1] - a[1])) / area
                    };
                    let (w0, w1, w2) = (e(v[1].0, v[2].0), e(v[2].0, v[0].0), e(v[0].0, v[1].0));
                    if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                        continue;
                    }
                    let src = match tex {
                        Some(tx) => {
                            let u = w0 * v[0].1[0] + w1 * v[1].1[0] + w2 * v[2].1[0];
                            let vv = w0 * v[0].1[1] + w1 * v[1].1[1] + w2 * v[2].1[1];
                            let wrap = |c: f32, n: u32| {
                                let c = if tx.repeat {
                                    c - c.floor()
                                } else {
                                    c.clamp(0.0, 1.0)
                                };
                                ((c * n as f32) as u32).min(n - 1)
                            };
                            let (ix, iy) = (wrap(u, tx.width), wrap(vv, tx.height));
                            let o = 4 * (iy * tx.width + ix) as usize;
                            [tx.rgba[o], tx.rgba[o + 1], tx.rgba[o + 2], tx.rgba[o + 3]]
                        }
                        None => [150, 190, 230, 255],
                    };
                    let dst = img.get_pixel_mut(px, py);
                    if mat.blend == Blend::AlphaBlend {
                        let a = src[3] as f32 / 255.0;
                        for (d, s) in dst.0.iter_mut().zip(src).take(3) {
                            *d = (s as f32 * a + *d as f32 * (1.0 - a)) as u8;
                        }
                    } else {
                        dst.0 = [src[0], src[1], src[2], 255];
                    }
                }
            }
        }
    }
    img
}
