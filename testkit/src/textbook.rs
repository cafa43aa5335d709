//! Textbook kernels the tests, the demo and the benches hold rayhit's
//! against, each written once here from its published formulas.

use rayhit::{Patch, Ray, Scalar, Vector};

type S<V> = <V as Vector>::Scalar;

/// The textbook ray/bilinear patch test, from the formulas of Reshetov,
/// "Cool Patches: A Geometric Approach to Ray/Bilinear Patch
/// Intersections" (Ray Tracing Gems, ch. 8, 2019), in the precision of
/// `V`: the quadratic `a u^2 + b u + c` whose roots are the `u` of the
/// patch's lines (from `v = 0` to `v = 1`) that the ray meets, with `a =
/// ((p10 - p00) x (p01 - p11)) . d`, `c = ((p00 - o) x d) . (p01 - p00)`,
/// `b = ((p10 - o) x d) . (p11 - p10) - a - c`; for each root in `[0, 1]`,
/// with `l0 = P(u, 0)`, `l = P(u, 1) - l0`, `n = d x l`, `v = ((l0 - o) .
/// (d x n)) / |n|^2` and `t = ((l0 - o) . (l x n)) / |n|^2`, kept where `v`
/// is in `[0, 1]` and `t` in `(t_min, t_max)`. `t` and `(u, v)`; for
/// comparison only.
pub fn reshetov<V: Vector>(
    ray: &Ray<V>,
    patch: &Patch<V>,
    t_min: S<V>,
    t_max: S<V>,
) -> Option<(S<V>, S<V>, S<V>)> {
    let (o, d) = (ray.origin, ray.dir);
    let (p00, p10, p01, p11) = (patch.p00, patch.p10, patch.p01, patch.p11);
    let (zero, one) = (S::<V>::ZERO, S::<V>::ONE);
    let a = (p10 - p00).cross(p01 - p11).dot(d);
    let c = (p00 - o).cross(d).dot(p01 - p00);
    let b = (p10 - o).cross(d).dot(p11 - p10) - a - c;
    let roots = if a.abs() < S::<V>::from_f64(1e-12) * (b.abs() + c.abs()) {
        [-c / b, S::<V>::NAN]
    } else {
        let disc = b * b - S::<V>::from_f64(4.0) * a * c;
        if disc < zero {
            return None;
        }
        let root = disc.sqrt();
        let q = -(b + if b < zero { -root } else { root }) * S::<V>::HALF;
        [q / a, c / q]
    };
    let mut best: Option<(S<V>, S<V>, S<V>)> = None;
    for u in roots {
        if !(zero <= u && u <= one) {
            continue;
        }
        let l0 = p00 + (p10 - p00) * u;
        let l = p01 + (p11 - p01) * u - l0;
        let n = d.cross(l);
        let n2 = n.dot(n);
        let w = l0 - o;
        let v = w.dot(d.cross(n)) / n2;
        let t = w.dot(l.cross(n)) / n2;
        if zero <= v && v <= one && t > t_min && t < t_max && best.is_none_or(|b| t < b.0) {
            best = Some((t, u, v));
        }
    }
    best
}
