//! Inputs the fuzzers (`fuzz/`) found in the plane kernel and its hit
//! point, kept as literal floats. Each test says which target found its
//! input and what went wrong: a fault of the fuzzer's check, of the kernel,
//! or of the docs (see the suite's documentation, `tests/suite/main.rs`).

use crate::common::draw::bits;
use rayhit::glam::Vec3;
use rayhit::{Plane, Ray, Surface, ray_plane};
use rayhit_testkit::oracle;
use rayhit_testkit::oracle::r;

/// `plane` (raw): a plane through a huge and a tiny coordinate, ray with a
/// subnormal direction component. The fuzzer's false-miss check fed an
/// infinite error bound to the exact oracle; the kernel was right: no hit
/// or an in-range one, and the bound is not NaN.
#[test]
fn plane_raw_input_with_unbounded_error() {
    let plane = Plane::new(
        bits([0x1d00_f300, 0x4f01_019c, 0x0000_0000]),
        bits([0x2800_0000, 0x2c2c_002c, 0xe7e7_2c2c]),
    );
    let ray = Ray::new(
        bits([0xe7e7_e7e7, 0x2c2c_e7e7, 0x2c2c_2c2c]),
        bits([0x2c2c_2c2c, 0x0000_002c, 0xff0b_3e3e]),
    );
    let t_max = f32::from_bits(0x00ef_0bac);
    if let Some(t) = ray_plane(&ray, &plane, t_max) {
        assert!(t > 0.0 && t <= t_max);
        assert!(!plane.hit_error(&ray, &t).is_nan());
    }
}

/// `plane` (raw): the hit point's error bound from `Plane::surface_point`
/// is `0` on x, but the point's x (`t * d_x`, subnormal) carries a rounding
/// error of up to half a subnormal: the bound's products underflow to zero.
/// The crate's error bounds assume no intermediate underflow, which the docs
/// did not say (they named overflow only) and now do.
#[test]
fn plane_hit_point_bound_with_underflow() {
    let plane = Plane::new(
        bits([0x0000_7f23, 0x905b_4000, 0x0000_0000]),
        bits([0x6500_0000, 0xbe54_26df, 0x0044_0000]),
    );
    let ray = Ray::new(
        bits([0x0000_0000, 0x0000_0044, 0x0000_0000]),
        bits([0x3a2b_3f5f, 0x4000_f7fb, 0x0000_00ff]),
    );
    let t = ray_plane(&ray, &plane, f32::INFINITY).expect("hit");
    let (p, err) = {
        let s = plane.surface_point(&ray, &t);
        (s.point, s.point_error)
    };
    // Outside the precondition: a product of the hit point underflows.
    let td = ray.dir * t;
    let underflows = |j: usize| ray.dir[j] != 0.0 && td[j].abs() < f32::MIN_POSITIVE;
    assert!((0..3).any(underflows));
    // Still safe: a finite point and bound.
    assert!(p.is_finite() && err.is_finite() && err.min_element() >= 0.0);
    // Where no product underflows, the bound holds.
    let exact = oracle::plane_t(&ray, &plane).unwrap();
    let (o, d) = (oracle::rv(ray.origin), oracle::rv(ray.dir));
    for j in (0..3).filter(|&j| !underflows(j)) {
        let star = &o[j] + &exact * &d[j];
        assert!(
            oracle::abs_diff(&r(p[j]), &star) <= r(err[j]),
            "axis {j}: point {p}, bound {err}"
        );
    }
}

/// `plane` (structured): a ray within rounding of parallel to the plane
/// gets an infinite `t` bound (right), and `Plane::surface_point`
/// multiplies it by the direction's zero x component: the x bound is NaN,
/// not a bound. It is now finite there: the x coordinate is exact whatever
/// `t` is.
#[test]
fn plane_hit_point_bound_is_never_nan() {
    let ray = Ray::new(
        Vec3::new(-0.000_835_418_7, 18.996_55, 18.996_544),
        Vec3::new(0.0, -4.0, -4.0),
    );
    let plane = Plane::new(
        Vec3::new(63.999_165, 64.0, 64.0),
        Vec3::new(0.0, 4.0, -3.999_999_5),
    );
    // `ray_plane` now rejects such rays (the sign of `dir . normal` is not
    // certain); the hit point function still gets any `t` a caller passes.
    assert_eq!(ray_plane(&ray, &plane, f32::INFINITY), None);
    let t = 0.125;
    assert!(plane.hit_error(&ray, &t).is_infinite());
    let (p, err) = {
        let s = plane.surface_point(&ray, &t);
        (s.point, s.point_error)
    };
    assert!(!err.is_nan(), "bound {err}");
    // x is exact; its bound is the rounding term alone,
    // bound_up(gamma(2) |o_x|, 3) = (2u / (1 - 2u)) (1 + gamma(4)) |o_x|
    // (stepped up an ulp or two), just above 2u |o_x| = EPSILON |o_x|, so
    // below 2 EPSILON |o_x|.
    assert_eq!(p.x, ray.origin.x);
    assert!(err.x > 0.0 && err.x <= 2.0 * f32::EPSILON * ray.origin.x.abs());
}

/// `plane` (structured, in CI): a ray tilted to within `2^-24` radians of
/// a plane whose normal has a component of `2.7e-20`, from an origin
/// `1.7e-21` off it on that axis: the numerator's product
/// `1.7e-21 * 2.7e-20` underflows to a subnormal, whose rounding error
/// (up to half the smallest subnormal) is far beyond `Plane::hit_error`'s
/// relative count (`t = 1.3e-37`, bound `8e-45`). The crate's bounds
/// assume no intermediate underflow (see the previous test); the fuzzer's
/// check held structured cases to them without testing for it, and now
/// tests every case. The kernel's answer stays safe: in range, finite,
/// with a finite bound.
#[test]
fn plane_tilted_ray_with_an_underflowing_numerator() {
    let plane = Plane::new(
        Vec3::new(0.0, -736.0, 0.0),
        Vec3::new(0.0, 64.0, 2.710506e-20),
    );
    let ray = Ray::new(
        Vec3::new(604.5, -736.0, -1.694_066_5e-21),
        Vec3::new(-64.0, 5.394_796_5e-6, 2.710_506_4e-20),
    );
    let t_max = 128.0;
    // Outside the precondition: a product of the numerator underflows.
    let w = plane.point - ray.origin;
    let product = w.z * plane.normal.z;
    assert!(product != 0.0 && product.abs() < f32::MIN_POSITIVE);
    let t = ray_plane(&ray, &plane, t_max).expect("hit");
    let err = plane.hit_error(&ray, &t);
    assert!(t > 0.0 && t <= t_max && t.is_finite());
    assert!(err.is_finite() && err >= 0.0);
    // And the bound alone does not cover the subnormal numerator's
    // rounding there: the case the precondition exists for.
    let exact = oracle::plane_t(&ray, &plane).expect("not parallel");
    assert!(!oracle::close(t, &exact, err));
}
