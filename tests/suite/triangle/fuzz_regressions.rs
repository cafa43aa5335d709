//! Inputs the fuzzers (`fuzz/`) found in the triangle kernels, kept as
//! literal floats. Each test says which target found its input and what
//! went wrong: a fault of the fuzzer's check, of the kernel, or of the docs
//! (see the suite's documentation, `tests/suite/main.rs`).

use rayhit::glam::{DVec3, Vec3};
use rayhit::{Ray, Side, Surface, Triangle, TriangleHit, ray_triangle};
use rayhit_testkit::oracle;
use rayhit_testkit::oracle::{R, r};

/// `triangle_watertight_vs_mt` (raw): a valid hit with `t_max = NaN`. The
/// fuzzer's agreement check read the NaN limit as "no limit"; the kernels
/// are right to return `None` (NaN `t_max` is invalid input).
#[test]
fn triangle_nan_t_max_is_a_miss() {
    let tri = Triangle::new(
        Vec3::ZERO,
        Vec3::new(2.0, 0.0, 0.0),
        Vec3::new(0.0, 2.0, 0.0),
    );
    let ray = Ray::new(Vec3::new(0.5, 0.25, 4.0), Vec3::new(0.0, 0.0, -2.0));
    assert!(ray_triangle(&ray, &tri, f32::NAN).is_none());
    assert!(tri.moller_trumbore(&ray, f32::NAN).is_none());
    assert!(ray_triangle(&ray, &tri, f32::INFINITY).is_some());
}

/// `triangle` (raw, `f64`): a ray along x in the plane `z = 7.7e-317`, a
/// triangle whose corner `a` is lifted by `5.3e-315` (both subnormal), so
/// the ray crosses the triangle's plane at `t = 2.47`, well inside (exact
/// `u = 0.735`, `v = 0.25`). The watertight test misses, and
/// `Triangle::hit_error` at the exact crossing is finite and small,
/// so the miss lies outside the band the bounds promise. The edge functions'
/// products underflow: the bounds assume no underflow, which the docs did
/// not say and now do. The answer is still safe.
#[test]
fn triangle_subnormal_lift_outside_the_error_band() {
    let ray = Ray::new(DVec3::new(-1.0, 0.5, 7.7386016e-317), DVec3::X);
    let tri = Triangle::new(
        DVec3::new(0.0, 0.0, 5.304989477e-315),
        DVec3::new(2.0, 0.0, 0.0),
        DVec3::new(0.0, 2.0, 0.0),
    );
    let exact = oracle::triangle(&ray, &tri);
    assert!(exact.interior() && exact.hits(&None));
    let probe = TriangleHit {
        t: 2.470_825_195_312_5,
        u: 0.735_412_597_656_25,
        v: 0.25,
        side: Side::Front,
    };
    let err = tri.hit_error(&ray, &probe);
    assert!(!err.t.is_nan() && !err.u.is_nan() && !err.v.is_nan());
    // Outside the precondition: the lift times a unit coordinate is a
    // subnormal product in the edge functions.
    let lift = tri.a.z * ray.origin.y;
    assert!(lift != 0.0 && lift.abs() < f64::MIN_POSITIVE);
    if let Some(hit) = ray_triangle(&ray, &tri, f64::INFINITY) {
        assert!(hit.t > 0.0 && hit.t.is_finite());
    }
}

/// `triangle` (raw, `f64`; found by the 10-minute run): huge y coordinates
/// (`8.7e127`) next to subnormal z coordinates. The ray's shear factor
/// `-d_z / d_y = -2.2e-440` underflows to zero, so the test's frame is not
/// the one its error bounds describe: it reports `t = 0.82` with a bound of
/// `0.06`, where the exact crossing is at `t = -3.2e11` (behind the ray).
/// The bounds assume no underflow, which the docs did not say and now do.
#[test]
fn triangle_underflowing_shear_factor() {
    let ray = Ray::new(
        DVec3::new(
            7.684_632_922_875_586e49,
            7.684_632_922_875_586e49,
            1.576_434_833_883e-312,
        ),
        DVec3::new(0.0, 8.656_131_277_727_177e127, 1.917_285_608_776e-312),
    );
    let tri = Triangle::new(
        DVec3::new(0.0, 2.421_078_100_475_535_5e-305, 5e-324),
        DVec3::new(0.0, 8.656_131_277_727_177e127, 1.917_285_608_776e-312),
        DVec3::new(
            1.783_886_899_799_318_6e127,
            1.783_886_751_621_816_2e127,
            4.778_646_941_129_981e-299,
        ),
    );
    let t_max = 1.783_886_899_799_318_6e127;
    // Outside the precondition: y is the dominant axis, and the shear
    // factor of z, `d_z / d_y`, underflows to zero.
    assert!(ray.dir.z != 0.0 && ray.dir.z / ray.dir.y == 0.0);
    if let Some(hit) = ray_triangle(&ray, &tri, t_max) {
        assert!(hit.t > 0.0 && hit.t <= t_max);
        let err = tri.hit_error(&ray, &hit);
        assert!(!err.t.is_nan());
    }
}

/// `triangle` (structured; found by the 10-minute run): a sliver seen from
/// close by, crossed at exact `t = 0.0624` with a `t` bound of `0.0624` at
/// that crossing. The watertight test decides `t > 0` conservatively and
/// rejects the hit, which its docs allow; the fuzzer's band for a required
/// hit was `t > bound` and is now `t > 2 bound / (1 - 3 err_u)` (derived in
/// `testkit/src/fuzz/triangle.rs`). Moller-Trumbore hits.
#[test]
fn triangle_conservative_t_rejection_near_the_origin() {
    let ray = Ray::new(
        Vec3::new(65.953_15, 65.937_52, -64.481_43),
        Vec3::new(-0.031_249_048, -0.031_25, -0.031_25),
    );
    let tri = Triangle::new(
        Vec3::new(66.727_97, 66.707_405, -64.608_246),
        Vec3::new(63.422_65, 63.422_65, -64.077_354),
        Vec3::new(63.430_725, 63.431_56, -64.077_774),
    );
    let exact = oracle::triangle(&ray, &tri);
    let t_exact = exact.t.clone().expect("not parallel");
    assert!(exact.interior() && exact.hits(&None));
    if ray_triangle(&ray, &tri, f32::INFINITY).is_none() {
        let (u, v) = exact.uv.clone().unwrap();
        let probe = TriangleHit {
            t: oracle::to_f64(&t_exact) as f32,
            u: oracle::to_f64(&u) as f32,
            v: oracle::to_f64(&v) as f32,
            side: Side::Back,
        };
        let err = tri.hit_error(&ray, &probe);
        let int = |n: i64| R::from_integer(n.into());
        let band = int(2) * r(err.t) / (int(1) - int(3) * r(err.u.max(err.v)));
        assert!(t_exact <= band, "a miss outside the conservative band");
    }
}

/// `triangle` (structured, `f64`; found by the 10-minute run): a ray exactly
/// parallel to a sliver's plane (exact determinant zero) along the diagonal
/// `(-1, -1, -1)`. The watertight test reports a hit at `t = 6.08` on the
/// edge `u = 0`, `v = 1`; its error bounds are infinite, which is how the
/// docs mark a hit whose determinant sign is not certain (the fuzzer asked
/// for the exact `t` before looking at the bound). Moller-Trumbore and the
/// one-hit test reject it.
#[test]
fn triangle_hit_parallel_to_the_plane_has_infinite_bounds() {
    let ray = Ray::new(
        DVec3::new(
            220.980_540_043_868_64,
            93.888_375_492_007_97,
            221.636_422_426_553_93,
        ),
        DVec3::splat(-25.976_470_588_235_294),
    );
    let tri = Triangle::new(
        DVec3::new(63.0, -63.998_046_904_801_87, 63.750_000_029_744_115),
        DVec3::new(
            63.422_649_730_810_38,
            -64.575_397_173_991_49,
            63.172_649_760_554_49,
        ),
        DVec3::new(
            63.044_465_523_908_514,
            -64.047_699_027_952_18,
            63.700_347_906_593_805,
        ),
    );
    let exact = oracle::triangle(&ray, &tri);
    assert!(exact.t.is_none(), "exactly parallel");
    if let Some(hit) = ray_triangle(&ray, &tri, f64::INFINITY) {
        assert!(hit.t > 0.0 && hit.t.is_finite());
        let err = tri.hit_error(&ray, &hit);
        assert!(err.t.is_infinite() && err.u.is_infinite() && err.v.is_infinite());
    }
}

/// `triangle` (raw; found by the 10-minute run): a ray from `z = 4` down
/// through a triangle at `z = 0`, but with a `z` speed of `-2.1e-38`, so the
/// exact crossing is at `t = 1.87e38`. The watertight test scales the
/// corners' `z` by `1 / d_z` (`|z_i|` near `1.87e38`) and sums `e_i z_i`,
/// which overflows (`e_0 = 2.5` here): outside the docs' shared
/// precondition of no intermediate overflow. It reports a miss, which is
/// safe; the fuzzer's raw-input guard now checks for overflow too.
#[test]
fn triangle_scaled_distance_overflows() {
    let ray = Ray::new(
        Vec3::new(0.5, 0.25, 4.0),
        Vec3::new(1e-45, -0.0, -2.140_861_8e-38),
    );
    let tri = Triangle::new(
        Vec3::ZERO,
        Vec3::new(2.0, 0.0, 4.5918e-41),
        Vec3::new(0.0, 2.0, 5.9e-44),
    );
    let exact = oracle::triangle(&ray, &tri);
    assert!(exact.interior() && exact.hits(&None));
    // Outside the precondition: e_0 z_0 overflows.
    let z0 = (tri.a.z - ray.origin.z) * (1.0 / ray.dir.z);
    assert!(z0.is_finite() && (2.5 * z0).is_infinite());
    if let Some(hit) = ray_triangle(&ray, &tri, f32::INFINITY) {
        assert!(hit.t > 0.0 && hit.t.is_finite());
    }
}

/// Found by the `triangle` target's tetrahedron check (after the sphere
/// target joined the replay's shared stream): a ray from outside crosses
/// the tetrahedron twice by the one-hit rule and hits no face by the
/// closed rule. The exact line passes through the corner `v[0]` where
/// three faces meet, and touches the solid there only. The check's
/// `closed >= one-hit` was wrong: the one-hit rule decides in exact
/// arithmetic for the line moved off the corner (which goes in and out),
/// the closed rule in the ray's rounded frame (where the corner lands off
/// the ray, outside all three faces). Pinned down: the one-hit answers are
/// exactly the exact module's, two of them.
#[test]
fn tetrahedron_grazed_at_its_silhouette_one_hit_is_exact() {
    use rayhit::exact::oracle::one_hit_line_hits;
    use rayhit::{EdgeRule, Intersect, Ray, Triangle, glam::Vec3};
    let ray = Ray::new(
        Vec3::new(-39.718506, 2.5432792, 53.41002),
        Vec3::new(0.09973323, 0.07336711, -0.00045961142),
    );
    let v = [
        Vec3::new(-33.33558, 7.2387743, 53.380604),
        Vec3::new(-33.3315, 5.4353094, 51.26661),
        Vec3::new(-35.63824, 5.8881674, 53.694984),
        Vec3::new(-35.284546, 7.431898, 50.83234),
    ];
    let faces = [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]]
        .map(|[a, b, c]| Triangle::new(v[a], v[b], v[c]));
    let mut one = 0;
    for face in &faces {
        let got = face.hit(&ray, (f32::INFINITY, EdgeRule::OneHit)).is_some();
        assert_eq!(Some(got), one_hit_line_hits(&ray, face), "{face:?}");
        one += usize::from(got);
    }
    assert_eq!(one, 2);
}

/// `quad` (raw, `f64`): the quad's first triangle, a sliver whose corner
/// `a` is lifted off `b` by the subnormal `1.36e-312` (its plane is `x =
/// y`), and a ray along x that crosses it on the edge from `b` to `c` at
/// `t = 1.5`. Over `(0, inf]` the interval form decides the crossing exactly
/// (there is one) but the determinant underflows, so the computed `t` is
/// brought into the interval at `MAX`; the error bound's spread from the
/// corners was then infinite and, times an edge bound of zero, NaN. The
/// kernel was at fault (a NaN bound); now the bound is infinite, which the
/// docs give where the determinant's sign is not known.
#[test]
fn triangle_bound_at_the_top_of_an_interval_is_not_nan() {
    use rayhit::{Intersect, Interval};
    let a = DVec3::new(0.0, 0.0, 1.35675105885e-312);
    let tri = Triangle::new(a, DVec3::ZERO, DVec3::new(1.0, 1.0, 0.0));
    let ray = Ray::new(DVec3::new(-1.0, 0.5, 0.0), DVec3::X);
    let window = Interval::new(0.0, f64::INFINITY).unwrap();
    let hit = tri
        .hit(&ray, window)
        .expect("the crossing at t = 1.5 is decided");
    assert!(hit.t.is_finite() && (0.0..=1.0).contains(&hit.u) && (0.0..=1.0).contains(&hit.v));
    let err = tri.hit_error(&ray, &hit);
    assert!(
        !err.t.is_nan() && !err.u.is_nan() && !err.v.is_nan(),
        "{err:?}"
    );
    // The exact crossing, t = 1.5, is within the bound.
    assert!((hit.t - 1.5).abs() <= err.t, "{hit:?} {err:?}");
}

/// `quad` (raw, `f32`): corners near `4e21`, beyond the documented range
/// (`2^63` from the origin), and the one-hit rule: a hit at the subnormal
/// `t = 1e-45` whose `t` bound was NaN (an infinite term times a zero
/// one). The kernel was at fault: every bound is now at least zero or
/// infinite, as documented, for any input.
#[test]
fn triangle_bound_beyond_the_range_is_not_nan() {
    use rayhit::{EdgeRule, Intersect};
    let tri = Triangle::new(
        Vec3::new(4.1945725e21, 3.2066e-41, 0.0),
        Vec3::new(4.1945725e21, 4.1945725e21, 0.0),
        Vec3::ZERO,
    );
    let ray = Ray::new(
        Vec3::new(0.3, 8.7311495e-12, -8.8e-44),
        Vec3::new(2.361201e21, 4.1945725e21, 4.1945725e21),
    );
    let hit = tri
        .hit(&ray, (1.0, EdgeRule::OneHit))
        .expect("a hit, as found");
    let err = tri.hit_error(&ray, &hit);
    for b in [err.t, err.u, err.v] {
        assert!(b >= 0.0, "{hit:?} {err:?}");
    }
}

/// `patch` (structured, `f32`): a patch with a collapsed edge, tested as
/// its triangle, one of whose corners is NaN, with the one-hit rule: a hit
/// at `t = 1e-45`. The triangle kernel was at fault: where no edge
/// function had a usable sign it went on to the exact signs and the
/// unresolved hit, which took the NaN for a sign. Both now reject a corner
/// that is not finite, as the closed rule always did.
#[test]
fn one_hit_rule_never_hits_a_nan_corner() {
    use rayhit::{EdgeRule, Intersect, Interval, PreparedRay};
    let tri = Triangle::new(
        Vec3::new(0.0, 2.355576e-38, 0.0),
        Vec3::new(0.0, 0.0, 2.3509887e-38),
        Vec3::new(0.5, f32::NAN, 0.5),
    );
    let ray = Ray::new(Vec3::ZERO, Vec3::new(0.0, 8388608.0, 0.0));
    let prepared = PreparedRay::new(&ray);
    for t_max in [4.5918e-41, 1.0, f32::INFINITY] {
        let window = Interval::up_to(t_max).expect("valid");
        for rule in [EdgeRule::Closed, EdgeRule::OneHit] {
            assert_eq!(tri.hit(&ray, (t_max, rule)), None, "{rule:?} {t_max}");
            assert_eq!(tri.hit(&prepared, (t_max, rule)), None, "{rule:?} {t_max}");
            assert_eq!(tri.hit(&ray, (window, rule)), None, "{rule:?} {t_max}");
        }
    }
}
