//! Quad cases: a quad, a ray aimed at it and a `t_max`.

use rayhit::{Quad, Ray, Scalar, Vector};

use super::{Generator, S, add, aimed, scaled, t_max, v};
use crate::source::Source;

/// One quad case: the quad, the ray and `t_max`.
pub type QuadCase<V> = (Quad<V>, Ray<V>, S<V>);

/// Every quad family of the corpus, with its seed.
pub fn generators<V: Vector>() -> [Generator<QuadCase<V>>; 4] {
    [
        ("quad parallelogram", 51, parallelogram::<V>),
        ("quad convex", 52, convex::<V>),
        ("quad folded", 53, folded::<V>),
        ("quad near ends", 54, near_ends::<V>),
    ]
}

/// A planar quad and where to aim at it, in `f64`: its corners `a`, `b`,
/// `c`, `d`, a point of it, its size and a unit normal.
struct Planar {
    corners: [[f64; 3]; 4],
    target: [f64; 3],
    size: f64,
    normal: [f64; 3],
}

/// A planar quad of size `1e-3` to `1e3` (a parallelogram, or a convex
/// quad near one: the unit square's corners moved by up to `0.2` in its
/// plane), in any orientation, centred `0`, `1e2` or `1e5` from the
/// origin, and a point of it: a third of the time inside, else on an
/// edge, at a corner, or on the diagonal `a-c`, a sixth of the time each.
fn planar(src: &mut Source, parallelogram: bool) -> Planar {
    let size = 10f64.powf(src.range(-3.0, 3.0));
    let reach = [0.0, 1e2, 1e5][src.index(3)];
    let centre = [0; 3].map(|_| reach * src.range(-1.0, 1.0));
    // Two directions in the quad's plane, not parallel.
    let e1 = src.direction();
    let m = src.direction();
    let dot = e1[0] * m[0] + e1[1] * m[1] + e1[2] * m[2];
    let e2 = [0, 1, 2].map(|i| m[i] - 0.8 * dot * e1[i]);
    let at = |(x, y): (f64, f64)| add(centre, [0, 1, 2].map(|i| size * (x * e1[i] + y * e2[i])));
    let mut plane = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
    if !parallelogram {
        for p in &mut plane {
            p.0 += 0.2 * src.range(-1.0, 1.0);
            p.1 += 0.2 * src.range(-1.0, 1.0);
        }
    }
    let (s, t) = (src.unit(), src.unit());
    let lerp =
        |p: (f64, f64), q: (f64, f64), w: f64| (p.0 + w * (q.0 - p.0), p.1 + w * (q.1 - p.1));
    let on = match src.index(6) {
        0 | 1 => lerp(lerp(plane[0], plane[1], s), lerp(plane[3], plane[2], s), t),
        2 => {
            let k = src.index(4);
            lerp(plane[k], plane[(k + 1) % 4], s)
        }
        3 => plane[src.index(4)],
        4 => lerp(plane[0], plane[2], s),
        _ => lerp(lerp(plane[0], plane[1], s), lerp(plane[3], plane[2], s), t),
    };
    let n = [
        e1[1] * e2[2] - e1[2] * e2[1],
        e1[2] * e2[0] - e1[0] * e2[2],
        e1[0] * e2[1] - e1[1] * e2[0],
    ];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    Planar {
        corners: plane.map(at),
        target: at(on),
        size,
        normal: n.map(|x| x / len),
    }
}

/// A quad of precision `V` from its corners (each rounded once), or for a
/// parallelogram from its first corner and edges
/// ([`Quad::parallelogram`], rounding the sums).
fn quad_of<V: Vector>(p: &Planar, parallelogram: bool) -> Quad<V> {
    let [a, b, c, d] = p.corners;
    if parallelogram {
        let edge = |q: [f64; 3]| v::<V>([0, 1, 2].map(|k| q[k] - a[k]));
        Quad::parallelogram(v(a), edge(b), edge(d))
    } else {
        Quad::new(v(a), v(b), v(c), v(d))
    }
}

/// A ray at `target` from `10^0.5` to `10^2.5` sizes away in any
/// direction, its direction the offset back to the target (so that the
/// crossing is at `t` near 1).
fn ray_at<V: Vector>(src: &mut Source, target: [f64; 3], size: f64) -> Ray<V> {
    let away = 10f64.powf(src.range(0.5, 2.5)) * size;
    let back = scaled(src.direction(), away);
    let origin: V = v(add(target, back));
    let to = v::<V>(target) - origin;
    Ray::new(origin, to)
}

/// The quad oracle test's cases: a planar quad (a parallelogram built by
/// [`Quad::parallelogram`], or a convex quad near one; size `1e-3` to
/// `1e3`, any orientation, `0`, `1e2` or `1e5` from the origin) and a ray
/// aimed at a point of it (inside, on an edge, at a corner or on the
/// diagonal) from a few to a few hundred sizes away.
pub fn aimed_quad<V: Vector>(src: &mut Source, parallelogram: bool) -> (Quad<V>, Ray<V>) {
    let p = planar(src, parallelogram);
    let quad = quad_of::<V>(&p, parallelogram);
    (quad, ray_at(src, p.target, p.size))
}

/// [`aimed_quad`]'s parallelograms, and [`t_max`].
pub fn parallelogram<V: Vector>(src: &mut Source) -> QuadCase<V> {
    let (quad, ray) = aimed_quad(src, true);
    (quad, ray, t_max::<V>(src))
}

/// [`aimed_quad`]'s convex quads, and [`t_max`].
pub fn convex<V: Vector>(src: &mut Source) -> QuadCase<V> {
    let (quad, ray) = aimed_quad(src, false);
    (quad, ray, t_max::<V>(src))
}

/// Quads whose corners are not coplanar, folded along the diagonal `a-c`:
/// [`aimed_quad`]'s convex quads with the corner `c` lifted off the plane
/// by `2^-20` to `2^-1` of the size either way, the rays aimed as there,
/// or a quarter of the time nearly along the plane (tilted `2^-12` to
/// `2^-2` out of it), so that both triangles may be crossed; and
/// [`t_max`].
pub fn folded<V: Vector>(src: &mut Source) -> QuadCase<V> {
    let mut p = planar(src, false);
    let lift = p.size * src.log2_range(-20.0, -1.0) * src.sign();
    p.corners[2] = add(p.corners[2], scaled(p.normal, lift));
    let quad = quad_of::<V>(&p, false);
    let ray = if src.one_in(4) {
        let along = src.direction();
        let dn: f64 = (0..3).map(|k| along[k] * p.normal[k]).sum();
        let tilt = src.log2_range(-12.0, -2.0) * src.sign();
        let dir = [0, 1, 2].map(|k| along[k] - (dn - tilt) * p.normal[k]);
        aimed::<V>(p.target, scaled(dir, p.size), src.log2_range(-2.0, 4.0))
    } else {
        ray_at(src, p.target, p.size)
    };
    (quad, ray, t_max::<V>(src))
}

/// The ends of the range: [`aimed_quad`]'s quads (parallelograms or
/// convex), the ray's origin within `2^-40` to `2^-8` direction lengths
/// of the aimed-at point (in front of it or behind), or the ray aimed
/// from a few sizes away with `t_max` at the crossing's `t` computed in
/// `f64` (rounded) or up to four floats either side of it.
pub fn near_ends<V: Vector>(src: &mut Source) -> QuadCase<V> {
    let parallelogram = src.one_in(2);
    let p = planar(src, parallelogram);
    let quad = quad_of::<V>(&p, parallelogram);
    let dir = scaled(src.direction(), p.size);
    if src.one_in(2) {
        let s = src.log2_range(-40.0, -8.0) * src.sign();
        (quad, aimed::<V>(p.target, dir, s), S::<V>::INFINITY)
    } else {
        let s = src.log2_range(0.5, 6.0);
        let ray = aimed::<V>(p.target, dir, s);
        (quad, ray, near::<V>(src, s))
    }
}

/// `s` rounded to the precision of `V`, moved by up to four floats
/// either way.
pub(super) fn near<V: Vector>(src: &mut Source, s: f64) -> S<V> {
    let mut t = S::<V>::from_f64(s);
    let steps = src.below(9) as i32 - 4;
    for _ in 0..steps.abs() {
        t = if steps > 0 {
            t.next_up()
        } else {
            t.next_down()
        };
    }
    t
}
