//! The exact transfer of a ray differential to a triangle hit.

use super::values::*;
use crate::{Triangle, Vector};
use num_traits::Zero;

/// The exact transfer of one ray differential to a triangle at parameter
/// `t` (the formulas of [`Triangle::hit_differentials`](crate::Triangle::hit_differentials),
/// evaluated exactly on the given floats): with `n = (b - a) x (c - a)`
/// and `q = d_origin + t d_dir`, `dp = q - dir (q . n) / (dir . n)`, `du =
/// dp . ((c - a) x n) / |n|^2`, `dv = dp . (n x (b - a)) / |n|^2`: the
/// derivative of the hit point and of its barycentrics along the
/// differential, at `t`.
///
/// `None` when an input is not finite, or `dir . n` or `|n|^2` is zero.
#[must_use]
pub fn hit_differential<V: Vector>(
    dir: V,
    d_origin: V,
    d_dir: V,
    tri: &Triangle<V>,
    t: V::Scalar,
) -> Option<(R3, R, R)> {
    let (dir, d_origin, d_dir) = (rv(dir)?, rv(d_origin)?, rv(d_dir)?);
    let (a, b, c) = (rv(tri.a)?, rv(tri.b)?, rv(tri.c)?);
    let t = r(t)?;
    let (e1, e2) = (sub(&b, &a), sub(&c, &a));
    let n = cross(&e1, &e2);
    let den = dot(&dir, &n);
    let nn = dot(&n, &n);
    if den.is_zero() || nn.is_zero() {
        return None;
    }
    let q: R3 = core::array::from_fn(|k| &d_origin[k] + &t * &d_dir[k]);
    let dt = -dot(&q, &n) / den;
    let dp: R3 = core::array::from_fn(|k| &q[k] + &dt * &dir[k]);
    let du = dot(&dp, &cross(&e2, &n)) / &nn;
    let dv = dot(&dp, &cross(&n, &e1)) / &nn;
    Some((dp, du, dv))
}
