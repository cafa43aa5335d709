//! Judging a claimed answer against the exact one.

use super::measure::{err_in, rel_err, root_err, root_err_in};
use core::fmt;
use std::vec::Vec;

use super::oracle::{self, R};
use num_traits::Zero;

use super::Rational;
use crate::{Aabb, Disc, Patch, Plane, Quad, Ray, Scalar, Side, Sphere, Triangle, Vector};

/// One question a kernel answers: a ray against a box, a triangle, a
/// plane, a sphere, a disc, a quad or a bilinear patch, with the limit
/// `t_max`. New shapes add variants (hence `non_exhaustive`).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Case<V: Vector> {
    /// Ray/box, `t` in `[0, t_max]`.
    Box(Ray<V>, Aabb<V>, V::Scalar),
    /// Ray/triangle (closed, two-sided), `0 < t <= t_max`.
    Triangle(Ray<V>, Triangle<V>, V::Scalar),
    /// Ray/plane, `0 < t <= t_max`.
    Plane(Ray<V>, Plane<V>, V::Scalar),
    /// Ray/sphere, the first crossing (entry, else exit) in `0 < t <=
    /// t_max`.
    Sphere(Ray<V>, Sphere<V>, V::Scalar),
    /// Ray/disc (both circles closed, two-sided), `0 < t <= t_max`.
    Disc(Ray<V>, Disc<V>, V::Scalar),
    /// Ray/quad (its two closed triangles `a, b, c` and `a, c, d`,
    /// two-sided), the nearer crossing in `0 < t <= t_max`.
    Quad(Ray<V>, Quad<V>, V::Scalar),
    /// Ray/bilinear patch (closed, two-sided), the nearest crossing in `0
    /// < t <= t_max`.
    Patch(Ray<V>, Patch<V>, V::Scalar),
}

/// What a kernel answered for a [`Case`]; one variant per shape (new
/// shapes add variants).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Claim<F> {
    /// No hit.
    Miss,
    /// A box hit: entry and exit.
    Box {
        /// Claimed entry.
        enter: F,
        /// Claimed exit.
        exit: F,
    },
    /// A triangle hit.
    Triangle {
        /// Claimed `t`.
        t: F,
        /// Claimed weight of `b`.
        u: F,
        /// Claimed weight of `c`.
        v: F,
    },
    /// A plane hit.
    Plane {
        /// Claimed `t`.
        t: F,
    },
    /// A sphere hit: the crossing and whether it enters the ball.
    Sphere {
        /// Claimed `t`.
        t: F,
        /// Claimed side: [`Side::Front`] entering the ball,
        /// [`Side::Back`] leaving it.
        side: Side,
    },
    /// A disc hit.
    Disc {
        /// Claimed `t`.
        t: F,
        /// Claimed side: [`Side::Front`] arriving against the normal.
        side: Side,
    },
    /// A quad hit: `t` and the place on the quad, as
    /// [`QuadHit`](crate::QuadHit) gives it (`a` at `(0, 0)`, `b` at `(1,
    /// 0)`, `c` at `(1, 1)`, `d` at `(0, 1)`, linear on each triangle).
    Quad {
        /// Claimed `t`.
        t: F,
        /// Claimed `u`.
        u: F,
        /// Claimed `v`.
        v: F,
    },
    /// A bilinear patch hit: `t`, the place `(u, v)` and the side, as
    /// [`PatchHit`](crate::PatchHit) gives them.
    Patch {
        /// Claimed `t`.
        t: F,
        /// Claimed `u` (along `p00 -> p10`).
        u: F,
        /// Claimed `v` (along `p00 -> p01`).
        v: F,
        /// Claimed side: [`Side::Front`] where `dir . (dP/du x dP/dv) <=
        /// 0`.
        side: Side,
    },
}

impl<F> Claim<F> {
    /// True for every claim but [`Claim::Miss`].
    #[must_use]
    pub fn is_hit(&self) -> bool {
        !matches!(self, Claim::Miss)
    }
}

/// Hit or miss against the exact answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Verdict {
    /// Hit when the exact answer hits, miss when it misses.
    Right,
    /// A hit where the exact answer misses.
    FalseHit,
    /// A miss where the exact answer hits.
    FalseMiss,
}

/// Whether rounding may excuse a wrong hit/miss.
///
/// `Clear` cases lie outside the crate's documented rounding band for the
/// kernel (see [`band`]): a kernel that meets the crate's guarantees gets
/// every one right. `Edge` cases lie within it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Band {
    /// Outside the rounding band.
    Clear,
    /// Within it.
    Edge,
}

/// A claimed value: which one (new shapes may add fields).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Field {
    /// Box entry.
    Enter,
    /// Box exit.
    Exit,
    /// Triangle, plane, sphere, disc, quad or patch `t`.
    T,
    /// Triangle, quad or patch `u`.
    U,
    /// Triangle, quad or patch `v`.
    V,
    /// Sphere, disc or patch side (entering or leaving the ball, arriving
    /// against or along the normal, against or along the patch's normal).
    Side,
}

/// The judgement of one claim.
#[derive(Clone, Debug, PartialEq)]
pub struct Judgement {
    /// Right, false hit or false miss.
    pub verdict: Verdict,
    /// Whether the case is outside the rounding band.
    pub band: Band,
    /// The distance of the ray from the decisive boundary, in ulps of the
    /// case's largest coordinate (see [`distance_ulps`]).
    pub distance_ulps: f64,
    /// For a right hit, each claimed value's error: `t`, entry and exit in
    /// ulps of the exact value (the spacing of floats at its magnitude),
    /// `u` and `v` in ulps of 1 (they are fractions of the shape), a
    /// side 0 when right and infinite when wrong.
    pub errors: Vec<(Field, f64)>,
    /// The fields whose error exceeds the bound given to [`judge`], and a
    /// wrong side whatever the bound (none for a sphere or patch case in
    /// the `Edge` band, nor for a quad's there whose triangles are both
    /// crossed: see [`judge`]).
    pub outside: Vec<Field>,
}

impl Judgement {
    /// The largest error of a `t`-like field (`t`, entry, exit), or 0.
    #[must_use]
    pub fn worst_t_error(&self) -> f64 {
        self.errors
            .iter()
            .filter(|(f, _)| matches!(f, Field::T | Field::Enter | Field::Exit))
            .map(|e| e.1)
            .fold(0.0, f64::max)
    }
}

fn f(x: &R) -> f64 {
    oracle::to_f64(x)
}

fn max_abs<V: Vector>(points: &[V]) -> f64 {
    points
        .iter()
        .flat_map(|p| [p.x(), p.y(), p.z()])
        .map(|c| c.to_f64().abs())
        .fold(0.0, f64::max)
}

fn valid<V: Vector>(case: &Case<V>) -> bool {
    match case {
        Case::Box(ray, b, t_max) => {
            ray.is_valid() && b.is_valid() && t_max.partial_cmp(t_max).is_some()
        }
        Case::Triangle(ray, tri, t_max) => {
            ray.is_valid()
                && tri.a.is_finite()
                && tri.b.is_finite()
                && tri.c.is_finite()
                && t_max.partial_cmp(t_max).is_some()
        }
        Case::Plane(ray, p, t_max) => {
            ray.is_valid()
                && p.point.is_finite()
                && p.normal.is_finite()
                && t_max.partial_cmp(t_max).is_some()
        }
        Case::Sphere(ray, s, t_max) => {
            ray.is_valid()
                && s.center.is_finite()
                && s.radius.is_finite()
                && t_max.partial_cmp(t_max).is_some()
        }
        Case::Disc(ray, d, t_max) => {
            ray.is_valid()
                && d.center.is_finite()
                && d.normal.is_finite()
                && d.radius.is_finite()
                && d.inner_radius.is_finite()
                && t_max.partial_cmp(t_max).is_some()
        }
        Case::Quad(ray, q, t_max) => {
            ray.is_valid()
                && [q.a, q.b, q.c, q.d].iter().all(|p| p.is_finite())
                && t_max.partial_cmp(t_max).is_some()
        }
        Case::Patch(ray, p, t_max) => {
            ray.is_valid()
                && [p.p00, p.p10, p.p01, p.p11].iter().all(|p| p.is_finite())
                && t_max.partial_cmp(t_max).is_some()
        }
    }
}

/// `gap`, the distance of a ray from its decisive boundary, with the
/// distance along the ray from the crossing at `t` (about) to 0 and
/// `t_max` where that is smaller (`speed` the direction's length).
fn along<F: Scalar>(gap: f64, t: f64, t_max: F, speed: f64) -> f64 {
    let mut gap = gap.min(t.abs() * speed);
    if t_max.is_finite() {
        gap = gap.min((t - t_max.to_f64()).abs() * speed);
    }
    gap
}

/// How far the case's ray is from the boundary that decides hit or miss, in
/// ulps of the largest coordinate involved (origin and shape; the spacing of
/// floats of the case's precision there): the measure the crate's oracle
/// tests print. Infinite when no boundary is near (an axis the ray does not
/// move along rules a box out; a ray parallel to a plane), and for invalid
/// input.
///
/// - box: the exact gap between entry and exit in `t` times the speed along
///   the axis that sets either (how far outside the ray passes, or how deep
///   inside it goes);
/// - triangle: the distance of the ray's line from the nearest edge's line,
///   or, if smaller, the distance along the ray from the crossing to `t = 0`
///   or `t_max`;
/// - plane: the distance in `t` from the crossing to 0 or `t_max`, times the
///   largest direction component;
/// - sphere: the distance of the ray's line from tangency (`||l| - r|`,
///   `l` the centre's offset from the line), or, if smaller, the distance
///   along the ray from the first crossing ahead (the exit where none is
///   ahead) to `t = 0` or `t_max`; the radius counts among the
///   coordinates;
/// - disc: the distance of the crossing from the nearer circle, or, if
///   smaller, the distance along the ray from it to `t = 0` or `t_max`;
///   the outer radius counts among the coordinates;
/// - quad: as the triangle, from the lines of its four edges (the
///   diagonal is inside it), along the ray from either triangle's plane
///   crossing;
/// - bilinear patch: as the quad, from the lines of its four edges, along
///   the ray from each crossing (how near a fold's two crossings are to
///   meeting is not measured).
#[must_use]
pub fn distance_ulps<V: Vector>(case: &Case<V>) -> f64 {
    if !valid(case) {
        return f64::INFINITY;
    }
    match case {
        Case::Box(ray, b, t_max) => {
            let scale = max_abs(&[ray.origin, b.min, b.max]);
            oracle::box_gap(ray, b, *t_max)
                .map_or(f64::INFINITY, |g| f(&g) / oracle::ulp::<V::Scalar>(scale))
        }
        Case::Triangle(ray, tri, t_max) => {
            // Valid (checked above), so every exact value exists.
            let gap = || -> Option<f64> {
                let ex = oracle::triangle(ray, tri)?;
                let d = oracle::rv(ray.dir)?;
                let mut gap = oracle::edges_gap(ray, &[tri.a, tri.b, tri.c])?;
                if let Some(t) = &ex.t {
                    gap = along(gap, f(t), *t_max, f(&oracle::dot(&d, &d)).sqrt());
                }
                Some(gap)
            };
            let scale = max_abs(&[ray.origin, tri.a, tri.b, tri.c]);
            gap().map_or(f64::INFINITY, |g| g / oracle::ulp::<V::Scalar>(scale))
        }
        Case::Plane(ray, plane, t_max) => {
            let scale = max_abs(&[ray.origin, plane.point]);
            oracle::plane_t(ray, plane).map_or(f64::INFINITY, |t| {
                let dmax = max_abs(&[ray.dir]);
                let edge = if t_max.is_finite() {
                    f(&t).abs().min((f(&t) - t_max.to_f64()).abs())
                } else {
                    f(&t).abs()
                };
                edge * dmax / oracle::ulp::<V::Scalar>(scale)
            })
        }
        Case::Sphere(ray, s, t_max) => {
            let scale = max_abs(&[ray.origin, s.center]).max(s.radius.to_f64().abs());
            let gap = || -> Option<f64> {
                let e = oracle::sphere(ray, s.center, s.radius)?;
                let (a, y, r) = (f(&e.a), f(&e.discriminant()), s.radius.to_f64().abs());
                // y = a (r^2 - |l|^2), so ||l| - r| = |y| / (a (|l| + r)).
                let l = (r * r - y / a).max(0.0).sqrt();
                let tangent = if l + r > 0.0 {
                    y.abs() / a / (l + r)
                } else {
                    0.0
                };
                if !e.line_hits() {
                    return Some(tangent);
                }
                let side = e.first_in(&Rational::zero(), None).unwrap_or(Side::Back);
                Some(along(tangent, e.estimate(side), *t_max, a.sqrt()))
            };
            let g = gap().map_or(f64::INFINITY, |g| g / oracle::ulp::<V::Scalar>(scale));
            if g.is_nan() { f64::INFINITY } else { g }
        }
        Case::Disc(ray, d, t_max) => {
            let (outer, inner) = (d.radius.to_f64().abs(), d.inner_radius.to_f64().abs());
            let scale = max_abs(&[ray.origin, d.center]).max(outer);
            let gap = || -> Option<f64> {
                let e = oracle::disc(ray, d)?;
                let dist = f(&e.dist2).sqrt();
                let mut rim = (dist - outer).abs();
                if inner > 0.0 {
                    rim = rim.min((dist - inner).abs());
                }
                let dd = oracle::rv(ray.dir)?;
                Some(along(
                    rim,
                    f(&e.t),
                    *t_max,
                    f(&oracle::dot(&dd, &dd)).sqrt(),
                ))
            };
            let g = gap().map_or(f64::INFINITY, |g| g / oracle::ulp::<V::Scalar>(scale));
            if g.is_nan() { f64::INFINITY } else { g }
        }
        Case::Quad(ray, q, t_max) => {
            let scale = max_abs(&[ray.origin, q.a, q.b, q.c, q.d]);
            let gap = || -> Option<f64> {
                let d = oracle::rv(ray.dir)?;
                let mut gap = oracle::edges_gap(ray, &[q.a, q.b, q.c, q.d])?;
                let speed = f(&oracle::dot(&d, &d)).sqrt();
                for tri in q.triangles() {
                    if let Some(t) = oracle::triangle(ray, &tri)?.t {
                        gap = along(gap, f(&t), *t_max, speed);
                    }
                }
                Some(gap)
            };
            let g = gap().map_or(f64::INFINITY, |g| g / oracle::ulp::<V::Scalar>(scale));
            if g.is_nan() { f64::INFINITY } else { g }
        }
        Case::Patch(ray, p, t_max) => {
            let scale = max_abs(&[ray.origin, p.p00, p.p10, p.p01, p.p11]);
            let gap = || -> Option<f64> {
                let d = oracle::rv(ray.dir)?;
                // Around the boundary: p00, p10, p11, p01.
                let mut gap = oracle::edges_gap(ray, &[p.p00, p.p10, p.p11, p.p01])?;
                let speed = f(&oracle::dot(&d, &d)).sqrt();
                for c in oracle::patch(ray, p)?.crossings {
                    gap = along(gap, c.t.to_f64(), *t_max, speed);
                }
                Some(gap)
            };
            let g = gap().map_or(f64::INFINITY, |g| g / oracle::ulp::<V::Scalar>(scale));
            if g.is_nan() { f64::INFINITY } else { g }
        }
    }
}

/// The band of a case: `Clear` when exact arithmetic decides it outside the
/// documented rounding band of the crate's kernel for it, `Edge` otherwise
/// (and for invalid input, which every kernel must miss: `Clear`).
///
/// - box: the exact interval is more than `32u` (`80u` where a direction
///   component's reciprocal is subnormal; relative, plus four subnormals
///   over the slowest direction component) from empty, and no direction
///   component is subnormal;
/// - triangle: a hit or a miss behind the origin or past `t_max` decided
///   outside the watertight test's error bounds
///   ([`Triangle`'s `hit_error`](crate::Triangle#method.hit_error)) widened
///   by Moller-Trumbore's, in `u`, `v`, `1 - u - v` and `t`; or a miss whose
///   line crosses the plane outside the triangle by more than either test's
///   rounding (of the edge functions, and of `u`, `v`, `1 - u - v`). A line
///   parallel to the plane and a triangle of zero area are never clear (the
///   exact determinant is zero, a rounded one need not be);
/// - plane: not within rounding of parallel and the crossing farther than
///   [`Plane`'s `hit_error`](crate::Plane#method.hit_error) from 0 and `t_max`;
/// - sphere ([`oracle::sphere_clear`]): the line not within (twice) the
///   miss test's rounding of tangent, the origin not within rounding of
///   the sphere, and the first crossing ahead farther than
///   [`Sphere`'s `hit_error`](crate::Sphere#method.hit_error) from 0 and
///   `t_max`; in this band a correct kernel may report a line that misses
///   by a rounding error, drop a crossing just ahead of the origin or
///   report the other one, and its `t` may be as ill-conditioned as a
///   square root;
/// - disc ([`oracle::disc_clear`]): as the plane, the crossing more than
///   three times its bound from 0 and no value near underflow; the rims
///   need no band (the crate's kernel decides them exactly);
/// - quad ([`oracle::quad_clear`]): each of its two triangles decided
///   outside the watertight test's band (no Moller-Trumbore widening: the
///   quad is that test's answer, bit for bit), and where both are
///   crossed, their crossings farther apart than their `t` bounds; a ray
///   within rounding of the diagonal is `Edge`;
/// - bilinear patch ([`oracle::patch_clear`]): a collapsed edge, the
///   triangle's band; otherwise the line clear of each boundary edge by
///   more than the edge function's rounding, the quadratic's discriminant
///   farther from zero than `2^10` times its rounding, each root of a
///   fold (zero winding number) clear of the unit square's edges by a
///   first-order estimate of its error (times 16), and each crossing's
///   `t` more than 16 times its certified bound from 0, `t_max` and the
///   other crossing; in this band a correct kernel may report a line that
///   misses, drop a crossing near the origin or an edge, or report the
///   other crossing of a fold.
#[must_use]
pub fn band<V: Vector>(case: &Case<V>) -> Band {
    let clear = !valid(case)
        || match case {
            Case::Box(ray, b, t_max) => oracle::box_clear(ray, b, *t_max),
            Case::Triangle(ray, tri, t_max) => oracle::triangle_clear(ray, tri, *t_max),
            Case::Plane(ray, p, t_max) => oracle::plane_clear(ray, p, *t_max),
            Case::Sphere(ray, s, t_max) => oracle::sphere_clear(ray, s, *t_max),
            Case::Disc(ray, d, t_max) => oracle::disc_clear(ray, d, *t_max),
            Case::Quad(ray, q, t_max) => oracle::quad_clear(ray, q, *t_max),
            Case::Patch(ray, p, t_max) => oracle::patch_clear(ray, p, *t_max),
        };
    if clear { Band::Clear } else { Band::Edge }
}

/// A claimed `t`, `u`, `v` against exact ones: `t` in its own ulps, `u`
/// and `v` in ulps of one (`one`).
fn tuv_errors<F: Scalar>(claim: [F; 3], exact: [&Rational; 3], one: f64) -> [(Field, f64); 3] {
    [
        (Field::T, rel_err(claim[0], exact[0])),
        (Field::U, err_in(claim[1], exact[1], one)),
        (Field::V, err_in(claim[2], exact[2], one)),
    ]
}

/// The claimed side against the exact one: 0 or infinitely wrong.
fn side_err(claimed: Side, exact: Side) -> (Field, f64) {
    (
        Field::Side,
        if claimed == exact { 0.0 } else { f64::INFINITY },
    )
}

/// Judges `claim` for `case`: right, false hit or false miss, the case's
/// band and distance from the boundary, and for a right hit the error of
/// each claimed value, with those over `bound_ulps` listed (`t`, entry,
/// exit in ulps of the exact value, `u`, `v` in ulps of 1, a wrong side
/// infinitely wrong; see [`Judgement::errors`]). A claim of the wrong kind
/// (a triangle hit for a box case) counts as a hit with every value
/// infinitely wrong.
///
/// Spheres and discs: the exact answer is the first crossing in `(0,
/// t_max]` ([`ray_sphere`](super::ray_sphere), [`ray_disc`](super::ray_disc));
/// a claimed hit is right where the exact answer hits, its `t` is
/// measured in ulps of the exact crossing (a sphere's, irrational, to
/// within `2^-24` ulps) and its side must be the exact one (a wrong side
/// is listed in [`Judgement::outside`] whatever `bound_ulps`). On a sphere
/// case in the `Edge` band ([`band`]: within rounding of tangent, an
/// origin within rounding of the sphere, a crossing within its bound of 0
/// or `t_max`) the values are measured but not held to `bound_ulps`
/// ([`Judgement::outside`] stays empty): there a kernel with the crate's
/// guarantees may report the other crossing, or a `t` whose error grows as
/// the square root of the discriminant's rounding. On `Clear` cases they
/// are held to it, and the crate's own bound there is
/// [`Sphere`'s `hit_error`](crate::Sphere#method.hit_error) (in ulps of
/// `t`: a few, more where the origin is close to the sphere, as `|o -
/// c|^2 - r^2` cancels).
///
/// Quads are judged as triangles (the exact answer is
/// [`ray_quad`](super::ray_quad)'s, `u` and `v` in ulps of 1), their
/// values held but on an `Edge` case where both triangles are crossed in
/// `(0, t_max]` (there the nearer may be either, within rounding, with
/// its own `u` and `v`). Bilinear patches: the exact answer is the nearest
/// crossing in `(0, t_max]` ([`ray_patch`](super::ray_patch)); its `t`,
/// `u` and `v` are irrational in general and measured by exact
/// comparisons (to within `2^-24` ulps, `u` and `v` in ulps of 1), and
/// the side must be the exact one. On a patch case in the `Edge` band
/// ([`oracle::patch_clear`]) the values are measured but not held, as for
/// spheres: there a kernel with the crate's guarantees may report a
/// fold's other crossing, or one just past an edge.
///
/// ```
/// use rayhit::{Patch, Quad, Ray, Side, exact, glam::Vec3};
/// use rayhit::exact::{Band, Case, Claim, Field, Verdict};
/// // The unit square, straight down onto (0.5, 0.25) from z = 1.
/// let quad = Quad::parallelogram(Vec3::ZERO, Vec3::X, Vec3::Y);
/// let down = Ray::new(Vec3::new(0.5, 0.25, 1.0), -Vec3::Z);
/// let case = Case::Quad(down, quad, f32::INFINITY);
/// let j = exact::judge(&case, &Claim::Quad { t: 1.0, u: 0.5, v: 0.25 }, 1.0);
/// assert_eq!((j.verdict, j.band), (Verdict::Right, Band::Clear));
/// assert!(j.outside.is_empty());
/// // The saddle z = x y over the unit square, down onto (0.5, 0.5): its
/// // height there is 0.25, so t = 2.75, from the front.
/// let saddle = Patch::new(Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 1.0));
/// let case = Case::Patch(Ray::new(Vec3::new(0.5, 0.5, 3.0), -Vec3::Z), saddle, f32::INFINITY);
/// let right = Claim::Patch { t: 2.75, u: 0.5, v: 0.5, side: Side::Front };
/// let j = exact::judge(&case, &right, 1.0);
/// assert_eq!((j.verdict, j.band), (Verdict::Right, Band::Clear));
/// assert!(j.outside.is_empty());
/// let wrong_side = Claim::Patch { t: 2.75, u: 0.5, v: 0.5, side: Side::Back };
/// assert_eq!(exact::judge(&case, &wrong_side, 1.0).outside, vec![Field::Side]);
/// ```
///
/// ```
/// use rayhit::{Ray, Side, Sphere, exact, glam::Vec3};
/// use rayhit::exact::{Band, Case, Claim, Field, Verdict};
/// let case = Case::Sphere(Ray::new(Vec3::new(0.0, 0.0, -3.0), Vec3::Z), Sphere::new(Vec3::ZERO, 1.0), f32::INFINITY);
/// let j = exact::judge(&case, &Claim::Sphere { t: 2.0, side: Side::Front }, 1.0);
/// assert_eq!((j.verdict, j.band), (Verdict::Right, Band::Clear));
/// assert!(j.outside.is_empty());
/// // The exit, claimed as the first crossing: the side and t are wrong.
/// let j = exact::judge(&case, &Claim::Sphere { t: 4.0, side: Side::Back }, 1.0);
/// assert_eq!((j.verdict, j.outside), (Verdict::Right, vec![Field::T, Field::Side]));
/// ```
///
/// ```
/// use rayhit::{Ray, Triangle, exact, glam::Vec3};
/// use rayhit::exact::{Band, Case, Claim, Verdict};
/// let tri = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
/// let ray = Ray::new(Vec3::new(0.25, 0.25, 1.0), Vec3::NEG_Z);
/// let case = Case::Triangle(ray, tri, f32::INFINITY);
/// let j = exact::judge(&case, &Claim::Triangle { t: 1.0, u: 0.25, v: 0.25 }, 2.0);
/// assert_eq!((j.verdict, j.band), (Verdict::Right, Band::Clear));
/// assert!(j.outside.is_empty());
/// let j = exact::judge(&case, &Claim::Miss, 2.0);
/// assert_eq!(j.verdict, Verdict::FalseMiss);
/// ```
#[must_use]
pub fn judge<V: Vector>(case: &Case<V>, claim: &Claim<V::Scalar>, bound_ulps: f64) -> Judgement {
    let one = oracle::ulp::<V::Scalar>(1.0);
    let mut errors = Vec::new();
    let exact_hit = match case {
        Case::Box(ray, b, t_max) => {
            let ex = super::ray_aabb(ray, b, *t_max);
            if let (Some(ex), Claim::Box { enter, exit }) = (&ex, claim) {
                errors.push((Field::Enter, rel_err(*enter, &ex.enter.value)));
                errors.push((Field::Exit, rel_err(*exit, &ex.exit.value)));
            }
            ex.is_some()
        }
        Case::Triangle(ray, tri, t_max) => {
            let ex = super::ray_triangle(ray, tri, *t_max);
            if let (Some(ex), Claim::Triangle { t, u, v }) = (&ex, claim) {
                let exact = [&ex.t.value, &ex.u.value, &ex.v.value];
                errors.extend(tuv_errors([*t, *u, *v], exact, one));
            }
            ex.is_some()
        }
        Case::Plane(ray, p, t_max) => {
            let ex = super::ray_plane(ray, p, *t_max);
            if let (Some(ex), Claim::Plane { t }) = (&ex, claim) {
                errors.push((Field::T, rel_err(*t, &ex.value)));
            }
            ex.is_some()
        }
        Case::Sphere(ray, s, t_max) => {
            let ex = super::sphere_first(ray, s, *t_max);
            if let (Some((e, h)), Claim::Sphere { t, side }) = (&ex, claim) {
                let err = e
                    .place(h.side)
                    .map_or(f64::INFINITY, |p| root_err(*t, h.t, p));
                errors.push((Field::T, err));
                errors.push(side_err(*side, h.side));
            }
            ex.is_some()
        }
        Case::Disc(ray, d, t_max) => {
            let ex = super::disc_first(ray, d, *t_max);
            if let (Some((e, h)), Claim::Disc { t, side }) = (&ex, claim) {
                errors.push((Field::T, rel_err(*t, &e.t)));
                errors.push(side_err(*side, h.side));
            }
            ex.is_some()
        }
        Case::Quad(ray, q, t_max) => {
            let ex = super::ray_quad(ray, q, *t_max);
            if let (Some(ex), Claim::Quad { t, u, v }) = (&ex, claim) {
                let exact = [&ex.t.value, &ex.u.value, &ex.v.value];
                errors.extend(tuv_errors([*t, *u, *v], exact, one));
            }
            ex.is_some()
        }
        Case::Patch(ray, p, t_max) => {
            let ex = super::patch_first(ray, p, *t_max);
            if let (Some((c, h)), Claim::Patch { t, u, v, side }) = (&ex, claim) {
                let (ct, cu, cv) = (&c.t, &c.u, &c.v);
                errors.push((Field::T, root_err(*t, h.t, |y| ct.cmp_rational(y))));
                errors.push((
                    Field::U,
                    root_err_in(*u, h.u, |y| cu.cmp_rational(y), Some(one)),
                ));
                errors.push((
                    Field::V,
                    root_err_in(*v, h.v, |y| cv.cmp_rational(y), Some(one)),
                ));
                errors.push(side_err(*side, h.side));
            }
            ex.is_some()
        }
    };
    if exact_hit && claim.is_hit() && errors.is_empty() {
        // A hit of the wrong kind.
        errors.push((Field::T, f64::INFINITY));
    }
    let verdict = match (claim.is_hit(), exact_hit) {
        (true, false) => Verdict::FalseHit,
        (false, true) => Verdict::FalseMiss,
        _ => Verdict::Right,
    };
    let band = band(case);
    // A sphere's or patch's Edge case holds no value to the bound, nor a
    // quad's whose two triangles are both crossed (see above).
    let held = band == Band::Clear
        || match case {
            Case::Sphere(..) | Case::Patch(..) => false,
            Case::Quad(ray, q, t_max) => q
                .triangles()
                .iter()
                .any(|tri| super::ray_triangle(ray, tri, *t_max).is_none()),
            _ => true,
        };
    let outside = errors
        .iter()
        .filter(|e| held && (!(e.1 <= bound_ulps) || (e.0 == Field::Side && e.1 > 0.0)))
        .map(|e| e.0)
        .collect();
    Judgement {
        verdict,
        band,
        distance_ulps: distance_ulps(case),
        errors,
        outside,
    }
}

/// Counts of judgements: right, false hits and misses (those on `Clear`
/// cases apart), the worst distance of a wrong answer from the boundary, the
/// worst `t` error of a right hit, and how many hits had a value outside
/// the bound.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Tally {
    /// Cases judged.
    pub cases: u64,
    /// Cases the exact answer hits.
    pub exact_hits: u64,
    /// False hits, all bands.
    pub false_hits: u64,
    /// False misses, all bands.
    pub false_misses: u64,
    /// False hits on `Clear` cases.
    pub clear_false_hits: u64,
    /// False misses on `Clear` cases.
    pub clear_false_misses: u64,
    /// The largest [`Judgement::distance_ulps`] of a false hit (0 if none).
    pub worst_false_hit_ulps: f64,
    /// The largest [`Judgement::distance_ulps`] of a false miss (0 if none).
    pub worst_false_miss_ulps: f64,
    /// The largest [`Judgement::worst_t_error`] of a right hit.
    pub worst_t_error: f64,
    /// Right hits with some value outside the bound.
    pub outside_bound: u64,
}

impl Tally {
    /// Counts one judgement.
    pub fn add(&mut self, j: &Judgement) {
        self.cases += 1;
        let clear = j.band == Band::Clear;
        match j.verdict {
            Verdict::Right => {}
            Verdict::FalseHit => {
                self.false_hits += 1;
                self.clear_false_hits += u64::from(clear);
                self.worst_false_hit_ulps = self.worst_false_hit_ulps.max(j.distance_ulps);
            }
            Verdict::FalseMiss => {
                self.false_misses += 1;
                self.clear_false_misses += u64::from(clear);
                self.worst_false_miss_ulps = self.worst_false_miss_ulps.max(j.distance_ulps);
            }
        }
        let exact_hit = matches!(j.verdict, Verdict::FalseMiss)
            || (j.verdict == Verdict::Right && !j.errors.is_empty());
        self.exact_hits += u64::from(exact_hit);
        self.worst_t_error = self.worst_t_error.max(j.worst_t_error());
        self.outside_bound += u64::from(!j.outside.is_empty());
    }

    /// True when anything counts against the kernel: a false hit or miss on
    /// a `Clear` case, or a value outside the bound.
    #[must_use]
    pub fn failed(&self) -> bool {
        self.clear_false_hits + self.clear_false_misses + self.outside_bound > 0
    }
}

impl fmt::Display for Tally {
    fn fmt(&self, out: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            out,
            "{:>8} cases | false hits {:>6} (clear {:>4}, worst {:.3e} ulps) | false misses {:>6} (clear {:>4}, worst {:.3e} ulps) | worst t error {:.3} ulps | over bound {}",
            self.cases,
            self.false_hits,
            self.clear_false_hits,
            self.worst_false_hit_ulps,
            self.false_misses,
            self.clear_false_misses,
            self.worst_false_miss_ulps,
            self.worst_t_error,
            self.outside_bound
        )
    }
}
