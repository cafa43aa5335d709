//! `spawn_to`: [`SurfacePoint::spawn_to`] and
//! [`SurfacePoint::spawn_to_point`], the shadow-ray segment between two
//! surface points (or to a point light).
//!
//! Input: raw mode, two `(Triangle, Ray)` pairs as raw bits (each end the
//! ray's hit on its triangle, when it hits) and a raw point light, then a
//! `(Plane, Ray)` pair for a plane end; structured mode, the start on
//! [`cases::triangles::with_fillers`] (aimed at faces, edges and
//! corners, zero-area fillers included), the target on another such
//! triangle, on the same triangle (a second ray aimed at it), or on a
//! plane ([`cases::planes::plane`]), and the light at the target's point.
//!
//! Checks: no panic; a segment is a valid ray, finite, with the interval
//! `(0, 1]`; and where the ends' bounds are relative-error arguments (raw
//! inputs with every coordinate, edge and bound zero or between `2^-40`
//! and `2^40`, `2^-100` and `2^100` for `f64`, and the barycentric
//! products far from underflow; every structured input): neither end's
//! surface is reported over the interval by the interval kernels
//! (`Triangle::hit` with both edge rules, `Plane::hit`), and the start
//! surface by the plain kernels for any `t_max` either.

use arbitrary::Arbitrary;
use rayhit::{
    EdgeRule, Intersect, Interval, Plane, Ray, Scalar, Surface, SurfacePoint, Triangle, Vector,
    ray_plane, ray_triangle,
};

use super::spawn::{triangle_no_underflow, within_binades};
use super::{Check, Input, S, raw, raw_vec};
use crate::cases;

/// The `spawn_to` target.
#[derive(Debug)]
pub struct SpawnTo;

/// A surface an end lies on.
#[derive(Clone, Copy, Debug)]
enum End<V: Vector> {
    Tri(Triangle<V>),
    Plane(Plane<V>),
}

impl Check for SpawnTo {
    fn run<'a, V>(input: &mut Input<'a>)
    where
        V: Vector,
        S<V>: Arbitrary<'a> + Scalar,
    {
        match input {
            Input::Raw(u) => {
                let on_triangle = |u: &mut arbitrary::Unstructured<'a>| {
                    let (tri, ray) = (raw::<Triangle<V>>(u), raw::<Ray<V>>(u));
                    ray_triangle(&ray, &tri, S::<V>::INFINITY).map(|hit| {
                        let point = tri.surface_point(&ray, &hit);
                        let (e1, e2) = (tri.b - tri.a, tri.c - tri.a);
                        let bounded = triangle_no_underflow(&tri, hit.u, hit.v)
                            && in_range(&[
                                tri.a,
                                tri.b,
                                tri.c,
                                e1,
                                e2,
                                point.point,
                                point.point_error,
                                point.normal,
                                point.normal_error,
                                ray.origin,
                                ray.dir,
                            ]);
                        (End::Tri(tri), point, bounded)
                    })
                };
                let start = on_triangle(u);
                let target = on_triangle(u);
                let light = raw_vec::<V>(u);
                let (plane, ray) = (raw::<Plane<V>>(u), raw::<Ray<V>>(u));
                let on_plane = ray_plane(&ray, &plane, S::<V>::INFINITY).map(|t| {
                    let point = plane.surface_point(&ray, &t);
                    let bounded = super::plane::no_underflow(&ray, &plane)
                        && in_range(&[plane.point, plane.normal, point.point, point.point_error]);
                    (End::Plane(plane), point, bounded)
                });
                if let Some(s) = &start {
                    light_segment(s, light, s.2 && in_range(&[light]));
                    for t in [&target, &on_plane].into_iter().flatten() {
                        segment(s, t);
                        segment(t, s);
                    }
                }
            }
            Input::Structured(src) => {
                let inf = S::<V>::INFINITY;
                let (tri, ray, _) = cases::triangles::with_fillers::<V>(src);
                let Some(hit) = ray_triangle(&ray, &tri, inf) else {
                    return;
                };
                let start = (End::Tri(tri), tri.surface_point(&ray, &hit), true);
                let target = match src.index(3) {
                    0 => {
                        let (other, ray, _) = cases::triangles::with_fillers::<V>(src);
                        ray_triangle(&ray, &other, inf)
                            .map(|h| (End::Tri(other), other.surface_point(&ray, &h)))
                    }
                    1 => {
                        let ray = cases::triangles::ray_at(src, &tri);
                        ray_triangle(&ray, &tri, inf)
                            .map(|h| (End::Tri(tri), tri.surface_point(&ray, &h)))
                    }
                    _ => {
                        let (plane, ray, _) = cases::planes::plane::<V>(src);
                        ray_plane(&ray, &plane, inf)
                            .map(|t| (End::Plane(plane), plane.surface_point(&ray, &t)))
                    }
                };
                let Some((surface, point)) = target else {
                    return;
                };
                let target = (surface, point, true);
                light_segment(&start, point.point, true);
                segment(&start, &target);
                segment(&target, &start);
            }
        }
    }
}

/// Every coordinate of `vs` zero or between `2^-40` and `2^40` (`2^-100`
/// and `2^100` for `f64`): the ends' bounds and the interval kernels'
/// exact decisions are relative-error arguments, with ranges of their own.
fn in_range<V: Vector>(vs: &[V]) -> bool {
    within_binades(vs, 40, 100)
}

/// The segment from `start` to `target`, checked (see the module docs).
fn segment<V: Vector>(
    (start, p, p_bounded): &(End<V>, SurfacePoint<V>, bool),
    (target, q, q_bounded): &(End<V>, SurfacePoint<V>, bool),
) {
    let bounded = *p_bounded && *q_bounded;
    if let Some((ray, interval)) = p.spawn_to(q) {
        check_ray(&ray, interval);
        if bounded {
            not_start(&ray, start, interval);
            assert!(
                !reported(&ray, target, interval),
                "spawn_to: the segment hits its target's surface: {p:?} {q:?} {start:?} {target:?} {ray:?}"
            );
        }
    }
}

/// The segment from `start` to a point light, checked.
fn light_segment<V: Vector>(
    (start, p, _): &(End<V>, SurfacePoint<V>, bool),
    light: V,
    bounded: bool,
) {
    if let Some((ray, interval)) = p.spawn_to_point(light) {
        check_ray(&ray, interval);
        if bounded {
            not_start(&ray, start, interval);
        }
    }
}

/// A valid, finite ray with the interval `(0, 1]`.
fn check_ray<V: Vector>(ray: &Ray<V>, interval: Interval<S<V>>) {
    assert_eq!(interval, Interval::up_to(S::<V>::ONE).expect("(0, 1]"));
    assert!(
        ray.is_valid() && ray.origin.is_finite() && ray.dir.is_finite(),
        "spawn_to: not a valid ray: {ray:?}"
    );
}

/// The start surface is reported neither over the interval nor, by the
/// plain kernels, for any `t_max`.
fn not_start<V: Vector>(ray: &Ray<V>, start: &End<V>, interval: Interval<S<V>>) {
    let inf = S::<V>::INFINITY;
    let plain = match start {
        End::Tri(t) => {
            ray_triangle(ray, t, inf).is_some() || t.hit(ray, (inf, EdgeRule::OneHit)).is_some()
        }
        End::Plane(p) => ray_plane(ray, p, inf).is_some(),
    };
    assert!(
        !(plain || reported(ray, start, interval)),
        "spawn_to: the segment hits its start's surface: {start:?} {ray:?}"
    );
}

/// Whether an interval kernel reports `surface`.
fn reported<V: Vector>(ray: &Ray<V>, surface: &End<V>, interval: Interval<S<V>>) -> bool {
    match surface {
        End::Tri(t) => {
            t.hit(ray, interval).is_some() || t.hit(ray, (interval, EdgeRule::OneHit)).is_some()
        }
        End::Plane(p) => p.hit(ray, interval).is_some(),
    }
}
