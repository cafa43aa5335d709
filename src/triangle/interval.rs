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
//!    The shortcut runs this step where its corners straddle an end
//!    ([`band_verdict`]), with the same bound's terms evaluated from its
//!    lanes and widened once (`super::band`).
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

use super::band::band_verdict;
use super::bounds::{ErrorBounds, HitCondition, longest_edge_t};
use super::conditioning::edge_signs_known_at_corners;
use super::definition::{EdgeRule, hit_at, inside};
use super::frame::Frame;
use super::lanes::{DefinitionRay, Packed, frame_lanes, lanes_hit, pack, unpack};
use super::one_hit::{crossing, unresolved_hit};
use super::{Triangle, TriangleHit};
use crate::num::{Axis, L, Lanes, S, Scalar, Vector};
use crate::ray::{Interval, PreparedRay, Ray, Shear, bring_into, decide};
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
