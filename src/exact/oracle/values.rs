//! Exact values: the exact rational of a float, vector arithmetic on
//! them, and the constants and comparisons every exact check needs.

use crate::{Ray, Scalar, Vector};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};

/// An exact rational.
pub type R = BigRational;
/// An exact 3-vector.
pub type R3 = [R; 3];

/// The exact value of a float (every finite float is a dyadic rational),
/// or `None` for NaN and the infinities.
#[must_use]
pub fn r<F: Scalar>(x: F) -> Option<R> {
    R::from_float(x.to_f64())
}

/// The exact value of a precision's constant (`TINY`, `UNIT_ROUNDOFF`: finite
/// by definition, so the conversion cannot fail).
pub(super) fn constant<F: Scalar>(x: F) -> R {
    R::from_float(x.to_f64()).expect("the precision's constants are finite")
}

/// The exact components of a vector, or `None` when one is not finite.
#[must_use]
pub fn rv<V: Vector>(v: V) -> Option<R3> {
    Some([r(v.x())?, r(v.y())?, r(v.z())?])
}

/// `a - b`, exactly.
#[must_use]
pub fn sub(a: &R3, b: &R3) -> R3 {
    [&a[0] - &b[0], &a[1] - &b[1], &a[2] - &b[2]]
}

/// `a . b`, exactly.
#[must_use]
pub fn dot(a: &R3, b: &R3) -> R {
    &a[0] * &b[0] + &a[1] * &b[1] + &a[2] * &b[2]
}

/// `a x b`, exactly.
#[must_use]
pub fn cross(a: &R3, b: &R3) -> R3 {
    [
        &a[1] * &b[2] - &a[2] * &b[1],
        &a[2] * &b[0] - &a[0] * &b[2],
        &a[0] * &b[1] - &a[1] * &b[0],
    ]
}

/// `t_max` as an exact bound, `None` for no bound (`+inf`; also any other
/// non-finite value, which the checked entry points reject before they get
/// here).
#[must_use]
pub fn limit<F: Scalar>(t_max: F) -> Option<R> {
    r(t_max)
}

pub(super) fn within(t: &R, t_max: &Option<R>) -> bool {
    t_max.as_ref().is_none_or(|m| t <= m)
}

/// An exact value as the nearest `f64` (for reports and for scales),
/// rounded to nearest, ties to even: a value beyond `f64`'s range saturates
/// to an infinity of its sign, one too small for it gives a subnormal or a
/// zero of its sign. Never NaN (`num-rational`'s conversion always answers
/// for a big rational; the NaN fallback is only there to keep this total).
#[must_use]
pub fn to_f64(x: &R) -> f64 {
    x.to_f64().unwrap_or(f64::NAN)
}

/// `|a - b|`, exactly (to compare against a bound given as a float: the
/// comparison is exact, because a float bound is itself exact).
#[must_use]
pub fn abs_diff(a: &R, b: &R) -> R {
    (a - b).abs()
}

/// True when a computed value is within `bound` of the exact one, decided
/// exactly: `|computed - exact| <= bound`. False when `computed` or `bound`
/// is not finite.
#[must_use]
pub fn close<F: Scalar>(computed: F, exact: &R, bound: F) -> bool {
    match (r(computed), r(bound)) {
        (Some(c), Some(b)) => abs_diff(&c, exact) <= b,
        _ => false,
    }
}

/// The exact origin and direction of a ray that moves: `None` when a
/// coordinate is not finite or the direction is zero.
pub(super) fn moving<V: Vector>(ray: &Ray<V>) -> Option<(R3, R3)> {
    let (o, d) = (rv(ray.origin)?, rv(ray.dir)?);
    d.iter().any(|x| !x.is_zero()).then_some((o, d))
}

/// An exact dyadic rational `m * 2^e` as an `R` (for building inputs). Any
/// `e` works; the value takes about `|e|` bits.
#[must_use]
pub fn dyadic(m: i64, e: i32) -> R {
    let power = BigInt::from(1) << e.unsigned_abs();
    if e >= 0 {
        R::from_integer(BigInt::from(m) * power)
    } else {
        R::new(BigInt::from(m), power)
    }
}

/// The spacing of floats of precision `F` at magnitude `m` (one ulp), as
/// `f64`: `|m|` is rounded to `F`, and the answer is the gap from there to
/// the next float up, at least the smallest subnormal. At the largest finite
/// float the next one up is the infinity, so the gap is infinite; a
/// magnitude beyond `F`'s range (and NaN) has no next float and gives the
/// smallest subnormal.
#[must_use]
pub fn ulp<F: Scalar>(m: f64) -> f64 {
    let x = F::from_f64(m.abs());
    (x.next_up().to_f64() - x.to_f64()).max(F::TINY.to_f64())
}

/// `gamma(n) = n u / (1 - n u)` for precision `F` (`u` its unit roundoff),
/// exactly: the bound on the relative error of `n` roundings (Higham,
/// Accuracy and Stability of Numerical Algorithms, 2002, section 3.1).
/// Defined for every `n` the type admits: `n u <= 65535 * 2^-24 < 1` (the
/// formula needs `n u < 1`).
#[must_use]
pub fn gamma<F: Scalar>(n: u16) -> R {
    let nu = int(n.into()) * constant(F::UNIT_ROUNDOFF);
    &nu / (int(1) - &nu)
}

/// An exact integer.
#[must_use]
pub fn int(n: i64) -> R {
    R::from_integer(n.into())
}

/// `|x|`.
#[must_use]
pub fn abs(x: &R) -> R {
    x.abs()
}
