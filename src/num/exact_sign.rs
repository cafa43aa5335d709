//! Exact signs and error-free transformations: the fallbacks that decide
//! a sign rounding cannot (an edge function that rounds to zero, an entry
//! face near an edge, whether a triangle has zero area), and the
//! floating-point expansions the exact plane crossing
//! (`ray/exact_crossing.rs`) and the exact module's filter build on.

use super::Scalar;

/// In `f64` the two products of `f32` values are exact (24 + 24 bits fit
/// in 53, and exponents from `2^-298` to `2^256` are in range), and a
/// rounded difference of two floats is zero only when they are equal, so
/// the `f64` result has the exact sign. Narrowing to `f32` may flush a
/// tiny nonzero value to zero; it is then replaced by the smallest
/// subnormal of the same sign, so that the sign survives.
#[inline]
pub(crate) fn f32(a: f32, b: f32, c: f32, d: f32) -> f32 {
    let wide = f64::from(a) * f64::from(b) - f64::from(c) * f64::from(d);
    let narrow = wide as f32;
    if narrow == 0.0 && wide != 0.0 {
        let tiny = f32::from_bits(1);
        if wide > 0.0 { tiny } else { -tiny }
    } else {
        narrow
    }
}

/// `a*b = p + e` exactly, with `p = fl(a*b)` and `e = fma(a, b, -p)`, as
/// long as `e` does not underflow. The rounded difference `fl(p - q)` is
/// zero only when `p == q`; then `a*b - c*d = e_ab - e_cd` exactly, and
/// `fl(e_ab - e_cd)` has its sign. An exact zero keeps the rounded
/// difference's zero, its sign included, as the `f32` form does: so the
/// value is the plain `a*b - c*d`'s, bit for bit, wherever that is exact,
/// and a fast path that knows the difference is exactly zero (both
/// products zero) may keep it.
#[inline]
pub(crate) fn f64(a: f64, b: f64, c: f64, d: f64) -> f64 {
    let p = a * b;
    let q = c * d;
    let diff = p - q;
    if diff != 0.0 {
        return diff;
    }
    let exact = fma(a, b, -p) - fma(c, d, -q);
    if exact == 0.0 { diff } else { exact }
}

/// The products of the pairs, as `f64` terms whose exact sum is the exact
/// sum of the products: each product's rounded value and its exact error
/// (at most 16 terms for 8 pairs).
fn products(terms: &[(f64, f64)]) -> ([f64; 16], usize) {
    let mut out = [0.0; 16];
    let mut n = 0;
    for &(a, b) in terms.iter().take(8) {
        let p = a * b;
        out[n] = p;
        out[n + 1] = fma(a, b, -p);
        n += 2;
    }
    (out, n)
}

/// The exact sign of the sum of the first `n` terms: they are added one
/// by one to a nonoverlapping expansion (components of increasing
/// magnitude, each a two-sum's exact error), dropping zero components;
/// the sign of an expansion is that of its largest component.
fn sum_sign((terms, n): ([f64; 16], usize)) -> core::cmp::Ordering {
    let two_sum = |a: f64, b: f64| {
        let s = a + b;
        let bb = s - a;
        (s, (a - (s - bb)) + (b - bb))
    };
    let mut e = [0.0f64; 16];
    let mut len = 0;
    for &x in &terms[..n] {
        let mut q = x;
        let mut kept = 0;
        for i in 0..len {
            let (s, err) = two_sum(q, e[i]);
            if err != 0.0 {
                e[kept] = err;
                kept += 1;
            }
            q = s;
        }
        if q != 0.0 {
            e[kept] = q;
            kept += 1;
        }
        len = kept;
    }
    if len == 0 {
        core::cmp::Ordering::Equal
    } else if e[len - 1] > 0.0 {
        core::cmp::Ordering::Greater
    } else {
        core::cmp::Ordering::Less
    }
}

#[inline]
fn fma(a: f64, b: f64, c: f64) -> f64 {
    #[cfg(feature = "std")]
    {
        a.mul_add(b, c)
    }
    #[cfg(not(feature = "std"))]
    {
        libm::fma(a, b, c)
    }
}

/// `(s, e)` with `s = fl(a - b)` and `s + e = a - b` exactly (Knuth's
/// two-sum; exact whenever `a - b` does not overflow).
#[inline]
pub(crate) fn two_diff<F: Scalar>(a: F, b: F) -> (F, F) {
    let s = a - b;
    let bb = s - a;
    (s, (a - (s - bb)) - (b + bb))
}

/// The exact sign of `sum a_i * b_i` over at most eight pairs of `f64`.
///
/// Each product is split into its rounded value and its exact error by a
/// fused multiply-add (exact while the products are above `2^-969` or
/// zero), and the sixteen terms are summed exactly as a floating-point
/// expansion (Shewchuk, "Adaptive Precision Floating-Point Arithmetic and
/// Fast Robust Geometric Predicates", 1997: growing a nonoverlapping
/// expansion with error-free sums), whose sign is that of its largest
/// component.
pub(crate) fn sum_of_products_sign(terms: &[(f64, f64)]) -> core::cmp::Ordering {
    sum_sign(products(terms))
}

/// `x` times the power of two that brings `m` (positive, finite) into
/// `[1, 2)`: exact unless the product leaves the normal range.
pub(crate) fn scale_to_one(x: f64, m: f64) -> f64 {
    let pow2 = |k: i32| f64::from_bits(((1023 + k) as u64) << 52);
    let exponent = |m: f64| ((m.to_bits() >> 52) & 0x7ff) as i32 - 1023;
    // A subnormal `m` (biased exponent 0) is lifted by 2^64 first, and `x`
    // with it: x 2^-e(m) = (x 2^64) 2^-e(m 2^64).
    let (x, e) = if exponent(m) == -1023 {
        (x * pow2(64), exponent(m * pow2(64)))
    } else {
        (x, exponent(m))
    };
    let half = -e / 2;
    x * pow2(half) * pow2(-e - half)
}

/// `a*b = p + e` exactly (`p = fl(a*b)`, `e = fma(a, b, -p)`), while `e`
/// does not underflow.
#[inline]
pub(crate) fn two_product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, fma(a, b, -p))
}

/// A nonoverlapping floating-point expansion grown one term at a time
/// (Shewchuk's grow-expansion with zero elimination), for the sign of a
/// long exact sum. Its nonzero components have disjoint bit ranges within
/// `f64`'s 2,100 exponents, so 64 slots hold any expansion of finite terms;
/// a non-finite term (an overflow) marks it undecided instead.
#[derive(Clone)]
pub(crate) struct Expansion {
    e: [f64; 64],
    len: usize,
    ok: bool,
}

impl Expansion {
    pub(crate) fn new() -> Self {
        Self {
            e: [0.0; 64],
            len: 0,
            ok: true,
        }
    }

    pub(crate) fn add(&mut self, x: f64) {
        if !x.is_finite() {
            self.ok = false;
        }
        if !self.ok || x == 0.0 {
            return;
        }
        let two_sum = |a: f64, b: f64| {
            let s = a + b;
            let bb = s - a;
            (s, (a - (s - bb)) + (b - bb))
        };
        let mut q = x;
        let mut kept = 0;
        for i in 0..self.len {
            let (s, err) = two_sum(q, self.e[i]);
            if err != 0.0 {
                self.e[kept] = err;
                kept += 1;
            }
            q = s;
        }
        if !q.is_finite() || kept >= self.e.len() {
            self.ok = false;
            return;
        }
        if q != 0.0 {
            self.e[kept] = q;
            kept += 1;
        }
        self.len = kept;
    }

    /// Adds `sign * f[0] * f[1] * ... ` exactly: the product of up to four
    /// factors as a sum of `2^(n-1)` floats (each step splits every term's
    /// product with the next factor into its rounded value and exact
    /// error).
    pub(crate) fn add_product(&mut self, f: &[f64], negate: bool) {
        let mut terms = [0.0f64; 8];
        let mut n = 0;
        if let Some((&first, rest)) = f.split_first() {
            terms[0] = if negate { -first } else { first };
            n = 1;
            for &g in rest.iter().take(3) {
                let mut next = [0.0f64; 8];
                for (i, &t) in terms[..n].iter().enumerate() {
                    let (p, e) = two_product(t, g);
                    next[2 * i] = p;
                    next[2 * i + 1] = e;
                }
                terms = next;
                n *= 2;
            }
        }
        for &t in &terms[..n] {
            self.add(t);
        }
    }

    /// The largest component (zero for an empty expansion).
    pub(crate) fn lead(&self) -> f64 {
        if self.len == 0 {
            0.0
        } else {
            self.e[self.len - 1]
        }
    }

    /// The nonzero components, smallest first.
    pub(crate) fn components(&self) -> &[f64] {
        &self.e[..self.len]
    }

    /// The sign of the exact sum, `None` when a term or a partial sum was
    /// not finite.
    pub(crate) fn sign(&self) -> Option<core::cmp::Ordering> {
        if !self.ok {
            return None;
        }
        Some(match self.len {
            0 => core::cmp::Ordering::Equal,
            n if self.e[n - 1] > 0.0 => core::cmp::Ordering::Greater,
            _ => core::cmp::Ordering::Less,
        })
    }
}

/// `floor(log2 |v|)` for a finite nonzero `v` (subnormals included).
pub(crate) fn exponent(v: f64) -> i32 {
    let b = v.abs().to_bits();
    let e = (b >> 52) as i32;
    if e == 0 {
        (63 - b.leading_zeros() as i32) - 1074
    } else {
        e - 1023
    }
}

/// `v * 2^k`, in steps that each stay within the normal powers of two:
/// exact unless the result overflows or loses bits to underflow.
pub(crate) fn scale2(v: f64, k: i32) -> f64 {
    let pow2 = |k: i32| f64::from_bits(((1023 + k) as u64) << 52);
    let mut v = v;
    let mut k = k;
    while k != 0 {
        let step = k.clamp(-1000, 1000);
        v *= pow2(step);
        k -= step;
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_sign_f32_sees_what_f32_cannot() {
        // 1.1 * 1.1 and 1.21 round to nearby f32 values whose products in
        // f32 tie; only the exact products tell them apart.
        let a = 1.0f32 + f32::EPSILON;
        let c = 1.0f32 + 2.0 * f32::EPSILON;
        let d = 1.0f32;
        // a*a = 1 + 2e + e^2 exactly, c*d = 1 + 2e: a*a - c*d = e^2 > 0,
        // but in f32 both products round to 1 + 2e and the difference is 0.
        assert_eq!(a * a - c * d, 0.0);
        assert!(f32::diff_of_products_exact_sign(a, a, c, d) > 0.0);
        assert!(f32::diff_of_products_exact_sign(c, d, a, a) < 0.0);
        // A difference too small for f32 keeps its sign.
        let tiny = f32::from_bits(1);
        assert!(f32::diff_of_products_exact_sign(tiny, tiny, 0.0, 0.0) > 0.0);
        assert!(f32::diff_of_products_exact_sign(0.0, 0.0, tiny, tiny) < 0.0);
        assert_eq!(f32::diff_of_products_exact_sign(2.0, 3.0, 6.0, 1.0), 0.0);
    }

    #[test]
    fn exact_sign_f64_sees_what_f64_cannot() {
        let e = f64::EPSILON;
        let a = 1.0 + e;
        let c = 1.0 + 2.0 * e;
        assert_eq!(a * a - c, 0.0);
        assert!(f64::diff_of_products_exact_sign(a, a, c, 1.0) > 0.0);
        assert!(f64::diff_of_products_exact_sign(c, 1.0, a, a) < 0.0);
        assert_eq!(f64::diff_of_products_exact_sign(2.0, 3.0, 6.0, 1.0), 0.0);
        // An exact zero is the plain difference's zero, its sign included,
        // in both precisions: `-0 - +0` is `-0`. (The error terms' `fma`s
        // are `+0` here, whose difference would be `+0`.)
        assert_eq!(
            f64::diff_of_products_exact_sign(0.0, -1.0, 0.0, 1.0).to_bits(),
            (-0.0f64).to_bits()
        );
        assert_eq!(
            f32::diff_of_products_exact_sign(0.0, -1.0, 0.0, 1.0).to_bits(),
            (-0.0f32).to_bits()
        );
    }
}
