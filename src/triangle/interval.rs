//! The interval forms of the watertight tests: [`ray_triangle_in`],
//! [`ray_triangle_prepared_in`] and [`ray_triangle_one_hit_in`], which
//! decide `t_min < t* <= t_max` for the exact crossing `t*`.
//!
//! The inside test is the watertight test's (the same frame, the same
//! edge rules, bit for bit). What changes is the range test. The plain
//! tests decide `t > 0` by sufficient tests and drop a hit they cannot
//! place; here both ends are decided exactly, by a shortcut for the common
//! case and two steps for the rest:
//!
//! 0. The corners' depths ([`corner_verdict`]): where every edge
//!    function's sign is surely exact (`edge_signs_known`), the exact line
//!    crosses the exact triangle inside it, so `t*` is a convex
//!    combination of the corners' exact depths `Z_i = (c_i - o)_z / d_z`
//!    (`z` the ray's main axis) and lies between the smallest and the
//!    largest. Where every corner is surely past `t_min` and none surely
//!    past `t_max`, `t*` is in the interval; where every corner is past
//!    `t_max`, or none past `t_min`, it is not. Nothing else is computed:
//!    this decides what steps 1 and 2 would, and the answer is the same.
//! 1. A filter: the reported `t` and its error bound `err` (the bound of
//!    [`ray_triangle_error_bounds`](super::bounds::ray_triangle_error_bounds),
//!    `HitCondition::t_error`) place `t*` within `[t - err, t + err]`;
//!    where that range lies on one side of an end, the end is decided.
//!    The shortcut runs this step inline where its corners straddle an
//!    end ([`band_verdict`]), with the same bound's terms evaluated from
//!    its lanes and widened once ([`band_error`]).
//! 2. Inside the band, the exact sign of `(a - o) . n - t_end (d . n)`
//!    against that of `d . n` (with `n = (b - a) x (c - a)`), computed with
//!    exact expansions (`PlaneCrossing`).
//!
//! The crossing `t*` is the line's exact crossing with the triangle's
//! plane, computed from the input floats. Where it does not exist (`d . n`
//! is exactly zero: a triangle of zero area, or a ray parallel to the
//! triangle's plane that rounding shows a sliver of it), the distance
//! compared is the `t` the test reports (for a zero-area triangle, where
//! the ray passes its longest edge), a float compared exactly. Either way
//! each (ray, triangle) pair has one distance, compared exactly against
//! both ends, so consecutive intervals `(t0, t1]`, `(t1, t2]` never report
//! a triangle twice and never skip one.

use super::bounds::{ErrorBounds, HitCondition, longest_edge_t};
use super::conditioning::edge_signs_known_at_corners;
use super::definition::{EdgeRule, hit_at, inside};
use super::frame::Frame;
use super::lanes::{DefinitionRay, Packed, frame_lanes, lanes_hit, pack, unpack};
use super::one_hit::{crossing, unresolved_hit};
use super::{Triangle, TriangleHit};
use crate::num::{Axis, L, Lanes, S, Scalar, Vector};
use crate::ray::{Interval, PreparedRay, Ray, Shear, bring_into, decide, filter};
use core::cmp::Ordering;

/// An interval's ends as the corners' depths are compared with them
/// ([`corner_verdict`]), once per call.
#[derive(Clone, Copy, Debug)]
pub(super) struct DepthWindow<F> {
    /// The ends decided against, `t_min` and `min(t_max, MAX)`.
    pub(super) lo: F,
    pub(super) hi: F,
    /// The same, raised to at least `MIN_POSITIVE`: a depth above either
    /// is a normal float.
    pub(super) lo_normal: F,
    pub(super) hi_normal: F,
    /// Whether the ray's `fl(1 / d_z)` is a normal float, without which
    /// the depths' relative bound does not hold.
    pub(super) usable: bool,
}

impl<F: Scalar> DepthWindow<F> {
    #[inline(always)]
    pub(super) fn new(interval: Interval<F>, sz: F) -> Self {
        use crate::num::round::max2;
        let (lo, hi) = interval.ends();
        let size = sz.abs();
        Self {
            lo,
            hi,
            lo_normal: max2(lo, F::MIN_POSITIVE),
            hi_normal: max2(hi, F::MIN_POSITIVE),
            usable: F::MIN_POSITIVE <= size && size <= F::MAX,
        }
    }

    /// `1 - 8u` and `1 + 8u`, both floats: a depth's lower and upper
    /// factor (see [`corner_verdict`]).
    #[inline(always)]
    pub(super) fn factors() -> (F, F) {
        let eight_u = F::from_u32(8) * F::UNIT_ROUNDOFF;
        (F::ONE - eight_u, F::ONE + eight_u)
    }
}

/// Where the exact crossing `t*` lies against `window`, from the corners'
/// computed depths `z` (lanes 0 to 2), for a triangle whose exact crossing
/// is known to be inside it (so `min Z_i <= t* <= max Z_i`) and a usable
/// window: `Some(true)` inside the interval, `Some(false)` outside, `None`
/// when the depths do not settle it.
///
/// Why: `z_i = fl(fl(c_i - o) fl(1 / d_z))` rounds three times, each
/// relative where no result is subnormal (a subnormal difference is exact;
/// `fl(1 / d_z)` is normal for a usable window; a product of at least
/// `MIN_POSITIVE` is normal), so `|z_i - Z_i| <= gamma(3) |Z_i|`, with the
/// sign of `z_i` that of `Z_i`. Then, for `z_i >= MIN_POSITIVE`,
/// `Z_i >= z_i / (1 + gamma(3)) > z_i (1 - 8u)(1 + u) >= fl(z_i (1 - 8u))`
/// and `Z_i <= z_i / (1 - gamma(3)) <= z_i (1 + 8u)(1 - u) <= fl(z_i (1 +
/// 8u))`; a `z_i <= -MIN_POSITIVE` has `Z_i < 0`. So:
/// - every `fl(z_i (1 - 8u)) > max(t_min, MIN_POSITIVE)`: `t* > t_min`; and
///   with every `fl(z_i (1 + 8u)) <= t_max`, `t* <= t_max` too;
/// - every `fl(z_i (1 - 8u)) > max(t_max, MIN_POSITIVE)`: `t* > t_max`;
/// - every `z_i <= -MIN_POSITIVE`: `t* < 0 <= t_min`; every `z_i >=
///   MIN_POSITIVE` and every `fl(z_i (1 + 8u)) <= t_min`: `t* <= t_min`.
///
/// (The batch kernels decide the same four conditions from the smallest
/// and largest `z_i`: rounding is monotone, so `fl(z_min (1 - 8u))` is
/// the smallest `fl(z_i (1 - 8u))`.)
#[inline(always)]
fn corner_verdict<W: Lanes>(window: &DepthWindow<W::F>, z: W) -> Option<bool>
where
    W::F: Scalar,
{
    let splat = W::splat;
    let (down, up) = DepthWindow::<W::F>::factors();
    let (low, high) = (z.mul(splat(down)), z.mul(splat(up)));
    if splat(window.lo_normal).lt(low) == 0b111 && high.le(splat(window.hi)) == 0b111 {
        return Some(true);
    }
    let normal = splat(W::F::MIN_POSITIVE);
    let before =
        normal.le(z) == 0b111 && high.le(splat(window.lo)) == 0b111 || z.le(normal.neg()) == 0b111;
    (before || splat(window.hi_normal).lt(low) == 0b111).then_some(false)
}

/// [`watertight_in`] with the corners in lanes, for a ray given by its
/// origin's lanes, shear lanes and axis order (as [`PreparedRay`] keeps
/// them): the common case decided by [`corner_verdict`], everything else
/// by [`watertight_in`] itself, out of line. The same answer, bit for bit:
/// the shortcut decides exactly what `watertight_in` decides, and its `t`,
/// `u`, `v` and side are the same operations on the same values.
///
/// An invalid ray (whose origin lanes are NaN, as [`PreparedRay::new`]
/// makes them) needs no test on the common path: its edge functions and
/// determinant are NaN, which fails the shortcut, and the out-of-line path
/// answers `None` for it.
#[inline(always)]
fn watertight_in_lanes<V: Vector, R: DefinitionRay<V>>(
    ray: &R,
    (origin_lanes, shear_lanes, axes): (&[L<V>; 3], &[L<V>; 3], &[Axis; 3]),
    tri: &Triangle<V>,
    interval: Interval<S<V>>,
    rule: EdgeRule,
) -> Option<TriangleHit<S<V>>> {
    let zero = S::<V>::ZERO;
    let (x, y, pz, e) = frame_lanes(origin_lanes, shear_lanes, axes, tri);
    let lanes_zero = L::<V>::splat(zero);
    if e.lt(lanes_zero) != 0 && lanes_zero.lt(e) != 0 {
        // Outside by the closed rule; by the one-hit rule where a positive
        // and a negative sign are surely exact (else the exact signs, out
        // of line).
        let known = |v: S<V>| edge_signs_known_at_corners(x, y, pz, v);
        if rule == EdgeRule::Closed || known(e.max_all().x()) && known(e.neg().max_all().x()) {
            return None;
        }
        return unpack(in_out_of_line(ray, tri, interval, rule));
    }
    let sz = shear_lanes[2];
    let window = DepthWindow::new(interval, sz.x());
    let det = e.sum3();
    // (A zero or NaN edge function fails `edge_signs_known`; an infinite
    // one would pass it, so `det` must be finite.)
    let known = window.usable
        && det.abs() <= S::<V>::MAX
        && edge_signs_known_at_corners(x, y, pz, e.abs().min_all().x());
    let z = pz.mul(sz);
    let verdict = known
        .then(|| {
            corner_verdict(&window, z).or_else(|| {
                band_verdict(
                    (origin_lanes, shear_lanes, axes),
                    tri,
                    [x, y, pz, z, e],
                    det,
                    interval,
                )
            })
        })
        .flatten();
    match verdict {
        Some(true) => {
            // As `watertight_in` computes them (`det` finite and far from
            // zero, so `u` and `v` are finite).
            let inv_det = S::<V>::ONE / det;
            let t = e.mul(z).sum3() * inv_det;
            let t = bring_into(t, window.lo, window.hi);
            Some(lanes_hit(t, e, det, inv_det, sz.x()))
        }
        Some(false) => None,
        None => unpack(in_out_of_line(ray, tri, interval, rule)),
    }
}

/// The filter step for a triangle whose corners' depths straddle an end
/// of the interval (so [`corner_verdict`] cannot settle it), from the
/// lanes the shortcut already has: the crossing `t` and its error bound
/// ([`band_error`]), decided where the band `[t - err, t + err]` lies on
/// one side of each end (the filter of [`watertight_in`]); `None` where
/// it does not, or where the bound does not exist, for [`watertight_in`]
/// to finish out of line.
///
/// Every answer it gives is the exact one, as [`watertight_in`]'s: the
/// shortcut runs only where `watertight_in` would pass `inside` with these
/// edge functions (all of one sign, none zero), so the exact crossing is
/// the one whose distance from `t` the bound holds. The common case it
/// catches is a segment that starts on or next to the triangle's
/// neighbourhood, as a shadow ray from a surface does: the corners lie on
/// both sides of its start while the crossing is far from it, by more
/// than rounding. Kept out of the traversal's inner loop, but not cold.
#[inline(never)]
fn band_verdict<V: Vector>(
    (origin_lanes, shear_lanes, axes): (&[L<V>; 3], &[L<V>; 3], &[Axis; 3]),
    tri: &Triangle<V>,
    [x, y, pz, z, e]: [L<V>; 5],
    det: S<V>,
    interval: Interval<S<V>>,
) -> Option<bool> {
    let corners = |k: Axis| L::<V>::new(tri.a.get(k), tri.b.get(k), tri.c.get(k));
    let p = [
        corners(axes[0]).sub(origin_lanes[0]),
        corners(axes[1]).sub(origin_lanes[1]),
        pz,
    ];
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
/// The terms are [`ErrorBounds`]' and [`HitCondition`]'s, in terms of the
/// computed values: with `m_x = max |x_i|` (likewise `m_y`, `m_px`,
/// `m_py`, `m_pz`, `m_z`),
/// - `|x_i - X_i| <= dx = gamma(1) (m_px + m_x) + gamma(4) |s_x| m_pz`, and
///   `dy` alike ([`axis_error`](super::bounds::axis_error));
/// - `|e_i - E_i| <= de = 2 (gamma(2) m_x m_y + m_x dy + m_y dx + dx dy)`;
/// - `|z_i - Z_i| <= dz = gamma(4) m_z`;
/// - `|sum e| / (1 + u)^2 <= |det| <= |sum e| / (1 - u)^2` (two roundings
///   of terms of one sign), so with `L = |det| / (1 + u)^2 - 3 de` and
///   `U = |det| / (1 - u)^2 + 3 de`, `L <= |sum E|` and `sum |E_i| <= U`
///   (`L > 0`: the exact determinant has the computed one's sign);
/// - `|t - t*| <= R + de S / L + dz U / L`, with `R = gamma(8) m_z` (the
///   rounding of `t`) and `S = sum |z_i - t| + 3R`
///   ([`HitCondition::t_error`] derives it).
///
/// As `U >= L`, that is at most `N / L` with `N = (gamma(8) + gamma(4))
/// m_z U + de S <= gamma(12) m_z U + de (sum |z_i - t| + gamma(24) m_z)`
/// (`x / (1 - x)` is convex and zero at zero, so `gamma(a) + gamma(b) <=
/// gamma(a + b)`). Evaluated as follows, where every value but `L` is a
/// sum of products of non-negative numbers, so that counting its roundings
/// bounds it ([`bound_up`]):
/// - `de` with at most 7 roundings on any path (`m_x dy` is 4 deep, then
///   three sums), widened as if 8;
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
///   so `N` is at most 6 deep and `N / L'` 7; widened as if 9.
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
/// |det| <= 4 eta / floor^2`; the rounding each bound was widened beyond
/// its count (a factor `1 + u`: at least `u^2 floor (m_x + m_y)` on `de`,
/// `u gamma(12) floor` on the bound of `t`) exceeds each.
///
/// No leaf is NaN: the edge functions are finite, and each `x_i`, `y_i`
/// (so each `p_x`, `p_y`, `p_z`) enters one of them through a product; a
/// NaN `t` gives a NaN bound, which the filter leaves undecided.
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
    let dx = g(1) * (mpx + mx) + g(4) * (sx * mpz);
    let dy = g(1) * (mpy + my) + g(4) * (sy * mpz);
    let de = bound_up(two * (g(2) * (mx * my) + mx * dy + my * dx + dx * dy), 8);
    let lower = (d * (one - four * u) - four * de) * (one - two * u);
    if !(lower > S::<V>::ZERO) {
        return None;
    }
    let t = e.mul(z).sum3() * (one / det);
    let upper = d * (one + four * u) + four * de;
    let spread = z.sub(L::<V>::splat(t)).abs().sum3() + g(24) * mz;
    let n = g(12) * mz * upper + de * spread;
    Some((t, bound_up(max2(n / lower, S::<V>::MIN_POSITIVE), 9)))
}

/// [`watertight_in`], out of the hot path: the rare cases of
/// [`watertight_in_lanes`], and its invalid rays (a miss).
#[cold]
#[inline(never)]
fn in_out_of_line<V: Vector, R: DefinitionRay<V>>(
    ray: &R,
    tri: &Triangle<V>,
    interval: Interval<S<V>>,
    rule: EdgeRule,
) -> Packed<S<V>> {
    if !ray.valid() {
        return pack::<S<V>>(None);
    }
    let (origin, shear) = ray.origin_and_shear();
    pack(watertight_in(
        origin,
        ray.direction(),
        &shear,
        tri,
        interval,
        rule,
    ))
}

/// The watertight test with the exact interval decision, for a valid ray
/// (origin, direction, shear) and any interval.
#[inline(always)]
pub(super) fn watertight_in<V: Vector>(
    origin: V,
    dir: V,
    shear: &Shear<S<V>>,
    tri: &Triangle<V>,
    interval: Interval<S<V>>,
    rule: EdgeRule,
) -> Option<TriangleHit<S<V>>> {
    let zero = S::<V>::ZERO;
    let f = Frame::new(origin, tri, shear);
    let [e0, e1, e2] = inside(&f, rule, (origin, dir), shear, tri)?;
    let det = e0 + e1 + e2;
    // Zero (or NaN) in the sheared plane: no crossing, as in the plain
    // test; but a one-hit hit is exact, and answers without the frame.
    if !(det != zero && det.is_finite()) {
        return match rule {
            EdgeRule::Closed => None,
            EdgeRule::OneHit => unresolved_hit((origin, dir), shear, tri, &f, interval),
        };
    }
    let z = f.scaled_z(shear);
    let t_scaled = e0 * z[0] + e1 * z[1] + e2 * z[2];
    let inv_det = S::<V>::ONE / det;
    let plain = t_scaled * inv_det;
    // The largest distance a hit can report: `t <= MAX` as in the plain
    // test (a crossing beyond it has no finite `t`).
    let (lo, hi) = interval.ends();
    let bounds = ErrorBounds::new(&f, &z, shear);
    let t = match HitCondition::new(&bounds, det) {
        // The exact determinant has the computed one's sign, so `d . n` is
        // not zero and `t*` exists, within `err` of `plain`.
        Some(c) => {
            let err = c.t_error(&bounds, &z, plain);
            if !decide(plain, err, lo, hi, || crossing(origin, dir, tri))? {
                return None;
            }
            plain
        }
        // A triangle of zero area: no plane; the distance is the longest
        // edge's point nearest the ray, as in the plain test.
        None if tri.is_degenerate() => {
            let (t, _) = longest_edge_t(&f, &z, &bounds)?;
            if !(lo < t && t <= hi) {
                return None;
            }
            return hit_at(t, [e1, e2], det, inv_det, shear);
        }
        // The determinant's sign is not known: ask the exact one.
        None => {
            let exact = crossing(origin, dir, tri);
            match exact.den_sign()? {
                // Parallel in exact arithmetic: the distance is `plain`.
                Ordering::Equal => {
                    if !(lo < plain && plain <= hi) {
                        return None;
                    }
                    return hit_at(plain, [e1, e2], det, inv_det, shear);
                }
                _ => {
                    if !decide(plain, S::<V>::INFINITY, lo, hi, || exact)? {
                        return None;
                    }
                    plain
                }
            }
        }
    };
    // `t*` is in `(lo, hi]`; the reported `t` is brought into it too (see
    // `bring_into`: within its error bound of `t*`, or one ulp of `lo`;
    // and, with `hi <= MAX`, finite, as on the other paths to `hit_at`).
    hit_at(bring_into(t, lo, hi), [e1, e2], det, inv_det, shear)
}

/// [`watertight_in`] for a plain ray (its shear computed here), or `None`
/// for an invalid ray.
#[inline(always)]
fn on_ray<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    interval: Interval<S<V>>,
    rule: EdgeRule,
) -> Option<TriangleHit<S<V>>> {
    if !ray.is_valid() {
        return None;
    }
    let shear = Shear::new(&ray.dir);
    let lanes = (
        &shear.origin_lanes(ray.origin),
        &shear.lanes(),
        &[shear.kx, shear.ky, shear.kz],
    );
    watertight_in_lanes(ray, lanes, tri, interval, rule)
}

/// The watertight test over an interval, both ends decided exactly: the
/// `Within` case of [`Triangle`]'s `hit`, whose documentation has the
/// guarantees. The inside test is `ray_triangle`'s, bit for bit; the range
/// is decided by `watertight_in` (this module's steps 0 to 2).
#[inline]
#[must_use]
pub(crate) fn ray_triangle_in<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    interval: Interval<S<V>>,
) -> Option<TriangleHit<S<V>>> {
    on_ray(ray, tri, interval, EdgeRule::Closed)
}

/// [`ray_triangle_in`] (the closed rule) or [`ray_triangle_one_hit_in`]
/// (the one-hit rule), by `rule`, on a prepared ray: the same answer, bit
/// for bit.
// (Always inlined, as `ray_triangle_prepared` is: the body of a
// traversal's inner loop, its rare paths out of line.)
#[inline(always)]
#[must_use]
pub(crate) fn ray_triangle_prepared_in<V: Vector>(
    ray: &PreparedRay<V>,
    tri: &Triangle<V>,
    interval: Interval<S<V>>,
    rule: EdgeRule,
) -> Option<TriangleHit<S<V>>> {
    let lanes = (&ray.origin_lanes, &ray.shear_lanes, &ray.axes);
    watertight_in_lanes(ray, lanes, tri, interval, rule)
}

/// [`ray_triangle_in`] with the one-hit edge rule.
#[inline]
#[must_use]
pub(crate) fn ray_triangle_one_hit_in<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    interval: Interval<S<V>>,
) -> Option<TriangleHit<S<V>>> {
    on_ray(ray, tri, interval, EdgeRule::OneHit)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::IntersectLanes;
    use crate::testing::Draws;
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
            let corners = |k: Axis| L::<V>::new(tri.a.get(k), tri.b.get(k), tri.c.get(k));
            let p = [
                corners(axes[0]).sub(lanes[0]),
                corners(axes[1]).sub(lanes[1]),
                pz,
            ];
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

    /// The interval tests' shortcut (`watertight_in_lanes`, what
    /// `ray_triangle_in`, `ray_triangle_prepared_in` and
    /// `ray_triangle_one_hit_in` run) and its batch form (what
    /// `ray_triangle_batch_in` and `ray_triangle_batch_occluded` run) give,
    /// bit for bit, the answer of `watertight_in` alone, in both precisions
    /// and both edge rules (the batches: the closed one): on
    /// random triangles with rays aimed at their centroid, an edge's
    /// midpoint or a corner (most of them hits), and on zero-area ones;
    /// with interval ends far from the crossing (the shortcut decides),
    /// and the hit's `t` and its neighbours a few ulps away as either end
    /// (the shortcut cannot, and the exact steps decide).
    #[test]
    fn shortcut_is_watertight_in() {
        /// `shape`: 0 any triangle, 1 zero area, 2 flat (corners at one
        /// `z`, the ray mostly along `z`: every corner at the crossing's
        /// depth, where the depths' margin is all that decides).
        fn check<V: Vector>(draws: &mut Draws, shape: u8) -> (usize, usize) {
            let mut v = || {
                V::new(
                    S::<V>::from_f64(draws.coordinate(40)),
                    S::<V>::from_f64(draws.coordinate(40)),
                    S::<V>::from_f64(draws.coordinate(40)),
                )
            };
            let (a, b, mut c, mut origin) = (v(), v(), v(), v());
            if shape == 2 {
                c = V::new(c.x(), c.y(), a.z());
            }
            let tri = match shape {
                1 => Triangle::new(a, (a + b) * S::<V>::HALF, b),
                2 => Triangle::new(a, V::new(b.x(), b.y(), a.z()), c),
                _ => Triangle::new(a, b, c),
            };
            let third = S::<V>::ONE / S::<V>::from_u32(3);
            let target = match draws.next() % 4 {
                _ if shape == 2 => (tri.a + tri.b + tri.c) * third,
                0 => (tri.a + tri.b) * S::<V>::HALF,
                1 => tri.c,
                _ => (tri.a + tri.b + tri.c) * third,
            };
            if shape == 2 {
                let mut small = || S::<V>::from_f64(draws.coordinate(40).clamp(-4.0, 4.0));
                let (dx, dy, dz) = (small(), small(), small());
                origin = target + V::new(dx, dy, dz.abs() + S::<V>::from_u32(5));
            }
            let ray = Ray::new(origin, target - origin);
            if !ray.is_valid() {
                return (0, 0);
            }
            let prepared = PreparedRay::new(&ray);
            let shear = Shear::new(&ray.dir);
            let bits = crate::testing::hit_bits::<S<V>>;
            let all = Interval::up_to(S::<V>::INFINITY).unwrap();
            let Some(t) = watertight_in(ray.origin, ray.dir, &shear, &tri, all, EdgeRule::Closed)
                .map(|h| h.t)
            else {
                return (0, 0);
            };
            let step = |t: S<V>, k: i32| {
                (0..k.abs()).fold(t, |t, _| if k > 0 { t.next_up() } else { t.next_down() })
            };
            let (mut near, mut far) = (0, 0);
            let mut ends: std::vec::Vec<S<V>> = (-3..=3).map(|k| step(t, k)).collect();
            for scale in [0.0, 0.25, 0.5, 0.999, 1.001, 2.0, 1e6] {
                ends.push(t * S::<V>::from_f64(scale));
            }
            ends.push(S::<V>::INFINITY);
            for &lo in &ends {
                for &hi in &ends {
                    let Some(window) = Interval::new(lo, hi) else {
                        continue;
                    };
                    for rule in [EdgeRule::Closed, EdgeRule::OneHit] {
                        let expected = bits(watertight_in(
                            ray.origin, ray.dir, &shear, &tri, window, rule,
                        ));
                        let got = match rule {
                            EdgeRule::Closed => {
                                assert_eq!(
                                    bits(ray_triangle_prepared_in(&prepared, &tri, window, rule)),
                                    expected,
                                    "{ray:?} {tri:?} {window:?}"
                                );
                                // The batch forms, with the triangle in
                                // lanes 0 and 9 of two chunks.
                                let mut batch = crate::batch::TriangleBatch::<V, 16>::empty();
                                batch.set(0, &tri);
                                batch.set(9, &tri);
                                let hits = batch.hit(&prepared, window);
                                for lane in [0, 9] {
                                    assert_eq!(
                                        bits(hits.get(lane)),
                                        expected,
                                        "{ray:?} {tri:?} {window:?}"
                                    );
                                }
                                assert_eq!(hits.mask & !0b10_0000_0001, 0);
                                assert_eq!(batch.occluded(&prepared, window), expected.is_some());
                                ray_triangle_in(&ray, &tri, window)
                            }
                            EdgeRule::OneHit => {
                                assert_eq!(
                                    bits(ray_triangle_prepared_in(&prepared, &tri, window, rule)),
                                    expected,
                                    "{ray:?} {tri:?} {window:?}"
                                );
                                ray_triangle_one_hit_in(&ray, &tri, window)
                            }
                        };
                        assert_eq!(bits(got), expected, "{ray:?} {tri:?} {window:?} {rule:?}");
                    }
                    if lo < t && t <= hi {
                        far += usize::from(lo < t * S::<V>::HALF && t * S::<V>::TWO <= hi);
                    }
                }
            }
            for k in -3..=3 {
                near += usize::from(Interval::new(step(t, k), S::<V>::INFINITY).is_some());
            }
            (near, far)
        }
        // Each check draws a fixed number of values (twelve coordinates and
        // the target's choice, three more for `shape` 2), so the cases are
        // laid out first, each with the generator's state it starts from
        // and the one it must end at, and run on two threads: the same
        // cases, in the same precisions, as one sequential run.
        let per_case = |shape: u8| if shape == 2 { 16 } else { 13 };
        let mut draws = Draws(0x0bad_cafe_1234_5678);
        let mut cases = std::vec::Vec::new();
        for (shapes, count) in [(&[0u8, 2][..], 1_000), (&[1u8][..], 1_000)] {
            for _ in 0..count {
                for &shape in shapes {
                    for wide in [false, true] {
                        let start = draws.0;
                        for _ in 0..per_case(shape) {
                            draws.next();
                        }
                        cases.push((start, draws.0, wide, shape));
                    }
                }
            }
        }
        let run = |cases: &[(u64, u64, bool, u8)]| {
            cases
                .iter()
                .map(|&(start, end, wide, shape)| {
                    let mut d = Draws(start);
                    let got = if wide {
                        check::<DVec3>(&mut d, shape)
                    } else {
                        check::<Vec3>(&mut d, shape)
                    };
                    assert_eq!(d.0, end, "a check drew an unexpected number of values");
                    (got, shape)
                })
                .collect::<std::vec::Vec<_>>()
        };
        let (first, second) = cases.split_at(cases.len() / 2);
        let results = std::thread::scope(|s| {
            let other = s.spawn(|| run(second));
            let mut all = run(first);
            all.extend(other.join().expect("the second half ran"));
            all
        });
        let (mut near, mut far, mut hits) = (0, 0, 0);
        for ((n, f), shape) in results {
            if shape == 1 {
                hits += n;
            } else {
                near += n;
                far += f;
            }
        }
        // Enough hits, with ends both near and far, that the comparison
        // means something.
        assert!(near > 10_000 && far > 10_000, "{near} {far}");
        assert!(hits > 100, "{hits}");
    }
}
