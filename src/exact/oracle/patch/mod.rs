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

use super::triangle::{I3, icross, idot, integers, isub};
use super::values::*;
use crate::num::exact_sign::scale2;
use crate::{Patch, Ray, Scalar, Side, Triangle, Vector};
use core::cmp::Ordering;
use num_bigint::BigInt;
use num_traits::{Signed, Zero};
use std::vec;
use std::vec::Vec;

mod band;
mod surd;
#[cfg(test)]
mod tests;

pub use band::*;
pub use surd::*;

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
