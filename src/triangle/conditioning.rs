//! Whether the sign of a crossing's exact determinant is known: the
//! predicate that lets the watertight test return its plain answer. One
//! threshold ([`det_sign_known`]), evaluated in three forms: on one frame,
//! lane by lane on three frames (the per-call test), and per corner with a
//! cheaper sufficient test first (the prepared test).

use crate::num::{Lanes, Lanes8, Scalar};

/// A sufficient condition for the determinant's sign to be known (for
/// [`HitCondition::new`] to be `Some`), from `m`, the largest `|x_i|` and
/// `|y_i|` of the corners, and `w = max |p_z,i|`, their largest depth before
/// scaling (or `|d_z| max |z_i|`, which differs from it by at most `2u`
/// relative, well within the margin below):
/// `|det| > u (64 m (m + 2w) + 256 u (m + w)^2)`. For a hit, `m` is about
/// the triangle's size and `w` its distance, so the test asks for
/// `det`, about the squared size, to exceed about `128 u` times size times
/// distance: only slivers seen edge-on fail it.
///
/// Why: `|s_x|, |s_y| <= 1`, so each
/// shear product `|s_x p_z|` is at most about `w`, and each `|p_x|`,
/// `|p_y|` at most about `m + w`. Then [`ErrorBounds`] gives `dx, dy <=
/// u (2m + 5w)` and `de <= u (12 m^2 + 20 m w) + 2 u^2 (2m + 5w)^2`
/// (to first order in the `(1 + k u)` factors), so `4 de`, at most
/// `u (48 m^2 + 80 m w) + 200 u^2 (m + w)^2`, is below the threshold by a
/// factor of at least 1.28, which covers those factors and the few
/// roundings of the threshold itself; then the lower bound of
/// [`HitCondition`] is positive. NaN or infinite input fails it.
#[inline(always)]
pub(crate) fn det_sign_known<F: Scalar>(det: F, m: F, w: F) -> bool {
    let splat = F::L4::splat;
    det_sign_known_lanes(splat(det), splat(m), splat(w)) & 1 != 0
}

/// [`det_sign_known`] for the corners in the lanes of `x`, `y` and `pz`
/// (the prepared test's form).
///
/// First [`det_sign_known_roughly`], lane by lane with no maximum across
/// lanes, with each corner's `k_i = max(|x_i|, |y_i|, |p_z,i|)` (every
/// lane passing is the test for the largest `k_i`, which is `max(m, w)`).
/// It fails only for triangles small next to their distance, which take
/// the exact threshold, out of line.
#[inline(always)]
pub(crate) fn det_sign_known_at_corners<W: Lanes>(x: W, y: W, pz: W, det: W::F) -> bool
where
    W::F: Scalar,
{
    let k = x.abs().max(y.abs()).max(pz.abs());
    det_sign_known_roughly(W::splat(det), k) == 0b111
        || det_sign_known_at_corners_exactly(x, y, pz, det)
}

/// The cheaper sufficient test behind [`det_sign_known`], lane by lane:
/// `|det| > 200 u k^2` for a `k` at least `m` and `w`. With `M = max(m,
/// w) <= k`, the threshold is at most `u M^2 (192 + 1024 u)`, below
/// `193 u M^2`, and rounding the product twice keeps it above that.
#[inline(always)]
pub(crate) fn det_sign_known_roughly<W: Lanes>(det: W, k: W) -> u32
where
    W::F: Scalar,
{
    k.mul(k).mul(W::splat(rough_factor())).lt(det.abs())
}

/// The factor `200 u` of [`det_sign_known_roughly`] and [`edge_signs_known`].
#[inline(always)]
fn rough_factor<F: Scalar>() -> F {
    F::from_u32(200) * F::UNIT_ROUNDOFF
}

/// The threshold of [`det_sign_known`] itself, for
/// [`det_sign_known_at_corners`].
#[cold]
#[inline(never)]
fn det_sign_known_at_corners_exactly<W: Lanes>(x: W, y: W, pz: W, det: W::F) -> bool
where
    W::F: Scalar,
{
    let m = x.abs().max(y.abs()).max_all().x();
    let w = pz.abs().max_all().x();
    det_sign_known(det, m, w)
}

/// [`det_sign_known`] on lanes, its one formula: lane `i` tests `det[i]`
/// against `m[i]` and `w[i]` (the per-call test's lanes are its three
/// frames).
#[inline(always)]
pub(crate) fn det_sign_known_lanes<W: Lanes>(det: W, m: W, w: W) -> u32
where
    W::F: Scalar,
{
    let u = W::F::UNIT_ROUNDOFF;
    let s = m.add(w);
    let threshold = m
        .mul(m.add(w.add(w)))
        .mul(W::splat(W::F::from_u32(64) * u))
        .add(s.mul(s).mul(W::splat(W::F::from_u32(256) * u * u)));
    threshold.lt(det.abs())
}

/// A sufficient condition for every edge function's sign to be known, so
/// that the exact edge functions `E_i` share the computed ones' sign and
/// none is zero: the exact line crosses the exact triangle's plane inside
/// the triangle, and its crossing `t*` is a convex combination of the
/// corners' exact depths (what the interval tests' shortcut needs).
///
/// The test, per lane of a batch (a triangle each): the smallest `|e_i|`
/// above `200 u K^2`, with `K` at least the largest `|x_i|`, `|y_i|` and
/// `|p_z,i|` (`m` and `w` of [`det_sign_known`]), and `K` at least
/// [`scale_floor`]. [`edge_signs_known_at_corners`] is the same test with
/// the corners in lanes.
///
/// Why: [`det_sign_known`]'s derivation bounds the edge functions' error
/// `de` of [`ErrorBounds`] by `u (12 m^2 + 20 m w) + 2 u^2 (2m + 5w)^2`,
/// below `33 u K^2` and so below `|e_i| / 5`: each `E_i` has the sign of
/// `e_i`. The threshold rounds twice, which `200` (against `193`, as in
/// [`det_sign_known_roughly`]) covers. Those bounds count every rounding as
/// relative; a result in the subnormal range is off by at most `eta = u
/// MIN_POSITIVE` more (a difference that is subnormal is exact, a product
/// off by `eta`), which adds at most `5 K eta + 2 eta` to an edge function,
/// below `2^-70 u K^2` for `K >= scale_floor()`; and `200 u K^2` is then a
/// normal float, so its own rounding is relative. NaN fails the test.
#[inline(always)]
pub(crate) fn edge_signs_known<W: Lanes8>(min_abs_e: W, k: W) -> W::Mask
where
    W::F: Scalar,
{
    let large = W::splat(scale_floor::<W::F>()).le(k);
    W::and(k.mul(k).mul(W::splat(rough_factor())).lt(min_abs_e), large)
}

/// [`edge_signs_known`] with the corners in lanes: `min_abs_e` holds the
/// smallest `|e_i|` in every lane and lane `i` of `k` is corner `i`'s
/// `max(|x_i|, |y_i|, |p_z,i|)`; every lane passing is the test for the
/// largest `k_i`.
#[inline(always)]
pub(crate) fn edge_signs_known_at_corners<W: Lanes>(min_abs_e: W, k: W) -> bool
where
    W::F: Scalar,
{
    det_sign_known_roughly(min_abs_e, k) == 0b111 && W::splat(scale_floor::<W::F>()).le(k) != 0
}

/// The smallest scale of a triangle, seen from the ray, for which
/// [`edge_signs_known`] holds as derived: `2^-50` for `f32`, `2^-480` for
/// `f64` (so that `200 u K^2` is a normal float, and underflow is
/// negligible against it).
#[inline(always)]
pub(crate) fn scale_floor<F: Scalar>() -> F {
    if F::UNIT_ROUNDOFF.to_f64() < 1e-10 {
        F::from_f64(f64::from_bits((1023 - 480) << 52))
    } else {
        F::from_f64(f64::from_bits((1023 - 50) << 52))
    }
}
