//! The interval triangle test's band step: where a triangle's corners lie
//! on both sides of an end of the interval, the crossing's error bound,
//! evaluated from the lanes the shortcut holds ([`band_error`]), decides
//! that end whenever the crossing is farther from it than rounding
//! ([`band_verdict`]).

use super::Triangle;
use super::bounds::{axis_error, edge_error};
use super::lanes::translated;
use crate::num::{Axis, L, Lanes, S, Scalar, Vector};
use crate::ray::{Interval, filter};

/// The filter step for a triangle whose corners' depths straddle an end
/// of the interval (so `corner_verdict` cannot settle it), from the
/// lanes the shortcut already has: the crossing `t` and its error bound
/// ([`band_error`]), decided where the band `[t - err, t + err]` lies on
/// one side of each end (the filter of [`watertight_in`]); `None` where
/// it does not, or where the bound does not exist, for [`watertight_in`]
/// to finish out of line. Called by the interval test's shortcut
/// (`watertight_in_lanes`).
///
/// Every answer it gives is the exact one, as [`watertight_in`]'s: the
/// shortcut runs only where `watertight_in` would pass `inside` with these
/// edge functions (all of one sign, none zero), so the exact crossing is
/// the one whose distance from `t` the bound holds. The common case it
/// catches is a segment that starts on or next to the triangle's
/// neighbourhood, as a shadow ray from a surface does: the corners lie on
/// both sides of its start while the crossing is far from it, by more
/// than rounding. Kept out of the traversal's inner loop, but not cold.
///
/// [`watertight_in`]: super::interval::watertight_in
#[inline(never)]
pub(super) fn band_verdict<V: Vector>(
    (origin_lanes, shear_lanes, axes): (&[L<V>; 3], &[L<V>; 3], &[Axis; 3]),
    tri: &Triangle<V>,
    [x, y, pz, z, e]: [L<V>; 5],
    det: S<V>,
    interval: Interval<S<V>>,
) -> Option<bool> {
    let [px, py, _] = translated(origin_lanes, axes, [&tri.a, &tri.b, &tri.c]);
    let p = [px, py, pz];
    let shear = [shear_lanes[0].x(), shear_lanes[1].x()];
    let (t, err) = band_error::<V>(p, [x, y, z, e], det, shear)?;
    let (lo, hi) = interval.ends();
    filter(t, err, lo, hi).ok()
}

/// The smallest magnitude [`band_error`] gives its leaves: `2^-26` for
/// `f32`, `2^-300` for `f64`, so that `u^2 floor^3` is a normal float.
#[inline(always)]
fn band_floor<F: Scalar>() -> F {
    if F::UNIT_ROUNDOFF.to_f64() < 1e-10 {
        F::from_f64(f64::from_bits((1023 - 300) << 52))
    } else {
        F::from_f64(f64::from_bits((1023 - 26) << 52))
    }
}

/// The crossing `t` of a triangle all of whose edge functions share a
/// sign, as the shortcut computes it (`fl(fl(sum e_i z_i) fl(1 / det))`),
/// and a float `err >= |t - t*|` (`t*` the exact crossing); `None` where
/// the determinant's sign is not known, or the triangle is too small for
/// the bound as evaluated here (`|det| < floor^2`). The corners in the
/// ray's frame as lanes (as [`frame_lanes`] computes them): translated
/// `p = (p_x, p_y, p_z)`, sheared `x`, `y`, scaled depths `z = p_z s_z`,
/// edge functions `e`, their sum `det`; the shear factors `s_x`, `s_y`.
///
/// The terms are `ErrorBounds`' and `HitCondition`'s, in terms of the
/// computed values: with `m_x = max |x_i|` (likewise `m_y`, `m_px`,
/// `m_py`, `m_pz`, `m_z`),
/// - `|x_i - X_i| <= dx` and `|y_i - Y_i| <= dy`, [`axis_error`]'s bounds;
/// - `|e_i - E_i| <= de`, [`edge_error`]'s bound from those (both as
///   `ErrorBounds` computes them, each widened by its count of roundings);
/// - `|z_i - Z_i| <= dz = gamma(4) m_z`;
/// - `|sum e| / (1 + u)^2 <= |det| <= |sum e| / (1 - u)^2` (two roundings
///   of terms of one sign), so with `L = |det| / (1 + u)^2 - 3 de` and
///   `U = |det| / (1 - u)^2 + 3 de`, `L <= |sum E|` and `sum |E_i| <= U`
///   (`L > 0`: the exact determinant has the computed one's sign);
/// - `|t - t*| <= R + de S / L + dz U / L`, with `R = gamma(8) m_z` (the
///   rounding of `t`) and `S = sum |z_i - t| + 3R`
///   (`HitCondition::t_error` derives it).
///
/// As `U >= L`, that is at most `N / L` with `N = (gamma(8) + gamma(4))
/// m_z U + de S <= gamma(12) m_z U + de (sum |z_i - t| + gamma(24) m_z)`
/// (`x / (1 - x)` is convex and zero at zero, so `gamma(a) + gamma(b) <=
/// gamma(a + b)`). Evaluated as follows, where every value but `L` is a
/// sum of products of non-negative numbers, so that counting its roundings
/// bounds it ([`bound_up`]):
/// - `L' = fl(fl(A - 4 de) (1 - 2u)) <= L`, `A = fl(|det| (1 - 4u))`: `A`
///   is normal (below), so `A <= |det| (1 - 4u)(1 + u) <= |det| / (1 +
///   u)^2`. A difference `x = fl(A - 4 de)` that is subnormal is exact,
///   and `fl(x (1 - 2u)) <= x`; one that is normal is at most `(A - 4 de)
///   (1 + u)`, and `fl(x (1 - 2u))` at most `x (1 - 2u) + u x` (half an ulp,
///   relative or, below `MIN_POSITIVE`, at most `u MIN_POSITIVE <= u x`),
///   so at most `(A - 4 de)(1 + u)(1 - u)`. Either way `L' <= |det| / (1 +
///   u)^2 - 4 de < L`. Only `L' > 0` is used;
/// - `U' = fl(|det| (1 + 4u)) + 4 de >= U`, two roundings deep;
/// - `N` from `U'` and `de`: `fl(z_i - t)` is one rounding of `|z_i - t|`,
///   so `N` is at most 6 deep and `N / L'` 7, widened by 7.
///
/// Underflow: every leaf (`m_x`, ..., `m_z`, `|s_x|`, `|s_y|`) is raised to
/// at least [`band_floor`] (the bound only grows with each), and `|det| >=
/// floor^2` is required, so that every product and sum above is a normal
/// float (the smallest, `dx dy`, is at least `u^2 floor^2`), the last
/// quotient raised to `MIN_POSITIVE` (an exact quotient below it is below
/// the raised value). A subnormal result among the inputs' own roundings
/// (`x_i`, `e_i`, `z_i`, the products in `t`) is off by at most `eta = u
/// MIN_POSITIVE` rather than relatively: in `e_i` by at most `2 eta (m_x +
/// m_y + 1)`, in `z_i` by `eta < gamma(4) floor`, in `t` by `4 eta /
/// |det| <= 4 eta / floor^2`. Each is covered by the slack of the widening
/// it passes through: [`bound_up`]'s factor is rounded up past `1 +
/// gamma(k + 1)` by at least `u` (one ulp of `2u` above a value rounded to
/// nearest), a relative slack of about `u`: at least `u^2 floor (m_x +
/// m_y)` on `de` (as `de >= 2 (m_x dy + m_y dx) >= 2u floor (m_x + m_y)`),
/// and `u gamma(12) floor` on the bound of `t`; these exceed the deficits
/// by factors of at least `2^25` in `f32` (more in `f64`).
///
/// No leaf is NaN: the edge functions are finite, and each `x_i`, `y_i`
/// (so each `p_x`, `p_y`, `p_z`) enters one of them through a product; a
/// NaN `t` gives a NaN bound, which the filter leaves undecided.
///
/// [`frame_lanes`]: super::lanes::frame_lanes
/// [`bound_up`]: crate::num::round::bound_up
#[inline(always)]
fn band_error<V: Vector>(
    [px, py, pz]: [L<V>; 3],
    [x, y, z, e]: [L<V>; 4],
    det: S<V>,
    [sx, sy]: [S<V>; 2],
) -> Option<(S<V>, S<V>)> {
    use crate::num::round::{bound_up, max2};
    let (one, two, four) = (S::<V>::ONE, S::<V>::TWO, S::<V>::from_u32(4));
    let (u, g) = (S::<V>::UNIT_ROUNDOFF, S::<V>::gamma_n);
    let floor = band_floor::<S<V>>();
    let d = det.abs();
    if !(d >= floor * floor) {
        return None;
    }
    let big = |v: L<V>| max2(v.abs().max_all().x(), floor);
    let (mx, my, mz) = (big(x), big(y), big(z));
    let (mpx, mpy, mpz) = (big(px), big(py), big(pz));
    let (sx, sy) = (max2(sx.abs(), floor), max2(sy.abs(), floor));
    let dx = axis_error(mpx, mx, sx, mpz);
    let dy = axis_error(mpy, my, sy, mpz);
    let de = edge_error(mx, my, dx, dy);
    let lower = (d * (one - four * u) - four * de) * (one - two * u);
    if !(lower > S::<V>::ZERO) {
        return None;
    }
    let t = e.mul(z).sum3() * (one / det);
    let upper = d * (one + four * u) + four * de;
    let spread = z.sub(L::<V>::splat(t)).abs().sum3() + g(24) * mz;
    let n = g(12) * mz * upper + de * spread;
    Some((t, bound_up(max2(n / lower, S::<V>::MIN_POSITIVE), 7)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ray::{PreparedRay, Ray};
    use crate::testing::Draws;
    use crate::triangle::lanes::frame_lanes;
    use glam::{DVec3, Vec3};

    /// [`band_error`]'s bound holds against the exact crossing (the
    /// exact-arithmetic oracle), on triangles all of whose edge functions
    /// share a sign: any triangle through a point of it, a ray from a
    /// point rounded onto the plane (the crossing a few ulps from the
    /// origin, on either side), and zero-area ones (no crossing: there
    /// must be no bound), over coordinates from quarters to a spread of
    /// `2^40`. And it is tight enough to be of use: on a shadow segment
    /// from a hit point (`spawn_to_point`), it places the crossing of the
    /// hit's own triangle before the segment's start.
    #[cfg(feature = "exact")]
    #[test]
    fn band_error_bounds_the_exact_crossing() {
        use crate::exact::oracle::{r, triangle};
        use crate::{Intersect, Surface};
        use num_traits::{Signed, ToPrimitive};
        /// `shape`: 0 a ray through a point of the triangle, 1 from a point
        /// rounded onto its plane, 2 zero area, 3 a shadow segment from
        /// the hit of a ray through a small triangle away from the
        /// origin. Returns (bounds given, shadow starts the bound
        /// decided, shadow cases, the error over its bound).
        fn check<V: Vector>(draws: &mut Draws, shape: u8) -> (usize, usize, usize, f64) {
            let (a, b, c, o): (V, V, V, V) = (
                draws.point(40),
                draws.point(40),
                draws.point(40),
                draws.point(40),
            );
            let w = [draws.next() % 1000 + 1, draws.next() % 1000 + 1]
                .map(|k| S::<V>::from_u32(k as u32) / S::<V>::from_u32(1001));
            // Shadows: a triangle of a mesh, small and away from the
            // coordinates' origin (corners on the grid of eighths, a
            // sixteenth of it, around a point of the grid of quarters
            // beyond 4).
            let away = V::new(
                S::<V>::from_f64(draws.coordinate(3).abs() + 4.0),
                S::<V>::from_f64(draws.coordinate(3)),
                S::<V>::from_f64(draws.coordinate(3)),
            );
            let sixteenth = S::<V>::from_f64(1.0 / 16.0);
            let mut eighths = || {
                let mut e = || S::<V>::from_f64(f64::from(draws.eighth()));
                V::new(e(), e(), e()) * sixteenth
            };
            let (ea, eb, ec) = (eighths(), eighths(), eighths());
            let tri = match shape {
                2 => Triangle::new(a, (a + b) * S::<V>::HALF, b),
                3 => Triangle::new(away + ea, away + eb, away + ec),
                _ => Triangle::new(a, b, c),
            };
            let point =
                tri.a + (tri.b - tri.a) * w[0] * (S::<V>::ONE - w[1]) + (tri.c - tri.a) * w[1];
            let mut ray = match shape {
                1 => Ray::new(point, o - point),
                _ => Ray::new(o, point - o),
            };
            let mut shadow = false;
            if shape == 3 {
                let Some(hit) = tri.hit(&ray, S::<V>::INFINITY) else {
                    return (0, 0, 0, 0.0);
                };
                let light = o * S::<V>::from_u32(8);
                let Some((segment, _)) = tri.surface_point(&ray, &hit).spawn_to_point(light) else {
                    return (0, 0, 0, 0.0);
                };
                ray = segment;
                shadow = true;
            }
            if !ray.is_valid() {
                return (0, 0, 0, 0.0);
            }
            let prepared = PreparedRay::new(&ray);
            let (lanes, axes) = (&prepared.origin_lanes, &prepared.axes);
            let (x, y, pz, e) = frame_lanes(lanes, &prepared.shear_lanes, axes, &tri);
            let zero = L::<V>::splat(S::<V>::ZERO);
            if e.le(zero) != 0 && zero.le(e) != 0 {
                return (0, 0, 0, 0.0);
            }
            let [px, py, _] = translated(lanes, axes, [&tri.a, &tri.b, &tri.c]);
            let p = [px, py, pz];
            let z = pz.mul(prepared.shear_lanes[2]);
            let shear = [prepared.shear_lanes[0].x(), prepared.shear_lanes[1].x()];
            let Some((t, err)) = band_error::<V>(p, [x, y, z, e], e.sum3(), shear) else {
                return (0, 0, usize::from(shadow), 0.0);
            };
            let exact = triangle(&ray, &tri).expect("finite input");
            let Some(t_exact) = exact.t else {
                panic!("a bound without a crossing: {ray:?} {tri:?}");
            };
            let (off, bound) = ((r(t).unwrap() - &t_exact).abs(), r(err).unwrap());
            assert!(off <= bound, "{ray:?} {tri:?} t {t:?} err {err:?}");
            let before = shadow && t + err < S::<V>::ZERO;
            let ratio = (off / bound).to_f64().expect("finite");
            (1, usize::from(before), usize::from(shadow), ratio)
        }
        let mut draws = Draws(0x5eed_ba11_d0d0_0001);
        let (mut given, mut before, mut shadows, mut worst) = (0, 0, 0, 0f64);
        for _ in 0..4_000 {
            for shape in 0..4 {
                for (g, b, s, ratio) in [
                    check::<Vec3>(&mut draws, shape),
                    check::<DVec3>(&mut draws, shape),
                ] {
                    (given, before, shadows) = (given + g, before + b, shadows + s);
                    worst = worst.max(ratio);
                }
            }
        }
        assert!(given > 5_000, "{given}");
        // The worst case comes within a factor of ten of the bound (0.34
        // of it when written), so a bound ten times too small would fail.
        assert!(worst > 0.1, "{worst}");
        // The hit's own triangle, seen from the segment's start: nearly
        // always placed before it by the bound alone.
        assert!(
            shadows > 1_000 && before * 10 > shadows * 9,
            "{before} of {shadows}"
        );
    }
}
