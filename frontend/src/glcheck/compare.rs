//! The agreement of Mesa's replays of a frame with wasp's rasterization
//! of the same frame, pixel by pixel: coverage, depth complexity and the
//! texture of the last fragment written.

use super::rewrite::name_of_colour;
use crate::raster::PixelMaps;
use serde::Serialize;
use std::collections::BTreeMap;

/// What one side says about one pixel.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PixelView {
    /// Fragments written (that passed the scissor, alpha and depth tests).
    pub count: u32,
    /// The texture of the last fragment written: `None` where none was,
    /// `Some(None)` for an untextured draw, else the GL texture name.
    pub texture: Option<Option<u32>>,
}

/// A side's view of every pixel of the frame.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct View {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<PixelView>,
}

impl View {
    /// Mesa's view from its two replays' images (RGBA8, top row first):
    /// the count replay's red channel and the id replay's colour. Also the
    /// number of pixels of the count image whose channels differ (each
    /// channel counts the same fragments, so none should).
    pub fn from_mesa(width: u32, height: u32, count_rgba: &[u8], id_rgba: &[u8]) -> (View, u64) {
        let mut odd = 0;
        let pixels = count_rgba
            .chunks_exact(4)
            .zip(id_rgba.chunks_exact(4))
            .map(|(c, i)| {
                odd += u64::from(c[0] != c[1] || c[0] != c[2]);
                PixelView {
                    count: u32::from(c[0]),
                    texture: name_of_colour([i[0], i[1], i[2]]),
                }
            })
            .collect();
        let view = View {
            width,
            height,
            pixels,
        };
        (view, odd)
    }

    /// wasp's view from its maps: `written` per pixel, and the texture of
    /// the last material written (`textures[material]`: its first sampled
    /// texture's GL name, `None` untextured).
    pub fn from_wasp(maps: &PixelMaps, textures: &[Option<u32>]) -> View {
        let pixels = maps
            .written
            .iter()
            .zip(&maps.last_material)
            .map(|(&w, &m)| PixelView {
                count: u32::from(w),
                texture: m
                    .checked_sub(1)
                    .map(|m| textures.get(m as usize).copied().flatten()),
            })
            .collect();
        View {
            width: maps.width,
            height: maps.height,
            pixels,
        }
    }
}

/// Coverage: pixels some fragment was written to, on each side.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Coverage {
    pub both: u64,
    pub mesa_only: u64,
    pub wasp_only: u64,
    pub neither: u64,
    /// Pixels where both sides agree (covered or not), % of the frame.
    pub agreement_percent: f64,
}

/// Depth complexity: fragments written per pixel, over the pixels either
/// side covers.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct DepthComplexity {
    /// Pixels compared (covered by either side).
    pub pixels: u64,
    /// Of those, pixels with the same count.
    pub exact: u64,
    pub exact_percent: f64,
    /// Mean of |wasp - Mesa|.
    pub mean_abs_difference: f64,
    pub mesa_mean: f64,
    pub wasp_mean: f64,
    /// wasp's count minus Mesa's (clamped to -5..=5): pixels.
    pub difference_histogram: BTreeMap<i32, u64>,
    /// Pixels by count (the last bin: 8 or more), each side.
    pub mesa_histogram: Vec<u64>,
    pub wasp_histogram: Vec<u64>,
    /// Pixels where Mesa's 8-bit count saturated (255).
    pub mesa_saturated: u64,
}

/// The texture of the last fragment written, over pixels both cover.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct TextureAgreement {
    /// Pixels both sides cover.
    pub pixels: u64,
    /// Of those, pixels naming the same texture.
    pub same: u64,
    pub agreement_percent: f64,
    /// The most frequent disagreements: (Mesa's texture, wasp's, pixels);
    /// a texture is its GL name, or "untextured".
    pub confusions: Vec<(String, String, u64)>,
}

/// The three measures.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Agreement {
    pub width: u32,
    pub height: u32,
    pub coverage: Coverage,
    pub depth_complexity: DepthComplexity,
    pub texture: TextureAgreement,
}

fn percent(n: u64, of: u64) -> f64 {
    if of == 0 {
        100.0
    } else {
        // Four decimals, so the figures print as they are stored.
        (n as f64 * 1_000_000.0 / of as f64).round() / 10_000.0
    }
}

fn texture_name(t: Option<Option<u32>>) -> String {
    match t {
        None => "none".into(),
        Some(None) => "untextured".into(),
        Some(Some(n)) => n.to_string(),
    }
}

/// Compares the two views (of the same size).
pub fn compare(mesa: &View, wasp: &View) -> Agreement {
    let mut a = Agreement {
        width: mesa.width,
        height: mesa.height,
        ..Default::default()
    };
    let (c, d, t) = (&mut a.coverage, &mut a.depth_complexity, &mut a.texture);
    d.mesa_histogram = vec![0; 9];
    d.wasp_histogram = vec![0; 9];
    let (mut abs, mut sum_m, mut sum_w) = (0u64, 0u64, 0u64);
    let mut confusions: BTreeMap<(String, String), u64> = BTreeMap::new();
    for (m, w) in mesa.pixels.iter().zip(&wasp.pixels) {
        match (m.count > 0, w.count > 0) {
            (true, true) => c.both += 1,
            (true, false) => c.mesa_only += 1,
            (false, true) => c.wasp_only += 1,
            (false, false) => {
                c.neither += 1;
                continue;
            }
        }
        d.pixels += 1;
        d.exact += u64::from(m.count == w.count);
        abs += u64::from(m.count.abs_diff(w.count));
        sum_m += u64::from(m.count);
        sum_w += u64::from(w.count);
        let diff = (i64::from(w.count) - i64::from(m.count)).clamp(-5, 5) as i32;
        *d.difference_histogram.entry(diff).or_default() += 1;
        d.mesa_histogram[m.count.min(8) as usize] += 1;
        d.wasp_histogram[w.count.min(8) as usize] += 1;
        d.mesa_saturated += u64::from(m.count >= 255);
        if m.count > 0 && w.count > 0 {
            t.pixels += 1;
            if m.texture == w.texture {
                t.same += 1;
            } else {
                let key = (texture_name(m.texture), texture_name(w.texture));
                *confusions.entry(key).or_default() += 1;
            }
        }
    }
    let total = mesa.pixels.len() as u64;
    c.agreement_percent = percent(c.both + c.neither, total);
    d.exact_percent = percent(d.exact, d.pixels);
    let mean = |s: u64| {
        if d.pixels == 0 {
            0.0
        } else {
            s as f64 / d.pixels as f64
        }
    };
    (d.mean_abs_difference, d.mesa_mean, d.wasp_mean) = (mean(abs), mean(sum_m), mean(sum_w));
    t.agreement_percent = percent(t.same, t.pixels);
    let mut conf: Vec<(String, String, u64)> = confusions
        .into_iter()
        .map(|((m, w), n)| (m, w, n))
        .collect();
    conf.sort_by(|x, y| y.2.cmp(&x.2).then_with(|| (&x.0, &x.1).cmp(&(&y.0, &y.1))));
    conf.truncate(10);
    t.confusions = conf;
    a
}

impl Agreement {
    /// The figures as text, one measure per line.
    pub fn text(&self) -> String {
        let (c, d, t) = (&self.coverage, &self.depth_complexity, &self.texture);
        let mut s = format!(
            "coverage agreement: {:.4}% of {}x{} pixels (both {}, Mesa only {}, wasp only {}, \
             neither {})\n",
            c.agreement_percent,
            self.width,
            self.height,
            c.both,
            c.mesa_only,
            c.wasp_only,
            c.neither
        );
        s += &format!(
            "depth complexity: {:.4}% exact over {} covered pixels, mean |wasp - Mesa| {:.6}, \
             mean Mesa {:.4}, wasp {:.4}\n",
            d.exact_percent, d.pixels, d.mean_abs_difference, d.mesa_mean, d.wasp_mean
        );
        let hist: Vec<String> = d
            .difference_histogram
            .iter()
            .map(|(k, v)| format!("{k:+}: {v}"))
            .collect();
        s += &format!("  wasp - Mesa: {}\n", hist.join(", "));
        s += &format!(
            "texture agreement: {:.4}% of {} pixels both cover\n",
            t.agreement_percent, t.pixels
        );
        for (m, w, n) in &t.confusions {
            s += &format!("  Mesa {m}, wasp {w}: {n} pixels\n");
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn px(count: u32, tex: Option<Option<u32>>) -> PixelView {
        PixelView {
            count,
            texture: tex,
        }
    }

    #[test]
    fn the_three_measures_count_what_each_side_says() {
        let view = |p: Vec<PixelView>| View {
            width: p.len() as u32,
            height: 1,
            pixels: p,
        };
        let mesa = view(vec![
            px(0, None),
            px(1, Some(Some(3))),
            px(2, Some(Some(3))),
            px(1, Some(None)),
            px(0, None),
        ]);
        let wasp = view(vec![
            px(0, None),
            px(1, Some(Some(3))),
            px(3, Some(Some(4))),
            px(0, None),
            px(2, Some(Some(4))),
        ]);
        let a = compare(&mesa, &wasp);
        let c = &a.coverage;
        assert_eq!((c.both, c.mesa_only, c.wasp_only, c.neither), (2, 1, 1, 1));
        assert_eq!(c.agreement_percent, 60.0);
        let d = &a.depth_complexity;
        assert_eq!((d.pixels, d.exact), (4, 1));
        assert_eq!(d.mean_abs_difference, 1.0);
        assert_eq!(
            d.difference_histogram,
            [(-1, 1), (0, 1), (1, 1), (2, 1)].into()
        );
        let t = &a.texture;
        assert_eq!((t.pixels, t.same, t.agreement_percent), (2, 1, 50.0));
        assert_eq!(t.confusions, [("3".into(), "4".into(), 1)]);
        assert!(a.text().contains("coverage agreement: 60.0000%"));
    }

    #[test]
    fn mesa_images_decode_to_counts_and_names() {
        let count = [2, 2, 2, 255, 1, 0, 1, 255];
        let id = [3, 0, 0, 255, 255, 255, 255, 255];
        let (v, odd) = View::from_mesa(2, 1, &count, &id);
        assert_eq!(odd, 1);
        assert_eq!(v.pixels, [px(2, Some(Some(2))), px(1, Some(None))]);
        let maps = PixelMaps {
            width: 2,
            height: 1,
            shaded: vec![3, 0],
            written: vec![2, 0],
            last_material: vec![2, 0],
        };
        let w = View::from_wasp(&maps, &[None, Some(7)]);
        assert_eq!(w.pixels, [px(2, Some(Some(7))), px(0, None)]);
    }
}
