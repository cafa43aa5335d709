//! Axis-aligned boxes.
//!
//! - `mod.rs`: [`Aabb`], [`ValidAabb`] and the boxes the tests take.
//! - `definition.rs`: the slab test's reference definition, one axis at a
//!   time, and its rounding bounds (the exit's widening and slack).
//! - `slab.rs`: [`ray_aabb`] and `ray_aabb_prepared`, the slab test on
//!   lanes, held to the definition bit for bit, and their interval forms
//!   (the same code with a lower end).
//! - `face.rs`: [`BoxFace`], [`BoxHit`]: the face a ray enters through,
//!   decided exactly, over `[0, t_max]` and over an interval.
//! - `naive.rs`: [`Aabb::clip_by_faces`], the face-by-face reference.
//! - `batch.rs`: [`AabbBatch`], the slab test on eight lanes of boxes at a
//!   time, held to the definition bit for bit.
//! - `query.rs`: the [`Bounds`](crate::Bounds) and
//!   [`Intersect`](crate::Intersect) implementations, and a box's surface
//!   point.

mod batch;
mod definition;
mod face;
mod naive;
mod query;
mod slab;

use glam::Vec3;

use crate::num::{S, Scalar, Vector};

pub use batch::{AabbBatch, AabbBatchHits};
pub(crate) use batch::{MaskOf, Slab8};
pub use face::{BoxFace, BoxHit};
pub(crate) use query::batch_query;
pub(crate) use slab::ends as slab_ends;
pub use slab::ray_aabb;
pub(crate) use slab::{ray_aabb_in, ray_aabb_prepared, ray_aabb_prepared_in};

/// The closed box `min <= p <= max` (component-wise).
///
/// A box is valid when every coordinate is finite and `min <= max` on every
/// axis; a box of zero thickness on some axes (a rectangle, a segment, a
/// point) is valid. An invalid box (inverted on any axis, NaN or infinite)
/// is hit by nothing.
///
/// Its queries: [`Bounds`](crate::Bounds) (the conservative slab test, for
/// BVH nodes; [`ray_aabb`] on a plain ray and a `t_max`) and
/// [`Intersect`](crate::Intersect) (the box as a closed solid, with the face
/// the ray enters through, decided exactly, and
/// [`Aabb::surface_point`]).
///
/// ```
/// use rayhit::{Aabb, glam::Vec3};
/// let b = Aabb::new(Vec3::ZERO, Vec3::ONE);
/// assert!(b.is_valid());
/// assert!(!Aabb::new(Vec3::ONE, Vec3::ZERO).is_valid());
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[repr(C)]
pub struct Aabb<V = Vec3> {
    /// The corner with the smallest coordinates.
    pub min: V,
    /// The corner with the largest coordinates.
    pub max: V,
}

impl<V: Vector> Aabb<V> {
    /// The box from `min` to `max`. Nothing is checked; see [`Aabb::is_valid`].
    #[inline]
    #[must_use]
    pub const fn new(min: V, max: V) -> Self {
        Self { min, max }
    }

    /// True when all coordinates are finite and `min <= max` on every axis.
    #[inline]
    #[must_use]
    pub fn is_valid(&self) -> bool {
        valid_box(self.min, self.max)
    }

    /// The box `center - reach ..= center + reach` (`reach` not negative),
    /// each face moved outward by an ulp where its sum rounded inward (the
    /// rounding error's sign from Knuth's two-sum), so that it holds the
    /// exact box: the shapes' bounds.
    #[inline]
    #[must_use]
    pub(crate) fn around(center: V, reach: V) -> Self {
        use crate::num::exact_sign::two_diff;
        let zero = S::<V>::ZERO;
        let face = |i: usize, side: S<V>| match two_diff(center[i], -(side * reach[i])) {
            (s, e) if e * side > zero => {
                if side > zero {
                    s.next_up()
                } else {
                    s.next_down()
                }
            }
            (s, _) => s,
        };
        let one = S::<V>::ONE;
        Self::new(
            V::new(face(0, -one), face(1, -one), face(2, -one)),
            V::new(face(0, one), face(1, one), face(2, one)),
        )
    }
}

/// A box known to be valid ([`Aabb::is_valid`]): checked once, when it is
/// made, so that its tests ([`Bounds::clip`](crate::Bounds::clip), the
/// node test) need not check it on every call. Store a BVH's node boxes
/// this way.
///
/// Its corners can be read, not changed, so the check holds for as long
/// as the value lives. The tests give the same answers, bit for bit, as for
/// the [`Aabb`] it holds.
///
/// ```
/// use rayhit::{Aabb, Bounds, PreparedRay, Ray, ValidAabb, glam::Vec3};
/// let b = Aabb::new(Vec3::ZERO, Vec3::ONE);
/// let node = ValidAabb::new(b).unwrap();
/// assert!(ValidAabb::new(Aabb::new(Vec3::ONE, Vec3::ZERO)).is_none());
/// let ray = PreparedRay::new(&Ray::new(Vec3::new(-1.0, 0.5, 0.5), Vec3::X));
/// let (enter, exit) = node.clip(&ray, f32::INFINITY).unwrap();
/// // The exit is widened by its rounding bound (see `ray_aabb`).
/// assert!(enter == 1.0 && exit >= 2.0 && exit < 2.0001);
/// assert_eq!(b.clip(&ray, f32::INFINITY), Some((enter, exit)));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(transparent)]
pub struct ValidAabb<V = Vec3>(Aabb<V>);

impl<V: Vector> ValidAabb<V> {
    /// `aabb`, if it is valid ([`Aabb::is_valid`]); `None` otherwise.
    #[inline]
    #[must_use]
    pub fn new(aabb: Aabb<V>) -> Option<Self> {
        aabb.is_valid().then_some(Self(aabb))
    }

    /// The box.
    #[inline]
    #[must_use]
    pub const fn aabb(&self) -> &Aabb<V> {
        &self.0
    }
}

impl<V> From<ValidAabb<V>> for Aabb<V> {
    #[inline]
    fn from(b: ValidAabb<V>) -> Self {
        b.0
    }
}

mod sealed {
    /// The seal of [`SlabBox`](super::SlabBox), with what the tests need to
    /// know of each box type.
    pub trait Sealed {
        /// Whether the tests must check the box's validity.
        const CHECK: bool;
    }
}

/// The boxes the slab tests take: an [`Aabb`], whose validity they check on
/// every call (an invalid box is hit by nothing), or a [`ValidAabb`],
/// checked once when it was made. Sealed.
pub(crate) trait SlabBox<V: Vector>: sealed::Sealed {
    /// The box.
    fn corners(&self) -> &Aabb<V>;
}

impl<V> sealed::Sealed for Aabb<V> {
    const CHECK: bool = true;
}
impl<V> sealed::Sealed for ValidAabb<V> {
    const CHECK: bool = false;
}

impl<V: Vector> SlabBox<V> for Aabb<V> {
    #[inline(always)]
    fn corners(&self) -> &Aabb<V> {
        self
    }
}

impl<V: Vector> SlabBox<V> for ValidAabb<V> {
    #[inline(always)]
    fn corners(&self) -> &Aabb<V> {
        &self.0
    }
}

/// `-MAX <= min[k] <= max[k] <= MAX` on every axis: finite and not
/// inverted (a NaN fails), as three packed comparisons.
#[inline(always)]
pub(crate) fn valid_box<V: Vector>(min: V, max: V) -> bool {
    let big = V::splat(S::<V>::MAX);
    (-big).all_le(min) & min.all_le(max) & max.all_le(big)
}
