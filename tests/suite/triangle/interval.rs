//! The interval forms of the watertight tests (`Triangle::hit` over an
//! interval, on a `Ray` and on a `PreparedRay`, and with
//! `EdgeRule::OneHit`) held to exact arithmetic at the ends of their
//! intervals.
//!
//! - *Random ends*: triangles of every scale (1e-3 to 1e3) translated by up
//!   to 1e5, rays from a few triangle sizes away aimed at points of the
//!   triangle, its edges and corners, directions of any length
//!   (`2^-20` to `2^21` times the distance). The interval ends are the exact
//!   crossing `t*` rounded, and its neighbours a few ulps either side, as
//!   `t_min` and as `t_max`; the expected answer is "the inside test
//!   accepts, and `t*` is in the interval", with `t*` from `rayhit::exact`,
//!   and where the exact module says the inside decision is clear of
//!   rounding (`exact::oracle::triangle_clear`), `exact::ray_triangle_in`
//!   itself.
//! - *Exact ends*: triangles built so that the ray meets their plane at
//!   exactly a float `t0` (the centroid `p = o + t0 d` is exact, the corners
//!   are `p + e1`, `p + e2`, `p - e1 - e2`), checked with the exact module;
//!   `t0` as `t_min` is a miss and as `t_max` a hit, one ulp below the
//!   reverse; and the same triangle with one corner moved by an ulp, so
//!   that `t*` is a rational just beside `t0`.
//! - *Any-hit*: `Triangle::occluded`, on a `Ray` and on a `PreparedRay`,
//!   is `tri.hit(ray, window).is_some()` on every interval above.
//! - *Near the origin*: rays starting a few ulps off a triangle's centroid
//!   (its plane crossed at a tiny `t*` of either sign, or zero), along
//!   directions well away from the plane: with `(0, inf]` a hit exactly
//!   when `t* > 0`, including the hits the plain test drops because its
//!   sufficient tests cannot establish `t > 0`.
//! - *Relation to the plain test*: with `(0, t_max]`, a hit of
//!   `ray_triangle` is the interval form's hit, bit for bit, wherever
//!   `t*` is farther than the error bound from the ends; a hit only the
//!   interval form reports lies within the error bound of `t = 0`.
//!
//! 400 cases per generator and precision (a few seconds), times
//! `RAYHIT_CASES`.

use crate::common::draw::{f, point, signed, v};
use rayhit::exact::{self, oracle};
use rayhit::glam::{DVec3, Vec3};
use rayhit::{
    EdgeRule, Intersect, Interval, PreparedRay, Ray, Scalar, Surface, Triangle, TriangleHit,
    Vector, ray_triangle,
};
use rayhit_testkit::rng::Pcg32;

type S<V> = <V as Vector>::Scalar;

fn cases() -> usize {
    rayhit_testkit::case_count(400)
}

/// `x` moved by `k` ulps (up for `k > 0`).
fn step<F: Scalar>(x: F, k: i32) -> F {
    let mut x = x;
    for _ in 0..k.unsigned_abs() {
        x = if k > 0 { x.next_up() } else { x.next_down() };
    }
    x
}

fn bits<F: Scalar>(h: Option<TriangleHit<F>>) -> Option<(u64, u64, u64, rayhit::Side)> {
    h.map(|h| {
        (
            h.t.to_f64().to_bits(),
            h.u.to_f64().to_bits(),
            h.v.to_f64().to_bits(),
            h.side,
        )
    })
}

/// The three interval forms agree where they should (prepared = per call;
/// one-hit never hits where the closed test misses) and return `t` in the
/// interval; the closed answer is returned.
fn closed_in<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    i: Interval<S<V>>,
) -> Option<TriangleHit<S<V>>> {
    let hit = tri.hit(ray, i);
    // The any-hit forms: exactly whether there is a hit.
    assert_eq!(tri.occluded(ray, i), hit.is_some());
    assert_eq!(tri.occluded(&PreparedRay::new(ray), i), hit.is_some());
    assert_eq!(
        bits(tri.hit(&PreparedRay::new(ray), i)),
        bits(hit),
        "{ray:?} {tri:?} {i:?}"
    );
    // The one-hit rule: exactly where the moved line crosses the triangle
    // (exact arithmetic, `one_hit_line_hits`) at a `t*` in the interval.
    let one = tri.hit(ray, (i, EdgeRule::OneHit));
    let crossed = oracle::one_hit_line_hits(ray, tri) == Some(true) && {
        let t = oracle::triangle(ray, tri).and_then(|e| e.t).unwrap();
        let (lo, hi) = (i.min(), i.max());
        oracle::r(lo).unwrap() < t && (!hi.is_finite() || t <= oracle::r(hi).unwrap())
    };
    assert_eq!(
        one.is_some(),
        crossed,
        "one-hit against exact: {ray:?} {tri:?} {i:?}"
    );
    assert_eq!(
        bits(tri.hit(&PreparedRay::new(ray), (i, EdgeRule::OneHit))),
        bits(one),
        "one-hit, prepared: {ray:?} {tri:?} {i:?}"
    );
    if let Some(h) = one {
        assert!(i.contains(h.t));
    }
    if let Some(h) = hit {
        assert!(i.contains(h.t) && h.t.is_finite(), "{h:?} outside {i:?}");
        assert!(
            h.u >= S::<V>::ZERO && h.v >= S::<V>::ZERO && h.u <= S::<V>::ONE && h.v <= S::<V>::ONE
        );
    }
    hit
}

#[derive(Default, Debug)]
struct Tally {
    cases: usize,
    checked_ends: usize,
    inside: usize,
    /// Ends where the rounded `t` and `t*` are on different sides: a plain
    /// float comparison would have been wrong there.
    float_wrong: usize,
    clear: usize,
    only_interval: usize,
    /// Cases with `t* > 0`.
    positive: usize,
}

/// A triangle of size 1e-3 to 1e3 (the scale returned), centred at the
/// origin or translated by up to 1e5 (the centre returned).
fn random_triangle<V: Vector>(rng: &mut Pcg32) -> (Triangle<V>, f64, [f64; 3]) {
    let scale = 10f64.powi(rng.below(7) as i32 - 3);
    let far = 1e5 * f64::from(rng.below(3)) / 2.0;
    let centre = [far * signed(rng), far * signed(rng), far * signed(rng)];
    let tri = Triangle::new(
        point::<V>(rng, scale, centre),
        point::<V>(rng, scale, centre),
        point::<V>(rng, scale, centre),
    );
    (tri, scale, centre)
}

fn random_ends<V: Vector>(seed: u64) -> Tally {
    let mut rng = Pcg32::new(seed);
    let mut tally = Tally::default();
    let inf = S::<V>::INFINITY;
    let all = Interval::up_to(inf).unwrap();
    for _ in 0..cases() {
        let (tri, scale, centre) = random_triangle::<V>(&mut rng);
        // Aim at an interior point, an edge point or a corner.
        let (a, b, c) = (tri.a, tri.b, tri.c);
        let target = match rng.below(4) {
            0 => a,
            1 => (a + b) * f::<V>(0.5),
            _ => {
                let (s, t) = (f::<V>(f64::from(rng.unit())), f::<V>(f64::from(rng.unit())));
                a + (b - a) * (s * f::<V>(0.5)) + (c - a) * (t * f::<V>(0.5))
            }
        };
        let origin = point::<V>(&mut rng, 4.0 * scale, centre);
        // A direction of any length: its scale and the triangle's differ.
        let length = (1.0 + signed(&mut rng).abs()) * 2f64.powi(rng.below(41) as i32 - 20);
        let dir = (target - origin) * f::<V>(length);
        let ray = Ray::new(origin, dir);
        if !ray.is_valid() {
            continue;
        }
        let ex = oracle::triangle(&ray, &tri).unwrap();
        let Some(t_exact) = ex.t.clone() else {
            continue;
        };
        if t_exact <= oracle::r(S::<V>::ZERO).unwrap() {
            continue;
        }
        tally.cases += 1;
        let inside = closed_in(&ray, &tri, all);
        let clear = oracle::triangle_clear(&ray, &tri, inf);
        tally.clear += usize::from(clear);
        if clear {
            assert_eq!(
                inside.is_some(),
                exact::ray_triangle(&ray, &tri, inf).is_some(),
                "{ray:?} {tri:?}"
            );
        }
        // Relation to the plain test, with (0, inf].
        let plain = ray_triangle(&ray, &tri, inf);
        match (plain, inside) {
            (Some(_), _) => assert_eq!(bits(plain), bits(inside), "{ray:?} {tri:?}"),
            (None, Some(h)) => {
                tally.only_interval += 1;
                let err = tri.hit_error(&ray, &h).t;
                assert!(
                    h.t <= err,
                    "plain test dropped a hit far from 0: {h:?} err {err:?} {ray:?} {tri:?}"
                );
            }
            (None, None) => {}
        }
        let Some(hit) = inside else { continue };
        tally.inside += 1;
        let t0 = exact::round::<S<V>>(&t_exact);
        for k in -2..=2 {
            let end = step(t0, k);
            if !(end >= S::<V>::ZERO) {
                continue;
            }
            let above = oracle::r(end).unwrap() < t_exact;
            tally.checked_ends += 1;
            tally.float_wrong += usize::from((hit.t > end) != above);
            // As t_min, and as t_max.
            let lower = Interval::new(end, inf).unwrap();
            let upper = Interval::up_to(end).unwrap();
            assert_eq!(
                closed_in(&ray, &tri, lower).is_some(),
                above,
                "t_min {end:?} t* {t_exact} {ray:?} {tri:?}"
            );
            assert_eq!(
                closed_in(&ray, &tri, upper).is_some(),
                !above,
                "t_max {end:?} t* {t_exact} {ray:?} {tri:?}"
            );
            if clear {
                assert_eq!(
                    closed_in(&ray, &tri, lower).is_some(),
                    exact::ray_triangle_in(&ray, &tri, end, inf).is_some()
                );
                assert_eq!(
                    closed_in(&ray, &tri, upper).is_some(),
                    exact::ray_triangle_in(&ray, &tri, S::<V>::ZERO, end).is_some()
                );
            }
        }
    }
    tally
}

fn exact_ends<V: Vector>(seed: u64) -> Tally {
    let mut rng = Pcg32::new(seed);
    let mut tally = Tally::default();
    let inf = S::<V>::INFINITY;
    // A value on a grid of 2^-k, from few bits, so that sums and products stay exact.
    let grid = |rng: &mut Pcg32, bits: u32, k: i32| {
        (f64::from(rng.below(1 << bits)) - f64::from(1u32 << (bits - 1))) * 2f64.powi(-k)
    };
    for _ in 0..cases() {
        let big = if rng.below(2) == 0 { 0.0 } else { 65536.0 };
        let o = v::<V>(
            big + grid(&mut rng, 10, 4),
            grid(&mut rng, 10, 4),
            grid(&mut rng, 10, 4),
        );
        let d = v::<V>(
            grid(&mut rng, 8, 3),
            grid(&mut rng, 8, 3),
            grid(&mut rng, 8, 3),
        );
        let t0 = f::<V>(f64::from(1 + rng.below(1 << 10)) * 2f64.powi(-6));
        let p = o + d * t0;
        let edge = |rng: &mut Pcg32| {
            let size = 2.0f64.powi(rng.below(8) as i32 - 4);
            point::<V>(rng, size, [0.0; 3])
        };
        let (e1, e2) = (edge(&mut rng), edge(&mut rng));
        let tri = Triangle::new(p + e1, p + e2, p - e1 - e2);
        let ray = Ray::new(o, d);
        if !ray.is_valid() {
            continue;
        }
        // The construction is exact only where no sum above rounded: ask.
        let ex = oracle::triangle(&ray, &tri).unwrap();
        if ex.t != Some(oracle::r(t0).unwrap()) || !ex.line_hits() {
            continue;
        }
        tally.cases += 1;
        let Some(hit) = closed_in(&ray, &tri, Interval::up_to(inf).unwrap()) else {
            continue;
        };
        tally.inside += 1;
        tally.float_wrong += usize::from(hit.t != t0);
        let below = t0.next_down();
        let check = |i: Interval<S<V>>, expected: bool| {
            assert_eq!(
                closed_in(&ray, &tri, i).is_some(),
                expected,
                "{i:?} t* = {t0:?} {ray:?} {tri:?}"
            );
            assert_eq!(
                tri.hit(&ray, (i, EdgeRule::OneHit)).is_some(),
                expected
                    && tri
                        .hit(&ray, (Interval::up_to(inf).unwrap(), EdgeRule::OneHit))
                        .is_some()
            );
        };
        check(Interval::new(t0, inf).unwrap(), false);
        check(Interval::new(below, inf).unwrap(), true);
        check(Interval::up_to(t0).unwrap(), true);
        check(Interval::up_to(below).unwrap(), false);
        check(Interval::new(below, t0).unwrap(), true);
        check(Interval::new(t0, t0).unwrap(), false);
        tally.checked_ends += 6;
        // One corner moved by an ulp: t* is a rational beside t0.
        let mut moved = tri;
        moved.c = V::new(
            step(tri.c.x(), 1 - 2 * rng.below(2) as i32),
            tri.c.y(),
            tri.c.z(),
        );
        let ex = oracle::triangle(&ray, &moved).unwrap();
        let Some(t_moved) = ex.t else { continue };
        let Some(inside) = closed_in(&ray, &moved, Interval::up_to(inf).unwrap()) else {
            continue;
        };
        for end in [below, t0, t0.next_up()] {
            let above = oracle::r(end).unwrap() < t_moved;
            tally.checked_ends += 1;
            tally.float_wrong += usize::from((inside.t > end) != above);
            assert_eq!(
                closed_in(&ray, &moved, Interval::new(end, inf).unwrap()).is_some(),
                above
            );
            assert_eq!(
                closed_in(&ray, &moved, Interval::up_to(end).unwrap()).is_some(),
                !above
            );
        }
    }
    tally
}

/// Rays starting within rounding of the triangle, near its centroid (so
/// that the line surely crosses its interior), along directions well away
/// from its plane: `t*` is a tiny positive or negative number, or zero.
/// The plain test drops the hits whose `t > 0` it cannot establish; the
/// interval form with `(0, inf]` hits exactly when `t* > 0`.
fn near_origin<V: Vector>(seed: u64) -> Tally {
    let mut rng = Pcg32::new(seed);
    let mut tally = Tally::default();
    let inf = S::<V>::INFINITY;
    let all = Interval::up_to(inf).unwrap();
    for _ in 0..cases() {
        let (tri, ..) = random_triangle::<V>(&mut rng);
        let third = f::<V>(1.0 / 3.0);
        let mut origin = (tri.a + tri.b + tri.c) * third;
        // A few ulps off, on one axis.
        let axis = rng.below(3) as usize;
        let k = rng.below(9) as i32 - 4;
        let moved = step(origin[axis], k);
        origin = match axis {
            0 => V::new(moved, origin.y(), origin.z()),
            1 => V::new(origin.x(), moved, origin.z()),
            _ => V::new(origin.x(), origin.y(), moved),
        };
        let n = tri.normal();
        let dir = point::<V>(&mut rng, 1.0, [0.0; 3]);
        // Well away from the plane: |cos| above 1/4.
        let (dn, len) = (
            dir.dot(n).to_f64(),
            dir.length().to_f64() * n.length().to_f64(),
        );
        if !(dn.abs() > 0.25 * len) {
            continue;
        }
        let ray = Ray::new(origin, dir);
        let ex = oracle::triangle(&ray, &tri).unwrap();
        let Some(t_exact) = ex.t.clone() else {
            continue;
        };
        // The line must cross the interior clearly: every edge's product of
        // one sign (the centroid is far from the edges of a fat triangle;
        // slivers are skipped).
        if !ex.interior() || tri.is_degenerate() {
            continue;
        }
        tally.cases += 1;
        let positive = t_exact > oracle::r(S::<V>::ZERO).unwrap();
        let hit = closed_in(&ray, &tri, all);
        if positive {
            tally.positive += 1;
            tally.inside += usize::from(hit.is_some());
            assert!(
                hit.is_some(),
                "t* = {} > 0 missed: {ray:?} {tri:?}",
                oracle::to_f64(&t_exact)
            );
        } else {
            assert!(
                hit.is_none(),
                "t* = {} <= 0 hit: {ray:?} {tri:?}",
                oracle::to_f64(&t_exact)
            );
        }
        let plain = ray_triangle(&ray, &tri, inf);
        match (plain, hit) {
            (Some(_), _) => assert_eq!(bits(plain), bits(hit), "{ray:?} {tri:?}"),
            (None, Some(h)) => {
                tally.only_interval += 1;
                let err = tri.hit_error(&ray, &h).t;
                assert!(
                    h.t <= err,
                    "plain test dropped a hit far from 0: {h:?} {err:?}"
                );
            }
            (None, None) => {}
        }
    }
    tally
}

#[test]
fn near_origin_decided_exactly_f32() {
    let t = near_origin::<Vec3>(5);
    println!("f32 near origin: {t:?}");
    assert!(t.only_interval > 0 && t.inside > t.cases / 4, "{t:?}");
}

#[test]
fn near_origin_decided_exactly_f64() {
    let t = near_origin::<DVec3>(6);
    println!("f64 near origin: {t:?}");
    assert!(t.only_interval > 0 && t.inside > t.cases / 4, "{t:?}");
}

#[test]
fn random_ends_are_decided_exactly_f32() {
    let t = random_ends::<Vec3>(1);
    println!("f32 random ends: {t:?}");
    assert!(t.inside > t.cases / 3 && t.float_wrong > 0, "{t:?}");
}

#[test]
fn random_ends_are_decided_exactly_f64() {
    let t = random_ends::<DVec3>(2);
    println!("f64 random ends: {t:?}");
    assert!(t.inside > t.cases / 3 && t.float_wrong > 0, "{t:?}");
}

#[test]
fn exact_ends_are_decided_exactly_f32() {
    let t = exact_ends::<Vec3>(3);
    println!("f32 exact ends: {t:?}");
    assert!(t.inside > t.cases / 2 && t.cases > cases() / 4, "{t:?}");
}

#[test]
fn exact_ends_are_decided_exactly_f64() {
    let t = exact_ends::<DVec3>(4);
    println!("f64 exact ends: {t:?}");
    assert!(t.inside > t.cases / 2 && t.cases > cases() / 4, "{t:?}");
}

/// Bad input: no panic, a miss.
#[test]
fn bad_input_misses() {
    let tri = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
    let ray = Ray::new(Vec3::new(0.25, 0.25, 1.0), Vec3::NEG_Z);
    assert!(Interval::new(f32::NAN, 1.0).is_none());
    assert!(Interval::new(0.0, f32::NAN).is_none());
    assert!(Interval::new(2.0, 1.0).is_none());
    assert!(Interval::new(-1.0, 1.0).is_none());
    assert!(Interval::new(f32::NEG_INFINITY, 1.0).is_none());
    let all = Interval::up_to(f32::INFINITY).unwrap();
    assert_eq!(tri.hit(&ray, all).unwrap().t, 1.0);
    for bad in [
        Ray::new(Vec3::NAN, Vec3::NEG_Z),
        Ray::new(Vec3::ZERO, Vec3::ZERO),
        Ray::new(Vec3::ZERO, Vec3::INFINITY),
    ] {
        assert!(tri.hit(&bad, all).is_none());
        assert!(tri.hit(&bad, (all, EdgeRule::OneHit)).is_none());
        assert!(tri.hit(&PreparedRay::new(&bad), all).is_none());
    }
    let nan_tri = Triangle::new(Vec3::NAN, Vec3::X, Vec3::Y);
    assert!(nan_tri.hit(&ray, all).is_none());
    assert!(
        tri.hit(&ray, Interval::new(f32::INFINITY, f32::INFINITY).unwrap())
            .is_none()
    );
    assert!(exact::ray_triangle_in(&ray, &tri, 2.0, 1.0).is_none());
    assert!(exact::ray_triangle_in(&ray, &tri, f32::NAN, 1.0).is_none());
}
