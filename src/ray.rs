//! The ray: an origin and a direction.

use glam::Vec3;

use crate::real::{S, Scalar, Vector};

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
        self.origin.is_finite() && self.dir.is_finite() && self.dir != V::ZERO
    }
}

/// Checks that `t_max` is a usable upper limit: `t_max >= 0` (NaN fails).
/// Infinity is allowed and means no limit.
#[inline(always)]
pub(crate) fn t_max_ok<F: Scalar>(t_max: F) -> bool {
    t_max >= F::ZERO
}
