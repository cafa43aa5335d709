//! Plane cases: a plane, a ray aimed at a point of it and a `t_max`.

use rayhit::strategies;
use rayhit::{Plane, Ray, Scalar, Vector};

use super::{S, add, aimed, c, far_offset, t_max, v};
use crate::source::Source;

/// One plane case: the plane, the ray and `t_max`.
pub type PlaneCase<V> = (Plane<V>, Ray<V>, S<V>);

/// A plane and a ray from the crate's strategy
/// ([`strategies::plane_and_ray`]), moved `10^3` to `10^7` away a quarter
/// of the time, the plane given by its coefficients a quarter of the time,
/// and the ray tilted to within `2^-8` to `2^-24` radians of the plane
/// (still aimed at the same point of it) a quarter of the time; and
/// [`t_max`].
pub fn plane<V: Vector>(src: &mut Source) -> PlaneCase<V> {
    let (pl, ray) = src
        .draw(&strategies::plane_and_ray::<V>())
        .unwrap_or_else(|| {
            let one = S::<V>::ONE;
            (
                Plane::new(V::ZERO, V::splat(one)),
                Ray::new(V::splat(one), V::splat(-one)),
            )
        });
    let offset = if src.one_in(4) {
        far_offset(src)
    } else {
        [0.0; 3]
    };
    let (p, n) = (add(c(pl.point), offset), c(pl.normal));
    let plane = if src.one_in(4) {
        // A x + B y + C z + D = 0 through p.
        let d = -(n[0] * p[0] + n[1] * p[1] + n[2] * p[2]);
        let f = |x: f64| S::<V>::from_f64(x);
        Plane::from_coefficients(f(n[0]), f(n[1]), f(n[2]), f(d))
    } else {
        Plane::new(v(p), pl.normal)
    };
    let (o, d) = (add(c(ray.origin), offset), c(ray.dir));
    let ray = if src.one_in(4) {
        // Grazing: the direction tilted to within 2^-8..2^-24 of the plane,
        // aimed at the point the ray was aimed at.
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let t = dot([0, 1, 2].map(|k| p[k] - o[k]), n) / dot(d, n);
        let target = [0, 1, 2].map(|k| o[k] + t * d[k]);
        let (l2, dn) = (dot(n, n), dot(d, n));
        let tilt = src.log2_range(-24.0, -8.0) * (l2 * dot(d, d)).sqrt();
        let dir = [0, 1, 2].map(|k| d[k] - (dn - tilt) * n[k] / l2);
        aimed(target, dir, src.log2_range(-4.0, 6.0))
    } else {
        Ray::new(v(o), ray.dir)
    };
    (plane, ray, t_max::<V>(src))
}
