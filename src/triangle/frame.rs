//! A triangle in a ray's sheared frame: translated to the ray origin,
//! permuted so that the ray runs mostly along `z`, sheared so that it runs
//! exactly along `z`; and its three edge functions, with their signs exact.

use super::Triangle;
use crate::num::{Scalar, Vector};
use crate::ray::Shear;

/// The triangle in the ray's frame: translated to the ray origin, permuted,
/// and sheared in `x, y`; the ray is the `+z` axis.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Frame<F> {
    /// Sheared `x` and `y` of the three corners.
    pub(crate) x: [F; 3],
    pub(crate) y: [F; 3],
    /// Translated, permuted, unsheared coordinates (for the error bounds).
    pub(crate) px: [F; 3],
    pub(crate) py: [F; 3],
    pub(crate) pz: [F; 3],
    /// Edge functions: `e[i]` is the 2-D cross product of the two corners
    /// other than `i` (in order `i+1, i+2`), with its sign exact.
    pub(crate) e: [F; 3],
}

impl<F: Scalar> Frame<F> {
    /// The corners' depths along the ray in units of `t`: `p_z / d_z`,
    /// computed as `p_z fl(1 / d_z)`.
    #[inline(always)]
    pub(crate) fn scaled_z(&self, shear: &Shear<F>) -> [F; 3] {
        self.pz.map(|p| p * shear.sz)
    }

    #[inline(always)]
    pub(crate) fn new<V: Vector<Scalar = F>>(
        origin: V,
        tri: &Triangle<V>,
        shear: &Shear<F>,
    ) -> Self {
        let mut f = Frame {
            x: [F::ZERO; 3],
            y: [F::ZERO; 3],
            px: [F::ZERO; 3],
            py: [F::ZERO; 3],
            pz: [F::ZERO; 3],
            e: [F::ZERO; 3],
        };
        for (i, p) in [tri.a, tri.b, tri.c].into_iter().enumerate() {
            [f.px[i], f.py[i], f.pz[i], f.x[i], f.y[i]] = project(origin, p, shear);
        }
        for i in 0..3 {
            f.e[i] = edge_function(
                (f.x[(i + 1) % 3], f.y[(i + 1) % 3]),
                (f.x[(i + 2) % 3], f.y[(i + 2) % 3]),
            );
        }
        f
    }
}

/// A corner in the ray's frame: translated, permuted (`px, py, pz`) and
/// sheared (`x, y`), as [`Frame::new`] computes each of its corners.
#[inline(always)]
fn project<V: Vector>(origin: V, p: V, shear: &Shear<V::Scalar>) -> [V::Scalar; 5] {
    let (px, py, pz) = shear.permute(p - origin);
    [px, py, pz, px + shear.sx * pz, py + shear.sy * pz]
}

/// The edge function of the edge from `(xj, yj)` to `(xk, yk)` in the
/// sheared plane, `xj yk - yj xk`, with its sign exact: rounding is
/// monotone, so `fl(fl(ab) - fl(cd))` has the sign of `ab - cd` or is
/// zero, and only a zero needs the exact recomputation (Woop, Benthin and
/// Wald, JCGT 2013, section 3). Two shapes sharing the edge compute it
/// bit for bit (negated where they run it the other way).
#[inline(always)]
pub(crate) fn edge_function<F: Scalar>((xj, yj): (F, F), (xk, yk): (F, F)) -> F {
    let e = xj * yk - yj * xk;
    if e == F::ZERO {
        F::diff_of_products_exact_sign(xj, yk, yj, xk)
    } else {
        e
    }
}
