//! The plane in exact arithmetic: where a ray's line crosses it, the
//! kernel's answer, and whether a case is outside the kernel's rounding
//! band.

use super::values::*;
use crate::{Plane, Ray, Scalar, Vector};
use num_traits::{Signed, Zero};

/// Exact ray/plane: the `t` where the ray's line crosses the plane (any
/// sign), or `None` when the ray is parallel to the plane (or the normal or
/// the direction is zero) or a coordinate is not finite.
#[must_use]
pub fn plane_t<V: Vector>(ray: &Ray<V>, plane: &Plane<V>) -> Option<R> {
    let n = rv(plane.normal)?;
    let den = dot(&rv(ray.dir)?, &n);
    if den.is_zero() {
        return None;
    }
    Some(dot(&sub(&rv(plane.point)?, &rv(ray.origin)?), &n) / den)
}

/// Exact ray/plane answer with the kernel's conventions: the crossing `t`
/// when `0 < t <= t_max`, else `None` (as for [`plane_t`]).
#[must_use]
pub fn plane_hit<V: Vector>(ray: &Ray<V>, plane: &Plane<V>, t_max: V::Scalar) -> Option<R> {
    let t = plane_t(ray, plane)?;
    (t.is_positive() && within(&t, &limit(t_max))).then_some(t)
}

/// The plane case is outside the kernel's rounding band: not within rounding
/// of parallel (`|d.n| > 4 gamma(3) sum |d_i n_i|`, twice the kernel's own
/// threshold), and the crossing farther than its error bound from 0 and
/// `t_max`. False when a coordinate is not finite.
#[must_use]
pub fn plane_clear<V: Vector>(ray: &Ray<V>, plane: &Plane<V>, t_max: V::Scalar) -> bool {
    crossing_clear(ray, plane, t_max, 1)
}

/// [`plane_clear`], with the crossing farther than `margin` times its
/// bound from 0 (the disc, which drops a crossing within its bound of 0,
/// asks for more).
pub(super) fn crossing_clear<V: Vector>(
    ray: &Ray<V>,
    plane: &Plane<V>,
    t_max: V::Scalar,
    margin: i64,
) -> bool {
    let (Some(d), Some(n)) = (rv(ray.dir), rv(plane.normal)) else {
        return false;
    };
    if !(ray.origin.is_finite() && plane.point.is_finite()) {
        return false;
    }
    let mag: R = (0..3).map(|k| (&d[k] * &n[k]).abs()).sum();
    let resolved = dot(&d, &n).abs() > int(4) * gamma::<V::Scalar>(3) * mag;
    resolved
        && plane_t(ray, plane).is_none_or(|t| {
            let bound =
                crate::Surface::hit_error(plane, ray, &V::Scalar::from_f64(to_f64(&t))).next_up();
            // An unbounded error (an overflow) decides nothing.
            let Some(err) = r(bound) else {
                return false;
            };
            let limit = limit(t_max);
            t.abs() > int(margin) * &err && limit.is_none_or(|m| (m - &t).abs() > err)
        })
}
