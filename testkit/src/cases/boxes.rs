//! Box cases: a box, a ray aimed at it and a `t_max`.

use rayhit::strategies;
use rayhit::{Aabb, Ray, Scalar, Vector};

use super::{Generator, S, add, aimed, c, direction, far_offset, t_max, v};
use crate::source::Source;

/// One box case: the box, the ray and `t_max`.
pub type BoxCase<V> = (Aabb<V>, Ray<V>, S<V>);

/// Every box family, with its seed.
pub fn generators<V: Vector>() -> [Generator<BoxCase<V>>; 8] {
    [
        ("box uniform", 1, uniform::<V>),
        ("box edges, corners", 2, edges::<V>),
        ("box on slab plane", 3, on_slab::<V>),
        ("box in face plane", 4, in_face::<V>),
        ("box grazing", 5, grazing::<V>),
        ("box tiny dir", 6, tiny_dirs::<V>),
        ("box far 1e3..1e7", 7, far::<V>),
        ("box 1e-6 and 1e6", 8, scaled::<V>),
    ]
}

/// A box on a dyadic grid (multiples of `2^-6` in `[-64, 64]`), of zero
/// thickness on each axis one time in eight: coordinates with few
/// significant bits, so that rays built from them can pass exactly through
/// edges and corners.
pub fn grid_box(src: &mut Source) -> ([f64; 3], [f64; 3]) {
    let g = |src: &mut Source| f64::from(src.below(8192) as i32 - 4096) / 64.0;
    let mut lo = [0.0; 3];
    let mut hi = [0.0; 3];
    for k in 0..3 {
        let (a, b) = (g(src), g(src));
        (lo[k], hi[k]) = if src.one_in(8) {
            (a, a)
        } else {
            (a.min(b), a.max(b))
        };
    }
    (lo, hi)
}

/// The box rounded outward to precision `V` (so that it stays valid and
/// contains the `f64` one).
pub fn to_box<V: Vector>(lo: [f64; 3], hi: [f64; 3]) -> Aabb<V> {
    let down = |x: f64| {
        let y = S::<V>::from_f64(x);
        if y.to_f64() > x { y.next_down() } else { y }
    };
    let up = |x: f64| {
        let y = S::<V>::from_f64(x);
        if y.to_f64() < x { y.next_up() } else { y }
    };
    Aabb::new(
        V::new(down(lo[0]), down(lo[1]), down(lo[2])),
        V::new(up(hi[0]), up(hi[1]), up(hi[2])),
    )
}

/// A point in the box grown by half its size on each side.
pub fn near(src: &mut Source, lo: [f64; 3], hi: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|k| lo[k] + (hi[k] - lo[k]) * src.range(-0.5, 1.5))
}

/// The crate's strategy ([`strategies::aabb_and_ray`]: a box, and a ray
/// aimed inside it, at a face, an edge or a corner, or just outside) and
/// [`t_max`].
pub fn uniform<V: Vector>(src: &mut Source) -> BoxCase<V> {
    let (b, ray) = src
        .draw(&strategies::aabb_and_ray::<V>())
        .unwrap_or_else(|| {
            (
                Aabb::new(V::ZERO, V::splat(S::<V>::ONE)),
                Ray::new(V::ZERO, V::splat(S::<V>::ONE)),
            )
        });
    (b, ray, t_max::<V>(src))
}

/// Rays exactly through box edges and corners: the box, the target (a
/// corner, or a point of an edge) and the ray are all on dyadic grids with
/// few enough bits that every coordinate and the origin `target - m dir`
/// are exact in `f32`, so exact arithmetic says the ray touches the edge.
pub fn edges<V: Vector>(src: &mut Source) -> BoxCase<V> {
    let (lo, hi) = grid_box(src);
    let mut target = [0.0; 3];
    let free = src.index(4); // 3: a corner, else the free axis of an edge
    for k in 0..3 {
        target[k] = if k == free {
            lo[k] + (hi[k] - lo[k]) * f64::from(src.below(5)) / 4.0
        } else if src.one_in(2) {
            lo[k]
        } else {
            hi[k]
        };
    }
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
    (
        Aabb::new(v(lo), v(hi)),
        Ray::new(v(origin), v(dir)),
        S::<V>::INFINITY,
    )
}

/// Axis-parallel rays whose origin lies exactly on a slab plane of another
/// axis (the `0 * inf = NaN` case of the slab test), the other direction
/// components `+0.0` or `-0.0`.
pub fn on_slab<V: Vector>(src: &mut Source) -> BoxCase<V> {
    let (lo, hi) = grid_box(src);
    let k = src.index(3);
    let mut dir = [0.0; 3];
    dir[k] = src.sign();
    for (j, d) in dir.iter_mut().enumerate() {
        if j != k && src.one_in(2) {
            *d = -0.0;
        }
    }
    let mut o = near(src, lo, hi);
    let j = (k + 1 + src.index(2)) % 3;
    o[j] = if src.one_in(2) { lo[j] } else { hi[j] };
    o[k] = src.range(-200.0, 200.0);
    (
        Aabb::new(v(lo), v(hi)),
        Ray::new(v(o), v(dir)),
        t_max::<V>(src),
    )
}

/// Rays lying in a face plane: the direction's component on that axis is
/// `+0.0` or `-0.0` and the origin is on the plane.
pub fn in_face<V: Vector>(src: &mut Source) -> BoxCase<V> {
    let (lo, hi) = grid_box(src);
    let j = src.index(3);
    let mut dir = c(direction::<V>(src));
    dir[j] = if src.one_in(2) { 0.0 } else { -0.0 };
    if dir.iter().all(|&d| d == 0.0) {
        dir[(j + 1) % 3] = 1.0;
    }
    let mut target = near(src, lo, hi);
    target[j] = if src.one_in(2) { lo[j] } else { hi[j] };
    let s = src.log2_range(-2.0, 6.0);
    // (Aiming rounds nothing on axis j, as dir_j is zero: the origin is on
    // the face plane.)
    (
        Aabb::new(v(lo), v(hi)),
        aimed(target, dir, s),
        S::<V>::INFINITY,
    )
}

/// Grazing rays: nearly parallel to a face (one direction component `2^-8`
/// to `2^-24` of the others), passing near an edge.
pub fn grazing<V: Vector>(src: &mut Source) -> BoxCase<V> {
    let b = src
        .draw(&strategies::aabb::<V>())
        .unwrap_or(Aabb::new(V::ZERO, V::splat(S::<V>::ONE)));
    let (lo, hi) = (c(b.min), c(b.max));
    let j = src.index(3);
    let mut dir = src.direction();
    dir[j] = src.sign() * src.log2_range(-24.0, -8.0);
    let mut target = near(src, lo, hi);
    target[j] = if src.one_in(2) { lo[j] } else { hi[j] };
    let k = (j + 1) % 3;
    target[k] = if src.one_in(2) { lo[k] } else { hi[k] };
    let s = src.log2_range(-2.0, 6.0);
    (b, aimed(target, dir, s), S::<V>::INFINITY)
}

/// Tiny direction components: `1e-30`, subnormal, `+-0.0`, mixed with
/// ordinary ones; origins near or on slab planes, one subnormal off a plane
/// at zero.
pub fn tiny_dirs<V: Vector>(src: &mut Source) -> BoxCase<V> {
    let (mut lo, mut hi) = grid_box(src);
    let tiny = S::<V>::TINY.to_f64();
    let choices = [1e-30, -1e-30, 37.0 * tiny, -tiny, 0.0, -0.0, 1e-20];
    let mut dir = src.direction();
    for d in &mut dir {
        if src.one_in(2) {
            *d = choices[src.index(choices.len())];
        }
    }
    if dir.iter().all(|&d| d == 0.0) {
        dir[0] = 1.0;
    }
    let mut o = near(src, lo, hi);
    for k in 0..3 {
        match src.below(4) {
            0 => o[k] = lo[k],
            1 => o[k] = hi[k],
            2 => {
                // A plane at zero and an origin one subnormal away.
                lo[k] = 0.0;
                hi[k] = hi[k].max(0.0);
                o[k] = if src.one_in(2) { -tiny } else { tiny };
            }
            _ => {}
        }
    }
    (
        Aabb::new(v(lo), v(hi)),
        Ray::new(v(o), v(dir)),
        t_max::<V>(src),
    )
}

/// The uniform cases moved `10^3` to `10^7` away from the origin (the box
/// rounded outward, the origin to nearest).
pub fn far<V: Vector>(src: &mut Source) -> BoxCase<V> {
    let offset = far_offset(src);
    let (b, ray, _) = uniform::<V>(src);
    (
        to_box(add(c(b.min), offset), add(c(b.max), offset)),
        Ray::new(v(add(c(ray.origin), offset)), ray.dir),
        S::<V>::INFINITY,
    )
}

/// The uniform cases scaled by `1e-6` or `1e6`, direction included.
pub fn scaled<V: Vector>(src: &mut Source) -> BoxCase<V> {
    let k = if src.one_in(2) { 1e-6 } else { 1e6 };
    let (b, ray, _) = uniform::<V>(src);
    let s = |p: V| super::scaled(c(p), k);
    (
        to_box(s(b.min), s(b.max)),
        Ray::new(v(s(ray.origin)), v(s(ray.dir))),
        S::<V>::INFINITY,
    )
}
