//! Exact-arithmetic helpers: `rayhit::exact`'s building blocks under the
//! short names the checks use, and two of the checks' own.

use rayhit::Vector;

pub use crate::oracle::{R, R3, abs, cross, dot, dyadic, gamma, int, r, rv, sub, to_f64 as f};

/// `2^k`, exactly.
pub fn pow2(k: i32) -> R {
    dyadic(1, k)
}

/// True when every component of every vector is finite.
pub fn all_finite<V: Vector>(vs: &[V]) -> bool {
    vs.iter().all(|v| v.is_finite())
}

/// `floor(log2 |x|)` of a finite nonzero `x`, subnormals included.
pub fn exponent(x: f64) -> i32 {
    let bits = x.abs().to_bits();
    let e = (bits >> 52) as i32;
    if e == 0 {
        (63 - bits.leading_zeros() as i32) - 1074
    } else {
        e - 1023
    }
}

/// `c - o` component by component as exact pairs `(sum, error)` (Knuth's
/// two-sum), or `None` where a difference overflows.
pub fn difference_pairs(c: [f64; 3], o: [f64; 3]) -> Option<[(f64, f64); 3]> {
    let f = [0, 1, 2].map(|i| {
        let s = c[i] - o[i];
        let bb = s - c[i];
        (s, (c[i] - (s - bb)) + (-o[i] - bb))
    });
    f.iter().all(|p| p.0.is_finite()).then_some(f)
}

/// The exponent of the largest magnitude among `xs` (0 where all are
/// zero): the power of two that scales them into `[1, 2)`.
pub fn scale_of(xs: &[f64]) -> i32 {
    let m = xs.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if m > 0.0 { exponent(m) } else { 0 }
}

/// `x` is zero, or at least `2^-150` once scaled by `2^-e`: the range in
/// which the crate's `f64` exact signs are documented exact.
pub fn in_exact_range(x: f64, e: i32) -> bool {
    x == 0.0 || exponent(x) - e >= -150
}
