//! Disc cases: a disc or an annulus, a ray at it and a `t_max`.

use rayhit::strategies;
use rayhit::{Disc, Ray, Scalar, Vector};

use super::{Generator, S, add, aimed, c, far_offset, scaled, t_max, v};
use crate::source::Source;

/// One disc case: the disc, the ray and `t_max`.
pub type DiscCase<V> = (Disc<V>, Ray<V>, S<V>);

/// Every disc family of the corpus, with its seed.
pub fn generators<V: Vector>() -> [Generator<DiscCase<V>>; 1] {
    [("disc far", 41, far::<V>)]
}

/// A disc and a ray from the crate's strategy
/// ([`strategies::disc_and_ray`]: aimed at either circle, just off them,
/// inside the annulus, in the hole or outside; from anywhere, nearly along
/// the plane, or from the plane itself), moved `10^3` to `10^7` away a
/// quarter of the time (the centre and the origin moved in `f64` and
/// rounded, so a far ray may no longer meet a small disc), every position
/// and both radii scaled by `2^k`, `k` uniform in `[-40, 40]`, a quarter of
/// the time (exactly: the same geometry at another scale), the normal
/// scaled likewise, independently, a quarter of the time (the same disc);
/// and [`t_max`].
pub fn disc<V: Vector>(src: &mut Source) -> DiscCase<V> {
    let (d, ray) = src
        .draw(&strategies::disc_and_ray::<V>())
        .unwrap_or_else(|| {
            let one = S::<V>::ONE;
            (
                Disc::new(V::ZERO, V::new(one, one, one), one),
                Ray::new(V::splat(S::<V>::from_f64(-3.0)), V::splat(one)),
            )
        });
    let (d, ray) = if src.one_in(4) {
        let offset = far_offset(src);
        (
            Disc {
                center: v(add(c(d.center), offset)),
                ..d
            },
            Ray::new(v(add(c(ray.origin), offset)), ray.dir),
        )
    } else {
        (d, ray)
    };
    let (d, ray) = if src.one_in(4) {
        let s = S::<V>::from_f64(src.pow2(-40, 40));
        (
            Disc::annulus(d.center * s, d.normal, d.radius * s, d.inner_radius * s),
            Ray::new(ray.origin * s, ray.dir),
        )
    } else {
        (d, ray)
    };
    let d = if src.one_in(4) {
        let s = S::<V>::from_f64(src.pow2(-40, 40));
        Disc {
            normal: d.normal * s,
            ..d
        }
    } else {
        d
    };
    (d, ray, t_max::<V>(src))
}

/// A disc (half the time an annulus, its hole a fifth to nine tenths of
/// the radius) with its centre up to `1e5` from the origin, radius `1e-3`
/// to `1e4`, a normal of any direction and of length `1e-2` to `1e2`, and
/// a ray aimed at a point of its plane: on the outer circle or on the
/// inner one (the circle's point rounded, or moved off it by a relative
/// `1e-7` either way), inside the annulus, in the hole, or outside; from
/// `1e-1` to `1e3` radii away, along any direction, or a quarter of the
/// time nearly along the plane (tilted `1e-3`, `1e-6`, `1e-9`, `1e-12`
/// or `1e-15` out of it); and [`t_max`]. Values in `f64`, rounded once to `V`.
pub fn far<V: Vector>(src: &mut Source) -> DiscCase<V> {
    let n = src.direction();
    let centre = scaled(src.direction(), 10f64.powf(src.range(0.0, 5.0)));
    let radius = 10f64.powf(src.range(-3.0, 4.0));
    let inner = if src.one_in(2) {
        radius * src.range(0.2, 0.9)
    } else {
        0.0
    };
    // A unit vector in the plane.
    let m = src.direction();
    let mut along = [
        n[1] * m[2] - n[2] * m[1],
        n[2] * m[0] - n[0] * m[2],
        n[0] * m[1] - n[1] * m[0],
    ];
    let len = along.iter().map(|x| x * x).sum::<f64>().sqrt();
    if len > 0.0 {
        along = along.map(|x| x / len);
    }
    let off = [1.0, 1.0 + 1e-7, 1.0 - 1e-7][src.index(3)];
    let rho = match src.below(5) {
        0 => radius * off,
        1 => inner * off,
        2 => (radius + inner) * 0.5,
        3 => inner * 0.5,
        _ => radius * 1.5,
    };
    let target = add(centre, scaled(along, rho));
    let away = if src.one_in(4) {
        // Nearly along the plane.
        let tilt = [1e-3, 1e-6, 1e-9, 1e-12, 1e-15][src.index(5)];
        [0, 1, 2].map(|i| along[i] + n[i] * tilt)
    } else {
        src.direction()
    };
    let dist = radius * 10f64.powf(src.range(-1.0, 3.0));
    // The direction from the origin to the target, of length `dist`.
    let ray = aimed::<V>(target, scaled(away, -dist), 1.0);
    let normal = scaled(n, 10f64.powf(src.range(-2.0, 2.0)));
    let f = S::<V>::from_f64;
    let disc = Disc::annulus(v(centre), v(normal), f(radius), f(inner));
    (disc, ray, t_max::<V>(src))
}
