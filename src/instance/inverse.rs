//! Building an [`Instance`]: the stored inverse, and the bounds on its error
//! measured from the matrix itself.
//!
//! # The inverse
//!
//! `A` is the adjugate of `M` over its determinant, evaluated in `f64` and
//! rounded to the instance's precision (for `f32` matrices this is the
//! correctly rounded inverse but for a few ulps; for `f64` it is whatever
//! `f64` arithmetic gives). `b = -A T`, evaluated in `f64` from the
//! *stored* `A` and rounded. Nothing below assumes either is accurate.
//!
//! # The residual
//!
//! `R = M A - I`, entrywise. In `f64`, `fl(sum_k M_ik A_kj - delta_ij)` is a
//! dot product of length four (the `-delta_ij` as a fourth term with an
//! exact product), so (Higham, "Accuracy and Stability of Numerical
//! Algorithms", (3.5))
//!
//! ```text
//! |R_ij| <= |fl(...)| + gamma_64(4) (sum_k |M_ik| |A_kj| + delta_ij) + 6 tiny_64
//! ```
//!
//! where the last term covers products and sums that fall into the
//! subnormal range (each loses at most half of `tiny_64`, the smallest
//! subnormal, in absolute terms, and six roundings happen). For `f32`
//! matrices the products are exact in `f64`, and the bound is within a few
//! `f64` ulps of the true residual: the cheap way to a tight bound that
//! pbrt-v4 and OptiX's self-intersection avoidance do not take (they assume
//! an inverse accurate to an ulp or so). `beta = M b + T` is bounded the
//! same way:
//! `|beta_i| <= |fl(...)| + gamma_64(4) (sum_k |M_ik| |b_k| + |T_i|) + 6 tiny_64`.
//!
//! Each bound, a sum of products of non-negative `f64` values, is made an
//! upper bound of its exact value with `bound_up`, then converted to the
//! instance's precision rounding up.
//!
//! # The derived matrices (used in `ray.rs` and `surface.rs`)
//!
//! With `Rb` the residual bound, `|M||A|` evaluated rounding up and `g(n)`
//! the instance precision's `gamma(n)`:
//!
//! ```text
//! K_o = Rb + g(4) |M||A|          c_o = |beta|b + g(4) |M||b| + U
//! K_d = Rb + g(3) |M||A|          c_d = U
//! U   = MIN_POSITIVE (1 + max_i sum_j |M_ij|)
//! c_p = g(4) |T| + U
//! ```
//!
//! each evaluated in `f64`, made an upper bound with `bound_up` and
//! rounded up to the instance's precision (`c_p` is evaluated with `U`
//! as stored, itself rounded up; a product `g(4) |T_i|` that underflows
//! `f64` loses at most half an `f64` `TINY`, one more of the roundings
//! `U` covers).
//!
//! `U` covers every rounding of the per-ray arithmetic that falls into
//! the subnormal range (at most half a `TINY` each, a few dozen of them,
//! mapped through `M`; `MIN_POSITIVE` is `2^23` or `2^52` `TINY`).
//! `rho = max_j sum_i Rb_ij` (the largest column sum, the infinity norm of
//! `R^T`) must be at most `1/2`, else the instance is
//! [`InstanceError::IllConditioned`]; the normal's bound divides by
//! `1 - rho`.

use super::{Four, Instance, InstanceError};
use crate::num::round::bound_up;
use crate::num::{S, Scalar, Vector};

/// The smallest `F` at least `x` (`x` not NaN).
fn up_to<F: Scalar>(x: f64) -> F {
    let y = F::from_f64(x);
    if y.to_f64() >= x { y } else { y.next_up() }
}

/// The instance of `M` (columns `cols`) and `T`; see [`Instance::new`].
pub(super) fn build<V: Vector>(cols: [V; 3], t: V) -> Result<Instance<V>, InstanceError> {
    if !(cols[0].is_finite() && cols[1].is_finite() && cols[2].is_finite() && t.is_finite()) {
        return Err(InstanceError::NotFinite);
    }
    // M and T in f64 (exact).
    let m = |i: usize, j: usize| cols[j][i].to_f64();
    let tt = |i: usize| t[i].to_f64();
    // The adjugate: adj_ij = cofactor_ji.
    let cof = |i: usize, j: usize| {
        let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
        let (j1, j2) = ((j + 1) % 3, (j + 2) % 3);
        m(i1, j1) * m(i2, j2) - m(i1, j2) * m(i2, j1)
    };
    let det = m(0, 0) * cof(0, 0) + m(0, 1) * cof(0, 1) + m(0, 2) * cof(0, 2);
    if det == 0.0 {
        return Err(InstanceError::Singular);
    }
    if !det.is_finite() {
        return Err(InstanceError::Overflow);
    }
    let mut a = [[S::<V>::ZERO; 3]; 3];
    for (i, row) in a.iter_mut().enumerate() {
        for (j, entry) in row.iter_mut().enumerate() {
            *entry = S::<V>::from_f64(cof(j, i) / det);
            if !entry.is_finite() {
                return Err(InstanceError::Overflow);
            }
        }
    }
    let af = |i: usize, j: usize| a[i][j].to_f64();
    let mut b = [S::<V>::ZERO; 3];
    for (i, bi) in b.iter_mut().enumerate() {
        *bi = S::<V>::from_f64(-(af(i, 0) * tt(0) + af(i, 1) * tt(1) + af(i, 2) * tt(2)));
        if !bi.is_finite() {
            return Err(InstanceError::Overflow);
        }
    }
    let bf = |i: usize| b[i].to_f64();

    // The residual bound Rb, |M||A| and |M||b| in f64, each rounded up.
    let g64 = f64::gamma_n(4);
    let tiny6 = 6.0 * f64::TINY;
    let mut rb = [[0.0f64; 3]; 3];
    let mut ma = [[0.0f64; 3]; 3];
    let mut beta = [0.0f64; 3];
    let mut mb = [0.0f64; 3];
    for i in 0..3 {
        for j in 0..3 {
            let delta = if i == j { 1.0 } else { 0.0 };
            let s = m(i, 0) * af(0, j) + m(i, 1) * af(1, j) + m(i, 2) * af(2, j) - delta;
            let abs = (m(i, 0) * af(0, j)).abs()
                + (m(i, 1) * af(1, j)).abs()
                + (m(i, 2) * af(2, j)).abs();
            // |fl| + gamma(4) (abs + delta) + tiny: at most 6 roundings on
            // a path of the evaluation.
            rb[i][j] = bound_up(s.abs() + g64 * (abs + delta) + tiny6, 6);
            ma[i][j] = bound_up(abs + tiny6, 3);
        }
        let s = m(i, 0) * bf(0) + m(i, 1) * bf(1) + m(i, 2) * bf(2) + tt(i);
        let abs = (m(i, 0) * bf(0)).abs() + (m(i, 1) * bf(1)).abs() + (m(i, 2) * bf(2)).abs();
        beta[i] = bound_up(s.abs() + g64 * (abs + tt(i).abs()) + tiny6, 6);
        mb[i] = bound_up(abs + tiny6, 3);
    }
    // rho: the largest column sum of Rb.
    let col_sum = |j: usize| bound_up(rb[0][j] + rb[1][j] + rb[2][j], 2);
    let rho = col_sum(0).max(col_sum(1)).max(col_sum(2));
    if !rho.is_finite() {
        return Err(InstanceError::Overflow);
    }
    if !(rho <= 0.5) {
        return Err(InstanceError::IllConditioned);
    }
    // 1 - rho >= 1/2 is exact (Sterbenz), so the quotient has one rounding.
    let one_minus_rho = 1.0 - rho;

    let (g3, g4) = (S::<V>::gamma_n(3).to_f64(), S::<V>::gamma_n(4).to_f64());
    let row_sum_m = (0..3).fold(0.0f64, |acc, i| {
        acc.max(bound_up(m(i, 0).abs() + m(i, 1).abs() + m(i, 2).abs(), 2))
    });
    let tiny_world = S::<V>::MIN_POSITIVE.to_f64() * bound_up(1.0 + row_sum_m, 2);
    let tiny_world = bound_up(tiny_world, 1);

    let vec = |f: &dyn Fn(usize) -> f64| -> V { V::new(up_to(f(0)), up_to(f(1)), up_to(f(2))) };
    // A matrix's columns, each entry rounded up: column `j` holds entries
    // `(0, j)`, `(1, j)`, `(2, j)`.
    let cols_of = |f: &dyn Fn(usize, usize) -> f64| -> [Four<V>; 3] {
        [0, 1, 2].map(|j| Four::new(vec(&|i| f(i, j))))
    };
    let k_origin = cols_of(&|i, j| bound_up(rb[i][j] + g4 * ma[i][j], 2));
    let k_dir = cols_of(&|i, j| bound_up(rb[i][j] + g3 * ma[i][j], 2));
    let c_origin = vec(&|i| bound_up(beta[i] + g4 * mb[i] + tiny_world, 3));
    // `U` as the per-ray and per-hit arithmetic adds it (and `c_d`):
    // rounded up to the precision.
    let u = vec(&|_| tiny_world);
    let tiny_up = u[0].to_f64();
    // c_p = g(4) |T| + U: a product and a sum in f64.
    let c_point = vec(&|i| bound_up(g4 * tt(i).abs() + tiny_up, 2));
    let normal_residual = vec(&|j| bound_up(col_sum(j) / one_minus_rho, 1));

    let a_rows = [0, 1, 2].map(|i| V::new(a[i][0], a[i][1], a[i][2]));
    let a_cols = [0, 1, 2].map(|j| V::new(a[0][j], a[1][j], a[2][j]));
    let finite = |v: &[V]| v.iter().all(|r| r.is_finite());
    if !(finite(&k_origin.map(|c| c.get()))
        && finite(&k_dir.map(|c| c.get()))
        && finite(&[c_origin, c_point, normal_residual, u]))
    {
        return Err(InstanceError::Overflow);
    }
    let four = |v: [V; 3]| v.map(Four::new);
    let inst = Instance {
        m_cols: four(cols),
        t: Four::new(t),
        a_cols: four(a_cols),
        b: Four::new(V::new(b[0], b[1], b[2])),
        a_rows: four(a_rows),
        m_abs_cols: four(cols.map(Vector::abs)),
        a_abs_rows: four(a_rows.map(Vector::abs)),
        k_origin,
        c_origin: Four::new(c_origin),
        k_dir,
        c_point: Four::new(c_point),
        normal_residual: Four::new(normal_residual),
        tiny_world: Four::new(u),
    };
    Ok(inst)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DVec3, Vec3};

    #[test]
    fn an_exact_inverse_has_a_tiny_residual() {
        // diag(4, 2, 1/2) is inverted exactly: R = 0, so its bound is only
        // the f64 evaluation's a-priori term, gamma_64(4) (|M||A| + I) =
        // 2 gamma_64(4) ~ 8.9e-16 on the diagonal, far below f32's u.
        let i = build([Vec3::X * 4.0, Vec3::Y * 2.0, Vec3::Z * 0.5], Vec3::ZERO).unwrap();
        assert_eq!(i.inverse().0[0], Vec3::new(0.25, 0.0, 0.0));
        let normal_residual: Vec3 = i.normal_residual.get();
        assert!(normal_residual.max_element() < 1e-15);
        assert!(normal_residual.min_element() > 0.0);
    }

    #[test]
    fn bad_matrices_are_errors() {
        let nan = DVec3::new(f64::NAN, 0.0, 0.0);
        assert_eq!(
            build([nan, DVec3::Y, DVec3::Z], DVec3::ZERO),
            Err(InstanceError::NotFinite)
        );
        let inf = DVec3::splat(f64::INFINITY);
        assert_eq!(
            build([DVec3::X, DVec3::Y, DVec3::Z], inf),
            Err(InstanceError::NotFinite)
        );
        assert_eq!(
            build([DVec3::X, DVec3::Y, DVec3::ZERO], DVec3::ZERO),
            Err(InstanceError::Singular)
        );
        // A determinant that overflows f64.
        let big = DVec3::splat(1e200);
        assert_eq!(
            build(
                [big * DVec3::X, big * DVec3::Y, big * DVec3::Z],
                DVec3::ZERO
            ),
            Err(InstanceError::Overflow)
        );
    }
}
