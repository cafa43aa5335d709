//! The queries of a triangle ([`Intersect`], [`Surface`]) and of a
//! triangle batch ([`Intersect`]): each combination of ray form, range and
//! edge rule, sent to its kernel.

use super::batch::{TriangleBatchKernel, one_hit_lanes};
use super::batch_interval::TriangleBatchInKernel;
use super::bounds::{ray_triangle_error_bounds, triangle_hit_point};
use super::interval::{ray_triangle_in, ray_triangle_one_hit_in, ray_triangle_prepared_in};
use super::watertight::{ray_triangle, ray_triangle_one_hit, ray_triangle_prepared};
use super::{Triangle, TriangleBatch, TriangleBatchHits, TriangleHit, TriangleHitError};
use crate::num::{S, Vector};
use crate::query::{EdgeRule, Form, Intersect, IntersectLanes, Range, RayForm, Search, Surface};
use crate::surface::SurfacePoint;

/// The watertight ray/triangle test, two-sided: `t` in units of the ray's
/// `dir`, barycentrics as in [`TriangleHit`].
impl<V: Vector> Intersect<V> for Triangle<V> {
    type Hit = TriangleHit<S<V>>;

    /// The closest crossing of the ray with the triangle within `search`.
    ///
    /// **With a `t_max`** (`0 < t <= t_max`): [`ray_triangle`]'s test and
    /// guarantees, bit for bit, on every ray form: watertight (no ray
    /// passes between two triangles that share an edge), `t > 0` decided
    /// conservatively (a ray spawned off the triangle does not hit it
    /// again), `t` within [`hit_error`](Surface::hit_error) of the exact
    /// crossing.
    ///
    /// **With an [`Interval`](crate::Interval)** `(t_min, t_max]`: the
    /// same inside test, and the range decided exactly: a hit where the
    /// ray's line crosses the closed triangle at an exact distance `t*`
    /// with `t_min < t* <= t_max` (`t*` computed exactly from the input
    /// floats). The reported `t` is the plain test's quotient, within its
    /// error bound of `t*`, brought into the interval where rounding put
    /// it outside: to `t_max` (only towards `t*`) or to the float just
    /// above `t_min` (within the larger of the bound and one ulp of
    /// `t_min`); `u`, `v` and the side are the plain test's. So
    /// consecutive intervals `(t0, t1]`, `(t1, t2]`, ... report each
    /// crossed triangle in exactly one of them: a walk that continues past
    /// a hit never skips a crossing and never reports one twice. To walk
    /// every hit in order, take the nearest hit of `(t_lo, t_max]`, set
    /// `t_hi` to its `t` plus its error bound (rounded up), report every
    /// hit of `(t_lo, t_hi]` sorted by `t`, and continue from `t_lo =
    /// t_hi`. Where the crossing is not defined (`dir . n` exactly zero: a
    /// zero-area triangle, or a ray exactly parallel that rounding shows a
    /// sliver), the reported `t` itself is compared exactly. With `(0,
    /// t_max]` the answer is the plain one wherever `t*` is farther than
    /// its error bound from both ends. Cost: about the plain test's; the
    /// exact signs (a few hundred operations) only within the error bound
    /// of an end. The decision is exact for every `f32` input; for `f64`
    /// while the nonzero coordinate differences (origin to corners, corner
    /// to corner, and their rounding errors) are within `2^250` of the
    /// largest and the direction's nonzero components within `2^250` of
    /// its largest.
    ///
    /// # One hit per crossing
    ///
    /// **With [`EdgeRule::OneHit`]**, the inside test is decided in exact
    /// arithmetic for the ray moved by an infinitesimal `(eps1, eps2)`,
    /// `0 < eps2 << eps1`, across itself (along the two axes after the
    /// direction's largest component; simulation of simplicity,
    /// Edelsbrunner and Mucke, 1990). The moved ray lies on no edge line,
    /// and every triangle answers for the same moved ray exactly, so each
    /// point where it crosses the surface the triangles form is reported
    /// by exactly one triangle: a ray through an edge or a vertex of a
    /// mesh is reported once per crossing (twice, front and back at one
    /// `t*`, where it only touches the mesh there). This holds for any
    /// triangles: shared edges need not be stored identically, a
    /// T-junction whose vertex lies exactly on the long edge closes
    /// without a filler, and a triangle of exactly zero area (a filler) is
    /// never hit. Where a T-junction's vertex is off the edge (rounded),
    /// the surface folds there, and a ray through the fold crosses three
    /// sheets (front, back, front): each is reported, and the signed
    /// count (front minus back) is the crossing count. Over an
    /// [`Interval`](crate::Interval) this is exact at the ends too, so the
    /// crossings of consecutive intervals are the surface's crossings, each
    /// once: the walk for transparency and volumes
    /// ([`Walk`](crate::Walk)). With a `t_max` the ends are as for the
    /// closed rule. What it gives up: a point on an open boundary or a
    /// lone triangle's edge belongs to a triangle only if the moved ray is
    /// inside it (about half the time). Cost: over an interval, the
    /// closed test's arithmetic plus a check that the computed edge
    /// functions' signs are surely exact (about 1.3 to 1.6 times the
    /// closed rule on the same ray form), and, where one is within its
    /// rounding error of zero, a few hundred operations for the exact
    /// signs; with a `t_max`, the reference definition, one component at
    /// a time. The decision is exact for every `f32` input, and for `f64`
    /// under the same conditions as the interval's ends.
    ///
    /// # Invalid input
    ///
    /// Invalid rays, triangles with a NaN or infinite coordinate, a NaN or
    /// negative `t_max` and triangles of zero area in the ray's sheared
    /// frame (after rounding) give `None`; never a panic, never a NaN. A
    /// triangle of exactly zero area can still be hit where rounding
    /// leaves it a sliver (see [`Triangle`]). Precondition: coordinates
    /// relative to the ray origin small enough that the edge functions do
    /// not overflow (`|coordinate| < 2^63` in `f32`, `2^511` in `f64`).
    ///
    /// ```
    /// use rayhit::{EdgeRule, Intersect, Interval, PreparedRay, Ray, Side, Triangle, glam::Vec3};
    /// let tri = Triangle::new(Vec3::ZERO, Vec3::new(2.0, 0.0, 0.0), Vec3::new(0.0, 2.0, 0.0));
    /// let ray = Ray::new(Vec3::new(0.5, 0.25, 4.0), Vec3::new(0.0, 0.0, -2.0));
    /// let hit = tri.hit(&ray, f32::INFINITY).unwrap();
    /// assert_eq!((hit.t, hit.u, hit.v, hit.side), (2.0, 0.25, 0.125, Side::Front));
    /// // A prepared ray: the same answer, bit for bit.
    /// assert_eq!(tri.hit(&PreparedRay::new(&ray), f32::INFINITY), Some(hit));
    /// // Over intervals: open below, closed above.
    /// let window = |lo: f32, hi: f32| Interval::new(lo, hi).unwrap();
    /// assert!(tri.hit(&ray, window(1.0, 2.0)).is_some());
    /// assert!(tri.hit(&ray, window(2.0, 3.0)).is_none());
    ///
    /// // Two triangles of the unit square, sharing the diagonal from (1,0) to (0,1),
    /// // and a ray straight down through the middle of that diagonal.
    /// let (p00, p10, p01, p11) = (Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 0.0));
    /// let mesh = [Triangle::new(p00, p10, p01), Triangle::new(p10, p11, p01)];
    /// let down = Ray::new(Vec3::new(0.5, 0.5, 1.0), -Vec3::Z);
    /// let count = |rule| mesh.iter().filter(|t| t.hit(&down, (10.0, rule)).is_some()).count();
    /// assert_eq!(count(EdgeRule::Closed), 2);
    /// assert_eq!(count(EdgeRule::OneHit), 1);
    /// ```
    #[inline(always)]
    fn hit(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> Option<Self::Hit> {
        let search = search.into();
        match (search.edges, search.range, ray.form()) {
            (EdgeRule::Closed, Range::UpTo(t_max), Form::Plain(r)) => ray_triangle(r, self, t_max),
            (EdgeRule::Closed, Range::UpTo(t_max), Form::Prepared(p)) => {
                ray_triangle_prepared(p, self, t_max)
            }
            (EdgeRule::Closed, Range::Within(i), Form::Plain(r)) => ray_triangle_in(r, self, i),
            (EdgeRule::Closed, Range::Within(i), Form::Prepared(p)) => {
                ray_triangle_prepared_in(p, self, i, EdgeRule::Closed)
            }
            (EdgeRule::OneHit, Range::UpTo(t_max), _) => {
                ray_triangle_one_hit(&ray.to_ray(), self, t_max)
            }
            (EdgeRule::OneHit, Range::Within(i), Form::Plain(r)) => {
                ray_triangle_one_hit_in(r, self, i)
            }
            (EdgeRule::OneHit, Range::Within(i), Form::Prepared(p)) => {
                ray_triangle_prepared_in(p, self, i, EdgeRule::OneHit)
            }
        }
    }
}

impl<V: Vector> Surface<V> for Triangle<V> {
    type HitError = TriangleHitError<S<V>>;

    /// Bounds on the errors of a hit's `t`, `u` and `v`, against the
    /// crossing of the ray's line with the triangle's plane computed
    /// exactly from the same inputs.
    ///
    /// The derivation is in the source, step by step: the rounding of the
    /// sheared coordinates and edge functions (as in pbrt-v4), then the
    /// sensitivity of `t = sum e_i z_i / sum e_i` and of `e_i / sum e_i` to
    /// them. The `t` bound grows with the spread of the corners' distances
    /// along the ray, not with the distance itself, so it stays within a
    /// few ulps of `t` for a triangle facing the ray, however far away.
    ///
    /// For a hit over an [`Interval`](crate::Interval) `(lo, hi]`, whose
    /// computed `t` is moved into the interval where it fell outside (the
    /// exact crossing being inside), the reported `t` is within `max(t
    /// bound, succ(lo) - lo)` of the exact crossing: the move is towards
    /// it, except that a crossing within one ulp above `lo` is reported at
    /// `lo`'s successor. With the one-hit rule, a computed edge function
    /// whose sign is not the exact one counts as zero, here as in the hit
    /// itself. A [`Walk`](crate::Walk) takes this bound for its windows;
    /// an infinite bound there gives the rest of the range as one window.
    ///
    /// Where the exact determinant's sign is not known, the bounds are
    /// infinite (the ray is within rounding of parallel to the triangle,
    /// or the triangle is so thin, seen from the ray, that rounding its
    /// corners could flip it: a sliver far away), with one exception: for
    /// a triangle of zero area (corners exactly collinear) the test takes
    /// `t` from the point of the longest edge (in the ray's frame) nearest
    /// the ray, and the `t` bound is finite, a bound on the distance from
    /// where the ray passes the segment (`u` and `v` are then only known
    /// to be in `[0, 1]`, and their bounds are infinite). Every bound is
    /// infinite for invalid input.
    ///
    /// ```
    /// use rayhit::{Intersect, Ray, Surface, Triangle, glam::Vec3};
    /// let cz = 3.1f32;
    /// let tri = Triangle::new(Vec3::new(0.0, 0.0, 3.0), Vec3::new(1.0, 0.0, 3.0), Vec3::new(0.0, 1.0, cz));
    /// let (dy, dz) = (0.2f32, 1.0f32);
    /// let ray = Ray::new(Vec3::ZERO, Vec3::new(0.1, dy, dz));
    /// let hit = tri.hit(&ray, f32::INFINITY).unwrap();
    /// let err = tri.hit_error(&ray, &hit);
    /// // The plane is z - 3 = (cz - 3) y, so t = 3 / (dz - (cz - 3) dy); f64
    /// // evaluates that far more accurately than the f32 bound.
    /// let exact = 3.0 / (f64::from(dz) - (f64::from(cz) - 3.0) * f64::from(dy));
    /// assert!((f64::from(hit.t) - exact).abs() <= f64::from(err.t));
    /// assert!(err.t < 1e-5 * hit.t);
    /// ```
    #[inline]
    fn hit_error(&self, ray: &impl RayForm<V>, hit: &Self::Hit) -> Self::HitError {
        ray_triangle_error_bounds(&ray.to_ray(), self, hit)
    }

    /// The hit point from the barycentrics, `a + u (b - a) + v (c - a)`,
    /// with the geometric normal [`Triangle::normal`] and
    /// [`Triangle::normal_error`]. The ray is not read.
    ///
    /// The point's bound is on its distance from a point of the exact
    /// plane (for any reals `u`, `v`, `a + u (b - a) + v (c - a)` lies
    /// exactly in it): the edges (one rounding each), the products and the
    /// two sums, at most `gamma(5) (|a_j| + |u e1_j| + |v e2_j|)` with the
    /// computed edges, plus four roundings to evaluate that. This is the
    /// error that matters for leaving the surface; where on the triangle
    /// the point lies is the barycentrics' business
    /// ([`hit_error`](Surface::hit_error)).
    ///
    /// ```
    /// use rayhit::{Intersect, Ray, Surface, Triangle, glam::Vec3};
    /// let tri = Triangle::new(Vec3::ZERO, Vec3::new(4.0, 0.0, 0.0), Vec3::new(0.0, 4.0, 0.0));
    /// let ray = Ray::new(Vec3::new(1.0, 2.0, 5.0), -Vec3::Z);
    /// let hit = tri.hit(&ray, f32::INFINITY).unwrap();
    /// let here = tri.surface_point(&ray, &hit);
    /// assert_eq!(here.point, Vec3::new(1.0, 2.0, 0.0));
    /// assert!(here.point_error.z == 0.0 && here.point_error.x < 1e-5);
    /// // A shadow ray towards a light above cannot hit the triangle it left.
    /// let shadow = here.spawn(Vec3::new(0.3, 0.2, 1.0));
    /// assert!(tri.hit(&shadow, f32::INFINITY).is_none());
    /// ```
    #[inline]
    fn surface_point(&self, _ray: &impl RayForm<V>, hit: &Self::Hit) -> SurfacePoint<V> {
        self.surface_point_at(hit.u, hit.v)
    }
}

impl<V: Vector> Triangle<V> {
    /// The surface point at barycentrics `(u, v)`: the point `a + u (b -
    /// a) + v (c - a)` with its bound, and the normal with its bound, as
    /// [`surface_point`](Surface::surface_point) gives them for a hit
    /// there. For points that come from no ray: samples on an area light,
    /// the ends of a shadow segment ([`SurfacePoint::spawn_to`]). The bound
    /// holds for any `u` and `v`.
    ///
    /// ```
    /// use rayhit::{Triangle, glam::Vec3};
    /// let light = Triangle::new(Vec3::new(0.0, 3.0, 0.0), Vec3::new(0.0, 3.0, 2.0), Vec3::new(2.0, 3.0, 0.0));
    /// let sample = light.surface_point_at(0.25, 0.5);
    /// assert_eq!(sample.point, Vec3::new(1.0, 3.0, 0.5));
    /// assert_eq!(sample.normal, light.normal());
    /// ```
    #[inline]
    #[must_use]
    pub fn surface_point_at(&self, u: S<V>, v: S<V>) -> SurfacePoint<V> {
        let (point, point_error) = triangle_hit_point(self, u, v);
        SurfacePoint {
            point,
            point_error,
            normal: self.normal(),
            normal_error: self.normal_error(),
        }
    }
}

/// The watertight test on every lane of a batch: each lane's answer is,
/// bit for bit, what [`Triangle`]'s [`hit`](Intersect::hit) returns for
/// that lane's triangle, so its guarantees hold per lane.
impl<V: Vector, const N: usize> IntersectLanes<V> for TriangleBatch<V, N> {
    /// Every lane's hit (see [`TriangleBatchHits`]; its
    /// [`nearest`](TriangleBatchHits::nearest) is the closest).
    type Hits = TriangleBatchHits<S<V>, N>;

    /// The hits of every lane within `search` (`mask` is zero when no
    /// lane is hit).
    ///
    /// With the closed edge rule, eight lanes at a time in SIMD registers
    /// (SSE2 by default; AVX2 or AVX-512 where the build or the CPU has
    /// it, chosen per call on x86-64 with `std`; NEON on aarch64): every lane runs the
    /// scalar test's arithmetic, in the same order, on its own triangle,
    /// and the rare lanes (an edge function that rounds to exactly zero, a
    /// crossing near an end of the range or an edge) run the scalar code
    /// itself. A prepared ray on an instruction set
    /// ([`SimdRay`](crate::batch::SimdRay)) skips the per-call choice; a
    /// plain ray is prepared first (prepare once when one ray meets many
    /// batches). With [`EdgeRule::OneHit`], each lane runs the scalar
    /// test. Empty lanes give no hit.
    ///
    /// ```
    /// use rayhit::{Intersect, IntersectLanes, Interval, PreparedRay, Ray, Triangle, glam::Vec3};
    /// use rayhit::batch::TriangleBatch;
    /// // Four layers along z, at z = 1, 2, 3, 4, crossed at t = 1, 2, 3, 4.
    /// let tris: Vec<Triangle> = (1..=4)
    ///     .map(|k| {
    ///         let z = k as f32;
    ///         Triangle::new(Vec3::new(0.0, 0.0, z), Vec3::new(1.0, 0.0, z), Vec3::new(0.0, 1.0, z))
    ///     })
    ///     .collect();
    /// let batch = TriangleBatch::<Vec3, 4>::from_slice(&tris).unwrap();
    /// let ray = PreparedRay::new(&Ray::new(Vec3::new(0.25, 0.25, 0.0), Vec3::Z));
    /// let hits = batch.hit(&ray, 3.5);
    /// assert_eq!(hits.mask, 0b0111);
    /// assert_eq!(hits.get(1), tris[1].hit(&ray, 3.5));
    /// let (lane, nearest) = hits.nearest().unwrap();
    /// assert_eq!((lane, nearest.t), (0, 1.0));
    /// // Past the hit at t = 2: the next ones, and never layer 2 again.
    /// let later = batch.hit(&ray, Interval::new(2.0, f32::INFINITY).unwrap());
    /// assert_eq!(later.mask, 0b1100);
    /// ```
    #[inline(always)]
    fn hit(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> Self::Hits {
        let search = search.into();
        match (search.edges, search.range) {
            (EdgeRule::Closed, Range::UpTo(t_max)) => {
                ray.batch::<TriangleBatchKernel<V, N>>(self, t_max)
            }
            (EdgeRule::Closed, Range::Within(i)) => {
                ray.batch::<TriangleBatchInKernel<V, N, false>>(self, i)
            }
            (EdgeRule::OneHit, _) => one_hit_lanes(&ray.to_ray(), self, search),
        }
    }

    /// Whether any lane is hit within `search`. Over an interval it stops
    /// at the first chunk of eight lanes with a hit and computes no `t`,
    /// `u` or `v`.
    ///
    /// ```
    /// use rayhit::{IntersectLanes, Interval, PreparedRay, Ray, Triangle, glam::Vec3};
    /// use rayhit::batch::TriangleBatch;
    /// let occluder = Triangle::new(Vec3::new(-1.0, -1.0, 1.0), Vec3::new(3.0, -1.0, 1.0), Vec3::new(-1.0, 3.0, 1.0));
    /// let batch = TriangleBatch::<Vec3, 8>::from_slice(&[occluder]).unwrap();
    /// // From the floor towards a light at t = 1, through the occluder at t = 0.5.
    /// let ray = PreparedRay::new(&Ray::new(Vec3::ZERO, Vec3::new(0.0, 0.0, 2.0)));
    /// assert!(batch.occluded(&ray, Interval::new(0.0, 1.0).unwrap()));
    /// assert!(!batch.occluded(&ray, Interval::new(0.0, 0.25).unwrap()));
    /// ```
    #[inline(always)]
    fn occluded(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> bool {
        let search = search.into();
        match (search.edges, search.range) {
            (EdgeRule::Closed, Range::Within(i)) => {
                ray.batch::<TriangleBatchInKernel<V, N, true>>(self, i).mask != 0
            }
            _ => self.hit(ray, search).mask != 0,
        }
    }
}
