//! Running one harness: estimate its case tree, then enumerate it or
//! sample it, and report.

use crate::explore::{Discarded, Explorer, Mode, Unenumerable};
use crate::rng::fnv;
use std::any::Any;
use std::io::Write as _;
use std::panic::{catch_unwind, resume_unwind, AssertUnwindSafe};
use std::time::Instant;

/// Random paths of the estimate.
const PROBES: u32 = 64;

/// Settings, from the environment.
#[derive(Clone, Debug)]
struct Settings {
    /// Largest estimated case tree run exhaustively.
    limit: f64,
    /// Accepted cases of a sampled harness.
    samples: u64,
    /// Xored into every harness's seed.
    seed: u64,
    /// File the report lines are appended to.
    report: Option<std::path::PathBuf>,
}

fn env_u64(name: &str, default: u64) -> u64 {
    match std::env::var(name) {
        Ok(v) => v.trim().parse().unwrap_or_else(|_| {
            panic!("{name}={v:?}: expected a non-negative integer (default {default})")
        }),
        Err(_) => default,
    }
}

impl Settings {
    fn from_env() -> Self {
        Self {
            limit: env_u64("WASP_KANI_SHIM_LIMIT", 1 << 20) as f64,
            samples: env_u64("WASP_KANI_SHIM_SAMPLES", 20_000).max(1),
            seed: env_u64("WASP_KANI_SHIM_SEED", 0),
            report: std::env::var_os("WASP_KANI_SHIM_REPORT").map(Into::into),
        }
    }
}

enum Outcome {
    Passed,
    Discarded,
    Unenumerable,
}

/// Run one case of `body`. A failure (any panic but the shim's own
/// payloads) prints the case's draws and fails the harness.
fn case(ex: &mut Explorer, path: &str, body: &dyn Fn()) -> Outcome {
    ex.begin_case();
    let (back, r) = std::mem::replace(ex, Explorer::new(Mode::Sample, 0))
        .with_installed(|| catch_unwind(AssertUnwindSafe(body)));
    *ex = back;
    match r {
        Ok(()) => Outcome::Passed,
        Err(p) if p.is::<Discarded>() => Outcome::Discarded,
        Err(p) if p.is::<Unenumerable>() => Outcome::Unenumerable,
        Err(p) => fail(ex, path, p),
    }
}

fn fail(ex: &Explorer, path: &str, payload: Box<dyn Any + Send>) -> ! {
    eprintln!(
        "kani shim: harness {path} failed ({:?} mode) on the case\n{}",
        ex.mode,
        ex.trail()
    );
    resume_unwind(payload)
}

/// What a run of one harness did.
struct Tally {
    mode: &'static str,
    cases: u64,
    discarded: u64,
}

/// Every path of the case tree, depth first; fails if the tree turns out
/// far larger than its estimate.
fn exhaustive(path: &str, seed: u64, body: &dyn Fn(), estimate: f64, s: &Settings) -> Tally {
    let cap = (8.0 * s.limit.max(estimate)) as u64;
    let mut ex = Explorer::new(Mode::Exhaustive, seed);
    let mut t = Tally {
        mode: "exhaustive",
        cases: 0,
        discarded: 0,
    };
    loop {
        match case(&mut ex, path, body) {
            Outcome::Passed => t.cases += 1,
            Outcome::Discarded => t.discarded += 1,
            Outcome::Unenumerable => panic!(
                "kani shim: {path}: an any_where over more than 2^16 values cannot be enumerated \
                 (its probes should have said so)"
            ),
        }
        if t.cases + t.discarded > cap {
            panic!(
                "kani shim: {path}: more than {cap} cases, the estimate was {estimate:.0}: \
                 set WASP_KANI_SHIM_LIMIT below the estimate to sample this harness"
            );
        }
        if !ex.advance() {
            return t;
        }
    }
}

/// `s.samples` accepted random cases, at most 100 tries per case.
fn sampled(path: &str, seed: u64, body: &dyn Fn(), s: &Settings) -> Tally {
    let mut ex = Explorer::new(Mode::Sample, seed);
    let mut t = Tally {
        mode: "sampled",
        cases: 0,
        discarded: 0,
    };
    let tries = s.samples.saturating_mul(100);
    while t.cases < s.samples {
        match case(&mut ex, path, body) {
            Outcome::Passed => t.cases += 1,
            Outcome::Discarded | Outcome::Unenumerable => t.discarded += 1,
        }
        if t.cases + t.discarded >= tries && t.cases < s.samples {
            panic!(
                "kani shim: {path}: kani::assume refused {} of {} random cases ({} accepted, {} wanted)",
                t.discarded,
                t.cases + t.discarded,
                t.cases,
                s.samples
            );
        }
    }
    t
}

/// The case tree's size: the mean of Knuth's estimate (the product of the
/// branching factors along a uniformly random path) over [`PROBES`] paths;
/// infinite if a draw cannot be enumerated. The probes are cases too: a
/// failing one fails the harness.
fn estimate(path: &str, seed: u64, body: &dyn Fn()) -> f64 {
    let mut probe = Explorer::new(Mode::Probe, seed.rotate_left(32));
    let (mut sum, mut unenumerable) = (0.0, false);
    for _ in 0..PROBES {
        case(&mut probe, path, body);
        sum += probe.branching;
        unenumerable |= probe.unenumerable;
    }
    if unenumerable {
        f64::INFINITY
    } else {
        sum / f64::from(PROBES)
    }
}

/// The test `#[kani::proof]` makes of a harness: run `body` under the
/// explorer (`module` is the harness's `module_path!()`).
pub fn run_harness(module: &str, name: &str, body: impl Fn()) {
    let start = Instant::now();
    // libtest's name: the module path without the crate.
    let path = match module.split_once("::") {
        Some((_, m)) => format!("{m}::{name}"),
        None => name.to_string(),
    };
    let s = Settings::from_env();
    let seed = s.seed ^ fnv(&path);
    let estimate = estimate(&path, seed, &body);
    let t = if estimate <= s.limit {
        exhaustive(&path, seed, &body, estimate, &s)
    } else {
        sampled(&path, seed, &body, &s)
    };
    let line = format!(
        "{path}\t{}\t{}\t{}\t{estimate:.3e}\t{seed:#018x}\t{:.1}\n",
        t.mode,
        t.cases,
        t.discarded,
        start.elapsed().as_secs_f64()
    );
    print!("kani shim: {line}");
    if let Some(file) = &s.report {
        // One write per line: concurrent harnesses append whole lines.
        let r = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(file)
            .and_then(|mut f| f.write_all(line.as_bytes()));
        if let Err(e) = r {
            panic!("kani shim: cannot append to {}: {e}", file.display());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::RefCell;
    use std::collections::HashSet;

    fn settings(limit: f64, samples: u64) -> Settings {
        Settings {
            limit,
            samples,
            seed: 0,
            report: None,
        }
    }

    /// a in 0..5, b any bool but not (3, true), c in 0..=a: 26 cases, one
    /// refused prefix.
    fn small_tree(seen: &RefCell<HashSet<(u8, bool, u8)>>) {
        let a = crate::any_where(|x: &u8| *x < 5);
        let b: bool = crate::any();
        crate::assume(!(a == 3 && b));
        let c = crate::any_where(|x: &u8| *x <= a);
        seen.borrow_mut().insert((a, b, c));
    }

    #[test]
    fn exhaustive_runs_every_path_once() {
        let seen = RefCell::new(HashSet::new());
        let t = exhaustive("t", 0, &|| small_tree(&seen), 1.0, &settings(1e6, 1));
        assert_eq!((t.cases, t.discarded), (26, 1));
        assert_eq!(seen.borrow().len(), 26);
        let e = estimate("t", 0, &|| small_tree(&seen));
        assert!((10.0..=60.0).contains(&e), "estimate {e}");
    }

    #[test]
    fn wide_draws_are_estimated_and_sampled() {
        let body = || {
            let x: u32 = crate::any();
            let y = crate::any_where(|v: &u32| v.is_multiple_of(3));
            crate::assume(x.is_multiple_of(2));
            assert!(y.is_multiple_of(3));
        };
        assert!(estimate("w", 1, &body).is_infinite());
        let t = sampled("w", 1, &body, &settings(1e6, 500));
        assert_eq!(t.cases, 500);
        assert!(t.discarded > 100, "about half refused: {}", t.discarded);
        // u8 x u8: 65,536 paths, estimated exactly.
        let e = estimate("e", 1, &|| {
            let _: (u8, u8) = (crate::any(), crate::any());
        });
        assert_eq!(e, 65536.0);
    }

    #[test]
    fn a_failing_case_fails_the_harness() {
        let r = catch_unwind(|| {
            exhaustive(
                "f",
                0,
                &|| {
                    let v: u8 = crate::any();
                    assert!(v != 200, "planted");
                },
                256.0,
                &settings(1e6, 1),
            )
        });
        let p = r.err().expect("the harness fails");
        assert_eq!(p.downcast_ref::<&str>(), Some(&"planted"));
    }

    #[test]
    fn refusing_everything_fails_a_sampled_harness() {
        let r = catch_unwind(|| sampled("r", 0, &|| crate::assume(false), &settings(1.0, 10)));
        assert!(r.is_err());
    }
}
