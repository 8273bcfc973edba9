//! The frame: the scene checked and set up, the textures it samples laid
//! out, the tiling engine's polygon lists, and the tiles rasterized on
//! worker threads and joined in Z-order into the trace and the picture.

use super::*;
use crate::trace::TraceBuilder;

/// [`rasterize`], with or without the hierarchical depth test (`hiz`; the
/// results are the same, [`RasterStats::quads_rejected_hiz`] aside).
pub(super) fn rasterize_with(
    scene: &Scene,
    width: u32,
    height: u32,
    opts: &RasterOptions,
    hiz: bool,
) -> Result<Frame, SceneError> {
    rasterize_frame(scene, width, height, opts, hiz, false).map(|(f, _)| f)
}

/// [`rasterize_with`], and with `maps` the frame's [`PixelMaps`].
pub(super) fn rasterize_frame(
    scene: &Scene,
    width: u32,
    height: u32,
    opts: &RasterOptions,
    hiz: bool,
    maps: bool,
) -> Result<(Frame, Option<PixelMaps>), SceneError> {
    let fail = |m: String| SceneError::in_file(&scene.name, m);
    check_frame(scene, width, height, opts)?;
    let mut stats = initial_stats(scene, opts);
    let clock = std::time::Instant::now();
    let mut timings = RasterTimings::default();
    let threads = worker_threads(opts);
    let (runs, order_note) = runs(scene, opts.draw_order);
    let setups = geometry(scene, &runs, width, height, opts, &mut stats)?;
    timings.geometry = clock.elapsed().as_secs_f64();
    let tex_clock = std::time::Instant::now();
    let (formats, textures, map) = lay_out_textures(scene, &setups, opts, threads)?;
    timings.textures = tex_clock.elapsed().as_secs_f64();
    let mats = material_infos(scene);
    let lists = bin(&setups, opts.tile, width, height, &mut stats);
    // Geometry includes the binning.
    timings.geometry = clock.elapsed().as_secs_f64() - timings.textures;

    // Raster pipeline, tile by tile in Z-order.
    let mut join = Join {
        scene_name: &scene.name,
        stats,
        builder: trace_builder(scene, width, height, opts, order_note, map)?,
        image: clear_image(width, height),
        width,
        height,
        tile: opts.tile,
        colour: opts.colour,
        maps: maps.then(|| PixelMaps::new(width, height)),
    };
    let ctx = TileCtx {
        setups: &setups,
        mats: &mats,
        textures: &textures,
        tile: opts.tile,
        width,
        height,
        colour: opts.colour,
        prepass: opts.depth_prepass,
        hiz,
        maps,
    };
    raster_tiles(&ctx, &lists, threads, &mut join)?;
    let Join {
        stats,
        mut builder,
        image,
        maps,
        ..
    } = join;
    builder
        .note(summary_note(&stats, &textures, &formats, opts))
        .map_err(|e| fail(format!("trace note: {e}")))?;
    let trace = builder
        .finish()
        .map_err(|e| fail(format!("building the trace: {e}")))?;
    timings.tiles = clock.elapsed().as_secs_f64() - timings.textures - timings.geometry;
    let frame = Frame {
        trace,
        width,
        height,
        image,
        stats,
        timings,
    };
    Ok((frame, maps))
}

/// The threads that rasterize tiles and lay out textures: `opts.threads`,
/// 0 for as many as the host has, 1 to 64.
fn worker_threads(opts: &RasterOptions) -> usize {
    match opts.threads {
        0 => std::thread::available_parallelism().map_or(1, |n| n.get()),
        n => n,
    }
    .clamp(1, 64)
}

/// The scene's textures in the formats `opts` asks for, laid out for the
/// blocks `setups` sample; with decoded lines, laid out as RGBA8 and
/// mapped to their stored lines.
fn lay_out_textures<'s>(
    scene: &'s Scene,
    setups: &[Setup],
    opts: &RasterOptions,
    threads: usize,
) -> Result<
    (
        Vec<TextureFormat>,
        TextureSet<'s>,
        Option<crate::trace::TextureMap>,
    ),
    SceneError,
> {
    let formats = texture_formats(scene, opts.texture_format)?;
    let decoded = opts.decoded_lines && opts.texture_format != FormatChoice::Rgba8;
    let laid_out = match decoded {
        true => vec![TextureFormat::Rgba8; formats.len()],
        false => formats.clone(),
    };
    let uses = texture_uses(scene, setups, &laid_out);
    let textures = TextureSet::with_threads(&scene.textures, threads, &uses);
    let map = decoded.then(|| textures.decoded_map(&formats));
    Ok((formats, textures, map))
}

/// Check the frame size, the tile size and the scene.
fn check_frame(
    scene: &Scene,
    width: u32,
    height: u32,
    opts: &RasterOptions,
) -> Result<(), SceneError> {
    let fail = |m: String| SceneError::in_file(&scene.name, m);
    if width == 0 || height == 0 || width > 16384 || height > 16384 {
        return Err(fail(format!(
            "frame {width}x{height}: expected 1 to 16384 pixels each"
        )));
    }
    if opts.tile < 2 || !opts.tile.is_multiple_of(2) || opts.tile > 512 {
        return Err(fail(format!(
            "tile {}: expected an even size from 2 to 512",
            opts.tile
        )));
    }
    validate(scene)
}

/// Statistics before anything is counted: one entry per material, and the
/// draw order in effect.
fn initial_stats(scene: &Scene, opts: &RasterOptions) -> RasterStats {
    RasterStats {
        materials: scene
            .materials
            .iter()
            .map(|m| MaterialStats {
                name: m.name.clone(),
                blend: format!("{:?}", m.blend).to_lowercase(),
                ..Default::default()
            })
            .collect(),
        draw_order: opts.draw_order.effective(scene),
        ..Default::default()
    }
}

/// The format of each texture under `choice` (RGBA8 without looking at
/// the textures), or the error naming the texture that cannot take it.
fn texture_formats(scene: &Scene, choice: FormatChoice) -> Result<Vec<TextureFormat>, SceneError> {
    match choice {
        FormatChoice::Rgba8 => Ok(vec![TextureFormat::Rgba8; scene.textures.len()]),
        _ => choice.formats(scene),
    }
}

/// How each texture is used: only those of materials a set-up triangle
/// uses are sampled; an alpha test reads its material's first texture's
/// alpha; each is stored in its entry of `formats`.
fn texture_uses(scene: &Scene, setups: &[Setup], formats: &[TextureFormat]) -> Vec<TextureUse> {
    let mut uses: Vec<TextureUse> = formats
        .iter()
        .map(|&format| TextureUse {
            sampled: false,
            alpha_tested: false,
            format,
        })
        .collect();
    let mut used_mat = vec![false; scene.materials.len()];
    for s in setups {
        used_mat[s.material as usize] = true;
    }
    for (m, _) in scene.materials.iter().zip(&used_mat).filter(|(_, &u)| u) {
        let mut first = true;
        for op in &m.shader {
            if let ShaderOp::Tex(s) = op {
                let state = m.state.unwrap_or(DrawState::for_blend(m.blend));
                for t in std::iter::once(s.texture).chain(s.second.map(|x| x.texture)) {
                    uses[t].sampled = true;
                    uses[t].alpha_tested |= first && state.alpha_test.is_some();
                }
                first = false;
            }
        }
    }
    uses
}

/// What the inner loop needs of each material.
fn material_infos(scene: &Scene) -> Vec<MatInfo> {
    scene
        .materials
        .iter()
        .map(|m| {
            let tex: Vec<_> = m
                .shader
                .iter()
                .filter_map(|op| match op {
                    ShaderOp::Tex(s) => Some(*s),
                    ShaderOp::Alu(_) => None,
                })
                .collect();
            MatInfo {
                state: m.state.unwrap_or(DrawState::for_blend(m.blend)),
                tex,
                shader: m.shader.clone(),
            }
        })
        .collect()
}

/// The tiling engine: each tile's polygon list (the set-up triangles whose
/// edges overlap it, in draw order), tiles in row order.
fn bin(
    setups: &[Setup],
    t: u32,
    width: u32,
    height: u32,
    stats: &mut RasterStats,
) -> Vec<Vec<u32>> {
    let (tiles_x, tiles_y) = (width.div_ceil(t), height.div_ceil(t));
    let mut lists: Vec<Vec<u32>> = vec![Vec::new(); (tiles_x * tiles_y) as usize];
    for (i, s) in setups.iter().enumerate() {
        let [x0, x1, y0, y1] = s.bbox;
        for ty in y0 / t..=(y1 - 1) / t {
            for tx in x0 / t..=(x1 - 1) / t {
                let (tx0, ty0) = ((tx * t).max(x0), (ty * t).max(y0));
                let (tx1, ty1) = (((tx + 1) * t).min(x1), ((ty + 1) * t).min(y1));
                if overlaps(s, tx0, tx1, ty0, ty1) {
                    lists[(ty * tiles_x + tx) as usize].push(i as u32);
                    stats.bin_entries += 1;
                }
            }
        }
    }
    lists
}

/// The trace builder, its header naming the scene and the draw order.
fn trace_builder(
    scene: &Scene,
    width: u32,
    height: u32,
    opts: &RasterOptions,
    order_note: Option<String>,
    map: Option<crate::trace::TextureMap>,
) -> Result<TraceBuilder, SceneError> {
    let mut header = TraceHeader::new(scene.name.clone(), width, height, opts.tile);
    // RGBA8 writes no line: its traces stay as they were.
    header.texture_format = (opts.texture_format != FormatChoice::Rgba8)
        .then(|| opts.texture_format.name().to_string());
    header.texture_map = map;
    header
        .notes
        .push(format!(" scene {} ({})", scene.name, scene.source));
    header.notes.extend(order_note);
    Trace::builder(header)
        .map_err(|e| SceneError::in_file(&scene.name, format!("trace header: {e}")))
}

/// A picture of the clear colour.
fn clear_image(width: u32, height: u32) -> Vec<u8> {
    let mut image = vec![0u8; width as usize * height as usize * 4];
    for px in image.chunks_exact_mut(4) {
        px.copy_from_slice(&to_u8(CLEAR));
    }
    image
}

/// Where the tiles' results are joined, in Z-order: the statistics, the
/// trace and the picture.
struct Join<'a> {
    scene_name: &'a str,
    stats: RasterStats,
    builder: TraceBuilder,
    image: Vec<u8>,
    width: u32,
    height: u32,
    tile: u32,
    /// Whether the picture is drawn.
    colour: bool,
    /// The per-pixel maps, when asked for.
    maps: Option<PixelMaps>,
}

impl Join<'_> {
    /// Join tile (`tx`, `ty`)'s results: its counts, its pixels and its
    /// trace records (a tile that rasterized no quad has none).
    fn tile(&mut self, tx: u32, ty: u32, b: &mut TileBuf) -> Result<(), SceneError> {
        let stats = &mut self.stats;
        stats.quads_covered += b.covered;
        stats.quads_rejected_early_z += b.rejected;
        stats.quads_rejected_hiz += b.rejected_hiz;
        stats.warps += b.frags.len() as u64;
        stats.positions += b.positions;
        stats.pixels_shaded += b.pixels;
        for (m, c) in stats.materials.iter_mut().zip(&b.per_material) {
            m.warps += c[0];
            m.quads_rejected_early_z += c[1];
            m.pixels += c[2];
        }
        let (t, width) = (self.tile, self.width);
        let (ox, oy) = (tx * t, ty * t);
        let (tw, th) = (t.min(width - ox), t.min(self.height - oy));
        if self.colour {
            for ly in 0..th {
                let row = ((oy + ly) * width + ox) as usize * 4;
                for lx in 0..tw {
                    let c = to_u8(b.colour[(ly * t + lx) as usize]);
                    let at = row + lx as usize * 4;
                    self.image[at..at + 4].copy_from_slice(&c);
                }
            }
        }
        if let (Some(m), Some(tm)) = (&mut self.maps, &b.maps) {
            m.join(tm, (ox, oy, tw, th, t));
        }
        let fail = |e: crate::trace::Problem| {
            SceneError::in_file(self.scene_name, format!("building the trace: {e}"))
        };
        let part = std::mem::replace(&mut b.part, Ok(None)).map_err(fail)?;
        if let Some(part) = part {
            self.stats.tiles += 1;
            self.builder.append(part).map_err(fail)?;
        }
        Ok(())
    }
}

/// Rasterize every tile with triangles, in Z-order. Tiles are independent,
/// so batches of them run on `threads` worker threads, each taking one tile
/// at a time (costs vary a lot) and building its trace records too; the
/// results are joined in order.
fn raster_tiles(
    ctx: &TileCtx,
    lists: &[Vec<u32>],
    threads: usize,
    join: &mut Join,
) -> Result<(), SceneError> {
    let t = ctx.tile;
    let (tiles_x, tiles_y) = (ctx.width.div_ceil(t), ctx.height.div_ceil(t));
    let order: Vec<(u32, u32)> = crate::trace::z_order(tiles_x, tiles_y)
        .into_iter()
        .filter(|&(tx, ty)| !lists[(ty * tiles_x + tx) as usize].is_empty())
        .collect();
    let batch = threads * 16;
    let bufs: Vec<std::sync::Mutex<TileBuf>> = (0..batch.min(order.len().max(1)))
        .map(|_| std::sync::Mutex::new(TileBuf::new(t, ctx.mats.len())))
        .collect();
    let part_header = join.builder.header().clone();
    for chunk in order.chunks(batch) {
        let next = std::sync::atomic::AtomicUsize::new(0);
        let work = || loop {
            let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            let Some(&(tx, ty)) = chunk.get(i) else {
                break;
            };
            let mut b = bufs[i].lock().unwrap_or_else(|e| e.into_inner());
            raster_tile(ctx, tx, ty, &lists[(ty * tiles_x + tx) as usize], &mut b);
            b.part = build_tile(ctx, &part_header, tx, ty, &mut b);
        };
        if threads > 1 && chunk.len() > 1 {
            std::thread::scope(|sc| {
                for _ in 1..threads.min(chunk.len()) {
                    sc.spawn(work);
                }
                work();
            });
        } else {
            work();
        }
        for (&(tx, ty), b) in chunk.iter().zip(&bufs) {
            let mut b = b.lock().unwrap_or_else(|e| e.into_inner());
            join.tile(tx, ty, &mut b)?;
        }
    }
    Ok(())
}

/// The trace's closing note: what was rasterized and how much overdraw,
/// and where the texture heap is and how its textures are stored.
fn summary_note(
    stats: &RasterStats,
    textures: &TextureSet,
    formats: &[TextureFormat],
    opts: &RasterOptions,
) -> String {
    let choice = opts.texture_format;
    let layout = match choice {
        FormatChoice::Rgba8 => "4x4-texel 64-byte blocks in Morton order".to_string(),
        _ if opts.decoded_lines => format!(
            "textures as {choice} ({}), listed as their decoded 4x4-texel 64-byte blocks in \
             Morton order",
            format_counts(formats)
        ),
        _ => format!(
            "textures as {choice} ({}), 64-byte blocks in Morton order",
            format_counts(formats)
        ),
    };
    format!(
        " rasterized by wasp scene::raster: {} triangles ({} clipped, {} culled), {} quads \
         covered, {} rejected by early-Z, {} fragments shaded, one warp each in \
         rasterization order, at {} quad positions ({:.2} warps per position); texture heap \
         {} KiB at {:#x}, {layout}",
        stats.primitives,
        stats.clipped,
        stats.culled_outside + stats.culled_back_faces,
        stats.quads_covered,
        stats.quads_rejected_early_z,
        stats.warps,
        stats.positions,
        if stats.positions == 0 {
            0.0
        } else {
            stats.warps as f64 / stats.positions as f64
        },
        textures.heap_bytes() / 1024,
        crate::texture::HEAP_BASE
    )
}

/// How many textures of the set are in each format: `12 etc2-rgb, 3
/// etc2-rgba`, formats in [`TextureFormat::ALL`] order.
fn format_counts(formats: &[TextureFormat]) -> String {
    let parts: Vec<String> = TextureFormat::ALL
        .iter()
        .filter_map(|&f| {
            let n = formats.iter().filter(|&&t| t == f).count();
            (n > 0).then(|| format!("{n} {f}"))
        })
        .collect();
    if parts.is_empty() {
        "no textures".into()
    } else {
        parts.join(", ")
    }
}

pub(super) fn to_u8(c: [f32; 4]) -> [u8; 4] {
    let q = |v: f32| (v.clamp(0.0, 1.0) * 255.0 + 0.5) as u8;
    [q(c[0]), q(c[1]), q(c[2]), q(c[3])]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::raster::fixtures::*;

    #[test]
    fn tiles_are_visited_in_z_order_and_empty_tiles_skipped() {
        // 256x192 frame: 4x3 tiles; the quad leaves tile (3, 2) empty.
        let scene = ortho_scene(
            vec![
                quad_mesh(0.0, 0.0, 256.0, 128.0, 0.0, 0),
                quad_mesh(0.0, 128.0, 192.0, 192.0, 0.0, 0),
            ],
            vec![mat("m", Blend::Opaque, 0)],
            256.0,
            192.0,
        );
        let f = rasterize(&scene, 256, 192, &RasterOptions::default()).unwrap();
        let got: Vec<(u32, u32)> = f.trace.tiles().iter().map(|t| (t.tx(), t.ty())).collect();
        let want: Vec<(u32, u32)> = crate::trace::z_order(4, 3)
            .into_iter()
            .filter(|&p| p != (3, 2))
            .collect();
        assert_eq!(got, want);
        assert_eq!(
            got[..5],
            [(0, 0), (1, 0), (0, 1), (1, 1), (2, 0)],
            "Morton order"
        );
        // Every tile is fully covered: 32x32 quad positions each, one warp
        // each but where a rectangle's diagonal crosses a quad: both of its
        // triangles shade a fragment there (each pixel exactly once).
        let mut extra = 0;
        for tile in f.trace.tiles() {
            assert_eq!(tile.position_count(), 1024);
            extra += tile.quad_count() - 1024;
        }
        assert_eq!(extra as u64, f.stats.warps - f.stats.positions);
        assert!(extra > 0);
        assert_eq!(f.stats.pixels_shaded, 256 * 128 + 192 * 64);
    }

    /// Timing of the front end on the procedural scenes at the paper's
    /// 1960x768 (a measurement, not a check: run with
    /// `cargo test --release -p wasp-frontend raster_timing -- --ignored --nocapture`).
    #[test]
    #[ignore = "timing measurement; run in release with --ignored --nocapture"]
    fn raster_timing() {
        use crate::procedural;
        let scenes = [
            procedural::plane("ground", "standard").unwrap(),
            procedural::plane("ground", "lightmapped").unwrap(),
            procedural::sprites("full", 1960, 768).unwrap(),
        ];
        // CPU seconds of this process (user + system), from /proc (Linux):
        // the machine may be shared, so wall time alone misleads.
        fn cpu_seconds() -> f64 {
            let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
            let after = stat.rsplit_once(')').map_or("", |x| x.1);
            let f: Vec<f64> = after
                .split_whitespace()
                .map(|t| t.parse().unwrap_or(0.0))
                .collect();
            // Fields 14 and 15 (utime, stime) are the 12th and 13th after
            // the command name; clock ticks of 1/100 s.
            (f.get(11).copied().unwrap_or(0.0) + f.get(12).copied().unwrap_or(0.0)) / 100.0
        }
        for scene in &scenes {
            for (colour, threads) in [(false, 1), (true, 1), (false, 0), (true, 0)] {
                let opts = RasterOptions {
                    colour,
                    threads,
                    ..RasterOptions::default()
                };
                let cpu0 = cpu_seconds();
                let runs = 5;
                let best = (0..runs)
                    .map(|_| rasterize_timed(scene, 1960, 768, &opts).unwrap().1)
                    .fold(f64::INFINITY, f64::min);
                let cpu = (cpu_seconds() - cpu0) / f64::from(runs);
                println!(
                    "{:<24} colour {:<5} threads {:<4} wall best of {runs}: {:.3} s, CPU per run: {:.3} s",
                    scene.name,
                    colour,
                    if threads == 0 { "auto".to_string() } else { threads.to_string() },
                    best,
                    cpu
                );
            }
        }
    }

    #[test]
    fn hierarchical_z_changes_no_result() {
        let mut rejected = 0;
        for (seed, (w, h), tile, prepass) in [
            (1u64, (200u32, 150u32), 64u32, false),
            (2, (200, 150), 64, true),
            (3, (97, 61), 10, false),
            (4, (128, 96), 6, false),
            (5, (130, 70), 16, true),
        ] {
            let scene = random_scene(0x9e37_79b9_7f4a_7c15 ^ seed, 300);
            let opts = RasterOptions {
                tile,
                depth_prepass: prepass,
                threads: 1,
                ..Default::default()
            };
            let fast = rasterize_with(&scene, w, h, &opts, true).unwrap();
            let slow = rasterize_with(&scene, w, h, &opts, false).unwrap();
            assert_eq!(slow.stats.quads_rejected_hiz, 0);
            assert!(fast.stats.quads_rejected_hiz <= fast.stats.quads_rejected_early_z);
            rejected += fast.stats.quads_rejected_hiz;
            assert_eq!(trace_bytes(&fast), trace_bytes(&slow), "seed {seed}");
            assert_eq!(
                fast.trace.rejected_count(),
                fast.stats.quads_rejected_early_z,
                "seed {seed}: every rejected quad is in the trace"
            );
            assert!(fast.image == slow.image, "seed {seed}: picture differs");
            let stats = RasterStats {
                quads_rejected_hiz: 0,
                ..fast.stats.clone()
            };
            assert_eq!(stats, slow.stats, "seed {seed}");
            assert!(
                slow.stats.quads_rejected_early_z > 0,
                "seed {seed}: no overdraw"
            );
        }
        assert!(rejected > 0, "the coarse test rejected nothing");
    }

    #[test]
    fn procedural_scenes_record_every_rejected_quad_in_the_trace() {
        use crate::def::{Game, SceneDef};
        use crate::procedural;
        let (w, h) = (320, 192);
        let mut rejected = 0;
        for map in procedural::MAPS {
            let def = SceneDef {
                name: format!("procedural-{map}"),
                ..crate::def::test_def(
                    Game::Procedural,
                    map,
                    if map == "plane" { "ground" } else { "full" },
                    w,
                    h,
                )
            };
            let scene = procedural::load(&def).unwrap();
            for depth_prepass in [false, true] {
                let opts = RasterOptions {
                    colour: false,
                    depth_prepass,
                    ..RasterOptions::default()
                };
                let f = rasterize(&scene, w, h, &opts).unwrap();
                let what = format!("{map}, prepass {depth_prepass}");
                let want = f.stats.quads_rejected_early_z;
                // Every rejected quad (coarse ones included) is in the
                // trace once: with the warps, every covered quad.
                assert_eq!(f.trace.rejected_count(), want, "{what}");
                assert_eq!(f.trace.stats().rejected_quads, want, "{what}");
                let produced: u64 = f.trace.tiles().iter().map(|t| t.raster_count()).sum();
                assert_eq!(produced, f.stats.quads_covered, "{what}");
                assert_eq!(f.stats.warps + want, f.stats.quads_covered, "{what}");
                assert_eq!(f.trace.tiles().len() as u64, f.stats.tiles, "{what}");
                // Written as format 4 and read back, each stays in place.
                let back = Trace::parse(&f.trace.to_text(), "rt").unwrap();
                assert_eq!(back, f.trace, "{what}");
                rejected += want;
            }
        }
        assert!(rejected > 0, "no procedural scene rejected a quad");
    }

    #[test]
    fn compressed_formats_move_blocks_not_warps_and_are_recorded() {
        let scene = ortho_scene(
            vec![quad_mesh(0.0, 0.0, 256.0, 192.0, 0.0, 0)],
            vec![mat("m", Blend::Opaque, 0)],
            256.0,
            192.0,
        );
        let with = |choice: FormatChoice| {
            let opts = RasterOptions {
                texture_format: choice,
                threads: 1,
                ..RasterOptions::default()
            };
            rasterize(&scene, 256, 192, &opts).unwrap()
        };
        let plain = rasterize(&scene, 256, 192, &RasterOptions::default()).unwrap();
        let rgba8 = with(FormatChoice::Rgba8);
        assert_eq!(trace_bytes(&rgba8), trace_bytes(&plain));
        assert_eq!(rgba8.trace.header().texture_format, None);
        let etc2 = with(FormatChoice::Etc2);
        let astc = with(FormatChoice::All(TextureFormat::Astc8x8));
        assert_eq!(etc2.trace.header().texture_format.as_deref(), Some("etc2"));
        let text = etc2.trace.to_text();
        assert!(text.contains("\ntexture-format etc2\n"), "{text:.300}");
        assert!(
            text.contains("textures as etc2 (1 etc2-rgb)"),
            "{text:.900}"
        );
        let (a, b, c) = (plain.trace.stats(), etc2.trace.stats(), astc.trace.stats());
        assert_eq!((a.warps, a.tex_instrs), (b.warps, b.tex_instrs));
        assert_eq!(plain.image, etc2.image, "the picture is the same");
        // A line holds 8x (ETC2 RGB) and 16x (ASTC 8x8) the texels.
        // Level 0 of the 64x64 texture, all of it read (magnified).
        assert_eq!(a.frame_unique_blocks, 256);
        assert_eq!(b.frame_unique_blocks, 32);
        assert_eq!(c.frame_unique_blocks, 16);
        assert!(c.tile_unique_blocks < b.tile_unique_blocks);
        assert!(b.tile_unique_blocks < a.tile_unique_blocks);
        assert!(c.cf <= b.cf && b.cf < a.cf, "{} {} {}", a.cf, b.cf, c.cf);
    }

    #[test]
    fn a_texture_whose_alpha_is_used_cannot_be_forced_into_etc2_rgb() {
        let mut scene = ortho_scene(
            vec![quad_mesh(0.0, 0.0, 128.0, 128.0, 0.0, 0)],
            vec![mat("leaves", Blend::AlphaTest, 0)],
            128.0,
            128.0,
        );
        let rgb = RasterOptions {
            texture_format: FormatChoice::All(TextureFormat::Etc2Rgb),
            ..RasterOptions::default()
        };
        // Opaque texels: nothing is lost, ETC2 RGB is fine.
        assert!(rasterize(&scene, 128, 128, &rgb).is_ok());
        scene.textures[0].rgba[3] = 0;
        let e = rasterize(&scene, 128, 128, &rgb).unwrap_err().to_string();
        assert!(
            e.starts_with("test:ortho: texture `c` cannot be stored as etc2-rgb"),
            "{e}"
        );
        assert!(
            e.contains("allowed texture formats for it: rgba8, etc2, etc2-rgba, astc-4x4, astc-6x6, astc-8x8"),
            "{e}"
        );
        // The rule gives it ETC2 RGBA.
        let rule = RasterOptions {
            texture_format: FormatChoice::Etc2,
            ..RasterOptions::default()
        };
        let f = rasterize(&scene, 128, 128, &rule).unwrap();
        assert!(f
            .trace
            .header()
            .notes
            .iter()
            .any(|n| n.contains("(1 etc2-rgba)")));
        // An opaque material never needs the alpha.
        scene.materials[0].blend = Blend::Opaque;
        assert!(rasterize(&scene, 128, 128, &rgb).is_ok());
    }
}
