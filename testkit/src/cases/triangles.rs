//! Triangle cases: a triangle, a ray aimed at it and a `t_max`.

use rayhit::strategies;
use rayhit::{Ray, Scalar, Triangle, Vector};

use super::{Generator, S, add, aimed, c, far_offset, t_max, v};
use crate::source::Source;

/// One triangle case: the triangle, the ray and `t_max`.
pub type TriCase<V> = (Triangle<V>, Ray<V>, S<V>);

/// Every single-triangle family, with its seed.
pub fn generators<V: Vector>() -> [Generator<TriCase<V>>; 6] {
    [
        ("tri uniform", 11, uniform::<V>),
        ("tri edges, corners", 12, edges::<V>),
        ("tri thin", 13, thin::<V>),
        ("tri far 1e3..1e7", 14, far::<V>),
        ("tri 1e-6 and 1e6", 15, scaled::<V>),
        ("tri grazing", 16, grazing::<V>),
    ]
}

/// A triangle's corners as `f64` (exact).
pub fn corners<V: Vector>(t: &Triangle<V>) -> [[f64; 3]; 3] {
    [c(t.a), c(t.b), c(t.c)]
}

/// The triangle of precision `V` with corners `t` (each rounded once).
pub fn to_tri<V: Vector>(t: [[f64; 3]; 3]) -> Triangle<V> {
    Triangle::new(v(t[0]), v(t[1]), v(t[2]))
}

/// The point `a + u (b - a) + w (c - a)` of corners `t`, in `f64`.
pub fn point_on(t: &[[f64; 3]; 3], u: f64, w: f64) -> [f64; 3] {
    [0, 1, 2].map(|k| t[0][k] + u * (t[1][k] - t[0][k]) + w * (t[2][k] - t[0][k]))
}

/// A non-degenerate triangle from the crate's strategy
/// ([`strategies::triangle`]: centre in `[-64, 64]^3`, corners `2^-3` to
/// `2^3` away, one time in eight a sliver).
pub fn triangle<V: Vector>(src: &mut Source) -> Triangle<V> {
    src.draw(&strategies::triangle::<V>()).unwrap_or_else(|| {
        let o = S::<V>::ONE;
        let z = S::<V>::ZERO;
        Triangle::new(V::ZERO, V::new(o, z, z), V::new(z, o, z))
    })
}

/// A ray aimed at `t` by the crate's strategies
/// ([`strategies::triangle_target`]: inside, on an edge, at a corner or
/// just outside; [`strategies::ray_through`]).
pub fn ray_at<V: Vector>(src: &mut Source, t: &Triangle<V>) -> Ray<V> {
    let target = src.draw(&strategies::triangle_target(*t)).unwrap_or(t.a);
    src.draw(&strategies::ray_through(target))
        .unwrap_or(Ray::new(
            target + V::splat(S::<V>::ONE),
            V::splat(-S::<V>::ONE),
        ))
}

/// [`triangle`] and [`ray_at`], and [`t_max`].
pub fn uniform<V: Vector>(src: &mut Source) -> TriCase<V> {
    let t = triangle::<V>(src);
    let ray = ray_at(src, &t);
    (t, ray, t_max::<V>(src))
}

/// A triangle of zero area on a grid of `1/64` (exact in both precisions),
/// the filler meshes close T-junctions with: the third corner the midpoint
/// of the first two, or the first reflected through the second.
pub fn filler<V: Vector>(src: &mut Source) -> Triangle<V> {
    let mut g = || f64::from(src.below(8192) as i32 - 4096) / 64.0;
    let (a, b) = ([0; 3].map(|_| g()), [0; 3].map(|_| g()));
    let third = if src.one_in(2) {
        [0, 1, 2].map(|k| (a[k] + b[k]) / 2.0)
    } else {
        [0, 1, 2].map(|k| 2.0 * b[k] - a[k])
    };
    to_tri([a, b, third])
}

/// A [`triangle`], or one time in sixteen a zero-area [`filler`] (the
/// fuzz targets' structured triangles).
pub fn any_triangle<V: Vector>(src: &mut Source) -> Triangle<V> {
    if src.one_in(16) {
        filler::<V>(src)
    } else {
        triangle::<V>(src)
    }
}

/// [`any_triangle`], a ray aimed at it ([`ray_at`]) and [`t_max`].
pub fn with_fillers<V: Vector>(src: &mut Source) -> TriCase<V> {
    let t = any_triangle::<V>(src);
    let ray = ray_at(src, &t);
    (t, ray, t_max::<V>(src))
}

/// Rays exactly through edges and corners: dyadic corners and rays, as for
/// the box edges.
pub fn edges<V: Vector>(src: &mut Source) -> TriCase<V> {
    let g = |src: &mut Source| f64::from(src.below(8192) as i32 - 4096) / 64.0;
    let t = [0; 3].map(|_| [g(src), g(src), g(src)]);
    let target = match src.below(2) {
        0 => t[src.index(3)],
        _ => {
            let (a, b) = (src.index(3), src.index(3));
            let s = f64::from(src.below(5)) / 4.0;
            [0, 1, 2].map(|k| t[a][k] + s * (t[b][k] - t[a][k]))
        }
    };
    let dir = loop {
        let d = [0; 3].map(|_| f64::from(src.below(17) as i32 - 8) / 8.0);
        if d != [0.0; 3] {
            break d;
        }
        if src.bits() == 0 {
            break [0.125, 0.25, -0.5];
        }
    };
    let m = f64::from(src.below(64) + 1) / 4.0;
    let origin = [0, 1, 2].map(|k| target[k] - m * dir[k]);
    (to_tri(t), Ray::new(v(origin), v(dir)), S::<V>::INFINITY)
}

/// Long thin triangles: the third corner within `2^-4` to `2^-20` of the
/// first edge's line (relative to its length).
pub fn thin<V: Vector>(src: &mut Source) -> TriCase<V> {
    let mut t = corners(&triangle::<V>(src));
    let along = src.unit();
    let across = src.log2_range(-20.0, -4.0);
    let side = src.direction();
    let e = [0, 1, 2].map(|k| t[1][k] - t[0][k]);
    let len = (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt();
    t[2] = [0, 1, 2].map(|k| t[0][k] + along * e[k] + across * len * side[k]);
    let t = to_tri(t);
    let ray = ray_at(src, &t);
    (t, ray, S::<V>::INFINITY)
}

/// The uniform cases moved `10^3` to `10^7` away from the origin.
pub fn far<V: Vector>(src: &mut Source) -> TriCase<V> {
    let offset = far_offset(src);
    let (t, ray, _) = uniform::<V>(src);
    (
        to_tri(corners(&t).map(|p| add(p, offset))),
        Ray::new(v(add(c(ray.origin), offset)), ray.dir),
        S::<V>::INFINITY,
    )
}

/// The uniform cases scaled by `1e-6` or `1e6`, direction included.
pub fn scaled<V: Vector>(src: &mut Source) -> TriCase<V> {
    let k = if src.one_in(2) { 1e-6 } else { 1e6 };
    let (t, ray, _) = uniform::<V>(src);
    let s = |p: [f64; 3]| super::scaled(p, k);
    (
        to_tri(corners(&t).map(s)),
        Ray::new(v(s(c(ray.origin))), v(s(c(ray.dir)))),
        S::<V>::INFINITY,
    )
}

/// Grazing rays: within `2^-8` to `2^-24` radians of the triangle's plane.
pub fn grazing<V: Vector>(src: &mut Source) -> TriCase<V> {
    let tri = triangle::<V>(src);
    let t = corners(&tri);
    let e1 = [0, 1, 2].map(|k| t[1][k] - t[0][k]);
    let e2 = [0, 1, 2].map(|k| t[2][k] - t[0][k]);
    let n = [
        e1[1] * e2[2] - e1[2] * e2[1],
        e1[2] * e2[0] - e1[0] * e2[2],
        e1[0] * e2[1] - e1[1] * e2[0],
    ];
    let nl = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    let d = src.direction();
    let dn = (d[0] * n[0] + d[1] * n[1] + d[2] * n[2]) / nl;
    let tilt = src.log2_range(-24.0, -8.0) * src.sign();
    let dir = [0, 1, 2].map(|k| d[k] - (dn - tilt) * n[k] / nl);
    let target = src
        .draw(&strategies::triangle_target(tri))
        .map(c)
        .unwrap_or(t[0]);
    let s = src.log2_range(-2.0, 4.0);
    (tri, aimed(target, dir, s), S::<V>::INFINITY)
}
