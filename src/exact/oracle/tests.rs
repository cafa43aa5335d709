//! The oracle's building blocks against each other and against the
//! kernels: the integer path against the rational formulas, the filter's
//! bounds and answers against exact arithmetic.

use super::filter::{EdgeFrame, filter, plucker_f64, surely_outside_watertight_exact};
use super::values::moving;
use super::*;
use crate::testing::Draws;
use crate::{Aabb, Plane, Ray, Scalar, Triangle, Vector};
use crate::{EdgeRule, Intersect};
use glam::{DVec3, Vec3};
use num_traits::{Signed, Zero};

#[test]
fn non_finite_input_gives_none_or_false() {
    let (nan, inf) = (f32::NAN, f32::INFINITY);
    let good = Ray::new(Vec3::new(0.25, 0.25, 1.0), Vec3::NEG_Z);
    let tri = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
    let aabb = Aabb::new(Vec3::ZERO, Vec3::ONE);
    let plane = Plane::new(Vec3::ZERO, Vec3::Z);
    assert!(r(nan).is_none() && r(inf).is_none() && rv(Vec3::new(0.0, inf, 0.0)).is_none());
    for bad in [
        Ray::new(Vec3::new(nan, 0.25, 1.0), Vec3::NEG_Z),
        Ray::new(Vec3::new(0.25, 0.25, 1.0), Vec3::new(0.0, inf, -1.0)),
    ] {
        assert!(plane_t(&bad, &plane).is_none() && box_slabs(&bad, &aabb).is_none());
        assert!(box_face(&bad, &aabb).is_none() && triangle(&bad, &tri).is_none());
        assert!(
            segment_crossing(&bad, &tri).is_none() && edge_function_bound(&bad, &tri).is_none()
        );
        assert!(mt_bounds(&bad, &tri, &int(0), &int(0)).is_none());
        assert!(!box_clear(&bad, &aabb, inf) && !triangle_clear(&bad, &tri, inf));
        assert!(!plane_clear(&bad, &plane, inf) && !reciprocal_subnormal(bad.dir));
        let exact = triangle(&good, &tri).unwrap();
        assert!(triangle_decided(&bad, &tri, &exact, inf, &no_extra()).is_none());
        assert!(!surely_outside(&bad, &tri, &exact, &no_extra()));
    }
    assert!(!reciprocal_overflows(Vec3::new(nan, 1.0, 1.0)));
    assert!(!close(nan, &int(0), 1.0) && !close(0.0, &int(0), inf));
    assert!(close(0.5, &dyadic(1, -1), 0.0));
    assert_eq!(main_axis(Vec3::new(nan, nan, nan)), 2);
}

#[test]
fn a_segment_seen_end_on_has_no_crossing() {
    let seg = Triangle::new(Vec3::ZERO, Vec3::Z, Vec3::Z * 2.0);
    let ray = Ray::new(Vec3::new(0.0, 0.0, 5.0), Vec3::NEG_Z);
    assert!(segment_crossing(&ray, &seg).is_none());
    let across = Ray::new(Vec3::new(-1.0, 0.0, 1.5), Vec3::X);
    assert_eq!(segment_crossing(&across, &seg), Some(int(1)));
}

#[test]
fn conversions_saturate_and_gamma_is_total() {
    assert_eq!(to_f64(&dyadic(1, 2000)), f64::INFINITY);
    assert_eq!(to_f64(&dyadic(-1, 2000)), f64::NEG_INFINITY);
    assert_eq!(to_f64(&dyadic(-1, -2000)).to_bits(), (-0.0f64).to_bits());
    assert_eq!(to_f64(&dyadic(3, -1074)), 3.0 * f64::from_bits(1));
    assert_eq!(to_f64(&r(f64::MAX).unwrap()), f64::MAX);
    assert_eq!(ulp::<f32>(1.0), f64::from(f32::EPSILON));
    assert_eq!(ulp::<f32>(f64::from(f32::MAX)), f64::INFINITY);
    assert_eq!(ulp::<f32>(1e300), f64::from(f32::from_bits(1)));
    assert!(gamma::<f32>(u16::MAX) < int(1) && gamma::<f64>(1) > int(0));
}

/// `triangle`'s rational formulas as they read before they were
/// computed in integers: the reference it is held to.
fn triangle_reference<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>) -> Option<ExactTriangle> {
    let (o, d) = (rv(ray.origin)?, rv(ray.dir)?);
    let (a, b, c) = (
        sub(&rv(tri.a)?, &o),
        sub(&rv(tri.b)?, &o),
        sub(&rv(tri.c)?, &o),
    );
    let s = [(&a, &b), (&b, &c), (&c, &a)].map(|(p, q)| dot(&cross(p, q), &d));
    let signs = [0, 1, 2].map(|i| s[i].cmp(&R::zero()));
    let sum = &s[0] + &s[1] + &s[2];
    if sum.is_zero() {
        return Some(ExactTriangle {
            signs,
            t: None,
            uv: None,
        });
    }
    let n = cross(&sub(&b, &a), &sub(&c, &a));
    Some(ExactTriangle {
        signs,
        t: Some(dot(&a, &n) / &sum),
        uv: Some((&s[2] / &sum, &s[0] / &sum)),
    })
}

fn unit(g: &mut Draws) -> f64 {
    (g.next() >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
}

pub(super) fn grid(g: &mut Draws) -> f64 {
    ((g.next() >> 8) % 17) as f64 / 4.0 - 2.0
}

fn pow2(k: i64) -> f64 {
    2f64.powi(k as i32)
}

/// A ray and a triangle of precision `V` for the filter and verdict
/// tests, by `kind`:
/// 0. grid coordinates (quarters in `[-2, 2]`): exact zeros, rays
///    exactly through corners and along edges, lines exactly parallel
///    to the plane, zero-area triangles;
/// 1. wide magnitudes (`Draws::coordinate` over `2^±60`), and one
///    coordinate in eight a special value (NaN, infinities, `MAX`,
///    subnormal, signed zeros);
/// 2. a ray aimed `2^-j` (`j` up to 60) of the triangle's size off a
///    corner, an edge midpoint or a point of an edge;
/// 3. a ray `2^-j` off parallel to the triangle's plane;
///
/// kinds 2 and 3 scaled by `2^±40` and, one time in two, translated by
/// up to `2^20` times that (so that rounding the corners and the
/// direction in `V` moves the ray by more than the aim's offset).
fn case<V: Vector>(g: &mut Draws, kind: u64) -> (Ray<V>, Triangle<V>) {
    let v = |p: [f64; 3]| {
        V::new(
            V::Scalar::from_f64(p[0]),
            V::Scalar::from_f64(p[1]),
            V::Scalar::from_f64(p[2]),
        )
    };
    let point = |g: &mut Draws| [unit(g), unit(g), unit(g)];
    match kind {
        0 => {
            let mut p = || v([grid(g), grid(g), grid(g)]);
            let (o, d, a, b, c) = (p(), p(), p(), p(), p());
            (Ray::new(o, d), Triangle::new(a, b, c))
        }
        1 => {
            let mut p = || {
                v([0; 3].map(|_| {
                    if g.next().is_multiple_of(8) {
                        f64::from(g.special_f32())
                    } else {
                        g.coordinate(120)
                    }
                }))
            };
            let (o, d, a, b, c) = (p(), p(), p(), p(), p());
            (Ray::new(o, d), Triangle::new(a, b, c))
        }
        _ => {
            let (a, b, c) = (point(g), point(g), point(g));
            let scale = pow2((g.next() % 81) as i64 - 40);
            let far = if g.next().is_multiple_of(2) {
                scale * pow2((g.next() % 21) as i64)
            } else {
                0.0
            };
            let offset = [unit(g) * far, unit(g) * far, unit(g) * far];
            let place = |p: [f64; 3]| v([0, 1, 2].map(|k| offset[k] + scale * p[k]));
            let tri = Triangle::new(place(a), place(b), place(c));
            let off = pow2(-((g.next() % 61) as i64));
            let e1 = [0, 1, 2].map(|k| b[k] - a[k]);
            let e2 = [0, 1, 2].map(|k| c[k] - a[k]);
            if kind == 2 {
                let along = [0.0, 0.5, unit(g).abs()][(g.next() % 3) as usize];
                let jitter = point(g);
                let target = [0, 1, 2].map(|k| a[k] + along * e1[k] + off * jitter[k]);
                let from = point(g);
                let origin = [0, 1, 2].map(|k| target[k] + 4.0 * from[k]);
                let (o, t) = (place(origin), place(target));
                (Ray::new(o, t - o), tri)
            } else {
                // n = e1 x e2, a direction in the plane plus `off` of n.
                let n = [
                    e1[1] * e2[2] - e1[2] * e2[1],
                    e1[2] * e2[0] - e1[0] * e2[2],
                    e1[0] * e2[1] - e1[1] * e2[0],
                ];
                let (x, y) = (unit(g), unit(g));
                let d = [0, 1, 2].map(|k| x * e1[k] + y * e2[k] + off * n[k]);
                let o = point(g);
                (Ray::new(place(o), v(d)), tri)
            }
        }
    }
}

fn same(x: &Option<ExactTriangle>, y: &Option<ExactTriangle>) -> bool {
    match (x, y) {
        (None, None) => true,
        (Some(x), Some(y)) => x.signs == y.signs && x.t == y.t && x.uv == y.uv,
        _ => false,
    }
}

#[test]
fn triangle_in_integers_is_the_rational_formulas() {
    fn check<V: Vector>(g: &mut Draws, kind: u64) -> (bool, bool) {
        let (ray, tri) = case::<V>(g, kind);
        let (fast, slow) = (triangle(&ray, &tri), triangle_reference(&ray, &tri));
        assert!(same(&fast, &slow), "{ray:?} {tri:?}: {fast:?} {slow:?}");
        (fast.is_none(), fast.is_some_and(|x| x.t.is_none()))
    }
    let mut g = Draws(0x2545_f491_4f6c_dd1d);
    let (mut invalid, mut parallel) = (0, 0);
    for i in 0..3000 {
        for (x, y) in [check::<Vec3>(&mut g, i % 4), check::<DVec3>(&mut g, i % 4)] {
            invalid += usize::from(x);
            parallel += usize::from(y);
        }
    }
    assert!(invalid > 50 && parallel > 3, "{invalid} {parallel}");
}

/// `segment_crossing` as it read before it was computed in integers, in
/// big rationals throughout: the reference it is held to.
fn segment_crossing_reference<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>) -> Option<R> {
    let k = main_axis(ray.dir);
    let (kx, ky) = ((k + 1) % 3, (k + 2) % 3);
    let (o, dir) = moving(ray)?;
    let corners = [rv(tri.a)?, rv(tri.b)?, rv(tri.c)?];
    let dist2 = |i: usize, j: usize| {
        let e = sub(&corners[j], &corners[i]);
        dot(&e, &e)
    };
    let (mut i, mut j) = (0, 1);
    for (a, b) in [(1, 2), (2, 0)] {
        if dist2(a, b) > dist2(i, j) {
            (i, j) = (a, b);
        }
    }
    let frame = |w: &[R; 3]| -> [R; 3] {
        let w = sub(w, &o);
        let z = &w[k] / &dir[k];
        [&w[kx] - &dir[kx] * &z, &w[ky] - &dir[ky] * &z, z]
    };
    let (p, q) = (frame(&corners[i]), frame(&corners[j]));
    let (ex, ey) = (&q[0] - &p[0], &q[1] - &p[1]);
    let den = &ex * &ex + &ey * &ey;
    if den.is_zero() {
        return None;
    }
    let s = -(&p[0] * &ex + &p[1] * &ey) / den;
    let s = s.clamp(R::zero(), int(1));
    Some(&p[2] + s * (&q[2] - &p[2]))
}

/// `segment_crossing` in integers against the rational formulas, on the
/// filter's cases and on zero-area triangles made from them (a corner
/// moved to the midpoint of the other two, or onto one of them).
#[test]
fn segment_crossing_in_integers_is_the_rational_formulas() {
    fn check<V: Vector>(g: &mut Draws, kind: u64) -> (bool, bool) {
        let (ray, tri) = case::<V>(g, kind);
        let half = V::Scalar::from_f64(0.5);
        let flat = match g.next() % 3 {
            0 => Triangle::new(tri.a, tri.b, (tri.a + tri.b) * half),
            1 => Triangle::new(tri.a, tri.b, tri.a),
            _ => tri,
        };
        let (fast, slow) = (
            segment_crossing(&ray, &flat),
            segment_crossing_reference(&ray, &flat),
        );
        assert_eq!(fast, slow, "{ray:?} {flat:?}");
        (fast.is_none(), fast.is_some())
    }
    let mut g = Draws(0x6a09_e667_f3bc_c908);
    let (mut none, mut some) = (0, 0);
    for i in 0..3000 {
        for (x, y) in [check::<Vec3>(&mut g, i % 4), check::<DVec3>(&mut g, i % 4)] {
            none += usize::from(x);
            some += usize::from(y);
        }
    }
    assert!(none > 50 && some > 3000, "{none} {some}");
}

/// `mt_bounds` as it read before it was computed in integers, in big
/// rationals throughout: the reference it is held to.
fn mt_bounds_reference<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    u: &R,
    v: &R,
) -> Option<(R, R, R)> {
    let (o, d) = (rv(ray.origin)?, rv(ray.dir)?);
    let (a, b, c) = (rv(tri.a)?, rv(tri.b)?, rv(tri.c)?);
    let (e1, e2, s) = (sub(&b, &a), sub(&c, &a), sub(&o, &a));
    let mag = |x: &[R; 3], y: &[R; 3], z: &[R; 3]| -> R {
        (0..3)
            .map(|i| {
                let (j, k) = ((i + 1) % 3, (i + 2) % 3);
                abs(&x[i]) * (abs(&(&y[j] * &z[k])) + abs(&(&y[k] * &z[j])))
            })
            .sum()
    };
    let g7 = gamma::<V::Scalar>(7);
    let det = dot(&e1, &cross(&d, &e2));
    let d_det = &g7 * mag(&e1, &d, &e2);
    let big = dyadic(1, 2000);
    if abs(&det) <= d_det {
        return Some((big.clone(), big.clone(), big));
    }
    let q = cross(&s, &e1);
    let t = dot(&e2, &q) / &det;
    let g2 = gamma::<V::Scalar>(2);
    let quotient = |dn: R, q: &R| (dn + abs(q) * &d_det) / (abs(&det) - &d_det) + &g2 * abs(q);
    Some((
        quotient(&g7 * mag(&s, &d, &e2), u),
        quotient(&g7 * mag(&d, &s, &e1), v),
        quotient(&g7 * mag(&e2, &s, &e1), &t),
    ))
}

/// `mt_bounds` in integers against the rational formulas, on the filter's
/// cases (with the exact barycentrics where the line crosses the plane,
/// and arbitrary ones where it does not).
#[test]
fn mt_bounds_in_integers_is_the_rational_formulas() {
    fn check<V: Vector>(g: &mut Draws, kind: u64) -> (bool, bool) {
        let (ray, tri) = case::<V>(g, kind);
        let (u, v) = triangle(&ray, &tri)
            .and_then(|x| x.uv)
            .unwrap_or_else(|| (dyadic(3, -2), dyadic(-5, -3)));
        let (fast, slow) = (
            mt_bounds(&ray, &tri, &u, &v),
            mt_bounds_reference(&ray, &tri, &u, &v),
        );
        assert_eq!(fast, slow, "{ray:?} {tri:?}");
        let big = dyadic(1, 2000);
        (fast.is_none(), fast.is_some_and(|b| b.0 != big))
    }
    let mut g = Draws(0xbb67_ae85_84ca_a73b);
    let (mut none, mut bounded) = (0, 0);
    for i in 0..3000 {
        for (x, y) in [check::<Vec3>(&mut g, i % 4), check::<DVec3>(&mut g, i % 4)] {
            none += usize::from(x);
            bounded += usize::from(y);
        }
    }
    assert!(none > 50 && bounded > 3000, "{none} {bounded}");
}

/// The filter's parts against exact arithmetic: every `f64` Plucker
/// product within its error bound of the exact one, and the margin
/// between its two float bounds (which are close: within `2^-40` of
/// it, plus the smallest subnormals they may round to).
#[test]
fn filter_bounds_hold() {
    fn check<V: Vector>(g: &mut Draws, kind: u64, tally: &mut [usize; 3]) {
        let (ray, tri) = case::<V>(g, kind);
        let Some(frame) = EdgeFrame::new(&ray, &tri) else {
            assert!(edge_function_bound(&ray, &tri).is_none());
            return;
        };
        let (de, dz) = edge_function_bound(&ray, &tri).unwrap();
        let margin = de * dz;
        let (lo, up) = (frame.margin(false), frame.margin(true));
        if up.is_finite() {
            let (rl, ru) = (r(lo).unwrap(), r(up).unwrap());
            assert!(rl <= margin && margin <= ru, "{ray:?} {tri:?}");
            let slack = &margin * dyadic(1, -40) + dyadic(1, -1070);
            assert!(ru - rl <= slack, "{lo:e} {up:e}: {ray:?} {tri:?}");
            tally[0] += 1;
        }
        let w = |p: V| [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()];
        let corners = [w(tri.a), w(tri.b), w(tri.c)];
        let (o, d) = (w(ray.origin), w(ray.dir));
        let ro = rv(ray.origin).unwrap();
        let p = [tri.a, tri.b, tri.c].map(|c| sub(&rv(c).unwrap(), &ro));
        let rd = rv(ray.dir).unwrap();
        for (i, (s, err)) in plucker_f64(o, d, corners).into_iter().enumerate() {
            if !(s.is_finite() && err.is_finite()) {
                continue;
            }
            let (j, k) = [(0, 1), (1, 2), (2, 0)][i];
            let exact = dot(&cross(&p[j], &p[k]), &rd);
            let off = abs_diff(&r(s).unwrap(), &exact);
            assert!(off <= r(err).unwrap(), "{s:e} {err:e}: {ray:?} {tri:?}");
            tally[1] += 1;
            tally[2] += usize::from(!off.is_zero());
        }
    }
    let mut g = Draws(0x9e37_79b9_7f4a_7c15);
    let mut tally = [0; 3];
    for i in 0..3000 {
        check::<Vec3>(&mut g, i % 4, &mut tally);
        check::<DVec3>(&mut g, i % 4, &mut tally);
    }
    // Most cases have a finite frame; many products round.
    std::println!("{tally:?}");
    assert!(
        tally[0] > 5000 && tally[1] > 15_000 && tally[2] > 5000,
        "{tally:?}"
    );
}

/// The filter against exact arithmetic on the same sample: wherever it
/// answers (with its error bounds alone, and with the exact expansions
/// too), it answers as `surely_outside_watertight_exact`. The sample
/// reaches both answers many times, and reaches products within the
/// error bounds of the margin, where the expansions decide.
#[test]
fn filter_agrees_with_exact_arithmetic() {
    #[derive(Debug, Default)]
    struct Tally {
        outside: usize,
        not_outside: usize,
        by_bounds: usize,
        by_expansions: usize,
        undecided: usize,
    }
    fn check<V: Vector>(g: &mut Draws, kind: u64, t: &mut Tally) {
        let (ray, tri) = case::<V>(g, kind);
        let exact = surely_outside_watertight_exact(&ray, &tri);
        let (bounds, full) = (filter(&ray, &tri, false), filter(&ray, &tri, true));
        for answer in [bounds, full] {
            assert!(
                answer.is_none_or(|x| x == exact),
                "filter {answer:?}, exact {exact}: {ray:?} {tri:?}"
            );
        }
        assert_eq!(surely_outside_watertight(&ray, &tri), exact);
        assert!(bounds.is_none() || full == bounds);
        t.outside += usize::from(exact);
        t.not_outside += usize::from(!exact);
        t.by_bounds += usize::from(bounds.is_some());
        t.by_expansions += usize::from(bounds.is_none() && full.is_some());
        t.undecided += usize::from(full.is_none());
    }
    let mut g = Draws(0x0123_4567_89ab_cdef);
    let mut t = Tally::default();
    for i in 0..4000 {
        check::<Vec3>(&mut g, i % 4, &mut t);
        check::<DVec3>(&mut g, i % 4, &mut t);
    }
    std::println!("{t:?}");
    assert!(
        t.outside > 4000 && t.not_outside > 1500 && t.by_expansions > 100,
        "{t:?}"
    );
    // Undecided only beyond the expansions' range (f64 inputs past
    // 2^+-300, kind 1) or strictly between the margin's float bounds.
    assert!(t.undecided * 50 < t.by_bounds, "{t:?}");
}

/// `triangle_clear_watertight` against `triangle_clear` and the
/// kernels: clear wherever `triangle_clear` is (and in more cases), and
/// where it is clear, every watertight form answers as exact arithmetic
/// (the closed and one-hit tests, plain, prepared and over `(0,
/// t_max]`).
#[test]
fn watertight_clear_is_triangle_clear_without_mt() {
    fn check<V: Vector>(g: &mut Draws, kind: u64, t: &mut [usize; 3]) {
        let (ray, tri) = case::<V>(g, kind);
        let t_max = if g.next().is_multiple_of(2) {
            V::Scalar::INFINITY
        } else {
            V::Scalar::from_f64(pow2((g.next() % 20) as i64 - 10))
        };
        let Some(ex) = triangle(&ray, &tri) else {
            assert!(!triangle_clear(&ray, &tri, t_max));
            return;
        };
        let (mt, wt) = (
            triangle_clear(&ray, &tri, t_max),
            triangle_clear_watertight(&ray, &tri, &ex, t_max),
        );
        assert!(!mt || wt, "clear with MT, not without: {ray:?} {tri:?}");
        t[0] += usize::from(mt);
        t[1] += usize::from(wt && !mt);
        if !(wt && ray.is_valid()) {
            return;
        }
        t[2] += 1;
        let expect = ex.hits(&limit(t_max));
        let prepared = crate::PreparedRay::new(&ray);
        let window = crate::Interval::up_to(t_max).unwrap();
        let answers = [
            crate::ray_triangle(&ray, &tri, t_max).is_some(),
            tri.hit(&ray, (t_max, EdgeRule::OneHit)).is_some(),
            tri.hit(&prepared, t_max).is_some(),
            tri.hit(&ray, window).is_some(),
            tri.hit(&ray, (window, EdgeRule::OneHit)).is_some(),
            tri.hit(&prepared, window).is_some(),
        ];
        assert!(
            answers.iter().all(|&a| a == expect),
            "{answers:?}, exact {expect}: {ray:?} {tri:?} {t_max:?}"
        );
    }
    let mut g = Draws(0x5851_f42d_4c95_7f2d);
    let mut t = [0; 3];
    for i in 0..3000 {
        check::<Vec3>(&mut g, i % 4, &mut t);
        check::<DVec3>(&mut g, i % 4, &mut t);
    }
    std::println!("{t:?}");
    assert!(t[0] > 2000 && t[1] > 200 && t[2] > 4000, "{t:?}");
}

/// A line nearly parallel to a tilted triangle's plane, passing far
/// from it: Moller-Trumbore's determinant (`d . n`, a few `f32` ulps
/// of `d`'s components, which are near 1) is within its error bound of
/// zero, so `triangle_clear` cannot call it; seen along the ray, the
/// triangle is a sliver far from the ray's point, whose two long edges'
/// functions have opposite signs well beyond their rounding, so
/// `triangle_clear_watertight` can.
#[test]
fn nearly_parallel_far_miss_is_clear_for_the_watertight_test_only() {
    let (a, b, c) = (Vec3::ZERO, Vec3::ONE, Vec3::new(1.0, -1.0, 0.5));
    let tri = Triangle::new(a, b, c);
    // n = (b - a) x (c - a) = (1.5, 0.5, -2); d is b - a and a few ulps
    // of n: d . n = 3.5 2^-23.
    let eps = f32::EPSILON;
    let d = Vec3::new(1.0 + eps, 1.0, 1.0 - eps);
    // From c + 2 (c - a) + n, along b - a: off the plane by |n|, and
    // (along the plane) three times as far from the edge a-b as c.
    let ray = Ray::new(Vec3::new(4.5, -2.5, -0.5), d);
    let ex = triangle(&ray, &tri).unwrap();
    assert!(ex.t.is_some() && !ex.line_hits());
    let (ue, ve) = ex.uv.clone().unwrap();
    let (eu, ev, _) = mt_bounds(&ray, &tri, &ue, &ve).unwrap();
    assert!(eu > int(1) && ev > int(1), "MT's bounds are not wide here");
    assert!(!triangle_clear(&ray, &tri, f32::INFINITY));
    assert!(triangle_clear_watertight(&ray, &tri, &ex, f32::INFINITY));
    assert_eq!(surely_outside_watertight_filter(&ray, &tri), Some(true));
    assert!(crate::ray_triangle(&ray, &tri, f32::INFINITY).is_none());
}

/// `exact::ray_triangle_from_exact` is `exact::ray_triangle`, and its
/// side (from the edge products' signs) is the sign of `dir . n`.
#[test]
fn answer_from_exact_is_ray_triangle() {
    fn check<V: Vector>(g: &mut Draws, kind: u64) -> usize {
        let (ray, tri) = case::<V>(g, kind);
        let t_max = V::Scalar::INFINITY;
        let direct = crate::exact::ray_triangle(&ray, &tri, t_max);
        let given = triangle(&ray, &tri)
            .and_then(|ex| crate::exact::ray_triangle_from_exact(&ray, &tri, &ex, t_max));
        assert_eq!(direct, given, "{ray:?} {tri:?}");
        let Some(hit) = direct else { return 0 };
        let (a, b, c) = (rv(tri.a).unwrap(), rv(tri.b).unwrap(), rv(tri.c).unwrap());
        let n = cross(&sub(&b, &a), &sub(&c, &a));
        let front = dot(&rv(ray.dir).unwrap(), &n).is_negative();
        assert_eq!(hit.side == crate::Side::Front, front, "{ray:?} {tri:?}");
        1
    }
    let mut g = Draws(0x6a09_e667_f3bc_c909);
    let mut hits = 0;
    for i in 0..2000 {
        hits += check::<Vec3>(&mut g, i % 4) + check::<DVec3>(&mut g, i % 4);
    }
    assert!(hits > 500, "{hits}");
}

/// `nearest_float` on values known only by comparison agrees with the
/// rounding of the exact value (`exact::round`): quotients of floats
/// (ties between floats among them), near `MAX` and beyond it, subnormal,
/// from estimates right, wild, infinite and NaN.
#[test]
fn nearest_float_rounds_as_round_does() {
    fn check<F: Scalar>(v: &R, estimate: f64) {
        let got: F = nearest_float(estimate, |x| v.cmp(x));
        let want: F = crate::exact::round(v);
        assert_eq!(
            got.to_f64().to_bits(),
            want.to_f64().to_bits(),
            "{v} from {estimate}"
        );
    }
    let mut draws = Draws(5);
    let max32 = r(f32::MAX).unwrap();
    let max64 = r(f64::MAX).unwrap();
    let mut values = std::vec![
        dyadic(1, -149),
        dyadic(3, -150),
        dyadic(1, -1074),
        dyadic(1, 0) + dyadic(1, -24),
        dyadic(1, 0) + dyadic(3, -53),
        &max32 + dyadic(1, 102),
        &max32 + dyadic(1, 103),
        &max64 + dyadic(1, 970),
        R::new(1.into(), 3.into()),
    ];
    for _ in 0..200 {
        let (p, q) = (draws.coordinate(60).abs(), draws.coordinate(60).abs());
        if let (Some(p), Some(q)) = (r(p), r(q))
            && !q.is_zero()
            && p.is_positive()
        {
            values.push(p / q);
        }
    }
    for v in &values {
        let e = to_f64(v);
        for estimate in [e, e * 1e30, e * 1e-30, f64::INFINITY, f64::NAN, -1.0] {
            check::<f32>(v, estimate);
            check::<f64>(v, estimate);
        }
    }
}
