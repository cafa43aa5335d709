//! Whether the sign of a crossing's exact determinant is known: the
//! predicate that lets the watertight test return its plain answer. One
//! threshold ([`det_sign_known`]), evaluated in three forms: on one frame,
//! lane by lane on three frames (the per-call test), and per corner with a
//! cheaper sufficient test first (the prepared test).

use crate::num::{Lanes, Scalar};

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
    let bound = W::splat(W::F::from_u32(200) * W::F::UNIT_ROUNDOFF);
    k.mul(k).mul(bound).lt(det.abs())
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
