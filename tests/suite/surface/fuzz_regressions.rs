//! Inputs the fuzzers (`fuzz/`) found in spawning rays from surface points,
//! kept as literal floats. Each test says which target found its input and
//! what went wrong: a fault of the fuzzer's check, of the kernel, or of the
//! docs (see the suite's documentation, `tests/suite/main.rs`).

use rayhit::glam::Vec3;
use rayhit::{Plane, Ray, Surface, SurfacePoint, ray_plane};
use rayhit_testkit::oracle;
use rayhit_testkit::oracle::{R, r};

/// `spawn` (structured): a bounce direction nearly in the plane. Exactly,
/// `dir . normal = +7.4e-11` (the documented precondition holds: the plane's
/// normal is exact, so its right-hand side is zero), but the rounded dot
/// product is `-3.4e-10`, so `SurfacePoint::spawn` moves the point to the
/// wrong side of the plane: the new origin is behind the plane seen along
/// `dir`. No offset can pick the side when the computed dot product cannot
/// tell it; the precondition now says so (the dot product's own rounding
/// bound, `gamma(3) sum |dir_i normal_i|`, is part of it), and this input is
/// outside it.
#[test]
fn spawn_from_plane_nearly_parallel_goes_to_the_wrong_side() {
    let plane = Plane::new(
        Vec3::new(-63.988_28, 64.0, -63.998_047),
        Vec3::new(-0.015_624_523, -0.015_624_283, 0.003_002_451),
    );
    let point = Vec3::new(-73.8551, 71.525_24, -76.1841);
    let point_error = Vec3::new(5.660_092_6e-5, 4.233_192e-5, 5.687_856_5e-5);
    let dir = Vec3::new(-0.707_102_2, 0.707_111_3, -9.107_16e-6);
    let n = oracle::rv(plane.normal);
    let heading = oracle::dot(&oracle::rv(dir), &n);
    assert!(
        heading > R::from_integer(0.into()),
        "dir points to the + side"
    );
    let computed = dir.dot(plane.normal);
    assert!(computed < 0.0, "the rounded dot product has the wrong sign");
    let magnitude: R = (0..3)
        .map(|i| {
            oracle::abs_diff(
                &(r(dir[i]) * r(plane.normal[i])),
                &R::from_integer(0.into()),
            )
        })
        .sum();
    assert!(
        r(computed.abs()) <= oracle::gamma::<f32>(3) * magnitude,
        "outside the documented precondition"
    );
    let origin = SurfacePoint {
        point,
        point_error,
        normal: plane.normal,
        normal_error: Vec3::ZERO,
    }
    .spawn(dir)
    .origin;
    assert!(origin.is_finite());
}

/// `spawn` (raw): a ray with a huge x speed (`4.8e35`) crosses a plane at a
/// subnormal `t` (`9.7e-43`); the hit point then lies farther from the
/// plane than `Plane::surface_point`'s bound allows, and
/// `SurfacePoint::spawn` (correctly sized for that bound) leaves the new
/// origin behind the plane.
/// Same cause as `plane_hit_point_bound_with_underflow`: the bounds assume
/// no underflow, and the docs now say so; `t` is subnormal here.
#[test]
fn spawn_from_plane_hit_at_subnormal_t() {
    let b = f32::from_bits(0xb9b9_b9b9); // -3.5424324e-4
    let plane = Plane::new(Vec3::new(f32::from_bits(0xb9b9_7ab9), b, b), Vec3::splat(b));
    let ray = Ray::new(Vec3::splat(b), Vec3::new(f32::from_bits(0x7ab9_b9b9), b, b));
    let dir = Vec3::splat(b);
    let t = ray_plane(&ray, &plane, f32::INFINITY).expect("hit");
    assert!(t < f32::MIN_POSITIVE, "t = {t} is subnormal");
    let (p, err) = {
        let s = plane.surface_point(&ray, &t);
        (s.point, s.point_error)
    };
    let origin = SurfacePoint {
        point: p,
        point_error: err,
        normal: plane.normal,
        normal_error: Vec3::ZERO,
    }
    .spawn(dir)
    .origin;
    assert!(p.is_finite() && err.is_finite() && origin.is_finite());
}
