//! Sphere cases: a sphere, a ray at it and a `t_max`.

use rayhit::strategies;
use rayhit::{Ray, Scalar, Sphere, Vector};

use super::{S, add, c, far_offset, t_max, v};
use crate::source::Source;

/// One sphere case: the sphere, the ray and `t_max`.
pub type SphereCase<V> = (Sphere<V>, Ray<V>, S<V>);

/// A sphere and a ray from the crate's strategy
/// ([`strategies::sphere_and_ray`]: aimed at the surface, inside the ball
/// or just outside it, grazing, from inside), moved `10^3` to `10^7` away a
/// quarter of the time (the centre and the origin moved in `f64` and
/// rounded, so a far ray may no longer meet a small sphere), every position
/// and the radius scaled by `2^k`, `k` uniform in `[-40, 40]`, a quarter of
/// the time (exactly: the same geometry at another scale); and [`t_max`].
pub fn sphere<V: Vector>(src: &mut Source) -> SphereCase<V> {
    let (sph, ray) = src
        .draw(&strategies::sphere_and_ray::<V>())
        .unwrap_or_else(|| {
            let one = S::<V>::ONE;
            (
                Sphere::new(V::ZERO, one),
                Ray::new(V::splat(S::<V>::from_f64(-3.0)), V::splat(one)),
            )
        });
    let (sph, ray) = if src.one_in(4) {
        let offset = far_offset(src);
        (
            Sphere::new(v(add(c(sph.center), offset)), sph.radius),
            Ray::new(v(add(c(ray.origin), offset)), ray.dir),
        )
    } else {
        (sph, ray)
    };
    let (sph, ray) = if src.one_in(4) {
        let s = S::<V>::from_f64(src.pow2(-40, 40));
        (
            Sphere::new(sph.center * s, sph.radius * s),
            Ray::new(ray.origin * s, ray.dir),
        )
    } else {
        (sph, ray)
    };
    (sph, ray, t_max::<V>(src))
}
