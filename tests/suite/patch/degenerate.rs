//! Degenerate patches answer as their definition says: a planar
//! parallelogram as the [`Quad`] of its corners, a patch with a collapsed
//! edge as the [`Triangle`] of its other three corners; hit or miss the
//! same on every ray, with either edge rule; where both hit, a
//! parallelogram's `t`, `u` and `v` within the sum of the two shapes'
//! bounds of each other (each is within its own of the same exact
//! crossing), and a collapsed patch's `t` the triangle's, bit for bit.

use rayhit::glam::{DVec3, Vec3};
use rayhit::{
    EdgeRule, Intersect, Patch, PreparedRay, Quad, Ray, Scalar, Surface, Triangle, Vector,
};
use rayhit_testkit::case_count;
use rayhit_testkit::rng::Pcg32;

use crate::common::draw::{S, signed, v};

/// A random point in `[-1, 1]^3`.
fn point<V: Vector>(rng: &mut Pcg32) -> V {
    v::<V>(signed(rng), signed(rng), signed(rng))
}

/// A ray from a random origin three to five units out, aimed at `target`.
fn aimed<V: Vector>(rng: &mut Pcg32, target: V) -> Ray<V> {
    let origin = target + point::<V>(rng).normalize_or_zero() * S::<V>::from_f64(4.0);
    Ray::new(origin, target - origin)
}

/// A target near the parallelogram `corner + s e1 + t e2`: `s`, `t` in
/// `[-0.25, 1.25]`, a quarter of the time on an edge or a corner.
fn near<V: Vector>(rng: &mut Pcg32, corner: V, e1: V, e2: V) -> V {
    let mut w = || {
        let k = rng.below(8);
        if k < 2 {
            f64::from(k)
        } else {
            0.5 + 0.75 * signed(rng)
        }
    };
    let (s, t) = (w(), w());
    corner + e1 * S::<V>::from_f64(s) + e2 * S::<V>::from_f64(t)
}

/// Two values within `ea` and `eb` of one exact value: at most `ea + eb`
/// apart (in `f64`, where the difference of two floats of `V` and the
/// sum of the bounds are exact or rounded up by far less than either).
fn close<V: Vector>(a: S<V>, b: S<V>, ea: S<V>, eb: S<V>) -> bool {
    (a.to_f64() - b.to_f64()).abs() <= (ea.to_f64() + eb.to_f64()) * (1.0 + 1e-12)
}

fn parallelograms<V: Vector>(seed: u64) -> (usize, usize) {
    let mut rng = Pcg32::new(seed);
    let (mut hits, mut rays) = (0, 0);
    for _ in 0..case_count(4000) {
        // Corners on a dyadic grid, so that `c = b + d - a` exactly.
        let grid = |rng: &mut Pcg32| {
            let g = |rng: &mut Pcg32| f64::from(rng.below(64) as i32 - 32) / 16.0;
            v::<V>(g(rng), g(rng), g(rng))
        };
        let (a, e1, e2) = (grid(&mut rng), grid(&mut rng), grid(&mut rng));
        let quad = Quad::parallelogram(a, e1, e2);
        let patch = Patch::new(quad.a, quad.b, quad.d, quad.c);
        let target = near(&mut rng, a, e1, e2);
        let ray = aimed(&mut rng, target);
        rays += 1;
        for rule in [EdgeRule::Closed, EdgeRule::OneHit] {
            let search = (S::<V>::INFINITY, rule);
            let (p, q) = (patch.hit(&ray, search), quad.hit(&ray, search));
            assert_eq!(
                p.is_some(),
                q.is_some(),
                "{rule:?} {patch:?} {ray:?}: {p:?} {q:?}"
            );
            if let (Some(p), Some(q)) = (p, q) {
                hits += 1;
                assert_eq!(p.side, q.side, "{patch:?} {ray:?}");
                // The same exact crossing (the parallelogram is exactly
                // planar, its corners on a dyadic grid): each within its
                // own bounds of it, where those are finite.
                let (ep, eq) = (patch.hit_error(&ray, &p), quad.hit_error(&ray, &q));
                assert!(
                    close::<V>(p.t, q.t, ep.t, eq.t)
                        && close::<V>(p.u, q.u, ep.u, eq.u)
                        && close::<V>(p.v, q.v, ep.v, eq.v),
                    "{patch:?} {ray:?}: {p:?} {q:?} {ep:?} {eq:?}"
                );
            }
        }
    }
    (hits, rays)
}

fn collapsed<V: Vector>(seed: u64) -> (usize, usize) {
    let mut rng = Pcg32::new(seed);
    let (mut hits, mut rays) = (0, 0);
    for _ in 0..case_count(4000) {
        let (a, b, c) = (
            point::<V>(&mut rng),
            point::<V>(&mut rng),
            point::<V>(&mut rng),
        );
        // Each edge in turn collapsed: the patch is the triangle of the
        // three distinct corners, in the patch's winding.
        let (patch, tri) = match rng.below(4) {
            0 => (Patch::new(a, b, c, c), Triangle::new(a, b, c)),
            1 => (Patch::new(a, a, b, c), Triangle::new(a, c, b)),
            2 => (Patch::new(a, b, a, c), Triangle::new(a, b, c)),
            _ => (Patch::new(a, b, c, b), Triangle::new(a, b, c)),
        };
        let target = near(&mut rng, a, b - a, c - a);
        let ray = aimed(&mut rng, target);
        rays += 1;
        for rule in [EdgeRule::Closed, EdgeRule::OneHit] {
            let search = (S::<V>::INFINITY, rule);
            let (p, t) = (patch.hit(&ray, search), tri.hit(&ray, search));
            assert_eq!(
                p.is_some(),
                t.is_some(),
                "{rule:?} {patch:?} {ray:?}: {p:?} {t:?}"
            );
            if let (Some(p), Some(t)) = (p, t) {
                hits += 1;
                assert_eq!(p.side, t.side, "{patch:?} {ray:?}");
                // Tested as its triangle: the same `t`, bit for bit.
                assert_eq!(
                    p.t.to_f64().to_bits(),
                    t.t.to_f64().to_bits(),
                    "{patch:?} {ray:?}"
                );
            }
        }
    }
    (hits, rays)
}

#[test]
fn a_planar_parallelogram_is_its_quad() {
    for (hits, rays) in [parallelograms::<Vec3>(71), parallelograms::<DVec3>(72)] {
        println!("parallelograms: {hits} hits of {rays} rays (both rules)");
        assert!(hits > rays / 2, "{hits} of {rays}");
    }
}

#[test]
fn a_collapsed_edge_is_its_triangle() {
    for (hits, rays) in [collapsed::<Vec3>(73), collapsed::<DVec3>(74)] {
        println!("collapsed: {hits} hits of {rays} rays (both rules)");
        assert!(hits > rays / 4, "{hits} of {rays}");
    }
}

/// Invalid rays, plain or prepared, hit no patch: not one the prepared
/// stand-in (a ray from `+inf`) would reach if its origin were finite,
/// not one with a corner at the top of the range or beyond it, not a
/// collapsed one.
#[test]
fn invalid_rays_hit_no_patch() {
    let (nan, inf, max) = (f32::NAN, f32::INFINITY, f32::MAX);
    let bad = [
        Ray::new(Vec3::splat(nan), Vec3::X),
        Ray::new(Vec3::ZERO, Vec3::ZERO),
        Ray::new(Vec3::ZERO, Vec3::new(inf, 0.0, 0.0)),
        Ray::new(Vec3::splat(inf), Vec3::Z),
    ];
    let patch = |a: [f32; 3], b: [f32; 3], c: [f32; 3], d: [f32; 3]| {
        Patch::new(a.into(), b.into(), c.into(), d.into())
    };
    let patches = [
        patch(
            [-1.0, -1.0, 1.0],
            [1.0, -1.0, -1.0],
            [-1.0, 1.0, -1.0],
            [1.0, 1.0, 1.0],
        ),
        patch(
            [-max, -max, max],
            [max, -max, max],
            [-max, max, max],
            [max, max, max],
        ),
        patch(
            [0.0, 0.0, inf],
            [1.0, 0.0, 1.0],
            [0.0, 1.0, 1.0],
            [1.0, 1.0, 1.0],
        ),
        patch(
            [max, max, -max],
            [max, max, max],
            [inf, inf, 0.0],
            [max, max, 0.0],
        ),
        patch(
            [-1.0, -1.0, 1.0],
            [-1.0, -1.0, 1.0],
            [-1.0, 1.0, 1.0],
            [1.0, 1.0, 1.0],
        ),
    ];
    for ray in bad {
        let prepared = PreparedRay::new(&ray);
        for p in &patches {
            for rule in [EdgeRule::Closed, EdgeRule::OneHit] {
                let search = (inf, rule);
                assert_eq!(p.hit(&ray, search), None, "{ray:?} {p:?}");
                assert_eq!(p.hit(&prepared, search), None, "{ray:?} {p:?}");
                assert!(!p.occluded(&prepared, search), "{ray:?} {p:?}");
            }
        }
    }
}
