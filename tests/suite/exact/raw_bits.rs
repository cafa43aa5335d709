//! `rayhit::exact` on raw float bits (NaN, infinities, subnormals, huge and
//! tiny values mixed): never a panic, never a NaN distance, invalid input a
//! miss; and its answers agree with its own verdicts.

use rayhit::exact::{self, Case, Claim, Verdict};
use rayhit::glam::{DVec3, Vec3};
use rayhit::{Aabb, Disc, Patch, Plane, Quad, Ray, Scalar, Sphere, Triangle, Vector};
use rayhit_testkit::case_count;
use rayhit_testkit::source::Source;

/// A float from raw bits, biased towards the interesting ones.
fn raw<F: Scalar>(rng: &mut Source) -> F {
    let pick = rng.below(8);
    let bits = rng.bits();
    let x = match pick {
        0 => f64::from(f32::from_bits(bits as u32)),
        1 => f64::from_bits(bits),
        2 => [0.0, -0.0, 1.0, -1.0, f64::INFINITY, f64::NAN][rng.below(6) as usize],
        _ => rng.range(-4.0, 4.0).round(),
    };
    F::from_f64(x)
}

fn vec<V: Vector>(rng: &mut Source) -> V {
    V::new(raw(rng), raw(rng), raw(rng))
}

/// A patch of raw corners, a quarter of the time with a collapsed edge
/// (one corner copied onto a neighbour: the triangle it is).
fn patch<V: Vector>(rng: &mut Source) -> Patch<V> {
    let mut c: [V; 4] = [0; 4].map(|_| vec(rng));
    if rng.one_in(4) {
        let (from, to) = [(0, 1), (1, 3), (2, 3), (0, 2)][rng.index(4)];
        c[to] = c[from];
    }
    Patch::new(c[0], c[1], c[2], c[3])
}

fn run<V: Vector>(n: usize) {
    let mut rng = Source::seeded(99);
    for _ in 0..n {
        let ray = Ray::new(vec::<V>(&mut rng), vec::<V>(&mut rng));
        let t_max: V::Scalar = raw(&mut rng);
        let cases = [
            Case::Box(ray, Aabb::new(vec(&mut rng), vec(&mut rng)), t_max),
            Case::Triangle(
                ray,
                Triangle::new(vec(&mut rng), vec(&mut rng), vec(&mut rng)),
                t_max,
            ),
            Case::Plane(ray, Plane::new(vec(&mut rng), vec(&mut rng)), t_max),
            Case::Sphere(ray, Sphere::new(vec(&mut rng), raw(&mut rng)), t_max),
            Case::Disc(
                ray,
                Disc::annulus(vec(&mut rng), vec(&mut rng), raw(&mut rng), raw(&mut rng)),
                t_max,
            ),
            Case::Quad(
                ray,
                Quad::new(vec(&mut rng), vec(&mut rng), vec(&mut rng), vec(&mut rng)),
                t_max,
            ),
            Case::Patch(ray, patch(&mut rng), t_max),
        ];
        for case in &cases {
            // The exact answer, as a claim: judged right, values within half an ulp.
            let answer = match case {
                Case::Box(r, b, t) => exact::ray_aabb(r, b, *t).map(|h| Claim::Box {
                    enter: h.enter.rounded,
                    exit: h.exit.rounded,
                }),
                Case::Triangle(r, tri, t) => {
                    exact::ray_triangle(r, tri, *t).map(|h| Claim::Triangle {
                        t: h.t.rounded,
                        u: h.u.rounded,
                        v: h.v.rounded,
                    })
                }
                Case::Plane(r, p, t) => {
                    exact::ray_plane(r, p, *t).map(|t| Claim::Plane { t: t.rounded })
                }
                Case::Sphere(r, s, t) => exact::ray_sphere(r, s, *t).map(|h| Claim::Sphere {
                    t: h.t,
                    side: h.side,
                }),
                Case::Disc(r, d, t) => exact::ray_disc(r, d, *t).map(|h| Claim::Disc {
                    t: h.t,
                    side: h.side,
                }),
                Case::Quad(r, q, t) => exact::ray_quad(r, q, *t).map(|h| Claim::Quad {
                    t: h.t.rounded,
                    u: h.u.rounded,
                    v: h.v.rounded,
                }),
                Case::Patch(r, p, t) => exact::ray_patch(r, p, *t).map(|h| Claim::Patch {
                    t: h.t,
                    u: h.u,
                    v: h.v,
                    side: h.side,
                }),
                _ => unreachable!("every case built above is matched"),
            };
            let valid = ray.is_valid() && t_max.partial_cmp(&t_max).is_some();
            assert!(valid || answer.is_none(), "{case:?}");
            let claim = answer.unwrap_or(Claim::Miss);
            let j = exact::judge(case, &claim, 0.5);
            assert_eq!(j.verdict, Verdict::Right, "{case:?}");
            assert!(!j.distance_ulps.is_nan(), "{case:?}");
            // Overflowing roundings (an exact t beyond MAX) are infinitely off.
            assert!(
                j.outside.is_empty() || j.errors.iter().any(|e| e.1.is_infinite()),
                "{case:?}: {j:?}"
            );
            // The opposite claim is wrong the right way.
            let other = if claim.is_hit() {
                Claim::Miss
            } else {
                Claim::Plane { t: V::Scalar::ONE }
            };
            let flipped = exact::judge(case, &other, 0.5).verdict;
            assert_eq!(
                flipped,
                if claim.is_hit() {
                    Verdict::FalseMiss
                } else {
                    Verdict::FalseHit
                }
            );
        }
    }
}

#[test]
fn raw_bits_f32() {
    run::<Vec3>(case_count(1500));
}

#[test]
fn raw_bits_f64() {
    run::<DVec3>(case_count(1500));
}
