//! Whether a triangle or quad case is clear of the kernels' rounding, and
//! the float filter in front of exact arithmetic that decides the watertight
//! test's clear misses: the Plucker products in `f64` with error bounds,
//! the margin the test's edge functions are known within, and the exact
//! expansion of a product where the bounds do not decide.

use super::triangle::{ExactTriangle, main_axis, mt_bounds, no_extra, triangle, triangle_decided};
use super::values::*;
use crate::num::exact_sign::{Expansion, scale2, two_diff};
use crate::{Ray, Scalar, Triangle, Vector};
use num_traits::Signed;
use std::vec::Vec;

/// The triangle case is decided outside the watertight test's rounding band
/// widened by Moller-Trumbore's: [`triangle_decided`] with [`mt_bounds`], or
/// a line that crosses the plane outside the triangle by more than both
/// tests' rounding ([`surely_outside`]). A line parallel to the plane, or a
/// triangle of zero area, is never clear: a determinant that is zero in exact
/// arithmetic can round to either sign, and Moller-Trumbore's `u`, `v` and
/// `t` are then unbounded. False when a coordinate is not finite.
#[must_use]
pub fn triangle_clear<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>, t_max: V::Scalar) -> bool {
    let Some(ex) = triangle(ray, tri) else {
        return false;
    };
    let Some((ue, ve)) = &ex.uv else {
        return false;
    };
    let Some(mte) = mt_bounds(ray, tri, ue, ve) else {
        return false;
    };
    triangle_decided(ray, tri, &ex, t_max, &mte).is_some() || surely_outside(ray, tri, &ex, &mte)
}

/// The triangle case is decided outside the watertight test's rounding
/// band: [`triangle_decided`] with no widening, or a line that passes the
/// triangle by more than the test's rounding of its edge functions
/// ([`surely_outside_watertight`]). `exact` must be
/// [`triangle`]`(ray, tri)`, computed once by the caller.
///
/// What it decides: the answer of every watertight form of the crate (the
/// closed test and its prepared, interval and batch forms, and the one-hit
/// test, which differs only on edge functions that are exactly zero) is
/// exact arithmetic's answer (`exact.hits`) wherever this is `true`.
/// [`triangle_clear`] decides the same for the watertight test and
/// Moller-Trumbore together, with the band widened by Moller-Trumbore's
/// bounds; this is its watertight half. It is `true` wherever
/// [`triangle_clear`] is (the same tests with a narrower band), and also
/// where only Moller-Trumbore's rounding keeps that one `false`: near
/// parallel lines, where its determinant's error bound swamps the
/// determinant, and lines that are exactly parallel to the plane (or
/// triangles of zero area) whose edge functions have opposite strict
/// signs.
///
/// Why it is sound: [`triangle_decided`] with zeros is the watertight
/// test's own documented error bound evaluated at the exact crossing (its
/// derivation there), and [`surely_outside_watertight`] is a miss on the
/// edge functions' signs alone (its derivation there). False when a
/// coordinate is not finite.
#[must_use]
pub fn triangle_clear_watertight<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    exact: &ExactTriangle,
    t_max: V::Scalar,
) -> bool {
    // (The float filter first: it settles most misses cheaply.)
    surely_outside_watertight(ray, tri)
        || triangle_decided(ray, tri, exact, t_max, &no_extra()).is_some()
}

/// The quad case is decided outside the quad test's rounding band: each
/// of the quad's two triangles (`a, b, c` and `a, c, d`) is decided
/// outside the watertight test's band ([`triangle_clear_watertight`]),
/// and where both are crossed in `(0, t_max]` their exact crossings are
/// farther apart than the sum of the watertight test's bounds on their
/// `t` at those crossings, `T_i / (1 - 3 e_i)` each (`T_i` and `e_i` the
/// triangle's `t` and largest barycentric bound from
/// [`Triangle`'s `hit_error`](crate::Triangle#method.hit_error) at the
/// exact crossing).
///
/// Why it is sound: the quad test is the watertight triangle test on its
/// two triangles, bit for bit, reporting the hit with the smaller
/// computed `t` (the first where they tie), and [`ray_quad`] is the same
/// rule on the exact crossings. Each triangle clear, each triangle's hit
/// or miss is the exact one; where both hit, the computed `t_i` is within
/// `T_i(t_i) <= T_i / (1 - 3 e_i)` of the exact one (the bound evaluated
/// at the computed `t` against the exact, as [`triangle_decided`]
/// derives), so the separation keeps the order and the quad reports the
/// triangle the exact answer names, with its `u` and `v`. No
/// Moller-Trumbore widening: the quad never runs that test. A ray within
/// rounding of the diagonal, which both triangles share, is not clear
/// (neither triangle is): there either may be reported. False when a
/// coordinate is not finite.
///
/// [`ray_quad`]: crate::exact::ray_quad
#[must_use]
pub fn quad_clear<V: Vector>(ray: &Ray<V>, quad: &crate::Quad<V>, t_max: V::Scalar) -> bool {
    let limit = limit(t_max);
    let mut spans = Vec::new();
    for tri in quad.triangles() {
        let Some(ex) = triangle(ray, &tri) else {
            return false;
        };
        if !triangle_clear_watertight(ray, &tri, &ex, t_max) {
            return false;
        }
        if ex.hits(&limit) {
            let Some(span) = t_span(ray, &tri, &ex) else {
                return false;
            };
            spans.push(span);
        }
    }
    match spans.as_slice() {
        [(ta, ba), (tb, bb)] => abs(&(ta - tb)) > ba + bb,
        _ => true,
    }
}

/// A triangle hit's exact `t` and the width `T / (1 - 3 e)` around it
/// within which the watertight test's computed `t` lies (see
/// [`quad_clear`]); `None` where a bound is not finite or `3 e >= 1`.
fn t_span<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>, ex: &ExactTriangle) -> Option<(R, R)> {
    let (te, (ue, ve)) = (ex.t.as_ref()?, ex.uv.as_ref()?);
    let as_s = |x: &R| V::Scalar::from_f64(to_f64(x));
    let probe = crate::TriangleHit {
        t: as_s(te),
        u: as_s(ue),
        v: as_s(ve),
        side: crate::Side::Front,
    };
    let err = crate::Surface::hit_error(tri, ray, &probe);
    let (eu, ev, et) = (r(err.u)?, r(err.v)?, r(err.t)?);
    let e = if eu > ev { eu } else { ev };
    let room = int(1) - int(3) * e;
    room.is_positive().then(|| (te.clone(), et / room))
}

/// Every watertight test and Moller-Trumbore miss: the line crosses the
/// plane outside the triangle by more than either's rounding.
///
/// - Watertight ([`surely_outside_watertight`]): two exact Plucker
///   products `s_i`, `s_j` of opposite signs, each larger than `|d_z|`
///   times the bound on the test's computed edge functions' error
///   ([`edge_function_bound`]; the exact edge functions are `s_i / d_z`, up
///   to one shared sign): the computed ones then have opposite strict signs
///   too, and the test rejects on the signs alone, whatever `t`.
/// - Moller-Trumbore (bounds `eu`, `ev` from [`mt_bounds`]): `u < -eu` or
///   `v < -ev` makes the computed one negative; `1 - u - v < -(eu + ev) - 2
///   unit` makes the computed sum exceed `1 + 2 unit`, so its rounding still
///   exceeds 1.
///
/// False when a coordinate is not finite.
#[must_use]
pub fn surely_outside<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    exact: &ExactTriangle,
    mt: &(R, R, R),
) -> bool {
    let Some((ue, ve)) = &exact.uv else {
        return false;
    };
    let (eu, ev) = (&mt.0, &mt.1);
    let w = int(1) - ue - ve;
    let slack = int(2) * constant(V::Scalar::UNIT_ROUNDOFF);
    let mt_outside = ue < &-eu.clone() || ve < &-ev.clone() || w < -(eu + ev + slack);
    mt_outside && surely_outside_watertight(ray, tri)
}

/// Every form of the watertight test misses, on the signs of its edge
/// functions alone: two exact Plucker products `s_i = ((p_i - o) x (p_j -
/// o)) . d` (edges `a->b`, `b->c`, `c->a`) have opposite signs and are each
/// larger in magnitude than the margin `de |d_z|` ([`edge_function_bound`]).
/// Decided by [`surely_outside_watertight_filter`] in floating point where
/// it can (nearly always), else in exact arithmetic; the answer is the
/// exact one either way.
///
/// Why it is sound: in the ray's sheared frame the exact edge functions are
/// `s_i / d_z` (all with one shared sign flip when `d_z < 0`), and the
/// test's computed ones are within `de` of them. So an `s_i > de |d_z|`
/// and an `s_j < -de |d_z|` give two computed edge functions of opposite
/// strict signs, which every edge rule (closed, and the one-hit rule,
/// which only decides exact zeros) rejects before anything else is looked
/// at: whatever `t`, the interval, or whether the line is parallel to the
/// plane or the triangle has zero area. The exact line misses the triangle
/// too (its edge products have mixed signs), so the kernels' miss is the
/// exact answer. This is the watertight half of [`surely_outside`],
/// without Moller-Trumbore's condition.
///
/// False when a coordinate is not finite, the direction is zero, or the
/// computed frame overflows.
#[must_use]
pub fn surely_outside_watertight<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>) -> bool {
    surely_outside_watertight_filter(ray, tri)
        .unwrap_or_else(|| surely_outside_watertight_exact(ray, tri))
}

/// An upper bound, in `f64`, on [`edge_function_bound`]'s margin `de
/// |d_z|` (the Plucker products' units); `None` where the computed frame
/// overflows, an input is not finite, or the bound is not finite.
pub(super) fn edge_margin_up<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>) -> Option<f64> {
    let m = EdgeFrame::new(ray, tri)?.margin(true);
    m.is_finite().then_some(m)
}

/// Upper bounds, in `f64`, on how far the watertight test's computed
/// sheared coordinates `x`, `y` of the triangle's corners are from the
/// exact ones: the `dx = gamma(1) (m_px + m_x) + gamma(4) |s_x| m_pz` and
/// `dy` of [`edge_function_bound`]'s derivation; `None` where the
/// computed frame overflows, an input is not finite, or a bound is not
/// finite.
pub(super) fn coordinate_bound_up<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
) -> Option<(f64, f64)> {
    let (dx, dy) = EdgeFrame::new(ray, tri)?.coordinate_errors(true);
    (dx.is_finite() && dy.is_finite()).then_some((dx, dy))
}

/// [`surely_outside_watertight`] in exact arithmetic throughout.
pub(super) fn surely_outside_watertight_exact<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>) -> bool {
    let Some(margin) = edge_function_bound(ray, tri).map(|(de, dz)| de * dz) else {
        return false;
    };
    let exact = || {
        Some((
            rv(ray.origin)?,
            rv(ray.dir)?,
            [rv(tri.a)?, rv(tri.b)?, rv(tri.c)?],
        ))
    };
    let Some((o, d, corners)) = exact() else {
        return false;
    };
    let p = corners.map(|c| sub(&c, &o));
    let s = [(0, 1), (1, 2), (2, 0)].map(|(i, j)| dot(&cross(&p[i], &p[j]), &d));
    s.iter().any(|x| x > &margin) && s.iter().any(|x| x < &-margin.clone())
}

/// [`surely_outside_watertight`] decided without rationals: `Some(answer)`
/// where floating-point arithmetic decides it (the exact answer), `None`
/// where it cannot (a product within a few `f64` roundings of the margin,
/// inputs beyond `2^±300` in `f64`, an overflow). A filter to run before
/// exact arithmetic: a few dozen float operations per triangle where the
/// line passes it by more than a few roundings, a few hundred (exact
/// expansions) where it passes near an edge or corner.
///
/// What it computes, from the inputs' exact values as `f64` (every `f32`
/// and `f64` is one):
///
/// - the margin `M = de |d_z|` of [`edge_function_bound`] twice, every
///   operation rounded upwards for `M_up >= M` and downwards (and not below
///   zero) for `M_lo <= M` (see `EdgeFrame::margin`);
/// - each Plucker product `s_i` in `f64`, with a bound `err_i` on its error
///   (derived at `plucker_f64`), so the exact one is in `[s_i - err_i, s_i
///   + err_i]` (both ends rounded outwards);
///
/// and places each exact product against `M` and `-M`: beyond `M` where
/// its range is above `M_up`, not beyond where it is at or below `M_lo`;
/// where the range straddles them, the product's exact sign against
/// `M_up` and `M_lo` decides instead (an exact expansion of the product,
/// `PluckerProduct` in `crate::num::exact_sign`, exact for nonzero inputs
/// within `2^±300`, every `f32` included), and only a product strictly
/// between `M_lo` and `M_up` stays unknown. The answer is "some product
/// beyond `M` and some beyond `-M`" in three-valued logic: `Some` wherever
/// the known places settle it. Inputs that are not finite, a zero
/// direction or an overflowing frame give `Some(false)`, as in exact
/// arithmetic.
#[must_use]
pub fn surely_outside_watertight_filter<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
) -> Option<bool> {
    filter(ray, tri, true)
}

/// [`surely_outside_watertight_filter`], with the exact expansions or (for
/// the tests) with the error bounds alone.
pub(super) fn filter<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>, expansions: bool) -> Option<bool> {
    let Some(frame) = EdgeFrame::new(ray, tri) else {
        return Some(false);
    };
    let (lo, up) = (frame.margin(false), frame.margin(true));
    if !(lo.is_finite() && up.is_finite()) {
        return None;
    }
    let w = |p: V| [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()];
    let (o, d, corners) = (w(ray.origin), w(ray.dir), [w(tri.a), w(tri.b), w(tri.c)]);
    let mut products = PluckerProducts {
        o,
        d,
        corners,
        float: plucker_f64(o, d, corners),
        exact: [None, None, None],
        expansions,
    };
    let mut beyond = |sign: f64| {
        let mut unknown = false;
        for i in 0..3 {
            match products.beyond(i, sign, (lo, up)) {
                Some(true) => return Some(true),
                Some(false) => {}
                None => unknown = true,
            }
        }
        (!unknown).then_some(false)
    };
    match beyond(1.0) {
        Some(false) => Some(false),
        above => match (above, beyond(-1.0)) {
            (_, Some(false)) => Some(false),
            (Some(true), Some(true)) => Some(true),
            _ => None,
        },
    }
}

/// The three Plucker products of [`surely_outside_watertight_filter`]: in
/// `f64` with error bounds, and exactly where those do not decide
/// (computed once, when first needed).
struct PluckerProducts {
    o: [f64; 3],
    d: [f64; 3],
    corners: [[f64; 3]; 3],
    float: [(f64, f64); 3],
    exact: [Option<Option<PluckerProduct>>; 3],
    /// Whether to fall back on the exact expansions.
    expansions: bool,
}

impl PluckerProducts {
    /// Whether `sign s_i` (`sign` is 1 or -1) is above the margin, given
    /// as `(M_lo, M_up)`: `Some(true)` above `M_up`, `Some(false)` at most
    /// `M_lo`, `None` unknown.
    fn beyond(&mut self, i: usize, sign: f64, (lo, up): (f64, f64)) -> Option<bool> {
        use crate::num::round::outward::{add_up, sub_down};
        use core::cmp::Ordering;
        let (s, err) = self.float[i];
        if s.is_finite() && err.is_finite() {
            let (low, high) = (sub_down(sign * s, err), add_up(sign * s, err));
            if low > up {
                return Some(true);
            }
            if high <= lo {
                return Some(false);
            }
        }
        if !self.expansions {
            return None;
        }
        let (o, d, c) = (self.o, self.d, self.corners);
        let (p, q) = [(0, 1), (1, 2), (2, 0)][i];
        let exact = self.exact[i]
            .get_or_insert_with(|| PluckerProduct::new(o, d, c[p], c[q]))
            .as_ref()?;
        // `sign s_i > m` is `s_i > m` for sign 1, `s_i < -m` for sign -1.
        let beyond = if sign > 0.0 {
            Ordering::Greater
        } else {
            Ordering::Less
        };
        if exact.cmp(sign * up)? == beyond {
            Some(true)
        } else if exact.cmp(sign * lo)? != beyond {
            Some(false)
        } else {
            None
        }
    }
}

/// The three Plucker products `s_i = ((p_i - o) x (p_j - o)) . d` of the
/// edges `a->b`, `b->c`, `c->a`, computed in `f64`, each with an upper
/// bound on its error: `(s_i, err_i)` with `|s_i - exact s_i| <= err_i`
/// wherever both are finite.
///
/// Derivation, with `u = 2^-53` (`f64`'s unit roundoff), `A = p_i - o`, `B
/// = p_j - o` exact, `a`, `b` their rounded values and `M = sum |A_j B_k
/// d_l|` over the six monomials of `(A x B) . d`:
/// - `a = A (1 + delta)` with `|delta| <= u` (a difference that is
///   subnormal is exact; one that overflows is not finite and declines);
/// - on the path from an input to `s`, each monomial `A_j B_k d_l` meets at
///   most seven roundings: `a_j`, `b_k`, their product, the difference
///   `c_l`, the product with `d_l`, and two sums. So (Higham, Accuracy and
///   Stability of Numerical Algorithms, 2002, lemma 3.1) `|s - S| <=
///   gamma(7) M` where no product underflows;
/// - a product that underflows is off by at most `eta = 2^-1075` instead:
///   the six products `a_j b_k`, each carried on by one `d_l` and three more
///   roundings, and the three `c_l d_l`, by two: at most `(6 max |d_l| + 3)
///   eta (1 + u)^4 <= (6 max |d_l| + 3) 2^-1074`;
/// - `M` is bounded from the computed values: `|A_j| <= |a_j| / (1 - u)`,
///   so `M <= M' / (1 - u)^2` with `M' = sum |a_j| |b_k| |d_l|` evaluated
///   rounded upwards (at least its exact value), and `gamma(7) / (1 -
///   u)^2 = 7u / ((1 - 7u)(1 - u)^2) < 8u = 2^-50`.
///
/// So `err_i = 2^-50 M' + (6 max |d_l| + 3) 2^-1074`, every operation
/// rounded upwards. Addition never needs an underflow term (a subnormal sum
/// or difference of floats is exact). An overflow anywhere leaves `s_i` or
/// `err_i` not finite (no operation here turns an infinity or NaN back into
/// a finite value), so a finite pair was computed with the relative model
/// throughout (a result rounded down to `MAX` is still within `u` of its
/// exact value).
pub(super) fn plucker_f64(o: [f64; 3], d: [f64; 3], corners: [[f64; 3]; 3]) -> [(f64, f64); 3] {
    use crate::num::round::outward::{add_up, mul_up};
    let p = corners.map(|c| [c[0] - o[0], c[1] - o[1], c[2] - o[2]]);
    let dmax = d
        .iter()
        .fold(0.0f64, |m, x| if x.abs() > m { x.abs() } else { m });
    let underflow = mul_up(add_up(mul_up(6.0, dmax), 3.0), f64::from_bits(1));
    [(0, 1), (1, 2), (2, 0)].map(|(i, j)| {
        let (a, b) = (p[i], p[j]);
        let c = [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ];
        let s = c[0] * d[0] + c[1] * d[1] + c[2] * d[2];
        // The six monomials |a_j| |b_k| |d_l|, each rounded up, summed up.
        let mono =
            |j: usize, k: usize, l: usize| mul_up(mul_up(a[j].abs(), b[k].abs()), d[l].abs());
        let magnitude = [
            mono(1, 2, 0),
            mono(2, 1, 0),
            mono(2, 0, 1),
            mono(0, 2, 1),
            mono(0, 1, 2),
            mono(1, 0, 2),
        ]
        .into_iter()
        .fold(0.0, add_up);
        (s, add_up(mul_up(magnitude, EIGHT_U), underflow))
    })
}

/// `8u = 2^-50` for `f64`: the filter's relative error factor (see
/// `plucker_f64`).
const EIGHT_U: f64 = 1.0 / (1u64 << 50) as f64;

/// A bound on how far the watertight test's computed edge functions can be
/// from the exact ones, and `|d_z|`: `(de, |d_z|)`, or `None` where the
/// computed frame overflows or an input is not finite.
///
/// The test's arithmetic is fixed by its algorithm (Woop, Benthin and
/// Wald, JCGT 2013), so its rounded values are computed here the way IEEE
/// arithmetic defines them: in the frame of the main axis `kz`
/// ([`main_axis`]), `kx`, `ky` the next two cyclically, the shear factors
/// `s_x = fl(-d_kx / d_kz)`, `s_y` likewise, and per corner
/// `p = fl(c - o)`, `x = fl(p_kx + fl(s_x p_kz))`, `y` likewise. The edge
/// function of corners `j`, `k` is `e = fl(fl(x_j y_k) - fl(y_j x_k))`
/// (where that is zero the test recomputes its sign exactly, which only
/// brings it closer).
///
/// Derivation, with `u` the unit roundoff, `gamma(n) = n u / (1 - n u)`,
/// `P` the exact translated coordinates, `X = P_kx + S_x P_kz` and `Y` the
/// exact sheared ones, `m_x = max |x_i|`, `m_y = max |y_i|`, and `m_px`,
/// `m_py`, `m_pz` the largest `|p|` per axis:
/// - `x - X = P_kx d_1 + S_x P_kz theta_3 + (p_kx + fl(s_x p_kz)) d_5`
///   (the translation, the shear factor with its product, the sum), so
///   `|x - X| <= gamma(1) (m_px + m_x) + gamma(4) |s_x| m_pz = dx`, and `dy`
///   likewise;
/// - the edge function's own two roundings add `gamma(2) (|x_j y_k| +
///   |y_j x_k|) <= 2 gamma(2) m_x m_y`, and replacing the computed
///   coordinates by the exact ones `2 (m_x dy + m_y dx + dx dy)`;
/// - where products underflow, each rounding is off by up to half a
///   subnormal `tiny` instead: the edge function's two products, the shear
///   products (half a `tiny` each, times the other coordinate, at most
///   `m = max(m_x, m_y)`) and a shear factor that underflowed (half a
///   `tiny`, times `m_pz` and then `m`), all within `4 tiny (1 + m)(1 +
///   m_pz)`.
///
/// So `de = 2 (gamma(2) m_x m_y + m_x dy + m_y dx + dx dy) + 4 tiny (1 +
/// m)(1 + m_pz)`, evaluated here exactly.
#[must_use]
pub fn edge_function_bound<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>) -> Option<(R, R)> {
    let f = EdgeFrame::new(ray, tri)?;
    let [mx, my, mpx, mpy, mpz, sx, sy, dz] = [f.mx, f.my, f.mpx, f.mpy, f.mpz, f.sx, f.sy, f.dz];
    let (mx, my, mpx, mpy, mpz) = (r(mx)?, r(my)?, r(mpx)?, r(mpy)?, r(mpz)?);
    let g = |n: u16| gamma::<V::Scalar>(n);
    let dx = g(1) * (&mpx + &mx) + g(4) * r(sx)? * &mpz;
    let dy = g(1) * (&mpy + &my) + g(4) * r(sy)? * &mpz;
    let m = if mx > my { mx.clone() } else { my.clone() };
    let rounding = int(2) * (g(2) * &mx * &my + &mx * &dy + &my * &dx + &dx * &dy);
    let underflow = int(4) * constant(V::Scalar::TINY) * (int(1) + m) * (int(1) + mpz);
    Some((rounding + underflow, r(dz)?))
}

/// The watertight test's computed frame, as far as [`edge_function_bound`]
/// needs it: the largest `|x_i|`, `|y_i|`, `|p_kx|`, `|p_ky|`, `|p_kz|`,
/// and `|s_x|`, `|s_y|`, `|d_kz|`, floats of the ray's precision.
pub(super) struct EdgeFrame<F> {
    mx: F,
    my: F,
    mpx: F,
    mpy: F,
    mpz: F,
    sx: F,
    sy: F,
    dz: F,
}

impl<F: Scalar> EdgeFrame<F> {
    /// The frame as the test rounds it (see [`edge_function_bound`]);
    /// `None` where it overflows or an input is not finite.
    pub(super) fn new<V: Vector<Scalar = F>>(ray: &Ray<V>, tri: &Triangle<V>) -> Option<Self> {
        let kz = main_axis(ray.dir);
        let (kx, ky) = ((kz + 1) % 3, (kz + 2) % 3);
        let (o, d) = (ray.origin, ray.dir);
        let (sx, sy) = (-d[kx] / d[kz], -d[ky] / d[kz]);
        let corners = [tri.a, tri.b, tri.c];
        let p = |k: usize| corners.map(|c| c[k] - o[k]);
        let (px, py, pz) = (p(kx), p(ky), p(kz));
        let x: [F; 3] = core::array::from_fn(|i| px[i] + sx * pz[i]);
        let y: [F; 3] = core::array::from_fn(|i| py[i] + sy * pz[i]);
        let finite = |v: &[F; 3]| v.iter().all(|c| c.is_finite());
        if !([px, py, pz, x, y].iter().all(finite)
            && sx.is_finite()
            && sy.is_finite()
            && d[kz].is_finite())
        {
            return None;
        }
        let largest = |v: &[F; 3]| {
            v.iter()
                .fold(F::ZERO, |m, c| if c.abs() > m { c.abs() } else { m })
        };
        Some(Self {
            mx: largest(&x),
            my: largest(&y),
            mpx: largest(&px),
            mpy: largest(&py),
            mpz: largest(&pz),
            sx: sx.abs(),
            sy: sy.abs(),
            dz: d[kz].abs(),
        })
    }

    /// [`edge_function_bound`]'s coordinate bounds `dx = gamma(1) (m_px +
    /// m_x) + gamma(4) |s_x| m_pz` and `dy`, evaluated in `f64` as
    /// [`EdgeFrame::margin`] evaluates it: at least the exact values when
    /// `up`, at most them otherwise.
    fn coordinate_errors(&self, up: bool) -> (f64, f64) {
        let r = Directed::new::<F>(up);
        let w = |x: F| x.to_f64();
        let mpz = w(self.mpz);
        let along = |mp: F, m: F, s: F| {
            r.add(
                r.mul(r.gamma(1), r.add(w(mp), w(m))),
                r.mul(r.mul(r.gamma(4), w(s)), mpz),
            )
        };
        (
            along(self.mpx, self.mx, self.sx),
            along(self.mpy, self.my, self.sy),
        )
    }

    /// [`edge_function_bound`]'s `de |d_z|` evaluated in `f64`: at least
    /// its exact value when `up`, at most it otherwise. The same
    /// expression, every operation rounded in that direction (`fl(x)` is
    /// within half an ulp of `x`, so the float above it is at least `x`,
    /// the float below at most `x`; rounded down, a result is also kept
    /// from going below zero, which the exact one is not), on non-negative
    /// terms, so each bound stays one through the rest of the expression.
    /// `gamma(n) = n u / (1 - n u)` is rounded likewise (`n u` and `1 - n u`
    /// are exact in `f64` for both precisions' `u` and `n <= 4`). Not
    /// finite where it overflows.
    pub(super) fn margin(&self, up: bool) -> f64 {
        let r = Directed::new::<F>(up);
        let w = |x: F| x.to_f64();
        let (mx, my, mpz) = (w(self.mx), w(self.my), w(self.mpz));
        let (dx, dy) = self.coordinate_errors(up);
        let m = if mx > my { mx } else { my };
        let sum = [r.mul(mx, dy), r.mul(my, dx), r.mul(dx, dy)]
            .into_iter()
            .fold(r.mul(r.mul(r.gamma(2), mx), my), |a, b| r.add(a, b));
        let rounding = r.mul(2.0, sum);
        let underflow = r.mul(
            r.mul(4.0 * F::TINY.to_f64(), r.add(1.0, m)),
            r.add(1.0, mpz),
        );
        r.mul(r.add(rounding, underflow), w(self.dz))
    }
}

/// Arithmetic on non-negative `f64`s rounded one way: each result stepped
/// a float up (`up`: at least the exact value) or down and kept from
/// going below zero (at most it), and `gamma(n) = n u / (1 - n u)` for
/// the unit roundoff `u` rounded likewise (see [`EdgeFrame::margin`]).
#[derive(Clone, Copy)]
struct Directed {
    up: bool,
    unit: f64,
}

impl Directed {
    /// Rounded up (`up`) or down, with the unit roundoff of `F`.
    fn new<F: Scalar>(up: bool) -> Self {
        Self {
            up,
            unit: F::UNIT_ROUNDOFF.to_f64(),
        }
    }

    fn round(self, x: f64) -> f64 {
        if self.up {
            x.next_up()
        } else {
            x.next_down().max(0.0)
        }
    }

    fn add(self, a: f64, b: f64) -> f64 {
        self.round(a + b)
    }

    fn mul(self, a: f64, b: f64) -> f64 {
        self.round(a * b)
    }

    fn gamma(self, n: u32) -> f64 {
        let nu = f64::from(n) * self.unit;
        self.round(nu / (1.0 - nu))
    }
}

/// A Plucker product `((p - o) x (q - o)) . d` held exactly, as a
/// floating-point expansion, for comparing it with floats
/// ([`PluckerProduct::cmp`]): the exact fallback of the oracle's float
/// filter for the watertight test's clear misses.
///
/// The differences are held as exact pairs (Knuth's two-sum: `hi + lo` is
/// the exact difference), and each of the six monomials `(A_j B_k - A_k
/// B_j) d_l` as the products of their parts, each expanded exactly into
/// four terms and summed as an expansion (Shewchuk, 1997): at most 96
/// terms.
///
/// Exactness: every nonzero input must have its magnitude in `[2^-300,
/// 2^300]` (every finite `f32` does). Then a difference's parts are
/// multiples of `2^-352` (the smaller input's ulp, at least `2^-300 2^-52`)
/// below `2^301`, so a product of three parts is a multiple of `2^-1056`
/// (as is every rounding error the expansion of a product splits off:
/// exact, above `f64`'s subnormal spacing `2^-1074`) below `2^903`, and no
/// sum overflows. Other inputs are refused (`None`).
pub(crate) struct PluckerProduct(Expansion);

impl PluckerProduct {
    /// `((p - o) x (q - o)) . d`, or `None` for an input outside the exact
    /// range (a nonzero magnitude outside `[2^-300, 2^300]`, or not finite).
    pub(crate) fn new(o: [f64; 3], d: [f64; 3], p: [f64; 3], q: [f64; 3]) -> Option<Self> {
        let (small, large) = (scale2(1.0, -300), scale2(1.0, 300));
        let in_range = |x: &f64| *x == 0.0 || (small <= x.abs() && x.abs() <= large);
        if ![o, d, p, q].iter().flatten().all(in_range) {
            return None;
        }
        let a = [0, 1, 2].map(|k| two_diff(p[k], o[k]));
        let b = [0, 1, 2].map(|k| two_diff(q[k], o[k]));
        let mut acc = Expansion::new();
        for (l, &dl) in d.iter().enumerate() {
            let (j, k) = ((l + 1) % 3, (l + 2) % 3);
            for (x, y, negate) in [(a[j], b[k], false), (a[k], b[j], true)] {
                for xp in [x.0, x.1] {
                    for yp in [y.0, y.1] {
                        if xp != 0.0 && yp != 0.0 && dl != 0.0 {
                            acc.add_product(&[xp, yp, dl], negate);
                        }
                    }
                }
            }
        }
        acc.sign().is_some().then_some(Self(acc))
    }

    /// The exact sign of `product - c`; `None` for a `c` that is not
    /// finite.
    pub(crate) fn cmp(&self, c: f64) -> Option<core::cmp::Ordering> {
        let mut diff = self.0.clone();
        diff.add(-c);
        diff.sign()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{coords, xorshift};

    /// The Plucker product's exact signs against big rationals: `f32`
    /// inputs from arbitrary finite bit patterns, `f64` inputs over the
    /// documented range (magnitudes from about `2^-300` to `2^240`, with
    /// exact zeros, and points translated far from the origin so that `p - o`
    /// rounds); each against the exact product rounded and a few ulps
    /// either side, and zero. Inputs beyond the range are refused.
    #[cfg(feature = "exact")]
    #[test]
    fn plucker_product_signs_are_exact() {
        use crate::exact::oracle::{cross, dot, r, sub};
        let mut next = xorshift(0x6c8e_9cf5_7093_2bd5);
        let (mut checked, mut refused) = (0, 0);
        for case in 0..3000 {
            let wide = case % 3 != 0;
            let v = |scale: f64, next: &mut dyn FnMut() -> u64| coords(wide, true, scale, next);
            let scale = |next: &mut dyn FnMut() -> u64| scale2(1.0, (next() % 480) as i32 - 240);
            let (g, h) = (scale(&mut next), scale(&mut next));
            let o = v(g, &mut next);
            let (mut p, mut q) = (v(g, &mut next), v(g, &mut next));
            if wide && case % 5 == 1 {
                let (dp, dq) = (
                    v(g * scale2(1.0, -30), &mut next),
                    v(g * scale2(1.0, -30), &mut next),
                );
                p = [0, 1, 2].map(|i| o[i] + dp[i]);
                q = [0, 1, 2].map(|i| o[i] + dq[i]);
            }
            let d = v(h, &mut next);
            let Some(product) = PluckerProduct::new(o, d, p, q) else {
                // Refused only beyond the range (f64 only).
                let out = |x: &f64| {
                    *x != 0.0 && !(scale2(1.0, -300)..=scale2(1.0, 300)).contains(&x.abs())
                };
                assert!(
                    wide && [o, d, p, q].iter().flatten().any(out),
                    "{o:?} {d:?} {p:?} {q:?}"
                );
                refused += 1;
                continue;
            };
            let rv = |p: [f64; 3]| p.map(|x| r(x).unwrap());
            let ro = rv(o);
            let exact = dot(&cross(&sub(&rv(p), &ro), &sub(&rv(q), &ro)), &rv(d));
            let near = crate::exact::round::<f64>(&exact);
            let (mut up, mut down) = (near, near);
            let mut cs = std::vec![0.0];
            for _ in 0..3 {
                cs.extend([up, down]);
                (up, down) = (up.next_up(), down.next_down());
            }
            for c in cs {
                let expected = exact.cmp(&r(c).unwrap());
                assert_eq!(
                    product.cmp(c),
                    Some(expected),
                    "{c:e}: {o:?} {d:?} {p:?} {q:?}"
                );
                checked += 1;
            }
        }
        assert!(checked > 20_000 && refused < 100, "{checked} {refused}");
        let big = scale2(1.0, 301);
        let refused =
            |x: f64| PluckerProduct::new([x, 0.0, 0.0], [1.0; 3], [1.0; 3], [0.0, 1.0, 2.0]);
        assert!(
            refused(big).is_none() && refused(1.0 / big).is_none() && refused(f64::NAN).is_none()
        );
        assert!(refused(scale2(1.0, 300)).is_some() && refused(scale2(1.0, -300)).is_some());
    }
}
