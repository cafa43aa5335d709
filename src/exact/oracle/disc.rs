//! The disc in exact arithmetic: where a ray's line crosses the disc's
//! plane, and whether that point lies within the disc's two circles.

use super::values::*;
use crate::{Disc, Plane, Ray, Scalar, Side, Vector};
use core::cmp::Ordering;
use num_traits::{Signed, Zero};

/// A ray's line against a disc, exactly: the crossing `t* = ((c - o) . n) /
/// (d . n)` with the disc's plane and the squared distance of that point
/// from the centre, against the squared radii.
#[derive(Debug, Clone)]
pub struct ExactDisc {
    /// The crossing's `t` (any sign).
    pub t: R,
    /// `|o + t* d - c|^2`.
    pub dist2: R,
    /// The outer radius, squared.
    pub outer2: R,
    /// The inner radius, squared.
    pub inner2: R,
    /// The side the ray arrives from: [`Side::Front`] where `d . n < 0`.
    pub side: Side,
}

impl ExactDisc {
    /// The crossing lies in the closed annulus (both circles included).
    #[must_use]
    pub fn within_rims(&self) -> bool {
        self.dist2 <= self.outer2 && self.dist2 >= self.inner2
    }

    /// The squared distance from the centre against `r^2` (for a radius
    /// `r`), as the kernel's rim test decides it.
    #[must_use]
    pub fn rim_cmp(&self, r2: &R) -> Ordering {
        self.dist2.cmp(r2)
    }

    /// The disc is crossed within `(lo, hi]` (`hi` `None`: no upper end).
    #[must_use]
    pub fn hit_in(&self, lo: &R, hi: Option<&R>) -> bool {
        self.t > *lo && hi.is_none_or(|h| self.t <= *h) && self.within_rims()
    }
}

/// Exact ray/disc: `None` where the ray is parallel to the plane (`d . n`
/// exactly zero, a zero normal included) or a value is not finite.
#[must_use]
pub fn disc<V: Vector>(ray: &Ray<V>, disc: &Disc<V>) -> Option<ExactDisc> {
    let (o, d, c, n) = (
        rv(ray.origin)?,
        rv(ray.dir)?,
        rv(disc.center)?,
        rv(disc.normal)?,
    );
    let (ro, ri) = (r(disc.radius)?, r(disc.inner_radius)?);
    let den = dot(&d, &n);
    if den.is_zero() {
        return None;
    }
    let t = dot(&sub(&c, &o), &n) / &den;
    let p: R3 = [0, 1, 2].map(|i| &o[i] + &t * &d[i] - &c[i]);
    Some(ExactDisc {
        dist2: dot(&p, &p),
        outer2: &ro * &ro,
        inner2: &ri * &ri,
        side: if den.is_negative() {
            Side::Front
        } else {
            Side::Back
        },
        t,
    })
}

/// The disc case is outside the ray/disc test's rounding band (the `t_max`
/// form's: see [`Disc`'s `hit`](crate::Disc#method.hit)): the plane's band
/// ([`plane_clear`](super::plane_clear): not within rounding of parallel,
/// the crossing farther than its bound from `t_max`), the crossing more
/// than three times its bound from 0 (the test drops a crossing within its
/// bound of 0, judged on the computed `t`), and `|t*|`, `|(c - o) . n|`
/// and `|d . n|` each at least `16 MIN_POSITIVE / u` (twice the floor
/// below which the test's bound is not used). The rims need no band: the
/// test decides them exactly. False (an `Edge` case) elsewhere, and when
/// a value is not finite or the direction is zero.
#[must_use]
pub fn disc_clear<V: Vector>(ray: &Ray<V>, dsc: &Disc<V>, t_max: V::Scalar) -> bool {
    let finite = dsc.radius.is_finite() && dsc.inner_radius.is_finite();
    let plane = Plane::new(dsc.center, dsc.normal);
    let Some(e) = disc(ray, dsc).filter(|_| finite) else {
        return false;
    };
    let (Some(o), Some(d), Some(c), Some(n)) =
        (rv(ray.origin), rv(ray.dir), rv(dsc.center), rv(dsc.normal))
    else {
        return false;
    };
    let floor = int(16) * constant(V::Scalar::MIN_POSITIVE) / constant(V::Scalar::UNIT_ROUNDOFF);
    let above = |x: R| x.abs() >= floor;
    super::plane::crossing_clear(ray, &plane, t_max, 3)
        && above(e.t)
        && above(dot(&sub(&c, &o), &n))
        && above(dot(&d, &n))
}
