//! Tests of `wasp cost`: Yosys's log read, the paper machine's report and
//! its table, the prose's wrapping, exact gate equivalents, and the twin
//! synthesized when Yosys is installed.

use super::*;

const SAMPLE: &str = "4. Printing statistics.\n\n=== t ===\n\n   Number of wires:                 43\n   Number of cells:                 47\n     $_ANDNOT_                      16\n     $_AND_                          2\n     $_DFF_P_                        5\n     $_XOR_                          6\n\n   Estimated number of transistors:        392\n\nEnd of script.";

#[test]
fn parses_yosys_statistics() {
    let s = parse_yosys_stat(SAMPLE).unwrap();
    assert_eq!(s.cells, 47);
    assert_eq!(s.flip_flops, 5);
    assert_eq!(s.transistors, Some(392));
    assert_eq!(s.cell_types["$_ANDNOT_"], 16);
    assert_eq!(s.cell_types.len(), 4);
    assert!(parse_yosys_stat("no statistics here").is_none());
}

#[test]
fn paper_machine_report() {
    let r = report(
        &MachineConfig::paper(),
        GateRules::default(),
        &RfParams::for_config(&MachineConfig::paper()),
        false,
    )
    .unwrap();
    // 5 + 7 + 5 (threshold) + 6 + 6 + 7 (queue pointers, occupancy).
    assert_eq!(r.per_core_register_bits, 36);
    assert_eq!(r.gpu_register_bits, 36 * 4);
    // Width 4: 64 - 48 = 16 warps x 4 threads x 32 registers x 32 bits.
    assert_eq!(r.savings.rf_bits_saved_per_core, 16 * 4 * 32 * 32);
    let w2 = report(
        &MachineConfig::paper_width2(),
        GateRules::default(),
        &RfParams::for_config(&MachineConfig::paper_width2()),
        false,
    )
    .unwrap();
    assert_eq!((w2.savings.wasp_warps, w2.savings.baseline_warps), (32, 48));
    assert!(r.per_core_ge < r.savings.ge_saved_per_core / 50.0);
    let t = r.to_table();
    assert!(t.contains("free_mshrs") && t.contains("nonblocked_priority"));
    assert!(t.contains("no Yosys numbers"));
    // The measured-CF variant: 16 more flip-flops (4 + 7 + 5), the
    // constant multiplier's one adder (CF 2.5) replaced by four.
    let m = &r.measured_cf_variant;
    assert_eq!(m.per_core_register_bits, 36 + 16);
    assert_eq!(m.removed.len(), 1);
    assert!(m.per_core_ge > r.per_core_ge);
    assert!(t.contains("(d) the measured-CF variant") && t.contains("+ cf_meter"));
    assert!(t.contains("(e) the issue order (core.issue, this machine: lrr)"));
    assert!(t.contains("issue_lrr") && t.contains("age matrix"));
    assert_eq!(r.issue_order.register_bits, [6, 2080]);
    assert!(m.yosys.is_none() && m.yosys_meter.is_none());
    // The prefetchers, at the shipped limits: a 32-entry filtered
    // queue (32 x 25 bits, two 5-bit pointers, a 6-bit count) and the
    // oracle's list in SRAM.
    assert_eq!(r.prefetchers.len(), 2);
    let raster = &r.prefetchers[0];
    assert_eq!(raster.kind, "raster");
    assert_eq!(raster.register_bits, 32 * 25 + 5 + 5 + 6);
    assert!(raster.ge > 10.0 * r.per_core_ge, "{} GE", raster.ge);
    let oracle = &r.prefetchers[1];
    assert_eq!(oracle.kind, "oracle-tile");
    assert!(oracle.sram_bits > 0 && oracle.note.contains("bound"));
    assert!(t.contains("(f) the prefetchers") && t.contains("duplicate_filter"));
    // Exact parts and totals: 591 + 621.5 - 66 = 1146.5.
    assert!(
        t.contains(
            "per core: 52 flip-flops, 1146.5 GE = WaSP's 591 GE + 621.5 GE added - 66 GE \
             removed (+555.5 GE against WaSP with a constant CF 3)"
        ),
        "{t}"
    );
    // Per core and per GPU in their own units.
    assert!(
        t.contains(
            "per core: 36 flip-flops, 591 GE (216 GE in flip-flops, 375 GE of logic); per \
             GPU (4 cores): 144 flip-flops, 2364 GE\n"
        ),
        "{t}"
    );
    // The register-file claim is the paper's, and wasp's measurement is
    // named.
    assert!(
        t.contains("(c) what it would save (the paper's claim, width 4: WaSP with 48 warps"),
        "{t}"
    );
    let flat = t.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(
        flat.contains("sensitivity row \"WaSP@48 over the baseline@64, width 4\""),
        "{t}"
    );
    assert!(
        t.contains("if the claim holds, WaSP's logic costs 0.60%"),
        "{t}"
    );
}

#[test]
fn the_yosys_column_says_what_it_counts() {
    let mut r = report(
        &MachineConfig::paper(),
        GateRules::default(),
        &RfParams::for_config(&MachineConfig::paper()),
        false,
    )
    .unwrap();
    r.yosys = parse_yosys_stat(SAMPLE);
    let t = r.to_table();
    let t = t.split_whitespace().collect::<Vec<_>>().join(" ");
    assert!(
        t.contains(
            "Flip-flops: the inventory's 36 are the registers WaSP adds (free_mshrs 5, \
             nonblocked_priority 7, threshold 5, input_queue 19)"
        ),
        "{t}"
    );
    assert!(t.contains("so Yosys finds 5."), "{t}");
    // 392 against 591 GE x 4.
    assert!(
        t.contains("Yosys's count is 0.2 times the inventory's."),
        "{t}"
    );
    assert!(t.contains("Both are per core; the GPU has 4 cores."), "{t}");
}

#[test]
fn prose_wraps_at_spaces() {
    assert_eq!(wrap("aa bb cc", 5), "aa bb\ncc\n");
    assert_eq!(wrap("a verylongword b", 4), "a\nverylongword\nb\n");
    assert_eq!(wrap("", 4), "");
}

#[test]
fn gate_equivalents_print_exactly() {
    assert_eq!(ge(591.0), "591");
    assert_eq!(ge(1146.5), "1146.5");
    assert_eq!(ge(555.5), "555.5");
}

/// Yosys on the twin: the meter alone has the 16 flip-flops of its
/// three registers (4 + 7 + 5), and the twin under wasp-m has WaSP's
/// flip-flops plus the meter's and more cells (the meter and the
/// variable multiplier). Without Yosys it passes with a note, unless
/// `WASP_REQUIRE_TOOLS=1` (CI).
#[test]
fn yosys_synthesizes_the_meter_beside_wasp() {
    let cfg = MachineConfig::paper();
    let r = report(
        &cfg,
        GateRules::default(),
        &RfParams::for_config(&cfg),
        true,
    )
    .unwrap();
    let Some(wasp) = &r.yosys else {
        assert_ne!(
            std::env::var("WASP_REQUIRE_TOOLS").as_deref(),
            Ok("1"),
            "yosys required: {:?}",
            r.yosys_note
        );
        eprintln!("skipped: yosys not installed ({:?})", r.yosys_note);
        return;
    };
    let m = &r.measured_cf_variant;
    let meter = m.yosys_meter.as_ref().expect("the meter synthesized");
    let sched = m.yosys.as_ref().expect("the wasp-m twin synthesized");
    assert_eq!(meter.flip_flops, 16);
    assert_eq!(sched.flip_flops, wasp.flip_flops + 16);
    assert!(sched.cells > wasp.cells + meter.cells, "{sched:?}");
    assert!(r.to_table().contains("CF meter alone (wasp_cf_meter)"));
}
