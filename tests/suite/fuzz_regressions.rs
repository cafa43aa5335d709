//! Inputs the fuzzers (`fuzz/`) found, kept as literal floats.
//!
//! Each test says which target found the input and what went wrong. Where
//! the fault was in the fuzzer's own check, the test pins down the kernel's
//! documented behaviour on that input. Where the kernel was at fault, the
//! test asserts what the docs promise (and failed before the fix). Where the
//! docs were (a guarantee stated without a precondition it needs), the test
//! shows that the input is outside the precondition the docs now state, and
//! that the answer is still safe (no panic, no NaN, in range).

use rayhit::glam::{DVec3, Vec3};
use rayhit::{
    Aabb, Camera, CameraSample, PinholeCamera, Plane, Ray, Side, Surface, SurfacePoint, Triangle,
    TriangleHit, ray_aabb, ray_plane, ray_triangle,
};
use rayhit_testkit::oracle;
use rayhit_testkit::oracle::{R, r};

fn bits(x: [u32; 3]) -> Vec3 {
    Vec3::from_array(x.map(f32::from_bits))
}

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

/// `aabb_slab_vs_naive` (structured): a ray along the box's diagonal, in
/// through one corner and out through the opposite one. The naive test
/// rounds the exit corner outside all three faces it lies on and reports the
/// entry as the exit; its docs allow that ("agrees with the slab test away
/// from edges"), and the fuzzer's check (like the property test's) had not
/// excluded crossings at edges and corners. Both tests still hit, and the
/// slab interval contains the exact one.
#[test]
fn aabb_diagonal_through_two_corners() {
    let ray = Ray::new(Vec3::splat(3.784_353_3), Vec3::splat(-1.709_803_9));
    let b = Aabb::new(Vec3::splat(-27.662_565), Vec3::splat(-27.051_16));
    let t_max = 36.643_14;
    let (enter, exit) = ray_aabb(&ray, &b, t_max).expect("slab hit");
    let (ee, xx) = oracle::box_interval(&ray, &b, t_max).expect("exact hit");
    assert!(r(exit) >= xx);
    assert!(r(enter) <= xx && ee > R::from_integer(0.into()));
    assert!(b.clip_by_faces(&ray, t_max).is_some());
}

/// `camera` (raw): a finite, nonzero view direction whose squared length
/// underflows (`4.8e-44` along x, a subnormal) was rejected as
/// `InvalidViewDir`, which the docs define as "zero or not finite"; so were
/// views and up vectors whose squared length overflows (`1e30`). The camera
/// now normalises in a frame scaled by a power of two.
#[test]
fn camera_view_with_underflowing_length() {
    let tiny = f32::from_bits(34); // 4.8e-44
    for (view, up) in [
        (Vec3::new(tiny, 0.0, 0.0), Vec3::Y),
        (Vec3::new(1e30, 0.0, 0.0), Vec3::Y),
        (-Vec3::Z, Vec3::new(0.0, tiny, 0.0)),
        (-Vec3::Z, Vec3::new(0.0, 3e38, 3e38)),
    ] {
        assert!(view.is_finite() && view != Vec3::ZERO);
        let cam = PinholeCamera::new(Vec3::ZERO, view, up, 1.0, 1, 1).expect("valid camera");
        // The one pixel looks along the view direction (exactly: x and y are
        // at the image centre), and is a unit vector.
        let dir = cam.pixel_ray(0, 0).dir;
        let axis = if view.x != 0.0 { Vec3::X } else { -Vec3::Z };
        assert_eq!(dir, axis, "view {view}, up {up}");
    }
}

/// Found while writing the `camera` target: a focal length is accepted when
/// positive and finite, but above about `2^64` pixels the squared length of
/// every ray direction overflowed and `ray` returned a zero direction, not
/// the documented unit one; below about `2^-64` the centre pixel's squared
/// length underflowed the same way.
#[test]
fn camera_huge_focal_length_gives_unit_directions() {
    for focal in [1e30, 1e-30] {
        let cam = PinholeCamera::new(Vec3::ZERO, -Vec3::Z, Vec3::Y, focal, 3, 3).unwrap();
        // The centre pixel of an odd image looks exactly along the view.
        assert_eq!(cam.pixel_ray(1, 1).dir, -Vec3::Z, "focal {focal}");
        // A corner: the documented unit length (gamma(6), about 4e-7).
        let dir = cam.pixel_ray(0, 0).dir;
        assert!((dir.length() - 1.0).abs() < 1e-6, "focal {focal}: {dir}");
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

/// `aabb` (raw): a box of zero width at `x = 0`, a ray starting `1.1e-16`
/// short of it and moving away along `-x` with a huge speed: the exact exit
/// is `-2.8026e-45`, just past two subnormals below zero, a miss. The slab
/// test reports a hit (its subnormal products round by half a subnormal
/// each), so the false hit lay a fraction of a subnormal outside the band
/// the docs stated ("a factor 1 + 16u plus two subnormals"). The derivation
/// (at `exit_slack` in src/aabb.rs) gives four subnormals, and the docs say
/// so now; this case is within 3.
#[test]
fn aabb_false_hit_band_in_the_subnormal_range() {
    let ray = Ray::new(
        Vec3::new(-1.110_223e-16, 0.0, 0.0),
        Vec3::new(-3.961_408_1e28, -1.280_654_7e-9, 6.3384e-41),
    );
    let b = Aabb::new(Vec3::ZERO, Vec3::new(0.0, 0.0, 4.316_268e-39));
    let t_max = 0.0;
    if ray_aabb(&ray, &b, t_max).is_some() {
        let (ee, xx) = oracle::box_raw(&ray, &b, t_max).expect("moves along x");
        let u = r(f32::EPSILON / 2.0);
        let one = R::from_integer(1.into());
        let band = &xx * (one + R::from_integer(16.into()) * u)
            + r(f32::from_bits(1)) * R::from_integer(4.into());
        assert!(ee <= band, "false hit beyond the band: exact exit {xx}");
    }
}

/// `aabb_slab_vs_naive` (raw): face distances around `1e-50` underflow to
/// zero in the naive test, so its exit is `0` where the exact exit is a
/// positive value below the smallest subnormal. Its "within a few ulps"
/// assumes no underflow, like every relative bound; the fuzzer's check now
/// skips such inputs. Both tests hit, the slab interval contains the exact
/// one, and the naive one is in range.
#[test]
fn aabb_naive_distances_underflow() {
    let ray = Ray::new(
        Vec3::new(-9.488_531_5e-14, 9.981_981e-37, -2.842_171e-14),
        Vec3::new(-7.534_539e-14, 58_913_700_000_000.0, 1.044_035_45e36),
    );
    let b = Aabb::new(
        Vec3::new(-9.4962e-14, -2.842_228_2e-14, -2.842_488_4e-14),
        Vec3::new(-7.534_539e-14, 2.578_511_8e-9, 8.8e-44),
    );
    let t_max = 1e-45;
    let (ee, xx) = oracle::box_interval(&ray, &b, t_max).expect("exact hit");
    let (enter, exit) = ray_aabb(&ray, &b, t_max).expect("slab hit");
    assert!(r(exit) >= xx && r(enter) <= xx && ee >= R::from_integer(0.into()));
    let (e, x) = b.clip_by_faces(&ray, t_max).expect("naive hit");
    assert!(0.0 <= e && e <= x && x <= t_max);
}

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

/// `aabb` (raw; found by the first CI run): a ray that does not move along
/// x, with its origin outside the box's x slab, and a subnormal y speed
/// (`1.9e-41`, whose reciprocal overflows), with `t_max = inf`. Exact
/// arithmetic: a miss (x never enters the slab). The slab test returns
/// `Some((inf, inf))`: every exit is infinite, so the infinite entry passes
/// `enter <= limit`. The docs say the entry is finite for every hit, with no
/// precondition (the "no false miss" precondition, exact distances at most
/// `MAX / 2`, does not hold here, which excuses a false hit but not an
/// infinite entry). Fixed: an infinite entry is a miss.
#[test]
fn aabb_infinite_entry_with_overflowing_reciprocal() {
    let ray = Ray::new(Vec3::new(-1.0, 1.0, 0.5), Vec3::new(0.0, 1.9013e-41, 0.0));
    let b = Aabb::new(Vec3::ZERO, Vec3::ONE);
    assert_eq!(oracle::box_interval(&ray, &b, f32::INFINITY), None);
    if let Some((enter, exit)) = ray_aabb(&ray, &b, f32::INFINITY) {
        assert!(enter.is_finite() && enter <= exit, "({enter}, {exit})");
    }
    // Found by the 10-minute `aabb_slab_vs_naive` run: the same answer where
    // the precondition does hold (the z distances are near 3e4). A point
    // box at the origin; the ray does not move along y and starts above it.
    let ray = Ray::new(
        Vec3::new(0.0, 2.524_355e-29, -5.785_636e-39),
        Vec3::new(0.0, -0.0, 1.78e-43),
    );
    let b = Aabb::new(Vec3::ZERO, Vec3::ZERO);
    assert_eq!(oracle::box_interval(&ray, &b, f32::INFINITY), None);
    assert_eq!(ray_aabb(&ray, &b, f32::INFINITY), None);
    // And without an overflowing reciprocal (found by the 10-minute run):
    // the y exit `(1.8e19 - 0.5) / 5.9e-39` overflows as a product.
    let ray = Ray::new(
        Vec3::new(-1.0, 0.5, 2.350_988_7e-38),
        Vec3::new(0.0, 5.871_732e-39, 0.0),
    );
    let b = Aabb::new(Vec3::ZERO, Vec3::new(1.175_494_4e-38, 1.848_221e19, 1.0));
    assert_eq!(oracle::box_interval(&ray, &b, f32::INFINITY), None);
    assert_eq!(ray_aabb(&ray, &b, f32::INFINITY), None);
}

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

/// `aabb` (raw; found by CI's 20-second run): the origin lies exactly on the
/// box's `max.x` plane and the ray moves out along x at `2.7e-43` (a
/// subnormal speed, whose reciprocal overflows). Exactly, the ray leaves
/// the x slab at `t = 0` while the z slab is entered only at `t = 1.2e-25`:
/// a miss, and the documented precondition holds (every exact distance is
/// far below `MAX / 2`). The slab test computes that plane's distance as
/// `0 * inf = NaN`, treats it as a ray lying in the face plane, and
/// reports a hit far outside the band (exact entry `1.2e-25`, exact exit
/// `0`). The docs now state the band only for components with a finite
/// reciprocal (`|d_i| >= 1/MAX`); beyond that a false hit passes the box at
/// a distance of at most `t |d_i| < t / MAX` along that axis, as here.
#[test]
fn aabb_origin_on_slab_plane_with_overflowing_reciprocal() {
    let ray = Ray::new(
        Vec3::new(1.212_387_3e-25, 1.212_387_3e-25, -3.1e-44),
        Vec3::new(2.68e-43, 8.8e-44, 1.0),
    );
    let b = Aabb::new(
        Vec3::new(1.033_975_8e-25, 1.212_387_3e-25, 1.212_387_3e-25),
        Vec3::splat(1.212_387_3e-25),
    );
    let t_max = 0.000_488_281_25;
    let (ee, xx) = oracle::box_raw(&ray, &b, t_max).expect("moves along every axis");
    assert!(ee > xx, "exact miss");
    assert!(overflows(ray.dir.x), "outside the band's condition");
    overflow_false_hit_is_close(&ray, &b, t_max);
}

/// A slab hit where a direction component's reciprocal overflows: in range,
/// and at the reported entry the ray is within the documented distance
/// `enter / (MAX (1 - u)^2)` of the box along every such axis.
fn overflow_false_hit_is_close(ray: &Ray, b: &Aabb, t_max: f32) {
    let Some((enter, exit)) = ray_aabb(ray, b, t_max) else {
        return;
    };
    assert!(0.0 <= enter && enter <= exit && exit <= t_max && enter.is_finite());
    let e = r(enter);
    let zero = R::from_integer(0.into());
    let one_minus_u = R::from_integer(1.into()) - r(f32::EPSILON / 2.0);
    let limit = &e / (r(f32::MAX) * &one_minus_u * &one_minus_u);
    for k in (0..3).filter(|&k| overflows(ray.dir[k])) {
        let x = r(ray.origin[k]) + &e * r(ray.dir[k]);
        let below = r(b.min[k]) - &x;
        let above = &x - r(b.max[k]);
        let outside = below.max(above).max(zero.clone());
        assert!(outside <= limit, "axis {k}: {ray:?} {b:?}");
    }
}

/// A nonzero component whose reciprocal overflows (`|d| < 1/MAX`).
fn overflows(d: f32) -> bool {
    d != 0.0 && !(1.0 / d).is_finite()
}

/// `aabb` (raw; found by the 10-minute run): the same cause without the
/// origin on a plane. The x and y speeds (`8.8e-44`, `2.3e-41`) have
/// overflowing reciprocals; the slab test uses `MAX` for the y entry, which
/// puts the computed entry at `0.023` where the exact entry is `3.02`, and
/// an infinite x exit. Exactly, the ray leaves the z slab at `0.98`, before
/// it enters the y slab: a miss by a factor of 3, far outside the
/// band the docs then stated, with the precondition holding. The docs now
/// state the band only for components with a finite reciprocal; this test
/// holds the hit to the distance they give for the others.
#[test]
fn aabb_false_hit_with_overflowing_reciprocals() {
    let ray = Ray::new(
        Vec3::new(2.278e-41, -6.8697e-41, 2.68e-43),
        Vec3::new(8.8e-44, 2.2768e-41, 1.758_649_8e-38),
    );
    let b = Aabb::new(Vec3::ZERO, Vec3::new(9.1835e-41, 5.9e-44, 1.726_507_3e-38));
    let t_max = 1.766_275_7e21;
    let (ee, xx) = oracle::box_raw(&ray, &b, t_max).expect("moves along every axis");
    assert!(
        ee > &xx * R::from_integer(3.into()),
        "exact miss by a factor of 3"
    );
    assert!(overflows(ray.dir.y), "outside the band's condition");
    overflow_false_hit_is_close(&ray, &b, t_max);
    // f64 (found by the 10-minute `aabb_slab_vs_naive` run): the ray does
    // not move along z and starts below the box (`0 < 1.3e-321`), a miss;
    // its x speed `5.3e-315` has an overflowing reciprocal, every exit is
    // clipped to `t_max = MAX`, whose widening overflows, and the slab test
    // reports `Some((MAX, MAX))`.
    let ray = Ray::new(
        DVec3::new(0.0, 6.953_355_807_835e-310, 0.0),
        DVec3::new(5.299_808_824e-315, 0.0, 0.0),
    );
    let b = Aabb::new(
        DVec3::new(0.0, 0.0, 1.265e-321),
        DVec3::new(1.61895e-319, 1.0, 3.645_561_009_778_199e-304),
    );
    assert_eq!(oracle::box_raw(&ray, &b, f64::MAX), None, "exact miss");
    assert_eq!(ray_aabb(&ray, &b, f64::MAX), None);
}

/// `aabb_slab_vs_naive` (raw): a box of zero thickness in z at `z = 0`, the
/// ray starting on that plane and rising at `2.35e-38`: exactly, it leaves
/// the z slab at `t = 0`, before it reaches the x slab at `1.09e-24`, a
/// miss. The slab test is right. The naive test hits: its face test
/// computes `t d_z = 2.5e-62`, which underflows to `0`, inside the face. The
/// fuzzer's "naive hits, so the slab test hits" (also a property test)
/// holds only where the naive test's false hits are rounding-sized.
#[test]
fn aabb_naive_false_hit_by_underflow() {
    let ray = Ray::new(
        Vec3::new(-46_179_510_000_000.0, 9.18712e-40, 0.0),
        Vec3::new(4.253_575_7e37, 4.499_995e-39, 2.350_952_8e-38),
    );
    let b = Aabb::new(
        Vec3::new(3.85762e-34, 9.1834e-41, 0.0),
        Vec3::new(2.911_449e-11, 7.106_625e-15, 0.0),
    );
    let t_max = 2.238_725_5e29;
    assert_eq!(oracle::box_interval(&ray, &b, t_max), None);
    assert_eq!(ray_aabb(&ray, &b, t_max), None);
    // The naive answer (a hit, today) is allowed; it must be in range.
    if let Some((e, x)) = b.clip_by_faces(&ray, t_max) {
        assert!(0.0 <= e && e <= x && x <= t_max);
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

/// `aabb` (raw; found by CI's 20-second run): a ray from a corner of a thin
/// box moving along y at `2.26e-41` (overflowing reciprocal), `t_max = inf`.
/// The slab test returns an infinite exit, which is allowed (at least the
/// exact exit `1.016`, and `t_max` is infinite); the fuzzer's check fed that
/// infinite exit to the exact oracle.
#[test]
fn aabb_infinite_exit_with_infinite_t_max() {
    let b = Aabb::new(Vec3::ZERO, bits([0x0000_a300, 0x0000_4000, 0x3f80_0000]));
    let ray = Ray::new(Vec3::ZERO, bits([0x0000_0000, 0x0000_3f00, 0x0000_0000]));
    let (ee, xx) = oracle::box_interval(&ray, &b, f32::INFINITY).expect("exact hit");
    let (enter, exit) = ray_aabb(&ray, &b, f32::INFINITY).expect("no false miss");
    assert_eq!(r(enter), ee);
    assert!(!exit.is_finite() || r(exit) >= xx);
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

/// `aabb` (raw): direction components near `3.4e38`, whose reciprocals are
/// subnormal (`|d| > 2^126`), and a box `1.5e16` out. The test reported a
/// hit that exact arithmetic misses by about `26u` relative, past the
/// documented `16u`. The docs were at fault: a subnormal reciprocal is
/// within `1.5` subnormals of `1/d` after the conservative step, up to
/// `12u` relative, so the band is `40u` there (derived at
/// `SlabRay::stepped`); the docs and the fuzzer's check now say so.
#[test]
fn aabb_false_hit_band_with_subnormal_reciprocals() {
    let ray = Ray::new(
        Vec3::new(3.2412e-41, 2.2959e-41, 0.0),
        Vec3::new(2.538_825_5e38, 3.396_146e38, 3.396_151_4e38),
    );
    let b = Aabb::new(
        Vec3::new(9_218_305_000_000_000.0, 1.536_522_2e16, 1.536_522_2e16),
        Vec3::splat(1.536_522_2e16),
    );
    let t_max = 3.396_151_4e38;
    assert!(oracle::reciprocal_subnormal(ray.dir));
    let (ee, xx) = oracle::box_raw(&ray, &b, t_max).expect("moves along every axis");
    assert!(ee > xx, "exact arithmetic misses");
    assert!(
        ray_aabb(&ray, &b, t_max).is_some(),
        "the reported false hit"
    );
    let u = r(f32::EPSILON / 2.0);
    let band = |k: i64| {
        &xx * (R::from_integer(1.into()) + R::from_integer(k.into()) * &u)
            + r(f32::from_bits(1)) * R::from_integer(4.into())
    };
    assert!(
        ee > band(16),
        "beyond the band without subnormal reciprocals"
    );
    assert!(ee <= band(40), "within the band with them");
}

/// `thin_lens` (raw): a zero lens radius and a NaN lens sample. The ray
/// went down the lens's path (the offset `0 * NaN` is NaN, not zero) and
/// came out NaN; the docs say a zero radius is the pinhole camera, bit for
/// bit, and now it is, whatever the sample.
#[test]
fn thin_lens_zero_radius_with_nan_sample_is_the_pinhole() {
    use rayhit::camera::ThinLensCamera;
    let pinhole = PinholeCamera::new(Vec3::ZERO, -Vec3::Z, Vec3::Y, 100.0, 64, 64).unwrap();
    let cam = ThinLensCamera::new(pinhole, 0.0, 3.0).unwrap();
    for (s, t) in [(0.1, f32::NAN), (f32::NAN, f32::NAN), (f32::INFINITY, 0.3)] {
        assert_eq!(
            cam.ray(CameraSample::new(10.0, 10.0).with_lens(s, t)),
            pinhole.ray(CameraSample::new(10.0, 10.0))
        );
    }
}

/// `equirectangular` and `equal_area` (structured): an up vector nearly
/// parallel to the view direction (the sine of their angle just above the
/// cameras' `gamma(16)` limit). `right`, normalised from the cross product,
/// was off orthogonal to `forward` by the product's rounding over that
/// sine (over 100 `gamma(13)` here), and the round trip missed the bound
/// that assumed a basis orthonormal within `gamma(13)`. The basis now
/// removes `right`'s component along `forward` once more: orthonormal
/// within `gamma(13)` for this up vector too, and the round trips within
/// the bounds for that basis.
#[test]
fn panorama_round_trip_with_a_nearly_parallel_up_vector() {
    use rayhit::camera::{EqualAreaCamera, EquirectangularCamera};
    use rayhit_testkit::fuzz::panoramic::basis_skew;
    let view = Vec3::new(-0.2036, -0.6923, -0.6923);
    // Sine 3e-6: up is the view turned by 3e-6 radians.
    let up = view.normalize() + Vec3::new(0.0, 3e-6, -3e-6) * 0.7;
    let equi = EquirectangularCamera::new(Vec3::ZERO, view, up, 1, 1).unwrap();
    let g13 = f64::from(<f32 as rayhit::Scalar>::gamma_n(13));
    // basis_skew is never below gamma(13): equal means within it.
    assert_eq!(basis_skew([equi.right(), equi.up(), equi.forward()]), g13);
    let (x, y) = equi
        .raster_position(equi.ray(CameraSample::new(0.5, 0.5)).dir)
        .unwrap();
    let (bx, by) = equi.raster_position_error(0.5, 0.5);
    let (ex, ey) = ((x - 0.5).abs(), (y - 0.5).abs());
    assert!(ex <= bx && ey <= by, "({ex}, {ey}) beyond ({bx}, {by})");
    let area = EqualAreaCamera::new(
        DVec3::new(6.0, -8.0, 0.0),
        view.as_dvec3(),
        up.as_dvec3(),
        1,
        1,
    )
    .unwrap();
    let g13 = <f64 as rayhit::Scalar>::gamma_n(13);
    assert_eq!(basis_skew([area.right(), area.up(), area.forward()]), g13);
    let (bx, by) = area.raster_position_error(0.5, 0.5);
    let (x, y) = area
        .raster_position(area.ray(CameraSample::new(0.5, 0.5)).dir)
        .unwrap();
    assert!((x - 0.5).abs() <= bx && (y - 0.5).abs() <= by);
}

/// `thin_lens` (raw): a subnormal lens radius, `1e-45`, and the lens sample
/// `(0.3, 0.7)`. The offset `radius * disc point` rounds to zero, and the
/// camera took the pinhole ray (unit direction, not through the focus
/// point), against its docs (only the lens centre and a zero radius give
/// the pinhole ray). Now every other sample takes the lens's path and
/// meets the focus point exactly.
#[test]
fn thin_lens_subnormal_radius_meets_the_focus_point() {
    use rayhit::camera::ThinLensCamera;
    let pinhole = PinholeCamera::new(
        Vec3::new(100000.0, -30000.0, 200000.0),
        Vec3::X,
        Vec3::Z,
        1000.0,
        1920,
        1080,
    )
    .unwrap();
    let cam = ThinLensCamera::new(pinhole, 1e-45, 1.875).unwrap();
    let focus = cam.focus(0.5, 1079.5);
    let ray = cam.ray_through(&focus, 0.3, 0.7);
    assert_eq!(ray.at(1.0), focus.point());
    assert_ne!(ray, pinhole.ray(CameraSample::new(0.5, 1079.5)));
}

// `equal_area` (structured, f64), `equirectangular` (structured, f64) and
// `matrix_camera` (structured, f32): the checks' faults, the cameras were
// right (their reproducers are replayed from fuzz/crashes by
// testkit/tests/fuzz_replay.rs). The equal-area differentials were
// compared with a central difference of a camera rebuilt from this one's
// `forward` and `up`, whose basis differs from this one's by more than a
// rounding when the up vector was nearly parallel to the view (now the
// map on this camera's own basis); the equirectangular differentials are
// the unnormalised map's derivative, which the normalisation changes in
// proportion to the basis's departure from orthonormal (now in the
// bound); and a matrix camera of an axis-aligned view stores components
// in the subnormal range, where a rounding's error is absolute, not
// relative (now half a subnormal per rounding in the bound).

// `hit_differentials` (structured, f32): a triangle generated around the
// ray's point with two nearly opposite corner offsets, a sliver whose
// normal is known to less than its own length; the running error bound
// was infinite, as it should be (the division by `|n|^2` has no certain
// room), and the check expected it finite for any hit that was not
// grazing. The check's fault: it now also exempts slivers (reproducer in
// fuzz/crashes/hit_differentials).

/// `hit_differentials` (structured; an orthographic camera's ray): the ray
/// is exactly parallel to the triangle's plane (every direction component
/// `-0.57735026`, and `dir . n = 0` in exact arithmetic), yet the
/// watertight test reports a hit: it decides on the sheared, rounded
/// corners, which the ray does cross. The fuzzer's check took every hit to
/// have an exact transfer; the kernel was right: the transfer's values are
/// finite and every bound on them is infinite, since the computed `dir .
/// n` is rounding alone.
#[test]
fn hit_differentials_of_a_ray_exactly_parallel_to_the_plane() {
    use rayhit::camera::RayDifferential;
    let dir = Vec3::splat(-0.577_350_26);
    let diff = RayDifferential {
        ray: Ray::new(Vec3::new(-13.125122, -2.718715, 5.558_819_3), dir),
        dx_origin: Vec3::new(-1.194_736_2, 1.194_699_8, 3.643_913e-5),
        dx_dir: Vec3::ZERO,
        dy_origin: Vec3::new(0.689_739_3, 0.689_802_4, -1.379_541_6),
        dy_dir: Vec3::ZERO,
    };
    let tri = Triangle::new(
        Vec3::new(-25.340595, -7.755_673_4, 4.415_642_7),
        Vec3::new(-13.488924, -3.082_516_7, 5.195_017_3),
        Vec3::new(-15.758787, -12.530894, -8.147142),
    );
    let hit = ray_triangle(&diff.ray, &tri, f32::INFINITY).expect("the reported hit");
    assert_eq!(hit.t, 5.631_909_4);
    // Exactly parallel: the direction's dot product with the exact normal.
    let rv = |v: Vec3| [r(v.x), r(v.y), r(v.z)];
    let (a, b, c, d) = (rv(tri.a), rv(tri.b), rv(tri.c), rv(dir));
    let e1: [R; 3] = core::array::from_fn(|k| &b[k] - &a[k]);
    let e2: [R; 3] = core::array::from_fn(|k| &c[k] - &a[k]);
    let n = [
        &e1[1] * &e2[2] - &e1[2] * &e2[1],
        &e1[2] * &e2[0] - &e1[0] * &e2[2],
        &e1[0] * &e2[1] - &e1[1] * &e2[0],
    ];
    let dn = &d[0] * &n[0] + &d[1] * &n[1] + &d[2] * &n[2];
    assert_eq!(dn, r(0.0f32));
    let got = tri.hit_differentials(&diff, hit.t).expect("a transfer");
    assert!(got.dp_dx.is_finite() && got.dp_dy.is_finite());
    assert!(
        [got.du_dx, got.dv_dx, got.du_dy, got.dv_dy]
            .iter()
            .all(|x| x.is_finite())
    );
    let err = tri.hit_differentials_error(&diff, hit.t);
    assert!(err.dp_dx.min_element() == f32::INFINITY && err.dp_dy.min_element() == f32::INFINITY);
    assert!(
        [err.du_dx, err.dv_dx, err.du_dy, err.dv_dy]
            .iter()
            .all(|x| x.is_infinite())
    );
    rayhit_testkit::fuzz::hit_differentials::check(&diff, &tri, hit.t, true);
}

/// `matrix_camera` (structured, `f64`): an image one pixel high. At its
/// only row the vertical `raster_error` is the subnormal slack alone,
/// below the normal range, and its `f64` evaluation multiplied the
/// smallest subnormal by the slack's factor first: rounded there, the
/// bound came out 0.02% below the derivation. The kernel was at fault: the
/// slack is now carried as a multiple of the smallest subnormal to the
/// last step. Every perspective kind, both handednesses, a few fields of
/// view and near planes.
#[test]
fn matrix_camera_one_pixel_high_in_f64() {
    use rayhit::camera::ClipSpace;
    use rayhit::glam::DMat4;
    use rayhit::glam::dcamera::{lh, rh};
    use rayhit_testkit::fuzz::matrix_camera::check_matrix_pixel;
    let eye = DVec3::new(6.0004, -8.0006, 0.0);
    let dir = DVec3::new(0.0, -1.0, -1.0).normalize();
    let aspect = 1825.0;
    let (d3d, gl, vk) = (ClipSpace::Direct3D, ClipSpace::OpenGl, ClipSpace::Vulkan);
    for fov in [10.0f64, 40.0, 120.0].map(f64::to_radians) {
        for near in [1.0 / 64.0, 0.1, 4.0] {
            let far = near * 8.0;
            let views = [
                rh::view::look_to_mat4(eye, dir, DVec3::X),
                lh::view::look_to_mat4(eye, dir, DVec3::X),
            ];
            let projections: [[(DMat4, ClipSpace); 4]; 2] = [
                [
                    (rh::proj::directx::perspective(fov, aspect, near, far), d3d),
                    (
                        rh::proj::directx::perspective_infinite_reverse(fov, aspect, near),
                        d3d,
                    ),
                    (rh::proj::opengl::perspective(fov, aspect, near, far), gl),
                    (rh::proj::vulkan::perspective(fov, aspect, near, far), vk),
                ],
                [
                    (lh::proj::directx::perspective(fov, aspect, near, far), d3d),
                    (
                        lh::proj::directx::perspective_infinite_reverse(fov, aspect, near),
                        d3d,
                    ),
                    (lh::proj::opengl::perspective(fov, aspect, near, far), gl),
                    (lh::proj::vulkan::perspective(fov, aspect, near, far), vk),
                ],
            ];
            for (view, projections) in views.iter().zip(projections) {
                for (proj, clip) in projections {
                    let m = (&view.to_cols_array_2d(), &proj.to_cols_array_2d());
                    check_matrix_pixel::<DVec3>(m, clip, (1825, 1), (0, 0));
                }
            }
        }
    }
}
