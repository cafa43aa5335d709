//! Whether the sign of a crossing's exact determinant is known: the
//! predicate that lets the watertight test return its plain answer. One
//! threshold ([`det_sign_known`]), evaluated in three forms: on one frame,
//! lane by lane on three frames (the per-call test), and per corner with a
//! cheaper sufficient test first (the prepared test). The interval tests
//! ask the same threshold about each edge function ([`edge_signs_known`]).

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
/// The test: the smallest `|e_i|` above [`det_sign_known`]'s threshold
/// `T(m', w) = u (64 m' (m' + 2w) + 256 u (m' + w)^2)`, with `m' = max(m,
/// scale_floor())` (`m` the corners' largest `|x_i|` and `|y_i|`, `w`
/// their largest `|p_z,i|`). Per lane of a batch (a triangle each), it is
/// evaluated as `64 u (m' + 4u (m' + w)) (m' + 2w)`, which is at least
/// `T(m', w)` (expand it: `m' + 2w >= m' + w`).
///
/// Why: [`det_sign_known`]'s derivation bounds each edge function's error
/// `de` of [`ErrorBounds`] by `u (12 m^2 + 20 m w) + 2 u^2 (2m + 5w)^2`,
/// and `T` exceeds `4 de` by a factor of at least 1.28 (the determinant,
/// a sum of three edge functions, needs `4 de`; one edge function needs
/// `de`): each `E_i` has the sign of `e_i`. Those bounds grow with `m`, so
/// they hold for `m' >= m`. They count every rounding as relative; a
/// result in the subnormal range is off by at most `eta = u MIN_POSITIVE`
/// more (a difference that is subnormal is exact, a product off by
/// `eta`), which adds at most `5 (m + w) eta + 2 eta` to an edge function;
/// with `m' >= scale_floor()`, against `T >= 64 u m' (m' + w)`, the first
/// part is below `2^-79 T` and `2 eta` below `MIN_POSITIVE / (32 m'^2) T`,
/// `2^-31 T` in `f32` and `2^-67 T` in `f64`, inside the margin; and `64 u
/// m'^2` is a normal float, so the threshold's own few roundings are
/// relative (the second-order term, if subnormal, is off by `eta`, also
/// far below `T`).
/// A NaN edge function fails the test; a NaN coordinate makes one (the
/// callers also require a finite determinant).
///
/// For a triangle seen from afar (`m`, its size across the ray, small
/// against its distance `w`) the threshold is about `128 u m w`: the
/// shortcut then holds for crossings farther than about `128 u w / m` of
/// the triangle's size from its edges.
#[inline(always)]
pub(crate) fn edge_signs_known<W: Lanes8>(min_abs_e: W, m: W, w: W) -> W::Mask
where
    W::F: Scalar,
{
    let u = W::F::UNIT_ROUNDOFF;
    let m = m.max(W::splat(scale_floor::<W::F>()));
    let s = m.add(w);
    let near = m.add(s.mul(W::splat(W::F::from_u32(4) * u)));
    let threshold = near.mul(s.add(w)).mul(W::splat(W::F::from_u32(64) * u));
    threshold.lt(min_abs_e)
}

/// [`edge_signs_known`] with the corners in lanes: [`det_sign_known_at_corners`]
/// asked about `min_abs_e`, the smallest `|e_i|`, with the `x_i` raised to
/// at least `scale_floor()` in magnitude, so that its `m` is `m'`. (Its
/// cheaper first test, `200 u K^2` with `K >= m'` and `K >= w`, exceeds
/// `T(m', w)` as its derivation shows.)
#[inline(always)]
pub(crate) fn edge_signs_known_at_corners<W: Lanes>(x: W, y: W, pz: W, min_abs_e: W::F) -> bool
where
    W::F: Scalar,
{
    let x = x.abs().max(W::splat(scale_floor::<W::F>()));
    det_sign_known_at_corners(x, y, pz, min_abs_e)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::{L, S, Vector};
    use crate::simd::Portable8;
    use crate::triangle::watertight::frame_lanes;
    use crate::{PreparedRay, Ray, Triangle};
    use glam::{DVec3, Vec3};

    /// A triangle small against its distance (size 1 at 10^3 in `f32`,
    /// 10^-6 at 10^3 in `f64`), crossed at its centroid: the
    /// edge functions' signs are surely known, by the per-corner test and
    /// by the batch's, though the cheaper `200 u K^2` test cannot tell
    /// (so the threshold's `m w` form is what decides). With the corners'
    /// largest coordinate standing for `m`, the test fails.
    #[test]
    fn edge_signs_known_far_from_the_triangle() {
        fn check<V: Vector>(tri: Triangle<V>, origin: V)
        where
            S<V>: Scalar,
        {
            let centroid = (tri.a + tri.b + tri.c) * (S::<V>::ONE / S::<V>::from_u32(3));
            let ray = PreparedRay::new(&Ray::new(origin, centroid - origin));
            let (x, y, pz, e) = frame_lanes(&ray.origin_lanes, &ray.shear_lanes, &ray.axes, &tri);
            let min_abs_e = e.abs().min_all().x();
            let k = x.abs().max(y.abs()).max(pz.abs());
            assert_ne!(det_sign_known_roughly(L::<V>::splat(min_abs_e), k), 0b111);
            assert!(edge_signs_known_at_corners(x, y, pz, min_abs_e));
            let [x, y, pz] = [x, y, pz].map(|l| l.abs().max_all().x());
            let (m, w) = (crate::num::round::max2(x, y), pz);
            let splat = Portable8::<S<V>>::splat;
            let known = |m, w| {
                Portable8::<S<V>>::bits(edge_signs_known(splat(min_abs_e), splat(m), splat(w)))
            };
            assert_eq!(known(m, w), 0xff);
            assert_eq!(known(w, w), 0);
        }
        let z = |v: f64| Vec3::new(0.0, 0.0, v as f32);
        check(
            Triangle::new(z(0.0), Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0)),
            z(1e3) + Vec3::new(0.2, 0.1, 0.0),
        );
        check(
            Triangle::new(
                DVec3::ZERO,
                DVec3::new(1e-6, 0.0, 0.0),
                DVec3::new(0.0, 1e-6, 0.0),
            ),
            DVec3::new(1e-7, 3e-7, 1e3),
        );
    }
}
