//! The machine's unstated choices that the map varies, one at a time, each
//! over a range a real mobile GPU could have, and the runs made at every
//! value.
//!
//! Every knob is a set of typed overrides on the shipped machine
//! (configs/paper.toml, shared-tile dispatch). The ranges and their sources
//! are in docs/machine.md ("What decides WaSP's gain"); the shipped value is
//! always one of the values, so every knob's range passes through the
//! shipped machine.

use serde::Serialize;
use std::str::FromStr;
use wasp_frontend::raster::DrawOrder;
use wasp_frontend::texture::FormatChoice;
use wasp_rtl::policy::PolicySpec;
use wasp_sim::config::{CoreMap, IssueOrder, MachineConfig, Override, TextureCache};
use wasp_sim::mem::PrefetchKind;

/// One unstated choice of the machine and the values the map gives it.
#[derive(Clone, Debug)]
pub struct Knob {
    /// Short id for files and tables (`warps`).
    pub id: &'static str,
    /// The configuration field(s) it sets, as a user would name them.
    pub field: &'static str,
    /// What it is, for labels ("warps per core").
    pub label: &'static str,
    /// The shipped value.
    pub shipped: &'static str,
    /// Every value of the full map, in ascending order, the shipped one
    /// included.
    pub values: &'static [&'static str],
    /// The values of the quick look (the shipped one included).
    pub quick: &'static [&'static str],
    /// The overrides that give the knob a value.
    pub sets: fn(&str) -> Vec<Override>,
    /// A value as a label ("32 warps").
    pub unit: fn(&str) -> String,
    /// Whether the knob is the scene's draw order (the front end's, not a
    /// machine field): its values are draw orders and `sets` is unused.
    pub draw_order: bool,
    /// Whether the knob is the scenes' texture format (the front end's):
    /// its values are [`FormatChoice`]s, each alone (the texture caches
    /// hold what memory holds) or followed by [`DECOMPRESSED`] (the L0/L1
    /// hold decoded texels), and `sets` is unused.
    pub texture_format: bool,
}

impl Knob {
    /// The overrides of `value` (none for the shipped value, so that the
    /// shipped point is the shipped machine, spelled the same way).
    pub fn overrides(&self, value: &str) -> Vec<Override> {
        if self.texture_format && value.ends_with(DECOMPRESSED) {
            vec![Override::new(
                "memory.texture_cache",
                &TextureCache::Decompressed,
            )]
        } else if value == self.shipped || self.draw_order || self.texture_format {
            Vec::new()
        } else {
            (self.sets)(value)
        }
    }

    /// The draw order of `value` for a draw-order knob (None for the
    /// shipped value, so that the shipped point keeps the scene's own).
    pub fn order(&self, value: &str) -> Option<DrawOrder> {
        (self.draw_order && value != self.shipped)
            .then(|| value.parse().ok())
            .flatten()
    }

    /// The texture format of `value` for a texture-format knob (None for
    /// the shipped value, so that the shipped point keeps the scene's own).
    pub fn format(&self, value: &str) -> Option<FormatChoice> {
        let format = value.strip_suffix(DECOMPRESSED).unwrap_or(value);
        (self.texture_format && value != self.shipped)
            .then(|| format.parse().ok())
            .flatten()
    }

    /// Whether the knob is the front end's (draw order, texture format),
    /// not a machine field.
    pub fn scene_knob(&self) -> bool {
        self.draw_order || self.texture_format
    }

    /// The values of a plan.
    pub fn values_for(&self, quick: bool) -> &'static [&'static str] {
        if quick {
            self.quick
        } else {
            self.values
        }
    }
}

/// The suffix of a texture-format knob value whose L0/L1 texture caches
/// hold decompressed texels (`memory.texture_cache = "decompressed"`;
/// docs/textures.md): `etc2+decompressed`.
pub const DECOMPRESSED: &str = "+decompressed";

/// A texture-format value as a label: `textures etc2`, or `textures etc2,
/// decompressed in L0/L1`.
fn texture_unit(v: &str) -> String {
    match v.strip_suffix(DECOMPRESSED) {
        Some(f) => format!("textures {f}, decompressed in L0/L1"),
        None => format!("textures {v}"),
    }
}

/// Field `path` set to the value `v` of a knob, as type `T` (a value
/// that is not one is kept as text, which applying it refuses, naming the
/// field and what it holds).
fn typed<T: FromStr + Serialize>(path: &str, v: &str) -> Override {
    match v.parse::<T>() {
        Ok(t) => Override::new(path, &t),
        Err(_) => Override::new(path, v),
    }
}

/// The filter rate: cycles a bilinear quad-sample holds the filter unit;
/// trilinear takes two passes, as on the shipped machine.
fn filter(v: &str) -> Vec<Override> {
    let n: u32 = v.parse().unwrap_or(1);
    vec![
        Override::new("core.filter_cycles_bilinear", &n),
        Override::new("core.filter_cycles_trilinear", &(2 * n)),
    ]
}

/// DRAM latency, as the unloaded row-hit latency in cycles: the banked
/// model's row hit costs `t_cl + t_burst + controller_latency`, so the
/// knob sets the controller latency that gives it (the paper: "Latency
/// 50-100 cycles").
fn dram_latency(v: &str) -> Vec<Override> {
    let d = MachineConfig::paper().dram;
    let hit: u32 = v.parse().unwrap_or(50);
    let fixed = d.t_cl + d.t_burst;
    vec![Override::new(
        "dram.controller_latency",
        &hit.saturating_sub(fixed),
    )]
}

fn plain(v: &str) -> String {
    v.to_string()
}

/// Every knob of the map, in the order of docs/machine.md: the latency,
/// raster, texture, placement and scene knobs, in turn.
pub fn all() -> Vec<Knob> {
    [
        latency_knobs(),
        raster_knobs(),
        texture_knobs(),
        placement_knobs(),
        scene_knobs(),
    ]
    .concat()
}

/// The knobs of hiding memory latency: warps per core, the L0's and L1's
/// MSHRs and the DRAM row-hit latency.
fn latency_knobs() -> Vec<Knob> {
    vec![
        Knob {
            id: "warps",
            field: "core.max_warps",
            label: "warps per core",
            shipped: "64",
            values: &["32", "48", "64", "96", "128"],
            quick: &["32", "64", "128"],
            sets: |v| vec![typed::<u32>("core.max_warps", v)],
            unit: |v| format!("{v} warps"),
            draw_order: false,
            texture_format: false,
        },
        Knob {
            id: "l0-mshrs",
            field: "l0.mshrs",
            label: "L0 MSHRs",
            shipped: "16",
            values: &["4", "8", "16", "31"],
            quick: &["16", "31"],
            sets: |v| vec![typed::<u32>("l0.mshrs", v)],
            unit: |v| format!("{v} L0 MSHRs"),
            draw_order: false,
            texture_format: false,
        },
        Knob {
            id: "l1-mshrs",
            field: "l1.mshrs",
            label: "L1 MSHRs",
            shipped: "16",
            values: &["8", "16", "32"],
            quick: &["16"],
            sets: |v| vec![typed::<u32>("l1.mshrs", v)],
            unit: |v| format!("{v} L1 MSHRs"),
            draw_order: false,
            texture_format: false,
        },
        Knob {
            id: "dram-latency",
            field: "dram.controller_latency",
            label: "DRAM row-hit latency",
            shipped: "50",
            values: &["50", "75", "100"],
            quick: &["50"],
            sets: dram_latency,
            unit: |v| format!("{v}-cycle row hit"),
            draw_order: false,
            texture_format: false,
        },
    ]
}

/// The knobs of the raster and the queue it feeds: the cores' input queue,
/// the raster's quads a cycle and Early-Z's rejects a slot.
fn raster_knobs() -> Vec<Knob> {
    vec![
        Knob {
            id: "input-queue",
            field: "core.input_queue",
            label: "input queue entries",
            shipped: "64",
            values: &["16", "32", "64", "128", "256"],
            quick: &["64"],
            sets: |v| vec![typed::<u32>("core.input_queue", v)],
            unit: |v| format!("{v}-entry queue"),
            draw_order: false,
            texture_format: false,
        },
        Knob {
            id: "raster-rate",
            field: "raster.quads_per_cycle",
            label: "raster quads a cycle",
            shipped: "4",
            values: &["1", "2", "4", "8"],
            quick: &["4"],
            sets: |v| vec![typed::<u32>("raster.quads_per_cycle", v)],
            unit: |v| format!("{v} quads/cycle"),
            draw_order: false,
            texture_format: false,
        },
        Knob {
            id: "early-z",
            field: "raster.rejected_per_slot",
            label: "Early-Z rejects a slot",
            shipped: "1",
            values: &["1", "4", "16"],
            quick: &["1"],
            sets: |v| vec![typed::<u32>("raster.rejected_per_slot", v)],
            unit: |v| format!("{v} rejected/slot"),
            draw_order: false,
            texture_format: false,
        },
    ]
}

/// The knobs of the texture unit: its latency and filter rate.
fn texture_knobs() -> Vec<Knob> {
    vec![
        Knob {
            id: "texture-latency",
            field: "core.texture_latency",
            label: "texture latency",
            shipped: "4",
            values: &["1", "4", "16", "32"],
            quick: &["4"],
            sets: |v| vec![typed::<u32>("core.texture_latency", v)],
            unit: |v| format!("{v}-cycle texture"),
            draw_order: false,
            texture_format: false,
        },
        Knob {
            id: "filter",
            field: "core.filter_cycles_bilinear",
            label: "filter cycles a quad",
            shipped: "1",
            values: &["1", "2", "4"],
            quick: &["1"],
            sets: filter,
            unit: |v| format!("{v} cycles/quad filter"),
            draw_order: false,
            texture_format: false,
        },
    ]
}

/// The knobs of where and when warps run: the issue order and the map of
/// tiles to cores.
fn placement_knobs() -> Vec<Knob> {
    vec![
        Knob {
            id: "issue",
            field: "core.issue",
            label: "issue order",
            shipped: "lrr",
            values: &["lrr", "gto"],
            quick: &["lrr"],
            sets: |v| vec![typed::<IssueOrder>("core.issue", v)],
            unit: plain,
            draw_order: false,
            texture_format: false,
        },
        Knob {
            id: "core-map",
            field: "raster.core_map",
            label: "core map",
            shipped: "latin:8",
            values: &["latin:4", "latin:8", "latin:16", "rowmajor:16"],
            quick: &["latin:8"],
            sets: |v| vec![typed::<CoreMap>("raster.core_map", v)],
            unit: plain,
            draw_order: false,
            texture_format: false,
        },
    ]
}

/// The front end's knobs (not machine fields): the scenes' opaque draw
/// order and texture format.
fn scene_knobs() -> Vec<Knob> {
    vec![
        Knob {
            id: "draw-order",
            field: "draw_order (scene)",
            label: "opaque draw order",
            shipped: "as-loaded",
            values: &["as-loaded", "front-to-back-object", "front-to-back-draw"],
            quick: &["as-loaded"],
            sets: |_| Vec::new(),
            unit: plain,
            draw_order: true,
            texture_format: false,
        },
        Knob {
            id: "texture-format",
            field: "texture_format (scene)",
            label: "texture format",
            shipped: "etc2",
            values: &["rgba8", "etc2", "etc2+decompressed", "astc-8x8"],
            quick: &["rgba8", "etc2"],
            sets: |_| Vec::new(),
            unit: texture_unit,
            draw_order: false,
            texture_format: true,
        },
    ]
}

/// The runs made at every value of every knob, on every scene.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Variant {
    /// The scanline baseline.
    Baseline,
    /// The shipped WaSP.
    Wasp,
    /// Every priority warp first.
    FullPriority,
    /// The baseline with the raster prefetcher.
    Raster,
    /// The baseline with the oracle tile prefetcher: the bound of any
    /// "launch early to prefetch" scheme.
    Oracle,
    /// The baseline with zero-latency main memory: the other bound.
    Ideal,
}

impl Variant {
    /// Every variant, in table order.
    pub const ALL: [Variant; 6] = [
        Variant::Baseline,
        Variant::Wasp,
        Variant::FullPriority,
        Variant::Raster,
        Variant::Oracle,
        Variant::Ideal,
    ];

    /// The policy the variant runs, `wasp` being the shipped WaSP.
    pub fn policy(self, wasp: PolicySpec) -> PolicySpec {
        match self {
            Variant::Wasp => wasp,
            Variant::FullPriority => PolicySpec::FullPriority,
            _ => PolicySpec::Baseline,
        }
    }

    /// What the variant adds to the machine beside its policy: a
    /// prefetcher or ideal memory (the bounds).
    pub fn machine(self) -> Vec<Override> {
        match self {
            Variant::Raster => vec![Override::new("prefetch.kind", &PrefetchKind::Raster)],
            Variant::Oracle => vec![Override::new("prefetch.kind", &PrefetchKind::OracleTile)],
            Variant::Ideal => vec![Override::new("memory.ideal", &true)],
            _ => Vec::new(),
        }
    }

    /// The overrides of the variant: its policy, then its machine.
    pub fn overrides(self, wasp: PolicySpec) -> Vec<Override> {
        let mut v = vec![Override::new("scheduler.policy", &self.policy(wasp))];
        v.extend(self.machine());
        v
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_knob_passes_through_the_shipped_machine() {
        let paper = MachineConfig::paper();
        for k in all() {
            assert!(k.values.contains(&k.shipped), "{}", k.id);
            assert!(k.quick.contains(&k.shipped), "{}", k.id);
            assert!(k.quick.iter().all(|q| k.values.contains(q)), "{}", k.id);
            assert!(k.overrides(k.shipped).is_empty(), "{}", k.id);
            if k.texture_format {
                for v in k.values {
                    let f = k.format(v);
                    assert_eq!(f.is_none(), *v == k.shipped, "{v}");
                    // Only the decompressed-texel values set the machine.
                    let sets = k.overrides(v);
                    assert_eq!(sets.is_empty(), !v.ends_with(DECOMPRESSED), "{v}");
                    let c = paper.with_overrides(&sets).unwrap();
                    let decompressed = wasp_sim::config::TextureCache::Decompressed;
                    assert_eq!(
                        c.memory.texture_cache == decompressed,
                        v.ends_with(DECOMPRESSED),
                        "{v}"
                    );
                }
                assert_eq!(
                    k.format("etc2+decompressed"),
                    Some(FormatChoice::Etc2),
                    "the same format under both cache choices"
                );
                assert_eq!(
                    (k.unit)("etc2+decompressed"),
                    "textures etc2, decompressed in L0/L1"
                );
            }
            // The shipped value spelled as an override is the shipped
            // machine: the knob's range really passes through it.
            let same = paper.with_overrides(&(k.sets)(k.shipped)).unwrap();
            assert_eq!(same, paper, "{}", k.id);
        }
    }

    #[test]
    fn the_knobs_keep_the_order_of_the_machine_docs_table() {
        // The order names the map's files, tables and figures: a change
        // of it changes `wasp reproduce`'s output.
        let ids: Vec<&str> = all().iter().map(|k| k.id).collect();
        assert_eq!(
            ids,
            [
                "warps",
                "l0-mshrs",
                "l1-mshrs",
                "dram-latency",
                "input-queue",
                "raster-rate",
                "early-z",
                "texture-latency",
                "filter",
                "issue",
                "core-map",
                "draw-order",
                "texture-format",
            ]
        );
    }

    #[test]
    fn every_override_names_a_parameter_and_applies() {
        let paper = MachineConfig::paper();
        let params: Vec<String> = paper.params().into_iter().map(|p| p.path).collect();
        let variants = Variant::ALL.map(|v| v.overrides(PolicySpec::SHIPPED_WASP));
        let knobs = all().into_iter().flat_map(|k| {
            let values = k.values.iter().map(move |v| k.overrides(v));
            values.collect::<Vec<_>>()
        });
        for sets in knobs.chain(variants) {
            for o in &sets {
                assert!(params.iter().any(|p| p == o.path()), "{o}");
            }
            assert!(paper.with_overrides(&sets).is_ok(), "{sets:?}");
        }
    }

    #[test]
    fn the_dram_knob_sets_the_row_hit_latency() {
        let paper = MachineConfig::paper();
        let d = &paper.dram;
        assert_eq!(d.t_cl + d.t_burst + d.controller_latency, 50);
        let texts = |v: Vec<Override>| -> Vec<String> { v.iter().map(|o| o.to_string()).collect() };
        assert_eq!(texts(dram_latency("100")), ["dram.controller_latency=83"]);
        assert_eq!(
            texts(filter("4")),
            [
                "core.filter_cycles_bilinear=4",
                "core.filter_cycles_trilinear=8"
            ]
        );
    }
}
