//! The potentially visible set: which faces the engine draws from an eye
//! position, from the BSP's planes (lump 2), nodes (3), leaves (4), leaf
//! faces (5) and visibility data (16).
//!
//! ioquake3's renderer finds the leaf holding the eye by walking the
//! nodes (the front child where the point is in front of the node's
//! plane, else the back one), takes that leaf's cluster, and draws the
//! faces of the leaves whose cluster's bit is set in the eye cluster's
//! row of the visibility data. An eye in no cluster (outside the map, in
//! solid) or a map without visibility data draws every leaf. The engine
//! also leaves out areas that closed doors separate (the game's area
//! mask); the loader keeps every area (wasp: it has no game state, so
//! every door counts as open). Faces that no leaf lists (those of brush
//! models: doors, platforms) are drawn as entities, and kept.

use super::*;

/// The visibility structures of a map.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Vis {
    /// Planes: normal, distance.
    planes: Vec<(Vec3, f32)>,
    /// Nodes: plane index, children (a child below 0 is leaf -1 - child).
    nodes: Vec<(usize, [i32; 2])>,
    /// Leaves: cluster (-1: none) and their faces.
    leaves: Vec<(i32, Vec<usize>)>,
    /// Clusters in the visibility data, and bytes per cluster's row.
    clusters: usize,
    row_bytes: usize,
    /// The rows: bit `c` of row `r` set if cluster `c` is visible from `r`.
    bits: Vec<u8>,
}

/// A lump as (file offset, record count).
type Lump = (usize, usize);

impl Vis {
    /// Read the planes, nodes, leaves, leaf faces and visibility lumps,
    /// checking every index (faces against `n_faces`).
    pub(super) fn read(
        r: &Bytes,
        [planes, nodes, leaves, leaf_faces, vis]: [Lump; 5],
        n_faces: usize,
    ) -> Result<Vis, SceneError> {
        let planes = read_planes(r, planes)?;
        let nodes = read_nodes(r, nodes, planes.len(), leaves.1)?;
        let leaves = read_leaves(r, leaves, leaf_faces, n_faces)?;
        let (clusters, row_bytes, bits) = read_bits(r, vis)?;
        Ok(Vis {
            planes,
            nodes,
            leaves,
            clusters,
            row_bytes,
            bits,
        })
    }

    /// The leaf holding point `p` (None for a map without nodes).
    pub fn leaf_of(&self, p: Vec3) -> Option<usize> {
        let mut node = 0usize;
        // Every step goes down one level: at most one step per node.
        for _ in 0..self.nodes.len() {
            let (plane, children) = self.nodes.get(node)?;
            let (n, d) = self.planes[*plane];
            let child = if dot(n, p) - d > 0.0 {
                children[0]
            } else {
                children[1]
            };
            if child < 0 {
                return Some((-1 - child) as usize);
            }
            node = child as usize;
        }
        None
    }

    /// Which of `n_faces` faces the engine draws from `eye`: the faces of
    /// the leaves in the eye cluster's potentially visible set, and every
    /// face no leaf lists. None when it draws every leaf (no visibility
    /// data, or the eye in no cluster).
    pub fn visible_faces(&self, eye: Vec3, n_faces: usize) -> Option<Vec<bool>> {
        let cluster = self.leaves.get(self.leaf_of(eye)?)?.0;
        let from = usize::try_from(cluster)
            .ok()
            .filter(|&c| c < self.clusters)?;
        let row = &self.bits[from * self.row_bytes..(from + 1) * self.row_bytes];
        let mut listed = vec![false; n_faces];
        let mut visible = vec![false; n_faces];
        for (c, faces) in &self.leaves {
            let seen = usize::try_from(*c)
                .ok()
                .filter(|&c| c < self.clusters)
                .is_some_and(|c| row[c >> 3] & (1 << (c & 7)) != 0);
            for &f in faces {
                listed[f] = true;
                visible[f] |= seen;
            }
        }
        Some(
            visible
                .iter()
                .zip(&listed)
                .map(|(&v, &l)| v || !l)
                .collect(),
        )
    }
}

/// The planes lump: normal and distance of each plane.
fn read_planes(r: &Bytes, planes: Lump) -> Result<Vec<([f32; 3], f32)>, SceneError> {
    (0..planes.1)
        .map(|i| {
            let at = planes.0 + 16 * i;
            let f = |k: usize| r.f32_at(at + 4 * k, "plane");
            Ok(([f(0)?, f(1)?, f(2)?], f(3)?))
        })
        .collect::<Result<Vec<_>, SceneError>>()
}

/// The nodes lump: each node's plane and children (a leaf as `-1 - index`),
/// checked against `n_planes`, the nodes and `n_leaves`.
fn read_nodes(
    r: &Bytes,
    nodes: Lump,
    n_planes: usize,
    n_leaves: usize,
) -> Result<Vec<(usize, [i32; 2])>, SceneError> {
    (0..nodes.1)
        .map(|i| {
            let at = nodes.0 + 36 * i;
            let plane = r.i32_at(at, "node")?;
            let plane = usize::try_from(plane)
                .ok()
                .filter(|&p| p < n_planes)
                .ok_or_else(|| {
                    r.err(
                        at,
                        format!("node {i}: plane {plane} out of range ({})", n_planes),
                    )
                })?;
            let children = [r.i32_at(at + 4, "node")?, r.i32_at(at + 8, "node")?];
            for (k, &c) in children.iter().enumerate() {
                let ok = if c >= 0 {
                    (c as usize) < nodes.1
                } else {
                    ((-1 - c) as usize) < n_leaves
                };
                if !ok {
                    return Err(r.err(
                        at + 4 + 4 * k,
                        format!(
                            "node {i}: child {c} out of range ({} nodes, {n_leaves} leaves)",
                            nodes.1
                        ),
                    ));
                }
            }
            Ok((plane, children))
        })
        .collect::<Result<Vec<_>, SceneError>>()
}

/// The leaves lump: each leaf's cluster and its faces (through the leaf
/// faces lump), the faces checked against `n_faces`.
fn read_leaves(
    r: &Bytes,
    leaves: Lump,
    leaf_faces: Lump,
    n_faces: usize,
) -> Result<Vec<(i32, Vec<usize>)>, SceneError> {
    (0..leaves.1)
        .map(|i| {
            let at = leaves.0 + 48 * i;
            let cluster = r.i32_at(at, "leaf")?;
            let (first, count) = (r.i32_at(at + 32, "leaf")?, r.i32_at(at + 36, "leaf")?);
            let range = match (usize::try_from(first), usize::try_from(count)) {
                (Ok(f), Ok(c)) if f + c <= leaf_faces.1 => f..f + c,
                _ => {
                    return Err(r.err(
                        at + 32,
                        format!(
                            "leaf {i}: leaf faces {first}+{count} out of range ({})",
                            leaf_faces.1
                        ),
                    ))
                }
            };
            let faces = range
                .map(|k| {
                    let f = r.i32_at(leaf_faces.0 + 4 * k, "leaf face")?;
                    usize::try_from(f)
                        .ok()
                        .filter(|&f| f < n_faces)
                        .ok_or_else(|| {
                            r.err(
                                leaf_faces.0 + 4 * k,
                                format!("leaf face {f} out of range ({n_faces})"),
                            )
                        })
                })
                .collect::<Result<Vec<_>, SceneError>>()?;
            Ok((cluster, faces))
        })
        .collect::<Result<Vec<_>, SceneError>>()
}

/// The visibility lump: clusters, bytes per row and the rows (none for a
/// map without visibility data).
fn read_bits(r: &Bytes, vis: Lump) -> Result<(usize, usize, Vec<u8>), SceneError> {
    Ok(if vis.1 == 0 {
        (0, 0, Vec::new())
    } else {
        let n = r.i32_at(vis.0, "visibility")?;
        let sz = r.i32_at(vis.0 + 4, "visibility")?;
        let size = usize::try_from(n)
            .ok()
            .zip(usize::try_from(sz).ok())
            .and_then(|(n, s)| n.checked_mul(s).map(|b| (n, s, b)))
            .filter(|&(n, s, b)| b + 8 <= vis.1 && s * 8 >= n);
        let Some((n, s, b)) = size else {
            return Err(r.err(
                vis.0,
                format!(
                    "visibility: {n} clusters of {sz} bytes do not fit its {} bytes",
                    vis.1
                ),
            ));
        };
        (n, s, r.slice(vis.0 + 8, b, "visibility")?.to_vec())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A map of two leaves split by the plane x = 0 (front: leaf 0,
    /// cluster 0; back: leaf 1, cluster 1), faces 0 in leaf 0, 1 in leaf
    /// 1, 2 in both, 3 in none; cluster 0 sees only itself, cluster 1 both.
    fn two_rooms(vis_rows: &[u8]) -> Vec<u8> {
        let mut b = vec![0u8; 8 + 8 * 17];
        let put = |b: &mut Vec<u8>, lump: usize, data: &[u8]| {
            let off = b.len() as i32;
            b[8 + 8 * lump..12 + 8 * lump].copy_from_slice(&off.to_le_bytes());
            b[12 + 8 * lump..16 + 8 * lump].copy_from_slice(&(data.len() as i32).to_le_bytes());
            b.extend_from_slice(data);
        };
        let le = |v: &[i32]| v.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
        let plane: Vec<u8> = [1.0f32, 0.0, 0.0, 0.0]
            .iter()
            .flat_map(|x| x.to_le_bytes())
            .collect();
        put(&mut b, 2, &plane);
        put(&mut b, 3, &le(&[0, -1, -2, 0, 0, 0, 0, 0, 0]));
        let leaf =
            |cluster: i32, first: i32, n: i32| le(&[cluster, 0, 0, 0, 0, 0, 0, 0, first, n, 0, 0]);
        put(&mut b, 4, &[leaf(0, 0, 2), leaf(1, 2, 2)].concat());
        put(&mut b, 5, &le(&[0, 2, 1, 2]));
        put(&mut b, 16, &[le(&[2, 1]), vis_rows.to_vec()].concat());
        b
    }

    fn read(b: &[u8]) -> Result<Vis, SceneError> {
        let r = Bytes::new(b, Path::new("two.bsp"));
        let lump = |i: usize, rec: usize| {
            let off = r.i32_at(8 + 8 * i, "lump").unwrap() as usize;
            (off, r.i32_at(12 + 8 * i, "lump").unwrap() as usize / rec)
        };
        Vis::read(
            &r,
            [
                lump(2, 16),
                lump(3, 36),
                lump(4, 48),
                lump(5, 4),
                lump(16, 1),
            ],
            4,
        )
    }

    #[test]
    fn the_eye_sees_the_faces_of_its_clusters_set() {
        let v = read(&two_rooms(&[0b01, 0b11])).unwrap();
        assert_eq!(v.leaf_of([5.0, 0.0, 0.0]), Some(0));
        assert_eq!(v.leaf_of([-5.0, 0.0, 0.0]), Some(1));
        // From cluster 0: leaf 0's faces, and face 3 that no leaf lists.
        assert_eq!(
            v.visible_faces([5.0, 0.0, 0.0], 4).unwrap(),
            [true, false, true, true]
        );
        // From cluster 1: both leaves.
        assert_eq!(v.visible_faces([-5.0, 0.0, 0.0], 4).unwrap(), [true; 4]);
        // No visibility data: every leaf.
        let mut b = two_rooms(&[]);
        let n = b.len();
        b[8 + 8 * 16 + 4..8 + 8 * 16 + 8].copy_from_slice(&0i32.to_le_bytes());
        let v = read(&b[..n]).unwrap();
        assert_eq!(v.visible_faces([5.0, 0.0, 0.0], 4), None);
    }

    #[test]
    fn bad_indices_name_the_file_and_offset() {
        let mut b = two_rooms(&[0b01, 0b11]);
        // Node 0's back child: leaf 5, past the two leaves.
        let nodes = i32::from_le_bytes(b[8 + 8 * 3..12 + 8 * 3].try_into().unwrap()) as usize;
        b[nodes + 8..nodes + 12].copy_from_slice(&(-6i32).to_le_bytes());
        let e = read(&b).unwrap_err();
        assert!(
            e.file.ends_with("two.bsp") && e.offset == Some(nodes as u64 + 8),
            "{e}"
        );
        assert!(e.message.contains("child -6"), "{e}");
        // Rows that do not fit the lump.
        let e = read(&two_rooms(&[0b01])).unwrap_err();
        assert!(e.message.contains("visibility"), "{e}");
    }
}
