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
//! - a plain and a prepared ray get the two triangles' answer, bit for
//!   bit (`t`, `u`, `v` and the side of the nearer hit, the first where
//!   they tie), on parallelograms, quads folded along their diagonal,
//!   quads with a collapsed edge, and seen from far off (where the
//!   determinant's sign needs the exact threshold): the quad's common path
//!   is its own code, finishing both triangles in lanes.
//!
//! (The bounds against exact arithmetic are `quad::oracle`'s.)

use crate::common::props::{config, in_both_precisions};
use proptest::prelude::*;
use rayhit::glam::{DVec3, Vec3};
use rayhit::strategies as strat;
use rayhit::{
    Intersect, Interval, PreparedRay, Quad, QuadHit, Ray, Scalar, Triangle, TriangleHit, Vector,
};

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

/// The quad of kind `kind` on `tri`: the parallelogram (0), folded along
/// the diagonal `a`-`c` by `fold` of the edge's length (1), with the edge
/// `d`-`a` collapsed (2) or `c`-`d` (3).
fn quad_of_kind<V: Vector>(tri: Triangle<V>, kind: u8, fold: f64) -> Quad<V> {
    let q = quad_of(tri);
    let f = |v: V| [0, 1, 2].map(|k| v[k].to_f64());
    let [a, b, c, d] = [q.a, q.b, q.c, q.d].map(f);
    let sub = |p: [f64; 3], q: [f64; 3]| [0, 1, 2].map(|k| p[k] - q[k]);
    let (e1, e2) = (sub(b, a), sub(c, a));
    let n = [
        e1[1] * e2[2] - e1[2] * e2[1],
        e1[2] * e2[0] - e1[0] * e2[2],
        e1[0] * e2[1] - e1[1] * e2[0],
    ];
    let len = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let scale = if len(n) > 0.0 {
        fold * len(e1) / len(n)
    } else {
        0.0
    };
    let folded = [0, 1, 2].map(|k| S::<V>::from_f64(d[k] + scale * n[k]));
    match kind {
        0 => q,
        1 => Quad::new(q.a, q.b, q.c, V::new(folded[0], folded[1], folded[2])),
        2 => Quad::new(q.a, q.b, q.c, q.a),
        _ => Quad::new(q.a, q.b, q.c, q.c),
    }
}

in_both_precisions! {
    fn both_ray_forms_answer_as_the_two_triangles((tri, ray) in strat::triangle_and_ray::<V>(), t_max in strat::t_max::<V>(), kind in 0u8..4, fold in -0.5..0.5f64, back in prop_oneof![Just(0.0), Just(1e3), Just(1e5)]) {
        let quad = quad_of_kind(tri, kind, fold);
        // (Moved back along the ray: the quad small next to its distance.)
        let ray = Ray::new(ray.origin - ray.dir * S::<V>::from_f64(back), ray.dir);
        // The nearer triangle hit (the first where they tie), its weights
        // summed as the quad's docs say.
        let [first, second] = quad.triangles();
        let one = S::<V>::ONE;
        let sum = |h: TriangleHit<S<V>>| if h.u + h.v < one { h.u + h.v } else { one };
        let expected = match (first.hit(&ray, t_max), second.hit(&ray, t_max)) {
            (Some(p), Some(q)) if q.t < p.t => Some((q.t, q.u, sum(q), q.side)),
            (Some(p), _) => Some((p.t, sum(p), p.v, p.side)),
            (None, Some(q)) => Some((q.t, q.u, sum(q), q.side)),
            (None, None) => None,
        };
        let key = |h: QuadHit<S<V>>| (h.t, h.u, h.v, h.side);
        prop_assert_eq!(quad.hit(&ray, t_max).map(key), expected, "{:?} {:?} {:?}", quad, ray, t_max);
        let prepared = PreparedRay::new(&ray);
        prop_assert_eq!(quad.hit(&prepared, t_max).map(key), expected, "{:?} {:?} {:?}", quad, ray, t_max);
    }

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

/// A NaN or infinite corner makes the triangles with that corner nothing
/// hits, as the quad's docs say: a ray through the other triangle still
/// hits it (and only it), a ray through a triangle with the corner
/// misses, and a non-finite `a` or `c` (on both triangles) leaves nothing.
#[test]
fn non_finite_corners_leave_the_triangles_without_them() {
    let corners = [Vec3::ZERO, Vec3::X, Vec3::new(1.0, 1.0, 0.0), Vec3::Y];
    // Straight down through the first triangle (`u > v`), then the second.
    let rays = [(0.8, 0.2), (0.2, 0.8)].map(|(x, y)| Ray::new(Vec3::new(x, y, 1.0), -Vec3::Z));
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        for corner in 0..4 {
            let mut c = corners;
            c[corner].x = bad;
            let quad = Quad::new(c[0], c[1], c[2], c[3]);
            // Which triangles keep their corners: `a, b, c` unless the bad
            // corner is a, b or c; `a, c, d` unless it is a, c or d.
            let kept = [corner == 3, corner == 1];
            for (ray, keeps) in rays.iter().zip(kept) {
                for hit in [
                    quad.hit(ray, f32::INFINITY),
                    quad.hit(&PreparedRay::new(ray), f32::INFINITY),
                ] {
                    assert_eq!(hit.is_some(), keeps, "{quad:?} {ray:?}");
                    if let Some(h) = hit {
                        assert_eq!(h.t, 1.0, "{quad:?} {ray:?}");
                    }
                }
            }
        }
    }
}
