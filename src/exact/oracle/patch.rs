//! The bilinear patch in exact arithmetic: where a ray meets the patch
//! `P(u, v) = (1 - u)(1 - v) p00 + u (1 - v) p10 + (1 - u) v p01 + u v
//! p11`, each crossing's `u`, `v`, `t` and side.
//!
//! For each `u` the patch holds the segment from `A(u) = P(u, 0)` to
//! `B(u) = P(u, 1)`; the ray's line meets that segment's line where
//! `f(u) = ((A(u) - o) x d) . (B(u) - A(u))` vanishes (the two lines are
//! coplanar), a quadratic with rational coefficients (Reshetov's, Ray
//! Tracing Gems ch. 8, 2019, in exact arithmetic). At a root, with `w =
//! A - o`, `e = B - A` and `n = d x e`: `v = ((w x d) . n) / (n . n)` and
//! `t = ((w x e) . n) / (n . n)`. The roots lie in `Q(sqrt(D))` for the
//! discriminant `D`, and so do `v` and `t`: every question is the sign of
//! a number `p + q sqrt(D)` with rational `p`, `q`, decided without a
//! square root ([`Surd`]).

use super::values::*;
use crate::{Patch, Ray, Scalar, Side, Vector};
use core::cmp::Ordering;
use core::ops::{Add, Mul, Neg, Sub};
use num_traits::{Signed, Zero};
use std::vec;
use std::vec::Vec;

/// A number `p + q sqrt(d)`, `p` and `q` rational, `d >= 0` rational
/// (the same `d` for every number of one computation).
#[derive(Debug, Clone, PartialEq)]
pub struct Surd {
    /// The rational part.
    pub p: R,
    /// The coefficient of `sqrt(d)`.
    pub q: R,
    /// The radicand, at least zero.
    pub d: R,
}

impl Surd {
    /// The rational `p`.
    #[must_use]
    pub fn rational(p: R, d: &R) -> Self {
        Self {
            p,
            q: R::zero(),
            d: d.clone(),
        }
    }

    /// The sign of `p + q sqrt(d)`, exactly: where `p` and `q` differ in
    /// sign, by comparing `p^2` with `q^2 d`.
    #[must_use]
    pub fn sign(&self) -> Ordering {
        let (sp, sq) = (sign_of(&self.p), sign_of(&self.q));
        if sq == Ordering::Equal || self.d.is_zero() {
            return sp;
        }
        if sp == Ordering::Equal || sp == sq {
            return sq;
        }
        // Opposite signs: the larger magnitude decides.
        match (&self.p * &self.p).cmp(&(&self.q * &self.q * &self.d)) {
            Ordering::Greater => sp,
            Ordering::Less => sq,
            Ordering::Equal => Ordering::Equal,
        }
    }

    /// How `self` compares with the rational `x`.
    #[must_use]
    pub fn cmp_rational(&self, x: &R) -> Ordering {
        (self.clone() - Surd::rational(x.clone(), &self.d)).sign()
    }

    /// The nearest `f64` (for estimates).
    #[must_use]
    pub fn to_f64(&self) -> f64 {
        to_f64(&self.p) + to_f64(&self.q) * to_f64(&self.d).sqrt()
    }
}

fn sign_of(x: &R) -> Ordering {
    if x.is_positive() {
        Ordering::Greater
    } else if x.is_negative() {
        Ordering::Less
    } else {
        Ordering::Equal
    }
}

impl Add for Surd {
    type Output = Surd;
    fn add(self, o: Surd) -> Surd {
        Surd {
            p: self.p + o.p,
            q: self.q + o.q,
            d: self.d,
        }
    }
}

impl Sub for Surd {
    type Output = Surd;
    fn sub(self, o: Surd) -> Surd {
        Surd {
            p: self.p - o.p,
            q: self.q - o.q,
            d: self.d,
        }
    }
}

impl Neg for Surd {
    type Output = Surd;
    fn neg(self) -> Surd {
        Surd {
            p: -self.p,
            q: -self.q,
            d: self.d,
        }
    }
}

impl Mul for Surd {
    type Output = Surd;
    fn mul(self, o: Surd) -> Surd {
        Surd {
            p: &self.p * &o.p + &self.q * &o.q * &self.d,
            q: &self.p * &o.q + &self.q * &o.p,
            d: self.d,
        }
    }
}

type S3 = [Surd; 3];

fn lift(v: &R3, d: &R) -> S3 {
    [0, 1, 2].map(|k| Surd::rational(v[k].clone(), d))
}

fn s_cross(a: &S3, b: &S3) -> S3 {
    [0, 1, 2].map(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        a[j].clone() * b[k].clone() - a[k].clone() * b[j].clone()
    })
}

fn s_dot(a: &S3, b: &S3) -> Surd {
    a[0].clone() * b[0].clone() + a[1].clone() * b[1].clone() + a[2].clone() * b[2].clone()
}

/// One crossing of a ray's line with a patch: `u`, `v`, `t` (each exact,
/// in `Q(sqrt(D))`) and the side.
#[derive(Debug, Clone)]
pub struct PatchCrossing {
    /// The place along `p00 -> p10`.
    pub u: Surd,
    /// The place along `p00 -> p01`.
    pub v: Surd,
    /// The distance along the ray, in units of `dir`.
    pub t: Surd,
    /// [`Side::Front`] where `d . (dP/du x dP/dv) <= 0` (a tangent
    /// crossing counts as front).
    pub side: Side,
}

impl PatchCrossing {
    /// `t`, `u` or `v` rounded to the nearest float (`0` for a value at
    /// most zero; `t` may round to infinity beyond `MAX`).
    #[must_use]
    pub fn rounded<F: Scalar>(value: &Surd) -> F {
        nearest_float::<F>(value.to_f64(), |x: &R| value.cmp_rational(x))
    }
}

/// A ray's line against a patch: every crossing with `(u, v)` in the
/// closed unit square, in increasing `t` (behind the origin too).
#[derive(Debug, Clone)]
pub struct ExactPatch {
    /// The crossings, nearest first.
    pub crossings: Vec<PatchCrossing>,
}

impl ExactPatch {
    /// The nearest crossing with `lo < t` and `t <= hi` (`None`: no upper
    /// end).
    #[must_use]
    pub fn first_in(&self, lo: &R, hi: Option<&R>) -> Option<&PatchCrossing> {
        self.crossings.iter().find(|c| {
            c.t.cmp_rational(lo) == Ordering::Greater
                && hi.is_none_or(|h| c.t.cmp_rational(h) != Ordering::Greater)
        })
    }
}

/// The exact crossings of `ray`'s line with `patch`; `None` for a
/// non-finite input or a zero direction.
///
/// Where the line lies in the patch's ruled family (`f` vanishing for
/// every `u`: a ray in the plane of a planar patch, among others) there
/// is no isolated crossing, and none is reported; likewise a ruling line
/// parallel to the ray. A collapsed edge (a ruling that is a point) is
/// crossed where the line passes through that point.
///
/// ```
/// use rayhit::exact::oracle::patch;
/// use rayhit::{Patch, Ray, glam::Vec3};
/// // The saddle z = x y over [-1, 1]^2, and the line (s, s, 1/4).
/// let saddle = Patch::new(
///     Vec3::new(-1.0, -1.0, 1.0),
///     Vec3::new(1.0, -1.0, -1.0),
///     Vec3::new(-1.0, 1.0, -1.0),
///     Vec3::new(1.0, 1.0, 1.0),
/// );
/// let ray = Ray::new(Vec3::new(-1.0, -1.0, 0.25), Vec3::new(1.0, 1.0, 0.0));
/// let e = patch(&ray, &saddle).unwrap();
/// assert_eq!(e.crossings.len(), 2);
/// assert_eq!(e.crossings[0].t.to_f64(), 0.5);
/// assert_eq!(e.crossings[1].t.to_f64(), 1.5);
/// ```
#[must_use]
pub fn patch<V: Vector>(ray: &Ray<V>, patch: &Patch<V>) -> Option<ExactPatch> {
    let (o, d) = (rv(ray.origin)?, rv(ray.dir)?);
    if d.iter().all(Zero::is_zero) {
        return None;
    }
    let [p00, p10, p01, p11] = [patch.p00, patch.p10, patch.p01, patch.p11].map(rv);
    let (p00, p10, p01, p11) = (p00?, p10?, p01?, p11?);
    // f(u) = ((w0 + u g) x d) . (e0 + u k).
    let w0 = sub(&p00, &o);
    let g = sub(&p10, &p00);
    let e0 = sub(&p01, &p00);
    let k = sub(&sub(&p11, &p10), &e0);
    let (w0d, gd) = (cross(&w0, &d), cross(&g, &d));
    let a = dot(&gd, &k);
    let b = dot(&w0d, &k) + dot(&gd, &e0);
    let c = dot(&w0d, &e0);
    // The roots, as numbers of Q(sqrt(disc)).
    let roots: Vec<Surd> = if a.is_zero() {
        if b.is_zero() {
            // Constant: no root (c != 0), or every u (the ruled family).
            Vec::new()
        } else {
            let zero = R::zero();
            vec![Surd::rational(-c / b, &zero)]
        }
    } else {
        let disc = &b * &b - int(4) * &a * &c;
        if disc.is_negative() {
            return Some(ExactPatch {
                crossings: Vec::new(),
            });
        }
        let two_a = int(2) * &a;
        let p = -&b / &two_a;
        if disc.is_zero() {
            vec![Surd::rational(p, &disc)]
        } else {
            let q = R::from_integer(1.into()) / &two_a;
            vec![
                Surd {
                    p: p.clone(),
                    q: -q.clone(),
                    d: disc.clone(),
                },
                Surd { p, q, d: disc },
            ]
        }
    };
    let mut crossings = Vec::new();
    for u in roots {
        let dd = u.d.clone();
        let (zero, one) = (R::zero(), R::from_integer(1.into()));
        if u.cmp_rational(&zero) == Ordering::Less || u.cmp_rational(&one) == Ordering::Greater {
            continue;
        }
        let lerp3 = |a: &R3, b: &R3| -> S3 {
            let (a, b) = (lift(a, &dd), lift(b, &dd));
            [0, 1, 2].map(|i| a[i].clone() + u.clone() * (b[i].clone() - a[i].clone()))
        };
        let at_a = lerp3(&p00, &p10);
        let at_b = lerp3(&p01, &p11);
        let (os, ds) = (lift(&o, &dd), lift(&d, &dd));
        let w: S3 = [0, 1, 2].map(|i| at_a[i].clone() - os[i].clone());
        let e: S3 = [0, 1, 2].map(|i| at_b[i].clone() - at_a[i].clone());
        let n = s_cross(&ds, &e);
        let nn = s_dot(&n, &n);
        let (v, t) = if nn.sign() == Ordering::Equal {
            // The ruling is a point (a collapsed edge), or parallel to the
            // ray: a crossing only at a point ruling the line passes
            // through, at its place along the ray.
            let point = e.iter().all(|x| x.sign() == Ordering::Equal);
            let wd = s_cross(&w, &ds);
            if !(point && wd.iter().all(|x| x.sign() == Ordering::Equal)) {
                continue;
            }
            // t = (w . d) / (d . d).
            let dd2 = s_dot(&ds, &ds);
            let inv = Surd::rational(R::from_integer(1.into()) / &dd2.p, &dd);
            (Surd::rational(zero.clone(), &dd), s_dot(&w, &ds) * inv)
        } else {
            // Divide by n . n (in Q(sqrt(D)): multiply by its conjugate).
            let conj = Surd {
                p: nn.p.clone(),
                q: -nn.q.clone(),
                d: dd.clone(),
            };
            let norm = (nn.clone() * conj.clone()).p;
            let inv = Surd {
                p: &conj.p / &norm,
                q: &conj.q / &norm,
                d: dd.clone(),
            };
            let v = s_dot(&s_cross(&w, &ds), &n) * inv.clone();
            let t = s_dot(&s_cross(&w, &e), &n) * inv;
            (v, t)
        };
        if v.cmp_rational(&zero) == Ordering::Less || v.cmp_rational(&one) == Ordering::Greater {
            continue;
        }
        // The side: d . (dP/du x dP/dv) at (u, v).
        let du: S3 = {
            let (g0, g1) = (lift(&g, &dd), lift(&sub(&p11, &p01), &dd));
            [0, 1, 2].map(|i| g0[i].clone() + v.clone() * (g1[i].clone() - g0[i].clone()))
        };
        let dv: S3 = {
            let (h0, h1) = (lift(&e0, &dd), lift(&sub(&p11, &p10), &dd));
            [0, 1, 2].map(|i| h0[i].clone() + u.clone() * (h1[i].clone() - h0[i].clone()))
        };
        let side = if s_dot(&ds, &s_cross(&du, &dv)).sign() == Ordering::Greater {
            Side::Back
        } else {
            Side::Front
        };
        crossings.push(PatchCrossing { u, v, t, side });
    }
    if crossings.len() == 2
        && (crossings[1].t.clone() - crossings[0].t.clone()).sign() == Ordering::Less
    {
        crossings.swap(0, 1);
    }
    Some(ExactPatch { crossings })
}
