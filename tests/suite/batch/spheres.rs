//! `SphereBatch::hit` against `Sphere::hit`, lane by lane, bit for bit.
//!
//! Each case is a ray from the sphere cases (`sphere::case`: far spheres,
//! grazing rays, rays from inside) and a batch of 4, 8 or 16 lanes: the
//! case's sphere, copies of it moved along the ray (several hits at
//! different `t`) and scaled, the ray's origin inside one, spheres of the
//! other cases, bad spheres (a NaN or infinite centre or radius, radius
//! zero or negative) and empty lanes; `t_max` infinite, finite, zero,
//! negative or NaN. Every lane must be the scalar answer (hit or miss,
//! `t`'s bits, the side), through a plain ray, a prepared one, a prepared
//! ray on the target's instruction set and one through `with_simd` (the
//! AVX2 copy where the CPU has it); the interval form lane by lane too.
//! 2,000 cases per precision, times `RAYHIT_CASES`.

use crate::sphere::{Kind, case};
use rayhit::batch::{Simd, SimdWork, SphereBatch, SphereBatchHits, TargetSimd, with_simd};
use rayhit::glam::{DVec3, Vec3};
use rayhit::{Intersect, IntersectLanes, Interval, PreparedRay, Ray, Scalar, Sphere, Vector};
use rayhit_testkit::case_count;
use rayhit_testkit::rng::Pcg32;

type S<V> = <V as Vector>::Scalar;

/// The batch through `with_simd`.
struct ViaWithSimd<'a, V: Vector, const N: usize> {
    ray: &'a PreparedRay<V>,
    batch: &'a SphereBatch<V, N>,
    t_max: S<V>,
}

impl<V: Vector, const N: usize> SimdWork for ViaWithSimd<'_, V, N> {
    type Output = SphereBatchHits<S<V>, N>;
    #[inline(always)]
    fn run<I: Simd>(self, simd: I) -> Self::Output {
        self.batch.hit(&simd.ray(self.ray), self.t_max)
    }
}

fn same<F: Scalar>(a: Option<rayhit::SphereHit<F>>, b: Option<rayhit::SphereHit<F>>) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(x), Some(y)) => x.side == y.side && x.t.to_f64().to_bits() == y.t.to_f64().to_bits(),
        _ => false,
    }
}

fn check<V: Vector, const N: usize>(ray: &Ray<V>, lanes: &[Option<Sphere<V>>], t_max: S<V>) -> u32 {
    let mut batch = SphereBatch::<V, N>::empty();
    for (lane, s) in lanes.iter().enumerate().take(N) {
        if let Some(s) = s {
            batch.set(lane, s);
        }
    }
    let prepared = PreparedRay::new(ray);
    let answers = [
        batch.hit(ray, t_max),
        batch.hit(&prepared, t_max),
        batch.hit(&TargetSimd.ray(&prepared), t_max),
        with_simd(ViaWithSimd {
            ray: &prepared,
            batch: &batch,
            t_max,
        }),
    ];
    for hits in &answers {
        for lane in 0..N {
            let expected = match lanes.get(lane) {
                Some(Some(s)) => s.hit(ray, t_max),
                _ => None,
            };
            assert!(
                same(hits.get(lane), expected),
                "lane {lane} of {N}: batch {:?}, scalar {expected:?}; {ray:?} {:?} t_max {t_max:?}",
                hits.get(lane),
                lanes.get(lane)
            );
            if expected.is_none() {
                assert_eq!(hits.t[lane].to_f64(), f64::INFINITY);
            }
        }
        assert_eq!(hits.mask, answers[0].mask);
    }
    if let Some(window) = Interval::new(S::<V>::ZERO, t_max) {
        let hits = batch.hit(ray, window);
        for lane in 0..N {
            let expected = match lanes.get(lane) {
                Some(Some(s)) => s.hit(ray, window),
                _ => None,
            };
            assert!(same(hits.get(lane), expected), "interval lane {lane}");
        }
        assert_eq!(batch.occluded(ray, window), hits.mask != 0);
    }
    answers[0].mask
}

fn run<V: Vector>(seed: u64) -> (usize, usize) {
    let mut rng = Pcg32::new(seed);
    let kinds = [Kind::Aimed, Kind::Grazing, Kind::Inside];
    let (mut lanes_hit, mut lanes_all) = (0, 0);
    let f = S::<V>::from_f64;
    for i in 0..case_count(2_000) {
        let (ray, s) = case::<V>(&mut rng, kinds[i % 3]);
        let (_, other) = case::<V>(&mut rng, kinds[(i + 1) % 3]);
        let along = |t: f64| Sphere::new(s.center + ray.dir * f(t), s.radius);
        let mut lanes: Vec<Option<Sphere<V>>> = vec![
            Some(s),
            Some(along(2.0)),
            Some(along(-3.0)),
            Some(Sphere::new(s.center, s.radius * f(0.5))),
            Some(Sphere::new(ray.origin, s.radius)),
            Some(other),
            None,
            Some(Sphere::new(s.center, -s.radius)),
            Some(Sphere::new(s.center, S::<V>::ZERO)),
            Some(Sphere::new(
                V::new(S::<V>::NAN, s.center.y(), s.center.z()),
                s.radius,
            )),
            Some(Sphere::new(s.center, S::<V>::INFINITY)),
            Some(Sphere::new(
                ray.origin + ray.dir * f(0.25),
                s.radius * f(1e-3),
            )),
            Some(along(10.0)),
            None,
            Some(Sphere::new(s.center, s.radius * f(1e3))),
            Some(Sphere::new(
                V::new(S::<V>::INFINITY, s.center.y(), s.center.z()),
                s.radius,
            )),
        ];
        let rot = (i / 3) % lanes.len();
        lanes.rotate_left(rot);
        let t_max = [
            S::<V>::INFINITY,
            f(1.0),
            f(100.0),
            S::<V>::ZERO,
            f(-1.0),
            S::<V>::NAN,
        ][i % 6];
        let m = check::<V, 16>(&ray, &lanes, t_max);
        check::<V, 8>(&ray, &lanes, t_max);
        check::<V, 4>(&ray, &lanes, t_max);
        lanes_hit += m.count_ones() as usize;
        lanes_all += 16;
    }
    (lanes_hit, lanes_all)
}

#[test]
fn every_lane_is_the_scalar_answer_f32() {
    let (hit, all) = run::<Vec3>(51);
    assert!(hit > all / 10, "{hit} of {all}");
}

#[test]
fn every_lane_is_the_scalar_answer_f64() {
    let (hit, all) = run::<DVec3>(52);
    assert!(hit > all / 10, "{hit} of {all}");
}
