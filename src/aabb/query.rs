//! The queries of a box ([`Bounds`], the node test; [`Intersect`], the box
//! as a solid with its entry face; its surface point) and of a box batch
//! ([`Bounds`]): each combination of ray form and range, sent to its
//! kernel.

use super::batch::{AabbBatch, AabbBatchHits, AabbBatchKernel, FromZero, MaskOf};
use super::face::{
    BoxHit, ray_aabb_face, ray_aabb_face_in, ray_aabb_prepared_face, ray_aabb_prepared_face_in,
};
#[cfg(doc)]
use super::slab::ray_aabb;
use super::slab::{ray_aabb_in, ray_aabb_prepared, ray_aabb_prepared_in, ray_slab_box};
use super::{Aabb, SlabBox, ValidAabb, slab_ends};
use crate::num::{S, Scalar, Vector};
use crate::query::{Bounds, Form, Intersect, Range, RayForm, Search};
use crate::ray::{PreparedRay, t_max_ok};
use crate::simd::Kernel;
use crate::surface::SurfacePoint;

/// The slab test of any box the slab tests take, with every form of ray
/// and range.
#[inline(always)]
fn clip<V: Vector>(
    aabb: &impl SlabBox<V>,
    ray: &impl RayForm<V>,
    search: Search<S<V>>,
) -> Option<(S<V>, S<V>)> {
    match (search.range, ray.form()) {
        (Range::UpTo(t_max), Form::Plain(r)) => ray_slab_box(r, aabb, t_max),
        (Range::UpTo(t_max), Form::Prepared(p)) => ray_aabb_prepared(p, aabb, t_max),
        (Range::Within(i), Form::Plain(r)) => ray_aabb_in(r, aabb, i),
        (Range::Within(i), Form::Prepared(p)) => ray_aabb_prepared_in(p, aabb, i),
    }
}

/// The box with its entry face, with every form of ray and range.
#[inline(always)]
fn entry<V: Vector>(
    aabb: &Aabb<V>,
    ray: &impl RayForm<V>,
    search: Search<S<V>>,
) -> Option<BoxHit<S<V>>> {
    match (search.range, ray.form()) {
        (Range::UpTo(t_max), Form::Plain(r)) => ray_aabb_face(r, aabb, t_max),
        (Range::UpTo(t_max), Form::Prepared(p)) => ray_aabb_prepared_face(p, aabb, t_max),
        (Range::Within(i), Form::Plain(r)) => ray_aabb_face_in(r, aabb, i),
        (Range::Within(i), Form::Prepared(p)) => ray_aabb_prepared_face_in(p, aabb, i),
    }
}

/// The slab test, conservative: a BVH node's test.
impl<V: Vector> Bounds<V> for Aabb<V> {
    /// `Some((enter, exit))`: the part of the range the ray spends inside
    /// the closed box, up to rounding (never less than the exact part).
    type Clip = Option<(S<V>, S<V>)>;
    /// Whether the ray meets the box within the range.
    type Meets = bool;

    /// The slab test over `search`: with a `t_max`, [`ray_aabb`]'s
    /// answer and guarantees, bit for bit, on every ray form (no false
    /// miss against exact arithmetic on the same inputs; false hits only
    /// within a few ulps of an edge or corner; `0 <= enter <= exit <=
    /// t_max`, `exit` at least the exact exit).
    ///
    /// With an [`Interval`](crate::Interval) `(t_min, t_max]`: the part of
    /// the interval the ray spends inside the closed box, `t_min <= enter
    /// <= exit <= t_max`, by the same test with the entries folded against
    /// `t_min`. **No false miss**: where exact arithmetic says the closed
    /// box meets the ray anywhere in `[t_min, t_max]` (so whenever the
    /// exact segment inside the box meets `(t_min, t_max]`) it is
    /// reported, and `exit` is at least the exact exit (clipped to
    /// `t_max`); the ends are floats compared with the computed distances,
    /// never rounded (the proof is in `aabb/slab.rs`). False hits only at
    /// the boundary, as for a `t_max`: a box the ray leaves exactly at
    /// `t_min` is reported (the entry face, [`Intersect::hit`], is decided
    /// exactly). With `(0, t_max]` the answer is the `t_max` one, bit for
    /// bit.
    ///
    /// The preconditions of [`ray_aabb`] apply (no difference `min - o`,
    /// `max - o` overflows; exact entry and exit below `MAX / 2`).
    /// Invalid rays and boxes, and a NaN or negative `t_max`, give `None`.
    ///
    /// ```
    /// use rayhit::{Aabb, Bounds, Interval, PreparedRay, Ray, ValidAabb, glam::Vec3};
    /// let unit = Aabb::new(Vec3::ZERO, Vec3::ONE);
    /// // x = -1 + 2t is in [0, 1] for t in [0.5, 1].
    /// let ray = Ray::new(Vec3::new(-1.0, 0.5, 0.5), Vec3::new(2.0, 0.0, 0.0));
    /// let window = |lo: f32, hi: f32| Interval::new(lo, hi).unwrap();
    /// let (enter, exit) = unit.clip(&ray, window(0.75, 4.0)).unwrap();
    /// assert_eq!(enter, 0.75); // already inside at t_min
    /// assert!(exit >= 1.0 && exit <= 1.0 + 8.0 * f32::EPSILON); // widened
    /// assert_eq!(unit.clip(&ray, window(2.0, 4.0)), None); // left before t_min
    /// assert_eq!(unit.clip(&ray, window(0.0, 0.25)), None); // not yet entered
    /// // A node box checked once, and a prepared ray: the same answers.
    /// let node = ValidAabb::new(unit).unwrap();
    /// let prepared = PreparedRay::new(&ray);
    /// assert_eq!(node.clip(&prepared, window(0.75, 4.0)), Some((enter, exit)));
    /// ```
    #[inline(always)]
    fn clip(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> Self::Clip {
        clip(self, ray, search.into())
    }

    /// [`clip`](Bounds::clip)`.is_some()`.
    #[inline(always)]
    fn meets(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> bool {
        clip(self, ray, search.into()).is_some()
    }
}

/// As for [`Aabb`], bit for bit, without checking the box on every call.
impl<V: Vector> Bounds<V> for ValidAabb<V> {
    /// As for [`Aabb`].
    type Clip = Option<(S<V>, S<V>)>;
    /// As for [`Aabb`].
    type Meets = bool;

    /// [`Aabb`]'s [`clip`](Bounds::clip), bit for bit.
    #[inline(always)]
    fn clip(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> Self::Clip {
        clip(self, ray, search.into())
    }

    /// [`clip`](Bounds::clip)`.is_some()`.
    #[inline(always)]
    fn meets(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> bool {
        clip(self, ray, search.into()).is_some()
    }
}

/// The box as a closed solid a ray can see: the slab test's interval and
/// the face the ray enters through, decided exactly.
impl<V: Vector> Intersect<V> for Aabb<V> {
    type Hit = BoxHit<S<V>>;

    /// The slab test's interval ([`Bounds::clip`], bit for bit, and the
    /// same `None`) with the face the ray enters through.
    ///
    /// The face is decided in exact arithmetic on the same inputs: a face
    /// whose plane the exact ray crosses at the exact entry distance `E*`;
    /// where several do (through an edge or a corner), the one on the
    /// lowest axis (x, then y, then z). Where `E* <= 0` (the ray starts
    /// inside the box or on its boundary) there is no entry face. Where
    /// the conservative test reports a box that the exact ray misses by a
    /// few ulps, the face is still the entry plane the exact ray crosses
    /// last.
    ///
    /// With an [`Interval`](crate::Interval) `(t_min, t_max]`, the face is
    /// reported only when `t_min < E* <= t_max`, decided exactly (the
    /// crossing of one face plane, placed against both ends as a plane's
    /// crossing is); otherwise it is `None` (the ray entered at or before
    /// `t_min`). So over consecutive intervals a box's entry is reported
    /// once: the face appears in exactly one interval, the one holding
    /// `E*`.
    ///
    /// Cost: the slab test, then the axes' entry distances compared; where
    /// two are within about four ulps of each other the comparison is
    /// redone exactly, from error-free products. Use
    /// [`clip`](Bounds::clip) when only the interval is wanted (and for the
    /// any-hit answer, which is the same). Precondition of the exact face,
    /// for `f64` only: on each axis the origin coordinate and the box's
    /// are each zero or within a factor `2^300` of each other, and the
    /// nonzero direction components within `2^300` of each other.
    ///
    /// ```
    /// use rayhit::{Aabb, BoxFace, Intersect, Interval, Ray, glam::Vec3};
    /// let unit = Aabb::new(Vec3::ZERO, Vec3::ONE);
    /// // From the left, enters through x = 0 at exactly t = 1.
    /// let ray = Ray::new(Vec3::new(-1.0, 0.5, 0.5), Vec3::X);
    /// let hit = unit.hit(&ray, f32::INFINITY).unwrap();
    /// assert_eq!((hit.enter, hit.face), (1.0, Some(BoxFace::MinX)));
    /// assert_eq!(BoxFace::MinX.normal::<Vec3>(), -Vec3::X);
    /// // Through the edge x = 0, y = 1: both planes at t = 1; x is chosen.
    /// let edge = Ray::new(Vec3::new(-1.0, 2.0, 0.5), Vec3::new(1.0, -1.0, 0.0));
    /// assert_eq!(unit.hit(&edge, f32::INFINITY).unwrap().face, Some(BoxFace::MinX));
    /// // From inside: no entry face.
    /// let inside = Ray::new(Vec3::splat(0.5), Vec3::Y);
    /// assert_eq!(unit.hit(&inside, f32::INFINITY).unwrap().face, None);
    /// // The next window starts at the entry: the box is there, its entry is not.
    /// let window = |lo: f32, hi: f32| Interval::new(lo, hi).unwrap();
    /// assert_eq!(unit.hit(&ray, window(0.0, 1.0)).unwrap().face, Some(BoxFace::MinX));
    /// assert_eq!(unit.hit(&ray, window(1.0, 1.5)).unwrap().face, None);
    /// ```
    #[inline]
    fn hit(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> Option<Self::Hit> {
        entry(self, ray, search.into())
    }

    /// [`clip`](Bounds::clip)`.is_some()`: no face is decided.
    #[inline(always)]
    fn occluded(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> bool {
        clip(self, ray, search.into()).is_some()
    }
}

/// As for [`Aabb`], bit for bit.
impl<V: Vector> Intersect<V> for ValidAabb<V> {
    type Hit = BoxHit<S<V>>;

    /// [`Aabb`]'s [`hit`](Intersect::hit), bit for bit.
    #[inline]
    fn hit(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> Option<Self::Hit> {
        entry(self.aabb(), ray, search.into())
    }

    /// [`clip`](Bounds::clip)`.is_some()`.
    #[inline(always)]
    fn occluded(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> bool {
        clip(self, ray, search.into()).is_some()
    }
}

impl<V: Vector> Aabb<V> {
    /// The point where the ray enters the box through the face of `hit`
    /// (from this box's [`hit`](Intersect::hit) for the same ray), with the
    /// face's exact outward normal; `None` when the hit has no entry face
    /// (the ray starts inside the box, or entered before an interval's
    /// lower end).
    ///
    /// The point is `ray.at(hit.enter)` with its coordinate on the face's
    /// axis replaced by the face's plane, so it lies exactly on that plane
    /// (its other coordinates carry the rounding of `origin + enter dir`,
    /// and near an edge can be a rounding outside the face). The bounds are
    /// those of an exact point on an exact plane, so
    /// [`spawn`](SurfacePoint::spawn) moves a new ray's origin one ulp off
    /// the plane, to the side its direction points into.
    ///
    /// ```
    /// use rayhit::{Aabb, Bounds, Intersect, Ray, Surface, glam::Vec3};
    /// let unit = Aabb::new(Vec3::ZERO, Vec3::ONE);
    /// let ray = Ray::new(Vec3::new(0.3, 3.0, 0.6), Vec3::new(0.1, -1.0, 0.2));
    /// let hit = unit.hit(&ray, f32::INFINITY).unwrap();
    /// let surface = unit.surface_point(&ray, &hit).unwrap();
    /// assert_eq!((surface.point.y, surface.normal), (1.0, Vec3::Y));
    /// // A bounce off the top face does not touch the box again.
    /// let bounce = surface.spawn(Vec3::new(0.1, 1.0, 0.2));
    /// assert!(bounce.origin.y > 1.0);
    /// assert_eq!(unit.clip(&bounce, f32::INFINITY), None);
    /// ```
    #[must_use]
    pub fn surface_point(
        &self,
        ray: &impl RayForm<V>,
        hit: &BoxHit<S<V>>,
    ) -> Option<SurfacePoint<V>> {
        let face = hit.face?;
        let k = face.axis();
        let p = ray.to_ray().at(hit.enter);
        let on = |i: usize| if i == k { face.plane(self) } else { p[i] };
        // The point is exactly on the plane: an error of the smallest
        // subnormal on the axis (a bound, and not zero, so that the offset
        // is not zero either) and none elsewhere, which the exact normal
        // ignores.
        let error = |i: usize| if i == k { S::<V>::TINY } else { S::<V>::ZERO };
        Some(SurfacePoint {
            point: V::new(on(0), on(1), on(2)),
            point_error: V::new(error(0), error(1), error(2)),
            normal: face.normal(),
            normal_error: V::ZERO,
        })
    }
}

/// The slab test on every lane of a batch: each lane's answer is, bit for
/// bit, what [`Aabb`]'s [`clip`](Bounds::clip) returns for that lane's box
/// (hit or miss, and the entry `t`), so its guarantees hold per lane.
impl<V: Vector, const N: usize> Bounds<V> for AabbBatch<V, N> {
    /// The lanes hit, and each one's entry.
    type Clip = AabbBatchHits<S<V>, N>;
    /// The lanes hit.
    type Meets = u32;

    /// The slab test on every lane, eight at a time in SIMD registers
    /// (SSE2 by default; AVX2 or AVX-512 where the build or the CPU has
    /// it, chosen per call on x86-64 with `std`; NEON on aarch64; a prepared ray on an
    /// instruction set, [`SimdRay`](crate::batch::SimdRay), skips the
    /// per-call choice). A plain ray is prepared first. Empty lanes are
    /// never hit. With an [`Interval`](crate::Interval), children that the
    /// ray leaves before `t_min` are culled, and `t_min <= enter <= t_max`.
    ///
    /// ```
    /// use rayhit::{Aabb, Bounds, Interval, PreparedRay, Ray, glam::Vec3};
    /// use rayhit::batch::AabbBatch;
    /// let boxes: Vec<Aabb> = (0..4)
    ///     .map(|i| {
    ///         let z = 2.0 * i as f32;
    ///         Aabb::new(Vec3::new(-1.0, -1.0, z), Vec3::new(1.0, 1.0, z + 1.0))
    ///     })
    ///     .collect();
    /// let batch = AabbBatch::<Vec3, 4>::from_slice(&boxes).unwrap();
    /// let ray = PreparedRay::new(&Ray::new(Vec3::new(0.0, 0.0, -1.0), Vec3::Z));
    /// let hits = batch.clip(&ray, f32::INFINITY);
    /// assert_eq!(hits.mask, 0b1111);
    /// assert_eq!(hits.get(1), boxes[1].clip(&ray, f32::INFINITY).map(|(enter, _)| enter));
    /// // Past t = 3.5 (z = 2.5): box 1 (z in [2, 3]) is still being crossed,
    /// // box 0 is behind.
    /// let later = batch.clip(&ray, Interval::new(3.5, f32::INFINITY).unwrap());
    /// assert_eq!(later.mask, 0b1110);
    /// assert_eq!(later.enter[1], 3.5);
    /// ```
    #[inline(always)]
    fn clip(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> Self::Clip {
        batch_query::<V, AabbBatchKernel<V, N>>(ray, self, search.into(), AabbBatchHits::none())
    }

    /// [`clip`](Bounds::clip)`.mask`, returned in a register: the test a
    /// plain call should use where the entries go unused.
    ///
    /// ```
    /// use rayhit::{Aabb, Bounds, PreparedRay, Ray, glam::Vec3};
    /// use rayhit::batch::AabbBatch;
    /// let boxes = [Aabb::new(Vec3::ZERO, Vec3::ONE), Aabb::new(Vec3::splat(2.0), Vec3::splat(3.0))];
    /// let batch = AabbBatch::<Vec3, 8>::from_slice(&boxes).unwrap();
    /// let ray = PreparedRay::new(&Ray::new(Vec3::splat(-1.0), Vec3::ONE));
    /// assert_eq!(batch.meets(&ray, f32::INFINITY), 0b11);
    /// assert_eq!(batch.meets(&ray, 2.0), 0b01); // box 1 starts at t = 3
    /// ```
    #[inline(always)]
    fn meets(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> u32 {
        batch_query::<V, MaskOf<AabbBatchKernel<V, N>>>(ray, self, search.into(), 0)
    }
}

/// Batch kernel `K` (over `(t_min, t_max)`) on `ray` over `search`: for a
/// plain `t_max`, its copy with `t_min` the constant zero, or `none` for a
/// NaN or negative `t_max` (answered here, inline at the call, so that the
/// kernels need not check); for an interval (whose ends were checked when
/// it was made), over its ends as the slab test takes them (see
/// [`slab_ends`]).
#[inline(always)]
pub(crate) fn batch_query<V: Vector, K: Kernel<Ray = PreparedRay<V>, Limit = (S<V>, S<V>)>>(
    ray: &impl RayForm<V>,
    shapes: &K::Shapes,
    search: Search<S<V>>,
    none: K::Output,
) -> K::Output {
    match search.range {
        Range::UpTo(t_max) if !t_max_ok(t_max) => none,
        Range::UpTo(t_max) => ray.batch::<FromZero<K>>(shapes, (S::<V>::ZERO, t_max)),
        Range::Within(i) => ray.batch::<K>(shapes, slab_ends(i)),
    }
}
