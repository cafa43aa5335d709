//! The slab test's reference definition: one axis at a time, with scalar
//! comparisons. [`ray_aabb_prepared`](super::slab::ray_aabb_prepared),
//! [`ray_aabb`](crate::ray_aabb), the box batches and the compressed
//! node test run the same operations on lanes, and their tests hold them to
//! [`slab_definition`] bit for bit. The exit's widening and slack, which
//! every form applies, are derived here.

use crate::num::Scalar;

/// The widening factor `W = 1 + 2*gamma(4)` for the exit distance, rounded
/// up.
///
/// Derivation. For one axis, the computed entry distance is
/// `fl(fl(min - o) * inv)` with `inv` the rounded reciprocal (or, outside the
/// normal range, one no larger in magnitude than `1/d`): at most three
/// roundings, so for an exact entry `e >= 0` it is at most `e (1 + u)^3`
/// (plus at most half a subnormal if the product underflows). The exit is
/// likewise at least `x (1 - u)^3`. `0` and `t_max` are exact, and min and
/// max are exact. If exactly `max(E, 0) <= L = min(X, t_max)` (the box is
/// hit), the computed entry is at most `L (1 + u)^3` and the computed limit
/// at least `L (1 - u)^3`; multiplying the limit by `W` and rounding once
/// more keeps `entry <= fl(limit * W)` whenever `W (1 - u)^4 >= (1 + u)^3`.
/// With `W = 1 + 8u/(1 - 4u)`, multiplying out,
/// `(1 + 4u)(1 - u)^4 - (1 + u)^3 (1 - 4u) = u - u^2 + 31u^3 - 11u^4 + 4u^5`,
/// which is positive. pbrt-v4 widens by `1 + 2*gamma(3)`, enough for its two
/// roundings per distance; Ize, "Robust BVH Ray Traversal", JCGT 2013, makes
/// the same argument in ulps. The value is stepped up one ulp to cover its
/// own rounding.
#[inline(always)]
pub(crate) fn exit_widening<F: Scalar>() -> F {
    (F::ONE + F::TWO * F::gamma_n(4)).next_up()
}

/// The absolute slack `2 * TINY` added to the widened exit. Where products
/// underflow, rounding errors are absolute (at most half a subnormal each)
/// rather than relative; three of them (entry, exit, widening) are covered by
/// two subnormals. For normal-range distances adding it changes nothing.
///
/// The false-hit band pays for it: exactly, `E (1 - u)^3 - TINY/2` is at
/// most the computed entry, which is at most the computed limit,
/// `(X (1 + u)^3 + TINY/2) W (1 + u) + TINY/2 + 2 TINY`. So
/// `E <= X (1 + u)^4 W / (1 - u)^3 + 3.5 TINY / (1 - u)^3`, that is
/// `E < X (1 + 16u) + 4 TINY`: the documented band has four subnormals, not
/// two (the fuzzer found a false hit 2.5 subnormals out, which the
/// regression tests keep).
#[inline(always)]
pub(crate) fn exit_slack<F: Scalar>() -> F {
    F::TWO * F::TINY
}

#[cfg(test)]
pub(crate) use reference::slab_definition;

/// The definition itself, compiled for the tests (the kernels run its
/// operations on lanes).
#[cfg(test)]
mod reference {
    use super::{exit_slack, exit_widening};
    use crate::num::Scalar;
    use crate::num::round::{at_most, max2, min2};

    /// `t` unless it is below `lo` or NaN, else `lo`.
    fn at_least<F: Scalar>(t: F, lo: F) -> F {
        if t > lo { t } else { lo }
    }

    /// The slab test's definition: its arithmetic for one box, one axis at a
    /// time, without the checks of the box's validity and of `t_max >= 0`:
    /// `(hit, enter, exit)`, where `enter` and `exit` are the answer when `hit`
    /// holds. [`ray_aabb_prepared`](super::slab::ray_aabb_prepared) and the box
    /// batches must give exactly these bits. (Compiled for the tests: the
    /// kernels run its operations on lanes.)
    pub(crate) fn slab_definition<F: Scalar>(
        origin: [F; 3],
        inv_to_min: [F; 3],
        inv_to_max: [F; 3],
        min: [F; 3],
        max: [F; 3],
        t_max: F,
    ) -> (bool, F, F) {
        let zero = F::ZERO;
        // Each axis folds its two plane distances into the interval [0, t_max]
        // the way Tavian Barnes does ("Fast, Branchless Ray/Bounding Box
        // Intersections, Part 3", 2022): a NaN distance (origin exactly on a slab
        // plane of an axis the ray does not move along) leaves the interval
        // unchanged, which is what exact arithmetic says of a closed box.
        let slab = |k: usize| {
            let t0 = (min[k] - origin[k]) * inv_to_min[k];
            let t1 = (max[k] - origin[k]) * inv_to_max[k];
            let enter = min2(at_least(t0, zero), at_least(t1, zero));
            let exit = max2(at_most(t0, t_max), at_most(t1, t_max));
            (enter, exit)
        };
        let (ex, xx) = slab(0);
        let (ey, xy) = slab(1);
        let (ez, xz) = slab(2);
        slab_finish(max2(ex, max2(ey, ez)), min2(xx, min2(xy, xz)), t_max)
    }

    /// The end of the slab test, from the largest per-axis entry and the
    /// smallest per-axis exit: `(hit, enter, exit)`.
    fn slab_finish<F: Scalar>(enter: F, exit: F, t_max: F) -> (bool, F, F) {
        // Widen the exit by the rounding bound so that no box that exact
        // arithmetic hits is missed (see `exit_widening`).
        let limit = exit * exit_widening::<F>() + exit_slack::<F>();
        // `enter` is infinite only for an axis the ray never enters (its
        // direction component is zero, or so small that every distance
        // overflows): a miss even when `limit` is infinite too. (`enter` is
        // never NaN, `at_least` sees to that, so `enter <= MAX` is
        // `enter < inf`, in one comparison.)
        let hit = (enter <= limit) & (enter <= F::MAX);
        let exit = at_most(limit, t_max);
        (hit, at_most(enter, exit), exit)
    }
}
