//! The disc in exact arithmetic: where a ray's line crosses the disc's
//! plane, and whether that point lies within the disc's two circles.

use super::values::*;
use crate::{Disc, Ray, Side, Vector};
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
