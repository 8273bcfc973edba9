//! Synthetic workloads: traces generated from a simple model of texture
//! mapping, so the cycle model can run before real scenes exist.
//!
//! Every generated trace names itself `synthetic:texmap ...` and carries its
//! full [`GenParams`] (as JSON) and its measured statistics in header notes.
//! The parameters state *inputs* of the model (texel scale, memory-instruction
//! ratio, ...); block reuse and CF *follow* from them and are measured on the
//! generated trace ([`GenReport`]), never claimed.
//!
//! # The model
//!
//! * **Geometry.** The frame is cut into *surfaces*: the Voronoi cells of
//!   random sites, about `surface_size` pixels across, with straight edges
//!   between them, as between the triangles of different draw calls. A
//!   quad belongs to the surface nearest its centre; each surface has its
//!   own material.
//! * **Coverage.** Objects stand against an unshaded background: a smooth
//!   random field (two octaves of value noise with features about
//!   `blob_size` pixels across) is thresholded so that exactly
//!   round(`coverage` x quads of the frame) quads are shaded. Tiles along
//!   silhouettes are partially covered; tiles with no shaded quad are not
//!   emitted. Quads whose top-left pixel lies outside the frame (the right
//!   and bottom tile edges when the frame is not a multiple of the tile)
//!   never exist.
//! * **Texture mapping.** A material maps screen pixels to texel
//!   coordinates by a projective map around its site: scale (texels per
//!   pixel) `texel_scale` x 2^U(-spread/2, spread/2), a rotation uniform in
//!   +-`max_rotation_deg`, a perspective divide w = 1 + g . (pixel - site)
//!   with |g| = `perspective` / frame diagonal (so w stays within
//!   1 +- `perspective` and the local scale varies with it), and a random
//!   texel offset.
//!   A material has `textures_per_material` textures sharing that map; the
//!   first (base) at the material's scale, the others at `secondary_scale`
//!   times it (1/16: lightmap-like; 1: a normal or specular map).
//! * **Texture layout.** A texture is `texture_size` texels square, RGBA8,
//!   with a full mip chain. Each level is block-linear: 4x4-texel blocks of
//!   64 bytes, stored in Morton (Z) order of block coordinates, like the
//!   swizzled layouts GPUs use, so that a screen region maps to nearby
//!   blocks spread evenly over cache sets. Textures lie one after another from block
//!   [`TEXTURE_HEAP_BASE_BLOCK`], each starting on a 64 KiB boundary.
//!   Addressing wraps (repeat).
//! * **Filtering.** Bilinear: each of a quad's 4 pixels samples at its
//!   centre and touches the 2x2 texels around the sample point. With
//!   `mipmaps`, the quad picks the nearest mip level to log2 of its texel
//!   footprint per pixel (measured across the quad, as hardware does), so
//!   minified textures fetch from a coarser level. A texture instruction
//!   touches the distinct blocks holding those 16 texels: typically 1 to 4.
//! * **Shaders.** A material's program has about `instrs_per_quad`
//!   instructions (+-25 %), of which k are texture instructions, spread at
//!   random among the ALU instructions. k is chosen per material, largest
//!   surfaces first, so that the trace's running memory-instruction ratio
//!   (weighted by each material's quads) stays closest to `mem_ratio`.
//!   Texture instruction j samples texture j mod `textures_per_material`;
//!   repeats sample the same texture 1.5 texels further along a fixed
//!   direction (a second filter tap).
//! * **Order.** Tiles in Z-order (Morton order of tile coordinates), quads
//!   in scanline order within a tile, as the front end emits them.
//!
//! Generation is deterministic: a [`GenParams`] (seed included) gives the
//! same trace on every platform (the generator avoids the platform's libm,
//! see `synth/math.rs`).

use crate::rng::Rng;
use crate::trace::z_order;
use crate::trace::{Trace, TraceHeader};
use std::f64::consts::PI;

mod material;
mod math;
mod params;
mod report;

use material::{Material, Texture};
use math::{exp2, noise, sin_cos};
pub use params::{GenError, GenParams};
pub use report::GenReport;

/// First block number of the texture heap (byte address 64 MiB).
pub const TEXTURE_HEAP_BASE_BLOCK: u64 = (64 << 20) / 64;

/// Most quads a generated frame may have (the generator keeps a few words
/// per quad of the frame in memory).
pub const MAX_GEN_QUADS: u64 = 1 << 24;

/// Generates the synthetic trace described by `p`: the quads the frame
/// covers, the surfaces (Voronoi cells) that own them, a material per
/// surface, then the trace.
pub fn generate(p: &GenParams) -> Result<Trace, GenError> {
    p.validate()?;
    let grid = Grid::of(p);
    let present = covered(p, &grid);
    let (sites, owner, quads_of) = surfaces(p, &grid, &present);
    let materials = make_materials(p, &sites, &quads_of);
    let mut trace = emit(p, &grid, &present, &owner, &materials)?;
    let s = trace.stats();
    trace.push_note(format!(
        " measured: mem-instr ratio {:.4}, block reuse in tile {:.3}, CF {:.3}, \
         Min_Estimate1 {:.4}, Min_Estimate2 {:.4}, coverage {:.4}, warps {}",
        s.mem_instr_ratio, s.reuse, s.cf, s.min_estimate1, s.min_estimate2, s.coverage, s.warps
    ))?;
    Ok(trace)
}

/// The frame's quads: `qw` x `qh`, quad `i` at (`i % qw`, `i / qw`).
struct Grid {
    qw: usize,
    qh: usize,
}

impl Grid {
    fn of(p: &GenParams) -> Self {
        Grid {
            qw: p.frame_w.div_ceil(2) as usize,
            qh: p.frame_h.div_ceil(2) as usize,
        }
    }

    fn quads(&self) -> usize {
        self.qw * self.qh
    }

    /// The pixel centre of quad `i`.
    fn centre(&self, i: usize) -> (f64, f64) {
        let (gx, gy) = (i % self.qw, i / self.qw);
        (2.0 * gx as f64 + 1.0, 2.0 * gy as f64 + 1.0)
    }
}

/// Coverage: the round(coverage x N) quads with the highest noise value
/// (ties broken by index, so the set does not depend on the sort).
fn covered(p: &GenParams, grid: &Grid) -> Vec<bool> {
    let n_quads = grid.quads();
    let mut present = vec![true; n_quads];
    if p.coverage < 1.0 {
        let noise_seed = Rng::with_stream(p.seed, 1).next_u64();
        let mut keyed: Vec<(f64, usize)> = (0..n_quads)
            .map(|i| {
                let (x, y) = grid.centre(i);
                (noise(noise_seed, x, y, f64::from(p.blob_size)), i)
            })
            .collect();
        keyed.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
        let keep = ((p.coverage * n_quads as f64).round() as usize).clamp(1, n_quads);
        present.iter_mut().for_each(|x| *x = false);
        for &(_, i) in &keyed[..keep] {
            present[i] = true;
        }
    }
    present
}

/// Surfaces: Voronoi cells of random sites. Returns the sites, the site
/// that owns each quad, and the quads each site owns.
fn surfaces(p: &GenParams, grid: &Grid, present: &[bool]) -> (Vec<(f64, f64)>, Vec<u32>, Vec<u64>) {
    let (w, h) = (p.frame_w, p.frame_h);
    let area = f64::from(w) * f64::from(h);
    let edge = f64::from(p.surface_size);
    let n_sites = ((area / (edge * edge)).round() as usize).clamp(1, 4096);
    let mut site_rng = Rng::with_stream(p.seed, 2);
    let sites: Vec<(f64, f64)> = (0..n_sites)
        .map(|_| {
            (
                site_rng.range_f64(0.0, f64::from(w)),
                site_rng.range_f64(0.0, f64::from(h)),
            )
        })
        .collect();
    let mut owner = vec![0u32; grid.quads()];
    let mut quads_of = vec![0u64; n_sites];
    for (i, o) in owner.iter_mut().enumerate() {
        if !present[i] {
            continue;
        }
        let (x, y) = grid.centre(i);
        let mut best = (f64::INFINITY, 0usize);
        for (s, &(sx, sy)) in sites.iter().enumerate() {
            let d = (x - sx) * (x - sx) + (y - sy) * (y - sy);
            if d < best.0 {
                best = (d, s);
            }
        }
        *o = best.1 as u32;
        quads_of[best.1] += 1;
    }
    (sites, owner, quads_of)
}

/// The trace: tiles in Z-order, quads in scanline order, each running its
/// surface's material.
fn emit(
    p: &GenParams,
    grid: &Grid,
    present: &[bool],
    owner: &[u32],
    materials: &[Material],
) -> Result<Trace, GenError> {
    let (qw, qh) = (grid.qw, grid.qh);
    let mut header = TraceHeader::new(p.workload_name(), p.frame_w, p.frame_h, p.tile);
    header.notes = vec![
        " synthetic workload: generated by wasp-sim synth (texture-mapping model: \
         Voronoi surfaces, block-linear Morton-swizzled RGBA8 textures, bilinear)"
            .to_string(),
        format!(
            " generator-params {}",
            serde_json::to_string(p).map_err(|e| GenError(e.to_string()))?
        ),
    ];
    let mut b = Trace::builder(header)?;
    let side = p.tile / 2;
    let mut blocks = Vec::with_capacity(16);
    for (tx, ty) in z_order(b.header().tiles_x(), b.header().tiles_y()) {
        let mut open = false;
        for y in 0..side {
            let gy = (ty * side + y) as usize;
            if gy >= qh {
                break;
            }
            for x in 0..side {
                let gx = (tx * side + x) as usize;
                if gx >= qw {
                    break;
                }
                let i = gy * qw + gx;
                if !present[i] {
                    continue;
                }
                if !open {
                    b.begin_tile(tx, ty)?;
                    open = true;
                }
                b.begin_quad(x, y)?;
                let mat = &materials[owner[i] as usize];
                let (px, py) = (2.0 * gx as f64, 2.0 * gy as f64);
                let mut j = 0;
                for op in &mat.program {
                    match op {
                        Some(n) => b.alu(*n)?,
                        None => {
                            mat.tex_blocks(j, px, py, p.mipmaps, &mut blocks);
                            b.tex(&blocks)?;
                            j += 1;
                        }
                    }
                }
            }
        }
        if open {
            b.end_tile()?;
        }
    }
    Ok(b.finish()?)
}

fn make_materials(p: &GenParams, sites: &[(f64, f64)], quads_of: &[u64]) -> Vec<Material> {
    let (fw, fh) = (f64::from(p.frame_w), f64::from(p.frame_h));
    let diag = (fw * fw + fh * fh).sqrt();
    let size = p.texture_size;
    let tpm = p.textures_per_material as usize;
    // Textures one after another, each on a 64 KiB (1024-block) boundary.
    let stride = Texture::new(0, size).total_blocks().div_ceil(1024) * 1024;
    let mut materials: Vec<Material> = sites
        .iter()
        .enumerate()
        .map(|(s, &(cx, cy))| {
            let mut r = Rng::with_stream(p.seed, 1000 + s as u64);
            let scale = p.texel_scale * exp2(r.range_f64(-0.5, 0.5) * p.texel_scale_spread);
            let theta = r.range_f64(-p.max_rotation_deg, p.max_rotation_deg) * (PI / 180.0);
            let (sin, cos) = sin_cos(theta);
            let (phi_sin, phi_cos) = sin_cos(r.range_f64(-PI, PI));
            let (tap_sin, tap_cos) = sin_cos(r.range_f64(-PI, PI));
            let g = p.perspective / diag;
            let textures = (0..tpm)
                .map(|t| {
                    let index = (s * tpm + t) as u64;
                    Texture::new(TEXTURE_HEAP_BASE_BLOCK + index * stride, size)
                })
                .collect();
            let tex_scale = (0..tpm)
                .map(|t| if t == 0 { 1.0 } else { p.secondary_scale })
                .collect();
            Material {
                cx,
                cy,
                m: [scale * cos, -scale * sin, scale * sin, scale * cos],
                g: [g * phi_cos, g * phi_sin],
                u0: r.range_f64(0.0, f64::from(size)),
                v0: r.range_f64(0.0, f64::from(size)),
                tap: [tap_cos, tap_sin],
                textures,
                tex_scale,
                program: Vec::new(),
            }
        })
        .collect();

    // Programs: lengths first, then texture counts, largest surfaces first,
    // keeping the quad-weighted running ratio closest to mem_ratio.
    let lens: Vec<u32> = (0..sites.len())
        .map(|s| {
            let mut r = Rng::with_stream(p.seed, 500_000 + s as u64);
            let n = f64::from(p.instrs_per_quad) * r.range_f64(0.75, 1.25);
            (n.round() as u32).max(1)
        })
        .collect();
    let mut order: Vec<usize> = (0..sites.len()).collect();
    order.sort_by_key(|&s| (std::cmp::Reverse(quads_of[s]), s));
    let (mut tex_sum, mut all_sum) = (0.0f64, 0.0f64);
    for s in order {
        let n = lens[s];
        let q = quads_of[s].max(1) as f64;
        let k = (0..=n)
            .min_by(|&a, &b| {
                let err = |k: u32| {
                    ((tex_sum + f64::from(k) * q) / (all_sum + f64::from(n) * q) - p.mem_ratio)
                        .abs()
                };
                err(a).total_cmp(&err(b))
            })
            .unwrap_or(0);
        if quads_of[s] > 0 {
            tex_sum += f64::from(k) * q;
            all_sum += f64::from(n) * q;
        }
        let mut r = Rng::with_stream(p.seed, 1_000_000 + s as u64);
        materials[s].program = program(n, k, &mut r);
    }
    materials
}

/// A program of `n` instructions, `k` of them texture instructions, with
/// the n - k ALU instructions scattered at random over the k + 1 gaps.
fn program(n: u32, k: u32, r: &mut Rng) -> Vec<Option<u32>> {
    let mut gaps = vec![0u32; k as usize + 1];
    for _ in 0..(n - k) {
        gaps[r.below(u64::from(k) + 1) as usize] += 1;
    }
    let mut prog = Vec::new();
    for (i, &g) in gaps.iter().enumerate() {
        if g > 0 {
            prog.push(Some(g));
        }
        if i < k as usize {
            prog.push(None);
        }
    }
    prog
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::trace::morton;

    fn small(seed: u64) -> GenParams {
        GenParams {
            frame_w: 512,
            frame_h: 256,
            seed,
            ..GenParams::default()
        }
    }

    #[test]
    fn deterministic_for_a_seed() {
        let a = generate(&small(5)).unwrap();
        let b = generate(&small(5)).unwrap();
        let c = generate(&small(6)).unwrap();
        assert_eq!(a, b);
        assert_ne!(a, c);
    }

    #[test]
    fn names_itself_synthetic_and_round_trips() {
        let p = small(3);
        let t = generate(&p).unwrap();
        assert!(t.header().workload.starts_with("synthetic:texmap "));
        assert!(t.header().workload.contains("seed=3"));
        let json = t.header().notes[1]
            .trim_start()
            .strip_prefix("generator-params ")
            .unwrap();
        let back: GenParams = serde_json::from_str(json).unwrap();
        assert_eq!(back, p);
        let again = Trace::parse(&t.to_text(), "synth").unwrap();
        assert_eq!(again, t);
    }

    #[test]
    fn quads_in_range_and_coverage_as_requested() {
        let mut p = small(2);
        p.frame_w = 300; // partial tiles at the right and bottom edges
        p.frame_h = 170;
        p.coverage = 0.6;
        let t = generate(&p).unwrap();
        let h = t.header();
        for tile in t.tiles() {
            assert!(tile.tx() < h.tiles_x() && tile.ty() < h.tiles_y());
            assert!(tile.quad_count() > 0);
            for q in tile.quads() {
                assert!(q.x() < 32 && q.y() < 32);
                assert!(h.quad_in_frame(tile.tx(), tile.ty(), q.x(), q.y()));
            }
        }
        let expected = (0.6 * h.frame_quads() as f64).round() as usize;
        assert_eq!(t.quad_count(), expected);
        // Silhouettes cut some tiles.
        assert!(t
            .tiles()
            .iter()
            .any(|tile| tile.quad_count() < 1024 && tile.tx() < 4));
        // Tiles in Z-order.
        let order: Vec<(u32, u32)> = t.tiles().iter().map(|t| (t.tx(), t.ty())).collect();
        let mut z = order.clone();
        z.sort_by_key(|&(x, y)| morton(x, y));
        assert_eq!(order, z);
    }

    #[test]
    fn memory_ratio_close_to_request_over_a_large_trace() {
        for (mem, instrs) in [(0.07, 12), (0.15, 10), (0.26, 8), (0.0, 10)] {
            let p = GenParams {
                frame_w: 1024,
                frame_h: 512,
                mem_ratio: mem,
                instrs_per_quad: instrs,
                ..GenParams::default()
            };
            let s = generate(&p).unwrap().stats();
            assert!(
                (s.mem_instr_ratio - mem).abs() < 0.01,
                "requested {mem}, got {}",
                s.mem_instr_ratio
            );
            let ipw = s.instrs_per_warp;
            assert!(
                (ipw - f64::from(instrs)).abs() < 0.3 * f64::from(instrs),
                "{ipw}"
            );
        }
    }

    fn reuse_at(scale: f64, mipmaps: bool) -> f64 {
        let p = GenParams {
            texel_scale: scale,
            mipmaps,
            ..small(4)
        };
        generate(&p).unwrap().stats().reuse
    }

    #[test]
    fn reuse_increases_as_texel_scale_decreases() {
        let with_mips: Vec<f64> = [1.0, 0.5, 0.25]
            .iter()
            .map(|&s| reuse_at(s, true))
            .collect();
        assert!(with_mips.windows(2).all(|w| w[0] < w[1]), "{with_mips:?}");
        let no_mips: Vec<f64> = [4.0, 2.0, 1.0]
            .iter()
            .map(|&s| reuse_at(s, false))
            .collect();
        assert!(no_mips.windows(2).all(|w| w[0] < w[1]), "{no_mips:?}");
        // Mipmapping keeps minified textures from losing all reuse.
        assert!(reuse_at(4.0, true) > 2.0 * reuse_at(4.0, false));
    }

    #[test]
    fn cf_plausible_at_one_texel_per_pixel_bilinear() {
        // One texture, one texel per pixel: a quad's texture instruction
        // spans 3 texels per axis, so 1.5 blocks per axis when aligned.
        let p = GenParams {
            textures_per_material: 1,
            texel_scale: 1.0,
            texel_scale_spread: 0.0,
            perspective: 0.0,
            max_rotation_deg: 0.0,
            ..small(8)
        };
        let s = generate(&p).unwrap().stats();
        // Exactly 3x3 texels per instruction when aligned: 1.5 x 1.5 blocks
        // on average over the sub-block offsets.
        let per_instr = s.block_accesses as f64 / s.tex_instrs as f64;
        assert!(
            (per_instr - 2.25).abs() < 0.05,
            "aligned blocks/instr {per_instr}"
        );
        // Per warp a bit more: a second texture instruction samples 1.5
        // texels away.
        assert!((2.2..2.8).contains(&s.cf), "aligned CF {}", s.cf);
        let rotated = GenParams {
            max_rotation_deg: 180.0,
            ..p
        };
        let s = generate(&rotated).unwrap().stats();
        assert!((2.2..3.2).contains(&s.cf), "rotated CF {}", s.cf);
        // Every texture instruction touches 1 to 16 blocks.
        let t = generate(&rotated).unwrap();
        for tile in t.tiles() {
            for q in tile.quads() {
                for i in q.instrs() {
                    if let crate::trace::Instr::Tex(b) = i {
                        assert!((1..=16).contains(&b.len()));
                    }
                }
            }
        }
    }

    #[test]
    fn target_reuse_is_searched_and_reported() {
        let base = GenParams {
            frame_w: 256,
            frame_h: 128,
            ..GenParams::default()
        };
        let (p, probe_reuse) = base.with_target_reuse(15.0).unwrap();
        assert!((probe_reuse - 15.0).abs() < 1.0, "{probe_reuse}");
        let report = GenReport::new(&p, &generate(&p).unwrap());
        assert!((report.measured.reuse - probe_reuse).abs() < 1e-9);
        assert!(report.to_string().contains("block reuse in tile"));
        // Out of reach: the scale stops at a bound.
        let (p, r) = base.with_target_reuse(1e6).unwrap();
        assert_eq!(p.texel_scale, 1.0 / 64.0);
        assert!(r < 1e6);
    }

    #[test]
    fn invalid_parameters_are_rejected() {
        let bad = |f: fn(&mut GenParams)| {
            let mut p = GenParams::default();
            f(&mut p);
            generate(&p).unwrap_err()
        };
        bad(|p| p.coverage = 0.0);
        bad(|p| p.mem_ratio = 1.5);
        bad(|p| p.texel_scale = f64::NAN);
        bad(|p| p.texture_size = 1000);
        bad(|p| p.perspective = 1.0);
        bad(|p| p.tile = 63);
        bad(|p| p.textures_per_material = 0);
        bad(|p| {
            p.frame_w = 65536;
            p.frame_h = 4096;
        });
        let e = bad(|p| p.instrs_per_quad = 0);
        assert!(e.to_string().contains("instrs_per_quad"));
    }

    #[test]
    fn texture_layout_is_morton_block_linear() {
        let t = Texture::new(1000, 16);
        // Level 0: 4x4 blocks; texel (5, 2) is in block (1, 0) -> Morton 1.
        assert_eq!(t.block(0, 5, 2), 1001);
        assert_eq!(t.block(0, 0, 4), 1002); // block (0, 1)
        assert_eq!(t.block(0, 15, 15), 1015);
        assert_eq!(t.block(0, 16, -1), t.block(0, 0, 15)); // wraps
                                                           // Level 1 (8x8 texels, 2x2 blocks) follows level 0's 16 blocks.
        assert_eq!(t.block(1, 0, 0), 1016);
        assert_eq!(t.levels.len(), 5); // 16, 8, 4, 2, 1
        assert_eq!(t.total_blocks(), 16 + 4 + 1 + 1 + 1);
    }

    #[test]
    fn deterministic_math_is_accurate() {
        for i in -400..=400 {
            let x = f64::from(i) / 40.0;
            assert!((exp2(x) / x.exp2() - 1.0).abs() < 1e-14, "{x}");
        }
        for i in -100..=100 {
            let x = PI * f64::from(i) / 100.0;
            let (s, c) = sin_cos(x);
            assert!(
                (s - x.sin()).abs() < 1e-13 && (c - x.cos()).abs() < 1e-13,
                "{x}"
            );
        }
    }

    #[test]
    fn program_shapes() {
        let mut r = Rng::new(1);
        let p = program(10, 2, &mut r);
        assert_eq!(p.iter().filter(|o| o.is_none()).count(), 2);
        assert_eq!(p.iter().flatten().sum::<u32>(), 8);
        assert!(p.windows(2).all(|w| !(w[0].is_some() && w[1].is_some())));
        assert_eq!(program(3, 0, &mut r), vec![Some(3)]);
        assert_eq!(program(2, 2, &mut r), vec![None, None]);
    }

    /// The figures of the default workload, printed for the report (run
    /// with `--nocapture`) and checked loosely: the defaults were chosen to
    /// resemble the paper's averages, the checks keep them there.
    #[test]
    fn default_figures() {
        let p = GenParams::default();
        let t = generate(&p).unwrap();
        let r = GenReport::new(&p, &t);
        println!("{r}");
        let m = &r.measured;
        assert!((m.mem_instr_ratio - 0.15).abs() < 0.01);
        assert!((2.2..2.8).contains(&m.cf), "CF {}", m.cf);
        assert!((9.0..15.0).contains(&m.reuse), "reuse {}", m.reuse);
        let mesh =
            |k: u32| crate::trace::mean_footprint_ratio(&t, move |x, y| x % k == 0 && y % k == 0);
        let (mesh2, mesh4) = (mesh(2), mesh(4));
        println!("texture footprint ratio: Mesh2 {mesh2:.3}, Mesh4 {mesh4:.3}");
        assert!(mesh4 > 1.0 / 16.0 && mesh4 < mesh2 && mesh2 < 1.0);
    }

    #[test]
    fn synthetic_small_file_is_this_generator_output() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../tests/traces/synthetic-small.trace"
        );
        let p = synthetic_small_params();
        let t = generate(&p).unwrap();
        if std::env::var_os("WASP_REGEN_TRACES").is_some() {
            std::fs::write(path, t.to_text()).unwrap();
        }
        let file = Trace::read(path).unwrap();
        assert_eq!(file, t, "regenerate with WASP_REGEN_TRACES=1");
    }

    /// The parameters of `tests/traces/synthetic-small.trace`.
    fn synthetic_small_params() -> GenParams {
        GenParams {
            frame_w: 128,
            frame_h: 128,
            tile: 64,
            coverage: 0.85,
            blob_size: 96,
            surface_size: 96,
            instrs_per_quad: 8,
            seed: 1,
            ..GenParams::default()
        }
    }
}
