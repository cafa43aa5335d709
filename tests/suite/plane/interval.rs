//! The interval form of the plane test (`Plane::hit` over an interval, on
//! a `Ray` and on a `PreparedRay`) held to exact arithmetic, in `f32`
//! (`Vec3`) and `f64` (`DVec3`).
//!
//! Planes, decided exactly. The cases: random planes (scales 1e-3 to 1e3,
//! translated by up to 1e5) and rays of any direction length; origins far
//! away (1e6 to 1e8); directions nearly parallel to the plane (the in-plane
//! part of a random vector, rounded, sometimes tilted by a few ulps), where
//! `ray_plane` drops most; directions exactly parallel (the ray lying in the
//! plane, or beside it); crossings at exactly a float `t0` (grid inputs);
//! and tiny inputs (everything scaled by a power of two until the products
//! underflow). For every window `(lo, hi]` with ends among 0, the exact
//! crossing `t*` rounded and two ulps either side, and others: a hit exactly
//! when `lo < t* <= min(hi, MAX)`, compared in big rationals, and, on the
//! first windows of each case, `rayhit::exact::ray_plane_in` itself. The
//! reported `t` is in the window and finite, equal to `ray_plane`'s
//! quotient where that is in the window, and otherwise the upper end (no
//! farther from `t*` than the quotient) or the lower end's successor (no
//! farther than the quotient or one ulp);
//! with `(0, t_max]` it is `ray_plane`'s answer bit for bit where the exact
//! module says the case is clear of rounding (`oracle::plane_clear`).
//!
//! Partitions: `[0, T]` cut at random points and at `t*` rounded and its
//! neighbours, and `(.., inf]` last: the plane is reported in exactly one
//! window when `t*` is in `(0, min(T, MAX)]` and in none otherwise.
//!
//! 150 cases per kind and precision (about 5 s for planes and boxes on 2
//! cores in the test profile), times `RAYHIT_CASES`. The long run and the
//! bad input, with the box's: `shapes::interval`.

use crate::common::draw::{f, point, signed};
use crate::common::window::{CASES, Tally, bits, ends, grid_v, in_window, partition, r, single};
use rayhit::exact::num_traits::Signed;
use rayhit::exact::{self, Rational, oracle};
use rayhit::glam::{DVec3, Vec3};
use rayhit::{Intersect, Interval, Plane, Ray, Scalar, Vector, ray_plane};
use rayhit_testkit::case_count;
use rayhit_testkit::rng::Pcg32;

type S<V> = <V as Vector>::Scalar;

/// A plane case of one of six kinds (see the file's docs).
fn plane_case<V: Vector>(rng: &mut Pcg32, kind: u32) -> (Ray<V>, Plane<V>) {
    let scale = 10f64.powi(rng.below(7) as i32 - 3);
    let far = 1e5 * f64::from(rng.below(3)) / 2.0;
    let centre = [far * signed(rng), far * signed(rng), far * signed(rng)];
    let normal_scale = 2f64.powi(rng.below(21) as i32 - 10);
    let normal = point::<V>(rng, normal_scale, [0.0; 3]);
    let p = point::<V>(rng, scale, centre);
    let length = 2f64.powi(rng.below(41) as i32 - 20);
    match kind {
        // Random, nearby.
        0 => {
            let o = point::<V>(rng, 4.0 * scale, centre);
            let target = point::<V>(rng, scale, centre);
            (
                Ray::new(o, (target - o) * f::<V>(length)),
                Plane::new(p, normal),
            )
        }
        // Far away.
        1 => {
            let d = 10f64.powi(6 + rng.below(3) as i32);
            let o = point::<V>(rng, d, centre);
            let target = point::<V>(rng, scale, centre);
            (
                Ray::new(o, (target - o) * f::<V>(length)),
                Plane::new(p, normal),
            )
        }
        // Nearly parallel: the in-plane part of a random vector, rounded,
        // sometimes tilted by a few ulps of itself towards the normal.
        2 => {
            let w = point::<V>(rng, 1.0, [0.0; 3]);
            let mut d = w - normal * (w.dot(normal) / normal.dot(normal));
            if rng.below(2) == 0 {
                let tilt = f::<V>(signed(rng) * 8.0) * S::<V>::UNIT_ROUNDOFF;
                d = d + normal * (tilt * d.length() / normal.length());
            }
            let o = point::<V>(rng, 4.0 * scale, centre);
            (Ray::new(o, d * f::<V>(length)), Plane::new(p, normal))
        }
        // Exactly parallel: `normal` orthogonal to `dir` in exact arithmetic
        // (the products `d_x d_y` cancel), the origin in the plane or not.
        3 => {
            let d = point::<V>(rng, 1.0, [0.0; 3]);
            let n = V::new(d.y(), -d.x(), S::<V>::ZERO);
            let o = if rng.below(2) == 0 {
                p
            } else {
                point::<V>(rng, 4.0 * scale, centre)
            };
            (Ray::new(o, d), Plane::new(p, n))
        }
        // A crossing at exactly a float `t0`: grid values, `p = o + t0 d`.
        4 => {
            let o = grid_v::<V>(rng, 10, 4);
            let d = grid_v::<V>(rng, 8, 3);
            let t0 = f::<V>(f64::from(1 + rng.below(1 << 10)) * 2f64.powi(-6));
            let n = grid_v::<V>(rng, 6, 2);
            (Ray::new(o, d), Plane::new(o + d * t0, n))
        }
        // Tiny: a random case scaled down until products underflow.
        _ => {
            let inner = rng.below(3);
            let (ray, plane) = plane_case::<V>(rng, inner);
            let k = if single::<V>() { 50 } else { 480 } + rng.below(30) as i32;
            let s = f::<V>(2f64.powi(-k));
            let n = f::<V>(2f64.powi(-(rng.below(20) as i32)));
            (
                Ray::new(ray.origin * s, ray.dir * s),
                Plane::new(plane.point * s, plane.normal * s * n),
            )
        }
    }
}

/// `ray_plane`'s quotient, computed as it computes it.
fn quotient<V: Vector>(ray: &Ray<V>, plane: &Plane<V>) -> S<V> {
    (plane.point - ray.origin).dot(plane.normal) / ray.dir.dot(plane.normal)
}

/// One window: the kernel against the exact crossing; the answer returned.
fn plane_window<V: Vector>(
    ray: &Ray<V>,
    plane: &Plane<V>,
    t_star: Option<&Rational>,
    lo: S<V>,
    hi: S<V>,
    with_exact_module: bool,
    tally: &mut Tally,
) -> Option<S<V>> {
    let window = Interval::new(lo, hi).unwrap();
    let got = plane.hit(ray, window);
    let expected = t_star.is_some_and(|t| in_window(t, lo, hi));
    assert_eq!(
        got.is_some(),
        expected,
        "({lo:?}, {hi:?}] t* = {:?}: {ray:?} {plane:?}",
        t_star.map(oracle::to_f64)
    );
    if with_exact_module {
        let cap = if hi < S::<V>::MAX { hi } else { S::<V>::MAX };
        assert_eq!(exact::ray_plane_in(ray, plane, lo, cap).is_some(), expected);
    }
    tally.windows += 1;
    let q = quotient(ray, plane);
    if t_star.is_some() {
        let q_in = q.is_finite() && in_window(&r(q), lo, hi);
        tally.float_wrong += usize::from(q_in != expected);
    }
    if let Some(t) = got {
        tally.hits += 1;
        let t_star = t_star.unwrap();
        assert!(
            window.contains(t) && t.is_finite(),
            "{t:?} outside {window:?}"
        );
        // (A quotient beyond MAX is out of reach of any window.)
        if window.contains(q) && q <= S::<V>::MAX {
            assert_eq!(bits(t), bits(q), "{ray:?} {plane:?} {window:?}");
        } else if q.is_finite() {
            // Brought in: to `hi`, no farther from t* than the quotient;
            // to `lo`'s successor, within the larger of that and one ulp.
            let dist = |x: S<V>| (r(x) - t_star).abs();
            let ulp = r(lo.next_up()) - r(lo);
            if q > hi {
                assert_eq!(bits(t), bits(hi));
                assert!(dist(t) <= dist(q), "{t:?} {q:?} {ray:?} {plane:?}");
            } else {
                assert_eq!(bits(t), bits(lo.next_up()));
                assert!(
                    dist(t) <= dist(q) || dist(t) <= ulp,
                    "{t:?} {q:?} ({lo:?}, {hi:?}] t* {} {ray:?} {plane:?}",
                    oracle::to_f64(t_star)
                );
            }
        }
    }
    got
}

pub fn plane_cases<V: Vector>(seed: u64, n: usize) -> Tally {
    let mut rng = Pcg32::new(seed);
    let mut tally = Tally::default();
    let inf = S::<V>::INFINITY;
    for kind in 0..6 {
        for _ in 0..n {
            let (ray, plane) = plane_case::<V>(&mut rng, kind);
            if !(ray.is_valid() && plane.point.is_finite() && plane.normal.is_finite()) {
                continue;
            }
            tally.cases += 1;
            let t_star = oracle::plane_t(&ray, &plane);
            if kind == 3 {
                assert!(t_star.is_none(), "{ray:?} {plane:?}");
            }
            if let Some(t) = &t_star {
                let plain = ray_plane(&ray, &plane, inf);
                let positive = *t > r(S::<V>::ZERO) && in_window(t, S::<V>::ZERO, inf);
                tally.dropped_by_plain += usize::from(plain.is_none() && positive);
                tally.exact_float += usize::from(
                    exact::round::<S<V>>(t) == S::<V>::ZERO || {
                        let t0 = exact::round::<S<V>>(t);
                        t0.is_finite() && r(t0) == *t
                    },
                );
            }
            let ends = ends::<V>(&mut rng, t_star.as_slice());
            for (i, &lo) in ends.iter().enumerate() {
                for &hi in ends[i..].iter().chain([&inf]) {
                    let first = i == 0 || hi == inf;
                    plane_window(&ray, &plane, t_star.as_ref(), lo, hi, first, &mut tally);
                }
            }
            // (0, t_max] against ray_plane, where the case is clear of
            // rounding. Not for the tiny kind: `Plane::hit_error` (and so
            // `plane_clear`) assumes no product underflows (the crate's
            // standing precondition of its error bounds), which those
            // cases break on purpose; the interval form does not assume it.
            let clear_of_underflow = kind != 5;
            for &t_max in ends.iter().chain([&inf]).filter(|_| clear_of_underflow) {
                let plain = ray_plane(&ray, &plane, t_max);
                if plain.is_some() && oracle::plane_clear(&ray, &plane, t_max) {
                    let window = Interval::up_to(t_max).unwrap();
                    assert_eq!(
                        plane.hit(&ray, window).map(bits),
                        plain.map(bits),
                        "{ray:?} {plane:?} {t_max:?}"
                    );
                    tally.plain_equal += 1;
                }
            }
            plane_partition(&mut rng, &ray, &plane, t_star.as_ref(), &mut tally);
        }
    }
    tally
}

fn plane_partition<V: Vector>(
    rng: &mut Pcg32,
    ray: &Ray<V>,
    plane: &Plane<V>,
    t_star: Option<&Rational>,
    tally: &mut Tally,
) {
    let cuts = partition::<V>(rng, t_star);
    let reports = cuts
        .windows(2)
        .filter(|w| plane.hit(ray, Interval::new(w[0], w[1]).unwrap()).is_some())
        .count();
    let expected = t_star.is_some_and(|t| in_window(t, S::<V>::ZERO, S::<V>::INFINITY));
    assert_eq!(reports, usize::from(expected), "{cuts:?} {ray:?} {plane:?}");
    tally.partitions += 1;
    tally.reported_once += reports;
}

#[test]
fn planes_are_decided_exactly_f32() {
    let t = plane_cases::<Vec3>(1, case_count(CASES));
    println!("f32 planes: {t:?}");
    assert!(
        t.hits > t.windows / 8 && t.float_wrong > 0 && t.dropped_by_plain > 0,
        "{t:?}"
    );
    assert!(t.exact_float > 0 && t.plain_equal > 0 && t.reported_once > t.partitions / 4);
}

#[test]
fn planes_are_decided_exactly_f64() {
    let t = plane_cases::<DVec3>(2, case_count(CASES));
    println!("f64 planes: {t:?}");
    assert!(
        t.hits > t.windows / 8 && t.float_wrong > 0 && t.dropped_by_plain > 0,
        "{t:?}"
    );
    assert!(t.exact_float > 0 && t.plain_equal > 0 && t.reported_once > t.partitions / 4);
}
