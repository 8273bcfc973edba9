//! The map's sentence on compressed textures: whether storing the scenes'
//! textures as a mobile port ships them (the shipped `etc2` rule, or
//! ASTC) brings wasp's CF and WaSP's speedup closer to the paper's CF of
//! 2.5 and its +3.9% than RGBA8 does, from the texture-format knob's rows
//! of the run (kept apart from the other conclusions,
//! [`super::conclusion`]).

use super::table::{KnobResult, MapTable};
use crate::reproduce::paper;
use crate::reproduce::plan::Group;
use crate::reproduce::prose::pct;
use std::fmt::Write as _;

/// The paragraph on the texture-format knob for each group of `groups`
/// but the procedural one (nothing when the map has no such knob or no
/// rows for it).
pub fn compressed(md: &mut String, t: &MapTable, groups: &[Group]) {
    let Some(k) = t.knobs.iter().find(|k| k.id == "texture-format") else {
        return;
    };
    let mut any = false;
    for &g in groups.iter().filter(|&&g| g != Group::Procedural) {
        if let Some(s) = sentence(k, g) {
            if !any {
                let _ = writeln!(md, "### Compressed textures\n");
                any = true;
            }
            let _ = writeln!(md, "{s}\n");
        }
    }
}

/// How far `v` is from `target`.
fn gap(v: f64, target: f64) -> f64 {
    (v - target).abs()
}

/// The knob's value of uncompressed textures, the reference of the
/// sentence.
const RGBA8: &str = "rgba8";

/// The sentence for group `g`: each format's CF, blocks per tile and
/// WaSP's speedup, and whether the compressed formats come closer to the
/// paper's CF and speedup than RGBA8 does (None without an RGBA8 row).
fn sentence(k: &KnobResult, g: Group) -> Option<String> {
    let (cf_paper, wasp_paper) = (paper::CF.value, paper::WASP_SPEEDUP.value);
    let rgba8 = k.rows.iter().find(|r| r.value == RGBA8)?.of(g);
    let (cf0, w0) = (rgba8.cf?, rgba8.wasp?);
    let mut parts = Vec::new();
    let mut closer_cf = Vec::new();
    let mut closer_wasp = Vec::new();
    for r in &k.rows {
        let m = r.of(g);
        let (Some(cf), Some(w)) = (m.cf, m.wasp) else {
            continue;
        };
        parts.push(format!(
            "{}{} CF {cf:.2}, {:.0} blocks per tile, WaSP {}",
            r.value,
            if r.shipped { " (shipped)" } else { "" },
            m.blocks_per_tile.unwrap_or(0.0),
            pct(Some(w))
        ));
        if r.value != RGBA8 {
            if gap(cf, cf_paper) < gap(cf0, cf_paper) {
                closer_cf.push(r.value.as_str());
            }
            if gap(w, wasp_paper) < gap(w0, wasp_paper) {
                closer_wasp.push(r.value.as_str());
            }
        }
    }
    if parts.len() < 2 {
        return None;
    }
    let says = |v: &[&str], what: &str| match v {
        [] => format!("no compressed format brings {what} closer than rgba8"),
        _ => format!("{} brings {what} closer", v.join(" and ")),
    };
    Some(format!(
        "On {} scenes, by texture format: {}. Against the paper's CF of {cf_paper} and WaSP's \
         {}: {}; {}.",
        g.label(),
        parts.join("; "),
        pct(Some(wasp_paper)),
        says(&closer_cf, "CF"),
        says(&closer_wasp, "WaSP's speedup")
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::reproduce::map::data::{Metrics, GROUPS};
    use crate::reproduce::map::table::Row;

    fn row(value: &str, shipped: bool, cf: f64, wasp: f64) -> Row {
        let m = Metrics {
            cf: Some(cf),
            wasp: Some(wasp),
            blocks_per_tile: Some(100.0),
            ..Metrics::default()
        };
        Row {
            knob: "texture-format".into(),
            value: value.into(),
            label: format!("textures {value}"),
            shipped,
            repeats: false,
            groups: GROUPS.map(|_| m),
        }
    }

    #[test]
    fn the_sentence_says_which_formats_come_closer() {
        let k = KnobResult {
            index: 0,
            id: "texture-format".into(),
            label: "texture format".into(),
            rows: vec![
                row("rgba8", false, 4.35, 0.002),
                row("etc2", true, 2.6, 0.001),
                row("astc-8x8", false, 1.9, 0.03),
            ],
            wasp_range: [None, None, None],
        };
        let s = sentence(&k, Group::ThreeD).unwrap();
        assert!(s.contains("rgba8 CF 4.35, 100 blocks per tile"), "{s}");
        assert!(s.contains("etc2 (shipped) CF 2.60"), "{s}");
        assert!(s.contains("etc2 and astc-8x8 brings CF closer"), "{s}");
        assert!(s.contains("astc-8x8 brings WaSP's speedup closer"), "{s}");
        let only = KnobResult {
            rows: vec![
                row("rgba8", false, 4.35, 0.002),
                row("etc2", true, 5.0, -0.01),
            ],
            ..k
        };
        let s = sentence(&only, Group::ThreeD).unwrap();
        assert!(
            s.contains("no compressed format brings CF closer than rgba8"),
            "{s}"
        );
        // Without an RGBA8 row there is nothing to compare with.
        let none = KnobResult {
            rows: vec![
                row("etc2", true, 2.6, 0.001),
                row("astc-8x8", false, 1.9, 0.03),
            ],
            ..only
        };
        assert_eq!(sentence(&none, Group::ThreeD), None);
    }
}
