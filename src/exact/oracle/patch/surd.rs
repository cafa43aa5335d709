//! Numbers `p + q sqrt(D)` of one quadratic field, for the patch's
//! exact crossings: [`Surd`] (rational parts) and [`Zd`] (integer
//! parts over one scale), and their signs without a square root.

use super::super::triangle::I3;
use super::super::values::*;
use core::cmp::Ordering;
use core::ops::{Add, Mul, Neg, Sub};
use num_bigint::{BigInt, Sign};
use num_traits::{Signed, Zero};

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
pub(super) fn surd_sign(
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

pub(super) fn int_sign(x: &BigInt) -> Ordering {
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
pub(super) struct Zd {
    pub(super) x: BigInt,
    pub(super) y: BigInt,
}

impl Zd {
    pub(super) fn int(x: BigInt) -> Self {
        Self {
            x,
            y: BigInt::zero(),
        }
    }

    pub(super) fn add(&self, o: &Zd) -> Zd {
        Zd {
            x: &self.x + &o.x,
            y: &self.y + &o.y,
        }
    }

    pub(super) fn sub(&self, o: &Zd) -> Zd {
        Zd {
            x: &self.x - &o.x,
            y: &self.y - &o.y,
        }
    }

    pub(super) fn mul(&self, o: &Zd, disc: &BigInt) -> Zd {
        Zd {
            x: &self.x * &o.x + &self.y * &o.y * disc,
            y: &self.x * &o.y + &self.y * &o.x,
        }
    }

    pub(super) fn scale(&self, k: &BigInt) -> Zd {
        Zd {
            x: &self.x * k,
            y: &self.y * k,
        }
    }

    pub(super) fn is_zero(&self) -> bool {
        self.x.is_zero() && self.y.is_zero()
    }

    pub(super) fn sign(&self, disc: &BigInt) -> Ordering {
        let one = BigInt::from(1);
        surd_sign((&self.x, &one), (&self.y, &one), (disc, &one))
    }

    /// `self / (k 2^shift)` as a [`Surd`] of radicand `disc` (`k`
    /// nonzero). Its rationals are not reduced (a greatest common divisor
    /// of numbers of thousands of bits costs more than all the rest):
    /// their values are what is read.
    pub(super) fn over(&self, k: &BigInt, shift: i64, disc: &BigInt) -> Surd {
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
pub(super) type Z3 = [Zd; 3];

/// `a + u b` for integer vectors `a`, `b` and `u` in `Z[sqrt(D)]`, times
/// the integer `s` on `a`: `s a + u b`.
pub(super) fn affine(s: &BigInt, a: &I3, u: &Zd, b: &I3) -> Z3 {
    [0, 1, 2].map(|k| Zd {
        x: s * &a[k] + &u.x * &b[k],
        y: &u.y * &b[k],
    })
}

/// `a x d` for an integer `d`.
pub(super) fn cross_int(a: &Z3, d: &I3) -> Z3 {
    [0, 1, 2].map(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        a[j].scale(&d[k]).sub(&a[k].scale(&d[j]))
    })
}

pub(super) fn z_cross(a: &Z3, b: &Z3, disc: &BigInt) -> Z3 {
    [0, 1, 2].map(|i| {
        let (j, k) = ((i + 1) % 3, (i + 2) % 3);
        a[j].mul(&b[k], disc).sub(&a[k].mul(&b[j], disc))
    })
}

pub(super) fn z_dot(a: &Z3, b: &Z3, disc: &BigInt) -> Zd {
    a[0].mul(&b[0], disc)
        .add(&a[1].mul(&b[1], disc))
        .add(&a[2].mul(&b[2], disc))
}
