//! Spheres: the ray/sphere test, exact over an interval, with error
//! bounds, and the surface point a ray leaves from.

mod batch;
mod exact;
mod roots;

pub(crate) use batch::SphereBatchKernel;
pub use batch::{SphereBatch, SphereBatchHits};

use core::cmp::Ordering;

use glam::Vec3;

use crate::aabb::Aabb;
use crate::num::round::bound_up;
use crate::num::{S, Scalar, Vector};
use crate::query::{Intersect, IntersectLanes, Range, RayForm, Search, Surface};
use crate::ray::{Interval, Ray, bring_into, decide};
use crate::surface::SurfacePoint;
use crate::triangle::Side;
use exact::{Root, SphereCrossing, SphereSigns};
use roots::{Crossings, Fast, crossings, fast};

/// The sphere of points at distance `radius` from `center`: a closed ball's
/// boundary.
///
/// The radius's sign is ignored (a radius of `-r` is the sphere of radius
/// `r`); a radius of zero is the point `center`, met only by a line
/// through it. A NaN or infinite coordinate or radius makes a sphere that
/// nothing hits. Its queries are [`Intersect`] (the nearest crossing over a
/// `t_max` or an [`Interval`], the interval's ends decided exactly) and
/// [`Surface`]; its box for a BVH is [`Sphere::bounds`].
///
/// ```
/// use rayhit::{Intersect, Ray, Side, Sphere, glam::Vec3};
/// let ball = Sphere::new(Vec3::new(0.0, 0.0, -5.0), 1.0);
/// let ray = Ray::new(Vec3::ZERO, Vec3::new(0.0, 0.0, -2.0));
/// let hit = ball.hit(&ray, f32::INFINITY).unwrap();
/// assert_eq!((hit.t, hit.side), (2.0, Side::Front)); // z = -4, entering
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sphere<V: Vector = Vec3> {
    /// The centre.
    pub center: V,
    /// The radius; its sign is ignored.
    pub radius: S<V>,
}

/// A ray/sphere hit: `t` in units of the ray's `dir`, and whether the ray
/// enters the ball there or leaves it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereHit<F = f32> {
    /// Distance along the ray, in units of `dir`.
    pub t: F,
    /// [`Side::Front`] where the ray enters the ball (it arrives from
    /// outside, against the outward normal), [`Side::Back`] where it
    /// leaves (a ray from inside, or the far side).
    pub side: Side,
}

impl<V: Vector> Sphere<V> {
    /// The sphere with centre `center` and radius `radius` (its magnitude).
    /// Nothing is checked.
    #[inline]
    #[must_use]
    pub const fn new(center: V, radius: S<V>) -> Self {
        Self { center, radius }
    }

    /// The smallest box around the sphere, each face rounded outward: it
    /// contains every point of the exact ball, for a BVH built over
    /// spheres. A sphere with a NaN or infinite value gives a box with one
    /// too (which [`ValidAabb::new`](crate::ValidAabb::new) rejects).
    ///
    /// ```
    /// use rayhit::{Sphere, glam::Vec3};
    /// let b = Sphere::new(Vec3::new(1.0, 2.0, 3.0), 0.5).bounds();
    /// assert_eq!((b.min, b.max), (Vec3::new(0.5, 1.5, 2.5), Vec3::new(1.5, 2.5, 3.5)));
    /// ```
    #[inline]
    #[must_use]
    pub fn bounds(&self) -> Aabb<V> {
        let r = self.radius.abs();
        Aabb::around(self.center, V::new(r, r, r))
    }
}

/// [`Sphere`]'s `hit` over `(0, t_max]`; its documentation has the
/// guarantees. (Always inlined: called out of line, the ray the caller
/// copies is stored and reloaded at once, and the loads wait on the
/// stores; a `PreparedRay` took 2.4 times as long.)
#[inline(always)]
#[must_use]
pub(crate) fn ray_sphere<V: Vector>(
    ray: &Ray<V>,
    sphere: &Sphere<V>,
    t_max: S<V>,
) -> Option<SphereHit<S<V>>> {
    // (Bad input needs no check here: a NaN or infinite value, or a zero
    // `dir`, sends the fast path to `unbounded`, which checks it; a NaN or
    // negative `t_max` fails every `t <= t_max`.)
    match fast(
        ray.origin,
        ray.dir,
        sphere.center,
        sphere.radius.abs(),
        t_max,
    ) {
        Fast::Answer(hit) => hit.map(|(t, entering)| SphereHit {
            t,
            side: if entering { Side::Front } else { Side::Back },
        }),
        Fast::Unsure => unbounded(ray, sphere, t_max),
    }
}

/// The `t_max` form where the signs are not known from their bounds (the
/// origin within rounding of the plane through the centre across the
/// ray, an overflow, a very short `dir`): decided exactly over `(0,
/// t_max]`, as the interval form does.
#[cold]
#[inline(never)]
fn unbounded<V: Vector>(ray: &Ray<V>, sphere: &Sphere<V>, t_max: S<V>) -> Option<SphereHit<S<V>>> {
    ray_sphere_in(ray, sphere, Interval::up_to(t_max)?)
}

/// [`Sphere`]'s `hit` over an interval; its documentation has the
/// guarantees.
#[inline]
#[must_use]
pub(crate) fn ray_sphere_in<V: Vector>(
    ray: &Ray<V>,
    sphere: &Sphere<V>,
    interval: Interval<S<V>>,
) -> Option<SphereHit<S<V>>> {
    if !ray.is_valid() {
        return None;
    }
    let c = crossings(ray.origin, ray.dir, sphere.center, sphere.radius)?;
    let (lo, hi) = interval.ends();
    let signs = || signs(ray, sphere);
    if !c.sure && signs().disc_sign()? == Ordering::Less {
        return None;
    }
    let roots = [
        (Root::Entry, c.entry, c.entry_err, Side::Front),
        (Root::Exit, c.exit, c.exit_err, Side::Back),
    ];
    for (root, t, err, side) in roots {
        let exact = || SphereCrossing {
            signs: signs(),
            root,
        };
        if decide(t, err, lo, hi, exact)? {
            return Some(SphereHit {
                t: bring_into(t, lo, hi),
                side,
            });
        }
    }
    None
}

/// The exact signs of the line against the sphere, out of line.
#[cold]
#[inline(never)]
fn signs<V: Vector>(ray: &Ray<V>, sphere: &Sphere<V>) -> SphereSigns {
    let w = |p: V| [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()];
    // `f64` inputs are scaled; `f32` ones are in range as they are.
    let wide = S::<V>::UNIT_ROUNDOFF.to_f64() < 1e-10;
    SphereSigns::new(
        w(ray.origin),
        w(ray.dir),
        w(sphere.center),
        sphere.radius.to_f64(),
        wide,
    )
}

/// The crossings' bound for the side a hit reports.
#[must_use]
pub(crate) fn ray_sphere_t_error<V: Vector>(
    ray: &Ray<V>,
    sphere: &Sphere<V>,
    hit: &SphereHit<S<V>>,
) -> S<V> {
    let inf = S::<V>::INFINITY;
    if !ray.is_valid() {
        return inf;
    }
    match crossings(ray.origin, ray.dir, sphere.center, sphere.radius) {
        Some(Crossings {
            entry_err,
            exit_err,
            ..
        }) => match hit.side {
            Side::Front => entry_err,
            Side::Back => exit_err,
        },
        None => inf,
    }
}

/// The point of a hit moved onto the sphere, with its bounds; derived in
/// [`Sphere`]'s `surface_point`.
#[must_use]
pub(crate) fn sphere_point<V: Vector>(sphere: &Sphere<V>, p: V) -> SurfacePoint<V> {
    let c = sphere.center;
    let r = sphere.radius.abs();
    // `p - c` scaled by a power of two to put its largest component in
    // `[1, 2)`, so that `|v|` neither overflows nor underflows: the
    // direction is all that counts, and the point `q` below is defined
    // from the scaled vector itself.
    let v = scaled_to_one(p - c);
    let len = v.dot(v).sqrt();
    let scale = r / len;
    let w = v * scale;
    let point = c + w;
    let g = S::<V>::gamma_n(7);
    let u = S::<V>::UNIT_ROUNDOFF;
    // An underflowing product or quotient errs by at most `u T` absolutely.
    let tiny = S::<V>::from_u32(4) * S::<V>::MIN_POSITIVE;
    let each = |f: &dyn Fn(usize) -> S<V>| V::new(f(0), f(1), f(2));
    if len >= S::<V>::ONE && w.is_finite() && point.is_finite() {
        SurfacePoint {
            point,
            point_error: each(&|i| bound_up(g * w[i].abs() + u * point[i].abs() + tiny, 3)),
            normal: w,
            normal_error: each(&|i| bound_up(g * w[i].abs() + tiny, 2)),
        }
    } else {
        // No direction from the centre (a point at the centre, a sphere of
        // radius zero) or an overflow: the centre, within `r` of every
        // point of the sphere, with no normal.
        SurfacePoint {
            point: c,
            point_error: V::new(r, r, r),
            normal: V::ZERO,
            normal_error: V::ZERO,
        }
    }
}

/// `v` times the power of two that puts its largest magnitude in `[1,
/// 2)`; `v` itself where that is zero or not finite. (Exact but for
/// components that fall below the smallest subnormal.)
fn scaled_to_one<V: Vector>(v: V) -> V {
    use crate::num::exact_sign::{exponent, scale2};
    let a = v.abs();
    let big = |p: S<V>, q: S<V>| if p > q { p } else { q };
    let m = big(big(a.x(), a.y()), a.z()).to_f64();
    if !(m > 0.0 && m.is_finite()) {
        return v;
    }
    let k = exponent(m);
    let s = |x: S<V>| S::<V>::from_f64(scale2(x.to_f64(), -k));
    V::new(s(v.x()), s(v.y()), s(v.z()))
}

/// The ray/sphere test: the nearest crossing of the ray with the sphere,
/// entering or leaving, `t` in units of the ray's `dir`.
impl<V: Vector> Intersect<V> for Sphere<V> {
    /// `t` and the side: entering the ball or leaving it.
    type Hit = SphereHit<S<V>>;

    /// The nearest crossing of the ray with the sphere within `search`
    /// (the edge rule is ignored): the entry where it is in range, else
    /// the exit (a ray starting inside finds the far side).
    ///
    /// The line `o + t d` meets the sphere at the roots `t- <= t+` of
    /// `|o + t d - c|^2 = r^2`, computed stably (the discriminant from the
    /// centre's distance to the line, `r^2 - |l|^2`, and the pair of roots
    /// `q / a`, `k / q`: Haines, Guenther and Akenine-Moller, Ray Tracing
    /// Gems ch. 7), each with a rigorous error bound
    /// ([`hit_error`](Surface::hit_error)).
    ///
    /// **No false miss.** A line that meets the closed ball in exact
    /// arithmetic is never dropped by the miss test: the test drops a line
    /// only where its computed distance from the centre exceeds the radius
    /// by more than that distance's error bound (a line within rounding of
    /// tangent may be reported as touching).
    ///
    /// **With a `t_max`**: the entry `t-` where it is surely ahead of the
    /// origin and its computed value is at most `t_max`; else the exit
    /// `t+` on the same terms; else `None`. "Surely ahead" is decided from
    /// signs, not from `t`'s size: the entry lies ahead exactly when the
    /// origin is outside the ball and moves towards the centre's nearest
    /// point, and the exit when it lies inside, or moves towards that point
    /// (`|o - c|^2 - r^2` and `(c - o) . d` computed with their error
    /// bounds, so each sign used is the exact one). An origin within
    /// rounding of the sphere counts as on it: the crossing there is not
    /// reported, so a ray spawned off a sphere
    /// ([`SurfacePoint::spawn`]) never meets the surface it left, with no
    /// epsilon, and one spawned into the ball finds the far side. Where
    /// those signs are not known (the origin within rounding of the plane
    /// through the centre across the ray, an overflow, a `dir` shorter
    /// than about `1e-15` in `f32`, `1e-146` in `f64`), the crossings are
    /// placed against `0` and `t_max` exactly instead, as with an interval.
    ///
    /// **With an [`Interval`]** `(t_min, t_max]`: the entry where the exact
    /// `t-` is in the interval, else the exit where the exact `t+` is,
    /// decided exactly (whether the line meets the ball, and each end);
    /// `t` is the computed crossing brought into the interval (finite).
    /// Consecutive intervals report each crossing once; a tangent line's
    /// double crossing is reported once, as an entry. The decision
    /// is exact for every `f32` input, and for `f64` inputs whose nonzero
    /// values (the centre's offset from the origin and its rounding
    /// errors, the radius, the direction, each scaled by a power of two
    /// to put its vector's largest in `[1, 2)`, and an end scaled to
    /// match) are at least `2^-150`.
    ///
    /// Invalid rays (see [`Ray::is_valid`]) and spheres with a NaN or
    /// infinite value miss. Never panics; `t` is never NaN.
    ///
    /// ```
    /// use rayhit::{Intersect, Interval, Ray, Side, Sphere, glam::Vec3};
    /// let ball = Sphere::new(Vec3::ZERO, 2.0);
    /// // From x = -4 along +x: in at t = 2, out at t = 6.
    /// let ray = Ray::new(Vec3::new(-4.0, 0.0, 0.0), Vec3::X);
    /// let hit = |lo: f32, hi: f32| ball.hit(&ray, Interval::new(lo, hi).unwrap());
    /// assert_eq!(hit(0.0, 10.0).map(|h| (h.t, h.side)), Some((2.0, Side::Front)));
    /// assert_eq!(hit(2.0, 10.0).map(|h| (h.t, h.side)), Some((6.0, Side::Back)));
    /// assert_eq!(hit(6.0, 10.0), None); // open below: the exit is not repeated
    /// // From the centre, the far side.
    /// let inside = Ray::new(Vec3::ZERO, Vec3::Y);
    /// assert_eq!(ball.hit(&inside, f32::INFINITY).map(|h| (h.t, h.side)), Some((2.0, Side::Back)));
    /// ```
    #[inline(always)]
    fn hit(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> Option<Self::Hit> {
        let ray = ray.to_ray();
        match search.into().range {
            Range::UpTo(t_max) => ray_sphere(&ray, self, t_max),
            Range::Within(interval) => ray_sphere_in(&ray, self, interval),
        }
    }
}

impl<V: Vector> Surface<V> for Sphere<V> {
    /// The bound on `t`'s error.
    type HitError = S<V>;

    /// A bound on `|t - t*|` for a hit this sphere returned, `t*` the exact
    /// crossing on the hit's side (`t-` for [`Side::Front`], `t+` for
    /// [`Side::Back`]), where the line meets the ball; infinite where it is
    /// not known. The derivation is in the source (`src/sphere/roots.rs`),
    /// term by term. Away from tangency it is a few ulps of the crossing's
    /// distance from the nearest point plus a few ulps of `|o - c| / |d|`;
    /// near tangency it grows as the square root of the discriminant's
    /// error, as any formula's must (two nearly equal roots of a quadratic
    /// are that ill-conditioned).
    ///
    /// For a hit of an interval form, `t` may have been brought into the
    /// interval: then it is within `max(bound, succ(t_min) - t_min)` of
    /// `t*`.
    ///
    /// ```
    /// use rayhit::{Intersect, Ray, Sphere, Surface, glam::Vec3};
    /// let ball = Sphere::new(Vec3::new(0.0, 0.0, -10.0), 3.0);
    /// let ray = Ray::new(Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0));
    /// let hit = ball.hit(&ray, f32::INFINITY).unwrap();
    /// let err = ball.hit_error(&ray, &hit);
    /// assert!((hit.t - 7.0).abs() <= err && err < 1e-5); // a few ulps
    /// ```
    #[inline]
    fn hit_error(&self, ray: &impl RayForm<V>, hit: &Self::Hit) -> S<V> {
        ray_sphere_t_error(&ray.to_ray(), self, hit)
    }

    /// The hit point moved onto the sphere (pbrt-v4's reprojection), with
    /// its bound, and the outward normal (length about `r`).
    ///
    /// With `v = fl(ray.at(t) - center)`, scaled by a power of two to put
    /// its largest component in `[1, 2)` (so that `|v|` neither overflows
    /// nor underflows), and `q = center + r v / |v|` (a point of the exact
    /// sphere), the point is `center + w`, `w = fl(fl(r / fl(|v|)) v)`, and
    /// the normal is `w`: `|w_i - (q - center)_i| <= gamma(6) |w_i|` (six
    /// roundings along `|v|`, the quotient and the product), so
    /// `normal_error_i = gamma(7) |w_i|` and `point_error_i = gamma(7)
    /// |w_i| + u |point_i|`, rounded up, each plus four `MIN_POSITIVE` for
    /// underflow. Both are against the
    /// same `q`: the tangent plane [`SurfacePoint::spawn`] leaves is the
    /// exact sphere's at `q`, and the ball lies on one side of it, so a
    /// ray spawned away from the surface never meets the ball again, and
    /// one spawned into it starts inside (for a sphere larger than a few
    /// error bounds).
    ///
    /// The point is a point of the sphere near the hit, not the exact
    /// crossing: its distance from the crossing is about `hit_error` times
    /// `|dir|`. At the centre (a zero-radius sphere) there is no normal:
    /// the point is the centre, its error `r`, the normal zero (a spawned
    /// ray starts there unmoved).
    ///
    /// ```
    /// use rayhit::{Intersect, Ray, Sphere, Surface, glam::Vec3};
    /// let ball = Sphere::new(Vec3::new(1.0, 2.0, -10.0), 3.0);
    /// let ray = Ray::new(Vec3::new(0.3, 1.7, 0.0), Vec3::new(0.1, 0.05, -1.0));
    /// let hit = ball.hit(&ray, f32::INFINITY).unwrap();
    /// let here = ball.surface_point(&ray, &hit);
    /// let off = (here.point - ball.center).length() - 3.0;
    /// assert!(off.abs() < 1e-5);
    /// // A reflection leaves the sphere and never meets it again.
    /// let n = here.normal.normalize();
    /// let bounce = here.spawn(ray.dir - 2.0 * ray.dir.dot(n) * n);
    /// assert!(ball.hit(&bounce, f32::INFINITY).is_none());
    /// // A refracted ray finds the far side.
    /// let into = here.spawn(ray.dir);
    /// assert_eq!(ball.hit(&into, f32::INFINITY).unwrap().side, rayhit::Side::Back);
    /// ```
    #[inline]
    fn surface_point(&self, ray: &impl RayForm<V>, hit: &Self::Hit) -> SurfacePoint<V> {
        sphere_point(self, ray.to_ray().at(hit.t))
    }
}

impl<V: Vector, const N: usize> IntersectLanes<V> for SphereBatch<V, N> {
    /// Every lane's hit (see [`SphereBatchHits`]; its
    /// [`nearest`](SphereBatchHits::nearest) is the closest).
    type Hits = SphereBatchHits<S<V>, N>;

    /// The hits of every lane within `search` (`mask` is zero when no lane
    /// is hit; the edge rule is ignored).
    ///
    /// With a `t_max`, eight lanes at a time in SIMD registers (SSE2 by
    /// default; AVX2 or AVX-512 where the build or the CPU has it, chosen per
    /// call on x86-64 with `std`; NEON on aarch64): every lane runs
    /// [`Sphere`]'s arithmetic, in the same order, on its own sphere, and
    /// the rare lanes it cannot decide from signs run the scalar code
    /// itself, so each lane is [`Sphere`]'s `hit` bit for bit. A prepared
    /// ray on an instruction set ([`SimdRay`](crate::batch::SimdRay))
    /// skips the per-call choice. With an [`Interval`], each lane runs the
    /// scalar test. Empty lanes give no hit.
    ///
    /// ```
    /// use rayhit::{Intersect, IntersectLanes, Interval, Ray, Sphere, glam::Vec3};
    /// use rayhit::batch::SphereBatch;
    /// // Three particles along z; the ray starts inside the first.
    /// let balls = [0.0, 4.0, 8.0].map(|z| Sphere::new(Vec3::new(0.0, 0.0, z), 1.0));
    /// let batch = SphereBatch::<Vec3, 8>::from_slice(&balls).unwrap();
    /// let ray = Ray::new(Vec3::ZERO, Vec3::Z);
    /// let hits = batch.hit(&ray, f32::INFINITY);
    /// assert_eq!((hits.mask, hits.front), (0b111, 0b110)); // the first one left, the others entered
    /// assert_eq!(hits.t, [1.0, 3.0, 7.0, f32::INFINITY, f32::INFINITY, f32::INFINITY, f32::INFINITY, f32::INFINITY]);
    /// let beyond = batch.hit(&ray, Interval::new(3.0, 10.0).unwrap());
    /// assert_eq!(beyond.get(1), balls[1].hit(&ray, Interval::new(3.0, 10.0).unwrap()));
    /// ```
    #[inline(always)]
    fn hit(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> Self::Hits {
        match search.into().range {
            Range::UpTo(t_max) => ray.batch::<SphereBatchKernel<V, N>>(self, t_max),
            Range::Within(interval) => {
                let ray = ray.to_ray();
                let mut out = SphereBatchHits::none();
                for lane in 0..N {
                    if self.used & (1 << lane) != 0 {
                        out.set(lane, ray_sphere_in(&ray, &self.lane(lane), interval));
                    }
                }
                out
            }
        }
    }

    /// Whether any lane is hit within `search`.
    #[inline(always)]
    fn occluded(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> bool {
        self.hit(ray, search).mask != 0
    }
}
