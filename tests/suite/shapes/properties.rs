//! Metamorphic properties of every shape kernel at once (box, plane and
//! the triangle tests), in both precisions: scaling the direction or every
//! position by a power of two, mirroring an axis and translating on a grid
//! change every answer exactly as predicted (or not at all), bit for bit.

use crate::common::props::{config, in_both_precisions};
use proptest::prelude::*;
use rayhit::glam::{DVec3, Vec3};
use rayhit::strategies as strat;
use rayhit::{
    Aabb, Intersect, Plane, Ray, Scalar, Side, Triangle, Vector, ray_aabb, ray_plane, ray_triangle,
};

type S<V> = <V as Vector>::Scalar;

/// Every kernel gives on the transformed inputs exactly the answers it gave
/// on the originals, with every `t` mapped by `map` (the metamorphic
/// identities below that change `t`).
#[allow(clippy::too_many_arguments)]
fn check_all_kernels_map<V: Vector>(
    (ray, aabb, tri, plane): (Ray<V>, Aabb<V>, Triangle<V>, Plane<V>),
    (ray2, aabb2, tri2, plane2): (Ray<V>, Aabb<V>, Triangle<V>, Plane<V>),
    map: impl Fn(S<V>) -> S<V>,
) -> Result<(), TestCaseError> {
    let inf = S::<V>::INFINITY;
    prop_assert_eq!(
        ray_aabb(&ray2, &aabb2, inf),
        ray_aabb(&ray, &aabb, inf).map(|(e, x)| (map(e), map(x)))
    );
    prop_assert_eq!(
        aabb2.clip_by_faces(&ray2, inf),
        aabb.clip_by_faces(&ray, inf).map(|(e, x)| (map(e), map(x)))
    );
    prop_assert_eq!(
        ray_plane(&ray2, &plane2, inf),
        ray_plane(&ray, &plane, inf).map(&map)
    );
    for kernel in [ray_triangle::<V>, moller_trumbore::<V>, one_hit::<V>] {
        let a = kernel(&ray2, &tri2, inf);
        let b = kernel(&ray, &tri, inf).map(|h| rayhit::TriangleHit { t: map(h.t), ..h });
        prop_assert_eq!(a, b);
    }
    Ok(())
}

/// Scaling `dir` by `2^k` scales every `t` by `2^-k` exactly and changes
/// nothing else: every kernel uses `dir` only through quantities that scale
/// exactly (within the ranges the strategies draw, nothing under- or
/// overflows).
fn check_direction_scaling<V: Vector>(
    aabb: Aabb<V>,
    tri: Triangle<V>,
    plane: Plane<V>,
    ray: Ray<V>,
    k: i32,
) -> Result<(), TestCaseError> {
    let s = S::<V>::from_f64(2f64.powi(k));
    let scaled = Ray::new(ray.origin, ray.dir * s);
    check_all_kernels_map((ray, aabb, tri, plane), (scaled, aabb, tri, plane), |t| {
        t / s
    })
}

/// Mirroring an axis (negating one coordinate of every input) gives the same
/// answers bit for bit: negation is exact and every rounding is symmetric.
/// The box's min and max swap on that axis; a triangle's side flips (the
/// mirror reverses orientation). The one-hit variant is left out: its
/// tie-break is deliberately not mirror-symmetric.
fn check_mirror<V: Vector>(
    aabb: Aabb<V>,
    tri: Triangle<V>,
    plane: Plane<V>,
    ray: Ray<V>,
    axis: usize,
) -> Result<(), TestCaseError> {
    let m = |v: V| {
        let mut c = [v.x(), v.y(), v.z()];
        c[axis] = -c[axis];
        V::new(c[0], c[1], c[2])
    };
    let mray = Ray::new(m(ray.origin), m(ray.dir));
    let (mut lo, mut hi) = (m(aabb.min), m(aabb.max));
    let (mut l, mut h) = ([lo.x(), lo.y(), lo.z()], [hi.x(), hi.y(), hi.z()]);
    core::mem::swap(&mut l[axis], &mut h[axis]);
    (lo, hi) = (V::new(l[0], l[1], l[2]), V::new(h[0], h[1], h[2]));
    let inf = S::<V>::INFINITY;
    prop_assert_eq!(
        ray_aabb(&mray, &Aabb::new(lo, hi), inf),
        ray_aabb(&ray, &aabb, inf)
    );
    prop_assert_eq!(
        Aabb::new(lo, hi).clip_by_faces(&mray, inf),
        aabb.clip_by_faces(&ray, inf)
    );
    prop_assert_eq!(
        ray_plane(&mray, &Plane::new(m(plane.point), m(plane.normal)), inf),
        ray_plane(&ray, &plane, inf)
    );
    let mtri = Triangle::new(m(tri.a), m(tri.b), m(tri.c));
    for kernel in [ray_triangle::<V>, moller_trumbore::<V>] {
        let flip = |h: rayhit::TriangleHit<S<V>>| rayhit::TriangleHit {
            side: if h.side == Side::Front {
                Side::Back
            } else {
                Side::Front
            },
            ..h
        };
        prop_assert_eq!(kernel(&mray, &mtri, inf), kernel(&ray, &tri, inf).map(flip));
    }
    Ok(())
}

/// Translating ray and shapes by the same vector: exact when every
/// coordinate lies on a grid coarse enough that the sums are exact, so the
/// answers must not change at all. Inputs are snapped to multiples of
/// `2^-8` within `[-2^8, 2^8]` and translated by multiples of `2^-4` within
/// `[-2^10, 2^10]`: every sum needs at most 8 + 11 = 19 bits, which `f32`
/// holds exactly.
fn check_translation<V: Vector>(
    aabb: Aabb<V>,
    tri: Triangle<V>,
    ray: Ray<V>,
    shift: [i32; 3],
) -> Result<(), TestCaseError> {
    let snap = |v: V| {
        let g = |x: S<V>| S::<V>::from_f64((x.to_f64() * 256.0).round() / 256.0);
        V::new(g(v.x()), g(v.y()), g(v.z()))
    };
    let t = V::new(
        S::<V>::from_f64(f64::from(shift[0]) / 16.0),
        S::<V>::from_f64(f64::from(shift[1]) / 16.0),
        S::<V>::from_f64(f64::from(shift[2]) / 16.0),
    );
    let ray = Ray::new(snap(ray.origin), snap(ray.dir));
    if !ray.is_valid() {
        return Ok(());
    }
    let moved = Ray::new(ray.origin + t, ray.dir);
    let (lo, hi) = (snap(aabb.min), snap(aabb.max));
    let tri = Triangle::new(snap(tri.a), snap(tri.b), snap(tri.c));
    let inf = S::<V>::INFINITY;
    prop_assert_eq!(
        ray_aabb(&moved, &Aabb::new(lo + t, hi + t), inf),
        ray_aabb(&ray, &Aabb::new(lo, hi), inf)
    );
    let mtri = Triangle::new(tri.a + t, tri.b + t, tri.c + t);
    for kernel in [ray_triangle::<V>, moller_trumbore::<V>, one_hit::<V>] {
        prop_assert_eq!(kernel(&moved, &mtri, inf), kernel(&ray, &tri, inf));
    }
    Ok(())
}

/// Scaling every position (origins, corners, box, plane point) by `2^k`
/// and keeping directions scales every `t` by `2^k` exactly, with the same
/// hit or miss and the same barycentrics: every intermediate quantity scales
/// by a power of two, and every bound with it (within the strategies'
/// ranges nothing under- or overflows).
fn check_position_scaling<V: Vector>(
    aabb: Aabb<V>,
    tri: Triangle<V>,
    plane: Plane<V>,
    ray: Ray<V>,
    k: i32,
) -> Result<(), TestCaseError> {
    let s = S::<V>::from_f64(2f64.powi(k));
    let scaled = (
        Ray::new(ray.origin * s, ray.dir),
        Aabb::new(aabb.min * s, aabb.max * s),
        Triangle::new(tri.a * s, tri.b * s, tri.c * s),
        Plane::new(plane.point * s, plane.normal),
    );
    check_all_kernels_map((ray, aabb, tri, plane), scaled, |t| t * s)
}

in_both_precisions! {
    fn direction_scaling(aabb in strat::aabb::<V>(), (tri, ray) in strat::triangle_and_ray::<V>(), plane in strat::plane::<V>(), k in -8i32..=8) {
        check_direction_scaling(aabb, tri, plane, ray, k)?;
    }

    fn mirror((aabb, ray) in strat::aabb_and_ray::<V>(), tri in strat::triangle::<V>(), plane in strat::plane::<V>(), axis in 0..3usize) {
        check_mirror(aabb, tri, plane, ray, axis)?;
    }

    fn position_scaling((tri, ray) in strat::triangle_and_ray::<V>(), aabb in strat::aabb::<V>(), plane in strat::plane::<V>(), k in -8i32..=8) {
        check_position_scaling(aabb, tri, plane, ray, k)?;
    }

    fn translation((tri, ray) in strat::triangle_and_ray::<V>(), aabb in strat::aabb::<V>(), shift in prop::array::uniform3(-16384i32..=16384)) {
        check_translation(aabb, tri, ray, shift)?;
    }

    fn mirror_triangle((tri, ray) in strat::triangle_and_ray::<V>(), aabb in strat::aabb::<V>(), plane in strat::plane::<V>(), axis in 0..3usize) {
        check_mirror(aabb, tri, plane, ray, axis)?;
    }
}

/// Moller-Trumbore as a kernel of the same shape as `ray_triangle`.
fn moller_trumbore<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    t_max: S<V>,
) -> Option<rayhit::TriangleHit<S<V>>> {
    tri.moller_trumbore(ray, t_max)
}

/// The one-hit rule as a kernel of the same shape as `ray_triangle`.
fn one_hit<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    t_max: S<V>,
) -> Option<rayhit::TriangleHit<S<V>>> {
    tri.hit(ray, (t_max, rayhit::EdgeRule::OneHit))
}
