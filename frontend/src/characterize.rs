//! Workload characterisation per scene, beside the paper's figures: the
//! statistics of Table I and Section III-B ([`crate::trace::TraceStats`])
//! and the texture footprint ratio of every priority subset (Figure 11's
//! quantity, [`crate::trace::mean_footprint_ratio`]).
//!
//! The paper's figures come from ten Android games on TEAPOT; ours from the
//! scenes named in each row (procedural ones say so). They are shown side
//! by side to judge whether a scene is in the paper's range, never to tune
//! anything towards it.
//!
//! A warp is one shaded (primitive, quad) fragment, as in the hardware the
//! paper models, so with overdraw a tile holds more warps than quad
//! positions (up to 1024 positions, any number of warps). The definitions
//! then read: CF is the distinct blocks one fragment's shader touches;
//! Min_Estimate1 is a tile's unique blocks over its fragments (overdraw
//! lowers it: more warps share one footprint); Min_Estimate2 = Min_Estimate1
//! / CF. A priority subset selects quad *positions* (the hardware selector
//! looks at the quad's coordinates), hence every fragment at a selected
//! position: its size ratio is the fraction of a tile's positions, and its
//! warp ratio the fraction of the warps it actually selects (above the size
//! ratio where overdraw is heavier at its positions). Its footprint ratio
//! is the distinct blocks of the selected warps over the tile's.

use super::def::SceneDef;
use super::raster::{rasterize_timed, DrawOrder, Frame, RasterOptions};
use super::{load, SceneError};
#[cfg(test)]
use crate::trace::mean_footprint_ratio;
use crate::trace::Trace;
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use wasp_rtl::subset::SubsetSpec;

/// The footprint of one priority subset.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SubsetFootprint {
    /// Subset name (`mesh4`, `top16`, ...).
    pub subset: String,
    /// Fraction of a tile's quad positions it selects.
    pub size_ratio: f64,
    /// Fraction of the warps (fragments) it selects, over the whole frame.
    pub warp_ratio: f64,
    /// Mean texture footprint ratio over tiles (warp-weighted).
    pub footprint_ratio: f64,
    /// The paper's value (Figure 11 / Section V-D), where it gives one.
    pub paper: Option<f64>,
}

/// One scene's characterisation.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Characterization {
    /// Scene definition name.
    pub scene: String,
    /// Workload name in the trace (procedural scenes say so).
    pub workload: String,
    /// Frame width.
    pub width: u32,
    /// Frame height.
    pub height: u32,
    /// Tiles with at least one warp.
    pub tiles: u64,
    /// Warps: surviving (triangle, quad) fragments, one warp each.
    pub warps: u64,
    /// Warps per tile.
    pub warps_per_tile: f64,
    /// Quad positions with at least one warp (summed over tiles).
    pub positions: u64,
    /// warps / positions: shaded warps (fragments) per quad position
    /// covered, the overdraw in warps. Arm's guidance for mobile games is
    /// under 3 shaded fragments per output pixel (`docs/scenes.md`).
    pub warps_per_position: f64,
    /// The same per tile (a tile's warps over its quad positions), over
    /// the tiles with a warp: the median (nearest rank).
    #[serde(default)]
    pub warps_per_position_p50: f64,
    /// The 90th percentile over tiles.
    #[serde(default)]
    pub warps_per_position_p90: f64,
    /// The 99th percentile over tiles.
    #[serde(default)]
    pub warps_per_position_p99: f64,
    /// Quads rejected by early-Z.
    pub rejected_early_z: u64,
    /// Of the covered (triangle, quad) pairs, the share early-Z rejected:
    /// rejected / (rejected + warps).
    #[serde(default)]
    pub rejected_early_z_share: f64,
    /// The draw order the frame was rasterized in (the one that took
    /// effect: a 2D scene is always drawn as loaded).
    #[serde(default)]
    pub draw_order: DrawOrder,
    /// How the textures were stored (the trace's `texture-format`, `rgba8`
    /// when it names none).
    #[serde(default = "rgba8")]
    pub texture_format: String,
    /// Distinct blocks per tile with a warp (the tile's texture footprint,
    /// a mean over tiles).
    #[serde(default)]
    pub blocks_per_tile: f64,
    /// Texture instructions / instructions (Table I).
    pub mem_instr_ratio: f64,
    /// Memory-block reuse in tile (Table I).
    pub reuse: f64,
    /// Distinct blocks per warp (Section III-B's CF).
    pub cf: f64,
    /// Blocks per texture instruction (repeats across instructions of a
    /// warp counted).
    pub blocks_per_tex_instr: f64,
    /// Min_Estimate1 (Section III-B).
    pub min_estimate1: f64,
    /// Min_Estimate2 (Section III-B).
    pub min_estimate2: f64,
    /// Footprint ratio of each subset of [`SubsetSpec::all`].
    pub footprints: Vec<SubsetFootprint>,
    /// Seconds to rasterize (not part of the figures).
    pub raster_seconds: f64,
}

fn rgba8() -> String {
    "rgba8".into()
}

/// The paper's value of a subset's footprint ratio, where stated.
pub fn paper_footprint(spec: &SubsetSpec) -> Option<f64> {
    match spec {
        SubsetSpec::Top16 => Some(0.17),
        SubsetSpec::HorizontalLines => Some(0.3),
        SubsetSpec::VerticalLines => Some(0.4),
        SubsetSpec::Mesh(2) => Some(0.9),
        SubsetSpec::Mesh(4) => Some(0.59),
        SubsetSpec::Random(_) => Some(0.56),
        SubsetSpec::Mesh(_) => None,
    }
}

/// [`mean_footprint_ratio`](crate::trace::mean_footprint_ratio) of several subsets at once: each tile's unique
/// blocks are sorted once instead of once per subset (same definition,
/// same result; a test checks it).
pub fn mean_footprint_ratios(trace: &Trace, specs: &[SubsetSpec]) -> Vec<f64> {
    subset_ratios(trace, specs).0
}

/// Per subset: the mean footprint ratio (as [`mean_footprint_ratios`]) and
/// the fraction of the trace's warps at its positions.
pub fn subset_ratios(trace: &Trace, specs: &[SubsetSpec]) -> (Vec<f64>, Vec<f64>) {
    let side = trace.header().quads_per_side();
    let sels: Vec<_> = specs.iter().map(|s| s.build(side)).collect();
    let mut num = vec![0.0f64; specs.len()];
    let mut selected = vec![0u64; specs.len()];
    for (k, sel) in sels.iter().enumerate() {
        selected[k] = trace
            .tiles()
            .iter()
            .flat_map(|t| t.quads())
            .filter(|q| sel.is_priority(q.x(), q.y()))
            .count() as u64;
    }
    let warps = trace.quad_count() as f64;
    let warp_ratios = selected
        .iter()
        .map(|&n| if warps == 0.0 { 0.0 } else { n as f64 / warps })
        .collect();
    let mut den = 0.0f64;
    let (mut all, mut chosen) = (Vec::new(), Vec::new());
    for tile in trace.tiles() {
        all.clear();
        all.extend_from_slice(tile.block_accesses());
        all.sort_unstable();
        all.dedup();
        if all.is_empty() {
            continue;
        }
        let w = tile.quad_count() as f64;
        den += w;
        for (k, sel) in sels.iter().enumerate() {
            chosen.clear();
            for q in tile.quads().filter(|q| sel.is_priority(q.x(), q.y())) {
                chosen.extend_from_slice(q.block_accesses());
            }
            chosen.sort_unstable();
            chosen.dedup();
            num[k] += w * chosen.len() as f64 / all.len() as f64;
        }
    }
    let footprints = num
        .iter()
        .map(|n| if den == 0.0 { 0.0 } else { n / den })
        .collect();
    (footprints, warp_ratios)
}

/// Characterise a rasterized frame.
pub fn characterize(scene: &str, frame: &Frame, raster_seconds: f64) -> Characterization {
    let s = frame.trace.stats();
    let side = frame.trace.header().quads_per_side();
    let specs = SubsetSpec::all();
    let (ratios, warp_ratios) = subset_ratios(&frame.trace, &specs);
    let footprints = specs
        .iter()
        .zip(ratios)
        .zip(warp_ratios)
        .map(|((spec, footprint_ratio), warp_ratio)| SubsetFootprint {
            subset: spec.to_string(),
            size_ratio: spec.build(side).size_ratio(side),
            warp_ratio,
            footprint_ratio,
            paper: paper_footprint(spec),
        })
        .collect();
    let ratio = |a: f64, b: f64| if b == 0.0 { 0.0 } else { a / b };
    let mut per_tile: Vec<f64> = frame
        .trace
        .tiles()
        .iter()
        .filter(|t| t.position_count() > 0)
        .map(|t| t.quad_count() as f64 / t.position_count() as f64)
        .collect();
    per_tile.sort_by(f64::total_cmp);
    let rejected = frame.stats.quads_rejected_early_z;
    Characterization {
        scene: scene.to_string(),
        workload: s.workload.clone(),
        width: frame.width,
        height: frame.height,
        tiles: s.warp_tiles,
        warps: s.warps,
        warps_per_tile: s.warps_per_tile,
        positions: s.positions,
        warps_per_position: s.warps_per_position,
        warps_per_position_p50: percentile(&per_tile, 0.5),
        warps_per_position_p90: percentile(&per_tile, 0.9),
        warps_per_position_p99: percentile(&per_tile, 0.99),
        rejected_early_z: rejected,
        rejected_early_z_share: ratio(rejected as f64, (rejected + s.warps) as f64),
        draw_order: frame.stats.draw_order,
        texture_format: frame
            .trace
            .header()
            .texture_format
            .clone()
            .unwrap_or_else(rgba8),
        blocks_per_tile: ratio(s.tile_unique_blocks as f64, s.warp_tiles as f64),
        mem_instr_ratio: s.mem_instr_ratio,
        reuse: s.reuse,
        cf: s.cf,
        blocks_per_tex_instr: ratio(s.block_accesses as f64, s.tex_instrs as f64),
        min_estimate1: s.min_estimate1,
        min_estimate2: s.min_estimate2,
        footprints,
        raster_seconds,
    }
}

/// The value at fraction `q` of `sorted` (nearest rank; 0 when empty).
fn percentile(sorted: &[f64], q: f64) -> f64 {
    if sorted.is_empty() {
        return 0.0;
    }
    let rank = (q * sorted.len() as f64).ceil() as usize;
    sorted[rank.clamp(1, sorted.len()) - 1]
}

/// Load, rasterize (trace only, 64-pixel tiles, in the definition's draw
/// order and texture format; hidden-surface removal by a depth pre-pass if
/// `depth_prepass`) and characterise a scene.
pub fn characterize_def(
    def: &SceneDef,
    depth_prepass: bool,
) -> Result<Characterization, SceneError> {
    let scene = load::load_scene(def)?;
    let opts = RasterOptions {
        colour: false,
        depth_prepass,
        draw_order: def.draw_order,
        texture_format: def.texture_format,
        ..RasterOptions::default()
    };
    let (frame, secs) = rasterize_timed(&scene, def.width, def.height, &opts)?;
    Ok(characterize(&def.name, &frame, secs))
}

/// A row of the table: the figure's name, its value for a scene, and the
/// paper's value.
type Figure = (&'static str, fn(&Characterization) -> String, &'static str);

/// The rows of every scene's figures, in the table's order (the footprint
/// ratio of each subset follows them).
const FIGURES: &[Figure] = &[
    ("workload", |c| c.workload.clone(), "10 Android games"),
    ("frame", |c| format!("{}x{}", c.width, c.height), "1960x768"),
    ("tiles", |c| c.tiles.to_string(), "-"),
    ("warps (fragments)", |c| c.warps.to_string(), "-"),
    (
        "warps per tile",
        |c| format!("{:.1}", c.warps_per_tile),
        "-",
    ),
    ("quad positions", |c| c.positions.to_string(), "-"),
    ("draw order", |c| c.draw_order.to_string(), "-"),
    ("texture format", |c| c.texture_format.clone(), "-"),
    (
        "shaded warps per quad position",
        |c| format!("{:.2}", c.warps_per_position),
        "-",
    ),
    (
        "  per tile p50/p90/p99",
        |c| {
            format!(
                "{:.2}/{:.2}/{:.2}",
                c.warps_per_position_p50, c.warps_per_position_p90, c.warps_per_position_p99
            )
        },
        "-",
    ),
    (
        "early-Z rejected share",
        |c| format!("{:.3}", c.rejected_early_z_share),
        "-",
    ),
    (
        "memory-instr ratio",
        |c| format!("{:.3}", c.mem_instr_ratio),
        "0.07-0.26 (Table I)",
    ),
    (
        "block reuse in tile",
        |c| format!("{:.1}", c.reuse),
        "3.3-22.9 (Table I)",
    ),
    (
        "CF (blocks/warp)",
        |c| format!("{:.2}", c.cf),
        "2.5 mean (III-B)",
    ),
    (
        "distinct blocks per tile",
        |c| format!("{:.1}", c.blocks_per_tile),
        "-",
    ),
    (
        "blocks/tex instr",
        |c| format!("{:.2}", c.blocks_per_tex_instr),
        "-",
    ),
    (
        "Min_Estimate1",
        |c| format!("{:.3}", c.min_estimate1),
        "0.12 mean (III-B)",
    ),
    (
        "Min_Estimate2",
        |c| format!("{:.3}", c.min_estimate2),
        "~1/16 (III-B)",
    ),
];

/// The table: one row per figure, one column per scene, then the paper's.
pub fn table(rows: &[Characterization]) -> String {
    let mut lines: Vec<(String, Vec<String>, String)> = FIGURES
        .iter()
        .map(|(name, value, paper)| {
            (
                name.to_string(),
                rows.iter().map(value).collect(),
                paper.to_string(),
            )
        })
        .collect();
    let subsets = rows.first().map(|r| r.footprints.len()).unwrap_or(0);
    for i in 0..subsets {
        let f0 = &rows[0].footprints[i];
        let paper = match (f0.paper, f0.subset.as_str()) {
            (Some(p), "mesh4") => format!("{p:.2} (Fig. 11; 0.64 in V-D)"),
            (Some(p), _) => format!("{p:.2} (Fig. 11)"),
            (None, _) => "lower than Mesh4".into(),
        };
        lines.push((
            format!("footprint {} ({:.3})", f0.subset, f0.size_ratio),
            rows.iter()
                .map(|c| format!("{:.3}", c.footprints[i].footprint_ratio))
                .collect(),
            paper,
        ));
    }
    layout(rows, &lines)
}

/// The table's text: a header of the scenes, then each (figure, values,
/// paper) line, every column as wide as its widest entry.
fn layout(rows: &[Characterization], lines: &[(String, Vec<String>, String)]) -> String {
    let w0 = lines.iter().map(|l| l.0.len()).max().unwrap_or(0).max(6);
    let widths: Vec<usize> = (0..rows.len())
        .map(|i| {
            lines
                .iter()
                .map(|l| l.1[i].len())
                .chain(std::iter::once(rows[i].scene.len()))
                .max()
                .unwrap_or(0)
        })
        .collect();
    let mut out = String::new();
    let _ = write!(out, "{:<w0$}", "figure");
    for (r, w) in rows.iter().zip(&widths) {
        let _ = write!(out, "  {:>w$}", r.scene);
    }
    let _ = writeln!(out, "  paper");
    for (name, vals, paper) in lines {
        let _ = write!(out, "{name:<w0$}");
        for (v, w) in vals.iter().zip(&widths) {
            let _ = write!(out, "  {v:>w$}");
        }
        let _ = writeln!(out, "  {paper}");
    }
    out
}

/// CSV: one line per scene.
pub fn csv(rows: &[Characterization]) -> String {
    let mut w = ::csv::WriterBuilder::new()
        .flexible(true)
        .from_writer(Vec::new());
    let subsets = rows.first().map_or(&[][..], |r| &r.footprints[..]);
    let names = |prefix: &'static str| {
        subsets
            .iter()
            .map(move |f| format!("{prefix}{}", f.subset.replace(':', "_")))
    };
    let header = CSV_COLUMNS
        .iter()
        .map(|c| c.to_string())
        .chain(names("footprint_"))
        .chain(names("warp_ratio_"));
    w.write_record(header.collect::<Vec<String>>())
        .expect("CSV into memory: no I/O error");
    for c in rows {
        w.write_record(csv_record(c))
            .expect("CSV into memory: no I/O error");
    }
    let bytes = w.into_inner().expect("CSV into memory: no I/O error");
    String::from_utf8(bytes).expect("CSV of UTF-8 fields is UTF-8")
}

/// The CSV's columns before the footprint and warp ratio of each subset.
const CSV_COLUMNS: [&str; 23] = [
    "scene",
    "workload",
    "width",
    "height",
    "tiles",
    "warps",
    "warps_per_tile",
    "positions",
    "warps_per_position",
    "rejected_early_z",
    "mem_instr_ratio",
    "reuse",
    "cf",
    "blocks_per_tex_instr",
    "min_estimate1",
    "min_estimate2",
    "draw_order",
    "warps_per_position_p50",
    "warps_per_position_p90",
    "warps_per_position_p99",
    "rejected_early_z_share",
    "texture_format",
    "blocks_per_tile",
];

/// A scene's CSV record, in the order of [`CSV_COLUMNS`] then the
/// footprint and warp ratio of each subset.
fn csv_record(c: &Characterization) -> Vec<String> {
    let fields = [
        c.scene.clone(),
        c.workload.clone(),
        c.width.to_string(),
        c.height.to_string(),
        c.tiles.to_string(),
        c.warps.to_string(),
        format!("{:.3}", c.warps_per_tile),
        c.positions.to_string(),
        format!("{:.4}", c.warps_per_position),
        c.rejected_early_z.to_string(),
        format!("{:.5}", c.mem_instr_ratio),
        format!("{:.4}", c.reuse),
        format!("{:.4}", c.cf),
        format!("{:.4}", c.blocks_per_tex_instr),
        format!("{:.5}", c.min_estimate1),
        format!("{:.5}", c.min_estimate2),
        c.draw_order.to_string(),
        format!("{:.4}", c.warps_per_position_p50),
        format!("{:.4}", c.warps_per_position_p90),
        format!("{:.4}", c.warps_per_position_p99),
        format!("{:.5}", c.rejected_early_z_share),
        c.texture_format.to_string(),
        format!("{:.2}", c.blocks_per_tile),
    ];
    let ratios =
        |f: fn(&SubsetFootprint) -> f64| c.footprints.iter().map(move |x| format!("{:.5}", f(x)));
    fields
        .into_iter()
        .chain(ratios(|f| f.footprint_ratio))
        .chain(ratios(|f| f.warp_ratio))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::def::Game;

    #[test]
    fn table_and_csv_of_a_procedural_scene() {
        let def = SceneDef {
            name: "procedural-sprites".into(),
            ..crate::def::test_def(Game::Procedural, "sprites", "full", 256, 128)
        };
        let c = characterize_def(&def, false).unwrap();
        assert_eq!(c.footprints.len(), SubsetSpec::all().len());
        assert!(c.workload.starts_with("procedural:"));
        let t = table(std::slice::from_ref(&c));
        assert!(
            t.contains("memory-instr ratio") && t.contains("0.07-0.26"),
            "{t}"
        );
        assert!(t.contains("footprint mesh4 (0.062)"), "{t}");
        let v = csv(std::slice::from_ref(&c));
        assert_eq!(v.lines().count(), 2);
        assert_eq!(
            v.lines().next().unwrap().split(',').count(),
            v.lines().nth(1).unwrap().split(',').count()
        );
        let j = serde_json::to_value(&c).unwrap();
        assert!(j["footprints"][0]["paper"].is_number());
        // Sprites over a backdrop: overdraw, one warp per fragment.
        assert!(c.warps > c.positions, "{} {}", c.warps, c.positions);
        assert!((c.warps_per_position - c.warps as f64 / c.positions as f64).abs() < 1e-12);
        assert!(t.contains("shaded warps per quad position"), "{t}");
        // Per tile, the percentiles bracket the mean's tiles.
        assert!(c.warps_per_position_p50 >= 1.0);
        assert!(c.warps_per_position_p50 <= c.warps_per_position_p90);
        assert!(c.warps_per_position_p90 <= c.warps_per_position_p99);
        assert_eq!(c.rejected_early_z_share, 0.0, "sprites reject nothing");
        assert_eq!(c.draw_order, DrawOrder::AsLoaded);
        assert!(v.lines().next().unwrap().contains(",draw_order,"));
        assert!(
            v.contains("\nprocedural-sprites,procedural:sprites,256,128,"),
            "{v}"
        );
        let odd = Characterization {
            workload: "a, \"b\"".into(),
            ..c.clone()
        };
        assert!(
            csv(&[odd]).contains(",\"a, \"\"b\"\"\",256,"),
            "quoted as it must be"
        );
        for f in &c.footprints {
            assert!(f.warp_ratio > 0.0 && f.warp_ratio < 1.0, "{f:?}");
        }
    }

    #[test]
    fn the_draw_order_moves_warps_per_position_and_the_early_z_share() {
        let mut def = crate::def::all()
            .unwrap()
            .into_iter()
            .find(|d| d.name == "procedural-plane")
            .unwrap();
        (def.width, def.height) = (392, 154);
        let by = |o: DrawOrder| {
            let d = SceneDef {
                draw_order: o,
                ..def.clone()
            };
            characterize_def(&d, false).unwrap()
        };
        let loaded = by(DrawOrder::AsLoaded);
        // The ground (one object, loaded first, its bounds' centre far
        // away) is drawn after the blocks standing on it.
        let objects = by(DrawOrder::FrontToBackObject);
        assert_eq!(objects.draw_order, DrawOrder::FrontToBackObject);
        assert_eq!(objects.positions, loaded.positions);
        assert!(objects.warps < loaded.warps);
        assert!(objects.warps_per_position < loaded.warps_per_position);
        assert!(objects.rejected_early_z_share > loaded.rejected_early_z_share);
        // Shaded or rejected, every covered quad is still there.
        assert_eq!(
            objects.warps + objects.rejected_early_z,
            loaded.warps + loaded.rejected_early_z
        );
        let t = table(&[loaded, objects]);
        assert!(t.contains("front-to-back-object"), "{t}");
    }

    #[test]
    fn batched_footprints_equal_the_trace_module_definition() {
        let scene = crate::procedural::plane("ground", "standard").unwrap();
        let f = crate::raster::rasterize(
            &scene,
            320,
            192,
            &RasterOptions {
                colour: false,
                ..RasterOptions::default()
            },
        )
        .unwrap();
        let specs = SubsetSpec::all();
        let (got, warp_ratios) = subset_ratios(&f.trace, &specs);
        assert_eq!(got, mean_footprint_ratios(&f.trace, &specs));
        for ((spec, g), w) in specs.iter().zip(got).zip(warp_ratios) {
            let sel = spec.build(32);
            let want = mean_footprint_ratio(&f.trace, |x, y| sel.is_priority(x, y));
            assert!((g - want).abs() < 1e-12, "{spec}: {g} vs {want}");
            let n = f
                .trace
                .tiles()
                .iter()
                .flat_map(|t| t.quads())
                .filter(|q| sel.is_priority(q.x(), q.y()))
                .count();
            assert!((w - n as f64 / f.trace.quad_count() as f64).abs() < 1e-12);
        }
    }
}
