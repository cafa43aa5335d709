//! Leaving a quad: rays spawned from `Quad::surface_point`, reflected and
//! passing through, start strictly on the side of the quad's plane they
//! leave to (decided exactly) and never meet the quad again, for parallelograms lying
//! exactly in a plane (`z` constant: a Cornell box's walls) at scales
//! `1e-3` to `1e3` and offsets to `1e5`, rays aimed at their interiors,
//! edges, diagonals and corners. The textbook practice ("The Next Week":
//! the unmoved point and `t > 0.001`) is counted beside it.
//!
//! 2,000 cases per precision, times `RAYHIT_CASES`.

use rayhit::glam::{DVec3, Vec3};
use rayhit::{Intersect, Quad, Ray, Scalar, Surface, Vector};
use rayhit_testkit::case_count;
use rayhit_testkit::rng::Pcg32;

use crate::common::draw::{S, signed, v};
use crate::quad::textbook;

/// Hits, spawned rays, re-hits of rayhit's spawned rays, re-hits of the
/// textbook's rays.
fn check<V: Vector>() -> [usize; 4] {
    let mut rng = Pcg32::new(0x0051_5541 + S::<V>::UNIT_ROUNDOFF.to_f64().to_bits() % 83);
    let inf = S::<V>::INFINITY;
    let (mut hits, mut spawned, mut ours, mut theirs) = (0, 0, 0, 0);
    for k in 0..case_count(2_000) {
        let scale = 10f64.powf(3.0 * signed(&mut rng));
        let reach = [0.0, 1e2, 1e5][k % 3];
        let c = [0, 1, 2].map(|_| reach * signed(&mut rng));
        let mut edge = || v::<V>(scale * signed(&mut rng), scale * signed(&mut rng), 0.0);
        let (eu, ev) = (edge(), edge());
        // Every corner has z = c[2] exactly.
        let quad = Quad::parallelogram(v::<V>(c[0], c[1], c[2]), eu, ev);
        let (s, t) = (
            (signed(&mut rng) + 1.0) / 2.0,
            (signed(&mut rng) + 1.0) / 2.0,
        );
        let (s, t) = [(s, t), (s, 0.0), (s, s), (0.0, 0.0)][k % 4];
        let f = S::<V>::from_f64;
        let target = quad.a + eu * f(s) + ev * f(t);
        let dir = v::<V>(signed(&mut rng), signed(&mut rng), signed(&mut rng));
        if dir.z().abs() < f(0.05) {
            continue;
        }
        let away = f(scale * 4.0);
        let ray = Ray::new(target - dir * away, dir * away);
        let Some(hit) = quad.hit(&ray, inf) else {
            continue;
        };
        hits += 1;
        let here = quad.surface_point(&ray, &hit);
        // Reflected about the plane, and passing straight through.
        let reflected = V::new(ray.dir.x(), ray.dir.y(), -ray.dir.z());
        for out in [reflected, ray.dir] {
            spawned += 1;
            let leaving = here.spawn(out);
            // The origin is strictly on the side of the plane `out` points
            // to (exact: the plane is `z = c[2]`, a float).
            let off = leaving.origin.z() - quad.a.z();
            assert!(
                off != S::<V>::ZERO && (off > S::<V>::ZERO) == (out.z() > S::<V>::ZERO),
                "{quad:?} {ray:?} {leaving:?}"
            );
            ours += usize::from(quad.hit(&leaving, inf).is_some());
            let unmoved = Ray::new(ray.at(hit.t), out);
            theirs += usize::from(textbook(&unmoved, &quad, f(1e-3), inf).is_some());
        }
    }
    [hits, spawned, ours, theirs]
}

#[test]
fn spawned_rays_never_meet_the_quad_they_leave() {
    for (name, [hits, spawned, ours, theirs]) in
        [("f32", check::<Vec3>()), ("f64", check::<DVec3>())]
    {
        println!(
            "{name}: {hits} hits, {spawned} spawned rays: rayhit re-hits {ours}, \
             textbook (t > 0.001) re-hits {theirs}"
        );
        assert!(hits > case_count(2_000) / 2, "{hits}");
        assert_eq!(ours, 0);
    }
}
