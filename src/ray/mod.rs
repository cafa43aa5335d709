//! The ray, and its prepared form: what every kernel takes.
//!
//! - `mod.rs`: [`Ray`], and the check of a `t_max`.
//! - `interval.rs`: [`Interval`], the range `(t_min, t_max]` of the
//!   kernels' interval forms, and the exact decision of a crossing
//!   against its ends.
//! - `crossing.rs`: a ray's line crossing a plane given by a point and a
//!   normal (the plane test's and a box face's): the quotient, its error
//!   bound, and the crossing over an interval.
//! - `exact_crossing.rs`: the exact place of a crossing with a plane (a
//!   triangle's, or a point and a normal) against a float `t`, the
//!   interval forms' fallback.
//! - `slab.rs`: the box tests' per-ray part, the directed reciprocals.
//! - `shear.rs`: the watertight triangle test's per-ray part, the axis
//!   permutation and shear.
//! - `prepared.rs`: [`PreparedRay`], both parts once per ray, and the one
//!   encoding of an invalid ray.
//! - `walk.rs`: [`Walk`], the windows of a walk along a ray (every hit in
//!   order, from a sequence of interval calls).

mod crossing;
mod exact_crossing;
mod interval;
mod prepared;
mod shear;
mod slab;
mod walk;

use glam::Vec3;

use crate::num::{L, Lanes, S, Scalar, Vector, lanes};

pub(crate) use crossing::{crossing_in, t_error};
pub(crate) use exact_crossing::PlaneCrossing;
pub use interval::Interval;
pub(crate) use interval::{ExactPlace, bring_into, decide, filter};
pub use prepared::PreparedRay;
pub(crate) use shear::{Shear, largest_axis};
pub(crate) use slab::SlabRay;
pub use walk::Walk;

/// A ray `origin + t * dir` for `t >= 0`.
///
/// `dir` need not have unit length: every `t` the crate reports is measured in
/// multiples of `dir`, so scaling `dir` by `k` divides every `t` by `k` (by
/// exactly `k` when `k` is a power of two). A ray whose `dir` is zero, or
/// whose origin or direction has a NaN or infinite component, is not a ray:
/// every kernel returns `None` for it.
///
/// Generic over the precision: `Ray` is `Ray<Vec3>` (`f32`), and
/// `Ray<DVec3>` is the same ray in `f64`.
///
/// ```
/// use rayhit::{Ray, glam::Vec3};
/// let ray = Ray::new(Vec3::new(1.0, 2.0, 3.0), Vec3::new(0.0, 0.0, -2.0));
/// assert_eq!(ray.at(0.5), Vec3::new(1.0, 2.0, 2.0));
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[repr(C)]
pub struct Ray<V = Vec3> {
    /// Where the ray starts (`t = 0`).
    pub origin: V,
    /// The direction; the ray moves by `dir` per unit of `t`.
    pub dir: V,
}

impl<V: Vector> Ray<V> {
    /// A ray from `origin` along `dir`. Nothing is checked or normalised.
    #[inline]
    #[must_use]
    pub const fn new(origin: V, dir: V) -> Self {
        Self { origin, dir }
    }

    /// The point `origin + t * dir`, rounded: each component carries at most
    /// two roundings (`gamma(2)` relative to `|origin| + |t * dir|`).
    #[inline]
    #[must_use]
    pub fn at(&self, t: S<V>) -> V {
        self.origin + self.dir * t
    }

    /// True when the origin and direction are finite and the direction is not
    /// zero: the rays the kernels can hit anything with.
    #[inline]
    #[must_use]
    pub fn is_valid(&self) -> bool {
        // `origin.is_finite() && dir.is_finite() && dir != 0`, written as
        // comparisons on lanes: `|c| <= MAX` is false exactly for the
        // infinities and NaN.
        valid_lanes::<V>(lanes(self.origin), lanes(self.dir))
    }
}

/// Checks that `t_max` is a usable upper limit: `t_max >= 0` (NaN fails).
/// Infinity is allowed and means no limit.
#[inline(always)]
pub(crate) fn t_max_ok<F: Scalar>(t_max: F) -> bool {
    t_max >= F::ZERO
}

/// [`Ray::is_valid`] of the ray from `o` along `d`, given in lanes 0 to 2.
#[inline(always)]
pub(crate) fn valid_lanes<V: Vector>(o: L<V>, d: L<V>) -> bool {
    let big = L::<V>::splat(S::<V>::MAX);
    let finite = o.abs().le(big) & d.abs().le(big) == 0b111;
    finite & (d.eq(L::<V>::splat(S::<V>::ZERO)) != 0b111)
}

/// The ray every invalid ray is prepared as: from `(+inf, +inf, +inf)`
/// along `+z`. This is the one encoding of an invalid ray in a
/// [`PreparedRay`], and every kernel's miss on it comes from its arithmetic
/// alone: the slab test puts every box at `t = -inf`; the triangle tests'
/// shear of `+z` (`s_x = s_y = -0`) makes every sheared coordinate
/// `-inf + (-0)(-inf) = NaN` (or NaN outright), so no edge function has a
/// sign and no corner is in front. `PreparedRay::is_valid` reads it back
/// from the origin.
#[inline(always)]
pub(crate) fn invalid_stand_in<V: Vector>() -> Ray<V> {
    let (zero, one, inf) = (S::<V>::ZERO, S::<V>::ONE, S::<V>::INFINITY);
    Ray::new(V::splat(inf), V::new(zero, zero, one))
}
