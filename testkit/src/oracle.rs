//! `rayhit::exact::oracle` for inputs a test knows are finite: the same
//! names, where the ones that answer `None` for a non-finite input (`r`,
//! `rv`, `triangle`, `box_face`, `segment_crossing`, `mt_bounds`) panic
//! instead, which fails the test that passed such an input. Everything else
//! is the crate's own.

use rayhit::exact::oracle as exact;
pub use rayhit::exact::oracle::*;
use rayhit::{Aabb, BoxFace, Ray, Scalar, Triangle, Vector};

/// Why an exact value is missing: the caller's input was not finite.
const FINITE: &str = "a test input the caller made finite";

/// The exact value of a finite float.
pub fn r<F: Scalar>(x: F) -> R {
    exact::r(x).expect(FINITE)
}

/// The exact value of a finite vector.
pub fn rv<V: Vector>(v: V) -> R3 {
    exact::rv(v).expect(FINITE)
}

/// [`exact::triangle`] of finite inputs.
pub fn triangle<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>) -> ExactTriangle {
    exact::triangle(ray, tri).expect(FINITE)
}

/// [`exact::box_face`] of finite inputs.
pub fn box_face<V: Vector>(ray: &Ray<V>, b: &Aabb<V>) -> (Option<BoxFace>, bool) {
    exact::box_face(ray, b).expect(FINITE)
}

/// [`exact::segment_crossing`] of finite inputs, a moving ray and a
/// segment not seen end-on.
pub fn segment_crossing<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>) -> R {
    exact::segment_crossing(ray, tri).expect("finite inputs, a segment not seen end-on")
}

/// [`exact::mt_bounds`] of finite inputs.
pub fn mt_bounds<V: Vector>(ray: &Ray<V>, tri: &Triangle<V>, u: &R, v: &R) -> (R, R, R) {
    exact::mt_bounds(ray, tri, u, v).expect(FINITE)
}

/// A float and a bound on its distance from an exact value (which lies in
/// `[v - e, v + e]`): the float filter in front of exact arithmetic. Tests
/// evaluate an expression on [`Bounded`] values first and fall back on big
/// rationals only where [`Bounded::sign`] cannot answer.
///
/// Built from floats taken as exact ([`Bounded::exact`]: every `f32` and
/// `f64` is one) and carried through `+`, `-` and `*` in `f64` with a
/// running error bound. With `u = 2^-53`, round to nearest gives `fl(x) =
/// x / (1 + delta)`, `|delta| <= u` (Higham, Accuracy and Stability of
/// Numerical Algorithms, 2002, section 2.2), so `|x - fl(x)| <= u |fl(x)|`
/// wherever the result is normal; a sum or difference that is subnormal is
/// exact, and a product that underflows is off by at most `2^-1075`, so
/// `eta = 2^-1074` is added for products. Then, with `|X - x| <= ex` and
/// `|Y - y| <= ey` for the exact `X`, `Y` and the floats `x`, `y`:
///
/// - `X +- Y` is within `ex + ey + u |fl(x +- y)|` of `fl(x +- y)`;
/// - `X Y` is within `|x| ey + |y| ex + ex ey + u |fl(x y)| + eta` of
///   `fl(x y)`.
///
/// Every bound is evaluated on non-negative terms, each operation's result
/// stepped one float up (`next_up`), so the computed bound is at least the
/// exact one. An overflow leaves a value or bound that is not finite, and
/// [`Bounded::sign`] then declines.
#[derive(Clone, Copy, Debug)]
pub struct Bounded {
    /// The computed value.
    pub v: f64,
    /// The bound on its distance from the exact value.
    pub e: f64,
}

/// `f64`'s unit roundoff, `2^-53`.
const U: f64 = f64::EPSILON / 2.0;

/// `a + b`, at least the exact sum of two non-negative floats.
fn add_up(a: f64, b: f64) -> f64 {
    (a + b).next_up()
}

/// `a b`, at least the exact product of two non-negative floats.
fn mul_up(a: f64, b: f64) -> f64 {
    (a * b).next_up()
}

impl core::ops::Add for Bounded {
    type Output = Self;

    /// The sum.
    fn add(self, o: Self) -> Self {
        let v = self.v + o.v;
        Self {
            v,
            e: add_up(add_up(self.e, o.e), mul_up(U, v.abs())),
        }
    }
}

impl core::ops::Sub for Bounded {
    type Output = Self;

    /// The difference.
    fn sub(self, o: Self) -> Self {
        self + Self { v: -o.v, e: o.e }
    }
}

impl core::ops::Mul for Bounded {
    type Output = Self;

    /// The product.
    fn mul(self, o: Self) -> Self {
        let v = self.v * o.v;
        let carried = add_up(
            add_up(mul_up(self.v.abs(), o.e), mul_up(o.v.abs(), self.e)),
            mul_up(self.e, o.e),
        );
        Self {
            v,
            e: add_up(add_up(carried, mul_up(U, v.abs())), f64::from_bits(1)),
        }
    }
}

impl Bounded {
    /// A float, exactly.
    pub fn exact(x: f64) -> Self {
        Self { v: x, e: 0.0 }
    }

    /// The exact value's sign where the bound decides it: `Some` when the
    /// interval `[v - e, v + e]` lies on one side of zero (or is the exact
    /// zero), `None` otherwise or where something overflowed. (`v > e` is
    /// compared exactly: both are floats.)
    pub fn sign(self) -> Option<core::cmp::Ordering> {
        use core::cmp::Ordering;
        if !(self.v.is_finite() && self.e.is_finite()) {
            None
        } else if self.v > self.e {
            Some(Ordering::Greater)
        } else if -self.v > self.e {
            Some(Ordering::Less)
        } else if self.v == 0.0 && self.e == 0.0 {
            Some(Ordering::Equal)
        } else {
            None
        }
    }
}

/// The three components of a vector as [`Bounded`] values, exactly.
pub fn bv<V: Vector>(p: V) -> [Bounded; 3] {
    [p.x(), p.y(), p.z()].map(|c| Bounded::exact(c.to_f64()))
}

/// `a - b`, componentwise, on [`Bounded`] values.
pub fn bsub(a: &[Bounded; 3], b: &[Bounded; 3]) -> [Bounded; 3] {
    [0, 1, 2].map(|k| a[k] - b[k])
}

/// `a . b` on [`Bounded`] values.
pub fn bdot(a: &[Bounded; 3], b: &[Bounded; 3]) -> Bounded {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `a x b` on [`Bounded`] values.
pub fn bcross(a: &[Bounded; 3], b: &[Bounded; 3]) -> [Bounded; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::cmp::Ordering;

    /// Every [`Bounded`] result's interval contains the exact value, on
    /// expressions where rounding cancels (`(1 + e)^2 - (1 + 2e)` is `e^2`
    /// exactly while `f64` computes zero), with underflow and overflow;
    /// and the sign answers only where the interval decides it.
    #[test]
    fn bounded_intervals_hold_the_exact_value() {
        let e = f64::EPSILON;
        let (a, c) = (Bounded::exact(1.0 + e), Bounded::exact(1.0 + 2.0 * e));
        let x = a * a - c;
        let exact = (r(1.0 + e) * r(1.0 + e)) - r(1.0 + 2.0 * e);
        assert!(close(x.v, &exact, x.e), "{x:?}");
        assert_eq!(x.sign(), None, "rounding hid e^2: no sign");
        let tiny = Bounded::exact(f64::from_bits(1));
        let t2 = tiny * tiny;
        assert_eq!(t2.v, 0.0);
        assert_eq!(t2.sign(), None, "an underflowed product: no sign");
        let big = Bounded::exact(f64::MAX);
        assert_eq!((big * big).sign(), None, "an overflow: no sign");
        let (two, three) = (Bounded::exact(2.0), Bounded::exact(3.0));
        assert_eq!((two * three - Bounded::exact(6.0)).sign(), None);
        // A computed zero carries a bound of one subnormal (each bound is
        // stepped up), so exact arithmetic decides it.
        assert_eq!((two - two).sign(), None);
        assert_eq!(Bounded::exact(0.0).sign(), Some(Ordering::Equal));
        assert_eq!((two * three - two).sign(), Some(Ordering::Greater));
        // Random dot and cross products against big rationals.
        let mut rng = crate::rng::Pcg32::new(7);
        for _ in 0..10_000 {
            let mut p = || {
                let k = (rng.below(80) as i32) - 40;
                let m = f64::from(rng.next_u32()) / f64::from(u32::MAX);
                (m * 2.0 - 1.0) * 2f64.powi(k)
            };
            let (u, v, w) = ([p(), p(), p()], [p(), p(), p()], [p(), p(), p()]);
            let b = |x: [f64; 3]| x.map(Bounded::exact);
            let got = bdot(&bcross(&bsub(&b(u), &b(w)), &b(v)), &b(w));
            let q = |x: [f64; 3]| x.map(r);
            let want = dot(&cross(&sub(&q(u), &q(w)), &q(v)), &q(w));
            assert!(close(got.v, &want, got.e), "{u:?} {v:?} {w:?}");
            if let Some(s) = got.sign() {
                assert_eq!(s, want.cmp(&int(0)));
            }
        }
    }
}
