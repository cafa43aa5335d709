//! Discs and annuli: the ray/disc test over a `t_max` and over an
//! interval, the radius test decided exactly, and the surface point.

mod exact;

use core::cmp::Ordering;

use glam::Vec3;

use crate::aabb::Aabb;
use crate::num::exact_sign::{exponent, scale2};
use crate::num::round::bound_up;
use crate::num::round::outward::{add_up, div_up, mul_down, mul_up};
use crate::num::{S, Scalar, Vector};
use crate::plane::Plane;
use crate::query::{Intersect, Range, RayForm, Search, Surface};
use crate::ray::{Interval, Ray, crossing_in, t_error};
use crate::surface::SurfacePoint;
use crate::triangle::Side;
use exact::DiscSigns;

/// The flat disc of points `p` in the plane through `center` with normal
/// `normal` whose distance from `center` is between `inner_radius` and
/// `radius`, both circles included: a disc (`inner_radius` zero) or an
/// annulus (pbrt's `Disk`, without its angle cut).
///
/// `normal` need not be unit length; its direction picks the front side
/// ([`Side::Front`] is a ray arriving against it). Radii are used by
/// magnitude; an inner radius above the outer one leaves nothing to hit, as
/// does a zero or non-finite normal, and any NaN or infinite value. Its
/// queries are [`Intersect`] and [`Surface`]; its box is
/// [`Disc::bounds`].
///
/// ```
/// use rayhit::{Disc, Intersect, Ray, Side, glam::Vec3};
/// // A ring in the plane z = 1, between radii 1 and 2.
/// let ring = Disc::annulus(Vec3::Z, Vec3::Z, 2.0, 1.0);
/// let down = |x: f32| Ray::new(Vec3::new(x, 0.0, 5.0), -Vec3::Z);
/// assert_eq!(ring.hit(&down(1.5), f32::INFINITY).map(|h| (h.t, h.side)), Some((4.0, Side::Front)));
/// assert!(ring.hit(&down(0.5), f32::INFINITY).is_none()); // through the hole
/// assert!(ring.hit(&down(2.0), f32::INFINITY).is_some()); // on the rim: closed
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Disc<V: Vector = Vec3> {
    /// The centre.
    pub center: V,
    /// The normal; any nonzero length.
    pub normal: V,
    /// The outer radius.
    pub radius: S<V>,
    /// The radius of the hole; zero for a full disc.
    pub inner_radius: S<V>,
}

/// A ray/disc hit: `t` in units of the ray's `dir`, and the side the ray
/// arrived from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DiscHit<F = f32> {
    /// Distance along the ray, in units of `dir`.
    pub t: F,
    /// [`Side::Front`] for a ray arriving against the normal (`dir .
    /// normal < 0`).
    pub side: Side,
}

impl<V: Vector> Disc<V> {
    /// The full disc of radius `radius`. Nothing is checked.
    #[inline]
    #[must_use]
    pub const fn new(center: V, normal: V, radius: S<V>) -> Self {
        Self {
            center,
            normal,
            radius,
            inner_radius: <S<V> as Scalar>::ZERO,
        }
    }

    /// The annulus between `inner_radius` and `radius`. Nothing is
    /// checked.
    #[inline]
    #[must_use]
    pub const fn annulus(center: V, normal: V, radius: S<V>, inner_radius: S<V>) -> Self {
        Self {
            center,
            normal,
            radius,
            inner_radius,
        }
    }

    /// A box around the disc, each face rounded outward: along axis `i` the
    /// disc reaches `radius sqrt(1 - n_i^2 / |n|^2)` from its centre (the
    /// whole radius where that cannot be bounded: where a nonzero normal
    /// component is below `2^-63` (`f32`) or `2^-511` (`f64`) of the
    /// largest, its square would underflow).
    ///
    /// ```
    /// use rayhit::{Disc, glam::Vec3};
    /// let b = Disc::new(Vec3::new(1.0, 2.0, 3.0), Vec3::Z, 0.5).bounds();
    /// assert_eq!((b.min.z, b.max.z), (3.0, 3.0)); // flat along its normal
    /// assert!(b.min.x <= 0.5 && b.max.x >= 1.5);
    /// ```
    #[inline]
    #[must_use]
    pub fn bounds(&self) -> Aabb<V> {
        let r = self.radius.abs();
        // The normal scaled by the power of two that puts its largest
        // component in `[1, 2)` (exact but where a component falls below
        // the normal range): the ratios below are unchanged, and no square
        // overflows, nor does the largest underflow.
        let w = [0, 1, 2].map(|i| self.normal[i].to_f64());
        let m = w.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let n = if m > 0.0 && m.is_finite() {
            let e = exponent(m);
            let f = |x: f64| S::<V>::from_f64(scale2(x, -e));
            V::new(f(w[0]), f(w[1]), f(w[2]))
        } else {
            self.normal
        };
        let sq = |x: S<V>| x * x;
        // A nonzero component whose scaled square underflows (or that
        // scaled to zero): its relative error is not bounded.
        let zero = S::<V>::ZERO;
        let lost = |i: usize| self.normal[i] != zero && sq(n[i]) < S::<V>::MIN_POSITIVE;
        let nn = mul_down(
            sq(n.x()) + sq(n.y()) + sq(n.z()),
            S::<V>::ONE - S::<V>::gamma_n(3),
        );
        let reach = |i: usize| {
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            let other = bound_up(sq(n[j]) + sq(n[k]), 2);
            if self.normal[j] == zero && self.normal[k] == zero {
                // The normal along axis `i` exactly: the disc is flat there.
                return zero;
            }
            if lost(j) || lost(k) {
                return r;
            }
            let e = mul_up(r, bound_up(div_up(other, nn).sqrt(), 1));
            if e < r { e } else { r }
        };
        Aabb::around(self.center, V::new(reach(0), reach(1), reach(2)))
    }

    /// Every value finite.
    #[inline(always)]
    fn is_finite(&self) -> bool {
        self.center.is_finite()
            && self.normal.is_finite()
            && self.radius.is_finite()
            && self.inner_radius.is_finite()
    }

    #[inline(always)]
    fn plane(&self) -> Plane<V> {
        Plane::new(self.center, self.normal)
    }
}

/// Where the crossing at `t` (within `err_t` of the exact `t*`, infinite
/// where unknown) lies against the rims: `Some(true)` inside the closed
/// annulus, exactly. `D = dir . normal` must not be zero.
///
/// The filter: `p = fl(o + t d)` is within `e_j = err_t |d_j| + gamma(2)
/// (|o_j| + |t d_j|)` of `p*` per component (the plane's hit point bound),
/// `v = fl(p - c)` within `eps_j = e_j + u |v_j|` of `p* - c`, and `s =
/// fl(v . v)` within `E = sum eps_j (2 |v_j| + eps_j) + gamma(3) s` of
/// `|p* - c|^2`; each rim is decided where `s` is farther than `E` (plus
/// the squared radius's rounding) from it, and by the exact sign
/// otherwise.
#[inline(always)]
fn within_rims<V: Vector>(ray: &Ray<V>, disc: &Disc<V>, t: S<V>, err_t: S<V>) -> Option<bool> {
    let u = S::<V>::UNIT_ROUNDOFF;
    let g = S::<V>::gamma_n;
    let (r_out, r_in) = (disc.radius.abs(), disc.inner_radius.abs());
    let c = disc.center;
    let p = ray.at(t);
    let v = p - c;
    let s = v.dot(v);
    let err = if err_t.is_finite() && s.is_finite() {
        let d = ray.dir.abs();
        let (o, v_abs) = (ray.origin.abs(), v.abs());
        let mut sum = S::<V>::ZERO;
        for j in 0..3 {
            let e = err_t * d[j] + g(2) * (o[j] + t.abs() * d[j]) + u * v_abs[j];
            sum = sum + e * (S::<V>::TWO * v_abs[j] + e);
        }
        bound_up(
            sum + g(3) * s + S::<V>::from_u32(8) * S::<V>::MIN_POSITIVE,
            8,
        )
    } else {
        S::<V>::INFINITY
    };
    // `fl(r r)` is within `u r^2` (and the smallest subnormal) of `r^2`.
    let place = |radius: S<V>| -> Option<Ordering> {
        let rr = radius * radius;
        let slack = add_up(mul_up(u, rr), S::<V>::MIN_POSITIVE);
        let (lo, hi) = (rr - slack, add_up(rr, slack));
        if add_up(s, err) < lo {
            Some(Ordering::Less)
        } else if s - err > hi {
            Some(Ordering::Greater)
        } else {
            rim_exact(ray, disc, radius)
        }
    };
    if place(r_out)? == Ordering::Greater {
        return Some(false);
    }
    Some(r_in == S::<V>::ZERO || place(r_in)? != Ordering::Less)
}

/// The exact sign of `|p* - c|^2 - radius^2`, out of line.
#[cold]
#[inline(never)]
fn rim_exact<V: Vector>(ray: &Ray<V>, disc: &Disc<V>, radius: S<V>) -> Option<Ordering> {
    let w = |p: V| [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()];
    let wide = S::<V>::UNIT_ROUNDOFF.to_f64() < 1e-10;
    let (signs, ew) = DiscSigns::new(
        w(ray.origin),
        w(ray.dir),
        w(disc.center),
        w(disc.normal),
        radius.to_f64().abs(),
        wide,
    );
    signs.rim(crate::num::exact_sign::scale2(radius.to_f64().abs(), -ew))
}

/// [`Disc`]'s `hit` over `(0, t_max]`.
#[inline]
#[must_use]
pub(crate) fn ray_disc<V: Vector>(
    ray: &Ray<V>,
    disc: &Disc<V>,
    t_max: S<V>,
) -> Option<DiscHit<S<V>>> {
    let plane = disc.plane();
    if !(ray.is_valid() && disc.is_finite()) {
        return None;
    }
    let denom = ray.dir.dot(plane.normal);
    let resolution = S::<V>::TWO * S::<V>::gamma_n(3) * ray.dir.abs().dot(plane.normal.abs());
    if !(denom.abs() > resolution) {
        return None;
    }
    let numer = (plane.point - ray.origin).dot(plane.normal);
    let t = numer / denom;
    if !(t <= t_max && t.is_finite()) {
        return None;
    }
    let err = crossing_error(ray, &plane, numer, denom, t);
    // `t > 0` decided conservatively: the surface a spawned ray leaves.
    if !(t > err) {
        return None;
    }
    within_rims(ray, disc, t, err)?.then_some(DiscHit {
        t,
        side: side(denom),
    })
}

/// [`Disc`]'s `hit` over an interval: the plane's crossing decided exactly
/// against the interval, then the rims exactly.
#[inline]
#[must_use]
pub(crate) fn ray_disc_in<V: Vector>(
    ray: &Ray<V>,
    disc: &Disc<V>,
    interval: Interval<S<V>>,
) -> Option<DiscHit<S<V>>> {
    let plane = disc.plane();
    if !(ray.is_valid() && disc.is_finite()) {
        return None;
    }
    let t = crossing_in(ray.origin, ray.dir, plane.point, plane.normal, interval)?;
    // The brought-in `t` is within `max(err, succ(lo) - lo)` of `t*`, `err`
    // the bound of the quotient it came from.
    let denom = ray.dir.dot(plane.normal);
    let numer = (plane.point - ray.origin).dot(plane.normal);
    let err = crossing_error(ray, &plane, numer, denom, numer / denom);
    let ulp = interval.min().next_up() - interval.min();
    let err_t = if err > ulp { err } else { ulp };
    if !within_rims(ray, disc, t, err_t)? {
        return None;
    }
    // Within rounding of parallel (or where the bound does not cover
    // underflow), the computed `dir . normal` may have the wrong sign, or
    // be zero: the exact one, which is not zero since the crossing exists.
    let resolution = S::<V>::TWO * S::<V>::gamma_n(3) * ray.dir.abs().dot(plane.normal.abs());
    let side = if err.is_finite() && denom.abs() > resolution {
        side(denom)
    } else {
        exact_side(ray, disc)?
    };
    Some(DiscHit { t, side })
}

/// The side a ray arrives from, by the exact sign of `dir . normal`, out
/// of line.
#[cold]
#[inline(never)]
fn exact_side<V: Vector>(ray: &Ray<V>, disc: &Disc<V>) -> Option<Side> {
    let w = |p: V| [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()];
    let wide = S::<V>::UNIT_ROUNDOFF.to_f64() < 1e-10;
    let (signs, _) = DiscSigns::new(
        w(ray.origin),
        w(ray.dir),
        w(disc.center),
        w(disc.normal),
        0.0,
        wide,
    );
    match signs.den_sign()? {
        Ordering::Less => Some(Side::Front),
        Ordering::Greater => Some(Side::Back),
        Ordering::Equal => None,
    }
}

/// The plane test's bound on the quotient `t = numer / denom`, infinite
/// where a value is below `8 MIN_POSITIVE / u` (the bound counts every
/// rounding as relative, which underflow breaks: see `crossing_in`).
#[inline(always)]
fn crossing_error<V: Vector>(
    ray: &Ray<V>,
    plane: &Plane<V>,
    numer: S<V>,
    denom: S<V>,
    t: S<V>,
) -> S<V> {
    let floor = S::<V>::from_u32(8) * S::<V>::MIN_POSITIVE / S::<V>::UNIT_ROUNDOFF;
    if numer.abs() >= floor && denom.abs() >= floor && t.abs() >= floor {
        t_error(ray.origin, ray.dir, plane.point, plane.normal, t)
    } else {
        S::<V>::INFINITY
    }
}

/// The side a ray arrives from, by the sign of the computed `dir . normal`
/// (exact wherever the hit's bound is finite and the ray is not within
/// rounding of parallel; elsewhere `exact_side` decides).
#[inline(always)]
fn side<F: Scalar>(denom: F) -> Side {
    if denom < F::ZERO {
        Side::Front
    } else {
        Side::Back
    }
}

/// The ray/disc test, two-sided.
impl<V: Vector> Intersect<V> for Disc<V> {
    /// `t` and the side.
    type Hit = DiscHit<S<V>>;

    /// Where the ray crosses the disc within `search` (the edge rule is
    /// ignored).
    ///
    /// The crossing with the disc's plane is the plane test's (its `t`,
    /// its error bound); whether it lies within the rims is decided
    /// exactly: the computed point's distance from the centre, with its
    /// error bound, decides where it is clear of both circles, and the
    /// exact sign of `|p* - c|^2 - r^2` (for the exact crossing `p*`)
    /// decides the rest. So a ray through the rim of the exact disc, or
    /// the rim of its hole, is never misjudged, and two discs (or a disc and
    /// an annulus) that share a circle leave no gap between them where the
    /// ray crosses their common plane.
    ///
    /// **With a `t_max`**: `0 < t <= t_max`, rays within rounding of
    /// parallel to the plane dropped (as [`ray_plane`](crate::ray_plane)
    /// does), `t > 0` decided conservatively (a crossing within its error
    /// bound of the origin is dropped: the disc a spawned ray leaves),
    /// `t <= t_max` on the computed `t`. Where `(c - o) . n`, `dir . n` or
    /// `t` is below `8 MIN_POSITIVE / u` the plane's bound does not cover
    /// underflow, and the crossing is dropped too (the interval form
    /// decides it exactly).
    ///
    /// **With an [`Interval`]**: the plane's crossing decided exactly
    /// against both ends (see [`Plane`'s `hit`](crate::Plane#method.hit)),
    /// and then the rims; `t` is brought into the interval. The decision is
    /// exact for every `f32` input; for `f64`, while the nonzero
    /// components of each of `c - o` (and its rounding errors, with the
    /// radius), `dir` and `normal` are within `2^150` of that vector's
    /// largest.
    ///
    /// Invalid rays and discs with a NaN or infinite value miss. Never
    /// panics; `t` is never NaN.
    ///
    /// ```
    /// use rayhit::{Disc, Intersect, Interval, Ray, glam::Vec3};
    /// let disc = Disc::new(Vec3::ZERO, Vec3::Y, 1.0);
    /// let ray = Ray::new(Vec3::new(1.0, 1.0, 0.0), -Vec3::Y); // through the rim
    /// assert_eq!(disc.hit(&ray, f32::INFINITY).map(|h| h.t), Some(1.0));
    /// assert!(disc.hit(&ray, Interval::new(1.0, 2.0).unwrap()).is_none()); // open below
    /// ```
    #[inline(always)]
    fn hit(&self, ray: &impl RayForm<V>, search: impl Into<Search<S<V>>>) -> Option<Self::Hit> {
        let ray = ray.to_ray();
        match search.into().range {
            Range::UpTo(t_max) => ray_disc(&ray, self, t_max),
            Range::Within(interval) => ray_disc_in(&ray, self, interval),
        }
    }
}

impl<V: Vector> Surface<V> for Disc<V> {
    /// The bound on `t`'s error.
    type HitError = S<V>;

    /// The plane test's bound on `|t - t*|` (see [`Plane`'s
    /// `hit_error`](crate::Plane#method.hit_error)); for a hit of an
    /// interval form brought into the interval, `max(bound, succ(t_min) -
    /// t_min)`.
    #[inline]
    fn hit_error(&self, ray: &impl RayForm<V>, hit: &Self::Hit) -> S<V> {
        self.plane().hit_error(ray, &hit.t)
    }

    /// The hit point `ray.at(t)` with the plane's bound on its distance
    /// from the exact crossing, and the disc's normal, exact.
    ///
    /// ```
    /// use rayhit::{Disc, Intersect, Ray, Surface, glam::Vec3};
    /// let disc = Disc::new(Vec3::ZERO, Vec3::Y, 2.0);
    /// let ray = Ray::new(Vec3::new(0.5, 3.0, 0.25), Vec3::new(0.1, -1.0, 0.2));
    /// let hit = disc.hit(&ray, f32::INFINITY).unwrap();
    /// let here = disc.surface_point(&ray, &hit);
    /// let bounce = here.spawn(Vec3::new(0.1, 1.0, 0.2));
    /// assert!(disc.hit(&bounce, f32::INFINITY).is_none());
    /// ```
    #[inline]
    fn surface_point(&self, ray: &impl RayForm<V>, hit: &Self::Hit) -> SurfacePoint<V> {
        self.plane().surface_point(ray, &hit.t)
    }
}
