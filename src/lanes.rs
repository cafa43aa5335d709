//! Four-lane arithmetic for the kernels' hot paths: the three axes of a
//! box, or the three corners of a triangle, in one register.
//!
//! [`Lanes`] is the small set of operations the scalar kernels need, each
//! defined lane by lane with the semantics of the scalar code it replaces,
//! so that a kernel written against it gives the same bits as the
//! one-component-at-a-time code (which the batch kernels and the `f64`
//! kernels still run): IEEE add, subtract and multiply; `max(a, b)` is
//! `if a > b { a } else { b }` and `min(a, b)` is `if a < b { a } else { b }`
//! (so a NaN in `a` gives `b`: the property the slab test's NaN-safe folds
//! rely on); comparisons are false for NaN. Only lanes 0 to 2 carry data;
//! lane 3 is computed along and never read.
//!
//! `f32` on x86 and x86-64 (where SSE2 is part of every target the crate
//! builds for) uses SSE registers: each operation is one instruction,
//! because SSE's `maxps`/`minps` are exactly the comparisons above,
//! operand order included (Intel SDM, MAXPS: "if only one value is a NaN ...
//! the second operand ... is returned"). Everywhere else, and for `f64`,
//! [`Portable`] runs the same definitions on an array.

use core::fmt::Debug;

use crate::real::Scalar;

/// A coordinate axis, as an index the compiler knows is below 3 (so that
/// indexing a three-component array with it needs no bounds check).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum Axis {
    /// `x`, index 0.
    X = 0,
    /// `y`, index 1.
    Y = 1,
    /// `z`, index 2.
    Z = 2,
}

impl Axis {
    /// The axis of index `k`, for `k` in 0..3 (`z` for anything larger).
    #[inline(always)]
    pub(crate) fn from_index(k: usize) -> Self {
        match k {
            0 => Axis::X,
            1 => Axis::Y,
            _ => Axis::Z,
        }
    }
}

/// Four lanes of a scalar type; see the module docs for the semantics.
///
/// Public only so that it can appear in the sealed [`Scalar`] trait; it is
/// not reachable from outside the crate.
pub trait Lanes: Copy + Debug + Send + Sync + 'static {
    /// The scalar in each lane.
    type F: Scalar;
    /// `(x, y, z)`; lane 3 repeats `z`.
    fn new(x: Self::F, y: Self::F, z: Self::F) -> Self;
    /// `(x, y, z)`, with `w` in lane 3 (any value: lane 3 is computed
    /// along and never read). Where `w` is the value stored next to `z`, the
    /// four lanes can come from one load.
    fn new4(x: Self::F, y: Self::F, z: Self::F, w: Self::F) -> Self;
    /// `v` in every lane.
    fn splat(v: Self::F) -> Self;
    /// Lanes 0, 1, 2.
    fn to_array(self) -> [Self::F; 3];
    /// Lane 0.
    fn x(self) -> Self::F;
    /// Lane-wise `self + o`.
    fn add(self, o: Self) -> Self;
    /// Lane-wise `self - o`.
    fn sub(self, o: Self) -> Self;
    /// Lane-wise `self * o`.
    fn mul(self, o: Self) -> Self;
    /// Lane-wise `self / o`.
    fn div(self, o: Self) -> Self;
    /// Lane-wise `if self > o { self } else { o }`.
    fn max(self, o: Self) -> Self;
    /// Lane-wise `if self < o { self } else { o }`.
    fn min(self, o: Self) -> Self;
    /// Lane-wise absolute value.
    fn abs(self) -> Self;
    /// Lane-wise negation (the sign bit flipped, as `-x` does).
    fn neg(self) -> Self;
    /// Bit `k` set when `self[k] < o[k]`, for `k` in 0..3.
    fn lt(self, o: Self) -> u32;
    /// Bit `k` set when `self[k] <= o[k]`.
    fn le(self, o: Self) -> u32;
    /// Bit `k` set when `self[k] == o[k]`.
    fn eq(self, o: Self) -> u32;
    /// `(y, z, x)`: lane `k` holds lane `k + 1` (mod 3).
    fn rot1(self) -> Self;
    /// `(z, x, y)`: lane `k` holds lane `k + 2` (mod 3).
    fn rot2(self) -> Self;
    /// `max(max(v[k], v[k + 1]), v[k + 2])` in lane `k` (indices mod 3),
    /// with [`Lanes::max`]'s semantics: for values that are not NaN, the
    /// largest of the three in every lane (a `+0`/`-0` tie aside).
    #[inline(always)]
    fn max_all(self) -> Self {
        self.max(self.rot1()).max(self.rot2())
    }
    /// The same with [`Lanes::min`]: the smallest of the three.
    #[inline(always)]
    fn min_all(self) -> Self {
        self.min(self.rot1()).min(self.rot2())
    }
    /// `(x + y) + z`, in that order.
    fn sum3(self) -> Self::F;
    /// Bit `k` set when `self[k] <= o[k]` fails (NaN included): `!le` on
    /// lanes 0 to 2, one comparison.
    fn nle(self, o: Self) -> u32;
}

/// The lanes as an array, each operation a loop over it: the definition of
/// the semantics, and the implementation wherever no register type is used.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Portable<F>([F; 4]);

impl<F: Scalar> Portable<F> {
    #[inline(always)]
    fn map2(self, o: Self, f: impl Fn(F, F) -> F) -> Self {
        let (a, b) = (self.0, o.0);
        Self([f(a[0], b[0]), f(a[1], b[1]), f(a[2], b[2]), f(a[3], b[3])])
    }

    #[inline(always)]
    fn mask(self, o: Self, f: impl Fn(F, F) -> bool) -> u32 {
        let (a, b) = (self.0, o.0);
        u32::from(f(a[0], b[0])) | u32::from(f(a[1], b[1])) << 1 | u32::from(f(a[2], b[2])) << 2
    }
}

impl<F: Scalar> Lanes for Portable<F> {
    type F = F;
    #[inline(always)]
    fn new(x: F, y: F, z: F) -> Self {
        Self([x, y, z, z])
    }
    #[inline(always)]
    fn new4(x: F, y: F, z: F, w: F) -> Self {
        Self([x, y, z, w])
    }
    #[inline(always)]
    fn splat(v: F) -> Self {
        Self([v; 4])
    }
    #[inline(always)]
    fn to_array(self) -> [F; 3] {
        [self.0[0], self.0[1], self.0[2]]
    }
    #[inline(always)]
    fn x(self) -> F {
        self.0[0]
    }
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        self.map2(o, |a, b| a + b)
    }
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        self.map2(o, |a, b| a - b)
    }
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        self.map2(o, |a, b| a * b)
    }
    #[inline(always)]
    fn div(self, o: Self) -> Self {
        self.map2(o, |a, b| a / b)
    }
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        self.map2(o, |a, b| if a > b { a } else { b })
    }
    #[inline(always)]
    fn min(self, o: Self) -> Self {
        self.map2(o, |a, b| if a < b { a } else { b })
    }
    #[inline(always)]
    fn abs(self) -> Self {
        Self(self.0.map(F::abs))
    }
    #[inline(always)]
    fn neg(self) -> Self {
        Self(self.0.map(|x| -x))
    }
    #[inline(always)]
    fn lt(self, o: Self) -> u32 {
        self.mask(o, |a, b| a < b)
    }
    #[inline(always)]
    fn le(self, o: Self) -> u32 {
        self.mask(o, |a, b| a <= b)
    }
    #[inline(always)]
    fn eq(self, o: Self) -> u32 {
        self.mask(o, |a, b| a == b)
    }
    #[inline(always)]
    fn nle(self, o: Self) -> u32 {
        self.mask(o, |a, b| !(a <= b))
    }
    #[inline(always)]
    fn rot1(self) -> Self {
        let a = self.0;
        Self([a[1], a[2], a[0], a[3]])
    }
    #[inline(always)]
    fn rot2(self) -> Self {
        let a = self.0;
        Self([a[2], a[0], a[1], a[3]])
    }
    #[inline(always)]
    fn sum3(self) -> F {
        let [x, y, z, _] = self.0;
        (x + y) + z
    }
}

/// The `f32` lanes the kernels use on this target.
#[cfg(all(
    any(target_arch = "x86", target_arch = "x86_64"),
    target_feature = "sse2"
))]
pub type F32Lanes = sse::F32x4;
/// The `f32` lanes the kernels use on this target.
#[cfg(not(all(
    any(target_arch = "x86", target_arch = "x86_64"),
    target_feature = "sse2"
)))]
pub type F32Lanes = Portable<f32>;

/// SSE registers, one instruction per operation.
///
/// Safety of the `unsafe` blocks below: each calls an SSE or SSE2 intrinsic
/// (`core::arch`), and the only precondition of those is that the CPU
/// supports the instruction set. This module is compiled only when the
/// target has SSE2 enabled at compile time (`target_feature = "sse2"`, part
/// of every x86-64 target and of the i686 ones), so every CPU the code can
/// run on has it. None of them touches memory except the loads and stores
/// of `F32x4x2`, whose comments say why they stay inside their reference.
#[cfg(all(
    any(target_arch = "x86", target_arch = "x86_64"),
    target_feature = "sse2"
))]
#[allow(unsafe_code)]
pub(crate) mod sse {
    #[cfg(target_arch = "x86")]
    use core::arch::x86::*;
    #[cfg(target_arch = "x86_64")]
    use core::arch::x86_64::*;

    use super::Lanes;

    /// Four `f32` lanes in an SSE register.
    #[derive(Clone, Copy)]
    pub struct F32x4(__m128);

    impl core::fmt::Debug for F32x4 {
        fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
            self.to_array().fmt(f)
        }
    }

    /// Lane 1 of `v` in every lane.
    #[inline(always)]
    fn lane1(v: __m128) -> __m128 {
        // SAFETY: see the module docs (SSE, no memory access).
        unsafe { _mm_shuffle_ps::<0b01_01_01_01>(v, v) }
    }

    /// Lane 2 of `v` in every lane.
    #[inline(always)]
    fn lane2(v: __m128) -> __m128 {
        // SAFETY: see the module docs (SSE, no memory access).
        unsafe { _mm_shuffle_ps::<0b10_10_10_10>(v, v) }
    }

    /// A lane-wise operation of two registers.
    macro_rules! op2 {
        ($name:ident, $intrinsic:ident) => {
            #[inline(always)]
            fn $name(self, o: Self) -> Self {
                // SAFETY: see the module docs (SSE, no memory access).
                Self(unsafe { $intrinsic(self.0, o.0) })
            }
        };
    }

    /// A comparison of two registers, as a mask of lanes 0 to 2.
    macro_rules! cmp {
        ($name:ident, $intrinsic:ident) => {
            #[inline(always)]
            fn $name(self, o: Self) -> u32 {
                // SAFETY: see the module docs (SSE, no memory access).
                (unsafe { _mm_movemask_ps($intrinsic(self.0, o.0)) } as u32) & 0b111
            }
        };
    }

    impl Lanes for F32x4 {
        type F = f32;
        #[inline(always)]
        fn new(x: f32, y: f32, z: f32) -> Self {
            // SAFETY: see the module docs (SSE, no memory access).
            Self(unsafe { _mm_set_ps(z, z, y, x) })
        }
        #[inline(always)]
        fn new4(x: f32, y: f32, z: f32, w: f32) -> Self {
            // SAFETY: see the module docs (SSE, no memory access).
            Self(unsafe { _mm_set_ps(w, z, y, x) })
        }
        #[inline(always)]
        fn splat(v: f32) -> Self {
            // SAFETY: see the module docs (SSE, no memory access).
            Self(unsafe { _mm_set1_ps(v) })
        }
        #[inline(always)]
        fn to_array(self) -> [f32; 3] {
            // SAFETY: see the module docs (SSE, no memory access).
            unsafe {
                [
                    _mm_cvtss_f32(self.0),
                    _mm_cvtss_f32(lane1(self.0)),
                    _mm_cvtss_f32(lane2(self.0)),
                ]
            }
        }
        #[inline(always)]
        fn x(self) -> f32 {
            // SAFETY: see the module docs (SSE, no memory access).
            unsafe { _mm_cvtss_f32(self.0) }
        }
        op2!(add, _mm_add_ps);
        op2!(sub, _mm_sub_ps);
        op2!(mul, _mm_mul_ps);
        op2!(div, _mm_div_ps);
        // MAXPS/MINPS return the second operand unless the first compares
        // greater (less): `if a > b { a } else { b }`, NaN included.
        op2!(max, _mm_max_ps);
        op2!(min, _mm_min_ps);
        #[inline(always)]
        fn abs(self) -> Self {
            // SAFETY: see the module docs (SSE, no memory access).
            Self(unsafe { _mm_andnot_ps(_mm_set1_ps(-0.0), self.0) })
        }
        #[inline(always)]
        fn neg(self) -> Self {
            // SAFETY: see the module docs (SSE, no memory access).
            Self(unsafe { _mm_xor_ps(_mm_set1_ps(-0.0), self.0) })
        }
        cmp!(lt, _mm_cmplt_ps);
        cmp!(le, _mm_cmple_ps);
        cmp!(eq, _mm_cmpeq_ps);
        cmp!(nle, _mm_cmpnle_ps);
        #[inline(always)]
        fn rot1(self) -> Self {
            // (y, z, x, w): lanes 1, 2, 0, 3.
            // SAFETY: see the module docs (SSE, no memory access).
            Self(unsafe { _mm_shuffle_ps::<0b11_00_10_01>(self.0, self.0) })
        }
        #[inline(always)]
        fn rot2(self) -> Self {
            // (z, x, y, w): lanes 2, 0, 1, 3.
            // SAFETY: see the module docs (SSE, no memory access).
            Self(unsafe { _mm_shuffle_ps::<0b11_01_00_10>(self.0, self.0) })
        }
        #[inline(always)]
        fn sum3(self) -> f32 {
            // SAFETY: see the module docs (SSE, no memory access).
            unsafe {
                let xy = _mm_add_ss(self.0, lane1(self.0));
                _mm_cvtss_f32(_mm_add_ss(xy, lane2(self.0)))
            }
        }
    }

    /// Eight `f32` lanes in two SSE registers.
    #[derive(Clone, Copy, Debug)]
    pub struct F32x4x2([__m128; 2]);

    impl F32x4x2 {
        #[inline(always)]
        fn map2(self, o: Self, f: impl Fn(__m128, __m128) -> __m128) -> Self {
            Self([f(self.0[0], o.0[0]), f(self.0[1], o.0[1])])
        }
    }

    /// A lane-wise operation of two register pairs.
    macro_rules! op2x2 {
        ($name:ident, $intrinsic:ident) => {
            #[inline(always)]
            fn $name(self, o: Self) -> Self {
                // SAFETY: see the module docs (SSE, no memory access).
                self.map2(o, |a, b| unsafe { $intrinsic(a, b) })
            }
        };
    }

    /// A comparison of two register pairs, as a mask pair.
    macro_rules! cmpx2 {
        ($name:ident, $intrinsic:ident) => {
            #[inline(always)]
            fn $name(self, o: Self) -> [__m128; 2] {
                // SAFETY: see the module docs (SSE, no memory access).
                self.map2(o, |a, b| unsafe { $intrinsic(a, b) }).0
            }
        };
    }

    impl super::Lanes8 for F32x4x2 {
        type F = f32;
        type Mask = [__m128; 2];
        #[inline(always)]
        fn splat(v: f32) -> Self {
            // SAFETY: see the module docs (SSE, no memory access).
            let x = unsafe { _mm_set1_ps(v) };
            Self([x, x])
        }
        #[inline(always)]
        fn load(a: &[f32; 8]) -> Self {
            // SAFETY: see the module docs (SSE); each unaligned load reads
            // 16 bytes inside a reference to 8 `f32`.
            Self(unsafe { [_mm_loadu_ps(a.as_ptr()), _mm_loadu_ps(a.as_ptr().add(4))] })
        }
        #[inline(always)]
        fn store(self, a: &mut [f32; 8]) {
            // SAFETY: see the module docs (SSE); each unaligned store writes
            // 16 bytes inside a mutable reference to 8 `f32`.
            unsafe {
                _mm_storeu_ps(a.as_mut_ptr(), self.0[0]);
                _mm_storeu_ps(a.as_mut_ptr().add(4), self.0[1]);
            }
        }
        #[inline(always)]
        fn from_bytes(b: &[u8; 8]) -> Self {
            // SAFETY: see the module docs (SSE2); the load reads 8 bytes
            // from a reference to 8 bytes. Bytes widen to 16 and then 32
            // bits by interleaving with zeros (SSE2 has no zero extension).
            Self(unsafe {
                let zero = _mm_setzero_si128();
                let words = _mm_unpacklo_epi8(_mm_loadl_epi64(b.as_ptr().cast()), zero);
                [
                    _mm_cvtepi32_ps(_mm_unpacklo_epi16(words, zero)),
                    _mm_cvtepi32_ps(_mm_unpackhi_epi16(words, zero)),
                ]
            })
        }
        op2x2!(add, _mm_add_ps);
        op2x2!(sub, _mm_sub_ps);
        op2x2!(mul, _mm_mul_ps);
        op2x2!(div, _mm_div_ps);
        op2x2!(max, _mm_max_ps);
        op2x2!(min, _mm_min_ps);
        cmpx2!(lt, _mm_cmplt_ps);
        cmpx2!(le, _mm_cmple_ps);
        cmpx2!(eq, _mm_cmpeq_ps);
        #[inline(always)]
        fn and(a: [__m128; 2], b: [__m128; 2]) -> [__m128; 2] {
            // SAFETY: see the module docs (SSE, no memory access).
            [0, 1].map(|h| unsafe { _mm_and_ps(a[h], b[h]) })
        }
        #[inline(always)]
        fn or(a: [__m128; 2], b: [__m128; 2]) -> [__m128; 2] {
            // SAFETY: see the module docs (SSE, no memory access).
            [0, 1].map(|h| unsafe { _mm_or_ps(a[h], b[h]) })
        }
        #[inline(always)]
        fn and_not(a: [__m128; 2], b: [__m128; 2]) -> [__m128; 2] {
            // ANDNPS complements its first operand.
            // SAFETY: see the module docs (SSE, no memory access).
            [0, 1].map(|h| unsafe { _mm_andnot_ps(b[h], a[h]) })
        }
        #[inline(always)]
        fn bits(m: [__m128; 2]) -> u32 {
            // SAFETY: see the module docs (SSE, no memory access).
            let (lo, hi) = unsafe { (_mm_movemask_ps(m[0]), _mm_movemask_ps(m[1])) };
            (lo | hi << 4) as u32
        }
        #[inline(always)]
        fn select(m: [__m128; 2], a: Self, b: Self) -> Self {
            // SSE2 has no blend: (m & a) | (!m & b).
            // SAFETY: see the module docs (SSE, no memory access).
            Self([0, 1].map(|h| unsafe {
                _mm_or_ps(_mm_and_ps(m[h], a.0[h]), _mm_andnot_ps(m[h], b.0[h]))
            }))
        }
    }
}

/// Eight lanes of a scalar type: one lane per shape of a batch. The same
/// semantics as [`Lanes`] (see the module docs), on all eight lanes, with
/// comparisons giving a lane mask.
///
/// Public only so that it can appear in the sealed [`Scalar`] trait.
pub trait Lanes8: Copy {
    /// The scalar in each lane.
    type F: Scalar;
    /// A per-lane flag, as the comparisons give it.
    type Mask: Copy;
    /// `v` in every lane.
    fn splat(v: Self::F) -> Self;
    /// The lanes from an array.
    fn load(a: &[Self::F; 8]) -> Self;
    /// The lanes into an array.
    fn store(self, a: &mut [Self::F; 8]);
    /// Eight bytes as numbers (exact).
    fn from_bytes(b: &[u8; 8]) -> Self;
    /// Lane-wise `self + o`.
    fn add(self, o: Self) -> Self;
    /// Lane-wise `self - o`.
    fn sub(self, o: Self) -> Self;
    /// Lane-wise `self * o`.
    fn mul(self, o: Self) -> Self;
    /// Lane-wise `self / o`.
    fn div(self, o: Self) -> Self;
    /// Lane-wise `if self > o { self } else { o }`.
    fn max(self, o: Self) -> Self;
    /// Lane-wise `if self < o { self } else { o }`.
    fn min(self, o: Self) -> Self;
    /// Lane-wise `self < o`.
    fn lt(self, o: Self) -> Self::Mask;
    /// Lane-wise `self <= o`.
    fn le(self, o: Self) -> Self::Mask;
    /// Lane-wise `self == o`.
    fn eq(self, o: Self) -> Self::Mask;
    /// Lane-wise `a && b`.
    fn and(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// Lane-wise `a || b`.
    fn or(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// Lane-wise `a && !b`.
    fn and_not(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// Bit `l` set when lane `l` is set.
    fn bits(m: Self::Mask) -> u32;
    /// Lane-wise `if m { a } else { b }`.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
}

/// Eight lanes as an array: the definition, and the implementation where
/// no register type is used.
#[derive(Clone, Copy, Debug)]
pub struct Portable8<F>([F; 8]);

impl<F: Scalar> Portable8<F> {
    #[inline(always)]
    fn map2(self, o: Self, f: impl Fn(F, F) -> F) -> Self {
        Self(core::array::from_fn(|l| f(self.0[l], o.0[l])))
    }
    #[inline(always)]
    fn test(self, o: Self, f: impl Fn(F, F) -> bool) -> [bool; 8] {
        core::array::from_fn(|l| f(self.0[l], o.0[l]))
    }
}

impl<F: Scalar> Lanes8 for Portable8<F> {
    type F = F;
    type Mask = [bool; 8];
    #[inline(always)]
    fn splat(v: F) -> Self {
        Self([v; 8])
    }
    #[inline(always)]
    fn load(a: &[F; 8]) -> Self {
        Self(*a)
    }
    #[inline(always)]
    fn store(self, a: &mut [F; 8]) {
        *a = self.0;
    }
    #[inline(always)]
    fn from_bytes(b: &[u8; 8]) -> Self {
        Self(b.map(|x| F::from_u32(u32::from(x))))
    }
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        self.map2(o, |a, b| a + b)
    }
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        self.map2(o, |a, b| a - b)
    }
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        self.map2(o, |a, b| a * b)
    }
    #[inline(always)]
    fn div(self, o: Self) -> Self {
        self.map2(o, |a, b| a / b)
    }
    #[inline(always)]
    fn max(self, o: Self) -> Self {
        self.map2(o, |a, b| if a > b { a } else { b })
    }
    #[inline(always)]
    fn min(self, o: Self) -> Self {
        self.map2(o, |a, b| if a < b { a } else { b })
    }
    #[inline(always)]
    fn lt(self, o: Self) -> [bool; 8] {
        self.test(o, |a, b| a < b)
    }
    #[inline(always)]
    fn le(self, o: Self) -> [bool; 8] {
        self.test(o, |a, b| a <= b)
    }
    #[inline(always)]
    fn eq(self, o: Self) -> [bool; 8] {
        self.test(o, |a, b| a == b)
    }
    #[inline(always)]
    fn and(a: [bool; 8], b: [bool; 8]) -> [bool; 8] {
        core::array::from_fn(|l| a[l] & b[l])
    }
    #[inline(always)]
    fn or(a: [bool; 8], b: [bool; 8]) -> [bool; 8] {
        core::array::from_fn(|l| a[l] | b[l])
    }
    #[inline(always)]
    fn and_not(a: [bool; 8], b: [bool; 8]) -> [bool; 8] {
        core::array::from_fn(|l| a[l] & !b[l])
    }
    #[inline(always)]
    fn bits(m: [bool; 8]) -> u32 {
        m.iter()
            .enumerate()
            .fold(0, |acc, (l, &b)| acc | u32::from(b) << l)
    }
    #[inline(always)]
    fn select(m: [bool; 8], a: Self, b: Self) -> Self {
        Self(core::array::from_fn(|l| if m[l] { a.0[l] } else { b.0[l] }))
    }
}

/// The `f32` eight lanes the batch kernels use on this target.
#[cfg(all(target_arch = "x86_64", target_feature = "avx2"))]
pub type F32Lanes8 = avx::F32x8;
/// The `f32` eight lanes the batch kernels use on this target.
#[cfg(all(
    any(target_arch = "x86", target_arch = "x86_64"),
    target_feature = "sse2",
    not(all(target_arch = "x86_64", target_feature = "avx2"))
))]
pub type F32Lanes8 = sse::F32x4x2;
/// The `f32` eight lanes the batch kernels use on this target.
#[cfg(not(any(
    all(
        any(target_arch = "x86", target_arch = "x86_64"),
        target_feature = "sse2"
    ),
    all(target_arch = "x86_64", target_feature = "avx2")
)))]
pub type F32Lanes8 = Portable8<f32>;

/// Eight `f32` lanes in one AVX register.
///
/// Safety of the `unsafe` blocks below: each calls an AVX or AVX2
/// intrinsic, whose one precondition is that the CPU supports it, and none
/// touches memory. Values of this type are made and used only (a) in a
/// build whose target has AVX2 enabled at compile time, where every CPU the
/// code runs on has it, or (b) inside the functions of `batch::avx2`,
/// compiled with `#[target_feature(enable = "avx2")]` and called only after
/// `is_x86_feature_detected!("avx2")`. Nothing else in the crate names the
/// type: it is reached through `Scalar::Lanes8` in case (a) and
/// `Scalar::Lanes8Avx2`, which only `batch::avx2` uses, in case (b).
#[cfg(all(target_arch = "x86_64", any(target_feature = "avx2", feature = "std")))]
#[allow(unsafe_code)]
pub(crate) mod avx {
    use core::arch::x86_64::*;

    use super::Lanes8;

    /// Eight `f32` lanes in an AVX register.
    #[derive(Clone, Copy, Debug)]
    pub struct F32x8(__m256);

    /// A lane-wise operation of two registers.
    macro_rules! op2 {
        ($name:ident, $intrinsic:ident) => {
            #[inline(always)]
            fn $name(self, o: Self) -> Self {
                // SAFETY: see the module docs (AVX, no memory access).
                Self(unsafe { $intrinsic(self.0, o.0) })
            }
        };
    }

    /// A comparison, as a lane mask.
    macro_rules! cmp {
        ($name:ident, $pred:ident) => {
            #[inline(always)]
            fn $name(self, o: Self) -> __m256 {
                // SAFETY: see the module docs (AVX, no memory access).
                unsafe { _mm256_cmp_ps::<$pred>(self.0, o.0) }
            }
        };
    }

    impl Lanes8 for F32x8 {
        type F = f32;
        type Mask = __m256;
        #[inline(always)]
        fn splat(v: f32) -> Self {
            // SAFETY: see the module docs (AVX, no memory access).
            Self(unsafe { _mm256_set1_ps(v) })
        }
        #[inline(always)]
        fn load(a: &[f32; 8]) -> Self {
            // SAFETY: see the module docs (AVX); the unaligned load reads
            // 32 bytes from a reference to 8 `f32`, which is valid for that.
            Self(unsafe { _mm256_loadu_ps(a.as_ptr()) })
        }
        #[inline(always)]
        fn store(self, a: &mut [f32; 8]) {
            // SAFETY: see the module docs (AVX); the unaligned store writes
            // 32 bytes through a mutable reference to 8 `f32`.
            unsafe { _mm256_storeu_ps(a.as_mut_ptr(), self.0) }
        }
        #[inline(always)]
        fn from_bytes(b: &[u8; 8]) -> Self {
            // SAFETY: see the module docs (AVX2); the load reads 8 bytes
            // from a reference to 8 bytes.
            Self(unsafe {
                let bytes = _mm_loadl_epi64(b.as_ptr().cast());
                _mm256_cvtepi32_ps(_mm256_cvtepu8_epi32(bytes))
            })
        }
        op2!(add, _mm256_add_ps);
        op2!(sub, _mm256_sub_ps);
        op2!(mul, _mm256_mul_ps);
        op2!(div, _mm256_div_ps);
        // VMAXPS/VMINPS return the second operand unless the first compares
        // greater (less), NaN included, as MAXPS does.
        op2!(max, _mm256_max_ps);
        op2!(min, _mm256_min_ps);
        cmp!(lt, _CMP_LT_OQ);
        cmp!(le, _CMP_LE_OQ);
        cmp!(eq, _CMP_EQ_OQ);
        #[inline(always)]
        fn and(a: __m256, b: __m256) -> __m256 {
            // SAFETY: see the module docs (AVX, no memory access).
            unsafe { _mm256_and_ps(a, b) }
        }
        #[inline(always)]
        fn or(a: __m256, b: __m256) -> __m256 {
            // SAFETY: see the module docs (AVX, no memory access).
            unsafe { _mm256_or_ps(a, b) }
        }
        #[inline(always)]
        fn and_not(a: __m256, b: __m256) -> __m256 {
            // ANDNPS complements its first operand.
            // SAFETY: see the module docs (AVX, no memory access).
            unsafe { _mm256_andnot_ps(b, a) }
        }
        #[inline(always)]
        fn bits(m: __m256) -> u32 {
            // SAFETY: see the module docs (AVX, no memory access).
            (unsafe { _mm256_movemask_ps(m) }) as u32
        }
        #[inline(always)]
        fn select(m: __m256, a: Self, b: Self) -> Self {
            // SAFETY: see the module docs (AVX, no memory access).
            Self(unsafe { _mm256_blendv_ps(b.0, a.0, m) })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A value from a mix of ordinary numbers and the special ones.
    fn pick(state: &mut u64) -> f32 {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        const SPECIAL: [f32; 8] = [
            0.0,
            -0.0,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            f32::MAX,
            f32::from_bits(1),
            1.0,
        ];
        match *state % 4 {
            0 => SPECIAL[(*state >> 8) as usize % 8],
            1 => ((*state >> 16) % 9) as f32 - 4.0,
            _ => f32::from_bits((*state >> 20) as u32),
        }
    }

    fn same(a: [f32; 3], b: [f32; 3]) -> bool {
        a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits())
    }

    /// Every operation of the register type gives the portable definition's
    /// bits, NaN, infinities and signed zeros included (lane 3 aside).
    #[test]
    fn registers_match_the_definition() {
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        for _ in 0..200_000 {
            let mut v = || [pick(&mut state), pick(&mut state), pick(&mut state)];
            let (a, b) = (v(), v());
            let (pa, pb) = (
                Portable::new(a[0], a[1], a[2]),
                Portable::new(b[0], b[1], b[2]),
            );
            let (fa, fb) = (
                F32Lanes::new(a[0], a[1], a[2]),
                F32Lanes::new(b[0], b[1], b[2]),
            );
            type Op<L> = fn(L, L) -> L;
            let ops: [(Op<Portable<f32>>, Op<F32Lanes>); 6] = [
                (Lanes::add, Lanes::add),
                (Lanes::sub, Lanes::sub),
                (Lanes::mul, Lanes::mul),
                (Lanes::div, Lanes::div),
                (Lanes::max, Lanes::max),
                (Lanes::min, Lanes::min),
            ];
            for (p, f) in ops {
                assert!(
                    same(p(pa, pb).to_array(), f(fa, fb).to_array()),
                    "{a:?} {b:?}"
                );
            }
            for (p, f) in [
                (pa.abs(), fa.abs()),
                (pa.neg(), fa.neg()),
                (pa.rot1(), fa.rot1()),
                (pa.rot2(), fa.rot2()),
            ] {
                assert!(same(p.to_array(), f.to_array()), "{a:?}");
            }
            assert_eq!(pa.lt(pb), fa.lt(fb));
            assert_eq!(pa.le(pb), fa.le(fb));
            assert_eq!(pa.eq(pb), fa.eq(fb));
            assert_eq!(pa.nle(pb), fa.nle(fb));
            for (p, f) in [(pa.max_all(), fa.max_all()), (pa.min_all(), fa.min_all())] {
                assert!(same(p.to_array(), f.to_array()), "{a:?}");
            }
            assert_eq!(pa.sum3().to_bits(), fa.sum3().to_bits(), "{a:?}");
            assert_eq!(pa.x().to_bits(), fa.x().to_bits());
        }
    }

    /// Eight lanes of random specials and ordinary values.
    fn eight(state: &mut u64) -> [f32; 8] {
        core::array::from_fn(|_| pick(state))
    }

    /// Every operation of an eight-lane register type gives the portable
    /// definition's bits and masks.
    fn check_lanes8<W: Lanes8<F = f32>>(a: [f32; 8], b: [f32; 8]) {
        let (pa, pb) = (Portable8::load(&a), Portable8::load(&b));
        let (wa, wb) = (W::load(&a), W::load(&b));
        // Bits, with every NaN alike: which NaN's payload an operation
        // passes on is the hardware's choice (and the compiler may swap
        // the operands of an addition), and no kernel answer is a NaN.
        let canonical = |x: f32| if x.is_nan() { u32::MAX } else { x.to_bits() };
        let out = |w: W| {
            let mut x = [0.0; 8];
            w.store(&mut x);
            x.map(canonical)
        };
        let pout = |p: Portable8<f32>| {
            let mut x = [0.0; 8];
            p.store(&mut x);
            x.map(canonical)
        };
        type Op<L> = fn(L, L) -> L;
        let ops: [(Op<Portable8<f32>>, Op<W>); 6] = [
            (Lanes8::add, Lanes8::add),
            (Lanes8::sub, Lanes8::sub),
            (Lanes8::mul, Lanes8::mul),
            (Lanes8::div, Lanes8::div),
            (Lanes8::max, Lanes8::max),
            (Lanes8::min, Lanes8::min),
        ];
        for (p, w) in ops {
            assert_eq!(pout(p(pa, pb)), out(w(wa, wb)), "{a:?} {b:?}");
        }
        let bytes = a.map(|x| x.to_bits() as u8);
        assert_eq!(
            pout(Portable8::from_bytes(&bytes)),
            out(W::from_bytes(&bytes))
        );
        assert_eq!(pout(Portable8::splat(a[3])), out(W::splat(a[3])));
        let masks = [
            (pa.lt(pb), wa.lt(wb)),
            (pa.le(pb), wa.le(wb)),
            (pa.eq(pb), wa.eq(wb)),
        ];
        for (p, w) in masks {
            assert_eq!(Portable8::<f32>::bits(p), W::bits(w), "{a:?} {b:?}");
        }
        let (pm, pn) = (pa.lt(pb), pb.le(pa));
        let (wm, wn) = (wa.lt(wb), wb.le(wa));
        assert_eq!(
            Portable8::<f32>::bits(Portable8::<f32>::and(pm, pn)),
            W::bits(W::and(wm, wn))
        );
        assert_eq!(
            Portable8::<f32>::bits(Portable8::<f32>::or(pm, pn)),
            W::bits(W::or(wm, wn))
        );
        assert_eq!(
            Portable8::<f32>::bits(Portable8::<f32>::and_not(pm, pn)),
            W::bits(W::and_not(wm, wn))
        );
        assert_eq!(
            pout(Portable8::select(pm, pa, pb)),
            out(W::select(wm, wa, wb))
        );
    }

    /// The eight-lane types the batch kernels use on this target, and the
    /// AVX one where the CPU has AVX2, match the definition.
    #[test]
    fn eight_lane_registers_match_the_definition() {
        #[cfg(all(target_arch = "x86_64", not(target_feature = "avx2")))]
        #[target_feature(enable = "avx2")]
        fn with_avx2(a: [f32; 8], b: [f32; 8]) {
            check_lanes8::<avx::F32x8>(a, b);
        }
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        for _ in 0..50_000 {
            let (a, b) = (eight(&mut state), eight(&mut state));
            check_lanes8::<F32Lanes8>(a, b);
            #[cfg(all(target_arch = "x86_64", not(target_feature = "avx2")))]
            if std::is_x86_feature_detected!("avx2") {
                #[allow(unsafe_code)]
                // SAFETY: AVX2 was just detected.
                unsafe {
                    with_avx2(a, b)
                };
            }
        }
    }

    /// The semantics the slab test relies on, spelled out.
    #[test]
    fn max_and_min_return_the_second_operand_for_nan() {
        let nan = F32Lanes::splat(f32::NAN);
        let zero = F32Lanes::splat(0.0);
        assert_eq!(nan.max(zero).to_array(), [0.0; 3]);
        assert_eq!(nan.min(zero).to_array(), [0.0; 3]);
        assert!(zero.max(nan).x().is_nan());
        // -0 > +0 is false: the second operand.
        assert_eq!(F32Lanes::splat(-0.0).max(zero).x().to_bits(), 0);
    }
}
