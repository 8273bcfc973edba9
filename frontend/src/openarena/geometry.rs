//! Geometry of the map's faces: polygons, meshes and Bezier patches
//! tessellated into triangles.

use super::*;

/// The vertex at (s, t) of a 3x3-control-point biquadratic Bezier patch.
pub(super) fn biquadratic(c: &[BspVertex; 9], s: f32, t: f32) -> BspVertex {
    let w = |u: f32| [(1.0 - u) * (1.0 - u), 2.0 * u * (1.0 - u), u * u];
    let (ws, wt) = (w(s), w(t));
    let mut v = BspVertex {
        pos: [0.0; 3],
        uv: [0.0; 2],
        lm: [0.0; 2],
        normal: [0.0; 3],
    };
    for (j, wj) in wt.iter().enumerate() {
        for (i, wi) in ws.iter().enumerate() {
            let k = wi * wj;
            let p = &c[j * 3 + i];
            for a in 0..3 {
                v.pos[a] += k * p.pos[a];
                v.normal[a] += k * p.normal[a];
            }
            for a in 0..2 {
                v.uv[a] += k * p.uv[a];
                v.lm[a] += k * p.lm[a];
            }
        }
    }
    v
}

/// A face's triangles as (vertices, indices), counter-clockwise seen from
/// the front; None for faces that are not drawn (flares, unknown types).
pub fn face_triangles(bsp: &Bsp, f: &BspFace) -> Option<(Vec<BspVertex>, Vec<u32>)> {
    let verts = &bsp.vertices[f.first_vertex..f.first_vertex + f.n_vertices];
    match f.kind {
        1 | 3 => {
            let mv = &bsp.meshverts[f.first_meshvert..f.first_meshvert + f.n_meshverts];
            let mut idx = Vec::with_capacity(mv.len());
            for t in mv.chunks_exact(3) {
                // Stored clockwise: reverse.
                idx.extend_from_slice(&[t[0] as u32, t[2] as u32, t[1] as u32]);
            }
            Some((verts.to_vec(), idx))
        }
        2 => {
            let [w, h] = f.size;
            let l = PATCH_LEVEL;
            let mut out_v = Vec::new();
            let mut out_i = Vec::new();
            for py in 0..(h - 1) / 2 {
                for px in 0..(w - 1) / 2 {
                    let mut c = [verts[0]; 9];
                    for j in 0..3 {
                        for i in 0..3 {
                            c[j * 3 + i] = verts[(py * 2 + j) * w + px * 2 + i];
                        }
                    }
                    let base = out_v.len() as u32;
                    for j in 0..=l {
                        for i in 0..=l {
                            out_v.push(biquadratic(&c, i as f32 / l as f32, j as f32 / l as f32));
                        }
                    }
                    let row = (l + 1) as u32;
                    for j in 0..l as u32 {
                        for i in 0..l as u32 {
                            let a = base + j * row + i;
                            for t in [[a, a + 1, a + row + 1], [a, a + row + 1, a + row]] {
                                let (p0, p1, p2) = (
                                    &out_v[t[0] as usize],
                                    &out_v[t[1] as usize],
                                    &out_v[t[2] as usize],
                                );
                                let n = cross(sub(p1.pos, p0.pos), sub(p2.pos, p0.pos));
                                let vn = [
                                    p0.normal[0] + p1.normal[0] + p2.normal[0],
                                    p0.normal[1] + p1.normal[1] + p2.normal[1],
                                    p0.normal[2] + p1.normal[2] + p2.normal[2],
                                ];
                                if dot(n, vn) < 0.0 {
                                    out_i.extend_from_slice(&[t[0], t[2], t[1]]);
                                } else {
                                    out_i.extend_from_slice(&t);
                                }
                            }
                        }
                    }
                }
            }
            Some((out_v, out_i))
        }
        _ => None,
    }
}
