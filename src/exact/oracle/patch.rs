//! The bilinear patch in exact arithmetic: where a ray meets the patch
//! `P(u, v) = (1 - u)(1 - v) p00 + u (1 - v) p10 + (1 - u) v p01 + u v
//! p11`, each crossing's `u`, `v`, `t` and side; and the ray/patch test's
//! rounding band.
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
//!
//! Computed in integers, as [`triangle`](super::triangle) is: the points'
//! coordinates scaled to integers of one unit and the direction's to
//! integers of another, the quadratic's coefficients are integers, a root
//! is `U / S` with `U` in `Z[sqrt(D)]` and an integer `S`, and `v` and `t`
//! are quotients in `Z[sqrt(D)]`, made rational in the end by the
//! conjugate of the divisor: one reduction each, not one per operation.

use super::filter::{coordinate_bound_up, edge_margin_up};
use super::main_axis;
use super::triangle::{I3, icross, idot, integers, isub};
use super::values::*;
use crate::num::exact_sign::scale2;
use crate::num::round::outward::{add_up, div_up, mul_up};
use crate::{Patch, Ray, Scalar, Side, Triangle, Vector};
use core::cmp::Ordering;
use core::ops::{Add, Mul, Neg, Sub};
use num_bigint::{BigInt, Sign};
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
    /// sign, by comparing `p^2` with `q^2 d` (in integers, the
    /// denominators multiplied across).
    #[must_use]
    pub fn sign(&self) -> Ordering {
        surd_sign(
            (self.p.numer(), self.p.denom()),
            (self.q.numer(), self.q.denom()),
            (self.d.numer(), self.d.denom()),
        )
    }

    /// How `self` compares with the rational `x` (in integers: `p - x`
    /// is not reduced).
    #[must_use]
    pub fn cmp_rational(&self, x: &R) -> Ordering {
        let (pd, qd, xd) = (self.p.denom(), self.q.denom(), x.denom());
        let num = self.p.numer() * xd - x.numer() * pd;
        let d = (self.d.numer(), self.d.denom());
        if pd == qd {
            // `(num + q_n x_d sqrt(d)) / (p_d x_d)`: one denominator.
            let both = pd * xd;
            return surd_sign((&num, &both), (&(self.q.numer() * xd), &both), d);
        }
        surd_sign((&num, &(pd * xd)), (self.q.numer(), qd), d)
    }

    /// The nearest `f64`, about (for estimates): within a few roundings
    /// of the value, relative to it, even where `p` and `q sqrt(d)`
    /// nearly cancel (computed there as `(p^2 - q^2 d) / (p - q
    /// sqrt(d))`).
    #[must_use]
    pub fn to_f64(&self) -> f64 {
        let (p, q) = (to_f64(&self.p), to_f64(&self.q));
        let root = q * to_f64(&self.d).sqrt();
        if (p > 0.0) == (root > 0.0) || p == 0.0 || root == 0.0 {
            return p + root;
        }
        // Opposite signs: no cancellation in the conjugate. (In integers,
        // the quotient not reduced: only its value is read.)
        let (pn, pd, qn, qd) = (
            self.p.numer(),
            self.p.denom(),
            self.q.numer(),
            self.q.denom(),
        );
        let (dn, dd) = (self.d.numer(), self.d.denom());
        let num = pn * pn * qd * qd * dd - qn * qn * pd * pd * dn;
        let norm = R::new_raw(num, pd * pd * qd * qd * dd);
        let estimate = to_f64(&norm) / (p - root);
        if estimate.is_finite() {
            estimate
        } else {
            p + root
        }
    }
}

/// The sign of `pn / pd + (qn / qd) sqrt(dn / dd)` (`pd`, `qd`, `dd`
/// positive, `dn` at least zero), in integers.
fn surd_sign(
    (pn, pd): (&BigInt, &BigInt),
    (qn, qd): (&BigInt, &BigInt),
    (dn, dd): (&BigInt, &BigInt),
) -> Ordering {
    let (sp, sq) = (int_sign(pn), int_sign(qn));
    if sq == Ordering::Equal || dn.is_zero() {
        return sp;
    }
    if sp == Ordering::Equal || sp == sq {
        return sq;
    }
    // Opposite signs: the larger magnitude decides, `p^2` against `q^2
    // d`, every denominator multiplied across (one denominator, as a
    // crossing's numbers have, needs no multiplying).
    let (left, right) = if pd == qd {
        (pn * pn * dd, qn * qn * dn)
    } else {
        (pn * pn * qd * qd * dd, qn * qn * pd * pd * dn)
    };
    match left.cmp(&right) {
        Ordering::Greater => sp,
        Ordering::Less => sq,
        Ordering::Equal => Ordering::Equal,
    }
}

fn int_sign(x: &BigInt) -> Ordering {
    match x.sign() {
        Sign::Plus => Ordering::Greater,
        Sign::Minus => Ordering::Less,
        Sign::NoSign => Ordering::Equal,
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

/// A number `x + y sqrt(D)` of `Z[sqrt(D)]` (the `D` of its computation,
/// held apart).
#[derive(Debug, Clone)]
struct Zd {
    x: BigInt,
    y: BigInt,
}

impl Zd {
    fn int(x: BigInt) -> Self {
        Self {
            x,
            y: BigInt::zero(),
        }
    }

    fn add(&self, o: &Zd) -> Zd {
        Zd {
            x: &self.x + &o.x,
            y: &self.y + &o.y,
        }
    }

    fn sub(&self, o: &Zd) -> Zd {
        Zd {
            x: &self.x - &o.x,
            y: &self.y - &o.y,
        }
    }

    fn mul(&self, o: &Zd, disc: &BigInt) -> Zd {
        Zd {
            x: &self.x * &o.x + &self.y * &o.y * disc,
            y: &self.x * &o.y + &self.y * &o.x,
        }
    }

    fn scale(&self, k: &BigInt) -> Zd {
        Zd {
            x: &self.x * k,
            y: &self.y * k,
        }
    }

    fn is_zero(&self) -> bool {
        self.x.is_zero() && self.y.is_zero()
    }

    fn sign(&self, disc: &BigInt) -> Ordering {
        let one = BigInt::from(1);
        surd_sign((&self.x, &one), (&self.y, &one), (disc, &one))
    }

    /// `self / (k 2^shift)` as a [`Surd`] of radicand `disc` (`k`
    /// nonzero). Its rationals are not reduced (a greatest common divisor
    /// of numbers of thousands of bits costs more than all the rest):
    /// their values are what is read.
    fn over(&self, k: &BigInt, shift: i64, disc: &BigInt) -> Surd {
        let power = BigInt::from(1) << shift.unsigned_abs();
        let (mut num, mut den) = if shift >= 0 {
            (power, k.clone())
        } else {
            (BigInt::from(1), k * power)
        };
        if den.is_negative() {
            (num, den) = (-num, -den);
        }
        Surd {
            p: R::new_raw(&self.x * &num, den.clone()),
            q: R::new_raw(&self.y * num, den),
            d: R::from_integer(disc.clone()),
        }
    }
}

/// A vector of `Z[sqrt(D)]`.
type Z3 = [Zd; 3];

/// `a + u b` for integer vectors `a`, `b` and `u` in `Z[sqrt(D)]`, times
/// the integer `s` on `a`: `s a + u b`.
fn affine(s: &BigInt, a: &I3, u: &Zd, b: &I3) -> Z3 {
    [0, 1, 2].map(|k| Zd {
        x: s * &a[k] + &u.x * &b[k],
        y: &u.y * &b[k],
    })
}

/// `a x d` for an integer `d`.
fn cross_int(a: &Z3, d: &I3) -> Z3 {
    [0, 1, 2].map(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        a[j].scale(&d[k]).sub(&a[k].scale(&d[j]))
    })
}

fn z_cross(a: &Z3, b: &Z3, disc: &BigInt) -> Z3 {
    [0, 1, 2].map(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        a[j].mul(&b[k], disc).sub(&a[k].mul(&b[j], disc))
    })
}

fn z_dot(a: &Z3, b: &Z3, disc: &BigInt) -> Zd {
    a[0].mul(&b[0], disc)
        .add(&a[1].mul(&b[1], disc))
        .add(&a[2].mul(&b[2], disc))
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
/// // A collapsed edge (p01 = p00): the triangle p00, p10, p11.
/// let o = Vec3::ZERO;
/// let fan = Patch::new(o, Vec3::X, o, Vec3::new(1.0, 1.0, 0.0));
/// let down = Ray::new(Vec3::new(0.75, 0.25, 1.0), -Vec3::Z);
/// let e = patch(&down, &fan).unwrap();
/// assert_eq!(e.crossings.len(), 1);
/// assert_eq!((e.crossings[0].u.to_f64(), e.crossings[0].v.to_f64()), (0.75, 1.0 / 3.0));
/// ```
#[must_use]
pub fn patch<V: Vector>(ray: &Ray<V>, patch: &Patch<V>) -> Option<ExactPatch> {
    let line = PatchLine::new(ray, patch)?;
    Some(nearest_first(patch_crossings(&line)))
}

/// The crossings of `ray`'s line with the patch's surface extended
/// bilinearly past its edges: as [`patch`], for every `(u, v)`, not only
/// those of the unit square (the meeting of the line with the ruling of
/// each root of its quadratic), nearest first. What [`Patch`'s
/// `hit_error`](crate::Patch#method.hit_error) certifies is a crossing
/// of this surface within its bounds of the hit, which for a hit within
/// rounding of an edge may lie just outside the square.
///
/// ```
/// use rayhit::exact::oracle::{patch, patch_extended};
/// use rayhit::{Patch, Ray, glam::Vec3};
/// let saddle = Patch::new(Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 1.0));
/// // Down at (2, 0.5): past the edge u = 1, on the surface z = x y
/// // extended, at height 1.
/// let ray = Ray::new(Vec3::new(2.0, 0.5, 3.0), -Vec3::Z);
/// assert!(patch(&ray, &saddle).unwrap().crossings.is_empty());
/// let e = patch_extended(&ray, &saddle).unwrap();
/// assert_eq!((e.crossings[0].u.to_f64(), e.crossings[0].t.to_f64()), (2.0, 2.0));
/// ```
#[must_use]
pub fn patch_extended<V: Vector>(ray: &Ray<V>, patch: &Patch<V>) -> Option<ExactPatch> {
    let line = PatchLine::new(ray, patch)?;
    let meetings = line
        .roots()
        .iter()
        .filter_map(|root| line.crossing(root, false))
        .collect();
    Some(nearest_first(meetings))
}

/// Two crossings put nearest first.
fn nearest_first(mut crossings: Vec<PatchCrossing>) -> ExactPatch {
    if crossings.len() == 2
        && (crossings[1].t.clone() - crossings[0].t.clone()).sign() == Ordering::Less
    {
        crossings.swap(0, 1);
    }
    ExactPatch { crossings }
}

/// A ray's line against a patch, before the unit square is imposed: the
/// quadratic `f(u) = a u^2 + b u + c` whose roots are the rulings the
/// line meets, and for each root the place of the meeting (`v`, `t`).
/// What [`patch`] is built from, and what the patch's band reads (roots
/// just outside the square too). In integers: the origin and the corners
/// in units of `2^E`, the direction in units of `2^F`.
pub(crate) struct PatchLine {
    /// The corners less the origin, `p00 - o`, `p10 - o`, `p01 - o`, `p11
    /// - o`.
    offsets: [I3; 4],
    /// The exponents `E` and `F` of the units.
    exponents: (i64, i64),
    /// `w0 = p00 - o`, the edges and the twist: `g = p10 - p00`, `e0 =
    /// p01 - p00`, `k = p11 - p10 - e0`, and `g1 = p11 - p01`.
    w0: I3,
    g: I3,
    e0: I3,
    k: I3,
    g1: I3,
    d: I3,
    /// `E - F`: `t` is in units of `2^(E - F)`.
    shift: i64,
    a: BigInt,
    b: BigInt,
    c: BigInt,
    /// The discriminant `b^2 - 4 a c`.
    disc: BigInt,
    /// The radicand of the roots' numbers: the discriminant, or zero
    /// where the roots are rational.
    radicand: BigInt,
}

/// A root `u = U / S` of the line's quadratic, `U` in `Z[sqrt(D)]`.
pub(crate) struct Root {
    top: Zd,
    bottom: BigInt,
}

/// A root's meeting with its ruling, in `Z[sqrt(D)]`: `v = vn / vd`, `t =
/// tn / td` (times `2^(E - F)`).
struct Meeting {
    vn: Zd,
    vd: BigInt,
    tn: Zd,
    td: BigInt,
}

impl PatchLine {
    /// The quadratic of `ray`'s line against `patch`; `None` for a
    /// non-finite input or a zero direction.
    pub(crate) fn new<V: Vector>(ray: &Ray<V>, patch: &Patch<V>) -> Option<Self> {
        let w = |p: V| [p.x().to_f64(), p.y().to_f64(), p.z().to_f64()];
        let points = [ray.origin, patch.p00, patch.p10, patch.p01, patch.p11].map(w);
        let dir = w(ray.dir);
        if !points.iter().chain([&dir]).flatten().all(|x| x.is_finite())
            || dir.iter().all(|&x| x == 0.0)
        {
            return None;
        }
        let ([o, p00, p10, p01, p11], e) = integers(points);
        let ([d], f) = integers([dir]);
        // f(u) = ((w0 + u g) x d) . (e0 + u k).
        let w0 = isub(&p00, &o);
        let g = isub(&p10, &p00);
        let e0 = isub(&p01, &p00);
        let k = isub(&isub(&p11, &p10), &e0);
        let g1 = isub(&p11, &p01);
        let (w0d, gd) = (icross(&w0, &d), icross(&g, &d));
        let a = idot(&gd, &k);
        let b = idot(&w0d, &k) + idot(&gd, &e0);
        let c = idot(&w0d, &e0);
        let disc = &b * &b - BigInt::from(4) * &a * &c;
        let rational = a.is_zero() || !disc.is_positive() || {
            let root = disc.sqrt();
            &root * &root == disc
        };
        let radicand = if rational {
            BigInt::zero()
        } else {
            disc.clone()
        };
        let offsets = [p00, p10, p01, p11].map(|p| isub(&p, &o));
        Some(Self {
            offsets,
            exponents: (e, f),
            w0,
            g,
            e0,
            k,
            g1,
            d,
            shift: e - f,
            a,
            b,
            c,
            disc,
            radicand,
        })
    }

    /// The Plucker product `((p_i - o) x (p_j - o)) . d` of corners `i`,
    /// `j` (`0` to `3` for `p00`, `p10`, `p01`, `p11`), in units of
    /// [`PatchLine::plucker_exponent`].
    pub(crate) fn plucker(&self, i: usize, j: usize) -> BigInt {
        idot(&icross(&self.offsets[i], &self.offsets[j]), &self.d)
    }

    /// The Plucker products' unit is `2^(2E + F)`: its exponent.
    pub(crate) fn plucker_exponent(&self) -> i64 {
        2 * self.exponents.0 + self.exponents.1
    }

    /// The largest magnitude of a corner's coordinate relative to the
    /// origin, about (in `f64`).
    fn reach(&self) -> f64 {
        let m = self
            .offsets
            .iter()
            .flatten()
            .map(num_traits::Signed::abs)
            .max()
            .unwrap_or_default();
        scaled_f64(&m, self.exponents.0)
    }

    /// The real roots of `f`, smaller first: none where `f` is a nonzero
    /// constant or every `u` is a root (the ruled family), one where `f`
    /// is linear or has a double root. Where the discriminant is a
    /// square the roots are rational (radicand 0): a quotient by a
    /// number of `Q(sqrt(D))` multiplies by its conjugate, which there
    /// would be the number's value at the other root, and may be zero.
    pub(crate) fn roots(&self) -> Vec<Root> {
        let (a, b, c) = (&self.a, &self.b, &self.c);
        if a.is_zero() {
            return if b.is_zero() {
                Vec::new()
            } else {
                vec![Root {
                    top: Zd::int(-c),
                    bottom: b.clone(),
                }]
            };
        }
        if self.disc.is_negative() {
            return Vec::new();
        }
        // u = (-b -+ sqrt(D)) / 2a, the smaller first: the sign of the
        // root's term taken with a's.
        let two_a = BigInt::from(2) * a;
        let sign = BigInt::from(if a.is_positive() { 1 } else { -1 });
        if self.disc.is_zero() {
            return vec![Root {
                top: Zd::int(-b),
                bottom: two_a,
            }];
        }
        let tops: [Zd; 2] = if self.radicand.is_zero() {
            let step = &sign * self.disc.sqrt();
            [Zd::int(-b - &step), Zd::int(-b + step)]
        } else {
            [
                Zd {
                    x: -b,
                    y: -sign.clone(),
                },
                Zd { x: -b, y: sign },
            ]
        };
        tops.into_iter()
            .map(|top| Root {
                top,
                bottom: two_a.clone(),
            })
            .collect()
    }

    /// A root as a [`Surd`].
    pub(crate) fn u(&self, root: &Root) -> Surd {
        root.top.over(&root.bottom, 0, &self.radicand)
    }

    /// The ruling at a root: where the line meets it. With `u = U / S`,
    /// `W = S w` and `E = S e` (`w = A(u) - o`, `e = B(u) - A(u)`) and `N =
    /// d x E`: `v = ((W x d) . N) / (N . N)` and `t = ((W x E) . N) / (S N
    /// . N)`, each made rational by the conjugate of its divisor (nonzero:
    /// `sqrt(D)` is irrational there, see [`PatchLine::roots`]). A ruling
    /// that is a point is met where the line passes through it, at `v = 0`
    /// and `t = (W . d) / (S d . d)`. `None` where the ruling is parallel
    /// to the line, or a point it misses.
    fn meet(&self, root: &Root) -> Option<Meeting> {
        let disc = &self.radicand;
        let (u, s) = (&root.top, &root.bottom);
        let w = affine(s, &self.w0, u, &self.g);
        let e = affine(s, &self.e0, u, &self.k);
        let dz: Z3 = self.d.clone().map(Zd::int);
        let n = cross_int(&e, &self.d).map(|x| Zd { x: -x.x, y: -x.y });
        let nn = z_dot(&n, &n, disc);
        if nn.is_zero() {
            // The ruling is a point (a collapsed edge), or parallel to the
            // ray: a crossing only at a point ruling the line passes
            // through, at its place along the ray.
            let point = e.iter().all(Zd::is_zero);
            let wd = cross_int(&w, &self.d);
            if !(point && wd.iter().all(Zd::is_zero)) {
                return None;
            }
            return Some(Meeting {
                vn: Zd::int(BigInt::zero()),
                vd: BigInt::from(1),
                tn: z_dot(&w, &dz, disc),
                td: s * idot(&self.d, &self.d),
            });
        }
        let conj = Zd {
            x: nn.x.clone(),
            y: -nn.y.clone(),
        };
        let norm = nn.mul(&conj, disc).x;
        let v = z_dot(&cross_int(&w, &self.d), &n, disc).mul(&conj, disc);
        let t = z_dot(&z_cross(&w, &e, disc), &n, disc).mul(&conj, disc);
        Some(Meeting {
            vn: v,
            vd: norm.clone(),
            tn: t,
            td: s * norm,
        })
    }

    /// The ruling at a root: where the line meets it, `v` and `t`.
    pub(crate) fn place(&self, root: &Root) -> RulingPlace {
        let m = self.meet(root)?;
        let disc = &self.radicand;
        Some((
            m.vn.over(&m.vd, 0, disc),
            m.tn.over(&m.td, self.shift, disc),
        ))
    }

    /// The crossing at a root, where the line meets its ruling (at a
    /// place of the closed unit square, if `square`), with its side.
    fn crossing(&self, root: &Root, square: bool) -> Option<PatchCrossing> {
        let disc = &self.radicand;
        // `n / m` in `[0, 1]`: `n m >= 0` and `(n - m) m <= 0`.
        let unit = |n: &Zd, m: &BigInt| {
            let (nm, over) = (n.scale(m), n.sub(&Zd::int(m.clone())).scale(m));
            nm.sign(disc) != Ordering::Less && over.sign(disc) != Ordering::Greater
        };
        if square && !unit(&root.top, &root.bottom) {
            return None;
        }
        let m = self.meet(root)?;
        if square && !unit(&m.vn, &m.vd) {
            return None;
        }
        let side = self.side_at(root, &m, disc);
        Some(PatchCrossing {
            u: root.top.over(&root.bottom, 0, disc),
            v: m.vn.over(&m.vd, 0, disc),
            t: m.tn.over(&m.td, self.shift, disc),
            side,
        })
    }

    /// The side at a root and its meeting: [`Side::Front`] where `d .
    /// (dP/du x dP/dv) <= 0`. With `v = Vn / Vd`: `Vd dP/du = Vd g + Vn
    /// (g1 - g)` and `S dP/dv = E`; the product's sign is corrected by
    /// those of `Vd` and `S`.
    fn side_at(&self, root: &Root, m: &Meeting, disc: &BigInt) -> Side {
        let du = affine(&m.vd, &self.g, &m.vn, &isub(&self.g1, &self.g));
        let dv = affine(&root.bottom, &self.e0, &root.top, &self.k);
        let n = z_cross(&du, &dv, disc);
        let dz: Z3 = self.d.clone().map(Zd::int);
        let mut sign = z_dot(&dz, &n, disc).sign(disc);
        if m.vd.is_negative() != root.bottom.is_negative() {
            sign = sign.reverse();
        }
        if sign == Ordering::Greater {
            Side::Back
        } else {
            Side::Front
        }
    }
}

/// Where the line meets the ruling of a root: `v` and `t`, or `None`
/// where the ruling is parallel to the line (or a point the line misses).
pub(crate) type RulingPlace = Option<(Surd, Surd)>;

/// Whether `|x| 2^e > m` (`m` finite, at least zero), exactly: `m` is
/// `k 2^j` with an integer `k`, and the integers are compared shifted.
fn above(x: &BigInt, e: i64, m: f64) -> bool {
    above_times(x, e, m, &BigInt::from(1))
}

/// Whether `|x| 2^e > m |factor|`, exactly, as [`above`].
fn above_times(x: &BigInt, e: i64, m: f64, factor: &BigInt) -> bool {
    use num_traits::float::FloatCore;
    if !m.is_finite() {
        return false;
    }
    let (mant, exp, _) = m.integer_decode();
    let (k, j) = (BigInt::from(mant) * factor.abs(), i64::from(exp));
    let x = x.abs();
    let shift = |v: &BigInt, by: i64| v << by.unsigned_abs();
    if e >= j {
        shift(&x, e - j) > k
    } else {
        x > shift(&k, j - e)
    }
}

/// `x 2^e` as an `f64`, rounded (to an infinity beyond the range).
fn scaled_f64(x: &BigInt, e: i64) -> f64 {
    let bits = i64::try_from(x.bits()).unwrap_or(i64::MAX);
    // The top 64 bits, then the exponent: within a few roundings.
    let drop = (bits - 64).max(0);
    let top = num_traits::ToPrimitive::to_f64(&(x >> drop.unsigned_abs())).unwrap_or(f64::NAN);
    let k = (e + drop).clamp(-4000, 4000) as i32;
    scale2(top, k)
}

/// The crossings of [`patch`], from its line.
fn patch_crossings(line: &PatchLine) -> Vec<PatchCrossing> {
    line.roots()
        .iter()
        .filter_map(|u| line.crossing(u, true))
        .collect()
}

/// The triangle a patch with a collapsed edge is, as the ray/patch test
/// takes it: the first of `p10 = p00`, `p11 = p10`, `p11 = p01`, `p01 =
/// p00` that holds (coordinates compared as floats, so `-0.0` equals
/// `0.0`), giving the triangle of the other three corners in the patch's
/// winding (`p00, p11, p01`; `p00, p10, p01` for both middle ones; `p00,
/// p10, p11`). `None` where no edge collapsed.
///
/// ```
/// use rayhit::exact::oracle::collapsed_triangle;
/// use rayhit::{Patch, Triangle, glam::Vec3};
/// let (a, b, c) = (Vec3::ZERO, Vec3::X, Vec3::Y);
/// let fan = Patch::new(a, b, a, c); // p01 = p00
/// assert_eq!(collapsed_triangle(&fan), Some(Triangle::new(a, b, c)));
/// assert_eq!(collapsed_triangle(&Patch::new(a, b, c, Vec3::ONE)), None);
/// ```
#[must_use]
pub fn collapsed_triangle<V: Vector>(p: &Patch<V>) -> Option<Triangle<V>> {
    let Patch { p00, p10, p01, p11 } = *p;
    if p10 == p00 {
        Some(Triangle::new(p00, p11, p01))
    } else if p11 == p10 || p11 == p01 {
        Some(Triangle::new(p00, p10, p01))
    } else if p01 == p00 {
        Some(Triangle::new(p00, p10, p11))
    } else {
        None
    }
}

/// The factor by which the band of [`patch_clear`] widens the
/// discriminant's rounding.
const DISC_FACTOR: i64 = 1 << 10;

/// The factor by which the band of [`patch_clear`] widens the roots'
/// and the crossings' error estimates.
const PLACE_FACTOR: f64 = 16.0;

/// The patch case is outside the ray/patch test's rounding band (the
/// `t_max` form's, closed rule: see [`Patch`]): a kernel with the
/// crate's documented guarantees answers hit or miss, and the side, as
/// [`ray_patch`](crate::exact::ray_patch) does, and reports the crossing
/// it names. `false` (an `Edge` case) unless every condition below holds
/// in exact arithmetic.
///
/// A patch with a collapsed edge ([`collapsed_triangle`]) is that
/// triangle, bit for bit: its band is the watertight test's
/// ([`triangle_clear_watertight`](super::triangle_clear_watertight)).
/// Otherwise, in the ray's sheared frame (the triangle test's), where the
/// patch's boundary is decided by the edge functions of its two
/// triangles `p00, p10, p11` and `p00, p11, p01` and its crossings by the
/// quadratic `c(u) = b0 (1 - u)^2 + 2 b1 u (1 - u) + b2 u^2` with
/// discriminant `D = b1^2 - b0 b2` (Reshetov, Ray Tracing Gems ch. 8, in
/// that frame; every bound below is evaluated in `f64` rounded up, which
/// only widens the band, and compared exactly):
///
/// - (precondition) the corners relative to the origin are within the
///   documented range: every coordinate below `2^63` (`f32`) or `2^511`
///   (`f64`) in magnitude, and the largest at least `sqrt(MIN_POSITIVE) /
///   u`;
/// - (a) the line is clear of each boundary edge's line, `p00-p10`,
///   `p10-p11`, `p11-p01`, `p01-p00`: its exact edge function (the
///   Plucker product over `d_z`) farther from zero than the test's
///   rounding of it, [`edge_function_bound`](super::edge_function_bound)
///   of the triangle holding the edge. Then each computed edge function
///   has the exact sign. The diagonal `p00-p11` needs no margin where its
///   sign cannot change the winding number the test sums: both triangles
///   compute its edge function bit for bit, negated, and the sum of the
///   two triangles' windings changes with its sign by `[s1 = s2] - [s3 =
///   s4]` (`s_i` the boundary edges' signs in order), which is zero
///   whenever its exact edge function is zero (the line through the
///   origin and `q00` then holds `q11`, on the same side, making both
///   pairs differ, or on the other, making both agree); where the
///   diagonal is within its rounding and that difference is not zero,
///   the case is not clear;
/// - (b) the discriminant is decided with room: `|D| > 2^10 (dD + E^2)`,
///   `dD` the bound on the computed discriminant's error (the
///   coefficients' errors `E_i`: the edge functions' bounds, and for
///   `b1`, the mean of the diagonal's and of the cross product `q10 x
///   q01`, that one's rounding too, carried through `b1^2 - b0 b2`, and
///   `gamma(3)` of its terms for the scaling and the products), `E` the
///   largest `E_i`. With `dD` alone the computed discriminant's sign is
///   the exact one; the factor is chosen, not derived, for what follows
///   from it: at each crossing the projected Jacobian is `+-2 sqrt(D)`,
///   which must stay clear of the rounding of the corners' orientations
///   (a two-crossing fold is only looked for where they differ in sign)
///   and of the certificate's determinant, and a simple root of the
///   computed quadratic moves by about `E / sqrt(D)`. Held with one
///   crossing too (the test's `t > 0` decision certifies it). Where the
///   winding number is zero and `D < 0`, there is no crossing, and the
///   case is a clear miss;
/// - (b') with zero winding and `D > 0`, each root `u*` of the quadratic
///   is farther than `r_u = 16 (E + gamma(8) B) / sqrt(D)` (`B` the
///   largest `|b_i| + E_i`) from 0 and 1, and where it is between them
///   the place `v*` of the line on its ruling is farther than `r_v = r_u
///   (1 + |Q_u| / |Q_v|) + 16 r_c` from 0 and 1 (`Q_u`, `Q_v` the
///   projected patch's derivatives at `(u*, v*)` brought into the square,
///   `r_c` the certified `(u, v)` radius of
///   [`Patch`'s `hit_error`](crate::Patch#method.hit_error) at `(u*,
///   v*)`, finite), or, for a `v*` more than a half outside `[0, 1]`, `r_u
///   (1 + |Q_u| / |Q_v|)` is at most a quarter: the test's `0 <= u, v <=
///   1` checks on its computed roots then agree with the exact ones (a
///   first-order estimate of how far a computed root and its `v` move,
///   with a factor 16 for the solution's own roundings and the estimate's
///   slack);
/// - (c) every crossing in the square (behind the origin too) has `t`
///   farther than 16 times its certified bound (`hit_error`'s `t` at the
///   exact crossing; finite) from 0 and from `t_max` (from `MAX` for an
///   infinite one), and two crossings both in `(0, t_max]` are farther
///   apart than 16 times the sum of theirs. The test takes a crossing as
///   in front of the origin where every corner is, or where its `t`
///   exceeds its certified bound at its own `(u, v)`, which the factor
///   takes to be within 8 times the bound at the exact crossing (chosen,
///   not derived);
/// - (d) with zero winding and a crossing, the corners' exact sheared
///   coordinates reach past each of the frame's axes through the ray, on
///   both sides, by more than their rounding
///   (`dx`, `dy` of [`edge_function_bound`](super::edge_function_bound)'s
///   derivation, the larger of the two triangles'): the test's shortcut
///   that rules out a patch whose corners all lie on one side of such an
///   axis then sees them as they are.
///
/// False too when a value is not finite or the direction is zero.
///
/// ```
/// use rayhit::exact::oracle::patch_clear;
/// use rayhit::{Patch, Ray, glam::Vec3};
/// let saddle = Patch::new(Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 1.0));
/// // Straight down at (0.3, 0.6): far from every edge and from t = 0.
/// let ray = Ray::new(Vec3::new(0.3, 0.6, 2.0), -Vec3::Z);
/// assert!(patch_clear(&ray, &saddle, f32::INFINITY));
/// // Through the edge v = 0, or ending at the crossing: not clear.
/// let edge = Ray::new(Vec3::new(0.3, 0.0, 2.0), -Vec3::Z);
/// assert!(!patch_clear(&edge, &saddle, f32::INFINITY));
/// assert!(!patch_clear(&ray, &saddle, 1.82));
/// ```
#[must_use]
pub fn patch_clear<V: Vector>(ray: &Ray<V>, patch: &Patch<V>, t_max: V::Scalar) -> bool {
    patch_band(ray, patch, t_max).is_some()
}

/// [`patch_clear`]: `Some(())` for a clear case.
fn patch_band<V: Vector>(ray: &Ray<V>, patch: &Patch<V>, t_max: V::Scalar) -> Option<()> {
    let Patch { p00, p10, p01, p11 } = *patch;
    let finite = [p00, p10, p01, p11].iter().all(|p| p.is_finite());
    if !(ray.is_valid() && finite && t_max.partial_cmp(&t_max).is_some()) {
        return None;
    }
    if let Some(tri) = collapsed_triangle(patch) {
        let exact = super::triangle(ray, &tri)?;
        return super::triangle_clear_watertight(ray, &tri, &exact, t_max).then_some(());
    }
    let line = PatchLine::new(ray, patch)?;
    in_range::<V::Scalar>(line.reach())?;
    // The margins, in units of the Plucker products (`d_z` times the edge
    // functions'), as `f64` upper bounds.
    let [first, second] = patch.triangles();
    let m1 = edge_margin_up(ray, &first)?;
    let m2 = edge_margin_up(ray, &second)?;
    let mx = edge_margin_up(ray, &Triangle::new(p10, p01, p00))?;
    let md = m1.min(m2);
    let exponent = line.plucker_exponent();
    let s = |i: usize, j: usize| line.plucker(i, j);
    // `|x| 2^exponent > m`, exactly.
    let beyond = |x: &BigInt, m: f64| above(x, exponent, m);
    // (a) The boundary edges 00-10, 10-11, 11-01, 01-00.
    let edges = [s(0, 1), s(1, 3), s(3, 2), s(2, 0)];
    if !edges
        .iter()
        .zip([m1, m1, m2, m2])
        .all(|(e, m)| beyond(e, m))
    {
        return None;
    }
    let sign = |x: &BigInt| x.is_positive();
    let pair = |a: usize, b: usize| sign(&edges[a]) == sign(&edges[b]);
    let diagonal = s(3, 0);
    if !beyond(&diagonal, md) && pair(0, 1) != pair(2, 3) {
        return None;
    }
    // The winding number, from the first triangle (00-10, 10-11, 11-00)
    // and the second (00-11, 11-01, 01-00); a diagonal of exactly zero
    // taken as positive (where the check above passed, either sign gives
    // the same sum).
    let covers = |e: [&BigInt; 3]| {
        let all = |f: fn(&BigInt) -> bool| e.iter().all(|x| f(x));
        i32::from(all(BigInt::is_positive)) - i32::from(all(BigInt::is_negative))
    };
    let signed = if diagonal.is_zero() {
        BigInt::from(1)
    } else {
        diagonal.clone()
    };
    let winding =
        covers([&edges[0], &edges[1], &signed]) + covers([&-&signed, &edges[2], &edges[3]]);
    let across = -diagonal.clone();
    // (b) The quadratic's Bernstein coefficients (`b1` twice over, to stay
    // in integers), bounds on their errors and on the discriminant's, all
    // rounded up.
    let b0 = -edges[3].clone();
    let b2 = edges[1].clone();
    let twice_b1 = &across + s(1, 2);
    let up = |x: &BigInt, halve: bool| {
        let e = exponent - i64::from(halve);
        scaled_f64(&x.abs(), e).next_up()
    };
    let (a0, a1, a2) = (up(&b0, false), up(&twice_b1, true), up(&b2, false));
    let u = V::Scalar::UNIT_ROUNDOFF.to_f64();
    let g = |n: f64| div_up(n * u, 1.0 - n * u);
    let tiny = V::Scalar::TINY.to_f64();
    let dz = ray.dir[main_axis(ray.dir)].to_f64().abs();
    let half_sum = mul_up(add_up(md, mx), 0.5);
    let e1 = add_up(
        add_up(half_sum, mul_up(u, add_up(a1, half_sum))),
        mul_up(tiny, dz),
    );
    let (e0, e2) = (m2, m1);
    let (g0, g1, g2) = (add_up(a0, e0), add_up(a1, e1), add_up(a2, e2));
    let e_max = e0.max(e1).max(e2);
    let b_max = g0.max(g1).max(g2);
    let disc_err = [
        mul_up(mul_up(2.0, a1), e1),
        mul_up(e1, e1),
        mul_up(a0, e2),
        mul_up(a2, e0),
        mul_up(e0, e2),
        mul_up(g(3.0), add_up(mul_up(g1, g1), mul_up(g0, g2))),
        mul_up(mul_up(4.0 * tiny, b_max), b_max),
    ]
    .into_iter()
    .fold(0.0, add_up);
    let threshold = mul_up(DISC_FACTOR as f64, add_up(disc_err, mul_up(e_max, e_max)));
    // `D = b1^2 - b0 b2 = four_d / 4`, in units of `2^(2 exponent)`.
    let four_d = &twice_b1 * &twice_b1 - BigInt::from(4) * &b0 * &b2;
    // `|D| > threshold`: `|four_d| 2^(2 exponent - 2) > threshold`.
    if !above(&four_d, 2 * exponent - 2, threshold) {
        return None;
    }
    let crossings: Vec<PatchCrossing> = if winding != 0 {
        let e = patch_crossings(&line);
        (e.len() == 1).then_some(e)?
    } else if four_d.is_negative() {
        // No root: a clear miss.
        return Some(());
    } else {
        // (b') Each root clear of the square's edges.
        let noise = add_up(e_max, mul_up(g(8.0), b_max));
        let r_u = PLACE_FACTOR * noise / scaled_f64(&four_d, 2 * exponent - 2).sqrt();
        let frame = Sheared::new(&line, main_axis(ray.dir));
        let mut found = Vec::new();
        for root in line.roots() {
            let u = line.u(&root);
            if !clear_of_ends(&u, r_u)? {
                return None;
            }
            let u_f = u.to_f64();
            if !(0.0 < u_f && u_f < 1.0) {
                continue;
            }
            let (v, _) = line.place(&root)?;
            let v_f = v.to_f64();
            // How far the computed root's `v` moves with it.
            let moved = r_u * (1.0 + frame.stretch(u_f, v_f.clamp(0.0, 1.0))?);
            if !(-0.5..=1.5).contains(&v_f) {
                // Far outside: the test's `v` would be off by more than a
                // half.
                if moved > 0.25 {
                    return None;
                }
                continue;
            }
            let r_v = moved + PLACE_FACTOR * certified(ray, patch, u_f, v_f)?.1;
            if !clear_of_ends(&v, r_v)? {
                return None;
            }
            if 0.0 < v_f && v_f < 1.0 {
                found.push(line.crossing(&root, true)?);
            }
        }
        if found.len() == 2 {
            // (d) The corners on both sides of each axis.
            let (x1, y1) = coordinate_bound_up(ray, &first)?;
            let (x2, y2) = coordinate_bound_up(ray, &second)?;
            if !(frame.straddles(0, x1.max(x2)) && frame.straddles(1, y1.max(y2))) {
                return None;
            }
        }
        (found.len() != 1).then_some(found)?
    };
    // (c) The crossings' t.
    let end = if t_max < V::Scalar::MAX {
        t_max.to_f64()
    } else {
        V::Scalar::MAX.to_f64()
    };
    let mut ahead = Vec::new();
    for x in &crossings {
        let (bound, _) = certified(ray, patch, x.u.to_f64(), x.v.to_f64())?;
        let room = PLACE_FACTOR * bound;
        if !(apart(&x.t, 0.0, room)? && apart(&x.t, end, room)?) {
            return None;
        }
        if x.t.cmp_rational(&R::zero()) == Ordering::Greater
            && x.t.cmp_rational(&sum(end, 0.0)?) != Ordering::Greater
        {
            ahead.push((x.t.clone(), bound));
        }
    }
    if let [(t1, b1), (t2, b2)] = ahead.as_slice() {
        let room = R::from_float(PLACE_FACTOR * (b1 + b2))?;
        let gap = t2.clone() - t1.clone();
        let gap = if gap.sign() == Ordering::Less {
            -gap
        } else {
            gap
        };
        (gap.cmp_rational(&room) == Ordering::Greater).then_some(())?;
    }
    Some(())
}

/// Whether `x` is farther than `room` (an `f64`, at least zero) from 0
/// and from 1; `None` where `room` is not finite.
fn clear_of_ends(x: &Surd, room: f64) -> Option<bool> {
    Some(apart(x, 0.0, room)? && apart(x, 1.0, room)?)
}

/// Whether `x` is farther than `room` from `y` (floats; `None` where one
/// is not finite).
fn apart(x: &Surd, y: f64, room: f64) -> Option<bool> {
    Some(
        x.cmp_rational(&sum(y, -room)?) == Ordering::Less
            || x.cmp_rational(&sum(y, room)?) == Ordering::Greater,
    )
}

/// `a + b` for floats, exactly, as a rational not reduced (`None` where
/// one is not finite).
fn sum(a: f64, b: f64) -> Option<R> {
    use num_traits::float::FloatCore;
    if !(a.is_finite() && b.is_finite()) {
        return None;
    }
    let part = |x: f64| {
        let (m, e, sign) = x.integer_decode();
        (BigInt::from(sign) * BigInt::from(m), i64::from(e))
    };
    let ((ma, ea), (mb, eb)) = (part(a), part(b));
    let e = ea.min(eb);
    let n = (ma << (ea - e).unsigned_abs()) + (mb << (eb - e).unsigned_abs());
    let one = BigInt::from(1);
    Some(if e >= 0 {
        R::new_raw(n << e.unsigned_abs(), one)
    } else {
        R::new_raw(n, one << e.unsigned_abs())
    })
}

/// [`Patch`'s `hit_error`](crate::Patch#method.hit_error) at `(u, v)`:
/// the bounds on `t` and on `u`, `v`, as `f64`; `None` where they are not
/// finite.
fn certified<V: Vector>(ray: &Ray<V>, patch: &Patch<V>, u: f64, v: f64) -> Option<(f64, f64)> {
    let f = V::Scalar::from_f64;
    let probe = crate::PatchHit {
        t: V::Scalar::ONE,
        u: f(u),
        v: f(v),
        side: Side::Front,
    };
    let e = crate::Surface::hit_error(patch, ray, &probe);
    let (t, uv) = (e.t.to_f64(), e.u.to_f64());
    (t.is_finite() && uv.is_finite()).then_some((t, uv))
}

/// The corners' `x` and `y` in the ray's sheared frame (the triangle
/// test's, on the main axis `kz` of [`main_axis`]), exactly: `x = X 2^E /
/// d_kz` with the integer `X = q_kx d_kz - d_kx q_kz` (`q` a corner less
/// the origin, in the line's units), and `y` likewise.
struct Sheared {
    x: [BigInt; 4],
    y: [BigInt; 4],
    /// `d_kz` in the line's integers, and `E`.
    dz: BigInt,
    e: i64,
}

impl Sheared {
    fn new(line: &PatchLine, kz: usize) -> Self {
        let (kx, ky) = ((kz + 1) % 3, (kz + 2) % 3);
        let d = &line.d;
        let at = |k: usize| {
            line.offsets
                .clone()
                .map(|q| &q[k] * &d[kz] - &d[k] * &q[kz])
        };
        Self {
            x: at(kx),
            y: at(ky),
            dz: d[kz].clone(),
            e: line.exponents.0,
        }
    }

    /// `|Q_u| / |Q_v|` at `(u, v)`, in `f64` (the common factor `2^E /
    /// d_kz` cancels); `None` where `Q_v` is zero.
    fn stretch(&self, u: f64, v: f64) -> Option<f64> {
        let bits = self
            .x
            .iter()
            .chain(&self.y)
            .map(BigInt::bits)
            .max()
            .unwrap_or(0);
        let top = -i64::try_from(bits).ok()?;
        let f = |c: &[BigInt; 4]| c.clone().map(|x| scaled_f64(&x, top));
        let (x, y) = (f(&self.x), f(&self.y));
        let du = |c: &[f64; 4]| (1.0 - v) * (c[1] - c[0]) + v * (c[3] - c[2]);
        let dv = |c: &[f64; 4]| (1.0 - u) * (c[2] - c[0]) + u * (c[3] - c[1]);
        let qu = du(&x).hypot(du(&y));
        let qv = dv(&x).hypot(dv(&y));
        let ratio = qu / qv;
        ratio.is_finite().then_some(ratio)
    }

    /// Whether the corners' coordinate on axis `k` (0 for `x`, 1 for `y`)
    /// reaches beyond `-m` and beyond `m`: some `X 2^E / d_kz < -m` and
    /// some `> m`, decided in integers.
    fn straddles(&self, k: usize, m: f64) -> bool {
        let c = if k == 0 { &self.x } else { &self.y };
        let flip = |x: &BigInt| if self.dz.is_negative() { -x } else { x.clone() };
        let beyond = |x: BigInt| x.is_positive() && above_times(&x, self.e, m, &self.dz);
        c.iter().any(|x| beyond(-flip(x))) && c.iter().any(|x| beyond(flip(x)))
    }
}

/// The documented range of the patch test's guarantees, for `m` the
/// largest magnitude of a corner coordinate relative to the origin: below
/// `2^63` (`f32`) or `2^511` (`f64`), and at least `sqrt(MIN_POSITIVE) /
/// u`.
fn in_range<F: Scalar>(m: f64) -> Option<()> {
    let single = F::UNIT_ROUNDOFF.to_f64() > 1e-10;
    let top = if single {
        2f64.powi(63)
    } else {
        2f64.powi(511)
    };
    let floor = F::MIN_POSITIVE.to_f64().sqrt() / F::UNIT_ROUNDOFF.to_f64();
    (m < top && m >= floor).then_some(())
}
