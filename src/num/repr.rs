//! How a precision is represented inside the kernels: the private
//! supertrait [`Repr`] of [`Scalar`](super::Scalar), which carries only
//! associated types, each bounded by an interface of this crate's own
//! (so nothing on it can be called from outside the crate).
//!
//! - The lane types ([`Lanes`], [`Lanes8`]): the interfaces are in
//!   `super::lanes`, the implementations and the choice per target in
//!   `crate::simd` (which implements `Repr` for `f32` and `f64`).
//! - The bits ([`Bits`]): the bit-level tricks some hot paths need.
//!
//! [`Components`], likewise the private supertrait of
//! [`Vector`](super::Vector), reads a vector's component by [`Axis`].

use super::lanes::{Axis, Lanes, Lanes8};

/// The kernels' view of a precision: its lane types and its bits.
pub trait Repr: Sized {
    /// Four lanes: the three axes or corners of one shape.
    type L4: Lanes<F = Self>;
    /// Eight lanes, as the build's target computes them (one lane per shape
    /// of a batch).
    type L8: Lanes8<F = Self>;
    /// Eight lanes, for code compiled with AVX2 (and AVX-512) enabled and
    /// run only where the CPU has it.
    #[cfg(rayhit_runtime_avx)]
    type L8Avx2: Lanes8<F = Self>;
    /// The precision's bit-level operations.
    type Bits: Bits<F = Self>;
}

/// The kernels' view of a vector: its component on an axis.
pub trait Components {
    /// The component type.
    type Elem;
    /// The component on axis `k`: an index the compiler knows is in range
    /// (for the triangle tests' permutation), read from the vector's
    /// storage.
    fn get(&self, k: Axis) -> Self::Elem;
}

/// Bit-level operations of a precision.
pub trait Bits {
    /// The precision.
    type F: Copy;
    /// Three values and a small code, packed so that a function returns
    /// them in registers (a `u128` for `f32`; `f64`'s do not fit, and stay
    /// as they are).
    type Packed: Copy;
    /// `values` and `code` (below 8) packed.
    fn pack(values: [Self::F; 3], code: u32) -> Self::Packed;
    /// The inverse of [`Bits::pack`], bit for bit.
    fn unpack(packed: Self::Packed) -> ([Self::F; 3], u32);
    /// `0 <= x <= 1`, as one comparison of the bits and a test for `-0`
    /// (which the bits put above 1), so that it compiles to one branch.
    /// False for NaN.
    fn in_unit_interval(x: Self::F) -> bool;
    /// `|x|` with the sign bit of `sign` (IEEE 754 `copySign`: `-0` and
    /// NaN's sign bits count).
    fn copysign(x: Self::F, sign: Self::F) -> Self::F;
    /// The power of two of `|x|`'s binade (`2^e` with `2^e <= |x| <
    /// 2^(e+1)`) for normal `x`; zero for zero and subnormals, infinity
    /// for infinities and NaN: the exponent bits alone.
    fn binade(x: Self::F) -> Self::F;
    /// The float after `x` for `x` in `[-0, +inf]` (what `next_up` gives
    /// there: the smallest subnormal after either zero, `+inf` after
    /// `+inf`), as integer operations on the bits with no branch. Other
    /// inputs (negative, NaN) give some float.
    fn successor(x: Self::F) -> Self::F;
    /// `2^-e` for `|x|` in the binade `[2^e, 2^(e+1))`, exactly, so that
    /// `|x| 2^-e` is in `[1, 2)`; for `|x|` at or above `2^(emax - 1)`,
    /// `2^(1 - emax)` (the largest `e` whose `2^-e` is normal; `emax` is 127
    /// or 1023); for zero, subnormals, infinities and NaN (which need no
    /// exact answer) some power of two: `2^emax` for zero and subnormals,
    /// `2^(1 - emax)` for the others. Integer operations on the bits only,
    /// with no branch.
    fn inverse_binade(x: Self::F) -> Self::F;
    /// `(sin, cos)` turned `q` quarter turns further on (`(cos, -sin)`,
    /// `(-sin, -cos)` or `(-cos, sin)`), `q` read from the low two bits of
    /// `y`'s significand: for `y = c + k` with `c = 1.5 * 2^(p-1)` (`p` the
    /// precision) and `k` an integer, `|k| < 2^(p-2)`, those bits are `k`
    /// modulo 4. Integer operations on the bits only (a swap by masks and
    /// sign flips), exact, with no comparison and no branch.
    fn quarter_turns(y: Self::F, sin: Self::F, cos: Self::F) -> (Self::F, Self::F);
}

/// [`Bits`] of `f32`.
#[derive(Clone, Copy, Debug)]
pub struct F32Bits;

/// [`Bits`] of `f64`.
#[derive(Clone, Copy, Debug)]
pub struct F64Bits;

impl Bits for F32Bits {
    type F = f32;
    /// The three values in bits 0, 32 and 64, the code above them.
    type Packed = u128;

    #[inline(always)]
    fn pack(values: [f32; 3], code: u32) -> u128 {
        let bits = |x: f32| u128::from(x.to_bits());
        bits(values[0]) | bits(values[1]) << 32 | bits(values[2]) << 64 | u128::from(code) << 96
    }

    #[inline(always)]
    fn unpack(packed: u128) -> ([f32; 3], u32) {
        // (Truncating to the low 32 bits is the point.)
        let field = |shift: u32| (packed >> shift) as u32;
        (
            [field(0), field(32), field(64)].map(f32::from_bits),
            field(96),
        )
    }

    #[inline(always)]
    fn in_unit_interval(x: f32) -> bool {
        // The bits of a non-negative float (NaN aside) order as its value,
        // and every negative one's sign bit puts it above 1's: so the first
        // test is `+0 <= x <= 1`.
        (x.to_bits() <= 1f32.to_bits()) | (x == 0.0)
    }

    #[inline(always)]
    fn copysign(x: f32, sign: f32) -> f32 {
        x.copysign(sign)
    }

    #[inline(always)]
    fn successor(x: f32) -> f32 {
        // Without the sign bit, the bits of [+0, +inf] count up.
        f32::from_bits(((x.to_bits() & 0x7fff_ffff) + 1).min(0x7f80_0000))
    }

    #[inline(always)]
    fn binade(x: f32) -> f32 {
        f32::from_bits(x.to_bits() & 0x7f80_0000)
    }

    #[inline(always)]
    fn inverse_binade(x: f32) -> f32 {
        // The exponent field E (biased: 2^e has E = e + 127), clamped to
        // 253 (2^126); 254 - E is the field of 2^-e, in 1..=254.
        // (The clamp as a float minimum, one instruction in SIMD, where
        // an unsigned integer minimum is several without SSE4.1; a NaN
        // gives the clamp.)
        let a = f32::from_bits(x.to_bits() & 0x7fff_ffff);
        let cap = f32::from_bits(253 << 23);
        let field = (if a < cap { a } else { cap }).to_bits() & 0x7f80_0000;
        f32::from_bits((254 << 23) - field)
    }

    #[inline(always)]
    fn quarter_turns(y: f32, sin: f32, cos: f32) -> (f32, f32) {
        let q = y.to_bits();
        // All ones for odd q: then sin and cos swap places.
        let swap = 0u32.wrapping_sub(q & 1);
        let (s, c) = (sin.to_bits(), cos.to_bits());
        let (a, b) = ((s & !swap) | (c & swap), (c & !swap) | (s & swap));
        // sin(x + q pi/2) is negative for q = 2, 3 (bit 1 of q); cos(x +
        // q pi/2) for q = 1, 2 (bit 1 of q + 1).
        (
            f32::from_bits(a ^ ((q & 2) << 30)),
            f32::from_bits(b ^ ((q.wrapping_add(1) & 2) << 30)),
        )
    }
}

impl Bits for F64Bits {
    type F = f64;
    type Packed = ([f64; 3], u32);

    #[inline(always)]
    fn pack(values: [f64; 3], code: u32) -> ([f64; 3], u32) {
        (values, code)
    }

    #[inline(always)]
    fn unpack(packed: ([f64; 3], u32)) -> ([f64; 3], u32) {
        packed
    }

    #[inline(always)]
    fn in_unit_interval(x: f64) -> bool {
        // As for `f32`.
        (x.to_bits() <= 1f64.to_bits()) | (x == 0.0)
    }

    #[inline(always)]
    fn copysign(x: f64, sign: f64) -> f64 {
        x.copysign(sign)
    }

    #[inline(always)]
    fn successor(x: f64) -> f64 {
        f64::from_bits(((x.to_bits() & 0x7fff_ffff_ffff_ffff) + 1).min(0x7ff0_0000_0000_0000))
    }

    #[inline(always)]
    fn binade(x: f64) -> f64 {
        f64::from_bits(x.to_bits() & 0x7ff0_0000_0000_0000)
    }

    #[inline(always)]
    fn inverse_binade(x: f64) -> f64 {
        // As for `f32`: E = e + 1023, clamped to 2045 (2^1022).
        let a = f64::from_bits(x.to_bits() & 0x7fff_ffff_ffff_ffff);
        let cap = f64::from_bits(2045 << 52);
        let field = (if a < cap { a } else { cap }).to_bits() & 0x7ff0_0000_0000_0000;
        f64::from_bits((2046 << 52) - field)
    }

    #[inline(always)]
    fn quarter_turns(y: f64, sin: f64, cos: f64) -> (f64, f64) {
        // As for `f32`.
        let q = y.to_bits();
        let swap = 0u64.wrapping_sub(q & 1);
        let (s, c) = (sin.to_bits(), cos.to_bits());
        let (a, b) = ((s & !swap) | (c & swap), (c & !swap) | (s & swap));
        (
            f64::from_bits(a ^ ((q & 2) << 62)),
            f64::from_bits(b ^ ((q.wrapping_add(1) & 2) << 62)),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::Scalar;

    /// `successor` is `next_up` on `[-0, +inf]`: both zeros, subnormals,
    /// the normal range's ends, binade edges and random floats.
    #[test]
    fn successor_is_next_up_from_zero_up() {
        fn check<F: Scalar + core::fmt::Debug>(successor: fn(F) -> F, random: &[F]) {
            let mut values = std::vec![
                F::ZERO,
                -F::ZERO,
                F::TINY,
                F::MIN_POSITIVE,
                F::MIN_POSITIVE.next_down(),
                F::ONE,
                F::ONE.next_down(),
                F::TWO,
                F::MAX,
                F::MAX.next_down(),
                F::INFINITY,
            ];
            values.extend_from_slice(random);
            for x in values {
                let (got, expected) = (successor(x), x.next_up());
                assert!(
                    got == expected && got > x || x == F::INFINITY && got == x,
                    "{x:?}: {got:?}"
                );
            }
        }
        let mut draws = crate::testing::Draws(0x5ecc_e550);
        let r32: std::vec::Vec<f32> = (0..1000)
            .map(|_| f32::from_bits((draws.next() >> 33) as u32 & 0x7f7f_ffff))
            .collect();
        let r64: std::vec::Vec<f64> = (0..1000)
            .map(|_| f64::from_bits(draws.next() >> 2))
            .collect();
        check::<f32>(F32Bits::successor, &r32);
        check::<f64>(F64Bits::successor, &r64);
    }

    /// `in_unit_interval` is `0 <= x && x <= 1`, signed zeros, the
    /// neighbours of 0 and 1, infinities and NaN included.
    #[test]
    fn in_unit_interval_is_the_two_comparisons() {
        fn check<F: Scalar>(in_unit: fn(F) -> bool) {
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
                assert_eq!(in_unit(x), expected, "{x:?}");
            }
        }
        check::<f32>(F32Bits::in_unit_interval);
        check::<f64>(F64Bits::in_unit_interval);
    }

    /// Packed values come back bit for bit, and distinct ones pack apart.
    #[test]
    fn packed_values_come_back_bit_for_bit() {
        let odd = [0.0, -0.0, f32::from_bits(1), 1.0, f32::MAX, f32::INFINITY];
        let mut packed = std::vec::Vec::new();
        for (i, &a) in odd.iter().enumerate() {
            let values = [a, odd[(i + 1) % odd.len()], odd[(i + 2) % odd.len()]];
            for code in 0..8 {
                let p = F32Bits::pack(values, code);
                let (v, c) = F32Bits::unpack(p);
                assert_eq!((v.map(f32::to_bits), c), (values.map(f32::to_bits), code));
                packed.push(p);
            }
        }
        packed.sort_unstable();
        assert!(packed.windows(2).all(|w| w[0] < w[1]));
        let (v, c) = F64Bits::unpack(F64Bits::pack([2.5, -0.0, 0.5], 2));
        assert_eq!(
            (v.map(f64::to_bits), c),
            ([2.5, -0.0, 0.5].map(f64::to_bits), 2)
        );
    }
}
