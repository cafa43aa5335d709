//! How far a claimed value is from the exact one, as [`judge`](super::judge)
//! measures it: in ulps of the exact value or of one, exactly for a
//! rational value and by bracketing for a root known by comparisons.

use super::*;
use core::cmp::Ordering;

/// `|claimed - exact|` in units of `unit` (a claimed non-finite value is
/// infinitely wrong).
pub(super) fn err_in<F: Scalar>(claimed: F, exact: &Rational, unit: f64) -> f64 {
    match rational(claimed) {
        Some(c) => oracle::to_f64(&(c - exact).abs()) / unit,
        None => f64::INFINITY,
    }
}

pub(super) fn rel_err<F: Scalar>(claimed: F, exact: &Rational) -> f64 {
    err_in(claimed, exact, oracle::ulp::<F>(oracle::to_f64(exact)))
}

/// `|claimed - x|` in ulps of `x`, for a value `x` known by comparisons
/// (`place`, as [`oracle::nearest_float`] takes it) whose nearest float is
/// `near`: `x` is bracketed between the midpoints around `near`, and the
/// bracket halved 24 times, so the error is exact to `2^-24` ulps (the
/// distance to the bracket, never more than the true error: so the
/// nearest float is within half an ulp).
pub(super) fn root_err<F: Scalar>(
    claimed: F,
    near: F,
    place: impl Fn(&Rational) -> Ordering,
) -> f64 {
    root_err_in(claimed, near, place, None)
}

/// [`root_err`] in units of `unit` (`None`: ulps of `x`), to within
/// `2^-24` of an ulp of `x`.
pub(super) fn root_err_in<F: Scalar>(
    claimed: F,
    near: F,
    place: impl Fn(&Rational) -> Ordering,
    unit: Option<f64>,
) -> f64 {
    let (Some(c), Some(n), Some(below), Some(above)) = (
        rational(claimed),
        rational(near),
        rational(near.next_down()),
        rational(near.next_up()),
    ) else {
        return f64::INFINITY;
    };
    let two = Rational::from_integer(2.into());
    let (mut lo, mut hi) = ((below + &n) / &two, (n + above) / &two);
    for _ in 0..24 {
        let mid = (&lo + &hi) / &two;
        match place(&mid) {
            Ordering::Greater => lo = mid,
            Ordering::Less => hi = mid,
            Ordering::Equal => {
                (lo, hi) = (mid.clone(), mid);
                break;
            }
        }
    }
    let gap = if c < lo {
        &lo - c
    } else if c > hi {
        c - &hi
    } else {
        Rational::zero()
    };
    oracle::to_f64(&gap) / unit.unwrap_or_else(|| oracle::ulp::<F>(oracle::to_f64(&lo)))
}
