//! Inputs the fuzzers (`fuzz/`) found in the exact module, `rayhit::exact`,
//! kept as literal floats. Each test says which target found its input and
//! what went wrong: a fault of the fuzzer's check, of the kernel, or of the
//! docs (see the suite's documentation, `tests/suite/main.rs`).

use rayhit::glam::Vec3;
use rayhit::{Ray, Triangle, ray_triangle};

/// The exact judgement of a kernel that claims a hit (at `t = 1`, `u =
/// 0.5`, `v = 0.25`; these tests look only at the verdict and the band).
fn judge_a_claimed_hit(case: &rayhit::exact::Case<Vec3>) -> rayhit::exact::Judgement {
    let claim = rayhit::exact::Claim::Triangle {
        t: 1.0,
        u: 0.5,
        v: 0.25,
    };
    rayhit::exact::judge(case, &claim, f64::INFINITY)
}

/// `exact_judge` (the README's fuzz snippet, with the textbook
/// Moller-Trumbore as the kernel under test): a triangle of zero area
/// (`b == c`) whose segment's line the ray's line meets behind the origin.
/// The exact determinant is zero, but Moller-Trumbore's rounds to a tiny
/// nonzero value, and its `u`, `v`, `t` claimed a hit. The oracle was at
/// fault: it called every case without a crossing (parallel line, or zero
/// area) clear. Such a case is never clear now. The watertight test still
/// misses it, for a reason independent of the oracle: with `b == c` its
/// edge functions are `e_b = 0` and `e_c = -e_a` exactly (the same two
/// rounded products, subtracted in the opposite order), so they are mixed
/// unless all zero, and a zero determinant is a miss.
#[test]
fn zero_area_triangle_is_never_clear() {
    use rayhit::exact::{self, Band, Case, Verdict};
    let ray = Ray::new(Vec3::splat(-477.875), Vec3::splat(-477.875));
    let tri = Triangle::new(
        Vec3::new(-477.875, 130.125, 128.5),
        Vec3::splat(128.5),
        Vec3::splat(128.5),
    );
    let case = Case::Triangle(ray, tri, f32::INFINITY);
    assert_eq!(exact::band(&case), Band::Edge);
    assert!(ray_triangle(&ray, &tri, f32::INFINITY).is_none());
    // What the snippet's kernel claimed: a hit, which exact arithmetic
    // rejects (the line meets the segment at t < 0), inside the band.
    let j = judge_a_claimed_hit(&case);
    assert_eq!((j.verdict, j.band), (Verdict::FalseHit, Band::Edge));
}

/// The band's other side: a line that crosses the plane far outside the
/// triangle is a clear miss (before, a triangle miss was only clear when
/// its line was parallel to the plane, so no false hit could be called a
/// bug). A kernel that claimed it is judged wrong outside the band.
#[test]
fn triangle_miss_outside_is_clear() {
    use rayhit::exact::{self, Band, Case, Verdict};
    let tri = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
    // Crosses z = 0 at (2, 0.25): u = 2, v = 0.25, and past edge b-c.
    let ray = Ray::new(Vec3::new(2.0, 0.25, -1.0), Vec3::Z);
    let case = Case::Triangle(ray, tri, f32::INFINITY);
    assert_eq!(exact::band(&case), Band::Clear);
    let j = judge_a_claimed_hit(&case);
    assert_eq!((j.verdict, j.band), (Verdict::FalseHit, Band::Clear));
    // Just outside edge b-c (by 2^-16 in u + v, more than either test's
    // rounding at this scale): still clear; on the edge: not clear.
    let near = Ray::new(Vec3::new(0.75 + 2f32.powi(-16), 0.25, -1.0), Vec3::Z);
    assert_eq!(
        exact::band(&Case::Triangle(near, tri, f32::INFINITY)),
        Band::Clear
    );
    let on = Ray::new(Vec3::new(0.75, 0.25, -1.0), Vec3::Z);
    assert_eq!(
        exact::band(&Case::Triangle(on, tri, f32::INFINITY)),
        Band::Edge
    );
}
