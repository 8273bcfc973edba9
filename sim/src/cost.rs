//! `wasp cost`: the hardware overhead of WaSP.
//!
//! (a) An inventory from the RTL blocks ([`wasp_rtl::cost`]): every register
//! and its width, adders, comparators, the multiplier, per core and per
//! GPU, in bits and gate equivalents (counting rules stated in
//! [`GateRules`]). (b) The same scheduler block synthesized by Yosys from
//! the shipped Verilog twin (`props/verilog/wasp_sched.v`): cell counts,
//! flip-flops and `stat -tech cmos` transistors, side by side, with what
//! each counts. (c) What it would save: the register file of the extra
//! warps the baseline needs for the same performance by the paper's claim
//! (WaSP at 32 warps matches the baseline at 48 at width 2; at 48 beats it
//! at 64 at width 4), sized from the register-file parameters. The claim is
//! the paper's: this command runs no simulation, and wasp's reproduction
//! measures it separately (`wasp reproduce`'s sensitivity rows). (d) The
//! measured-CF variant. (e) The issue orders (`core.issue`) beside each
//! other ([`issue_order`]).
//!
//! Gate equivalents are sums of multiples of 0.5 GE, printed exactly
//! ([`ge`]), so that parts and totals agree.

pub mod issue_order;

use crate::config::MachineConfig;
use crate::mem::prefetch::cost::{self as prefetch_cost, SramItem, SRAM_GE_PER_BIT};
pub use issue_order::{issue_order_cost, IssueOrderCost};
use serde::Serialize;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;
use std::process::Command;
use wasp_rtl::cost::{
    constant_multiplier_inventory, core_inventory, measured_cf_inventory, GateRules, Item, Part,
};
use wasp_rtl::datapath::{Cf, Threshold, WaspDatapath};
use wasp_rtl::policy::PolicySpec;
use wasp_rtl::subset::Mesh;

/// An inventory line with its cost.
#[derive(Clone, Debug, Serialize)]
pub struct CostedItem {
    /// The item.
    #[serde(flatten)]
    pub item: Item,
    /// Flip-flop bits.
    pub register_bits: u32,
    /// Gate equivalents.
    pub ge: f64,
}

/// Yosys's view of the synthesized twin.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct YosysStat {
    /// The command that produced it.
    pub command: String,
    /// Cells after `synth`.
    pub cells: u64,
    /// Cells by type (`$_AND_`, `$_DFF_P_`, ...).
    pub cell_types: BTreeMap<String, u64>,
    /// Flip-flop cells.
    pub flip_flops: u64,
    /// `stat -tech cmos` transistor estimate.
    pub transistors: Option<u64>,
}

/// The register-file side of the ledger.
#[derive(Clone, Debug, Serialize)]
pub struct Savings {
    /// Warps WaSP needs.
    pub wasp_warps: u32,
    /// Warps the baseline needs for the same performance.
    pub baseline_warps: u32,
    /// Where those two numbers come from.
    pub source: String,
    /// Whose claim that is, and where wasp measures it.
    pub caveat: String,
    /// Register-file bits per warp (threads x registers x bits).
    pub rf_bits_per_warp: u64,
    /// Register-file bits saved per core.
    pub rf_bits_saved_per_core: u64,
    /// GE per register-file bit (state the rule).
    pub ge_per_rf_bit: f64,
    /// GE saved per core.
    pub ge_saved_per_core: f64,
}

/// The measured-CF variant (beyond the paper) against the report's WaSP.
#[derive(Clone, Debug, Serialize)]
pub struct VariantCost {
    /// What the variant adds per core: the CF meter and the variable
    /// multiplier.
    pub added: Vec<CostedItem>,
    /// What it no longer needs: the constant-CF multiplier's adders.
    pub removed: Vec<CostedItem>,
    /// Per-core flip-flops of the variant (WaSP's plus the meter's).
    pub per_core_register_bits: u32,
    /// Per-core GE of the variant.
    pub per_core_ge: f64,
    /// Yosys synthesis of the twin's CF meter alone (`wasp_cf_meter`).
    pub yosys_meter: Option<YosysStat>,
    /// Yosys synthesis of the twin's scheduler under wasp-m (`POLICY` 4:
    /// the meter and the variable multiplier), beside the report's
    /// [`CostReport::yosys`].
    pub yosys: Option<YosysStat>,
}

/// The whole report.
#[derive(Clone, Debug, Serialize)]
pub struct CostReport {
    /// Machine.
    pub machine: String,
    /// Cores.
    pub cores: u32,
    /// The datapath costed: CF and threshold.
    pub cf: f64,
    /// Threshold.
    pub threshold: u32,
    /// Input queue entries (split into two FIFOs).
    pub input_queue: u32,
    /// Counting rules.
    pub rules: GateRules,
    /// Per-core inventory.
    pub per_core: Vec<CostedItem>,
    /// Per-core totals.
    pub per_core_register_bits: u32,
    /// Per-core GE.
    pub per_core_ge: f64,
    /// Per-core transistors (GE x transistors per GE).
    pub per_core_transistors: f64,
    /// Whole-GPU register bits.
    pub gpu_register_bits: u32,
    /// Whole-GPU GE.
    pub gpu_ge: f64,
    /// Yosys synthesis of the Verilog twin (absent without Yosys).
    pub yosys: Option<YosysStat>,
    /// Why there is no Yosys column, if there is none.
    pub yosys_note: Option<String>,
    /// What WaSP saves.
    pub savings: Savings,
    /// The measured-CF variant's cost beside WaSP's.
    pub measured_cf_variant: VariantCost,
    /// The issue orders' hardware (`core.issue`).
    pub issue_order: IssueOrderCost,
    /// The prefetchers (`prefetch.kind`), per core.
    pub prefetchers: Vec<PrefetcherCost>,
}

/// One prefetcher's hardware per core ([`crate::mem::prefetch::cost`]).
#[derive(Clone, Debug, Serialize)]
pub struct PrefetcherCost {
    /// The kind (`raster`, `oracle-tile`).
    pub kind: String,
    /// Flip-flops and logic.
    pub items: Vec<CostedItem>,
    /// SRAM.
    pub sram: Vec<SramItem>,
    /// Per-core flip-flops.
    pub register_bits: u32,
    /// Per-core SRAM bits.
    pub sram_bits: u64,
    /// Per-core GE: logic and flip-flops, plus SRAM at
    /// [`SRAM_GE_PER_BIT`].
    pub ge: f64,
    /// A design, or a bound.
    pub note: String,
}

/// Both prefetchers' inventories for `cfg`'s limits.
fn prefetcher_costs(cfg: &MachineConfig, rules: &GateRules) -> Vec<PrefetcherCost> {
    let p = &cfg.prefetch;
    [
        prefetch_cost::raster_inventory(p.queue, p.queue_filter, cfg.l1.mshrs),
        prefetch_cost::oracle_inventory(prefetch_cost::ORACLE_LONGEST_LIST, cfg.l1.mshrs),
    ]
    .into_iter()
    .map(|inv| {
        let items = costed(inv.items, rules);
        let sram_bits: u64 = inv.sram.iter().map(|s| s.bits).sum();
        PrefetcherCost {
            kind: inv.kind.to_string(),
            register_bits: items.iter().map(|c| c.register_bits).sum(),
            ge: items.iter().map(|c| c.ge).sum::<f64>() + sram_bits as f64 * SRAM_GE_PER_BIT,
            items,
            sram: inv.sram,
            sram_bits,
            note: inv.note,
        }
    })
    .collect()
}

/// Register-file parameters for the savings column.
#[derive(Clone, Debug)]
pub struct RfParams {
    /// Threads per warp (a quad: 4).
    pub threads_per_warp: u32,
    /// Registers per thread.
    pub registers_per_thread: u32,
    /// Bits per register.
    pub register_bits: u32,
    /// GE per register-file bit.
    pub ge_per_bit: f64,
    /// Warps WaSP needs.
    pub wasp_warps: u32,
    /// Warps the baseline needs for the same performance.
    pub baseline_warps: u32,
    /// Provenance of the warp counts.
    pub source: String,
    /// Whose claim the warp counts are, and where wasp measures it.
    pub caveat: String,
}

impl RfParams {
    /// For `cfg`: a quad warp of 4 threads with `core.registers_per_thread`
    /// 32-bit registers each, a 6-transistor SRAM bit cell = 1.5 GE
    /// (periphery not counted, so the saving is a lower bound), and the
    /// paper's equivalence for the machine's pipeline width: at width 2,
    /// WaSP with 32 warps matches the baseline with 48 (Section V-A and the
    /// conclusions); at width 4, WaSP with 48 warps outperforms the best
    /// baseline with 64.
    pub fn for_config(cfg: &MachineConfig) -> Self {
        let (wasp_warps, baseline_warps, width, verb) = if cfg.core.pipeline_width >= 4 {
            (48, 64, 4, "outperforms")
        } else {
            (32, 48, 2, "matches")
        };
        let source = format!(
            "the paper's claim, width {width}: WaSP with {wasp_warps} warps {verb} the baseline \
             with {baseline_warps}"
        );
        let caveat = format!(
            "This is the paper's claim, not a measurement of this command (which runs no \
             simulation). wasp's own reproduction measures it differently: REPORT.md of \
             `wasp reproduce` gives it as the sensitivity row \"WaSP@{wasp_warps} over the \
             baseline@{baseline_warps}, width {width}\" and says whether the saving holds on \
             its scenes; docs/results.md records the shipped suite's value."
        );
        Self {
            threads_per_warp: 4,
            registers_per_thread: cfg.core.registers_per_thread,
            register_bits: 32,
            ge_per_bit: 1.5,
            wasp_warps,
            baseline_warps,
            source,
            caveat,
        }
    }
}

/// Width of the event counts (allocations, replies, blocks, ...) a cycle
/// in the Verilog twin's counters: its `CNT_W` default, which `wasp cost`
/// does not change.
const TWIN_EVENT_BITS: u32 = 8;

/// Columns of the table's prose paragraphs.
const TEXT_WIDTH: usize = 100;

/// `text` broken into lines of at most `width` columns at spaces (a longer
/// word stands alone), each ending in a newline.
fn wrap(text: &str, width: usize) -> String {
    let mut out = String::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        if !line.is_empty() && line.len() + 1 + word.len() > width {
            out.push_str(&line);
            out.push('\n');
            line.clear();
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    if !line.is_empty() {
        out.push_str(&line);
        out.push('\n');
    }
    out
}

/// Gate equivalents as text, exactly: whole numbers without a decimal,
/// halves with one (`591`, `1146.5`); every GE rule is a multiple of 0.5 per
/// bit, so sums print without rounding.
pub fn ge(v: f64) -> String {
    if v.fract() == 0.0 {
        format!("{v:.0}")
    } else {
        format!("{v:.1}")
    }
}

/// The Verilog twin (`props/verilog/wasp_sched.v`), embedded so that
/// `wasp cost` synthesizes it wherever the binary is installed.
pub const VERILOG_TWIN: &str = include_str!("../../props/verilog/wasp_sched.v");

/// Run Yosys on the embedded twin: it is written to a temporary file for
/// the run and removed after.
pub fn run_yosys_on_twin(params: &[(&str, i64)], top: &str) -> Result<YosysStat, String> {
    let path = std::env::temp_dir().join(format!("wasp-twin-{}.v", std::process::id()));
    std::fs::write(&path, VERILOG_TWIN)
        .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    let r = run_yosys(&path, params, top);
    let _ = std::fs::remove_file(&path);
    r.map(|mut s| {
        s.command = s
            .command
            .replace(&path.display().to_string(), "props/verilog/wasp_sched.v");
        s
    })
}

/// Parse the last statistics block of a Yosys log.
pub fn parse_yosys_stat(log: &str) -> Option<YosysStat> {
    let start = log.rfind("Printing statistics")?;
    let block = &log[start..];
    let mut s = YosysStat::default();
    let mut in_cells = false;
    for line in block.lines() {
        let t = line.trim();
        if let Some(v) = t.strip_prefix("Number of cells:") {
            s.cells = v.trim().parse().ok()?;
            in_cells = true;
            continue;
        }
        if let Some(v) = t.strip_prefix("Estimated number of transistors:") {
            s.transistors = v.trim().parse().ok();
            in_cells = false;
            continue;
        }
        if in_cells {
            let mut parts = t.split_whitespace();
            match (parts.next(), parts.next(), parts.next()) {
                (Some(name), Some(n), None) if name.starts_with('$') => {
                    let n: u64 = n.parse().ok()?;
                    if name.contains("DFF") {
                        s.flip_flops += n;
                    }
                    s.cell_types.insert(name.to_string(), n);
                }
                _ => in_cells = !t.is_empty() && in_cells && t.starts_with('$'),
            }
        }
    }
    (s.cells > 0).then_some(s)
}

/// Run Yosys on `verilog` with the machine's parameters.
pub fn run_yosys(verilog: &Path, params: &[(&str, i64)], top: &str) -> Result<YosysStat, String> {
    if !verilog.exists() {
        return Err(format!("{} not found", verilog.display()));
    }
    let chparam: String = params
        .iter()
        .map(|(k, v)| format!("chparam -set {k} {v} {top}; "))
        .collect();
    let script = format!(
        "read_verilog {}; {chparam}synth -flatten -top {top}; dffunmap; stat; stat -tech cmos",
        verilog.display()
    );
    let out = Command::new("yosys")
        .arg("-p")
        .arg(&script)
        .output()
        .map_err(|e| format!("cannot run yosys ({e}): install it with `apt-get install yosys`"))?;
    let log = String::from_utf8_lossy(&out.stdout);
    if !out.status.success() {
        let tail: Vec<&str> = log.lines().rev().take(15).collect();
        return Err(format!(
            "yosys failed:\n{}{}",
            tail.into_iter().rev().collect::<Vec<_>>().join("\n"),
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    let mut s = parse_yosys_stat(&log).ok_or("no statistics in the yosys log")?;
    s.command = format!("yosys -p \"{script}\"");
    Ok(s)
}

/// Build the report for `cfg`. `yosys`: whether to run Yosys.
pub fn report(
    cfg: &MachineConfig,
    rules: GateRules,
    rf: &RfParams,
    yosys: bool,
) -> Result<CostReport, String> {
    let (threshold, cf) = match cfg.scheduler.policy {
        PolicySpec::Wasp { threshold, cf } => (threshold, cf),
        _ => (4, 2.5),
    };
    let dp = WaspDatapath {
        cf: Cf::from_f64(cf).ok_or("CF is not a multiple of 0.25 in 0..=7.75")?,
        threshold: Threshold::new(threshold).ok_or("threshold does not fit 5 bits")?,
    };
    let mesh = Mesh::new(4).expect("mesh4");
    let items = core_inventory(&dp, &mesh, cfg.core.input_queue);
    let per_core = costed(items, &rules);
    let bits: u32 = per_core.iter().map(|c| c.register_bits).sum();
    let ge: f64 = per_core.iter().map(|c| c.ge).sum();
    let added = costed(measured_cf_inventory(), &rules);
    let removed = costed(constant_multiplier_inventory(&dp), &rules);
    let mut variant = VariantCost {
        per_core_register_bits: bits + added.iter().map(|c| c.register_bits).sum::<u32>(),
        per_core_ge: ge + added.iter().map(|c| c.ge).sum::<f64>()
            - removed.iter().map(|c| c.ge).sum::<f64>(),
        added,
        removed,
        yosys_meter: None,
        yosys: None,
    };
    let (ys, note) = match yosys {
        true => yosys_stats(cfg, &dp, threshold, &mut variant),
        false => (None, Some("not run (--no-yosys)".into())),
    };
    Ok(CostReport {
        machine: cfg.name.clone(),
        cores: cfg.gpu.cores,
        cf: dp.cf.value(),
        threshold,
        input_queue: cfg.core.input_queue,
        rules,
        per_core_register_bits: bits,
        per_core_ge: ge,
        per_core_transistors: ge * rules.transistors_per_ge,
        gpu_register_bits: bits * cfg.gpu.cores,
        gpu_ge: ge * cfg.gpu.cores as f64,
        per_core,
        yosys: ys,
        yosys_note: note,
        savings: savings(rf),
        measured_cf_variant: variant,
        issue_order: issue_order_cost(cfg, &rules),
        prefetchers: prefetcher_costs(cfg, &rules),
    })
}

/// Yosys's statistics of the scheduler twin on `cfg`'s machine (with the
/// measured-CF variant's, and its meter's, into `variant`), or why there
/// are none.
fn yosys_stats(
    cfg: &MachineConfig,
    dp: &WaspDatapath,
    threshold: u32,
    variant: &mut VariantCost,
) -> (Option<YosysStat>, Option<String>) {
    let params = [
        ("CAPACITY", cfg.watched_mshrs() as i64),
        ("QUEUE_CAP", cfg.core.input_queue as i64),
        ("CF_Q", dp.cf.quarters() as i64),
        ("THRESHOLD", threshold as i64),
    ];
    match run_yosys_on_twin(&params, "wasp_sched") {
        Ok(s) => {
            // The same machine under wasp-m (POLICY 4), and its meter.
            let mut measured = params.to_vec();
            measured.push(("POLICY", 4));
            variant.yosys = run_yosys_on_twin(&measured, "wasp_sched").ok();
            variant.yosys_meter = run_yosys_on_twin(&[], "wasp_cf_meter").ok();
            (Some(s), None)
        }
        Err(e) => (None, Some(e)),
    }
}

/// The register-file side of the ledger: what the warps WaSP runs without
/// save, per `rf`.
fn savings(rf: &RfParams) -> Savings {
    let rf_bits =
        rf.threads_per_warp as u64 * rf.registers_per_thread as u64 * rf.register_bits as u64;
    let saved_warps = rf.baseline_warps.saturating_sub(rf.wasp_warps) as u64;
    Savings {
        wasp_warps: rf.wasp_warps,
        baseline_warps: rf.baseline_warps,
        source: rf.source.clone(),
        caveat: rf.caveat.clone(),
        rf_bits_per_warp: rf_bits,
        rf_bits_saved_per_core: rf_bits * saved_warps,
        ge_per_rf_bit: rf.ge_per_bit,
        ge_saved_per_core: (rf_bits * saved_warps) as f64 * rf.ge_per_bit,
    }
}

fn costed(items: Vec<Item>, rules: &GateRules) -> Vec<CostedItem> {
    items
        .into_iter()
        .map(|item| CostedItem {
            register_bits: match item.part {
                Part::Register { bits } => bits,
                _ => 0,
            },
            ge: rules.ge(&item.part),
            item,
        })
        .collect()
}

impl CostReport {
    /// The report as a table.
    pub fn to_table(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "WaSP hardware overhead: machine {}, {} cores, CF {}, threshold {}, input queue {}",
            self.machine, self.cores, self.cf, self.threshold, self.input_queue
        );
        self.inventory_table(&mut s);
        self.yosys_table(&mut s);
        self.savings_table(&mut s);
        self.variant_table(&mut s);
        self.issue_order_table(&mut s);
        self.prefetchers_table(&mut s);
        s
    }

    /// Flip-flop bits and GE of the inventory's registers.
    fn flip_flop_ge(&self) -> f64 {
        f64::from(self.per_core_register_bits) * self.rules.flip_flop
    }

    /// (a): the inventory per core, its totals and the counting rules.
    fn inventory_table(&self, s: &mut String) {
        let _ = writeln!(s, "\n(a) inventory per core, from the RTL blocks");
        let _ = writeln!(
            s,
            "{:<22}{:<52}{:<22}{:>6}{:>9}",
            "block", "purpose", "part", "ff", "GE"
        );
        for c in &self.per_core {
            item_line(s, c, "");
        }
        let ff = self.flip_flop_ge();
        let _ = writeln!(
            s,
            "per core: {} flip-flops, {} GE ({} GE in flip-flops, {} GE of logic); per GPU ({} \
             cores): {} flip-flops, {} GE",
            self.per_core_register_bits,
            ge(self.per_core_ge),
            ge(ff),
            ge(self.per_core_ge - ff),
            self.cores,
            self.gpu_register_bits,
            ge(self.gpu_ge)
        );
        let r = &self.rules;
        let _ = writeln!(
            s,
            "rules: flip-flop {} GE, full-adder bit {} GE, comparator bit {} GE, zero-detect input {} GE, mux2 bit {} GE, {} transistors/GE",
            r.flip_flop, r.full_adder, r.comparator_bit, r.zero_detect_input, r.mux2_bit, r.transistors_per_ge
        );
    }

    /// The inventory's flip-flops by block (`free_mshrs 5, ...`).
    fn flip_flops_by_block(&self) -> String {
        let mut by: Vec<(&str, u32)> = Vec::new();
        for c in self.per_core.iter().filter(|c| c.register_bits > 0) {
            match by.iter_mut().find(|b| b.0 == c.item.block) {
                Some(b) => b.1 += c.register_bits,
                None => by.push((c.item.block, c.register_bits)),
            }
        }
        let parts: Vec<String> = by.iter().map(|(b, n)| format!("{b} {n}")).collect();
        parts.join(", ")
    }

    /// (b): the Yosys synthesis beside the inventory, and what each counts.
    fn yosys_table(&self, s: &mut String) {
        let _ = writeln!(s, "\n(b) the Verilog twin synthesized by Yosys (per core)");
        let Some(y) = &self.yosys else {
            let _ = writeln!(
                s,
                "no Yosys numbers: {}",
                self.yosys_note.as_deref().unwrap_or("unknown")
            );
            return;
        };
        let _ = writeln!(s, "{:<28}{:>12}{:>12}", "", "inventory", "yosys");
        let _ = writeln!(
            s,
            "{:<28}{:>12}{:>12}",
            "flip-flops", self.per_core_register_bits, y.flip_flops
        );
        let yt = y.transistors.map(|t| t.to_string());
        let _ = writeln!(
            s,
            "{:<28}{:>12.0}{:>12}",
            "transistors",
            self.per_core_transistors,
            yt.as_deref().unwrap_or("-")
        );
        let _ = writeln!(s, "{:<28}{:>12}{:>12}", "cells", "-", y.cells);
        let types: Vec<String> = y
            .cell_types
            .iter()
            .map(|(k, v)| format!("{k} {v}"))
            .collect();
        let _ = writeln!(s, "cell types: {}", types.join(", "));
        let _ = writeln!(s, "re-derive with: {}", y.command);
        let ratio = y
            .transistors
            .map(|t| t as f64 / self.per_core_transistors.max(1.0))
            .map_or(String::new(), |r| {
                format!(" Yosys's count is {r:.1} times the inventory's.")
            });
        let text = format!(
            "The two columns count different things. Flip-flops: the inventory's {} are the \
             registers WaSP adds ({}); the twin keeps the threshold as a synthesis constant \
             (no register) and tracks the split queue by two occupancy counters instead of the \
             second FIFO's pointers, so Yosys finds {}. Transistors: the inventory's are its \
             gate equivalents x {} (textbook static CMOS, the blocks listed in (a) only); Yosys's \
             `stat -tech cmos` counts each generic cell of the whole twin at that cell's own \
             size (4 for a NAND or NOR, 12 for an XOR or MUX, 16 for a flip-flop), unmapped to \
             any library, and the twin holds logic the inventory leaves out: event counts of \
             up to {} bits a cycle in the counters' updates, their range checks (the \
             properties' fault output), the queue's full check and the policy select.{ratio} \
             Both are per core; the GPU has {} cores.",
            self.per_core_register_bits,
            self.flip_flops_by_block(),
            y.flip_flops,
            self.rules.transistors_per_ge,
            TWIN_EVENT_BITS,
            self.cores
        );
        s.push_str(&wrap(&text, TEXT_WIDTH));
    }

    /// (c): the register file WaSP would save by the paper's claim.
    fn savings_table(&self, s: &mut String) {
        let v = &self.savings;
        let _ = writeln!(s, "\n(c) what it would save ({})", v.source);
        s.push_str(&wrap(&v.caveat, TEXT_WIDTH));
        let _ = writeln!(
            s,
            "register file per warp: {} bits; {} warps instead of {}: {} bits = {:.1} KiB per core, {} GE at {} GE/bit",
            v.rf_bits_per_warp,
            v.wasp_warps,
            v.baseline_warps,
            v.rf_bits_saved_per_core,
            v.rf_bits_saved_per_core as f64 / 8192.0,
            ge(v.ge_saved_per_core),
            v.ge_per_rf_bit
        );
        let _ = writeln!(
            s,
            "if the claim holds, WaSP's logic costs {:.2}% of the register file it saves (per core: {} GE against {} GE)",
            100.0 * self.per_core_ge / v.ge_saved_per_core.max(1.0),
            ge(self.per_core_ge),
            ge(v.ge_saved_per_core)
        );
    }

    /// (d): the measured-CF variant: what it adds and removes.
    fn variant_table(&self, s: &mut String) {
        let m = &self.measured_cf_variant;
        let _ = writeln!(
            s,
            "\n(d) the measured-CF variant (wasp-m, beyond the paper): CF measured per core by a meter"
        );
        for c in &m.added {
            item_line(s, c, "+ ");
        }
        for c in &m.removed {
            item_line(s, c, "- ");
        }
        let added: f64 = m.added.iter().map(|c| c.ge).sum();
        let removed: f64 = m.removed.iter().map(|c| c.ge).sum();
        let _ = writeln!(
            s,
            "per core: {} flip-flops, {} GE = WaSP's {} GE + {} GE added - {} GE removed ({:+} GE \
             against WaSP with a constant CF {})",
            m.per_core_register_bits,
            ge(m.per_core_ge),
            ge(self.per_core_ge),
            ge(added),
            ge(removed),
            m.per_core_ge - self.per_core_ge,
            self.cf
        );
        if let (Some(meter), Some(sched), Some(wasp)) = (&m.yosys_meter, &m.yosys, &self.yosys) {
            let _ = writeln!(s, "synthesized by Yosys from the twin (per core):");
            for (what, y) in [
                ("CF meter alone (wasp_cf_meter)", meter),
                ("scheduler under wasp-m (POLICY 4)", sched),
                ("scheduler under WaSP, as (b)", wasp),
            ] {
                let _ = writeln!(
                    s,
                    "  {what:<36}{:>6} cells{:>5} flip-flops{:>7} transistors",
                    y.cells,
                    y.flip_flops,
                    y.transistors
                        .map(|t| t.to_string())
                        .unwrap_or_else(|| "-".into())
                );
            }
        }
    }

    /// Section (e): the issue orders.
    fn issue_order_table(&self, s: &mut String) {
        let o = &self.issue_order;
        let _ = writeln!(
            s,
            "\n(e) the issue order (core.issue, this machine: {}), per core: {} slots, {} picks a cycle",
            o.configured, o.slots, o.width
        );
        for c in o.lrr.iter().chain(&o.gto) {
            item_line(s, c, "");
        }
        let _ = writeln!(
            s,
            "lrr: {} flip-flops, {} GE; gto: {} flip-flops, {} GE ({:+} GE); gto split as \
             GPGPU-Sim's cores ({} schedulers of {} slots): {} flip-flops, {} GE",
            o.register_bits[0],
            ge(o.ge[0]),
            o.register_bits[1],
            ge(o.ge[1]),
            o.ge[1] - o.ge[0],
            o.width,
            o.slots.div_ceil(o.width),
            o.gto_split.0,
            ge(o.gto_split.1)
        );
    }

    /// Section (f): the prefetchers beside WaSP.
    fn prefetchers_table(&self, s: &mut String) {
        let _ = writeln!(
            s,
            "\n(f) the prefetchers (prefetch.kind; beyond the paper), per core"
        );
        for p in &self.prefetchers {
            let _ = writeln!(s, "{}: {}", p.kind, p.note);
            for c in &p.items {
                item_line(s, c, "");
            }
            for m in &p.sram {
                let _ = writeln!(
                    s,
                    "{:<22}{:<52}{:<22}{:>6}{:>9.1}",
                    m.block,
                    m.purpose,
                    format!("SRAM {}b", m.bits),
                    0,
                    m.bits as f64 * SRAM_GE_PER_BIT
                );
            }
            let _ = writeln!(
                s,
                "per core: {} flip-flops, {} SRAM bits ({:.1} KiB), {} GE ({:.1}x WaSP's {} GE; SRAM at {} GE/bit)",
                p.register_bits,
                p.sram_bits,
                p.sram_bits as f64 / 8192.0,
                ge(p.ge),
                p.ge / self.per_core_ge.max(1.0),
                ge(self.per_core_ge),
                SRAM_GE_PER_BIT
            );
        }
    }
}

fn item_line(s: &mut String, c: &CostedItem, sign: &str) {
    let part = match c.item.part {
        Part::Register { bits } => format!("register {bits}b"),
        Part::Adder { bits } => format!("adder {bits}b"),
        Part::Comparator { bits } => format!("comparator {bits}b"),
        Part::ZeroDetect { bits } => format!("zero detect {bits} in"),
        Part::Mux2 { bits } => format!("mux2 {bits}b"),
    };
    let _ = writeln!(
        s,
        "{:<22}{:<52}{:<22}{:>6}{:>9.1}",
        format!("{sign}{}", c.item.block),
        c.item.purpose,
        part,
        c.register_bits,
        c.ge
    );
}

#[cfg(test)]
mod tests;
