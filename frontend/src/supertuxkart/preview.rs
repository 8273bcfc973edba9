//! A crude software preview of a scene (tests only): near-plane clipping,
//! z-buffer, perspective-correct nearest texturing, back faces culled
//! (counter-clockwise = front), to check transforms, winding and cameras
//! by eye.

use super::*;

pub(crate) fn render(scene: &Scene, w: usize, h: usize, out: &Path) {
    let Camera::Perspective {
        eye,
        target,
        up,
        fov_y_deg,
        near,
        ..
    } = scene.camera
    else {
        return;
    };
    let f = normalize(sub(target, eye));
    let r = normalize(cross(f, up));
    let u = cross(r, f);
    let ty = (fov_y_deg.to_radians() * 0.5).tan();
    let tx = ty * w as f32 / h as f32;
    let mut color = vec![[40u8, 40, 60]; w * h];
    let mut depth = vec![0f32; w * h];
    for mesh in &scene.meshes {
        let mat = &scene.materials[mesh.material];
        let tex = mat.shader.iter().find_map(|op| match op {
            ShaderOp::Tex(t) => Some(&scene.textures[t.texture]),
            _ => None,
        });
        let blend = mat.blend;
        for t in mesh.indices.chunks_exact(3) {
            // View space: (x, y, z, u, v).
            let mut poly: Vec<[f32; 5]> = t
                .iter()
                .map(|&i| {
                    let d = sub(mesh.positions[i as usize], eye);
                    let uv = mesh.uv[i as usize];
                    [
                        super::super::vec3::dot(d, r),
                        super::super::vec3::dot(d, u),
                        super::super::vec3::dot(d, f),
                        uv[0],
                        uv[1],
                    ]
                })
                .collect();
            // Clip against z >= near.
            let mut clipped = Vec::new();
            for k in 0..poly.len() {
                let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
                if a[2] >= near {
                    clipped.push(a);
                }
                if (a[2] >= near) != (b[2] >= near) {
                    let s = (near - a[2]) / (b[2] - a[2]);
                    let mut p = [0.0; 5];
                    for c in 0..5 {
                        p[c] = a[c] + (b[c] - a[c]) * s;
                    }
                    clipped.push(p);
                }
            }
            poly = clipped;
            if poly.len() < 3 {
                continue;
            }
            // Screen: (sx, sy, 1/z, u/z, v/z).
            let scr: Vec<[f32; 5]> = poly
                .iter()
                .map(|p| {
                    let iz = 1.0 / p[2];
                    [
                        (p[0] * iz / tx * 0.5 + 0.5) * w as f32,
                        (0.5 - p[1] * iz / ty * 0.5) * h as f32,
                        iz,
                        p[3] * iz,
                        p[4] * iz,
                    ]
                })
                .collect();
            for k in 1..scr.len() - 1 {
                let (a, b, c) = (scr[0], scr[k], scr[k + 1]);
                // Screen y grows down: front faces have negative area here.
                let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
                if area >= 0.0 {
                    continue;
                }
                let x0 = a[0].min(b[0]).min(c[0]).max(0.0) as usize;
                let x1 = (a[0].max(b[0]).max(c[0]).ceil() as usize).min(w);
                let y0 = a[1].min(b[1]).min(c[1]).max(0.0) as usize;
                let y1 = (a[1].max(b[1]).max(c[1]).ceil() as usize).min(h);
                for py in y0..y1 {
                    for px in x0..x1 {
                        let (x, y) = (px as f32 + 0.5, py as f32 + 0.5);
                        let e = |p: [f32; 5], q: [f32; 5]| {
                            (q[0] - p[0]) * (y - p[1]) - (q[1] - p[1]) * (x - p[0])
                        };
                        let (w0, w1, w2) = (e(b, c) / area, e(c, a) / area, e(a, b) / area);
                        if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                            continue;
                        }
                        let iz = w0 * a[2] + w1 * b[2] + w2 * c[2];
                        let o = py * w + px;
                        if iz <= depth[o] {
                            continue;
                        }
                        let uu = (w0 * a[3] + w1 * b[3] + w2 * c[3]) / iz;
                        let vv = (w0 * a[4] + w1 * b[4] + w2 * c[4]) / iz;
                        let texel = match tex {
                            Some(t) => {
                                let tx = ((uu.rem_euclid(1.0) * t.width as f32) as usize)
                                    .min(t.width as usize - 1);
                                let ty = ((vv.rem_euclid(1.0) * t.height as f32) as usize)
                                    .min(t.height as usize - 1);
                                let i = (ty * t.width as usize + tx) * 4;
                                [t.rgba[i], t.rgba[i + 1], t.rgba[i + 2], t.rgba[i + 3]]
                            }
                            None => [200, 200, 200, 255],
                        };
                        match blend {
                            Blend::Opaque => {
                                color[o] = [texel[0], texel[1], texel[2]];
                                depth[o] = iz;
                            }
                            Blend::AlphaTest => {
                                if texel[3] >= 128 {
                                    color[o] = [texel[0], texel[1], texel[2]];
                                    depth[o] = iz;
                                }
                            }
                            Blend::AlphaBlend => {
                                let al = texel[3] as u32;
                                for ch in 0..3 {
                                    color[o][ch] =
                                        ((texel[ch] as u32 * al + color[o][ch] as u32 * (255 - al))
                                            / 255) as u8;
                                }
                            }
                        }
                    }
                }
            }
        }
    }
    let mut img = image::RgbImage::new(w as u32, h as u32);
    for (i, c) in color.iter().enumerate() {
        img.put_pixel((i % w) as u32, (i / w) as u32, image::Rgb(*c));
    }
    img.save(out).unwrap();
}
