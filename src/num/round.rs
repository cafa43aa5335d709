//! Arithmetic for error bounds: evaluating a bound so that it stays an
//! upper bound of its exact value ([`bound_up`], [`outward`]), and the
//! comparisons the kernels use where NaN must not decide.

use super::Scalar;

/// Makes an error bound that was evaluated in floating point an upper bound
/// of the same expression evaluated exactly.
///
/// `value` must be a sum of products of non-negative numbers (the shape of
/// every bound in the crate), possibly divided by positive floats (each
/// taken as exact: a lower bound, where it is a divisor), evaluated with
/// at most `roundings` roundings along any path from an input to the
/// result. Each rounding of a
/// non-negative quantity can only shrink it by a factor `1 - u`, so the
/// computed value is at least `exact * (1 - u)^roundings`. Multiplying by
/// `c >= 1 + gamma(roundings + 1) >= (1 - u)^-(roundings + 1)` (Bernoulli)
/// and rounding once more gives at least `exact`. `c` is itself rounded up.
#[inline(always)]
pub(crate) fn bound_up<F: Scalar>(value: F, roundings: u32) -> F {
    value * (F::ONE + F::gamma_n(roundings + 1)).next_up()
}

/// Arithmetic rounded outward, for error bounds with differences and
/// quotients in them (where [`bound_up`]'s counting argument does not
/// apply). `fl(x)` is within half an ulp of `x`, so stepping it one ulp
/// up (down) gives a float at least (at most) `x`, infinities included.
pub(crate) mod outward {
    use super::Scalar;

    /// At least `a + b`.
    #[inline(always)]
    pub(crate) fn add_up<F: Scalar>(a: F, b: F) -> F {
        (a + b).next_up()
    }
    /// At most `a + b`.
    #[inline(always)]
    pub(crate) fn add_down<F: Scalar>(a: F, b: F) -> F {
        (a + b).next_down()
    }
    /// At most `a - b`.
    #[inline(always)]
    pub(crate) fn sub_down<F: Scalar>(a: F, b: F) -> F {
        (a - b).next_down()
    }
    /// At least `a * b`.
    #[inline(always)]
    pub(crate) fn mul_up<F: Scalar>(a: F, b: F) -> F {
        (a * b).next_up()
    }
    /// At most `a * b`.
    #[inline(always)]
    pub(crate) fn mul_down<F: Scalar>(a: F, b: F) -> F {
        (a * b).next_down()
    }
    /// At least `a / b`.
    #[inline(always)]
    pub(crate) fn div_up<F: Scalar>(a: F, b: F) -> F {
        (a / b).next_up()
    }
}

/// `t` unless it is above `hi` or NaN, else `hi`.
#[inline(always)]
pub(crate) fn at_most<F: Scalar>(t: F, hi: F) -> F {
    if t < hi { t } else { hi }
}

/// The larger of two values known not to be NaN.
#[inline(always)]
pub(crate) fn max2<F: Scalar>(a: F, b: F) -> F {
    if a > b { a } else { b }
}

/// The smaller of two values known not to be NaN.
#[inline(always)]
pub(crate) fn min2<F: Scalar>(a: F, b: F) -> F {
    if a < b { a } else { b }
}
