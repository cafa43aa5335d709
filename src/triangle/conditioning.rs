//! Whether the sign of a crossing's exact determinant is known: the
//! predicate that lets the watertight test return its plain answer. One
//! threshold ([`det_sign_known`]), evaluated in three forms: on one frame,
//! lane by lane on three frames (the per-call test), and per corner with a
//! cheaper sufficient test first (the prepared test). The interval tests
//! ask the same threshold about each edge function ([`edge_signs_known`]).

use crate::num::round::max2;
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

/// [`det_sign_known_roughly`] lane by lane on the determinants in `det`,
/// each of a triangle whose corners are among the four in the lanes of
/// `x`, `y` and `pz` (a quad's two triangles), with the largest `k_i` of
/// all four corners: at least any three's, so a pass is a pass of
/// [`det_sign_known_at_corners`] for the triangle. Bit `l` set where lane
/// `l` passes.
#[inline(always)]
pub(crate) fn det_sign_known_roughly_at_four_corners<W: Lanes>(x: W, y: W, pz: W, det: W) -> u32
where
    W::F: Scalar,
{
    let k = x.abs().max(y.abs()).max(pz.abs());
    // (The largest in every lane; squaring and rounding keep the order,
    // so this is every corner's `k_i^2 200 u` tested at once.)
    let k = k.max(k.roll4().roll4());
    let k = k.max(k.roll4());
    k.mul(k).mul(W::splat(rough_factor())).lt4(det.abs())
}

/// [`det_sign_known`] itself lane by lane on the determinants in `det`,
/// with `m` and `w` the largest of the four corners in the lanes of `x`,
/// `y` and `pz` (at least any three's, as above). (The maxima here and in
/// [`det_sign_known_roughly_at_four_corners`] may drop a NaN coordinate;
/// that changes no answer: the determinant of a triangle with that corner
/// is NaN, which fails the test whatever `m` and `w` are, and for a
/// triangle without it they are still at least its own corners'.)
#[inline(always)]
pub(crate) fn det_sign_known_at_four_corners<W: Lanes>(x: W, y: W, pz: W, det: W) -> u32
where
    W::F: Scalar,
{
    let largest = |l: W| l.to_array4().into_iter().fold(W::F::ZERO, max2);
    let (m, w) = (largest(x.abs().max(y.abs())), largest(pz.abs()));
    det.to_array4()
        .iter()
        .enumerate()
        .map(|(l, &d)| u32::from(det_sign_known(d, m, w)) << l)
        .sum()
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
/// their largest `|p_z,i|`), or above any value at least `T` for some `m'
/// >= max(m / 2, scale_floor())` and `w' >= w`.
///
/// Why: [`det_sign_known`]'s derivation bounds each edge function's error
/// `de` of [`ErrorBounds`] by `de(m, w) = u (12 m^2 + 20 m w) + 2 u^2 (2m +
/// 5w)^2`, and `T` exceeds `4 de` by a factor of at least 1.28 (the
/// determinant, a sum of three edge functions, needs `4 de`; one edge
/// function needs `de`): each `E_i` has the sign of `e_i`. The spare
/// factor of four is what allows `m' >= m / 2`: `de` grows with `m` and
/// `w` and is homogeneous of degree two, so `de(m, w) <= de(2m', 2w') = 4
/// de(m', w')`. Those bounds count every rounding as relative; a
/// result in the subnormal range is off by at most `eta = u MIN_POSITIVE`
/// more (a difference that is subnormal is exact, a product off by
/// `eta`), which adds at most `5 (m + w) eta + 2 eta` to an edge function;
/// with `m' >= scale_floor()`, against `T >= 64 u m' (m' + w')`, the first
/// part is below `2^-78 T` and `2 eta` below `MIN_POSITIVE / (32 m'^2) T`,
/// `2^-31 T` in `f32` and `2^-67 T` in `f64`, inside the margin; and `64 u
/// m'^2` is a normal float, so the threshold's own few roundings are
/// relative (the second-order term, if subnormal, is off by `eta`, also
/// far below `T`).
/// A NaN edge function fails the test; a NaN coordinate makes one (the
/// callers also require a finite determinant).
///
/// **The batch's form** (this function, a triangle per lane) bounds `m` and
/// `w` from one corner and the triangle's `reach`, stored with the batch:
/// at least `max_{i, a} |p_i[a] - p_0[a]|` over the corners `i = 1, 2` and
/// the three axes (in exact arithmetic). With `A = max(|x_0|, |y_0|)` and
/// `r` the reach, the corners' computed coordinates satisfy (the error
/// analysis of [`ErrorBounds`] applied to the differences `x_i - x_0`, in
/// which `p_i - p_0` contributes at most `r` through `p_x` and `r` through
/// the shear, `|s_x| <= 1`, and each rounding `u` times a coordinate):
///
/// - `w <= (|p_z,0| + r)(1 + 2.1u)`, so `w <= w^ = w_b (1 + 3.1u)` with
///   `w_b = fl(|p_z,0| + r)`;
/// - `m <= (A + 2r + 6.02u w)(1 + 5.1u)`, so `m <= 2 mu` with
///   `mu = (A + 2r + 6.02u w^)(1 + 5.1u) / 2`.
///
/// It evaluates `n = fl(max(fl(A + r), 2 scale_floor()) + fl(32u w_b))`
/// and tests `min |e_i| > fl(fl(64u n) fl(n + fl(w_b + w_b)))`. That
/// product, before its three roundings, is at least `T(mu', w^)`, with
/// `mu' = max(mu, scale_floor())`, when both `n >= mu' + 4u (mu' + w^)`
/// and `n + 2 w_b >= mu' + 2 w^`, which follow from `n >= mu' (1 + 4u) +
/// 6.2u w_b`. Where `mu >= scale_floor()`, `n >= (A + r)(1 - 2u) + 32u
/// w_b (1 - 3u)`, which exceeds `(A / 2 + r)(1 + 9.2u) + 9.3u w_b`, itself
/// at least `mu (1 + 4u) + 6.2u w_b` (the `A / 2` absorbs `A`'s factors
/// and, as `r <= w_b (1 + u)`, the `32u w_b` absorbs those of `r`).
/// Elsewhere `n >= 2 scale_floor() (1 - u) + 32u w_b (1 - 3u)`, which
/// exceeds `scale_floor() (1 + 4u) + 6.2u w_b`. (A product `32u w_b` that
/// underflows is off by at most `eta`, far below `u n`.) The three
/// roundings of the product are inside the 1.28 margin.
///
/// Where the scalar tests use `m` and `w` themselves, this takes about ten
/// operations fewer per lane. For a crossing inside the triangle `A` is at
/// most about `r`, so the threshold is a few times the scalar tests',
/// about `128 u (A + r) w` for a triangle seen from afar: the shortcut
/// holds for crossings farther than about `256 u w / r` of the triangle's
/// size from its edges. A NaN or infinite reach or coordinate fails the
/// test.
#[inline(always)]
pub(crate) fn edge_signs_known<W: Lanes8>(
    min_abs_e: W,
    (x0, y0, pz0): (W, W, W),
    reach: W,
) -> W::Mask
where
    W::F: Scalar,
{
    let u = W::F::UNIT_ROUNDOFF;
    let zero = W::splat(W::F::ZERO);
    // |v| as max(v, -v): exact, and NaN stays NaN.
    let a = x0.max(y0).max(zero.sub(x0.min(y0)));
    let w_b = pz0.max(zero.sub(pz0)).add(reach);
    let n = a
        .add(reach)
        .max(W::splat(W::F::TWO * scale_floor::<W::F>()))
        .add(w_b.mul(W::splat(W::F::from_u32(32) * u)));
    let threshold = n
        .mul(W::splat(W::F::from_u32(64) * u))
        .mul(n.add(w_b.add(w_b)));
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
    use crate::testing::Draws;
    use crate::triangle::lanes::frame_lanes;
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
            // The batch's form, from corner 0 and the reach.
            let splat = Portable8::<S<V>>::splat;
            let known = |reach| {
                let corner = (splat(x.x()), splat(y.x()), splat(pz.x()));
                Portable8::<S<V>>::bits(edge_signs_known(splat(min_abs_e), corner, splat(reach)))
            };
            let reach = crate::triangle::batch::reach(&tri);
            assert_eq!(known(reach), 0xff);
            // With the distance standing for the reach, it fails.
            assert_eq!(known(pz.abs().max_all().x()), 0);
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
    /// The batch's form of the edge-sign test, from corner 0 and the
    /// reach, is sound: where it holds, every exact edge function (exact
    /// arithmetic on the float corners, origin and shear) has the computed
    /// one's sign. Also checked: the two bounds its derivation rests on,
    /// `w <= (|p_z,0| + r)(1 + 2.1u)` and `m <= (A + 2r + 6.02u w)(1 +
    /// 5.1u)`, including on triangles built to nearly attain the second
    /// (a corner `r` along `x` and `z` from corner 0, seen along about the
    /// diagonal from near corner 0, so the shear nearly doubles the reach:
    /// a bound of `A + r` would fail there). The triangles: random, small ones far from
    /// the origin, and rays aimed at or just off an edge, so that the
    /// threshold decides.
    #[test]
    fn batch_edge_signs_are_exact_where_known() {
        use num_rational::BigRational;
        use num_traits::{Signed, Zero};
        fn check<V: Vector>(draws: &mut Draws) -> (usize, usize, bool)
        where
            S<V>: Scalar,
        {
            let mut c = || S::<V>::from_f64(draws.coordinate(60));
            let mut v = || V::new(c(), c(), c());
            let (a, mut b, mut cc, mut origin) = (v(), v(), v(), v());
            let kind = draws.next() % 4;
            if kind == 1 {
                // Small and far: size about 2^-k of the distance.
                let size = S::<V>::from_f64(2f64.powi(-((draws.next() % 40) as i32)));
                b = a + (b - a) * size;
                cc = a + (cc - a) * size;
            } else if kind == 2 {
                // The shear's worst case: corner 1 at +r along x and z, the
                // ray along about (-1, 0, 1.01) from near corner 0 (so
                // s_x is about 0.99 and x_1 - x_0 about 1.99 r).
                let r = S::<V>::from_f64(2f64.powi((draws.next() % 20) as i32 - 10));
                let zero = S::<V>::ZERO;
                b = a + V::new(r, zero, r);
                cc = a + V::new(zero, r, zero);
                let back = S::<V>::from_f64(draws.coordinate(20).abs() + 1.0);
                origin = a + V::new(back, zero, zero - back * S::<V>::from_f64(1.01));
            }
            let tri = Triangle::new(a, b, cc);
            // Aim at a point of edge a-b, or just off it, or the centroid.
            let along = if kind == 2 {
                S::<V>::ZERO
            } else {
                S::<V>::from_f64((draws.next() % 1024) as f64 / 1024.0)
            };
            let off = S::<V>::from_f64(match draws.next() % 4 {
                0 => 0.0,
                1 => 1e-7,
                2 => -1e-5,
                _ => 0.3,
            });
            let target = a + (b - a) * along + (cc - a) * off;
            let ray = Ray::new(origin, target - origin);
            if !ray.is_valid() || !tri.a.is_finite() || !tri.b.is_finite() || !tri.c.is_finite() {
                return (0, 0, false);
            }
            let ray = PreparedRay::new(&ray);
            let (x, y, pz, e) = frame_lanes(&ray.origin_lanes, &ray.shear_lanes, &ray.axes, &tri);
            let reach = crate::triangle::batch::reach(&tri);
            let u = S::<V>::UNIT_ROUNDOFF.to_f64();
            // The derivation's two bounds, evaluated in exact arithmetic.
            let q = |f: S<V>| BigRational::from_float(f.to_f64()).unwrap();
            let qf = |f: f64| BigRational::from_float(f).unwrap();
            let (m, w) = (x.abs().max(y.abs()).max_all().x(), pz.abs().max_all().x());
            if !(m.is_finite() && w.is_finite() && reach.is_finite()) {
                return (0, 0, false);
            }
            let big_a = q(x.x().abs()).max(q(y.x().abs()));
            let (qm, qw, qr) = (q(m), q(w), q(reach));
            assert!(
                qw <= (q(pz.x().abs()) + &qr) * qf(1.0 + 2.1 * u),
                "w bound: {tri:?} {ray:?}"
            );
            let m_bound = (big_a.clone() + &qr + &qr + qf(6.02 * u) * &qw) * qf(1.0 + 5.1 * u);
            assert!(qm <= m_bound, "m bound: {tri:?} {ray:?}");
            // Nearly attained in the shear's worst case.
            let tight = kind == 2 && qm > big_a + qr * qf(1.9);
            // Soundness of the verdict.
            let min_abs_e = e.abs().min_all().x();
            let splat = Portable8::<S<V>>::splat;
            let corner = (splat(x.x()), splat(y.x()), splat(pz.x()));
            let known =
                Portable8::<S<V>>::bits(edge_signs_known(splat(min_abs_e), corner, splat(reach)))
                    == 0xff;
            if !known {
                return (0, 0, tight);
            }
            let [sx, sy, _] = ray.shear_lanes.map(|l| q(l.x()));
            let [ox, oy, oz] = ray.origin_lanes.map(|l| q(l.x()));
            let [kx, ky, kz] = ray.axes;
            let frame = |p: V| {
                let pz = q(p.get(kz)) - &oz;
                (
                    q(p.get(kx)) - &ox + &sx * &pz,
                    q(p.get(ky)) - &oy + &sy * &pz,
                )
            };
            let p = [frame(tri.a), frame(tri.b), frame(tri.c)];
            let computed = e.to_array();
            for (i, computed) in computed.into_iter().enumerate() {
                let (j, k) = ((i + 1) % 3, (i + 2) % 3);
                let exact = &p[j].0 * &p[k].1 - &p[j].1 * &p[k].0;
                assert!(!exact.is_zero(), "zero edge function {i}: {tri:?} {ray:?}");
                assert_eq!(
                    exact.is_positive(),
                    computed > S::<V>::ZERO,
                    "edge function {i}: {tri:?} {ray:?}"
                );
            }
            // A verdict near an edge: the threshold decided.
            let largest = e.abs().max_all().x();
            (
                1,
                usize::from(min_abs_e < largest * S::<V>::from_f64(1e-3)),
                tight,
            )
        }
        let mut draws = Draws(0x5eed_0fed_9e51_6300);
        let (mut known, mut near, mut tight) = (0, 0, 0);
        for _ in 0..20_000 {
            for (k, n, t) in [check::<Vec3>(&mut draws), check::<DVec3>(&mut draws)] {
                known += k;
                near += n;
                tight += usize::from(t);
            }
        }
        // Enough verdicts, near edges too, and worst cases, that the checks
        // mean something.
        assert!(
            known > 5_000 && near > 200 && tight > 1_000,
            "{known} {near} {tight}"
        );
    }
}
