//! The face a ray enters a box through, decided exactly, and the box tests
//! that report it, over `[0, t_max]` and over an interval.

use super::{Aabb, ray_aabb, ray_aabb_in, ray_aabb_prepared, ray_aabb_prepared_in};
use crate::num::exact_sign::{scale_to_one, sum_of_products_sign, two_diff};
use crate::num::{S, Scalar, Vector};
use crate::ray::{Interval, PreparedRay, Ray, crossing_in};

/// A face of a box: one axis's `min` or `max` side.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[repr(u8)]
pub enum BoxFace {
    /// The face `x = min.x`, outward normal `-x`.
    MinX,
    /// The face `x = max.x`, outward normal `+x`.
    MaxX,
    /// The face `y = min.y`, outward normal `-y`.
    MinY,
    /// The face `y = max.y`, outward normal `+y`.
    MaxY,
    /// The face `z = min.z`, outward normal `-z`.
    MinZ,
    /// The face `z = max.z`, outward normal `+z`.
    MaxZ,
}

impl BoxFace {
    /// The face on `axis` (0, 1, 2 for x, y, z; `None` above), on the `max`
    /// side or the `min` side.
    #[inline]
    #[must_use]
    pub const fn new(axis: usize, max_side: bool) -> Option<Self> {
        Some(match (axis, max_side) {
            (0, false) => BoxFace::MinX,
            (0, true) => BoxFace::MaxX,
            (1, false) => BoxFace::MinY,
            (1, true) => BoxFace::MaxY,
            (2, false) => BoxFace::MinZ,
            (2, true) => BoxFace::MaxZ,
            _ => return None,
        })
    }

    /// The face's axis: 0, 1 or 2 for x, y, z.
    #[inline]
    #[must_use]
    pub const fn axis(self) -> usize {
        self as usize / 2
    }

    /// True for the `max` side of the axis.
    #[inline]
    #[must_use]
    pub const fn is_max(self) -> bool {
        self as usize % 2 == 1
    }

    /// The outward unit normal: `+1` or `-1` on the face's axis, exactly.
    #[inline]
    #[must_use]
    pub fn normal<V: Vector>(self) -> V {
        let s = if self.is_max() {
            S::<V>::ONE
        } else {
            -S::<V>::ONE
        };
        let z = S::<V>::ZERO;
        match self.axis() {
            0 => V::new(s, z, z),
            1 => V::new(z, s, z),
            _ => V::new(z, z, s),
        }
    }

    /// The coordinate of the face's plane on its axis, for `aabb`.
    #[inline]
    #[must_use]
    pub fn plane<V: Vector>(self, aabb: &Aabb<V>) -> S<V> {
        let corner = if self.is_max() { aabb.max } else { aabb.min };
        corner[self.axis()]
    }
}

/// A box hit: the slab test's interval and the face the ray enters through.
///
/// `enter` and `exit` are exactly what [`ray_aabb`](crate::ray_aabb) (or
/// [`Aabb`'s `clip`](crate::Aabb#method.clip), or for the interval
/// forms [`Aabb`'s `clip` over an interval](crate::Aabb#method.clip)) returns. `face` is decided in exact arithmetic:
/// see [`Aabb`'s `hit`](crate::Aabb#method.hit), and [`Aabb`'s `hit` over an interval](crate::Aabb#method.hit) for the interval forms,
/// where it is also `None` when the entry is not within the interval.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[repr(C)]
pub struct BoxHit<F = f32> {
    /// Where the ray enters the box (0 when it starts inside).
    pub enter: F,
    /// Where it leaves the box, or `t_max`.
    pub exit: F,
    /// The face it enters through; `None` when it starts inside the box or
    /// on its boundary (the exact entry is at `t <= 0`).
    pub face: Option<BoxFace>,
}

/// The face through which the ray `origin + t dir` enters the box, decided
/// exactly: among the axes whose entry plane the ray crosses at a `t > 0`,
/// the one it crosses last (largest `t`), the lowest axis on a tie;
/// `None` when there is none.
fn entry_face<V: Vector>(origin: V, dir: V, aabb: &Aabb<V>) -> Option<BoxFace> {
    let zero = S::<V>::ZERO;
    // Per candidate axis: the axis and `(s, e, d, c)`, with the exact
    // distance to its entry plane `(s + e) / d`, `s + e = plane - o`
    // exactly, and `c = fl(s / d)`.
    type Distance<F> = (F, F, F, F);
    let mut best: Option<(usize, Distance<S<V>>)> = None;
    for k in 0..3 {
        let d = dir[k];
        if !(d != zero) {
            continue; // parallel to the slab: no entry plane
        }
        let plane = if d > zero { aabb.min[k] } else { aabb.max[k] };
        let (s, e) = two_diff(plane, origin[k]);
        // `fl(plane - o)` has the exact difference's sign (and is zero only
        // when it is): the plane is ahead exactly when `s` has `d`'s sign.
        if !(s != zero && (s > zero) == (d > zero)) {
            continue;
        }
        let c = s / d;
        let later = match best {
            None => true,
            Some((_, other)) => crosses_later((s, e, d, c), other),
        };
        if later {
            best = Some((k, (s, e, d, c)));
        }
    }
    best.and_then(|(k, (_, _, d, _))| BoxFace::new(k, d < zero))
}

/// Whether the exact distance `(s + e) / d` of the first plane is larger
/// than that of the second (both positive; `c` is `fl(s / d)`).
///
/// `c` carries two roundings of the exact distance (that of `s`, and the
/// division), so where both are normal floats `c` lies within a factor
/// `(1 + u)^2` of it, and `c1 > c2 (1 + 8u)` (or `<` with `1 - 8u`) settles
/// the comparison. Otherwise (within about four ulps, or an overflowed or
/// tiny quotient) the sign of `(s1 + e1) |d2| - (s2 + e2) |d1|` is computed
/// exactly from the four products, in `f64` (exact for `f32` inputs), with
/// the two numerators and the two directions each scaled by a common power
/// of two first, so that tiny or huge inputs do not underflow or overflow
/// the products. (For `f64` inputs whose two numerators, or two
/// directions, differ by a factor beyond `2^900`, a product can still
/// underflow: the crate's standing precondition of no intermediate
/// underflow.)
fn crosses_later<F: Scalar>(
    (s1, e1, d1, c1): (F, F, F, F),
    (s2, e2, d2, c2): (F, F, F, F),
) -> bool {
    let normal = |c: F| c >= F::MIN_POSITIVE && c <= F::MAX;
    if normal(c1) && normal(c2) {
        let margin = F::from_u32(8) * F::UNIT_ROUNDOFF;
        if c1 > c2 * (F::ONE + margin) {
            return true;
        }
        if c1 < c2 * (F::ONE - margin) {
            return false;
        }
    }
    let (s1, e1, d1, s2, e2, d2) = (
        s1.to_f64(),
        e1.to_f64(),
        d1.to_f64(),
        s2.to_f64(),
        e2.to_f64(),
        d2.to_f64(),
    );
    // |plane - o| = sign(s) (s + e): both distances are positive.
    let (g1, g2) = (s1.signum(), s2.signum());
    let ks = |x: f64| scale_to_one(x, s1.abs().max(s2.abs()));
    let kd = |x: f64| scale_to_one(x, d1.abs().max(d2.abs()));
    let terms = [
        (ks(g1 * s1), kd(d2.abs())),
        (ks(g1 * e1), kd(d2.abs())),
        (-ks(g2 * s2), kd(d1.abs())),
        (-ks(g2 * e2), kd(d1.abs())),
    ];
    sum_of_products_sign(&terms) == core::cmp::Ordering::Greater
}

/// [`ray_aabb`](crate::ray_aabb) with the face the ray enters through.
///
/// Same interval as [`ray_aabb`](crate::ray_aabb), bit for bit, and the same `None`. The
/// face is decided in exact arithmetic on the same inputs: it is a face
/// whose plane the exact ray crosses at the exact entry distance. Where
/// several do (the ray enters through an edge or a corner), it is the one
/// on the lowest axis (x, then y, then z). Where the exact entry is at
/// `t <= 0` (the ray starts inside the box or on its boundary) there is no
/// entry face, and `face` is `None`. Where the conservative test reports a
/// box that the exact ray misses by a few ulps (see [`ray_aabb`](crate::ray_aabb)), the face
/// is still the entry plane the exact ray crosses last.
///
/// Cost: the entry face needs the axes' distances compared; where two are
/// within about four ulps of each other (near an edge or corner) the
/// comparison is redone exactly, from error-free products. Use [`ray_aabb`](crate::ray_aabb)
/// when only the interval is wanted.
///
/// Precondition of the exact face, for `f64` only (`f32` has none): on each
/// axis the origin coordinate and the box's are each zero or within a
/// factor `2^300` of each other, and the nonzero direction components are
/// within a factor `2^300` of each other (beyond that a product in the
/// exact comparison can underflow, and a tie can be decided wrongly).
#[must_use]
pub(crate) fn ray_aabb_face<V: Vector>(
    ray: &Ray<V>,
    aabb: &Aabb<V>,
    t_max: S<V>,
) -> Option<BoxHit<S<V>>> {
    let (enter, exit) = ray_aabb(ray, aabb, t_max)?;
    Some(BoxHit {
        enter,
        exit,
        face: entry_face(ray.origin, ray.dir, aabb),
    })
}

/// [`Aabb`'s `clip`](crate::Aabb#method.clip) with the face the ray enters through: the same
/// interval, bit for bit, and the face as [`Aabb`'s `hit`](crate::Aabb#method.hit) decides it.
#[must_use]
pub(crate) fn ray_aabb_prepared_face<V: Vector>(
    ray: &PreparedRay<V>,
    aabb: &Aabb<V>,
    t_max: S<V>,
) -> Option<BoxHit<S<V>>> {
    let (enter, exit) = ray_aabb_prepared(ray, aabb, t_max)?;
    Some(BoxHit {
        enter,
        exit,
        face: entry_face(ray.origin(), ray.dir, aabb),
    })
}

/// The entry face of `ray` into `aabb` (as [`entry_face`] decides it) if
/// its exact crossing is in `interval`, decided exactly.
///
/// The entry is the crossing of one plane, the face's: the plane through
/// the origin with the face's coordinate on its axis, normal the axis.
/// Its point differs from the origin on that axis only, so the exact
/// signs see one difference and one direction component (the
/// preconditions of [`Aabb`'s `hit`](crate::Aabb#method.hit) cover them), and the quotient is
/// `fl(fl(plane - o) / d)`, as [`entry_face`] computes it.
fn entry_face_in<V: Vector>(
    origin: V,
    dir: V,
    aabb: &Aabb<V>,
    interval: Interval<S<V>>,
) -> Option<BoxFace> {
    let face = entry_face(origin, dir, aabb)?;
    let k = face.axis();
    let c = face.plane(aabb);
    let point = match k {
        0 => V::new(c, origin.y(), origin.z()),
        1 => V::new(origin.x(), c, origin.z()),
        _ => V::new(origin.x(), origin.y(), c),
    };
    let normal = BoxFace::new(k, true)?.normal::<V>();
    crossing_in(origin, dir, point, normal, interval).map(|_| face)
}

/// [`Aabb`'s `hit`](crate::Aabb#method.hit) over an interval: [`Aabb`'s `clip` over an interval](crate::Aabb#method.clip)'s conservative
/// interval, and the face the ray enters through when it enters within
/// `(t_min, t_max]`, decided exactly.
///
/// `enter` and `exit` are exactly what [`Aabb`'s `clip` over an interval](crate::Aabb#method.clip) returns (so
/// `t_min <= enter <= exit <= t_max`), and `None` exactly when it does.
/// `face` is the entry face as [`Aabb`'s `hit`](crate::Aabb#method.hit) defines it (the face
/// whose plane the exact ray crosses at the exact entry distance `E*`,
/// the lowest axis at an edge or corner; decided in exact arithmetic),
/// reported only when `t_min < E* <= t_max`, decided exactly (`E*` is the
/// crossing of one face plane, placed against both ends as
/// [`Plane`'s `hit` over an interval](crate::Plane#method.hit) places a crossing). Otherwise
/// `face` is `None`: the ray entered at or before `t_min` (it is inside the
/// closed box at `t_min`, or started inside), or, for a box reported
/// within rounding of a miss, `E*` lies beyond `t_max`.
///
/// So over consecutive intervals `(t0, t1]`, `(t1, t2]`, ... a box entry
/// is reported once: the entry face appears in exactly one interval
/// (the one holding `E*`) when the exact ray meets the box and `E*` is in
/// their union; in the other intervals the box may be reported (it is
/// there, or within rounding), but with `face: None`. Where the exact ray
/// misses the box by a few ulps and the conservative test still reports
/// it, the face appears at most once.
///
/// With `interval = (0, t_max]` the answer is [`Aabb`'s `hit`](crate::Aabb#method.hit)'s, bit
/// for bit (its face is `None` exactly when `E* <= 0`), except that a
/// face whose `E*` is beyond `t_max` (or beyond `MAX`, which no float `t`
/// reaches) is not reported here.
///
/// Cost: [`Aabb`'s `clip` over an interval](crate::Aabb#method.clip), the entry face, and for a face, one plane
/// crossing decided against the ends (a filter, and exact signs within
/// rounding of an end). Precondition of the exact face and of the exact
/// decision, for `f64` only: that of [`Aabb`'s `hit`](crate::Aabb#method.hit). Invalid rays and
/// boxes give `None`; bad intervals cannot be built ([`Interval::new`]).
#[must_use]
pub(crate) fn ray_aabb_face_in<V: Vector>(
    ray: &Ray<V>,
    aabb: &Aabb<V>,
    interval: Interval<S<V>>,
) -> Option<BoxHit<S<V>>> {
    let (enter, exit) = ray_aabb_in(ray, aabb, interval)?;
    Some(BoxHit {
        enter,
        exit,
        face: entry_face_in(ray.origin, ray.dir, aabb, interval),
    })
}

/// [`Aabb`'s `hit` over an interval](crate::Aabb#method.hit) on a [`PreparedRay`]: the same answer, bit for
/// bit.
#[must_use]
pub(crate) fn ray_aabb_prepared_face_in<V: Vector>(
    ray: &PreparedRay<V>,
    aabb: &Aabb<V>,
    interval: Interval<S<V>>,
) -> Option<BoxHit<S<V>>> {
    let (enter, exit) = ray_aabb_prepared_in(ray, aabb, interval)?;
    Some(BoxHit {
        enter,
        exit,
        face: entry_face_in(ray.origin(), ray.dir, aabb, interval),
    })
}
