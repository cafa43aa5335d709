//! The interval forms of the plane and box tests together
//! (`plane::interval`, `aabb::interval`): their long run, and bad input.
//!
//! Bad input: NaN or inverted intervals cannot be built; NaN rays, planes
//! and boxes miss, without a panic.
//!
//! The long run, ignored by default: 100 times the default cases, every
//! kind, both precisions, in one test (so on one core); about half an
//! hour, estimated from the default run's times, not timed:
//!
//! ```sh
//! cargo test --release --test suite shapes::interval:: -- --ignored --nocapture
//! ```

use crate::aabb::interval::box_cases;
use crate::common::window::CASES;
use crate::plane::interval::plane_cases;
use rayhit::exact;
use rayhit::glam::{DVec3, Vec3};
use rayhit::{Aabb, Bounds, Intersect, Interval, Plane, PreparedRay, Ray};
use rayhit_testkit::case_count;

/// The long run: a hundred times the default cases, every kind, both
/// precisions (see the module's docs for the command).
#[test]
#[ignore]
fn long_run() {
    let n = case_count(100 * CASES);
    for (i, t) in [
        plane_cases::<Vec3>(11, n),
        plane_cases::<DVec3>(12, n),
        box_cases::<Vec3>(13, n),
        box_cases::<DVec3>(14, n),
    ]
    .iter()
    .enumerate()
    {
        println!("{i}: {t:?}");
    }
}

/// Bad input: no panic, a miss; bad intervals cannot be built.
#[test]
fn bad_input_misses() {
    assert!(Interval::new(f32::NAN, 1.0).is_none());
    assert!(Interval::new(0.0, f32::NAN).is_none());
    assert!(Interval::new(2.0, 1.0).is_none());
    assert!(Interval::new(-1.0, 1.0).is_none());
    assert!(Interval::new(0.0f64, f64::NAN).is_none());
    let all = Interval::up_to(f32::INFINITY).unwrap();
    let floor = Plane::new(Vec3::ZERO, Vec3::Y);
    let unit = Aabb::new(Vec3::ZERO, Vec3::ONE);
    let ray = Ray::new(Vec3::new(0.5, 2.0, 0.5), Vec3::NEG_Y);
    assert_eq!(floor.hit(&ray, all), Some(2.0));
    assert!(unit.clip(&ray, all).is_some());
    for bad in [
        Ray::new(Vec3::NAN, Vec3::NEG_Y),
        Ray::new(Vec3::ZERO, Vec3::ZERO),
        Ray::new(Vec3::ZERO, Vec3::new(0.0, f32::INFINITY, 0.0)),
        Ray::new(Vec3::new(0.0, f32::NEG_INFINITY, 0.0), Vec3::Y),
    ] {
        assert_eq!(floor.hit(&bad, all), None);
        assert_eq!(unit.clip(&bad, all), None);
        assert_eq!(unit.clip(&PreparedRay::new(&bad), all), None);
        assert_eq!(unit.hit(&bad, all), None);
        assert!(exact::ray_plane_in(&bad, &floor, 0.0, f32::INFINITY).is_none());
        assert!(exact::ray_aabb_in(&bad, &unit, 0.0, f32::INFINITY).is_none());
    }
    for plane in [
        Plane::new(Vec3::NAN, Vec3::Y),
        Plane::new(Vec3::ZERO, Vec3::new(0.0, f32::NAN, 0.0)),
        Plane::new(Vec3::ZERO, Vec3::new(f32::INFINITY, 1.0, 0.0)),
        Plane::new(Vec3::ZERO, Vec3::ZERO),
    ] {
        assert_eq!(plane.hit(&ray, all), None);
    }
    for b in [
        Aabb::new(Vec3::NAN, Vec3::ONE),
        Aabb::new(Vec3::ONE, Vec3::ZERO),
        Aabb::new(Vec3::ZERO, Vec3::new(1.0, f32::INFINITY, 1.0)),
    ] {
        assert_eq!(b.clip(&ray, all), None);
        assert_eq!(b.hit(&ray, all), None);
        assert_eq!(b.hit(&PreparedRay::new(&ray), all), None);
        assert!(exact::ray_aabb_in(&ray, &b, 0.0, f32::INFINITY).is_none());
    }
    // The exact module's intervals: inverted and NaN ends are no interval.
    assert!(exact::ray_plane_in(&ray, &floor, 3.0, 1.0).is_none());
    assert!(exact::ray_plane_in(&ray, &floor, f32::NAN, 1.0).is_none());
    assert!(exact::ray_aabb_in(&ray, &unit, 3.0, 1.0).is_none());
    // A crossing beyond MAX is reported by no interval: f32 inputs whose
    // exact t* = 2^127 * 3 > MAX.
    let steep = Ray::new(
        Vec3::new(0.0, 3.0, 0.0),
        Vec3::new(1.0, -(2f32.powi(-127)), 0.0),
    );
    assert!(exact::ray_plane_in(&steep, &floor, 0.0, f32::INFINITY).is_some());
    assert_eq!(floor.hit(&steep, all), None);
    let past_max = Interval::new(f32::MAX, f32::INFINITY).unwrap();
    assert_eq!(floor.hit(&steep, past_max), None);
}
