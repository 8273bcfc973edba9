//! Deterministic math for the generator: only IEEE-754 operations whose
//! results are exactly specified (+ - * / sqrt, floor, round, comparisons)
//! and these series instead of the platform's libm, so a seed gives the
//! same trace everywhere.

use crate::rng::splitmix64;

// Deterministic math. The generator uses only IEEE-754 operations whose
// results are exactly specified (+ - * / sqrt, floor, round, comparisons) and
// these series instead of the platform's libm, so a seed gives the same
// trace everywhere.

/// 2^x for |x| < 1000, by 2^floor(x) times a Taylor series of e^(f ln 2).
pub(super) fn exp2(x: f64) -> f64 {
    let n = x.floor();
    let y = (x - n) * std::f64::consts::LN_2; // in [0, ln 2)
    let mut term = 1.0;
    let mut sum = 1.0;
    for k in 1..=20 {
        term = term * y / f64::from(k);
        sum += term;
    }
    let n = n.clamp(-1022.0, 1023.0) as i64;
    sum * f64::from_bits(((n + 1023) as u64) << 52)
}

/// (sin x, cos x) for |x| <= pi by Taylor series (error below 1e-14).
pub(super) fn sin_cos(x: f64) -> (f64, f64) {
    let x2 = x * x;
    let (mut s_term, mut c_term) = (x, 1.0);
    let (mut s, mut c) = (x, 1.0);
    for k in 1..=15 {
        let k = f64::from(k);
        s_term = -s_term * x2 / ((2.0 * k) * (2.0 * k + 1.0));
        c_term = -c_term * x2 / ((2.0 * k - 1.0) * (2.0 * k));
        s += s_term;
        c += c_term;
    }
    (s, c)
}

/// Hash of lattice point (i, j) of noise octave `o` to [0, 1).
pub(super) fn lattice(seed: u64, o: u64, i: i64, j: i64) -> f64 {
    let mut s = seed
        ^ (o.wrapping_mul(0x9e37_79b9_7f4a_7c15))
        ^ ((i as u64).wrapping_mul(0xd1b5_4a32_d192_ed03))
        ^ ((j as u64).wrapping_mul(0x8cb9_2ba7_2f3d_8dd7));
    (splitmix64(&mut s) >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// Two octaves of smooth value noise at pixel (x, y), feature size `l`.
pub(super) fn noise(seed: u64, x: f64, y: f64, l: f64) -> f64 {
    let mut sum = 0.0;
    for (o, (scale, amp)) in [(1.0, 1.0), (0.5, 0.5)].into_iter().enumerate() {
        let (gx, gy) = (x / (l * scale), y / (l * scale));
        let (i, j) = (gx.floor(), gy.floor());
        let (fx, fy) = (gx - i, gy - j);
        let (sx, sy) = (fx * fx * (3.0 - 2.0 * fx), fy * fy * (3.0 - 2.0 * fy));
        let (i, j) = (i as i64, j as i64);
        let o = o as u64;
        let a = lattice(seed, o, i, j);
        let b = lattice(seed, o, i + 1, j);
        let c = lattice(seed, o, i, j + 1);
        let d = lattice(seed, o, i + 1, j + 1);
        let top = a + (b - a) * sx;
        let bottom = c + (d - c) * sx;
        sum += amp * (top + (bottom - top) * sy);
    }
    sum
}
