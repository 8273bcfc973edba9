//! The draw order: in which order the scene's geometry reaches the
//! rasterizer, which decides what Early-Z can reject (a fragment hidden by
//! one drawn earlier is never shaded; one hidden by a later fragment is).
//!
//! - [`DrawOrder::AsLoaded`]: the meshes in the order the loader gives
//!   them (each game's loader keeps its renderer's order where that is
//!   known; `docs/scenes.md` says what each renderer does).
//! - [`DrawOrder::FrontToBackObject`]: the opaque objects sorted nearest
//!   first by the distance from the eye to the centre of their bounding
//!   box (every draw call of the object counts towards its bounds), each
//!   object's opaque draw calls in the order loaded. This is the key
//!   Unity documents for its distance sorts ("distance from camera
//!   position to the object center", `TransparencySortMode.Perspective`);
//!   its opaque sort (`SortingCriteria.CommonOpaque`) groups objects "in
//!   rough front-to-back buckets" on the GPUs where that helps, which
//!   here is exact, unbucketed, order (wasp: no bucket size to choose).
//! - [`DrawOrder::FrontToBackDraw`]: the opaque draw calls sorted by
//!   their nearest view depth: the smallest distance along the view
//!   direction of the corners of their bounding box, no nearer than the
//!   near plane (an engine sorts by bounds, never by the triangles).
//!
//! What a draw call and an object are is each loader's choice
//! ([`crate::Mesh::draws`], [`crate::Draw`]). Only opaque geometry is
//! sorted: the alpha-tested draw calls follow in the order loaded, then
//! the sky ([`crate::Mesh::sky`]), then the alpha-blended ones, as engines
//! draw opaque geometry first, then sky, then transparent geometry back
//! to front (which the rasterizer does for every order). Ties keep the
//! order loaded.
//!
//! A scene with an orthographic camera is a 2D game drawn in painter's
//! order without a depth test: there the order *is* the picture, and no
//! engine sorts it by depth, so every order is the order loaded
//! ([`DrawOrder::effective`]) and the trace is the same.

use super::*;
use serde::Deserialize;
use std::fmt;
use std::str::FromStr;

/// How the opaque geometry is ordered before rasterization (see the
/// module documentation).
#[derive(
    Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize,
)]
#[serde(rename_all = "kebab-case")]
pub enum DrawOrder {
    /// The order the loader gives (the default of every shipped scene).
    #[default]
    AsLoaded,
    /// Opaque objects nearest first by the distance to their bounds'
    /// centre (Unity's default opaque sort on most mobile GPUs).
    FrontToBackObject,
    /// Opaque draw calls nearest first by the nearest view depth of their
    /// bounds.
    FrontToBackDraw,
}

impl DrawOrder {
    /// Every order.
    pub const ALL: [DrawOrder; 3] = [
        DrawOrder::AsLoaded,
        DrawOrder::FrontToBackObject,
        DrawOrder::FrontToBackDraw,
    ];

    /// The name in scene files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            DrawOrder::AsLoaded => "as-loaded",
            DrawOrder::FrontToBackObject => "front-to-back-object",
            DrawOrder::FrontToBackDraw => "front-to-back-draw",
        }
    }

    /// The order that takes effect on `scene`: this one, except on a 2D
    /// scene (orthographic camera, painter's order without a depth test),
    /// where it is [`DrawOrder::AsLoaded`].
    pub fn effective(self, scene: &Scene) -> DrawOrder {
        match scene.camera {
            Camera::Ortho { .. } | Camera::Clip => DrawOrder::AsLoaded,
            Camera::Perspective { .. } => self,
        }
    }
}

impl fmt::Display for DrawOrder {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for DrawOrder {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        DrawOrder::ALL
            .into_iter()
            .find(|o| o.name() == s.trim())
            .ok_or_else(|| {
                format!(
                    "unknown draw order `{s}` (expected as-loaded, front-to-back-object or \
                     front-to-back-draw)"
                )
            })
    }
}

/// A run of one mesh's triangles, in the order the rasterizer takes them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Run {
    /// Index into [`Scene::meshes`].
    pub(super) mesh: usize,
    /// First triangle.
    pub(super) first: usize,
    /// Triangles.
    pub(super) count: usize,
}

/// Where a draw call goes: the sorted opaque ones, then the others in the
/// order loaded, queue by queue.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Queue {
    Opaque,
    AlphaTest,
    Sky,
    Blend,
}

/// One draw call with its object, queue and bounding box.
struct Item {
    run: Run,
    object: u64,
    queue: Queue,
    lo: [f64; 3],
    hi: [f64; 3],
}

/// The runs of `scene` in draw order `order`, and a note for the trace
/// saying what was sorted (none for the order loaded).
pub(super) fn runs(scene: &Scene, order: DrawOrder) -> (Vec<Run>, Option<String>) {
    let Camera::Perspective {
        eye, target, near, ..
    } = scene.camera
    else {
        return (as_loaded(scene), None);
    };
    if order == DrawOrder::AsLoaded {
        return (as_loaded(scene), None);
    }
    let eye = v64(eye);
    // A degenerate camera is reported by the projection; any axis will do.
    let fwd = normalize(sub(v64(target), eye)).unwrap_or([0.0, 0.0, -1.0]);
    let items = items(scene);
    let key: Vec<f64> = match order {
        DrawOrder::FrontToBackDraw => items
            .iter()
            .map(|it| nearest_depth(it.lo, it.hi, eye, fwd).max(f64::from(near)))
            .collect(),
        _ => object_distances(&items, eye),
    };
    // Objects stay together when their keys tie: by first appearance.
    let mut first_of: std::collections::HashMap<u64, usize> = Default::default();
    for (i, it) in items.iter().enumerate() {
        first_of.entry(it.object).or_insert(i);
    }
    let mut idx: Vec<usize> = (0..items.len()).collect();
    // Stable: ties keep the order loaded.
    idx.sort_by(|&a, &b| {
        let (ia, ib) = (&items[a], &items[b]);
        ia.queue.cmp(&ib.queue).then_with(|| {
            if ia.queue != Queue::Opaque {
                return std::cmp::Ordering::Equal;
            }
            let tie = match order {
                DrawOrder::FrontToBackObject => first_of[&ia.object].cmp(&first_of[&ib.object]),
                _ => std::cmp::Ordering::Equal,
            };
            key[a].total_cmp(&key[b]).then(tie)
        })
    });
    let count = |q: Queue| items.iter().filter(|it| it.queue == q).count();
    let mut objects: Vec<u64> = items
        .iter()
        .filter(|it| it.queue == Queue::Opaque)
        .map(|it| it.object)
        .collect();
    objects.sort_unstable();
    objects.dedup();
    let note = format!(
        " draw order {order}: {} opaque draw calls of {} objects sorted nearest first ({}), \
         then {} alpha-tested, {} sky and {} alpha-blended draw calls in the order loaded",
        count(Queue::Opaque),
        objects.len(),
        match order {
            DrawOrder::FrontToBackDraw => "by the nearest view depth of each draw call's bounds",
            _ => "objects by the distance from the eye to their bounds' centre",
        },
        count(Queue::AlphaTest),
        count(Queue::Sky),
        count(Queue::Blend),
    );
    (merged(idx.iter().map(|&i| items[i].run)), Some(note))
}

/// One run per mesh, in mesh order: the order loaded.
fn as_loaded(scene: &Scene) -> Vec<Run> {
    scene
        .meshes
        .iter()
        .enumerate()
        .map(|(mesh, m)| Run {
            mesh,
            first: 0,
            count: m.indices.len() / 3,
        })
        .collect()
}

/// Every draw call of the scene in the order loaded. A mesh without
/// draws is one draw call of an object of its own (ids above the
/// loaders' 32-bit ones).
fn items(scene: &Scene) -> Vec<Item> {
    let mut out = Vec::new();
    for (mesh, m) in scene.meshes.iter().enumerate() {
        let blend = scene.materials[m.material].blend;
        let queue = match blend {
            Blend::AlphaBlend => Queue::Blend,
            _ if m.sky => Queue::Sky,
            Blend::AlphaTest => Queue::AlphaTest,
            Blend::Opaque => Queue::Opaque,
        };
        let whole = [(m.indices.len() / 3, (1u64 << 32) + mesh as u64)];
        let draws: Vec<(usize, u64)> = if m.draws.is_empty() {
            whole.to_vec()
        } else {
            m.draws
                .iter()
                .map(|d| (d.triangles as usize, u64::from(d.object)))
                .collect()
        };
        let mut first = 0;
        for (count, object) in draws {
            let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
            for &v in &m.indices[first * 3..(first + count) * 3] {
                let p = v64(m.positions[v as usize]);
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
            out.push(Item {
                run: Run { mesh, first, count },
                object,
                queue,
                lo,
                hi,
            });
            first += count;
        }
    }
    out
}

/// The smallest view depth (distance along `fwd` from `eye`) of the
/// corners of the box `lo`..`hi` (infinite for an empty box).
fn nearest_depth(lo: [f64; 3], hi: [f64; 3], eye: [f64; 3], fwd: [f64; 3]) -> f64 {
    if lo[0] > hi[0] {
        return f64::INFINITY;
    }
    // Per axis, the corner coordinate that lowers the depth most.
    (0..3)
        .map(|k| {
            let c = if fwd[k] >= 0.0 { lo[k] } else { hi[k] };
            (c - eye[k]) * fwd[k]
        })
        .sum()
}

/// For every item, the distance from the eye to the centre of its
/// object's bounding box (the union of the object's draw calls').
fn object_distances(items: &[Item], eye: [f64; 3]) -> Vec<f64> {
    let mut boxes: std::collections::HashMap<u64, ([f64; 3], [f64; 3])> = Default::default();
    for it in items {
        let b = boxes
            .entry(it.object)
            .or_insert(([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]));
        for k in 0..3 {
            b.0[k] = b.0[k].min(it.lo[k]);
            b.1[k] = b.1[k].max(it.hi[k]);
        }
    }
    items
        .iter()
        .map(|it| {
            let (lo, hi) = boxes[&it.object];
            if lo[0] > hi[0] {
                return f64::INFINITY;
            }
            let c = [
                0.5 * (lo[0] + hi[0]),
                0.5 * (lo[1] + hi[1]),
                0.5 * (lo[2] + hi[2]),
            ];
            dot(sub(c, eye), sub(c, eye)).sqrt()
        })
        .collect()
}

/// `runs` with neighbours that continue one another joined, empty ones
/// left out.
fn merged(runs: impl Iterator<Item = Run>) -> Vec<Run> {
    let mut out: Vec<Run> = Vec::new();
    for r in runs.filter(|r| r.count > 0) {
        match out.last_mut() {
            Some(l) if l.mesh == r.mesh && l.first + l.count == r.first => l.count += r.count,
            _ => out.push(r),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::fixtures::*;
    use crate::{Draw, Mesh};

    /// A square of side 2 facing the camera at distance `d` (z = -d).
    fn square(d: f32, material: usize) -> Mesh {
        Mesh {
            positions: vec![
                [-1.0, -1.0, -d],
                [1.0, -1.0, -d],
                [1.0, 1.0, -d],
                [-1.0, 1.0, -d],
            ],
            uv: vec![[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]],
            indices: vec![0, 1, 2, 0, 2, 3],
            material,
            ..Default::default()
        }
    }

    /// A perspective scene looking down -z.
    fn persp(meshes: Vec<Mesh>, blends: &[Blend]) -> Scene {
        Scene {
            name: "test:order".into(),
            source: "unit test".into(),
            meshes,
            materials: blends
                .iter()
                .enumerate()
                .map(|(i, &b)| mat(&format!("m{i}"), b, 0))
                .collect(),
            textures: vec![checker("c", 16)],
            camera: look_down_z(60.0, 0.1, 100.0),
        }
    }

    fn opts(order: DrawOrder) -> RasterOptions {
        RasterOptions {
            draw_order: order,
            threads: 1,
            ..RasterOptions::default()
        }
    }

    #[test]
    fn names_parse_back_and_bad_ones_say_what_is_allowed() {
        for o in DrawOrder::ALL {
            assert_eq!(o.name().parse::<DrawOrder>(), Ok(o));
            assert_eq!(o.to_string(), o.name());
        }
        let e = "back-to-front".parse::<DrawOrder>().unwrap_err();
        assert_eq!(
            e,
            "unknown draw order `back-to-front` (expected as-loaded, front-to-back-object or \
             front-to-back-draw)"
        );
        assert_eq!(DrawOrder::default(), DrawOrder::AsLoaded);
    }

    #[test]
    fn front_to_back_lets_early_z_reject_what_far_first_shades() {
        // Loaded far first: the near square hides the far one where they
        // overlap, but only after it was shaded.
        let scene = persp(vec![square(10.0, 0), square(3.0, 0)], &[Blend::Opaque]);
        let (w, h) = (64, 64);
        let loaded = rasterize(&scene, w, h, &opts(DrawOrder::AsLoaded)).unwrap();
        assert_eq!(loaded.stats.quads_rejected_early_z, 0);
        for order in [DrawOrder::FrontToBackDraw, DrawOrder::FrontToBackObject] {
            let f = rasterize(&scene, w, h, &opts(order)).unwrap();
            // Every quad of the far square lies behind the near one.
            let far_quads = loaded.stats.warps - f.stats.warps;
            assert!(far_quads > 0, "{order}");
            assert_eq!(f.stats.quads_rejected_early_z, far_quads, "{order}");
            assert_eq!(f.stats.quads_covered, loaded.stats.quads_covered, "{order}");
            assert_eq!(f.stats.positions, loaded.stats.positions, "{order}");
            // The depth test decides the picture, whatever the order.
            assert!(f.image == loaded.image, "{order}: the picture changed");
            assert!(
                f.trace
                    .header()
                    .notes
                    .iter()
                    .any(|n| n.contains(order.name())),
                "{order}: no note"
            );
        }
        // Loaded near first, every order is the same trace.
        let near_first = persp(vec![square(3.0, 0), square(10.0, 0)], &[Blend::Opaque]);
        let a = rasterize(&near_first, w, h, &opts(DrawOrder::AsLoaded)).unwrap();
        let b = rasterize(&near_first, w, h, &opts(DrawOrder::FrontToBackDraw)).unwrap();
        assert_eq!(b.stats.draw_order, DrawOrder::FrontToBackDraw);
        let b_stats = RasterStats {
            draw_order: DrawOrder::AsLoaded,
            ..b.stats.clone()
        };
        assert_eq!(a.stats, b_stats);
        assert_eq!(
            a.stats.quads_rejected_early_z,
            b.stats.quads_rejected_early_z
        );
    }

    #[test]
    fn only_opaque_draws_are_sorted_the_rest_keep_their_order_after_them() {
        // Loaded: blend(5), opaque(9), alpha-test(2), sky(50), opaque(4),
        // alpha-test(1), blend(7).
        let mut sky = square(50.0, 0);
        sky.sky = true;
        let scene = persp(
            vec![
                square(5.0, 2),
                square(9.0, 0),
                square(2.0, 1),
                sky,
                square(4.0, 0),
                square(1.0, 1),
                square(7.0, 2),
            ],
            &[Blend::Opaque, Blend::AlphaTest, Blend::AlphaBlend],
        );
        let (loaded, note) = runs(&scene, DrawOrder::AsLoaded);
        assert!(note.is_none());
        assert_eq!(
            loaded.iter().map(|r| r.mesh).collect::<Vec<_>>(),
            [0, 1, 2, 3, 4, 5, 6]
        );
        for order in [DrawOrder::FrontToBackDraw, DrawOrder::FrontToBackObject] {
            let (r, note) = runs(&scene, order);
            let meshes: Vec<usize> = r.iter().map(|r| r.mesh).collect();
            // Opaque nearest first, then alpha-tested and sky, then
            // blended, each in the order loaded.
            assert_eq!(meshes, [4, 1, 2, 5, 3, 0, 6], "{order}");
            let note = note.unwrap();
            assert!(
                note.contains("2 opaque draw calls of 2 objects")
                    && note.contains("2 alpha-tested, 1 sky and 2 alpha-blended"),
                "{note}"
            );
        }
    }

    #[test]
    fn objects_keep_their_draws_together_draw_calls_do_not() {
        // Mesh 0 holds two draw calls of object 7: one at 2, one at 20;
        // mesh 1 one draw call of object 8 at 10 (bounds centre nearer
        // than object 7's).
        let mut a = square(2.0, 0);
        let far = square(20.0, 0);
        a.positions.extend_from_slice(&far.positions);
        a.uv.extend_from_slice(&far.uv);
        a.indices.extend(far.indices.iter().map(|i| i + 4));
        a.draws = vec![
            Draw {
                triangles: 2,
                object: 7,
            },
            Draw {
                triangles: 2,
                object: 7,
            },
        ];
        let mut b = square(10.0, 0);
        b.draws = vec![Draw {
            triangles: 2,
            object: 8,
        }];
        let scene = persp(vec![a, b], &[Blend::Opaque]);
        let run = |mesh, first, count| Run { mesh, first, count };
        // Draw calls: 2, 10, 20.
        let (d, _) = runs(&scene, DrawOrder::FrontToBackDraw);
        assert_eq!(d, [run(0, 0, 2), run(1, 0, 2), run(0, 2, 2)]);
        // Objects: 8 (centre at 10) before 7 (centre at 11), whose draws
        // stay together and in order (joined into one run).
        let (o, _) = runs(&scene, DrawOrder::FrontToBackObject);
        assert_eq!(o, [run(1, 0, 2), run(0, 0, 4)]);
        // Bad draws are an error, not a panic.
        let mut bad = scene.clone();
        bad.meshes[1].draws[0].triangles = 3;
        let e = rasterize(&bad, 32, 32, &opts(DrawOrder::FrontToBackDraw)).unwrap_err();
        assert!(
            e.message.contains("mesh 1") && e.message.contains("3 triangles"),
            "{e}"
        );
    }

    #[test]
    fn two_d_scenes_are_painters_order_and_every_order_is_a_no_op() {
        let scene = ortho_scene(
            vec![
                quad_mesh(0.0, 0.0, 64.0, 64.0, 0.0, 0),
                quad_mesh(8.0, 8.0, 40.0, 40.0, 1.0, 0),
                quad_mesh(16.0, 16.0, 24.0, 24.0, 0.5, 0),
            ],
            vec![mat("m", Blend::Opaque, 0)],
            64.0,
            64.0,
        );
        let base = rasterize(&scene, 64, 64, &opts(DrawOrder::AsLoaded)).unwrap();
        for order in DrawOrder::ALL {
            assert_eq!(order.effective(&scene), DrawOrder::AsLoaded);
            let (r, note) = runs(&scene, order);
            assert_eq!(r, as_loaded(&scene));
            assert!(note.is_none());
            let f = rasterize(&scene, 64, 64, &opts(order)).unwrap();
            assert_eq!(trace_bytes(&f), trace_bytes(&base), "{order}");
            assert!(f.image == base.image, "{order}");
        }
        let p = persp(vec![square(3.0, 0)], &[Blend::Opaque]);
        assert_eq!(
            DrawOrder::FrontToBackDraw.effective(&p),
            DrawOrder::FrontToBackDraw
        );
    }

    #[test]
    fn nearest_depth_takes_the_nearest_corner_and_the_near_plane_bounds_it() {
        let eye = [0.0; 3];
        let fwd = [0.0, 0.0, -1.0];
        assert_eq!(
            nearest_depth([-1.0, -1.0, -9.0], [1.0, 1.0, -4.0], eye, fwd),
            4.0
        );
        // A box around the eye: behind it, clamped by the caller.
        assert!(nearest_depth([-1.0; 3], [1.0; 3], eye, fwd) < 0.0);
        let scene = persp(vec![square(0.0, 0)], &[Blend::Opaque]);
        assert_eq!(runs(&scene, DrawOrder::FrontToBackDraw).0.len(), 1);
    }
}
