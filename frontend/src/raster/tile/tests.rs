//! Tests of a tile's raster pipeline: Early-Z against opaque and blended
//! quads, alpha-tested texels without depth, the coarse test's rejections,
//! and per-draw scissor, culling, depth and clear states.

use super::*;
use crate::raster::fixtures::*;
use crate::{Material, Mesh};

#[test]
fn early_z_rejects_hidden_quads_but_blended_sprites_do_not() {
    // Perspective: a near opaque square drawn first hides a far one.
    let persp = |meshes: Vec<Mesh>, materials: Vec<Material>| Scene {
        name: "test:persp".into(),
        source: "unit test".into(),
        meshes,
        materials,
        textures: vec![checker("c", 64)],
        camera: look_down_z(60.0, 0.1, 100.0),
    };
    let near = quad_mesh(-5.0, -5.0, 5.0, 5.0, -2.0, 0);
    let far = quad_mesh(-1.0, -1.0, 1.0, 1.0, -10.0, 1);
    let scene = persp(
        vec![near.clone(), far.clone()],
        vec![mat("near", Blend::Opaque, 0), mat("far", Blend::Opaque, 0)],
    );
    let f = rasterize(&scene, 128, 128, &RasterOptions::default()).unwrap();
    assert!(f.stats.quads_rejected_early_z > 0);
    assert_eq!(
        f.stats.materials[1].quads_rejected_early_z,
        f.stats.quads_rejected_early_z
    );
    assert_eq!(f.stats.materials[1].warps, 0, "far square hidden");
    // The trace records every rejected quad where it was rasterized:
    // the far square is drawn last, so after each tile's warps.
    assert_eq!(f.trace.rejected_count(), f.stats.quads_rejected_early_z);
    for t in f.trace.tiles() {
        assert_eq!(u64::from(t.rejected_after_last()), t.rejected_count());
    }
    assert_eq!(f.stats.positions, 64 * 64);
    // The near square's two triangles share a diagonal: the 64 quads it
    // crosses hold one fragment of each, two warps.
    assert_eq!(f.stats.warps, f.stats.positions + 64);
    assert_eq!(f.trace.quad_count() as u64, f.stats.warps);
    assert_eq!(f.trace.stats().positions, f.stats.positions);
    // The same far square, but the near one alpha-blended: both shade.
    let scene = persp(
        vec![near, far],
        vec![
            mat("near", Blend::AlphaBlend, 0),
            mat("far", Blend::Opaque, 0),
        ],
    );
    let g = rasterize(&scene, 128, 128, &RasterOptions::default()).unwrap();
    assert_eq!(g.stats.quads_rejected_early_z, 0);
    let far_quads = g.stats.materials[1].warps;
    assert!(far_quads > 0);
    assert_eq!(g.stats.materials[0].warps, f.stats.warps);
    assert_eq!(g.stats.positions, 64 * 64);
    assert_eq!(g.stats.warps, f.stats.warps + far_quads);
    // Where the sprite covers the far square, the position holds two
    // warps of one 11-instruction program each (never merged): the far
    // square's first (opaque, drawn first), then the sprite's
    // (blended, drawn last).
    let tile = g
        .trace
        .tiles()
        .iter()
        .find(|t| t.tx() == 0 && t.ty() == 0)
        .unwrap();
    let at: Vec<_> = tile.quads_at(31, 31).collect();
    assert_eq!(at.len(), 2);
    for q in &at {
        assert_eq!((q.instr_count(), q.tex_count()), (11, 1));
    }
    assert!(at[0].index() < at[1].index());
}

#[test]
fn alpha_tested_texels_below_half_write_no_depth() {
    let mut tex = checker("c", 8);
    for px in tex.rgba.chunks_exact_mut(4) {
        px[3] = 0; // fully cut out
    }
    let mut scene = ortho_scene(
        vec![
            quad_mesh(0.0, 0.0, 32.0, 32.0, 1.0, 0),
            quad_mesh(0.0, 0.0, 32.0, 32.0, 0.0, 1),
        ],
        vec![
            mat("cutout", Blend::AlphaTest, 0),
            mat("behind", Blend::Opaque, 0),
        ],
        32.0,
        32.0,
    );
    scene.textures = vec![tex];
    let f = rasterize(&scene, 32, 32, &RasterOptions::default()).unwrap();
    assert_eq!(f.stats.quads_rejected_early_z, 0);
    // 256 quads each, plus the 16 quads on each square's diagonal.
    assert_eq!(f.stats.materials[0].warps, 16 * 16 + 16);
    assert_eq!(f.stats.materials[1].warps, 16 * 16 + 16);
    assert_eq!(f.stats.positions, 16 * 16);
    assert_eq!(f.stats.warps, 2 * (16 * 16 + 16));
    // With an opaque texture the cut-out hides the square behind.
    for px in scene.textures[0].rgba.chunks_exact_mut(4) {
        px[3] = 255;
    }
    let g = rasterize(&scene, 32, 32, &RasterOptions::default()).unwrap();
    assert_eq!(g.stats.materials[1].warps, 0);
}

#[test]
fn hidden_triangles_are_rejected_coarsely_and_visible_ones_are_not() {
    let persp = |meshes: Vec<Mesh>| Scene {
        name: "test:hiz".into(),
        source: "unit test".into(),
        meshes,
        materials: vec![
            mat("near", Blend::Opaque, 0),
            mat("far", Blend::Opaque, 0),
            mat("nearer", Blend::Opaque, 0),
            mat("tie", Blend::Opaque, 0),
        ],
        textures: vec![checker("c", 64)],
        camera: look_down_z(60.0, 0.1, 100.0),
    };
    // The near square fills the frame; the far one behind it is
    // hidden, the tie (the near square again: a later triangle at the
    // same depth wins) and then the nearer one in front are not.
    let near = quad_mesh(-5.0, -5.0, 5.0, 5.0, -2.0, 0);
    let far = quad_mesh(-1.0, -1.0, 1.0, 1.0, -10.0, 1);
    let nearer = quad_mesh(-0.5, -0.5, 0.5, 0.5, -1.5, 2);
    let tie = Mesh {
        material: 3,
        ..near.clone()
    };
    let scene = persp(vec![near, far, tie, nearer]);
    let f = rasterize(&scene, 128, 128, &RasterOptions::default()).unwrap();
    let m = &f.stats.materials;
    assert!(m[1].quads_rejected_early_z > 0);
    assert_eq!(m[1].warps, 0);
    assert!(m[2].warps > 0 && m[3].warps > 0);
    assert_eq!(m[2].quads_rejected_early_z, 0);
    assert_eq!(m[3].quads_rejected_early_z, 0);
    assert_eq!(m[3].warps, m[0].warps);
    assert_eq!(
        f.stats.quads_rejected_hiz, m[1].quads_rejected_early_z,
        "every hidden quad of the far square, nothing else, rejected coarsely"
    );
    let g = rasterize_with(&scene, 128, 128, &RasterOptions::default(), false).unwrap();
    assert_eq!(trace_bytes(&f), trace_bytes(&g));
    assert_eq!(
        g.stats.quads_rejected_early_z,
        f.stats.quads_rejected_early_z
    );
}

/// A scene in clip space (w = 1): `quads` of (NDC rectangle, z, state)
/// each its own material, drawn in order.
fn clip_scene(quads: &[([f32; 4], f32, crate::DrawState)]) -> Scene {
    let mut meshes = Vec::new();
    let mut materials = Vec::new();
    for (i, (r, z, st)) in quads.iter().enumerate() {
        // Counter-clockwise in NDC (y up).
        meshes.push(quad_mesh(r[0], r[1], r[2], r[3], *z, i));
        let mut mt = mat("q", Blend::Opaque, 0);
        mt.state = Some(*st);
        materials.push(mt);
    }
    Scene {
        name: "test:clip".into(),
        source: "unit test".into(),
        meshes,
        materials,
        textures: vec![checker("c", 64)],
        camera: Camera::Clip,
    }
}

#[test]
fn per_draw_states_decide_scissor_culling_depth_and_clears() {
    use crate::{Compare, Cull, DrawState};
    let opaque = DrawState::for_blend(Blend::Opaque);
    let all = [-1.0, -1.0, 1.0, 1.0];
    let opts = RasterOptions {
        threads: 1,
        ..Default::default()
    };
    let run =
        |q: &[([f32; 4], f32, DrawState)]| rasterize(&clip_scene(q), 32, 32, &opts).unwrap().stats;
    // A scissor of pixels 3..9 x 5..6 (odd edges): exactly 6 pixels.
    let sc = DrawState {
        scissor: Some([3, 5, 9, 6]),
        ..opaque
    };
    let st = run(&[(all, 0.0, sc)]);
    assert_eq!(st.pixels_shaded, 6);
    assert_eq!(st.positions, 4, "quads at columns 2, 4, 6, 8");
    // Back faces culled: the counter-clockwise quad stays, a clockwise
    // front face setting culls it.
    let back = DrawState {
        cull: Cull::Back,
        ..opaque
    };
    assert_eq!(run(&[(all, 0.0, back)]).pixels_shaded, 32 * 32);
    let cw = DrawState {
        front_ccw: false,
        ..back
    };
    let st = run(&[(all, 0.0, cw)]);
    assert_eq!((st.pixels_shaded, st.culled_back_faces), (0, 2));
    // A near square then a far one: rejected by GL_LESS, not after a
    // depth clear between them, nor with the far one's depth range
    // pulled in front, nor with a large negative polygon offset.
    let far = |st: DrawState| run(&[(all, -0.5, opaque), (all, 0.5, st)]);
    let less = DrawState {
        depth_test: Some(Compare::Less),
        ..opaque
    };
    assert_eq!(far(less).quads_rejected_early_z, 16 * 16 + 16);
    let cleared = DrawState {
        depth_epoch: 1,
        ..less
    };
    assert_eq!(far(cleared).quads_rejected_early_z, 0);
    let range = DrawState {
        depth_range: Some([0.0, 0.1]),
        ..less
    };
    assert_eq!(far(range).quads_rejected_early_z, 0);
    let offset = DrawState {
        polygon_offset: Some((0.0, -16_777_216.0 * 0.6)),
        ..less
    };
    assert_eq!(far(offset).quads_rejected_early_z, 0);
    // A far square (0.9) rejected coarsely sets the coarse bound to
    // 0.25; GL_GREATER then writes a farther depth (0.75): the bound
    // follows, so a square between the two (0.5) passes everywhere,
    // none of it rejected on the old bound.
    let greater = DrawState {
        depth_test: Some(Compare::Greater),
        ..opaque
    };
    let mid = DrawState {
        depth_test: Some(Compare::LEqual),
        ..opaque
    };
    let st = run(&[
        (all, -0.5, opaque),
        (all, 0.8, mid),
        (all, 0.5, greater),
        (all, 0.0, mid),
    ]);
    assert_eq!(st.materials[1].quads_rejected_early_z, 16 * 16 + 16);
    assert_eq!(st.materials[2].quads_rejected_early_z, 0);
    assert_eq!(st.materials[3].quads_rejected_early_z, 0);
    assert_eq!(st.materials[3].warps, 16 * 16 + 16);
}
