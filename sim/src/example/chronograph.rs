//! The chronographs of the example: each cycle's access, outcome and
//! replies per launch order, and their rendering as the paper's figure.

use super::ExampleConfig;
use serde::Serialize;
use std::fmt::Write as _;
use wasp_rtl::policy::LaunchRule;

/// Cache outcome of one access, as the paper's chronograph marks it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
pub enum Outcome {
    /// H: the block is in the cache.
    #[serde(rename = "H")]
    Hit,
    /// X: primary miss, an MSHR entry is allocated.
    #[serde(rename = "X")]
    Miss,
    /// O: secondary miss, merged into the block's MSHR entry.
    #[serde(rename = "O")]
    Secondary,
}

impl Outcome {
    fn mark(self) -> char {
        match self {
            Outcome::Hit => 'H',
            Outcome::Miss => 'X',
            Outcome::Secondary => 'O',
        }
    }
    pub(super) fn code(self) -> u64 {
        match self {
            Outcome::Hit => 1,
            Outcome::Miss => 2,
            Outcome::Secondary => 3,
        }
    }
}

/// One cycle of a chronograph.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct CycleRow {
    /// Cycle number, from 1.
    pub cycle: u64,
    /// Block accessed (absent on a stall or an idle cycle).
    pub block: Option<char>,
    /// Warp that accessed it.
    pub warp: Option<u32>,
    /// Cache outcome.
    pub outcome: Option<Outcome>,
    /// The cache refused the pending access: all MSHRs occupied.
    pub blocked: bool,
    /// Blocks whose reply arrived this cycle.
    pub replies: Vec<char>,
    /// MSHR entries the cache holds at the end of the cycle.
    pub mshrs_held: u32,
    /// Free-MSHR register value seen by this cycle's launch decision.
    pub free_mshrs: u32,
    /// Non-blocked priority-warp counter seen by this cycle's decision.
    pub nonblocked_priority: u32,
    /// Real_freeMSHRs computed by the WaSP datapath (WaSP run only).
    pub real_free_mshrs: Option<i32>,
    /// Warp launched this cycle, and from which queue.
    pub launched: Option<(u32, String)>,
}

/// The result of one launch order.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Chronograph {
    /// What this order is.
    pub title: String,
    /// The launch policy that produced it.
    pub policy: String,
    /// The machine.
    pub machine: ExampleConfig,
    /// CF used by the WaSP datapath (1: one access per warp).
    pub cf: f64,
    /// Cycles until the last warp finished.
    pub cycles: u64,
    /// Cycles in which the cache refused an access (MSHRs full).
    pub stall_cycles: u64,
    /// Cycles in which the LDST register was free and a priority warp
    /// waited but the launch rule `hold` launched nothing (gate closed, no
    /// regular warp waiting).
    pub held_cycles: u64,
    /// Hits.
    pub hits: u32,
    /// Primary misses.
    pub misses: u32,
    /// Secondary misses.
    pub secondary_misses: u32,
    /// Warps in launch order.
    pub launch_order: Vec<u32>,
    /// Per cycle.
    pub timeline: Vec<CycleRow>,
}

/// The three chronographs of the paper's figure.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ExampleReport {
    /// Baseline scanline order.
    pub scanline: Chronograph,
    /// Fullpriority: W0, W5, W10 first.
    pub all_priority_first: Chronograph,
    /// The WaSP launch rule.
    pub wasp: Chronograph,
}

impl ExampleReport {
    /// The WaSP speedup over scanline order (cycles ratio minus one).
    pub fn wasp_speedup(&self) -> f64 {
        self.scanline.cycles as f64 / self.wasp.cycles as f64 - 1.0
    }
}

/// The chronograph as the paper's figure shows it: one column per cycle,
/// rows for the block accessed, the warp, the cache outcome (`##` where the
/// full MSHR file blocks the access) and the block replied.
pub fn render_chronograph(c: &Chronograph) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{} [{}]: {} cycles, {} stall cycles ({} hits, {} misses, {} secondary misses)",
        c.title, c.policy, c.cycles, c.stall_cycles, c.hits, c.misses, c.secondary_misses
    );
    let cell = 4;
    let mut rows: Vec<(&str, Vec<String>)> = vec![
        ("cycle", vec![]),
        ("block", vec![]),
        ("warp", vec![]),
        ("cache", vec![]),
        ("reply", vec![]),
        ("mshrs held", vec![]),
        ("free_mshrs", vec![]),
    ];
    let show_real = c.timeline.iter().any(|r| r.real_free_mshrs.is_some());
    if show_real {
        rows.push(("real_free", vec![]));
    }
    for r in &c.timeline {
        rows[0].1.push(r.cycle.to_string());
        rows[1]
            .1
            .push(r.block.map(String::from).unwrap_or_default());
        rows[2]
            .1
            .push(r.warp.map(|w| format!("W{w}")).unwrap_or_default());
        rows[3].1.push(if r.blocked {
            "##".into()
        } else {
            r.outcome.map(|o| o.mark().to_string()).unwrap_or_default()
        });
        rows[4].1.push(r.replies.iter().collect());
        rows[5].1.push(r.mshrs_held.to_string());
        rows[6].1.push(r.free_mshrs.to_string());
        if show_real {
            rows[7]
                .1
                .push(r.real_free_mshrs.map(|v| v.to_string()).unwrap_or_default());
        }
    }
    for (name, cells) in rows {
        let _ = write!(s, "  {name:<10} |");
        for v in cells {
            let _ = write!(s, "{v:>cell$}");
        }
        s.push('\n');
    }
    let order: Vec<String> = c.launch_order.iter().map(|w| format!("W{w}")).collect();
    let _ = writeln!(s, "  launch order: {}", order.join(" "));
    s
}

/// The whole report as text.
pub fn render_report(r: &ExampleReport) -> String {
    let m = &r.scanline.machine;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "The worked example of WaSP, Section III-A: 15 warps, one access each (W0-W4 -> A, W5-W9 -> B, W10-W14 -> C),\n\
         a single-level cache with {} MSHRs, main memory latency {}, one access per cycle.\n\
         Priority warps: W0, W5, W10. WaSP: Real_freeMSHRs = free_mshrs - CF x nonblocked_priority > threshold, CF = 1, threshold = {},\n\
         launch rule {} (with the gate closed and only priority warps waiting: {}).\n\
         Legend: X miss, O secondary miss, H hit, ## blocked (all MSHRs occupied); reply = block answered by memory.\n",
        m.mshrs,
        m.latency,
        m.threshold,
        m.launch_rule,
        match m.launch_rule {
            LaunchRule::Hold => "launch nothing",
            LaunchRule::Launch => "launch the priority warp",
        }
    );
    for c in [&r.scanline, &r.all_priority_first, &r.wasp] {
        s.push_str(&render_chronograph(c));
        s.push('\n');
    }
    let _ = writeln!(
        s,
        "Totals: scanline {} cycles ({} stall), all priority first {} cycles ({} stall), WaSP {} cycles ({} stall).\n{}",
        r.scanline.cycles,
        r.scanline.stall_cycles,
        r.all_priority_first.cycles,
        r.all_priority_first.stall_cycles,
        r.wasp.cycles,
        r.wasp.stall_cycles,
        verdict(r)
    );
    s
}

/// WaSP against scanline order as the cycles of this run show it, and the
/// paper's figure, which is for its own example's machine.
fn verdict(r: &ExampleReport) -> String {
    let (scan, wasp) = (r.scanline.cycles as f64, r.wasp.cycles as f64);
    let change = 100.0 * (wasp / scan - 1.0).abs();
    let compared = if wasp < scan {
        format!("WaSP takes {change:.1}% fewer cycles than scanline order")
    } else if wasp > scan {
        format!("WaSP takes {change:.1}% more cycles than scanline order, a slowdown")
    } else {
        "WaSP takes as many cycles as scanline order".to_string()
    };
    let paper = if r.scanline.machine == ExampleConfig::default() {
        "the paper's \"11% speedup\""
    } else {
        "the paper's \"11% speedup\" is for its own machine: latency 7, 3 MSHRs, threshold 1, hold"
    };
    format!("{compared} ({paper}; speedup {:.3}x).", scan / wasp)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_verdict_follows_the_cycles_and_names_the_papers_machine() {
        let paper = crate::example::run(&ExampleConfig::default()).unwrap();
        let t = render_report(&paper);
        assert!(
            t.contains("WaSP takes 11.1% fewer cycles than scanline order (the paper's \"11% speedup\"; speedup 1.125x)."),
            "{t}"
        );
        // Two MSHRs, latency 3, threshold 0: WaSP is slower here.
        let slower = ExampleConfig {
            latency: 3,
            mshrs: 2,
            threshold: 0,
            ..ExampleConfig::default()
        };
        let t = render_report(&crate::example::run(&slower).unwrap());
        assert!(
            t.contains("WaSP takes 20.0% more cycles than scanline order, a slowdown (the paper's \"11% speedup\" is for its own machine"),
            "{t}"
        );
        assert!(!t.contains("fewer cycles"), "{t}");
    }
}
