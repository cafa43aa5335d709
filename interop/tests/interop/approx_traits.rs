//! The `approx` impls compare what their docs say they compare.

use approx::{AbsDiffEq, RelativeEq, UlpsEq, assert_relative_eq, assert_relative_ne};
use rayhit::glam::{DVec3, Vec3};
use rayhit::{Aabb, DRay, DTriangleHit, Plane, Ray, Side, Triangle, TriangleHit};

#[test]
fn hits_compare_t_u_v_and_side() {
    let a = TriangleHit {
        t: 10.0f32,
        u: 0.25,
        v: 0.5,
        side: Side::Front,
    };
    // One ulp of t away: equal within 1 ulp or a relative 1e-6, not exactly.
    let b = TriangleHit {
        t: 10.0f32.next_up(),
        ..a
    };
    assert!(a.ulps_eq(&b, 0.0, 1) && !a.ulps_eq(&b, 0.0, 0));
    assert_relative_eq!(a, b, max_relative = 1e-6);
    assert_relative_ne!(a, b, max_relative = 1e-8);
    // u or v off: not equal at a tolerance that admits the t difference.
    let c = TriangleHit { u: 0.2501, ..a };
    assert!(!a.relative_eq(&c, 0.0, 1e-6));
    // The side must match exactly, whatever the tolerance.
    let d = TriangleHit {
        side: Side::Back,
        ..a
    };
    assert!(!a.abs_diff_eq(&d, 1e9));
    // f64.
    let e = DTriangleHit {
        t: 1.0,
        u: 0.0,
        v: 1.0,
        side: Side::Back,
    };
    let f = DTriangleHit {
        t: 1.0 + 1e-12,
        ..e
    };
    assert!(e.abs_diff_eq(&f, 1e-11) && !e.abs_diff_eq(&f, 1e-13));
}

#[test]
fn shapes_compare_every_field() {
    let r = Ray::new(Vec3::new(1.0, 2.0, 3.0), Vec3::X);
    assert!(r.abs_diff_eq(&Ray::new(Vec3::new(1.0, 2.0, 3.0 + 1e-4), Vec3::X), 2e-4));
    assert!(!r.abs_diff_eq(&Ray::new(r.origin, Vec3::new(1.0, 1e-3, 0.0)), 2e-4));
    let b = Aabb::new(Vec3::ZERO, Vec3::ONE);
    assert!(!b.relative_eq(&Aabb::new(Vec3::ZERO, Vec3::new(1.0, 1.0, 1.01)), 0.0, 1e-3));
    assert!(b.relative_eq(
        &Aabb::new(Vec3::ZERO, Vec3::new(1.0, 1.0, 1.0001)),
        0.0,
        1e-3
    ));
    // Representations, not geometry: the same plane with a scaled normal differs.
    let p = Plane::new(Vec3::ZERO, Vec3::Z);
    assert!(!p.abs_diff_eq(&Plane::new(Vec3::ZERO, Vec3::Z * 2.0), 1e-3));
    let t = Triangle::new(DVec3::ZERO, DVec3::X, DVec3::Y);
    assert!(t.ulps_eq(
        &Triangle::new(
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(0.0, 1.0f64.next_up(), 0.0)
        ),
        0.0,
        1
    ));
    assert!(!t.ulps_eq(&t.flipped(), 0.0, 4));
    let dr = DRay::new(DVec3::ZERO, DVec3::Y);
    assert_relative_eq!(
        dr,
        DRay::new(DVec3::new(0.0, 0.0, 1e-20), DVec3::Y),
        epsilon = 1e-15
    );
}
