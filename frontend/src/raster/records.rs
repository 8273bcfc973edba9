//! A tile's trace records: one warp per surviving fragment in
//! rasterization order, each with its shader's ALU runs and texture
//! blocks, and the counts of quads Early-Z rejected between them.

use super::*;

/// The trace records of the tile `b` holds: one warp per fragment, in
/// rasterization order (the order [`raster_tile`] produced them), as a
/// one-tile trace with `header`'s frame; counts its quad positions.
pub(super) fn build_tile(
    ctx: &TileCtx,
    header: &TraceHeader,
    tx: u32,
    ty: u32,
    b: &mut TileBuf,
) -> Result<Option<Trace>, crate::trace::Problem> {
    b.positions = 0;
    if b.frags.is_empty() && b.rej_since == 0 {
        return Ok(None);
    }
    let side = ctx.tile / 2;
    let mut builder = Trace::builder(header.clone())?;
    builder.begin_tile(tx, ty)?;
    let entries: usize = b
        .frags
        .iter()
        .map(|f| ctx.mats[f.material as usize].shader.len())
        .sum();
    builder.reserve(b.frags.len(), entries, b.pool.len());
    for f in &b.frags {
        if !b.seen[f.pos as usize] {
            b.seen[f.pos as usize] = true;
            b.positions += 1;
        }
        if f.rej > 0 {
            builder.rejected(f.rej)?;
        }
        builder.begin_quad(f.pos % side, f.pos / side)?;
        let mut r = f.range as usize;
        for op in &ctx.mats[f.material as usize].shader {
            match op {
                ShaderOp::Alu(0) => {}
                ShaderOp::Alu(n) => builder.alu(*n)?,
                ShaderOp::Tex(_) => {
                    let (start, len, tri) = b.ranges[r];
                    r += 1;
                    builder.tex_filtered(&b.pool[start as usize..(start + len) as usize], tri)?;
                }
            }
        }
    }
    for f in &b.frags {
        b.seen[f.pos as usize] = false;
    }
    if b.rej_since > 0 {
        builder.rejected(b.rej_since)?;
    }
    builder.end_tile()?;
    builder.finish().map(Some)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::fixtures::*;

    #[test]
    fn warps_come_in_rasterization_order() {
        // Two overlapping opaque squares (orthographic, the second nearer):
        // the tile's warps are all quads of the first square's triangles in
        // scanline order per triangle, then the second square's.
        let scene = ortho_scene(
            vec![
                quad_mesh(0.0, 0.0, 16.0, 16.0, 0.0, 0),
                quad_mesh(8.0, 8.0, 24.0, 24.0, 1.0, 1),
            ],
            vec![mat("a", Blend::Opaque, 0), mat("b", Blend::Opaque, 0)],
            32.0,
            32.0,
        );
        let f = rasterize(&scene, 32, 32, &RasterOptions::default()).unwrap();
        let tile = &f.trace.tiles()[0];
        let pos: Vec<(u32, u32)> = tile.quads().map(|q| (q.x(), q.y())).collect();
        // Square a: 8x8 quads plus 8 on the shared diagonal; square b the
        // same, 16 of its positions over a's.
        assert_eq!(pos.len(), 2 * (64 + 8));
        assert_eq!(f.stats.positions, 64 + 64 - 16);
        // Each triangle's quads are in scanline order; where the order goes
        // back, a new triangle starts: 4 triangles, 4 runs.
        let runs = 1 + pos
            .windows(2)
            .filter(|w| (w[1].1, w[1].0) <= (w[0].1, w[0].0))
            .count();
        assert_eq!(runs, 4);
        // Square a's warps (quads 0..8) all come before square b's (4..12).
        assert!(pos[..72].iter().all(|&(x, y)| x < 8 && y < 8));
        let in_b = |v: u32| (4..12).contains(&v);
        assert!(pos[72..].iter().all(|&(x, y)| in_b(x) && in_b(y)));
        // Threads do not change the trace.
        for threads in [1, 3] {
            let g = rasterize(
                &scene,
                32,
                32,
                &RasterOptions {
                    threads,
                    ..RasterOptions::default()
                },
            )
            .unwrap();
            assert_eq!(g.trace.to_text(), f.trace.to_text());
        }
    }

    #[test]
    fn rejected_quads_sit_between_the_warps_they_were_rasterized_between() {
        // One 64x64 tile: a near left half, a far square hidden behind it,
        // then a right half nothing hides.
        let scene = ortho_scene(
            vec![
                quad_mesh(0.0, 0.0, 32.0, 64.0, 1.0, 0),
                quad_mesh(4.0, 4.0, 20.0, 20.0, 0.0, 1),
                quad_mesh(32.0, 0.0, 64.0, 64.0, 0.5, 2),
            ],
            vec![
                mat("near", Blend::Opaque, 0),
                mat("hidden", Blend::Opaque, 0),
                mat("right", Blend::Opaque, 0),
            ],
            64.0,
            64.0,
        );
        let f = rasterize(&scene, 64, 64, &RasterOptions::default()).unwrap();
        let m = &f.stats.materials;
        assert_eq!(m[1].warps, 0, "the far square is hidden");
        let hidden = m[1].quads_rejected_early_z;
        assert!(hidden >= 64, "{hidden}");
        assert_eq!(f.stats.quads_rejected_early_z, hidden);
        let tile = &f.trace.tiles()[0];
        assert_eq!(tile.quad_count() as u64, m[0].warps + m[2].warps);
        let first = m[0].warps as usize;
        for i in 0..tile.quad_count() {
            let want = if i == first { hidden } else { 0 };
            assert_eq!(u64::from(tile.rejected_before(i)), want, "quad {i}");
        }
        assert_eq!(tile.rejected_after_last(), 0);
        assert_eq!(tile.raster_count(), f.stats.quads_covered);
        assert!(f.trace.to_text().contains(&format!("\nz {hidden}\nq ")));
    }

    #[test]
    fn a_tile_whose_every_quad_is_rejected_is_a_record_without_warps() {
        // (Raster order makes this rare: the first fragment drawn at a
        // pixel passes the depth test. The record must still be written.)
        let textures = TextureSet::new(&[]);
        let ctx = TileCtx {
            setups: &[],
            mats: &[],
            textures: &textures,
            tile: 64,
            width: 128,
            height: 64,
            colour: false,
            prepass: false,
            hiz: true,
            maps: false,
        };
        let header = TraceHeader::new("w", 128, 64, 64);
        let mut b = TileBuf::new(64, 0);
        assert!(build_tile(&ctx, &header, 1, 0, &mut b).unwrap().is_none());
        b.rej_since = 37;
        let t = build_tile(&ctx, &header, 1, 0, &mut b)
            .unwrap()
            .expect("a record");
        let tile = &t.tiles()[0];
        assert_eq!((tile.tx(), tile.ty(), tile.quad_count()), (1, 0, 0));
        assert_eq!(tile.rejected_after_last(), 37);
        assert_eq!((tile.rejected_count(), tile.raster_count()), (37, 37));
        assert!(t.to_text().ends_with("\ntile 1 0\nz 37\nend\n"));
        assert_eq!(b.positions, 0);
    }
}
