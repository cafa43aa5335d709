//! Constructors from [`mint`]'s point and vector types, the common currency
//! of Rust math crates (nalgebra, cgmath, ultraviolet and glam itself convert
//! to and from them).
//!
//! The shapes are built from `mint::Point3` (positions) and `mint::Vector3`
//! (directions and normals) of the vector type's scalar, component by
//! component, so the bits are those of the input: a shape built this way
//! gives exactly the answers of one built from the same components with
//! `new`. Going the other way needs nothing from this crate: with this
//! feature on, glam's own mint conversions are on for every glam enabled, so
//! a hit point or a ray's fields convert with `.into()`.
//!
//! ```
//! use rayhit::{Ray, Triangle, ray_triangle, glam::Vec3};
//! // Another math crate's points, as mint types.
//! let corners = [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
//!     .map(mint::Point3::from);
//! let tri: Triangle<Vec3> = Triangle::from_mint(corners[0], corners[1], corners[2]);
//! let ray: Ray<Vec3> = Ray::from_mint(
//!     mint::Point3::from([0.25, 0.25, 1.0]),
//!     mint::Vector3::from([0.0, 0.0, -1.0]),
//! );
//! let hit = ray_triangle(&ray, &tri, f32::INFINITY).unwrap();
//! let point: mint::Point3<f32> = ray.at(hit.t).into();
//! assert_eq!((point.x, point.y, point.z), (0.25, 0.25, 0.0));
//! ```

use mint::{Point3, Vector3};

use crate::num::{S, Vector};
use crate::{Aabb, Plane, Ray, Triangle};

#[inline]
fn point<V: Vector>(p: impl Into<Point3<S<V>>>) -> V {
    let p = p.into();
    V::new(p.x, p.y, p.z)
}

#[inline]
fn vector<V: Vector>(v: impl Into<Vector3<S<V>>>) -> V {
    let v = v.into();
    V::new(v.x, v.y, v.z)
}

impl<V: Vector> Ray<V> {
    /// [`Ray::new`] from mint types: the origin as a point, the direction as
    /// a vector (not necessarily unit; `t` is measured in its lengths).
    #[inline]
    #[must_use]
    pub fn from_mint(origin: impl Into<Point3<S<V>>>, dir: impl Into<Vector3<S<V>>>) -> Self {
        Self::new(point(origin), vector(dir))
    }
}

impl<V: Vector> Aabb<V> {
    /// [`Aabb::new`] from two mint points, the minimum and maximum corners.
    #[inline]
    #[must_use]
    pub fn from_mint(min: impl Into<Point3<S<V>>>, max: impl Into<Point3<S<V>>>) -> Self {
        Self::new(point(min), point(max))
    }
}

impl<V: Vector> Triangle<V> {
    /// [`Triangle::new`] from three mint points, in winding order.
    #[inline]
    #[must_use]
    pub fn from_mint(
        a: impl Into<Point3<S<V>>>,
        b: impl Into<Point3<S<V>>>,
        c: impl Into<Point3<S<V>>>,
    ) -> Self {
        Self::new(point(a), point(b), point(c))
    }
}

impl<V: Vector> Plane<V> {
    /// [`Plane::new`] from a mint point on the plane and a mint normal (not
    /// necessarily unit).
    #[inline]
    #[must_use]
    pub fn from_mint(point_on: impl Into<Point3<S<V>>>, normal: impl Into<Vector3<S<V>>>) -> Self {
        Self::new(point(point_on), vector(normal))
    }
}
