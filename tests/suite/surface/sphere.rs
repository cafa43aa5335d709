//! Leaving a sphere: rays spawned from `Sphere::surface_point` and
//! shadow segments from it, held to exact arithmetic in both precisions,
//! with the textbook practice beside them.
//!
//! Hits are the `t_max` form's on the sphere cases (`sphere::case`: far
//! spheres, radii `1e-3` to `1e4`, rays aimed at them and from inside).
//! For each:
//!
//! - the surface point is within its error bound of the exact sphere
//!   (its distance from the sphere at most the bound's 1-norm, in big
//!   rationals);
//! - *spawned rays*, reflected (mirrored about the computed normal) and
//!   transmitted (the direction kept), where the direction is not within
//!   rounding of tangent (`spawn`'s precondition): along the normal
//!   (outward), the spawned ray meets the exact ball nowhere ahead and no
//!   form reports it, for every sphere, however small against its
//!   coordinates; against the normal (inward), for a radius above 64
//!   times the point's bound, the origin is exactly inside the ball, the
//!   interval form reports the far side, and so does the `t_max` form
//!   unless the far side lies within its bound of the origin;
//! - *segments*: between two points of the same sphere (a chord through
//!   the ball), `spawn_to` reports neither end (and exactly nothing is
//!   crossed in `(0, 1]`); to a point light outside, the start is never
//!   entered again (the exit of a light behind the horizon is the far
//!   side, reported as the exact verdict says).
//!
//! The textbook practice on the same hits (One Weekend: the point
//! `o + t d` unmoved, its normal `(p - c) / r`, and `t > 0.001`): a
//! reflected ray from outside that reports a hit is acne, a transmitted
//! ray that finds no far side is a hole; the counts print.
//!
//! 1,500 cases per kind and precision, times `RAYHIT_CASES`.

use crate::sphere::{Kind, S, case, exact, q, textbook, verdict, within};
use rayhit::exact::num_traits::Signed;
use rayhit::glam::{DVec3, Vec3};
use rayhit::{Intersect, Interval, Ray, Scalar, Side, Sphere, Surface, SurfacePoint, Vector};
use rayhit_testkit::case_count;
use rayhit_testkit::rng::Pcg32;

/// Whether `p.point` is within the 1-norm of `p.point_error` of the
/// exact sphere, in big rationals.
fn on_sphere<V: Vector>(p: &SurfacePoint<V>, s: &Sphere<V>) -> bool {
    let (mut d2, mut bound) = (q(S::<V>::ZERO), q(S::<V>::ZERO));
    for i in 0..3 {
        let d = q(p.point[i]) - q(s.center[i]);
        d2 += &d * &d;
        bound += q(p.point_error[i]);
    }
    let r = q(s.radius).abs();
    let outer = &r + &bound;
    let inner_ok = bound >= r || d2 >= (&r - &bound) * (&r - &bound);
    d2 <= &outer * &outer && inner_ok
}

/// `spawn`'s precondition: `|fl(w . n)|` above its rounding bound plus the
/// normal's error, with room (twice the bound, evaluated in `f64`).
fn clear_of_tangent<V: Vector>(w: V, p: &SurfacePoint<V>) -> bool {
    let u = S::<V>::UNIT_ROUNDOFF.to_f64();
    let (mut dot, mut bound) = (0.0, 0.0);
    for i in 0..3 {
        let (wi, ni) = (w[i].to_f64(), p.normal[i].to_f64());
        dot += wi * ni;
        bound += 4.0 * u * (wi * ni).abs() + wi.abs() * p.normal_error[i].to_f64();
    }
    dot.abs() > 2.0 * bound
}

#[derive(Default, Debug)]
struct Counts {
    hits: usize,
    reflected: usize,
    transmitted_in: usize,
    far_side_by_t_max: usize,
    skipped_small: usize,
    chords: usize,
    lights: usize,
    textbook_acne: usize,
    textbook_holes: usize,
}

fn run<V: Vector>(seed: u64) -> Counts {
    let mut rng = Pcg32::new(seed);
    let mut n = Counts::default();
    let inf = S::<V>::INFINITY;
    let zero = S::<V>::ZERO;
    let all = Interval::up_to(inf).unwrap();
    for kind in [Kind::Aimed, Kind::Inside] {
        for _ in 0..case_count(1_500) {
            let (ray, s) = case::<V>(&mut rng, kind);
            let Some(h) = s.hit(&ray, inf) else {
                continue;
            };
            n.hits += 1;
            let p = s.surface_point(&ray, &h);
            assert!(on_sphere(&p, &s), "{p:?} {s:?}");
            let normal = p.normal;
            // Outward (along the computed normal, clear of tangent): the
            // ray leaves the exact tangent plane at the exact point the
            // bounds stand for, and the ball lies behind that plane, so it
            // meets the ball nowhere ahead, whatever the sphere's size.
            // Inward: for a sphere larger than the point's bound, the
            // origin is exactly inside, and the far side is found.
            let largest = (0..3)
                .map(|i| p.point_error[i].to_f64())
                .fold(0.0, f64::max);
            let small = s.radius.to_f64().abs() <= 64.0 * largest;
            n.skipped_small += usize::from(small);
            let d = ray.dir;
            let reflected = d - normal * (S::<V>::TWO * d.dot(normal) / normal.dot(normal));
            for (w, reflection) in [(reflected, true), (d, false)] {
                if !clear_of_tangent(w, &p) {
                    continue;
                }
                let spawned = p.spawn(w);
                let e = exact(&spawned, &s);
                if w.dot(normal) > zero {
                    n.reflected += usize::from(reflection);
                    assert_eq!(verdict(&e, zero, inf), None, "{spawned:?} {s:?} {p:?}");
                    assert_eq!(s.hit(&spawned, inf), None, "{spawned:?} {s:?}");
                    assert_eq!(s.hit(&spawned, all), None);
                } else if !small {
                    n.transmitted_in += usize::from(!reflection);
                    assert!(e.k.is_negative(), "not inside: {spawned:?} {s:?}");
                    assert_eq!(verdict(&e, zero, inf), Some(Side::Back));
                    let far = s.hit(&spawned, all).expect("the far side");
                    assert_eq!(far.side, Side::Back);
                    match s.hit(&spawned, inf) {
                        Some(h) => {
                            n.far_side_by_t_max += 1;
                            assert_eq!(h.side, Side::Back);
                            assert!(within(&e, h.side, h.t, s.hit_error(&spawned, &h)));
                        }
                        None => assert!(far.t <= s.hit_error(&spawned, &far)),
                    }
                }
            }
            // A chord to another point of the sphere, and a light.
            let other = Ray::new(
                s.center + V::new(S::<V>::ZERO, S::<V>::ZERO, s.radius * S::<V>::from_f64(3.0)),
                V::new(
                    S::<V>::from_f64(f64::from(rng.unit()) - 0.5),
                    S::<V>::from_f64(f64::from(rng.unit()) - 0.5),
                    S::<V>::from_f64(-3.0),
                ) * s.radius.abs(),
            );
            if let (Some(h2), Side::Front) = (s.hit(&other, inf), h.side) {
                let p2 = s.surface_point(&other, &h2);
                if let Some((seg, range)) = p.spawn_to(&p2) {
                    n.chords += 1;
                    assert_eq!(
                        verdict(&exact(&seg, &s), zero, S::<V>::ONE),
                        None,
                        "{seg:?} {s:?}"
                    );
                    assert_eq!(s.hit(&seg, range), None, "{seg:?} {s:?}");
                }
            }
            let away = crate::sphere::unit(&mut rng);
            let reach = 1.5 + 8.0 * f64::from(rng.unit());
            let light = s.center
                + V::new(
                    S::<V>::from_f64(away[0]),
                    S::<V>::from_f64(away[1]),
                    S::<V>::from_f64(away[2]),
                ) * (s.radius.abs() * S::<V>::from_f64(reach));
            if let Some((seg, range)) = p.spawn_to_point(light) {
                n.lights += 1;
                let expected = verdict(&exact(&seg, &s), zero, S::<V>::ONE);
                assert_ne!(expected, Some(Side::Front), "{seg:?} {s:?}");
                assert_eq!(s.hit(&seg, range).map(|h| h.side), expected);
            }
            // The textbook practice on the same ray.
            if let (Some((t, Side::Front)), Side::Front) =
                (textbook(&ray, &s, S::<V>::from_f64(0.001)), h.side)
            {
                let at = ray.origin + ray.dir * t;
                let nrm = (at - s.center) * (S::<V>::ONE / s.radius);
                let w = d - nrm * (S::<V>::TWO * d.dot(nrm) / nrm.dot(nrm));
                if clear_of_tangent(w, &p)
                    && textbook(&Ray::new(at, w), &s, S::<V>::from_f64(0.001)).is_some()
                {
                    n.textbook_acne += 1;
                }
                if textbook(&Ray::new(at, d), &s, S::<V>::from_f64(0.001)).is_none() {
                    n.textbook_holes += 1;
                }
            }
        }
    }
    n
}

#[test]
fn spawned_rays_and_segments_f32() {
    let n = run::<Vec3>(41);
    eprintln!("f32: {n:?}");
    assert!(
        n.reflected > 1_000 && n.transmitted_in > 300 && n.chords > 300,
        "{n:?}"
    );
}

#[test]
fn spawned_rays_and_segments_f64() {
    let n = run::<DVec3>(42);
    eprintln!("f64: {n:?}");
    assert!(
        n.reflected > 1_000 && n.transmitted_in > 300 && n.chords > 300,
        "{n:?}"
    );
}
