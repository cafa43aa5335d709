//! The triangle in exact arithmetic: the edge signs, crossing and
//! barycentrics of a ray's line (in integers), Moller-Trumbore's error
//! bounds, the watertight test's rounding band, and the checks of a
//! hit's point.

use super::values::*;
use crate::{Ray, Scalar, Triangle, TriangleHit, TriangleHitError, Vector};
use core::cmp::Ordering;
use num_bigint::{BigInt, Sign};
use num_traits::{Signed, Zero};

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

/// The one-hit rule ([`EdgeRule::OneHit`](crate::EdgeRule::OneHit)) in
/// exact arithmetic: whether the ray's line, moved by an infinitesimal
/// `eps1 x + eps2 y` (`0 < eps2 << eps1`; `x`, `y` the axes after the
/// direction's largest-magnitude axis `z`, cyclically), passes through
/// the triangle's interior; `None` when a coordinate is not finite.
///
/// Moving the origin by `delta` changes an edge's Plucker product
/// `((p - o) x (q - o)) . d` by `-(delta x (q - p)) . d`, so where the
/// product is zero its sign is that of `-(x x D) . d`, or else of
/// `-(y x D) . d`, with `D = q - p` (zero for both: the edge is parallel
/// to the ray, and the moved line passes no triangle on it). Computed in
/// integers, as [`triangle`].
#[must_use]
pub fn one_hit_line_hits<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>) -> Option<bool> {
    let ex = triangle(ray, tri)?;
    if ex.t.is_none() {
        return Some(false);
    }
    let w = |p: V| [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()];
    let (pts, _) = integers([w(tri.a), w(tri.b), w(tri.c)]);
    let ([d], _) = integers([w(ray.dir)]);
    let shear = crate::ray::Shear::new(&ray.dir);
    let (kx, ky) = (shear.kx as usize, shear.ky as usize);
    let unit = |k: usize| {
        let mut u = [BigInt::zero(), BigInt::zero(), BigInt::zero()];
        u[k] = BigInt::from(1);
        u
    };
    let mut signs = ex.signs;
    for (i, s) in signs.iter_mut().enumerate() {
        if *s != Ordering::Equal {
            continue;
        }
        let (p, q) = (&pts[i], &pts[(i + 1) % 3]);
        let edge = isub(q, p);
        let moved = |k: usize| {
            (-idot(&icross(&unit(k), &edge), &d))
                .sign()
                .cmp(&Sign::NoSign)
        };
        *s = match moved(kx) {
            Ordering::Equal => moved(ky),
            o => o,
        };
    }
    Some(signs[0] != Ordering::Equal && signs[0] == signs[1] && signs[1] == signs[2])
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

/// The distance of a ray's line from the nearest of the lines through
/// consecutive `corners` (the last back to the first), in `f64`: each
/// `|((p - o) x (q - o)) . d| / |d x (q - p)|` computed in integers (as
/// [`triangle`]) and divided once; infinite where every line is parallel
/// to the ray's; `None` where a coordinate is not finite (at most 4
/// corners).
pub(crate) fn edges_gap<V: Vector>(ray: &Ray<V>, corners: &[V]) -> Option<f64> {
    let w = |p: V| [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()];
    let mut points = [[0.0; 3]; 5];
    points[0] = w(ray.origin);
    for (slot, &c) in points[1..].iter_mut().zip(corners) {
        *slot = w(c);
    }
    let dir = w(ray.dir);
    if !points.iter().chain([&dir]).flatten().all(|x| x.is_finite()) {
        return None;
    }
    let (pts, e) = integers(points);
    let ([d], _) = integers([dir]);
    let n = corners.len().min(4);
    let mut gap = f64::INFINITY;
    for k in 0..n {
        let (p, q) = (&pts[1 + k], &pts[1 + (k + 1) % n]);
        let s = idot(&icross(&isub(p, &pts[0]), &isub(q, &pts[0])), &d);
        let m = icross(&d, &isub(q, p));
        let mm = idot(&m, &m);
        if mm.is_zero() {
            continue;
        }
        // |s| / |m| in units of 2^E.
        let ratio = to_f64(&R::new_raw(&s * &s, mm)).sqrt();
        let exponent = i32::try_from(e).unwrap_or(0);
        gap = gap.min(crate::num::exact_sign::scale2(ratio, exponent));
    }
    Some(gap)
}

/// An integer 3-vector.
pub(super) type I3 = [BigInt; 3];

/// Finite floats as integers of one scale: `(x 2^-E, E)` with `E` the
/// smallest exponent `e` of the nonzero values written `m 2^e` with an odd
/// integer `m` (0 when all are zero).
pub(super) fn integers<const N: usize>(points: [[f64; 3]; N]) -> ([I3; N], i64) {
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

pub(super) fn isub(a: &I3, b: &I3) -> I3 {
    [&a[0] - &b[0], &a[1] - &b[1], &a[2] - &b[2]]
}

pub(super) fn idot(a: &I3, b: &I3) -> BigInt {
    &a[0] * &b[0] + &a[1] * &b[1] + &a[2] * &b[2]
}

pub(super) fn icross(a: &I3, b: &I3) -> I3 {
    [
        &a[1] * &b[2] - &a[2] * &b[1],
        &a[2] * &b[0] - &a[0] * &b[2],
        &a[0] * &b[1] - &a[1] * &b[0],
    ]
}

/// Where the ray passes the segment of a zero-area triangle, exactly: in
/// the ray's sheared frame (main axis the direction's largest component,
/// the kernel's tie rule; `x`, `y` the next two cyclically), the depth of
/// the point of the segment between the two corners farthest apart nearest
/// the ray, clamped to the segment. `None` when the ray does not move, a
/// coordinate is not finite, or the segment is seen end-on (its two
/// corners at one point of the frame).
///
/// Computed in integers, as [`triangle`] is: with the corners taken from
/// the origin and the coordinates scaled to integers `W` (and the
/// direction to `D`), a point's sheared coordinates are `(W_x D_k - D_x
/// W_k, W_y D_k - D_y W_k) / D_k` and its depth `W_k / D_k`, up to powers
/// of two, so the segment's parameter nearest the ray is a quotient of
/// integers and the depth one more; the values are those of the rational
/// formulas, exactly.
#[must_use]
pub fn segment_crossing<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>) -> Option<R> {
    let k = main_axis(ray.dir);
    let (kx, ky) = ((k + 1) % 3, (k + 2) % 3);
    let w = |p: V| [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()];
    let points = [w(ray.origin), w(tri.a), w(tri.b), w(tri.c)];
    let dir = w(ray.dir);
    let finite = points.iter().chain([&dir]).flatten().all(|x| x.is_finite());
    if !finite || dir.iter().all(|&x| x == 0.0) {
        return None;
    }
    let ([o, a, b, c], e) = integers(points);
    let ([d], f) = integers([dir]);
    let corners = [isub(&a, &o), isub(&b, &o), isub(&c, &o)];
    let dist2 = |i: usize, j: usize| {
        let x = isub(&corners[j], &corners[i]);
        idot(&x, &x)
    };
    let (mut i, mut j) = (0, 1);
    for (a, b) in [(1, 2), (2, 0)] {
        if dist2(a, b) > dist2(i, j) {
            (i, j) = (a, b);
        }
    }
    // `d[k]` is the largest component of a nonzero direction: not zero.
    let sheared = |w: &I3| {
        (
            &w[kx] * &d[k] - &d[kx] * &w[k],
            &w[ky] * &d[k] - &d[ky] * &w[k],
        )
    };
    let ((xp, yp), (xq, yq)) = (sheared(&corners[i]), sheared(&corners[j]));
    let (ex, ey) = (&xq - &xp, &yq - &yp);
    let den = &ex * &ex + &ey * &ey;
    if den.is_zero() {
        return None;
    }
    let s = R::new(-(&xp * &ex + &yp * &ey), den);
    let (zero, one) = (R::zero(), int(1));
    let s = if s < zero {
        zero
    } else if s > one {
        one
    } else {
        s
    };
    let (zp, zq) = (
        R::from_integer(corners[i][k].clone()),
        R::from_integer(corners[j][k].clone()),
    );
    // The depth in units of `2^(E - F) / D_k`.
    let depth = &zp + s * (zq - &zp);
    let shift = e - f;
    // (Exponents of finite floats differ by less than 2,200: an `i32`.)
    let unit = dyadic(1, i32::try_from(shift).ok()?) / R::from_integer(d[k].clone());
    Some(depth * unit)
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
///
/// Computed in integers, as [`triangle`] is: with the origin's and
/// corners' coordinates scaled to integers in units of `2^E` and the
/// direction's in units of `2^F`, `det` and the magnitudes of `u`'s and
/// `v`'s numerators share the units `2^(2E + F)`, which cancel, and `t`'s
/// numerator and its magnitude are in units of `2^3E`, a factor `2^(E -
/// F)` against `det`; only the final quotients are rationals. The values
/// are those of the rational formulas, exactly.
#[must_use]
pub fn mt_bounds<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>, u: &R, v: &R) -> Option<(R, R, R)> {
    let w = |p: V| [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()];
    let points = [w(ray.origin), w(tri.a), w(tri.b), w(tri.c)];
    let dir = w(ray.dir);
    if !points.iter().chain([&dir]).flatten().all(|x| x.is_finite()) {
        return None;
    }
    let ([o, a, b, c], e) = integers(points);
    let ([d], f) = integers([dir]);
    let (e1, e2, s) = (isub(&b, &a), isub(&c, &a), isub(&o, &a));
    let mag = |x: &I3, y: &I3, z: &I3| -> R {
        // sum_i |x_i| (|y_j z_k| + |y_k z_j|): the monomials of x . (y x z).
        let m: BigInt = (0..3)
            .map(|i| {
                let (j, k) = ((i + 1) % 3, (i + 2) % 3);
                x[i].abs() * ((&y[j] * &z[k]).abs() + (&y[k] * &z[j]).abs())
            })
            .sum();
        R::from_integer(m)
    };
    let g7 = gamma::<V::Scalar>(7);
    // `det` and `d_det` in units of `2^(2E + F)`.
    let det = R::from_integer(idot(&e1, &icross(&d, &e2)));
    let d_det = &g7 * mag(&e1, &d, &e2);
    // Above any bound in either precision (f64's largest is below 2^1024).
    let big = dyadic(1, 2000);
    if abs(&det) <= d_det {
        return Some((big.clone(), big.clone(), big));
    }
    let q = icross(&s, &e1);
    // `t`'s numerator in units of `2^3E`: `2^(E - F)` times `det`'s.
    let shift = e - f;
    // (Exponents of finite floats differ by less than 2,200: an `i32`.)
    let pow = dyadic(1, i32::try_from(shift).ok()?);
    let t = R::from_integer(idot(&e2, &q)) * &pow / &det;
    let g2 = gamma::<V::Scalar>(2);
    let quotient = |dn: R, q: &R| (dn + abs(q) * &d_det) / (abs(&det) - &d_det) + &g2 * abs(q);
    Some((
        quotient(&g7 * mag(&s, &d, &e2), u),
        quotient(&g7 * mag(&d, &s, &e1), v),
        quotient(&g7 * mag(&e2, &s, &e1) * &pow, &t),
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
