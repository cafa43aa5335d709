//! `approx` comparisons for the public types (feature `approx-05`).
//!
//! [`AbsDiffEq`], [`RelativeEq`] and [`UlpsEq`] for [`Ray`], [`Aabb`],
//! [`Plane`], [`Triangle`] and [`TriangleHit`], in both precisions, so that a
//! renderer's own results can be held against this crate's with
//! `assert_relative_eq!`. What a comparison means:
//! - a shape or ray: every component of every vector field (`origin` and
//!   `dir`; `min` and `max`; `point` and `normal`; `a`, `b` and `c`) within
//!   the tolerance. It compares representations, not geometry: a plane given
//!   by another point or a scaled normal is a different plane here;
//! - a [`TriangleHit`]: `t`, `u` and `v` each within the tolerance, and the
//!   same [`Side`](crate::Side) exactly;
//! - a box interval `(enter, exit)` is a tuple, which `approx` does not
//!   cover: compare `enter` and `exit` as floats.
//!
//! The tolerances are `approx`'s: `epsilon` absolute, `max_relative`
//! relative to the larger magnitude, `max_ulps` in units in the last place
//! of the precision. For a hit, a relative tolerance on `t` is usually the
//! meaningful one; the crate's error bounds
//! ([`Triangle`'s `hit_error`](crate::Triangle#method.hit_error),
//! [`Plane`'s `hit_error`](crate::Plane#method.hit_error)) say how large it must be.
//!
//! ```
//! use approx::assert_relative_eq;
//! use rayhit::{Ray, Triangle, TriangleHit, ray_triangle, glam::Vec3};
//! let tri = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
//! let ray = Ray::new(Vec3::new(0.2, 0.3, 1.0), -Vec3::Z);
//! let a = ray_triangle(&ray, &tri, f32::INFINITY).unwrap();
//! let b = tri.moller_trumbore(&ray, f32::INFINITY).unwrap();
//! assert_relative_eq!(a, b, max_relative = 1e-6);
//! ```

use approx::{AbsDiffEq, RelativeEq, UlpsEq};

use crate::num::{S, Scalar, Vector};
use crate::{Aabb, Plane, Ray, Triangle, TriangleHit};

/// The three traits for a struct of vector fields, compared field by field.
macro_rules! impl_fields {
    ($T:ident: $($field:ident),+) => {
        impl<V> AbsDiffEq for $T<V>
        where
            V: Vector + AbsDiffEq<Epsilon = S<V>>,
        {
            type Epsilon = S<V>;
            fn default_epsilon() -> S<V> {
                V::default_epsilon()
            }
            fn abs_diff_eq(&self, other: &Self, epsilon: S<V>) -> bool {
                $(self.$field.abs_diff_eq(&other.$field, epsilon))&&+
            }
        }

        impl<V> RelativeEq for $T<V>
        where
            V: Vector + RelativeEq<Epsilon = S<V>>,
        {
            fn default_max_relative() -> S<V> {
                V::default_max_relative()
            }
            fn relative_eq(&self, other: &Self, epsilon: S<V>, max_relative: S<V>) -> bool {
                $(self.$field.relative_eq(&other.$field, epsilon, max_relative))&&+
            }
        }

        impl<V> UlpsEq for $T<V>
        where
            V: Vector + UlpsEq<Epsilon = S<V>>,
        {
            fn default_max_ulps() -> u32 {
                V::default_max_ulps()
            }
            fn ulps_eq(&self, other: &Self, epsilon: S<V>, max_ulps: u32) -> bool {
                $(self.$field.ulps_eq(&other.$field, epsilon, max_ulps))&&+
            }
        }
    };
}

impl_fields!(Ray: origin, dir);
impl_fields!(Aabb: min, max);
impl_fields!(Plane: point, normal);
impl_fields!(Triangle: a, b, c);

impl<F> AbsDiffEq for TriangleHit<F>
where
    F: Scalar + AbsDiffEq<Epsilon = F>,
{
    type Epsilon = F;
    fn default_epsilon() -> F {
        F::default_epsilon()
    }
    fn abs_diff_eq(&self, other: &Self, epsilon: F) -> bool {
        self.side == other.side
            && self.t.abs_diff_eq(&other.t, epsilon)
            && self.u.abs_diff_eq(&other.u, epsilon)
            && self.v.abs_diff_eq(&other.v, epsilon)
    }
}

impl<F> RelativeEq for TriangleHit<F>
where
    F: Scalar + RelativeEq<Epsilon = F>,
{
    fn default_max_relative() -> F {
        F::default_max_relative()
    }
    fn relative_eq(&self, other: &Self, epsilon: F, max_relative: F) -> bool {
        self.side == other.side
            && self.t.relative_eq(&other.t, epsilon, max_relative)
            && self.u.relative_eq(&other.u, epsilon, max_relative)
            && self.v.relative_eq(&other.v, epsilon, max_relative)
    }
}

impl<F> UlpsEq for TriangleHit<F>
where
    F: Scalar + UlpsEq<Epsilon = F>,
{
    fn default_max_ulps() -> u32 {
        F::default_max_ulps()
    }
    fn ulps_eq(&self, other: &Self, epsilon: F, max_ulps: u32) -> bool {
        self.side == other.side
            && self.t.ulps_eq(&other.t, epsilon, max_ulps)
            && self.u.ulps_eq(&other.u, epsilon, max_ulps)
            && self.v.ulps_eq(&other.v, epsilon, max_ulps)
    }
}
