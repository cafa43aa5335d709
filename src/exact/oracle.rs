//! The exact building blocks, for writing exact checks of your own: the
//! exact value of a float ([`r`], [`rv`]), vector arithmetic on exact
//! values, the exact slab, triangle and plane computations with the
//! crate's conventions (`t` in units of the ray's direction, closed boxes
//! and triangles, the watertight test's tie rules), and the rounding bands
//! [`judge`](super::judge) uses to call a case [`Clear`](super::Band::Clear)
//! or [`Edge`](super::Band::Edge).
//!
//! Every value here is exact: a big rational computed from the floats' exact
//! values, with no rounding anywhere. The one rule for bad input: a float
//! that has no exact value (NaN, an infinity) gives `None`, as does a ray
//! whose direction is zero where a function needs it to move; predicates
//! (`*_clear`, `*_clear_watertight`, [`close`], `surely_outside*`,
//! `reciprocal_*`) answer `false` for such input (the filter
//! [`surely_outside_watertight_filter`] `Some(false)`), and
//! [`hit_point_disagreement`], which looks for trouble, counts it as a
//! disagreement. Nothing here panics.
//!
//! For whole answers with the kernels' conventions (validity, `t_max`,
//! rounding to a float) use the parent module's checked entry points,
//! [`ray_aabb`](super::ray_aabb), [`ray_triangle`](super::ray_triangle),
//! [`ray_plane`](super::ray_plane) and [`judge`](super::judge).
//!
//! ```
//! use rayhit::exact::oracle;
//! use rayhit::{Plane, Ray, Surface, glam::Vec3, ray_plane};
//!
//! let ray = Ray::new(Vec3::new(0.1, 0.2, 0.3), Vec3::new(0.3, 0.7, 1.1));
//! let plane = Plane::new(Vec3::new(0.0, 0.0, 5.0), Vec3::new(0.1, 0.2, 1.0));
//! let t = ray_plane(&ray, &plane, f32::INFINITY).unwrap();
//! // The kernel's t is within its documented bound of the exact crossing.
//! let exact_t = oracle::plane_t(&ray, &plane).unwrap();
//! assert!(oracle::close(t, &exact_t, plane.hit_error(&ray, &t)));
//! // Floats without an exact value give None, never a panic.
//! assert!(oracle::r(f32::NAN).is_none());
//! ```

use std::vec::Vec;

use std::cmp::Ordering;

use crate::{Aabb, BoxFace, Plane, Ray, Scalar, Triangle, TriangleHit, TriangleHitError, Vector};
use num_bigint::{BigInt, Sign};
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};

/// An exact rational.
pub type R = BigRational;
/// An exact 3-vector.
pub type R3 = [R; 3];

/// The exact value of a float (every finite float is a dyadic rational),
/// or `None` for NaN and the infinities.
#[must_use]
pub fn r<F: Scalar>(x: F) -> Option<R> {
    R::from_float(x.to_f64())
}

/// The exact value of a precision's constant (`TINY`, `UNIT_ROUNDOFF`: finite
/// by definition, so the conversion cannot fail).
fn constant<F: Scalar>(x: F) -> R {
    R::from_float(x.to_f64()).expect("the precision's constants are finite")
}

/// The exact components of a vector, or `None` when one is not finite.
#[must_use]
pub fn rv<V: Vector>(v: V) -> Option<R3> {
    Some([r(v.x())?, r(v.y())?, r(v.z())?])
}

/// `a - b`, exactly.
#[must_use]
pub fn sub(a: &R3, b: &R3) -> R3 {
    [&a[0] - &b[0], &a[1] - &b[1], &a[2] - &b[2]]
}

/// `a . b`, exactly.
#[must_use]
pub fn dot(a: &R3, b: &R3) -> R {
    &a[0] * &b[0] + &a[1] * &b[1] + &a[2] * &b[2]
}

/// `a x b`, exactly.
#[must_use]
pub fn cross(a: &R3, b: &R3) -> R3 {
    [
        &a[1] * &b[2] - &a[2] * &b[1],
        &a[2] * &b[0] - &a[0] * &b[2],
        &a[0] * &b[1] - &a[1] * &b[0],
    ]
}

/// `t_max` as an exact bound, `None` for no bound (`+inf`; also any other
/// non-finite value, which the checked entry points reject before they get
/// here).
#[must_use]
pub fn limit<F: Scalar>(t_max: F) -> Option<R> {
    r(t_max)
}

fn within(t: &R, t_max: &Option<R>) -> bool {
    t_max.as_ref().is_none_or(|m| t <= m)
}

/// An exact value as the nearest `f64` (for reports and for scales),
/// rounded to nearest, ties to even: a value beyond `f64`'s range saturates
/// to an infinity of its sign, one too small for it gives a subnormal or a
/// zero of its sign. Never NaN (`num-rational`'s conversion always answers
/// for a big rational; the NaN fallback is only there to keep this total).
#[must_use]
pub fn to_f64(x: &R) -> f64 {
    x.to_f64().unwrap_or(f64::NAN)
}

/// `|a - b|`, exactly (to compare against a bound given as a float: the
/// comparison is exact, because a float bound is itself exact).
#[must_use]
pub fn abs_diff(a: &R, b: &R) -> R {
    (a - b).abs()
}

/// True when a computed value is within `bound` of the exact one, decided
/// exactly: `|computed - exact| <= bound`. False when `computed` or `bound`
/// is not finite.
#[must_use]
pub fn close<F: Scalar>(computed: F, exact: &R, bound: F) -> bool {
    match (r(computed), r(bound)) {
        (Some(c), Some(b)) => abs_diff(&c, exact) <= b,
        _ => false,
    }
}

/// The exact origin and direction of a ray that moves: `None` when a
/// coordinate is not finite or the direction is zero.
fn moving<V: Vector>(ray: &Ray<V>) -> Option<(R3, R3)> {
    let (o, d) = (rv(ray.origin)?, rv(ray.dir)?);
    d.iter().any(|x| !x.is_zero()).then_some((o, d))
}

/// Exact ray/plane: the `t` where the ray's line crosses the plane (any
/// sign), or `None` when the ray is parallel to the plane (or the normal or
/// the direction is zero) or a coordinate is not finite.
#[must_use]
pub fn plane_t<V: Vector>(ray: &Ray<V>, plane: &Plane<V>) -> Option<R> {
    let n = rv(plane.normal)?;
    let den = dot(&rv(ray.dir)?, &n);
    if den.is_zero() {
        return None;
    }
    Some(dot(&sub(&rv(plane.point)?, &rv(ray.origin)?), &n) / den)
}

/// Exact ray/plane answer with the kernel's conventions: the crossing `t`
/// when `0 < t <= t_max`, else `None` (as for [`plane_t`]).
#[must_use]
pub fn plane_hit<V: Vector>(ray: &Ray<V>, plane: &Plane<V>, t_max: V::Scalar) -> Option<R> {
    let t = plane_t(ray, plane)?;
    (t.is_positive() && within(&t, &limit(t_max))).then_some(t)
}

/// The exact slab distances of the ray for every axis it moves along:
/// `(near, far, axis)`, or `None` when an axis it does not move along
/// already excludes it (a miss that no rounding of the other axes can
/// change), when the ray does not move, or when a coordinate is not finite.
#[must_use]
pub fn box_slabs<V: Vector>(ray: &Ray<V>, b: &Aabb<V>) -> Option<Vec<(R, R, usize)>> {
    let (o, d) = moving(ray)?;
    let (lo, hi) = (rv(b.min)?, rv(b.max)?);
    let mut slabs = Vec::new();
    for k in 0..3 {
        if d[k].is_zero() {
            if o[k] < lo[k] || o[k] > hi[k] {
                return None;
            }
            continue;
        }
        let t0 = (&lo[k] - &o[k]) / &d[k];
        let t1 = (&hi[k] - &o[k]) / &d[k];
        slabs.push(if t0 <= t1 { (t0, t1, k) } else { (t1, t0, k) });
    }
    Some(slabs)
}

/// The exact `(enter, exit)` of the ray against the closed box, clipped to
/// `[0, t_max]`, whether or not it is empty (`enter > exit` is a miss by
/// that much), or `None` as for [`box_slabs`].
#[must_use]
pub fn box_raw<V: Vector>(ray: &Ray<V>, b: &Aabb<V>, t_max: V::Scalar) -> Option<(R, R)> {
    let slabs = box_slabs(ray, b)?;
    let enter = slabs.iter().map(|s| s.0.clone()).chain([R::zero()]).max()?;
    let exit = slabs
        .iter()
        .map(|s| s.1.clone())
        .chain(limit(t_max))
        .min()?;
    Some((enter, exit))
}

/// How far (in space, along one axis) a ray passes from a box that it
/// misses, or how deep it goes into one it hits, exactly: the gap between
/// entry and exit in `t` times the speed along the axis that sets the entry
/// (at the exit time the ray is that far outside along it) or the exit
/// (likewise at the entry time), whichever is smaller. `t = 0` and `t_max`
/// count as limits with no axis, and contribute only through the other side.
/// `None` as for [`box_slabs`].
#[must_use]
pub fn box_gap<V: Vector>(ray: &Ray<V>, b: &Aabb<V>, t_max: V::Scalar) -> Option<R> {
    let slabs = box_slabs(ray, b)?;
    let d = rv(ray.dir)?;
    let (enter, exit) = box_raw(ray, b, t_max)?;
    // The axes whose near (far) distance is the entry (exit), if any.
    let by_enter = slabs.iter().filter(|s| s.0 == enter).map(|s| d[s.2].abs());
    let by_exit = slabs.iter().filter(|s| s.1 == exit).map(|s| d[s.2].abs());
    let speed = by_enter.chain(by_exit).min()?;
    Some((enter - exit).abs() * speed)
}

/// How unambiguous the faces that set the entry and the exit are: the gap
/// between the exact entry and the next largest lower limit (another axis's
/// near distance, or 0), and likewise between the exit and the next
/// smallest upper limit (`10^6` when there is none: one moving axis and no
/// `t_max`). Near an edge one of them is small and a kernel may take either
/// face. `None` as for [`box_slabs`].
#[must_use]
pub fn box_face_margins<V: Vector>(ray: &Ray<V>, b: &Aabb<V>, t_max: V::Scalar) -> Option<(R, R)> {
    let slabs = box_slabs(ray, b)?;
    let mut nears: Vec<R> = slabs
        .iter()
        .map(|s| s.0.clone())
        .chain([R::zero()])
        .collect();
    let mut fars: Vec<R> = slabs
        .iter()
        .map(|s| s.1.clone())
        .chain(limit(t_max))
        .collect();
    nears.sort();
    fars.sort();
    let gap = |v: &[R], i: usize, j: usize| {
        v.get(j)
            .map_or_else(|| R::from_integer(1_000_000.into()), |x| (x - &v[i]).abs())
    };
    // The ray moves along some axis, so there is a slab besides the 0.
    let n = nears.len();
    Some((gap(&nears, n - 1, n - 2), gap(&fars, 0, 1)))
}

/// The exact entry face: the face of the largest positive entry-plane
/// distance, the lowest axis on a tie, `None` inside when no entry plane is
/// ahead; and whether it was a tie. `None` when a coordinate is not finite.
#[must_use]
pub fn box_face<V: Vector>(ray: &Ray<V>, b: &Aabb<V>) -> Option<(Option<BoxFace>, bool)> {
    let (o, d, lo, hi) = (rv(ray.origin)?, rv(ray.dir)?, rv(b.min)?, rv(b.max)?);
    let mut best: Option<(usize, R)> = None;
    let mut tie = false;
    for k in 0..3 {
        if d[k].is_zero() {
            continue;
        }
        let plane = if d[k] > R::zero() { &lo[k] } else { &hi[k] };
        let t = (plane - &o[k]) / &d[k];
        if t <= R::zero() {
            continue;
        }
        match &best {
            Some((_, bt)) if t.cmp(bt) == Ordering::Equal => tie = true,
            Some((_, bt)) if t < *bt => {}
            _ => {
                best = Some((k, t));
                tie = false;
            }
        }
    }
    Some((
        best.and_then(|(k, _)| BoxFace::new(k, d[k] < R::zero())),
        tie,
    ))
}

/// Where the ray passes the segment of a zero-area triangle, exactly: in
/// the ray's sheared frame (main axis the direction's largest component,
/// the kernel's tie rule; `x`, `y` the next two cyclically), the depth of
/// the point of the segment between the two corners farthest apart nearest
/// the ray, clamped to the segment. `None` when the ray does not move, a
/// coordinate is not finite, or the segment is seen end-on (its two
/// corners at one point of the frame).
#[must_use]
pub fn segment_crossing<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>) -> Option<R> {
    let k = main_axis(ray.dir);
    let (kx, ky) = ((k + 1) % 3, (k + 2) % 3);
    let (o, dir) = moving(ray)?;
    let corners = [rv(tri.a)?, rv(tri.b)?, rv(tri.c)?];
    let dist2 = |i: usize, j: usize| {
        let e = sub(&corners[j], &corners[i]);
        dot(&e, &e)
    };
    let (mut i, mut j) = (0, 1);
    for (a, b) in [(1, 2), (2, 0)] {
        if dist2(a, b) > dist2(i, j) {
            (i, j) = (a, b);
        }
    }
    // `dir[k]` is the largest component of a nonzero direction: not zero.
    let frame = |w: &[R; 3]| -> [R; 3] {
        let w = sub(w, &o);
        let z = &w[k] / &dir[k];
        [&w[kx] - &dir[kx] * &z, &w[ky] - &dir[ky] * &z, z]
    };
    let (p, q) = (frame(&corners[i]), frame(&corners[j]));
    let (ex, ey) = (&q[0] - &p[0], &q[1] - &p[1]);
    let den = &ex * &ex + &ey * &ey;
    if den.is_zero() {
        return None;
    }
    let s = -(&p[0] * &ex + &p[1] * &ey) / den;
    let (zero, one) = (R::zero(), int(1));
    let s = if s < zero {
        zero
    } else if s > one {
        one
    } else {
        s
    };
    Some(&p[2] + s * (&q[2] - &p[2]))
}

/// Exact interval `[enter, exit]` of `t` in `[0, t_max]` with the ray inside
/// the closed box, or `None` when it is empty (or as for [`box_slabs`]).
#[must_use]
pub fn box_interval<V: Vector>(ray: &Ray<V>, b: &Aabb<V>, t_max: V::Scalar) -> Option<(R, R)> {
    box_raw(ray, b, t_max).filter(|(e, x)| e <= x)
}

/// The exact answer for a ray against a triangle (two-sided, closed).
#[derive(Debug, Clone)]
pub struct ExactTriangle {
    /// Orientation of the ray's line against each edge (`a->b`, `b->c`,
    /// `c->a`): the sign of the Plucker product `((p - o) x (q - o)) . d`.
    pub signs: [Ordering; 3],
    /// The line's crossing with the plane, when not parallel.
    pub t: Option<R>,
    /// Barycentric weights of `b` and `c` at the crossing.
    pub uv: Option<(R, R)>,
}

impl ExactTriangle {
    /// The line passes through the closed triangle (not parallel to it).
    #[must_use]
    pub fn line_hits(&self) -> bool {
        self.t.is_some()
            && !(self.signs.contains(&Ordering::Less) && self.signs.contains(&Ordering::Greater))
    }

    /// The kernel's question: the closed triangle is crossed at `0 < t <= t_max`.
    #[must_use]
    pub fn hits(&self, t_max: &Option<R>) -> bool {
        self.line_hits()
            && self
                .t
                .as_ref()
                .is_some_and(|t| t.is_positive() && within(t, t_max))
    }

    /// The line crosses the triangle's interior (no edge product is zero).
    #[must_use]
    pub fn interior(&self) -> bool {
        self.line_hits() && !self.signs.contains(&Ordering::Equal)
    }
}

/// Exact ray/triangle: signs of the three edge Plucker products, the plane
/// crossing `t` and the barycentrics `(u, v)` there; `None` when a
/// coordinate is not finite.
///
/// Computed in integers: every float is `m 2^e` with an integer `m`, so
/// with `E` the smallest exponent among the origin's and corners'
/// coordinates and `F` among the direction's, the coordinates are the
/// integers `x 2^-E` (`d 2^-F`) and every product and sum below is an
/// integer; only the three quotients are reduced (one greatest common
/// divisor each, not one per operation). The values are those of the
/// rational formulas, exactly.
#[must_use]
pub fn triangle<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>) -> Option<ExactTriangle> {
    let w = |p: V| [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()];
    let points = [w(ray.origin), w(tri.a), w(tri.b), w(tri.c)];
    let dir = w(ray.dir);
    if !points.iter().chain([&dir]).flatten().all(|x| x.is_finite()) {
        return None;
    }
    let (pts, e) = integers(points);
    let ([d], f) = integers([dir]);
    let [o, a, b, c] = pts;
    let (a, b, c) = (isub(&a, &o), isub(&b, &o), isub(&c, &o));
    let s_ab = idot(&icross(&a, &b), &d);
    let s_bc = idot(&icross(&b, &c), &d);
    let s_ca = idot(&icross(&c, &a), &d);
    let signs = [&s_ab, &s_bc, &s_ca].map(|x| x.sign().cmp(&Sign::NoSign));
    // The three in units of 2^(2E + F), so their sum, `d . n` with `n =
    // (b - a) x (c - a)`, too.
    let sum = &s_ab + &s_bc + &s_ca;
    if sum.is_zero() {
        return Some(ExactTriangle {
            signs,
            t: None,
            uv: None,
        });
    }
    // The weight of each corner is the product of the edge opposite it, and
    // the sum of the three is `d . n`.
    let u = R::new(s_ca, sum.clone());
    let v = R::new(s_ab, sum.clone());
    // `t = (a . n) / (d . n)`: `a . n` in units of `2^3E`, so `t` is the
    // integers' quotient times `2^(E - F)`.
    let n = icross(&isub(&b, &a), &isub(&c, &a));
    let num = idot(&a, &n);
    let shift = e - f;
    let t = if shift >= 0 {
        R::new(num << shift.unsigned_abs(), sum)
    } else {
        R::new(num, sum << shift.unsigned_abs())
    };
    Some(ExactTriangle {
        signs,
        t: Some(t),
        uv: Some((u, v)),
    })
}

/// An integer 3-vector.
type I3 = [BigInt; 3];

/// Finite floats as integers of one scale: `(x 2^-E, E)` with `E` the
/// smallest exponent `e` of the nonzero values written `m 2^e` with an odd
/// integer `m` (0 when all are zero).
fn integers<const N: usize>(points: [[f64; 3]; N]) -> ([I3; N], i64) {
    let parts = points.map(|p| p.map(odd_parts));
    let e = parts
        .iter()
        .flatten()
        .filter(|(m, _)| *m != 0)
        .map(|&(_, e)| e)
        .min()
        .unwrap_or(0);
    let scaled = parts.map(|p| p.map(|(m, x)| BigInt::from(m) << (x - e).unsigned_abs()));
    (scaled, e)
}

/// A finite float as `(m, e)` with `x = m 2^e` and `m` odd, or `(0, 0)`:
/// num-traits' `integer_decode` with the mantissa's trailing zeros moved
/// into the exponent.
fn odd_parts(x: f64) -> (i64, i64) {
    use num_traits::float::FloatCore;
    let (m, e, sign) = x.integer_decode();
    if m == 0 {
        return (0, 0);
    }
    let zeros = m.trailing_zeros();
    // `m < 2^53`: it fits.
    let m = (m >> zeros) as i64;
    (i64::from(sign) * m, i64::from(e) + i64::from(zeros))
}

fn isub(a: &I3, b: &I3) -> I3 {
    [&a[0] - &b[0], &a[1] - &b[1], &a[2] - &b[2]]
}

fn idot(a: &I3, b: &I3) -> BigInt {
    &a[0] * &b[0] + &a[1] * &b[1] + &a[2] * &b[2]
}

fn icross(a: &I3, b: &I3) -> I3 {
    [
        &a[1] * &b[2] - &a[2] * &b[1],
        &a[2] * &b[0] - &a[0] * &b[2],
        &a[0] * &b[1] - &a[1] * &b[0],
    ]
}

/// An exact dyadic rational `m * 2^e` as an `R` (for building inputs). Any
/// `e` works; the value takes about `|e|` bits.
#[must_use]
pub fn dyadic(m: i64, e: i32) -> R {
    let power = BigInt::from(1) << e.unsigned_abs();
    if e >= 0 {
        R::from_integer(BigInt::from(m) * power)
    } else {
        R::new(BigInt::from(m), power)
    }
}

/// The spacing of floats of precision `F` at magnitude `m` (one ulp), as
/// `f64`: `|m|` is rounded to `F`, and the answer is the gap from there to
/// the next float up, at least the smallest subnormal. At the largest finite
/// float the next one up is the infinity, so the gap is infinite; a
/// magnitude beyond `F`'s range (and NaN) has no next float and gives the
/// smallest subnormal.
#[must_use]
pub fn ulp<F: Scalar>(m: f64) -> f64 {
    let x = F::from_f64(m.abs());
    (x.next_up().to_f64() - x.to_f64()).max(F::TINY.to_f64())
}

/// `gamma(n) = n u / (1 - n u)` for precision `F` (`u` its unit roundoff),
/// exactly: the bound on the relative error of `n` roundings (Higham,
/// Accuracy and Stability of Numerical Algorithms, 2002, section 3.1).
/// Defined for every `n` the type admits: `n u <= 65535 * 2^-24 < 1` (the
/// formula needs `n u < 1`).
#[must_use]
pub fn gamma<F: Scalar>(n: u16) -> R {
    let nu = int(n.into()) * constant(F::UNIT_ROUNDOFF);
    &nu / (int(1) - &nu)
}

/// An exact integer.
#[must_use]
pub fn int(n: i64) -> R {
    R::from_integer(n.into())
}

/// `|x|`.
#[must_use]
pub fn abs(x: &R) -> R {
    x.abs()
}

/// Error bounds of Moller-Trumbore's `u`, `v` and `t`, for the agreement band.
///
/// MT computes `u = (s . p)/det`, `v = (d . q)/det`, `t = (e2 . q)/det` with
/// `s = o - a`, `p = d x e2`, `q = s x e1`, `e1 = b - a`, `e2 = c - a`. Each
/// numerator and `det` is a sum of triple products whose monomials carry at
/// most 7 roundings (two subtractions, a product, a difference, a product,
/// two sums), so each is within `gamma(7)` times the sum of the monomials'
/// magnitudes `M`. A quotient `N/D` computed as `fl(N) fl(1/det)` is then
/// within `(dN + |q| dD)/(|D| - dD) + gamma(2)|q|`, which is what this
/// returns (with `q` the exact quotient), or `2^2000` when `dD >= |D|`.
/// `None` when a coordinate is not finite.
#[must_use]
pub fn mt_bounds<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>, u: &R, v: &R) -> Option<(R, R, R)> {
    let (o, d) = (rv(ray.origin)?, rv(ray.dir)?);
    let (a, b, c) = (rv(tri.a)?, rv(tri.b)?, rv(tri.c)?);
    let (e1, e2, s) = (sub(&b, &a), sub(&c, &a), sub(&o, &a));
    let mag = |x: &[R; 3], y: &[R; 3], z: &[R; 3]| -> R {
        // sum_i |x_i| (|y_j z_k| + |y_k z_j|): the monomials of x . (y x z).
        (0..3)
            .map(|i| {
                let (j, k) = ((i + 1) % 3, (i + 2) % 3);
                abs(&x[i]) * (abs(&(&y[j] * &z[k])) + abs(&(&y[k] * &z[j])))
            })
            .sum()
    };
    let g7 = gamma::<V::Scalar>(7);
    let det = dot(&e1, &cross(&d, &e2));
    let d_det = &g7 * mag(&e1, &d, &e2);
    // Above any bound in either precision (f64's largest is below 2^1024).
    let big = dyadic(1, 2000);
    if abs(&det) <= d_det {
        return Some((big.clone(), big.clone(), big));
    }
    let q = cross(&s, &e1);
    let t = dot(&e2, &q) / &det;
    let g2 = gamma::<V::Scalar>(2);
    let quotient = |dn: R, q: &R| (dn + abs(q) * &d_det) / (abs(&det) - &d_det) + &g2 * abs(q);
    Some((
        quotient(&g7 * mag(&s, &d, &e2), u),
        quotient(&g7 * mag(&d, &s, &e1), v),
        quotient(&g7 * mag(&e2, &s, &e1), &t),
    ))
}

/// What the watertight test must answer on `ray` and `tri` with limit
/// `t_max`, when exact arithmetic decides it outside the test's rounding
/// band: `Some(hit)`, or `None` inside the band (and for a line parallel to
/// the triangle's plane). `extra` widens the band by another kernel's
/// `(u, v, t)` bounds (Moller-Trumbore's, from [`mt_bounds`]), or zeros.
/// `None` also where a bound is not finite, and for an invalid ray or a
/// corner that is not finite.
///
/// The band is the watertight test's documented error bound
/// ([`Triangle`'s `hit_error`](crate::Triangle#method.hit_error), held
/// to exact arithmetic by the crate's tests) evaluated at the exact crossing:
/// the edge weight `w = 1 - u - v` gets `err_u + err_v`, and for `t` the
/// conservative `t > 0` test's band. That test accepts a hit only if its
/// computed `t` exceeds `T(t)`, the `t` bound evaluated at that `t` (or a
/// cheaper sufficient test passes). If it rejects, `t <= T(t)` and
/// `|t - t*| <= T(t)`, so `t* <= 2 T(t)`. `T` depends on `t` only through
/// the spread `sum |z_i - t|`, with sensitivity at most `err_u` (the edge
/// error over the determinant's lower bound), so
/// `T(t) <= T(t*) + 3 |t - t*| err_u`, and `T(t) <= T(t*) / (1 - 3 err_u)`.
/// A rejection thus needs `t* <= 2 T(t*) / (1 - 3 max(err_u, err_v))`.
#[must_use]
pub fn triangle_decided<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    exact: &ExactTriangle,
    t_max: V::Scalar,
    extra: &(R, R, R),
) -> Option<bool> {
    let corners_finite = [tri.a, tri.b, tri.c].iter().all(|c| c.is_finite());
    if !(ray.is_valid() && corners_finite) {
        return None;
    }
    let (te, (ue, ve)) = (exact.t.as_ref()?, exact.uv.as_ref()?);
    let as_s = |x: &R| V::Scalar::from_f64(to_f64(x));
    let probe = TriangleHit {
        t: as_s(te),
        u: as_s(ue),
        v: as_s(ve),
        side: crate::Side::Front,
    };
    let err = crate::Surface::hit_error(tri, ray, &probe);
    if !(err.u.is_finite() && err.v.is_finite() && err.t.is_finite()) {
        return None;
    }
    let (err_u, err_v, err_t) = (r(err.u)?, r(err.v)?, r(err.t)?);
    let e_max = if err_u > err_v { &err_u } else { &err_v };
    if int(3) * e_max >= int(1) {
        return None;
    }
    let t_band = int(2) * err_t / (int(1) - int(3) * e_max);
    let (eu, ev, et) = (err_u + &extra.0, err_v + &extra.1, t_band + &extra.2);
    let we = &eu + &ev;
    let w = int(1) - ue - ve;
    let inside = ue > &eu && ve > &ev && w > we;
    let outside = ue < &-eu.clone() || ve < &-ev.clone() || w < -we;
    let limit = limit(t_max);
    let t_clear = (te > &et && limit.as_ref().is_none_or(|m| (m - te) > et)) || te < &-et;
    ((inside || outside) && t_clear)
        .then(|| inside && te > &int(0) && limit.as_ref().is_none_or(|m| te <= m))
}

/// No widening: the zeros for [`triangle_decided`]'s `extra`.
#[must_use]
pub fn no_extra() -> (R, R, R) {
    (int(0), int(0), int(0))
}

/// Where a triangle hit's barycentric point and `ray.at(t)` disagree by
/// more than their bounds allow, the first such axis; `None` when they
/// agree.
///
/// Both are within their errors of the exact crossing `p*`: from the
/// reported `u`, `v`, `|p_bary_j - p*_j| <= err_u |b_j - a_j| + err_v |c_j -
/// a_j|` (exactly, from the reported barycentrics); `ray.at(t)` adds
/// `|t - t*| |d_j|` and its own two roundings, `gamma(2) (|o_j| + |t d_j|)`.
///
/// A hit must be safe to use, so anything not finite (the inputs, the hit,
/// its bounds, `ray.at(t)`) counts as a disagreement, on axis 0.
#[must_use]
pub fn hit_point_disagreement<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    h: &TriangleHit<V::Scalar>,
    err: &TriangleHitError<V::Scalar>,
) -> Option<usize> {
    let exact = || {
        Some((
            [rv(tri.a)?, rv(tri.b)?, rv(tri.c)?],
            [rv(ray.origin)?, rv(ray.dir)?, rv(ray.at(h.t))?],
            [r(h.u)?, r(h.v)?, r(h.t)?],
            [r(err.u)?, r(err.v)?, r(err.t)?],
        ))
    };
    let Some(([a, b, c], [o, d, p], [u, v, t], [eu, ev, et])) = exact() else {
        return Some(0);
    };
    let g2 = gamma::<V::Scalar>(2);
    (0..3).find(|&j| {
        let bary = &a[j] + &u * (&b[j] - &a[j]) + &v * (&c[j] - &a[j]);
        let bound = &eu * abs(&(&b[j] - &a[j]))
            + &ev * abs(&(&c[j] - &a[j]))
            + &et * abs(&d[j])
            + &g2 * (abs(&o[j]) + &t * abs(&d[j]));
        abs(&(&bary - &p[j])) > bound
    })
}

/// True when some nonzero direction component is so small that its
/// reciprocal overflows (`|d_i| < 1/MAX`): the slab test's exit is then only
/// an upper bound, not within its relative band (see `ray_aabb`). False
/// when a component is not finite.
#[must_use]
pub fn reciprocal_overflows<V: Vector>(dir: V) -> bool {
    dir.is_finite()
        && [dir.x(), dir.y(), dir.z()]
            .into_iter()
            .any(|d| d != V::Scalar::ZERO && !(V::Scalar::ONE / d).is_finite())
}

/// True when some direction component is so large that its reciprocal is
/// subnormal (`|d_i| > 2^126` in `f32`, `2^1022` in `f64`): the slab test's
/// false-hit band is then `40u` instead of `16u` (see `ray_aabb`). False
/// when a component is not finite.
#[must_use]
pub fn reciprocal_subnormal<V: Vector>(dir: V) -> bool {
    dir.is_finite()
        && [dir.x(), dir.y(), dir.z()]
            .into_iter()
            .any(|d| d != V::Scalar::ZERO && (V::Scalar::ONE / d).abs() < V::Scalar::MIN_POSITIVE)
}

/// True when no nonzero direction component is subnormal (where the slab
/// test's bands stop being relative).
fn dir_normal<V: Vector>(dir: V) -> bool {
    [dir.x(), dir.y(), dir.z()]
        .into_iter()
        .all(|d| d == V::Scalar::ZERO || d.abs() >= V::Scalar::MIN_POSITIVE)
}

/// The box case is outside the slab test's rounding band: the exact
/// interval is more than `32u` (relative to the larger of entry and exit;
/// `80u` where a direction component's reciprocal is subnormal, twice the
/// test's `40u` there) plus four subnormals over the slowest moving
/// direction component from empty, or an axis the ray does not move along
/// rules it out; and no nonzero direction component is subnormal. False for
/// an invalid ray or box (the kernels' answer to those is a miss by rule,
/// not by arithmetic).
#[must_use]
pub fn box_clear<V: Vector>(ray: &Ray<V>, b: &Aabb<V>, t_max: V::Scalar) -> bool {
    let dmin = [ray.dir.x(), ray.dir.y(), ray.dir.z()]
        .into_iter()
        .filter(|d| *d != V::Scalar::ZERO)
        .filter_map(|d| r(d.abs()))
        .min();
    let Some(dmin) = dmin.filter(|_| ray.is_valid() && b.is_valid()) else {
        return false;
    };
    dir_normal(ray.dir)
        && match box_raw(ray, b, t_max) {
            None => true,
            Some((e, x)) => {
                let scale = if e.abs() > x.abs() { e.abs() } else { x.abs() };
                let absolute = constant(V::Scalar::TINY) * int(4) / dmin;
                let k = if reciprocal_subnormal(ray.dir) {
                    80
                } else {
                    32
                };
                (x - e).abs() > int(k) * constant(V::Scalar::UNIT_ROUNDOFF) * scale + absolute
            }
        }
}

/// The triangle case is decided outside the watertight test's rounding band
/// widened by Moller-Trumbore's: [`triangle_decided`] with [`mt_bounds`], or
/// a line that crosses the plane outside the triangle by more than both
/// tests' rounding ([`surely_outside`]). A line parallel to the plane, or a
/// triangle of zero area, is never clear: a determinant that is zero in exact
/// arithmetic can round to either sign, and Moller-Trumbore's `u`, `v` and
/// `t` are then unbounded. False when a coordinate is not finite.
#[must_use]
pub fn triangle_clear<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>, t_max: V::Scalar) -> bool {
    let Some(ex) = triangle(ray, tri) else {
        return false;
    };
    let Some((ue, ve)) = &ex.uv else {
        return false;
    };
    let Some(mte) = mt_bounds(ray, tri, ue, ve) else {
        return false;
    };
    triangle_decided(ray, tri, &ex, t_max, &mte).is_some() || surely_outside(ray, tri, &ex, &mte)
}

/// Every watertight test and Moller-Trumbore miss: the line crosses the
/// plane outside the triangle by more than either's rounding.
///
/// - Watertight ([`surely_outside_watertight`]): two exact Plucker
///   products `s_i`, `s_j` of opposite signs, each larger than `|d_z|`
///   times the bound on the test's computed edge functions' error
///   ([`edge_function_bound`]; the exact edge functions are `s_i / d_z`, up
///   to one shared sign): the computed ones then have opposite strict signs
///   too, and the test rejects on the signs alone, whatever `t`.
/// - Moller-Trumbore (bounds `eu`, `ev` from [`mt_bounds`]): `u < -eu` or
///   `v < -ev` makes the computed one negative; `1 - u - v < -(eu + ev) - 2
///   unit` makes the computed sum exceed `1 + 2 unit`, so its rounding still
///   exceeds 1.
///
/// False when a coordinate is not finite.
#[must_use]
pub fn surely_outside<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    exact: &ExactTriangle,
    mt: &(R, R, R),
) -> bool {
    let Some((ue, ve)) = &exact.uv else {
        return false;
    };
    let (eu, ev) = (&mt.0, &mt.1);
    let w = int(1) - ue - ve;
    let slack = int(2) * constant(V::Scalar::UNIT_ROUNDOFF);
    let mt_outside = ue < &-eu.clone() || ve < &-ev.clone() || w < -(eu + ev + slack);
    mt_outside && surely_outside_watertight(ray, tri)
}

/// Every form of the watertight test misses, on the signs of its edge
/// functions alone: two exact Plucker products `s_i = ((p_i - o) x (p_j -
/// o)) . d` (edges `a->b`, `b->c`, `c->a`) have opposite signs and are each
/// larger in magnitude than the margin `de |d_z|` ([`edge_function_bound`]).
/// Decided by [`surely_outside_watertight_filter`] in floating point where
/// it can (nearly always), else in exact arithmetic; the answer is the
/// exact one either way.
///
/// Why it is sound: in the ray's sheared frame the exact edge functions are
/// `s_i / d_z` (all with one shared sign flip when `d_z < 0`), and the
/// test's computed ones are within `de` of them. So an `s_i > de |d_z|`
/// and an `s_j < -de |d_z|` give two computed edge functions of opposite
/// strict signs, which every edge rule (closed, and the one-hit rule,
/// which only decides exact zeros) rejects before anything else is looked
/// at: whatever `t`, the interval, or whether the line is parallel to the
/// plane or the triangle has zero area. The exact line misses the triangle
/// too (its edge products have mixed signs), so the kernels' miss is the
/// exact answer. This is the watertight half of [`surely_outside`],
/// without Moller-Trumbore's condition.
///
/// False when a coordinate is not finite, the direction is zero, or the
/// computed frame overflows.
#[must_use]
pub fn surely_outside_watertight<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>) -> bool {
    surely_outside_watertight_filter(ray, tri)
        .unwrap_or_else(|| surely_outside_watertight_exact(ray, tri))
}

/// [`surely_outside_watertight`] in exact arithmetic throughout.
fn surely_outside_watertight_exact<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>) -> bool {
    let Some(margin) = edge_function_bound(ray, tri).map(|(de, dz)| de * dz) else {
        return false;
    };
    let exact = || {
        Some((
            rv(ray.origin)?,
            rv(ray.dir)?,
            [rv(tri.a)?, rv(tri.b)?, rv(tri.c)?],
        ))
    };
    let Some((o, d, corners)) = exact() else {
        return false;
    };
    let p = corners.map(|c| sub(&c, &o));
    let s = [(0, 1), (1, 2), (2, 0)].map(|(i, j)| dot(&cross(&p[i], &p[j]), &d));
    s.iter().any(|x| x > &margin) && s.iter().any(|x| x < &-margin.clone())
}

/// [`surely_outside_watertight`] decided without rationals: `Some(answer)`
/// where floating-point arithmetic decides it (the exact answer), `None`
/// where it cannot (a product within a few `f64` roundings of the margin,
/// inputs beyond `2^±300` in `f64`, an overflow). A filter to run before
/// exact arithmetic: a few dozen float operations per triangle where the
/// line passes it by more than a few roundings, a few hundred (exact
/// expansions) where it passes near an edge or corner.
///
/// What it computes, from the inputs' exact values as `f64` (every `f32`
/// and `f64` is one):
///
/// - the margin `M = de |d_z|` of [`edge_function_bound`] twice, every
///   operation rounded upwards for `M_up >= M` and downwards (and not below
///   zero) for `M_lo <= M` (see `EdgeFrame::margin`);
/// - each Plucker product `s_i` in `f64`, with a bound `err_i` on its error
///   (derived at `plucker_f64`), so the exact one is in `[s_i - err_i, s_i
///   + err_i]` (both ends rounded outwards);
///
/// and places each exact product against `M` and `-M`: beyond `M` where
/// its range is above `M_up`, not beyond where it is at or below `M_lo`;
/// where the range straddles them, the product's exact sign against
/// `M_up` and `M_lo` decides instead (an exact expansion of the product,
/// `PluckerProduct` in `crate::num::exact_sign`, exact for nonzero inputs
/// within `2^±300`, every `f32` included), and only a product strictly
/// between `M_lo` and `M_up` stays unknown. The answer is "some product
/// beyond `M` and some beyond `-M`" in three-valued logic: `Some` wherever
/// the known places settle it. Inputs that are not finite, a zero
/// direction or an overflowing frame give `Some(false)`, as in exact
/// arithmetic.
#[must_use]
pub fn surely_outside_watertight_filter<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
) -> Option<bool> {
    filter(ray, tri, true)
}

/// [`surely_outside_watertight_filter`], with the exact expansions or (for
/// the tests) with the error bounds alone.
fn filter<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>, expansions: bool) -> Option<bool> {
    let Some(frame) = EdgeFrame::new(ray, tri) else {
        return Some(false);
    };
    let (lo, up) = (frame.margin(false), frame.margin(true));
    if !(lo.is_finite() && up.is_finite()) {
        return None;
    }
    let w = |p: V| [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()];
    let (o, d, corners) = (w(ray.origin), w(ray.dir), [w(tri.a), w(tri.b), w(tri.c)]);
    let mut products = PluckerProducts {
        o,
        d,
        corners,
        float: plucker_f64(o, d, corners),
        exact: [None, None, None],
        expansions,
    };
    let mut beyond = |sign: f64| {
        let mut unknown = false;
        for i in 0..3 {
            match products.beyond(i, sign, (lo, up)) {
                Some(true) => return Some(true),
                Some(false) => {}
                None => unknown = true,
            }
        }
        (!unknown).then_some(false)
    };
    match beyond(1.0) {
        Some(false) => Some(false),
        above => match (above, beyond(-1.0)) {
            (_, Some(false)) => Some(false),
            (Some(true), Some(true)) => Some(true),
            _ => None,
        },
    }
}

/// The three Plucker products of [`surely_outside_watertight_filter`]: in
/// `f64` with error bounds, and exactly where those do not decide
/// (computed once, when first needed).
struct PluckerProducts {
    o: [f64; 3],
    d: [f64; 3],
    corners: [[f64; 3]; 3],
    float: [(f64, f64); 3],
    exact: [Option<Option<crate::num::exact_sign::PluckerProduct>>; 3],
    /// Whether to fall back on the exact expansions.
    expansions: bool,
}

impl PluckerProducts {
    /// Whether `sign s_i` (`sign` is 1 or -1) is above the margin, given
    /// as `(M_lo, M_up)`: `Some(true)` above `M_up`, `Some(false)` at most
    /// `M_lo`, `None` unknown.
    fn beyond(&mut self, i: usize, sign: f64, (lo, up): (f64, f64)) -> Option<bool> {
        use crate::num::round::outward::{add_up, sub_down};
        use core::cmp::Ordering;
        let (s, err) = self.float[i];
        if s.is_finite() && err.is_finite() {
            let (low, high) = (sub_down(sign * s, err), add_up(sign * s, err));
            if low > up {
                return Some(true);
            }
            if high <= lo {
                return Some(false);
            }
        }
        if !self.expansions {
            return None;
        }
        let (o, d, c) = (self.o, self.d, self.corners);
        let (p, q) = [(0, 1), (1, 2), (2, 0)][i];
        let exact = self.exact[i]
            .get_or_insert_with(|| crate::num::exact_sign::PluckerProduct::new(o, d, c[p], c[q]))
            .as_ref()?;
        // `sign s_i > m` is `s_i > m` for sign 1, `s_i < -m` for sign -1.
        let beyond = if sign > 0.0 {
            Ordering::Greater
        } else {
            Ordering::Less
        };
        if exact.cmp(sign * up)? == beyond {
            Some(true)
        } else if exact.cmp(sign * lo)? != beyond {
            Some(false)
        } else {
            None
        }
    }
}

/// The three Plucker products `s_i = ((p_i - o) x (p_j - o)) . d` of the
/// edges `a->b`, `b->c`, `c->a`, computed in `f64`, each with an upper
/// bound on its error: `(s_i, err_i)` with `|s_i - exact s_i| <= err_i`
/// wherever both are finite.
///
/// Derivation, with `u = 2^-53` (`f64`'s unit roundoff), `A = p_i - o`, `B
/// = p_j - o` exact, `a`, `b` their rounded values and `M = sum |A_j B_k
/// d_l|` over the six monomials of `(A x B) . d`:
/// - `a = A (1 + delta)` with `|delta| <= u` (a difference that is
///   subnormal is exact; one that overflows is not finite and declines);
/// - on the path from an input to `s`, each monomial `A_j B_k d_l` meets at
///   most seven roundings: `a_j`, `b_k`, their product, the difference
///   `c_l`, the product with `d_l`, and two sums. So (Higham, Accuracy and
///   Stability of Numerical Algorithms, 2002, lemma 3.1) `|s - S| <=
///   gamma(7) M` where no product underflows;
/// - a product that underflows is off by at most `eta = 2^-1075` instead:
///   the six products `a_j b_k`, each carried on by one `d_l` and three more
///   roundings, and the three `c_l d_l`, by two: at most `(6 max |d_l| + 3)
///   eta (1 + u)^4 <= (6 max |d_l| + 3) 2^-1074`;
/// - `M` is bounded from the computed values: `|A_j| <= |a_j| / (1 - u)`,
///   so `M <= M' / (1 - u)^2` with `M' = sum |a_j| |b_k| |d_l|` evaluated
///   rounded upwards (at least its exact value), and `gamma(7) / (1 -
///   u)^2 = 7u / ((1 - 7u)(1 - u)^2) < 8u = 2^-50`.
///
/// So `err_i = 2^-50 M' + (6 max |d_l| + 3) 2^-1074`, every operation
/// rounded upwards. Addition never needs an underflow term (a subnormal sum
/// or difference of floats is exact). An overflow anywhere leaves `s_i` or
/// `err_i` not finite (no operation here turns an infinity or NaN back into
/// a finite value), so a finite pair was computed with the relative model
/// throughout (a result rounded down to `MAX` is still within `u` of its
/// exact value).
fn plucker_f64(o: [f64; 3], d: [f64; 3], corners: [[f64; 3]; 3]) -> [(f64, f64); 3] {
    use crate::num::round::outward::{add_up, mul_up};
    let p = corners.map(|c| [c[0] - o[0], c[1] - o[1], c[2] - o[2]]);
    let dmax = d
        .iter()
        .fold(0.0f64, |m, x| if x.abs() > m { x.abs() } else { m });
    let underflow = mul_up(add_up(mul_up(6.0, dmax), 3.0), f64::from_bits(1));
    [(0, 1), (1, 2), (2, 0)].map(|(i, j)| {
        let (a, b) = (p[i], p[j]);
        let c = [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ];
        let s = c[0] * d[0] + c[1] * d[1] + c[2] * d[2];
        // The six monomials |a_j| |b_k| |d_l|, each rounded up, summed up.
        let mono =
            |j: usize, k: usize, l: usize| mul_up(mul_up(a[j].abs(), b[k].abs()), d[l].abs());
        let magnitude = [
            mono(1, 2, 0),
            mono(2, 1, 0),
            mono(2, 0, 1),
            mono(0, 2, 1),
            mono(0, 1, 2),
            mono(1, 0, 2),
        ]
        .into_iter()
        .fold(0.0, add_up);
        (s, add_up(mul_up(magnitude, EIGHT_U), underflow))
    })
}

/// `8u = 2^-50` for `f64`: the filter's relative error factor (see
/// `plucker_f64`).
const EIGHT_U: f64 = 1.0 / (1u64 << 50) as f64;

/// The triangle case is decided outside the watertight test's rounding
/// band: [`triangle_decided`] with no widening, or a line that passes the
/// triangle by more than the test's rounding of its edge functions
/// ([`surely_outside_watertight`]). `exact` must be
/// [`triangle`]`(ray, tri)`, computed once by the caller.
///
/// What it decides: the answer of every watertight form of the crate (the
/// closed test and its prepared, interval and batch forms, and the one-hit
/// test, which differs only on edge functions that are exactly zero) is
/// exact arithmetic's answer (`exact.hits`) wherever this is `true`.
/// [`triangle_clear`] decides the same for the watertight test and
/// Moller-Trumbore together, with the band widened by Moller-Trumbore's
/// bounds; this is its watertight half. It is `true` wherever
/// [`triangle_clear`] is (the same tests with a narrower band), and also
/// where only Moller-Trumbore's rounding keeps that one `false`: near
/// parallel lines, where its determinant's error bound swamps the
/// determinant, and lines that are exactly parallel to the plane (or
/// triangles of zero area) whose edge functions have opposite strict
/// signs.
///
/// Why it is sound: [`triangle_decided`] with zeros is the watertight
/// test's own documented error bound evaluated at the exact crossing (its
/// derivation there), and [`surely_outside_watertight`] is a miss on the
/// edge functions' signs alone (its derivation there). False when a
/// coordinate is not finite.
#[must_use]
pub fn triangle_clear_watertight<V: Vector>(
    ray: &Ray<V>,
    tri: &Triangle<V>,
    exact: &ExactTriangle,
    t_max: V::Scalar,
) -> bool {
    triangle_decided(ray, tri, exact, t_max, &no_extra()).is_some()
        || surely_outside_watertight(ray, tri)
}

/// The watertight test's main axis for a direction, the axis of the
/// largest `|d_k|`, with the test's rule for ties: `x` if `|d_x| > |d_y|`
/// and `|d_x| > |d_z|`, else `y` if `|d_y| > |d_z|`, else `z`. Always an
/// axis, `0..3`: a NaN component loses every comparison.
#[must_use]
pub fn main_axis<V: Vector>(dir: V) -> usize {
    let d = dir.abs();
    if d.x() > d.y() && d.x() > d.z() {
        0
    } else if d.y() > d.z() {
        1
    } else {
        2
    }
}

/// A bound on how far the watertight test's computed edge functions can be
/// from the exact ones, and `|d_z|`: `(de, |d_z|)`, or `None` where the
/// computed frame overflows or an input is not finite.
///
/// The test's arithmetic is fixed by its algorithm (Woop, Benthin and
/// Wald, JCGT 2013), so its rounded values are computed here the way IEEE
/// arithmetic defines them: in the frame of the main axis `kz`
/// ([`main_axis`]), `kx`, `ky` the next two cyclically, the shear factors
/// `s_x = fl(-d_kx / d_kz)`, `s_y` likewise, and per corner
/// `p = fl(c - o)`, `x = fl(p_kx + fl(s_x p_kz))`, `y` likewise. The edge
/// function of corners `j`, `k` is `e = fl(fl(x_j y_k) - fl(y_j x_k))`
/// (where that is zero the test recomputes its sign exactly, which only
/// brings it closer).
///
/// Derivation, with `u` the unit roundoff, `gamma(n) = n u / (1 - n u)`,
/// `P` the exact translated coordinates, `X = P_kx + S_x P_kz` and `Y` the
/// exact sheared ones, `m_x = max |x_i|`, `m_y = max |y_i|`, and `m_px`,
/// `m_py`, `m_pz` the largest `|p|` per axis:
/// - `x - X = P_kx d_1 + S_x P_kz theta_3 + (p_kx + fl(s_x p_kz)) d_5`
///   (the translation, the shear factor with its product, the sum), so
///   `|x - X| <= gamma(1) (m_px + m_x) + gamma(4) |s_x| m_pz = dx`, and `dy`
///   likewise;
/// - the edge function's own two roundings add `gamma(2) (|x_j y_k| +
///   |y_j x_k|) <= 2 gamma(2) m_x m_y`, and replacing the computed
///   coordinates by the exact ones `2 (m_x dy + m_y dx + dx dy)`;
/// - where products underflow, each rounding is off by up to half a
///   subnormal `tiny` instead: the edge function's two products, the shear
///   products (half a `tiny` each, times the other coordinate, at most
///   `m = max(m_x, m_y)`) and a shear factor that underflowed (half a
///   `tiny`, times `m_pz` and then `m`), all within `4 tiny (1 + m)(1 +
///   m_pz)`.
///
/// So `de = 2 (gamma(2) m_x m_y + m_x dy + m_y dx + dx dy) + 4 tiny (1 +
/// m)(1 + m_pz)`, evaluated here exactly.
#[must_use]
pub fn edge_function_bound<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>) -> Option<(R, R)> {
    let f = EdgeFrame::new(ray, tri)?;
    let [mx, my, mpx, mpy, mpz, sx, sy, dz] = [f.mx, f.my, f.mpx, f.mpy, f.mpz, f.sx, f.sy, f.dz];
    let (mx, my, mpx, mpy, mpz) = (r(mx)?, r(my)?, r(mpx)?, r(mpy)?, r(mpz)?);
    let g = |n: u16| gamma::<V::Scalar>(n);
    let dx = g(1) * (&mpx + &mx) + g(4) * r(sx)? * &mpz;
    let dy = g(1) * (&mpy + &my) + g(4) * r(sy)? * &mpz;
    let m = if mx > my { mx.clone() } else { my.clone() };
    let rounding = int(2) * (g(2) * &mx * &my + &mx * &dy + &my * &dx + &dx * &dy);
    let underflow = int(4) * constant(V::Scalar::TINY) * (int(1) + m) * (int(1) + mpz);
    Some((rounding + underflow, r(dz)?))
}

/// The watertight test's computed frame, as far as [`edge_function_bound`]
/// needs it: the largest `|x_i|`, `|y_i|`, `|p_kx|`, `|p_ky|`, `|p_kz|`,
/// and `|s_x|`, `|s_y|`, `|d_kz|`, floats of the ray's precision.
struct EdgeFrame<F> {
    mx: F,
    my: F,
    mpx: F,
    mpy: F,
    mpz: F,
    sx: F,
    sy: F,
    dz: F,
}

impl<F: Scalar> EdgeFrame<F> {
    /// The frame as the test rounds it (see [`edge_function_bound`]);
    /// `None` where it overflows or an input is not finite.
    fn new<V: Vector<Scalar = F>>(ray: &Ray<V>, tri: &Triangle<V>) -> Option<Self> {
        let kz = main_axis(ray.dir);
        let (kx, ky) = ((kz + 1) % 3, (kz + 2) % 3);
        let (o, d) = (ray.origin, ray.dir);
        let (sx, sy) = (-d[kx] / d[kz], -d[ky] / d[kz]);
        let corners = [tri.a, tri.b, tri.c];
        let p = |k: usize| corners.map(|c| c[k] - o[k]);
        let (px, py, pz) = (p(kx), p(ky), p(kz));
        let x: [F; 3] = core::array::from_fn(|i| px[i] + sx * pz[i]);
        let y: [F; 3] = core::array::from_fn(|i| py[i] + sy * pz[i]);
        let finite = |v: &[F; 3]| v.iter().all(|c| c.is_finite());
        if !([px, py, pz, x, y].iter().all(finite)
            && sx.is_finite()
            && sy.is_finite()
            && d[kz].is_finite())
        {
            return None;
        }
        let largest = |v: &[F; 3]| {
            v.iter()
                .fold(F::ZERO, |m, c| if c.abs() > m { c.abs() } else { m })
        };
        Some(Self {
            mx: largest(&x),
            my: largest(&y),
            mpx: largest(&px),
            mpy: largest(&py),
            mpz: largest(&pz),
            sx: sx.abs(),
            sy: sy.abs(),
            dz: d[kz].abs(),
        })
    }

    /// [`edge_function_bound`]'s `de |d_z|` evaluated in `f64`: at least
    /// its exact value when `up`, at most it otherwise. The same
    /// expression, every operation rounded in that direction (`fl(x)` is
    /// within half an ulp of `x`, so the float above it is at least `x`,
    /// the float below at most `x`; rounded down, a result is also kept
    /// from going below zero, which the exact one is not), on non-negative
    /// terms, so each bound stays one through the rest of the expression.
    /// `gamma(n) = n u / (1 - n u)` is rounded likewise (`n u` and `1 - n u`
    /// are exact in `f64` for both precisions' `u` and `n <= 4`). Not
    /// finite where it overflows.
    fn margin(&self, up: bool) -> f64 {
        let round = |x: f64| {
            if up {
                x.next_up()
            } else {
                x.next_down().max(0.0)
            }
        };
        let add = |a: f64, b: f64| round(a + b);
        let mul = |a: f64, b: f64| round(a * b);
        let w = |x: F| x.to_f64();
        let (mx, my, mpx, mpy, mpz) = (
            w(self.mx),
            w(self.my),
            w(self.mpx),
            w(self.mpy),
            w(self.mpz),
        );
        let g = |n: u32| {
            let nu = f64::from(n) * F::UNIT_ROUNDOFF.to_f64();
            round(nu / (1.0 - nu))
        };
        let dx = add(mul(g(1), add(mpx, mx)), mul(mul(g(4), w(self.sx)), mpz));
        let dy = add(mul(g(1), add(mpy, my)), mul(mul(g(4), w(self.sy)), mpz));
        let m = if mx > my { mx } else { my };
        let sum = [mul(mx, dy), mul(my, dx), mul(dx, dy)]
            .into_iter()
            .fold(mul(mul(g(2), mx), my), add);
        let rounding = mul(2.0, sum);
        let underflow = mul(mul(4.0 * F::TINY.to_f64(), add(1.0, m)), add(1.0, mpz));
        mul(add(rounding, underflow), w(self.dz))
    }
}

/// The plane case is outside the kernel's rounding band: not within rounding
/// of parallel (`|d.n| > 4 gamma(3) sum |d_i n_i|`, twice the kernel's own
/// threshold), and the crossing farther than its error bound from 0 and
/// `t_max`. False when a coordinate is not finite.
#[must_use]
pub fn plane_clear<V: Vector>(ray: &Ray<V>, plane: &Plane<V>, t_max: V::Scalar) -> bool {
    let (Some(d), Some(n)) = (rv(ray.dir), rv(plane.normal)) else {
        return false;
    };
    if !(ray.origin.is_finite() && plane.point.is_finite()) {
        return false;
    }
    let mag: R = (0..3).map(|k| (&d[k] * &n[k]).abs()).sum();
    let resolved = dot(&d, &n).abs() > int(4) * gamma::<V::Scalar>(3) * mag;
    resolved
        && plane_t(ray, plane).is_none_or(|t| {
            let bound =
                crate::Surface::hit_error(plane, ray, &V::Scalar::from_f64(to_f64(&t))).next_up();
            // An unbounded error (an overflow) decides nothing.
            let Some(err) = r(bound) else {
                return false;
            };
            let limit = limit(t_max);
            t.abs() > err && limit.is_none_or(|m| (m - &t).abs() > err)
        })
}

/// The exact transfer of one ray differential to a triangle at parameter
/// `t` (the formulas of [`Triangle::hit_differentials`](crate::Triangle::hit_differentials),
/// evaluated exactly on the given floats): with `n = (b - a) x (c - a)`
/// and `q = d_origin + t d_dir`, `dp = q - dir (q . n) / (dir . n)`, `du =
/// dp . ((c - a) x n) / |n|^2`, `dv = dp . (n x (b - a)) / |n|^2`: the
/// derivative of the hit point and of its barycentrics along the
/// differential, at `t`.
///
/// `None` when an input is not finite, or `dir . n` or `|n|^2` is zero.
#[must_use]
pub fn hit_differential<V: Vector>(
    dir: V,
    d_origin: V,
    d_dir: V,
    tri: &Triangle<V>,
    t: V::Scalar,
) -> Option<(R3, R, R)> {
    let (dir, d_origin, d_dir) = (rv(dir)?, rv(d_origin)?, rv(d_dir)?);
    let (a, b, c) = (rv(tri.a)?, rv(tri.b)?, rv(tri.c)?);
    let t = r(t)?;
    let (e1, e2) = (sub(&b, &a), sub(&c, &a));
    let n = cross(&e1, &e2);
    let den = dot(&dir, &n);
    let nn = dot(&n, &n);
    if den.is_zero() || nn.is_zero() {
        return None;
    }
    let q: R3 = core::array::from_fn(|k| &d_origin[k] + &t * &d_dir[k]);
    let dt = -dot(&q, &n) / den;
    let dp: R3 = core::array::from_fn(|k| &q[k] + &dt * &dir[k]);
    let du = dot(&dp, &cross(&e2, &n)) / &nn;
    let dv = dot(&dp, &cross(&n, &e1)) / &nn;
    Some((dp, du, dv))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::Draws;
    use crate::{EdgeRule, Intersect};
    use glam::{DVec3, Vec3};

    #[test]
    fn non_finite_input_gives_none_or_false() {
        let (nan, inf) = (f32::NAN, f32::INFINITY);
        let good = Ray::new(Vec3::new(0.25, 0.25, 1.0), Vec3::NEG_Z);
        let tri = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
        let aabb = Aabb::new(Vec3::ZERO, Vec3::ONE);
        let plane = Plane::new(Vec3::ZERO, Vec3::Z);
        assert!(r(nan).is_none() && r(inf).is_none() && rv(Vec3::new(0.0, inf, 0.0)).is_none());
        for bad in [
            Ray::new(Vec3::new(nan, 0.25, 1.0), Vec3::NEG_Z),
            Ray::new(Vec3::new(0.25, 0.25, 1.0), Vec3::new(0.0, inf, -1.0)),
        ] {
            assert!(plane_t(&bad, &plane).is_none() && box_slabs(&bad, &aabb).is_none());
            assert!(box_face(&bad, &aabb).is_none() && triangle(&bad, &tri).is_none());
            assert!(
                segment_crossing(&bad, &tri).is_none() && edge_function_bound(&bad, &tri).is_none()
            );
            assert!(mt_bounds(&bad, &tri, &int(0), &int(0)).is_none());
            assert!(!box_clear(&bad, &aabb, inf) && !triangle_clear(&bad, &tri, inf));
            assert!(!plane_clear(&bad, &plane, inf) && !reciprocal_subnormal(bad.dir));
            let exact = triangle(&good, &tri).unwrap();
            assert!(triangle_decided(&bad, &tri, &exact, inf, &no_extra()).is_none());
            assert!(!surely_outside(&bad, &tri, &exact, &no_extra()));
        }
        assert!(!reciprocal_overflows(Vec3::new(nan, 1.0, 1.0)));
        assert!(!close(nan, &int(0), 1.0) && !close(0.0, &int(0), inf));
        assert!(close(0.5, &dyadic(1, -1), 0.0));
        assert_eq!(main_axis(Vec3::new(nan, nan, nan)), 2);
    }

    #[test]
    fn a_segment_seen_end_on_has_no_crossing() {
        let seg = Triangle::new(Vec3::ZERO, Vec3::Z, Vec3::Z * 2.0);
        let ray = Ray::new(Vec3::new(0.0, 0.0, 5.0), Vec3::NEG_Z);
        assert!(segment_crossing(&ray, &seg).is_none());
        let across = Ray::new(Vec3::new(-1.0, 0.0, 1.5), Vec3::X);
        assert_eq!(segment_crossing(&across, &seg), Some(int(1)));
    }

    #[test]
    fn conversions_saturate_and_gamma_is_total() {
        assert_eq!(to_f64(&dyadic(1, 2000)), f64::INFINITY);
        assert_eq!(to_f64(&dyadic(-1, 2000)), f64::NEG_INFINITY);
        assert_eq!(to_f64(&dyadic(-1, -2000)).to_bits(), (-0.0f64).to_bits());
        assert_eq!(to_f64(&dyadic(3, -1074)), 3.0 * f64::from_bits(1));
        assert_eq!(to_f64(&r(f64::MAX).unwrap()), f64::MAX);
        assert_eq!(ulp::<f32>(1.0), f64::from(f32::EPSILON));
        assert_eq!(ulp::<f32>(f64::from(f32::MAX)), f64::INFINITY);
        assert_eq!(ulp::<f32>(1e300), f64::from(f32::from_bits(1)));
        assert!(gamma::<f32>(u16::MAX) < int(1) && gamma::<f64>(1) > int(0));
    }

    /// `triangle`'s rational formulas as they read before they were
    /// computed in integers: the reference it is held to.
    fn triangle_reference<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>) -> Option<ExactTriangle> {
        let (o, d) = (rv(ray.origin)?, rv(ray.dir)?);
        let (a, b, c) = (
            sub(&rv(tri.a)?, &o),
            sub(&rv(tri.b)?, &o),
            sub(&rv(tri.c)?, &o),
        );
        let s = [(&a, &b), (&b, &c), (&c, &a)].map(|(p, q)| dot(&cross(p, q), &d));
        let signs = [0, 1, 2].map(|i| s[i].cmp(&R::zero()));
        let sum = &s[0] + &s[1] + &s[2];
        if sum.is_zero() {
            return Some(ExactTriangle {
                signs,
                t: None,
                uv: None,
            });
        }
        let n = cross(&sub(&b, &a), &sub(&c, &a));
        Some(ExactTriangle {
            signs,
            t: Some(dot(&a, &n) / &sum),
            uv: Some((&s[2] / &sum, &s[0] / &sum)),
        })
    }

    fn unit(g: &mut Draws) -> f64 {
        (g.next() >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }

    fn grid(g: &mut Draws) -> f64 {
        ((g.next() >> 8) % 17) as f64 / 4.0 - 2.0
    }

    fn pow2(k: i64) -> f64 {
        2f64.powi(k as i32)
    }

    /// A ray and a triangle of precision `V` for the filter and verdict
    /// tests, by `kind`:
    /// 0. grid coordinates (quarters in `[-2, 2]`): exact zeros, rays
    ///    exactly through corners and along edges, lines exactly parallel
    ///    to the plane, zero-area triangles;
    /// 1. wide magnitudes (`Draws::coordinate` over `2^±60`), and one
    ///    coordinate in eight a special value (NaN, infinities, `MAX`,
    ///    subnormal, signed zeros);
    /// 2. a ray aimed `2^-j` (`j` up to 60) of the triangle's size off a
    ///    corner, an edge midpoint or a point of an edge;
    /// 3. a ray `2^-j` off parallel to the triangle's plane;
    ///
    /// kinds 2 and 3 scaled by `2^±40` and, one time in two, translated by
    /// up to `2^20` times that (so that rounding the corners and the
    /// direction in `V` moves the ray by more than the aim's offset).
    fn case<V: Vector>(g: &mut Draws, kind: u64) -> (Ray<V>, Triangle<V>) {
        let v = |p: [f64; 3]| {
            V::new(
                V::Scalar::from_f64(p[0]),
                V::Scalar::from_f64(p[1]),
                V::Scalar::from_f64(p[2]),
            )
        };
        let point = |g: &mut Draws| [unit(g), unit(g), unit(g)];
        match kind {
            0 => {
                let mut p = || v([grid(g), grid(g), grid(g)]);
                let (o, d, a, b, c) = (p(), p(), p(), p(), p());
                (Ray::new(o, d), Triangle::new(a, b, c))
            }
            1 => {
                let mut p = || {
                    v([0; 3].map(|_| {
                        if g.next().is_multiple_of(8) {
                            f64::from(g.special_f32())
                        } else {
                            g.coordinate(120)
                        }
                    }))
                };
                let (o, d, a, b, c) = (p(), p(), p(), p(), p());
                (Ray::new(o, d), Triangle::new(a, b, c))
            }
            _ => {
                let (a, b, c) = (point(g), point(g), point(g));
                let scale = pow2((g.next() % 81) as i64 - 40);
                let far = if g.next().is_multiple_of(2) {
                    scale * pow2((g.next() % 21) as i64)
                } else {
                    0.0
                };
                let offset = [unit(g) * far, unit(g) * far, unit(g) * far];
                let place = |p: [f64; 3]| v([0, 1, 2].map(|k| offset[k] + scale * p[k]));
                let tri = Triangle::new(place(a), place(b), place(c));
                let off = pow2(-((g.next() % 61) as i64));
                let e1 = [0, 1, 2].map(|k| b[k] - a[k]);
                let e2 = [0, 1, 2].map(|k| c[k] - a[k]);
                if kind == 2 {
                    let along = [0.0, 0.5, unit(g).abs()][(g.next() % 3) as usize];
                    let jitter = point(g);
                    let target = [0, 1, 2].map(|k| a[k] + along * e1[k] + off * jitter[k]);
                    let from = point(g);
                    let origin = [0, 1, 2].map(|k| target[k] + 4.0 * from[k]);
                    let (o, t) = (place(origin), place(target));
                    (Ray::new(o, t - o), tri)
                } else {
                    // n = e1 x e2, a direction in the plane plus `off` of n.
                    let n = [
                        e1[1] * e2[2] - e1[2] * e2[1],
                        e1[2] * e2[0] - e1[0] * e2[2],
                        e1[0] * e2[1] - e1[1] * e2[0],
                    ];
                    let (x, y) = (unit(g), unit(g));
                    let d = [0, 1, 2].map(|k| x * e1[k] + y * e2[k] + off * n[k]);
                    let o = point(g);
                    (Ray::new(place(o), v(d)), tri)
                }
            }
        }
    }

    fn same(x: &Option<ExactTriangle>, y: &Option<ExactTriangle>) -> bool {
        match (x, y) {
            (None, None) => true,
            (Some(x), Some(y)) => x.signs == y.signs && x.t == y.t && x.uv == y.uv,
            _ => false,
        }
    }

    #[test]
    fn triangle_in_integers_is_the_rational_formulas() {
        fn check<V: Vector>(g: &mut Draws, kind: u64) -> (bool, bool) {
            let (ray, tri) = case::<V>(g, kind);
            let (fast, slow) = (triangle(&ray, &tri), triangle_reference(&ray, &tri));
            assert!(same(&fast, &slow), "{ray:?} {tri:?}: {fast:?} {slow:?}");
            (fast.is_none(), fast.is_some_and(|x| x.t.is_none()))
        }
        let mut g = Draws(0x2545_f491_4f6c_dd1d);
        let (mut invalid, mut parallel) = (0, 0);
        for i in 0..3000 {
            for (x, y) in [check::<Vec3>(&mut g, i % 4), check::<DVec3>(&mut g, i % 4)] {
                invalid += usize::from(x);
                parallel += usize::from(y);
            }
        }
        assert!(invalid > 50 && parallel > 3, "{invalid} {parallel}");
    }

    /// The filter's parts against exact arithmetic: every `f64` Plucker
    /// product within its error bound of the exact one, and the margin
    /// between its two float bounds (which are close: within `2^-40` of
    /// it, plus the smallest subnormals they may round to).
    #[test]
    fn filter_bounds_hold() {
        fn check<V: Vector>(g: &mut Draws, kind: u64, tally: &mut [usize; 3]) {
            let (ray, tri) = case::<V>(g, kind);
            let Some(frame) = EdgeFrame::new(&ray, &tri) else {
                assert!(edge_function_bound(&ray, &tri).is_none());
                return;
            };
            let (de, dz) = edge_function_bound(&ray, &tri).unwrap();
            let margin = de * dz;
            let (lo, up) = (frame.margin(false), frame.margin(true));
            if up.is_finite() {
                let (rl, ru) = (r(lo).unwrap(), r(up).unwrap());
                assert!(rl <= margin && margin <= ru, "{ray:?} {tri:?}");
                let slack = &margin * dyadic(1, -40) + dyadic(1, -1070);
                assert!(ru - rl <= slack, "{lo:e} {up:e}: {ray:?} {tri:?}");
                tally[0] += 1;
            }
            let w = |p: V| [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()];
            let corners = [w(tri.a), w(tri.b), w(tri.c)];
            let (o, d) = (w(ray.origin), w(ray.dir));
            let ro = rv(ray.origin).unwrap();
            let p = [tri.a, tri.b, tri.c].map(|c| sub(&rv(c).unwrap(), &ro));
            let rd = rv(ray.dir).unwrap();
            for (i, (s, err)) in plucker_f64(o, d, corners).into_iter().enumerate() {
                if !(s.is_finite() && err.is_finite()) {
                    continue;
                }
                let (j, k) = [(0, 1), (1, 2), (2, 0)][i];
                let exact = dot(&cross(&p[j], &p[k]), &rd);
                let off = abs_diff(&r(s).unwrap(), &exact);
                assert!(off <= r(err).unwrap(), "{s:e} {err:e}: {ray:?} {tri:?}");
                tally[1] += 1;
                tally[2] += usize::from(!off.is_zero());
            }
        }
        let mut g = Draws(0x9e37_79b9_7f4a_7c15);
        let mut tally = [0; 3];
        for i in 0..3000 {
            check::<Vec3>(&mut g, i % 4, &mut tally);
            check::<DVec3>(&mut g, i % 4, &mut tally);
        }
        // Most cases have a finite frame; many products round.
        std::println!("{tally:?}");
        assert!(
            tally[0] > 5000 && tally[1] > 15_000 && tally[2] > 5000,
            "{tally:?}"
        );
    }

    /// The filter against exact arithmetic on the same sample: wherever it
    /// answers (with its error bounds alone, and with the exact expansions
    /// too), it answers as `surely_outside_watertight_exact`. The sample
    /// reaches both answers many times, and reaches products within the
    /// error bounds of the margin, where the expansions decide.
    #[test]
    fn filter_agrees_with_exact_arithmetic() {
        #[derive(Debug, Default)]
        struct Tally {
            outside: usize,
            not_outside: usize,
            by_bounds: usize,
            by_expansions: usize,
            undecided: usize,
        }
        fn check<V: Vector>(g: &mut Draws, kind: u64, t: &mut Tally) {
            let (ray, tri) = case::<V>(g, kind);
            let exact = surely_outside_watertight_exact(&ray, &tri);
            let (bounds, full) = (filter(&ray, &tri, false), filter(&ray, &tri, true));
            for answer in [bounds, full] {
                assert!(
                    answer.is_none_or(|x| x == exact),
                    "filter {answer:?}, exact {exact}: {ray:?} {tri:?}"
                );
            }
            assert_eq!(surely_outside_watertight(&ray, &tri), exact);
            assert!(bounds.is_none() || full == bounds);
            t.outside += usize::from(exact);
            t.not_outside += usize::from(!exact);
            t.by_bounds += usize::from(bounds.is_some());
            t.by_expansions += usize::from(bounds.is_none() && full.is_some());
            t.undecided += usize::from(full.is_none());
        }
        let mut g = Draws(0x0123_4567_89ab_cdef);
        let mut t = Tally::default();
        for i in 0..4000 {
            check::<Vec3>(&mut g, i % 4, &mut t);
            check::<DVec3>(&mut g, i % 4, &mut t);
        }
        std::println!("{t:?}");
        assert!(
            t.outside > 4000 && t.not_outside > 1500 && t.by_expansions > 100,
            "{t:?}"
        );
        // Undecided only beyond the expansions' range (f64 inputs past
        // 2^+-300, kind 1) or strictly between the margin's float bounds.
        assert!(t.undecided * 50 < t.by_bounds, "{t:?}");
    }

    /// `triangle_clear_watertight` against `triangle_clear` and the
    /// kernels: clear wherever `triangle_clear` is (and in more cases), and
    /// where it is clear, every watertight form answers as exact arithmetic
    /// (the closed and one-hit tests, plain, prepared and over `(0,
    /// t_max]`).
    #[test]
    fn watertight_clear_is_triangle_clear_without_mt() {
        fn check<V: Vector>(g: &mut Draws, kind: u64, t: &mut [usize; 3]) {
            let (ray, tri) = case::<V>(g, kind);
            let t_max = if g.next().is_multiple_of(2) {
                V::Scalar::INFINITY
            } else {
                V::Scalar::from_f64(pow2((g.next() % 20) as i64 - 10))
            };
            let Some(ex) = triangle(&ray, &tri) else {
                assert!(!triangle_clear(&ray, &tri, t_max));
                return;
            };
            let (mt, wt) = (
                triangle_clear(&ray, &tri, t_max),
                triangle_clear_watertight(&ray, &tri, &ex, t_max),
            );
            assert!(!mt || wt, "clear with MT, not without: {ray:?} {tri:?}");
            t[0] += usize::from(mt);
            t[1] += usize::from(wt && !mt);
            if !(wt && ray.is_valid()) {
                return;
            }
            t[2] += 1;
            let expect = ex.hits(&limit(t_max));
            let prepared = crate::PreparedRay::new(&ray);
            let window = crate::Interval::up_to(t_max).unwrap();
            let answers = [
                crate::ray_triangle(&ray, &tri, t_max).is_some(),
                tri.hit(&ray, (t_max, EdgeRule::OneHit)).is_some(),
                tri.hit(&prepared, t_max).is_some(),
                tri.hit(&ray, window).is_some(),
                tri.hit(&ray, (window, EdgeRule::OneHit)).is_some(),
                tri.hit(&prepared, window).is_some(),
            ];
            assert!(
                answers.iter().all(|&a| a == expect),
                "{answers:?}, exact {expect}: {ray:?} {tri:?} {t_max:?}"
            );
        }
        let mut g = Draws(0x5851_f42d_4c95_7f2d);
        let mut t = [0; 3];
        for i in 0..3000 {
            check::<Vec3>(&mut g, i % 4, &mut t);
            check::<DVec3>(&mut g, i % 4, &mut t);
        }
        std::println!("{t:?}");
        assert!(t[0] > 2000 && t[1] > 200 && t[2] > 4000, "{t:?}");
    }

    /// A line nearly parallel to a tilted triangle's plane, passing far
    /// from it: Moller-Trumbore's determinant (`d . n`, a few `f32` ulps
    /// of `d`'s components, which are near 1) is within its error bound of
    /// zero, so `triangle_clear` cannot call it; seen along the ray, the
    /// triangle is a sliver far from the ray's point, whose two long edges'
    /// functions have opposite signs well beyond their rounding, so
    /// `triangle_clear_watertight` can.
    #[test]
    fn nearly_parallel_far_miss_is_clear_for_the_watertight_test_only() {
        let (a, b, c) = (Vec3::ZERO, Vec3::ONE, Vec3::new(1.0, -1.0, 0.5));
        let tri = Triangle::new(a, b, c);
        // n = (b - a) x (c - a) = (1.5, 0.5, -2); d is b - a and a few ulps
        // of n: d . n = 3.5 2^-23.
        let eps = f32::EPSILON;
        let d = Vec3::new(1.0 + eps, 1.0, 1.0 - eps);
        // From c + 2 (c - a) + n, along b - a: off the plane by |n|, and
        // (along the plane) three times as far from the edge a-b as c.
        let ray = Ray::new(Vec3::new(4.5, -2.5, -0.5), d);
        let ex = triangle(&ray, &tri).unwrap();
        assert!(ex.t.is_some() && !ex.line_hits());
        let (ue, ve) = ex.uv.clone().unwrap();
        let (eu, ev, _) = mt_bounds(&ray, &tri, &ue, &ve).unwrap();
        assert!(eu > int(1) && ev > int(1), "MT's bounds are not wide here");
        assert!(!triangle_clear(&ray, &tri, f32::INFINITY));
        assert!(triangle_clear_watertight(&ray, &tri, &ex, f32::INFINITY));
        assert_eq!(surely_outside_watertight_filter(&ray, &tri), Some(true));
        assert!(crate::ray_triangle(&ray, &tri, f32::INFINITY).is_none());
    }

    /// `exact::ray_triangle_from_exact` is `exact::ray_triangle`, and its
    /// side (from the edge products' signs) is the sign of `dir . n`.
    #[test]
    fn answer_from_exact_is_ray_triangle() {
        fn check<V: Vector>(g: &mut Draws, kind: u64) -> usize {
            let (ray, tri) = case::<V>(g, kind);
            let t_max = V::Scalar::INFINITY;
            let direct = crate::exact::ray_triangle(&ray, &tri, t_max);
            let given = triangle(&ray, &tri)
                .and_then(|ex| crate::exact::ray_triangle_from_exact(&ray, &tri, &ex, t_max));
            assert_eq!(direct, given, "{ray:?} {tri:?}");
            let Some(hit) = direct else { return 0 };
            let (a, b, c) = (rv(tri.a).unwrap(), rv(tri.b).unwrap(), rv(tri.c).unwrap());
            let n = cross(&sub(&b, &a), &sub(&c, &a));
            let front = dot(&rv(ray.dir).unwrap(), &n).is_negative();
            assert_eq!(hit.side == crate::Side::Front, front, "{ray:?} {tri:?}");
            1
        }
        let mut g = Draws(0x6a09_e667_f3bc_c909);
        let mut hits = 0;
        for i in 0..2000 {
            hits += check::<Vec3>(&mut g, i % 4) + check::<DVec3>(&mut g, i % 4);
        }
        assert!(hits > 500, "{hits}");
    }
}
