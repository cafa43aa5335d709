//! Planes and the ray/plane test.

use glam::Vec3;

use crate::num::round::bound_up;
use crate::num::{S, Scalar, Vector};
use crate::query::{Intersect, Range, RayForm, Search, Surface};
use crate::ray::{Interval, Ray, crossing_in, t_error, t_max_ok};
use crate::surface::SurfacePoint;

/// The plane of points `p` with `(p - point) . normal = 0`.
///
/// `normal` need not be unit length and its sign does not matter to
/// [`ray_plane`]; a zero or non-finite `normal` or `point` makes a plane that
/// nothing hits. Its queries are [`Intersect`] (the crossing over a `t_max`
/// or an [`Interval`], decided exactly for an interval) and [`Surface`].
///
/// ```
/// use rayhit::{Plane, glam::Vec3};
/// // z = 2, written two ways.
/// let a = Plane::new(Vec3::new(5.0, -1.0, 2.0), Vec3::Z);
/// let b = Plane::from_coefficients(0.0, 0.0, 1.0, -2.0);
/// assert_eq!(b.point, Vec3::new(0.0, 0.0, 2.0));
/// assert_eq!(a.normal, b.normal);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[repr(C)]
pub struct Plane<V = Vec3> {
    /// Any point on the plane.
    pub point: V,
    /// A normal; any nonzero length.
    pub normal: V,
}

impl<V: Vector> Plane<V> {
    /// The plane through `point` with normal `normal`. Nothing is checked.
    #[inline]
    #[must_use]
    pub const fn new(point: V, normal: V) -> Self {
        Self { point, normal }
    }

    /// The plane `A*x + B*y + C*z + D = 0`: normal `(A, B, C)`.
    ///
    /// The stored point lies on the axis of the normal's largest component
    /// `k`, at coordinate `-D / n_k`, the other two coordinates zero; the only
    /// rounding is that one division, so the stored plane is the exact one
    /// moved by at most half an ulp of `D / n_k` along axis `k`. (The textbook
    /// point `-D * n / |n|^2` takes several roundings.) A zero normal gives a
    /// non-finite point, and so a plane nothing hits.
    #[inline]
    #[must_use]
    pub fn from_coefficients(a: S<V>, b: S<V>, c: S<V>, d: S<V>) -> Self {
        let normal = V::new(a, b, c);
        let z = S::<V>::ZERO;
        let (aa, ab, ac) = (a.abs(), b.abs(), c.abs());
        let point = if aa >= ab && aa >= ac {
            V::new(-d / a, z, z)
        } else if ab >= ac {
            V::new(z, -d / b, z)
        } else {
            V::new(z, z, -d / c)
        };
        Self { point, normal }
    }
}

/// Where `ray` crosses `plane`: `Some(t)` with `0 < t <= t_max`, else `None`.
///
/// `t = ((point - origin) . normal) / (dir . normal)`, in units of `ray.dir`.
/// Returns `None` for a ray parallel to the plane (a ray lying in the plane
/// included) and for one within rounding of parallel: `|dir . normal|` not
/// above twice its own rounding error bound `gamma(3) sum |dir_i normal_i|`
/// (an angle below about `4e-7` radians in `f32`, `7e-16` in `f64`), where
/// not even the side the plane is on is certain. Also `None` for a crossing
/// at `t <= 0` (the ray's own starting surface) or beyond `t_max`, for a `t`
/// too large to represent, and for any NaN or infinite input (then `t` is
/// NaN or infinite and fails the range test). Never panics; never returns
/// NaN.
///
/// Accuracy: `|t - t_exact|` is at most the plane's
/// [`hit_error`](crate::Surface::hit_error), the bound derived there, which is finite for every `t` this returns; away
/// from cancellation (the origin far from the plane relative to its
/// distance from `point`) it is a few ulps of `t`.
///
/// ```
/// use rayhit::{Plane, Ray, glam::Vec3, ray_plane};
/// let floor = Plane::new(Vec3::ZERO, Vec3::Y);
/// let ray = Ray::new(Vec3::new(0.0, 3.0, 0.0), Vec3::new(1.0, -2.0, 0.0));
/// // y = 3 - 2t reaches 0 at t = 1.5, at x = 1.5.
/// assert_eq!(ray_plane(&ray, &floor, f32::INFINITY), Some(1.5));
/// assert_eq!(ray_plane(&ray, &floor, 1.0), None);
/// // Parallel, and pointing away: no hit.
/// assert_eq!(ray_plane(&Ray::new(Vec3::Y, Vec3::X), &floor, 10.0), None);
/// assert_eq!(ray_plane(&Ray::new(Vec3::Y, Vec3::Y), &floor, 10.0), None);
/// ```
#[inline]
#[must_use]
pub fn ray_plane<V: Vector>(ray: &Ray<V>, plane: &Plane<V>, t_max: S<V>) -> Option<S<V>> {
    let denom = ray.dir.dot(plane.normal);
    // Parallel within rounding: the computed `dir . normal` is within twice
    // its own error bound (`gamma(3) sum |d_i n_i|`, see
    // `ray_plane_t_error`) of zero, so not even its sign is certain.
    let resolution = S::<V>::TWO * S::<V>::gamma_n(3) * ray.dir.abs().dot(plane.normal.abs());
    if !(denom.abs() > resolution) {
        return None;
    }
    let numer = (plane.point - ray.origin).dot(plane.normal);
    let t = numer / denom;
    // Every comparison is false for NaN; `t` is infinite when the crossing
    // overflows or an input is infinite.
    (t > S::<V>::ZERO && t <= t_max && t.is_finite() && t_max_ok(t_max)).then_some(t)
}

/// The bound on `t` of [`Plane`]'s `hit_error`, derived in its documentation.
#[inline]
#[must_use]
pub(crate) fn ray_plane_t_error<V: Vector>(ray: &Ray<V>, plane: &Plane<V>, t: S<V>) -> S<V> {
    t_error(ray.origin, ray.dir, plane.point, plane.normal, t)
}

/// [`Plane`]'s `hit` over an interval; its documentation has the guarantees.
#[inline]
#[must_use]
pub(crate) fn ray_plane_in<V: Vector>(
    ray: &Ray<V>,
    plane: &Plane<V>,
    interval: Interval<S<V>>,
) -> Option<S<V>> {
    if !(ray.is_valid() && plane.point.is_finite() && plane.normal.is_finite()) {
        return None;
    }
    crossing_in(ray.origin, ray.dir, plane.point, plane.normal, interval)
}

/// The point and bound of [`Plane`]'s `surface_point`, derived in its documentation.
#[must_use]
pub(crate) fn ray_plane_hit_point<V: Vector>(ray: &Ray<V>, plane: &Plane<V>, t: S<V>) -> (V, V) {
    let p = ray.at(t);
    let err_t = ray_plane_t_error(ray, plane, t);
    let g2 = S::<V>::gamma_n(2);
    let d = ray.dir.abs();
    let td = d * t.abs();
    // At most 3 roundings along any path (product, sum, product). Where the
    // ray does not move along an axis that coordinate is exact whatever `t`
    // is, and its `t` term is zero (not `inf * 0` for an unknown `t`).
    let e = |j: usize| {
        let from_t = if d[j] == S::<V>::ZERO {
            d[j]
        } else {
            err_t * d[j]
        };
        bound_up(from_t + g2 * (ray.origin[j].abs() + td[j]), 3)
    };
    (p, V::new(e(0), e(1), e(2)))
}

/// The ray/plane test, two-sided: `t` in units of the ray's `dir`.
impl<V: Vector> Intersect<V> for Plane<V> {
    /// The distance `t` of the crossing.
    type Hit = S<V>;

    /// Where the ray crosses the plane within `search` (the edge rule is
    /// ignored): `Some(t)`, or `None`.
    ///
    /// **With a `t_max`**: [`ray_plane`]'s answer and guarantees, bit for
    /// bit, on every ray form: `0 < t <= t_max`, rays within rounding of
    /// parallel dropped, `t` within [`hit_error`](Surface::hit_error) of the
    /// exact crossing.
    ///
    /// **With an [`Interval`]** `(t_min, t_max]`: where the ray crosses the
    /// plane at an exact distance `t*` with `interval.min() < t* <= interval.max()` (units
    /// of `ray.dir`), decided exactly; `Some(t)` with `t` in the interval, or
    /// `None`.
    ///
    /// `t* = ((point - origin) . normal) / (dir . normal)` computed exactly
    /// from the input floats. The decision is not up to rounding: the reported
    /// `t` (the quotient [`ray_plane`] computes) and its bound
    /// [`hit_error`](Surface::hit_error) place `t*` where they can; where `t*` lies within
    /// the bound of an end, or the bound is unusable, the exact signs of
    /// `(point - origin) . normal - t_end (dir . normal)` and `dir . normal`
    /// decide, from error-free expansions. So consecutive intervals `(t0, t1]`,
    /// `(t1, t2]`, ... report the plane in exactly one of them when `t*` is in
    /// their union, whatever the ends; a crossing beyond `MAX` (the largest
    /// finite float) is reported by none, as it has no float `t`.
    ///
    /// The reported `t` is always finite and in the interval. It is
    /// `ray_plane`'s quotient `q` where that is in the interval, and so within
    /// [`hit_error`](Surface::hit_error) of `t*` where that bound is
    /// finite. Where rounding put `q` outside, `t` is brought in: to `t_max`
    /// (closer to `t*` than `q`), or to the successor of `t_min`, which is
    /// within the larger of `|q - t*|` and one ulp of `t_min` of `t*` (`t*`
    /// may lie strictly between `t_min` and its successor).
    ///
    /// Rays within rounding of parallel: [`ray_plane`] drops them (the sign of
    /// `dir . normal` is uncertain after rounding). Here the exact sign is
    /// computed: where `dir . normal` is exactly zero (the ray parallel to the
    /// plane or lying in it, or a zero normal) there is no crossing and the
    /// answer is `None`; otherwise `t*` exists, however large, and is decided
    /// exactly like any other. The reported `t` is then the same quotient
    /// brought into the interval, with no error bound (the `t` error bound is
    /// infinite there): of a crossing that is in the interval, only that is
    /// known. This keeps the one-report rule for such rays too, where
    /// dropping them would leave their crossing unreported in every interval.
    ///
    /// Relation to the `t_max` form: with `interval = (0, t_max]`, both give the same `t`, bit for bit, wherever `ray_plane`
    /// hits and `t*` is farther than the error bound from `0` and `t_max`.
    ///
    /// Cost: `ray_plane`'s arithmetic and its error bound; the exact signs
    /// (a few dozen operations) only near an end, within rounding of
    /// parallel, or where the numerator, denominator or `t` is below
    /// `8 MIN_POSITIVE / u` (there the bound's derivation, which treats every
    /// rounding as relative, does not cover underflow).
    ///
    /// Invalid rays (see [`Ray::is_valid`]) and planes with a NaN or infinite
    /// coordinate miss; bad intervals cannot be built ([`Interval::new`]).
    /// Never panics. The decision is exact for every `f32` input; for `f64`,
    /// while the nonzero components of `point - origin` (and their rounding
    /// errors), of `dir` and of `normal` are each within a factor `2^400` of
    /// that vector's largest (so that no exact product underflows); beyond
    /// that it is not guaranteed, and an overflow in the exact signs gives
    /// `None`.
    ///
    /// ```
    /// use rayhit::{Intersect, Interval, Plane, Ray, glam::Vec3};
    /// let floor = Plane::new(Vec3::ZERO, Vec3::Y);
    /// // y = 3 - 2t reaches 0 at exactly t = 1.5.
    /// let ray = Ray::new(Vec3::new(0.0, 3.0, 0.0), Vec3::new(1.0, -2.0, 0.0));
    /// let hit = |lo: f32, hi: f32| floor.hit(&ray, Interval::new(lo, hi).unwrap());
    /// assert_eq!(hit(0.0, 10.0), Some(1.5));
    /// assert_eq!(hit(1.0, 1.5), Some(1.5)); // closed above
    /// assert_eq!(hit(1.5, 2.0), None); // open below: no repeat past t = 1.5
    /// assert_eq!(hit(1.5f32.next_down(), 2.0), Some(1.5));
    /// // A ray lying in the plane never crosses it.
    /// let along = Ray::new(Vec3::ZERO, Vec3::X);
    /// assert_eq!(floor.hit(&along, Interval::up_to(f32::INFINITY).unwrap()), None);
    /// ```
    ///
    /// A ray so close to parallel that `ray_plane` drops it is decided
    /// exactly:
    ///
    /// ```
    /// use rayhit::{Intersect, Interval, Plane, Ray, glam::Vec3, ray_plane};
    /// // x + y = 1, and a ray whose dir . normal = 1 - (1 - 2^-23) = 2^-23 is
    /// // within its own rounding bound of zero: t* = 1 / 2^-23 = 2^23.
    /// let plane = Plane::new(Vec3::X, Vec3::new(1.0, 1.0, 0.0));
    /// let ray = Ray::new(Vec3::ZERO, Vec3::new(1.0, -(1.0 - f32::EPSILON), 0.0));
    /// assert_eq!(ray_plane(&ray, &plane, f32::INFINITY), None);
    /// let window = |lo: f32, hi: f32| Interval::new(lo, hi).unwrap();
    /// let t_star = 8388608.0; // 2^23
    /// assert_eq!(plane.hit(&ray, window(0.0, t_star)), Some(t_star));
    /// assert_eq!(plane.hit(&ray, window(t_star, f32::INFINITY)), None);
    /// ```
    #[inline(always)]
    fn hit(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> Option<S<V>> {
        let ray = ray.to_ray();
        match search.into().range {
            Range::UpTo(t_max) => ray_plane(&ray, self, t_max),
            Range::Within(interval) => ray_plane_in(&ray, self, interval),
        }
    }
}

impl<V: Vector> Surface<V> for Plane<V> {
    /// The bound on `t`'s error.
    type HitError = S<V>;

    /// A bound on `|t - t_exact|` for a `t` this plane's
    /// [`hit`](Intersect::hit) (or [`ray_plane`]) returned, where `t_exact` is
    /// the crossing computed exactly from the same inputs; infinite where the
    /// sign of `dir . normal` is not certain.
    ///
    /// Derivation (`u` the unit roundoff, `gamma(n) = n*u/(1 - n*u)`). Write
    /// `w = point - origin`, `N = w . n` and `D = dir . n` exactly.
    /// - `fl(w)` is one rounding per component, and a 3-term dot product adds at
    ///   most three more to each term, so `|fl(N) - N| <= gamma(4) sum|w_i n_i|
    ///   =: a`; likewise `|fl(D) - D| <= gamma(3) sum|dir_i n_i| =: b`.
    /// - With `q = fl(N)/fl(D)`: `q - N/D = (e_N D - N e_D) / (fl(D) D)`, so
    ///   `|q - t_exact| <= (a + |t_exact| b) / |fl(D)|`; the division's own
    ///   rounding adds `|t - q| <= gamma(1) |t|`.
    /// - `|t_exact| <= |t| + err` turns this into
    ///   `err (1 - x) <= R := (a + |t| b) / |fl(D)| + gamma(1) |t|` with
    ///   `x = b / |fl(D)|`. For `x <= 1/2`, `1/(1 - x) <= 1 + 2x`, so
    ///   `err <= R (1 + 2x)`. For `x > 1/2` the denominator's sign is barely
    ///   known and the bound is infinite.
    ///
    /// The bound is evaluated in floating point on non-negative terms, with at
    /// most 9 roundings along any path, and made an upper bound by the factor
    /// `1 + gamma(10)` (see the crate's `bound_up`).
    ///
    /// ```
    /// use rayhit::{Intersect, Plane, Ray, Surface, glam::Vec3};
    /// let plane = Plane::new(Vec3::new(0.0, 0.0, 10.0), Vec3::Z);
    /// let ray = Ray::new(Vec3::ZERO, Vec3::new(0.3, 0.1, 3.0));
    /// let t = plane.hit(&ray, f32::INFINITY).unwrap();
    /// let err = plane.hit_error(&ray, &t);
    /// let exact = 10.0f64 / 3.0; // 10 and 3 are exact in f32
    /// assert!((f64::from(t) - exact).abs() <= f64::from(err));
    /// assert!(err < 8.0 * f32::EPSILON * t); // a few ulps of t here
    /// ```
    #[inline]
    fn hit_error(&self, ray: &impl RayForm<V>, t: &S<V>) -> S<V> {
        ray_plane_t_error(&ray.to_ray(), self, *t)
    }

    /// The hit point `ray.at(t)` for a `t` from [`hit`](Intersect::hit), a
    /// per-component bound on its distance from the exact crossing (which lies
    /// on the plane): `|p_j - p*_j| <= |t - t*| |d_j| + gamma(2) (|o_j| + |t d_j|)`,
    /// the first term from [`hit_error`](Surface::hit_error), the second from
    /// the two roundings of `o + t d`; and the plane's normal, exact (a zero
    /// normal error).
    ///
    /// ```
    /// use rayhit::{Intersect, Plane, Ray, Surface, glam::Vec3};
    /// let plane = Plane::new(Vec3::new(0.0, 0.0, 2.0), Vec3::Z);
    /// let ray = Ray::new(Vec3::ZERO, Vec3::new(0.25, 0.5, 1.0));
    /// let t = plane.hit(&ray, f32::INFINITY).unwrap();
    /// let here = plane.surface_point(&ray, &t);
    /// assert_eq!(here.point, Vec3::new(0.5, 1.0, 2.0));
    /// assert!(here.point_error.z < 16.0 * f32::EPSILON); // a few ulps of z = 2
    /// ```
    #[inline]
    fn surface_point(&self, ray: &impl RayForm<V>, t: &S<V>) -> SurfacePoint<V> {
        let (point, point_error) = ray_plane_hit_point(&ray.to_ray(), self, *t);
        SurfacePoint {
            point,
            point_error,
            normal: self.normal,
            normal_error: V::ZERO,
        }
    }
}
