//! Structured inputs: realistic ranges, aimed at boundaries.
//!
//! The same shapes of input as the crate's proptest strategies
//! (`rayhit::strategies`), but drawn from the fuzzer's bytes so that
//! libFuzzer's mutations move them smoothly: coordinates in `[-64, 64]`,
//! sizes from `2^-4` to `2^4`, directions of length `2^-6` to `2^6` (one in
//! eight axis-parallel, one in eight with a `+0.0` or `-0.0` component), and
//! rays aimed at a chosen point of a shape (inside, on a face, an edge or a
//! corner, or just outside) from `2^-4` to `2^6` direction lengths away.
//! Every value is computed in `f64` and rounded once to the precision under
//! test; a point "on an edge" is therefore within an ulp or so of it.

use arbitrary::Unstructured;
use rayhit::{Aabb, Plane, Ray, Scalar, Triangle, Vector};

use crate::S;

/// A fraction in `[0, 1]` from 4 bytes (0 when the data has run out).
pub fn unit(u: &mut Unstructured) -> f64 {
    f64::from(crate::raw::<u32>(u)) / f64::from(u32::MAX)
}

/// A value in `[lo, hi]`.
pub fn range(u: &mut Unstructured, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * unit(u)
}

/// An index below `n`.
pub fn index(u: &mut Unstructured, n: usize) -> usize {
    usize::from(crate::raw::<u8>(u)) % n
}

/// `2^k` for an integer `k` in `[lo, hi]`.
pub fn pow2(u: &mut Unstructured, lo: i32, hi: i32) -> f64 {
    let span = (hi - lo + 1) as usize;
    2f64.powi(lo + index(u, span) as i32)
}

/// `x` rounded to the precision of `V`.
pub fn s<V: Vector>(x: f64) -> S<V> {
    S::<V>::from_f64(x)
}

/// A vector from `f64` components, each rounded once.
pub fn v<V: Vector>(c: [f64; 3]) -> V {
    V::new(s::<V>(c[0]), s::<V>(c[1]), s::<V>(c[2]))
}

/// The components of a vector as `f64` (exact).
pub fn c<V: Vector>(p: V) -> [f64; 3] {
    [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()]
}

/// A point with coordinates uniform in `[-scale, scale]`.
pub fn point<V: Vector>(u: &mut Unstructured, scale: f64) -> V {
    v::<V>([
        range(u, -scale, scale),
        range(u, -scale, scale),
        range(u, -scale, scale),
    ])
}

/// `+0.0` or `-0.0`.
fn signed_zero(u: &mut Unstructured) -> f64 {
    if index(u, 2) == 0 { 0.0 } else { -0.0 }
}

/// A nonzero direction: random (6 in 8), axis-parallel (1 in 8, the other
/// components signed zeros) or random with one signed-zero component (1 in
/// 8); length `2^k`, `k` in `[-6, 6]`, times a factor in `[0.2, 1.7]` for the
/// random ones.
pub fn direction<V: Vector>(u: &mut Unstructured) -> V {
    let kind = index(u, 8);
    let scale = pow2(u, -6, 6);
    let mut d = [
        range(u, -1.0, 1.0),
        range(u, -1.0, 1.0),
        range(u, -1.0, 1.0),
    ];
    let k = index(u, 3);
    let (z1, z2) = (signed_zero(u), signed_zero(u));
    if kind == 6 {
        let neg = index(u, 2) == 0;
        d = [z1, z2, z1];
        d[k] = if neg { -1.0 } else { 1.0 };
    } else if kind == 7 {
        d[k] = z1;
    }
    // Too short (including all zeros): fall back to a diagonal.
    if d.iter().map(|x| x * x).sum::<f64>() < 0.04 {
        d = [0.6, -0.8, d[2].signum() * 0.5];
    }
    v::<V>(d.map(|x| x * scale))
}

/// A ray aimed at `target`: origin `target - s dir`, `s` in `[2^-4, 2^6]`.
pub fn ray_through<V: Vector>(u: &mut Unstructured, target: V) -> Ray<V> {
    let dir = direction::<V>(u);
    let dist = range(u, 0.0625, 64.0);
    Ray::new(target - dir * s::<V>(dist), dir)
}

/// `t_max`: `+inf` half the time, else in `[0, 128]`.
pub fn t_max<V: Vector>(u: &mut Unstructured) -> S<V> {
    if index(u, 2) == 0 {
        S::<V>::INFINITY
    } else {
        s::<V>(range(u, 0.0, 128.0))
    }
}

/// A valid box: centre in `[-64, 64]^3`, half extents `2^k` with `k` in
/// `[-4, 4]`, or zero (one time in eight per axis).
pub fn aabb<V: Vector>(u: &mut Unstructured) -> Aabb<V> {
    let centre = point::<V>(u, 64.0);
    let mut h = [0.0; 3];
    for hk in &mut h {
        *hk = if index(u, 8) == 0 {
            0.0
        } else {
            2f64.powf(range(u, -4.0, 4.0))
        };
    }
    let h = v::<V>(h);
    Aabb::new(centre - h, centre + h)
}

/// A target for a ray at `b`: inside the box grown by half its size (3 in
/// 4), or on a face, an edge or a corner.
pub fn aabb_target<V: Vector>(u: &mut Unstructured, b: &Aabb<V>) -> V {
    let (lo, hi) = (c(b.min), c(b.max));
    let mut f = [
        range(u, -0.5, 1.5),
        range(u, -0.5, 1.5),
        range(u, -0.5, 1.5),
    ];
    if index(u, 4) == 0 {
        let fixed = 1 + index(u, 3);
        let k = index(u, 3);
        for i in 0..fixed {
            f[(k + i) % 3] = if index(u, 2) == 0 { 0.0 } else { 1.0 };
        }
    }
    v::<V>([0, 1, 2].map(|k| lo[k] + (hi[k] - lo[k]) * f[k]))
}

/// A box and a ray aimed at it.
pub fn aabb_and_ray<V: Vector>(u: &mut Unstructured) -> (Aabb<V>, Ray<V>) {
    let b = aabb::<V>(u);
    let target = aabb_target(u, &b);
    (b, ray_through(u, target))
}

/// An offset of length `2^k`, `k` in `[-3, 3]`, in a random direction.
fn offset<V: Vector>(u: &mut Unstructured) -> [f64; 3] {
    let d = c(direction::<V>(u));
    let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    let size = pow2(u, -3, 3);
    d.map(|x| x * size / len)
}

/// A triangle: centre in `[-64, 64]^3`, corners at offsets of length
/// `2^-3` to `2^3`; one time in eight a sliver (the third corner within 1%
/// of the first edge), and one in sixteen exactly collinear corners (on a
/// grid of `1/64`, the third corner the midpoint of the first two or the
/// first reflected through the second: a T-junction filler). May be
/// degenerate after rounding; the checks cope.
pub fn triangle<V: Vector>(u: &mut Unstructured) -> Triangle<V> {
    let centre = c(point::<V>(u, 64.0));
    let (oa, ob, oc) = (offset::<V>(u), offset::<V>(u), offset::<V>(u));
    let at = |o: [f64; 3]| [0, 1, 2].map(|k| centre[k] + o[k]);
    let (a, b, mut cc) = (at(oa), at(ob), at(oc));
    if index(u, 16) == 0 {
        let grid = |p: [f64; 3]| p.map(|x| (x * 64.0).round() / 64.0);
        let (a, b) = (grid(a), grid(b));
        let cc = if index(u, 2) == 0 {
            [0, 1, 2].map(|k| (a[k] + b[k]) / 2.0)
        } else {
            [0, 1, 2].map(|k| 2.0 * b[k] - a[k])
        };
        return Triangle::new(v::<V>(a), v::<V>(b), v::<V>(cc));
    }
    if index(u, 8) == 0 {
        let along = unit(u);
        let across = range(u, -0.01, 0.01);
        let e = [0, 1, 2].map(|k| b[k] - a[k]);
        cc = [0, 1, 2].map(|k| a[k] + e[k] * along + oc[k] * across);
    }
    Triangle::new(v::<V>(a), v::<V>(b), v::<V>(cc))
}

/// A point `a + p (b - a) + q (c - a)` in `f64`, rounded once.
pub fn barycentric<V: Vector>(t: &Triangle<V>, p: f64, q: f64) -> V {
    let (a, b, cc) = (c(t.a), c(t.b), c(t.c));
    v::<V>([0, 1, 2].map(|k| a[k] + p * (b[k] - a[k]) + q * (cc[k] - a[k])))
}

/// A target for a ray at `t`: barycentrics in `[-0.25, 1]` (6 in 8), a point
/// of an edge (1 in 8) or a corner (1 in 8).
pub fn triangle_target<V: Vector>(u: &mut Unstructured, t: &Triangle<V>) -> V {
    match index(u, 8) {
        0 => {
            let s = unit(u);
            match index(u, 3) {
                0 => barycentric(t, s, 0.0),
                1 => barycentric(t, 0.0, s),
                _ => barycentric(t, s, 1.0 - s),
            }
        }
        1 => [t.a, t.b, t.c][index(u, 3)],
        _ => barycentric(t, range(u, -0.25, 1.0), range(u, -0.25, 1.0)),
    }
}

/// A triangle and a ray aimed at it.
pub fn triangle_and_ray<V: Vector>(u: &mut Unstructured) -> (Triangle<V>, Ray<V>) {
    let t = triangle::<V>(u);
    let target = triangle_target(u, &t);
    (t, ray_through(u, target))
}

/// A plane (point in `[-64, 64]^3`, normal from [`direction`]) and a ray
/// aimed at a point of it within 64 of that point.
pub fn plane_and_ray<V: Vector>(u: &mut Unstructured) -> (Plane<V>, Ray<V>) {
    let p = point::<V>(u, 64.0);
    let n = direction::<V>(u);
    let nf = c(n);
    // Two tangents: n x (axis of n's smallest component), and n x that.
    let k = (0..3)
        .min_by(|&i, &j| nf[i].abs().total_cmp(&nf[j].abs()))
        .unwrap_or(0);
    let mut axis = [0.0; 3];
    axis[k] = 1.0;
    let t1 = unit3(cross3(nf, axis));
    let t2 = unit3(cross3(nf, t1));
    let (a, b) = (range(u, -64.0, 64.0), range(u, -64.0, 64.0));
    let pf = c(p);
    let target = v::<V>([0, 1, 2].map(|i| pf[i] + a * t1[i] + b * t2[i]));
    (Plane::new(p, n), ray_through(u, target))
}

fn cross3(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn unit3(a: [f64; 3]) -> [f64; 3] {
    let l = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    a.map(|x| x / l)
}
