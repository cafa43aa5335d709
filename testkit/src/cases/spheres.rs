//! Sphere cases: a sphere, a ray at it and a `t_max`.

use rayhit::strategies;
use rayhit::{Ray, Scalar, Sphere, Vector};

use super::{Generator, S, add, c, far_offset, scaled, t_max, v};
use crate::source::Source;

/// One sphere case: the sphere, the ray and `t_max`.
pub type SphereCase<V> = (Sphere<V>, Ray<V>, S<V>);

/// Every sphere family, with its seed.
pub fn generators<V: Vector>() -> [Generator<SphereCase<V>>; 2] {
    [("sphere", 31, sphere::<V>), ("sphere far", 32, far::<V>)]
}

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

/// A far sphere of any size: the centre up to `1e5` from the origin, the
/// radius `1e-3` to `1e4`, and a ray, a third of the time each:
///
/// - aimed at a point on the sphere, half way in, at the centre, or just
///   inside or outside (a relative `1e-7`), from `2` to `1e4` radii away
///   in any direction;
/// - grazing: along a tangent at a point of the sphere, that point moved
///   off it by nothing or a relative `1e-7` or `1e-4` either way, from
///   `1e-1` to `1e3` radii back;
/// - from inside: the origin up to `0.999` radii from the centre, any
///   direction;
///
/// the direction's length the distance to the target (a radius from
/// inside), or (half the time) one; and [`t_max`]. Values in `f64`,
/// rounded once to `V` (a far, tiny sphere's rounded centre may leave a
/// ray "from inside" outside it: the case is the rounded one).
pub fn far<V: Vector>(src: &mut Source) -> SphereCase<V> {
    let centre = scaled(src.direction(), 10f64.powf(src.range(0.0, 5.0)));
    let radius = 10f64.powf(src.range(-3.0, 4.0));
    let normal = src.direction();
    let on = |reach: f64| add(centre, scaled(normal, radius * reach));
    // The origin, and the direction towards the target.
    let (origin, dir) = match src.below(3) {
        0 => {
            let reach = [1.0, 0.5, 0.0, 1.0 + 1e-7, 1.0 - 1e-7][src.index(5)];
            let back = scaled(src.direction(), radius * 10f64.powf(src.range(0.3, 4.0)));
            let target = on(reach);
            (add(target, back), scaled(back, -1.0))
        }
        1 => {
            let m = src.direction();
            let t = [
                normal[1] * m[2] - normal[2] * m[1],
                normal[2] * m[0] - normal[0] * m[2],
                normal[0] * m[1] - normal[1] * m[0],
            ];
            let len = t.iter().map(|x| x * x).sum::<f64>().sqrt();
            let off = [0.0, 1e-7, -1e-7, 1e-4, -1e-4][src.index(5)];
            let along = scaled(t, radius * 10f64.powf(src.range(-1.0, 3.0)) / len);
            (add(on(1.0 + off), scaled(along, -1.0)), along)
        }
        _ => (
            add(centre, scaled(src.direction(), radius * 0.999 * src.unit())),
            scaled(src.direction(), radius),
        ),
    };
    let dir = if src.one_in(2) {
        let len = dir.iter().map(|x| x * x).sum::<f64>().sqrt();
        dir.map(|x| x / len)
    } else {
        dir
    };
    (
        Sphere::new(v(centre), S::<V>::from_f64(radius)),
        Ray::new(v(origin), v(dir)),
        t_max::<V>(src),
    )
}
