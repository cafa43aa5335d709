//! The slab test on lanes: [`ray_aabb`] and [`ray_aabb_prepared`], all three
//! axes at once, held bit for bit to `super::definition`; and their
//! interval forms [`ray_aabb_in`] and [`ray_aabb_prepared_in`], the same
//! code with a lower end.

use super::definition::{exit_slack, exit_widening};
use super::{Aabb, SlabBox, sealed as sealed_check};
use crate::num::round::at_most;
use crate::num::{L, Lanes, S, Scalar, Vector, lanes};
use crate::ray::{Interval, PreparedRay, Ray, SlabRay, t_max_ok};

/// The slab test on a prepared ray: the part of `[0, t_max]` the ray spends
/// inside the closed box, or `None`.
///
/// Returns `Some((enter, exit))` with `0 <= enter <= exit <= t_max`, `enter`
/// finite. See [`ray_aabb`] for the guarantees; this is the same test with
/// the reciprocal computed once per ray.
#[inline]
#[must_use]
pub(crate) fn ray_aabb_prepared<V: Vector>(
    ray: &PreparedRay<V>,
    aabb: &impl SlabBox<V>,
    t_max: S<V>,
) -> Option<(S<V>, S<V>)> {
    slab_test(&ray.slab, aabb, S::<V>::ZERO, t_max)
}

/// [`ray_aabb_prepared`] on the slab part of a prepared ray (which is all
/// that [`ray_aabb`] prepares).
///
/// All three axes at once, on lanes (see `crate::num::lanes`). The unit
/// tests hold it, bit for bit, to the same operations written one axis at a
/// time (`super::definition::slab_definition`), which the box batches also
/// match: the
/// per-axis folds are lane-wise; the largest entry and the smallest exit
/// are taken in every lane (values that are never NaN: the folds see to
/// that; the entries are never `-0`, and a `-0`/`+0` tie among the exits
/// widens to the same limit); and the final comparisons, with
/// `enter <= limit && enter <= MAX` as `enter <= min(limit, MAX)`, and the
/// box's validity, are one mask.
///
/// `t_min` is the lower end the entries are folded against: `ZERO` for
/// the kernels without one (a constant, so they compile to what they
/// compiled to before it was a parameter), an interval's `min` for the
/// interval forms. It is at least zero and at most `t_max`.
///
/// Why a lower end keeps "no false miss" (the argument of
/// `exit_widening`, with `0` replaced by `t_min`). Let `E` be the exact
/// entry (the largest exact near distance over the axes the ray moves
/// along) and `X` the exact exit, and suppose the closed box meets the
/// ray somewhere in `[t_min, t_max]`: `E' = max(E, t_min) <= L = min(X,
/// t_max)`. Each computed near distance of an exact `e` is at most
/// `e (1 + u)^3` when `e >= 0`, and folding it against the float
/// `t_min >= 0` (exact, never rounded) gives at most
/// `max(e (1 + u)^3, t_min) <= max(e, t_min) (1 + u)^3`; a negative `e`
/// gives `t_min`; an axis the ray does not move along gives `t_min` or a
/// NaN that the fold ignores. So the computed entry is at most `E' (1 +
/// u)^3 <= L (1 + u)^3`. The exit side is unchanged: the computed exit
/// is at least `L (1 - u)^3` (`t_max` is exact too), and the widened exit
/// `fl(exit W) + slack` at least `L (1 - u)^4 W >= L (1 + u)^3`: at least
/// the exact exit `L`, and at least the computed entry, so the box is
/// reported. (The subnormal and overflowed-reciprocal cases are those of
/// `ray_aabb`'s documentation, where `t_min` plays no part.) The entry
/// reported is at least `t_min`, and at most the exit.
#[inline(always)]
fn slab_test<V: Vector, B: SlabBox<V>>(
    ray: &SlabRay<V>,
    aabb: &B,
    t_min: S<V>,
    t_max: S<V>,
) -> Option<(S<V>, S<V>)> {
    let aabb = aabb.corners();
    let splat = L::<V>::splat;
    // (Lane 3 is never read. Where a vector is its three components and
    // nothing more (`Vec3`, `DVec3`, not `Vec3A`), the maximum's `x` is
    // stored right after the minimum's `z`: filling lane 3 with it lets the
    // four lanes come from one load.)
    let packed = core::mem::size_of::<V>() == 3 * core::mem::size_of::<S<V>>();
    let (x, y, z) = (aabb.min.x(), aabb.min.y(), aabb.min.z());
    let min = L::<V>::new4(x, y, z, if packed { aabb.max.x() } else { z });
    let max = lanes(aabb.max);
    let big = S::<V>::MAX;
    let (lower, limit) = (splat(t_min), splat(t_max));
    let t0 = min.sub(ray.origin).mul(ray.inv_to_min);
    let t1 = max.sub(ray.origin).mul(ray.inv_to_max);
    // Each axis folds its two plane distances into the interval [t_min,
    // t_max] (`lower` holds `t_min`, zero but for the interval forms) the
    // way Tavian Barnes does ("Fast, Branchless Ray/Bounding Box
    // Intersections, Part 3", 2022): `max(t, t_min)` and `min(t, t_max)` give
    // the second operand for a NaN `t` (origin exactly on a slab plane of
    // an axis the ray does not move along), which leaves the interval
    // unchanged, as exact arithmetic says of a closed box.
    let enter = t0.max(lower).min(t1.max(lower));
    let exit = t0.min(limit).max(t1.min(limit));
    // Widen the exit by the rounding bound so that no box that exact
    // arithmetic hits is missed (see `exit_widening`). `enter` is infinite
    // only for an axis the ray never enters (its direction component is
    // zero, or so small that every distance overflows): a miss even when
    // the limit is infinite too, hence the `MAX`.
    let widened = exit.mul(splat(exit_widening())).add(splat(exit_slack()));
    // The box is hit when the last entry is at most every widened exit and
    // at most `MAX`. The last entry, in every lane, is ready before the
    // exits are widened, so the test waits on one comparison after the
    // widening. (Widening rounds monotonically, so widening each exit and
    // then taking the smallest is widening the smallest: the same bits as
    // the definition. Nothing here is NaN, unless `t_max` is, which fails
    // below.)
    let enter = enter.max_all();
    // (`min(widened, MAX) < enter` is `widened < enter || MAX < enter`
    // for an `enter` that is not NaN: with `enter <= MAX` the minimum is
    // below `enter` exactly when `widened` is, and an `enter` above `MAX`
    // is above both. A NaN `widened` comes only from a NaN `t_max`, which
    // fails below whatever the minimum gives.)
    let miss = widened.min(splat(big)).lt(enter);
    // The box must be valid: `-MAX <= min <= max <= MAX` on every axis, a
    // NaN failing. (A `ValidAabb` was checked when it was made.)
    let invalid = if <B as sealed_check::Sealed>::CHECK {
        splat(-big).nle(min) | min.nle(max) | max.nle(splat(big))
    } else {
        0
    };
    if (miss | invalid) != 0 || !t_max_ok(t_max) {
        return None;
    }
    let exit = at_most(widened.min_all().x(), t_max);
    // `at_most(enter, t_max)` is `at_most(enter, exit)`, bit for bit: on a
    // hit `enter` is at most every widened exit, so where the smallest is
    // below `t_max` (and is `exit`) `enter` is below `t_max` too and is
    // kept either way (an `enter` equal to it in value has its bits: the
    // entries are never `-0`, nor is a widened exit, which has `2 TINY`
    // added); elsewhere `exit` is `t_max`. Written so, the entry does not
    // wait on the exits' minimum, which a caller reading only the entry
    // then never computes.
    Some((at_most(enter.x(), t_max), exit))
}

/// The slab test: the part of `[0, t_max]` that `ray` spends inside the
/// closed box `aabb`, as `Some((enter, exit))`, or `None`.
///
/// Conventions: `t` in units of `ray.dir`; the box is a closed solid, so a
/// ray starting inside has `enter = 0`, and a ray through a face, edge or
/// corner, or lying in a face plane, hits. `0 <= enter <= exit <= t_max`
/// and `enter` is finite; `exit` is `+inf` only if `t_max` is.
///
/// Guarantees, for a valid ray and box and `t_max >= 0`:
/// - **No false miss.** If exact arithmetic on the same inputs says the
///   closed box meets the ray on `[0, t_max]`, this returns `Some`. This
///   covers axis-parallel rays, rays in a face plane, zero-thickness boxes,
///   `-0.0` direction components and components so small that their
///   reciprocal overflows. The reported `exit` is at least the exact exit
///   (clipped to `t_max`). Precondition: no difference `min - o`, `max - o`
///   overflows, and the exact entry and exit distances are below `MAX / 2`
///   (with a direction component below `1/MAX`, an entry far beyond the
///   range can otherwise come out as a hit at a huge finite `t`).
/// - **False hits only at the boundary.** A `Some` for a box exact
///   arithmetic misses means the exact entry exceeds the exact exit (or
///   `t_max`) by less than a factor `1 + 16u` plus four subnormals (`u` the
///   unit roundoff, so a few ulps): the ray passes within a few ulps of an
///   edge or corner; and the reported exit is at most that factor above the
///   exact one. Where a direction component is so large that its
///   reciprocal is subnormal (`|d_i| > 2^126` in `f32`, `2^1022` in `f64`),
///   the factor is `1 + 40u`: the reciprocal then carries up to `12u` of
///   relative error. Both hold when every nonzero direction component has
///   a finite reciprocal (`|d_i| >= 1/MAX`). A smaller component's reciprocal
///   overflows, its exit distance comes out infinite, and the reported exit
///   can be far too large, and its entry distance (computed with `MAX` for
///   the reciprocal) far too small; a false hit then passes the box at a
///   distance below `enter / (MAX (1 - u)^2)` along that axis (the computed
///   entry through that slab is at least `|b - o| MAX (1 - u)^2`, and a ray
///   already past the slab is at most `enter |d_i|` beyond it).
/// - `enter` is within three roundings of the exact entry when every
///   reciprocal is a normal float, within `15u` when one is subnormal, and
///   can be far below it when one overflows; it is not a lower bound. To cull against a closest hit so far, pass that as `t_max`,
///   which the test honours conservatively.
/// - Invalid input (NaN or infinite coordinates, zero direction, inverted
///   box, NaN or negative `t_max`) gives `None`. Never panics.
///
/// ```
/// use rayhit::{Aabb, Ray, glam::Vec3, ray_aabb};
/// let unit = Aabb::new(Vec3::ZERO, Vec3::ONE);
/// let ray = Ray::new(Vec3::new(-1.0, 0.5, 0.5), Vec3::new(2.0, 0.0, 0.0));
/// // x = -1 + 2t is in [0, 1] for t in [0.5, 1]; the exit is widened by a
/// // few ulps so that no hit is ever lost.
/// let (enter, exit) = ray_aabb(&ray, &unit, f32::INFINITY).unwrap();
/// assert_eq!(enter, 0.5);
/// assert!(exit >= 1.0 && exit <= 1.0 + 8.0 * f32::EPSILON);
/// // Lying in the face plane y = 1 of the closed box: a hit.
/// let in_face = Ray::new(Vec3::new(-1.0, 1.0, 0.5), Vec3::X);
/// assert!(ray_aabb(&in_face, &unit, f32::INFINITY).is_some());
/// ```
#[inline]
#[must_use]
pub fn ray_aabb<V: Vector>(ray: &Ray<V>, aabb: &Aabb<V>, t_max: S<V>) -> Option<(S<V>, S<V>)> {
    ray_slab_box(ray, aabb, t_max)
}

/// [`ray_aabb`] on any box the slab tests take.
#[inline(always)]
pub(crate) fn ray_slab_box<V: Vector>(
    ray: &Ray<V>,
    aabb: &impl SlabBox<V>,
    t_max: S<V>,
) -> Option<(S<V>, S<V>)> {
    slab_test(&SlabRay::new(ray).0, aabb, S::<V>::ZERO, t_max)
}

/// The slab test over an interval: conservative culling of a box against
/// `(t_min, t_max]`, the box form of [`ray_aabb`]'s `[0, t_max]`.
///
/// Returns `Some((enter, exit))` with `t_min <= enter <= exit <= t_max`
/// (`enter` finite; `exit` is `+inf` only if `t_max` is), the part of the
/// interval the ray spends inside the closed box, up to rounding; or
/// `None`.
///
/// Guarantees, for a valid ray and box and any interval (the
/// preconditions of [`ray_aabb`] apply: no difference `min - o`,
/// `max - o` overflows, exact entry and exit below `MAX / 2`):
/// - **No false miss.** If exact arithmetic on the same inputs says the
///   closed box meets the ray anywhere in `[t_min, t_max]` (so in
///   particular whenever the exact segment inside the box meets `(t_min,
///   t_max]`), this returns `Some`, and `exit` is at least the exact exit
///   (clipped to `t_max`). The interval's ends are floats compared with
///   the computed distances, never rounded; the proof is `ray_aabb`'s with
///   `0` replaced by `t_min` (see the source).
/// - **False hits only at the boundary**, as for [`ray_aabb`]: a box
///   whose exact segment misses `[t_min, t_max]` is reported only within
///   the same few ulps (`1 + 16u` relative, plus four subnormals), for
///   example a box that the ray leaves just before `t_min`. A box the ray
///   leaves exactly at `t_min` is reported: it is a conservative test, and
///   the ends are not decided exactly (use [`ray_aabb_face_in`](super::face::ray_aabb_face_in)
///   for an exactly decided entry).
/// - With `interval = (0, t_max]` the answer is [`ray_aabb`]'s, bit for
///   bit.
/// - Invalid rays and boxes give `None`; bad intervals cannot be built
///   ([`Interval::new`]). Never panics.
#[inline]
#[must_use]
pub(crate) fn ray_aabb_in<V: Vector>(
    ray: &Ray<V>,
    aabb: &impl SlabBox<V>,
    interval: Interval<S<V>>,
) -> Option<(S<V>, S<V>)> {
    let (lo, hi) = ends(interval);
    slab_test(&SlabRay::new(ray).0, aabb, lo, hi)
}

/// [`ray_aabb_in`] on a [`PreparedRay`]: the same answer, bit for bit,
/// with the reciprocals computed once per ray.
#[inline]
#[must_use]
pub(crate) fn ray_aabb_prepared_in<V: Vector>(
    ray: &PreparedRay<V>,
    aabb: &impl SlabBox<V>,
    interval: Interval<S<V>>,
) -> Option<(S<V>, S<V>)> {
    let (lo, hi) = ends(interval);
    slab_test(&ray.slab, aabb, lo, hi)
}

/// The ends the slab test folds against, `(lower(interval), max)`: what
/// the batch kernels take.
#[inline(always)]
pub(crate) fn ends<F: Scalar>(interval: Interval<F>) -> (F, F) {
    (lower(interval), interval.max())
}

/// The interval's lower end with `-0.0` made `+0.0` (an interval may
/// start at `-0.0`, and the entries must never be `-0`: see
/// [`slab_test`]).
#[inline(always)]
fn lower<F: Scalar>(interval: Interval<F>) -> F {
    interval.min() + F::ZERO
}

#[cfg(test)]
mod tests {
    use super::super::definition::slab_definition;
    use super::*;
    use crate::num::round::{max2, min2};
    use crate::testing::Draws;
    use crate::{Aabb, ValidAabb};
    use glam::{DVec3, Vec3};

    /// `ValidAabb::new` takes exactly the valid boxes: flat ones in, and
    /// NaN, infinite and inverted ones (on any axis) out; the slab test on
    /// it misses nothing the checked test hits, here for a flat box.
    #[test]
    fn valid_aabb_takes_exactly_the_valid_boxes() {
        let flat = Aabb::new(Vec3::ZERO, Vec3::new(1.0, 0.0, 1.0));
        let valid = ValidAabb::new(flat).unwrap();
        assert_eq!(valid.aabb(), &flat);
        let ray = PreparedRay::new(&Ray::new(Vec3::new(0.5, -1.0, 0.5), Vec3::Y));
        let hit = ray_aabb_prepared(&ray, &valid, f32::INFINITY);
        assert!(hit.is_some());
        assert_eq!(hit, ray_aabb_prepared(&ray, &flat, f32::INFINITY));
        for axis in 0..3 {
            for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, 2.0] {
                let mut min = Vec3::ZERO;
                min[axis] = bad;
                let b = Aabb::new(min, Vec3::ONE);
                assert!(!b.is_valid() && ValidAabb::new(b).is_none(), "{b:?}");
                let mut max = Vec3::ONE;
                max[axis] = if bad == 2.0 { -1.0 } else { bad };
                let b = Aabb::new(Vec3::ZERO, max);
                assert!(!b.is_valid() && ValidAabb::new(b).is_none(), "{b:?}");
            }
        }
    }

    /// `ray_aabb_prepared` and `ray_aabb` (all axes at once) give, bit for
    /// bit, the answer of the one-axis-at-a-time definition, in both
    /// precisions, for valid and invalid boxes and rays and any `t_max`.
    #[test]
    fn slab_test_is_the_definition() {
        fn check<V: Vector>(draws: &mut Draws) -> usize {
            let mut c = || S::<V>::from_f64(draws.coordinate(200));
            let ray = Ray::new(V::new(c(), c(), c()), V::new(c(), c(), c()));
            let (a, b) = (V::new(c(), c(), c()), V::new(c(), c(), c()));
            // Mostly valid boxes, some inverted.
            let aabb = if c() > S::<V>::from_f64(-1.5) {
                Aabb::new(
                    V::new(min2(a.x(), b.x()), min2(a.y(), b.y()), min2(a.z(), b.z())),
                    V::new(max2(a.x(), b.x()), max2(a.y(), b.y()), max2(a.z(), b.z())),
                )
            } else {
                Aabb::new(a, b)
            };
            let mut hits = 0;
            for t_max in [c().abs() * S::<V>::TWO, S::<V>::INFINITY, S::<V>::NAN] {
                let p = PreparedRay::new(&ray);
                let s = &p.slab;
                let expected = (ray.is_valid() && aabb.is_valid() && t_max_ok(t_max))
                    .then(|| {
                        let [min, max] = [aabb.min, aabb.max].map(|v| [v.x(), v.y(), v.z()]);
                        let arrays = (
                            s.origin.to_array(),
                            s.inv_to_min.to_array(),
                            s.inv_to_max.to_array(),
                        );
                        let (hit, enter, exit) =
                            slab_definition(arrays.0, arrays.1, arrays.2, min, max, t_max);
                        hit.then_some((enter, exit))
                    })
                    .flatten();
                let bits = |h: Option<(S<V>, S<V>)>| {
                    h.map(|(e, x)| (e.to_f64().to_bits(), x.to_f64().to_bits()))
                };
                hits += usize::from(expected.is_some());
                assert_eq!(
                    bits(ray_aabb_prepared(&p, &aabb, t_max)),
                    bits(expected),
                    "{ray:?} {aabb:?}"
                );
                assert_eq!(
                    bits(ray_aabb(&ray, &aabb, t_max)),
                    bits(expected),
                    "{ray:?} {aabb:?}"
                );
            }
            hits
        }
        let mut draws = Draws(0x0123_4567_89ab_cdef);
        let mut hits = 0;
        for _ in 0..100_000 {
            hits += check::<Vec3>(&mut draws) + check::<DVec3>(&mut draws);
        }
        assert!(hits > 20_000, "{hits}");
    }

    /// The interval forms are the slab test with a lower end: with `(0,
    /// t_max]` (and `(-0, t_max]`) they give `ray_aabb`'s answer bit for
    /// bit; with a lower end, the entry is that end where the plain entry
    /// is below it, the exit is unchanged (the lower end takes no part in
    /// it), and the box is missed where the widened exit is below the
    /// lower end; the prepared form is the plain one, bit for bit.
    #[test]
    fn interval_forms_are_the_slab_test_with_a_lower_end() {
        fn check<V: Vector>(draws: &mut Draws) -> (usize, usize) {
            let mut c = || S::<V>::from_f64(draws.coordinate(200));
            let ray = Ray::new(V::new(c(), c(), c()), V::new(c(), c(), c()));
            let (a, b) = (V::new(c(), c(), c()), V::new(c(), c(), c()));
            let aabb = Aabb::new(
                V::new(min2(a.x(), b.x()), min2(a.y(), b.y()), min2(a.z(), b.z())),
                V::new(max2(a.x(), b.x()), max2(a.y(), b.y()), max2(a.z(), b.z())),
            );
            let bits = |h: Option<(S<V>, S<V>)>| {
                h.map(|(e, x)| (e.to_f64().to_bits(), x.to_f64().to_bits()))
            };
            let p = PreparedRay::new(&ray);
            let (mut hits, mut cut) = (0, 0);
            for t_max in [c().abs() * S::<V>::TWO, S::<V>::INFINITY] {
                let plain = ray_aabb(&ray, &aabb, t_max);
                for zero in [S::<V>::ZERO, -S::<V>::ZERO] {
                    let all = Interval::new(zero, t_max).unwrap();
                    assert_eq!(bits(ray_aabb_in(&ray, &aabb, all)), bits(plain));
                    assert_eq!(bits(ray_aabb_prepared_in(&p, &aabb, all)), bits(plain));
                }
                let Some((enter, exit)) = plain else { continue };
                hits += 1;
                // Lower ends below, at and beyond the plain entry and exit.
                let lows = [
                    enter * S::<V>::HALF,
                    enter,
                    (enter + exit) * S::<V>::HALF,
                    exit,
                ];
                for lo in lows.into_iter().chain([exit.next_up(), exit * S::<V>::TWO]) {
                    let Some(window) = Interval::new(lo, t_max) else {
                        continue;
                    };
                    let got = ray_aabb_in(&ray, &aabb, window);
                    assert_eq!(bits(ray_aabb_prepared_in(&p, &aabb, window)), bits(got));
                    if lo <= exit {
                        let expected = (if enter > lo { enter } else { lo }, exit);
                        assert_eq!(bits(got), bits(Some(expected)), "{ray:?} {aabb:?} {lo:?}");
                    } else {
                        // The reported exit is the widened one clipped
                        // to t_max: beyond it, a miss.
                        assert_eq!(got, None, "{ray:?} {aabb:?} {lo:?}");
                        cut += 1;
                    }
                }
            }
            (hits, cut)
        }
        let mut draws = Draws(0x0fed_cba9_8765_4321);
        let (mut hits, mut cut) = (0, 0);
        for _ in 0..20_000 {
            for (h, c) in [check::<Vec3>(&mut draws), check::<DVec3>(&mut draws)] {
                hits += h;
                cut += c;
            }
        }
        assert!(hits > 5_000 && cut > 5_000, "{hits} {cut}");
    }
}
