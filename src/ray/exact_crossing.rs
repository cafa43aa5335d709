//! The exact place of a ray's crossing with a plane against a float `t`:
//! the fallback of the interval forms (a triangle's plane, or a plane
//! given by a point and a normal), where the crossing lies within its
//! rounding error bound of an end.

use crate::num::exact_sign::{Expansion, exponent, scale2, two_diff, two_product};

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

#[cfg(test)]
mod tests {
    use super::*;
    #[cfg(feature = "exact")]
    use crate::testing::{coords, xorshift};

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
}
