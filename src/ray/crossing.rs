//! A ray's line crossing a plane given by a point and a normal: the
//! quotient the plane test computes, its error bound, and the exact
//! decision of the crossing against an [`Interval`]. The plane test's
//! interval form uses it, and so does the box's entry face (the plane of
//! one face).

use super::exact_crossing::PlaneCrossing;
use super::interval::{Interval, bring_into, decide};
use crate::num::round::bound_up;
use crate::num::{S, Scalar, Vector};

/// `((point - origin) . normal) / (dir . normal)`, rounded as
/// [`ray_plane`](crate::ray_plane) rounds it: `(numerator, denominator,
/// quotient)`.
#[inline(always)]
pub(crate) fn quotient<V: Vector>(origin: V, dir: V, point: V, normal: V) -> (S<V>, S<V>, S<V>) {
    let denom = dir.dot(normal);
    let numer = (point - origin).dot(normal);
    (numer, denom, numer / denom)
}

/// The bound of [`ray_plane_t_error`](crate::plane::ray_plane_t_error) (derived
/// there), for a plane given by a point and a normal.
#[inline(always)]
pub(crate) fn t_error<V: Vector>(origin: V, dir: V, point: V, normal: V, t: S<V>) -> S<V> {
    let n = normal.abs();
    let w = (point - origin).abs();
    let denom = dir.dot(normal).abs();
    let a = S::<V>::gamma_n(4) * w.dot(n);
    let b = S::<V>::gamma_n(3) * dir.abs().dot(n);
    let t = t.abs();
    let x = b / denom;
    if !(x <= S::<V>::HALF) {
        return S::<V>::INFINITY;
    }
    let r = (a + t * b) / denom + S::<V>::gamma_n(1) * t;
    bound_up(r * (S::<V>::ONE + S::<V>::TWO * x), 9)
}

/// Where the line `origin + t dir` crosses the plane through `point` with
/// normal `normal`, if the exact crossing `t*` is in `interval` (and at
/// most `MAX`): the rounded quotient of [`quotient`], brought into the
/// interval; `None` where it is not, where the line is exactly parallel
/// to the plane (or the normal is zero), and where the exact signs
/// overflow (`f64` inputs outside their range, see [`PlaneCrossing`]).
/// The inputs must be finite.
///
/// The filter is [`t_error`], whose derivation counts roundings as
/// relative errors. Where a product or quotient underflows its error is
/// absolute instead (at most half the smallest subnormal `T = 2 u
/// MIN_POSITIVE`), so the filter is used only where that cannot matter:
/// `|numer|`, `|denom|` and `|t|` all at least `L = 8 MIN_POSITIVE / u`
/// (`2^-99` in `f32`, `2^-966` in `f64`); elsewhere the exact signs decide
/// both ends. Above `L`:
/// - the rounded products: three underflowing products add at most
///   `1.5 T (1 + u)^2 = 3 u MIN_POSITIVE (1 + u)^2` to the error of the
///   denominator, which is below `u^2 / 2` of `sum |d_i n_i|` (at least
///   `7 MIN_POSITIVE / u` where `|denom| >= L`), inside the gap between
///   `gamma(3)` and `(1 + u)^3 - 1` (at least `6 u^2`); likewise for the
///   numerator with `gamma(4)`; the quotient `t` is a normal float, so its
///   rounding is relative;
/// - the bound's own evaluation: `a >= 4 u L / 2 = 16 MIN_POSITIVE`,
///   `gamma(1) |t| >= 8 MIN_POSITIVE` and so `r` are normal; a term that
///   underflows (`|t| b`, `(a + |t| b) / |denom|`, `x`) loses at most
///   `u MIN_POSITIVE`, which is at most `u / 8` of `r` (or of `a`), less
///   than the spare factor `1 + u` in `bound_up`'s `1 + gamma(10)` for 9
///   roundings.
#[inline(always)]
pub(crate) fn crossing_in<V: Vector>(
    origin: V,
    dir: V,
    point: V,
    normal: V,
    interval: Interval<S<V>>,
) -> Option<S<V>> {
    let (numer, denom, t) = quotient(origin, dir, point, normal);
    let (lo, hi) = interval.ends();
    let floor = S::<V>::from_u32(8) * S::<V>::MIN_POSITIVE / S::<V>::UNIT_ROUNDOFF;
    let clear = numer.abs() >= floor && denom.abs() >= floor && t.abs() >= floor;
    // An infinite (or NaN) bound leaves both ends to the exact signs: the
    // denominator's sign is uncertain there ("parallel within rounding").
    let err = if clear {
        t_error(origin, dir, point, normal, t)
    } else {
        S::<V>::INFINITY
    };
    if !decide(t, err, lo, hi, || exact(origin, dir, point, normal))? {
        return None;
    }
    Some(bring_into(t, lo, hi))
}

/// The exact crossing's signs for the line and the plane.
#[cold]
#[inline(never)]
fn exact<V: Vector>(origin: V, dir: V, point: V, normal: V) -> PlaneCrossing {
    let w = |p: V| [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()];
    // `f64` inputs are scaled; `f32` ones are in range as they are.
    let wide = S::<V>::UNIT_ROUNDOFF.to_f64() < 1e-10;
    PlaneCrossing::with_normal(w(origin), w(dir), w(point), w(normal), wide)
}
