//! The disc test against exact arithmetic, in `f32` and `f64`.
//!
//! Cases: discs and annuli with centres up to `1e5` from the origin,
//! radii `1e-3` to `1e4`, holes of a fifth to nine tenths of the radius,
//! normals of any direction and length; rays aimed at a point of the
//! disc's plane on either circle (the circle's point rounded, and moved
//! off it by a relative `1e-7` either way), inside the annulus, in the
//! hole and outside, from any direction or nearly along the plane (the
//! corpus's generator, `rayhit_testkit::cases::discs::far`). For
//! each, over `(0, inf]` as an interval the answer is the exact verdict
//! (the crossing ahead, within both closed circles, in big rationals),
//! with the exact side; every reported `t` is within its bound; the
//! `t_max` form reports only exact hits, and misses one only where the
//! ray is within rounding of parallel or the crossing within its bound of
//! the origin. A disc and the annulus around it that share the circle
//! leave no gap: every exact crossing within the annulus's outer circle
//! is reported by one of them (by both exactly on the shared circle).
//! The exact crossing of every hit lies in `Disc::bounds`, and rays
//! spawned from its surface point (reflected, or passing through) never
//! meet the disc again.
//! The textbook test (the plane's `t`, then `|p - c|^2 <= r^2` on the
//! rounded point) on the same rays: its false misses and false hits
//! print. 3,000 cases per precision, times `RAYHIT_CASES`.

use crate::sphere::q;
use rayhit::exact::num_traits::Signed;
use rayhit::exact::oracle::{ExactDisc, disc};
use rayhit::glam::{DVec3, Vec3};
use rayhit::{Disc, Intersect, Interval, Scalar, Surface, Vector};
use rayhit_testkit::case_count;
use rayhit_testkit::cases::discs::far;
use rayhit_testkit::source::Source;

type S<V> = <V as Vector>::Scalar;

fn within<F: Scalar>(e: &ExactDisc, t: F, err: F) -> bool {
    !err.is_finite() || (q(t) - &e.t).abs() <= q(err)
}

#[derive(Default, Debug)]
struct Counts {
    hits: usize,
    spawned: usize,
    dropped_near_origin_or_parallel: usize,
    shared_rim_crossings: usize,
    textbook_false_misses: usize,
    textbook_false_hits: usize,
}

fn run<V: Vector>(seed: u64) -> Counts {
    let mut src = Source::seeded(seed);
    let mut n = Counts::default();
    let inf = S::<V>::INFINITY;
    let zero = S::<V>::ZERO;
    let max = q(S::<V>::MAX);
    let all = Interval::up_to(inf).unwrap();
    for _ in 0..case_count(3_000) {
        let (d, ray, _) = far::<V>(&mut src);
        if !ray.is_valid() {
            continue;
        }
        let exact = disc(&ray, &d);
        let expected = exact
            .as_ref()
            .filter(|e| e.hit_in(&q(zero), Some(&max)))
            .map(|e| e.side);
        let got = d.hit(&ray, all);
        assert_eq!(got.map(|h| h.side), expected, "{ray:?} {d:?} {exact:?}");
        if let (Some(h), Some(e)) = (got, exact.as_ref()) {
            n.hits += 1;
            let err = d.hit_error(&ray, &h);
            let err = if err > zero.next_up() {
                err
            } else {
                zero.next_up()
            };
            assert!(within(e, h.t, err), "{h:?} {err:?} {ray:?} {d:?}");
            // The exact crossing is inside the disc's box.
            let b = d.bounds();
            for i in 0..3 {
                let p = q(ray.origin[i]) + &e.t * q(ray.dir[i]);
                assert!(
                    q(b.min[i]) <= p && p <= q(b.max[i]),
                    "box axis {i}: {d:?} {b:?}"
                );
            }
        }
        let plain = d.hit(&ray, inf);
        if let Some(h) = plain {
            let e = exact.as_ref().expect("a crossing");
            assert!(
                e.hit_in(&q(zero), None) && h.side == e.side,
                "{h:?} {ray:?} {d:?}"
            );
            assert!(within(e, h.t, d.hit_error(&ray, &h)));
            // Spawned rays, reflected and passing through (clear of
            // tangent), never meet the disc they left.
            let p = d.surface_point(&ray, &h);
            let nrm = d.normal;
            let reflected = ray.dir - nrm * (S::<V>::TWO * ray.dir.dot(nrm) / nrm.dot(nrm));
            for w in [reflected, ray.dir] {
                let dn = w.dot(nrm).abs();
                if dn > S::<V>::from_f64(4.0) * S::<V>::gamma_n(3) * w.abs().dot(nrm.abs()) {
                    let spawned = p.spawn(w);
                    assert!(
                        d.hit(&spawned, inf).is_none() && d.hit(&spawned, all).is_none(),
                        "{spawned:?} {d:?}"
                    );
                    n.spawned += 1;
                }
            }
        } else if let Some(h) = got {
            // Dropped: within rounding of parallel, or within the bound of 0.
            let dn = ray.dir.dot(d.normal).abs();
            let mag = ray.dir.abs().dot(d.normal.abs());
            let parallel = dn <= S::<V>::TWO * S::<V>::gamma_n(3) * mag;
            assert!(
                parallel || h.t <= d.hit_error(&ray, &h),
                "{h:?} {ray:?} {d:?}"
            );
            n.dropped_near_origin_or_parallel += 1;
        }
        // The disc inside the annulus, sharing its circle.
        let r = d.radius;
        let inner_disc = Disc::new(d.center, d.normal, r);
        let ring = Disc::annulus(d.center, d.normal, r * S::<V>::TWO, r);
        if let Some(e) = disc(&ray, &inner_disc) {
            let four = &e.outer2 * q(S::<V>::from_f64(4.0));
            if e.t > q(zero) && e.t <= max && e.dist2 <= four {
                let (a, b) = (inner_disc.hit(&ray, all), ring.hit(&ray, all));
                assert!(
                    a.is_some() || b.is_some(),
                    "a gap on the shared circle: {ray:?} {d:?}"
                );
                if e.dist2 == e.outer2 {
                    assert!(a.is_some() && b.is_some());
                    n.shared_rim_crossings += 1;
                }
            }
        }
        // The textbook test.
        let textbook = rayhit::ray_plane(&ray, &rayhit::Plane::new(d.center, d.normal), inf)
            .filter(|t| {
                let v = ray.at(*t) - d.center;
                let s = v.dot(v);
                s <= d.radius * d.radius && s >= d.inner_radius * d.inner_radius
            });
        match (textbook.is_some(), expected.is_some()) {
            (false, true) => n.textbook_false_misses += 1,
            (true, false) => n.textbook_false_hits += 1,
            _ => {}
        }
    }
    n
}

#[test]
fn discs_against_exact_f32() {
    let n = run::<Vec3>(61);
    eprintln!("f32: {n:?}");
    assert!(n.hits > 1_000, "{n:?}");
}

#[test]
fn discs_against_exact_f64() {
    let n = run::<DVec3>(62);
    eprintln!("f64: {n:?}");
    assert!(n.hits > 1_000, "{n:?}");
}
