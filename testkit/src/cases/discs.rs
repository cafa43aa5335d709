//! Disc cases: a disc or an annulus, a ray at it and a `t_max`.

use rayhit::strategies;
use rayhit::{Disc, Ray, Scalar, Vector};

use super::{S, add, c, far_offset, t_max, v};
use crate::source::Source;

/// One disc case: the disc, the ray and `t_max`.
pub type DiscCase<V> = (Disc<V>, Ray<V>, S<V>);

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
