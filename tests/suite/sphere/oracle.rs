//! The sphere test against exact arithmetic, and the textbook test on the
//! same rays.
//!
//! For every case (see the module's documentation): over `(0, inf]` as an
//! interval the answer (entry, exit or none) is the exact verdict; the
//! `t_max` form reports only a crossing exactly ahead of the origin, on
//! the side it says, and drops the interval's answer only where that lies
//! within its error bound of `t = 0`; every reported `t` is within its
//! `hit_error` of the exact crossing (checked in big rationals). The
//! textbook test's false misses, false hits and `t` outside the kernel's
//! bound are counted and printed.
//!
//! 2,000 cases per kind and precision by default, times `RAYHIT_CASES`;
//! the long run: `cargo test --release --test suite sphere::oracle:: --
//! --ignored --nocapture` (200,000 per kind and precision).

use super::{Kind, S, case, exact, side_in, textbook, verdict, within};
use rayhit::glam::{DVec3, Vec3};
use rayhit::{Intersect, Interval, PreparedRay, Scalar, Surface, Vector};
use rayhit_testkit::case_count;
use rayhit_testkit::rng::Pcg32;

/// Failures counted for the textbook test.
#[derive(Default, Debug)]
struct Textbook {
    false_misses: usize,
    false_hits: usize,
    t_outside_bound: usize,
}

fn run<V: Vector>(kind: Kind, cases: usize, seed: u64) -> (usize, usize, Textbook) {
    let mut rng = Pcg32::new(seed);
    let mut tb = Textbook::default();
    let mut hits = 0;
    let mut touching = 0;
    let inf = S::<V>::INFINITY;
    let zero = S::<V>::ZERO;
    for _ in 0..cases {
        let (ray, s) = case::<V>(&mut rng, kind);
        let e = exact(&ray, &s);
        let all = Interval::up_to(inf).unwrap();
        let expected = verdict(&e, zero, inf);
        let within_range = s.hit(&ray, all);
        assert_eq!(
            within_range.map(|h| h.side),
            expected,
            "interval (0, inf]: {ray:?} {s:?}"
        );
        assert_eq!(within_range, s.hit(&PreparedRay::new(&ray), all));
        if let Some(h) = within_range {
            hits += 1;
            assert!(h.t > zero && h.t.is_finite());
            let err = s.hit_error(&ray, &h);
            // Brought into (0, inf]: within max(bound, succ(0) - 0).
            let err = if err > zero.next_up() {
                err
            } else {
                zero.next_up()
            };
            assert!(
                within(&e, h.side, h.t, err),
                "t outside its bound: {h:?} {err:?} {ray:?} {s:?}"
            );
        }
        let plain = s.hit(&ray, inf);
        if let (Some(h), false) = (plain, e.line_hits()) {
            // A false hit of a line within rounding of tangent: allowed.
            assert!(
                near_tangent::<V>(&ray, &s),
                "false hit: {h:?} {ray:?} {s:?}"
            );
            touching += 1;
            continue;
        }
        if let Some(h) = plain {
            assert!(h.t > zero && h.t.is_finite());
            assert!(
                side_in(&e, h.side, zero, inf),
                "not ahead: {h:?} {ray:?} {s:?}"
            );
            assert!(
                within(&e, h.side, h.t, s.hit_error(&ray, &h)),
                "t outside: {h:?} {ray:?} {s:?}"
            );
        }
        if plain.map(|h| h.side) != within_range.map(|h| h.side) {
            // Dropped as not surely ahead: the interval's crossing is
            // within its bound of 0.
            let h = within_range.expect("the t_max form reports only exact crossings");
            assert!(
                h.t <= s.hit_error(&ray, &h),
                "dropped: {h:?} {plain:?} {ray:?} {s:?}"
            );
        }
        // The textbook test, with One Weekend's `t > 0.001`.
        let t_min = S::<V>::from_f64(0.001);
        let ahead = verdict(&e, t_min, inf);
        match (textbook(&ray, &s, t_min), ahead) {
            (None, Some(_)) => tb.false_misses += 1,
            (Some(_), None) => tb.false_hits += 1,
            (Some((t, side)), Some(_)) => {
                let bound = s.hit(&ray, inf).map_or(zero, |h| s.hit_error(&ray, &h));
                if !within(&e, side, t, bound) {
                    tb.t_outside_bound += 1;
                }
            }
            (None, None) => {}
        }
    }
    (hits, touching, tb)
}

/// Whether the exact line passes within `32 u (|o - c|_1 + |kappa d|_1 + r)`
/// of the sphere (`kappa` where the line passes nearest the centre): the
/// miss test's band, with room to spare (its bound `e` is about `12 u` of
/// that sum), computed in `f64` from the exact values.
fn near_tangent<V: Vector>(ray: &rayhit::Ray<V>, s: &rayhit::Sphere<V>) -> bool {
    let w = |v: V| [v.x().to_f64(), v.y().to_f64(), v.z().to_f64()];
    let (o, d, c) = (w(ray.origin), w(ray.dir), w(s.center));
    let f = [o[0] - c[0], o[1] - c[1], o[2] - c[2]];
    let a = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    let kappa = -(f[0] * d[0] + f[1] * d[1] + f[2] * d[2]) / a;
    let l = [0, 1, 2].map(|i| f[i] + kappa * d[i]);
    let dist = (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt();
    let r = s.radius.to_f64().abs();
    let sum = f.iter().map(|x| x.abs()).sum::<f64>()
        + kappa.abs() * d.iter().map(|x| x.abs()).sum::<f64>()
        + r;
    (dist - r).abs() <= 32.0 * S::<V>::UNIT_ROUNDOFF.to_f64() * sum
}

fn check<V: Vector>(cases: usize) {
    let name = if S::<V>::UNIT_ROUNDOFF.to_f64() > 1e-10 {
        "f32"
    } else {
        "f64"
    };
    for (i, kind) in [Kind::Aimed, Kind::Grazing, Kind::Inside]
        .into_iter()
        .enumerate()
    {
        let (hits, touching, tb) = run::<V>(kind, cases, 7 + i as u64);
        eprintln!(
            "{name} {kind:?}: {cases} rays, {hits} hit, {touching} false hits within rounding of tangent; textbook: {tb:?}"
        );
        assert!(hits > cases / 4, "{hits}");
    }
}

#[test]
fn far_grazing_and_inside_f32() {
    check::<Vec3>(case_count(2_000));
}

#[test]
fn far_grazing_and_inside_f64() {
    check::<DVec3>(case_count(2_000));
}

#[test]
#[ignore = "long run: cargo test --release --test suite sphere::oracle:: -- --ignored --nocapture"]
fn long_run() {
    check::<Vec3>(200_000);
    check::<DVec3>(200_000);
}
