//! Exact signs and error-free transformations: the fallbacks that decide
//! a sign rounding cannot (an edge function that rounds to zero, an entry
//! face near an edge, whether a triangle has zero area), and for the exact
//! module's float filter, a Plucker product against a float.

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
/// `fl(e_ab - e_cd)` has its sign.
#[inline]
pub(crate) fn f64(a: f64, b: f64, c: f64, d: f64) -> f64 {
    let p = a * b;
    let q = c * d;
    let diff = p - q;
    if diff != 0.0 {
        return diff;
    }
    fma(a, b, -p) - fma(c, d, -q)
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
fn two_product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, fma(a, b, -p))
}

/// A nonoverlapping floating-point expansion grown one term at a time
/// (Shewchuk's grow-expansion with zero elimination), for the sign of a
/// long exact sum. Its nonzero components have disjoint bit ranges within
/// `f64`'s 2,100 exponents, so 64 slots hold any expansion of finite terms;
/// a non-finite term (an overflow) marks it undecided instead.
#[derive(Clone)]
struct Expansion {
    e: [f64; 64],
    len: usize,
    ok: bool,
}

impl Expansion {
    fn new() -> Self {
        Self {
            e: [0.0; 64],
            len: 0,
            ok: true,
        }
    }

    fn add(&mut self, x: f64) {
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
    fn add_product(&mut self, f: &[f64], negate: bool) {
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
    fn lead(&self) -> f64 {
        if self.len == 0 {
            0.0
        } else {
            self.e[self.len - 1]
        }
    }

    /// The nonzero components, smallest first.
    fn components(&self) -> &[f64] {
        &self.e[..self.len]
    }

    /// The sign of the exact sum, `None` when a term or a partial sum was
    /// not finite.
    fn sign(&self) -> Option<core::cmp::Ordering> {
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
fn exponent(v: f64) -> i32 {
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
fn scale2(v: f64, k: i32) -> f64 {
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

/// The exact signs that place a ray's crossing with a plane against a
/// float `t`, for the interval forms: the plane of a triangle's corners
/// ([`PlaneCrossing::new`]), or a plane given by a point and a normal
/// ([`PlaneCrossing::with_normal`], the plane test and a box's face).
///
/// With `A = a - o` (`a` a corner, or the given point) and `n` the normal
/// (`(b - a) x (c - a)`, or the given one), the line `o + t d` meets the
/// plane at `t* = (A . n) / (d . n)` when `D = d . n` is not zero. The
/// coordinate differences are held as exact pairs (Knuth's two-sum:
/// `hi + lo` is the exact difference); `A . n` and `D` are then sums of
/// products of three floats (a triangle's) or two (a given normal's), each
/// expanded exactly into four or two terms and summed as a floating-point
/// expansion (Shewchuk, "Adaptive Precision Floating-Point Arithmetic and
/// Fast Robust Geometric Predicates", 1997). A few hundred operations for
/// a triangle, a few dozen for a given normal: the rare fallback of the
/// interval tests, taken only where the crossing lies within its rounding
/// error bound of an end.
///
/// `A . n - t D` is compared without forming `t D` in one exponent range:
/// with `t = m 2^k` (`m` in `[1, 2)`), `N = A . n` and `M = m D` are
/// expansions near one, and `N` against `2^k M` is decided by their
/// leading components' exponents when those are three or more apart, and
/// otherwise by scaling the smaller one up by the power of two (exact: no
/// bits are lost scaling up, and the result is near the other) and summing.
///
/// Exactness: the products' rounding errors must not underflow. Inputs are
/// `f32` or `f64` converted to `f64`. For `f32` every factor (a
/// coordinate difference's parts, a direction or normal component, and
/// `m d_k`'s parts) is a multiple of `2^-172` below `2^130`, so every
/// product and its rounding error are far inside `f64`'s range: the signs
/// are always exact. For `f64` the differences are scaled by one power of
/// two, the direction by another (and a given normal by a third), so that
/// each has its largest component in `[1, 2)`. For a triangle the signs
/// are exact while every nonzero scaled value (the differences' rounding
/// errors included) is above `2^-300`: nonzero differences within a factor `2^250` of the largest, the direction's
/// nonzero components within `2^250` of its largest. For a given normal
/// (two factors per product) they are exact while every nonzero scaled
/// value is above `2^-400`: a product is then at least `2^-800`, and one
/// with the error part of `m d_k` (at least `2^-105` of `d_k`) at least
/// `2^-906`, so its own rounding error is exact (products above `2^-969`
/// split exactly). Any `t`, however large or small, is compared exactly.
/// A non-finite term is reported as `None`.
pub(crate) struct PlaneCrossing {
    /// `a - o`, each component an exact `(hi, lo)` pair, scaled by `2^-ea`.
    to_plane: [(f64, f64); 3],
    /// Where the normal comes from.
    normal: Normal,
    /// The direction, scaled by `2^-ed`.
    dir: [f64; 3],
    /// `ed - ea`: `t*` of the scaled problem is `t* 2^(ed - ea)` (`A . n`
    /// and `D` share the normal's scale, `A` is scaled by `2^-ea` and `d`
    /// by `2^-ed`), so a `t` is compared as `t 2^(ed - ea)`.
    shift: i32,
}

/// The normal of a [`PlaneCrossing`].
enum Normal {
    /// `n = (b - a) x (c - a)`, from the exact pairs of the two edges,
    /// scaled by `2^-ea` like `a - o`.
    Edges([[(f64, f64); 3]; 2]),
    /// A given normal, scaled by a power of two of its own.
    Given([f64; 3]),
}

/// The exponent of the largest magnitude among `values` when scaling is
/// asked for and it is a usable (finite, nonzero) number, else `0`.
fn scale_exponent(values: impl Iterator<Item = f64>, scale: bool) -> i32 {
    let m = values.fold(0.0f64, |m, x| if x.abs() > m { x.abs() } else { m });
    if scale && m > 0.0 && m.is_finite() {
        exponent(m)
    } else {
        0
    }
}

impl PlaneCrossing {
    /// For the plane of the corners `a`, `b`, `c`: from the origin, the
    /// direction and the corners, as `f64`; `scale` for `f64` inputs (for
    /// `f32` inputs scaling could only push the smallest parts towards
    /// underflow, and every product is in range without it).
    pub(crate) fn new(
        o: [f64; 3],
        d: [f64; 3],
        a: [f64; 3],
        b: [f64; 3],
        c: [f64; 3],
        scale: bool,
    ) -> Self {
        let split = |p: [f64; 3], q: [f64; 3]| [0, 1, 2].map(|k| two_diff(p[k], q[k]));
        let mut diff = [split(a, o), split(b, a), split(c, a)];
        let ea = scale_exponent(diff.iter().flatten().map(|p| p.0), scale);
        let ed = scale_exponent(d.into_iter(), scale);
        for p in diff.iter_mut().flatten() {
            *p = (scale2(p.0, -ea), scale2(p.1, -ea));
        }
        let [to_plane, e1, e2] = diff;
        Self {
            to_plane,
            normal: Normal::Edges([e1, e2]),
            dir: d.map(|x| scale2(x, -ed)),
            shift: ed - ea,
        }
    }

    /// For the plane through `p` with normal `n`: from the origin, the
    /// direction, the point and the normal, as `f64`; `scale` as for
    /// [`PlaneCrossing::new`].
    pub(crate) fn with_normal(
        o: [f64; 3],
        d: [f64; 3],
        p: [f64; 3],
        n: [f64; 3],
        scale: bool,
    ) -> Self {
        let mut to_plane = [0, 1, 2].map(|k| two_diff(p[k], o[k]));
        let ea = scale_exponent(to_plane.iter().map(|p| p.0), scale);
        let ed = scale_exponent(d.into_iter(), scale);
        let en = scale_exponent(n.into_iter(), scale);
        for p in &mut to_plane {
            *p = (scale2(p.0, -ea), scale2(p.1, -ea));
        }
        Self {
            to_plane,
            normal: Normal::Given(n.map(|x| scale2(x, -en))),
            dir: d.map(|x| scale2(x, -ed)),
            shift: ed - ea,
        }
    }

    /// Adds `v . n` to `acc`, with `v_k` given by `v(k)` as the parts of a
    /// sum (one of them zero for a plain float) and `n` the normal
    /// (expanded from the edge pairs, or given).
    fn add_dot_normal(&self, acc: &mut Expansion, v: impl Fn(usize) -> [f64; 2]) {
        match &self.normal {
            Normal::Edges([e1, e2]) => {
                for k in 0..3 {
                    let (j, l) = ((k + 1) % 3, (k + 2) % 3);
                    for (x, y, negate) in [(e1[j], e2[l], false), (e1[l], e2[j], true)] {
                        for vk in v(k) {
                            if vk == 0.0 {
                                continue;
                            }
                            for xp in [x.0, x.1] {
                                for yp in [y.0, y.1] {
                                    acc.add_product(&[vk, xp, yp], negate);
                                }
                            }
                        }
                    }
                }
            }
            Normal::Given(n) => {
                for (k, &nk) in n.iter().enumerate() {
                    for vk in v(k) {
                        if vk != 0.0 && nk != 0.0 {
                            acc.add_product(&[vk, nk], false);
                        }
                    }
                }
            }
        }
    }

    /// `D`, scaled, times `factor` (exact when `factor` is a power of two
    /// or the direction's components times it are exact, as for `m` in
    /// `[1, 2)`: see `num_minus_t_den_sign`).
    fn den(&self, factor: f64) -> Expansion {
        let mut acc = Expansion::new();
        // `factor * d_k` is split exactly first when it is not a float.
        for k in 0..3 {
            let (p, e) = two_product(self.dir[k], factor);
            let one = |kk: usize| if kk == k { [p, e] } else { [0.0, 0.0] };
            self.add_dot_normal(&mut acc, one);
        }
        acc
    }

    /// The exact sign of `D = d . n`; `None` on overflow.
    pub(crate) fn den_sign(&self) -> Option<core::cmp::Ordering> {
        self.den(1.0).sign()
    }

    /// The exact sign of `A . n - t D`; `None` on overflow or a non-finite
    /// `t`.
    pub(crate) fn num_minus_t_den_sign(&self, t: f64) -> Option<core::cmp::Ordering> {
        use core::cmp::Ordering;
        if !t.is_finite() {
            return None;
        }
        let a = self.to_plane;
        let mut num = Expansion::new();
        self.add_dot_normal(&mut num, |k| [a[k].0, a[k].1]);
        let num_sign = num.sign()?;
        if t == 0.0 {
            return Some(num_sign);
        }
        // t = m 2^k, m in [1, 2) (exact: scaling up a subnormal or down a
        // normal value into [1, 2) loses no bits).
        let kt = exponent(t);
        let m = scale2(t, -kt);
        let mden = self.den(m);
        let mden_sign = mden.sign()?;
        let k = kt + self.shift;
        let flip = |o: Ordering| o.reverse();
        match (num_sign, mden_sign) {
            (_, Ordering::Equal) => return Some(num_sign),
            (Ordering::Equal, _) => return Some(flip(mden_sign)),
            (x, y) if x != y => return Some(num_sign),
            _ => {}
        }
        // Same signs: by magnitude, the leading exponents first.
        let (xn, xm) = (exponent(num.lead()), exponent(mden.lead()) + k);
        if xn >= xm + 3 {
            return Some(num_sign);
        }
        if xm >= xn + 3 {
            return Some(flip(mden_sign));
        }
        // Within a factor of 16: scale the one that needs a power above
        // one, and sum.
        let mut sum = Expansion::new();
        let (num_k, mden_k) = if k >= 0 { (0, k) } else { (-k, 0) };
        for &x in num.components() {
            sum.add(scale2(x, num_k));
        }
        for &x in mden.components() {
            sum.add(-scale2(x, mden_k));
        }
        sum.sign()
    }
}

/// A Plucker product `((p - o) x (q - o)) . d` held exactly, as a
/// floating-point expansion, for comparing it with floats
/// ([`PluckerProduct::cmp`]): the exact fallback of the oracle's float
/// filter for the watertight test's clear misses.
///
/// The differences are held as exact pairs (Knuth's two-sum: `hi + lo` is
/// the exact difference), and each of the six monomials `(A_j B_k - A_k
/// B_j) d_l` as the products of their parts, each expanded exactly into
/// four terms and summed as an expansion (Shewchuk, 1997): at most 96
/// terms.
///
/// Exactness: every nonzero input must have its magnitude in `[2^-300,
/// 2^300]` (every finite `f32` does). Then a difference's parts are
/// multiples of `2^-352` (the smaller input's ulp, at least `2^-300 2^-52`)
/// below `2^301`, so a product of three parts is a multiple of `2^-1056`
/// (as is every rounding error the expansion of a product splits off:
/// exact, above `f64`'s subnormal spacing `2^-1074`) below `2^903`, and no
/// sum overflows. Other inputs are refused (`None`).
#[cfg(feature = "exact")]
pub(crate) struct PluckerProduct(Expansion);

#[cfg(feature = "exact")]
impl PluckerProduct {
    /// `((p - o) x (q - o)) . d`, or `None` for an input outside the exact
    /// range (a nonzero magnitude outside `[2^-300, 2^300]`, or not finite).
    pub(crate) fn new(o: [f64; 3], d: [f64; 3], p: [f64; 3], q: [f64; 3]) -> Option<Self> {
        let (small, large) = (scale2(1.0, -300), scale2(1.0, 300));
        let in_range = |x: &f64| *x == 0.0 || (small <= x.abs() && x.abs() <= large);
        if ![o, d, p, q].iter().flatten().all(in_range) {
            return None;
        }
        let a = [0, 1, 2].map(|k| two_diff(p[k], o[k]));
        let b = [0, 1, 2].map(|k| two_diff(q[k], o[k]));
        let mut acc = Expansion::new();
        for (l, &dl) in d.iter().enumerate() {
            let (j, k) = ((l + 1) % 3, (l + 2) % 3);
            for (x, y, negate) in [(a[j], b[k], false), (a[k], b[j], true)] {
                for xp in [x.0, x.1] {
                    for yp in [y.0, y.1] {
                        if xp != 0.0 && yp != 0.0 && dl != 0.0 {
                            acc.add_product(&[xp, yp, dl], negate);
                        }
                    }
                }
            }
        }
        acc.ok.then_some(Self(acc))
    }

    /// The exact sign of `product - c`; `None` for a `c` that is not
    /// finite.
    pub(crate) fn cmp(&self, c: f64) -> Option<core::cmp::Ordering> {
        let mut diff = self.0.clone();
        diff.add(-c);
        diff.sign()
    }
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
    }

    /// Marsaglia's xorshift64 from `state`: the tests' reproducible bits.
    #[cfg(feature = "exact")]
    fn xorshift(mut state: u64) -> impl FnMut() -> u64 {
        move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        }
    }

    /// Three coordinates for the sign tests: with `wide`, `f64` values at
    /// `scale` times `2^-59` to 1 (and, with `zeros`, an exact zero one
    /// time in eight); otherwise arbitrary finite `f32` bit patterns.
    #[cfg(feature = "exact")]
    fn coords(wide: bool, zeros: bool, scale: f64, next: &mut dyn FnMut() -> u64) -> [f64; 3] {
        let unit =
            |next: &mut dyn FnMut() -> u64| (next() >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0;
        [0, 1, 2].map(|_| {
            if !wide {
                return loop {
                    let x = f32::from_bits(next() as u32);
                    if x.is_finite() {
                        break f64::from(x);
                    }
                };
            }
            if zeros && next().is_multiple_of(8) {
                return 0.0;
            }
            let spread = scale2(1.0, -((next() % 60) as i32));
            scale * spread * unit(next)
        })
    }

    /// Holds `pc` to the exact numerator and denominator of its crossing:
    /// the denominator's sign, and that of `num - t den` for `t` at zero,
    /// the smallest subnormal, `MAX`, `random_t`, and (where the crossing
    /// exists) the crossing rounded and three ulps either side. Returns the
    /// number of `t` checked, and 1 where the crossing exists.
    #[cfg(feature = "exact")]
    fn check_signs(
        pc: &PlaneCrossing,
        num: &crate::exact::oracle::R,
        den: &crate::exact::oracle::R,
        random_t: f64,
        what: &dyn Fn() -> std::string::String,
    ) -> (usize, usize) {
        use crate::exact::oracle::{R, r};
        use num_traits::Zero;
        let zero = R::zero();
        assert_eq!(pc.den_sign(), Some(den.cmp(&zero)), "{}", what());
        let mut ts = std::vec![0.0, f64::from_bits(1), f64::MAX, random_t];
        let mut near = 0;
        if !den.is_zero() {
            let t = crate::exact::round::<f64>(&(num / den)).abs();
            let (mut up, mut down) = (t, t);
            for _ in 0..3 {
                ts.extend([up, down]);
                up = up.next_up();
                down = down.next_down();
            }
            near = 1;
        }
        let mut checked = 0;
        for t in ts {
            if !(t.is_finite() && t >= 0.0) {
                continue;
            }
            let expected = (num - r(t).unwrap() * den).cmp(&zero);
            assert_eq!(
                pc.num_minus_t_den_sign(t),
                Some(expected),
                "t {t:e}: {}",
                what()
            );
            checked += 1;
        }
        (checked, near)
    }

    /// The plane-crossing signs against big rationals: `f64` inputs over
    /// the documented range (coordinate differences within `2^60` of each
    /// other, at any overall scale from `2^-400` to `2^400`; directions
    /// likewise, independently), `f32` inputs from arbitrary finite bit
    /// patterns; `t` at the exact crossing rounded and a few ulps either
    /// side, and anywhere from `2^-1074` to `2^1023`.
    #[cfg(feature = "exact")]
    #[test]
    fn plane_crossing_signs_are_exact() {
        use crate::exact::oracle::{cross, dot, r, sub};
        let mut next = xorshift(0x9e37_79b9_7f4a_7c15);
        let (mut checked, mut near) = (0, 0);
        for case in 0..1500 {
            let wide = case % 3 != 0;
            let v = |scale: f64, next: &mut dyn FnMut() -> u64| coords(wide, false, scale, next);
            let g = scale2(1.0, (next() % 800) as i32 - 400);
            let h = scale2(1.0, (next() % 800) as i32 - 400);
            let (o, a, b, c) = (
                v(g, &mut next),
                v(g, &mut next),
                v(g, &mut next),
                v(g, &mut next),
            );
            let d = v(h, &mut next);
            let pc = PlaneCrossing::new(o, d, a, b, c, wide);
            let rv = |p: [f64; 3]| p.map(|x| r(x).unwrap());
            let (ro, rd) = (rv(o), rv(d));
            let ra = rv(a);
            let n = cross(&sub(&rv(b), &ra), &sub(&rv(c), &ra));
            let num = dot(&sub(&ra, &ro), &n);
            let den = dot(&rd, &n);
            let random_t = scale2(1.0, (next() % 2000) as i32 - 1000);
            let (c1, n1) = check_signs(&pc, &num, &den, random_t, &|| {
                std::format!("{o:?} {d:?} {a:?} {b:?} {c:?}")
            });
            (checked, near) = (checked + c1, near + n1);
        }
        assert!(checked > 10_000 && near > 1_000, "{checked} {near}");
    }

    /// The plane-crossing signs for a given normal against big rationals:
    /// `f64` inputs over the documented range (components within `2^60`
    /// of each other, point, origin, direction and normal each at its own
    /// scale from `2^-400` to `2^400`; and points at unit scale translated
    /// far away, so that `point - origin` carries a rounding error), `f32`
    /// inputs from arbitrary finite bit patterns; `t` at the exact
    /// crossing rounded and a few ulps either side, and anywhere from
    /// `2^-1074` to `2^1023`.
    #[cfg(feature = "exact")]
    #[test]
    fn given_normal_crossing_signs_are_exact() {
        use crate::exact::oracle::{dot, r, sub};
        use num_traits::Zero;
        let mut next = xorshift(0x2545_f491_4f6c_dd1d);
        let (mut checked, mut near, mut zero_den) = (0, 0, 0);
        for case in 0..3000 {
            let wide = case % 3 != 0;
            // (With some exact zeros, which the scaling must skip.)
            let v = |scale: f64, next: &mut dyn FnMut() -> u64| coords(wide, true, scale, next);
            let scale = |next: &mut dyn FnMut() -> u64| scale2(1.0, (next() % 800) as i32 - 400);
            let (g, h, k) = (scale(&mut next), scale(&mut next), scale(&mut next));
            let o = v(g, &mut next);
            let mut p = v(g, &mut next);
            if wide && case % 5 == 1 {
                // Far from the origin, with a rounding error in `p - o`.
                let off = v(g * scale2(1.0, -30), &mut next);
                p = [0, 1, 2].map(|i| o[i] + off[i]);
            }
            let d = v(h, &mut next);
            let mut n = v(k, &mut next);
            if case % 7 == 2 {
                // Exactly parallel: n orthogonal to d (exact for
                // components that are zero or swapped and negated).
                n = [d[1], -d[0], 0.0];
            }
            let pc = PlaneCrossing::with_normal(o, d, p, n, wide);
            let rv = |p: [f64; 3]| p.map(|x| r(x).unwrap());
            let rn = rv(n);
            let num = dot(&sub(&rv(p), &rv(o)), &rn);
            let den = dot(&rv(d), &rn);
            zero_den += usize::from(den.is_zero());
            let random_t = scale2(1.0, (next() % 2000) as i32 - 1000);
            let (c1, n1) = check_signs(&pc, &num, &den, random_t, &|| {
                std::format!("{o:?} {d:?} {p:?} {n:?}")
            });
            (checked, near) = (checked + c1, near + n1);
        }
        assert!(
            checked > 20_000 && near > 2_000 && zero_den > 100,
            "{checked} {near} {zero_den}"
        );
    }

    /// The Plucker product's exact signs against big rationals: `f32`
    /// inputs from arbitrary finite bit patterns, `f64` inputs over the
    /// documented range (magnitudes from about `2^-300` to `2^240`, with
    /// exact zeros, and points translated far from the origin so that `p - o`
    /// rounds); each against the exact product rounded and a few ulps
    /// either side, and zero. Inputs beyond the range are refused.
    #[cfg(feature = "exact")]
    #[test]
    fn plucker_product_signs_are_exact() {
        use crate::exact::oracle::{cross, dot, r, sub};
        let mut next = xorshift(0x6c8e_9cf5_7093_2bd5);
        let (mut checked, mut refused) = (0, 0);
        for case in 0..3000 {
            let wide = case % 3 != 0;
            let v = |scale: f64, next: &mut dyn FnMut() -> u64| coords(wide, true, scale, next);
            let scale = |next: &mut dyn FnMut() -> u64| scale2(1.0, (next() % 480) as i32 - 240);
            let (g, h) = (scale(&mut next), scale(&mut next));
            let o = v(g, &mut next);
            let (mut p, mut q) = (v(g, &mut next), v(g, &mut next));
            if wide && case % 5 == 1 {
                let (dp, dq) = (
                    v(g * scale2(1.0, -30), &mut next),
                    v(g * scale2(1.0, -30), &mut next),
                );
                p = [0, 1, 2].map(|i| o[i] + dp[i]);
                q = [0, 1, 2].map(|i| o[i] + dq[i]);
            }
            let d = v(h, &mut next);
            let Some(product) = PluckerProduct::new(o, d, p, q) else {
                // Refused only beyond the range (f64 only).
                let out = |x: &f64| {
                    *x != 0.0 && !(scale2(1.0, -300)..=scale2(1.0, 300)).contains(&x.abs())
                };
                assert!(
                    wide && [o, d, p, q].iter().flatten().any(out),
                    "{o:?} {d:?} {p:?} {q:?}"
                );
                refused += 1;
                continue;
            };
            let rv = |p: [f64; 3]| p.map(|x| r(x).unwrap());
            let ro = rv(o);
            let exact = dot(&cross(&sub(&rv(p), &ro), &sub(&rv(q), &ro)), &rv(d));
            let near = crate::exact::round::<f64>(&exact);
            let (mut up, mut down) = (near, near);
            let mut cs = std::vec![0.0];
            for _ in 0..3 {
                cs.extend([up, down]);
                (up, down) = (up.next_up(), down.next_down());
            }
            for c in cs {
                let expected = exact.cmp(&r(c).unwrap());
                assert_eq!(
                    product.cmp(c),
                    Some(expected),
                    "{c:e}: {o:?} {d:?} {p:?} {q:?}"
                );
                checked += 1;
            }
        }
        assert!(checked > 20_000 && refused < 100, "{checked} {refused}");
        let big = scale2(1.0, 301);
        let refused =
            |x: f64| PluckerProduct::new([x, 0.0, 0.0], [1.0; 3], [1.0; 3], [0.0, 1.0, 2.0]);
        assert!(
            refused(big).is_none() && refused(1.0 / big).is_none() && refused(f64::NAN).is_none()
        );
        assert!(refused(scale2(1.0, 300)).is_some() && refused(scale2(1.0, -300)).is_some());
    }
}
