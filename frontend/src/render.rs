//! `wasp render`: the rasterized frame as a PNG with the real texel
//! colours, and overlays that show what the cycle model sees.
//!
//! Overlays ([`Overlay`], parsed from the command line):
//!
//! * `grid` — the 64x64-pixel tile grid.
//! * `subset[:SUBSET]` — tints the priority quads of a priority subset
//!   (default `mesh4`; any of `mesh2|4|8|16`, `hlines`, `vlines`, `top16`,
//!   `random[:seed]`), positions taken from the hardware selector itself.
//! * `heat[:STAT]` — a per-quad heat map of a per-warp statistic of a cycle
//!   model run on the frame's trace: `latency` (default: the mean memory
//!   latency of the warp's texture instructions), `cycles` (launch to
//!   finish) or `launch` (launch cycle after the tile's first launch, so
//!   the launch order shows). With overdraw a quad position holds several
//!   warps (one per fragment): the map shows the **mean** of their values
//!   (the legend says `MEAN ... PER QUAD`), so a position is as hot as its
//!   typical warp; the range and percentiles are over these per-position
//!   means. Quads without a value keep a dimmed picture.
//!   The colour scale runs from the minimum to the 99th percentile (above
//!   it: red); a colour bar with the minimum, the 99th percentile and the
//!   maximum is drawn bottom right.

use super::raster::{rasterize_timed, DrawOrder, Frame, RasterOptions};
use super::texture::FormatChoice;
use super::{Scene, SceneError};
use std::fmt;
use std::path::Path;
use std::str::FromStr;
use wasp_rtl::subset::SubsetSpec;

/// A per-warp statistic for the heat map.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HeatStat {
    /// Mean memory latency of the warp's texture instructions (cycles).
    Latency,
    /// Cycles from launch to finish.
    Cycles,
    /// Launch cycle after the first launch of its tile.
    Launch,
}

impl HeatStat {
    /// Legend label.
    pub fn label(self) -> &'static str {
        match self {
            HeatStat::Latency => "MEAN MEM LATENCY PER QUAD (CYCLES)",
            HeatStat::Cycles => "MEAN WARP CYCLES PER QUAD",
            HeatStat::Launch => "MEAN LAUNCH CYCLE IN TILE PER QUAD",
        }
    }
}

/// One overlay drawn over the frame.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Overlay {
    /// Tile grid lines.
    Grid,
    /// Tint the priority quads of this subset.
    Subset(SubsetSpec),
    /// Heat map of a per-warp statistic (needs a cycle-model run).
    Heat(HeatStat),
}

impl FromStr for Overlay {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let lower = s.trim().to_ascii_lowercase();
        let (head, arg) = match lower.split_once(':') {
            Some((h, a)) => (h, Some(a)),
            None => (lower.as_str(), None),
        };
        match (head, arg) {
            ("grid", None) => Ok(Overlay::Grid),
            ("subset", None) => Ok(Overlay::Subset(SubsetSpec::Mesh(4))),
            ("subset", Some(a)) => a.parse().map(Overlay::Subset),
            ("heat", None | Some("latency")) => Ok(Overlay::Heat(HeatStat::Latency)),
            ("heat", Some("cycles")) => Ok(Overlay::Heat(HeatStat::Cycles)),
            ("heat", Some("launch")) => Ok(Overlay::Heat(HeatStat::Launch)),
            _ => Err(format!(
                "unknown overlay `{s}` (expected grid, subset[:SUBSET] or \
                 heat[:latency|cycles|launch])"
            )),
        }
    }
}

impl fmt::Display for Overlay {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Overlay::Grid => f.write_str("grid"),
            Overlay::Subset(s) => write!(f, "subset:{s}"),
            Overlay::Heat(HeatStat::Latency) => f.write_str("heat:latency"),
            Overlay::Heat(HeatStat::Cycles) => f.write_str("heat:cycles"),
            Overlay::Heat(HeatStat::Launch) => f.write_str("heat:launch"),
        }
    }
}

/// Why a render failed.
#[derive(Debug)]
pub enum RenderError {
    /// Loading or rasterizing the scene.
    Scene(SceneError),
    /// The values of a heat map (the caller's cycle-model run).
    Heat(String),
    /// Encoding or writing the picture.
    Image(String),
}

impl fmt::Display for RenderError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            RenderError::Scene(e) => write!(f, "{e}"),
            RenderError::Heat(e) => write!(f, "cycle model: {e}"),
            RenderError::Image(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for RenderError {}

/// What to render.
#[derive(Clone, Debug)]
pub struct RenderRequest {
    /// Overlays in drawing order.
    pub overlays: Vec<Overlay>,
    /// Tile edge in pixels (the machine's `gpu.tile_size`).
    pub tile: u32,
    /// Hidden-surface removal by a depth pre-pass (see
    /// [`RasterOptions::depth_prepass`]).
    pub depth_prepass: bool,
    /// Front-end worker threads ([`RasterOptions::threads`]; 0: one per
    /// hardware thread).
    pub threads: usize,
    /// The order of the opaque geometry ([`RasterOptions::draw_order`]).
    pub draw_order: DrawOrder,
    /// How the textures are stored ([`RasterOptions::texture_format`]).
    pub texture_format: FormatChoice,
    /// List decoded texture lines ([`RasterOptions::decoded_lines`]).
    pub decoded_lines: bool,
}

/// A rendered frame.
#[derive(Debug)]
pub struct Rendered {
    /// The rasterized frame (trace, picture, counts).
    pub frame: Frame,
    /// The picture with overlays, RGBA8.
    pub image: Vec<u8>,
    /// Seconds the front end took.
    pub raster_seconds: f64,
    /// The heat map's value range, if drawn.
    pub heat_range: Option<(f64, f64)>,
}

/// One warp's value of a heat-map statistic: the warp is quad `quad` of
/// tile `tile` (indices into the frame's trace).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WarpValue {
    /// Tile index in the trace.
    pub tile: u32,
    /// Quad (warp) index in the tile.
    pub quad: u32,
    /// The value.
    pub value: f64,
}

/// Gives every warp's value of a heat statistic for a rendered frame (the
/// caller's cycle-model run), or why it could not.
pub type HeatSource<'a> = dyn FnMut(&Frame, HeatStat) -> Result<Vec<WarpValue>, String> + 'a;

/// Rasterize `scene` at `width` x `height` and draw the overlays. A heat
/// overlay asks `heat` for every warp's value of its statistic (the caller
/// runs the cycle model on the frame's trace; the front end knows nothing
/// of the machine).
pub fn render(
    scene: &Scene,
    width: u32,
    height: u32,
    req: &RenderRequest,
    heat: &mut HeatSource<'_>,
) -> Result<Rendered, RenderError> {
    let opts = RasterOptions {
        tile: req.tile,
        depth_prepass: req.depth_prepass,
        threads: req.threads,
        draw_order: req.draw_order,
        texture_format: req.texture_format,
        decoded_lines: req.decoded_lines,
        ..RasterOptions::default()
    };
    let (frame, raster_seconds) =
        rasterize_timed(scene, width, height, &opts).map_err(RenderError::Scene)?;
    let mut values: Vec<(HeatStat, Vec<WarpValue>)> = Vec::new();
    for o in &req.overlays {
        if let Overlay::Heat(stat) = o {
            if !values.iter().any(|(s, _)| s == stat) {
                values.push((*stat, heat(&frame, *stat).map_err(RenderError::Heat)?));
            }
        }
    }
    let (image, heat_range) = compose(&frame, &req.overlays, &values);
    Ok(Rendered {
        frame,
        image,
        raster_seconds,
        heat_range,
    })
}

/// The frame's picture with `overlays` drawn in order; a heat map uses the
/// values given for its statistic (none: it is skipped). Returns the
/// picture and the last heat map's value range.
pub fn compose(
    frame: &Frame,
    overlays: &[Overlay],
    heat_values_by_stat: &[(HeatStat, Vec<WarpValue>)],
) -> (Vec<u8>, Option<(f64, f64)>) {
    let mut img = Canvas {
        w: frame.width,
        h: frame.height,
        px: frame.image.clone(),
    };
    let tile = frame.trace.header().tile;
    let side = tile / 2;
    let mut range = None;
    for o in overlays {
        match o {
            Overlay::Grid => {
                for x in (tile..frame.width).step_by(tile as usize) {
                    img.fill_rect(x, 0, 1, frame.height, [255, 230, 60], 0.75);
                }
                for y in (tile..frame.height).step_by(tile as usize) {
                    img.fill_rect(0, y, frame.width, 1, [255, 230, 60], 0.75);
                }
            }
            Overlay::Subset(spec) => {
                let sel = spec.build(side);
                for py in (0..frame.height).step_by(2) {
                    for px in (0..frame.width).step_by(2) {
                        let (qx, qy) = ((px % tile) / 2, (py % tile) / 2);
                        if sel.is_priority(qx, qy) {
                            img.fill_rect(px, py, 2, 2, [255, 30, 30], 0.7);
                        }
                    }
                }
            }
            Overlay::Heat(stat) => {
                if let Some((_, v)) = heat_values_by_stat.iter().find(|(s, _)| s == stat) {
                    range = heat(&mut img, frame, v, *stat);
                }
            }
        }
    }
    (img.px, range)
}

/// Per-quad values of a statistic: (top-left pixel x, y, value), one per
/// quad position with a value, in scanline order of the frame; the value is
/// the mean over the position's warps (in the given order, so the result is
/// deterministic). Values naming no quad of the trace, or not finite, are
/// left out.
pub fn heat_values(frame: &Frame, values: &[WarpValue]) -> Vec<(u32, u32, f64)> {
    let tiles = frame.trace.tiles();
    let t = frame.trace.header().tile;
    let mut per_warp: Vec<(u32, u32, f64)> = values
        .iter()
        .filter(|w| w.value.is_finite())
        .filter_map(|w| {
            let tile = tiles.get(w.tile as usize)?;
            let q = tile.quad(w.quad as usize)?;
            Some((
                tile.tx() * t + 2 * q.x(),
                tile.ty() * t + 2 * q.y(),
                w.value,
            ))
        })
        .collect();
    // Stable: a position's values stay in the given order.
    per_warp.sort_by_key(|&(x, y, _)| (y, x));
    let mut out: Vec<(u32, u32, f64)> = Vec::new();
    let mut n = 0u32;
    for (x, y, v) in per_warp {
        match out.last_mut() {
            Some(last) if (last.0, last.1) == (x, y) => {
                n += 1;
                last.2 += (v - last.2) / f64::from(n);
            }
            _ => {
                out.push((x, y, v));
                n = 1;
            }
        }
    }
    out
}

fn heat(
    img: &mut Canvas,
    frame: &Frame,
    values: &[WarpValue],
    stat: HeatStat,
) -> Option<(f64, f64)> {
    let vals = heat_values(frame, values);
    // Dim the picture: the heat reads on top of a grey frame.
    for p in img.px.chunks_exact_mut(4) {
        let l = (u32::from(p[0]) * 3 + u32::from(p[1]) * 6 + u32::from(p[2])) / 10;
        let g = (l * 2 / 5) as u8;
        p[0] = g;
        p[1] = g;
        p[2] = g;
    }
    if vals.is_empty() {
        return None;
    }
    let mut sorted: Vec<f64> = vals.iter().map(|v| v.2).collect();
    sorted.sort_unstable_by(f64::total_cmp);
    let lo = sorted[0];
    let hi = sorted[sorted.len() - 1];
    // The colour scale ends at the 99th percentile (a few outliers would
    // otherwise paint everything else one colour); above it is red.
    let p99 = sorted[((sorted.len() - 1) as f64 * 0.99).round() as usize];
    let top = if p99 > lo { p99 } else { hi };
    let span = if top > lo { top - lo } else { 1.0 };
    for &(x, y, v) in &vals {
        let c = colour_map(((v - lo) / span) as f32);
        img.fill_rect(x, y, 2, 2, c, 0.9);
    }
    legend(img, stat.label(), lo, top, hi);
    Some((lo, hi))
}

/// Dark blue - blue - cyan - yellow - red.
pub fn colour_map(t: f32) -> [u8; 3] {
    const STOPS: [[f32; 3]; 5] = [
        [0.05, 0.03, 0.35],
        [0.10, 0.35, 0.90],
        [0.10, 0.80, 0.70],
        [0.95, 0.85, 0.15],
        [0.85, 0.10, 0.05],
    ];
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) } * 4.0;
    let i = (t.floor() as usize).min(3);
    let f = t - i as f32;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    let q = |k: usize| ((a[k] + (b[k] - a[k]) * f) * 255.0 + 0.5) as u8;
    [q(0), q(1), q(2)]
}

fn fmt_value(v: f64) -> String {
    if v.abs() >= 100.0 {
        format!("{v:.0}")
    } else {
        format!("{v:.1}")
    }
}

fn legend(img: &mut Canvas, label: &str, lo: f64, top: f64, hi: f64) {
    let s = 2u32;
    let bar_w = 320u32.min(img.w.saturating_sub(40));
    let box_w = bar_w + 24;
    let box_h = 14 + 6 * s + 16 + 6 * s + 12;
    if img.w < box_w + 8 || img.h < box_h + 8 {
        return;
    }
    let (x0, y0) = (img.w - box_w - 8, img.h - box_h - 8);
    img.fill_rect(x0, y0, box_w, box_h, [0, 0, 0], 0.75);
    img.text(x0 + 12, y0 + 6, label, s, [255, 255, 255]);
    let by = y0 + 8 + 6 * s;
    for i in 0..bar_w {
        let c = colour_map(i as f32 / (bar_w - 1).max(1) as f32);
        img.fill_rect(x0 + 12 + i, by, 1, 16, c, 1.0);
    }
    let ty = by + 20;
    img.text(
        x0 + 12,
        ty,
        &format!("MIN {}", fmt_value(lo)),
        s,
        [220, 220, 220],
    );
    let max = if top < hi {
        format!("P99 {} MAX {}", fmt_value(top), fmt_value(hi))
    } else {
        format!("MAX {}", fmt_value(hi))
    };
    let mw = max.len() as u32 * 4 * s;
    img.text(x0 + 12 + bar_w - mw, ty, &max, s, [220, 220, 220]);
}

/// An RGBA8 picture being drawn on.
struct Canvas {
    w: u32,
    h: u32,
    px: Vec<u8>,
}

impl Canvas {
    fn fill_rect(&mut self, x: u32, y: u32, w: u32, h: u32, c: [u8; 3], alpha: f32) {
        let (x1, y1) = ((x + w).min(self.w), (y + h).min(self.h));
        for yy in y.min(self.h)..y1 {
            for xx in x.min(self.w)..x1 {
                let i = (yy as usize * self.w as usize + xx as usize) * 4;
                for (p, &ck) in self.px[i..i + 3].iter_mut().zip(&c) {
                    let d = f32::from(*p);
                    *p = (d + (f32::from(ck) - d) * alpha + 0.5) as u8;
                }
                self.px[i + 3] = 255;
            }
        }
    }

    fn text(&mut self, x: u32, y: u32, text: &str, s: u32, c: [u8; 3]) {
        for (i, ch) in text.chars().enumerate() {
            let Some(g) = glyph(ch) else { continue };
            let gx = x + i as u32 * 4 * s;
            for (row, bits) in g.iter().enumerate() {
                for col in 0..3u32 {
                    if bits & (4 >> col) != 0 {
                        self.fill_rect(gx + col * s, y + row as u32 * s, s, s, c, 1.0);
                    }
                }
            }
        }
    }
}

/// A 3x5 pixel font: five rows of three bits (bit 2 is the left column)
/// for digits, A-Z (either case), space and `.-:()/%`.
pub fn glyph(c: char) -> Option<[u8; 5]> {
    let g = match c.to_ascii_uppercase() {
        '0' => [7, 5, 5, 5, 7],
        '1' => [2, 6, 2, 2, 7],
        '2' => [7, 1, 7, 4, 7],
        '3' => [7, 1, 7, 1, 7],
        '4' => [5, 5, 7, 1, 1],
        '5' => [7, 4, 7, 1, 7],
        '6' => [7, 4, 7, 5, 7],
        '7' => [7, 1, 1, 1, 1],
        '8' => [7, 5, 7, 5, 7],
        '9' => [7, 5, 7, 1, 7],
        ' ' => [0, 0, 0, 0, 0],
        '.' => [0, 0, 0, 0, 2],
        '-' => [0, 0, 7, 0, 0],
        ':' => [0, 2, 0, 2, 0],
        '(' => [1, 2, 2, 2, 1],
        ')' => [4, 2, 2, 2, 4],
        '/' => [1, 1, 2, 4, 4],
        '%' => [5, 1, 2, 4, 5],
        'A' => [2, 5, 7, 5, 5],
        'B' => [6, 5, 6, 5, 6],
        'C' => [3, 4, 4, 4, 3],
        'D' => [6, 5, 5, 5, 6],
        'E' => [7, 4, 6, 4, 7],
        'F' => [7, 4, 6, 4, 4],
        'G' => [3, 4, 5, 5, 3],
        'H' => [5, 5, 7, 5, 5],
        'I' => [7, 2, 2, 2, 7],
        'J' => [1, 1, 1, 5, 2],
        'K' => [5, 5, 6, 5, 5],
        'L' => [4, 4, 4, 4, 7],
        'M' => [5, 7, 7, 5, 5],
        'N' => [6, 5, 5, 5, 5],
        'O' => [2, 5, 5, 5, 2],
        'P' => [6, 5, 6, 4, 4],
        'Q' => [2, 5, 5, 6, 3],
        'R' => [6, 5, 6, 5, 5],
        'S' => [3, 4, 2, 1, 6],
        'T' => [7, 2, 2, 2, 2],
        'U' => [5, 5, 5, 5, 7],
        'V' => [5, 5, 5, 5, 2],
        'W' => [5, 5, 7, 7, 5],
        'X' => [5, 5, 2, 5, 5],
        'Y' => [5, 5, 2, 2, 2],
        'Z' => [7, 1, 2, 4, 7],
        _ => return None,
    };
    Some(g)
}

/// The picture as PNG bytes.
pub fn encode_png(rgba: &[u8], width: u32, height: u32) -> Result<Vec<u8>, RenderError> {
    use image::ImageEncoder;
    let mut out = Vec::new();
    image::codecs::png::PngEncoder::new(&mut out)
        .write_image(rgba, width, height, image::ExtendedColorType::Rgba8)
        .map_err(|e| RenderError::Image(format!("encoding PNG: {e}")))?;
    Ok(out)
}

/// Write the picture as a PNG file.
pub fn write_png(path: &Path, rgba: &[u8], width: u32, height: u32) -> Result<(), RenderError> {
    let bytes = encode_png(rgba, width, height)?;
    std::fs::write(path, bytes)
        .map_err(|e| RenderError::Image(format!("cannot write {}: {e}", path.display())))
}

/// The picture of `scene` at `width` x `height`, no overlay, written to
/// `out` as PNG: what the loaders' preview tests write for a person to
/// look at, through the one rasterizer every scene goes through.
#[cfg(test)]
pub(crate) fn write_preview(scene: &Scene, width: u32, height: u32, out: &Path) {
    let req = RenderRequest {
        overlays: Vec::new(),
        tile: 64,
        depth_prepass: false,
        threads: 0,
        draw_order: DrawOrder::AsLoaded,
        texture_format: FormatChoice::Rgba8,
        decoded_lines: false,
    };
    let r = render(scene, width, height, &req, &mut |_, _| Ok(Vec::new())).expect("renders");
    write_png(out, &r.image, width, height).expect("writes the PNG");
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::procedural;

    fn small_frame() -> Frame {
        let scene = procedural::plane("ground", "lightmapped").unwrap();
        super::super::raster::rasterize(&scene, 192, 128, &RasterOptions::default()).unwrap()
    }

    #[test]
    fn png_decodes_with_the_frame_size() {
        let f = small_frame();
        let (img, _) = compose(&f, &[Overlay::Grid], &[]);
        let png = encode_png(&img, f.width, f.height).unwrap();
        let back = image::load_from_memory(&png).unwrap().to_rgba8();
        assert_eq!((back.width(), back.height()), (192, 128));
        assert_eq!(back.as_raw(), &img);
        // The grid changed the pixels on the tile boundary only.
        let i = (10 * 192 + 64) * 4;
        assert_ne!(img[i..i + 3], f.image[i..i + 3]);
        let j = (10 * 192 + 65) * 4;
        assert_eq!(img[j..j + 4], f.image[j..j + 4]);
    }

    #[test]
    fn heat_overlay_changes_pixels_and_subset_tints_mesh4() {
        let f = small_frame();
        // Every warp's value: its quad index.
        let vals: Vec<WarpValue> = f
            .trace
            .tiles()
            .iter()
            .enumerate()
            .flat_map(|(t, tile)| {
                (0..tile.quad_count()).map(move |q| WarpValue {
                    tile: t as u32,
                    quad: q as u32,
                    value: q as f64,
                })
            })
            .collect();
        let (heat, range) = compose(
            &f,
            &[Overlay::Heat(HeatStat::Latency)],
            &[(HeatStat::Latency, vals)],
        );
        let (lo, hi) = range.expect("values");
        assert!(lo >= 0.0 && hi > lo, "{lo} {hi}");
        let changed = heat
            .chunks_exact(4)
            .zip(f.image.chunks_exact(4))
            .filter(|(a, b)| a != b)
            .count();
        assert!(changed > (192 * 128) / 2, "{changed}");
        // Without values for its statistic a heat overlay draws nothing.
        let (none, r) = compose(&f, &[Overlay::Heat(HeatStat::Cycles)], &[]);
        assert_eq!((none, r), (f.image.clone(), None));
        let (sub, _) = compose(&f, &[Overlay::Subset(SubsetSpec::Mesh(4))], &[]);
        // Quad (0, 0) of tile 0 is Mesh4 priority, quad (1, 0) is not.
        assert_ne!(sub[0..4], f.image[0..4]);
        assert_eq!(sub[8..12], f.image[8..12]);
    }

    #[test]
    fn heat_values_are_the_mean_over_the_warps_of_a_position() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../tests/traces/overdraw.trace"
        );
        let trace = crate::trace::Trace::read(path).unwrap();
        let frame = Frame {
            trace,
            width: 16,
            height: 8,
            image: vec![0; 16 * 8 * 4],
            stats: Default::default(),
            timings: Default::default(),
        };
        let w = |quad: u32, value: f64| WarpValue {
            tile: 0,
            quad,
            value,
        };
        // Quads 5 and 6 share position (1, 1); 2 and 4 share (0, 1).
        let vals = [
            w(6, 30.0),
            w(0, 7.0),
            w(5, 10.0),
            w(2, f64::NAN),
            w(4, 4.0),
            w(99, 1.0),
        ];
        let v = heat_values(&frame, &vals);
        assert_eq!(v, vec![(0, 0, 7.0), (0, 2, 4.0), (2, 2, 20.0)]);
        assert!(HeatStat::Latency.label().starts_with("MEAN"));
    }

    #[test]
    fn overlays_parse() {
        assert_eq!("grid".parse::<Overlay>().unwrap(), Overlay::Grid);
        assert_eq!(
            "subset".parse::<Overlay>().unwrap(),
            Overlay::Subset(SubsetSpec::Mesh(4))
        );
        assert_eq!(
            "subset:top16".parse::<Overlay>().unwrap(),
            Overlay::Subset(SubsetSpec::Top16)
        );
        assert_eq!(
            "heat".parse::<Overlay>().unwrap(),
            Overlay::Heat(HeatStat::Latency)
        );
        assert!("heat:colour".parse::<Overlay>().is_err());
        assert!("subset:mesh3".parse::<Overlay>().is_err());
        for o in ["grid", "subset:mesh2", "heat:launch", "heat:cycles"] {
            assert_eq!(o.parse::<Overlay>().unwrap().to_string(), o);
        }
    }

    #[test]
    fn every_digit_and_letter_has_a_glyph() {
        for c in ('0'..='9').chain('A'..='Z').chain('a'..='z') {
            assert!(glyph(c).is_some(), "{c}");
        }
        assert!(glyph('~').is_none());
    }
}
