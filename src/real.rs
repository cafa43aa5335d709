//! The two precisions behind one source.
//!
//! Every kernel in the crate is written once, generically over [`Vector`]
//! (implemented by glam's `Vec3`, `Vec3A` and `DVec3`) and its [`Scalar`]
//! (`f32` and `f64`). Each error bound is derived in terms of the unit
//! roundoff `u` of the scalar type (`2^-24` for `f32`, `2^-53` for `f64`), so
//! the same derivation serves both precisions and neither is a copy of the
//! other. Both traits are sealed: the crate's guarantees are proven for IEEE
//! binary32 and binary64 with round-to-nearest-even, and for nothing else.

use core::fmt::Debug;
use core::ops::{Add, Div, Index, Mul, Neg, Sub};

mod sealed {
    pub trait Sealed {}
    impl Sealed for f32 {}
    impl Sealed for f64 {}
}

/// A floating-point scalar the kernels run in: `f32` or `f64`.
///
/// Sealed; it exists so that one generic source gives both precisions. The
/// methods are the handful of operations the kernels need, each with IEEE 754
/// round-to-nearest semantics.
pub trait Scalar:
    sealed::Sealed
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

    /// Four lanes of this scalar, for the kernels' hot paths (SSE registers
    /// for `f32` on x86). An implementation detail.
    #[doc(hidden)]
    type Lanes: crate::lanes::Lanes<F = Self>;

    /// Eight lanes of this scalar, for the batch kernels (AVX or SSE
    /// registers for `f32` on x86). An implementation detail.
    #[doc(hidden)]
    type Lanes8: crate::lanes::Lanes8<F = Self>;

    /// The eight lanes for code compiled with AVX2 enabled and run only
    /// where the CPU has it (the batch kernels' AVX2 copies). An
    /// implementation detail.
    #[cfg(all(feature = "std", target_arch = "x86_64", not(target_feature = "avx2")))]
    #[doc(hidden)]
    type Lanes8Avx2: crate::lanes::Lanes8<F = Self>;

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

    /// The exact sign of `sum a_i * b_i` over at most eight pairs (an
    /// implementation detail of the box tests' entry face and of
    /// [`Triangle::is_degenerate`](crate::Triangle::is_degenerate)).
    ///
    /// `f32`: each product is exact in `f64`; `f64`: each product is split
    /// into its rounded value and its exact error by a fused multiply-add
    /// (exact while the products are above `2^-969` or zero). The terms are
    /// then summed exactly as a floating-point expansion (Shewchuk,
    /// "Adaptive Precision Floating-Point Arithmetic and Fast Robust
    /// Geometric Predicates", 1997: growing a nonoverlapping expansion with
    /// error-free sums), whose sign is that of its largest component.
    #[doc(hidden)]
    #[must_use]
    fn sum_of_products_sign(terms: &[(Self, Self)]) -> core::cmp::Ordering;

    /// `(s, e)` with `s = fl(a - b)` and `s + e = a - b` exactly (Knuth's
    /// two-sum; exact whenever `a - b` does not overflow). An
    /// implementation detail.
    #[doc(hidden)]
    #[must_use]
    fn two_diff(a: Self, b: Self) -> (Self, Self);

    /// `0 <= self <= 1`, as one comparison of the bits and a test for
    /// `-0` (which the bits put above 1), so that it compiles to one
    /// branch. False for NaN. An implementation detail.
    #[doc(hidden)]
    #[must_use]
    fn in_unit_interval(self) -> bool;

    /// A triangle test's answer in a form that a function returns in
    /// registers (`u128` for `f32`; `f64`'s answer is too large, and stays
    /// as it is). The triangle tests' rare paths, out of line, return it:
    /// returned through memory, their answer made the inlined common path
    /// write its own answer through memory as well. An implementation
    /// detail.
    #[doc(hidden)]
    type PackedHit: Copy;
    /// See [`Scalar::PackedHit`].
    #[doc(hidden)]
    #[must_use]
    fn pack_hit(hit: Option<crate::TriangleHit<Self>>) -> Self::PackedHit;
    /// The inverse of [`Scalar::pack_hit`], bit for bit.
    #[doc(hidden)]
    #[must_use]
    fn unpack_hit(packed: Self::PackedHit) -> Option<crate::TriangleHit<Self>>;
}

/// A 3-component vector the kernels run on: glam's `Vec3` and `Vec3A`
/// (`f32`) and `DVec3` (`f64`), of the glam this crate re-exports and of
/// every older glam release whose feature is on (`glam-0_29` to
/// `glam-0_33`).
///
/// Sealed; see [`Scalar`]. The operations are glam's own or written out in
/// the order glam's `Vec3` uses, so every vector type of a precision gives
/// the same answers bit for bit, and a kernel written against this trait
/// compiles to the same code as one written against `Vec3` directly.
pub trait Vector:
    sealed::Sealed
    + Copy
    + PartialEq
    + Debug
    + Default
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Neg<Output = Self>
    + Mul<Output = Self>
    + Mul<<Self as Vector>::Scalar, Output = Self>
    + Index<usize, Output = <Self as Vector>::Scalar>
{
    /// The component type.
    type Scalar: Scalar;

    /// All zeros.
    const ZERO: Self;

    /// The component on axis `k`. (An implementation detail: an index the
    /// compiler knows is in range, for the triangle tests' permutation.)
    #[doc(hidden)]
    #[must_use]
    fn get(&self, k: crate::lanes::Axis) -> Self::Scalar;

    /// A vector from its components.
    #[must_use]
    fn new(x: Self::Scalar, y: Self::Scalar, z: Self::Scalar) -> Self;
    /// All three components equal to `v`.
    #[must_use]
    fn splat(v: Self::Scalar) -> Self;
    /// The `x` component.
    #[must_use]
    fn x(self) -> Self::Scalar;
    /// The `y` component.
    #[must_use]
    fn y(self) -> Self::Scalar;
    /// The `z` component.
    #[must_use]
    fn z(self) -> Self::Scalar;
    /// Dot product.
    #[must_use]
    fn dot(self, rhs: Self) -> Self::Scalar;
    /// Cross product (right-handed).
    #[must_use]
    fn cross(self, rhs: Self) -> Self;
    /// Component-wise absolute value.
    #[must_use]
    fn abs(self) -> Self;
    /// True when every component is finite.
    #[must_use]
    fn is_finite(self) -> bool;
    /// True when `self[k] <= rhs[k]` for every `k` (a NaN on either side
    /// makes it false). In `f32` on SIMD targets it is one packed
    /// comparison.
    #[must_use]
    fn all_le(self, rhs: Self) -> bool;
    /// Euclidean length.
    #[must_use]
    fn length(self) -> Self::Scalar;
    /// `self / |self|`, or zero when the length is zero or not finite.
    #[must_use]
    fn normalize_or_zero(self) -> Self;
}

/// The scalar type of the vector type `V`.
pub(crate) type S<V> = <V as Vector>::Scalar;
/// The four-lane type of the vector type `V`'s scalar.
pub(crate) type L<V> = <S<V> as Scalar>::Lanes;

macro_rules! impl_scalar {
    (
        $f:ident,
        $lanes:ty,
        $lanes8:ty,
        $lanes8_avx2:ty,
        $libm_tan:ident,
        $libm_sqrt:ident,
        $packed:ty,
        $pack:path,
        $unpack:path
    ) => {
        impl Scalar for $f {
            type Lanes = $lanes;
            type PackedHit = $packed;
            type Lanes8 = $lanes8;
            #[cfg(all(feature = "std", target_arch = "x86_64", not(target_feature = "avx2")))]
            type Lanes8Avx2 = $lanes8_avx2;
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
            fn sum_of_products_sign(terms: &[(Self, Self)]) -> core::cmp::Ordering {
                exact_sign::sum_sign(exact_sign::products::$f(terms))
            }
            #[inline]
            fn two_diff(a: Self, b: Self) -> (Self, Self) {
                let s = a - b;
                let bb = s - a;
                (s, (a - (s - bb)) - (b + bb))
            }
            #[inline(always)]
            fn in_unit_interval(self) -> bool {
                // The bits of a non-negative float (NaN aside) order as
                // its value, and every negative one's sign bit puts it
                // above 1's: so the first test is `+0 <= self <= 1`.
                (self.to_bits() <= (1.0 as $f).to_bits()) | (self == 0.0)
            }
            #[inline(always)]
            fn pack_hit(hit: Option<crate::TriangleHit<Self>>) -> $packed {
                $pack(hit)
            }
            #[inline(always)]
            fn unpack_hit(packed: $packed) -> Option<crate::TriangleHit<Self>> {
                $unpack(packed)
            }
        }
    };
}

impl_scalar!(
    f32,
    crate::lanes::F32Lanes,
    crate::lanes::F32Lanes8,
    crate::lanes::avx::F32x8,
    tanf,
    sqrtf,
    u128,
    packed_hit::pack_f32,
    packed_hit::unpack_f32
);
impl_scalar!(
    f64,
    crate::lanes::Portable<f64>,
    crate::lanes::Portable8<f64>,
    crate::lanes::Portable8<f64>,
    tan,
    sqrt,
    Option<crate::TriangleHit<f64>>,
    core::convert::identity,
    core::convert::identity
);

/// [`Scalar::pack_hit`] for `f32`: `t`, `u` and `v` in bits 0, 32 and 64,
/// and above them 0 for a miss, 1 for a hit from the front, 2 from the
/// back.
mod packed_hit {
    use crate::{Side, TriangleHit};

    #[inline(always)]
    pub(super) fn pack_f32(hit: Option<TriangleHit<f32>>) -> u128 {
        let Some(h) = hit else { return 0 };
        let side: u128 = match h.side {
            Side::Front => 1,
            Side::Back => 2,
        };
        let bits = |x: f32| u128::from(x.to_bits());
        bits(h.t) | bits(h.u) << 32 | bits(h.v) << 64 | side << 96
    }

    #[inline(always)]
    pub(super) fn unpack_f32(packed: u128) -> Option<TriangleHit<f32>> {
        let side = match packed >> 96 {
            0 => return None,
            1 => Side::Front,
            _ => Side::Back,
        };
        // (Truncating to the low 32 bits is the point.)
        let field = |shift: u32| f32::from_bits((packed >> shift) as u32);
        Some(TriangleHit {
            t: field(0),
            u: field(32),
            v: field(64),
            side,
        })
    }
}

/// The sign-exact `a*b - c*d` for each precision (see
/// [`Scalar::diff_of_products_exact_sign`]).
mod exact_sign {
    /// In `f64` the two products of `f32` values are exact (24 + 24 bits fit
    /// in 53, and exponents from `2^-298` to `2^256` are in range), and a
    /// rounded difference of two floats is zero only when they are equal, so
    /// the `f64` result has the exact sign. Narrowing to `f32` may flush a
    /// tiny nonzero value to zero; it is then replaced by the smallest
    /// subnormal of the same sign, so that the sign survives.
    #[inline]
    pub(super) fn f32(a: f32, b: f32, c: f32, d: f32) -> f32 {
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
    pub(super) fn f64(a: f64, b: f64, c: f64, d: f64) -> f64 {
        let p = a * b;
        let q = c * d;
        let diff = p - q;
        if diff != 0.0 {
            return diff;
        }
        fma(a, b, -p) - fma(c, d, -q)
    }

    /// The products of the pairs, as `f64` terms whose exact sum is the
    /// exact sum of the products (at most 16 terms for 8 pairs).
    pub(super) mod products {
        /// Exact: 24 + 24 bits fit in 53.
        pub(crate) fn f32(terms: &[(f32, f32)]) -> ([f64; 16], usize) {
            let mut out = [0.0; 16];
            for (o, &(a, b)) in out.iter_mut().zip(terms.iter().take(8)) {
                *o = f64::from(a) * f64::from(b);
            }
            (out, terms.len().min(8))
        }
        /// Each product as its rounded value and its exact error.
        pub(crate) fn f64(terms: &[(f64, f64)]) -> ([f64; 16], usize) {
            let mut out = [0.0; 16];
            let mut n = 0;
            for &(a, b) in terms.iter().take(8) {
                let p = a * b;
                out[n] = p;
                out[n + 1] = super::fma(a, b, -p);
                n += 2;
            }
            (out, n)
        }
    }

    /// The exact sign of the sum of the first `n` terms: they are added one
    /// by one to a nonoverlapping expansion (components of increasing
    /// magnitude, each a two-sum's exact error), dropping zero components;
    /// the sign of an expansion is that of its largest component.
    pub(super) fn sum_sign((terms, n): ([f64; 16], usize)) -> core::cmp::Ordering {
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
}

macro_rules! impl_vector {
    ($V:ty, $f:ty, $all_le:expr) => {
        impl sealed::Sealed for $V {}

        impl Vector for $V {
            type Scalar = $f;
            const ZERO: Self = <$V>::ZERO;

            #[inline(always)]
            fn get(&self, k: crate::lanes::Axis) -> $f {
                let a: &[$f; 3] = self.as_ref();
                a[k as usize]
            }

            #[inline]
            fn new(x: $f, y: $f, z: $f) -> Self {
                <$V>::new(x, y, z)
            }
            #[inline]
            fn splat(v: $f) -> Self {
                <$V>::splat(v)
            }
            #[inline]
            fn x(self) -> $f {
                self.x
            }
            #[inline]
            fn y(self) -> $f {
                self.y
            }
            #[inline]
            fn z(self) -> $f {
                self.z
            }
            // The products below are written out, in the order glam's `Vec3`
            // and `DVec3` use, so that every vector type of a precision gives
            // the same bits (glam's SIMD types may order a sum differently).
            #[inline]
            fn dot(self, rhs: Self) -> $f {
                (self.x * rhs.x) + (self.y * rhs.y) + (self.z * rhs.z)
            }
            #[inline]
            fn cross(self, rhs: Self) -> Self {
                <$V>::new(
                    self.y * rhs.z - rhs.y * self.z,
                    self.z * rhs.x - rhs.z * self.x,
                    self.x * rhs.y - rhs.x * self.y,
                )
            }
            #[inline]
            fn abs(self) -> Self {
                <$V>::abs(self)
            }
            #[inline]
            fn is_finite(self) -> bool {
                <$V>::is_finite(self)
            }
            #[inline]
            fn all_le(self, rhs: Self) -> bool {
                $all_le(self, rhs)
            }
            #[inline]
            fn length(self) -> $f {
                <$f as Scalar>::sqrt(Vector::dot(self, self))
            }
            #[inline]
            fn normalize_or_zero(self) -> Self {
                let rcp = 1.0 / Vector::length(self);
                if rcp.is_finite() && rcp > 0.0 {
                    self * rcp
                } else {
                    <$V>::ZERO
                }
            }
        }
    };
}

/// `Vec3`, `Vec3A` and `DVec3` of the glam crate `$glam` (the default one or
/// an older release under its renamed dependency). `Vec3A` is glam's SIMD
/// vector: `cmple` is one `cmpleps` on x86 (false for NaN, as `<=` is), and
/// `all` one `movmskps`; `Vec3` goes through it for the same reason.
macro_rules! impl_glam {
    ($glam:ident) => {
        impl_vector!($glam::Vec3, f32, |a: $glam::Vec3, b: $glam::Vec3| {
            $glam::Vec3A::from(a).cmple($glam::Vec3A::from(b)).all()
        });
        impl_vector!($glam::Vec3A, f32, |a: $glam::Vec3A, b: $glam::Vec3A| a
            .cmple(b)
            .all());
        impl_vector!($glam::DVec3, f64, |a: $glam::DVec3, b: $glam::DVec3| a
            .cmple(b)
            .all());
    };
}

impl_glam!(glam);
#[cfg(feature = "glam-0_29")]
impl_glam!(glam029);
#[cfg(feature = "glam-0_30")]
impl_glam!(glam030);
#[cfg(feature = "glam-0_31")]
impl_glam!(glam031);
#[cfg(feature = "glam-0_32")]
impl_glam!(glam032);
#[cfg(feature = "glam-0_33")]
impl_glam!(glam033);

/// Makes an error bound that was evaluated in floating point an upper bound
/// of the same expression evaluated exactly.
///
/// `value` must be a sum of products of non-negative numbers (the shape of
/// every bound in the crate), evaluated with at most `roundings` roundings
/// along any path from an input to the result. Each rounding of a
/// non-negative quantity can only shrink it by a factor `1 - u`, so the
/// computed value is at least `exact * (1 - u)^roundings`. Multiplying by
/// `c >= 1 + gamma(roundings + 1) >= (1 - u)^-(roundings + 1)` (Bernoulli)
/// and rounding once more gives at least `exact`. `c` is itself rounded up.
#[inline(always)]
pub(crate) fn bound_up<F: Scalar>(value: F, roundings: u32) -> F {
    value * (F::ONE + F::gamma_n(roundings + 1)).next_up()
}

/// `v / |v|`, computed as `v * (1 / sqrt(v . v))` (glam's `normalize`) on
/// `v` scaled by a power of two that brings its largest component into
/// `[1, 2)`, so that `v . v` can neither overflow nor underflow; a NaN
/// vector when `v` is zero or not finite.
///
/// Scaling by a power of two is exact in the normal range, and it scales
/// `v . v` by the square, its square root and reciprocal by the power
/// itself, all exactly: so where `v . v` is a normal float the result is bit
/// for bit `normalize(v)`, and that case skips the scaling. Elsewhere (a
/// length whose square overflows, such as a camera ray at a focal length of
/// `1e30` pixels, or underflows) it is the same computation on the scaled
/// vector, with the same error: components that the scaling pushes below
/// the normal range are below `2^-126` of the largest and change the
/// length by less than a rounding.
pub(crate) fn unit<V: Vector>(v: V) -> V {
    let one = S::<V>::ONE;
    let l2 = v.dot(v);
    if l2 >= S::<V>::MIN_POSITIVE && l2 <= S::<V>::MAX {
        return v * (one / l2.sqrt());
    }
    let a = v.abs();
    let m = max2(a.x(), max2(a.y(), a.z()));
    if !(m > S::<V>::ZERO && m <= S::<V>::MAX) {
        // Zero gives 0 * inf and an infinite component inf * 0: NaN.
        return v * (one / l2.sqrt());
    }
    // A subnormal maximum first goes up by 2^(2p) (p the precision), exactly.
    let lift = one / (S::<V>::UNIT_ROUNDOFF * S::<V>::UNIT_ROUNDOFF);
    let (v, m) = if m < S::<V>::MIN_POSITIVE {
        (v * lift, m * lift)
    } else {
        (v, m)
    };
    // m is normal: its exponent e, read from its f64 image (exact for both
    // precisions), and 2^-e applied in two steps whose factors are each
    // representable (|e| <= 1023 for f64, 127 for f32).
    let e = ((m.to_f64().to_bits() >> 52) & 0x7ff) as i32 - 1023;
    let pow2 = |k: i32| S::<V>::from_f64(f64::from_bits(((1023 + k) as u64) << 52));
    let half = -e / 2;
    let w = v * pow2(half) * pow2(-e - half);
    w * (one / w.dot(w).sqrt())
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

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DVec3, Vec3};

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

    #[test]
    fn in_unit_interval_is_the_two_comparisons() {
        fn check<F: Scalar>() {
            let (zero, one, tiny) = (F::ZERO, F::ONE, F::TINY);
            let (inf, nan) = (F::INFINITY, F::NAN);
            let values = [
                zero,
                -zero,
                tiny,
                -tiny,
                F::HALF,
                one.next_down(),
                one,
                one.next_up(),
                -one,
                F::MAX,
                inf,
                -inf,
                nan,
                -nan,
            ];
            for x in values {
                let expected = x >= zero && x <= one;
                assert_eq!(x.in_unit_interval(), expected, "{x:?}");
            }
        }
        check::<f32>();
        check::<f64>();
    }

    #[test]
    fn packed_hits_come_back_bit_for_bit() {
        use crate::{Side, TriangleHit};
        let odd = [0.0, -0.0, f32::from_bits(1), 1.0, f32::MAX, f32::INFINITY];
        let mut hits = [None; 13];
        for (i, &t) in odd.iter().enumerate() {
            let (u, v) = (odd[(i + 1) % odd.len()], odd[(i + 2) % odd.len()]);
            for (j, side) in [Side::Front, Side::Back].into_iter().enumerate() {
                hits[1 + 2 * i + j] = Some(TriangleHit { t, u, v, side });
            }
        }
        let key = |h: Option<TriangleHit<f32>>| {
            h.map(|h| (h.t.to_bits(), h.u.to_bits(), h.v.to_bits(), h.side))
        };
        let mut packed = hits.map(f32::pack_hit);
        for (h, p) in hits.iter().zip(packed) {
            assert_eq!(key(f32::unpack_hit(p)), key(*h));
        }
        // Distinct answers pack to distinct integers (a miss is not a hit
        // at t = u = v = 0, on either side).
        packed.sort_unstable();
        assert!(packed.windows(2).all(|w| w[0] < w[1]));
        let h = Some(TriangleHit {
            t: 2.5,
            u: 0.25,
            v: 0.5,
            side: Side::Back,
        });
        assert_eq!(f64::unpack_hit(f64::pack_hit(h)), h);
    }

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
    fn unit_is_normalize_where_that_works_and_unit_where_it_does_not() {
        // Bit for bit glam's normalize for an ordinary vector (the scaling
        // argument), in both precisions.
        let v = Vec3::new(0.3, -1.7, 2.9);
        assert_eq!(unit(v), v.normalize());
        let w = DVec3::new(1e-3, 5.0, -7.0);
        assert_eq!(unit(w), w.normalize());
        // Squares that underflow or overflow: glam gives zero or NaN, unit
        // gives the direction. The exact answer is (0.6, 0.8, 0); each
        // component is within gamma(6) (the camera's documented bound:
        // 3.6e-7 in f32, 6.7e-16 in f64) of it, plus the rounding of 0.6
        // and 0.8 themselves, well inside 1e-6 and 1e-15.
        for s in [1e-42_f32, 1e-30, 1e30, 8e37] {
            let u = unit(Vec3::new(3.0, 4.0, 0.0) * s);
            assert!(
                (u - Vec3::new(0.6, 0.8, 0.0)).abs().max_element() < 1e-6,
                "{s}: {u}"
            );
        }
        for s in [1e-320_f64, 1e-200, 1e200, 1e307] {
            let u = unit(DVec3::new(3.0, 4.0, 0.0) * s);
            assert!(
                (u - DVec3::new(0.6, 0.8, 0.0)).abs().max_element() < 1e-15,
                "{s}: {u}"
            );
        }
        // Zero and non-finite vectors give a non-finite result.
        for bad in [Vec3::ZERO, Vec3::new(f32::INFINITY, 0.0, 0.0), Vec3::NAN] {
            assert!(!unit(bad).is_finite());
        }
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
}
