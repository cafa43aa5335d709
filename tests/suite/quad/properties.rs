//! The quad's properties, in both precisions, on the crate's triangle
//! strategies (`rayhit::strategies::triangle_and_ray`: rays aimed at the
//! interior, the edges and the corners) made quads: the triangle is the
//! quad's first, `a, b, c`, and the fourth corner completes the
//! parallelogram (`d = a + c - b`, rounded), so that rays aimed at the
//! triangle's edge `c`-`a` cross the quad's diagonal.
//!
//! - scaling the origin and every corner by `2^k` (and keeping `dir`)
//!   scales `t` by `2^k` exactly and keeps `u`, `v` and the side, over a
//!   `t_max` and over an interval scaled alike: every quantity the
//!   watertight test forms scales by a power of two (the sheared
//!   coordinates by `2^k`, the edge functions and the determinant by
//!   `4^k`, `t`'s numerator by `8^k`), so every rounding and every
//!   comparison is the same (within the strategies' ranges nothing
//!   underflows or overflows);
//! - scaling `dir` by `2^k` scales `t` by `2^-k` exactly, the rest kept
//!   (the shear factors are ratios of `dir`'s components, unchanged; the
//!   depth scale `1 / d_z` scales by `2^-k`).
//!
//! (The bounds against exact arithmetic are `quad::oracle`'s.)

use crate::common::props::{config, in_both_precisions};
use proptest::prelude::*;
use rayhit::glam::{DVec3, Vec3};
use rayhit::strategies as strat;
use rayhit::{Intersect, Interval, Quad, Ray, Scalar, Triangle, Vector};

use crate::common::draw::S;

/// The quad whose first triangle is `tri`, completed to a parallelogram.
fn quad_of<V: Vector>(tri: Triangle<V>) -> Quad<V> {
    let d = |k: usize| S::<V>::from_f64(tri.a[k].to_f64() + tri.c[k].to_f64() - tri.b[k].to_f64());
    Quad::new(tri.a, tri.b, tri.c, V::new(d(0), d(1), d(2)))
}

/// A hit as `(t, u, v, side)`.
type Answer<F> = Option<(F, F, F, rayhit::Side)>;

/// The quad's answers on `ray` over `t_max` and over `window`.
fn answers<V: Vector>(
    quad: &Quad<V>,
    ray: &Ray<V>,
    t_max: S<V>,
    window: Option<Interval<S<V>>>,
) -> [Answer<S<V>>; 2] {
    let key = |h: rayhit::QuadHit<S<V>>| (h.t, h.u, h.v, h.side);
    [
        quad.hit(ray, t_max).map(key),
        window.and_then(|w| quad.hit(ray, w)).map(key),
    ]
}

/// The answers on `(quad2, ray2)`, with the range mapped by `map`, are the
/// answers on `(quad, ray)` with `t` mapped by `map`.
fn check_map<V: Vector>(
    (quad, ray): (Quad<V>, Ray<V>),
    (quad2, ray2): (Quad<V>, Ray<V>),
    t_max: S<V>,
    ends: (f64, f64),
    map: impl Fn(S<V>) -> S<V>,
) -> Result<(), TestCaseError> {
    let t = quad
        .hit(&ray, S::<V>::INFINITY)
        .map_or(S::<V>::ONE, |h| h.t);
    let (lo, hi) = (
        t * S::<V>::from_f64(ends.0),
        t * S::<V>::from_f64(ends.0 + ends.1),
    );
    let before = answers(&quad, &ray, t_max, Interval::new(lo, hi));
    let after = answers(&quad2, &ray2, map(t_max), Interval::new(map(lo), map(hi)));
    let mapped = before.map(|a| a.map(|(t, u, v, side)| (map(t), u, v, side)));
    prop_assert_eq!(
        after,
        mapped,
        "{:?} {:?} t_max {:?} ({:?}, {:?}]",
        quad,
        ray,
        t_max,
        lo,
        hi
    );
    Ok(())
}

in_both_precisions! {
    fn position_scaling((tri, ray) in strat::triangle_and_ray::<V>(), t_max in strat::t_max::<V>(), ends in (0.0..1.2f64, 0.0..1.0f64), k in -8i32..=8) {
        let s = S::<V>::from_f64(2f64.powi(k));
        let quad = quad_of(tri);
        let scaled = Quad::new(quad.a * s, quad.b * s, quad.c * s, quad.d * s);
        check_map(
            (quad, ray),
            (scaled, Ray::new(ray.origin * s, ray.dir)),
            t_max,
            ends,
            |t| t * s,
        )?;
    }

    fn direction_scaling((tri, ray) in strat::triangle_and_ray::<V>(), t_max in strat::t_max::<V>(), ends in (0.0..1.2f64, 0.0..1.0f64), k in -8i32..=8) {
        let s = S::<V>::from_f64(2f64.powi(k));
        let quad = quad_of(tri);
        check_map(
            (quad, ray),
            (quad, Ray::new(ray.origin, ray.dir * s)),
            t_max,
            ends,
            |t| t / s,
        )?;
    }
}
