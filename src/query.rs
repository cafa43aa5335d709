//! The questions every shape answers, asked one way: [`Intersect`] (the
//! closest hit and the any-hit answer), [`Surface`] (the hit's error
//! bound and the surface point it leaves) and [`Bounds`] (a BVH node's
//! conservative test); and the values that shape a question instead of a
//! function's name: the ray's form ([`RayForm`]: a [`Ray`], a
//! [`PreparedRay`], or a prepared ray on a chosen instruction set), and
//! what to search ([`Search`]: a `t_max` or an [`Interval`], and an
//! [`EdgeRule`]).
//!
//! Each combination is chosen when the call is compiled: the form of the
//! ray is its type, and a search built at the call is a constant there,
//! so a query through the traits compiles to the kernel it names.

use glam::Vec3;

use crate::num::{S, Scalar, Vector};
use crate::ray::{Interval, PreparedRay, Ray};
use crate::simd::{Kernel, per_call};
use crate::surface::SurfacePoint;

/// How a point on a shared edge or corner of a mesh counts.
///
/// Only shapes with edges that meshes share (triangles) read it; planes
/// and boxes ignore it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum EdgeRule {
    /// Closed: a ray through an edge or a corner hits every triangle that
    /// has it. Watertight: a ray crossing a shared edge hits at least one
    /// of the triangles around it. For a closest hit.
    #[default]
    Closed,
    /// One hit per crossing: decided exactly for the ray moved off every
    /// edge line (simulation of simplicity: see [`Triangle`'s
    /// `hit`](crate::Triangle#method.hit)), so where a ray crosses the
    /// surface the triangles form, at an edge or a corner included,
    /// exactly one triangle reports it, and a triangle of exactly zero
    /// area never does. For counting crossings (inside/outside, CSG) and
    /// for every hit along a ray in order ([`Walk`](crate::Walk)). A
    /// point on an open boundary or a lone triangle's edge belongs to a
    /// triangle only about half the time.
    OneHit,
}

/// What a query searches: the range of `t` (in units of the ray's `dir`)
/// and the [`EdgeRule`].
///
/// Built from the value the caller has, never by hand:
///
/// | argument | range | ends | edges |
/// | --- | --- | --- | --- |
/// | `t_max` (a float) | `(0, t_max]` | `t > 0` decided conservatively (a hit a kernel cannot show to be ahead of the origin is dropped: right for a ray spawned off a surface), `t <= t_max` on the computed `t` | closed |
/// | an [`Interval`] `(t_min, t_max]` | `(t_min, t_max]` | both decided exactly against the exact crossing, so consecutive intervals report each crossing once | closed |
/// | `(t_max, rule)` or `(interval, rule)` | as above | as above | `rule` |
///
/// A NaN or negative `t_max` searches nothing: every query answers `None`
/// (or no hit). With `Interval::up_to(t_max)` a query answers as with
/// `t_max` except within its `t` error bound of either end.
///
/// ```
/// use rayhit::{EdgeRule, Intersect, Interval, Ray, Triangle, glam::Vec3};
/// let tri = Triangle::new(Vec3::new(-1.0, -1.0, 0.0), Vec3::new(3.0, -1.0, 0.0), Vec3::new(-1.0, 3.0, 0.0));
/// let ray = Ray::new(Vec3::new(0.0, 0.0, 4.0), Vec3::new(0.0, 0.0, -2.0));
/// let window = Interval::new(1.0, 2.0).unwrap();
/// assert_eq!(tri.hit(&ray, 10.0).unwrap().t, 2.0);
/// assert_eq!(tri.hit(&ray, window).unwrap().t, 2.0);
/// assert_eq!(tri.hit(&ray, (window, EdgeRule::OneHit)).unwrap().t, 2.0);
/// assert!(tri.hit(&ray, 1.5).is_none());
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Search<F = f32> {
    pub(crate) range: Range<F>,
    pub(crate) edges: EdgeRule,
}

/// The range of a [`Search`]: a plain `t_max`, or an interval with exact
/// ends.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Range<F> {
    UpTo(F),
    Within(Interval<F>),
}

impl<F: Scalar> Search<F> {
    /// The edge rule.
    #[inline]
    #[must_use]
    pub fn edge_rule(&self) -> EdgeRule {
        self.edges
    }

    /// The `t_max` of a search built from one (the plain range `(0,
    /// t_max]`); `None` for a search built from an [`Interval`].
    #[inline]
    #[must_use]
    pub fn t_max(&self) -> Option<F> {
        match self.range {
            Range::UpTo(t) => Some(t),
            Range::Within(_) => None,
        }
    }

    /// The [`Interval`] of a search built from one (both ends exact);
    /// `None` for a search built from a `t_max`.
    #[inline]
    #[must_use]
    pub fn interval(&self) -> Option<Interval<F>> {
        match self.range {
            Range::UpTo(_) => None,
            Range::Within(i) => Some(i),
        }
    }
}

impl<F: Scalar> From<F> for Search<F> {
    #[inline(always)]
    fn from(t_max: F) -> Self {
        (t_max, EdgeRule::Closed).into()
    }
}

impl<F: Scalar> From<Interval<F>> for Search<F> {
    #[inline(always)]
    fn from(interval: Interval<F>) -> Self {
        (interval, EdgeRule::Closed).into()
    }
}

impl<F: Scalar> From<(F, EdgeRule)> for Search<F> {
    #[inline(always)]
    fn from((t_max, edges): (F, EdgeRule)) -> Self {
        Self {
            range: Range::UpTo(t_max),
            edges,
        }
    }
}

impl<F: Scalar> From<(Interval<F>, EdgeRule)> for Search<F> {
    #[inline(always)]
    fn from((interval, edges): (Interval<F>, EdgeRule)) -> Self {
        Self {
            range: Range::Within(interval),
            edges,
        }
    }
}

pub(crate) mod sealed {
    use super::*;

    /// A ray as the kernels take it: the plain ray, or its preparation.
    #[derive(Clone, Copy, Debug)]
    pub enum Form<'a, V: Vector> {
        Plain(&'a Ray<V>),
        Prepared(&'a PreparedRay<V>),
    }

    /// The seal of [`RayForm`](super::RayForm), and how the shapes read
    /// a ray of each form.
    pub trait Sealed<V: Vector> {
        /// The ray, plain or prepared (a constant variant per type, so
        /// that a `match` on it folds away).
        fn form(&self) -> Form<'_, V>;
        /// Batch kernel `K` on this ray: on its instruction set where it
        /// carries one, else chosen per call; a plain ray is prepared
        /// first.
        fn batch<K: Kernel<Ray = PreparedRay<V>>>(
            &self,
            shapes: &K::Shapes,
            limit: K::Limit,
        ) -> K::Output;
    }
}
pub(crate) use sealed::Form;

/// The forms of a ray a query takes: a [`Ray`], a [`PreparedRay`] (the
/// per-ray work of the box and triangle tests done once, for many
/// tests), or a prepared ray on the instruction set [`with_simd`]
/// chose ([`SimdRay`]). Every form gives the same answers, bit for bit;
/// they differ in what a call costs. Sealed.
///
/// [`with_simd`]: crate::batch::with_simd
/// [`SimdRay`]: crate::batch::SimdRay
pub trait RayForm<V: Vector = Vec3>: sealed::Sealed<V> {
    /// The ray as an origin and a direction: the ray itself, or the ray a
    /// prepared ray was prepared from (an invalid ray's preparation gives
    /// the invalid ray from `+inf` along `+z`, which every kernel misses).
    #[must_use]
    fn to_ray(&self) -> Ray<V>;
}

impl<V: Vector> sealed::Sealed<V> for Ray<V> {
    #[inline(always)]
    fn form(&self) -> Form<'_, V> {
        Form::Plain(self)
    }

    #[inline(always)]
    fn batch<K: Kernel<Ray = PreparedRay<V>>>(
        &self,
        shapes: &K::Shapes,
        limit: K::Limit,
    ) -> K::Output {
        per_call::<K>(&PreparedRay::new(self), shapes, limit)
    }
}

impl<V: Vector> RayForm<V> for Ray<V> {
    #[inline(always)]
    fn to_ray(&self) -> Ray<V> {
        *self
    }
}

impl<V: Vector> sealed::Sealed<V> for PreparedRay<V> {
    #[inline(always)]
    fn form(&self) -> Form<'_, V> {
        Form::Prepared(self)
    }

    #[inline(always)]
    fn batch<K: Kernel<Ray = PreparedRay<V>>>(
        &self,
        shapes: &K::Shapes,
        limit: K::Limit,
    ) -> K::Output {
        per_call::<K>(self, shapes, limit)
    }
}

impl<V: Vector> RayForm<V> for PreparedRay<V> {
    #[inline(always)]
    fn to_ray(&self) -> Ray<V> {
        self.ray()
    }
}

impl<V: Vector, R: RayForm<V>> sealed::Sealed<V> for &R {
    #[inline(always)]
    fn form(&self) -> Form<'_, V> {
        (**self).form()
    }

    #[inline(always)]
    fn batch<K: Kernel<Ray = PreparedRay<V>>>(
        &self,
        shapes: &K::Shapes,
        limit: K::Limit,
    ) -> K::Output {
        (**self).batch::<K>(shapes, limit)
    }
}

/// A reference to a ray is the ray, so that `&ray` works where `ray` is
/// already a reference.
impl<V: Vector, R: RayForm<V>> RayForm<V> for &R {
    #[inline(always)]
    fn to_ray(&self) -> Ray<V> {
        (**self).to_ray()
    }
}

/// What a ray hits: the closest hit and the any-hit answer over a range,
/// one way for every shape.
///
/// `ray` is any [`RayForm`]; `search` a `t_max`, an [`Interval`], or either
/// with an [`EdgeRule`] (see [`Search`]). The form of the ray changes
/// what a call costs, never its answer. Implemented by [`Triangle`],
/// [`Sphere`], [`Plane`], [`Aabb`] and [`ValidAabb`] (a box as a closed solid, with
/// the face the ray enters through); the guarantees of each are on its
/// implementation. A batch of shapes answers the same questions lane by
/// lane ([`IntersectLanes`]); a BVH node's test is [`Bounds`].
///
/// A new shape implements [`hit`](Intersect::hit) once (and
/// [`occluded`](Intersect::occluded) where the any-hit answer is cheaper
/// than the hit), and every form of ray and search follows.
///
/// [`Triangle`]: crate::Triangle
/// [`Sphere`]: crate::Sphere
/// [`Plane`]: crate::Plane
/// [`Aabb`]: crate::Aabb
/// [`ValidAabb`]: crate::ValidAabb
///
/// ```
/// use rayhit::{Intersect, Interval, Plane, PreparedRay, Ray, Triangle, glam::Vec3};
///
/// /// The nearest hit among `shapes`, of any kind that answers the query.
/// fn nearest<S: Intersect>(shapes: &[S], ray: &PreparedRay) -> Option<(usize, S::Hit)> {
///     let mut best = None;
///     for (i, shape) in shapes.iter().enumerate() {
///         if let Some(hit) = shape.hit(ray, f32::INFINITY) {
///             best = Some((i, hit)); // (keep the nearest: compare t here)
///         }
///     }
///     best
/// }
///
/// let floor = Plane::new(Vec3::ZERO, Vec3::Y);
/// let ray = Ray::new(Vec3::new(0.0, 2.0, 0.0), -Vec3::Y);
/// assert_eq!(floor.hit(&ray, f32::INFINITY), Some(2.0));
/// assert!(floor.occluded(&ray, Interval::new(1.0, 2.0).unwrap()));
/// let tris = [Triangle::new(Vec3::new(-1.0, 1.0, -1.0), Vec3::new(0.0, 1.0, 1.0), Vec3::new(1.0, 1.0, -1.0))];
/// assert_eq!(nearest(&tris, &PreparedRay::new(&ray)).unwrap().1.t, 1.0);
/// ```
pub trait Intersect<V: Vector = Vec3> {
    /// What a hit reports: `t` and what the shape adds to it.
    type Hit: Copy;

    /// The closest hit within `search`, or `None`.
    #[must_use]
    fn hit(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> Option<Self::Hit>;

    /// Whether anything of the shape is hit within `search`: `true`
    /// exactly when [`hit`](Intersect::hit) is `Some`, for shadow rays
    /// (a loop over occluders can stop at the first `true`), and no
    /// slower than `hit`.
    #[inline(always)]
    #[must_use]
    fn occluded(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> bool {
        self.hit(ray, search).is_some()
    }
}

/// Several shapes of one kind against one ray at once, every lane answering
/// [`Intersect`]'s questions: the closest hit of each lane, and whether any
/// lane is hit.
///
/// The answer is every lane's at once, with an empty mask where nothing is
/// hit (not an `Option`): returned as one value it is written once, into
/// the caller's memory, where a value moved out of an `Option` is copied
/// again. `ray` and `search` are as for [`Intersect`]. Implemented by
/// [`TriangleBatch`](crate::batch::TriangleBatch) and
/// [`SphereBatch`](crate::batch::SphereBatch).
///
/// ```
/// use rayhit::{IntersectLanes, PreparedRay, Ray, Triangle, glam::Vec3};
/// use rayhit::batch::TriangleBatch;
/// let tri = Triangle::new(Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0));
/// let batch = TriangleBatch::<Vec3, 8>::from_slice(&[tri, tri.flipped()]).unwrap();
/// let ray = PreparedRay::new(&Ray::new(Vec3::new(0.5, 0.25, 4.0), Vec3::new(0.0, 0.0, -2.0)));
/// let hits = batch.hit(&ray, f32::INFINITY);
/// assert_eq!((hits.mask, hits.front), (0b11, 0b01));
/// assert!(batch.occluded(&ray, f32::INFINITY));
/// ```
pub trait IntersectLanes<V: Vector = Vec3> {
    /// Every lane's answer: which are hit, and each hit.
    type Hits: Copy;

    /// Every lane's closest hit within `search`.
    #[must_use]
    fn hit(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> Self::Hits;

    /// Whether any lane is hit within `search`.
    #[must_use]
    fn occluded(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> bool;
}

/// A surface a ray can leave: the error bound of a hit, and the point it
/// leaves from ([`SurfacePoint`], with what
/// [`spawn`](SurfacePoint::spawn) and [`spawn_to`](SurfacePoint::spawn_to)
/// need to leave it without an epsilon).
///
/// `hit` is a hit this shape returned for the same ray (any form of it).
/// Implemented by [`Triangle`](crate::Triangle), [`Quad`](crate::Quad),
/// [`Sphere`](crate::Sphere), [`Disc`](crate::Disc) and
/// [`Plane`](crate::Plane); a box's point is
/// [`Aabb::surface_point`](crate::Aabb::surface_point), `None` for a ray
/// that starts inside.
///
/// ```
/// use rayhit::{Intersect, Plane, Ray, Surface, glam::Vec3};
/// let floor = Plane::new(Vec3::ZERO, Vec3::Y);
/// let ray = Ray::new(Vec3::new(0.1, 3.0, 0.2), Vec3::new(0.3, -1.0, 0.7));
/// let t = floor.hit(&ray, f32::INFINITY).unwrap();
/// assert!(floor.hit_error(&ray, &t) < 8.0 * f32::EPSILON * t); // a few ulps of t
/// // Bounce up and away: it cannot hit the floor it left.
/// let bounce = floor.surface_point(&ray, &t).spawn(Vec3::new(0.3, 1.0, 0.7));
/// assert!(bounce.origin.y > 0.0);
/// assert_eq!(floor.hit(&bounce, f32::INFINITY), None);
/// ```
pub trait Surface<V: Vector = Vec3>: Intersect<V> {
    /// A bound on the hit's rounding error: on `t`, and on what else the
    /// hit reports.
    type HitError: Copy;

    /// Bounds on the differences between `hit` and the exact crossing of
    /// the ray's line with the shape, computed from the same inputs.
    #[must_use]
    fn hit_error(&self, ray: &impl RayForm<V>, hit: &Self::Hit) -> Self::HitError;

    /// The hit point with a per-component bound on its distance from the
    /// exact surface, and the surface's normal with its error bound.
    #[must_use]
    fn surface_point(&self, ray: &impl RayForm<V>, hit: &Self::Hit) -> SurfacePoint<V>;
}

/// A BVH node's test: the part of the search's range the ray may spend
/// inside a box, never missing a box exact arithmetic says the ray meets
/// there (conservative), so that a traversal never loses a ray before
/// the leaves.
///
/// `ray` is any [`RayForm`] and `search` a `t_max` or an [`Interval`] (see
/// [`Search`]; the edge rule is ignored). Implemented by
/// [`Aabb`](crate::Aabb) and [`ValidAabb`](crate::ValidAabb)
/// (`Option<(enter, exit)>`, or a `bool` from [`meets`](Bounds::meets)),
/// and by [`AabbBatch`](crate::batch::AabbBatch) and
/// [`QuantizedChildren`](crate::batch::QuantizedChildren) (a mask of the
/// children hit and their entries, or the mask alone).
///
/// ```
/// use rayhit::{Aabb, Bounds, PreparedRay, Ray, glam::Vec3};
/// let node = Aabb::new(Vec3::ZERO, Vec3::ONE);
/// let ray = PreparedRay::new(&Ray::new(Vec3::new(-1.0, 0.5, 0.5), Vec3::X));
/// let (enter, exit) = node.clip(&ray, f32::INFINITY).unwrap();
/// assert!(enter == 1.0 && exit >= 2.0);
/// assert!(node.clip(&ray, 0.5).is_none());
/// assert!(node.meets(&ray, 1.0) && !node.meets(&ray, 0.5));
/// ```
pub trait Bounds<V: Vector = Vec3> {
    /// The answer: `Option<(enter, exit)>` for one box, the hit lanes for
    /// several.
    type Clip;
    /// Whether the ray meets it: `bool` for one box, a mask of the lanes
    /// (lane `i` is bit `i`) for several.
    type Meets: Copy;

    /// The conservative test over `search`.
    #[must_use]
    fn clip(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> Self::Clip;

    /// [`clip`](Bounds::clip)'s hit or miss alone, bit for bit, for a
    /// traversal that needs no entry distance (an any-hit query, or a
    /// wide BVH visiting children in a fixed order). It computes only
    /// that: for the batches, an answer in a register where the entries
    /// would go through memory.
    #[must_use]
    fn meets(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> Self::Meets;
}
