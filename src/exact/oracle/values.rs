//! Exact values: the exact rational of a float, vector arithmetic on
//! them, and the constants and comparisons every exact check needs.

use crate::{Ray, Scalar, Vector};
use core::cmp::Ordering;
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

/// The float of precision `F` nearest to a positive value known only by
/// comparisons (an irrational root, say), ties to even, as IEEE 754
/// rounds: `place(x)` is the value against the exact `x` (`Less` where
/// the value is below `x`), and `estimate` a guess of it (any `f64`: a
/// NaN, an infinity or a wild guess only costs steps). A value at or
/// above `MAX` plus half an ulp gives the infinity; a value that is not
/// positive (`place` of zero not `Greater`) gives zero.
///
/// The search runs over the positive floats in the order of their bit
/// patterns, which is their order as numbers: from the estimate it
/// gallops (1, 2, 4, ... floats) until two floats bracket the value, then
/// halves the bracket until the floats are neighbours, and compares the
/// value with their exact midpoint. It ends: the patterns are fewer than
/// `2^64`, so the gallop doubles its step at most 64 times and the
/// halving takes at most 64 steps, each one call of `place`.
///
/// ```
/// use core::cmp::Ordering;
/// use rayhit::exact::oracle::{R, int, nearest_float};
/// // sqrt(2), placed by the sign of 2 - x^2: no square root taken.
/// let place = |x: &R| {
///     if x < &int(0) { Ordering::Greater } else { int(2).cmp(&(x * x)) }
/// };
/// assert_eq!(nearest_float::<f32>(1.0, place), 2f32.sqrt());
/// assert_eq!(nearest_float::<f64>(f64::NAN, place), 2f64.sqrt());
/// assert_eq!(nearest_float::<f32>(1e30, |x: &R| int(3).cmp(x)), 3.0);
/// ```
#[must_use]
pub fn nearest_float<F: Scalar>(estimate: f64, place: impl Fn(&R) -> Ordering) -> F {
    let at = |i: u64| float_at::<F>(i);
    let value = |i: u64| r(at(i)).expect("a finite float");
    let cmp = |i: u64| place(&value(i));
    let top = index_of(F::MAX);
    if cmp(0) != Ordering::Greater {
        return F::ZERO;
    }
    let guess = F::from_f64(estimate);
    let start = if guess > F::ZERO && guess.is_finite() {
        index_of(guess)
    } else if guess > F::ZERO {
        top
    } else {
        index_of(F::ONE)
    };
    // `lo` below the value, `hi` above it (`None`: above MAX).
    let (mut lo, mut hi) = match cmp(start) {
        Ordering::Equal => return at(start),
        Ordering::Greater => {
            let (mut lo, mut step) = (start, 1u64);
            loop {
                if lo == top {
                    break (lo, None);
                }
                let next = lo.saturating_add(step).min(top);
                match cmp(next) {
                    Ordering::Equal => return at(next),
                    Ordering::Less => break (lo, Some(next)),
                    Ordering::Greater => lo = next,
                }
                step = step.saturating_mul(2);
            }
        }
        Ordering::Less => {
            let (mut hi, mut step) = (start, 1u64);
            loop {
                // Index 0 (zero) is below the value: checked above.
                let next = hi.saturating_sub(step);
                match cmp(next) {
                    Ordering::Equal => return at(next),
                    Ordering::Greater => break (next, Some(hi)),
                    Ordering::Less => hi = next,
                }
                step = step.saturating_mul(2);
            }
        }
    };
    let Some(mut up) = hi.take() else {
        // Above MAX: MAX below MAX + half an ulp, else the infinity
        // (`MAX`'s significand is odd, so a tie goes up).
        let half = (r(F::MAX).expect("finite") - value(top - 1)) / int(2);
        return if place(&(value(top) + half)) == Ordering::Less {
            F::MAX
        } else {
            F::INFINITY
        };
    };
    while up - lo > 1 {
        let mid = lo + (up - lo) / 2;
        match cmp(mid) {
            Ordering::Equal => return at(mid),
            Ordering::Greater => lo = mid,
            Ordering::Less => up = mid,
        }
    }
    match place(&((value(lo) + value(up)) / int(2))) {
        Ordering::Less => at(lo),
        Ordering::Greater => at(up),
        Ordering::Equal if lo % 2 == 0 => at(lo),
        Ordering::Equal => at(up),
    }
}

/// Whether `F` is `f32` (its unit roundoff is `2^-24`).
fn single<F: Scalar>() -> bool {
    F::UNIT_ROUNDOFF.to_f64() == f64::from(f32::EPSILON) * 0.5
}

/// The bit pattern of a float of precision `F` that is not negative:
/// the floats' order as numbers.
fn index_of<F: Scalar>(x: F) -> u64 {
    if single::<F>() {
        u64::from((x.to_f64() as f32).to_bits())
    } else {
        x.to_f64().to_bits()
    }
}

/// The float of precision `F` with the bit pattern `i` (at most `MAX`'s).
fn float_at<F: Scalar>(i: u64) -> F {
    if single::<F>() {
        F::from_f64(f64::from(f32::from_bits(i as u32)))
    } else {
        F::from_f64(f64::from_bits(i))
    }
}
