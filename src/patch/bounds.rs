//! The patch's error bounds, all derived here: a certificate that the
//! exact patch meets the exact ray near the computed `(u, v)` (and so
//! bounds on `u`, `v` and `t`), and the bounds of a surface point and its
//! normal.
//!
//! Notation: `u` (as a bound) is the unit roundoff and `gamma(n) = n u /
//! (1 - n u)`. `Q(u, v)` is the bilinear map of the computed projected
//! corners `q_ij = (x_ij, y_ij)` and `Z(u, v)` that of their computed
//! depths `z_ij` (in units of `t`); `Q*` and `Z*` are the same for the
//! exact corners in the exact sheared frame, where the exact ray is the
//! `z` axis. The triangle's bounds give `|q_ij - q*_ij| <= eq` (each
//! coordinate) and `|z_ij - z*_ij| <= ez` ([`corner_errors`]); bilinear
//! weights sum to one, so `|Q - Q*| <= S eq` and `|Z - Z*| <= S ez`
//! wherever the absolute weights sum to at most `S` (`S = (1 + 2 r)^2`
//! within `r` of the unit square).

use super::Patch;
use super::frame::{Framed, Projected, RayFrame};
use crate::num::round::outward::{add_down, mul_down, sub_down};
use crate::num::round::{bound_up, max2};
use crate::num::{Axis, L, Lanes, S, Scalar, Vector};
use crate::triangle::{axis_error, depth_error};

/// Bounds on the distance of a computed hit from a crossing of the exact
/// patch with the exact ray: `t` (the computed depth `fl(Z(u, v))`) and
/// `u`, `v` (each). Infinite where no crossing could be certified near
/// `(u, v)`.
#[derive(Clone, Copy, Debug)]
pub(super) struct Certified<F> {
    pub(super) t: F,
    pub(super) uv: F,
}

/// The largest magnitude among four values; infinite where one is not
/// finite (and then every bound below is).
#[inline(always)]
fn max4<F: Scalar>(v: &[F; 4]) -> F {
    if !v.iter().all(|x| x.abs() <= F::MAX) {
        return F::INFINITY;
    }
    v.iter()
        .fold(F::ZERO, |m, x| if x.abs() > m { x.abs() } else { m })
}

/// The `twist` `(c11 - c10) - (c01 - c00)` of bilinear values `c` (in the
/// boundary's order).
#[inline(always)]
fn twist<F: Scalar>(c: &[F; 4]) -> F {
    (c[2] - c[1]) - (c[3] - c[0])
}

/// The certificate's part before any division (see [`certify`] for the
/// derivation): a lower bound on `|det M|`, upper bounds on the
/// numerators of `a` (`|M^-1|`) and `c` (`|M^-1 k|`) over it, and the
/// computed residual with the corners' largest projected magnitude.
struct Linear<F> {
    det_lo: F,
    a_num: F,
    c_num: F,
    miss: F,
    mxy: F,
}

impl<F: Scalar> Linear<F> {
    /// At `(u, v)`; `None` where `|det M|` cannot be bounded away from
    /// zero (or a corner is not finite).
    #[inline(always)]
    fn at(p: &Projected<F>, u: F, v: F) -> Option<Self> {
        let g = F::gamma_n;
        let (x, y) = (&p.x, &p.y);
        let mxy = max2(max4(x), max4(y));
        // The Jacobian: columns Q_u = (m11, m21), Q_v = (m12, m22).
        let (qu, qv) = (p.d_du(x, v), p.d_dv(x, u));
        let (ru, rv) = (p.d_du(y, v), p.d_dv(y, u));
        let (m11, m12, m21, m22) = (qu.abs(), qv.abs(), ru.abs(), rv.abs());
        // eM (1 rounding).
        let em = g(9) * mxy;
        let det = (qu * rv - qv * ru).abs();
        // (5 roundings: the products' sum, times gamma(2), then two sums.)
        let det_err = bound_up(
            g(2) * (m11 * m22 + m12 * m21) + em * ((m11 + m22) + (m12 + m21)) + em * em * F::TWO,
            5,
        );
        let det_lo = sub_down(det, det_err);
        if !(det_lo > F::ZERO) {
            return None;
        }
        let (row_u, row_v) = (m22 + m12, m11 + m21);
        // The twist, and `|adj(M) k|`: each component (`m22 kx - m12
        // ky`, `m11 ky - m21 kx`) is within `gamma(2)` of its products'
        // magnitudes of the computed one, and replacing the computed
        // `M`, `k` by the exact ones (each entry within `eM`, `ek = eM`)
        // moves it by at most `eM (|kx| + |ky|) + (its row of |adj M|) eM
        // + 2 eM^2`.
        let (kx, ky) = (twist(x), twist(y));
        let (akx, aky) = (kx.abs(), ky.abs());
        let component = |p: F, q: F, pk: F, qk: F, row: F| {
            (p * pk - q * qk).abs()
                + g(2) * (p.abs() * pk.abs() + q.abs() * qk.abs())
                + em * (akx + aky)
                + row * em
                + em * em * F::TWO
        };
        let cu = component(rv, qv, kx, ky, row_u);
        let cv = component(qu, ru, ky, kx, row_v);
        Some(Self {
            det_lo,
            // (2: a row's sum, plus 2 eM.)
            a_num: bound_up(max2(row_u, row_v) + em * F::TWO, 2),
            // (7: the products' sum times gamma(2), then four sums.)
            c_num: bound_up(max2(cu, cv), 7),
            miss: p.miss_at(u, v),
            mxy,
        })
    }

    /// `beta` for the weight bound `s`: the exact residual at `(u, v)` of
    /// the computed corners (within `gamma(7) m` of the computed one) plus
    /// `s eq`. (3 roundings: two products, two sums.)
    #[inline(always)]
    fn beta(&self, s: F, eq: F) -> F {
        bound_up(self.miss + F::gamma_n(7) * self.mxy + s * eq, 3)
    }
}

/// Whether the exact patch, extended bilinearly, is certified to meet the
/// exact ray within `1/4` of `(u, v)`, by a test without division that
/// implies [`certify`]'s first radius (so it may fail where that holds):
/// `4 a c beta <= 1` as `4 a_num c_num beta <= det_lo^2`, and `2 a beta <=
/// 1/4` (the radius is at most `2 a beta`) as `8 a_num beta <= det_lo`.
#[inline(never)]
pub(super) fn meets<F: Scalar>(p: &Projected<F>, eq: F, u: F, v: F) -> bool {
    let Some(l) = Linear::at(p, u, v) else {
        return false;
    };
    let beta = l.beta(F::from_f64(2.25), eq);
    // (2 roundings each: two products; the factors 4 and 8 are exact.)
    let contracts = bound_up(l.a_num * l.c_num * beta * F::from_u32(4), 2);
    let reach = bound_up(l.a_num * beta * F::from_u32(8), 1);
    (contracts <= mul_down(l.det_lo, l.det_lo)) & (reach <= l.det_lo)
}

/// The certificate for the computed point `(u, v)` of the unit square.
///
/// Evaluation: `lerp(a, b, w) = fl(fl(fl(1 - w) a) + fl(w b))` with `w` in
/// `[0, 1]` is within `gamma(3) max(|a|, |b|)` of `(1 - w) a + w b`; two
/// levels (a bilinear value) within `gamma(7) m`, `m` the largest corner
/// magnitude; a derivative `lerp(a1 - a0, b1 - b0, w)`, whose differences
/// round once (each at most `2 m`), within `gamma(9) m`; the twist `k =
/// (q11 - q10) - (q01 - q00)` within `gamma(9) m` likewise.
///
/// The crossing. With `M` the Jacobian of `Q` at `(u, v)` and `k` its
/// twist, `Q(u + du, v + dv) = Q(u, v) + M (du, dv) + k du dv` exactly (a
/// bilinear map). A crossing `Q*(w + d) = 0` is a fixed point of `T(d) =
/// -M^-1 (Q(w) + k du dv + (Q* - Q)(w + d))`. With `a >= |M^-1|` (max
/// norm), `c >= |M^-1 k|`, `beta >= |Q(w)| + S eq` and `|d| <= r`:
/// `|T(d)| <= a beta + c r^2`, at most `r` for `r` the smaller root of `c
/// r^2 - r + a beta` (real where `4 a c beta <= 1`; at most `2 a beta`),
/// so `T` maps the closed ball into itself and (Brouwer) has a fixed
/// point: the exact patch, extended bilinearly, meets the exact ray at
/// some `w + d` with `|d| <= r`. A first radius with `S = 9/4` (valid up
/// to `r = 1/4`) gives `S = (1 + 2 r)^2` for a second, smaller one. Then
/// `t* = Z*(w + d)` and `|fl(Z(w)) - t*| <= (|Z_u| + |Z_v|) r + |k_z| r^2 +
/// S ez + gamma(7) m_z`.
///
/// `|M^-1| = max(|m22| + |m12|, |m21| + |m11|) / |det M|`; the computed
/// entries are within `eM = gamma(9) m` of `M`'s, and `|det M| >= |fl(det)|
/// - gamma(2) (|m11 m22| + |m12 m21|) - eM sum |m_ij| - 2 eM^2`.
///
/// Rounding of the bounds themselves: each is a sum of products (and
/// quotients by a lower bound held exactly) of non-negative values, made
/// an upper bound once by [`bound_up`] with the depth of its longest chain
/// of roundings (written beside it; a doubling is exact); only the two
/// differences (`det M`'s lower bound, `1 - 4 a c beta`) and the square
/// root below them are rounded down step by step.
#[inline(never)]
pub(super) fn certify<F: Scalar>(p: &Projected<F>, eq: F, ez: F, u: F, v: F) -> Certified<F> {
    let none = Certified {
        t: F::INFINITY,
        uv: F::INFINITY,
    };
    let g = F::gamma_n;
    let Some(l) = Linear::at(p, u, v) else {
        return none;
    };
    // (1 more rounding each: the quotient.)
    let a = bound_up(l.a_num / l.det_lo, 1);
    let c = bound_up(l.c_num / l.det_lo, 1);
    // The radius for a weight bound `s` (`S`): the smaller root of `c r^2
    // - r + a beta = 0`, `2 a beta / (1 + sqrt(1 - 4 a c beta))`, at most
    // `2 a beta`, rounded up (the square root's argument and result
    // rounded down); `None` where `4 a c beta > 1`. `beta` is the exact
    // residual at `(u, v)` of the computed corners, within `gamma(7)
    // m` of the computed one, plus `s eq`.
    let radius_for = |s: F| {
        let beta = l.beta(s, eq);
        // (2: two products; the factor 4 is exact.)
        let contracts = bound_up(a * c * beta * F::from_u32(4), 2);
        let root = sub_down(F::ONE, contracts);
        (root >= F::ZERO).then(|| {
            let denom = add_down(F::ONE, root.sqrt().next_down());
            // (2: a product, over denom.)
            bound_up(a * beta * F::TWO / denom, 2)
        })
    };
    // First with `S = 9/4` (for a radius up to 1/4), then with the `S`
    // of that radius, `(1 + 2 r)^2`, which bounds the weights over the
    // second, smaller radius too.
    let quarter = F::from_f64(0.25);
    let first = match radius_for(F::from_f64(2.25)) {
        Some(r0) if r0 <= quarter => r0,
        _ => return none,
    };
    // (2: a sum, squared.)
    let reach = F::ONE + first * F::TWO;
    let weights = bound_up(reach * reach, 2);
    let Some(radius) = radius_for(weights) else {
        return none;
    };
    // The depth: its derivatives' and twist's computed values, each
    // within `gamma(9) m_z` (7: the slope's 2, times the radius, then
    // the sums).
    let z = &p.z;
    let mz = max4(z);
    let (zu, zv) = (p.d_du(z, v).abs(), p.d_dv(z, u).abs());
    let ez_d = g(9) * mz;
    let slope = (zu + zv) + ez_d * F::TWO;
    let kz = twist(z).abs() + ez_d;
    let t = bound_up(
        slope * radius + kz * radius * radius + weights * ez + g(7) * mz,
        7,
    );
    if !(t.is_finite() && radius.is_finite()) {
        return none;
    }
    Certified { t, uv: radius }
}

/// A bound on each coordinate of `point_at(u, v)` (for `u`, `v` in `[0,
/// 1]`) against the exact `P(u, v)`: `gamma(7)` times the corners' largest
/// magnitude in that coordinate (see [`certify`]).
#[inline]
pub(super) fn point_error<F: Scalar>(m: [F; 3]) -> [F; 3] {
    m.map(|m| bound_up(F::gamma_n(7) * m, 1))
}

/// A bound on each component of the computed normal `du x dv` at `(u,
/// v)` against the exact `dP/du x dP/dv` there, given the computed
/// derivatives and the corners' largest magnitude per coordinate `m`:
/// each derivative component is within `e_j = gamma(9) m_j` (see
/// [`certify`]), so component `i` (`j, k` the next two) is within
/// `gamma(2) (|du_j dv_k| + |du_k dv_j|) + |du_j| e_k + e_j (|dv_k| + e_k)
/// + |du_k| e_j + e_k (|dv_j| + e_j)`.
#[inline]
pub(super) fn normal_error<F: Scalar>(du: [F; 3], dv: [F; 3], m: [F; 3]) -> [F; 3] {
    let e = m.map(|m| F::gamma_n(9) * m);
    let (du, dv) = (du.map(F::abs), dv.map(F::abs));
    [0, 1, 2].map(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        bound_up(
            F::gamma_n(2) * (du[j] * dv[k] + du[k] * dv[j])
                + du[j] * e[k]
                + e[j] * (dv[k] + e[k])
                + du[k] * e[j]
                + e[k] * (dv[j] + e[j]),
            4,
        )
    })
}

impl<F: Scalar> Framed<F> {
    /// [`meets`] at `(u, v)`, with the corners' projection bounds
    /// ([`corner_errors`]).
    #[inline(never)]
    pub(super) fn meets<V: Vector<Scalar = F>>(
        &self,
        r: &RayFrame<V>,
        patch: &Patch<V>,
        u: F,
        v: F,
    ) -> bool {
        let (eq, _) = corner_errors(r, patch, &self.p);
        eq.is_finite() && meets(&self.p, eq, u, v)
    }

    /// The certificate at `(u, v)`, with the corners' projection bounds
    /// ([`corner_errors`]).
    #[inline(never)]
    pub(super) fn certify<V: Vector<Scalar = F>>(
        &self,
        r: &RayFrame<V>,
        patch: &Patch<V>,
        u: F,
        v: F,
    ) -> Certified<F> {
        let (eq, ez) = corner_errors(r, patch, &self.p);
        if !(eq.is_finite() && ez.is_finite()) {
            return Certified {
                t: F::INFINITY,
                uv: F::INFINITY,
            };
        }
        certify(&self.p, eq, ez, u, v)
    }
}

/// Bounds on the computed corners' distance from the exact ones in the
/// exact sheared frame: `eq` on each of `x` and `y`, `ez` on the depth.
/// They are the triangle test's (`ErrorBounds`: `axis_error`,
/// `depth_error`), which hold for every corner of a frame computed as the
/// triangle test computes it (the patch's corners are) with the largest
/// magnitudes over its corners: here over all four.
#[inline(always)]
fn corner_errors<V: Vector>(
    r: &RayFrame<V>,
    patch: &Patch<V>,
    p: &Projected<S<V>>,
) -> (S<V>, S<V>) {
    let corners = |k: Axis| patch.boundary_lanes(k);
    let [ox, oy, oz] = *r.origin_lanes;
    let [kx, ky, kz] = r.axes;
    let largest = |c: [S<V>; 4]| c.iter().fold(S::<V>::ZERO, |m, &w| max2(m, w.abs()));
    let translated = |k: Axis, o: L<V>| largest(corners(k).sub(o).to_array4());
    let (mpx, mpy, mpz) = (translated(kx, ox), translated(ky, oy), translated(kz, oz));
    let [sx, sy, _] = *r.shear_lanes;
    let dx = axis_error(mpx, largest(p.x), sx.x(), mpz);
    let dy = axis_error(mpy, largest(p.y), sy.x(), mpz);
    (max2(dx, dy), depth_error(largest(p.z)))
}

#[cfg(test)]
mod tests {
    use super::{Projected, certify, meets};
    use crate::testing::Draws;

    /// `meets` is a sufficient test for `certify`'s first radius: where it
    /// holds, the full certificate holds too (an unsound shortcut would
    /// claim crossings the derivation does not), and it holds on most of
    /// the points where the certificate does (nine in ten here; a test
    /// that never passed would make it useless, not wrong). Points: the
    /// corners on the grid of eighths in `[-4, 4]` or, in one draw in
    /// four, scaled by a random binade; `(u, v)` a crossing's, nudged by
    /// up to half the scale.
    #[test]
    fn meets_implies_the_certificate() {
        let mut d = Draws(0x9e37_79b9_7f4a_7c15);
        let (mut both, mut certified) = (0, 0);
        for i in 0..20_000 {
            let scale = if i % 4 == 0 {
                2f32.powi((d.next() % 40) as i32 - 20)
            } else {
                1.0
            };
            let mut corner = || d.eighth() * scale;
            let p = Projected {
                x: [corner(), corner(), corner(), corner()],
                y: [corner(), corner(), corner(), corner()],
                z: [1.0, 2.0, 3.0, 4.0],
            };
            let (u, v) = (
                (d.next() % 1025) as f32 / 1024.0,
                (d.next() % 1025) as f32 / 1024.0,
            );
            // Moved so that the origin projects to `(u, v)` up to a small
            // residual: each corner shifted by the point at `(u, v)`.
            let (px, py) = (p.point(&p.x, u, v), p.point(&p.y, u, v));
            // Residual and corner bounds from `2^-24` to `1/2` of the
            // scale, so that some points are near the certificate's limit.
            let mut binade = || 2f32.powi(-((d.next() % 24) as i32) - 1) * scale;
            let nudge = binade();
            let eq = binade();
            let p = Projected {
                x: p.x.map(|c| c - px + nudge),
                y: p.y.map(|c| c - py),
                z: p.z,
            };
            let full = certify(&p, eq, 1e-7, u, v).uv.is_finite();
            if meets(&p, eq, u, v) {
                assert!(full, "{:?} {:?} ({u}, {v})", p.x, p.y);
                both += 1;
            }
            certified += usize::from(full);
        }
        assert!(certified > 1000, "{both} {certified}");
        assert!(both * 10 > certified * 9, "{both} of {certified}");
    }

    impl Projected<f32> {
        /// The bilinear value of `c` at `(u, v)`.
        fn point(&self, c: &[f32; 4], u: f32, v: f32) -> f32 {
            let lerp = |a: f32, b: f32, w: f32| a + (b - a) * w;
            lerp(lerp(c[0], c[1], u), lerp(c[3], c[2], u), v)
        }
    }
}
