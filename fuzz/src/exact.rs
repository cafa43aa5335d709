//! Small exact-arithmetic helpers on top of the shared oracle.

use num_traits::Signed;
use rayhit::{Scalar, Vector};

pub use crate::oracle::{R, R3, cross, dot, r, rv, sub};

/// `gamma(n) = n u / (1 - n u)` for the precision of `F`, exactly.
pub fn gamma<F: Scalar>(n: i64) -> R {
    let nu = int(n) * r(F::UNIT_ROUNDOFF);
    &nu / (int(1) - &nu)
}

/// An exact integer.
pub fn int(n: i64) -> R {
    R::from_integer(n.into())
}

/// `|x|`.
pub fn abs(x: &R) -> R {
    x.abs()
}

/// `2^k`, exactly.
pub fn pow2(k: i32) -> R {
    crate::oracle::dyadic(1, k)
}

/// True when every component of every vector is finite.
pub fn all_finite<V: Vector>(vs: &[V]) -> bool {
    vs.iter().all(|v| v.is_finite())
}

/// The nearest `f64` of an exact value (for messages).
pub fn f(x: &R) -> f64 {
    crate::oracle::to_f64(x)
}
