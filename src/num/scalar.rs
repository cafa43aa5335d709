//! The precisions behind one source: [`Scalar`], implemented by `f32` and
//! `f64`.
//!
//! Every kernel in the crate is written once, generically, and each error
//! bound is derived in terms of the unit roundoff `u` of the scalar type
//! (`2^-24` for `f32`, `2^-53` for `f64`), so the same derivation serves
//! both precisions and neither is a copy of the other. The trait is sealed
//! (its supertrait `Repr` is private): the crate's guarantees are proven for
//! IEEE binary32 and binary64 with round-to-nearest-even, and for nothing
//! else.

use core::fmt::Debug;
use core::ops::{Add, Div, Mul, Neg, Sub};

use super::exact_sign;
use super::repr::Repr;

/// A floating-point scalar the kernels run in: `f32` or `f64`.
///
/// Sealed; it exists so that one generic source gives both precisions. The
/// methods are the handful of operations the kernels need, each with IEEE 754
/// round-to-nearest semantics.
pub trait Scalar:
    Repr
    + Copy
    + PartialOrd
    + Debug
    + Default
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// `0`.
    const ZERO: Self;
    /// `1`.
    const ONE: Self;
    /// `0.5`.
    const HALF: Self;
    /// `2`.
    const TWO: Self;
    /// Positive infinity.
    const INFINITY: Self;
    /// A quiet NaN.
    const NAN: Self;
    /// Pi, rounded to nearest.
    const PI: Self;
    /// The largest finite value.
    const MAX: Self;
    /// The smallest positive normal value (`2^-126` for `f32`, `2^-1022` for
    /// `f64`).
    const MIN_POSITIVE: Self;
    /// The smallest positive subnormal value (`2^-149` for `f32`, `2^-1074`
    /// for `f64`): the spacing of the floats below the normal range, and so
    /// the largest absolute error of one rounding there is half of it.
    const TINY: Self;
    /// The unit roundoff `u`: half the distance from 1 to the next float
    /// (`2^-24` for `f32`, `2^-53` for `f64`). One correctly rounded
    /// operation whose result is normal has relative error at most `u`.
    const UNIT_ROUNDOFF: Self;

    /// The bound `gamma(n) = n*u / (1 - n*u)` on the relative error of `n`
    /// chained roundings, rounded up so that it is a true upper bound.
    ///
    /// The classical result (Higham, "Accuracy and Stability of Numerical
    /// Algorithms", lemma 3.1): if `|d_i| <= u` then
    /// `prod (1 + d_i)^(+-1)` over `n` factors lies in `1 +- gamma(n)` when
    /// `n*u < 1`. pbrt-v4 uses the same function. `n*u` and `1 - n*u` are
    /// exact for the small `n` the crate uses, the quotient is rounded once,
    /// and the result is stepped up one ulp to cover that rounding.
    #[must_use]
    fn gamma_n(n: u32) -> Self;

    /// Converts a small integer exactly (`n < 2^24`).
    #[must_use]
    fn from_u32(n: u32) -> Self;
    /// Converts from `f64`, rounding to nearest (exact for `f64` itself).
    #[must_use]
    fn from_f64(x: f64) -> Self;
    /// Converts to `f64`, exactly.
    #[must_use]
    fn to_f64(self) -> f64;

    /// Absolute value.
    #[must_use]
    fn abs(self) -> Self;
    /// True unless the value is infinite or NaN.
    #[must_use]
    fn is_finite(self) -> bool;
    /// The next float towards `+inf` (`inf` stays `inf`, NaN stays NaN).
    #[must_use]
    fn next_up(self) -> Self;
    /// The next float towards `-inf`.
    #[must_use]
    fn next_down(self) -> Self;
    /// Tangent, from `std` or from `libm`.
    #[must_use]
    fn tan(self) -> Self;
    /// Square root, from `std` or from `libm`.
    #[must_use]
    fn sqrt(self) -> Self;

    /// `a*b - c*d` with its sign exact: the result is positive, negative or
    /// zero exactly when the real number `a*b - c*d` is, for finite inputs.
    ///
    /// The watertight triangle test calls this only when the plain
    /// `fl(fl(a*b) - fl(c*d))` came out zero, the one case where its sign
    /// may be wrong (rounding is monotone, so a nonzero plain result already
    /// has the right sign). `f32` recomputes in `f64`, where the products of
    /// two `f32` are exact and cannot overflow or underflow, and keeps a
    /// nonzero result nonzero when narrowing back. `f64` splits each product
    /// into its rounded value and exact error with a fused multiply-add; the
    /// sign is exact as long as the products are above `2^-969` in
    /// magnitude or exactly zero (below that the error terms themselves
    /// underflow).
    #[must_use]
    fn diff_of_products_exact_sign(a: Self, b: Self, c: Self, d: Self) -> Self;
}

macro_rules! impl_scalar {
    ($f:ident, $libm_tan:ident, $libm_sqrt:ident) => {
        impl Scalar for $f {
            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const HALF: Self = 0.5;
            const TWO: Self = 2.0;
            const INFINITY: Self = $f::INFINITY;
            const NAN: Self = $f::NAN;
            const PI: Self = core::$f::consts::PI;
            const MAX: Self = $f::MAX;
            const MIN_POSITIVE: Self = $f::MIN_POSITIVE;
            const TINY: Self = $f::from_bits(1);
            const UNIT_ROUNDOFF: Self = $f::EPSILON * 0.5;

            #[inline]
            fn gamma_n(n: u32) -> Self {
                let nu = n as $f * Self::UNIT_ROUNDOFF;
                (nu / (1.0 - nu)).next_up()
            }
            #[inline]
            fn from_u32(n: u32) -> Self {
                n as $f
            }
            #[inline]
            fn from_f64(x: f64) -> Self {
                x as $f
            }
            #[inline]
            fn to_f64(self) -> f64 {
                self as f64
            }
            #[inline]
            fn abs(self) -> Self {
                $f::abs(self)
            }
            #[inline]
            fn is_finite(self) -> bool {
                $f::is_finite(self)
            }
            #[inline]
            fn next_up(self) -> Self {
                $f::next_up(self)
            }
            #[inline]
            fn next_down(self) -> Self {
                $f::next_down(self)
            }
            #[inline]
            fn tan(self) -> Self {
                #[cfg(feature = "std")]
                {
                    $f::tan(self)
                }
                #[cfg(not(feature = "std"))]
                {
                    libm::$libm_tan(self)
                }
            }
            #[inline]
            fn sqrt(self) -> Self {
                #[cfg(feature = "std")]
                {
                    $f::sqrt(self)
                }
                #[cfg(not(feature = "std"))]
                {
                    libm::$libm_sqrt(self)
                }
            }
            #[inline]
            fn diff_of_products_exact_sign(a: Self, b: Self, c: Self, d: Self) -> Self {
                exact_sign::$f(a, b, c, d)
            }
        }
    };
}

impl_scalar!(f32, tanf, sqrtf);
impl_scalar!(f64, tan, sqrt);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gamma_is_an_upper_bound() {
        // n*u/(1 - n*u) for n = 3 in f32: 3*2^-24 / (1 - 3*2^-24), which is
        // 1.788139...e-7 to ten digits; the rounded-up value may exceed it by
        // one ulp and no more.
        let g = f32::gamma_n(3);
        let exact = 3.0f64 * 2f64.powi(-24) / (1.0 - 3.0 * 2f64.powi(-24));
        assert!(f64::from(g) >= exact);
        assert!(f64::from(g.next_down()) < exact);
        let g = f64::gamma_n(3);
        assert!(g > 3.0 * 2f64.powi(-53));
        assert!(g < 3.0001 * 2f64.powi(-53));
    }
}
