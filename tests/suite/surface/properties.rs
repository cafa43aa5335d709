//! Rays spawned from surface points (`SurfacePoint::spawn`) never meet the
//! surface they left, in both precisions, on rays aimed at chosen points
//! (see `rayhit::strategies`): from a triangle's hit, a plane's, and a box
//! face's (whose point lies on the face's plane exactly). Bounds are
//! evaluated exactly (see `common::props`).

use crate::common::props::{config, in_both_precisions};
use num_traits::Zero;
use proptest::prelude::*;
use rayhit::glam::{DVec3, Vec3};
use rayhit::strategies as strat;
use rayhit::{
    Aabb, EdgeRule, Intersect, Plane, Ray, Scalar, Surface, SurfacePoint, Triangle, Vector,
    ray_aabb, ray_plane, ray_triangle,
};
use rayhit_testkit::oracle;
use rayhit_testkit::oracle::{R, rv};

type S<V> = <V as Vector>::Scalar;

/// A ray spawned from a hit with `SurfacePoint::spawn` never meets the
/// surface it left: the watertight tests (both variants) report nothing, and
/// exact arithmetic puts the spawned ray's crossing with the surface's plane
/// behind it. The spawn direction is any direction at least 2^-10 radians
/// from tangent (the documented precondition is "not within rounding of
/// tangent"; cases where the normal's own error bound makes the side
/// uncertain are left out, as the precondition says).
fn check_spawn<V: Vector>(tri: Triangle<V>, ray: Ray<V>, w: V) -> Result<(), TestCaseError> {
    let inf = S::<V>::INFINITY;
    let Some(hit) = ray_triangle(&ray, &tri, inf) else {
        return Ok(());
    };
    let (p, perr) = {
        let s = tri.surface_point(&ray, &hit);
        (s.point, s.point_error)
    };
    let (n, nerr) = (tri.normal(), tri.normal_error());
    let (wn, wl, nl) = (w.dot(n).to_f64(), w.length().to_f64(), n.length().to_f64());
    let side_known = w.dot(n).abs() > w.abs().dot(nerr) * S::<V>::TWO;
    if !(wn.abs() > wl * nl / 1024.0 && side_known) {
        return Ok(());
    }
    let spawned = tri.surface_point(&ray, &hit).spawn(w);
    prop_assert_eq!(
        spawned.origin,
        SurfacePoint {
            point: p,
            point_error: perr,
            normal: n,
            normal_error: nerr
        }
        .spawn(w)
        .origin
    );
    prop_assert!(
        ray_triangle(&spawned, &tri, inf).is_none(),
        "spawned ray re-hit its triangle: {spawned:?}"
    );
    prop_assert!(
        tri.hit(&spawned, (inf, EdgeRule::OneHit)).is_none(),
        "one-hit variant re-hit"
    );
    // Exactly: the crossing with the triangle's plane is behind the origin.
    let (a, b, c) = (rv(tri.a), rv(tri.b), rv(tri.c));
    let nn = oracle::cross(&oracle::sub(&b, &a), &oracle::sub(&c, &a));
    let (o, d) = (rv(spawned.origin), rv(spawned.dir));
    let num = oracle::dot(&oracle::sub(&a, &o), &nn);
    let den = oracle::dot(&d, &nn);
    prop_assert!(
        den.is_zero() || (num / den) < R::from_integer(0.into()),
        "exact crossing in front of the spawned origin"
    );
    Ok(())
}

/// The same for a plane, whose normal is exact.
fn check_spawn_plane<V: Vector>(plane: Plane<V>, ray: Ray<V>, w: V) -> Result<(), TestCaseError> {
    let inf = S::<V>::INFINITY;
    let Some(t) = ray_plane(&ray, &plane, inf) else {
        return Ok(());
    };
    let (p, perr) = {
        let s = plane.surface_point(&ray, &t);
        (s.point, s.point_error)
    };
    let n = plane.normal;
    if !(w.dot(n).to_f64().abs() > w.length().to_f64() * n.length().to_f64() / 1024.0) {
        return Ok(());
    }
    let spawned = plane.surface_point(&ray, &t).spawn(w);
    prop_assert_eq!(
        spawned.origin,
        SurfacePoint {
            point: p,
            point_error: perr,
            normal: n,
            normal_error: V::ZERO
        }
        .spawn(w)
        .origin
    );
    prop_assert!(
        ray_plane(&spawned, &plane, inf).is_none(),
        "spawned ray re-hit its plane"
    );
    let t = oracle::plane_t(&spawned, &plane).expect("not parallel");
    prop_assert!(
        t < R::from_integer(0.into()),
        "exact crossing in front of the spawned origin"
    );
    Ok(())
}

in_both_precisions! {
    fn spawn((tri, ray) in strat::triangle_and_ray::<V>(), w in strat::direction::<V>()) {
        check_spawn(tri, ray, w)?;
    }

    fn spawn_plane((plane, ray) in strat::plane_and_ray::<V>(), w in strat::direction::<V>()) {
        check_spawn_plane(plane, ray, w)?;
    }
}

/// The point on a box face is on the face's plane exactly, and a ray
/// spawned from it away from the box (not within rounding of tangent)
/// does not touch the box again.
fn spawn_leaves_the_box<V: Vector>(
    aabb: Aabb<V>,
    ray: Ray<V>,
    bounce: V,
) -> Result<(), TestCaseError> {
    let Some(hit) = aabb.hit(&ray, S::<V>::INFINITY) else {
        return Ok(());
    };
    let Some(surface) = aabb.surface_point(&ray, &hit) else {
        prop_assert!(hit.face.is_none());
        return Ok(());
    };
    let face = hit.face.expect("a surface point has a face");
    prop_assert_eq!(surface.point[face.axis()], face.plane(&aabb));
    prop_assert!(surface.point.is_finite() && surface.point_error.is_finite());
    // Outward, clearly away from tangent.
    let n: V = face.normal();
    let along = bounce.dot(n);
    let dir = if along < S::<V>::ZERO {
        bounce - n * (along * S::<V>::TWO)
    } else {
        bounce
    };
    prop_assume!(dir.dot(n) > S::<V>::from_f64(1e-3) * dir.length());
    let spawned = surface.spawn(dir);
    prop_assert!(spawned.origin.is_finite());
    prop_assert_eq!(
        ray_aabb(&spawned, &aabb, S::<V>::INFINITY),
        None,
        "{:?}",
        spawned
    );
    Ok(())
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn spawn_leaves_the_box_f32((aabb, ray) in strat::aabb_and_ray::<Vec3>(), bounce in strat::direction::<Vec3>()) {
        spawn_leaves_the_box(aabb, ray, bounce)?;
    }

    #[test]
    fn spawn_leaves_the_box_f64((aabb, ray) in strat::aabb_and_ray::<DVec3>(), bounce in strat::direction::<DVec3>()) {
        spawn_leaves_the_box(aabb, ray, bounce)?;
    }
}
