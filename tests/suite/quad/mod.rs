//! The quad: its hit against the exact crossings of its two triangles
//! (`oracle`), its 2^k scalings (`properties`), and closed meshes of quads, and of quads and triangles
//! with T-junctions, with no crack and no leak, the textbook quad test
//! ("The Next Week") beside it (`watertight`).

mod oracle;
mod properties;
pub(crate) mod watertight;

use rayhit::{Quad, Ray, Scalar, Vector};

use crate::common::draw::S;

/// The textbook ray/parallelogram test ("Ray Tracing: The Next Week", the
/// `quad` with corner `q` and edges `u`, `v`): the plane's `t` from the
/// unit normal, then the hit point's coordinates `alpha = w . (p x v)`,
/// `beta = w . (u x p)` with `w = n / (n . n)`, inside where both are in
/// `[0, 1]`. `t` in `(t_min, t_max)`. For comparison only.
pub fn textbook<V: Vector>(ray: &Ray<V>, quad: &Quad<V>, t_min: S<V>, t_max: S<V>) -> Option<S<V>> {
    let (q, u, v) = (quad.a, quad.b - quad.a, quad.d - quad.a);
    let n = u.cross(v);
    let normal = n.normalize_or_zero();
    let d = normal.dot(q);
    let w = n * (S::<V>::ONE / n.dot(n));
    let denom = normal.dot(ray.dir);
    if denom.abs() < S::<V>::from_f64(1e-8) {
        return None;
    }
    let t = (d - normal.dot(ray.origin)) / denom;
    if !(t > t_min && t < t_max) {
        return None;
    }
    let p = ray.at(t) - q;
    let alpha = w.dot(p.cross(v));
    let beta = w.dot(u.cross(p));
    let unit = |x: S<V>| x >= S::<V>::ZERO && x <= S::<V>::ONE;
    (unit(alpha) && unit(beta)).then_some(t)
}
