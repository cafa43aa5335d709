//! SSE registers, one instruction per operation: four `f32` lanes in one
//! register ([`F32x4`]) and eight in two ([`F32x4x2`]).
//!
//! Safety of the `unsafe` blocks below: each calls an SSE or SSE2 intrinsic
//! (`core::arch`), and the only precondition of those is that the CPU
//! supports the instruction set. This module is compiled only when the
//! target has SSE2 enabled at compile time (`target_feature = "sse2"`, part
//! of every x86-64 target and of the i686 ones), so every CPU the code can
//! run on has it. None of them touches memory except the loads and stores
//! of `F32x4x2`, whose comments say why they stay inside their reference.
#![allow(unsafe_code)]

#[cfg(target_arch = "x86")]
use core::arch::x86::*;
#[cfg(target_arch = "x86_64")]
use core::arch::x86_64::*;

use crate::num::Lanes;

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

/// A comparison of two registers, as a mask of all four lanes.
macro_rules! mask {
    ($name:ident, $intrinsic:ident) => {
        #[inline(always)]
        fn $name(self, o: Self) -> __m128 {
            // SAFETY: see the module docs (SSE, no memory access).
            unsafe { $intrinsic(self.0, o.0) }
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
    type Mask = __m128;
    #[inline(always)]
    fn to_array4(self) -> [f32; 4] {
        let [x, y, z] = self.to_array();
        // SAFETY: see the module docs (SSE, no memory access).
        let w = unsafe { _mm_cvtss_f32(_mm_shuffle_ps::<0b11_11_11_11>(self.0, self.0)) };
        [x, y, z, w]
    }
    mask!(lt_mask, _mm_cmplt_ps);
    #[inline(always)]
    fn mask_all(b: bool) -> __m128 {
        // SAFETY: see the module docs (SSE2, no memory access).
        unsafe { _mm_castsi128_ps(_mm_set1_epi32(-i32::from(b))) }
    }
    #[inline(always)]
    fn select(m: __m128, a: Self, b: Self) -> Self {
        // SAFETY: see the module docs (SSE, no memory access).
        Self(unsafe { _mm_or_ps(_mm_and_ps(m, a.0), _mm_andnot_ps(m, b.0)) })
    }
    #[inline(always)]
    fn roll4(self) -> Self {
        // SAFETY: see the module docs (SSE, no memory access).
        Self(unsafe { _mm_shuffle_ps::<0b00_11_10_01>(self.0, self.0) })
    }
    #[inline(always)]
    fn lt4(self, o: Self) -> u32 {
        // SAFETY: see the module docs (SSE, no memory access).
        unsafe { _mm_movemask_ps(_mm_cmplt_ps(self.0, o.0)) as u32 }
    }
    #[inline(always)]
    fn le4(self, o: Self) -> u32 {
        // SAFETY: see the module docs (SSE, no memory access).
        unsafe { _mm_movemask_ps(_mm_cmple_ps(self.0, o.0)) as u32 }
    }
    #[inline(always)]
    fn eq4(self, o: Self) -> u32 {
        // SAFETY: see the module docs (SSE, no memory access).
        unsafe { _mm_movemask_ps(_mm_cmpeq_ps(self.0, o.0)) as u32 }
    }
}

/// Eight lanes in two registers: the eight-lane type of x86 targets without
/// AVX2 (those with it use `super::avx2`'s).
#[cfg(rayhit_lanes8 = "sse2")]
pub mod pair {
    #[cfg(target_arch = "x86")]
    use core::arch::x86::*;
    #[cfg(target_arch = "x86_64")]
    use core::arch::x86_64::*;

    use crate::num::Lanes8;

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

    impl Lanes8 for F32x4x2 {
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
        #[inline(always)]
        fn sqrt(self) -> Self {
            // SAFETY: see the module docs (SSE, no memory access).
            Self(unsafe { [_mm_sqrt_ps(self.0[0]), _mm_sqrt_ps(self.0[1])] })
        }
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
