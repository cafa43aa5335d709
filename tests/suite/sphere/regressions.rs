//! Inputs the `sphere` fuzz target's check found, kept as literal floats
//! (see the suite's documentation for what each kind of fault means).

use crate::sphere::{exact, side_in, within};
use rayhit::glam::Vec3;
use rayhit::{Intersect, Interval, Ray, Side, Sphere, Surface};

/// A valid ray whose `d . d` underflows to zero: the kernel dropped it
/// as if `dir` were zero. The crossing at `t = 1e30` is decided exactly
/// now, in both forms.
#[test]
fn a_dir_whose_length_underflows_still_hits() {
    let ball = Sphere::new(Vec3::ZERO, 1.0);
    let ray = Ray::new(Vec3::new(0.0, 0.0, -2.0), Vec3::new(0.0, 0.0, 1e-30));
    let e = exact(&ray, &ball);
    let all = Interval::up_to(f32::INFINITY).unwrap();
    let hit = ball.hit(&ray, all).expect("the entry");
    assert_eq!(hit.side, Side::Front);
    assert!(side_in(&e, Side::Front, 0.0, f32::INFINITY));
    assert_eq!(
        ball.hit(&ray, f32::INFINITY).map(|h| h.side),
        Some(Side::Front)
    );
}

/// A radius whose square underflows (`1e-20` in `f32`) under a long
/// `dir`: `a fl(r r)` carried `r r`'s absolute error times `a`, which the
/// bound did not count (the reported exit was four bounds from the exact
/// one). The bound now holds.
#[test]
fn a_radius_whose_square_underflows_keeps_its_bound() {
    let ball = Sphere::new(Vec3::ZERO, 1e-20);
    let ray = Ray::new(Vec3::ZERO, Vec3::new(0.0, 0.0, 1e7));
    let e = exact(&ray, &ball);
    let hit = ball.hit(&ray, f32::INFINITY).expect("the exit");
    assert_eq!(hit.side, Side::Back);
    assert!(
        within(&e, hit.side, hit.t, ball.hit_error(&ray, &hit)),
        "{hit:?}"
    );
    let fuzz = |x: [u32; 3]| Vec3::from_array(x.map(f32::from_bits));
    let ray = Ray::new(
        fuzz([0x0100_0000, 0, 0x0080_0000]),
        fuzz([0x0022_0000, 0xc0a0, 0x4b80_9000]),
    );
    let ball = Sphere::new(
        fuzz([0x7f, 0x8b00_0000, 0x0091_7c81]),
        f32::from_bits(0x1da7_ad3b),
    );
    let e = exact(&ray, &ball);
    for hit in [
        ball.hit(&ray, f32::from_bits(0x7acd_e7c0)),
        ball.hit(&ray, f32::INFINITY),
    ]
    .into_iter()
    .flatten()
    {
        assert!(
            within(&e, hit.side, hit.t, ball.hit_error(&ray, &hit)),
            "{hit:?}"
        );
    }
}

/// A hit point so far from the centre that `|p - c|^2` overflows: the
/// surface point was the centre with no error. The point is now moved
/// onto the sphere from the scaled direction.
#[test]
fn a_far_hit_point_is_still_moved_onto_the_sphere() {
    let ball = Sphere::new(Vec3::ZERO, 1.0);
    let ray = Ray::new(Vec3::ZERO, Vec3::X);
    let here = ball.surface_point(
        &ray,
        &rayhit::SphereHit {
            t: 2e19,
            side: Side::Back,
        },
    );
    assert_eq!(here.point, Vec3::X);
    assert!(here.point_error.max_element() < 1e-6);
}
