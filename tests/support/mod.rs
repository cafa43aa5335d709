//! Shared test support: the exact-arithmetic oracle.
//!
//! Every finite `f32` or `f64` is a dyadic rational, so each kernel's
//! question (does the ray hit, and at which `t`) has an exact answer for the
//! very inputs the kernel saw. This module computes it with big rationals:
//! slow, obviously right, and the reference every other test is held to.
#![allow(dead_code)]

use std::cmp::Ordering;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};
use rayhit::{Aabb, Plane, Ray, Scalar, Triangle, Vector};

/// An exact rational.
pub type R = BigRational;
/// An exact 3-vector.
pub type R3 = [R; 3];

/// The exact value of a finite float.
pub fn r<F: Scalar>(x: F) -> R {
    R::from_float(x.to_f64()).expect("finite input")
}

/// The exact value of a finite vector.
pub fn rv<V: Vector>(v: V) -> R3 {
    [r(v.x()), r(v.y()), r(v.z())]
}

pub fn sub(a: &R3, b: &R3) -> R3 {
    [&a[0] - &b[0], &a[1] - &b[1], &a[2] - &b[2]]
}

pub fn dot(a: &R3, b: &R3) -> R {
    &a[0] * &b[0] + &a[1] * &b[1] + &a[2] * &b[2]
}

pub fn cross(a: &R3, b: &R3) -> R3 {
    [
        &a[1] * &b[2] - &a[2] * &b[1],
        &a[2] * &b[0] - &a[0] * &b[2],
        &a[0] * &b[1] - &a[1] * &b[0],
    ]
}

/// `t_max` as an exact bound, `None` for `+inf`.
pub fn limit<F: Scalar>(t_max: F) -> Option<R> {
    if t_max.is_finite() {
        Some(r(t_max))
    } else {
        None
    }
}

fn within(t: &R, t_max: &Option<R>) -> bool {
    t_max.as_ref().is_none_or(|m| t <= m)
}

/// The nearest float of precision `F` to an exact value (for reports).
pub fn to_f64(x: &R) -> f64 {
    x.to_f64().unwrap_or(f64::NAN)
}

/// `|a - b|` as an `f64` (for comparing against a bound given as a float:
/// an exact comparison, because a float bound is itself exact).
pub fn abs_diff(a: &R, b: &R) -> R {
    (a - b).abs()
}

/// True when the exact `|a - b| <= bound`.
pub fn close<F: Scalar>(computed: F, exact: &R, bound: F) -> bool {
    bound.is_finite() && abs_diff(&r(computed), exact) <= r(bound)
}

/// Exact ray/plane: the crossing `t` (any sign), or `None` when the ray is
/// parallel to the plane (or the normal is zero).
pub fn plane_t<V: Vector>(ray: &Ray<V>, plane: &Plane<V>) -> Option<R> {
    let n = rv(plane.normal);
    let den = dot(&rv(ray.dir), &n);
    if den.is_zero() {
        return None;
    }
    Some(dot(&sub(&rv(plane.point), &rv(ray.origin)), &n) / den)
}

/// Exact ray/plane answer with the kernel's conventions: `0 < t <= t_max`.
pub fn plane_hit<V: Vector>(ray: &Ray<V>, plane: &Plane<V>, t_max: V::Scalar) -> Option<R> {
    let t = plane_t(ray, plane)?;
    (t.is_positive() && within(&t, &limit(t_max))).then_some(t)
}

/// The exact `(enter, exit)` of the ray against the closed box, clipped to
/// `[0, t_max]`, whether or not it is empty (`enter > exit` is a miss by
/// that much), or `None` when an axis the ray does not move along already
/// excludes it (a miss that no rounding of the other axes can change).
pub fn box_raw<V: Vector>(ray: &Ray<V>, b: &Aabb<V>, t_max: V::Scalar) -> Option<(R, R)> {
    let (o, d, lo, hi) = (rv(ray.origin), rv(ray.dir), rv(b.min), rv(b.max));
    let mut enter = R::zero();
    let mut exit: Option<R> = limit(t_max);
    for k in 0..3 {
        if d[k].is_zero() {
            if o[k] < lo[k] || o[k] > hi[k] {
                return None;
            }
            continue;
        }
        let t0 = (&lo[k] - &o[k]) / &d[k];
        let t1 = (&hi[k] - &o[k]) / &d[k];
        let (near, far) = if t0 <= t1 { (t0, t1) } else { (t1, t0) };
        if near > enter {
            enter = near;
        }
        exit = Some(match exit {
            Some(x) if x <= far => x,
            _ => far,
        });
    }
    Some((enter, exit.expect("a valid ray moves along some axis")))
}

/// Exact interval `[enter, exit]` of `t` in `[0, t_max]` with the ray inside
/// the closed box, or `None` when it is empty.
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
    pub fn line_hits(&self) -> bool {
        self.t.is_some()
            && !(self.signs.contains(&Ordering::Less) && self.signs.contains(&Ordering::Greater))
    }

    /// The kernel's question: the closed triangle is crossed at `0 < t <= t_max`.
    pub fn hits(&self, t_max: &Option<R>) -> bool {
        self.line_hits()
            && self
                .t
                .as_ref()
                .is_some_and(|t| t.is_positive() && within(t, t_max))
    }

    /// The line crosses the triangle's interior (no edge product is zero).
    pub fn interior(&self) -> bool {
        self.line_hits() && !self.signs.contains(&Ordering::Equal)
    }
}

/// Exact ray/triangle: signs of the three edge Plucker products, the plane
/// crossing `t` and the barycentrics `(u, v)` there.
pub fn triangle<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>) -> ExactTriangle {
    let (o, d) = (rv(ray.origin), rv(ray.dir));
    let (a, b, c) = (
        sub(&rv(tri.a), &o),
        sub(&rv(tri.b), &o),
        sub(&rv(tri.c), &o),
    );
    let s_ab = dot(&cross(&a, &b), &d);
    let s_bc = dot(&cross(&b, &c), &d);
    let s_ca = dot(&cross(&c, &a), &d);
    let zero = R::zero();
    let signs = [s_ab.cmp(&zero), s_bc.cmp(&zero), s_ca.cmp(&zero)];
    let sum = &s_ab + &s_bc + &s_ca;
    if sum.is_zero() {
        return ExactTriangle {
            signs,
            t: None,
            uv: None,
        };
    }
    // The weight of each corner is the product of the edge opposite it.
    let u = &s_ca / &sum;
    let v = &s_ab / &sum;
    let n = cross(&sub(&b, &a), &sub(&c, &a));
    let t = dot(&a, &n) / dot(&d, &n);
    ExactTriangle {
        signs,
        t: Some(t),
        uv: Some((u, v)),
    }
}

/// An exact dyadic rational `m * 2^e` as an `R` (for building inputs).
pub fn dyadic(m: i64, e: i32) -> R {
    let m = R::from_integer(BigInt::from(m));
    let two = R::from_integer(BigInt::from(2));
    if e >= 0 {
        m * num_traits::pow(two, e as usize)
    } else {
        m / num_traits::pow(two, (-e) as usize)
    }
}
