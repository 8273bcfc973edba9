//! Building one layer's mesh: quads as triangle pairs, clipped to the
//! group's clip rectangle (the game's scissor) where they cross it.

use super::*;

/// Triangle vertex being clipped: x, y, u, v.
type ClipVert = [f32; 4];

fn clip_polygon(poly: Vec<ClipVert>, axis: usize, bound: f32, keep_greater: bool) -> Vec<ClipVert> {
    let inside = |v: &ClipVert| {
        if keep_greater {
            v[axis] >= bound
        } else {
            v[axis] <= bound
        }
    };
    let mut out = Vec::with_capacity(poly.len() + 2);
    for i in 0..poly.len() {
        let a = poly[i];
        let b = poly[(i + 1) % poly.len()];
        let (ia, ib) = (inside(&a), inside(&b));
        if ia {
            out.push(a);
        }
        if ia != ib {
            let t = (bound - a[axis]) / (b[axis] - a[axis]);
            let mut v = [0.0; 4];
            for k in 0..4 {
                v[k] = a[k] + (b[k] - a[k]) * t;
            }
            v[axis] = bound;
            out.push(v);
        }
    }
    out
}

/// Accumulates one mesh's triangles, clipping to a rectangle if asked.
pub(super) struct MeshBuilder {
    pub(super) positions: Vec<Vec3>,
    pub(super) uv: Vec<Vec2>,
    pub(super) indices: Vec<u32>,
    pub(super) z: f32,
    pub(super) clip: Option<[f32; 4]>,
}

impl MeshBuilder {
    pub(super) fn new(z: f32, clip: Option<[f32; 4]>) -> Self {
        Self {
            positions: Vec::new(),
            uv: Vec::new(),
            indices: Vec::new(),
            z,
            clip,
        }
    }

    fn push(&mut self, p: [f32; 2], t: [f32; 2]) -> u32 {
        self.positions.push([p[0], p[1], self.z]);
        self.uv.push(t);
        (self.positions.len() - 1) as u32
    }

    /// A quad with corners in drawing order c0 c1 c2 c3 (triangles c0 c1 c2
    /// and c0 c2 c3).
    pub(super) fn quad(&mut self, p: [[f32; 2]; 4], t: [[f32; 2]; 4]) {
        let inside = |c: &[f32; 4], q: &[f32; 2]| {
            q[0] >= c[0] && q[0] <= c[2] && q[1] >= c[1] && q[1] <= c[3]
        };
        match self.clip {
            Some(c) if !p.iter().all(|q| inside(&c, q)) => {
                for tri in [[0usize, 1, 2], [0, 2, 3]] {
                    let mut poly: Vec<ClipVert> = tri
                        .iter()
                        .map(|&k| [p[k][0], p[k][1], t[k][0], t[k][1]])
                        .collect();
                    poly = clip_polygon(poly, 0, c[0], true);
                    poly = clip_polygon(poly, 0, c[2], false);
                    poly = clip_polygon(poly, 1, c[1], true);
                    poly = clip_polygon(poly, 1, c[3], false);
                    if poly.len() < 3 {
                        continue;
                    }
                    let base: Vec<u32> = poly
                        .iter()
                        .map(|v| self.push([v[0], v[1]], [v[2], v[3]]))
                        .collect();
                    for k in 1..base.len() - 1 {
                        self.indices.extend([base[0], base[k], base[k + 1]]);
                    }
                }
            }
            _ => {
                let i: Vec<u32> = (0..4).map(|k| self.push(p[k], t[k])).collect();
                self.indices.extend([i[0], i[1], i[2], i[0], i[2], i[3]]);
            }
        }
    }

    pub(super) fn finish(self, material: usize) -> Option<Mesh> {
        if self.indices.is_empty() {
            return None;
        }
        Some(Mesh {
            positions: self.positions,
            uv: self.uv,
            uv2: None,
            indices: self.indices,
            material,
            ..Default::default()
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clipping_keeps_the_inside() {
        let mut b = MeshBuilder::new(0.0, Some([0.0, 0.0, 10.0, 10.0]));
        b.quad(
            [[-10.0, -10.0], [20.0, -10.0], [20.0, 20.0], [-10.0, 20.0]],
            [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        );
        let area: f32 = b
            .indices
            .chunks(3)
            .map(|t| {
                let [a, bb, c] = [t[0], t[1], t[2]].map(|i| b.positions[i as usize]);
                ((bb[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (bb[1] - a[1])).abs() / 2.0
            })
            .sum();
        assert!((area - 100.0).abs() < 1e-3, "{area}");
        for (p, t) in b.positions.iter().zip(&b.uv) {
            assert!(p[0] >= 0.0 && p[0] <= 10.0 && p[1] >= 0.0 && p[1] <= 10.0);
            assert!((t[0] - (p[0] + 10.0) / 30.0).abs() < 1e-5);
        }
    }
}
