//! The one palette of wasp's pictures: the reproduction's figures
//! ([`crate::charts`]) and the timeline ([`crate::timeline_plot`]).
//!
//! A series whose name starts with a policy (`baseline`, `fullpriority`,
//! `freemshr:10`, `wasp:0:3`, `WaSP, all`, `wasp-m:0`, `oracle-tile`,
//! `raster`) or a scene group (`3D`, `2D`, `games`, `procedural`, also as
//! `mean 3D`) always has that key's colour ([`named`]), whatever figure it
//! is in. Other series (subsets, cache levels of a chart, cores of the
//! timeline) take the colours of [`OTHERS`] in order, which are none of the
//! named ones. [`series_colours`] gives a chart's series their colours,
//! each distinct: a second series of the same key (e.g. `WaSP, priority
//! warps` beside `WaSP, all`) gets a darker, then a lighter shade of it.

use plotters::style::RGBColor;

/// The colour of each key, by the lower-case first word of a series name.
const NAMED: [(&str, RGBColor); 14] = [
    ("baseline", RGBColor(127, 127, 127)),
    ("scanline", RGBColor(127, 127, 127)),
    ("fullpriority", RGBColor(255, 127, 14)),
    ("full-priority", RGBColor(255, 127, 14)),
    ("freemshr", RGBColor(148, 103, 189)),
    ("wasp", RGBColor(31, 119, 180)),
    ("wasp-m", RGBColor(23, 190, 207)),
    ("oracle", RGBColor(140, 86, 75)),
    ("oracle-tile", RGBColor(140, 86, 75)),
    ("raster", RGBColor(227, 119, 194)),
    ("3d", RGBColor(44, 160, 44)),
    ("2d", RGBColor(214, 39, 40)),
    ("games", RGBColor(188, 189, 34)),
    ("procedural", RGBColor(82, 84, 163)),
];

/// The colours of series that are no named key, and of the timeline's
/// cores, in order (ColorBrewer's Dark2 and two more).
pub const OTHERS: [RGBColor; 10] = [
    RGBColor(27, 158, 119),
    RGBColor(217, 95, 2),
    RGBColor(117, 112, 179),
    RGBColor(231, 41, 138),
    RGBColor(102, 166, 30),
    RGBColor(230, 171, 2),
    RGBColor(166, 118, 29),
    RGBColor(102, 102, 102),
    RGBColor(0, 90, 50),
    RGBColor(120, 0, 60),
];

/// The timeline's cache levels L0, L1, L2.
pub const LEVELS: [RGBColor; 3] = [
    RGBColor(106, 61, 154),
    RGBColor(0, 139, 139),
    RGBColor(160, 60, 20),
];

/// Grid lines.
pub const GRID: RGBColor = RGBColor(225, 225, 225);
/// Reference and zero lines; marks that belong to no series.
pub const INK: RGBColor = RGBColor(60, 60, 60);
/// Tile starts in the timeline.
pub const TILE_START: RGBColor = RGBColor(40, 40, 40);
/// Tile ends in the timeline.
pub const TILE_END: RGBColor = RGBColor(200, 30, 30);

/// The key of a series name: its first word, lower case, after a leading
/// `mean ` (`"WaSP, all"` -> `wasp`, `"wasp:0:3"` -> `wasp`, `"mean 3D"`
/// -> `3d`).
fn key(name: &str) -> String {
    let lower = name.trim().to_ascii_lowercase();
    let rest = lower.strip_prefix("mean ").unwrap_or(&lower);
    rest.split([',', ' ', ':', '(', '@'])
        .next()
        .unwrap_or("")
        .to_string()
}

/// The colour of a series whose name starts with a named key.
pub fn named(name: &str) -> Option<RGBColor> {
    let k = key(name);
    NAMED.iter().find(|(n, _)| *n == k).map(|&(_, c)| c)
}

/// Other colour `i` (repeating past [`OTHERS`]).
pub fn other(i: usize) -> RGBColor {
    OTHERS[i % OTHERS.len()]
}

/// `c` darkened (`f` < 1) or lightened towards white (`f` > 1).
pub fn shade(c: RGBColor, f: f64) -> RGBColor {
    let s = |v: u8| {
        let v = f64::from(v);
        let out = if f <= 1.0 {
            v * f
        } else {
            255.0 - (255.0 - v) / f
        };
        out.round().clamp(0.0, 255.0) as u8
    };
    RGBColor(s(c.0), s(c.1), s(c.2))
}

/// The colours of a chart's series, in order: each named key its colour
/// (a repeat of a key darker, then lighter, by turns), other series the
/// [`OTHERS`] in order.
pub fn series_colours<S: AsRef<str>>(names: &[S]) -> Vec<RGBColor> {
    let mut repeats: Vec<(RGBColor, usize)> = Vec::new();
    let mut others = 0;
    names
        .iter()
        .map(|n| match named(n.as_ref()) {
            Some(c) => {
                let k = match repeats.iter_mut().find(|r| r.0 == c) {
                    Some(r) => {
                        r.1 += 1;
                        r.1
                    }
                    None => {
                        repeats.push((c, 0));
                        0
                    }
                };
                let step = k.div_ceil(2);
                match k {
                    0 => c,
                    _ if k % 2 == 1 => shade(c, 0.8f64.powi(step as i32)),
                    _ => shade(c, 1.0 + 0.6 * step as f64),
                }
            }
            None => {
                others += 1;
                other(others - 1)
            }
        })
        .collect()
}

/// The diverging scale of heat maps at `t` in [-1, 1]: red below 0, white
/// at 0, blue above (ColorBrewer's RdBu ends).
pub fn diverging(t: f64) -> RGBColor {
    let t = if t.is_finite() {
        t.clamp(-1.0, 1.0)
    } else {
        0.0
    };
    let end = if t < 0.0 {
        RGBColor(178, 24, 43)
    } else {
        RGBColor(33, 102, 172)
    };
    let mix = |e: u8| (255.0 + (f64::from(e) - 255.0) * t.abs()).round() as u8;
    RGBColor(mix(end.0), mix(end.1), mix(end.2))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_policy_has_one_colour_in_every_spelling() {
        let wasp = named("wasp").expect("wasp");
        for name in ["wasp:0:3", "WaSP", "WaSP, all", "wasp:6", "WaSP@48"] {
            assert_eq!(named(name), Some(wasp), "{name}");
        }
        assert_ne!(named("wasp-m:0"), Some(wasp));
        assert_eq!(named("freemshr:10"), named("freemshr"));
        assert_eq!(named("mean 3D"), named("3D"));
        assert_eq!(named("Mesh4 (size ratio 1/16)"), None);
    }

    #[test]
    fn other_colours_are_no_named_colour() {
        for c in OTHERS {
            assert!(NAMED.iter().all(|(_, n)| *n != c), "{c:?}");
        }
    }

    #[test]
    fn a_chart_gets_distinct_colours() {
        let names = [
            "baseline, all",
            "WaSP, all",
            "WaSP, priority warps",
            "WaSP, regular warps",
            "L1 misses",
        ];
        let c = series_colours(&names);
        assert_eq!(c[0], named("baseline").unwrap());
        assert_eq!(c[1], named("wasp").unwrap());
        assert_eq!(c[4], OTHERS[0]);
        for i in 0..c.len() {
            for j in 0..i {
                assert_ne!(c[i], c[j], "{} and {}", names[i], names[j]);
            }
        }
        // The same names give the same colours in any chart.
        assert_eq!(series_colours(&["fullpriority", "wasp:0:3"])[1], c[1]);
    }

    #[test]
    fn the_diverging_scale_is_white_at_zero() {
        assert_eq!(diverging(0.0), RGBColor(255, 255, 255));
        assert_eq!(diverging(-1.0), RGBColor(178, 24, 43));
        assert_eq!(diverging(2.0), RGBColor(33, 102, 172));
        assert_eq!(diverging(f64::NAN), RGBColor(255, 255, 255));
    }
}
