//! The machine configuration: the shipped machines, parsing and round
//! trips, errors that name the key, line and range, the register limits,
//! and the declared bounds (every field at and just above its bound).

use super::*;
use crate::config::BlockedOn;
use crate::mem::PrefetchKind;
use wasp_rtl::policy::LaunchRule;

fn with(edit: impl Fn(&str) -> String) -> Result<MachineConfig, ConfigError> {
    MachineConfig::parse(&edit(PAPER_TOML), "test.toml")
}

#[test]
fn shipped_configs_are_the_papers_machines() {
    let p = MachineConfig::paper();
    assert_eq!(p.core.pipeline_width, 4);
    assert_eq!(p.core.max_warps, 64);
    assert_eq!(p.gpu.tile_size, 64);
    assert_eq!(p.gpu.frequency_mhz, 600);
    let l0 = p.l0.expect("L0 present at width 4");
    assert_eq!((l0.size_bytes, l0.ports), (512, 2));
    assert_eq!(
        (p.l1.size_bytes, p.l1.ways, p.l1.hit_latency),
        (65536, 4, 1)
    );
    assert_eq!(
        (p.l2.size_bytes, p.l2.ways, p.l2.hit_latency),
        (1 << 20, 8, 18)
    );
    assert_eq!(p.scheduler_cache().0, "l0");
    let w2 = MachineConfig::paper_width2();
    assert_eq!(w2.core.pipeline_width, 2);
    assert!(w2.l0.is_none());
    assert_eq!(w2.scheduler_cache().0, "l1");
    // The paper's rule: a closed gate holds the priority warp.
    for c in [&p, &w2] {
        assert_eq!(c.scheduler.launch_rule, LaunchRule::Hold);
    }
}

#[test]
fn launch_rule_is_parsed_and_inherited() {
    // A file without it takes the base machine's (the paper's: hold).
    let c = with(|s| {
        s.lines()
            .filter(|l| !l.starts_with("launch_rule"))
            .collect::<Vec<_>>()
            .join("\n")
    })
    .unwrap();
    assert_eq!(c.scheduler.launch_rule, LaunchRule::Hold);
    let c = with(|s| s.replace("launch_rule = \"hold\"", "launch_rule = \"launch\"")).unwrap();
    assert_eq!(c.scheduler.launch_rule, LaunchRule::Launch);
}

#[test]
fn round_trips_through_toml() {
    let p = MachineConfig::paper();
    let again = MachineConfig::parse(&p.to_toml(), "again").unwrap();
    assert_eq!(p, again);
}

/// The line of the first line of `text` that starts with `start`.
fn line_of(text: &str, start: &str) -> usize {
    1 + text
        .lines()
        .position(|l| l.starts_with(start))
        .expect(start)
}

#[test]
fn unknown_keys_name_the_key_and_the_line() {
    let e = with(|s| s.replace("max_warps = 64", "max_warps = 64\nmax_wraps = 3")).unwrap_err();
    let line = line_of(PAPER_TOML, "max_warps = 64") + 1;
    assert_eq!(e.source, format!("test.toml:{line}"));
    assert!(
        e.message.starts_with("core.max_wraps: unknown field"),
        "{e}"
    );
}

#[test]
fn unknown_keys_in_cache_sections_are_errors() {
    let e =
        with(|s| s.replacen("hit_latency = 18", "hit_latency = 18\nlatnecy = 3", 1)).unwrap_err();
    assert!(e.message.contains("latnecy"), "{e}");
}

#[test]
fn values_out_of_range_name_the_field() {
    let cases: &[(&str, &str, &str)] = &[
        ("max_warps = 64", "max_warps = 0", "core.max_warps"),
        ("max_warps = 64", "max_warps = 129", "core.max_warps"),
        (
            "pipeline_width = 4",
            "pipeline_width = 0",
            "core.pipeline_width",
        ),
        ("tile_size = 64", "tile_size = 48", "gpu.tile_size"),
        ("cores = 4", "cores = 0", "cores"),
        (
            "policy = \"wasp:0:3\"",
            "policy = \"wasp:40\"",
            "scheduler.policy",
        ),
        (
            "policy = \"wasp:0:3\"",
            "policy = \"fifo\"",
            "scheduler.policy",
        ),
        (
            "subset = \"mesh4\"",
            "subset = \"mesh5\"",
            "scheduler.subset",
        ),
        (
            "launch_rule = \"hold\"",
            "launch_rule = \"idle\"",
            "scheduler.launch_rule",
        ),
        (
            "core_map = \"latin:8\"",
            "core_map = \"diagonal:8\"",
            "raster.core_map",
        ),
        (
            "dispatch = \"shared-tile\"",
            "dispatch = \"per-tile\"",
            "raster.dispatch",
        ),
        (
            "watchdog_cycles = 1000000",
            "watchdog_cycles = 0",
            "sim.watchdog_cycles",
        ),
        (
            "core_static_mw = 50.0",
            "core_static_mw = -1.0",
            "energy.core_static_mw",
        ),
    ];
    for (from, to, field) in cases {
        assert!(PAPER_TOML.contains(from), "fixture: {from}");
        let e = with(|s| s.replacen(from, to, 1)).unwrap_err();
        assert!(e.message.contains(field), "{to}: {e}");
        // The line that set it.
        let key = from.split(' ').next().unwrap();
        assert_eq!(
            e.source,
            format!("test.toml:{}", line_of(PAPER_TOML, key)),
            "{to}: {e}"
        );
    }
    // A text parameter's error names the value and the allowed forms.
    let e = with(|s| s.replacen("policy = \"wasp:0:3\"", "policy = \"fifo\"", 1)).unwrap_err();
    assert!(
        e.message
            .starts_with("scheduler.policy: unknown policy `fifo` (expected baseline,"),
        "{e}"
    );
}

#[test]
fn filter_fields_are_inherited_and_checked() {
    let p = MachineConfig::paper();
    assert_eq!(
        (
            p.core.filter_cycles_bilinear,
            p.core.filter_cycles_trilinear,
            p.core.filter_timing
        ),
        (1, 2, FilterTiming::Overlap)
    );
    let w2 = MachineConfig::paper_width2();
    assert_eq!(
        (
            w2.core.filter_cycles_bilinear,
            w2.core.filter_cycles_trilinear,
            w2.core.filter_timing
        ),
        (1, 2, FilterTiming::Overlap)
    );
    // A file without them takes the base machine's.
    for key in [
        "filter_cycles_bilinear = 1",
        "filter_cycles_trilinear = 2",
        "filter_timing = \"overlap\"",
    ] {
        assert!(PAPER_TOML.contains(key), "fixture: {key}");
        assert_eq!(with(|s| s.replacen(key, "", 1)).unwrap().core, p.core);
    }
    for (from, to, msg) in [
        (
            "filter_cycles_bilinear = 1",
            "filter_cycles_bilinear = 1001",
            "core.filter_cycles_bilinear = 1001",
        ),
        (
            "filter_cycles_trilinear = 2",
            "filter_cycles_trilinear = 5000",
            "core.filter_cycles_trilinear = 5000",
        ),
        (
            "filter_cycles_trilinear = 2",
            "filter_cycles_trilinear = -1",
            "filter_cycles_trilinear",
        ),
        (
            "filter_timing = \"overlap\"",
            "filter_timing = \"after\"",
            "unknown variant `after`",
        ),
    ] {
        let e = with(|s| s.replacen(from, to, 1)).unwrap_err();
        assert!(e.message.contains(msg), "{to}: {e}");
    }
    let e = with(|s| {
        s.replacen(
            "filter_cycles_bilinear = 1",
            "filter_cycles_bilinear = 1001",
            1,
        )
    })
    .unwrap_err();
    assert!(e.message.contains("1000"), "names the limit: {e}");
    // 0 and the serial timing are allowed.
    let c = with(|s| {
        s.replacen(
            "filter_cycles_bilinear = 1",
            "filter_cycles_bilinear = 0",
            1,
        )
        .replacen(
            "filter_timing = \"overlap\"",
            "filter_timing = \"serial\"",
            1,
        )
    })
    .unwrap();
    assert_eq!(c.core.filter_cycles_bilinear, 0);
    assert_eq!(c.core.filter_timing, FilterTiming::Serial);
    assert_eq!(c.core.filter_timing.to_string(), "serial");
}

#[test]
fn prefetch_fields_are_checked() {
    let p = MachineConfig::paper();
    assert_eq!(p.prefetch, PrefetchConfig::default());
    assert_eq!(
        MachineConfig::paper_width2().prefetch,
        PrefetchConfig::default()
    );
    // A file without the section is the machine without a prefetcher.
    let start = PAPER_TOML.find("\n[prefetch]").unwrap();
    let end = start + PAPER_TOML[start + 1..].find("\n[").unwrap() + 1;
    let c = with(|s| format!("{}{}", &s[..start], &s[end..])).unwrap();
    assert_eq!(c, p);
    // Unknown kinds and keys are refused, naming them.
    let e = with(|s| s.replace("kind = \"none\"", "kind = \"stride\"")).unwrap_err();
    assert!(e.message.contains("stride"), "{e}");
    let e = with(|s| {
        s.replace(
            "queue_filter = true",
            "queue_filter = true\nqueue_depth = 3",
        )
    })
    .unwrap_err();
    assert!(e.message.contains("queue_depth"), "{e}");
    // On, the reserve must leave a prefetch an L1 MSHR.
    let e = set(&["prefetch.kind=raster"], "prefetch.l1_reserve", "16").unwrap_err();
    assert!(
        e.message
            .contains("prefetch.l1_reserve = 16: must be in 0..=15"),
        "{e}"
    );
    let c = set(&["prefetch.kind=oracle-tile"], "prefetch.l1_reserve", "15").unwrap();
    assert_eq!(c.prefetch.kind, PrefetchKind::OracleTile);
    assert_eq!(c.mem_config().prefetch, c.prefetch);
    let e = set(&[], "prefetch.kind", "\"raster2\"").unwrap_err();
    assert!(e.message.contains("raster2"), "{e}");
}

#[test]
fn cache_geometry_errors() {
    // 64 KiB / 64 B / 3 ways is not a whole power-of-two set count.
    let e = with(|s| s.replacen("ways = 4", "ways = 3", 1)).unwrap_err();
    assert!(e.message.contains("l1"), "{e}");
    let e = with(|s| s.replacen("size_bytes = 65536", "size_bytes = 0", 1)).unwrap_err();
    assert!(
        e.message.contains("l1") && e.message.contains("size_bytes"),
        "{e}"
    );
}

#[test]
fn registers_limit_mshrs_and_warps() {
    let e = with(|s| s.replacen("mshrs = 16", "mshrs = 32", 1)).unwrap_err();
    assert!(
        e.message.contains("l0.mshrs") && e.message.contains("5-bit"),
        "{e}"
    );
    // Policies that do not read the register may have more MSHRs.
    with(|s| {
        s.replacen("mshrs = 16", "mshrs = 64", 1)
            .replace("policy = \"wasp:0:3\"", "policy = \"fullpriority\"")
    })
    .unwrap();
    // Mesh2 puts 256 priority quads in a tile; with 128 warp slots the
    // 7-bit counter could need to count 128.
    let e = with(|s| {
        s.replace("max_warps = 64", "max_warps = 128")
            .replace("subset = \"mesh4\"", "subset = \"mesh2\"")
    })
    .unwrap_err();
    assert!(e.message.contains("7-bit"), "{e}");
    // 128 warps with Mesh4 (64 priority quads per tile) is fine.
    with(|s| s.replace("max_warps = 64", "max_warps = 128")).unwrap();
}

#[test]
fn blocked_on_is_inherited_and_checked() {
    assert_eq!(
        MachineConfig::paper().scheduler.blocked_on,
        BlockedOn::L1Miss
    );
    assert_eq!(
        MachineConfig::paper_width2().scheduler.blocked_on,
        BlockedOn::L1Miss
    );
    let line = "blocked_on = \"l1-miss\"";
    assert!(PAPER_TOML.contains(line));
    for rule in BlockedOn::ALL {
        let c = with(|s| s.replacen(line, &format!("blocked_on = \"{rule}\""), 1)).unwrap();
        assert_eq!(c.scheduler.blocked_on, rule);
        assert_eq!(c.mem_config().report_misses, rule != BlockedOn::FirstLevel);
        assert_eq!(rule.to_string().parse::<BlockedOn>(), Ok(rule));
    }
    let e = with(|s| s.replacen(line, "blocked_on = \"l2\"", 1)).unwrap_err();
    assert!(
        e.message.contains("scheduler.blocked_on")
            && e.message.contains("l2")
            && e.message.contains("l1-miss"),
        "{e}"
    );
    assert_eq!(e.source, format!("test.toml:{}", line_of(PAPER_TOML, line)));
    let c = with(|s| s.replacen(line, "", 1)).unwrap();
    assert_eq!(c.scheduler.blocked_on, BlockedOn::L1Miss, "the base's");
    assert!("l2"
        .parse::<BlockedOn>()
        .unwrap_err()
        .contains("first-level"));
}

#[test]
fn texture_cache_is_checked_and_defaults_to_compressed() {
    let line = "texture_cache = \"compressed\"";
    assert!(PAPER_TOML.contains(line) && PAPER_WIDTH2_TOML.contains(line));
    assert_eq!(
        MachineConfig::paper().memory.texture_cache,
        TextureCache::Compressed
    );
    let c = with(|s| s.replacen(line, "texture_cache = \"decompressed\"", 1)).unwrap();
    assert_eq!(c.memory.texture_cache, TextureCache::Decompressed);
    let again = MachineConfig::parse(&c.to_toml(), "again").unwrap();
    assert_eq!(again, c, "written back, it reads back");
    // A file without the key (one written before it existed) is compressed.
    let c = with(|s| s.replacen(line, "", 1)).unwrap();
    assert_eq!(c, MachineConfig::paper());
    let e = with(|s| s.replacen(line, "texture_cache = \"decoded\"", 1)).unwrap_err();
    assert!(
        e.message.starts_with("memory.texture_cache:")
            && e.message.contains("decoded")
            && e.message.contains("compressed")
            && e.message.contains("decompressed"),
        "{e}"
    );
    assert_eq!(e.source, format!("test.toml:{}", line_of(PAPER_TOML, line)));
    assert!("x"
        .parse::<TextureCache>()
        .unwrap_err()
        .contains("compressed or decompressed"));
}

#[test]
fn issue_order_is_checked_and_defaults_to_lrr() {
    assert_eq!(MachineConfig::paper().core.issue, IssueOrder::Lrr);
    assert_eq!(MachineConfig::paper_width2().core.issue, IssueOrder::Lrr);
    let line = "issue = \"lrr\"";
    assert!(PAPER_TOML.contains(line) && PAPER_WIDTH2_TOML.contains(line));
    let c = with(|s| s.replacen(line, "issue = \"gto\"", 1)).unwrap();
    assert_eq!(c.core.issue, IssueOrder::Gto);
    // A file without the key (one written before it existed) runs lrr.
    let c = with(|s| s.replacen(line, "", 1)).unwrap();
    assert_eq!(c, MachineConfig::paper());
    // Written back, the order is named and reads back.
    let again = MachineConfig::parse(&c.to_toml(), "again").unwrap();
    assert_eq!(again.core.issue, IssueOrder::Lrr);
    assert!(c.to_toml().contains(line));
    let e = with(|s| s.replacen(line, "issue = \"fifo\"", 1)).unwrap_err();
    assert!(
        e.message.starts_with("core.issue:")
            && e.message.contains("fifo")
            && e.message.contains("lrr")
            && e.message.contains("gto"),
        "{e}"
    );
    assert_eq!(e.source, format!("test.toml:{}", line_of(PAPER_TOML, line)));
}

/// The other fields that must change for a field at its bound to pass the
/// rest of the validation.
const SETUP: &[(&str, &[&str])] = &[
    // 64 ways need at least 64 lines: a 4 KiB L0.
    ("l0.ways", &["l0.size_bytes=4096"]),
    // More than 31 MSHRs at the scheduler's level only for a policy
    // that does not read the 5-bit free-MSHR register.
    ("l0.mshrs", &["scheduler.policy=fullpriority"]),
];

/// One field's bound as the tests try it: the largest accepted value, the
/// smallest refused one above it, the range the error names (when its
/// check is `check_bounds`'s; a rule of its own names the field) and the
/// fields [`SETUP`] changes first.
struct Bound {
    field: String,
    at: String,
    above: String,
    range: Option<String>,
    extra: &'static [&'static str],
}

/// Every declared range of the machine configuration (`section!`'s
/// facts). Not here: `sim.seed` (every u64 is a seed) and the numbers
/// inside the `scheduler.policy`, `scheduler.subset` and
/// `raster.core_map` strings (checked by their parsers, see
/// `values_out_of_range_name_the_field`).
fn bounds() -> Vec<Bound> {
    let params = MachineConfig::paper().params();
    let bounds: Vec<Bound> = params
        .into_iter()
        .filter_map(|p| {
            let r = p.range?;
            let (at, above) = if p.ty == "f64" {
                (format!("{}.0", r.hi), format!("{}.5", r.hi))
            } else {
                let hi: u64 = r.hi.parse().unwrap();
                (r.hi.clone(), (hi + 1).to_string())
            };
            let extra = SETUP
                .iter()
                .find(|s| s.0 == p.path)
                .map_or(&[][..], |s| s.1);
            Some(Bound {
                range: r.generic.then(|| format!("{}..={}", r.lo, r.hi)),
                field: p.path,
                at,
                above,
                extra,
            })
        })
        .collect();
    // 60 declared ranges when the facts were first generated.
    assert!(bounds.len() >= 60, "{} bounds", bounds.len());
    bounds
}

fn set(extra: &[&str], field: &str, value: &str) -> Result<MachineConfig, ConfigError> {
    let mut sets = crate::config::Override::parse_sets(extra)?;
    sets.push(crate::config::Override::bare(field, value));
    MachineConfig::paper().with_overrides(&sets)
}

#[test]
fn every_numeric_field_has_a_declared_range() {
    // A field added to the config without a bound fails here.
    let root = toml::Value::try_from(MachineConfig::paper()).unwrap();
    let bounds = bounds();
    let mut numeric = Vec::new();
    for (section, table) in root.as_table().unwrap() {
        let Some(table) = table.as_table() else {
            continue;
        };
        for (key, v) in table {
            if v.is_integer() || v.is_float() {
                numeric.push(format!("{section}.{key}"));
            }
        }
    }
    for path in &numeric {
        assert!(
            path == "sim.seed" || bounds.iter().any(|b| &b.field == path),
            "{path} has no declared range"
        );
    }
    assert_eq!(numeric.len(), bounds.len() + 1, "{numeric:?}");
}

#[test]
fn each_field_just_above_its_bound_is_refused_naming_field_and_range() {
    for Bound {
        field,
        above,
        range,
        extra,
        ..
    } in bounds()
    {
        let e = set(extra, &field, &above).expect_err(&field);
        let key = field.split_once('.').unwrap().1;
        let named = match &range {
            Some(range) => {
                e.message.contains(&format!("{field} = {above}")) && e.message.contains(range)
            }
            None => e.message.contains(key),
        };
        assert!(named, "{field}={above}: {e}");
        // The same text from a file.
        let mut doc = toml::Value::try_from(MachineConfig::paper()).unwrap();
        for kv in extra
            .iter()
            .map(|s| s.to_string())
            .chain([format!("{field}={above}")])
        {
            let (path, v) = kv.split_once('=').unwrap();
            let (sec, key) = path.split_once('.').unwrap();
            let v: toml::Value = toml::from_str::<toml::Table>(&format!("v = {v}"))
                .map(|t| t["v"].clone())
                .unwrap_or(toml::Value::String(v.into()));
            doc[sec][key] = v;
        }
        let e =
            MachineConfig::parse(&toml::to_string(&doc).unwrap(), "bounds.toml").expect_err(&field);
        let named = range.as_ref().map_or(key, |r| r.as_str());
        assert!(e.message.contains(named), "{field}={above} in a file: {e}");
    }
}

#[test]
fn each_field_at_its_bound_is_accepted() {
    for Bound {
        field, at, extra, ..
    } in bounds()
    {
        let c = set(extra, &field, &at).unwrap_or_else(|e| panic!("{field}={at}: {e}"));
        let doc = toml::Value::try_from(&c).unwrap();
        let (sec, key) = field.split_once('.').unwrap();
        assert_eq!(doc[sec][key].to_string(), at, "{field}");
    }
}

#[test]
fn the_memory_systems_host_memory_is_budgeted() {
    // Each at its bound is accepted (above); together these would
    // allocate more than 1 GiB: 64 cores x (640 000 L0 completion
    // entries + a 16 MiB L1's 262 144 lines).
    let e = set(
        &["gpu.cores=64", "l0.ports=64", "l0.hit_latency=10000"],
        "l1.size_bytes",
        "16777216",
    )
    .unwrap_err();
    assert!(
        e.message.contains("gpu.cores = 64") && e.message.contains("budget of 1024 MiB"),
        "{e}"
    );
    let p = MachineConfig::paper().mem_config();
    assert!(p.host_bytes() < 1 << 20, "{}", p.host_bytes());
}

#[test]
fn bad_toml_reports_line() {
    let e = MachineConfig::parse("name = \"x\"\n[gpu\ncores = 1", "broken.toml").unwrap_err();
    assert!(e.to_string().starts_with("broken.toml: "));
    assert!(e.message.contains("line 2"), "{e}");
}
