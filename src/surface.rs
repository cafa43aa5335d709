//! Leaving a surface: a hit point with its error bounds ([`SurfacePoint`])
//! and the offset origin of a ray that cannot hit that surface again
//! ([`offset_ray_origin`]).

use glam::Vec3;

use crate::num::{S, Scalar, Vector};
use crate::ray::Ray;

/// Moves a point computed on a surface to where a ray leaving it along `dir`
/// cannot meet that surface again: the origin for a shadow or bounce ray.
///
/// Inputs: the computed `point` and a per-component bound `point_error`
/// such that some point `q` of the exact surface has
/// `|point_i - q_i| <= point_error_i`; the surface's `normal` (any length)
/// and a per-component bound `normal_error` on its difference from the
/// exact plane's normal `N` (zero when the normal is exact, as for a
/// [`Plane`](crate::Plane)); and the new ray's `dir`. The functions
/// [`ray_plane_hit_point`](crate::ray_plane_hit_point),
/// [`triangle_hit_point`](crate::triangle_hit_point) and
/// [`Triangle::normal_with_error`](crate::Triangle::normal_with_error) give
/// these.
///
/// Returns `point + s * lambda * normal`, each component rounded away from
/// `point`, with `s` the sign of `dir . normal`. Guarantee: the returned
/// origin lies strictly on the side of the exact plane (through `q`, normal
/// `N`) that `dir` points into, so the new ray's exact crossing with that
/// plane is behind it (`t < 0`), and the watertight test, which decides
/// `t > 0` conservatively, does not report it.
///
/// Derivation: `|(point - q) . N| <= A = sum point_error_i (|n_i| + eta_i)`.
/// Moving by `lambda * n` changes `(x - q) . N` by `lambda n . N >=
/// lambda (|n|^2 - sum |n_i| eta_i)`; rounding each moved component away
/// from `point` adds, in the components whose sign agrees with `N_i`, only
/// more, and in the others (where `|n_i| <= eta_i`) takes back at most two
/// ulps of `|point_i| + lambda |n_i|`, below `4u` of it. So
/// `lambda = (A + 4u sum |point_i| eta_i) / (|n|^2 - (1 + 4u) sum |n_i| eta_i)`
/// suffices; it is evaluated with outward rounding, and pbrt-v4's
/// `OffsetRayOrigin` (the same idea with an exact normal) is the special case
/// `eta = 0`.
///
/// Preconditions: `dir` is not within rounding of parallel to the surface,
/// so that `s`, the sign of the *computed* `dir . normal`, is the side exact
/// arithmetic would pick: `|fl(dir . normal)|` must exceed the dot
/// product's own rounding bound `gamma(3) sum |dir_i normal_i|` plus the
/// normal's error `sum |dir_i| eta_i` (a few ulps of the angle for an exact
/// normal). And the normal must be known well enough that the denominator
/// above is positive; otherwise, and for non-finite input, the point is
/// returned unchanged. Never panics.
///
/// ```
/// use rayhit::{Plane, Ray, offset_ray_origin, ray_plane, ray_plane_hit_point, glam::Vec3};
/// let floor = Plane::new(Vec3::ZERO, Vec3::Y);
/// let ray = Ray::new(Vec3::new(0.1, 3.0, 0.2), Vec3::new(0.3, -1.0, 0.7));
/// let t = ray_plane(&ray, &floor, f32::INFINITY).unwrap();
/// let (p, err) = ray_plane_hit_point(&ray, &floor, t);
/// // Bounce up and away: the new origin is strictly above the floor.
/// let bounce = Vec3::new(0.3, 1.0, 0.7);
/// let origin = offset_ray_origin(p, err, floor.normal, Vec3::ZERO, bounce);
/// assert!(origin.y > 0.0);
/// assert_eq!(ray_plane(&Ray::new(origin, bounce), &floor, f32::INFINITY), None);
/// ```
#[must_use]
pub fn offset_ray_origin<V: Vector>(
    point: V,
    point_error: V,
    normal: V,
    normal_error: V,
    dir: V,
) -> V {
    use crate::num::round::outward::{add_down, add_up, div_up, mul_down, mul_up, sub_down};
    let all_finite = point.is_finite()
        && point_error.is_finite()
        && normal.is_finite()
        && normal_error.is_finite()
        && dir.is_finite();
    if !all_finite {
        return point;
    }
    let zero = S::<V>::ZERO;
    let (n, eta) = (normal.abs(), normal_error.abs());
    let four_u = S::<V>::from_u32(4) * S::<V>::UNIT_ROUNDOFF;
    let mut a = zero; // sum point_error_i (|n_i| + eta_i)
    let mut slack = zero; // 4u sum |point_i| eta_i
    let mut n2 = zero; // |n|^2, rounded down
    let mut cross = zero; // sum |n_i| eta_i, rounded up
    for i in 0..3 {
        a = add_up(a, mul_up(point_error[i].abs(), add_up(n[i], eta[i])));
        slack = add_up(slack, mul_up(four_u, mul_up(point[i].abs(), eta[i])));
        n2 = add_down(n2, mul_down(n[i], n[i]));
        cross = add_up(cross, mul_up(n[i], eta[i]));
    }
    let denom = sub_down(n2, mul_up(add_up(S::<V>::ONE, four_u), cross));
    if !(denom > zero) {
        return point;
    }
    let lambda = div_up(add_up(a, slack), denom);
    let side = if dir.dot(normal) < zero {
        -S::<V>::ONE
    } else {
        S::<V>::ONE
    };
    let step = lambda * side;
    let moved = |i: usize| {
        let off = step * normal[i];
        let p = point[i] + off;
        // Round away from the point so the move is at least `off`.
        if off > zero {
            p.next_up()
        } else if off < zero {
            p.next_down()
        } else {
            point[i]
        }
    };
    V::new(moved(0), moved(1), moved(2))
}

/// A point on a surface with the error bounds needed to leave it safely:
/// what [`offset_ray_origin`] takes, gathered so that the arguments cannot be
/// passed in the wrong order.
///
/// Build it from a hit with [`SurfacePoint::on_triangle`],
/// [`SurfacePoint::on_plane`] or [`SurfacePoint::on_box`], then
/// [`spawn`](SurfacePoint::spawn) shadow and bounce rays from it.
///
/// ```
/// use rayhit::{Ray, SurfacePoint, Triangle, ray_triangle, glam::Vec3};
/// let tri = Triangle::new(Vec3::new(-1.0, 0.0, -1.0), Vec3::new(0.0, 0.0, 1.0), Vec3::new(1.0, 0.0, -1.0));
/// let ray = Ray::new(Vec3::new(0.1, 2.0, 0.0), Vec3::new(0.0, -1.0, -0.1));
/// let hit = ray_triangle(&ray, &tri, f32::INFINITY).unwrap();
/// let surface = SurfacePoint::on_triangle(&tri, &hit);
/// // A shadow ray towards a light above: it cannot hit the triangle it left.
/// let shadow = surface.spawn(Vec3::new(0.3, 1.0, 0.2));
/// assert!(ray_triangle(&shadow, &tri, f32::INFINITY).is_none());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint<V = Vec3> {
    /// The computed point.
    pub point: V,
    /// Per component, a bound on its distance from a point of the exact
    /// surface.
    pub point_error: V,
    /// The surface's normal, any length.
    pub normal: V,
    /// Per component, a bound on the normal's difference from the exact
    /// surface's normal (zero when it is exact).
    pub normal_error: V,
}

impl<V: Vector> SurfacePoint<V> {
    /// The point of a triangle hit, from its barycentrics, with the
    /// triangle's normal: [`triangle_hit_point`](crate::triangle_hit_point)
    /// and [`Triangle::normal_with_error`](crate::Triangle::normal_with_error).
    #[must_use]
    pub fn on_triangle(tri: &crate::Triangle<V>, hit: &crate::TriangleHit<S<V>>) -> Self {
        let (point, point_error) = crate::triangle_hit_point(tri, hit);
        let (normal, normal_error) = tri.normal_with_error();
        Self {
            point,
            point_error,
            normal,
            normal_error,
        }
    }

    /// The point where `ray` meets `plane` at `t` (from
    /// [`ray_plane`](crate::ray_plane)), with the plane's exact normal:
    /// [`ray_plane_hit_point`](crate::ray_plane_hit_point).
    #[must_use]
    pub fn on_plane(ray: &Ray<V>, plane: &crate::Plane<V>, t: S<V>) -> Self {
        let (point, point_error) = crate::ray_plane_hit_point(ray, plane, t);
        Self {
            point,
            point_error,
            normal: plane.normal,
            normal_error: V::ZERO,
        }
    }

    /// The point where `ray` enters a box through the face of `hit` (from
    /// [`ray_aabb_face`](crate::ray_aabb_face) or
    /// [`ray_aabb_prepared_face`](crate::ray_aabb_prepared_face)), with the
    /// face's exact outward normal; `None` when the hit has no entry face
    /// (the ray starts inside the box).
    ///
    /// The point is `ray.at(hit.enter)` with its coordinate on the face's
    /// axis replaced by the face's plane, so it lies exactly on that plane
    /// (its other coordinates carry the rounding of `origin + enter dir`,
    /// and near an edge can be a rounding outside the face). The bounds are
    /// those of an exact point on an exact plane, so
    /// [`spawn`](SurfacePoint::spawn) moves a new ray's origin one ulp off
    /// the plane, to the side its direction points into.
    ///
    /// ```
    /// use rayhit::{Aabb, Ray, SurfacePoint, ray_aabb, ray_aabb_face, glam::Vec3};
    /// let unit = Aabb::new(Vec3::ZERO, Vec3::ONE);
    /// let ray = Ray::new(Vec3::new(0.3, 3.0, 0.6), Vec3::new(0.1, -1.0, 0.2));
    /// let hit = ray_aabb_face(&ray, &unit, f32::INFINITY).unwrap();
    /// let surface = SurfacePoint::on_box(&ray, &unit, &hit).unwrap();
    /// assert_eq!((surface.point.y, surface.normal), (1.0, Vec3::Y));
    /// // A bounce off the top face does not touch the box again.
    /// let bounce = surface.spawn(Vec3::new(0.1, 1.0, 0.2));
    /// assert!(bounce.origin.y > 1.0);
    /// assert_eq!(ray_aabb(&bounce, &unit, f32::INFINITY), None);
    /// ```
    #[must_use]
    pub fn on_box(ray: &Ray<V>, aabb: &crate::Aabb<V>, hit: &crate::BoxHit<S<V>>) -> Option<Self> {
        let face = hit.face?;
        let k = face.axis();
        let p = ray.at(hit.enter);
        let on = |i: usize| if i == k { face.plane(aabb) } else { p[i] };
        // The point is exactly on the plane: an error of the smallest
        // subnormal on the axis (a bound, and not zero, so that the offset
        // is not zero either) and none elsewhere, which the exact normal
        // ignores.
        let error = |i: usize| if i == k { S::<V>::TINY } else { S::<V>::ZERO };
        Some(Self {
            point: V::new(on(0), on(1), on(2)),
            point_error: V::new(error(0), error(1), error(2)),
            normal: face.normal(),
            normal_error: V::ZERO,
        })
    }

    /// A ray leaving the surface along `dir`, from an origin offset by
    /// [`offset_ray_origin`] to the side `dir` points into: it does not meet
    /// the surface again (for `dir` not within rounding of tangent).
    ///
    /// Where the normal is not known well enough to pick a side (a zero or
    /// nearly zero normal, as on a zero-area triangle), the ray starts at
    /// `point` itself, unmoved: finite, but it may meet the surfaces through
    /// that point again at a tiny `t`.
    #[inline]
    #[must_use]
    pub fn spawn(&self, dir: V) -> Ray<V> {
        let origin = offset_ray_origin(
            self.point,
            self.point_error,
            self.normal,
            self.normal_error,
            dir,
        );
        Ray::new(origin, dir)
    }
}
