//! `rayhit::exact::judge` on quads: where both triangles of a quad are
//! crossed within rounding of each other, either is a right answer and
//! its values are not held; elsewhere they are.

use rayhit::exact::{self, Band, Case, Claim, Field, Verdict};
use rayhit::glam::Vec3;
use rayhit::{Quad, Ray};

/// The quad a, b, c, d with the triangle a c d inside a b c (d on b's
/// side of the diagonal), and a ray straight down onto (1.25, 0.75),
/// inside both: both crossed at t = 1, on a b c at (u, v) = (0.625,
/// 0.375), on a c d at (0.25, 0.75) (the weights 0.25 of b and 0.375 of
/// c; 0.25 of c and 0.5 of d).
#[test]
fn a_quad_crossed_twice_at_one_t_holds_either_triangle() {
    let quad = Quad::new(
        Vec3::ZERO,
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(2.0, 2.0, 0.0),
        Vec3::new(1.5, 0.5, 0.0),
    );
    let ray = Ray::new(Vec3::new(1.25, 0.75, 1.0), -Vec3::Z);
    let case = Case::Quad(ray, quad, f32::INFINITY);
    // The exact answer is the first triangle's (a tie goes to it).
    let answer = exact::ray_quad(&ray, &quad, f32::INFINITY).expect("a hit");
    assert_eq!(
        (answer.t.rounded, answer.u.rounded, answer.v.rounded),
        (1.0, 0.625, 0.375)
    );
    for (u, v) in [(0.625, 0.375), (0.25, 0.75)] {
        let j = exact::judge(&case, &Claim::Quad { t: 1.0, u, v }, 1.0);
        assert_eq!((j.verdict, j.band), (Verdict::Right, Band::Edge), "{j:?}");
        assert!(j.outside.is_empty(), "{j:?}");
    }
    // Away from the second triangle only the first is crossed: values
    // held, even on an edge case (here the edge b c).
    let alone = Ray::new(Vec3::new(2.0, 0.25, 1.0), -Vec3::Z);
    let case = Case::Quad(alone, quad, f32::INFINITY);
    let j = exact::judge(
        &case,
        &Claim::Quad {
            t: 1.0,
            u: 1.0,
            v: 0.5,
        },
        1.0,
    );
    assert_eq!(j.band, Band::Edge);
    assert_eq!(j.outside, [Field::V]);
}
