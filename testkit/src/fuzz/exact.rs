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
