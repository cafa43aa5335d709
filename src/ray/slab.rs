//! The box tests' per-ray part: the ray's origin and, per axis, the
//! reciprocal of its direction, rounded so that the slab test stays
//! conservative.

use super::{Ray, invalid_stand_in};
use crate::num::{L, Lanes, S, Scalar, Vector, lanes};

/// The slab test's per-ray data, in lanes: see `PreparedRay::new`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SlabRay<V: Vector> {
    pub(crate) origin: L<V>,
    /// Per axis, the reciprocal used for the distance to the `min` plane.
    pub(crate) inv_to_min: L<V>,
    /// Per axis, the reciprocal used for the distance to the `max` plane.
    pub(crate) inv_to_max: L<V>,
}

impl<V: Vector> PartialEq for SlabRay<V> {
    fn eq(&self, o: &Self) -> bool {
        self.origin.to_array() == o.origin.to_array()
            && self.inv_to_min.to_array() == o.inv_to_min.to_array()
            && self.inv_to_max.to_array() == o.inv_to_max.to_array()
    }
}

impl<V: Vector> SlabRay<V> {
    /// See `PreparedRay::new`; and whether every reciprocal is a normal
    /// float (`PreparedRay::simple`). An invalid ray is prepared as
    /// [`invalid_stand_in`]: an origin at `+inf` puts every box at
    /// `t = -inf`, a miss for every valid box with no flag to test in the
    /// hot loop.
    #[inline(always)]
    pub(crate) fn new(ray: &Ray<V>) -> (Self, bool) {
        if !ray.is_valid() {
            let stand_in = invalid_stand_in::<V>();
            return Self::of(lanes(stand_in.origin), lanes(stand_in.dir));
        }
        Self::of(lanes(ray.origin), lanes(ray.dir))
    }

    /// The preparation itself, for a ray that is valid or the stand-in for
    /// an invalid one, given as lanes.
    #[inline(always)]
    pub(crate) fn of(origin: L<V>, dir: L<V>) -> (Self, bool) {
        let (one, zero) = (L::<V>::splat(S::<V>::ONE), L::<V>::splat(S::<V>::ZERO));
        let r = one.div(dir);
        // Where every reciprocal is a normal float (or an exact infinity,
        // from d = +-0), both planes use it.
        let a = r.abs();
        let normal =
            L::<V>::splat(S::<V>::MIN_POSITIVE).le(a) & a.lt(L::<V>::splat(S::<V>::INFINITY));
        if normal | dir.eq(zero) == 0b111 {
            let slab = Self {
                origin,
                inv_to_min: r,
                inv_to_max: r,
            };
            return (slab, normal == 0b111);
        }
        (Self::stepped(origin, dir), false)
    }

    /// The rare case of [`SlabRay::new`]: some reciprocal is subnormal or
    /// has overflowed.
    ///
    /// A subnormal reciprocal `r = fl(1/d)` is within half a subnormal
    /// `tiny` of `1/d`, so each step is within `1.5 tiny`, that is within
    /// `1.5 tiny |d| <= 1.5 tiny MAX < 12u` relative (`u` the unit
    /// roundoff: `2^-21 1.5 = 12 2^-24` in `f32`, `2^-50 1.5 = 12 2^-53` in
    /// `f64`). An entry distance through that slab is then at least `E (1 -
    /// u)^2 (1 - 12u)` and an exit at most `X (1 + u)^2 (1 + 12u)`, so the
    /// `exit_slack` argument gives a false-hit factor of `(1 + u)^3 (1 +
    /// 12u) W / ((1 - u)^2 (1 - 12u))`, about `1 + 37u`: the documented
    /// `1 + 40u`. The reported entry stays within `(1 - u)^2 (1 - 12u)`, so
    /// within `15u`.
    #[cold]
    #[inline(never)]
    fn stepped(origin: L<V>, dir: L<V>) -> Self {
        // Stepping: for d > 0 the min plane is the entry (wants the smaller
        // magnitude, r stepped down) and the max plane the exit (r stepped
        // up). For d < 0, r is negative and the roles swap, and stepping
        // down again gives the min plane (now the exit) the larger magnitude.
        // So in both cases the min plane gets `r.next_down()` and the max
        // plane `r.next_up()`.
        let axis = |d: S<V>| {
            let r = S::<V>::ONE / d;
            let normal = r.abs() >= S::<V>::MIN_POSITIVE && r.abs() < S::<V>::INFINITY;
            if normal || d == S::<V>::ZERO {
                (r, r)
            } else {
                (r.next_down(), r.next_up())
            }
        };
        let [dx, dy, dz] = dir.to_array();
        let (x0, x1) = axis(dx);
        let (y0, y1) = axis(dy);
        let (z0, z1) = axis(dz);
        Self {
            origin,
            inv_to_min: L::<V>::new(x0, y0, z0),
            inv_to_max: L::<V>::new(x1, y1, z1),
        }
    }
}
