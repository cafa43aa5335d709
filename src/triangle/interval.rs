//! The interval forms of the watertight tests: [`ray_triangle_in`],
//! [`ray_triangle_prepared_in`] and [`ray_triangle_one_hit_in`], which
//! decide `t_min < t* <= t_max` for the exact crossing `t*`.
//!
//! The inside test is the watertight test's (the same frame, the same
//! edge rules, bit for bit). What changes is the range test. The plain
//! tests decide `t > 0` by sufficient tests and drop a hit they cannot
//! place; here both ends are decided exactly, in two steps:
//!
//! 1. A filter: the reported `t` and its error bound `err` (the bound of
//!    [`ray_triangle_error_bounds`](crate::ray_triangle_error_bounds),
//!    `HitCondition::t_error`) place `t*` within `[t - err, t + err]`;
//!    where that range lies on one side of an end, the end is decided.
//! 2. Inside the band, the exact sign of `(a - o) . n - t_end (d . n)`
//!    against that of `d . n` (with `n = (b - a) x (c - a)`), computed with
//!    exact expansions (`PlaneCrossing`).
//!
//! The crossing `t*` is the line's exact crossing with the triangle's
//! plane, computed from the input floats. Where it does not exist (`d . n`
//! is exactly zero: a triangle of zero area, or a ray parallel to the
//! triangle's plane that rounding shows a sliver of it), the distance
//! compared is the `t` the test reports (for a zero-area triangle, where
//! the ray passes its longest edge), a float compared exactly. Either way
//! each (ray, triangle) pair has one distance, compared exactly against
//! both ends, so consecutive intervals `(t0, t1]`, `(t1, t2]` never report
//! a triangle twice and never skip one.

use super::bounds::{ErrorBounds, HitCondition, longest_edge_t};
use super::definition::{EdgeRule, hit_at, inside};
use super::frame::Frame;
use super::{Triangle, TriangleHit};
use crate::num::exact_sign::PlaneCrossing;
use crate::num::{S, Scalar, Vector};
use crate::ray::{Interval, PreparedRay, Ray, Shear, bring_into, decide};
use core::cmp::Ordering;

/// The watertight test with the exact interval decision, for a valid ray
/// (origin, direction, shear) and any interval.
#[inline(always)]
pub(super) fn watertight_in<V: Vector>(
    origin: V,
    dir: V,
    shear: &Shear<S<V>>,
    tri: &Triangle<V>,
    interval: Interval<S<V>>,
    rule: EdgeRule,
) -> Option<TriangleHit<S<V>>> {
    let zero = S::<V>::ZERO;
    let f = Frame::new(origin, tri, shear);
    if !inside(&f, rule) {
        return None;
    }
    let [e0, e1, e2] = f.e;
    let det = e0 + e1 + e2;
    // Zero (or NaN) in the sheared plane: no crossing, as in the plain test.
    if !(det != zero && det.is_finite()) {
        return None;
    }
    let z = f.scaled_z(shear);
    let t_scaled = e0 * z[0] + e1 * z[1] + e2 * z[2];
    let inv_det = S::<V>::ONE / det;
    let plain = t_scaled * inv_det;
    // The largest distance a hit can report: `t <= MAX` as in the plain
    // test (a crossing beyond it has no finite `t`).
    let (lo, hi) = interval.ends();
    let bounds = ErrorBounds::new(&f, &z, shear);
    let t = match HitCondition::new(&bounds, det) {
        // The exact determinant has the computed one's sign, so `d . n` is
        // not zero and `t*` exists, within `err` of `plain`.
        Some(c) => {
            let err = c.t_error(&bounds, &z, plain);
            if !decide(plain, err, lo, hi, || crossing(origin, dir, tri))? {
                return None;
            }
            plain
        }
        // A triangle of zero area: no plane; the distance is the longest
        // edge's point nearest the ray, as in the plain test.
        None if tri.is_degenerate() => {
            let (t, _) = longest_edge_t(&f, &z, &bounds)?;
            if !(lo < t && t <= hi) {
                return None;
            }
            return hit_at(t, [e1, e2], det, inv_det, shear);
        }
        // The determinant's sign is not known: ask the exact one.
        None => {
            let exact = crossing(origin, dir, tri);
            match exact.den_sign()? {
                // Parallel in exact arithmetic: the distance is `plain`.
                Ordering::Equal => {
                    if !(lo < plain && plain <= hi) {
                        return None;
                    }
                    return hit_at(plain, [e1, e2], det, inv_det, shear);
                }
                _ => {
                    if !decide(plain, S::<V>::INFINITY, lo, hi, || exact)? {
                        return None;
                    }
                    plain
                }
            }
        }
    };
    // `t*` is in `(lo, hi]`; the reported `t` is brought into it too (see
    // `bring_into`: within its error bound of `t*`, or one ulp of `lo`;
    // and, with `hi <= MAX`, finite, as on the other paths to `hit_at`).
    hit_at(bring_into(t, lo, hi), [e1, e2], det, inv_det, shear)
}

/// [`watertight_in`] for a plain ray (its shear computed here), or `None`
/// for an invalid ray.
#[inline(always)]
fn on_ray<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    interval: Interval<S<V>>,
    rule: EdgeRule,
) -> Option<TriangleHit<S<V>>> {
    if !ray.is_valid() {
        return None;
    }
    watertight_in(
        ray.origin,
        ray.dir,
        &Shear::new(&ray.dir),
        tri,
        interval,
        rule,
    )
}

/// The exact crossing's signs for the ray and the triangle.
#[cold]
#[inline(never)]
fn crossing<V: Vector>(origin: V, dir: V, tri: &Triangle<V>) -> PlaneCrossing {
    let w = |p: V| [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()];
    // `f64` inputs are scaled; `f32` ones are in range as they are.
    let wide = S::<V>::UNIT_ROUNDOFF.to_f64() < 1e-10;
    PlaneCrossing::new(w(origin), w(dir), w(tri.a), w(tri.b), w(tri.c), wide)
}

/// The watertight ray/triangle test over an interval: a hit where the ray
/// crosses the closed triangle at an exact distance `t*` with
/// `interval.min() < t* <= interval.max()` (units of `ray.dir`).
///
/// The inside test is [`ray_triangle`](crate::ray_triangle)'s, bit for bit
/// (closed, two-sided, watertight). The range is decided exactly, not up
/// to rounding: `t*` is the exact crossing of the ray's line with the
/// triangle's plane, computed from the input floats. The reported `t` is
/// the same quotient as `ray_triangle`'s, within
/// [`ray_triangle_error_bounds`](crate::ray_triangle_error_bounds) of
/// `t*`, and brought into the interval when rounding put it outside: to
/// `t_max`, which only moves it towards `t*`, or to the float just above
/// `t_min`, which is within the larger of that bound and one ulp of
/// `t_min` (`t*` may lie strictly between `t_min` and that float); `u`,
/// `v` and the side are as for `ray_triangle`.
///
/// So consecutive intervals `(t0, t1]`, `(t1, t2]`, ... report each hit
/// triangle in exactly one of them, whatever the ends: a loop that
/// continues past a hit never skips a crossing and never reports one
/// twice, and two triangles crossed at one exact point are both reported
/// in the same interval. To walk every hit in order, take the nearest hit
/// of `(t_lo, t_max]`, set `t_hi` to its `t` plus its error bound (rounded
/// up), report every hit of `(t_lo, t_hi]` sorted by `t`, and continue
/// from `t_lo = t_hi`.
///
/// Where the crossing is not defined (`dir . n` exactly zero: a triangle of
/// zero area, or a ray exactly parallel to the plane that rounding shows a
/// sliver of it), the reported `t` itself is the distance, compared
/// exactly; for a zero-area triangle it is where the ray passes the longest
/// edge, as in `ray_triangle`.
///
/// Relation to `ray_triangle(ray, tri, t_max)`: with `interval = (0,
/// t_max]`, both give the same hit, bit for bit, wherever `t*` is farther
/// than the error bound from `0` and `t_max`. Nearer to an end they can
/// differ: `ray_triangle` compares its rounded `t` with `t_max` and drops a
/// hit whose `t > 0` its sufficient tests cannot establish (right for a
/// ray spawned off a surface, wrong for a sequence); this decides both
/// ends exactly.
///
/// Cost: the inside test plus the error bound of `t` for each triangle
/// whose inside test passes; the exact signs (a few hundred operations)
/// only where `t*` is within that bound of an end. The `t_max`-only
/// kernels are unchanged.
///
/// Invalid rays and triangles with a NaN or infinite coordinate miss;
/// bad intervals cannot be built ([`Interval::new`]). The range decision
/// is exact for every `f32` input and any ends; for `f64`, for any ends,
/// while the nonzero coordinate differences between the origin and the
/// corners and between corners (and their rounding errors) are within a
/// factor `2^250` of the largest, and the direction's nonzero components
/// within `2^250` of its largest (so that no exact product underflows);
/// beyond that it is not guaranteed. The preconditions of `ray_triangle`
/// (no overflow of the edge functions) apply.
///
/// ```
/// use rayhit::{Interval, Ray, Triangle, ray_triangle_in, glam::Vec3};
/// // The plane z = 0, crossed at exactly t = 2.
/// let tri = Triangle::new(Vec3::new(-1.0, -1.0, 0.0), Vec3::new(3.0, -1.0, 0.0), Vec3::new(-1.0, 3.0, 0.0));
/// let ray = Ray::new(Vec3::new(0.0, 0.0, 4.0), Vec3::new(0.0, 0.0, -2.0));
/// let hit = |lo: f32, hi: f32| ray_triangle_in(&ray, &tri, Interval::new(lo, hi).unwrap());
/// assert_eq!(hit(0.0, 10.0).unwrap().t, 2.0);
/// assert!(hit(1.0, 2.0).is_some()); // closed above
/// assert!(hit(2.0, 3.0).is_none()); // open below: no repeat past t = 2
/// assert!(hit(2.0f32.next_down(), 3.0).is_some());
/// ```
#[inline]
#[must_use]
pub fn ray_triangle_in<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    interval: Interval<S<V>>,
) -> Option<TriangleHit<S<V>>> {
    on_ray(ray, tri, interval, EdgeRule::Closed)
}

/// [`ray_triangle_in`] on a [`PreparedRay`]: the same answer, bit for bit.
///
/// ```
/// use rayhit::{Interval, PreparedRay, Ray, Triangle, ray_triangle_in, ray_triangle_prepared_in, glam::Vec3};
/// let tri = Triangle::new(Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0));
/// let ray = Ray::new(Vec3::new(0.5, 0.25, 4.0), Vec3::new(0.0, 0.0, -2.0));
/// let window = Interval::new(1.0, 3.0).unwrap();
/// let hit = ray_triangle_prepared_in(&PreparedRay::new(&ray), &tri, window);
/// assert_eq!(hit, ray_triangle_in(&ray, &tri, window));
/// assert_eq!(hit.unwrap().t, 2.0);
/// ```
#[inline]
#[must_use]
pub fn ray_triangle_prepared_in<V: Vector>(
    ray: &PreparedRay<V>,
    tri: &Triangle<V>,
    interval: Interval<S<V>>,
) -> Option<TriangleHit<S<V>>> {
    if !ray.is_valid() {
        return None;
    }
    watertight_in(
        ray.origin(),
        ray.dir,
        &ray.shear(),
        tri,
        interval,
        EdgeRule::Closed,
    )
}

/// [`ray_triangle_one_hit`](crate::ray_triangle_one_hit) over an interval:
/// its inside test (each point of a shared edge or corner belongs to
/// exactly one triangle of a consistently wound mesh) with the exact range
/// decision of [`ray_triangle_in`].
///
/// Together: over a sequence of consecutive intervals `(t0, t1]`, `(t1,
/// t2]`, ..., each crossing of a closed, consistently wound mesh (locally a
/// surface seen from one side, shared edges with bit-identical corners) is
/// reported exactly once, so the number of hits over the sequence is the
/// number the single interval `(t0, t_last]` gives, whose parity tells
/// inside from outside.
///
/// ```
/// use rayhit::{Interval, Ray, Triangle, ray_triangle_one_hit_in, glam::Vec3};
/// // Two triangles of the unit square, sharing the diagonal from (1,0) to (0,1).
/// let (p00, p10, p01, p11) = (Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 0.0));
/// let mesh = [Triangle::new(p00, p10, p01), Triangle::new(p10, p11, p01)];
/// // Straight down through the middle of the shared diagonal, at t = 1.
/// let ray = Ray::new(Vec3::new(0.5, 0.5, 1.0), Vec3::new(0.0, 0.0, -1.0));
/// let count = |lo: f32, hi: f32| {
///     let window = Interval::new(lo, hi).unwrap();
///     mesh.iter().filter(|t| ray_triangle_one_hit_in(&ray, t, window).is_some()).count()
/// };
/// assert_eq!(count(0.0, 1.0) + count(1.0, 2.0), 1);
/// ```
#[inline]
#[must_use]
pub fn ray_triangle_one_hit_in<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    interval: Interval<S<V>>,
) -> Option<TriangleHit<S<V>>> {
    on_ray(ray, tri, interval, EdgeRule::OneHit)
}

/// Whether anything blocks the ray within `interval`: the any-hit form of
/// [`ray_triangle_in`] for shadow rays, `true` exactly when
/// `ray_triangle_in(ray, tri, interval)` is `Some`.
///
/// Same conventions and guarantees (closed, two-sided, watertight, both
/// ends of `(t_min, t_max]` decided exactly against the exact crossing).
/// Nothing of the hit is returned, so a shadow ray's loop can stop at the
/// first `true`.
///
/// ```
/// use rayhit::{Interval, Ray, Triangle, ray_triangle_occluded, glam::Vec3};
/// let occluder = Triangle::new(Vec3::new(-1.0, -1.0, 1.0), Vec3::new(3.0, -1.0, 1.0), Vec3::new(-1.0, 3.0, 1.0));
/// // From the floor towards a light at t = 1, through the occluder at t = 0.5.
/// let ray = Ray::new(Vec3::ZERO, Vec3::new(0.0, 0.0, 2.0));
/// assert!(ray_triangle_occluded(&ray, &occluder, Interval::new(0.0, 1.0).unwrap()));
/// // A light below the occluder is not blocked.
/// assert!(!ray_triangle_occluded(&ray, &occluder, Interval::new(0.0, 0.25).unwrap()));
/// ```
#[inline]
#[must_use]
pub fn ray_triangle_occluded<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    interval: Interval<S<V>>,
) -> bool {
    ray_triangle_in(ray, tri, interval).is_some()
}

/// [`ray_triangle_occluded`] on a [`PreparedRay`]: the same answer.
///
/// ```
/// use rayhit::{Interval, PreparedRay, Ray, Triangle, ray_triangle_prepared_occluded, glam::Vec3};
/// let occluder = Triangle::new(Vec3::new(-1.0, -1.0, 1.0), Vec3::new(3.0, -1.0, 1.0), Vec3::new(-1.0, 3.0, 1.0));
/// let ray = PreparedRay::new(&Ray::new(Vec3::ZERO, Vec3::new(0.0, 0.0, 2.0)));
/// // The occluder is crossed at exactly t = 0.5: open below, closed above.
/// assert!(ray_triangle_prepared_occluded(&ray, &occluder, Interval::new(0.25, 0.5).unwrap()));
/// assert!(!ray_triangle_prepared_occluded(&ray, &occluder, Interval::new(0.5, 1.0).unwrap()));
/// ```
#[inline]
#[must_use]
pub fn ray_triangle_prepared_occluded<V: Vector>(
    ray: &PreparedRay<V>,
    tri: &Triangle<V>,
    interval: Interval<S<V>>,
) -> bool {
    ray_triangle_prepared_in(ray, tri, interval).is_some()
}
