//! The one palette of wasp's pictures: the reproduction's figures
//! ([`crate::charts`]) and the timeline ([`crate::timeline_plot`]).
//!
//! A series says what it shows with a [`Key`], set by whoever builds it:
//! a policy (from its [`PolicySpec`]), the oracle prefetcher or a scene
//! group has that key's colour ([`Key::colour`]) whatever figure it is in.
//! Other series (subsets, cache levels of a chart, cores of the timeline)
//! take the colours of [`OTHERS`] in order, which are none of the keys'.
//! [`series_colours`] gives a chart's series their colours, each distinct:
//! a second series of the same key (e.g. `WaSP, priority warps` beside
//! `WaSP, all`) gets a darker, then a lighter shade of it.

use plotters::style::RGBColor;
use wasp_rtl::policy::PolicySpec;

/// What a series shows, which chooses its colour.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Key {
    /// The scanline baseline.
    Baseline,
    /// Fullpriority.
    FullPriority,
    /// FreeMSHR-N, any N.
    FreeMshr,
    /// WaSP, any threshold and CF.
    Wasp,
    /// WaSP with a measured CF.
    WaspMeasured,
    /// The oracle prefetcher's bound.
    Oracle,
    /// The 3D games.
    ThreeD,
    /// The 2D games.
    TwoD,
    /// The games together.
    Games,
    /// The procedural scenes.
    Procedural,
    /// None of these: the next of [`OTHERS`].
    #[default]
    Other,
}

impl Key {
    /// The key's own colour; None for [`Key::Other`].
    pub fn colour(self) -> Option<RGBColor> {
        Some(match self {
            Key::Baseline => RGBColor(127, 127, 127),
            Key::FullPriority => RGBColor(255, 127, 14),
            Key::FreeMshr => RGBColor(148, 103, 189),
            Key::Wasp => RGBColor(31, 119, 180),
            Key::WaspMeasured => RGBColor(23, 190, 207),
            Key::Oracle => RGBColor(140, 86, 75),
            Key::ThreeD => RGBColor(44, 160, 44),
            Key::TwoD => RGBColor(214, 39, 40),
            Key::Games => RGBColor(188, 189, 34),
            Key::Procedural => RGBColor(82, 84, 163),
            Key::Other => return None,
        })
    }
}

/// A policy's key: its kind, whatever its parameters.
impl From<PolicySpec> for Key {
    fn from(p: PolicySpec) -> Key {
        match p {
            PolicySpec::Baseline => Key::Baseline,
            PolicySpec::FullPriority => Key::FullPriority,
            PolicySpec::FreeMshr(_) => Key::FreeMshr,
            PolicySpec::Wasp { .. } => Key::Wasp,
            PolicySpec::WaspMeasured { .. } => Key::WaspMeasured,
        }
    }
}

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

/// The colours of a chart's series of `keys`, in order: each key its
/// colour (a repeat of a key darker, then lighter, by turns), other series
/// the [`OTHERS`] in order.
pub fn series_colours(keys: &[Key]) -> Vec<RGBColor> {
    let mut repeats: Vec<(Key, usize)> = Vec::new();
    let mut others = 0;
    let mut colour = |&key: &Key| {
        let Some(c) = key.colour() else {
            others += 1;
            return other(others - 1);
        };
        let k = match repeats.iter_mut().find(|r| r.0 == key) {
            Some(r) => {
                r.1 += 1;
                r.1
            }
            None => {
                repeats.push((key, 0));
                0
            }
        };
        let step = k.div_ceil(2);
        match k {
            0 => c,
            _ if k % 2 == 1 => shade(c, 0.8f64.powi(step as i32)),
            _ => shade(c, 1.0 + 0.6 * step as f64),
        }
    };
    keys.iter().map(&mut colour).collect()
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
    fn a_policy_has_one_colour_whatever_its_parameters() {
        let wasp = Key::Wasp.colour();
        for p in ["wasp:0:3", "wasp:6", "wasp"] {
            let spec: PolicySpec = p.parse().expect("policy");
            assert_eq!(Key::from(spec).colour(), wasp, "{p}");
        }
        let measured: PolicySpec = "wasp-m:0".parse().expect("policy");
        assert_ne!(Key::from(measured).colour(), wasp);
        assert_eq!(Key::from(PolicySpec::FreeMshr(10)), Key::FreeMshr);
        assert_eq!(Key::Other.colour(), None);
    }

    #[test]
    fn other_colours_are_no_key_colour() {
        let keys = [Key::Baseline, Key::FullPriority, Key::FreeMshr, Key::Wasp];
        let keys = keys
            .into_iter()
            .chain([Key::WaspMeasured, Key::Oracle, Key::ThreeD]);
        let keys: Vec<Key> = keys
            .chain([Key::TwoD, Key::Games, Key::Procedural])
            .collect();
        for c in OTHERS {
            assert!(keys.iter().all(|k| k.colour() != Some(c)), "{c:?}");
        }
    }

    #[test]
    fn a_chart_gets_distinct_colours() {
        let keys = [Key::Baseline, Key::Wasp, Key::Wasp, Key::Wasp, Key::Other];
        let c = series_colours(&keys);
        assert_eq!(Some(c[0]), Key::Baseline.colour());
        assert_eq!(Some(c[1]), Key::Wasp.colour());
        assert_eq!(c[4], OTHERS[0]);
        for i in 0..c.len() {
            for j in 0..i {
                assert_ne!(c[i], c[j], "{:?} and {:?}", keys[i], keys[j]);
            }
        }
        // The same keys give the same colours in any chart.
        assert_eq!(series_colours(&[Key::FullPriority, Key::Wasp])[1], c[1]);
    }

    #[test]
    fn the_diverging_scale_is_white_at_zero() {
        assert_eq!(diverging(0.0), RGBColor(255, 255, 255));
        assert_eq!(diverging(-1.0), RGBColor(178, 24, 43));
        assert_eq!(diverging(2.0), RGBColor(33, 102, 172));
        assert_eq!(diverging(f64::NAN), RGBColor(255, 255, 255));
    }
}
