//! wasp-kani-shim: the Kani harnesses of `wasp-props` as ordinary tests.
//!
//! `wasp-props` depends on this crate under the name `kani`, only with its
//! own feature `kani-shim` (never under `cfg(kani)`, which the real Kani
//! sets when it links its own `kani` crate). Then every harness compiles
//! against the same five names the harness bodies use:
//!
//! | Kani | here |
//! |---|---|
//! | `#[kani::proof]` | the function becomes a `#[test]` that runs its body under the explorer, many times |
//! | `#[kani::unwind(N)]` | accepted and ignored: the shim runs real loops |
//! | `kani::any::<T>()` | a value of `T` ([`Arbitrary`]: `bool` and the integer types) |
//! | `kani::any_where(pred)` | a value of `T` that `pred` accepts |
//! | `kani::assume(cond)` | a false condition discards the case |
//!
//! **The shim samples; Kani proves.** Each harness runs in one of two
//! modes, chosen by the size of its case tree (every path of draws the
//! body can make), which the shim estimates first from 64 random paths:
//!
//! * **exhaustive** when the estimate is at most the limit (default
//!   2^20 cases, `WASP_KANI_SHIM_LIMIT`): every path, depth first, so the
//!   harness's whole domain (as its draws and `any_where` predicates
//!   constrain it) is checked;
//! * **sampled** otherwise: `WASP_KANI_SHIM_SAMPLES` (default 20,000)
//!   cases that `kani::assume` accepted, every draw uniformly random, from
//!   a seed fixed per harness (the FNV-1a of its path, xor
//!   `WASP_KANI_SHIM_SEED`): the same cases every run.
//!
//! A failing case prints its draws, then the harness fails. Each harness
//! appends one line (path, mode, cases, discarded, estimate, seed) to the
//! file named by `WASP_KANI_SHIM_REPORT`, if set (`scripts/harnesses.sh`
//! reads them).

mod arbitrary;
mod explore;
mod rng;
mod run;

pub use arbitrary::Arbitrary;
pub use wasp_kani_shim_macros::{proof, unwind};

/// A value of `T`: the next value of the harness's enumeration or sample.
#[inline]
pub fn any<T: Arbitrary>() -> T {
    explore::any()
}

/// A value of `T` that `pred` accepts (Kani: `any()` then
/// `assume(pred(&v))`). The shim enumerates the accepted values of a type
/// of at most 2^16 values, so a narrow predicate costs one branch per
/// accepted value, not per value of the type.
#[inline]
pub fn any_where<T: Arbitrary, F: Fn(&T) -> bool>(pred: F) -> T {
    explore::any_where(pred)
}

/// Discard the current case unless `cond` holds.
#[inline]
pub fn assume(cond: bool) {
    explore::assume(cond)
}

/// What `#[kani::proof]` expands to calls; not for harness code.
#[doc(hidden)]
pub mod __shim {
    pub use crate::run::run_harness;
}
