//! Sines, cosines and arctangents for the cameras, with angles in turns
//! (one turn is `2 pi`), and their error bounds.
//!
//! Written here, not taken from `std` or `libm`, for two reasons: their
//! error is derived below (the cameras' round-trip bounds rest on it), and
//! they are short polynomials the compiler inlines (a call to `sinf` costs
//! more than a whole pinhole ray). Angles in turns reduce exactly: `t -
//! round(t)` and `4 t - round(4 t)` are exact in floating point, so the
//! only rounding of the argument is the last product by `pi / 2`.

use super::Scalar;
use super::repr::{Bits, Repr};

/// True for `f32`, false for `f64`; a constant after inlining.
#[inline(always)]
fn single<F: Scalar>() -> bool {
    F::UNIT_ROUNDOFF.to_f64() > 1e-10
}

/// `x` rounded to an integer: the nearest one (ties to even) for
/// `|x| < 2^(p-2)` (`p` the precision: 24 or 53 bits), and some integer
/// within a few ulps of `x` above that (where `x` is a multiple of `1/2`
/// or coarser). NaN stays NaN; infinities give NaN.
///
/// `c = 1.5 * 2^(p-1)`: for `|x| < 2^(p-2)`, `x + c` lies in
/// `[2^(p-1), 2^p)`, where the floats are the integers, so it rounds `x`
/// to an integer (ties to the even one, as `c` is even), and subtracting
/// `c` is exact (Sterbenz). For larger `x` both `x + c` and `c` are
/// integers, and so is their rounded difference.
#[inline(always)]
pub(crate) fn round_int<F: Scalar>(x: F) -> F {
    let c = round_int_constant::<F>();
    (x + c) - c
}

/// The constant `c = 1.5 * 2^(p-1)` of [`round_int`].
#[inline(always)]
fn round_int_constant<F: Scalar>() -> F {
    if single::<F>() {
        F::from_f64(12_582_912.0) // 1.5 * 2^23
    } else {
        F::from_f64(6_755_399_441_055_744.0) // 1.5 * 2^52
    }
}

/// The bound `gamma(TRIG)` on the absolute error of [`sin_cos_quarter`]:
/// 24 for `f32`, 40 for `f64` (derived there).
#[inline(always)]
pub(crate) fn trig_n<F: Scalar>() -> u32 {
    if single::<F>() { 24 } else { 40 }
}

/// Taylor coefficients of `sin(pi r / 2) / r` in powers of `r^2`:
/// `(-1)^k (pi/2)^(2k+1) / (2k+1)!`, each the `f64` nearest the exact value
/// (computed in rational arithmetic from 80 digits of `pi`).
const SIN: [f64; 9] = [
    core::f64::consts::FRAC_PI_2,
    -0.645_964_097_506_246_3,
    0.079_692_626_246_167_05,
    -0.004_681_754_135_318_688,
    0.000_160_441_184_787_359_83,
    -3.598_843_235_212_085e-6,
    5.692_172_921_967_927e-8,
    -6.688_035_109_811_468e-10,
    6.066_935_731_106_195_5e-12,
];

/// Taylor coefficients of `cos(pi r / 2)` in powers of `r^2`: `(-1)^k
/// (pi/2)^(2k) / (2k)!`, as [`SIN`]'s.
const COS: [f64; 9] = [
    1.0,
    -1.233_700_550_136_169_7,
    0.253_669_507_901_048_03,
    -0.020_863_480_763_352_96,
    0.000_919_260_274_839_426_6,
    -2.520_204_237_306_060_7e-5,
    4.710_874_778_818_172e-7,
    -6.386_603_083_791_852e-9,
    6.565_963_114_979_473e-11,
];

/// `sum c[k] z^k` for the first `n` coefficients, by Horner's rule.
#[inline(always)]
fn horner<F: Scalar>(c: &[f64], n: usize, z: F) -> F {
    let mut p = F::from_f64(c[n - 1]);
    let mut k = n - 1;
    while k > 0 {
        k -= 1;
        p = p * z + F::from_f64(c[k]);
    }
    p
}

/// `(sin(pi r / 2), cos(pi r / 2))`, the sine and cosine of `r` quarter
/// turns, for `|r| <= 1/2` (an eighth of a turn; a rounding beyond is
/// fine): each within `3 u` of the exact value, absolutely, and so within
/// `gamma(TRIG)` ([`trig_n`]), the bound the cameras' derivations use.
///
/// Taylor polynomials in `z = r^2` with `pi/2` in the coefficients ([`SIN`],
/// [`COS`]), so that the argument is not rounded: `sin` to `r^9` and `cos`
/// to `r^10` in `f32`, `sin` to `r^17` and `cos` to `r^16` in `f64`, by
/// Horner's rule. The error, at most where `|r| = 1/2` (each term below
/// grows with `|r|`):
///
/// - truncation: the series alternate with decreasing terms, so the first
///   omitted term bounds the rest: below `0.03 u` in both precisions;
/// - coefficients: each rounded once to `f64`, and once more to `f32` (at
///   most `1.001 u` relative together); the cosine's `1` is exact;
/// - `z`: one rounding, relative;
/// - Horner's rule (Higham, *Accuracy and Stability of Numerical
///   Algorithms*, 2002, section 5.1, first order): the step giving `y_k =
///   fl(fl(z y_(k+1)) + c_k)` adds `u (|z y_(k+1)| + |y_k|)`, and the errors
///   before it are multiplied by `z <= 1/4`. Each partial value is an
///   alternating series with decreasing terms, so `|y_k| <= |c_k|`;
/// - the sine's product by `r`: one rounding.
///
/// Summed (`tests::running_error_bound` recomputes the sums from the
/// coefficients): below `2.8 u` for the sine and `2.4 u` for the cosine, in
/// both precisions, with second-order terms below `1e-5 u`. The `f32`
/// functions are also checked against the `f64` library on every `f32`
/// argument from `2^-12` to `1/2` (an ignored test; a sample by default).
#[inline(always)]
pub(crate) fn sin_cos_quarter<F: Scalar>(r: F) -> (F, F) {
    let z = r * r;
    let (ns, nc) = if single::<F>() { (5, 6) } else { (9, 9) };
    (r * horner(&SIN, ns, z), horner(&COS, nc, z))
}

/// `(sin 2 pi t, cos 2 pi t)`: the sine and cosine of `t` turns.
///
/// For `|t| < 2^(p-2)` (4 million turns in `f32`), each is within `3 u`
/// of the exact value, absolutely, and so within `gamma(TRIG + 2)`, the
/// bound the cameras' derivations use; beyond, the pair is
/// still finite, of length 1 within the same bound (the angle is then a
/// multiple of a quarter turn or coarser, and which one is not
/// specified). NaN or infinite `t` gives NaN.
///
/// Reduction, exact: `s = t - round(t)` is in `[-1/2, 1/2]` and `t - s`
/// an integer; `k = round(4 s)` is a quarter-turn count in `-2..=2`, and
/// `r = 4 s - k` in `[-1/2, 1/2]`, all exact. [`sin_cos_quarter`] of `r`
/// then has the only error, and the quarter turns are exact swaps and sign
/// changes, read from the bits of `4 s + c` (the sum [`round_int`] rounds
/// with), so that no comparison picks them: the whole function is
/// arithmetic and bit operations, which a loop of rays computes several
/// at a time.
#[inline(always)]
pub(crate) fn sin_cos_turns<F: Scalar>(t: F) -> (F, F) {
    let c = round_int_constant::<F>();
    // (Within half a turn, s = t: round(t) is 0, ties to even.)
    let s = t - round_int(t);
    let four_s = s * F::from_u32(4);
    // k + c: its low bits are k modulo 4 (for |t| < 2^(p-2), |k| <= 2).
    let kc = four_s + c;
    let r = four_s - (kc - c);
    let (sin, cos) = sin_cos_quarter(r);
    <F as Repr>::Bits::quarter_turns(kc, sin, cos)
}

/// [`sin_cos_turns`] for `t` in `[0, 1/4]` (a quarter turn), bit for bit,
/// with a shorter reduction: `q = 4t` quarter turns, in `[0, 1]`; above
/// `1/2`, `r = q - 1` (exact, Sterbenz) and the quarter turn's swap and
/// sign, `(cos r, -sin r)`, which is what [`sin_cos_turns`] computes there
/// (`k = 1`). NaN gives NaN.
#[inline(always)]
pub(crate) fn sin_cos_quadrant<F: Scalar>(t: F) -> (F, F) {
    let q = t * F::from_u32(4);
    let turned = q > F::HALF;
    let r = if turned { q - F::ONE } else { q };
    let (sin, cos) = sin_cos_quarter(r);
    if turned { (cos, -sin) } else { (sin, cos) }
}

/// Taylor coefficients of `atan(x) / x` in powers of `x^2`.
const ATAN: [f64; 21] = [
    1.0,
    -1.0 / 3.0,
    1.0 / 5.0,
    -1.0 / 7.0,
    1.0 / 9.0,
    -1.0 / 11.0,
    1.0 / 13.0,
    -1.0 / 15.0,
    1.0 / 17.0,
    -1.0 / 19.0,
    1.0 / 21.0,
    -1.0 / 23.0,
    1.0 / 25.0,
    -1.0 / 27.0,
    1.0 / 29.0,
    -1.0 / 31.0,
    1.0 / 33.0,
    -1.0 / 35.0,
    1.0 / 37.0,
    -1.0 / 39.0,
    1.0 / 41.0,
];

/// The bound, in turns, on the absolute error of [`atan2_turns`]:
/// `gamma(ATAN)` with 12 for `f32` and 24 for `f64` (derived there).
pub(crate) fn atan_n<F: Scalar>() -> u32 {
    if single::<F>() { 12 } else { 24 }
}

/// `atan2(y, x) / (2 pi)`: the angle of `(x, y)` in turns, in
/// `[-1/2, 1/2]`, within `gamma(ATAN)` turns ([`atan_n`]) of the exact
/// angle of the floats given, absolutely; `0` for `(0, 0)` (either sign),
/// NaN when either is NaN; an infinite component gives the angle of the
/// direction it dominates, or NaN for two infinities.
///
/// Steps and their errors, in radians before the last conversion:
///
/// 1. `m = min / max` of `|x|, |y|`, in `[0, 1]`: one rounding, and
///    `atan` has slope at most 1, so at most `u m / (1 + m^2) <= u/2`.
/// 2. For `m > tan(pi/8)`, `r = (m - 1) / (m + 1)` and `atan m = pi/4 +
///    atan r`, else `r = m`; `|r| <= tan(pi/8) < 0.4143`. Three roundings
///    of `r`: at most `0.42 gamma(3)`.
/// 3. `atan r` by its Taylor series in `r^2` to `r^17` (`f32`, 9 terms)
///    or `r^41` (`f64`, 21 terms): truncation below `0.4143^19 / 19 <
///    3e-9` and `0.4143^43 / 43 < 8e-19` (under `0.05 u` and `0.01 u`);
///    rounding, as in [`sin_cos_quarter`], `gamma(3n + 3) atanh(0.4143)`
///    with `n` 8 or 20, `atanh(0.4143) < 0.45`: `0.45 gamma(27)` and
///    `0.45 gamma(63)`.
/// 4. Adding `fl(pi/4)`: its rounding and the sum's, `u (pi/4 + 0.79)`.
///
/// In `f32` that is at most `(0.5 + 1.3 + 0.05 + 12.2 + 1.6) u < 16 u`,
/// in `f64` `(0.5 + 1.3 + 0.01 + 28.4 + 1.6) u < 32 u`. To turns: the
/// product by `fl(1 / 2 pi)` adds two roundings of a value at most `1/8`
/// (`u/4`), and then `1/4 - a`, `1/2 - a` and the sign are one rounding
/// each of a value at most `1/2` (`u/2` each): in total at most
/// `16 u / 2 pi + 1.25 u < 3.8 u` and `32 u / 2 pi + 1.25 u < 6.4 u`.
/// `gamma(12)` and `gamma(24)` leave room.
#[inline]
pub(crate) fn atan2_turns<F: Scalar>(y: F, x: F) -> F {
    let (zero, one) = (F::ZERO, F::ONE);
    let (ax, ay) = (x.abs(), y.abs());
    if ax == zero && ay == zero {
        // (0, 0), either sign: 0.
        return zero;
    }
    let steep = ay > ax;
    let (num, den) = if steep { (ax, ay) } else { (ay, ax) };
    let m = num / den;
    let tan_pi_8 = F::from_f64(0.414_213_562_373_095_03);
    let big = m > tan_pi_8;
    let r = if big { (m - one) / (m + one) } else { m };
    let n = if single::<F>() { 9 } else { 21 };
    let mut a = r * horner(&ATAN, n, r * r);
    if big {
        a = a + F::from_f64(core::f64::consts::FRAC_PI_4);
    }
    // Radians to turns, then the octant's angle to the quadrant's.
    let mut turns = a * F::from_f64(1.0 / core::f64::consts::TAU);
    let quarter = F::from_f64(0.25);
    if steep {
        turns = quarter - turns;
    }
    if x < zero {
        turns = F::HALF - turns;
    }
    <F as Repr>::Bits::copysign(turns, y)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each result of `sin_cos_turns` against the `f64` library's sine and
    /// cosine (for `f32`, whose bound is `1e9` times that library's error)
    /// and for `f64` against the same to its own bound plus one `f64` ulp
    /// of the library (glibc's and libm's documented accuracy).
    #[test]
    fn sin_cos_within_their_bound() {
        fn check<F: Scalar>(ts: &[f64], slack: f64) {
            let bound = F::gamma_n(trig_n::<F>() + 2).to_f64() + slack;
            let mut worst = 0.0f64;
            for &t in ts {
                let (s, c) = sin_cos_turns(F::from_f64(t));
                let t = F::from_f64(t).to_f64();
                let angle = (t - t.round()) * core::f64::consts::TAU;
                let es = (s.to_f64() - angle.sin()).abs();
                let ec = (c.to_f64() - angle.cos()).abs();
                worst = worst.max(es).max(ec);
                assert!(es <= bound && ec <= bound, "{t}: {s:?} {c:?}");
            }
            // The bound is not vacuous: the error is above zero somewhere.
            assert!(worst > 0.0 && worst < bound);
        }
        let mut ts = std::vec::Vec::new();
        for i in -4000..=4000 {
            ts.push(f64::from(i) / 1000.0);
            ts.push(f64::from(i) * 0.000_123_7 + 0.1);
        }
        ts.extend([0.0, -0.0, 0.125, -0.125, 0.25, 0.5, -0.5, 1.0, 1e6 + 0.3]);
        check::<f32>(&ts, 0.0);
        check::<f64>(&ts, 2.0 * f64::EPSILON);
    }

    /// The sums of the running error analysis in [`sin_cos_quarter`]'s
    /// comment, from the coefficients themselves, at `|r| = 1/2`: the
    /// bounds it states, in units of `u`.
    #[test]
    fn running_error_bound() {
        fn sums(u: f64, ns: usize, nc: usize) -> (f64, f64) {
            let (r, z) = (0.5, 0.25);
            // Horner's steps: u (z |c_(k+1)| + |c_k|), carried times z.
            let horner = |c: &[f64], n: usize| {
                (0..n - 1)
                    .rev()
                    .fold(0.0, |e, k| z * e + u * (z * c[k + 1].abs() + c[k].abs()))
            };
            let cu = u * 1.001;
            let at = |c: &[f64], k: usize| c[k].abs() * z.powi(k as i32);
            let slope = |c: &[f64], n: usize| {
                (1..n)
                    .map(|k| k as f64 * c[k].abs() * z.powi(k as i32 - 1))
                    .sum::<f64>()
            };
            // The first omitted terms (past the arrays' ends in f64): the
            // next coefficients by the series' ratios, at z.
            let h2 = core::f64::consts::FRAC_PI_2 * core::f64::consts::FRAC_PI_2;
            let omitted = |c: &[f64], n: usize, odd: usize| {
                let m = (2 * n + odd) as f64;
                (c[n - 1] * h2 / (m * (m - 1.0))).abs() * z.powi(n as i32)
            };
            let sin = r
                * (horner(&SIN, ns)
                    + cu * (0..ns).map(|k| at(&SIN, k)).sum::<f64>()
                    + slope(&SIN, ns) * u * z
                    + omitted(&SIN, ns, 1))
                + u * r * SIN[0];
            let cos = horner(&COS, nc)
                + cu * (1..nc).map(|k| at(&COS, k)).sum::<f64>()
                + slope(&COS, nc) * u * z
                + omitted(&COS, nc, 0);
            // Second-order terms, generously.
            ((sin / u) * (1.0 + 1e-5), (cos / u) * (1.0 + 1e-5))
        }
        for (u, ns, nc) in [(2f64.powi(-24), 5, 6), (2f64.powi(-53), 9, 9)] {
            let (sin, cos) = sums(u, ns, nc);
            assert!(sin < 2.8 && cos < 2.4, "{sin} {cos}");
            // Not vacuous: the sine's last rounding alone is 0.785 u.
            assert!(sin > 2.0 && cos > 1.5);
        }
        // Truncation below 0.03 u: the first omitted terms at r = 1/2.
        assert!(0.5 * SIN[5] * 0.25f64.powi(5) < 0.03 * 2f64.powi(-24));
        assert!(COS[6] * 0.25f64.powi(6) < 0.03 * 2f64.powi(-24));
    }

    /// The coefficients against `(pi/2)^m / m!` computed here in `f64`
    /// (a few roundings: within `1e-15` relative), so that a mistyped
    /// digit fails.
    #[test]
    fn coefficients_are_the_taylor_series() {
        let h = core::f64::consts::FRAC_PI_2;
        let mut term = 1.0; // (pi/2)^m / m!, m = 0
        for m in 0..18 {
            let (k, c) = if m % 2 == 0 {
                (m / 2, COS[m / 2])
            } else {
                (m / 2, SIN[m / 2])
            };
            let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
            assert!((c - sign * term).abs() <= 1e-15 * term, "{m}: {c} {term}");
            term *= h / (m + 1) as f64;
        }
    }

    /// The quarter-turn sine and cosine in `f32` against the `f64`
    /// library's (whose error, with the `f64` product `r pi/2`, is below
    /// `1e-15`: `1e-8` of the bound) within the `3 u` stated, at every
    /// `STEP`th `f32` from `2^-12` to `1/2`, and every one with `STEP = 1`
    /// (`cargo test --release -p rayhit --lib -- --ignored
    /// every_f32_quarter_turn`, 92 million arguments, a few seconds); below `2^-12`, the cosine
    /// is `1` within `u / 2` and the sine has only its first term's error.
    /// The sine is odd and the cosine even, bit for bit, so the negative
    /// arguments are covered too.
    fn quarter_turns_f32(step: usize) -> (u64, f64) {
        let bound = 3.0 * f64::from(f32::UNIT_ROUNDOFF);
        let (mut r, mut n, mut worst) = (2f32.powi(-12), 0u64, 0f64);
        while r <= 0.5 {
            let (s, c) = sin_cos_quarter(r);
            let (ns, nc) = sin_cos_quarter(-r);
            assert!(ns == -s && nc.to_bits() == c.to_bits());
            let x = f64::from(r) * core::f64::consts::FRAC_PI_2;
            let e = (f64::from(s) - x.sin())
                .abs()
                .max((f64::from(c) - x.cos()).abs());
            assert!(e <= bound, "{r}: {s} {c}: {e}");
            worst = worst.max(e);
            n += 1;
            for _ in 0..step {
                r = r.next_up();
            }
        }
        (n, worst / f64::from(f32::UNIT_ROUNDOFF))
    }

    #[test]
    fn quarter_turns_f32_sample() {
        let (n, worst) = quarter_turns_f32(997);
        assert!(n > 90_000 && worst > 0.1, "{n} {worst}");
    }

    #[test]
    #[ignore = "every f32 from 2^-12 to 1/2: a few seconds in release"]
    fn every_f32_quarter_turn() {
        let (n, worst) = quarter_turns_f32(1);
        std::println!("{n} arguments, largest error {worst} u");
    }

    /// The `f64` functions against the `f64` library's (within one of its
    /// ulps, as glibc and libm document) on a grid of `|r| <= 1/2`.
    #[test]
    fn quarter_turns_f64() {
        let bound = 3.0 * f64::UNIT_ROUNDOFF + f64::EPSILON;
        for i in -50_000..=50_000 {
            let r = f64::from(i) * 1e-5 + 1.234e-7;
            let r = if r.abs() > 0.5 { 0.5f64.copysign(r) } else { r };
            let (s, c) = sin_cos_quarter(r);
            let x = r * core::f64::consts::FRAC_PI_2;
            assert!(
                (s - x.sin()).abs() <= bound && (c - x.cos()).abs() <= bound,
                "{r}"
            );
        }
    }

    /// The quadrant's sine and cosine are `sin_cos_turns`, bit for bit
    /// (signed zeros included), over `[0, 1/4]`: every `f32` step of
    /// `2^-16` and the ends' neighbours, in both precisions.
    #[test]
    fn quadrant_is_sin_cos_turns() {
        fn check<F: Scalar>(t: F) {
            let (a, b) = (sin_cos_quadrant(t), sin_cos_turns(t));
            let bits = |(s, c): (F, F)| (s.to_f64().to_bits(), c.to_f64().to_bits());
            assert_eq!(bits(a), bits(b), "{t:?}");
        }
        for i in 0..=(1 << 14) {
            let t = f64::from(i) * 2f64.powi(-16);
            for t in [t, t + 1e-9] {
                check(t as f32);
                check(t);
            }
        }
        for t in [0.125f32, 0.125f32.next_up(), 0.25f32.next_down(), 0.25] {
            check(t);
            check(f64::from(t));
        }
        assert!(sin_cos_quadrant(f32::NAN).0.is_nan());
    }

    /// Exact cases: quarter turns give exact zeros and ones.
    #[test]
    fn quarter_turns_are_exact() {
        for (t, s, c) in [
            (0.0, 0.0, 1.0),
            (0.25, 1.0, 0.0),
            (0.5, 0.0, -1.0),
            (-0.25, -1.0, 0.0),
            (-0.5, 0.0, -1.0),
            (0.75, -1.0, 0.0),
            (3.0, 0.0, 1.0),
        ] {
            assert_eq!(sin_cos_turns(t as f32), (s as f32, c as f32), "{t}");
            assert_eq!(sin_cos_turns(t), (s, c), "{t}");
        }
        assert!(sin_cos_turns(f32::NAN).0.is_nan());
        assert!(sin_cos_turns(f64::INFINITY).1.is_nan());
        // Far beyond the reduction's exact range: finite and unit.
        let (s, c) = sin_cos_turns(3.0e30f32);
        assert!((s * s + c * c - 1.0).abs() < 1e-5);
    }

    #[test]
    fn atan2_within_its_bound() {
        fn check<F: Scalar>(slack: f64) {
            let bound = F::gamma_n(atan_n::<F>()).to_f64() + slack;
            let mut worst = 0.0f64;
            for i in 0..20_000 {
                let a = f64::from(i) * 0.000_314_159_3 * 2.0 - core::f64::consts::PI;
                for len in [1.0, 3.5e-3, 7e4] {
                    let (x, y) = (F::from_f64(len * a.cos()), F::from_f64(len * a.sin()));
                    let got = atan2_turns(y, x).to_f64();
                    let exact = y.to_f64().atan2(x.to_f64()) / core::f64::consts::TAU;
                    let e = (got - exact).abs();
                    worst = worst.max(e);
                    assert!(e <= bound, "({x:?}, {y:?}): {got} vs {exact}");
                }
            }
            assert!(worst > 0.0);
        }
        check::<f32>(0.0);
        check::<f64>(f64::EPSILON / 8.0);
        assert_eq!(atan2_turns(0.0f32, 0.0), 0.0);
        assert_eq!(atan2_turns(0.0f64, -1.0), 0.5);
        assert_eq!(atan2_turns(-0.0f64, -1.0), -0.5);
        assert_eq!(atan2_turns(1.0f32, 0.0), 0.25);
        assert!((atan2_turns(1.0f32, 1.0) - 0.125).abs() < 1e-7);
        assert!(atan2_turns(f64::NAN, 0.0).is_nan());
        assert!(atan2_turns(f32::NAN, 1.0).is_nan());
        assert!(atan2_turns(f32::INFINITY, f32::INFINITY).is_nan());
        assert_eq!(atan2_turns(f64::INFINITY, 1.0), 0.25);
    }
}
