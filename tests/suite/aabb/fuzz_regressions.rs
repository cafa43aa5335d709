//! Inputs the fuzzers (`fuzz/`) found in the box kernels, kept as literal
//! floats. Each test says which target found its input and what went wrong:
//! a fault of the fuzzer's check, of the kernel, or of the docs (see the
//! suite's documentation, `tests/suite/main.rs`).

use crate::common::draw::bits;
use rayhit::glam::{DVec3, Vec3};
use rayhit::{Aabb, Ray, ray_aabb};
use rayhit_testkit::oracle;
use rayhit_testkit::oracle::{R, r};

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
