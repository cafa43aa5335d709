//! AVX2: eight `f32` lanes in one register ([`F32x8`]), and, where the
//! build picks the instruction set at run time, the [`Avx2`] token and the
//! function that runs a kernel body compiled with AVX2 enabled.
//!
//! Safety of the `unsafe` blocks of `F32x8`: each calls an AVX or AVX2
//! intrinsic, whose one precondition is that the CPU supports it, and none
//! touches memory beyond the references it is given. Values of the type are
//! made and used only (a) in a build whose target has AVX2 enabled at
//! compile time (it is then the target's eight-lane type), where every CPU
//! the code runs on has it, or (b) as `Isa::W` of [`Avx2`] and
//! `Avx512`, that is inside a kernel or work run by the functions of this
//! file and of `super::avx512`, which are compiled with AVX2 enabled and called
//! only with a token, and a token is made only by detecting the CPU's
//! instruction sets.
#![allow(unsafe_code)]

use core::arch::x86_64::*;

use crate::num::Lanes8;
#[cfg(rayhit_runtime_avx)]
use {
    super::{Isa, Kernel, Work},
    crate::num::{Repr, Scalar},
};

/// Eight `f32` lanes in an AVX register.
#[derive(Clone, Copy, Debug)]
pub struct F32x8(__m256);

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
    #[inline(always)]
    fn sqrt(self) -> Self {
        // SAFETY: see the module docs (AVX, no memory access).
        Self(unsafe { _mm256_sqrt_ps(self.0) })
    }
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

/// AVX2, on a CPU that has it: [`with_simd`](crate::batch::with_simd) makes one
/// only after checking (x86-64 builds with `std` whose target does not
/// already assume AVX2).
#[cfg(rayhit_runtime_avx)]
#[derive(Clone, Copy, Debug)]
pub struct Avx2(());

#[cfg(rayhit_runtime_avx)]
impl Avx2 {
    /// `Some` when the CPU has AVX2: the one place an `Avx2` is made but
    /// for [`Avx2::detected`], which a cached answer of this one calls.
    #[inline]
    pub(crate) fn detect() -> Option<Self> {
        std::is_x86_feature_detected!("avx2").then_some(Avx2(()))
    }

    /// The token, for a caller that has seen [`Avx2::detect`] give one on
    /// this CPU (a cached detection).
    ///
    /// # Safety
    ///
    /// `Avx2::detect` must have returned `Some` in this process.
    #[inline(always)]
    pub(crate) unsafe fn detected() -> Self {
        Avx2(())
    }
}

#[cfg(rayhit_runtime_avx)]
impl Isa for Avx2 {
    type W<F: Scalar> = <F as Repr>::L8Avx2;

    #[inline(always)]
    fn kernel<K: Kernel>(self, ray: &K::Ray, shapes: &K::Shapes, t_max: K::Limit) -> K::Output {
        // SAFETY: the one precondition of calling a function compiled with
        // `#[target_feature(enable = "avx2")]` is that the CPU has AVX2; an
        // `Avx2` exists only where `Avx2::detect` found it.
        unsafe { kernel::<K>(self, ray, shapes, t_max) }
    }

    #[inline(always)]
    fn work<B: Work>(self, work: B) -> B::Output {
        // SAFETY: as above.
        unsafe { run(self, work) }
    }
}

/// Kernel `K`, compiled with AVX2 enabled (the kernel is inlined, whole,
/// into this function).
#[cfg(rayhit_runtime_avx)]
#[target_feature(enable = "avx2")]
#[inline]
fn kernel<K: Kernel>(isa: Avx2, ray: &K::Ray, shapes: &K::Shapes, t_max: K::Limit) -> K::Output {
    K::run(isa, ray, shapes, t_max)
}

/// `work`, compiled with AVX2 enabled.
#[cfg(rayhit_runtime_avx)]
#[target_feature(enable = "avx2")]
#[inline]
fn run<B: Work>(isa: Avx2, work: B) -> B::Output {
    work.run(isa)
}
